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
#include "commands.h"
#include "workers.h"
#include "simbob/files.h"
#include "simbob/sweep.h"
#include "simbob/trajectory.h"
#include "simbob/values.h"

namespace simbob::cli {

namespace {

namespace fs = std::filesystem;

constexpr size_t kMaxManifestBytes = size_t{1} << 30;

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

std::string absolutePath(const std::string& p) {
  std::error_code ec;
  fs::path a = fs::absolute(p, ec);
  return (ec ? fs::path(p) : a).lexically_normal().string();
}

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

// The options every case of a sweep runs with: the plug-ins and the global settings the sweep
// command was given, as absolute paths (a Slurm task may start elsewhere).
std::vector<std::string> caseOptions(const Common& common) {
  std::vector<std::string> args;
  for (const std::string& p : common.plugins) {
    args.emplace_back("--plugin");
    args.push_back(absolutePath(p));
  }
  if (!common.settings.empty()) {
    args.emplace_back("--settings");
    args.push_back(absolutePath(common.settings));
  }
  return args;
}

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
    Scene sc;
    Model model;
    if (!loadAndCompile(scene_path, *common.registry, &sc, &model, &code, false, false, {})) return code;
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
      Scene sc;
      Model model;
      if (!loadAndCompile(scene_path, *common.registry, &sc, &model, &code, false, false, {}, ov)) return code;
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

// ---- run ----

std::string caseStatus(const fs::path& dir) {
  std::string text;
  if (!readFile((dir / "case.json").string(), 1 << 20, &text, nullptr, true)) return "";
  try {
    return nlohmann::json::parse(text).value("status", "");
  } catch (const std::exception&) {
    return "";
  }
}

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

int runOneCase(const SweepArgs& a, const SweepCase& c, const std::string& manifest, const Common& common) {
  const fs::path final_dir = fs::path(a.out) / caseDirName(c.index);
  std::error_code ec;
  if (!a.force && fs::exists(final_dir, ec)) {
    const std::string st = caseStatus(final_dir);
    if (st == "ok") {
      g_log.info("case " + std::to_string(c.index) + ": done already (" + final_dir.string() +
                 "); skipped (--force redoes it)");
      return kExitOk;
    }
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
  fs::path scene = c.scene;
  if (scene.is_relative()) scene = fs::path(manifest).parent_path() / scene;
  std::vector<std::string> args = {"simbob",
                                   "run",
                                   scene.lexically_normal().string(),
                                   "--duration",
                                   formatNumber(c.duration),
                                   "--sample-interval",
                                   formatNumber(c.sample_interval),
                                   "--seed",
                                   std::to_string(c.seed),
                                   "--out",
                                   (tmp / "trajectory.csv").string()};
  if (c.dt > 0) {
    args.emplace_back("--dt");
    args.push_back(formatNumber(c.dt));
  }
  for (const std::string& s : c.set) {
    args.emplace_back("--set");
    args.push_back(s);
  }
  for (std::string& o : caseOptions(common)) args.push_back(std::move(o));
  catchStopSignals();
  const auto t0 = std::chrono::steady_clock::now();
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
  int exit_code = pid < 0 ? kExitSoftware : outcome.exit_code >= 0 ? outcome.exit_code : 128 + WTERMSIG(wstatus);
  std::string status = exit_code == kExitOk ? "ok" : exit_code == kExitResultWrong ? "diverged" : "failed";
  std::string error;
  if (exit_code != kExitOk) {
    error = firstErrorLine((tmp / "log").string());
    if (error.empty()) error = "simbob run exited with status " + std::to_string(exit_code);
  }
  nlohmann::ordered_json j;
  j["case"] = c.index;
  j["status"] = status;
  j["exit_code"] = exit_code;
  if (!error.empty()) j["error"] = error;
  j["wall_seconds"] = wall;
  j["seed"] = c.seed;
  nlohmann::ordered_json vary = nlohmann::ordered_json::object();
  for (const auto& [k, v] : c.vary) vary[k] = v;
  j["vary"] = vary;
  j["set"] = c.set;
  nlohmann::ordered_json metrics = nlohmann::ordered_json::object();
  if (status == "ok") {
    fs::rename(tmp / "trajectory.json", tmp / "summary.json", ec);
    Trajectory t;
    Error terr;
    std::vector<double> values;
    std::string merr;
    if (!readTrajectory((tmp / "trajectory.csv").string(), &t, &terr)) {
      merr = terr.str();
    } else if (computeMetrics(t, c.metrics, &values, &merr)) {
      for (size_t i = 0; i < values.size(); ++i) metrics[c.metrics[i].name] = values[i];
    }
    if (!merr.empty()) {
      j["status"] = status = "failed";
      j["error"] = error = merr;
      exit_code = kExitDataErr;
      j["exit_code"] = exit_code;
    }
  }
  j["metrics"] = metrics;
  if (int code = status == "ok" && a.case_pages ? sweepCasePage(c, manifest, tmp.string(), common) : kExitOk) {
    fs::remove_all(tmp, ec);
    return code;
  }
  Error err;
  if (!writeFileAtomically((tmp / "case.json").string(), jsonText(j), &err)) {
    g_log.error(err);
    fs::remove_all(tmp, ec);
    return exitCodeFor(err.kind);
  }
  // Publish: a new case is one rename; a redone one swaps with the old directory in one step.
  if (::rename(tmp.c_str(), final_dir.c_str()) != 0) {
    if (::renameat2(AT_FDCWD, tmp.c_str(), AT_FDCWD, final_dir.c_str(), RENAME_EXCHANGE) != 0) {
      g_log.error(
          {ErrorKind::CannotCreate, {final_dir.string(), 0}, std::string("cannot publish: ") + std::strerror(errno)});
      fs::remove_all(tmp, ec);
      return kExitCantCreate;
    }
    fs::remove_all(tmp, ec);  // now the old case
  }
  if (status == "ok")
    g_log.info("case " + std::to_string(c.index) + ": ok (" + fixed(wall, 2) + " s) -> " + final_dir.string());
  else
    g_log.error({ErrorKind::Diverged, {}, "case " + std::to_string(c.index) + ": " + status + ": " + error});
  return exit_code;
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
        for (std::string& o : caseOptions(common)) args.push_back(std::move(o));
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

// ---- gather ----

// RFC 4180: a field with a comma, a quote or a line break is quoted, its quotes doubled.
std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

int sweepGather(const SweepArgs& a) {
  const std::string manifest = (fs::path(a.input) / "manifest.jsonl").string();
  std::string text;
  std::vector<SweepCase> cases;
  int code = 0;
  if (!readManifest(manifest, &text, &cases, &code)) return code;
  const std::string out = a.out.empty() ? (fs::path(a.input) / "results.csv").string() : a.out;
  {
    // The table must not replace what it is gathered from.
    std::vector<NamedPath> inputs = {{"the manifest", manifest}};
    for (const SweepCase& c : cases)
      inputs.push_back({"the case file", (fs::path(a.input) / caseDirName(c.index) / "case.json").string()});
    if (int c = checkOutputs({{a.out.empty() ? "the table" : "-o", out}, {"--log-file", g_log.path}}, inputs)) return c;
  }
  const SweepCase& first = cases.front();
  std::string csv = "case";
  for (const auto& [k, v] : first.vary) csv += "," + csvField(k);
  csv += ",seed,status,wall_seconds";
  for (const SweepMetric& m : first.metrics) csv += "," + csvField(m.name);
  csv += "\n";
  std::vector<int> retry;
  size_t ok = 0;
  for (const SweepCase& c : cases) {
    const fs::path dir = fs::path(a.input) / caseDirName(c.index);
    std::string status = "missing", wall, error;
    std::vector<std::string> values(c.metrics.size());
    std::string jt;
    if (readFile((dir / "case.json").string(), 1 << 20, &jt, nullptr, true)) {
      // A field of the wrong type makes the case failed, never the gather.
      try {
        const nlohmann::json j = nlohmann::json::parse(jt);
        if (!j.is_object()) throw std::runtime_error("not a JSON object");
        status = j.value("status", "failed");
        wall = formatNumber(j.value("wall_seconds", 0.0));
        error = j.value("error", "");
        if (status == "ok") {
          for (size_t i = 0; i < c.metrics.size(); ++i) {
            const std::string& name = c.metrics[i].name;
            if (!j.contains("metrics") || !j["metrics"].is_object() || !j["metrics"].contains(name)) continue;
            const nlohmann::json& v = j["metrics"][name];
            if (!v.is_number() || !std::isfinite(v.get<double>()))
              throw std::runtime_error("metric '" + name + "' is " + v.dump() + ", not a number");
            values[i] = formatNumber(v.get<double>());
          }
        }
      } catch (const std::exception& e) {
        status = "failed";
        std::string what = e.what();  // "[json.exception.type_error.302] type must be ...": the part after "] "
        if (size_t b = what.find("] "); what.rfind("[json.exception", 0) == 0 && b != std::string::npos)
          what = what.substr(b + 2);
        error = "unreadable case.json: " + what;
        values.assign(c.metrics.size(), "");
      }
    }
    csv += std::to_string(c.index);
    for (const auto& [k, v] : c.vary) csv += "," + csvField(v);
    csv += "," + std::to_string(c.seed) + "," + csvField(status) + "," + csvField(wall);
    for (const std::string& v : values) csv += "," + v;
    csv += "\n";
    if (status == "ok") {
      ++ok;
    } else {
      retry.push_back(c.index);
      if (!a.retry)
        g_log.error({ErrorKind::Diverged,
                     {dir.string(), 0},
                     quoteInput(status) + (error.empty() ? "" : ": " + quoteInput(error))});
    }
  }
  Error err;
  if (!writeFileAtomically(out, csv, &err)) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  if (a.retry) {
    if (!retry.empty()) std::printf("--array=%s\n", arrayList(retry).c_str());
  }
  g_log.info("wrote " + out + ": " + std::to_string(ok) + " of " + std::to_string(cases.size()) + " cases ok" +
             (retry.empty() ? "" : "; to redo: --array=" + arrayList(retry)));
  return retry.empty() ? kExitOk : kExitResultWrong;
}

// ---- sbatch ----

// Single-quoted for sh.
std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

// The value of an `#SBATCH --opt=VALUE` line as sbatch reads it: it splits the line at blanks
// and ends it at an unquoted '#'; inside "..." blanks and '#' are kept and '\' escapes the next
// character. Plain values stay as they are.
std::string sbatchQuote(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-.,/:%@+=") ==
                        std::string::npos)
    return s;
  std::string q = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') q += '\\';
    q += ch;
  }
  return q + "\"";
}

// A value that goes into a generated script is one line of text: a newline would end the
// #SBATCH line (sbatch stops reading options there) and start a shell command.
bool scriptValue(const std::string& what, const std::string& value) {
  for (unsigned char ch : value)
    if (ch < 0x20 || ch == 0x7F) {
      g_log.error({ErrorKind::InvalidInput,
                   {},
                   what + " '" + quoteInput(value) +
                       "' holds a control character; it cannot go into a job script (choose another)"});
      return false;
    }
  return true;
}

int sweepSbatch(const SweepArgs& a, const Common& common) {
  char exe[4096] = {};
  ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  const std::string binary = n > 0 ? std::string(exe, static_cast<size_t>(n)) : "simbob";
  const std::string out = absolutePath(a.out);
  const std::string manifest = absolutePath(a.input);
  // Checked before anything is written: every value the scripts will hold.
  const std::vector<std::string> options = caseOptions(common);
  if (!scriptValue("--partition", a.partition) || !scriptValue("-o", out) || !scriptValue("the manifest", manifest) ||
      !scriptValue("the simbob binary", binary))
    return kExitUsage;
  std::string forwarded;  // --plugin and --settings, for every case
  for (const std::string& o : options) {
    if (!scriptValue(o.rfind("--", 0) == 0 ? "an option" : "--plugin or --settings", o)) return kExitUsage;
    forwarded += " " + (o.rfind("--", 0) == 0 ? o : shellQuote(o));
  }
  // sbatch's --output reads '%' as a pattern and drops every '\\' (which also turns the
  // patterns off): no folder holding either can be named there.
  if (out.find_first_of("%\\") != std::string::npos) {
    g_log.error({ErrorKind::InvalidInput,
                 {},
                 "-o '" + quoteInput(out) + "' holds '" + out[out.find_first_of("%\\")] +
                     "', which Slurm's --output reads as a file-name pattern (choose another folder)"});
    return kExitUsage;
  }
  std::string text;
  std::vector<SweepCase> cases;
  int code = 0;
  if (!readManifest(a.input, &text, &cases, &code)) return code;
  {
    // The scripts must not replace the manifest they are written for.
    std::vector<NamedPath> outputs;
    for (const char* name : {"sweep.sbatch", "gather.sbatch", "submit.sh"})
      outputs.push_back({std::string("the script"), (fs::path(a.out) / name).string()});
    outputs.push_back({"--log-file", g_log.path});
    if (int c = checkOutputs(outputs, {{"the manifest", a.input}})) return c;
  }
  if (int c = claimOutDir(a.out, text)) return c;
  std::string header = "#!/bin/sh\n";
  auto sbatchLines = [&](const std::string& name, const std::string& log) {
    std::string s = "#SBATCH --job-name=" + name + "\n#SBATCH --output=" + sbatchQuote(out + "/" + log) + "\n";
    if (!a.partition.empty()) s += "#SBATCH --partition=" + sbatchQuote(a.partition) + "\n";
    return s;
  };
  std::string array = "0-" + std::to_string(cases.size() - 1);
  if (a.max_parallel > 0) array += "%" + std::to_string(a.max_parallel);
  const std::string run = header + "# simbob sweep: one case per array task (written by simbob sweep sbatch).\n" +
                          sbatchLines("simbob-sweep", "slurm-%A_%a.out") + "#SBATCH --array=" + array +
                          "\n#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n" + "exec " + shellQuote(binary) +
                          " sweep run " + shellQuote(manifest) + " -o " + shellQuote(out) + forwarded + "\n";
  const std::string gather = header + "# simbob sweep: gather the cases into results.csv (after the array).\n" +
                             sbatchLines("simbob-gather", "slurm-gather-%j.out") + "#SBATCH --ntasks=1\n" + "exec " +
                             shellQuote(binary) + " sweep gather " + shellQuote(out) + "\n";
  const std::string submit =
      header + "# Submits the case array, then gather once every task has ended (afterany).\nset -e\n" +
      "job=$(sbatch --parsable " + shellQuote(out + "/sweep.sbatch") + ")\n" + "job=${job%%;*}\n" +
      "gather=$(sbatch --parsable --dependency=afterany:$job " + shellQuote(out + "/gather.sbatch") + ")\n" +
      "echo \"array job $job, gather job ${gather%%;*}\"\n";
  Error err;
  for (const auto& [name, body] : {std::pair<const char*, const std::string&>{"sweep.sbatch", run},
                                   {"gather.sbatch", gather},
                                   {"submit.sh", submit}}) {
    const std::string path = (fs::path(a.out) / name).string();
    if (!writeFileAtomically(path, body, &err)) {
      g_log.error(err);
      return exitCodeFor(err.kind);
    }
    ::chmod(path.c_str(), 0755);
  }
  std::printf("sh %s/submit.sh\n", shellQuote(out).c_str());
  g_log.info("wrote " + out + "/sweep.sbatch (" + std::to_string(cases.size()) +
             " array tasks), gather.sbatch and "
             "submit.sh; submit with the line above (or: sbatch sweep.sbatch, then sbatch "
             "--dependency=afterany:JOBID gather.sbatch)");
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
  run->add_option("-o,--out", s.out, "Output folder (case-NNNN/ per case)")->required();
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
  addCommon(gather, common);
  CLI::App* sbatch = sweep->add_subcommand("sbatch", "Write Slurm scripts: a case array and a dependent gather job");
  sbatch->add_option("manifest", s.input, "Case manifest")->required();
  sbatch->add_option("-o,--out", s.out, "Output folder of the sweep (the scripts go there too)")->required();
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
  if (*a.run) return sweepRun(a, common);
  if (*a.gather) return a.html.empty() ? sweepGather(a) : galleryAfterGather(a, common, sweepGather(a));
  return sweepSbatch(a, common);
}

}  // namespace simbob::cli
