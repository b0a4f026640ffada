#!/usr/bin/env bash
# simbob batch: worker processes, golden comparison, a crashing scene, determinism across -j,
# manifests, and compare --bless.
set -euo pipefail
simbob=$1
repo=$2
tmp=$(mktemp -d)
trap 'pkill -P $$ 2>/dev/null || true; rm -rf "$tmp"' EXIT
cd "$tmp"
fail() { echo "FAIL: $*"; exit 1; }
cp "$repo/scenes/pendulum.xml" "$repo/scenes/chain.xml" .

echo "== determinism across -j: -j1 and -j2 give identical bytes"
"$simbob" batch pendulum.xml chain.xml --duration 2 --out-dir j1 -j 1 >/dev/null
"$simbob" batch pendulum.xml chain.xml --duration 2 --out-dir j2 -j 2 >/dev/null
cmp j1/pendulum.csv j2/pendulum.csv || fail "pendulum differs between -j1 and -j2"
cmp j1/chain.csv j2/chain.csv || fail "chain differs between -j1 and -j2"
"$simbob" run pendulum.xml --duration 2 --out single.csv --quiet
cmp single.csv j1/pendulum.csv || fail "batch result differs from a single run"

echo "== golden: matching results pass, a moved scene fails naming the first divergence"
mkdir golden
cp j1/pendulum.csv j1/chain.csv golden/
"$simbob" batch pendulum.xml chain.xml --duration 2 --out-dir g1 --golden golden -j 2 > g1.txt
grep -q "2 of 2 scenes ok" g1.txt || fail "golden pass not reported: $(cat g1.txt)"
# Release the pendulum from 31 instead of 30 degrees: the trajectory moves.
sed 's/0 0 0 0 0 30/0 0 0 0 0 31/' pendulum.xml > moved.xml
grep -q "0 0 0 0 0 31" moved.xml || fail "test scene edit did not apply"
cp golden/pendulum.csv golden/moved.csv
set +e
"$simbob" batch moved.xml chain.xml --duration 2 --out-dir g2 --golden golden -j 2 > g2.txt
status=$?
set -e
[ $status -eq 1 ] || fail "golden mismatch should exit 1, got $status"
grep -q "mismatch" g2.txt || fail "mismatch not reported: $(cat g2.txt)"
grep -q "first divergence at t=0 s, body 'Pendulum.Hinge.Bob'" g2.txt || fail "first divergence not named: $(cat g2.txt)"
[ -f g2/moved.compare.txt ] || fail "no compare report written"
grep -q "1 of 2 scenes ok" g2.txt || fail "summary wrong: $(cat g2.txt)"

echo "== a missing golden file is a failure, not a pass"
set +e
"$simbob" batch pendulum.xml --duration 1 --out-dir g3 --golden empty-golden >g3.txt
status=$?
set -e
[ $status -eq 1 ] || fail "missing golden should exit 1, got $status"
grep -q "no golden file" g3.txt || fail "missing golden not reported"

echo "== an invalid scene is reported and the others still finish"
printf '<Simulation><ComponentList><RCNoSuchThing/></ComponentList></Simulation>\n' > bad.xml
set +e
"$simbob" batch bad.xml pendulum.xml --duration 1 --out-dir b1 -j 2 > b1.txt
status=$?
set -e
[ $status -eq 1 ] || fail "a failed scene should make batch exit 1, got $status"
grep -q "failed  bad.xml" b1.txt || fail "failed scene not reported: $(cat b1.txt)"
grep -q "bad.xml:1: error: unknown component type 'RCNoSuchThing'" b1.txt || fail "scene error not shown: $(cat b1.txt)"
[ -s b1/pendulum.csv ] || fail "the good scene did not finish"
# The refused worker's outcome is in its summary, where batch reads every failed worker's error.
[ -s b1/bad.partial.json ] || fail "the refused scene left no partial summary: $(ls b1)"
/usr/bin/python3 - b1/bad.partial.json <<'PY' || fail "refusal summary: $(cat b1/bad.partial.json)"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["status"] == "refused", s
assert s["error"]["text"] == "bad.xml:1: error: unknown component type 'RCNoSuchThing'", s
assert s["error"]["file"] == "bad.xml" and s["error"]["line"] == 1, s
PY

