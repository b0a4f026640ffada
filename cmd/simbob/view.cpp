// simbob view TRAJ.csv --scene SCENE -o PAGE.html [--golden GOLDEN.csv] [--title T] (issue #23):
// parses the options and hands the scene, the trajectories and the output to the library
// (simbob/view.h); `compare --html` goes through viewPage too.
#include <CLI/CLI.hpp>

#include "cli.h"
#include "commands.h"
#include "simbob/files.h"
#include "simbob/overrides.h"
#include "simbob/trajectory.h"
#include "simbob/view.h"

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
  Scene scene;
  Model model;
  int code = 0;
  if (!loadAndCompile(a.scene, *common.registry, &scene, &model, &code, false, false, {{"--settings", common.settings}},
                      overrides))
    return code;
  std::vector<NamedPath> inputs = {
      {"the trajectory", a.trajectory}, {"the golden file", a.golden}, {"--settings", common.settings}};
  appendSceneInputs(scene, a.scene, overrides, &inputs);
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

int viewAfterRun(const RunArgs& a, const Common& common) {
  if (isStreamOutput(a.out)) {
    g_log.error({ErrorKind::InvalidInput, {}, "--html reads the trajectory back: --out must be a file, not a stream"});
    return kExitUsage;
  }
  ViewPageArgs v;
  v.trajectory = a.out;
  v.scene = a.scene;
  v.out = a.html;
  v.sets = a.sets;
  return cmdView(v, common);
}

}  // namespace simbob::cli
