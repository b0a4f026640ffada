#!/usr/bin/env bash
# SIGINT and SIGTERM stop a run at the next step: exit 130 / 143, the samples so far kept in
# NAME.partial.csv, NAME.csv never created.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

# interrupt SIGNAL EXPECTED_STATUS NAME
interrupt() {
  local sig=$1 want=$2 name=$3 pid status=0 i
  check "SIG$sig: a 100000 s run of box_stack, interrupted after a second, exits $want"
  "$SIMBOB" run "$SCENES/box_stack.xml" --duration 100000 --out "$name.csv" >"$name.out" 2>"$name.err" &
  pid=$!
  # Wait until the run has started (its temporary trajectory exists), then let it run a while.
  for ((i = 0; i < 100; i++)); do
    compgen -G "$name.csv.tmp*" >/dev/null && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  sleep 1
  kill -0 "$pid" 2>/dev/null || fail "the run ended before it was signalled: $(cat "$name.err")"
  kill -"$sig" "$pid"
  # It must stop promptly; never leave it running.
  for ((i = 0; i < 100; i++)); do
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  if kill -0 "$pid" 2>/dev/null; then
    kill -KILL "$pid"
    wait "$pid" || true
    fail "SIG$sig did not stop the run within 10 s"
  fi
  wait "$pid" || status=$?
  expect_eq "exit status after SIG$sig" "$status" "$want"
  expect_match "the error says it was interrupted" "$name.err" "error: interrupted at t="
  expect_match "stderr names the partial trajectory" "$name.err" "$name.partial.csv"

  check "SIG$sig: $name.partial.csv holds whole samples from t = 0; no $name.csv, no .json"
  expect_no_file "$name.csv"
  expect_no_file "$name.json"
  expect_file "$name.partial.csv"
  local summary samples bodies rows first last
  summary=$(csv_summary "$name.partial.csv")
  read -r samples bodies rows first last <<<"$summary"
  expect_eq "bodies in the partial trajectory" "$bodies" 6
  expect_eq "first time" "$first" "0.0"
  expect_eq "rows = samples * bodies" "$rows" "$((samples * bodies))"
  [[ $samples -ge 2 ]] || fail "only $samples samples after running a second"
  local leftovers
  leftovers=$(find . -name "$name.*tmp*")
  expect_eq "temporary files" "$leftovers" ""
}

interrupt INT 130 int
interrupt TERM 143 term
say "ok"
