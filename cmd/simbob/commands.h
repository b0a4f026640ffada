// One function per subcommand; main.cpp wires them to CLI11.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "simbob/tool/comparison.h"
#include "simbob/scene_run.h"

namespace CLI {
class App;
}
namespace simbob {
class Registry;
struct NamedPath;
struct Override;
struct RenderOptions;
struct SweepCase;
struct Trajectory;
}  // namespace simbob

namespace simbob::cli {

struct Common;

/// The view options of `run --record` and `render` (issue #12).
struct ViewArgs {
  std::string size = "640x480";  ///< WIDTHxHEIGHT in pixels
  std::string camera;            ///< a camera's key ("" = the scene's first, else a default view)
  std::string quality;           ///< view quality level ("" = transparency)
  std::string gl;                ///< egl, osmesa ("" = $SIMBOB_GL, else EGL falling back to OSMesa)
  /// Frames per simulated second: of --record and --video; for `render --at T`, those of the
  /// recording whose camera moves the still repeats.
  double fps = 30;
  std::string draw;  ///< models, geoms, sensors, a comma list ("" = models, else geoms when no body has a model)
};
void addViewOptions(CLI::App* app, ViewArgs& v);
/// Checks the view options and fills `o` (the back end from $SIMBOB_GL when --gl is not given);
/// 0, or the exit status after logging the problem.
int renderOptions(const ViewArgs& v, const Common& common, RenderOptions* o);
/// What a Run says goes to the log (and the log file stops before it writes into a file the run
/// reads): the listener of `run` and `render`.
RunListener runListener();

/// `simbob run`: the run itself (RunOptions: most options bind straight to its fields) and what
/// only the command line has.
struct RunArgs {
  RunOptions run;
  bool json = false;
  bool batch_child = false;       ///< started by `simbob batch`: warnings stay out of the log
  std::string space;              ///< overrides SceneSettings Space ("" = the scene's)
  bool auto_disable = false;      ///< turns SceneSettings AutoDisable on
  int max_contacts = 0;           ///< overrides SceneSettings MaxContacts (0 = the scene's)
  std::vector<std::string> sets;  ///< --set KEY.PARAM=VALUE, in order
  ViewArgs view;                  ///< the recording's view (--size, --camera, ...): run.render
  std::string log;                ///< --log: comma list of joints, sensors, commands (run.log)
  std::string columns = "pose";   ///< --columns: "pose", or "pose,velocity" (run.velocity_columns)
};
int cmdRun(RunArgs& a, const Common& common);

/// The options of `simbob run` (also used to check the lines of a batch manifest).
void addRunOptions(CLI::App* run, RunArgs& ra, Common& common);
void addCommon(CLI::App* app, Common& c);
/// The files `simbob run` writes (runOutputFiles): --out, then (unless --out is a stream) the
/// summary, the partial files and the controllers' log, the replay page and the run log.
std::vector<NamedPath> runOutputs(const RunArgs& a);
/// What is wrong with run options beyond their syntax ("" if nothing): runOptionsProblem, then
/// what only the command line can get wrong (--out - with --json, --log and --log-out).
std::string runArgsProblem(const RunArgs& a);
/// Fills the fields of a.run that options do not bind directly: the run log's list, the
/// columns, a batch worker's silence, the overrides (runOverrides), the recording's view, the
/// global settings' texture folder, the stop flag, and the files the command reads and writes
/// besides the run's own. 0, or the exit status (reported).
int completeRunOptions(RunArgs& a, const Common& common);

int cmdCheck(const std::string& path, const Common& common, const std::vector<std::string>& sets = {}, double dt = 0);
int cmdDump(const std::string& path, const std::string& format, const Common& common,
            const std::vector<std::string>& sets = {});

/// The overrides a run applies: the shorthands (--space, --auto-disable, --max-contacts) as
/// SceneSettings overrides, then the DocumentIni's cameras (when the global setting is on), then
/// every --set in order. 64 after reporting a malformed one.
int runOverrides(const RunArgs& a, const Common& common, std::vector<Override>* out);
/// Every type with its parameters, or only the type `only` (its name or alias, any case): an
/// unknown one is a usage error (64) naming the nearest types.
int cmdTypes(bool markdown, const Registry& reg, const std::string& only = "");

struct CompareArgs {
  std::string actual, golden, report;
  std::string html, scene;  ///< --html PAGE --scene SCENE: the replay page of the comparison (simbob view)
  double tol_pos = 1e-6;
  double tol_rot = 1e-6;
  bool json = false;
  bool bless = false;
  std::string junit;  ///< --junit FILE: the comparison as a JUnit report of one test case
};
int cmdCompare(const CompareArgs& a, const Common& common);

/// `simbob view` (issue #23): the replay page of a trajectory in its scene.
struct ViewPageArgs {
  std::string trajectory, scene, out, golden, title;
  std::vector<std::string> sets;  ///< --set KEY.PARAM=VALUE: the overrides the run applied
  CompareOptions compare;         ///< tolerances of the golden comparison
};
CLI::App* addViewCommand(CLI::App& app, ViewPageArgs& v, Common& common);
int cmdView(const ViewPageArgs& a, const Common& common);
/// Writes the page of `actual` (and `golden`, may be null) in a.scene to a.out; the exit status.
int viewPage(const ViewPageArgs& a, const Common& common, const Trajectory* actual, const Trajectory* golden);

struct PlotArgs {
  std::string trajectory, golden, out, bodies, title;
  std::string x, y;       ///< a sweep table's columns: metric y against parameter x
  bool rotation = false;  ///< a fourth panel: each body's rotation from its first orientation
};
int cmdPlot(const PlotArgs& a, const Common& common);

struct RenderArgs {
  std::string scene;
  double at = 0;  ///< s of simulated time drawn (the scene is simulated up to it)
  std::string out;
  double dt = 0;
  uint32_t seed = 0;
  ViewArgs view;
};
int cmdRender(const RenderArgs& a, const Common& common);
/// simbob info: version and the GL back ends with their GL_RENDERER.
int cmdInfo(const std::string& gl, const Common& common);

struct BatchArgs {
  std::vector<std::string> scenes;  ///< paths or glob patterns
  std::string manifest;
  int jobs = 0;  ///< 0 = all cores
  double duration = 10;
  double dt = 0;
  double sample_interval = 0.01;
  std::string out_dir = "batch-out";
  std::string golden;
  double tol_pos = 1e-6;
  double tol_rot = 1e-6;
  std::string report;
  bool json = false;
  bool html = false;  ///< --html: each run's replay page beside its trajectory (STEM.html)
  // CI reports (docs/ci.md, batch_ci.cpp).
  std::string junit;       ///< --junit FILE: JUnit XML, one test case per scene
  std::string artifacts;   ///< --artifacts DIR: each failed scene's page and plot, DIR/index.html
  std::string summary_md;  ///< --summary-md FILE: a short Markdown table of what did not pass
  bool bless = false;      ///< --bless: show each change, then rewrite the golden files
};
int cmdBatch(const BatchArgs& a, const Common& common);

struct SweepArgs {
  std::string input;  ///< sweep description (plan), manifest (run, sbatch), output folder (gather)
  std::string out;
  int case_index = -1;
  int jobs = 0;  ///< run: 0 = one case
  bool force = false;
  bool case_pages = false;  ///< run --html: each ok case's replay page, case-NNNN/view.html
  bool retry = false;
  int max_parallel = 0;
  std::string partition;
  std::string html;   ///< gather --html PAGE: the gallery of the cases, each with its replay page
  std::string junit;  ///< gather --junit FILE: one JUnit test case per sweep case
  CLI::App *plan = nullptr, *run = nullptr, *gather = nullptr, *sbatch = nullptr;
};
CLI::App* addSweepCommands(CLI::App& app, SweepArgs& s, Common& common);
int cmdSweep(const SweepArgs& a, const Common& common);
/// `sweep gather --html PAGE` after the table is written (`gathered`: gather's exit status):
/// each ok case's replay page (OUT/case-NNNN/view.html) and the gallery linking them.
int galleryAfterGather(const SweepArgs& a, const Common& common, int gathered);
/// The replay page of sweep case `c` run in `scene`, from DIR/trajectory.csv to DIR/view.html,
/// titled with the case's index and varied values: `sweep run --html` and `sweep gather --html`
/// (the scene case.json names). The exit status.
int sweepCasePage(const SweepCase& c, const std::string& scene, const std::string& dir, const Common& common);

/// Every command's arguments and its CLI11 subcommand (command_line.cpp): what main parses,
/// checks and dispatches.
struct Invocation {
  Common common;
  RunArgs run;
  std::string check_scene;
  std::vector<std::string> check_sets;
  double check_dt = 0;
  std::string dump_scene, dump_format = "xml";
  std::vector<std::string> dump_sets;
  bool markdown = false;
  std::string types_only;
  CompareArgs compare;
  BatchArgs batch;
  PlotArgs plot;
  SweepArgs sweep;
  RenderArgs render;
  ViewPageArgs view;
  std::string info_gl;
  struct {
    CLI::App *run = nullptr, *check = nullptr, *dump = nullptr, *types = nullptr, *compare = nullptr, *batch = nullptr,
             *plot = nullptr, *sweep = nullptr, *render = nullptr, *view = nullptr, *info = nullptr;
  } cmd;
};
/// Adds every command and its options to `app`, bound to `in`.
void defineCommands(CLI::App& app, Invocation& in);
/// The files the parsed command writes (checked against --log-file before anything starts).
std::vector<NamedPath> commandOutputs(const Invocation& in);
/// Runs the parsed command; its exit status.
int dispatch(Invocation& in, Registry& registry);

}  // namespace simbob::cli
