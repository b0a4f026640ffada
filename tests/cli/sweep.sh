#!/usr/bin/env bash
# simbob run --set overrides and simbob sweep: plan, run (one case, -j), gather, sbatch.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

BOX="$SCENES/sliding_box.xml"

# ---------------------------------------------------------------- overrides
check "--set changes a parameter; the summary lists it"
expect_status 0 "$SIMBOB" run "$BOX" --duration 0.05 --out o.csv --set Crate.Material.Friction=0.25 --set Crate.Inertia.Mass=2
expect_eq "overrides in the summary" "$(json_get o.json 'j["overrides"]')" "['Crate.Material.Friction=0.25', 'Crate.Inertia.Mass=2']"

check "shorthands are SceneSettings overrides, listed in the summary"
expect_status 0 "$SIMBOB" run "$BOX" --duration 0.05 --out s.csv --space sap --auto-disable --max-contacts 2
expect_eq "shorthand overrides" "$(json_get s.json 'j["overrides"]')" \
  "['SceneSettings.Space=SweepAndPrune', 'SceneSettings.AutoDisable=True', 'SceneSettings.MaxContacts=2']"
expect_eq "space" "$(json_get s.json 'j["space"]')" "sap"
expect_eq "max_contacts" "$(json_get s.json 'j["max_contacts"]')" "2"

