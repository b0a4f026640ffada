// The human-facing forms of a TestSuiteReport: the Markdown summary and the artifacts index page.
#include <cstdio>

#include "simbob/tool/test_report.h"
#include "simbob/values.h"

namespace simbob {

namespace {

// Rows of cases that did not pass in the Markdown table; the rest are counted. GitHub caps a
// step summary at 1 MiB.
constexpr size_t kMaxMarkdownRows = 200;
constexpr size_t kMaxMarkdownCell = 300;
constexpr size_t kMaxPassedNames = 100;

// A table cell: printable, one line, no '|' that would split it, no HTML.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : quoteInput(text, kMaxMarkdownCell)) {
    if (c == '|' || c == '\\' || c == '`' || c == '*' || c == '[' || c == ']') out += '\\';
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

std::string countsLine(const TestSuiteReport& s) {
  char wall[32];
  std::snprintf(wall, sizeof wall, "%.2f", s.time);
  return std::to_string(s.count(TestOutcome::Passed)) + " passed, " + std::to_string(s.count(TestOutcome::Failed)) +
         " failed, " + std::to_string(s.count(TestOutcome::Error)) + " errors, " +
         std::to_string(s.count(TestOutcome::Skipped)) + " skipped (" + wall + " s)";
}

}  // namespace

std::string summaryMarkdown(const TestSuiteReport& s) {
  std::string md = "### " + cell(s.name) + ": " + countsLine(s) + "\n\n";
  size_t rows = 0, left_out = 0;
  std::string table;
  for (TestOutcome o : {TestOutcome::Failed, TestOutcome::Error, TestOutcome::Skipped})
    for (const TestCaseReport& c : s.cases) {
      if (c.outcome != o) continue;
      if (rows++ >= kMaxMarkdownRows) {
        ++left_out;
        continue;
      }
      table +=
          "| " + cell(c.file.empty() ? c.name : c.file) + " | " + testOutcomeName(o) + " | " + cell(c.message) + " |\n";
    }
  if (!table.empty()) md += "| scene | result | message |\n|---|---|---|\n" + table;
  if (left_out) md += "\n... and " + countOf(left_out, "more case", "more cases") + " (see the JUnit report)\n";
  std::string passed;
  size_t shown = 0, npassed = s.count(TestOutcome::Passed);
  for (const TestCaseReport& c : s.cases) {
    if (c.outcome != TestOutcome::Passed || shown >= kMaxPassedNames) continue;
    passed += (shown++ ? ", " : "") + cell(c.name);
  }
  if (npassed) {
    md += "\nPassed: " + passed;
    if (npassed > shown) md += " and " + std::to_string(npassed - shown) + " more";
    md += "\n";
  }
  return md;
}

std::string artifactsIndexHtml(const TestSuiteReport& s) {
  std::string h =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"generator\" "
      "content=\"simbob\">\n<title>" +
      xmlEscape(s.name) +
      "</title>\n<style>body{font:14px/1.4 system-ui,sans-serif;margin:1em 2em}td,th{padding:2px 8px;text-align:"
      "left;vertical-align:top}.failed{color:#b00}.error{color:#a50}.skipped{color:#777}.passed{color:#070}pre.output{"
      "font-size:12px;white-space:pre-wrap;margin:4px 0;color:#333}"
      "</style>\n</head>\n<body>\n<h1>" +
      xmlEscape(s.name) + "</h1>\n<p id=\"counts\">" + xmlEscape(countsLine(s)) + "</p>\n";
  static const char* kHeadings[] = {"Failed", "Errors", "Skipped", "Passed"};
  int k = 0;
  for (TestOutcome o : {TestOutcome::Failed, TestOutcome::Error, TestOutcome::Skipped, TestOutcome::Passed}) {
    const char* heading = kHeadings[k++];
    if (s.count(o) == 0) continue;
    h += "<h2>" + std::string(heading) + "</h2>\n<table class=\"" + testOutcomeName(o) +
         "\">\n<tr><th>scene</th><th>message</th><th>files</th></tr>\n";
    for (const TestCaseReport& c : s.cases) {
      if (c.outcome != o) continue;
      h += "<tr class=\"" + std::string(testOutcomeName(o)) + "\"><td>" + xmlEscape(c.file.empty() ? c.name : c.file) +
           "</td><td>" + xmlEscape(c.message);
      // The run's and its controllers' last words (the log tails the JUnit bodies carry).
      if (!c.output.empty()) h += "<pre class=\"output\">" + xmlEscape(c.output, true) + "</pre>";
      h += "</td><td>";
      bool first = true;
      for (const TestArtifact& a : c.artifacts) {
        if (a.link.empty()) continue;
        h += std::string(first ? "" : " ") + "<a href=\"" + xmlEscape(relativeLink(a.link)) + "\">" +
             xmlEscape(a.label) + "</a>";
        first = false;
      }
      h += "</td></tr>\n";
    }
    h += "</table>\n";
  }
  return h + "</body>\n</html>\n";
}

}  // namespace simbob
