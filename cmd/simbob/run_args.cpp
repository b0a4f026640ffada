// The options of `simbob run` turned into what a run needs: the paths it writes, the overrides it
// applies, and what is wrong with a combination of options (beyond their syntax).
#include <cmath>
#include <filesystem>
#include <map>

#include "cli.h"
#include "commands.h"
#include "simbob/files.h"
#include "simbob/overrides.h"
#include "simbob/run.h"
#include "simbob/run_log.h"
#include "simbob/run_outputs.h"
#include "simbob/values.h"

namespace simbob::cli {

// Where the run writes: --out (default SCENE.csv), its summary and partial files, the run log
// (--log-out, or --out with .csv replaced by .log.csv) and the video.
RunOutputPaths runPaths(const RunArgs& a) {
  const std::string out = a.out.empty() ? std::filesystem::path(a.scene).stem().string() + ".csv" : a.out;
  RunOutputPaths p = defaultOutputPaths(out, !a.log.empty());
  if (!a.log_out.empty()) p.run_log = a.log_out;
  if (!a.log.empty()) {
    std::string unused;
    parseRunLogWhat(a.log, &p.run_log_what, &unused);  // checked by runArgsProblem
  }
  p.video = a.video;
  p.velocity_columns = a.columns == "pose,velocity";
  return p;
}

std::string controllerLogPath(const std::string& out) {
  return std::filesystem::path(out).replace_extension(".controller.log").string();
}

std::vector<NamedPath> runOutputs(const RunArgs& a) {
  const RunOutputPaths p = runPaths(a);
  std::vector<NamedPath> all = {{"--out", p.trajectory}};
  if (!p.summary.empty())
    all.insert(all.end(), {{"the summary", p.summary},
                           {"the partial trajectory", partialPath(p.trajectory)},
                           {"the partial summary", partialSummaryPath(p.summary)}});
  if (!p.summary.empty()) all.push_back({"the controllers' log", controllerLogPath(p.trajectory)});
  if (!a.html.empty()) all.push_back({"--html", a.html});
  if (!p.run_log.empty()) {
    all.push_back({a.log_out.empty() ? "the run log" : "--log-out", p.run_log});
    if (!isStreamOutput(p.run_log)) all.push_back({"the partial run log", partialPath(p.run_log)});
  }
  return all;
}

std::string runArgsProblem(const RunArgs& a) {
  auto range = [](const char* name, double v) -> std::string {
    if (std::isfinite(v) && v >= kMinTimeOption && v <= kMaxTimeOption) return "";
    return std::string(name) + " must be between 1e-9 and 1e9 s, got " + formatNumber(v);
  };
  std::string p = range("--duration", a.duration);
  if (p.empty() && a.dt != 0) p = range("--dt", a.dt);
  if (p.empty()) p = range("--sample-interval", a.sample_interval);
  if (p.empty() && a.out == "-" && a.json) p = "--out - and --json would both write to stdout; drop one";
  if (p.empty() && !(a.peer_timeout >= 0.001 && a.peer_timeout <= 86400))
    p = "--peer-timeout must be between 0.001 and 86400 s, got " + formatNumber(a.peer_timeout);
  if (p.empty() && (a.port_offset < -65535 || a.port_offset > 65535))
    p = "--port-offset must be between -65535 and 65535, got " + std::to_string(a.port_offset);
  if (p.empty() && !a.log_out.empty() && a.log.empty()) p = "--log-out needs --log (what to log)";
  if (p.empty() && !a.log.empty()) {
    RunLogWhat what;
    if (!parseRunLogWhat(a.log, &what, &p)) return p;
    if (a.log_out.empty() && !a.out.empty() && isStreamOutput(a.out))
      p = "--log with --out " + a.out + " needs --log-out FILE";
    else if (a.log_out == "-" && (a.out == "-" || a.json))
      p = std::string("--log-out - and ") + (a.json ? "--json" : "--out -") + " would both write to stdout; drop one";
  }
  return p;
}

int runOverrides(const RunArgs& a, const Common& common, std::vector<Override>* out) {
  auto shorthand = [&](const std::string& option, const std::string& param, const std::string& value) {
    Override o;
    o.key = "SceneSettings";
    o.param = param;
    o.value = value;
    o.text = o.key + "." + param + "=" + value;
    o.place = option;
    out->push_back(std::move(o));
  };
  static const std::map<std::string, std::string> kSpaces = {
      {"hash", "Hash"}, {"sap", "SweepAndPrune"}, {"quadtree", "QuadTree"}, {"simple", "Simple"}};
  if (auto it = kSpaces.find(a.space); it != kSpaces.end()) shorthand("--space " + a.space, "Space", it->second);
  if (a.auto_disable) shorthand("--auto-disable", "AutoDisable", "True");
  if (a.max_contacts > 0)
    shorthand("--max-contacts " + std::to_string(a.max_contacts), "MaxContacts", std::to_string(a.max_contacts));
  return sceneOverrides(common, a.scene, a.sets, out);
}

}  // namespace simbob::cli
