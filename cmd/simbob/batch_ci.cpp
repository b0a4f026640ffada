// simbob batch in CI (docs/ci.md): --junit, --summary-md and --artifacts from the finished jobs,
// and --bless. The reports are built as one TestSuiteReport (simbob/test_report.h).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "batch.h"
#include "ci_report.h"
#include "cli.h"
#include "commands.h"
#include "simbob/tool/files.h"
#include "simbob/tool/plot.h"
#include "simbob/tool/test_report.h"
#include "simbob/trajectory.h"
#include "simbob/values.h"

namespace simbob::cli::batch {

namespace {

namespace fs = std::filesystem;

// "0.001" when every run took that step, "0.001, 0.01" when they differ; the same for seeds.
void addRunProperties(const std::vector<Job>& jobs, const BatchArgs& a, TestSuiteReport* s) {
  std::set<std::string> steps, seeds;
  for (const Job& j : jobs) {
    std::ifstream in(summaryPath(j));
    const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
    if (!summary.is_object()) continue;
    if (summary.contains("dt") && summary["dt"].is_number()) steps.insert(formatNumber(summary["dt"].get<double>()));
    if (summary.contains("seed") && summary["seed"].is_number()) seeds.insert(summary["seed"].dump());
  }
  auto join = [](const std::set<std::string>& v) {
    std::string out;
    for (const std::string& x : v) out += (out.empty() ? "" : ", ") + x;
    return out;
  };
  s->properties.push_back({"step", join(steps) + (a.dt > 0 ? " s (--dt)" : " s (each scene's MaxTimeStep)")});
  s->properties.push_back({"seed", join(seeds)});
  s->properties.push_back({"duration", formatNumber(a.duration) + " s"});
  s->properties.push_back({"sample_interval", formatNumber(a.sample_interval) + " s"});
  if (!a.golden.empty()) {
    s->properties.push_back({"golden", a.golden});
    s->properties.push_back({"tolerance.position", formatNumber(a.tol_pos) + " m"});
    s->properties.push_back({"tolerance.rotation", formatNumber(a.tol_rot) + " rad"});
  }
}

// Lines of a log a report carries (its tail), and their bytes at most.
constexpr size_t kTailLines = 20;
constexpr size_t kTailBytes = 4096;

// The last kTailLines lines of a text file (from its last kTailBytes), "" when it is empty or
// cannot be read.
std::string tailOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size <= 0) return "";
  const std::streamoff from = size > static_cast<std::streamoff>(kTailBytes) ? size - kTailBytes : 0;
  in.seekg(from);
  std::string text(static_cast<size_t>(size - from), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<size_t>(in.gcount()));
  if (from > 0) text.erase(0, text.find('\n') == std::string::npos ? 0 : text.find('\n') + 1);  // a whole first line
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  size_t start = text.size(), lines = 0;
  while (start > 0 && lines < kTailLines) {
    const size_t nl = text.rfind('\n', start - 1);
    ++lines;
    start = nl == std::string::npos ? 0 : nl + 1;
    if (nl == std::string::npos) break;
  }
  return text.substr(start);
}

// "FILE:LINE: " at the start of an error line: where it points.
SourceLoc locationOf(const std::string& line) {
  for (size_t colon = line.find(':'); colon != std::string::npos; colon = line.find(':', colon + 1)) {
    size_t end = colon + 1;
    while (end < line.size() && line[end] >= '0' && line[end] <= '9') ++end;
    if (end > colon + 1 && end < line.size() && line[end] == ':' && colon > 0)
      return {line.substr(0, colon), std::atoi(line.substr(colon + 1, end - colon - 1).c_str())};
  }
  return {};
}

