#!/usr/bin/env bash
# Global settings INI (guide 3.3.1) and logging: --settings FILE with LogFile, --log-file,
# -v/--quiet levels.
set -euo pipefail
simbob=$1
repo=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail() { echo "FAIL: $*"; exit 1; }

# Keys are case-insensitive (INI, guide 4.1).
mkdir ext # ExtensionFolder must exist (an empty one loads no plug-ins)
printf 'logfile = from-settings.log\nTextureFolder = textures\nExtensionFolder = ext\n' > settings.ini
"$simbob" run "$repo/scenes/pendulum.xml" --duration 0.1 --out a.csv --settings settings.ini 2> err.txt
grep -q "simbob: wrote a.csv" from-settings.log || fail "LogFile from --settings not written: $(cat from-settings.log 2>/dev/null)"
grep -q "simbob: wrote a.csv" err.txt || fail "info line missing on stderr"

"$simbob" run "$repo/scenes/pendulum.xml" --duration 0.1 --out b.csv --quiet --log-file quiet.log 2> err.txt
[ ! -s err.txt ] || fail "--quiet printed: $(cat err.txt)"
grep -q "simbob: wrote b.csv" quiet.log || fail "--log-file misses what --quiet kept off stderr"

"$simbob" run "$repo/scenes/pendulum.xml" --duration 0.1 --out c.csv -v 2> err.txt
grep -q "simbob: running .*: 1 mobile body, " err.txt || fail "-v did not print debug lines: $(cat err.txt)"

printf 'LogFil = x.log\n' > bad.ini
set +e
"$simbob" run "$repo/scenes/pendulum.xml" --duration 0.1 --out d.csv --settings bad.ini 2> err.txt
status=$?
set -e
[ $status -eq 65 ] || fail "bad settings key should exit 65, got $status"
grep -q "bad.ini:1: error: GlobalSettings: parameter 'LogFil' unknown (did you mean 'LogFile'?)" err.txt ||
  fail "bad settings message: $(cat err.txt)"
[ ! -e d.csv ] || fail "a run with bad settings wrote output"
echo PASS
