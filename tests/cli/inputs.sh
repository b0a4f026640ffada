#!/usr/bin/env bash
# Inputs are inputs everywhere (issue #19, item 3): textures, a DocumentIni without camera
# settings, a sweep's manifest and case files, and files in a recording folder that the
# recording would write or remove are inputs or outputs like the scene: naming one as an output
# is a usage error (64) before anything is written, and nothing changes on disk.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

mkdir scenes
cp "$SCENES/gallery.xml" scenes/gallery.xml
cp -r "$SCENES/textures" scenes/textures
cp "$SCENES/pendulum.xml" scenes/pendulum.xml
snapshot() { find . -path ./last.out -prune -o -path ./last.err -prune -o -type f -print0 | sort -z | xargs -0 sha1sum; }

# expect_refused WHAT PATTERN CMD...: exit 64, one error line matching PATTERN, and no file
# created, changed or removed.
expect_refused() {
  local what=$1 pattern=$2 before
  shift 2
  check "64: $what"
  before=$(snapshot)
  expect_status 64 "$@"
  expect_lines "$what: stderr" "$LAST_ERR" 1
  expect_match "$what: message" "$LAST_ERR" "$pattern"
  expect_eq "$what: files after" "$(snapshot)" "$before"
}

G=scenes/gallery.xml
P=scenes/pendulum.xml
# ---------------------------------------------------------------- textures
expect_refused "render --out a texture the scene reads" \
  "^simbob: error: --out scenes/textures/bricks.png is the texture scenes/textures/bricks.png: an output must not overwrite an input$" \
  "$SIMBOB" render $G --out scenes/textures/bricks.png
expect_refused "run --out a texture (with --record)" \
  "^simbob: error: --out scenes/textures/checker.bmp is the texture scenes/textures/checker.bmp: an output must not overwrite an input$" \
  "$SIMBOB" run $G --duration 0.1 --record rec --out scenes/textures/checker.bmp
expect_refused "run --video onto a texture" "--video scenes/textures/checker.bmp is the texture" \
  "$SIMBOB" run $G --duration 0.1 --video scenes/textures/checker.bmp --out v.csv
# A texture named without its extension is found with one: that file is the input.
sed 's|textures/checker.bmp|textures/checker|' $G >scenes/noext.xml
# (render --out takes only .png names, so run --record writes the file here.)
expect_refused "run --out a texture found by adding .bmp" "--out scenes/textures/checker.bmp is the texture" \
  "$SIMBOB" run scenes/noext.xml --duration 0.1 --record noext_frames --out scenes/textures/checker.bmp

# ---------------------------------------------------------------- DocumentIni
check "a DocumentIni without camera settings is still an input"
printf 'DocumentIni = True\n' >on.ini
printf '; no camera settings yet\n' >scenes/pendulum.ini
expect_refused "run --out the DocumentIni" \
  "^simbob: error: --out scenes/pendulum.ini is the DocumentIni scenes/pendulum.ini: an output must not overwrite an input$" \
  "$SIMBOB" run $P --duration 0.1 --settings on.ini --out scenes/pendulum.ini

# ---------------------------------------------------------------- recording folders
mkdir r1
expect_refused "run --out a frame of its own --record folder" \
  "^simbob: error: --out r1/frame_000000.png is a frame file of --record r1, which the recording writes or removes: outputs of one command must not collide$" \
  "$SIMBOB" run $P --duration 0.1 --record r1 --out r1/frame_000000.png
expect_refused "run --out a frame of its own --record folder (the folder spelled otherwise)" \
  "--out ./r1/frame_000001.png is a frame file of --record r1/" \
  "$SIMBOB" run $P --duration 0.1 --record r1/ --out ./r1/frame_000001.png
mkdir rec
cp $P rec/frame_000003.png
expect_refused "a scene stored as a frame the recording would overwrite" \
  "^simbob: error: the scene rec/frame_000003.png is a frame file of --record rec, which the recording writes or removes: an output must not overwrite an input$" \
  "$SIMBOB" run rec/frame_000003.png --duration 0.1 --record rec --out ok.csv
