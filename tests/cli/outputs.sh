#!/usr/bin/env bash
# Outputs never clobber what they should not (issue #10, items 1-4 and the output bits of 16):
#   - an output that names an input (scene, import, golden, settings) by any spelling is a usage
#     error (64) before anything is written;
#   - the outputs of one run never collide (--out traj.json);
#   - devices, FIFOs and stdout are written through, a symlink's target is replaced (never the
#     link), for every writer;
#   - every output is checked before the run, and a run's outputs are committed together.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

mkdir scenes parts
cp "$SCENES/pendulum.xml" scenes/pendulum.xml
cat >scenes/importer.xml <<'XML'
<?xml version="1.0" encoding="UTF-8"?>
<Simulation>
  <ComponentList>
    <RCGround Key="Ground"/>
    <RCImportBody Key="Part">
      <File Value="../parts/ball.xml"/>
    </RCImportBody>
  </ComponentList>
</Simulation>
XML
cat >parts/ball.xml <<'XML'
<Body>
  <RCMobileRigidBody Key="Ball">
    <Pose><RCGlobalCoordinates><Pose Value="0 1 0 0 0 0"/></RCGlobalCoordinates></Pose>
    <Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom>
  </RCMobileRigidBody>
</Body>
XML
printf 'LogFile =\n' >settings.ini
ln -s scenes/pendulum.xml link.xml
ln scenes/pendulum.xml hard.xml
snapshot() { find . -path ./last.out -prune -o -path ./last.err -prune -o -type f -print0 | sort -z | xargs -0 sha1sum; }

# expect_clobber_refused WHAT PATTERN CMD...: exit 64, one error line matching PATTERN, and no
# file created, changed or removed.
expect_clobber_refused() {
  local what=$1 pattern=$2 before
  shift 2
  check "64: $what"
  before=$(snapshot)
  expect_status 64 "$@"
  expect_lines "$what: stderr" "$LAST_ERR" 1
  expect_match "$what: message" "$LAST_ERR" "$pattern"
  expect_eq "$what: files after" "$(snapshot)" "$before"
}

# ---------------------------------------------------------------- 1: an output names an input
P=scenes/pendulum.xml
expect_clobber_refused "run --out the scene" \
  "^simbob: error: --out scenes/pendulum.xml is the scene scenes/pendulum.xml: an output must not overwrite an input$" \
  "$SIMBOB" run $P --duration 0.1 --out $P
expect_clobber_refused "run --out the scene through '..'" "--out scenes/../scenes/pendulum.xml is the scene" \
  "$SIMBOB" run $P --duration 0.1 --out scenes/../scenes/pendulum.xml
expect_clobber_refused "run --out the scene through an absolute path" "is the scene" \
  "$SIMBOB" run $P --duration 0.1 --out "$WORK/$P"
expect_clobber_refused "run --out a symlink to the scene" "--out link.xml is the scene" \
  "$SIMBOB" run $P --duration 0.1 --out link.xml
expect_clobber_refused "run --out a hard link to the scene" "--out hard.xml is the scene" \
  "$SIMBOB" run $P --duration 0.1 --out hard.xml
expect_clobber_refused "run --out an import" "--out parts/ball.xml is the import parts/ball.xml" \
  "$SIMBOB" run scenes/importer.xml --duration 0.1 --out parts/ball.xml
cp $P scenes/s.json
expect_clobber_refused "run whose summary would replace the scene" "the summary scenes/s.json is the scene" \
  "$SIMBOB" run scenes/s.json --duration 0.1 --out scenes/s.csv
expect_clobber_refused "run --out the settings file" "--out settings.ini is --settings settings.ini" \
  "$SIMBOB" run $P --duration 0.1 --settings settings.ini --out settings.ini
expect_clobber_refused "run --log-file the scene" "--log-file hard.xml is the scene" \
  "$SIMBOB" run $P --duration 0.1 --out ok.csv --log-file hard.xml
expect_clobber_refused "check --log-file an import" "--log-file parts/ball.xml is the import" \
  "$SIMBOB" check scenes/importer.xml --log-file parts/ball.xml

