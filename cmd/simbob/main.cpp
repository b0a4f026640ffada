// simbob: the command-line driver. Each subcommand lives in its own file (commands.h).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <exception>

#include "cli.h"
#include "commands.h"
#include "plugins.h"
#include "simbob/registry.h"
#include "version.h"

using namespace simbob::cli;

namespace {

// CLI11 says only "The following argument was not expected: --duraton": name the option of that
// command that was meant. Returns false when no unknown long option is found.
bool reportUnknownOption(CLI::App& app, int argc, char** argv) {
  CLI::App* cmd = &app;
  std::string path = "simbob";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--") break;
    if (arg.rfind("--", 0) != 0) {
      for (CLI::App* sub : cmd->get_subcommands({}))
        if (sub->get_name() == arg) {
          cmd = sub;
          path += " " + arg;
          break;
        }
      continue;
    }
    const std::string name = arg.substr(0, arg.find('='));
    if (cmd->get_option_no_throw(name) || app.get_option_no_throw(name)) continue;
    std::vector<std::string> names;
    for (const CLI::Option* o : cmd->get_options())
      for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
    const std::string near = simbob::didYouMean(name, names);
    std::fprintf(stderr, "%s: error: unknown option '%s'%s; %s --help lists the options\n", path.c_str(),
                 simbob::quoteInput(name).c_str(), near.empty() ? "" : (" (did you mean '" + near + "'?)").c_str(),
                 path.c_str());
    return true;
  }
  return false;
}

}  // namespace