mv rec/frame_000003.png rec/frame_000010.png
expect_refused "a scene stored as a frame the stale-frame cleanup would remove" \
  "the scene rec/frame_000010.png is a frame file of --record rec" \
  "$SIMBOB" run rec/frame_000010.png --duration 0.1 --record rec --out ok.csv
rm -r rec r1

# ---------------------------------------------------------------- sweeps
check "a small sweep to gather"
expect_status 0 "$SIMBOB" sweep plan "$SCENES/sliding_box.sweep.json" -o box.jsonl
head -n 2 box.jsonl >two.jsonl
expect_status 0 "$SIMBOB" sweep run two.jsonl -j 1 -o out -q
case0=$(ls -d out/case-* | head -n 1)
[[ -f "$case0/case.json" ]] || fail "no case.json in $case0"
expect_refused "sweep gather -o the manifest it reads" \
  "^simbob: error: -o out/manifest.jsonl is the manifest out/manifest.jsonl: an output must not overwrite an input$" \
  "$SIMBOB" sweep gather out -o out/manifest.jsonl
expect_refused "sweep gather -o a case file it reads" \
  "^simbob: error: -o $case0/case.json is the case file out/.*case.json: an output must not overwrite an input$" \
  "$SIMBOB" sweep gather out -o "$case0/case.json"
check "sweep gather into its default table still works"
expect_status 0 "$SIMBOB" sweep gather out -q
expect_file out/results.csv

mkdir sb
cp two.jsonl sb/submit.sh
expect_refused "sweep sbatch whose script would replace the manifest it reads" \
  "^simbob: error: the script sb/submit.sh is the manifest sb/submit.sh: an output must not overwrite an input$" \
  "$SIMBOB" sweep sbatch sb/submit.sh -o sb
check "a NUL in a manifest's scene path or --set is refused (65 at its line), never cut short at the NUL"
# Before, batch and sweep run ran scenes/pendulum.xml for 'scenes/pendulum.xml\0.ini' and batch wrote
# its trajectory as OUT/pendulum.xml (the OS ends the name at the NUL), exit 0.
printf 'scenes/pendulum.xml\0.ini --duration 0.1\n' >nul.txt
expect_status 65 "$SIMBOB" batch --manifest nul.txt -o nul-batch -j 1 -q
expect_eq "batch manifest" "$(cat "$LAST_ERR")" \
  "nul.txt:1: error: the line holds a NUL character, which no scene path or option can hold"
expect_no_file nul-batch
case0='{"case":0,"scene":"scenes/pendulum.xml%s","duration":0.1,"dt":0.001,"sample_interval":0.01,"seed":0,"vary":{},"set":[%s],"metrics":[]}\n'
# shellcheck disable=SC2059
printf "$case0" '\u0000.ini' '' >nul-scene.jsonl
expect_status 65 "$SIMBOB" sweep run nul-scene.jsonl -o nul-sweep -j 1 -q
expect_eq "sweep manifest scene" "$(cat "$LAST_ERR")" \
  "nul-scene.jsonl:1: error: not a sweep case: 'scene' holds a NUL character (\\u0000), which no file name can hold"
expect_no_file nul-sweep
# shellcheck disable=SC2059
printf "$case0" '' '"Pendulum.Hinge.Bob.Mass=1\u0000"' >nul-set.jsonl
expect_status 65 "$SIMBOB" sweep run nul-set.jsonl -o nul-sweep -j 1 -q
expect_eq "sweep manifest set" "$(cat "$LAST_ERR")" \
  "nul-set.jsonl:1: error: not a sweep case: a 'set' entry holds a NUL character (\\u0000), which no command line can pass"
expect_no_file nul-sweep
printf '{"scene": "scenes/pendulum.xml\\u0000.ini", "duration": 0.1}\n' >nul-plan.json
expect_status 65 "$SIMBOB" sweep plan nul-plan.json -o nul-plan.jsonl
expect_eq "sweep plan scene" "$(cat "$LAST_ERR")" \
  "nul-plan.json: error: 'scene' holds a NUL character (\\u0000), which no file name can hold"
expect_no_file nul-plan.jsonl
say "ok: inputs"