check "dump takes --set"
expect_status 0 "$SIMBOB" dump "$BOX" --set Crate.Inertia.Mass=3 --set SceneSettings.MaxContacts=7
expect_match "mass overridden" "$LAST_OUT" '<Mass Value="3" />'
expect_match "settings overridden" "$LAST_OUT" '<MaxContacts Value="7" />'
check "a default component left out of the file gets its own copy: the other balls keep theirs"
expect_status 0 "$SIMBOB" dump "$SCENES/bounce.xml" --set 'Dull.Motion.LinVelocity=1 0 0'
expect_eq "motions" "$(grep -o '<LinVelocity Value="[^"]*"' "$LAST_OUT" | tr '\n' ' ')" \
  '<LinVelocity Value="(1, 0)" <LinVelocity Value="0" <LinVelocity Value="0" '

check "every override error, exactly (65 for what the scene decides, 64 for the syntax)"
bad() {  # bad STATUS SET EXPECTED-STDERR
  expect_status "$1" "$SIMBOB" run "$BOX" --duration 0.05 --out bad.csv --set "$2"
  expect_eq "--set $2" "$(cat "$LAST_ERR")" "$3"
  expect_no_file bad.csv
}
bad 65 Crate.Material.Friction=abc \
  "--set Crate.Material.Friction=abc: error: RCGenericMaterial 'Crate.Material': parameter 'Friction': expected a number, got 'abc'"
bad 65 Crate.Materal.Friction=1 \
  "--set Crate.Materal.Friction=1: error: no component 'Crate.Materal' in $BOX (did you mean 'Crate.Material'?)"
bad 65 Crate.Material.Frction=1 \
  "--set Crate.Material.Frction=1: error: RCGenericMaterial 'Crate.Material': parameter 'Frction' unknown (did you mean 'Friction'?)"
bad 65 Crate.Material=1 \
  "--set Crate.Material=1: error: RCMobileRigidBody 'Crate': parameter 'Material' is a component, not a value; set a parameter inside it (Crate.Material.PARAM=VALUE)"
bad 65 Crate.Material.Friction=-1 \
  "--set Crate.Material.Friction=-1: error: RCGenericMaterial 'Crate.Material': parameter 'Friction' must be >= 0, got '-1'"
bad 65 Crate.Inertia.Mass=1e300 \
  "--set Crate.Inertia.Mass=1e300: error: RCInertiaByGeom 'Crate.Inertia': parameter 'Mass': 1e+300 is beyond the supported magnitude 1e+09"
bad 64 Crate \
  "--set Crate: error: expected KEY.PARAM=VALUE (a component key as \`simbob dump\` shows it, '.', a parameter name, '=', the value as in the scene file), got 'Crate'"
check "check takes --set and reports with the override's place"
expect_status 65 "$SIMBOB" check "$BOX" --set SceneSettings.MaxContacts=0
expect_eq "check --set" "$(cat "$LAST_ERR")" \
  "--set SceneSettings.MaxContacts=0: error: SceneSettings 'SceneSettings': parameter 'MaxContacts' must be > 0, got '0'"
expect_status 0 "$SIMBOB" check "$BOX" --set Crate.Material.Friction=0.7

# ---------------------------------------------------------------- plan expansion
check "plan: grid of a list and a zip group, ranges by step and by count; the first entry changes slowest"
mkdir -p p
cat >p/grid.json <<JSON
{"scene": "$BOX", "duration": 0.1, "seed": 5, "set": ["SceneSettings.MaxContacts=3"],
 "vary": [
   {"param": "Crate.Inertia.Mass", "values": [1, 2.5]},
   {"zip": [{"param": "Crate.Material.Friction", "range": {"start": 0.1, "stop": 0.3, "step": 0.1}},
            {"param": "seed", "range": {"start": 7, "stop": 9, "count": 3}}]}
 ],
 "metrics": [{"name": "x_end", "body": "Crate"}]}
JSON
expect_status 0 "$SIMBOB" sweep plan p/grid.json -o p/m.jsonl
expect_lines "six cases" p/m.jsonl 6
got=$(python3 -c '
import json,sys
for l in open(sys.argv[1]):
    c=json.loads(l); print(c["case"], c["seed"], " ".join(c["set"]))' p/m.jsonl)
expect_eq "cases in order" "$got" "0 7 SceneSettings.MaxContacts=3 Crate.Inertia.Mass=1 Crate.Material.Friction=0.1
1 8 SceneSettings.MaxContacts=3 Crate.Inertia.Mass=1 Crate.Material.Friction=0.2
2 9 SceneSettings.MaxContacts=3 Crate.Inertia.Mass=1 Crate.Material.Friction=0.3
3 7 SceneSettings.MaxContacts=3 Crate.Inertia.Mass=2.5 Crate.Material.Friction=0.1
4 8 SceneSettings.MaxContacts=3 Crate.Inertia.Mass=2.5 Crate.Material.Friction=0.2
5 9 SceneSettings.MaxContacts=3 Crate.Inertia.Mass=2.5 Crate.Material.Friction=0.3"
check "re-planning gives the same bytes"
expect_status 0 "$SIMBOB" sweep plan p/grid.json -o p/m2.jsonl
expect_same_file p/m.jsonl p/m2.jsonl

check "plan errors name the file and what is wrong"
plan_bad() {  # plan_bad JSON EXPECTED-STDERR
  printf '%s\n' "$1" >p/bad.json
  expect_status 65 "$SIMBOB" sweep plan p/bad.json -o p/bad.jsonl
  expect_eq "plan: $1" "$(cat "$LAST_ERR")" "$2"
  expect_no_file p/bad.jsonl
}
plan_bad "{\"scene\": \"$BOX\", \"duration\": 1, \"vary\": [{\"zip\": [{\"param\": \"A.B\", \"values\": [1, 2]}, {\"param\": \"C.D\", \"values\": [1]}]}]}" \
  "p/bad.json: error: vary[0].zip[1]: has 1 values, zip[0] has 2 (zipped parameters change together, so they need as many values)"
plan_bad "{\"scene\": \"$BOX\", \"duration\": 1, \"vary\": [{\"param\": \"A.B\", \"range\": {\"start\": 0, \"stop\": 1, \"step\": 0}}]}" \
  "p/bad.json: error: vary[0].range: 'step' must be > 0"
plan_bad "{\"scene\": \"$BOX\", \"duration\": 1, \"vary\": [{\"param\": \"Crate.Material.Friction\", \"values\": [0.1, \"x\"]}]}" \
  "p/bad.json: case 1: Crate.Material.Friction=x: error: RCGenericMaterial 'Crate.Material': parameter 'Friction': expected a number, got 'x'"
plan_bad "{\"scene\": \"$BOX\", \"duration\": 1, \"metrics\": [{\"name\": \"m\", \"body\": \"Crat\"}]}" \
  "p/bad.json: error: metric 'm': no mobile body 'Crat' in $BOX (did you mean 'Crate'?)"
plan_bad "{\"scene\": \"$BOX\", \"duraton\": 1}" \
  "p/bad.json: error: unknown field 'duraton' (did you mean 'duration'?)"
plan_bad "{\"scene\": \"$BOX\",
 \"duration\": 1,,}" \
  "p/bad.json:2: error: not valid JSON: syntax error while parsing object key - unexpected ','; expected string literal"

# ---------------------------------------------------------------- the sliding box over 20 friction values
check "the example sweep: plan, run -j2, gather"
expect_status 0 "$SIMBOB" sweep plan "$SCENES/sliding_box.sweep.json" -o box.jsonl
expect_lines "20 cases" box.jsonl 20
expect_status 0 "$SIMBOB" sweep run box.jsonl -j 2 -o box
expect_match "progress line" "$LAST_ERR" '^\[20/20\] case [0-9]+ ok'
expect_status 0 "$SIMBOB" sweep gather box
expect_file box/results.csv
check "the gathered stopping distance is v0^2 / (2 mu g) for each mu"
# Tolerance 0.5 % + 2 mm: ODE's friction decelerates at mu g per step (tests/physics checks the
# same law), but the box stops within a step of the exact time: v0 h = 2 mm with h = 1 ms.
python3 - box/results.csv <<'PY' || fail "stopping distances"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [r["case"] for r in rows] == [str(i) for i in range(20)], "cases 0..19"
assert rows[0].keys() >= {"Crate.Material.Friction", "status", "wall_seconds", "stop_x", "max_y"}
for r in rows:
    mu = float(r["Crate.Material.Friction"])
    d = float(r["stop_x"])
    want = 2.0 ** 2 / (2 * mu * 9.81)
    print(f"mu={mu:.2f} d={d:.4f} want={want:.4f} rel={abs(d - want) / want:.2e}")
    assert r["status"] == "ok", r
    assert abs(d - want) <= 0.005 * want + 0.002, f"mu {mu}: {d} vs {want}"
    assert abs(float(r["max_y"]) - 0.05) < 1e-3, "the box stays flat on the ground"
mus = [float(r["Crate.Material.Friction"]) for r in rows]
assert mus == sorted(mus) and abs(mus[0] - 0.2) < 1e-12 and abs(mus[-1] - 1.15) < 1e-12
PY

check "plot draws a metric against the varied parameter from the table"
expect_status 0 "$SIMBOB" plot box/results.csv --x Crate.Material.Friction --y stop_x --out mu.png
expect_eq "a PNG" "$(head -c 8 mu.png | od -An -tx1 | tr -d ' \n')" "89504e470d0a1a0a"
expect_status 65 "$SIMBOB" plot box/results.csv --x Crate.Material.Friction --y stopx --out bad.png
expect_eq "unknown column" "$(cat "$LAST_ERR")" "box/results.csv:1: error: no column 'stopx' (did you mean 'stop_x'?)"
expect_no_file bad.png

# ---------------------------------------------------------------- idempotent re-runs
check "a finished case is skipped; --force redoes it with the same trajectory bytes"
cp box/case-0003/trajectory.csv before.csv
ino=$(stat -c %i box/case-0003)
expect_status 0 "$SIMBOB" sweep run box.jsonl --case 3 -o box
expect_match "skipped" "$LAST_ERR" "case 3: done already"
expect_eq "same directory" "$(stat -c %i box/case-0003)" "$ino"
expect_status 0 "$SIMBOB" sweep run box.jsonl --case 3 -o box --force
[[ "$(stat -c %i box/case-0003)" != "$ino" ]] || fail "--force did not redo case 3"
expect_same_file before.csv box/case-0003/trajectory.csv
check "the case index comes from SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX"
expect_status 0 env SLURM_ARRAY_TASK_ID=4 "$SIMBOB" sweep run box.jsonl -o box
expect_match "slurm index" "$LAST_ERR" "case 4: done already"
expect_status 0 env JOB_COMPLETION_INDEX=5 "$SIMBOB" sweep run box.jsonl -o box
expect_match "k8s index" "$LAST_ERR" "case 5: done already"
expect_status 64 env -u SLURM_ARRAY_TASK_ID -u JOB_COMPLETION_INDEX "$SIMBOB" sweep run box.jsonl -o box
expect_eq "no index" "$(cat "$LAST_ERR")" "simbob: error: which case? give --case I, or run as a Slurm array task (SLURM_ARRAY_TASK_ID) or a Kubernetes Indexed Job (JOB_COMPLETION_INDEX); -j N runs every case here"
expect_status 64 "$SIMBOB" sweep run box.jsonl --case 20 -o box
expect_eq "out of range" "$(cat "$LAST_ERR")" "box.jsonl: error: no case 20 (the manifest has cases 0 to 19)"
check "an output folder of another manifest is refused"
expect_status 65 "$SIMBOB" sweep run p/m.jsonl --case 0 -o box
expect_eq "other manifest" "$(cat "$LAST_ERR")" "box/manifest.jsonl: error: this folder holds the cases of another manifest; give another -o or remove it"

# ---------------------------------------------------------------- gather: missing and failed cases
check "gather lists missing and failed cases, exits 1, --retry prints the array to resubmit"
cp -r box g
rm -r g/case-0017
python3 - g/case-0003/case.json <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); j["status"] = "diverged"; j["error"] = "made up for the test"
json.dump(j, open(sys.argv[1], "w"))
PY
expect_status 1 "$SIMBOB" sweep gather g
expect_match "failed case named" "$LAST_ERR" "^g/case-0003: error: diverged: made up for the test$"
expect_match "missing case named" "$LAST_ERR" "^g/case-0017: error: missing$"
expect_match "row of the missing case" g/results.csv "^17,1.05,0,missing,,,$"
expect_status 1 "$SIMBOB" sweep gather g --retry
expect_eq "retry list" "$(cat "$LAST_OUT")" "--array=3,17"
check "a failed case is redone by the next run (not skipped), and gather is clean again"
expect_status 0 "$SIMBOB" sweep run box.jsonl -j 2 -o g
expect_status 0 "$SIMBOB" sweep gather g --retry
expect_eq "nothing to retry" "$(cat "$LAST_OUT")" ""

# ---------------------------------------------------------------- atomic case directories
check "a case killed half-way leaves nothing under its final name"
cat >long.json <<JSON
{"scene": "$BOX", "duration": 100000, "vary": [{"param": "Crate.Material.Friction", "values": [0.5]}]}
JSON
expect_status 0 "$SIMBOB" sweep plan long.json -o long.jsonl
"$SIMBOB" sweep run long.jsonl --case 0 -o L 2>/dev/null &
pid=$!
for _ in $(seq 100); do
  compgen -G "L/.case-0000.tmp.*/log" >/dev/null && break
  sleep 0.1
done
compgen -G "L/.case-0000.tmp.*" >/dev/null || fail "the case never started"
sleep 0.5
kill -KILL "$pid"
wait "$pid" 2>/dev/null || true
expect_no_file L/case-0000
check "SIGTERM ends a case with 143 and removes its temporary directory"
"$SIMBOB" sweep run long.jsonl --case 0 -o T 2>/dev/null &
pid=$!
for _ in $(seq 100); do
  compgen -G "T/.case-0000.tmp.*/log" >/dev/null && break
  sleep 0.1
done
sleep 0.5
kill -TERM "$pid"
st=0
wait "$pid" || st=$?
expect_eq "exit status" "$st" 143
expect_no_file T/case-0000
expect_eq "temporaries" "$(compgen -G 'T/.case-*' || true)" ""

# ---------------------------------------------------------------- sbatch
check "sbatch writes an array script, a gather script and a submit script"
expect_status 0 "$SIMBOB" sweep sbatch box.jsonl -o box --max-parallel 4 --partition debug
expect_match "array" box/sweep.sbatch "^#SBATCH --array=0-19%4$"
expect_match "partition" box/sweep.sbatch "^#SBATCH --partition=debug$"
expect_match "runs a case with the absolute binary" box/sweep.sbatch "^exec '$SIMBOB' sweep run '$WORK/box.jsonl' -o '$WORK/box'$"
expect_match "gather" box/gather.sbatch "^exec '$SIMBOB' sweep gather '$WORK/box'$"
expect_match "dependency" box/submit.sh "--dependency=afterany:\\\$job"
bash -n box/submit.sh || fail "submit.sh is not valid sh"
say "ok"

check "sbatch: a value with a control character (partition, -o folder) is refused with 64, nothing written"
for v in $'batch\ntouch X' $'a\rb' $'tab\there' $'del\x7f'; do
  expect_status 64 "$SIMBOB" sweep sbatch box.jsonl -o ctl --partition "$v"
  expect_lines "one-line error for --partition $(printf %q "$v")" "$LAST_ERR" 1
  expect_match "names --partition" "$LAST_ERR" "^simbob: error: --partition '.*' holds a control character"
  expect_status 64 "$SIMBOB" sweep sbatch box.jsonl -o "ctl/$v"
  expect_lines "one-line error for -o $(printf %q "$v")" "$LAST_ERR" 1
  expect_no_file ctl
done
# Slurm's --output reads '%' as a pattern and drops '\' (checked on the test cluster).
expect_status 64 "$SIMBOB" sweep sbatch box.jsonl -o "ctl/100%a"
expect_match "a % in -o" "$LAST_ERR" "holds '%', which Slurm's --output reads as a file-name pattern"
expect_status 64 "$SIMBOB" sweep sbatch box.jsonl -o 'ctl/back\slash'
expect_match "a \\ in -o" "$LAST_ERR" "holds '\\\\', which Slurm's --output reads as a file-name pattern"
expect_no_file ctl
[[ ! -e X ]] || fail "an injected command ran"

check "sbatch: hostile partitions and -o folders stay values: sbatch reads them whole, sh runs no part of them"
# A stand-in for sbatch: records its arguments, prints a job id.
mkdir -p fakebin
cat >fakebin/sbatch <<'SH'
#!/bin/sh
for a in "$@"; do printf '%s\n' "$a"; done >>"$SBATCH_LOG"
echo 4242
SH
chmod +x fakebin/sbatch
# The #SBATCH lines as sbatch reads them (Slurm 22.05 sbatch/opt.c): options end at the first
# line that is neither a comment nor blank; each line's first argument after the option ends at
# an unquoted blank or '#'; "..." groups; '\' escapes the next character.
sbatch_options() {
  /usr/bin/python3 - "$1" <<'PY'
import sys
for line in open(sys.argv[1], encoding="utf-8", errors="surrogateescape").read().split("\n")[1:]:
    if line.strip() and not line.startswith("#"):
        break
    if not line.startswith("#SBATCH "):
        continue
    p, arg, quoted, esc = line[len("#SBATCH "):], "", False, False
    i = 0
    while i < len(p) and (quoted or not p[i].isspace()):
        c = p[i]; i += 1
        if esc: esc = False
        elif c == "\\": esc = True; continue
        elif c == '"': quoted = not quoted; continue
        elif not quoted and c == "#": break
        arg += c
    print(arg)
PY
}
hostile=('$(touch X)' '`touch X`' "it's" 'say "hi"' 'a;touch X' 'with space' 'hash#x' '$HOME' '&&touch X' '|touch X' '*' \
  $'caf\xc3\xa9 \xe2\x80\xae')
n=0
for h in "${hostile[@]}"; do
  n=$((n + 1))
  d="sb$n/$h"
  expect_status 0 "$SIMBOB" sweep sbatch box.jsonl -o "$d" --partition "$h"
  for s in sweep.sbatch gather.sbatch submit.sh; do bash -n "$d/$s" || fail "$d/$s is not valid sh"; done
  sbatch_options "$d/sweep.sbatch" >opts
  expect_eq "sweep.sbatch options for $h" "$(cat opts)" "--job-name=simbob-sweep
--output=$WORK/$d/slurm-%A_%a.out
--partition=$h
--array=0-19
--ntasks=1
--cpus-per-task=1"
  sbatch_options "$d/gather.sbatch" >opts
  expect_eq "gather.sbatch options for $h" "$(cat opts)" "--job-name=simbob-gather
--output=$WORK/$d/slurm-gather-%j.out
--partition=$h
--ntasks=1"
  rm -f sbatch.log
  expect_status 0 env PATH="$WORK/fakebin:$PATH" SBATCH_LOG="$WORK/sbatch.log" sh "$d/submit.sh"
  expect_eq "sbatch's arguments for $h" "$(cat sbatch.log)" "--parsable
$WORK/$d/sweep.sbatch
--parsable
--dependency=afterany:4242
$WORK/$d/gather.sbatch"
  # The scripts themselves, run by sh as a Slurm task would: case 0, then gather.
  expect_status 0 env SLURM_ARRAY_TASK_ID=0 sh "$d/sweep.sbatch"
  expect_file "$d/case-0000/case.json"
  expect_status 1 sh "$d/gather.sbatch"
  expect_lines "gathered table for $h" "$d/results.csv" 21
  [[ ! -e X ]] || fail "an injected command ran (from $h)"
done
# A backslash is refused in -o (above) but is a value in --partition.
expect_status 0 "$SIMBOB" sweep sbatch box.jsonl -o sbb --partition 'back\slash "q"'
sbatch_options sbb/sweep.sbatch >opts
expect_match "partition with a backslash" opts '^--partition=back\\slash "q"$'
say "ok"

# ---------------------------------------------------------------- issue 19: gather, manifests, limits
check "gather: a metric of the wrong type makes its case failed (exit 1), never the gather (70)"
for bad in '"1.5"' null '[1]' '{"a": 1}' true; do
  rm -rf w && cp -r box w
  /usr/bin/python3 - w/case-0002/case.json "$bad" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); j["metrics"]["stop_x"] = json.loads(sys.argv[2])
