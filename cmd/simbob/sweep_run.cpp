// simbob sweep run: one case (--case, a Slurm array task) or every case on local workers.
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

namespace simbob::cli::sweep {

namespace fs = std::filesystem;

namespace {

std::string caseStatus(const fs::path& dir) {
  std::string text;
  if (!readFile((dir / "case.json").string(), 1 << 20, &text, nullptr, true)) return "";
  try {
    return nlohmann::json::parse(text).value("status", "");
  } catch (const std::exception&) {
    return "";
  }
}

int caseIndex(const SweepArgs& a, int* index) {
  if (a.case_index >= 0) {
    *index = a.case_index;
    return kExitOk;
  }
  for (const char* var : {"SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"}) {
    const char* v = std::getenv(var);
    if (!v) continue;
    auto n = parseNumber(v);
    if (!n || *n < 0 || *n > 1e9 || std::floor(*n) != *n) {
      g_log.error({ErrorKind::InvalidInput, {}, std::string(var) + "='" + quoteInput(v) + "' is not a case index"});
      return kExitUsage;
    }
    *index = static_cast<int>(*n);
    return kExitOk;
  }
  g_log.error({ErrorKind::InvalidInput,
               {},
               "which case? give --case I, or run as a Slurm array task (SLURM_ARRAY_TASK_ID) or a Kubernetes "
               "Indexed Job (JOB_COMPLETION_INDEX); -j N runs every case here"});
  return kExitUsage;
}

// The scene of case c: relative to the manifest's folder.
fs::path caseScene(const SweepCase& c, const std::string& manifest) {
  fs::path scene = c.scene;
  if (scene.is_relative()) scene = fs::path(manifest).parent_path() / scene;
  return scene.lexically_normal();
}

// The `simbob run` of case c, writing into tmp.
std::vector<std::string> caseRunArgs(const SweepCase& c, const std::string& manifest, const fs::path& tmp,
                                     const Common& common) {
  std::vector<std::string> args = {"simbob",
                                   "run",
                                   caseScene(c, manifest).string(),
                                   "--duration",
                                   formatNumber(c.duration),
                                   "--sample-interval",
                                   formatNumber(c.sample_interval),
                                   "--seed",
                                   std::to_string(c.seed),
                                   "--out",
                                   (tmp / "trajectory.csv").string(),
                                   "--refusal-summary"};
  if (c.dt > 0) {
    args.emplace_back("--dt");
    args.push_back(formatNumber(c.dt));
  }
  for (const std::string& set : c.set) {
    args.emplace_back("--set");
    args.push_back(set);
  }
  for (std::string& o : workerOptions(common)) args.push_back(std::move(o));
  return args;
}

// A new case is one rename; a redone one swaps with the old directory in one step. 0, or 73.
int publishCase(const fs::path& tmp, const fs::path& final_dir) {
  std::error_code ec;
  if (::rename(tmp.c_str(), final_dir.c_str()) != 0) {
    if (::renameat2(AT_FDCWD, tmp.c_str(), AT_FDCWD, final_dir.c_str(), RENAME_EXCHANGE) != 0) {
      g_log.error(
          {ErrorKind::CannotCreate, {final_dir.string(), 0}, std::string("cannot publish: ") + std::strerror(errno)});
      fs::remove_all(tmp, ec);
      return kExitCantCreate;
    }
    fs::remove_all(tmp, ec);  // now the old case
  }
  return kExitOk;
}

int runOneCase(const SweepArgs& a, const SweepCase& c, const std::string& manifest, const Common& common) {
  const fs::path final_dir = fs::path(a.out) / caseDirName(c.index);
  std::error_code ec;
  if (!a.force && fs::exists(final_dir, ec) && caseStatus(final_dir) == "ok") {
    g_log.info("case " + std::to_string(c.index) + ": done already (" + final_dir.string() +
               "); skipped (--force redoes it)");
    return kExitOk;
  }
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  // Built beside its final name and renamed: the case directory is complete or absent.
  const fs::path tmp = fs::path(a.out) / ("." + caseDirName(c.index) + ".tmp." + host + "." + std::to_string(getpid()));
  fs::remove_all(tmp, ec);
  if (!fs::create_directory(tmp, ec)) {
    g_log.error({ErrorKind::CannotCreate, {tmp.string(), 0}, "cannot create: " + ec.message()});
    return kExitCantCreate;
  }
  const std::vector<std::string> args = caseRunArgs(c, manifest, tmp, common);
  catchStopSignals();
  const auto t0 = std::chrono::steady_clock::now();
  const auto since = fs::file_time_type::clock::now();
  pid_t pid = -1;
  int wstatus = 0;
  runWorkerPool(
      1, 1, [&](size_t) { return pid = spawnSelf(args, (tmp / "log").string()); },
      [&](size_t, int status) { wstatus = status; });
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (g_stop) {
    // An interrupted case (pre-emption, scancel) leaves nothing: the task reruns it.
    fs::remove_all(tmp, ec);
    g_log.error({ErrorKind::Diverged, {}, "case " + std::to_string(c.index) + ": interrupted"});
    return stopExitCode();
  }
  const WorkerOutcome outcome = workerOutcome(wstatus);
  const int run_exit = pid < 0 ? kExitSoftware : outcome.exit_code >= 0 ? outcome.exit_code : 128 + WTERMSIG(wstatus);
  std::string error;
  if (run_exit != kExitOk) {
    error = workerError((tmp / "trajectory.csv").string(), (tmp / "log").string(), since);
    if (error.empty()) error = "simbob run exited with status " + std::to_string(run_exit);
  }
  if (run_exit == kExitOk) fs::rename(tmp / "trajectory.json", tmp / "summary.json", ec);
  nlohmann::ordered_json j = sweepCaseRecord(c, tmp.string(), run_exit, error, wall);
  const fs::path scene = caseScene(c, manifest);
  j["scene"] = fs::absolute(scene, ec).lexically_normal().string();  // for gather --html, run from anywhere
  if (int code =
          j["status"] == "ok" && a.case_pages ? sweepCasePage(c, scene.string(), tmp.string(), common) : kExitOk) {
    fs::remove_all(tmp, ec);
    return code;
  }
  Error err;
  if (!writeFileAtomically((tmp / "case.json").string(), jsonText(j), &err)) {
    g_log.error(err);
    fs::remove_all(tmp, ec);
    return exitCodeFor(err.kind);
  }
  if (int code = publishCase(tmp, final_dir)) return code;
  const std::string status = j["status"].get<std::string>();
  if (status == "ok")
    g_log.info("case " + std::to_string(c.index) + ": ok (" + fixedDecimals(wall, 2) + " s) -> " + final_dir.string());
  else
    g_log.error({ErrorKind::Diverged,
                 {},
                 "case " + std::to_string(c.index) + ": " + status + ": " + j.value("error", std::string())});
  return j["exit_code"].get<int>();
}

int runAllCases(const SweepArgs& a, const std::vector<SweepCase>& cases, const Common& common) {
  catchStopSignals();
  std::vector<int> todo;
  std::error_code ec;
  for (const SweepCase& c : cases)
    if (a.force || caseStatus(fs::path(a.out) / caseDirName(c.index)) != "ok") todo.push_back(c.index);
  const size_t skipped = cases.size() - todo.size();
  size_t done = 0, running = 0, failed = 0;
  std::vector<std::chrono::steady_clock::time_point> started(todo.size());
  const bool tty = isatty(2) != 0;
  runWorkerPool(
      todo.size(), a.jobs,
      [&](size_t k) {
        std::vector<std::string> args = {"simbob", "sweep", "run",    a.input, "--case", std::to_string(todo[k]),
                                         "-o",     a.out,   "--quiet"};
        if (a.force) args.emplace_back("--force");
        if (a.case_pages) args.emplace_back("--html");
        for (std::string& o : workerOptions(common)) args.push_back(std::move(o));
        const pid_t pid = spawnSelf(args, "/dev/null");
        if (pid < 0) {
          ++done;
          ++failed;
        } else {
          started[k] = std::chrono::steady_clock::now();
          ++running;
        }
        return pid;
      },
      [&](size_t k, int wstatus) {
        const int i = todo[k];
        --running;
        ++done;
        const bool ok = workerOutcome(wstatus).status == "ok";
        if (!ok) ++failed;
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started[k]).count();
        const std::string status = caseStatus(fs::path(a.out) / caseDirName(i));
        char line[256];
        std::snprintf(line, sizeof line, "[%zu/%zu] case %d %s %.2f s  (%zu failed, %zu running)", done, todo.size(), i,
                      ok               ? "ok"
                      : status.empty() ? "failed"
                                       : status.c_str(),
                      wall, failed, running);
        if (g_log.level != Level::Quiet) std::fprintf(stderr, tty ? "\r%s\033[K" : "%s\n", line);
      });
  if (tty && g_log.level != Level::Quiet && !todo.empty()) std::fprintf(stderr, "\n");
  if (g_stop) return stopExitCode();
  g_log.info(std::to_string(todo.size() - failed) + " of " + std::to_string(todo.size()) + " cases ok" +
             (skipped ? ", " + std::to_string(skipped) + " done already" : "") + "; gather with: simbob sweep gather " +
             a.out);
  return failed == 0 ? kExitOk : kExitResultWrong;
}

}  // namespace

