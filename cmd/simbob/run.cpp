// simbob run: one scene, one trajectory, one summary.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "commands.h"
#include "simbob/physics.h"
#include "simbob/robot.h"
#include "simbob/run.h"
#include "simbob/values.h"

namespace simbob::cli {

namespace {

class Progress {
 public:
  Progress(double duration, bool enabled) : duration_(duration), enabled_(enabled && isatty(2)) {
    start_ = std::chrono::steady_clock::now();
  }
  void update(double t) {
    if (!enabled_) return;
    double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (wall < 1.0) return;  // runs shorter than a second print no bar
    int pct = static_cast<int>(100.0 * t / duration_ + 0.5);
    int bar = pct * 30 / 100;
    std::fprintf(stderr, "\r[%.*s%*s] %3d%% t=%.2f/%.2f s", bar, "##############################", 30 - bar, "", pct, t,
                 duration_);
    shown_ = true;
  }
  void done() {
    if (shown_) std::fprintf(stderr, "\n");
  }

 private:
  double duration_;
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_;
};

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

std::string replaceExtension(const std::string& path, const std::string& ext) {
  std::filesystem::path p(path);
  p.replace_extension(ext);
  return p.string();
}

const char* statusName(RunStatus s) {
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

// Runs the model a second time and names the first sample where the two runs part.
bool checkDeterminism(const Model& model, const RunOptions& base, const std::vector<double>& first_times,
                      const std::vector<double>& first_poses, std::string* where) {
  const size_t n = model.bodies.size();
  size_t sample = 0;
  bool differ = false;
  RunOptions opts = base;
  opts.progress = nullptr;
  opts.on_sample = [&](double t, const double* p) {
    if (differ) return;
    if (sample >= first_times.size() || t != first_times[sample]) {
      differ = true;
      *where = "sample times differ at sample " + std::to_string(sample);
      return;
    }
    const double* q = &first_poses[sample * n * kPoseSize];
    for (size_t b = 0; b < n && !differ; ++b)
      for (size_t k = 0; k < kPoseSize; ++k)
        if (std::memcmp(&p[b * kPoseSize + k], &q[b * kPoseSize + k], sizeof(double)) != 0) {
          differ = true;
          double dist = std::sqrt(std::pow(p[b * 7] - q[b * 7], 2) + std::pow(p[b * 7 + 1] - q[b * 7 + 1], 2) +
                                  std::pow(p[b * 7 + 2] - q[b * 7 + 2], 2));
          *where = "first difference at t=" + formatNumber(t) + " s (sample " + std::to_string(sample) + "), body '" +
                   model.bodies[b].key + "', position apart by " + formatNumber(dist) + " m";
          break;
        }
    ++sample;
  };
  RunResult r = runModel(model, opts, nullptr);
  if (!differ && sample != first_times.size()) {
    differ = true;
    *where = "second run produced " + std::to_string(sample) + " samples, first " + std::to_string(first_times.size());
  }
  (void)r;
  return !differ;
}

}  // namespace

int cmdRun(RunArgs& a, const Registry& reg) {
  Scene scene;
  Model model;
  int code = 0;
  if (!loadAndCompile(a.scene, reg, &scene, &model, &code, !a.batch_child)) return code;
  if (!(a.duration > 0) || !std::isfinite(a.duration) || a.duration > 1e9) {
    g_log.error({ErrorKind::InvalidInput, {}, "--duration must be a positive number of seconds (at most 1e9)"});
    return kExitUsage;
  }
  if (a.dt < 0 || !std::isfinite(a.dt) || (a.dt > 0 && a.dt < 1e-9)) {
    g_log.error({ErrorKind::InvalidInput, {}, "--dt must be at least 1e-9 s"});
    return kExitUsage;
  }
  if (!(a.sample_interval >= 1e-9) || !std::isfinite(a.sample_interval)) {
    g_log.error({ErrorKind::InvalidInput, {}, "--sample-interval must be at least 1e-9 s"});
    return kExitUsage;
  }
  if (a.out.empty()) a.out = std::filesystem::path(a.scene).stem().string() + ".csv";
  if (a.space == "hash") model.settings.space = SpaceKind::Hash;
  if (a.space == "sap") model.settings.space = SpaceKind::SweepAndPrune;
  if (a.space == "quadtree") model.settings.space = SpaceKind::QuadTree;
  if (a.space == "simple") model.settings.space = SpaceKind::Simple;
  if (a.auto_disable) model.settings.auto_disable = true;
  if (a.max_contacts > 0) model.settings.max_contacts = a.max_contacts;

  // The run needs only the compiled model: free the component graph before ODE allocates.
  const std::string scene_hash = scene.content_hash;
  scene = Scene{};
  std::vector<std::string> keys;
  for (const auto& b : model.bodies) keys.push_back(b.key);
  Error err;
  std::unique_ptr<TrajectoryWriter> writer = TrajectoryWriter::open(a.out, keys, &err);
  if (!writer) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  catchStopSignals();

  RunOptions opts;
  opts.duration = a.duration;
  opts.dt = a.dt;
  opts.sample_interval = a.sample_interval;
  opts.seed = a.seed;
  opts.stop = &g_stop;
  opts.make_parties = [&model] { return robotParties(model); };  // controllers, after the sampler
  std::vector<double> rec_times, rec_poses;
  if (a.check_determinism) {
    opts.on_sample = [&](double t, const double* p) {
      rec_times.push_back(t);
      rec_poses.insert(rec_poses.end(), p, p + model.bodies.size() * kPoseSize);
    };
  }
  Progress progress(a.duration, g_log.level != Level::Quiet);
  opts.progress = [&](double t) { progress.update(t); };
  g_log.debug("running " + a.scene + ": " + std::to_string(model.bodies.size()) + " mobile bodies, " +
              std::to_string(model.geoms.size()) + " geoms, " + std::to_string(model.joints.size()) + " joints");
  RunResult r = runModel(model, opts, writer.get());
  progress.done();

  nlohmann::ordered_json summary;
  summary["simbob_version"] = SIMBOB_VERSION;
  summary["scene"] = a.scene;
  summary["scene_hash"] = "fnv1a64:" + scene_hash;
  summary["status"] = statusName(r.status);
  summary["dt"] = r.dt;
  summary["duration"] = a.duration;
  summary["sim_time"] = r.sim_time;
  summary["sample_interval"] = a.sample_interval;
  summary["seed"] = a.seed;
  static const char* kSpaceNames[] = {"hash", "sap", "quadtree", "simple"};
  summary["space"] = kSpaceNames[static_cast<int>(model.settings.space)];
  summary["auto_disable"] = model.settings.auto_disable;
  summary["max_contacts"] = model.settings.max_contacts;
  summary["units"] = {{"time", "s"}, {"position", "m"}, {"orientation", "unit quaternion w x y z"}};
  summary["bodies"] = model.bodies.size();
  summary["steps"] = r.steps;
  summary["samples"] = r.samples;
  summary["wall_seconds"] = r.wall_seconds;
  summary["steps_per_second"] = r.wall_seconds > 0 ? static_cast<double>(r.steps) / r.wall_seconds : 0.0;
  // What bit-identical reruns depend on.
  summary["reproducibility"] = {{"physics", physicsVersion()},
                                {"precision", "double"},
#ifdef __clang__
                                {"compiler", "clang " __clang_version__},
#else
                                {"compiler", "gcc " __VERSION__},
#endif
                                {"fp_contract", "off"},
                                {"cpu_features", cpuFeatures()}};

  if (r.status == RunStatus::Completed && a.check_determinism) {
    std::string where;
    bool same = checkDeterminism(model, opts, rec_times, rec_poses, &where);
    summary["determinism_check"] = same ? "identical" : where;
    if (!same) {
      writer->abandon();
      if (a.json) std::fputs(jsonText(summary).c_str(), stdout);
      g_log.error({ErrorKind::Diverged, {a.scene, 0}, "two runs in one process differ: " + where});
      return kExitResultWrong;
    }
    g_log.info("determinism check: two runs gave identical samples");
  }

  if (r.status == RunStatus::Completed) {
    if (!writer->commit(&err)) {
      g_log.error(err);
      return exitCodeFor(err.kind);
    }
    summary["trajectory"] = a.out;
    summary["csv_bytes"] = writer->bytesWritten();
    if (!writeFileAtomically(replaceExtension(a.out, ".json"), jsonText(summary), &err)) {
      g_log.error(err);
      return exitCodeFor(err.kind);
    }
    if (a.json) std::fputs(jsonText(summary).c_str(), stdout);
    g_log.info("wrote " + a.out + " (" + std::to_string(r.samples) + " samples of " +
               std::to_string(model.bodies.size()) + " bodies, " + std::to_string(r.steps) + " steps in " +
               formatNumber(std::round(r.wall_seconds * 1000) / 1000) + " s)");
    return kExitOk;
  }
  if (r.status == RunStatus::Diverged) {
    // The checks of `simbob check` usually know why: name the first one about this body.
    Diagnostics lint;
    lintModel(model, lint);
    size_t q = r.error.message.find('\'');
    std::string key = r.error.message.substr(q + 1, r.error.message.find('\'', q + 1) - q - 1);
    for (const auto& w : lint.warnings())
      if (w.message.find("'" + key + "'") != std::string::npos) {
        r.error.message += "; likely cause: " + w.message;
        break;
      }
  }
  // A failed run keeps what it computed, beside the output and never over it.
  std::string partial = partialPath(a.out);
  Error perr;
  if (writer->keepPartial(partial, &perr)) summary["partial_trajectory"] = partial;
  if (a.json) std::fputs(jsonText(summary).c_str(), stdout);
  g_log.error(r.error);
  if (!perr.message.empty())
    g_log.error(perr);
  else
    g_log.info("kept the trajectory so far in " + partial);
  if (r.status == RunStatus::Interrupted) return g_stop == SIGTERM ? kExitSigTerm : kExitSigInt;
  return exitCodeFor(r.error.kind);
}

}  // namespace simbob::cli
