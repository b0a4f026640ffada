// simbob compare and simbob plot: looking at trajectories against golden ones.
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "ci_report.h"
#include "cli.h"
#include "commands.h"
#include "simbob/tool/comparison.h"
#include "simbob/tool/files.h"
#include "simbob/tool/plot.h"
#include "simbob/tool/sweep_plan.h"
#include "simbob/tool/test_report.h"
#include "simbob/trajectory.h"
#include "simbob/values.h"

namespace simbob::cli {

namespace {

bool readOrReport(const std::string& path, Trajectory* t, int* code) {
  Error err;
  if (!readTrajectory(path, t, &err)) {
    g_log.error(err);
    *code = exitCodeFor(err.kind);
    return false;
  }
  return true;
}

// --junit FILE: the comparison as one test case; `r` null when a file could not be read (an
// error case with the error line reported). 0, or the exit status of a report not written.
int compareJUnit(const CompareArgs& a, const CompareResult* r) {
  if (a.junit.empty()) return 0;
  TestSuiteReport suite = ciSuite("simbob compare");
  suite.properties.push_back({"tolerance.position", formatNumber(a.tol_pos) + " m"});
  suite.properties.push_back({"tolerance.rotation", formatNumber(a.tol_rot) + " rad"});
  TestCaseReport c;
  c.classname = testClassName(a.actual);
  c.name = std::filesystem::path(a.actual).stem().string();
  c.file = a.actual;
  if (!r) {
    c.outcome = TestOutcome::Error;
    c.type = "unreadable";
    c.message = g_log.first_error ? g_log.first_error->errorLine() : "cannot read the trajectories";
  } else if (!r->pass) {
    c.outcome = TestOutcome::Failed;
    c.type = "golden mismatch";
    c.message = divergenceMessage(*r);
    c.details = "actual: " + a.actual + "\ngolden: " + a.golden + "\n" + r->text();
  }
  suite.cases.push_back(std::move(c));
  Error err;
  if (!writeJUnit(suite, a.junit, &err)) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  return 0;
}

}  // namespace

int cmdCompare(const CompareArgs& a, const Common& common) {
  if (!(a.tol_pos >= 0) || !(a.tol_rot >= 0)) {
    g_log.error({ErrorKind::InvalidInput, {}, "--tol-pos and --tol-rot must be >= 0"});
    return kExitUsage;
  }
  if (a.html.empty() != a.scene.empty()) {
    g_log.error({ErrorKind::InvalidInput, {}, "--html and --scene go together: the page shows the scene"});
    return kExitUsage;
  }
  if (int c =
          checkOutputs({{"--report", a.report}, {"--html", a.html}, {"--junit", a.junit}, {"--log-file", g_log.path}},
                       {{"the trajectory", a.actual}, {"the golden file", a.golden}, {"--settings", common.settings}}))
    return c;
  Trajectory actual, golden;
  int code = 0;
  if (!readOrReport(a.actual, &actual, &code) || !readOrReport(a.golden, &golden, &code)) {
    compareJUnit(a, nullptr);
    return code;
  }
  CompareOptions opts;
  opts.tol_pos = a.tol_pos;
  opts.tol_rot = a.tol_rot;
  CompareResult r = compareTrajectories(actual, golden, opts);
  if (int c = compareJUnit(a, &r)) return c;
  std::string text =
      "actual: " + quoteInput(a.actual, 4096) + "\ngolden: " + quoteInput(a.golden, 4096) + "\n" + r.text();
  std::string json = jsonText(r.json());
  std::fputs(a.json ? json.c_str() : text.c_str(), stdout);
  std::fflush(stdout);
  if (!a.report.empty()) {
    Error err;
    if (!writeFileAtomically(a.report, endsWith(a.report, ".json") ? json : text, &err)) {
      g_log.error(err);
      return exitCodeFor(err.kind);
    }
  }
  if (!a.html.empty()) {
    ViewPageArgs v;
    v.trajectory = a.actual;
    v.golden = a.golden;
    v.scene = a.scene;
    v.out = a.html;
    v.compare = opts;
    if (int c = viewPage(v, common, &actual, &golden)) return c;
  }
  if (a.bless) {
    if (r.pass) {
      g_log.info("golden " + a.golden + " already matches; left as it is");
      return kExitOk;
    }
    // The bytes just compared, not a second read of the file; a symlinked golden file keeps
    // its link and gets new contents.
    std::ifstream in(a.actual, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    Error err;
    if (!in || !writeFileAtomically(a.golden, bytes.str(), &err)) {
      if (err.message.empty()) err = {ErrorKind::MissingInput, {a.actual, 0}, "cannot read it again"};
      g_log.error(err);
      return exitCodeFor(err.kind);
    }
    g_log.info("blessed: " + a.golden + " now holds " + a.actual + " (changes listed above)");
    return kExitOk;
  }
  return r.pass ? kExitOk : kExitResultWrong;
}

// `simbob plot TABLE --x PARAM --y METRIC`: one metric of a gathered sweep against a parameter.
static int plotSweepTable(const PlotArgs& a) {
  if (a.x.empty() || a.y.empty() || !a.golden.empty() || a.rotation) {
    g_log.error(
        {ErrorKind::InvalidInput, {}, "a sweep table plot needs both --x and --y (and no --golden or --rotation)"});
    return kExitUsage;
  }
  std::string text, reason;
  if (!readFile(a.trajectory, size_t{1} << 30, &text, &reason, true)) {
    g_log.error({ErrorKind::MissingInput, {a.trajectory, 0}, "cannot read: " + reason});
    return kExitNoInput;
  }
  Trajectory t;
  Error err;
  if (!sweepTableSeries(text, a.trajectory, a.x, a.y, &t, &err)) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  PlotOptions opts;
  opts.title = a.title.empty() ? a.y + " against " + a.x : a.title;
  opts.panels = 1;
  opts.panel_titles = {a.y};
  opts.time_label = a.x;
  if (!plotTrajectory(t, nullptr, opts, a.out, &err)) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  g_log.info("wrote " + a.out);
  return kExitOk;
}

int cmdPlot(const PlotArgs& a, const Common& common) {
  std::string ext = std::filesystem::path(a.out).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".png" && ext != ".svg") {
    g_log.error({ErrorKind::InvalidInput, {}, "--out " + quoteInput(a.out, 400) + ": a plot is .png or .svg"});
    return kExitUsage;
  }
  if (int c = checkOutputs(
          {{"--out", a.out}, {"--log-file", g_log.path}},
          {{"the trajectory", a.trajectory}, {"the golden file", a.golden}, {"--settings", common.settings}}))
    return c;
  Trajectory actual, golden;
  int code = 0;
  if (!a.x.empty() || !a.y.empty()) return plotSweepTable(a);
  if (!readOrReport(a.trajectory, &actual, &code)) return code;
  if (!a.golden.empty() && !readOrReport(a.golden, &golden, &code)) return code;
  PlotOptions opts;
  opts.title = a.title.empty() ? a.trajectory : a.title;
  opts.rotation = a.rotation;
  size_t start = 0;
  while (start < a.bodies.size()) {
    size_t comma = a.bodies.find(',', start);
    if (comma == std::string::npos) comma = a.bodies.size();
    if (comma > start) opts.bodies.push_back(a.bodies.substr(start, comma - start));
    start = comma + 1;
  }
  Error err;
  if (!plotTrajectory(actual, a.golden.empty() ? nullptr : &golden, opts, a.out, &err)) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  g_log.info("wrote " + a.out);
  return kExitOk;
}

}  // namespace simbob::cli