"$SIMBOB" run $P --duration 0.2 --out golden.csv --quiet
"$SIMBOB" run $P --duration 0.1 --out actual.csv --quiet
rm -f golden.json actual.json
expect_clobber_refused "compare --report the golden file" \
  "^simbob: error: --report golden.csv is the golden file golden.csv: an output must not overwrite an input$" \
  "$SIMBOB" compare actual.csv golden.csv --report golden.csv
ln -s actual.csv alias.csv
expect_clobber_refused "compare --report the actual file through a symlink" "--report alias.csv is the trajectory" \
  "$SIMBOB" compare actual.csv golden.csv --report alias.csv
rm alias.csv
ln actual.csv actual.png
expect_clobber_refused "plot --out a hard link to the trajectory" "--out actual.png is the trajectory" \
  "$SIMBOB" plot actual.csv --out actual.png
rm actual.png
mkdir -p gold out
cp golden.csv gold/pendulum.csv
expect_clobber_refused "batch whose trajectory would replace its golden file" \
  "the trajectory gold/pendulum.csv is the golden file gold/pendulum.csv" \
  "$SIMBOB" batch $P --golden gold --out-dir gold --duration 0.1

# ---------------------------------------------------------------- 2: outputs of one run collide
expect_clobber_refused "run --out traj.json (the summary would replace the trajectory)" \
  "^simbob: error: the summary traj.json and --out traj.json are the same file: outputs of one command must not collide$" \
  "$SIMBOB" run $P --duration 0.1 --out traj.json
expect_clobber_refused "run --log-file onto its own summary" "--log-file out.json and the summary out.json" \
  "$SIMBOB" run $P --duration 0.1 --out out.csv --log-file out.json
expect_clobber_refused "batch --report onto a trajectory" "the trajectory out/pendulum.csv and --report out/pendulum.csv" \
  "$SIMBOB" batch $P --out-dir out --report out/pendulum.csv --duration 0.1

# ---------------------------------------------------------------- 3: devices, FIFOs, symlinks
check "a device node made with mknod stays a device for every writer (root only)"
if [[ $(id -u) -eq 0 ]]; then
  mknod null c 1 3
  mknod full c 1 7
  expect_status 0 "$SIMBOB" run $P --duration 0.1 --out null
  [[ -c null ]] || fail "run --out null replaced the device node"
  expect_no_file null.json
  expect_status 0 "$SIMBOB" compare actual.csv actual.csv --report null
  [[ -c null ]] || fail "compare --report null replaced the device node"
  expect_status 0 "$SIMBOB" plot actual.csv --out null.png
  expect_status 0 bash -c "ln -sf null plot.svg && exec \"$SIMBOB\" plot actual.csv --out plot.svg"
  [[ -c null && -L plot.svg ]] || fail "plot replaced the device node or the symlink"
  rm plot.svg
  expect_status 0 "$SIMBOB" run $P --duration 0.1 --out n.csv --log-file null
  [[ -c null ]] || fail "--log-file null replaced the device node"
  check "74: --out onto a full device is a write error, and the node stays"
  expect_status 74 "$SIMBOB" run $P --duration 0.1 --out full
  expect_match "message" "$LAST_ERR" "^full: error: write failed: No space left on device$"
  [[ -c full ]] || fail "run --out full replaced the device node"
  rm null full n.csv n.json null.png
else
  say "SKIPPED: mknod needs root"
  SKIPPED_MKNOD=1
fi

check "--out /dev/null and --out - write through"
expect_status 0 "$SIMBOB" run $P --duration 0.1 --out /dev/null
[[ -c /dev/null ]] || fail "/dev/null is no longer a device"
expect_status 0 "$SIMBOB" run $P --duration 0.1 --out -
expect_eq "rows on stdout" "$(csv_summary "$LAST_OUT")" "11 1 11 0.0 0.1"
expect_status 64 "$SIMBOB" run $P --duration 0.1 --out - --json
expect_match "stdout twice" "$LAST_ERR" "^simbob: error: --out - and --json would both write to stdout; drop one$"