// OUT/manifest.jsonl is the manifest the cases in OUT came from: written by the first task,
// checked by every other, so two sweeps never mix in one folder.
int claimOutDir(const std::string& out, const std::string& manifest_text) {
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out)) {
    g_log.error(
        {ErrorKind::CannotCreate, {out, 0}, "cannot create output folder: " + (ec ? ec.message() : "not a folder")});
    return kExitCantCreate;
  }
  const std::string copy = (fs::path(out) / "manifest.jsonl").string();
  std::string have;
  if (readFile(copy, kMaxManifestBytes, &have, nullptr, true)) {
    if (have == manifest_text) return kExitOk;
    g_log.error({ErrorKind::InvalidInput,
                 {copy, 0},
                 "this folder holds the cases of another manifest; give another -o or remove it"});
    return kExitDataErr;
  }
  Error err;
  if (!writeFileAtomically(copy, manifest_text, &err)) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  return kExitOk;
}

int sweepRun(const SweepArgs& a, const Common& common) {
  std::string text;
  std::vector<SweepCase> cases;
  int code = 0;
  if (!readManifest(a.input, &text, &cases, &code)) return code;
  if (int c = claimOutDir(a.out, text)) return c;
  if (a.jobs > 0) return runAllCases(a, cases, common);
  int index = -1;
  if (int c = caseIndex(a, &index)) return c;
  if (index >= static_cast<int>(cases.size())) {
    g_log.error({ErrorKind::InvalidInput,
                 {a.input, 0},
                 "no case " + std::to_string(index) + " (the manifest has cases 0 to " +
                     std::to_string(cases.size() - 1) + ")"});
    return kExitUsage;
  }
  return runOneCase(a, cases[static_cast<size_t>(index)], a.input, common);
}

}  // namespace simbob::cli::sweep
