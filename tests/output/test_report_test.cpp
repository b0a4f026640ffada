// lib/output/test_report.cpp and test_report_pages.cpp: JUnit XML, the Markdown summary and the
// artifacts index of a batch against its golden files.
#include "simbob/tool/test_report.h"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace simbob;

namespace {

size_t occurrences(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

TestSuiteReport sample() {
  TestSuiteReport s;
  s.name = "simbob batch";
  s.timestamp = "2026-11-27T11:08:00";
  s.hostname = "ci-runner";
  s.time = 2.5;
  s.properties = {{"simbob.version", "0.1.0"}, {"seed", "0"}};
  TestCaseReport pass{
      "scenes.chain", "chain", "scenes/chain.xml", 0.25, TestOutcome::Passed, "", "", "", {}, "", {}, {}};
  TestCaseReport fail{"scenes.bounce",
                      "bounce",
                      "scenes/bounce.xml",
                      1.5,
                      TestOutcome::Failed,
                      "first divergence at t=0.5 s, body 'Ball'",
                      "golden mismatch",
                      "body  max pos err\nBall  0.1\n",
                      {},
                      "",
                      {},
                      {}};
  fail.artifacts.push_back({"replay page", "ci/bounce/view.html", "bounce/view.html"});
  TestCaseReport error{"scenes.broken",
                       "broken",
                       "scenes/broken.xml",
                       0.01,
                       TestOutcome::Error,
                       "scenes/broken.xml:3: error: unknown type",
                       "run failed",
                       "",
                       {},
                       "",
                       {},
                       {}};
  TestCaseReport skip{
      "scenes.new", "new", "scenes/new.xml", 0.1, TestOutcome::Skipped, "no golden file golden/new.csv", "", "", {}, "",
      {},           {}};
  s.cases = {pass, fail, error, skip};
  return s;
}

}  // namespace

TEST_CASE("junitXml counts the outcomes and writes one element per case", "[output][junit]") {
  std::string xml;
  Error err;
  REQUIRE(junitXml(sample(), &xml, &err));
  CHECK(xml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuite name=\"simbob batch\" tests=\"4\" "
                  "failures=\"1\" errors=\"1\" skipped=\"1\" time=\"2.500\" timestamp=\"2026-11-27T11:08:00\" "
                  "hostname=\"ci-runner\">\n",
                  0) == 0);
  CHECK(xml.find("<property name=\"simbob.version\" value=\"0.1.0\"/>") != std::string::npos);
  // The strict form: no file, no per-case output (Jenkins' junit-10.xsd and Ant's schema).
  CHECK(xml.find("<testcase classname=\"scenes.chain\" name=\"chain\" time=\"0.250\"/>") != std::string::npos);
  CHECK(xml.find("file=") == std::string::npos);
  // Every reason is in the body too (GitLab and CircleCI show the body), its first line the message.
  CHECK(xml.find("<failure message=\"first divergence at t=0.5 s, body &apos;Ball&apos;\" type=\"golden "
                 "mismatch\">first divergence at t=0.5 s, body &apos;Ball&apos;\nbody  max pos err\nBall  "
                 "0.1\n</failure>") != std::string::npos);
  CHECK(xml.find("<error message=\"scenes/broken.xml:3: error: unknown type\" type=\"run failed\">scenes/broken.xml:3: "
                 "error: unknown type</error>") != std::string::npos);
  CHECK(xml.find("<skipped message=\"no golden file golden/new.csv\">no golden file golden/new.csv</skipped>") !=
        std::string::npos);
  // The artifacts are listed once, in the suite's output; Ant's schema wants system-err too.
  CHECK(xml.find("  <system-out>bounce: replay page: ci/bounce/view.html\n</system-out>\n  <system-err/>\n"
                 "</testsuite>\n") != std::string::npos);
  CHECK(xml.find("[[ATTACHMENT|") == std::string::npos);
  CHECK(occurrences(xml, "<testcase ") == 4);
}

