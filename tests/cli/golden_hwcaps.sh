#!/usr/bin/env bash
# Determinism guarded (docs/ci.md): every scene with a golden file (lib.sh's golden_scenes, the
# list golden_regression.sh runs) gives byte-identical trajectories with glibc's CPU-specific code
# paths switched off. With GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX,-AVX2,-FMA,-AVX512F, Debian 12's
# glibc hands libm's callers the code a CPU without those features runs, whose results differ in
# the last bits: a small libm probe shows the switch took effect before the scenes are compared.
# A machine without FMA or AVX2 takes those paths anyway: the test then skips (77), saying so.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
if [[ -n "${SIMBOB_SANITIZED:-}" ]]; then
  # ASan's interceptors change nothing about libm; the slow run would only repeat the normal build's.
  say "SKIP: the sanitizer build; the normal build runs this test"
  exit 77
fi
TUNABLES=glibc.cpu.hwcaps=-AVX,-AVX2,-FMA,-AVX512F

check "a libm probe gives other bits with the CPU-specific paths switched off"
# sin() and exp() of 20,000 arguments, hashed: glibc picks their FMA variants on a CPU with FMA.
probe='
import hashlib, math, struct
h = hashlib.sha256()
for i in range(1, 20001):
    x = i * 0.001237 - 12.0
    h.update(struct.pack("<dd", math.sin(x), math.exp(x / 4)))
print(h.hexdigest())'
plain=$(/usr/bin/python3 -c "$probe")
switched=$(GLIBC_TUNABLES=$TUNABLES /usr/bin/python3 -c "$probe")
if [[ "$plain" == "$switched" ]]; then
  flags=$(grep -m 1 '^flags' /proc/cpuinfo || true)
  if [[ " $flags " != *" fma "* || " $flags " != *" avx2 "* ]]; then
    say "SKIP: this CPU has no FMA or AVX2, so libm takes the generic paths with or without $TUNABLES"
    exit 77
  fi
  fail "GLIBC_TUNABLES=$TUNABLES changed nothing in libm's results on a CPU with FMA and AVX2: the switch did not take effect"
fi
say "probe: $plain (default paths), $switched (switched off)"

check "every golden scene writes the same bytes with the CPU-specific paths switched off"
cd "$REPO"
list=$(golden_scenes)
mapfile -t scenes <<<"$list"
expect_status 0 env GLIBC_TUNABLES=$TUNABLES "$SIMBOB" batch "${scenes[@]}" --duration 10 --out-dir "$WORK/off" -j 2
differ=()
for s in "${scenes[@]}"; do
  name=$(basename "${s%.*}")
  if ! cmp -s "golden/$name.csv" "$WORK/off/$name.csv"; then
    where=$(cmp "golden/$name.csv" "$WORK/off/$name.csv" 2>&1 | head -n 1 || true)
    differ+=("$s: $where")
  fi
done
[[ ${#differ[@]} -eq 0 ]] || fail "not byte-identical with $TUNABLES (docs/ci.md names the causes):
$(printf '%s\n' "${differ[@]}")"
say "PASS: ${#scenes[@]} golden scenes byte-identical with $TUNABLES"
