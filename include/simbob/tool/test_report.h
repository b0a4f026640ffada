// Test reports for CI systems (docs/ci.md): the outcome of a batch against its golden files (or
// of one comparison, or of a sweep's cases) as one data model, written as JUnit XML (by default
// the strict form Jenkins' xunit plug-in (junit-10.xsd) and Ant's schema accept; extended with
// what GitLab and the annotating actions also read on request), as a short
// Markdown table and as the index page of a folder of failure artifacts. Plain data in, text out;
// every text from input files (scene paths, body keys, error lines) is escaped for its format
// and never carries a control character into the file.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "simbob/error.h"

namespace simbob {

enum class TestOutcome {
  Passed,
  Failed,   ///< ran, and the result is wrong (a golden mismatch, a diverged sweep case)
  Error,    ///< did not run to the end, or was refused (its one error line)
  Skipped,  ///< nothing to compare with (a scene without a golden file, when that is allowed)
};

/// Which JUnit: Strict validates against Jenkins xunit's junit-10.xsd and Ant's strict schema
/// (no `file` or `line` on a test case, no per-case properties or output); Extended adds them:
/// `file` and `line` (action-junit-report, dorny/test-reporter), per-case `<properties>` and a
/// per-case `<system-out>` with GitLab's `[[ATTACHMENT|path]]` lines.
enum class JUnitForm { Strict, Extended };

/// "passed", "failed", "error", "skipped".
const char* testOutcomeName(TestOutcome o);

/// A file that goes with a test case (a replay page, a plot, a log).
struct TestArtifact {
  std::string label;  ///< "replay page", "plot", ...
  std::string path;   ///< as the CI job sees it (relative to its working folder): JUnit attachments
  std::string link;   ///< relative to the artifacts folder, for its index page ("" = not in it)
};

/// One scene (or comparison, or sweep case).
struct TestCaseReport {
  std::string classname;  ///< "scenes.chain": the scene's path without extension, '/' as '.'
  std::string name;       ///< "chain"
  std::string file;       ///< the scene as given ("scenes/chain.xml")
  double time = 0;        ///< wall-clock s
  TestOutcome outcome = TestOutcome::Passed;
  std::string message;  ///< one line: the first divergence, the error line, why it was skipped
  std::string type;     ///< what kind of failure or error ("golden mismatch", "run failed", ...)
  std::string details;  ///< the failure's text: the per-body table (may be cut, see JUnitLimits)
  /// Where the failure points (annotators): the body's first line is "FILE:LINE: message" unless
  /// the message already starts with that place. Empty file: the message alone.
  SourceLoc where;
  std::string output;  ///< the last lines of the run's log and of its controllers' (before the details)
  std::vector<std::pair<std::string, std::string>> properties;  ///< per case (JUnitForm::Extended)
  std::vector<TestArtifact> artifacts;
};

/// The one line a case's failure, error or skipped body starts with: "FILE:LINE: message" (see
/// TestCaseReport::where).
std::string locatedMessage(const TestCaseReport& c);

/// One batch: a JUnit `testsuite`.
struct TestSuiteReport {
  std::string name;       ///< "simbob batch"
  std::string timestamp;  ///< ISO 8601 without zone, UTC ("2026-11-27T11:08:00"); see isoTimestamp
  std::string hostname;
  double time = 0;                                              ///< wall-clock s of the whole batch
  std::vector<std::pair<std::string, std::string>> properties;  ///< in order
  std::vector<TestCaseReport> cases;

  size_t count(TestOutcome o) const;
};

/// Bounds of a JUnit file. GitLab refuses reports over 30 MB: texts are cut to fit, the
/// per-case details first (evenly, at line ends, saying where the rest is), then messages.
struct JUnitLimits {
  size_t max_bytes = 30'000'000;          ///< the whole file
  size_t max_details = size_t{64} << 10;  ///< one case's details, bytes
  size_t max_message = size_t{2} << 10;   ///< one message, attribute or name, bytes
};

/// The suite as JUnit XML (UTF-8, one `testsuite` root). Every failure, error and skipped holds
/// its reason in its body: locatedMessage, the output, the details. The suite's `<system-out>`
/// lists every case's artifacts ("NAME: label: path"). False with *err (InvalidInput) when even
/// with every text cut to its minimum the file would exceed limits.max_bytes.
bool junitXml(const TestSuiteReport& suite, std::string* xml, Error* err, const JUnitLimits& limits = {},
              JUnitForm form = JUnitForm::Strict);

/// junitXml written to `path` as an output file (temporary file and rename): CannotCreate,
/// IoError, or the InvalidInput of junitXml.
bool writeJUnit(const TestSuiteReport& suite, const std::string& path, Error* err, const JUnitLimits& limits = {},
                JUnitForm form = JUnitForm::Strict);

/// GitHub Actions' workflow commands for the cases that did not pass: one
/// `::error file=F,line=L,title=T::message` line each (`::warning` for a skipped one), escaped as
/// the runner reads them (%, CR, LF; and , : in the properties). Printed when GITHUB_ACTIONS=true.
std::string githubAnnotations(const TestSuiteReport& suite);

/// A short Markdown report: a count line and a table of every case that did not pass (scene,
/// result, message), then the passed ones in one line. For $GITHUB_STEP_SUMMARY or a merge-request
/// comment.
std::string summaryMarkdown(const TestSuiteReport& suite);

/// The index page of an artifacts folder: failed, errored, skipped and passed cases, each with its
/// message and a link to each artifact that has one (percent-encoded, prefixed "./").
std::string artifactsIndexHtml(const TestSuiteReport& suite);

/// A relative path ('/'-separated) as a link a page may assign to a.href (the artifacts' index,
/// the sweep gallery): "./" first and every segment percent-encoded (all but A-Z a-z 0-9 - . _ ~),
/// so that no name reads as a scheme ("javascript:..."), a query ('?'), a fragment ('#') or an
/// escape ('%').
std::string relativeLink(const std::string& path);

/// Text as it may appear in XML (and HTML): & < > " ' as entities; control characters, invalid
/// UTF-8, invisible characters and the non-characters U+FFFE/U+FFFF shown visibly (\x01,
/// \u{FEFF}, as quoteInput does). With `multiline`, newlines and tabs stay as they are (element
/// text); without, they are shown visibly too (attributes, one-line messages).
std::string xmlEscape(const std::string& text, bool multiline = false);

/// "2026-11-27T11:08:00" for the current UTC time.
std::string isoTimestamp();

}  // namespace simbob
