// The options of `simbob run` that CLI11 does not bind straight to RunOptions: the run log's
// list, the columns, the shorthand overrides, the recording's view, the global settings; and what
// is wrong with a combination of options (beyond their syntax).
#include <map>

#include "cli.h"
#include "commands.h"
#include "simbob/tool/document_ini.h"
#include "simbob/tool/files.h"
#include "simbob/overrides.h"

namespace simbob::cli {

namespace {

// The run log's list and the columns, which RunOptions holds parsed.
RunOptions withParsedLists(const RunArgs& a) {
  RunOptions o = a.run;
  std::string unused;
  if (!a.log.empty()) parseRunLogWhat(a.log, &o.log, &unused);  // checked by runArgsProblem
  o.velocity_columns = a.columns == "pose,velocity";
  o.warnings = !a.batch_child;
  return o;
}

}  // namespace

std::vector<NamedPath> runOutputs(const RunArgs& a) { return runOutputFiles(withParsedLists(a)); }

std::string runArgsProblem(const RunArgs& a) {
  std::string p = runOptionsProblem(a.run);
  const std::string& out = a.run.out;
  if (p.empty() && out == "-" && a.json) p = "--out - and --json would both write to stdout; drop one";
  if (p.empty() && !a.run.log_out.empty() && a.log.empty()) p = "--log-out needs --log (what to log)";
  if (p.empty() && !a.log.empty()) {
    RunLogWhat what;
    if (!parseRunLogWhat(a.log, &what, &p)) return p;
    if (a.run.log_out.empty() && !out.empty() && isStreamOutput(out))
      p = "--log with --out " + out + " needs --log-out FILE";
    else if (a.run.log_out == "-" && (out == "-" || a.json))
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
  return sceneOverrides(common, a.run.scene, a.sets, out);
}

int completeRunOptions(RunArgs& a, const Common& common) {
  RunOptions& o = a.run;
  o = withParsedLists(a);
  if (int c = runOverrides(a, common, &o.simulation.overrides)) return c;
  if (!o.record.empty() || !o.video.empty()) {  // the view options matter only to a recording
    if (int c = renderOptions(a.view, common, &o.render)) return c;
    o.fps = a.view.fps;
  }
  o.simulation.texture_folder = common.texture_folder;
  o.simulation.no_controllers = common.no_controllers;
  o.simulation.stop = &g_stop;
  o.inputs = {{"--settings", common.settings}};
  if (common.document_ini) o.inputs.push_back({"the DocumentIni", documentIniPath(o.scene)});
  o.outputs = {{"--log-file", g_log.path}};
  return 0;
}

}  // namespace simbob::cli