json.dump(j, open(sys.argv[1], "w"))
PY
  expect_status 1 "$SIMBOB" sweep gather w
  expect_eq "one error line for metric $bad" "$(grep -c ': error: ' "$LAST_ERR")" 1
  expect_match "case 2 failed, the value named" "$LAST_ERR" \
    "^w/case-0002: error: failed: unreadable case.json: metric 'stop_x' is .*, not a number$"
  expect_lines "the table: header + 20 cases" w/results.csv 21
  expect_match "row of case 2: failed, no metrics" w/results.csv '^2,0.3,0,failed,[0-9.e-]+,,$'
done
rm -rf w && cp -r box w
/usr/bin/python3 - w/case-0002/case.json <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); j["status"] = 7
json.dump(j, open(sys.argv[1], "w"))
PY
expect_status 1 "$SIMBOB" sweep gather w
expect_match "status of the wrong type" "$LAST_ERR" "^w/case-0002: error: failed: unreadable case.json: type must be string, but is number$"

check "gather: a status with a comma, a quote and a line break stays one field (RFC 4180)"
rm -rf w && cp -r box w
/usr/bin/python3 - w/case-0004/case.json <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); j["status"] = 'ok,"x"\n99,injected,row'
json.dump(j, open(sys.argv[1], "w"))
PY
expect_status 1 "$SIMBOB" sweep gather w
expect_eq "one error line" "$(grep -c ': error: ' "$LAST_ERR")" 1
expect_eq "one line per message" "$(wc -l <"$LAST_ERR")" 2
/usr/bin/python3 - w/results.csv <<'PY' || fail "results.csv is not the table it should be"
import csv, sys
rows = list(csv.reader(open(sys.argv[1], newline="")))
assert len(rows) == 21, f"{len(rows)} records"
assert all(len(r) == len(rows[0]) for r in rows), "ragged rows"
assert [r[0] for r in rows[1:]] == [str(i) for i in range(20)], [r[0] for r in rows[1:]]
assert rows[5][3] == 'ok,"x"\n99,injected,row', rows[5]
assert rows[5][5] == "" and rows[5][6] == "", "a case that is not ok has no metrics"
PY
# plot reads the quoted table back (the quoted row is not ok, so it is left out).
expect_status 0 "$SIMBOB" plot w/results.csv --x Crate.Material.Friction --y stop_x --out w.png

