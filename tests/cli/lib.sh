#!/usr/bin/env bash
# Helpers for the end-to-end CLI tests in tests/cli/*.sh.
#
# Each test script is run by ctest as   bash SCRIPT.sh /path/to/simbob /path/to/repo
# and starts with
#     source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
#     cli_setup "$@"
# which sets SIMBOB, REPO and SCENES, makes a fresh `mktemp -d` directory WORK (removed on
# exit) and changes into it.
#
# This file is itself matched by the tests/cli/*.sh glob, so ctest runs it as the test
# "cli.lib": executed directly, it checks its own helpers (see the end of the file).

set -euo pipefail

# This directory (absolute: the tests change into their work directory).
CLI_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

# ---------------------------------------------------------------- reporting
say() { printf '%s\n' "$*"; }
# One line per check, so a failing ctest log shows how far the test got.
check() { printf 'check: %s\n' "$*"; }
fail() {
  printf 'FAIL: %s\n' "$*" >&2
  exit 1
}

# ---------------------------------------------------------------- setup
cli_setup() {
  if [[ $# -lt 2 ]]; then
    fail "usage: bash $(basename "$0") /path/to/simbob /path/to/repo"
  fi
  SIMBOB=$(realpath "$1")
  REPO=$(realpath "$2")
  SCENES="$REPO/scenes"
  [[ -x "$SIMBOB" ]] || fail "not an executable: $SIMBOB"
  [[ -d "$SCENES" ]] || fail "no scenes directory: $SCENES"
  command -v python3 >/dev/null || fail "python3 is needed to read CSV and JSON output"
  WORK=$(mktemp -d "${TMPDIR:-/tmp}/simbob-cli.XXXXXX")
  trap 'rm -rf "$WORK"' EXIT
  cd "$WORK"
  export SIMBOB REPO SCENES WORK
}

# Every shipped scene (scenes/*.xml; scenes/parts/ holds pieces, not scenes) that runs on its
# own: a scene with an RCLocalSocketCommunicator talks to a peer program (which it starts itself,
# its Controller), so the generic scene tests leave it to tests/cli/controller.sh, socket.sh and
# golden_regression.sh.
shipped_scenes() {
  local f
  for f in "$SCENES"/*.xml; do
    needs_peer "$f" || printf '%s\n' "$f"
  done
}
# needs_peer SCENE: true if the scene talks to a peer over a socket.
needs_peer() { grep -q '<RCLocalSocketCommunicator' "$1"; }

# golden_scenes: every scene that has a golden trajectory, one path a line relative to REPO
# (scenes/NAME.EXT for each golden/NAME.csv). Fails naming a scenes/*.xml without its golden
# file, or a golden file without exactly one scene of its name. golden_regression.sh and
# golden_hwcaps.sh both run this list: a new scene with its golden file is in both, unedited.
golden_scenes() {
  local f s name
  local -a found
  for f in "$REPO"/scenes/*.xml; do
    name=$(basename "${f%.xml}")
    [[ -f "$REPO/golden/$name.csv" ]] || fail "no golden/$name.csv for scenes/$name.xml (run scripts/update-golden.sh)"
  done
  for f in "$REPO"/golden/*.csv; do
    name=$(basename "${f%.csv}")
    found=()
    for s in "$REPO/scenes/$name".*; do
      [[ -f "$s" && "$s" != *.sweep.json ]] && found+=("$s")
    done
    [[ ${#found[@]} -eq 1 ]] ||
      fail "golden/$name.csv: ${#found[@]} scenes named scenes/$name.* (expected exactly one: ${found[*]:-none})"
    printf 'scenes/%s\n' "$(basename "${found[0]}")"
  done
}

# ---------------------------------------------------------------- running commands
# expect_status CODE CMD [ARGS...]
#   Runs CMD with stdout in $WORK/last.out and stderr in $WORK/last.err (also LAST_OUT and
#   LAST_ERR) and fails unless it exits with CODE. Never lets `set -e` abort on its own.
expect_status() {
  local want=$1
  shift
  LAST_OUT="$WORK/last.out"
  LAST_ERR="$WORK/last.err"
  local got=0
  "$@" >"$LAST_OUT" 2>"$LAST_ERR" || got=$?
  if [[ "$got" != "$want" ]]; then
    {
      printf 'FAIL: expected exit status %s, got %s from:\n  %s\n' "$want" "$got" "$*"
      printf -- '--- stdout (first 20 lines):\n'
      head -n 20 "$LAST_OUT"
      printf -- '--- stderr (first 20 lines):\n'
      head -n 20 "$LAST_ERR"
    } >&2
    exit 1
  fi
}

# ---------------------------------------------------------------- assertions
expect_eq() {  # expect_eq WHAT ACTUAL EXPECTED
  [[ "$2" == "$3" ]] || fail "$1: got '$2', expected '$3'"
}
expect_file() {
  [[ -f "$1" ]] || fail "expected file $1 to exist"
  return 0
}
expect_no_file() {
  [[ ! -e "$1" ]] || fail "expected $1 not to exist"
  return 0
}
# expect_match WHAT FILE ERE: some line of FILE matches the extended regular expression.
expect_match() {
  grep -Eq -- "$3" "$2" || fail "$1: no line of $2 matches /$3/; it holds:
$(head -n 20 "$2")"
}
# expect_lines WHAT FILE N: FILE has exactly N lines.
expect_lines() {
  local n
  n=$(wc -l <"$2")
  [[ "$n" -eq "$3" ]] || fail "$1: $2 has $n lines, expected $3:
$(head -n 20 "$2")"
}
# expect_same_file A B: byte-identical.
expect_same_file() {
  cmp -s -- "$1" "$2" || fail "$1 and $2 differ: $(cmp -- "$1" "$2" 2>&1 | head -n 1)"
}

# ---------------------------------------------------------------- trajectories
# csv_summary CSV: checks the trajectory contract and prints "SAMPLES BODIES ROWS FIRST LAST":
#   header exactly time,body,x,y,z,qw,qx,qy,qz; 9 fields a row; every number finite; times
#   never decrease; each sample has one row per body, the same bodies in the same order.
csv_summary() {
  python3 - "$1" <<'PY'
import math, sys
path = sys.argv[1]
def bad(msg):
    sys.exit(f"FAIL: {path}: {msg}")
with open(path, newline="") as f:
    lines = f.read().split("\n")
if lines[-1] != "":
    bad("does not end with a newline")
lines.pop()
if not lines:
    bad("empty file")
if lines[0] != "time,body,x,y,z,qw,qx,qy,qz":
    bad(f"header is {lines[0]!r}")
samples = []  # [(time, [bodies])]
for n, line in enumerate(lines[1:], start=2):
    fields = line.split(",")
    if len(fields) != 9:
        bad(f"line {n}: {len(fields)} fields")
    try:
        t = float(fields[0])
        nums = [float(x) for x in fields[2:]]
    except ValueError:
        bad(f"line {n}: not a number: {line}")
    if not all(math.isfinite(x) for x in [t] + nums):
        bad(f"line {n}: non-finite number: {line}")
    if samples and t < samples[-1][0]:
        bad(f"line {n}: time goes backwards")
    if not samples or t != samples[-1][0]:
        samples.append((t, []))
    samples[-1][1].append(fields[1])
if not samples:
    bad("no rows")
bodies = samples[0][1]
for t, b in samples:
    if b != bodies:
        bad(f"sample t={t} has bodies {b}, the first sample has {bodies}")
if len(set(bodies)) != len(bodies):
    bad(f"duplicate body in a sample: {bodies}")
print(len(samples), len(bodies), len(lines) - 1, repr(samples[0][0]), repr(samples[-1][0]))
PY
}

# json_get FILE EXPR: prints the Python expression EXPR evaluated with j = the parsed JSON.
json_get() {
  python3 -c 'import json, sys; j = json.load(open(sys.argv[1])); print(eval(sys.argv[2]))' "$1" "$2"
}

# json_fields FILE KEY...: prints the top-level values of KEY..., one a line, with a single
# python run; fails if a key is missing. Assign before splitting so that `set -e` sees a
# failure:   vals=$(json_fields f.json a b); mapfile -t v <<<"$vals"
json_fields() {
  python3 - "$@" <<'PY'
import json, sys
path, keys = sys.argv[1], sys.argv[2:]
j = json.load(open(path))
for k in keys:
    if k not in j:
        sys.exit(f"FAIL: {path}: no key {k!r}")
    print(j[k])
PY
}

# float_between WHAT VALUE LOW HIGH
float_between() {
  python3 -c 'import sys; v, lo, hi = map(float, sys.argv[1:4]); sys.exit(0 if lo <= v <= hi else 1)' \
    "$2" "$3" "$4" || fail "$1: $2 is not within [$3, $4]"
}

# ---------------------------------------------------------------- self-test
if [[ "${BASH_SOURCE[0]}" == "$0" ]]; then
  cli_setup "$@"
  check "expect_status accepts the right status and captures the output"
  expect_status 0 true
  expect_status 3 bash -c 'echo out; echo err >&2; exit 3'
  expect_eq "captured stdout" "$(cat "$LAST_OUT")" out
  expect_eq "captured stderr" "$(cat "$LAST_ERR")" err
  check "expect_status fails on a wrong status"
  if (expect_status 0 false) 2>/dev/null; then fail "expect_status 0 false passed"; fi
  if (expect_status 1 true) 2>/dev/null; then fail "expect_status 1 true passed"; fi
  check "csv_summary accepts a good trajectory and rejects bad ones"
  printf 'time,body,x,y,z,qw,qx,qy,qz\n0,A,0,1,0,1,0,0,0\n0,B,0,1,0,1,0,0,0\n0.5,A,0,1,0,1,0,0,0\n0.5,B,0,1,0,1,0,0,0\n' >good.csv
  expect_eq "summary" "$(csv_summary good.csv)" "2 2 4 0.0 0.5"
  printf 'time,body,x,y,z,qw,qx,qy,qz\n0,A,nan,1,0,1,0,0,0\n' >nan.csv
  printf 'time,body,x,y,z,qw,qx,qy,qz\n0,A,0,1,0,1,0,0,0\n0,B,0,1,0,1,0,0,0\n1,A,0,1,0,1,0,0,0\n' >missing.csv
  printf 'time,body,x,y,z\n0,A,0,1,0\n' >header.csv
  for f in nan missing header; do
    if csv_summary $f.csv >/dev/null 2>&1; then fail "csv_summary accepted $f.csv"; fi
  done
  check "the shipped scenes are found"
  [[ $(shipped_scenes | wc -l) -ge 1 ]] || fail "no scenes"
  say "ok"
fi