TEST_CASE("junitXml puts FILE:LINE first in the body, and the output before the details", "[output][junit]") {
  TestSuiteReport s = sample();
  s.cases[1].where = {"golden/bounce.csv", 52};
  s.cases[1].output = "--- its controller's output, last lines (out/bounce.controller.log):\nTraceback\n";
  s.cases[2].where = {"scenes/broken.xml", 3};  // the message starts with it already: not twice
  s.cases[3].where = {"scenes/new.xml", 0};     // no line: the file alone
  std::string xml;
  Error err;
  REQUIRE(junitXml(s, &xml, &err));
  CHECK(xml.find(">golden/bounce.csv:52: first divergence at t=0.5 s, body &apos;Ball&apos;\n--- its controller&apos;s "
                 "output, last lines (out/bounce.controller.log):\nTraceback\nbody  max pos err\n") !=
        std::string::npos);
  CHECK(xml.find(">scenes/broken.xml:3: error: unknown type</error>") != std::string::npos);
  CHECK(xml.find(">scenes/new.xml: no golden file golden/new.csv</skipped>") != std::string::npos);
  // --junit-extended: file and line (where the scene is the place), properties, GitLab's attachments.
  s.cases[2].properties = {{"scene_hash", "fnv1a64w:0123"}, {"seed", "0"}};
  REQUIRE(junitXml(s, &xml, &err, {}, JUnitForm::Extended));
  CHECK(xml.find("<testcase classname=\"scenes.chain\" name=\"chain\" file=\"scenes/chain.xml\" time=\"0.250\"/>") !=
        std::string::npos);
  CHECK(xml.find("name=\"broken\" file=\"scenes/broken.xml\" line=\"3\" time=") != std::string::npos);
  CHECK(xml.find("name=\"bounce\" file=\"scenes/bounce.xml\" time=") != std::string::npos);
  CHECK(xml.find("    <properties>\n      <property name=\"scene_hash\" value=\"fnv1a64w:0123\"/>") !=
        std::string::npos);
  CHECK(xml.find("<system-out>[[ATTACHMENT|ci/bounce/view.html]]\nreplay page: ci/bounce/view.html\n</system-out>") !=
        std::string::npos);
}

TEST_CASE("githubAnnotations: one workflow command per case that did not pass", "[output][junit]") {
  TestSuiteReport s = sample();
  s.cases[1].where = {"golden/bounce,1.csv", 52};
  s.cases[1].message = "100% off\nnext \x1b[2J";
  s.cases[2].where = {"scenes/broken.xml", 3};
  CHECK(githubAnnotations(s) ==
        "::error file=golden/bounce%2C1.csv,line=52,title=bounce%3A golden mismatch::100%25 off\\x0Anext \\x1B[2J\n"
        "::error file=scenes/broken.xml,line=3,title=broken%3A run failed::scenes/broken.xml:3: error: unknown type\n"
        "::warning file=scenes/new.xml,title=new%3A skipped::no golden file golden/new.csv\n");
}

TEST_CASE("junitXml escapes special characters and never writes a control character", "[output][junit]") {
  TestSuiteReport s = sample();
  s.properties.push_back({"key <&>\"'", std::string("a\x01"
                                                    "b\x1b[31m\x7f\xff\xef\xbf\xbe")});
  s.cases[1].message = "body 'a\"b' <x> & \x02 \n next";
  s.cases[1].details = "tab\there\nbell\x07 & <end>\r\n";
  s.cases[2].file = std::string("scenes/nul\0name.xml", 19);
  std::string xml;
  Error err;
  REQUIRE(junitXml(s, &xml, &err, {}, JUnitForm::Extended));
  for (unsigned char c : xml) {
    INFO("byte " << static_cast<int>(c));
    CHECK((c >= 0x20 || c == '\n' || c == '\t'));
    CHECK(c != 0x7F);
  }
  CHECK(xml.find("<property name=\"key &lt;&amp;&gt;&quot;&apos;\" value=\"a\\x01b\\x1B[31m\\x7F\\xFF\\u{FFFE}\"/>") !=
        std::string::npos);
  CHECK(xml.find("message=\"body &apos;a&quot;b&apos; &lt;x&gt; &amp; \\x02 \\x0A next\"") != std::string::npos);
  CHECK(xml.find("next\ntab\there\nbell\\x07 &amp; &lt;end&gt;\\x0D\n</failure>") != std::string::npos);
  CHECK(xml.find("file=\"scenes/nul\\x00name.xml\"") != std::string::npos);
}

TEST_CASE("junitXml cuts the per-case details to stay under the size limit", "[output][junit]") {
  TestSuiteReport s = sample();
  std::string table;
  for (int i = 0; i < 5000; ++i) table += "body" + std::to_string(i) + "  1e-3  2e-3  0.5  exceeded\n";
  s.cases[1].details = table;  // about 150 KB: more than max_details
  std::string xml;
  Error err;
  REQUIRE(junitXml(s, &xml, &err));
  CHECK(xml.size() < 64 * 1024 + 2000);
  CHECK(xml.find("body0  1e-3") != std::string::npos);
  CHECK(xml.find("more lines cut to keep the report small)\n</failure>") != std::string::npos);
  // A limit the whole report must fit in: the details share what the rest leaves.
  JUnitLimits tight;
  tight.max_bytes = 4000;
  for (int i = 0; i < 3; ++i) s.cases.push_back(s.cases[1]);
  REQUIRE(junitXml(s, &xml, &err, tight));
  CHECK(xml.size() <= tight.max_bytes);
  CHECK(occurrences(xml, "more lines cut to keep the report small") == 4);
  CHECK(occurrences(xml, "<failure ") == 4);
  // Too many cases for any cut: an error, not a truncated file.
  tight.max_bytes = 500;
  CHECK_FALSE(junitXml(s, &xml, &err, tight));
  CHECK(err.message == "the JUnit report of 7 test cases would exceed 500 bytes even with its texts cut");
  CHECK(xml.empty());
}

