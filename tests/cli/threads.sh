#!/usr/bin/env bash
# --threads N (docs/performance.md): a world's step on N threads writes the same bytes as on one.
# Every shipped scene on 2 threads, and the swarm, maze, box stack and chain on 3 (robots
# driving, sensors reading), write their golden trajectory byte for byte; the scene's own
# SceneSettings Threads does too; --check-determinism runs its second pass on another thread
# count; a thread count out of range is refused. (That the byte comparison can fail -- contacts
# committed out of order -- is shown in tests/physics_ode/threads_test.cpp.)
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

cd "$REPO"
check "every scene on 2 threads writes golden/ byte for byte"
# Scenes with a socket peer run one at a time (their peers answer within MaxAccessTime even on
# a loaded machine); the others as one batch with --threads 2 from a manifest.
: > "$WORK/manifest"
mkdir -p "$WORK/t2"
for s in scenes/*.xml; do
  name=$(basename "${s%.xml}")
  if needs_peer "$s"; then
    "$SIMBOB" run "$s" --duration 10 --threads 2 --out "$WORK/t2/$name.csv" --quiet
  else
    echo "$REPO/$s --threads 2" >> "$WORK/manifest"
  fi
done
"$SIMBOB" batch --manifest "$WORK/manifest" --duration 10 --out-dir "$WORK/t2" -j 2 --quiet > "$WORK/batch.out" ||
  { cat "$WORK/batch.out"; fail "batch on 2 threads failed"; }
for s in scenes/*.xml; do
  name=$(basename "${s%.xml}")
  cmp "$WORK/t2/$name.csv" "golden/$name.csv" || fail "$name on 2 threads differs from golden/$name.csv"
done

# (One thread is the default: tests/cli/golden_regression.sh runs it.)
for n in 3; do
  check "swarm, maze, box stack and chain on $n threads write golden/ byte for byte"
  for name in swarm maze box_stack chain; do
    "$SIMBOB" run "scenes/$name.xml" --duration 10 --threads "$n" --out "$WORK/$name.$n.csv" --quiet
    cmp "$WORK/$name.$n.csv" "golden/$name.csv" || fail "$name on $n threads differs from golden/$name.csv"
  done
done

check "SceneSettings Threads is no scene setting any more: refused (65) with what to use instead, in a file and by --set"
cat >"$WORK/threads_setting.xml" <<'EOF'
<Simulation>
  <SceneSettings>
    <Threads Value="3"/>
  </SceneSettings>
  <ComponentList><RCGround Key="G"/></ComponentList>
</Simulation>
EOF
set +e
"$SIMBOB" check "$WORK/threads_setting.xml" 2> "$WORK/ts.err"
rc=$?
set -e
[[ $rc -eq 65 ]] || fail "a scene with Threads: exit $rc, expected 65"
grep -qxF "$WORK/threads_setting.xml:3: error: SceneSettings 'SceneSettings': parameter 'Threads' removed: the thread count is no scene setting since 2026-12-06: give \`--threads N\` to the command (the same bytes for every count)" "$WORK/ts.err" ||
  { cat "$WORK/ts.err"; fail "no advice for a scene's Threads"; }

check "--check-determinism runs its second pass on another thread count"
"$SIMBOB" run scenes/box_stack.xml --duration 1 --out "$WORK/cd1.csv" --check-determinism -v 2> "$WORK/cd1.err"
grep -qF "running the scene a second time, on 2 threads (the first on 1)" "$WORK/cd1.err" ||
  { cat "$WORK/cd1.err"; fail "the second pass of a 1-thread run is not on 2 threads"; }
"$SIMBOB" run scenes/box_stack.xml --duration 1 --threads 3 --out "$WORK/cd3.csv" --check-determinism -v 2> "$WORK/cd3.err"
grep -qF "running the scene a second time, on 1 thread (the first on 3)" "$WORK/cd3.err" ||
  { cat "$WORK/cd3.err"; fail "the second pass of a 3-thread run is not on 1 thread"; }

check "a thread count out of range is refused (64, usage)"
for bad in 0 65; do
  set +e
  "$SIMBOB" run scenes/box_stack.xml --duration 1 --threads "$bad" --out "$WORK/bad.csv" 2> "$WORK/bad.err"
  rc=$?
  set -e
  [[ $rc -eq 64 ]] || fail "--threads $bad: exit $rc, expected 64"
  [[ ! -e "$WORK/bad.csv" ]] || fail "--threads $bad wrote output"
done
set +e
"$SIMBOB" run scenes/box_stack.xml --duration 1 --set SceneSettings.Threads=3 --out "$WORK/bad.csv" 2> "$WORK/bad.err"
rc=$?
set -e
[[ $rc -eq 65 ]] || fail "--set SceneSettings.Threads=3: exit $rc, expected 65"
grep -qF "parameter 'Threads' removed: the thread count is no scene setting since 2026-12-06" "$WORK/bad.err" ||
  { cat "$WORK/bad.err"; fail "no advice for --set SceneSettings.Threads"; }
[[ ! -e "$WORK/bad.csv" ]] || fail "--set SceneSettings.Threads wrote output"
say PASS
