#!/usr/bin/env bash
# `simbob view` on the command line (issue #23): it writes one self-contained page (three.js
# inlined from Debian's libjs-three, the data in it, nothing fetched); bad inputs fail with one
# line naming the file (and line), with sysexits statuses, and never replace an existing page.
# The page itself is driven in a browser by tests/view/browser_test.py.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
SCENE="$SCENES/pendulum.xml"
"$SIMBOB" run "$SCENE" --duration 0.2 --out pend.csv 2>/dev/null

check "view writes a page with three.js and the viewer inlined, and no address to fetch"
expect_status 0 "$SIMBOB" view pend.csv --scene "$SCENE" -o page.html --title "Pendulum <1>"
expect_file page.html
grep -q 'REVISION="111"' page.html || fail "three.js r111 is not inlined"
grep -q 'OrbitControls' page.html || fail "OrbitControls is not inlined"
grep -q 'window.simbobView' page.html || fail "the viewer is not inlined"
grep -q '<title>Pendulum &lt;1&gt;</title>' page.html || fail "the title is not escaped: $(grep -o '<title>.*</title>' page.html)"
if grep -Eo '(src|href)="[^"#]+' page.html | grep -v '^href="data:'; then fail "the page refers to a file or address"; fi
expect_match "it says where" "$LAST_ERR" "^simbob: wrote page.html$"

# An existing page, to see it is never replaced by a failed run.
printf 'old page\n' >old.html

check "a missing trajectory: 66 naming it; the old page stays"
expect_status 66 "$SIMBOB" view nothere.csv --scene "$SCENE" -o old.html
expect_match "names the file" "$LAST_ERR" "nothere.csv"
expect_eq "old page kept" "$(cat old.html)" "old page"

check "a malformed trajectory: 65 with file:line; the old page stays"
printf 'time,body,x,y,z,qw,qx,qy,qz\n0,A,1,2,3,1,0,0,0\n0.1,A,1,2\n' >bad.csv
expect_status 65 "$SIMBOB" view bad.csv --scene "$SCENE" -o old.html
expect_match "file:line" "$LAST_ERR" "^bad.csv:3: error: "
expect_eq "old page kept" "$(cat old.html)" "old page"

check "a broken scene: 65 with file:line; a golden that cannot be read: 66"
printf '<Simulation>\n<ComponentList>\n<RCNoSuchThing/>\n' >broken.xml
expect_status 65 "$SIMBOB" view pend.csv --scene broken.xml -o old.html
expect_match "file:line" "$LAST_ERR" "broken.xml:[0-9]+: "
expect_status 66 "$SIMBOB" view pend.csv --scene "$SCENE" --golden nothere.csv -o old.html
expect_eq "old page kept" "$(cat old.html)" "old page"

check "no three.js (libjs-three not installed): 66 naming the file and the package; the old page stays"
SIMBOB_THREE_DIR="$WORK/none" expect_status 66 "$SIMBOB" view pend.csv --scene "$SCENE" -o old.html
expect_match "names three.js" "$LAST_ERR" "none/three.min.js: error: cannot read three.js: .*install Debian.s libjs-three"
expect_eq "old page kept" "$(cat old.html)" "old page"

check "an output that cannot be created: 73; the page may not overwrite an input: 64"
expect_status 73 "$SIMBOB" view pend.csv --scene "$SCENE" -o nodir/page.html
expect_status 64 "$SIMBOB" view pend.csv --scene "$SCENE" -o pend.csv
expect_eq "the trajectory is untouched" "$(head -n 1 pend.csv)" "time,body,x,y,z,qw,qx,qy,qz"
expect_status 64 "$SIMBOB" view pend.csv --scene "$SCENE"
check "compare --html needs --scene (64, nothing written); with it, the page of the comparison"
expect_status 64 "$SIMBOB" compare pend.csv pend.csv --html cmp.html
expect_match "says why" "$LAST_ERR" "--html and --scene go together"
expect_no_file cmp.html
expect_status 0 "$SIMBOB" compare pend.csv pend.csv --html cmp.html --scene "$SCENE"
grep -q '"compare":{' cmp.html || fail "the comparison is not in the page"
check "run --html writes the page after the trajectory, with the run's --set; --html may not be --out (64, before the run)"
expect_status 0 "$SIMBOB" run "$SCENE" --duration 0.1 --out r.csv --html r.html --set "SceneSettings.Gravity=0 -1 0"
expect_file r.csv
expect_file r.html
grep -q '"actual":{"bodies":\["' r.html || fail "no trajectory in the page"
expect_status 64 "$SIMBOB" run "$SCENE" --duration 0.1 --out r2.csv --html r2.csv
expect_no_file r2.csv
expect_status 64 "$SIMBOB" run "$SCENE" --duration 0.1 --out - --html r3.html
expect_no_file r3.html
say "ok"