check "manifest: a seed, case or time out of range is 65 naming the line, never a wrapped value"
head -n 1 box.jsonl >one.jsonl
mbad() {  # mbad JSON-EDIT EXPECTED-MESSAGE-TAIL
  /usr/bin/python3 - one.jsonl m.jsonl "$1" <<'PY'
import json, sys
j = json.loads(open(sys.argv[1]).readline())
k, v = sys.argv[3].split("=", 1)
j[k] = json.loads(v)
open(sys.argv[2], "w").write(json.dumps(j) + "\n")
PY
  rm -rf mo
  expect_status 65 "$SIMBOB" sweep run m.jsonl --case 0 -o mo
  expect_eq "manifest $1" "$(cat "$LAST_ERR")" "m.jsonl:1: error: not a sweep case: $2"
  expect_no_file mo
}
mbad 'seed=-1' "'seed' must be a whole number from 0 to 4294967295, got -1"
mbad 'seed=4294967296' "'seed' must be a whole number from 0 to 4294967295, got 4294967296"
mbad 'seed=1.5' "'seed' must be a whole number from 0 to 4294967295, got 1.5"
mbad 'case=1e20' "'case' must be a whole number from 0 to 999999999, got 1e+20"
mbad 'case=-1' "'case' must be a whole number from 0 to 999999999, got -1"
mbad 'dt=-5' "'dt' must be a number of seconds from 1e-9 to 1e9, got -5"
mbad 'dt=0' "'dt' must be a number of seconds from 1e-9 to 1e9, got 0"
mbad 'duration="1"' "'duration' must be a number of seconds from 1e-9 to 1e9, got \"1\""
mbad 'sample_interval=1e300' "'sample_interval' must be a number of seconds from 1e-9 to 1e9, got 1e+300"

