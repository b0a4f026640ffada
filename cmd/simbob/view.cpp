// simbob view TRAJ.csv --scene SCENE -o PAGE.html [--golden GOLDEN.csv] [--title T] (issue #23):
// parses the options and hands the scene, the trajectories and the output to the library
// (simbob/tool/replay_page.h); `compare --html` goes through viewPage too.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "commands.h"
#include "simbob/tool/files.h"
#include "simbob/overrides.h"
#include "simbob/tool/sweep_plan.h"
#include "simbob/trajectory.h"
#include "simbob/tool/replay_page.h"

namespace simbob::cli {

CLI::App* addViewCommand(CLI::App& app, ViewPageArgs& v, Common& common) {
  CLI::App* view =
      app.add_subcommand("view", "Write a self-contained HTML page that replays a trajectory in its scene");
  view->add_option("trajectory", v.trajectory, "Trajectory CSV")->required();
  view->add_option("--scene", v.scene, "The scene the trajectory was run in")->required();
  view->add_option("-o,--out", v.out, "Output HTML page")->required();
  view->add_option("--golden", v.golden, "Golden trajectory: drawn as ghosts, its first divergence marked");
  view->add_option("--title", v.title, "Page title (default: the trajectory's name)");
  view->add_option("--tol-pos", v.compare.tol_pos, "Position tolerance of the comparison in m (default 1e-6)");
  view->add_option("--tol-rot", v.compare.tol_rot, "Rotation tolerance of the comparison in rad (default 1e-6)");
  view->add_option("--set", v.sets, "Override a scene parameter as the run did: KEY.PARAM=VALUE (repeatable)");
  addCommon(view, common);
  return view;
}

int viewPage(const ViewPageArgs& a, const Common& common, const Trajectory* actual, const Trajectory* golden) {
  std::vector<Override> overrides;
  if (int c = sceneOverrides(common, a.scene, a.sets, &overrides)) return c;
  LoadReport loaded;
  Model model;
  int code = 0;
  if (!loadAndCompile(a.scene, *common.registry, &model, &loaded, &code, false, false,
                      {{"--settings", common.settings}}, overrides))
    return code;
  std::vector<NamedPath> inputs = {
      {"the trajectory", a.trajectory}, {"the golden file", a.golden}, {"--settings", common.settings}};
  appendSceneInputs(loaded, a.scene, overrides, &inputs);
  appendModelInputs(model, common, a.scene, &inputs);
  if (int c = checkOutputs({{"--out", a.out}, {"--log-file", g_log.path}}, inputs)) return c;
  ViewPageInput in;
  in.model = &model;
  in.actual = actual;
  in.golden = golden;
  in.compare = a.compare;
  in.title = a.title.empty() ? a.trajectory : a.title;
  in.scene_name = a.scene;
  in.texture_folder = common.texture_folder;
  Error err;
  if (!writeViewPage(in, a.out, &err)) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  g_log.info("wrote " + a.out);
  return kExitOk;
}

int cmdView(const ViewPageArgs& a, const Common& common) {
  if (!(a.compare.tol_pos >= 0) || !(a.compare.tol_rot >= 0)) {
    g_log.error({ErrorKind::InvalidInput, {}, "--tol-pos and --tol-rot must be >= 0"});
    return kExitUsage;
  }
  Trajectory actual, golden;
  Error err;
  if (!readTrajectory(a.trajectory, &actual, &err) || (!a.golden.empty() && !readTrajectory(a.golden, &golden, &err))) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  return viewPage(a, common, &actual, a.golden.empty() ? nullptr : &golden);
}

namespace {

/// The rows of a CSV table (RFC 4180 quoting, as `sweep gather` writes it).
std::vector<std::vector<std::string>> csvRows(const std::string& text) {
  std::vector<std::vector<std::string>> rows(1);
  std::string field;
  bool quoted = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',' || c == '\n') {
      rows.back().push_back(field);
      field.clear();
      if (c == '\n') rows.emplace_back();
    } else {
      field += c;
    }
  }
  if (rows.back().empty()) rows.pop_back();
  return rows;
}

}  // namespace

int sweepCasePage(const SweepCase& c, const std::string& scene, const std::string& dir, const Common& common) {
  // The case's own page beside its trajectory, in its scene with its overrides.
  namespace fs = std::filesystem;
  ViewPageArgs v;
  v.trajectory = (fs::path(dir) / "trajectory.csv").string();
  v.scene = scene;
  v.out = (fs::path(dir) / "view.html").string();
  v.sets = c.set;
  v.title = "case " + std::to_string(c.index);
  for (const auto& [k, val] : c.vary) v.title += " " + k + "=" + val;
  return cmdView(v, common);
}

// The scene a gathered case ran: case.json's "scene" (absolute, written by sweep run); for a case
// of an older simbob, the scene its summary names (as sweep run was given it: from its folder).
static std::string gatheredScene(const std::filesystem::path& dir) {
  for (const char* file : {"case.json", "summary.json"}) {
    std::string text;
    if (!readFile((dir / file).string(), size_t{1} << 20, &text, nullptr, true)) continue;
    const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_object() && j.contains("scene") && j["scene"].is_string()) return j["scene"].get<std::string>();
  }
  return "";
}

int galleryAfterGather(const SweepArgs& a, const Common& common, int gathered) {
  if (gathered != kExitOk && gathered != kExitResultWrong) return gathered;  // no table
  namespace fs = std::filesystem;
  const std::string manifest = (fs::path(a.input) / "manifest.jsonl").string();
  const std::string table = a.out.empty() ? (fs::path(a.input) / "results.csv").string() : a.out;
  std::string mtext, ttext, reason;
  std::vector<SweepCase> cases;
  Error err;
  if (!readFile(manifest, size_t{1} << 30, &mtext, &reason, true) || !parseManifest(mtext, manifest, &cases, &err) ||
      !readFile(table, size_t{1} << 30, &ttext, &reason, true)) {
    if (err.message.empty()) err = {ErrorKind::MissingInput, {table, 0}, "cannot read: " + reason};
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  const std::vector<std::vector<std::string>> rows = csvRows(ttext);
  const fs::path gallery_dir = fs::absolute(fs::path(a.html)).parent_path();
  std::vector<GalleryCase> gallery;
  size_t status_col = 0;
  while (status_col < rows[0].size() && rows[0][status_col] != "status") ++status_col;
  for (size_t r = 1; r < rows.size() && r - 1 < cases.size(); ++r) {
    const SweepCase& c = cases[r - 1];
    GalleryCase g{c.index, status_col < rows[r].size() ? rows[r][status_col] : "missing", rows[r], ""};
    const fs::path dir = fs::path(a.input) / caseDirName(c.index);
    if (g.status == "ok" && fs::exists(dir / "trajectory.csv")) {
      if (int code = sweepCasePage(c, gatheredScene(dir), dir.string(), common)) return code;
      g.page = fs::relative(fs::absolute(dir / "view.html"), gallery_dir).generic_string();
    }
    gallery.push_back(std::move(g));
  }
  if (!writeFileAtomically(a.html, sweepGalleryHtml("sweep " + a.input, rows[0], gallery), &err)) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  g_log.info("wrote " + a.html + " (" + std::to_string(gallery.size()) + " cases)");
  return gathered;
}

}  // namespace simbob::cli
