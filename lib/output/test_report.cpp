#include "simbob/tool/test_report.h"

#include <algorithm>
#include <cstdio>
#include <ctime>

#include "simbob/tool/files.h"
#include "simbob/values.h"

namespace simbob {

namespace {

// No message or name is cut shorter than this, whatever the size limit.
constexpr size_t kMinText = 200;

std::string seconds(double s) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f", s >= 0 && s < 1e12 ? s : 0.0);
  return buf;
}

// One line of input made printable (quoteInput), then XML's five special characters.
void appendEscapedLine(std::string_view line, size_t max_bytes, std::string* out) {
  const std::string printable = quoteInput(line, max_bytes);
  for (size_t i = 0; i < printable.size(); ++i) {
    const char c = printable[i];
    // U+FFFE and U+FFFF are not XML characters (quoteInput passes them).
    if (c == '\xEF' && i + 2 < printable.size() && printable[i + 1] == '\xBF' &&
        (printable[i + 2] == '\xBE' || printable[i + 2] == '\xBF')) {
      *out += printable[i + 2] == '\xBE' ? "\\u{FFFE}" : "\\u{FFFF}";
      i += 2;
      continue;
    }
    switch (c) {
      case '&':
        *out += "&amp;";
        break;
      case '<':
        *out += "&lt;";
        break;
      case '>':
        *out += "&gt;";
        break;
      case '"':
        *out += "&quot;";
        break;
      case '\'':
        *out += "&apos;";
        break;
      default:
        *out += c;
    }
  }
}

std::string escapeCut(const std::string& text, bool multiline, size_t max_bytes) {
  std::string out;
  if (!multiline) {
    appendEscapedLine(text, max_bytes, &out);
    return out;
  }
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + start, end - start);
    // Tabs stay: split at them, escape the pieces.
    size_t p = 0;
    while (p <= line.size()) {
      size_t tab = line.find('\t', p);
      if (tab == std::string_view::npos) tab = line.size();
      appendEscapedLine(line.substr(p, tab - p), max_bytes, &out);
      if (tab < line.size()) out += '\t';
      p = tab + 1;
    }
    if (end < text.size()) out += '\n';
    start = end + 1;
  }
  return out;
}

// The first lines of `text` that fit in `budget` bytes, and a note of what was left out.
std::string cutAtLines(const std::string& text, size_t budget) {
  if (text.size() <= budget) return text;
  size_t end = text.rfind('\n', budget);
  if (end == std::string::npos) end = 0;
  size_t lines = static_cast<size_t>(std::count(text.begin() + static_cast<long>(end), text.end(), '\n'));
  if (!text.empty() && text.back() != '\n') ++lines;
  return text.substr(0, end) + (end ? "\n" : "") + "... (" + countOf(lines, "more line", "more lines") +
         " cut to keep the report small)\n";
}

std::string attr(const char* name, const std::string& value, size_t max) {
  return std::string(" ") + name + "=\"" + escapeCut(value, false, max) + "\"";
}

const char* elementOf(TestOutcome o) {
  switch (o) {
    case TestOutcome::Failed:
      return "failure";
    case TestOutcome::Error:
      return "error";
    case TestOutcome::Skipped:
      return "skipped";
    case TestOutcome::Passed:
      return "";
  }
  return "";
}

// The body of a failure, error or skipped: the located message on one line, then the output
// and the details (cut together at line ends to max_details).
std::string bodyXml(const TestCaseReport& c, size_t max_message, size_t max_details) {
  std::string body = escapeCut(locatedMessage(c), false, max_message);
  const std::string rest = c.output + c.details;
  if (!rest.empty()) body += "\n" + escapeCut(cutAtLines(rest, max_details), true, max_details + 64);
  return body;
}

