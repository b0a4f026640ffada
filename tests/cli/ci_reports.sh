#!/usr/bin/env bash
# simbob in CI (issue #29, docs/ci.md): `batch --golden --junit --artifacts --summary-md` on
# scenes/*.xml with one golden file perturbed, one scene broken and one golden file missing:
# the JUnit report validates against Jenkins xunit's junit-10 rules and Ant's strict schema
# (tests/ci/xunit-junit-10.xsd, ant-junit.xsd) as well as tests/ci/junit.xsd, and holds exactly
# 2 failures (the missing golden file is one: issue 45) and 1 error, each reason in its body
# with FILE:LINE first; the artifacts exist and the failed scene's replay page opens in
# headless Chromium with its ghosts and the divergence marked (tests/view/browser_test.py
# artifacts); the Markdown summary lists the three. Then --junit-extended, --allow-missing-golden,
# --suite-name, GitHub annotations, a failing controller's own words (the same text on two runs),
# --bless (refused after a failed run, then showing each change), compare --junit and sweep
# gather --junit. Everything runs on copies in a temporary folder: the repository's golden/ is
# never touched.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
command -v xmllint >/dev/null || fail "xmllint is needed (Debian's libxml2-utils: scripts/deps.sh test)"
# validate FILE [SCHEMA...]: against each (default: Jenkins' and Ant's strict rules and junit.xsd).
validate() {
  local f=$1 x
  shift
  (($#)) || set -- xunit-junit-10.xsd ant-junit.xsd junit.xsd
  for x in "$@"; do
    xmllint --noout --schema "$REPO/tests/ci/$x" "$f" 2>"$WORK/xmllint.err" || fail "$f does not validate against $x: $(cat "$WORK/xmllint.err")"
  done
}
# junit_get FILE EXPR: EXPR evaluated with r = the root element (xml.etree), cases = its testcases.
junit_get() {
  python3 -c 'import sys, xml.etree.ElementTree as ET
r = ET.parse(sys.argv[1]).getroot(); cases = {c.get("name"): c for c in r.iter("testcase")}
print(eval(sys.argv[2]))' "$1" "$2"
}
golden_sum=$(cd "$REPO" && sha256sum golden/*.csv)

check "copies of scenes/ and golden/, with the three broken things"
mkdir -p scenes golden
cp -r "$REPO"/scenes/* scenes/  # the scenes with their parts, textures and meshes
cp "$REPO"/golden/*.csv golden/
# The socket scenes start their peers from ../examples/clients and ../scripts (and the client
# module in ../python).
mkdir -p examples scripts python
cp -r "$REPO/examples/clients" examples/
cp "$REPO/scripts/simbob_client.py" scripts/
cp "$REPO/python/simbob_client.py" python/ 2>/dev/null || true
# bounce: every ball 1 cm higher in the golden file from t = 0.5 s on.
python3 - golden/bounce.csv <<'PY'
import sys
path = sys.argv[1]
lines = open(path).read().split('\n')
for i, line in enumerate(lines[1:], start=1):
    f = line.split(',')
    if len(f) == 9 and float(f[0]) >= 0.5:
        f[3] = repr(float(f[3]) + 0.01)
        lines[i] = ','.join(f)
open(path, 'w').write('\n'.join(lines))
PY
body=$(awk -F, 'NR == 2 { print $2 }' golden/bounce.csv)
rm golden/pendulum.csv
cat >scenes/broken.xml <<'XML'
<?xml version="1.0" encoding="UTF-8"?>
<Simulation>
  <ComponentList>
    <RCMobileRigidBody Key="Box" Mass="-1"/>
  </ComponentList>
</Simulation>
XML
broken_err=$("$SIMBOB" check scenes/broken.xml 2>&1 | grep -m 1 ': error: ' || true)
[[ "$broken_err" == scenes/broken.xml:4:* ]] || fail "check scenes/broken.xml says '$broken_err', expected an error at line 4"
mkdir -p copies && cp golden/*.csv copies/

check "batch --golden --junit --artifacts --summary-md: exit 1, the reports written"
expect_status 1 "$SIMBOB" batch scenes/*.xml --duration 10 --out-dir out -j 2 --golden golden \
  --junit report.xml --artifacts art --summary-md summary.md
validate report.xml
nscenes=$(ls scenes/*.xml | wc -l)
# What did not pass, for the log when a count is off.
junit_get report.xml '"\n".join(n + ": " + p.tag + ": " + (p.get("message") or "") for n, c in cases.items() for p in c if p.tag in ("failure", "error", "skipped"))'
expect_eq "counts" "$(junit_get report.xml '[r.get(k) for k in ("name", "tests", "failures", "errors", "skipped")]')" \
  "['simbob batch', '$nscenes', '2', '1', '0']"
expect_eq "cases" "$(junit_get report.xml 'len(cases)')" "$nscenes"
expect_eq "failures" "$(junit_get report.xml '[(c.get("name"), c.get("classname"), c.get("file")) for c in r.iter("testcase") if c.find("failure") is not None]')" \
  "[('bounce', 'scenes.bounce', None), ('pendulum', 'scenes.pendulum', None)]"
expect_eq "the failure's message" "$(junit_get report.xml 'cases["bounce"].find("failure").get("message")')" \
  "first divergence at t=0.5 s, body '$body': position error 0.01 m (tolerance 1e-06 m), rotation error 0 rad (tolerance 1e-06 rad)"
expect_eq "the failure's type" "$(junit_get report.xml 'cases["bounce"].find("failure").get("type")')" "golden mismatch"
junit_get report.xml 'cases["bounce"].find("failure").text' >failure.txt
expect_match "the failure's per-body table" failure.txt "^$body +0\\.01 +0 +0\\.5 +exceeded$"
expect_match "the failure's golden file" failure.txt "^golden: golden/bounce\\.csv$"
# The body's first line: the golden file's row of the first divergence, then the message.
row=$(awk -F, -v b="$body" '$1 == "0.5" && $2 == b { print NR; exit }' golden/bounce.csv)
[[ -n "$row" ]] || fail "no row of t=0.5 s for $body in golden/bounce.csv"
expect_eq "the failure's first line" "$(head -n 1 failure.txt)" \
  "golden/bounce.csv:$row: first divergence at t=0.5 s, body '$body': position error 0.01 m (tolerance 1e-06 m), rotation error 0 rad (tolerance 1e-06 rad)"
expect_eq "the error" "$(junit_get report.xml '"\n".join(n + ": " + c.find("error").get("message") for n, c in cases.items() if c.find("error") is not None)')" \
  "broken: $broken_err"
expect_eq "the error's body starts with its line" "$(junit_get report.xml 'cases["broken"].find("error").text.split("\n")[0]')" "$broken_err"
junit_get report.xml 'cases["broken"].find("error").text' >error-body.txt
expect_match "the error's body holds the run's log" error-body.txt \
  "^--- the run's log, last lines \\(out/broken\\.log\\):$"
expect_eq "the missing golden file is a failure" \
  "$(junit_get report.xml '[(p.get("type"), p.get("message"), p.text) for p in [cases["pendulum"].find("failure")]]')" \
  "[('no golden file', 'no golden file golden/pendulum.csv', 'scenes/pendulum.xml: no golden file golden/pendulum.csv')]"
expect_eq "properties" "$(junit_get report.xml '[p.get("name") for p in r.iter("property")][:9]')" \
  "['simbob.version', 'simbob.revision', 'ode.version', 'ode.configuration', 'compiler', 'libc', 'cpu.model', 'step', 'seed']"
expect_eq "seed" "$(junit_get report.xml '[p.get("value") for p in r.iter("property") if p.get("name") == "seed"]')" "['0']"
junit_get report.xml '[p.get("value") for p in r.iter("property") if p.get("name") == "ode.version"][0]' >ode.txt
expect_match "ODE's version" ode.txt '^0\.16\.[0-9]+$'

check "the failed scene's artifacts, referenced from its test case"
expect_file art/bounce/view.html
expect_file art/bounce/plot.png
expect_file art/bounce/compare.txt
expect_file art/broken/run.log
[[ "$(head -c 8 art/bounce/plot.png | od -An -tx1 | tr -d ' \n')" == 89504e470d0a1a0a ]] || fail "plot.png is no PNG"
expect_eq "no per-case system-out (Ant's schema)" "$(junit_get report.xml 'cases["bounce"].find("system-out")')" "None"
junit_get report.xml 'r.find("system-out").text' >suite-out.txt
expect_match "the suite's system-out lists the artifacts" suite-out.txt "^bounce: plot: art/bounce/plot\\.png$"
expect_match "... the replay page" suite-out.txt "^bounce: replay page: art/bounce/view\\.html$"
expect_match "... the log" suite-out.txt "^broken: log: art/broken/run\\.log$"
grep -q 'href="./bounce/view.html"' art/index.html || fail "index.html does not link ./bounce/view.html"
grep -q 'href="./broken/run.log"' art/index.html || fail "index.html does not link ./broken/run.log"
grep -q 'href="./chain/summary.json"' art/index.html || fail "index.html does not link the passed ./chain/summary.json"
python3 - art/index.html <<'PY' || fail "a link of index.html leads nowhere"
import os, re, sys, urllib.parse
page = sys.argv[1]
links = re.findall(r'href="([^"]+)"', open(page).read())
assert links and all(l.startswith('./') for l in links), links
for l in links:
    assert os.path.isfile(os.path.join(os.path.dirname(page), urllib.parse.unquote(l))), l
PY

check "the replay page in headless Chromium: ghosts, and the marker at the reported time"
expect_status 0 /usr/bin/python3 "$REPO/tests/view/browser_test.py" "$SIMBOB" "$REPO" artifacts "$WORK/browser" \
  art report.xml
cat "$LAST_OUT"

check "the Markdown summary lists the three"
expect_match "the header" summary.md "^### simbob batch: $((nscenes - 3)) passed, 2 failed, 1 errors, 0 skipped \("
expect_match "the failure" summary.md "^\| scenes/bounce\.xml \| failed \| first divergence at t=0\.5 s, body '$body'"
expect_match "the error" summary.md "^\| scenes/broken\.xml \| error \| scenes/broken\.xml:4: error: "
expect_match "the missing golden file" summary.md "^\| scenes/pendulum\.xml \| failed \| no golden file golden/pendulum\.csv \|$"

check "--junit-extended: file, line, per-case properties and GitLab's attachments (junit.xsd, not the strict ones)"
expect_status 1 "$SIMBOB" batch scenes/bounce.xml scenes/broken.xml --duration 10 --out-dir out-ext -j 2 --golden golden \
  --junit ext.xml --junit-extended --artifacts art-ext --suite-name "shard 1/2"
validate ext.xml junit.xsd
if xmllint --noout --schema "$REPO/tests/ci/xunit-junit-10.xsd" ext.xml 2>/dev/null; then
  fail "ext.xml (file, line, per-case output) passes Jenkins' junit-10 rules: the schema cannot see them"
fi
expect_eq "suite name" "$(junit_get ext.xml 'r.get("name")')" "shard 1/2"
expect_eq "the error's file and line" "$(junit_get ext.xml '(cases["broken"].get("file"), cases["broken"].get("line"))')" \
  "('scenes/broken.xml', '4')"
expect_eq "per-case properties" "$(junit_get ext.xml '[p.get("name") for p in cases["bounce"].find("properties")]')" \
  "['scene_hash', 'step', 'seed', 'ode.version', 'ode.configuration']"
junit_get ext.xml 'cases["bounce"].find("system-out").text' >ext-out.txt
expect_match "GitLab's attachment" ext-out.txt \
  "^\[\[ATTACHMENT\|art-ext/bounce/plot\.png\]\]$"

check "--allow-missing-golden: a scene without a golden file is skipped, and the batch passes"
expect_status 0 "$SIMBOB" batch scenes/pendulum.xml scenes/chain.xml --duration 10 --out-dir out-allow --golden golden \
  --allow-missing-golden --junit allow.xml
validate allow.xml
expect_eq "counts" "$(junit_get allow.xml '[r.get(k) for k in ("tests", "failures", "errors", "skipped")]')" "['2', '0', '0', '1']"
expect_eq "the skipped's body" "$(junit_get allow.xml 'cases["pendulum"].find("skipped").text')" \
  "scenes/pendulum.xml: no golden file golden/pendulum.csv"

check "GITHUB_ACTIONS=true: one ::error line per failure, with its file and line"
GITHUB_ACTIONS=true expect_status 1 "$SIMBOB" batch scenes/bounce.xml scenes/broken.xml --duration 10 --out-dir out-gha \
  -j 2 --golden golden
expect_match "the mismatch" "$LAST_OUT" "^::error file=golden/bounce\.csv,line=$row,title=bounce%3A golden mismatch::first divergence at t=0\.5 s, body '$body'"
expect_match "the error" "$LAST_OUT" "^::error file=scenes/broken\.xml,line=4,title=broken%3A run failed::scenes/broken\.xml:4: error: "
expect_lines "only those" <(grep '^::' "$LAST_OUT") 2

check "a failing controller: its own words in the body and the index, its log an artifact, the same text every run"
cat >ctl-fail.sh <<'SH'
#!/bin/sh
echo "arm driver: cannot open /dev/arm0" >&2
echo "giving up" >&2
exit 3
SH
chmod +x ctl-fail.sh
printf 'scenes/socket_robot.xml --controller Bot.Cart.Link=%s/ctl-fail.sh\n' "$WORK" >ctl.list
for n in 1 2; do
  expect_status 1 "$SIMBOB" batch --manifest ctl.list --duration 1 --out-dir out-ctl --golden golden \
    --junit "ctl$n.xml" --artifacts "art-ctl$n"
  validate "ctl$n.xml"
  junit_get "ctl$n.xml" '[(p.get("message"), p.text) for c in r.iter("testcase") for p in c if p.tag == "error"]' >"ctl$n.txt"
done
expect_same_file ctl1.txt ctl2.txt
expect_match "the controller's status" ctl1.txt "exited with status 3 before connecting"
junit_get ctl1.xml 'cases["socket_robot"].find("error").text' >ctl-body.txt
expect_match "its own words" ctl-body.txt "^giving up$"
if grep -q '127\.0\.0\.1:[0-9]' ctl1.txt; then fail "a port number in the error: $(cat ctl1.txt)"; fi
expect_file art-ctl1/socket_robot/controller.log
grep -q 'href="./socket_robot/controller.log"' art-ctl1/index.html || fail "index.html does not link the controller's log"
grep -q '^giving up$' art-ctl1/index.html || fail "index.html does not show the controller's last words"

check "--timeout: a scene past the limit is an error naming the limit, its partial trajectory kept"
expect_status 1 "$SIMBOB" batch scenes/chain.xml --duration 100000 --timeout 1 --out-dir out-slow --junit slow.xml
validate slow.xml
expect_eq "the error" "$(junit_get slow.xml '[(p.tag, p.get("type"), p.get("message")) for p in cases["chain"]]')" \
  "[('error', 'run timed out', 'the run took longer than --timeout 1 s (wall clock) and was stopped; its partial trajectory: out-slow/chain.partial.csv')]"
expect_file out-slow/chain.partial.csv

check "--bless-from: the trajectories a CI run left, blessed without running a scene"
expect_status 1 "$SIMBOB" batch --bless-from out --golden golden
expect_match "refused: a run did not finish" "$LAST_ERR" "^simbob: error: --bless refused: 1 scene did not run to the end or could not be compared \(first: scenes/broken\.xml: "
for f in copies/*.csv; do expect_same_file "$f" "golden/$(basename "$f")"; done
mkdir -p from golden-from
cp out/bounce.csv out/bounce.json out/pendulum.csv out/pendulum.json out/chain.csv out/chain.json from/
cp copies/*.csv golden-from/
expect_status 0 "$SIMBOB" batch --bless-from from --golden golden-from
expect_match "the change" "$LAST_OUT" "^changed  golden-from/bounce\.csv \(scenes/bounce\.xml\):$"
expect_match "the new file" "$LAST_OUT" "^new      golden-from/pendulum\.csv \(from scenes/pendulum\.xml\)$"
expect_lines "only those" <(grep -E '^(changed|new) ' "$LAST_OUT") 2
expect_same_file out/bounce.csv golden-from/bounce.csv
expect_same_file out/pendulum.csv golden-from/pendulum.csv
expect_status 64 "$SIMBOB" batch scenes/chain.xml --bless-from from --golden golden-from

check "--bless refuses after a failed run and changes no golden file"
few=(scenes/bounce.xml scenes/broken.xml scenes/chain.xml scenes/pendulum.xml)
expect_status 1 "$SIMBOB" batch "${few[@]}" --duration 10 --out-dir out -j 2 --golden golden --bless
expect_match "why" "$LAST_ERR" "^simbob: error: --bless refused: 1 scene did not run to the end or could not be compared \(first: scenes/broken\.xml: scenes/broken\.xml:4: error: .*\); no golden file was changed$"
for f in copies/*.csv; do expect_same_file "$f" "golden/$(basename "$f")"; done
expect_no_file golden/pendulum.csv

check "--bless shows each change, then rewrites; the next batch passes"
few=(scenes/bounce.xml scenes/chain.xml scenes/pendulum.xml)
expect_status 0 "$SIMBOB" batch "${few[@]}" --duration 10 --out-dir out -j 2 --golden golden --bless
expect_match "the change" "$LAST_OUT" "^changed  golden/bounce\.csv \(scenes/bounce\.xml\):$"
expect_match "its body" "$LAST_OUT" "^  body $body: largest difference 0\.01 m \(t=0\.5 s\), 0 rad \(t=0 s\), beyond the tolerances$"
expect_match "the new file" "$LAST_OUT" "^new      golden/pendulum\.csv \(from scenes/pendulum\.xml\)$"
expect_lines "only those" <(grep -E '^(changed|new) ' "$LAST_OUT") 2
expect_same_file out/bounce.csv golden/bounce.csv
expect_same_file out/pendulum.csv golden/pendulum.csv
expect_same_file golden/chain.csv copies/chain.csv
expect_status 0 "$SIMBOB" batch "${few[@]}" --duration 10 --out-dir out2 -j 2 --golden golden --junit report2.xml
validate report2.xml
expect_eq "all pass" "$(junit_get report2.xml '[r.get(k) for k in ("tests", "failures", "errors", "skipped")]')" "['3', '0', '0', '0']"
expect_status 0 "$SIMBOB" batch "${few[@]}" --duration 10 --out-dir out2 -j 2 --golden golden --bless
expect_match "nothing to bless" "$LAST_ERR" "every golden file in golden matches; nothing to bless"
expect_status 64 "$SIMBOB" batch scenes/chain.xml --duration 1 --out-dir out3 --bless
expect_match "--bless needs --golden" "$LAST_ERR" "^simbob: error: --bless rewrites the golden files of --golden DIR: give --golden$"

check "special characters are escaped and control characters never reach the report"
mkdir odd
cp scenes/chain.xml "odd/a&b <\"c\">'d.xml"
cp scenes/chain.xml "odd/ctl$(printf '\001')x.xml"
# A scene without a golden file fails the batch (exit 1), as before --junit.
expect_status 1 "$SIMBOB" batch odd/*.xml --duration 0.1 --out-dir odd-out --golden golden --junit odd.xml \
  --summary-md odd.md --artifacts odd-art
validate odd.xml
if LC_ALL=C grep -q '[[:cntrl:]]' <(tr -d '\n\t' <odd.xml); then fail "a control character in odd.xml"; fi
grep -q 'name="a&amp;b &lt;&quot;c&quot;&gt;&apos;d"' odd.xml || fail "the odd name is not escaped: $(grep testcase odd.xml)"
grep -q 'name="ctl\\x01x"' odd.xml || fail "the control character is not shown visibly: $(grep testcase odd.xml)"
expect_eq "both failed (no golden file)" "$(junit_get odd.xml 'r.get("failures")')" 2

check "compare --junit: a pass, a failure, an unreadable file"
expect_status 0 "$SIMBOB" compare out/chain.csv golden/chain.csv --junit c1.xml
validate c1.xml
expect_eq "pass" "$(junit_get c1.xml '[r.get(k) for k in ("name", "tests", "failures", "errors")]')" "['simbob compare', '1', '0', '0']"
expect_status 1 "$SIMBOB" compare out/bounce.csv copies/bounce.csv --junit c2.xml
validate c2.xml
expect_eq "failure" "$(junit_get c2.xml 'cases["bounce"].find("failure").get("message")')" \
  "first divergence at t=0.5 s, body '$body': position error 0.01 m (tolerance 1e-06 m), rotation error 0 rad (tolerance 1e-06 rad)"
expect_status 66 "$SIMBOB" compare out/missing.csv golden/chain.csv --junit c3.xml
validate c3.xml
expect_eq "error" "$(junit_get c3.xml 'cases["missing"].find("error").get("message")')" "$(head -n 1 "$LAST_ERR")"

check "sweep gather --junit: one test case per sweep case"
cat >box.sweep.json <<'JSON'
{"scene": "scenes/sliding_box.xml", "duration": 0.2, "sample_interval": 0.1,
 "vary": [{"param": "Crate.Material.Friction", "values": [0.2, 0.5, 0.8]}],
 "metrics": [{"name": "stop_x", "body": "Crate", "value": "x", "stat": "final"}]}
JSON
expect_status 0 "$SIMBOB" sweep plan box.sweep.json -o box.jsonl
expect_status 0 "$SIMBOB" sweep run box.jsonl -o box -j 2 -q
rm -r box/case-0001
expect_status 1 "$SIMBOB" sweep gather box --junit sweep.xml
validate sweep.xml
expect_eq "sweep counts" "$(junit_get sweep.xml '[r.get(k) for k in ("tests", "failures", "errors")]')" "['3', '0', '1']"
expect_eq "sweep cases" "$(junit_get sweep.xml '[c.get("name") for c in r.iter("testcase")]')" \
  "['case-0000 Crate.Material.Friction=0.2', 'case-0001 Crate.Material.Friction=0.5', 'case-0002 Crate.Material.Friction=0.8']"
expect_eq "the missing case" "$(junit_get sweep.xml 'cases["case-0001 Crate.Material.Friction=0.5"].find("error").get("message")')" \
  "no case.json: the case never ran or did not finish"

check "the repository's golden files are untouched"
expect_eq "golden/" "$(cd "$REPO" && sha256sum golden/*.csv)" "$golden_sum"
say "PASS"
