// simbob run: one scene, one trajectory, one summary.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli.h"
#include "commands.h"
#include "run_watch.h"
#include "simbob/files.h"
#include "simbob/overrides.h"
#include "simbob/physics.h"
#include "simbob/frame_sinks.h"
#include "simbob/render.h"
#include "simbob/robot.h"
#include "simbob/run.h"
#include "simbob/run_log.h"
#include "simbob/simulation.h"
#include "simbob/transform.h"
#include "simbob/values.h"

namespace simbob::cli {

namespace {

std::string replaceExtension(const std::string& path, const std::string& ext) {
  std::filesystem::path p(path);
  p.replace_extension(ext);
  return p.string();
}

// Runs the model a second time and names the first sample where the two runs part. The
// second run's result (interrupted, say) is in *second.
bool checkDeterminism(const Model& model, SimulationOptions opts, double sample_interval,
                      const std::function<void(double, const double*)>& track, const std::vector<double>& first_times,
                      const std::vector<double>& first_poses, std::string* where, RunResult* second) {
  const size_t n = model.bodies.size();
  size_t sample = 0;
  bool differ = false;
  opts.progress = nullptr;
  auto compare = [&](double t, const double* p) {
    if (track) track(t, p);
    if (differ) return;
    if (sample >= first_times.size() || t != first_times[sample]) {
      differ = true;
      *where = "sample times differ at sample " + std::to_string(sample);
      return;
    }
    const double* q = &first_poses[sample * n * kPoseSize];
    for (size_t b = 0; b < n && !differ; ++b)
      for (size_t k = 0; k < kPoseSize; ++k)
        // Bitwise on purpose: determinism means the same bits (-0.0 vs 0.0, NaN payloads).
        if (std::memcmp(&p[b * kPoseSize + k], &q[b * kPoseSize + k], sizeof(double)) != 0) {  // NOLINT

          differ = true;
          double dist = std::sqrt(std::pow(p[b * 7] - q[b * 7], 2) + std::pow(p[b * 7 + 1] - q[b * 7 + 1], 2) +
                                  std::pow(p[b * 7 + 2] - q[b * 7 + 2], 2));
          *where = "first difference at t=" + formatNumber(t) + " s (sample " + std::to_string(sample) + "), body '" +
                   model.bodies[b].key + "', position apart by " + formatNumber(dist) + " m";
          break;
        }
    ++sample;
  };
  Diagnostics unused;  // the model and options were accepted for the first run
  std::unique_ptr<Simulation> sim = Simulation::fromModel(model, opts, unused);
  sim->sampleTrajectory(nullptr, sample_interval, compare);
  *second = sim->runToEnd();
  if (second->status != RunStatus::Completed) return !differ;  // not a difference: the caller decides
  if (!differ && sample != first_times.size()) {
    differ = true;
    *where = "second run produced " + std::to_string(sample) + " samples, first " + std::to_string(first_times.size());
  }
  return !differ;
}

}  // namespace

namespace {

// The run log's path ("" without --log): --log-out, or --out with .csv replaced by .log.csv.
std::string runLogPath(const RunArgs& a, const std::string& out) {
  if (a.log.empty()) return "";
  return a.log_out.empty() ? replaceExtension(out, ".log.csv") : a.log_out;
}

}  // namespace

std::vector<NamedPath> runOutputs(const RunArgs& a) {
  const std::string out = a.out.empty() ? std::filesystem::path(a.scene).stem().string() + ".csv" : a.out;
  std::vector<NamedPath> all;
  if (isStreamOutput(out))
    all = {{"--out", out}};
  else
    all = {
        {"--out", out}, {"the summary", replaceExtension(out, ".json")}, {"the partial trajectory", partialPath(out)}};
  // The run log and its partial come after those three (cmdRun counts on the order).
  const std::string log = runLogPath(a, out);
  if (!log.empty()) {
    all.push_back({a.log_out.empty() ? "the run log" : "--log-out", log});
    if (!isStreamOutput(log)) all.push_back({"the partial run log", partialPath(log)});
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

int cmdRun(RunArgs& a, const Common& common) {
  if (std::string p = runArgsProblem(a); !p.empty()) {
    g_log.error({ErrorKind::InvalidInput, {}, p});
    return kExitUsage;
  }
  std::vector<Override> overrides;
  if (int c = runOverrides(a, common, &overrides)) return c;
  exitOnStopSignals(a.scene, "loading");
  Scene scene;
  Model model;
  int code = 0;
  if (!loadAndCompile(a.scene, *common.registry, &scene, &model, &code, !a.batch_child, false,
                      {{"--settings", common.settings}}, overrides))
    return code;
  // A body that starts beyond the runaway limit would "diverge" at the first step; `simbob
  // check` reports it (lintModel) and so does run, before anything is written.
  for (const BodyDef& b : model.bodies)
    if (norm(b.pose.p) > RunOptions{}.runaway_limit) {
      Model one;  // lint words it; a one-body model keeps that cheap
      one.settings = model.settings;
      one.bodies = {b};
      Diagnostics far;
      lintModel(one, far);
      return report(far, false);
    }
  // The scene's own step must fit the nanosecond clock as --dt does.
  const double dt = a.dt > 0 ? a.dt : model.settings.max_time_step;
  if (!(dt >= kMinTimeOption && dt <= kMaxTimeOption)) {
    g_log.error({ErrorKind::InvalidInput,
                 {a.scene, 0},
                 "SceneSettings MaxTimeStep " + formatNumber(dt) + " s is outside 1e-9 to 1e9 s (give --dt)"});
    return kExitDataErr;
  }
  if (a.out.empty()) a.out = std::filesystem::path(a.scene).stem().string() + ".csv";
  // The run itself: a Simulation of the compiled model (socket ports and timeouts are its
  // options). Built now, so that options it refuses fail before any output exists.
  Progress progress(a.duration, g_log.level != Level::Quiet);
  SimulationOptions so;
  so.seed = a.seed;
  so.dt = a.dt;
  so.duration = a.duration;
  so.peer_timeout = a.peer_timeout;
  so.port_offset = a.port_offset;
  so.controllers = a.controllers;
  if (!isStreamOutput(a.out)) so.controller_log = replaceExtension(a.out, ".controller.log");
  so.stop = &g_stop;
  so.progress = [&](double t) { progress.update(t); };
  std::unique_ptr<Simulation> sim;
  {
    Diagnostics sd;
    sim = Simulation::fromModel(model, so, sd);
    if (!sim) return report(sd, false);
  }

  Error err_early;
  // Every output is checked, and created under a temporary name, before the run starts: a run
  // must not end in "cannot create" after simulating for an hour.
  std::vector<NamedPath> outputs = runOutputs(a);
  auto outputNamed = [&outputs](const std::string& name) {
    for (const NamedPath& o : outputs)
      if (o.what == name) return o.path;
    return std::string();
  };
  const std::string summary_path = outputNamed("the summary");
  const std::string partial = outputNamed("the partial trajectory");
  const std::string log_path = runLogPath(a, a.out);
  const std::string log_partial = outputNamed("the partial run log");
  {
    std::vector<NamedPath> inputs = {{"--settings", common.settings}};
    appendSceneInputs(scene, a.scene, overrides, &inputs);
    appendModelInputs(model, common, a.scene, &inputs);
    outputs.push_back({"--log-file", g_log.path});
    if (!a.video.empty()) outputs.push_back({"--video", a.video});
    if (int c = checkOutputs(outputs, inputs)) return c;
    if (int c = checkRecordFolder(a.record, outputs, inputs)) return c;
  }

  // --record / --video: the renderer (a GL context) exists only then. Frames are drawn on a
  // render thread (drawOnRenderThread) and encoded on another (makeAsyncSink) while the physics
  // steps on.
  std::unique_ptr<Renderer> renderer;
  std::unique_ptr<FrameSink> sink;
  std::unique_ptr<OutputFile> video_file;  ///< --video's temporary file, committed with the trajectory
  if (!a.record.empty() || !a.video.empty()) {
    RenderOptions ro;
    if (int c = renderOptions(a.view, common, &ro)) return c;
    drawFallback(a.view, model, &ro);
    std::vector<std::unique_ptr<FrameSink>> sinks;
    if (!a.record.empty()) {
      std::error_code dir_ec;
      if (std::filesystem::exists(std::filesystem::path(a.record) / "frame_000000.png", dir_ec)) {
        g_log.error({ErrorKind::CannotCreate,
                     {a.record, 0},
                     "already holds a recording (frame_000000.png); remove it or record elsewhere"});
        return kExitCantCreate;
      }
      std::unique_ptr<FrameSink> pngs = makePngSequenceSink(a.record, &err_early);
      if (!pngs) {
        g_log.error(err_early);
        return exitCodeFor(err_early.kind);
      }
      sinks.push_back(std::move(pngs));
    }
    if (!a.video.empty()) {
      std::string why;
      const std::string encoder = videoEncoderFor(a.video, &why);
      if (encoder.empty()) {
        g_log.error({ErrorKind::InvalidInput, {a.video, 0}, why});
        return kExitUsage;
      }
      if (encoder != "mjpeg" && (ro.width % 2 != 0 || ro.height % 2 != 0)) {
        g_log.error({ErrorKind::InvalidInput, {}, "--size must be even in both directions for H.264 (--video .mp4)"});
        return kExitUsage;
      }
      // The video is committed with the trajectory and summary (all new or all old), not by
      // the sink when the recording ends: a run that fails after that publishes none of it.
      if (!isStreamOutput(a.video)) {
        video_file = OutputFile::open(a.video, &err_early);
        if (!video_file) {
          g_log.error(err_early);
          return exitCodeFor(err_early.kind);
        }
      }
      std::unique_ptr<FrameSink> video =
          makeVideoSink(a.video, a.view.fps, &err_early, video_file ? video_file->tempPath() : std::string());
      if (!video) {
        g_log.error(err_early);
        return exitCodeFor(err_early.kind);
      }
      sinks.push_back(std::move(video));
    }
    renderer = Renderer::create(model, ro, &err_early);
    if (!renderer) {
      g_log.error(err_early);
      return exitCodeFor(err_early.kind);
    }
    sink = makeAsyncSink(std::move(sinks));
    g_log.debug("recording through " + renderer->backendName() + " (" + renderer->glRenderer() + "), camera " +
                renderer->cameraName());
  }

  // The run needs only the compiled model: free the component graph before ODE allocates.
  const std::string scene_hash = scene.content_hash;
  scene = Scene{};
  std::vector<std::string> keys;
  for (const auto& b : model.bodies) keys.push_back(b.key);
  Error err;
  std::unique_ptr<TrajectoryWriter> writer = TrajectoryWriter::open(a.out, keys, &err, a.columns == "pose,velocity");
  if (!writer) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  std::unique_ptr<OutputFile> summary_file;
  if (!summary_path.empty()) {
    summary_file = OutputFile::open(summary_path, &err);
    if (!summary_file) {
      g_log.error(err);
      return exitCodeFor(err.kind);
    }
  }
  std::unique_ptr<OutputFile> log_file;
  RunLogWhat log_what;
  if (!log_path.empty()) {
    std::string unused;
    parseRunLogWhat(a.log, &log_what, &unused);  // checked by runArgsProblem
    log_file = OutputFile::open(log_path, &err);
    if (!log_file) {
      g_log.error(err);
      return exitCodeFor(err.kind);
    }
  }
  std::error_code ec;
  for (const std::string& kept : {partial, log_partial})
    if (!kept.empty() && std::filesystem::is_directory(kept, ec)) {
      g_log.error({ErrorKind::CannotCreate, {kept, 0}, "cannot create: is a directory"});
      return kExitCantCreate;
    }
  // Said once, when every input and output has been accepted and the run is about to start.
  for (const std::string& note :
       gridNotes(dt, a.sample_interval, a.record.empty() && a.video.empty() ? 0.0 : a.view.fps))
    g_log.info(note);
  if (!a.batch_child) {
    // What `simbob check` warns about (overlaps, tunnelling, step size), once before the run,
    // judged at the step this run takes; -q keeps stderr clear of it.
    Diagnostics lint;
    lintModel(model, lint, dt);
    for (const auto& w : lint.warnings()) g_log.warning(w);
  }
  catchStopSignals();

  std::vector<double> rec_times, rec_poses;
  std::atomic<double> last_sample{0.0};
  std::unique_ptr<FrameDrawer> drawer;
  std::unique_ptr<Recorder> recorder;
  if (renderer) drawer = drawOnRenderThread(*renderer, *sink);
  if (drawer)
    recorder = std::make_unique<Recorder>(*drawer, a.view.fps, toSimTime(model.settings.min_time_step).value_or(0),
                                          static_cast<int>(model.bodies.size()));
  // The sampler first, the scene's controllers and peers next (the Simulation's order); then the
  // run log, so that it records the commands they gave at each sample time; the recorder (it
  // sees what the controllers did at t); the clamp notices (once per actuator at the end).
  sim->sampleTrajectory(writer.get(), a.sample_interval, [&](double t, const double* p) {
    if (a.check_determinism) {
      rec_times.push_back(t);
      rec_poses.insert(rec_poses.end(), p, p + model.bodies.size() * kPoseSize);
    }
    last_sample = t;
  });
  if (log_file) {
    const SimTime interval = std::max<SimTime>(toSimTime(a.sample_interval).value_or(1), 1);
    const SimTime min_step = toSimTime(model.settings.min_time_step).value_or(0);
    sim->addParty(std::make_unique<RunLogParty>(model, log_what, interval, min_step, log_file.get()));
  }
  if (recorder) sim->addParty(*recorder);
  sim->addParty(clampNotices(model, [](const Error& e) { g_log.warning(e); }));
  StopWatchdog watchdog([&]() {
    g_log.error({ErrorKind::Diverged,
                 {},
                 "interrupted at t=" + formatNumber(last_sample) +
                     " s (the last whole sample; the step under way was abandoned)"});
    if (summary_file) summary_file->abandon();
    if (log_file) log_file->abandon();  // the main thread may be writing it: keep none of it
    if (video_file) video_file->abandon();
    Error perr;
    if (writer->keepPartialFromOtherThread(partial, &perr)) {
      if (!writer->isStream()) g_log.info("kept the trajectory so far in " + partial);
    } else {
      g_log.error(perr);
    }
    _exit(stopExitCode());
  });
  g_log.debug("running " + a.scene + ": " + countOf(model.bodies.size(), "mobile body", "mobile bodies") + ", " +
              countOf(model.geoms.size(), "geom", "geoms") + ", " + countOf(model.joints.size(), "joint", "joints"));
  RunResult r = sim->runToEnd();
  sim.reset();  // its parties flush what they hold (the run log) before the outputs are committed
  progress.done();

  RunSummaryInput si;
  si.scene = a.scene;
  si.scene_hash = scene_hash;
  si.duration = a.duration;
  si.sample_interval = a.sample_interval;
  si.seed = a.seed;
  for (const Override& o : overrides) si.overrides.push_back(o.text);
  nlohmann::ordered_json summary = runSummary(model, r, si);

  if (r.status == RunStatus::Completed && a.check_determinism) {
    std::string where;
    RunResult second;
    g_log.debug("determinism check: running the scene a second time");
    bool same = checkDeterminism(
        model, so, a.sample_interval, [&](double t, const double*) { last_sample = t; }, rec_times, rec_poses, &where,
        &second);
    if (second.status == RunStatus::Interrupted) {
      // An interrupt is an interrupt, whichever run it came in: not a difference.
      r.status = RunStatus::Interrupted;
      r.error = second.error;
      r.error.message += " (second run of --check-determinism)";
      summary["status"] = runStatusName(r.status);
    } else {
      summary["determinism_check"] = same ? "identical" : where;
      if (!same) {
        watchdog.loopReturned();
        writer->abandon();
        if (summary_file) summary_file->abandon();
        if (log_file) log_file->abandon();
        if (video_file) video_file->abandon();
        if (a.json) std::fputs(jsonText(summary).c_str(), stdout);
        g_log.error({ErrorKind::Diverged, {a.scene, 0}, "two runs in one process differ: " + where});
        return kExitResultWrong;
      }
      g_log.info("determinism check: two runs gave identical samples");
    }
  }
  watchdog.loopReturned();

  if (r.status == RunStatus::Completed && recorder && recorder->failure()) {
    r.status = RunStatus::Failed;  // the recording could not be finished
    r.error = *recorder->failure();
  }
  if (recorder) {
    if (!a.video.empty()) summary["video"] = a.video;
    summary["record"] = a.record;
    summary["frames"] = recorder->frames();
  }
  if (r.status == RunStatus::Completed) {
    summary["trajectory"] = a.out;
    summary["csv_bytes"] = writer->bytesWritten();
    if (log_file) summary["run_log"] = log_path;
    const std::string text = jsonText(summary);
    std::vector<OutputFile*> also;
    if (summary_file) {
      summary_file->write(text);
      also.push_back(summary_file.get());
    }
    if (log_file) also.push_back(log_file.get());
    if (video_file) also.push_back(video_file.get());
    // The trajectory and its summary replace the old pair together, or neither does.
    if (!writer->commit(&err, also)) {
      g_log.error(err);
      return exitCodeFor(err.kind);
    }
    if (a.json) std::fputs(text.c_str(), stdout);
    g_log.info("wrote " + a.out + " (" + countOf(r.samples, "sample", "samples") + " of " +
               countOf(model.bodies.size(), "body", "bodies") + ", " + countOf(r.steps, "step", "steps") + " in " +
               formatNumber(std::round(r.wall_seconds * 1000) / 1000) + " s)");
    return kExitOk;
  }
  if (summary_file) summary_file->abandon();
  if (video_file) video_file->abandon();
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
  Error perr;
  if (writer->keepPartial(partial, &perr) && !writer->isStream()) summary["partial_trajectory"] = partial;
  Error lerr;
  if (log_file && !log_file->isStream()) {
    if (log_file->close(&lerr) && log_file->rename(log_partial, &lerr)) summary["partial_run_log"] = log_partial;
  }
  if (a.json) std::fputs(jsonText(summary).c_str(), stdout);
  g_log.error(r.error);
  if (!perr.message.empty())
    g_log.error(perr);
  else if (!writer->isStream())
    g_log.info("kept the trajectory so far in " + partial);
  if (!lerr.message.empty())
    g_log.error(lerr);
  else if (log_file && !log_file->isStream())
    g_log.info("kept the run log so far in " + log_partial);
  if (r.status == RunStatus::Interrupted) return stopExitCode();
  return exitCodeFor(r.error.kind);
}

}  // namespace simbob::cli