echo "== a crashing worker (killed by SIGKILL) is reported and the others still finish"
"$simbob" batch pendulum.xml chain.xml --duration 100000 --out-dir c1 -j 2 > c1.txt &
batch_pid=$!
victim=""
for _ in $(seq 1 50); do
  # Only this batch's own workers: other tests may run chain.xml at the same time.
  victim=$(pgrep -P $batch_pid -f "simbob run .*chain.xml" || true)
  [ -n "$victim" ] && break
  sleep 0.1
done
[ -n "$victim" ] || fail "worker for chain.xml not found"
kill -KILL $victim
sleep 0.5
other=$(pgrep -P $batch_pid -f "simbob run .*pendulum.xml" || true)
[ -n "$other" ] && kill -INT $other
set +e
wait $batch_pid
status=$?
set -e
[ $status -eq 1 ] || fail "batch with a crashed worker should exit 1, got $status: $(cat c1.txt)"
grep -q "crashed  chain.xml" c1.txt || fail "crash not reported: $(cat c1.txt)"
grep -q "signal 9" c1.txt || fail "signal not named: $(cat c1.txt)"
grep -q "interrupted  pendulum.xml" c1.txt || fail "the other scene did not finish on its own terms: $(cat c1.txt)"
[ -s c1/pendulum.partial.csv ] || fail "the interrupted scene kept no partial trajectory"

echo "== manifest: paths relative to the manifest, per-scene options"
mkdir -p m/scenes
cp pendulum.xml m/scenes/
cat > m/list.txt <<'LIST'
# scene, then simbob run options
scenes/pendulum.xml --duration 1 --sample-interval 0.5 --out outputs/p.csv
LIST
mkdir -p m/outputs
"$simbob" batch --manifest m/list.txt --out-dir m/out > m.txt
[ "$(wc -l < m/outputs/p.csv)" -eq 4 ] || fail "manifest options not applied: $(cat m/outputs/p.csv)"

echo "== compare --bless replaces the golden file after showing the change"
cp golden/pendulum.csv old.csv
"$simbob" run moved.xml --duration 2 --out moved.csv --quiet
set +e
"$simbob" compare moved.csv old.csv > cmp.txt
status=$?
set -e
[ $status -eq 1 ] || fail "compare of a moved trajectory should exit 1, got $status"
"$simbob" compare moved.csv old.csv --bless > bless.txt
cmp moved.csv old.csv || fail "--bless did not replace the golden file"
"$simbob" compare moved.csv old.csv > /dev/null || fail "after --bless the files should match"

echo "== --artifacts: a scene named ...xml or index.html.xml stays in its own folder (issue 43, item 3)"
mkdir -p confine/scenes confine/golden
cp pendulum.xml confine/scenes/...xml
cp pendulum.xml confine/scenes/index.html.xml
cp pendulum.xml confine/scenes/Index.HTML.xml
set +e
"$simbob" batch confine/scenes/...xml confine/scenes/index.html.xml confine/scenes/Index.HTML.xml --duration 0.1 \
  --out-dir confine/out --golden confine/golden --artifacts confine/art/dir >confine.txt
status=$?
set -e
[ $status -eq 1 ] || fail "scenes without golden files should exit 1, got $status: $(cat confine.txt)"
# Nothing beside the artifacts folder: no view.html, plot.png, summary.json in its parent.
[ "$(ls -A confine/art)" = "dir" ] || fail "batch wrote beside the artifacts folder: $(ls -A confine/art)"
grep -q '<p id="counts">0 passed, 3 failed' confine/art/dir/index.html || fail "index.html is not the index: $(head -c 300 confine/art/dir/index.html)"
for d in _.. index.html-2 Index.HTML-3; do
  [ -s "confine/art/dir/$d/summary.json" ] || fail "no case folder $d: $(ls -A confine/art/dir)"
done
grep -q 'href="./_../summary.json"' confine/art/dir/index.html || fail "index.html does not link ./_../summary.json"
[ "$(ls -A confine/art/dir | wc -l)" -eq 4 ] || fail "unexpected entries: $(ls -A confine/art/dir)"
echo "PASS"