std::string caseXml(const TestCaseReport& c, size_t max_message, size_t max_details, JUnitForm form) {
  const bool extended = form == JUnitForm::Extended;
  std::string x = "  <testcase" + attr("classname", c.classname, max_message) + attr("name", c.name, max_message);
  if (extended) {
    x += attr("file", c.file, max_message);
    if (c.where.line > 0 && c.where.file == c.file) x += " line=\"" + std::to_string(c.where.line) + "\"";
  }
  x += " time=\"" + seconds(c.time) + "\"";
  std::string out;
  if (extended)
    for (const TestArtifact& a : c.artifacts) out += "[[ATTACHMENT|" + a.path + "]]\n" + a.label + ": " + a.path + "\n";
  const bool props = extended && !c.properties.empty();
  if (c.outcome == TestOutcome::Passed && out.empty() && !props) return x + "/>\n";
  x += ">\n";
  if (props) {
    x += "    <properties>\n";
    for (const auto& [k, v] : c.properties)
      x += "      <property" + attr("name", k, max_message) + attr("value", v, max_message) + "/>\n";
    x += "    </properties>\n";
  }
  if (c.outcome != TestOutcome::Passed) {
    const char* element = elementOf(c.outcome);
    x += std::string("    <") + element + attr("message", c.message, max_message);
    // Ant's schema requires a type on failure and error.
    if (c.outcome != TestOutcome::Skipped)
      x += attr("type", c.type.empty() ? std::string(testOutcomeName(c.outcome)) : c.type, max_message);
    x += ">" + bodyXml(c, max_message, max_details) + "</" + element + ">\n";
  }
  if (!out.empty()) x += "    <system-out>" + escapeCut(out, true, max_message * 4) + "</system-out>\n";
  return x + "  </testcase>\n";
}

// The suite's <system-out>: every case's artifacts, one "NAME: label: path" line each.
std::string artifactLines(const TestSuiteReport& s, size_t max_message) {
  std::string out;
  for (const TestCaseReport& c : s.cases)
    for (const TestArtifact& a : c.artifacts) out += c.name + ": " + a.label + ": " + a.path + "\n";
  return out.empty() ? "" : escapeCut(out, true, max_message * 4);
}

std::string suiteXml(const TestSuiteReport& s, size_t max_message, size_t max_details, JUnitForm form,
                     bool list_artifacts) {
  std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuite" + attr("name", s.name, max_message) +
                  " tests=\"" + std::to_string(s.cases.size()) + "\" failures=\"" +
                  std::to_string(s.count(TestOutcome::Failed)) + "\" errors=\"" +
                  std::to_string(s.count(TestOutcome::Error)) + "\" skipped=\"" +
                  std::to_string(s.count(TestOutcome::Skipped)) + "\" time=\"" + seconds(s.time) + "\"" +
                  attr("timestamp", s.timestamp, max_message) + attr("hostname", s.hostname, max_message) + ">\n";
  // Ant's schema requires <properties>, and <system-out> and <system-err> after the cases.
  if (s.properties.empty()) {
    x += "  <properties/>\n";
  } else {
    x += "  <properties>\n";
    for (const auto& [k, v] : s.properties)
      x += "    <property" + attr("name", k, max_message) + attr("value", v, max_message) + "/>\n";
    x += "  </properties>\n";
  }
  for (const TestCaseReport& c : s.cases) x += caseXml(c, max_message, max_details, form);
  const std::string listed = list_artifacts ? artifactLines(s, max_message) : "";
  x += listed.empty() ? "  <system-out/>\n" : "  <system-out>" + listed + "</system-out>\n";
  return x + "  <system-err/>\n</testsuite>\n";
}

}  // namespace

const char* testOutcomeName(TestOutcome o) {
  switch (o) {
    case TestOutcome::Passed:
      return "passed";
    case TestOutcome::Failed:
      return "failed";
    case TestOutcome::Error:
      return "error";
    case TestOutcome::Skipped:
      return "skipped";
  }
  return "error";
}

size_t TestSuiteReport::count(TestOutcome o) const {
  return static_cast<size_t>(
      std::count_if(cases.begin(), cases.end(), [o](const TestCaseReport& c) { return c.outcome == o; }));
}