namespace simbob::cli {

void addCommon(CLI::App* app, Common& c) {
  app->add_flag("-q,--quiet", c.quiet, "Print only errors (no progress bar, no info)");
  app->add_flag("-v,--verbose", c.verbose, "Print debug messages");
  app->add_option("--log-file", c.log_file, "Also append log messages to this file");
  app->add_option("--settings", c.settings, "Global settings INI (LogFile, ExtensionFolder, TextureFolder)");
  app->add_option("--plugin", c.plugins, "Load component types from this shared library (repeatable)");
}

void addRunOptions(CLI::App* run, RunArgs& ra, Common& common) {
  run->add_option("scene", ra.scene, "Scene file (XML, or INI by extension)")->required();
  run->add_option("--duration", ra.duration, "Simulated seconds (1e-9 to 1e9)")->required();
  run->add_option("--dt", ra.dt, "Step size in s, 1e-9 to 1e9 (default: the scene's MaxTimeStep)");
  run->add_option("--out", ra.out,
                  "Trajectory CSV (default: <scene name>.csv; - for stdout); the summary goes beside it as .json");
  run->add_option("--sample-interval", ra.sample_interval,
                  "Simulated seconds between samples, 1e-9 to 1e9 (default 0.01)");
  run->add_option("--seed", ra.seed, "Seed of ODE's random generator (default 0)");
  run->add_flag("--json", ra.json, "Also print the run summary as JSON on stdout");
  run->add_flag("--check-determinism", ra.check_determinism,
                "Run twice in this process; fail naming the first step and body where the runs differ");
  run->add_option("--space", ra.space, "Collision space (overrides the scene): hash, sap, quadtree, simple")
      ->check(CLI::IsMember({"hash", "sap", "quadtree", "simple"}));
  run->add_flag("--auto-disable", ra.auto_disable, "Let ODE put resting bodies to sleep (changes trajectories)");
  run->add_option("--max-contacts", ra.max_contacts, "Contact points per colliding pair (overrides the scene)")
      ->check(CLI::Range(1, 64));
  run->add_option("--set", ra.sets, "Override a scene parameter: KEY.PARAM=VALUE (repeatable; docs/sweeps.md)")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  run->add_option("--port-offset", ra.port_offset,
                  "Added to the Port of every RCLocalSocketCommunicator, so parallel runs do not clash (default 0)");
  run->add_option("--controller", ra.controllers,
                  "KEY=COMMAND: the program simbob starts as the peer of communicator KEY (repeatable; KEY= "
                  "starts none; docs/socket-protocol.md)")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  run->add_option("--peer-timeout", ra.peer_timeout,
                  "Wall-clock s a socket peer may take to connect or to answer, 0.001 to 86400 (default 10)");
  run->add_option("--html", ra.html, "Also write the run's replay page (simbob view) after the run");
  run->add_option("--columns", ra.columns,
                  "Trajectory columns: pose (default) or pose,velocity (adds vx,vy,vz m/s and wx,wy,wz rad/s, "
                  "world frame)")
      ->check(CLI::IsMember({"pose", "pose,velocity"}));
  run->add_option("--log", ra.log, "Also write a run log: comma list of joints, sensors, commands");
  run->add_option("--log-out", ra.log_out, "The run log CSV (default: --out with .csv replaced by .log.csv)");
  run->add_flag("--batch-child", ra.batch_child, "(internal) started by simbob batch")->group("");
  run->add_option("--record", ra.record, "Render frames to DIR/frame_000000.png, ... (frame n at t = n / fps)");
  run->add_option("--video", ra.video, "Render the frames into one video: FILE.avi (MJPEG) or FILE.mp4 (H.264)");
  addViewOptions(run, ra.view);
  addCommon(run, common);
  // A batch manifest appends per-scene options after the batch-wide ones: the last one wins
  // (every --set and --plugin counts).
  for (CLI::Option* o : run->get_options())
    if (o->get_name() != "--set" && o->get_name() != "--plugin" && o->get_name() != "--controller")
      o->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

}  // namespace simbob::cli

// CLI11 builds its options before the try below; an exception there is a bug worth a crash.
int main(int argc, char** argv) {  // NOLINT(bugprone-exception-escape)
  CLI::App app{"simbob: headless batch simulator for mobile robots (Simulator Bob scenes on ODE)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", versionLine());
  Common common;

  RunArgs ra;
  CLI::App* run = app.add_subcommand("run", "Simulate a scene and write its pose trajectory as CSV");
  addRunOptions(run, ra, common);

  std::string check_scene;
  CLI::App* check = app.add_subcommand("check", "Load and validate a scene; report every problem found");
  check->add_option("scene", check_scene, "Scene file")->required();
  std::vector<std::string> check_sets, dump_sets;
  check->add_option("--set", check_sets, "Override a scene parameter: KEY.PARAM=VALUE (repeatable)");
  double check_dt = 0;
  check->add_option("--dt", check_dt, "Check for this step (s) as `run --dt` takes it (default: MaxTimeStep)")
      ->check(CLI::Range(kMinTimeOption, kMaxTimeOption));
  addCommon(check, common);

  std::string dump_scene, dump_format = "xml";
  CLI::App* dump = app.add_subcommand("dump", "Print the normalized scene with every default filled in");
  dump->add_option("scene", dump_scene, "Scene file")->required();
  dump->add_option("--set", dump_sets, "Override a scene parameter: KEY.PARAM=VALUE (repeatable)");
  dump->add_option("--format", dump_format, "xml (default) or ini")->check(CLI::IsMember({"xml", "ini"}));
  addCommon(dump, common);

  bool markdown = false;
  CLI::App* types = app.add_subcommand("types", "List every component type with its parameters and defaults");
  std::string types_only;
  types->add_option("type", types_only, "Print only this type (its parameters, defaults and units)");
  types->add_flag("--markdown", markdown, "Markdown tables");
  addCommon(types, common);

  CompareArgs ca;
  CLI::App* compare = app.add_subcommand("compare", "Compare a trajectory with a golden one");
  compare->add_option("actual", ca.actual, "Trajectory CSV to check")->required();
  compare->add_option("golden", ca.golden, "Golden trajectory CSV")->required();
  compare->add_option("--tol-pos", ca.tol_pos, "Position tolerance in m (default 1e-6)");
  compare->add_option("--tol-rot", ca.tol_rot, "Rotation tolerance in rad (default 1e-6)");
  compare->add_option("--report", ca.report, "Also write the report to FILE (JSON if it ends in .json)");
  compare->add_flag("--json", ca.json, "Print the report as JSON");
  compare->add_flag("--bless", ca.bless, "Show what changes, then replace the golden file with the actual one");
  compare->add_option("--html", ca.html, "Also write the replay page of the comparison (needs --scene; simbob view)");
  compare->add_option("--scene", ca.scene, "With --html: the scene both trajectories were run in");
  addCommon(compare, common);

  BatchArgs ba;
  CLI::App* batch = app.add_subcommand("batch", "Run many scenes on worker processes, optionally against golden files");
  batch->add_option("scenes", ba.scenes, "Scene files or glob patterns");
  batch->add_option("--manifest", ba.manifest, "File with one `SCENE [run options]` per line (# comments)");
  batch->add_option("-j,--jobs", ba.jobs, "Worker processes, 1 to 1024 (default: all cores)")
      ->check(CLI::Range(1, 1024));
  batch->add_option("--duration", ba.duration, "Simulated seconds per scene (default 10)");
  batch->add_option("--dt", ba.dt, "Step size in s (default: each scene's MaxTimeStep)");
  batch->add_option("--sample-interval", ba.sample_interval, "Seconds between samples (default 0.01)");
  batch->add_option("--out-dir", ba.out_dir, "Folder for trajectories and logs (default batch-out)");
  batch->add_option("--golden", ba.golden, "Compare each result with GOLDEN/<name>.csv");
  batch->add_option("--tol-pos", ba.tol_pos, "Position tolerance in m (default 1e-6)");
  batch->add_option("--tol-rot", ba.tol_rot, "Rotation tolerance in rad (default 1e-6)");
  batch->add_option("--report", ba.report, "Also write the summary to FILE (JSON if it ends in .json)");
  batch->add_flag("--json", ba.json, "Print the summary as JSON");
  batch->add_flag("--html", ba.html, "Also write each run's replay page beside its trajectory, STEM.html");
  addCommon(batch, common);

  PlotArgs pa;
  CLI::App* plot = app.add_subcommand("plot", "Plot body positions over time to PNG or SVG");
  plot->add_option("trajectory", pa.trajectory, "Trajectory CSV")->required();
  plot->add_option("--golden", pa.golden, "Golden trajectory drawn dashed");
  plot->add_option("--bodies", pa.bodies, "Comma-separated body keys (default: all, at most 8)");
  plot->add_option("--title", pa.title, "Plot title");
  plot->add_option("--out", pa.out, "Output .png or .svg")->required();
  plot->add_option("--x", pa.x, "With --y: TRAJ.csv is a sweep table; plot column --y against column --x");
  plot->add_option("--y", pa.y, "With --x: the metric column of a sweep table");
  addCommon(plot, common);

  SweepArgs sa;
  CLI::App* sweep = addSweepCommands(app, sa, common);
  RenderArgs rna;
  CLI::App* render = app.add_subcommand("render", "Draw the scene at a simulated time to a PNG");
  render->add_option("scene", rna.scene, "Scene file")->required();
  render->add_option("--at", rna.at, "Simulated time in s (default 0; the scene is simulated up to it)");
  render->add_option("--out", rna.out, "Output PNG (the name must end in .png)")->required();
  render->add_option("--dt", rna.dt, "Step size in s (default: the scene's MaxTimeStep)");
  render->add_option("--seed", rna.seed, "Seed of ODE's random generator (default 0)");
  addViewOptions(render, rna.view);
  addCommon(render, common);

  ViewPageArgs va;
  CLI::App* view = addViewCommand(app, va, common);

  std::string info_gl;
  CLI::App* info = app.add_subcommand("info", "Print the version and the GL back ends with their renderer");
  info->add_option("--gl", info_gl, "Only this back end: egl or osmesa");
  addCommon(info, common);

  // Name an unknown subcommand instead of CLI11's "A subcommand is required".
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
  if (argc > 1 && argv[1][0] != '-' && std::find(names.begin(), names.end(), argv[1]) == names.end()) {
    std::string near = simbob::didYouMean(argv[1], names);
    std::fprintf(stderr,
                 "simbob: error: unknown command '%s'%s; commands: run, check, dump, types, compare, batch, plot, "
                 "sweep, render, view, info\n",
                 argv[1], near.empty() ? "" : (" (did you mean '" + near + "'?)").c_str());
    return kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // An unknown option explains the rest ("--duraton 1" also leaves --duration missing).
    if (!reportUnknownOption(app, argc, argv)) app.exit(e);
    return kExitUsage;
  }
  // An output option given as "" is a mistake, not a request for the default name.
  for (CLI::App* sub : {run, compare, plot, batch, check, dump, render, view, info})
    for (const char* name : {"--out", "--report", "--log-file", "--out-dir", "--settings", "--record", "--video"}) {
      CLI::Option* o = sub->get_option_no_throw(name);
      if (!o || o->count() == 0) continue;
      for (const std::string& v : o->results())
        if (int c = checkNotEmpty(name, v, true)) return c;
    }
  ra.out_given = run->count("--out") > 0;
  // The one registry of component types: built here, passed down (plug-ins will add to it).
  simbob::Registry registry;
  if (!simbob::registerBuiltins(registry)) {
    for (const std::string& p : registry.problems())
      g_log.error({simbob::ErrorKind::Internal, {}, "internal error: " + p});
    return kExitSoftware;
  }
  common.registry = &registry;
  int code = kExitUsage;
  try {
    if (int c = readSettings(common)) return c;
    // Plug-ins before any scene: their types resolve like the built-ins.
    if (int c = loadPlugins(registry, common.plugins, common.extension_folder)) return c;
    // The log file is opened (created) first: it must not be another output of the command.
    if (!common.log_file.empty()) {
      std::vector<NamedPath> outputs;
      if (*run) outputs = runOutputs(ra);
      if (*compare) outputs = {{"--report", ca.report}, {"--html", ca.html}};
      if (*plot) outputs = {{"--out", pa.out}};
      if (*render) outputs = {{"--out", rna.out}};
      if (*view) outputs = {{"--out", va.out}};
      if (*batch) outputs = {{"--report", ba.report}};
      outputs.push_back({"--log-file", common.log_file});
      if (int c = checkOutputs(outputs, {})) return c;
    }
    if (int c = setupLogging(common)) return c;
    if (*run) code = cmdRun(ra, common);
    if (*check) code = cmdCheck(check_scene, common, check_sets, check_dt);
    if (*dump) code = cmdDump(dump_scene, dump_format, common, dump_sets);
    if (*types) code = cmdTypes(markdown, registry, types_only);
    if (*compare) code = cmdCompare(ca, common);
    if (*batch) code = cmdBatch(ba, common);
    if (*plot) code = cmdPlot(pa, common);
    if (*sweep) code = cmdSweep(sa, common);
    if (*render) code = cmdRender(rna, common);
    if (*view) code = cmdView(va, common);
    if (*info) code = cmdInfo(info_gl, common);
  } catch (const std::exception& e) {
    g_log.error({simbob::ErrorKind::Internal, {}, std::string("internal error: ") + e.what()});
    code = kExitSoftware;
  }
  // A log that could not be written is an output that failed.
  if (int c = g_log.close(); c != 0 && code == kExitOk) code = c;
  return code;
}