check "plan: the number of cases is checked before any range is expanded (41 ranges of 10^6 values)"
/usr/bin/python3 - "$BOX" >many.json <<'PY'
import json, sys
vary = [{"param": f"Crate.Material.P{i}", "range": {"start": 0, "stop": 1, "count": 1000000}} for i in range(41)]
print(json.dumps({"scene": sys.argv[1], "duration": 1, "vary": vary}))
PY
/usr/bin/python3 - "$SIMBOB" <<'PY' || fail "plan of 41 x 10^6 values"
import resource, subprocess, sys, time
t0 = time.monotonic()
p = subprocess.run([sys.argv[1], "sweep", "plan", "many.json", "-o", "many.jsonl"], capture_output=True, text=True)
wall = time.monotonic() - t0
peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
print(f"exit {p.returncode}, {wall:.2f} s, peak {peak:.0f} MiB: {p.stderr.strip()}")
assert p.returncode == 65, p.returncode
assert p.stderr == "many.json: error: vary: more than 1000000 cases\n", p.stderr
assert peak < 200, f"peak {peak:.0f} MiB"
PY
expect_no_file many.jsonl

check "a trajectory CSV over 4 GiB is 65 (what the file holds), not 66 (a sparse file: no disk spent)"
head -c 200 box/case-0000/trajectory.csv | head -n 1 >huge.csv
truncate -s 4294967297 huge.csv
expect_status 65 "$SIMBOB" plot huge.csv --out huge.png
expect_match "says why" "$LAST_ERR" "^huge.csv: error: cannot read: larger than 4096 MiB$"
expect_no_file huge.png

