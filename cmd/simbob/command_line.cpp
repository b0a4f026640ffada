// The command line: every command's options (CLI11), what each writes, and the dispatch to the
// command's function (commands.h). main.cpp parses and reports; each command lives in its file.
#include <CLI/CLI.hpp>

#include "cli.h"
#include "commands.h"
#include "simbob/registry.h"

namespace simbob::cli {

void addCommon(CLI::App* app, Common& c) {
  app->add_flag("-q,--quiet", c.quiet, "Print only errors (no progress bar, no info)");
  app->add_flag("-v,--verbose", c.verbose, "Print debug messages");
  app->add_option("--log-file", c.log_file, "Also append log messages to this file");
  app->add_option("--settings", c.settings, "Global settings INI (LogFile, ExtensionFolder, TextureFolder)");
  app->add_option("--plugin", c.plugins, "Load component types from this shared library (repeatable)");
  app->add_option("--package", c.packages, "A URDF's package://NAME/... is in DIR: NAME=DIR (repeatable)");
  app->add_flag("--no-controllers", c.no_controllers,
                "Refuse a scene that would start a program (a communicator's Controller); check lists them");
}

void addRunOptions(CLI::App* run, RunArgs& ra, Common& common) {
  run->add_option("scene", ra.run.scene, "Scene file (XML, or INI by extension)")->required();
  run->add_option("--duration", ra.run.simulation.duration, "Simulated seconds (1e-9 to 1e9)")->required();
  run->add_option("--dt", ra.run.simulation.dt, "Step size in s, 1e-9 to 1e9 (default: the scene's MaxTimeStep)");
  run->add_option("--out", ra.run.out,
                  "Trajectory CSV (default: <scene name>.csv; - for stdout); the summary goes beside it as .json");
  run->add_option("--sample-interval", ra.run.sample_interval,
                  "Simulated seconds between samples, 1e-9 to 1e9 (default 0.01)");
  run->add_option("--seed", ra.run.simulation.seed, "Seed of ODE's random generator (default 0)");
  run->add_option("--threads", ra.run.simulation.threads,
                  "Threads one world's step uses, 1 to 64; the same bytes for every count (default: the scene's "
                  "Threads, 1)")
      ->check(CLI::Range(1, 64));
  run->add_flag("--json", ra.json, "Also print the run summary as JSON on stdout");
  run->add_flag("--check-determinism", ra.run.check_determinism,
                "Run twice in this process; fail naming the first step and body where the runs differ");
  run->add_option("--space", ra.space, "Collision space (overrides the scene): hash, sap, quadtree, simple")
      ->check(CLI::IsMember({"hash", "sap", "quadtree", "simple"}));
  run->add_flag("--auto-disable", ra.auto_disable, "Let ODE put resting bodies to sleep (changes trajectories)");
  run->add_option("--max-contacts", ra.max_contacts, "Contact points per colliding pair (overrides the scene)")
      ->check(CLI::Range(1, 64));
  run->add_option("--set", ra.sets, "Override a scene parameter: KEY.PARAM=VALUE (repeatable; docs/sweeps.md)")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  run->add_option("--port-offset", ra.run.simulation.port_offset,
                  "Added to the Port of every RCLocalSocketCommunicator, so parallel runs do not clash (default 0)");
  run->add_option("--controller", ra.run.simulation.controllers,
                  "KEY=COMMAND: the program simbob starts as the peer of communicator KEY (repeatable; KEY= "
                  "starts none; docs/socket-protocol.md)")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  run->add_option("--peer-timeout", ra.run.simulation.peer_timeout,
                  "Wall-clock s a socket peer may take to connect or to answer, 0.001 to 86400 (default 10)");
  run->add_option("--html", ra.run.html, "Also write the run's replay page (simbob view) after the run");
  run->add_option("--columns", ra.columns,
                  "Trajectory columns: pose (default) or pose,velocity (adds vx,vy,vz m/s and wx,wy,wz rad/s, "
                  "world frame)")
      ->check(CLI::IsMember({"pose", "pose,velocity"}));
  run->add_option("--log", ra.log, "Also write a run log: comma list of joints, sensors, commands");
  run->add_option("--log-out", ra.run.log_out, "The run log CSV (default: --out with .csv replaced by .log.csv)");
  run->add_flag("--batch-child", ra.batch_child, "(internal) started by simbob batch")->group("");
  run->add_flag("--refusal-summary", ra.run.refusal_summary,
                "(internal) started by batch or sweep run: a refused run writes its partial summary")
      ->group("");
  run->add_option("--record", ra.run.record, "Render frames to DIR/frame_000000.png, ... (frame n at t = n / fps)");
  run->add_option("--video", ra.run.video, "Render the frames into one video: FILE.avi (MJPEG) or FILE.mp4 (H.264)");
  addViewOptions(run, ra.view);
  addCommon(run, common);
  // A batch manifest appends per-scene options after the batch-wide ones: the last one wins
  // (every --set and --plugin counts).
  for (CLI::Option* o : run->get_options())
    if (o->get_name() != "--set" && o->get_name() != "--plugin" && o->get_name() != "--controller" &&
        o->get_name() != "--package")
      o->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

namespace {

void defineInspectCommands(CLI::App& app, Invocation& in) {
  in.cmd.check = app.add_subcommand("check", "Load and validate a scene; report every problem found");
  in.cmd.check->add_option("scene", in.check_scene, "Scene file")->required();
  in.cmd.check->add_option("--set", in.check_sets, "Override a scene parameter: KEY.PARAM=VALUE (repeatable)");
  in.cmd.check->add_option("--dt", in.check_dt, "Check for this step (s) as `run --dt` takes it (default: MaxTimeStep)")
      ->check(CLI::Range(kMinClockTime, kMaxClockTime));
  addCommon(in.cmd.check, in.common);
  in.cmd.dump = app.add_subcommand("dump", "Print the normalized scene with every default filled in");
  in.cmd.dump->add_option("scene", in.dump_scene, "Scene file")->required();
  in.cmd.dump->add_option("--set", in.dump_sets, "Override a scene parameter: KEY.PARAM=VALUE (repeatable)");
  in.cmd.dump->add_option("--format", in.dump_format, "xml (default) or ini")->check(CLI::IsMember({"xml", "ini"}));
  addCommon(in.cmd.dump, in.common);
  in.cmd.types = app.add_subcommand("types", "List every component type with its parameters and defaults");
  in.cmd.types->add_option("type", in.types_only, "Print only this type (its parameters, defaults and units)");
  in.cmd.types->add_flag("--markdown", in.markdown, "Markdown tables");
  addCommon(in.cmd.types, in.common);
}

void defineCompareCommand(CLI::App& app, Invocation& in) {
  CompareArgs& ca = in.compare;
  CLI::App* compare = in.cmd.compare = app.add_subcommand("compare", "Compare a trajectory with a golden one");
  compare->add_option("actual", ca.actual, "Trajectory CSV to check")->required();
  compare->add_option("golden", ca.golden, "Golden trajectory CSV")->required();
  compare->add_option("--tol-pos", ca.tol_pos, "Position tolerance in m (default 1e-6)");
  compare->add_option("--tol-rot", ca.tol_rot, "Rotation tolerance in rad (default 1e-6)");
  compare->add_option("--report", ca.report, "Also write the report to FILE (JSON if it ends in .json)");
  compare->add_flag("--json", ca.json, "Print the report as JSON");
  compare->add_flag("--bless", ca.bless, "Show what changes, then replace the golden file with the actual one");
  compare->add_option("--html", ca.html, "Also write the replay page of the comparison (needs --scene; simbob view)");
  compare->add_option("--scene", ca.scene, "With --html: the scene both trajectories were run in");
  compare->add_option("--junit", ca.junit, "Also write the result as a JUnit XML report (docs/ci.md)");
  addCommon(compare, in.common);
}

void defineBatchCommand(CLI::App& app, Invocation& in) {
  BatchArgs& ba = in.batch;
  CLI::App* batch = in.cmd.batch =
      app.add_subcommand("batch", "Run many scenes on worker processes, optionally against golden files");
  batch->add_option("scenes", ba.scenes, "Scene files or glob patterns");
  batch->add_option("--manifest", ba.manifest, "File with one `SCENE [run options]` per line (# comments)");
  batch->add_option("-j,--jobs", ba.jobs, "Worker processes, 1 to 1024 (default: all cores)")
      ->check(CLI::Range(1, 1024));
  batch->add_option("--duration", ba.duration, "Simulated seconds per scene (default 10)");
  batch->add_option("--dt", ba.dt, "Step size in s (default: each scene's MaxTimeStep)");
  batch->add_option("--sample-interval", ba.sample_interval, "Seconds between samples (default 0.01)");
  batch->add_option("-o,--out-dir", ba.out_dir, "Folder for trajectories and logs (default batch-out)");
  batch->add_option("--golden", ba.golden, "Compare each result with GOLDEN/<name>.csv");
  batch->add_option("--tol-pos", ba.tol_pos, "Position tolerance in m (default 1e-6)");
  batch->add_option("--tol-rot", ba.tol_rot, "Rotation tolerance in rad (default 1e-6)");
  batch->add_option("--report", ba.report, "Also write the summary to FILE (JSON if it ends in .json)");
  batch->add_flag("--json", ba.json, "Print the summary as JSON");
  batch->add_flag("--html", ba.html, "Also write each run's replay page beside its trajectory, STEM.html");
  batch->add_option("--junit", ba.junit, "Also write a JUnit XML report, one test case per scene (docs/ci.md)");
  batch->add_option("--artifacts", ba.artifacts,
                    "Folder for each failed scene's replay page against its golden run and plot, and index.html");
  batch->add_option("--summary-md", ba.summary_md, "Also write a short Markdown table of the scenes that did not pass");
  batch->add_flag("--bless", ba.bless,
                  "With --golden: show each change, then make the new trajectories the golden files (not after a "
                  "failed run)");
  addCommon(batch, in.common);
}

void defineOutputCommands(CLI::App& app, Invocation& in) {
  PlotArgs& pa = in.plot;
  CLI::App* plot = in.cmd.plot = app.add_subcommand("plot", "Plot body positions over time to PNG or SVG");
  plot->add_option("trajectory", pa.trajectory, "Trajectory CSV")->required();
  plot->add_option("--golden", pa.golden, "Golden trajectory drawn dashed");
  plot->add_option("--bodies", pa.bodies, "Comma-separated body keys (default: all, at most 8)");
  plot->add_option("--title", pa.title, "Plot title");
  plot->add_flag("--rotation", pa.rotation, "Add a panel: each body's rotation from its first orientation (rad)");
  plot->add_option("--out", pa.out, "Output .png or .svg")->required();
  plot->add_option("--x", pa.x, "With --y: TRAJ.csv is a sweep table; plot column --y against column --x");
  plot->add_option("--y", pa.y, "With --x: the metric column of a sweep table");
  addCommon(plot, in.common);
  in.cmd.sweep = addSweepCommands(app, in.sweep, in.common);
  RenderArgs& rna = in.render;
  CLI::App* render = in.cmd.render = app.add_subcommand("render", "Draw the scene at a simulated time to a PNG");
  render->add_option("scene", rna.scene, "Scene file")->required();
  render->add_option("--at", rna.at, "Simulated time in s (default 0; the scene is simulated up to it)");
  render->add_option("--out", rna.out, "Output PNG (the name must end in .png)")->required();
  render->add_option("--dt", rna.dt, "Step size in s (default: the scene's MaxTimeStep)");
  render->add_option("--seed", rna.seed, "Seed of ODE's random generator (default 0)");
  addViewOptions(render, rna.view);
  addCommon(render, in.common);
  in.cmd.view = addViewCommand(app, in.view, in.common);
  in.cmd.info = app.add_subcommand("info", "Print the version and the GL back ends with their renderer");
  in.cmd.info->add_option("--gl", in.info_gl, "Only this back end: egl or osmesa");
  addCommon(in.cmd.info, in.common);
}

}  // namespace

void defineCommands(CLI::App& app, Invocation& in) {
  in.cmd.run = app.add_subcommand("run", "Simulate a scene and write its pose trajectory as CSV");
  addRunOptions(in.cmd.run, in.run, in.common);
  defineInspectCommands(app, in);
  defineCompareCommand(app, in);
  defineBatchCommand(app, in);
  defineOutputCommands(app, in);
}

int dispatch(Invocation& in, simbob::Registry& registry) {
  const auto& c = in.cmd;
  if (*c.run) return cmdRun(in.run, in.common);
  if (*c.check) return cmdCheck(in.check_scene, in.common, in.check_sets, in.check_dt);
  if (*c.dump) return cmdDump(in.dump_scene, in.dump_format, in.common, in.dump_sets);
  if (*c.types) return cmdTypes(in.markdown, registry, in.types_only);
  if (*c.compare) return cmdCompare(in.compare, in.common);
  if (*c.batch) return cmdBatch(in.batch, in.common);
  if (*c.plot) return cmdPlot(in.plot, in.common);
  if (*c.sweep) return cmdSweep(in.sweep, in.common);
  if (*c.render) return cmdRender(in.render, in.common);
  if (*c.view) return cmdView(in.view, in.common);
  return cmdInfo(in.info_gl, in.common);
}

std::vector<NamedPath> commandOutputs(const Invocation& in) {
  const auto& c = in.cmd;
  if (*c.run) return runOutputs(in.run);
  if (*c.compare) return {{"--report", in.compare.report}, {"--html", in.compare.html}, {"--junit", in.compare.junit}};
  if (*c.plot) return {{"--out", in.plot.out}};
  if (*c.render) return {{"--out", in.render.out}};
  if (*c.view) return {{"--out", in.view.out}};
  if (*c.batch)
    return {{"--report", in.batch.report}, {"--junit", in.batch.junit}, {"--summary-md", in.batch.summary_md}};
  return {};
}

}  // namespace simbob::cli