TEST_CASE("writeJUnit's file validates against Jenkins' and Ant's schemas in tests/ci", "[output][junit]") {
  const fs::path dir = fs::temp_directory_path() / ("simbob_junit_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  TestSuiteReport s = sample();
  s.cases[1].details = "odd \x01\x02 bytes \xc3\x28 and ]]> and <![CDATA[\n";
  s.cases[1].where = {"scenes/bounce.xml", 7};
  s.cases[1].properties = {{"seed", "0"}};
  s.properties.push_back({"cpu", "\xef\xbf\xbf"});
  Error err;
  auto valid = [&](const std::string& xsd, const fs::path& file) {
    const std::string cmd =
        "xmllint --noout --schema '" SIMBOB_SOURCE_DIR "/tests/ci/" + xsd + "' '" + file.string() + "' >/dev/null 2>&1";
    return std::system(cmd.c_str()) == 0;
  };
  const fs::path strict = dir / "report.xml", extended = dir / "extended.xml";
  REQUIRE(writeJUnit(s, strict.string(), &err));
  REQUIRE(writeJUnit(s, extended.string(), &err, {}, JUnitForm::Extended));
  CHECK(valid("xunit-junit-10.xsd", strict));
  CHECK(valid("ant-junit.xsd", strict));
  CHECK(valid("junit.xsd", strict));
  CHECK(valid("junit.xsd", extended));
  // The strict schemas are not a formality: the extended form's file attribute, per-case output
  // and properties are what Jenkins' xunit plug-in and Ant's schema refuse...
  CHECK_FALSE(valid("xunit-junit-10.xsd", extended));
  CHECK_FALSE(valid("ant-junit.xsd", extended));
  // ... and a report without its counts is refused by all three.
  std::ofstream(dir / "bad.xml") << "<testsuite name=\"x\" time=\"1\" timestamp=\"2026-01-01T00:00:00\" "
                                    "hostname=\"h\"><properties/><testcase name=\"a\" classname=\"b\" time=\"0\"/>"
                                    "<system-out/><system-err/></testsuite>\n";
  for (const char* xsd : {"junit.xsd", "xunit-junit-10.xsd", "ant-junit.xsd"}) {
    INFO(xsd);
    CHECK_FALSE(valid(xsd, dir / "bad.xml"));
  }
  fs::remove_all(dir);
}

TEST_CASE("summaryMarkdown lists every case that did not pass, one row each", "[output][junit]") {
  TestSuiteReport s = sample();
  s.cases[2].message = "a | b <script>";
  const std::string md = summaryMarkdown(s);
  CHECK(md ==
        "### simbob batch: 1 passed, 1 failed, 1 errors, 1 skipped (2.50 s)\n\n"
        "| scene | result | message |\n|---|---|---|\n"
        "| scenes/bounce.xml | failed | first divergence at t=0.5 s, body 'Ball' |\n"
        "| scenes/broken.xml | error | a \\| b &lt;script&gt; |\n"
        "| scenes/new.xml | skipped | no golden file golden/new.csv |\n"
        "\nPassed: chain\n");
}

TEST_CASE("artifactsIndexHtml links each artifact relative to the folder, percent-encoded", "[output][junit]") {
  TestSuiteReport s = sample();
  s.cases[1].artifacts.push_back({"plot", "ci/x.png", "a b/#1:%.png"});
  const std::string html = artifactsIndexHtml(s);
  CHECK(html.find("<a href=\"./bounce/view.html\">replay page</a> <a href=\"./a%20b/%231%3A%25.png\">plot</a>") !=
        std::string::npos);
  CHECK(html.find("<h2>Failed</h2>") < html.find("<h2>Errors</h2>"));
  CHECK(html.find("<h2>Errors</h2>") < html.find("<h2>Skipped</h2>"));
  CHECK(html.find("<h2>Skipped</h2>") < html.find("<h2>Passed</h2>"));
  CHECK(html.find("<p id=\"counts\">1 passed, 1 failed, 1 errors, 1 skipped (2.50 s)</p>") != std::string::npos);
  s.cases[2].output = "--- its controller's output, last lines (out/x.controller.log):\n<boom> & bye\n";
  CHECK(artifactsIndexHtml(s).find("<pre class=\"output\">--- its controller&apos;s output, last lines "
                                   "(out/x.controller.log):\n&lt;boom&gt; &amp; bye\n</pre>") != std::string::npos);
  CHECK(relativeLink("case-0001/view.html") == "./case-0001/view.html");
  CHECK(relativeLink("http://x") == "./http%3A//x");
}