// The line of the golden file that holds the first divergence (its time and body), 0 if none.
int goldenRow(const std::string& golden, const Divergence& d) {
  std::ifstream in(golden);
  std::string row;
  for (int n = 1; std::getline(in, row); ++n) {
    const size_t c1 = row.find(',');
    if (c1 == std::string::npos) continue;
    const size_t c2 = row.find(',', c1 + 1);
    std::string body = row.substr(c1 + 1, c2 == std::string::npos ? std::string::npos : c2 - c1 - 1);
    if (body.size() >= 2 && body.front() == '"' && body.back() == '"') body = body.substr(1, body.size() - 2);
    char* end = nullptr;
    const double t = std::strtod(row.c_str(), &end);
    if (end == row.c_str() + c1 && t == d.time && body == d.body) return n;
  }
  return 0;
}

// The run's log tail (when it did not end well) and each controller's, for the report's body.
std::string outputOf(const Job& j) {
  std::string out;
  if (j.status != "ok")
    if (const std::string t = tailOf(j.log); !t.empty())
      out += "--- the run's log, last lines (" + j.log + "):\n" + t + "\n";
  for (const std::string& log : controllerLogs(j))
    if (const std::string t = tailOf(log); !t.empty())
      out += "--- its controller's output, last lines (" + log + "):\n" + t + "\n";
  return out;
}

// scene_hash, step, seed and ODE of one run, from its summary (--junit-extended).
std::vector<std::pair<std::string, std::string>> caseProperties(const Job& j) {
  std::vector<std::pair<std::string, std::string>> props;
  std::ifstream in(summaryPath(j));
  const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
  if (!summary.is_object()) return props;
  auto text = [](const nlohmann::json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); };
  if (summary.contains("scene_hash")) props.push_back({"scene_hash", text(summary["scene_hash"])});
  if (summary.contains("dt") && summary["dt"].is_number())
    props.push_back({"step", formatNumber(summary["dt"].get<double>()) + " s"});
  if (summary.contains("seed")) props.push_back({"seed", text(summary["seed"])});
  if (summary.contains("reproducibility") && summary["reproducibility"].is_object()) {
    const nlohmann::json& r = summary["reproducibility"];
    if (r.contains("ode_version")) props.push_back({"ode.version", text(r["ode_version"])});
    if (r.contains("physics")) props.push_back({"ode.configuration", text(r["physics"])});
  }
  return props;
}

TestCaseReport caseOf(const Job& j, const std::string& name, const BatchArgs& a) {
  TestCaseReport c;
  c.classname = testClassName(j.scene);
  c.name = name;
  c.file = j.scene;
  c.time = j.wall;
  c.where = {j.loc.file.empty() ? FileName(j.scene) : j.loc.file, j.loc.line};
  if (j.status != "ok") {
    c.outcome = TestOutcome::Error;
    c.type = "run " + j.status;
    c.message =
        j.error.empty() ? "the run " + j.status + " (exit status " + std::to_string(j.exit_code) + ")" : j.error;
    if (SourceLoc at = locationOf(c.message); !at.file.empty()) c.where = at;
  } else if (j.golden_status == "no-golden") {
    c.outcome = a.allow_missing_golden ? TestOutcome::Skipped : TestOutcome::Failed;
    c.type = "no golden file";
    c.message = j.error;
  } else if (j.golden_status == "unreadable") {
    c.outcome = TestOutcome::Error;
    c.type = "golden unreadable";
    c.message = j.error;
    if (SourceLoc at = locationOf(c.message); !at.file.empty()) c.where = at;
  } else if (j.golden_status == "mismatch" && j.comparison) {
    c.outcome = TestOutcome::Failed;
    c.type = "golden mismatch";
    c.message = divergenceMessage(*j.comparison);
    c.details = "actual: " + j.out + "\ngolden: " + j.golden_path + "\n" + j.comparison->text();
    c.where = {j.golden_path,
               j.comparison->first_divergence ? goldenRow(j.golden_path, *j.comparison->first_divergence) : 0};
  }
  if (c.outcome != TestOutcome::Passed) c.output = outputOf(j);
  if (a.junit_extended) c.properties = caseProperties(j);
  return c;
}

}  // namespace

