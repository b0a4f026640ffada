// simbob sweep: plan a parameter sweep into a manifest, run its cases (one per Slurm array
// task, or all on local workers), gather their results, write Slurm scripts (docs/sweeps.md).
#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "sweep_cli.h"
#include "commands.h"
#include "workers.h"
#include "simbob/tool/csv.h"
#include "simbob/tool/files.h"
#include "simbob/tool/sweep_plan.h"
#include "simbob/trajectory.h"
#include "simbob/values.h"

namespace simbob::cli {

namespace sweep {

namespace fs = std::filesystem;

bool readInput(const std::string& path, const char* what, std::string* text, int* code) {
  std::string reason;
  bool too_large = false;
  if (!readFile(path, kMaxManifestBytes, text, &reason, true, &too_large)) {
    g_log.error({too_large ? ErrorKind::InvalidInput : ErrorKind::MissingInput,
                 {path, 0},
                 std::string("cannot read ") + what + ": " + reason});
    *code = too_large ? kExitDataErr : kExitNoInput;
    return false;
  }
  return true;
}

bool readManifest(const std::string& path, std::string* text, std::vector<SweepCase>* cases, int* code) {
  if (!readInput(path, "manifest", text, code)) return false;
  Error err;
  if (!parseManifest(*text, path, cases, &err)) {
    g_log.error(err);
    *code = kExitDataErr;
    return false;
  }
  return true;
}

}  // namespace sweep

namespace {

using namespace sweep;
namespace fs = std::filesystem;

// ---- plan ----

int sweepPlan(const SweepArgs& a, const Common& common) {
  std::string text;
  int code = 0;
  if (!readInput(a.input, "sweep description", &text, &code)) return code;
  std::string scene;
  Error err;
  if (!sweepScene(text, a.input, &scene, &err)) {
    g_log.error(err);
    return kExitDataErr;
  }
  // The scene is relative to the description; the manifest names it relative to itself.
  fs::path scene_abs = fs::path(scene).is_absolute() ? fs::path(scene) : fs::path(a.input).parent_path() / scene;
  const std::string scene_path = scene_abs.lexically_normal().string();
  const fs::path man_dir = fs::path(absolutePath(a.out)).parent_path();
  std::string rel = fs::path(absolutePath(scene_path)).lexically_relative(man_dir).string();
  // A path that climbs out of the manifest's folder is written absolute: plainer to read.
  if (rel.empty() || rel.rfind("..", 0) == 0) rel = absolutePath(scene_path);
  std::vector<SweepCase> cases;
  if (!planSweep(text, a.input, rel, &cases, &err)) {
    g_log.error(err);
    return kExitDataErr;
  }
  // Every case's overrides are checked against the scene now, not in the thousandth array task.
  {
    LoadReport loaded;
    Model model;
    if (!loadAndCompile(scene_path, *common.registry, &model, &loaded, &code, false, false, {})) return code;
    std::vector<std::string> keys;
    for (const BodyDef& b : model.bodies) keys.push_back(b.key);
    for (const SweepMetric& m : cases.front().metrics)
      if (std::find(keys.begin(), keys.end(), m.body) == keys.end()) {
        std::string near = didYouMean(m.body, keys);
        g_log.error({ErrorKind::InvalidInput,
                     {a.input, 0},
                     "metric '" + m.name + "': no mobile body '" + quoteInput(m.body) + "' in " + scene_path +
                         (near.empty() ? "" : " (did you mean '" + near + "'?)")});
        return kExitDataErr;
      }
  }
  std::map<std::string, bool> checked;
  for (const SweepCase& c : cases)
    for (const std::string& s : c.set) {
      if (checked.count(s)) continue;
      checked[s] = true;
      std::vector<Override> ov;
      Override o;
      std::string perr;
      if (!parseOverride(s, &o, &perr)) {
        g_log.error({ErrorKind::InvalidInput, {a.input, 0}, "case " + std::to_string(c.index) + ": " + perr});
        return kExitDataErr;
      }
      o.place = a.input + ": case " + std::to_string(c.index) + ": " + s;
      ov.push_back(o);
      LoadReport loaded;
      Model model;
      if (!loadAndCompile(scene_path, *common.registry, &model, &loaded, &code, false, false, {}, ov)) return code;
    }
  std::string out;
  for (const SweepCase& c : cases) out += manifestLine(c) + "\n";
  if (int c = checkOutputs({{"-o", a.out}}, {{"the sweep description", a.input}, {"the scene", scene_path}})) return c;
  if (!writeFileAtomically(a.out, out, &err)) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  g_log.info("wrote " + a.out + ": " + std::to_string(cases.size()) + " cases");
  return kExitOk;
}

}  // namespace

CLI::App* addSweepCommands(CLI::App& app, SweepArgs& s, Common& common) {
  CLI::App* sweep = app.add_subcommand("sweep", "Parameter sweeps: plan, run (local or Slurm array), gather, sbatch");
  sweep->require_subcommand(1);
  CLI::App* plan = sweep->add_subcommand("plan", "Expand a sweep description into a case manifest (JSON lines)");
  plan->add_option("sweep", s.input, "Sweep description (JSON)")->required();
  plan->add_option("-o,--out", s.out, "Manifest to write")->required();
  addCommon(plan, common);
  CLI::App* run =
      sweep->add_subcommand("run", "Run one case (--case, SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX) or all (-j)");
  run->add_option("manifest", s.input, "Case manifest")->required();
  run->add_option("-o,--out,--out-dir", s.out, "Output folder (case-NNNN/ per case)")->required();
  run->add_option("--case", s.case_index, "Case index (default: from the environment)")
      ->check(CLI::Range(0, 999999999));
  run->add_option("-j,--jobs", s.jobs, "Run every case here on N worker processes")->check(CLI::Range(1, 1024));
  run->add_flag("--force", s.force, "Redo cases that are done already");
  run->add_flag("--html", s.case_pages, "Also write each case's replay page, case-NNNN/view.html (simbob view)");
  addCommon(run, common);
  CLI::App* gather = sweep->add_subcommand("gather", "Merge the case results into one CSV table");
  gather->add_option("out", s.input, "Output folder of the sweep")->required();
  gather->add_option("-o,--out", s.out, "Table to write (default OUT/results.csv)");
  gather->add_flag("--retry", s.retry, "Print the cases to resubmit as --array=3,17,42");
  gather->add_option("--html", s.html, "Also write a gallery page: the table, a plot, each case's replay page");
  gather->add_option("--junit", s.junit, "Also write a JUnit XML report, one test case per sweep case (docs/ci.md)");
  addCommon(gather, common);
  CLI::App* sbatch = sweep->add_subcommand("sbatch", "Write Slurm scripts: a case array and a dependent gather job");
  sbatch->add_option("manifest", s.input, "Case manifest")->required();
  sbatch->add_option("-o,--out,--out-dir", s.out, "Output folder of the sweep (the scripts go there too)")->required();
  sbatch->add_option("--max-parallel", s.max_parallel, "At most K array tasks at once (%K)")
      ->check(CLI::Range(1, 1000000));
  sbatch->add_option("--partition", s.partition, "Slurm partition");
  addCommon(sbatch, common);
  s.plan = plan;
  s.run = run;
  s.gather = gather;
  s.sbatch = sbatch;
  return sweep;
}

int cmdSweep(const SweepArgs& a, const Common& common) {
  if (*a.plan) return sweepPlan(a, common);
  if (*a.run) return sweep::sweepRun(a, common);
  if (*a.gather) return a.html.empty() ? sweep::sweepGather(a) : galleryAfterGather(a, common, sweep::sweepGather(a));
  return sweep::sweepSbatch(a, common);
}

}  // namespace simbob::cli
