// simbob batch: many scenes on N worker processes (workers.h), each a `simbob run` of its own:
// the runs go in parallel on the cores, and a crashing scene takes down only its worker.
#include <fcntl.h>
#include <glob.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <nlohmann/json.hpp>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli.h"
#include "commands.h"
#include "workers.h"
#include "simbob/compare.h"
#include "simbob/files.h"
#include "simbob/run.h"
#include "simbob/trajectory.h"
#include "simbob/values.h"

namespace simbob::cli {

namespace {

namespace fs = std::filesystem;

struct Job {
  std::string scene;
  std::vector<std::string> args;  // extra `simbob run` arguments from the manifest
  std::string out;
  std::string log;
  SourceLoc loc;  // manifest line, if any
  // Results.
  pid_t pid = -1;
  std::string status = "not started";  // ok, failed, diverged, crashed, interrupted
  int exit_code = -1;
  double wall = 0;
  std::chrono::steady_clock::time_point started;
  std::string error;          // first error line of the worker
  std::string golden_status;  // pass, mismatch, no-golden, unreadable ("" without --golden)
  double max_pos = 0, max_rot = 0;
  std::string divergence;
};

std::vector<std::string> splitArgs(const std::string& line, std::string* err) {
  std::vector<std::string> out;
  std::string cur;
  bool in_quotes = false, have = false;
  for (char c : line) {
    if (c == '"') {
      in_quotes = !in_quotes;
      have = true;
    } else if (!in_quotes && (c == ' ' || c == '\t' || c == '\r')) {
      if (have) out.push_back(cur);
      cur.clear();
      have = false;
    } else {
      cur += c;
      have = true;
    }
  }
  if (in_quotes) *err = "unterminated quote";
  if (have) out.push_back(cur);
  return out;
}

std::vector<std::string> expandGlob(const std::string& pattern) {
  glob_t g{};
  std::vector<std::string> out;
  if (glob(pattern.c_str(), 0, nullptr, &g) == 0)
    for (size_t i = 0; i < g.gl_pathc; ++i) out.emplace_back(g.gl_pathv[i]);  // glob sorts
  globfree(&g);
  if (out.empty()) out.push_back(pattern);  // a plain path: let the worker report it if missing
  return out;
}

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

pid_t startWorker(const Job& j, const BatchArgs& a) {
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
  if (o.exit_code < 0) return;
  if (j.exit_code != kExitOk) j.error = firstErrorLine(j.log);
  if (a.golden.empty() || j.status != "ok") return;
  std::string golden = (fs::path(a.golden) / fs::path(j.out).filename()).string();
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

// What `simbob run` would refuse in a manifest line (its options after the batch-wide ones).
std::string manifestLineProblem(const std::vector<std::string>& words, const BatchArgs& a) {
  std::vector<std::string> args = {words[0], "--duration", formatNumber(a.duration), "--sample-interval",
                                   formatNumber(a.sample_interval)};
  if (a.dt > 0) {
    args.emplace_back("--dt");
    args.push_back(formatNumber(a.dt));
  }
  args.insert(args.end(), words.begin() + 1, words.end());
  CLI::App app{"run"};
  RunArgs ra;
  Common common;
  addRunOptions(&app, ra, common);
  try {
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    return std::string("run options: ") + e.what();
  }
  if (app.count("--out") > 0 && ra.out.empty()) return "--out needs a file name, got \"\"";
  return runArgsProblem(ra);
}

// An output of the batch must not be any input (a scene, the manifest, a golden file), nor
// another output. Inputs are compared by device and inode, outputs by their resolved place.
int checkBatchFiles(const std::vector<Job>& jobs, const BatchArgs& a, const Common& common) {
  std::map<std::pair<dev_t, ino_t>, std::string> inputs;
  auto addInput = [&](const std::string& what, const std::string& path) {
    struct stat st {};
    if (!path.empty() && ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode))
      inputs.emplace(std::make_pair(st.st_dev, st.st_ino), what + " " + path);
  };
  addInput("the manifest", a.manifest);
  addInput("--settings", common.settings);
  for (const Job& j : jobs) {
    addInput("the scene", j.scene);
    if (!a.golden.empty()) addInput("the golden file", (fs::path(a.golden) / fs::path(j.out).filename()).string());
  }
  std::vector<NamedPath> outputs = {{"--report", a.report}, {"--log-file", g_log.path}};
  for (const Job& j : jobs) {
    outputs.push_back({"the trajectory", j.out});
    outputs.push_back({"the worker log", j.log});
    outputs.push_back({"the summary", fs::path(j.out).replace_extension(".json").string()});
    if (!a.golden.empty())
      outputs.push_back({"the comparison report", fs::path(j.out).replace_extension(".compare.txt").string()});
  }
  std::map<std::string, std::string> places;
  for (const NamedPath& o : outputs) {
    if (o.path.empty() || isStreamOutput(o.path)) continue;
    struct stat st {};
    if (::stat(o.path.c_str(), &st) == 0) {
      auto it = inputs.find({st.st_dev, st.st_ino});
      if (it != inputs.end()) {
        g_log.error({ErrorKind::InvalidInput,
                     {},
                     o.what + " " + o.path + " is " + it->second + ": an output must not overwrite an input"});
        return kExitUsage;
      }
    }
    std::error_code ec;
    std::string place = fs::weakly_canonical(fs::absolute(o.path), ec).string();
    if (ec) place = o.path;
    auto [it, fresh] = places.emplace(place, o.what + " " + o.path);
    if (!fresh) {
      g_log.error({ErrorKind::InvalidInput,
                   {},
                   o.what + " " + o.path + " and " + it->second +
                       " are the same file: outputs of one command must not collide"});
      return kExitUsage;
    }
  }
  return 0;
}

bool jobFailed(const Job& j) { return j.status != "ok" || (!j.golden_status.empty() && j.golden_status != "pass"); }

}  // namespace

int cmdBatch(const BatchArgs& a, const Common& common) {
  if (!checkTimeOption("--duration", a.duration) || (a.dt != 0 && !checkTimeOption("--dt", a.dt)) ||
      !checkTimeOption("--sample-interval", a.sample_interval))
    return kExitUsage;
  std::vector<Job> jobs;
  for (const auto& pattern : a.scenes)
    for (const auto& path : expandGlob(pattern)) {
      Job j;
      j.scene = path;
      jobs.push_back(std::move(j));
    }
  if (!a.manifest.empty()) {
    std::ifstream in(a.manifest);
    std::error_code dir_ec;
    if (fs::is_directory(a.manifest, dir_ec)) {
      g_log.error({ErrorKind::MissingInput, {a.manifest, 0}, "cannot read manifest: is a directory"});
      return kExitNoInput;
    }
    if (!in) {
      g_log.error(
          {ErrorKind::MissingInput, {a.manifest, 0}, std::string("cannot read manifest: ") + std::strerror(errno)});
      return kExitNoInput;
    }
    fs::path base = fs::path(a.manifest).parent_path();
    std::string line;
    int line_no = 0;
    while (std::getline(in, line)) {
      ++line_no;
      size_t hash = line.find('#');
      if (hash != std::string::npos) line.resize(hash);
      std::string err;
      std::vector<std::string> words = splitArgs(line, &err);
      if (!err.empty()) {
        g_log.error({ErrorKind::InvalidInput, {a.manifest, line_no}, err});
        return kExitDataErr;
      }
      if (words.empty()) continue;
      // Scenes in a manifest are relative to the manifest's folder.
      fs::path scene = words[0];
      if (scene.is_relative()) scene = base / scene;
      Job j;
      j.scene = scene.string();
      j.args.assign(words.begin() + 1, words.end());
      j.loc = {a.manifest, line_no};
      // The worker would say only "Run with --help": check the line here and name it.
      if (std::string problem = manifestLineProblem(words, a); !problem.empty()) {
        g_log.error({ErrorKind::InvalidInput, j.loc, problem});
        return kExitDataErr;
      }
      for (size_t i = 0; i + 1 < j.args.size(); ++i)
        if (j.args[i] == "--out") {
          fs::path out = j.args[i + 1];
          if (out.is_relative()) out = base / out;
          j.out = out.string();
          j.args.erase(j.args.begin() + static_cast<long>(i), j.args.begin() + static_cast<long>(i) + 2);
          break;
        }
      jobs.push_back(std::move(j));
    }
  }
  if (jobs.empty()) {
    g_log.error({ErrorKind::InvalidInput, {}, "no scenes given (name scene files, globs, or --manifest FILE)"});
    return kExitUsage;
  }
  std::error_code ec;
  fs::create_directories(a.out_dir, ec);
  if (ec) {
    g_log.error({ErrorKind::CannotCreate, {a.out_dir, 0}, "cannot create output folder: " + ec.message()});
    return kExitCantCreate;
  }
  std::map<std::string, size_t> outs;
  for (size_t i = 0; i < jobs.size(); ++i) {
    Job& j = jobs[i];
    if (j.out.empty()) j.out = (fs::path(a.out_dir) / fs::path(j.scene).stem()).string() + ".csv";
    j.log = fs::path(j.out).replace_extension(".log").string();
    auto [it, fresh] = outs.emplace(j.out, i);
    if (!fresh) {
      g_log.error({ErrorKind::InvalidInput, j.loc,
                   "scenes " + jobs[it->second].scene + " and " + j.scene + " would both write " + j.out +
                       "; give one of them --out"});
      return kExitUsage;
    }
  }
  if (int c = checkBatchFiles(jobs, a, common)) return c;

  int workers = a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
  catchStopSignals();
  auto t0 = std::chrono::steady_clock::now();
  size_t done = 0;
  runWorkerPool(
      jobs.size(), workers,
      [&](size_t i) {
        Job& j = jobs[i];
        j.started = std::chrono::steady_clock::now();
        j.pid = startWorker(j, a);
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
                           j.scene + "  " + fixed(j.wall, 2) + " s";
        if (!j.golden_status.empty()) line += "  golden: " + j.golden_status;
        if (!j.error.empty()) line += "  -- " + j.error;
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
      });
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  size_t failed = 0;
  for (const auto& j : jobs) failed += jobFailed(j) ? 1 : 0;
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
    std::snprintf(buf, sizeof buf, "%-40s %-12s %7.2f   %-11s %-12s %s\n", j.scene.c_str(), j.status.c_str(), j.wall,
                  j.golden_status.empty() ? "-" : j.golden_status.c_str(),
                  j.golden_status.empty() ? "-" : formatApprox(j.max_pos).c_str(),
                  j.golden_status.empty() ? "-" : formatApprox(j.max_rot).c_str());
    table += buf;
  }
  table += "\n" + std::to_string(jobs.size() - failed) + " of " + std::to_string(jobs.size()) + " scenes ok (" +
           countOf(static_cast<size_t>(workers), "worker", "workers") + ", " + fixed(wall, 2) + " s)\n";
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
  if (g_stop) return stopExitCode();
  return failed == 0 ? kExitOk : kExitResultWrong;
}

}  // namespace simbob::cli
