// simbob run: one scene, one trajectory, one summary. The run is a Simulation with its outputs
// (RunOutputs) and, for --record/--video, a Recording attached; this file turns the options into
// those, and says what happened.
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "commands.h"
#include "run_watch.h"
#include "simbob/determinism.h"
#include "simbob/files.h"
#include "simbob/overrides.h"
#include "simbob/render.h"
#include "simbob/robot.h"
#include "simbob/run.h"
#include "simbob/run_log.h"
#include "simbob/run_outputs.h"
#include "simbob/simulation.h"
#include "simbob/transform.h"
#include "simbob/values.h"

namespace simbob::cli {

namespace {

int fail(const Error& e) {
  g_log.error(e);
  return exitCodeFor(e.kind);
}

// Loads and compiles the scene with the run's overrides, and refuses what cannot run: a body
// that starts beyond the runaway limit (it would "diverge" at the first step) and a step the
// nanosecond clock cannot hold. 0, or the exit status (reported).
int loadForRun(const RunArgs& a, const Common& common, std::vector<Override>* overrides, Scene* scene, Model* model) {
  if (int c = runOverrides(a, common, overrides)) return c;
  exitOnStopSignals(a.scene, "loading");
  int code = 0;
  if (!loadAndCompile(a.scene, *common.registry, scene, model, &code, !a.batch_child, false,
                      {{"--settings", common.settings}}, *overrides))
    return code;
  for (const BodyDef& b : model->bodies)
    if (norm(b.pose.p) > RunOptions{}.runaway_limit) {
      Model one;  // `simbob check` words it (lintModel); a one-body model keeps that cheap
      one.settings = model->settings;
      one.bodies = {b};
      Diagnostics far;
      lintModel(one, far);
      return report(far, false);
    }
  const double dt = a.dt > 0 ? a.dt : model->settings.max_time_step;
  if (!(dt >= kMinTimeOption && dt <= kMaxTimeOption))
    return fail({ErrorKind::InvalidInput,
                 {a.scene, 0},
                 "SceneSettings MaxTimeStep " + formatNumber(dt) + " s is outside 1e-9 to 1e9 s (give --dt)"});
  return 0;
}

// A worker of batch or sweep run that is refused leaves its error in a partial summary, where
// its parent reads every failed worker's outcome (workerError). Returns `code`.
int refused(const RunArgs& a, int code) {
  if (!a.refusal_summary || !g_log.first_error) return code;
  Error ignored;  // without it the parent reads the worker's log: stderr keeps its one line
  writeRefusedSummary(a.out, a.scene, *g_log.first_error, &ignored);
  return code;
}

SimulationOptions simulationOptions(const RunArgs& a) {
  SimulationOptions so;
  so.seed = a.seed;
  so.dt = a.dt;
  so.duration = a.duration;
  so.peer_timeout = a.peer_timeout;
  so.port_offset = a.port_offset;
  so.controllers = a.controllers;
  if (!isStreamOutput(a.out)) so.controller_log = controllerLogPath(a.out);
  so.stop = &g_stop;
  return so;
}

// Every output is checked against the inputs (never written over one) before anything exists.
int checkRunFiles(const RunArgs& a, const Common& common, const Scene& scene, const Model& model,
                  const std::vector<Override>& overrides) {
  std::vector<NamedPath> inputs = {{"--settings", common.settings}};
  appendSceneInputs(scene, a.scene, overrides, &inputs);
  appendModelInputs(model, common, a.scene, &inputs);
  std::vector<NamedPath> outputs = runOutputs(a);
  outputs.push_back({"--log-file", g_log.path});
  if (!a.video.empty()) outputs.push_back({"--video", a.video});
  if (int c = checkOutputs(outputs, inputs)) return c;
  return checkRecordFolder(a.record, outputs, inputs);
}

// --record / --video: the renderer (a GL context) exists only then.
int openRecording(const RunArgs& a, const Common& common, const Model& model, const RunOutputs& outputs,
                  std::unique_ptr<Recording>* recording) {
  if (a.record.empty() && a.video.empty()) return 0;
  RecordingRequest q;
  if (int c = renderOptions(a.view, common, &q.render)) return c;
  drawFallback(a.view, model, &q.render);
  q.fps = a.view.fps;
  q.record_dir = a.record;
  q.video = a.video;
  q.video_temp = outputs.videoTempPath();
  Error err;
  *recording = Recording::open(model, q, toSimTime(model.settings.min_time_step).value_or(0), &err);
  if (!*recording) return fail(err);
  g_log.debug((*recording)->description());
  return 0;
}

// Said once, when every input and output has been accepted and the run is about to start.
void beforeRun(const RunArgs& a, const Model& model, double dt) {
  for (const std::string& note :
       gridNotes(dt, a.sample_interval, a.record.empty() && a.video.empty() ? 0.0 : a.view.fps))
    g_log.info(note);
  if (!a.batch_child) {
    // What `simbob check` warns about, judged at the step this run takes; -q keeps it quiet.
    Diagnostics lint;
    lintModel(model, lint, dt);
    for (const auto& w : lint.warnings()) g_log.warning(w);
  }
  g_log.debug("running " + a.scene + ": " + countOf(model.bodies.size(), "mobile body", "mobile bodies") + ", " +
              countOf(model.geoms.size(), "geom", "geoms") + ", " + countOf(model.joints.size(), "joint", "joints"));
}

// --check-determinism: the run again, in this process. "identical", or where the runs part; an
// interrupt of the second run is the run's interrupt ("" then: not a difference).
std::string secondRun(const RunArgs& a, const Model& model, const SampleRecord& first, std::atomic<double>* last_sample,
                      RunResult* r) {
  g_log.debug("determinism check: running the scene a second time");
  DeterminismCheck c = checkDeterminism(model, simulationOptions(a), a.sample_interval, first,
                                        [&](double t, const double*) { *last_sample = t; });
  if (c.second.status == RunStatus::Interrupted) {
    r->status = RunStatus::Interrupted;
    r->error = c.second.error;
    r->error.message += " (second run of --check-determinism)";
    return "";
  }
  if (c.same) g_log.info("determinism check: two runs gave identical samples");
  return c.same ? "identical" : c.where;
}

// Two runs that differ publish nothing.
int rejectDifferent(const RunArgs& a, const nlohmann::ordered_json& summary, RunOutputs& outputs) {
  outputs.abandon();
  if (a.json) std::fputs(jsonText(summary).c_str(), stdout);
  return fail({ErrorKind::Diverged,
               {a.scene, 0},
               "two runs in one process differ: " + summary["determinism_check"].get<std::string>()});
}

int publish(const RunArgs& a, const Common& common, const Model& model, const RunResult& r,
            nlohmann::ordered_json summary, RunOutputs& outputs) {
  summary["trajectory"] = outputs.paths().trajectory;
  summary["csv_bytes"] = outputs.trajectoryBytes();
  if (!outputs.paths().run_log.empty()) summary["run_log"] = outputs.paths().run_log;
  const std::string text = jsonText(summary);
  Error err;
  if (!outputs.commit(text, &err)) return fail(err);
  if (a.json) std::fputs(text.c_str(), stdout);
  g_log.info("wrote " + outputs.paths().trajectory + " (" + countOf(r.samples, "sample", "samples") + " of " +
             countOf(model.bodies.size(), "body", "bodies") + ", " + countOf(r.steps, "step", "steps") + " in " +
             formatNumber(std::round(r.wall_seconds * 1000) / 1000) + " s)");
  return a.html.empty() ? kExitOk : viewAfterRun(a, common);
}

// A failed run keeps what it computed, beside its outputs and never over them.
int keepFailed(const RunArgs& a, const RunResult& r, nlohmann::ordered_json summary, RunOutputs& outputs) {
  const KeptOutputs kept = outputs.keepPartial([&summary](const KeptOutputs& k) {
    if (!k.trajectory.empty()) summary["partial_trajectory"] = k.trajectory;
    if (!k.run_log.empty()) summary["partial_run_log"] = k.run_log;
    return jsonText(summary);
  });
  if (!kept.summary.empty()) summary["partial_summary"] = kept.summary;
  if (a.json) std::fputs(jsonText(summary).c_str(), stdout);
  g_log.error(r.error);
  for (const Error& e : kept.errors) g_log.error(e);
  if (!kept.trajectory.empty()) g_log.info("kept the trajectory so far in " + kept.trajectory);
  if (!kept.run_log.empty()) g_log.info("kept the run log so far in " + kept.run_log);
  if (r.status == RunStatus::Interrupted) return stopExitCode();
  return exitCodeFor(r.error.kind);
}

RunSummaryInput summaryInput(const RunArgs& a, const std::string& scene_hash, const std::vector<Override>& overrides) {
  RunSummaryInput si;
  si.scene = a.scene;
  si.scene_hash = scene_hash;
  si.duration = a.duration;
  si.sample_interval = a.sample_interval;
  si.seed = a.seed;
  for (const Override& o : overrides) si.overrides.push_back(o.text);
  return si;
}

}  // namespace

int cmdRun(RunArgs& a, const Common& common) {
  if (std::string p = runArgsProblem(a); !p.empty()) return fail({ErrorKind::Usage, {}, p});
  std::vector<Override> overrides;
  Scene scene;
  Model model;
  if (a.out.empty()) a.out = std::filesystem::path(a.scene).stem().string() + ".csv";
  if (int c = loadForRun(a, common, &overrides, &scene, &model)) return refused(a, c);
  Progress progress(a.duration, g_log.level != Level::Quiet);
  SimulationOptions so = simulationOptions(a);
  so.no_controllers = common.no_controllers;
  so.progress = [&](double t) { progress.update(t); };
  std::unique_ptr<Simulation> sim;
  {  // built now, so that options it refuses fail before any output exists
    Diagnostics sd;
    if (!(sim = Simulation::fromModel(model, so, sd))) return refused(a, report(sd, false));
  }
  if (int c = checkRunFiles(a, common, scene, model, overrides)) return refused(a, c);
  Error err;
  std::unique_ptr<RunOutputs> outputs = RunOutputs::open(model, runPaths(a), &err);
  if (!outputs) return fail(err);
  std::unique_ptr<Recording> recording;
  if (int c = openRecording(a, common, model, *outputs, &recording)) return c;
  const std::string scene_hash = scene.content_hash;
  scene = Scene{};  // the run needs only the compiled model: free the graph before ODE allocates
  beforeRun(a, model, sim->stepSize());
  catchStopSignals();

  // The sampler and run log first, around the scene's controllers and peers (the run log records
  // the commands they gave at each sample time); the recorder (it sees what they did at t); the
  // clamp notices (once per actuator at the end).
  SampleRecord first(model.bodies.size());
  std::atomic<double> last_sample{0.0};
  outputs->attach(*sim, a.sample_interval, [&](double t, const double* p) {
    if (a.check_determinism) first.record(t, p);
    last_sample = t;
  });
  if (recording) sim->addParty(recording->recorder());
  sim->addParty(clampNotices(model, [](const Error& e) { g_log.warning(e); }));
  StopWatchdog watchdog([&]() {
    g_log.error({ErrorKind::Diverged,
                 {},
                 "interrupted at t=" + formatNumber(last_sample) +
                     " s (the last whole sample; the step under way was abandoned)"});
    Error perr;
    const std::string kept = outputs->keepFromOtherThread(&perr);
    if (!kept.empty()) g_log.info("kept the trajectory so far in " + kept);
    if (!perr.message.empty()) g_log.error(perr);
    _exit(stopExitCode());
  });
  RunResult r = sim->runToEnd();
  if (r.status == RunStatus::Diverged) explainDivergence(model, &r.error);
  sim.reset();  // its parties are done with the outputs before they are committed
  progress.done();
  std::string determinism;
  if (r.status == RunStatus::Completed && a.check_determinism)
    determinism = secondRun(a, model, first, &last_sample, &r);
  watchdog.loopReturned();
  if (recording && r.status == RunStatus::Completed && recording->recorder().failure()) {
    r.status = RunStatus::Failed;  // the recording could not be finished
    r.error = *recording->recorder().failure();
  }
  nlohmann::ordered_json summary = runSummary(model, r, summaryInput(a, scene_hash, overrides));
  if (!determinism.empty()) summary["determinism_check"] = determinism;
  if (recording) {
    if (!a.video.empty()) summary["video"] = a.video;
    summary["record"] = a.record;
    summary["frames"] = recording->recorder().frames();
  }
  if (!determinism.empty() && determinism != "identical") return rejectDifferent(a, summary, *outputs);
  if (r.status == RunStatus::Completed) return publish(a, common, model, r, std::move(summary), *outputs);
  return keepFailed(a, r, std::move(summary), *outputs);
}

}  // namespace simbob::cli
