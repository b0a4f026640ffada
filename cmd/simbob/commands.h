// One function per subcommand; main.cpp wires them to CLI11.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace CLI {
class App;
}
namespace simbob {
class Registry;
}

namespace simbob::cli {

struct Common;
struct NamedPath;

struct RunArgs {
  std::string scene;
  double duration = 0;
  double dt = 0;
  double sample_interval = 0.01;
  std::string out;
  uint32_t seed = 0;
  bool json = false;
  bool check_determinism = false;
  bool batch_child = false;   ///< started by `simbob batch`: warnings stay out of the log
  std::string space;          ///< overrides SceneSettings Space ("" = the scene's)
  bool auto_disable = false;  ///< turns SceneSettings AutoDisable on
  int max_contacts = 0;       ///< overrides SceneSettings MaxContacts (0 = the scene's)
  bool out_given = false;     ///< --out was on the command line
  std::string log;            ///< --log: comma list of joints, sensors, commands ("" = no run log)
  std::string log_out;        ///< --log-out: the run log (default: --out with .csv -> .log.csv)
};
int cmdRun(RunArgs& a, const Common& common);

/// The options of `simbob run` (also used to check the lines of a batch manifest).
void addRunOptions(CLI::App* run, RunArgs& ra, Common& common);
void addCommon(CLI::App* app, Common& c);
/// The files `simbob run` writes: --out, then (unless --out is a stream) the summary and the
/// partial trajectory.
std::vector<NamedPath> runOutputs(const RunArgs& a);
/// What is wrong with run options beyond their syntax ("" if nothing): time ranges, --out.
std::string runArgsProblem(const RunArgs& a);

int cmdCheck(const std::string& path, const Common& common);
int cmdDump(const std::string& path, const std::string& format, const Common& common);
int cmdTypes(bool markdown, const Registry& reg);

struct CompareArgs {
  std::string actual, golden, report;
  double tol_pos = 1e-6;
  double tol_rot = 1e-6;
  bool json = false;
  bool bless = false;
};
int cmdCompare(const CompareArgs& a, const Common& common);

struct PlotArgs {
  std::string trajectory, golden, out, bodies, title;
};
int cmdPlot(const PlotArgs& a, const Common& common);

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
};
int cmdBatch(const BatchArgs& a, const Common& common);

}  // namespace simbob::cli
