// simbob batch in CI: the artifacts folder of one test case (docs/ci.md, "Artifacts"): the
// replay page, plot and comparison of a failure, the run's and controllers' logs, the summary.
#include <filesystem>
#include <set>

#include "batch.h"
#include "cli.h"
#include "commands.h"
#include "simbob/tool/files.h"
#include "simbob/tool/plot.h"
#include "simbob/tool/test_report.h"
#include "simbob/trajectory.h"

namespace simbob::cli::batch {

namespace fs = std::filesystem;

namespace {

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

}  // namespace

// A case's folder in DIR: its name with every byte but A-Z a-z 0-9 - _ . as '_', never starting
// with '.' (no "..", no hidden folder), never the index's name, and unique among the batch's
// folders also where case does not count (an archive unpacked on macOS or Windows).
std::string caseFolder(const std::string& name, std::set<std::string>* taken) {
  std::string safe;
  for (char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    const bool ok =
        (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
    safe += ok ? ch : '_';
  }
  if (safe.size() > 100) safe.resize(100);
  if (safe.empty() || safe[0] == '.') safe.insert(0, "_");
  auto lower = [](std::string t) {
    for (char& ch : t)
      if (ch >= 'A' && ch <= 'Z') ch = static_cast<char>(ch - 'A' + 'a');
    return t;
  };
  std::string folder = safe;
  for (int n = 2; lower(folder) == "index.html" || !taken->insert(lower(folder)).second; ++n)
    folder = safe + "-" + std::to_string(n);
  return folder;
}

// DIR/FOLDER/: what a reader needs to see why the scene is what it is. 0, or an exit status.
int caseArtifacts(const Job& j, const BatchArgs& a, const Common& common, const std::string& folder,
                  TestCaseReport* c) {
  const fs::path dir = fs::path(a.artifacts) / folder;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    g_log.error({ErrorKind::CannotCreate, {dir.string(), 0}, "cannot create the artifacts folder: " + ec.message()});
    return kExitCantCreate;
  }
  int code = 0;
  if (c->outcome == TestOutcome::Failed && j.comparison) code = failureArtifacts(j, a, common, dir, c);
  std::error_code size_ec;
  const bool has_log = fs::exists(j.log, size_ec) && fs::file_size(j.log, size_ec) > 0 && !size_ec;
  if (c->outcome != TestOutcome::Passed && has_log && copyInto(j.log, (dir / "run.log").string()))
    c->artifacts.push_back({"log", (dir / "run.log").string(), folder + "/run.log"});
  if (c->outcome != TestOutcome::Passed) {
    // Each controller's output: controller.log, or controller.log.KEY when the scene started several.
    const std::string stem = fs::path(j.out).stem().string();
    for (const std::string& log : controllerLogs(j)) {
      std::string name = fs::path(log).filename().string().substr(stem.size() + 1);
      for (char& ch : name)
        if (ch == '/' || static_cast<unsigned char>(ch) < 0x20) ch = '_';
      if (copyInto(log, (dir / name).string()))
        c->artifacts.push_back({"controller output", (dir / name).string(), folder + "/" + name});
    }
  }
  if (fs::exists(summaryPath(j)) && copyInto(summaryPath(j), (dir / "summary.json").string()))
    c->artifacts.push_back({"summary", (dir / "summary.json").string(), folder + "/summary.json"});
  return code;
}

}  // namespace simbob::cli::batch
