// One function per subcommand; main.cpp wires them to CLI11.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace simbob {
class Registry;
}

namespace simbob::cli {

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
};
int cmdRun(RunArgs& a, const Registry& reg);

int cmdCheck(const std::string& scene, const Registry& reg);
int cmdDump(const std::string& scene, const std::string& format, const Registry& reg);
int cmdTypes(bool markdown, const Registry& reg);

struct CompareArgs {
  std::string actual, golden, report;
  double tol_pos = 1e-6;
  double tol_rot = 1e-6;
  bool json = false;
  bool bless = false;
};
int cmdCompare(const CompareArgs& a);

struct PlotArgs {
  std::string trajectory, golden, out, bodies, title;
};
int cmdPlot(const PlotArgs& a);

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
int cmdBatch(const BatchArgs& a);

}  // namespace simbob::cli