std::string summaryPath(const Job& j) { return fs::path(j.out).replace_extension(".json").string(); }

// The logs of the controllers a job's run started: OUT.controller.log, and OUT.controller.log.KEY
// when it started several (simbob/scene_run.h), sorted.
std::vector<std::string> controllerLogs(const Job& j) {
  const fs::path base = fs::path(j.out).replace_extension(".controller.log");
  std::vector<std::string> logs;
  std::error_code ec;
  const fs::path dir = base.parent_path().empty() ? fs::path(".") : base.parent_path();
  const std::string name = base.filename().string();
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string f = it->path().filename().string();
    if ((f == name || f.rfind(name + ".", 0) == 0) && it->is_regular_file(ec))
      logs.push_back((base.parent_path() / f).string());
  }
  std::sort(logs.begin(), logs.end());
  return logs;
}

int checkCiOptions(const BatchArgs& a) {
  if ((a.bless || !a.bless_from.empty()) && a.golden.empty()) {
    g_log.error({ErrorKind::Usage,
                 {},
                 std::string(a.bless ? "--bless" : "--bless-from") +
                     " rewrites the golden files of --golden DIR: give --golden"});
    return kExitUsage;
  }
  if (!a.bless_from.empty() && (!a.scenes.empty() || !a.manifest.empty())) {
    g_log.error({ErrorKind::Usage,
                 {},
                 "--bless-from DIR takes the trajectories in DIR and runs no scene: give no scenes or --manifest"});
    return kExitUsage;
  }
  return 0;
}

int writeCiOutputs(const std::vector<Job>& jobs, const BatchArgs& a, const Common& common, double wall) {
  const char* gha = std::getenv("GITHUB_ACTIONS");
  const bool annotate = gha && std::string(gha) == "true";
  if (a.junit.empty() && a.summary_md.empty() && a.artifacts.empty() && !annotate) return 0;
  TestSuiteReport suite = ciSuite(a.suite_name);
  suite.time = wall;
  addRunProperties(jobs, a, &suite);
  int code = 0;
  std::map<std::string, int> names;  // a test case's name (its output's stem) made unique
  std::set<std::string> folders;     // the case folders of --artifacts
  for (const Job& j : jobs) {
    std::string name = fs::path(j.out).stem().string();
    if (int n = ++names[name]; n > 1) name += "-" + std::to_string(n);
    suite.cases.push_back(caseOf(j, name, a));
    if (a.artifacts.empty()) continue;
    const std::string folder = caseFolder(name, &folders);
    if (int c = caseArtifacts(j, a, common, folder, &suite.cases.back()); c && !code) code = c;
  }
  if (annotate) {
    // GitHub Actions reads workflow commands from the job's output: one annotation per case that
    // did not pass (with --json on stderr, so that stdout stays JSON).
    std::fputs(githubAnnotations(suite).c_str(), a.json ? stderr : stdout);
    std::fflush(a.json ? stderr : stdout);
  }
  Error err;
  auto write = [&](const std::string& path, bool ok) {
    if (ok) return g_log.info("wrote " + path);
    g_log.error(err);
    if (!code) code = exitCodeFor(err.kind);
  };
  if (!a.artifacts.empty()) {
    const std::string index = (fs::path(a.artifacts) / "index.html").string();
    write(index, writeFileAtomically(index, artifactsIndexHtml(suite), &err));
  }
  if (!a.summary_md.empty()) write(a.summary_md, writeFileAtomically(a.summary_md, summaryMarkdown(suite), &err));
  if (!a.junit.empty())
    write(a.junit, writeJUnit(suite, a.junit, &err, {}, a.junit_extended ? JUnitForm::Extended : JUnitForm::Strict));
  return code;
}

}  // namespace simbob::cli::batch
