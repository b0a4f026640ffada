// The run summary (docs/formats.md, "Run summary JSON"): what a run was, how it ended and what
// its bytes depend on. Built here so that every client of the Simulation API writes the same.
#include <fstream>
#include <string>
#include <vector>

#include "simbob/physics.h"
#include "simbob/tool/platform.h"
#include "simbob/simulation.h"

namespace simbob {

namespace {

// CPU features that change floating-point code paths in libraries (libm, ODE built with them).
std::vector<std::string> cpuFeatures() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  std::vector<std::string> found;
  static const char* wanted[] = {"sse2", "avx", "avx2", "fma", "avx512f"};
  while (std::getline(in, line)) {
    if (line.rfind("flags", 0) != 0) continue;
    line += " ";
    for (const char* w : wanted)
      if (line.find(std::string(" ") + w + " ") != std::string::npos) found.push_back(w);
    break;
  }
  return found;
}

}  // namespace

const char* runStatusName(RunStatus s) {
  switch (s) {
    case RunStatus::Completed:
      return "completed";
    case RunStatus::Diverged:
      return "diverged";
    case RunStatus::Interrupted:
      return "interrupted";
    case RunStatus::Failed:
      return "failed";
  }
  return "failed";
}

nlohmann::ordered_json runSummary(const Model& model, const RunResult& r, const RunSummaryInput& in) {
  nlohmann::ordered_json summary;
  summary["simbob_version"] = SIMBOB_VERSION;
  summary["scene"] = in.scene;
  summary["scene_hash"] = "fnv1a64w:" + in.scene_hash;
  summary["status"] = runStatusName(r.status);
  summary["dt"] = r.dt;
  summary["duration"] = in.duration;
  summary["sim_time"] = r.sim_time;
  summary["sample_interval"] = in.sample_interval;
  summary["seed"] = in.seed;
  static const char* kSpaceNames[] = {"hash", "sap", "quadtree", "simple"};
  summary["space"] = kSpaceNames[static_cast<int>(model.settings.space)];
  summary["auto_disable"] = model.settings.auto_disable;
  summary["max_contacts"] = model.settings.max_contacts;
  // The solver changes the bytes: which one stepped, and what chose it.
  summary["solver"] = {{"type", model.settings.quickstep ? "quickstep" : "step"},
                       {"iterations", model.settings.quickstep ? nlohmann::ordered_json(model.settings.iterations)
                                                               : nlohmann::ordered_json(nullptr)},
                       {"chosen_by", model.settings.solver_rule.empty() ? "scene" : model.settings.solver_rule}};
  summary["overrides"] = nlohmann::ordered_json::array();
  for (const std::string& o : in.overrides) summary["overrides"].push_back(o);
  summary["units"] = {{"time", "s"}, {"position", "m"}, {"orientation", "unit quaternion w x y z"}};
  summary["bodies"] = model.bodies.size();
  if (!model.frames.empty()) summary["frames"] = model.frames.size();  // rows of lumped URDF links
  summary["steps"] = r.steps;
  summary["samples"] = r.samples;
  summary["wall_seconds"] = r.wall_seconds;
  // Waiting for a socket peer to connect is not simulation speed.
  const double busy = r.wall_seconds - r.wait_seconds;
  summary["steps_per_second"] = busy > 0 ? static_cast<double>(r.steps) / busy : 0.0;
  // What bit-identical reruns depend on.
  summary["reproducibility"] = {{"physics", physicsVersion()},   {"ode_version", odeVersion()}, {"precision", "double"},
                                {"compiler", compilerVersion()}, {"fp_contract", "off"},        {"libc", libcVersion()},
                                {"cpu_features", cpuFeatures()}};
  if (r.physics_messages.count > 0)  // ODE's own reports (World::physicsMessages): only when there are any
    summary["physics_messages"] = {{"count", r.physics_messages.count},
                                   {"first", r.physics_messages.first},
                                   {"first_time", r.physics_messages.first_time}};
  if (r.status != RunStatus::Completed) {
    // Why it ended: what `simbob batch` and `sweep run` read from a worker's partial summary.
    summary["error"] = {{"file", r.error.loc.file},
                        {"line", r.error.loc.line},
                        {"message", r.error.message},
                        {"text", r.error.errorLine()}};
  }
  return summary;
}

}  // namespace simbob
