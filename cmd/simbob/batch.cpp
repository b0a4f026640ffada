// simbob batch: many scenes on N worker processes (workers.h), each a `simbob run` of its own:
// the runs go in parallel on the cores, and a crashing scene takes down only its worker.
#include <fcntl.h>
#include <glob.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <functional>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <nlohmann/json.hpp>
#include <sstream>

#include <CLI/CLI.hpp>

#include "batch.h"
#include "cli.h"
#include "commands.h"
#include "workers.h"
#include "simbob/tool/comparison.h"
#include "simbob/tool/files.h"
#include "simbob/loop.h"
#include "simbob/trajectory.h"
#include "simbob/values.h"

namespace simbob::cli {

namespace {

using batch::Job;
namespace fs = std::filesystem;

pid_t startWorker(const Job& j, const BatchArgs& a, const Common& common) {
  std::vector<std::string> args = {"simbob", "run", j.scene, "--quiet", "--out", j.out};
  args.emplace_back("--duration");
  args.push_back(formatNumber(a.duration));
  if (a.dt > 0) {
    args.emplace_back("--dt");
    args.push_back(formatNumber(a.dt));
  }
  args.emplace_back("--sample-interval");
  args.push_back(formatNumber(a.sample_interval));
  args.emplace_back("--batch-child");
  args.emplace_back("--refusal-summary");
  if (a.html) args.insert(args.end(), {"--html", fs::path(j.out).replace_extension(".html").string()});
  for (std::string& o : workerOptions(common)) args.push_back(std::move(o));
  // Manifest options come last: CLI11 keeps the last value of a repeated option.
  args.insert(args.end(), j.args.begin(), j.args.end());
  return spawnSelf(args, j.log);
}

void finish(Job& j, int wstatus, const BatchArgs& a) {
  j.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - j.started).count();
  const WorkerOutcome o = workerOutcome(wstatus);
  j.status = o.status;
  j.exit_code = o.exit_code;
  j.error = o.error;
  if (j.timed_out) {
    std::error_code ec;
    const std::string partial = partialPath(j.out);
    j.status = "timed out";
    j.error = "the run took longer than --timeout " + formatNumber(a.timeout) + " s (wall clock) and was stopped" +
              (fs::exists(partial, ec) ? "; its partial trajectory: " + partial : "");
    return;
  }
  if (o.exit_code < 0) return;
  if (j.exit_code != kExitOk) j.error = workerError(j.out, j.log, j.since);
  if (a.golden.empty() || j.status != "ok") return;
  batch::compareWithGolden(j, a);
}

// A scene that did not run, or whose comparison did not pass (a missing golden file too, unless
// --allow-missing-golden): what the exit status, the table and the reports count as failed.
bool jobFailed(const Job& j, const BatchArgs& a) {
  if (j.status != "ok") return true;
  if (j.golden_status == "no-golden") return !a.allow_missing_golden;
  return !j.golden_status.empty() && j.golden_status != "pass";
}

// Text from the input (scene paths, error lines) as the terminal may show it: control bytes as \xNN.
std::string shown(const std::string& text) { return quoteInput(text, 8192); }

// --timeout: a running worker past the limit gets SIGTERM (it stops as on a signal, keeping its
// partial trajectory), and SIGKILL if it is still there 10 s later. Called by the pool between
// reaps, so every pid here is still its worker's.
void stopLateWorkers(std::vector<Job>& jobs, const BatchArgs& a) {
  constexpr double kGrace = 10;
  const auto now = std::chrono::steady_clock::now();
  for (Job& j : jobs) {
    if (j.pid <= 0 || j.status != "not started") continue;  // not started yet, or finished
    const double took = std::chrono::duration<double>(now - j.started).count();
    if (!j.timed_out && took > a.timeout) {
      kill(j.pid, SIGTERM);
      j.timed_out = true;
    } else if (j.timed_out && took > a.timeout + kGrace) {
      kill(j.pid, SIGKILL);
    }
  }
}

// The batch's table (or --json) on stdout, and --report FILE. 0, or the exit status (reported).
int writeReport(const std::vector<Job>& jobs, const BatchArgs& a, int workers, double wall) {
  size_t failed = 0;
  for (const auto& j : jobs) failed += jobFailed(j, a) ? 1 : 0;
  nlohmann::ordered_json rep;
  rep["scenes"] = jobs.size();
  rep["failed"] = failed;
  rep["workers"] = workers;
  rep["wall_seconds"] = wall;
  rep["golden"] = a.golden;
  rep["results"] = nlohmann::json::array();
  std::string table =
      "\nscene                                    status       wall s   golden      max pos err  max rot err\n";
  for (const auto& j : jobs) {
    nlohmann::ordered_json r;
    r["scene"] = j.scene;
    r["status"] = j.status;
    r["exit_code"] = j.exit_code;
    r["out"] = j.out;
    r["log"] = j.log;
    r["wall_seconds"] = j.wall;
    if (!j.golden_status.empty()) {
      r["golden"] = j.golden_status;
      r["max_pos_err"] = j.max_pos;
      r["max_rot_err"] = j.max_rot;
    }
    if (!j.error.empty()) r["error"] = j.error;
    std::error_code pec;
    if (j.status != "ok" && fs::exists(partialPath(j.out), pec)) r["partial"] = partialPath(j.out);
    rep["results"].push_back(r);
    char buf[512];
    std::snprintf(buf, sizeof buf, "%-40s %-12s %7.2f   %-11s %-12s %s\n", shown(j.scene).c_str(), j.status.c_str(),
                  j.wall, j.golden_status.empty() ? "-" : j.golden_status.c_str(),
                  j.golden_status.empty() ? "-" : formatApprox(j.max_pos).c_str(),
                  j.golden_status.empty() ? "-" : formatApprox(j.max_rot).c_str());
    table += buf;
  }
  const std::string pool =
      " (" + countOf(static_cast<size_t>(workers), "worker", "workers") + ", " + fixedDecimals(wall, 2) + " s)\n";
  if (a.bless) {
    // What --bless needs is that the scenes ran; which golden files change is listed below.
    size_t ran = 0;
    for (const auto& j : jobs) ran += j.status == "ok" ? 1 : 0;
    table +=
        "\n" + std::to_string(ran) + " of " + std::to_string(jobs.size()) + " scenes ran to the end (--bless)" + pool;
  } else {
    table += "\n" + std::to_string(jobs.size() - failed) + " of " + std::to_string(jobs.size()) + " scenes ok" + pool;
  }
  if (a.json)
    std::fputs(jsonText(rep).c_str(), stdout);
  else
    std::fputs(table.c_str(), stdout);
  if (!a.report.empty()) {
    Error err;
    std::string text = endsWith(a.report, ".json") ? jsonText(rep) : table;
    if (!writeFileAtomically(a.report, text, &err)) {
      g_log.error(err);
      return exitCodeFor(err.kind);
    }
  }
  return 0;
}

}  // namespace