check "plot: data near +-1e308 is 65 naming the range, never an empty panel with 0"
{
  head -n 1 box/case-0000/trajectory.csv
  printf '0,Crate,1e308,0,0,1,0,0,0\n1,Crate,-1e308,0,0,1,0,0,0\n'
} >far.csv
expect_status 65 "$SIMBOB" plot far.csv --out far.png
expect_eq "message" "$(cat "$LAST_ERR")" "simbob: error: cannot plot x values from -1e+308 to 1e+308: a plot axis spans at most -1e300 to 1e300"
expect_no_file far.png
say "ok"

check "sweep run passes --plugin and --settings to its cases (-j and one --case), and sbatch to its script"
PLUGINS="$(dirname "$SIMBOB")/plugins"
[[ -f "$PLUGINS/square_driver.so" ]] || fail "no $PLUGINS/square_driver.so: the example plug-in is built with simbob"
SQ="$REPO/examples/plugins/square_robot.xml"
cat >sq.json <<JSON
{"scene": "$SQ", "duration": 0.2, "vary": [{"param": "seed", "values": [1, 2]}]}
JSON
expect_status 0 "$SIMBOB" sweep plan sq.json -o sq.jsonl --plugin "$PLUGINS/square_driver.so"
expect_status 0 "$SIMBOB" sweep run sq.jsonl -j 2 -o sqp --plugin "$PLUGINS/square_driver.so"
expect_status 0 "$SIMBOB" sweep gather sqp
# The same through the global settings' ExtensionFolder, one case at a time.
mkdir -p ext && cp "$PLUGINS/square_driver.so" ext/
printf 'ExtensionFolder = ext\n' >sq-settings.ini
expect_status 0 "$SIMBOB" sweep run sq.jsonl --case 0 -o sqs --settings sq-settings.ini
expect_status 0 "$SIMBOB" sweep run sq.jsonl --case 1 -o sqs --settings sq-settings.ini
expect_status 0 "$SIMBOB" sweep gather sqs
expect_same_file sqp/case-0001/trajectory.csv sqs/case-0001/trajectory.csv
# Without them, a case cannot load the scene: failed, not silently something else.
expect_status 65 "$SIMBOB" sweep run sq.jsonl --case 0 -o sqn
expect_status 0 "$SIMBOB" sweep sbatch sq.jsonl -o sqb --plugin "$PLUGINS/square_driver.so"
expect_match "the case line carries --plugin" sqb/sweep.sbatch \
  "^exec '$SIMBOB' sweep run '$WORK/sq.jsonl' -o '$WORK/sqb' --plugin '$PLUGINS/square_driver.so'$"
expect_status 0 env SLURM_ARRAY_TASK_ID=1 sh sqb/sweep.sbatch
expect_same_file sqp/case-0001/trajectory.csv sqb/case-0001/trajectory.csv
expect_status 0 "$SIMBOB" sweep sbatch sq.jsonl -o sqc --settings sq-settings.ini
expect_match "the case line carries --settings" sqc/sweep.sbatch \
  "^exec '$SIMBOB' sweep run '$WORK/sq.jsonl' -o '$WORK/sqc' --settings '$WORK/sq-settings.ini'$"
expect_status 0 env SLURM_ARRAY_TASK_ID=1 sh sqc/sweep.sbatch
expect_same_file sqp/case-0001/trajectory.csv sqc/case-0001/trajectory.csv
say "ok"
