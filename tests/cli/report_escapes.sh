#!/usr/bin/env bash
# Reports print input text as error messages do (issue 31, item 5): control bytes (ESC, BEL,
# CR, ...) in body names and file names reach the terminal as \xNN, never raw -- in compare's
# table, its "bodies only in" and "missing rows" lines, its first divergence, the paths it
# names, and the --report file.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

# no_raw_control FILE: no byte below 0x20 but newline, and no DEL.
no_raw_control() {
  /usr/bin/python3 - "$1" <<'PY'
import sys
data = open(sys.argv[1], 'rb').read()
bad = sorted({b for b in data if (b < 0x20 and b != 0x0A) or b == 0x7F})
if bad:
    sys.exit(f"FAIL: {sys.argv[1]} holds raw control bytes {[hex(b) for b in bad]}")
PY
}

CLEAR=$'Bot\e[2J'
TITLE=$'Arm\e]0;pwned\a'
CR=$'Cart\rX'
printf 'time,body,x,y,z,qw,qx,qy,qz\n0,%s,0,0,0,1,0,0,0\n0,%s,0,0,0,1,0,0,0\n0,Only,0,0,0,1,0,0,0\n0.5,%s,0,0,0,1,0,0,0\n0.5,%s,1,0,0,1,0,0,0\n0.5,Only,0,0,0,1,0,0,0\n' \
  "$CLEAR" "$TITLE" "$CLEAR" "$TITLE" >$'act\e[1mual.csv'
printf 'time,body,x,y,z,qw,qx,qy,qz\n0,%s,0,0,0,1,0,0,0\n0,%s,0,0,0,1,0,0,0\n0,%s,0,0,0,1,0,0,0\n0.5,%s,0,0,0,1,0,0,0\n0.5,%s,0,0,0,1,0,0,0\n0.5,%s,0,0,0,1,0,0,0\n' \
  "$CLEAR" "$TITLE" "$CR" "$CLEAR" "$TITLE" "$CR" >golden.csv

check "compare: the table, the 'bodies only in' lines, the divergence and the paths are escaped"
expect_status 1 "$SIMBOB" compare $'act\e[1mual.csv' golden.csv --report report.txt
no_raw_control "$LAST_OUT"
no_raw_control report.txt
expect_match "the table names the body escaped" "$LAST_OUT" '^Bot\\x1B\[2J +'
expect_match "the title escape" "$LAST_OUT" '^Arm\\x1B\]0;pwned\\x07 '
expect_match "only in golden" "$LAST_OUT" '^bodies only in golden: Cart\\x0DX$'
expect_match "only in actual" "$LAST_OUT" '^bodies only in actual: Only$'
expect_match "the divergence" "$LAST_OUT" '^first divergence: t=0.5 body Arm\\x1B\]0;pwned\\x07:'
expect_match "the path" "$LAST_OUT" '^actual: act\\x1B\[1mual.csv$'

check "batch: scene paths and error lines reach the terminal escaped (issue 43, item 4)"
cp "$SCENES/pendulum.xml" $'pend\e]0;pwned\aulum.xml'
printf '<Simulation><ComponentList><RCNoSuchThing/></ComponentList></Simulation>\n' >$'bad\e[2J.xml'
expect_status 1 "$SIMBOB" batch $'pend\e]0;pwned\aulum.xml' $'bad\e[2J.xml' --duration 0.1 --out-dir b-out \
  --golden no-golden -j 1 --report b-report.txt
no_raw_control "$LAST_OUT"
no_raw_control "$LAST_ERR"
no_raw_control b-report.txt
expect_match "the progress line" "$LAST_OUT" '^\[[12]/2\] ok  pend\\x1B\]0;pwned\\x07ulum\.xml  '
expect_match "the error line" "$LAST_OUT" '^\[[12]/2\] failed  bad\\x1B\[2J\.xml  .* -- bad\\x1B\[2J\.xml:1: error: '
expect_match "the table" "$LAST_OUT" '^pend\\x1B\]0;pwned\\x07ulum\.xml +ok '
say "ok"