int cmdBatch(const BatchArgs& a, const Common& common) {
  if (!checkTimeOption("--duration", a.duration) || (a.dt != 0 && !checkTimeOption("--dt", a.dt)) ||
      !checkTimeOption("--sample-interval", a.sample_interval))
    return kExitUsage;
  if (a.timeout != 0 && !checkTimeOption("--timeout", a.timeout)) return kExitUsage;
  if (int c = batch::checkCiOptions(a)) return c;
  if (!a.bless_from.empty()) return batch::blessFrom(a);
  std::vector<Job> jobs;
  if (int c = batch::readJobs(a, &jobs)) return c;
  if (int c = batch::assignOutputs(a, common, &jobs)) return c;

  int workers = a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
  catchStopSignals();
  auto t0 = std::chrono::steady_clock::now();
  size_t done = 0;
  runWorkerPool(
      jobs.size(), workers,
      [&](size_t i) {
        Job& j = jobs[i];
        j.started = std::chrono::steady_clock::now();
        j.since = fs::file_time_type::clock::now();
        j.pid = startWorker(j, a, common);
        if (j.pid < 0) {
          j.status = "failed";
          j.error = std::string("cannot fork: ") + std::strerror(errno);
          ++done;
        }
        return j.pid;
      },
      [&](size_t i, int wstatus) {
        Job& j = jobs[i];
        ++done;
        finish(j, wstatus, a);
        std::string line = "[" + std::to_string(done) + "/" + std::to_string(jobs.size()) + "] " + j.status + "  " +
                           shown(j.scene) + "  " + fixedDecimals(j.wall, 2) + " s";
        if (!j.golden_status.empty()) line += "  golden: " + j.golden_status;
        if (!j.error.empty()) line += "  -- " + shown(j.error);
        if (g_log.level == Level::Quiet && !jobFailed(j, a)) return;  // -q: only the scenes that failed
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
      },
      a.timeout > 0 ? std::function<void()>([&] { stopLateWorkers(jobs, a); }) : std::function<void()>());
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  size_t failed = 0;
  for (const auto& j : jobs) failed += jobFailed(j, a) ? 1 : 0;
  if (int c = writeReport(jobs, a, workers, wall)) return c;
  if (int c = batch::writeCiOutputs(jobs, a, common, wall)) return c;
  if (g_stop) return stopExitCode();
  if (a.bless) return batch::blessGoldens(jobs, a);
  return failed == 0 ? kExitOk : kExitResultWrong;
}

}  // namespace simbob::cli

namespace simbob::cli::batch {

namespace fs = std::filesystem;

// Compares a worker's trajectory with the golden file of the same name (--golden DIR).
void compareWithGolden(Job& j, const BatchArgs& a) {
  std::string golden = (fs::path(a.golden) / fs::path(j.out).filename()).string();
  j.golden_path = golden;
  if (!fs::exists(golden)) {
    j.golden_status = "no-golden";
    j.error = "no golden file " + golden;
    return;
  }
  Trajectory actual, gold;
  Error err;
  if (!readTrajectory(j.out, &actual, &err) || !readTrajectory(golden, &gold, &err)) {
    j.golden_status = "unreadable";
    j.error = err.str();
    return;
  }
  CompareOptions opts;
  opts.tol_pos = a.tol_pos;
  opts.tol_rot = a.tol_rot;
  CompareResult r = compareTrajectories(actual, gold, opts);
  j.comparison = r;
  for (const auto& b : r.bodies) {
    j.max_pos = std::max(j.max_pos, b.max_pos_err);
    j.max_rot = std::max(j.max_rot, b.max_rot_err);
  }
  j.golden_status = r.pass ? "pass" : "mismatch";
  if (!r.pass) {
    std::string report = fs::path(j.out).replace_extension(".compare.txt").string();
    Error werr;
    writeFileAtomically(report, "actual: " + j.out + "\ngolden: " + golden + "\n" + r.text(), &werr);
    if (r.first_divergence)
      j.divergence = "first divergence at t=" + formatNumber(r.first_divergence->time) + " s, body '" +
                     r.first_divergence->body + "' (" + formatApprox(r.first_divergence->pos_err) + " m, " +
                     formatApprox(r.first_divergence->rot_err) + " rad)";
    else
      j.divergence = "bodies or sample times differ";
    j.error = j.divergence + "; report: " + report;
  }
}

}  // namespace simbob::cli::batch
