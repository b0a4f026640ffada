// simbob batch in CI (docs/ci.md): --junit, --summary-md and --artifacts from the finished jobs,
// and --bless. The reports are built as one TestSuiteReport (simbob/test_report.h).
#include <cstdio>
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

std::string summaryPath(const Job& j) { return fs::path(j.out).replace_extension(".json").string(); }

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

TestCaseReport caseOf(const Job& j, const std::string& name) {
  TestCaseReport c;
  c.classname = testClassName(j.scene);
  c.name = name;
  c.file = j.scene;
  c.time = j.wall;
  if (j.status != "ok") {
    c.outcome = TestOutcome::Error;
    c.type = "run " + j.status;
    c.message =
        j.error.empty() ? "the run " + j.status + " (exit status " + std::to_string(j.exit_code) + ")" : j.error;
  } else if (j.golden_status == "no-golden") {
    c.outcome = TestOutcome::Skipped;
    c.message = j.error;
  } else if (j.golden_status == "unreadable") {
    c.outcome = TestOutcome::Error;
    c.type = "golden unreadable";
    c.message = j.error;
  } else if (j.golden_status == "mismatch" && j.comparison) {
    c.outcome = TestOutcome::Failed;
    c.type = "golden mismatch";
    c.message = divergenceMessage(*j.comparison);
    c.details = "actual: " + j.out + "\ngolden: " + j.golden_path + "\n" + j.comparison->text();
  }
  return c;
}

// Copies a small file into the artifacts; false (reported) when it cannot.
bool copyInto(const std::string& from, const std::string& to) {
  std::string bytes, reason;
  Error err;
  if (!readFile(from, kMaxTrajectoryFileBytes, &bytes, &reason)) {
    g_log.error({ErrorKind::MissingInput, {from, 0}, "cannot read it for --artifacts: " + reason});
    return false;
  }
  if (!writeFileAtomically(to, bytes, &err)) {
    g_log.error(err);
    return false;
  }
  return true;
}

// The page of the run against its golden run, and a plot of the diverging body.
int failureArtifacts(const Job& j, const BatchArgs& a, const Common& common, const fs::path& dir, TestCaseReport* c) {
  Trajectory actual, golden;
  Error err;
  if (!readTrajectory(j.out, &actual, &err) || !readTrajectory(j.golden_path, &golden, &err)) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  const std::string name = dir.filename().string();
  int code = 0;
  if (j.comparison && j.comparison->first_divergence) {
    PlotOptions opts;
    opts.bodies = {j.comparison->first_divergence->body};
    opts.rotation = true;
    opts.title = name + ": body " + opts.bodies[0] + " (solid) against its golden run (dashed)";
    if (plotTrajectory(actual, &golden, opts, (dir / "plot.png").string(), &err)) {
      c->artifacts.push_back({"plot", (dir / "plot.png").string(), name + "/plot.png"});
    } else {
      g_log.error(err);
      code = exitCodeFor(err.kind);
    }
  }
  ViewPageArgs v;
  v.trajectory = j.out;
  v.golden = j.golden_path;
  v.scene = j.scene;
  v.out = (dir / "view.html").string();
  v.title = name + " against " + j.golden_path;
  v.compare.tol_pos = a.tol_pos;
  v.compare.tol_rot = a.tol_rot;
  for (size_t i = 0; i + 1 < j.args.size(); ++i)
    if (j.args[i] == "--set") v.sets.push_back(j.args[i + 1]);
  if (int c2 = viewPage(v, common, &actual, &golden); c2 == 0)
    c->artifacts.push_back({"replay page", v.out, name + "/view.html"});
  else if (code == 0)
    code = c2;
  if (writeFileAtomically((dir / "compare.txt").string(), c->details, &err))
    c->artifacts.push_back({"comparison", (dir / "compare.txt").string(), name + "/compare.txt"});
  return code;
}

// DIR/NAME/: what a reader needs to see why the scene is what it is. 0, or an exit status.
int caseArtifacts(const Job& j, const BatchArgs& a, const Common& common, TestCaseReport* c) {
  const fs::path dir = fs::path(a.artifacts) / c->name;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    g_log.error({ErrorKind::CannotCreate, {dir.string(), 0}, "cannot create the artifacts folder: " + ec.message()});
    return kExitCantCreate;
  }
  int code = 0;
  if (c->outcome == TestOutcome::Failed) code = failureArtifacts(j, a, common, dir, c);
  std::error_code size_ec;
  const bool has_log = fs::exists(j.log, size_ec) && fs::file_size(j.log, size_ec) > 0 && !size_ec;
  if (c->outcome != TestOutcome::Passed && has_log && copyInto(j.log, (dir / "run.log").string()))
    c->artifacts.push_back({"log", (dir / "run.log").string(), c->name + "/run.log"});
  if (fs::exists(summaryPath(j)) && copyInto(summaryPath(j), (dir / "summary.json").string()))
    c->artifacts.push_back({"summary", (dir / "summary.json").string(), c->name + "/summary.json"});
  return code;
}

}  // namespace

int checkCiOptions(const BatchArgs& a) {
  if (a.bless && a.golden.empty()) {
    g_log.error({ErrorKind::Usage, {}, "--bless rewrites the golden files of --golden DIR: give --golden"});
    return kExitUsage;
  }
  return 0;
}

int writeCiOutputs(const std::vector<Job>& jobs, const BatchArgs& a, const Common& common, double wall) {
  if (a.junit.empty() && a.summary_md.empty() && a.artifacts.empty()) return 0;
  TestSuiteReport suite = ciSuite("simbob batch");
  suite.time = wall;
  addRunProperties(jobs, a, &suite);
  int code = 0;
  std::map<std::string, int> names;  // a test case's name (its output's stem) made unique
  for (const Job& j : jobs) {
    std::string name = fs::path(j.out).stem().string();
    if (int n = ++names[name]; n > 1) name += "-" + std::to_string(n);
    suite.cases.push_back(caseOf(j, name));
    if (a.artifacts.empty()) continue;
    if (int c = caseArtifacts(j, a, common, &suite.cases.back()); c && !code) code = c;
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
  if (!a.junit.empty()) write(a.junit, writeJUnit(suite, a.junit, &err));
  return code;
}

}  // namespace simbob::cli::batch