std::string locatedMessage(const TestCaseReport& c) {
  if (c.where.file.empty()) return c.message;
  const std::string place = c.where.file + (c.where.line > 0 ? ":" + std::to_string(c.where.line) : std::string());
  if (c.message.compare(0, place.size() + 1, place + ":") == 0) return c.message;
  return place + ": " + c.message;
}

bool junitXml(const TestSuiteReport& suite, std::string* xml, Error* err, const JUnitLimits& limits, JUnitForm form) {
  // Whole, if it fits; else each case's details get an even share of what the rest leaves (and
  // the suite's list of artifacts gives way: index.html lists them too).
  *xml = suiteXml(suite, limits.max_message, limits.max_details, form, true);
  if (xml->size() <= limits.max_bytes) return true;
  size_t with_details = 0;
  for (const TestCaseReport& c : suite.cases) with_details += c.details.empty() && c.output.empty() ? 0 : 1;
  for (size_t message : {limits.max_message, std::min(limits.max_message, kMinText)}) {
    const std::string bare = suiteXml(suite, message, 0, form, false);
    if (bare.size() > limits.max_bytes) continue;
    // Escaping can grow a text up to 6 times ("&quot;"): share the room by that bound.
    const size_t share = (limits.max_bytes - bare.size()) / std::max<size_t>(1, with_details) / 6;
    *xml = suiteXml(suite, message, std::min(limits.max_details, share), form, false);
    if (xml->size() <= limits.max_bytes) return true;
  }
  xml->clear();
  if (err)
    *err = {ErrorKind::InvalidInput,
            {},
            "the JUnit report of " + countOf(suite.cases.size(), "test case", "test cases") + " would exceed " +
                std::to_string(limits.max_bytes) + " bytes even with its texts cut"};
  return false;
}

bool writeJUnit(const TestSuiteReport& suite, const std::string& path, Error* err, const JUnitLimits& limits,
                JUnitForm form) {
  std::string xml;
  if (!junitXml(suite, &xml, err, limits, form)) {
    if (err) err->loc = {path, 0};
    return false;
  }
  return writeFileAtomically(path, xml, err);
}

std::string xmlEscape(const std::string& text, bool multiline) {
  return escapeCut(text, multiline, text.size() * 4 + 16);
}

std::string relativeLink(const std::string& path) {
  static const char* hex = "0123456789ABCDEF";
  std::string out = "./";
  for (char ch : path) {
    const auto c = static_cast<unsigned char>(ch);
    if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '.' ||
        c == '_' || c == '~' || c == '/') {
      out += ch;
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

namespace {

// A workflow command's text: quoted as messages are (no control character reaches the log),
// then %, CR and LF as the runner decodes them; in a property also ',' and ':'.
std::string workflowText(const std::string& text, bool property) {
  std::string out;
  for (char c : quoteInput(text, 2000)) {
    if (c == '%')
      out += "%25";
    else if (c == '\r')
      out += "%0D";
    else if (c == '\n')
      out += "%0A";
    else if (property && c == ',')
      out += "%2C";
    else if (property && c == ':')
      out += "%3A";
    else
      out += c;
  }
  return out;
}

}  // namespace

std::string githubAnnotations(const TestSuiteReport& suite) {
  std::string out;
  for (const TestCaseReport& c : suite.cases) {
    if (c.outcome == TestOutcome::Passed) continue;
    const std::string& file = c.where.file.empty() ? c.file : c.where.file.str();
    out += c.outcome == TestOutcome::Skipped ? "::warning " : "::error ";
    if (!file.empty()) out += "file=" + workflowText(file, true) + ",";
    if (!file.empty() && c.where.line > 0) out += "line=" + std::to_string(c.where.line) + ",";
    out += "title=" + workflowText(c.name + ": " + (c.type.empty() ? testOutcomeName(c.outcome) : c.type), true) +
           "::" + workflowText(c.message, false) + "\n";
  }
  return out;
}

std::string isoTimestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &tm);
  return buf;
}

}  // namespace simbob