check "a FIFO output is written through"
mkfifo pipe.csv
cat pipe.csv >from_pipe.csv &
reader=$!
expect_status 0 "$SIMBOB" run $P --duration 0.1 --out pipe.csv
wait $reader
[[ -p pipe.csv ]] || fail "the FIFO was replaced"
expect_eq "rows through the FIFO" "$(csv_summary from_pipe.csv)" "11 1 11 0.0 0.1"
rm pipe.csv from_pipe.csv

check "a symlinked output keeps its link; the file it points to is replaced"
mkdir real
printf 'old\n' >real/t.csv
ln -s real/t.csv t.csv
expect_status 0 "$SIMBOB" run $P --duration 0.1 --out t.csv
[[ -L t.csv ]] || fail "the symlink t.csv was replaced by a file"
expect_eq "target holds the trajectory" "$(head -n 1 real/t.csv)" "time,body,x,y,z,qw,qx,qy,qz"
ln -s real/report.txt report.txt
expect_status 1 "$SIMBOB" compare actual.csv golden.csv --report report.txt
[[ -L report.txt && -f real/report.txt ]] || fail "compare --report replaced its symlink"
cp golden.csv real/g.csv
ln -s real/g.csv g.csv
expect_status 0 "$SIMBOB" compare actual.csv g.csv --bless
[[ -L g.csv ]] || fail "--bless replaced the symlinked golden file"
expect_same_file real/g.csv actual.csv

# ---------------------------------------------------------------- 4: checked first, committed together
check "73 before the run: the summary's name is a directory"
printf 'old csv\n' >pair.csv
mkdir pair.json
start=$SECONDS
expect_status 73 "$SIMBOB" run $P --duration 100000 --out pair.csv
expect_match "message" "$LAST_ERR" "^pair.json: error: cannot create: is a directory$"
((SECONDS - start < 30)) || fail "the run started before its outputs were checked"
expect_eq "old csv kept" "$(cat pair.csv)" "old csv"
expect_eq "temporary files" "$(find . -name '*tmp*')" ""
rmdir pair.json

check "74 when the summary cannot be written: the old pair stays, all old"
printf 'old csv\n' >pair.csv
printf '{"old": true}\n' >pair.json
# A file size limit of 1 KiB: the 2-sample trajectory (~240 bytes) fits; the summary, which
# names the scene by its long path, does not.
long=$(printf 'd%.0s' {1..250})
mkdir -p "$long/$long"
cp $P "$long/$long/p.xml"
set +e
(trap '' XFSZ; ulimit -f 1; exec "$SIMBOB" run "$long/$long/p.xml" --duration 0.01 --out pair.csv) 2>pair.err
status=$?
set -e
expect_eq "exit status" "$status" 74
expect_match "message" pair.err "^pair.json: error: write failed: File too large$"
expect_eq "old csv kept" "$(cat pair.csv)" "old csv"
expect_eq "old json kept" "$(cat pair.json)" '{"old": true}'
expect_eq "temporary files" "$(find . -name '*tmp*' -o -name '*.old.*')" ""
rm -r "$long"

# ---------------------------------------------------------------- 16: output options
check "64: an empty output name is not the default name"
expect_status 64 "$SIMBOB" run $P --duration 0.1 --out ""
expect_match "message" "$LAST_ERR" '^simbob: error: --out needs a file name, got ""$'
expect_no_file pendulum.csv
expect_status 64 "$SIMBOB" compare actual.csv golden.csv --report ""
expect_status 64 "$SIMBOB" run $P --duration 0.1 --out e.csv --log-file ""
check "64: plot --out with an extension it cannot write"
expect_status 64 "$SIMBOB" plot actual.csv --out x.jpg
expect_match "message" "$LAST_ERR" "^simbob: error: --out x.jpg: a plot is .png or .svg$"
check "74: a log file that cannot be written"
expect_status 74 "$SIMBOB" run $P --duration 0.1 --out l.csv --log-file /dev/full
expect_match "message" "$LAST_ERR" "^/dev/full: error: writing the log file failed: No space left on device$"

if [[ -n "${SKIPPED_MKNOD:-}" ]]; then exit 77; fi
say "ok"
