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
