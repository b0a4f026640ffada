// A whole run of a scene: see simbob/scene_run.h. Open: load, refuse, open the outputs; finish:
// run, compare a second run, commit or keep, write the page.
#include "simbob/scene_run.h"

#include <cmath>
#include <filesystem>

#include "simbob/tool/frame_sinks.h"
#include "simbob/robot.h"
#include "simbob/transform.h"
#include "simbob/trajectory.h"
#include "simbob/values.h"
#include "simbob/tool/replay_page.h"
#include "simulation/determinism.h"
#include "simulation/outputs.h"

namespace simbob {

namespace {

std::string controllerLogPath(const std::string& out) {
  return std::filesystem::path(out).replace_extension(".controller.log").string();
}

std::string trajectoryPath(const RunOptions& o) {
  return o.out.empty() ? std::filesystem::path(o.scene).stem().string() + ".csv" : o.out;
}

RunOutputPaths outputPaths(const RunOptions& o) {
  RunOutputPaths p = defaultOutputPaths(trajectoryPath(o), o.log.any());
  if (!o.log_out.empty()) p.run_log = o.log_out;
  p.run_log_what = o.log;
  p.video = o.video;
  p.velocity_columns = o.velocity_columns;
  return p;
}

}  // namespace

std::string partialSummaryOf(const std::string& trajectory) {
  const RunOutputPaths p = defaultOutputPaths(trajectory, false);
  return p.summary.empty() ? "" : partialSummaryPath(p.summary);
}

std::string runOptionsProblem(const RunOptions& o) {
  const SimulationOptions& s = o.simulation;
  // A run that writes nothing (a still at --at 0) may end where it starts.
  std::string p = clockTimeProblem(o.write_outputs ? "--duration" : "--at", s.duration, !o.write_outputs);
  if (p.empty()) p = clockTimeProblem("--dt", s.dt, true);
  if (p.empty()) p = clockTimeProblem("--sample-interval", o.sample_interval);
  if (p.empty() && !(s.peer_timeout >= 0.001 && s.peer_timeout <= 86400))
    p = "--peer-timeout must be between 0.001 and 86400 s, got " + formatNumber(s.peer_timeout);
  if (p.empty() && (s.threads < 0 || s.threads > kMaxThreads))
    p = "--threads must be between 1 and " + std::to_string(kMaxThreads) + ", got " + std::to_string(s.threads);
  if (p.empty() && (s.port_offset < -65535 || s.port_offset > 65535))
    p = "--port-offset must be between -65535 and 65535, got " + std::to_string(s.port_offset);
  if (p.empty() && !o.html.empty() && isStreamOutput(trajectoryPath(o)))
    p = "--html reads the trajectory back: --out must be a file, not a stream";
  return p;
}

namespace {

// --record DIR writes DIR/frame_NNNNNN.png and removes such frames of an earlier, longer
// recording: no input or other output may be one of them.
Error recordFolderCollision(const std::string& dir, const std::vector<NamedPath>& outputs,
                            const std::vector<NamedPath>& inputs) {
  if (dir.empty()) return {};
  auto inFolder = [&](const std::string& p) {
    if (p.empty() || p == "-" || isStreamOutput(p)) return false;
    const std::filesystem::path path(p);
    if (!isFrameFileName(path.filename().string())) return false;
    const std::string parent = path.has_parent_path() ? path.parent_path().string() : ".";
    return sameOutputPlace(parent, dir);
  };
  for (const auto* list : {&inputs, &outputs})
    for (const NamedPath& f : *list)
      if (inFolder(f.path))
        return {ErrorKind::Usage,
                {},
                f.what + " " + quoteInput(f.path, 400) + " is a frame file of --record " + quoteInput(dir, 400) +
                    ", which the recording writes or removes: " +
                    (list == &inputs ? "an output must not overwrite an input"
                                     : "outputs of one command must not collide")};
  return {};
}

// The error that decides a refused load: the first, unless an input is missing (nothing behind
// a missing file could be checked).
Error decidingError(const std::vector<Error>& errors) {
  Error e = errors.front();
  for (const Error& x : errors)
    if (x.kind == ErrorKind::MissingInput) {
      e.kind = ErrorKind::MissingInput;
      break;
    }
  return e;
}

}  // namespace

std::vector<NamedPath> runOutputFiles(const RunOptions& opts) {
  if (!opts.write_outputs) return {};
  const RunOutputPaths p = outputPaths(opts);
  std::vector<NamedPath> all = {{"--out", p.trajectory}};
  if (!p.summary.empty())
    all.insert(all.end(), {{"the summary", p.summary},
                           {"the partial trajectory", partialPath(p.trajectory)},
                           {"the partial summary", partialSummaryPath(p.summary)},
                           {"the controllers' log", controllerLogPath(p.trajectory)}});
  if (!opts.html.empty()) all.push_back({"--html", opts.html});
  if (!p.run_log.empty()) {
    all.push_back({opts.log_out.empty() ? "the run log" : "--log-out", p.run_log});
    if (!isStreamOutput(p.run_log)) all.push_back({"the partial run log", partialPath(p.run_log)});
  }
  return all;
}

Run::~Run() {
  sim_.reset();  // its parties write into the outputs
}

void Run::note(RunNote::Level level, const std::string& text, SourceLoc loc) {
  if (listener_.note) listener_.note({level, {ErrorKind::InvalidInput, loc, text}});
}

std::unique_ptr<Run> Run::open(RunOptions opts, const Registry& reg, RunListener listener, Error* refusal) {
  std::unique_ptr<Run> run(new Run());
  run->opts_ = std::move(opts);
  run->listener_ = std::move(listener);
  if (!run->prepare(reg, refusal) || !run->openOutputs(refusal)) {
    if (run->opts_.refusal_summary && run->opts_.write_outputs) {
      Error ignored;  // without it the parent reads the worker's log: stderr keeps its one line
      writeRefusedSummary(trajectoryPath(run->opts_), run->opts_.scene, *refusal, &ignored);
    }
    return nullptr;
  }
  return run;
}

// Loads the scene and builds the Simulation; refuses (and says why) what cannot run.
bool Run::prepare(const Registry& reg, Error* refusal) {
  RunOptions& o = opts_;
  auto refuse = [&](const Error& e) {
    if (listener_.note) listener_.note({RunNote::Error, e});
    *refusal = e;
    return false;
  };
  if (std::string p = runOptionsProblem(o); !p.empty()) return refuse({ErrorKind::Usage, {}, p});
  if (o.write_outputs && o.controller_log && !isStreamOutput(trajectoryPath(o)))
    o.simulation.controller_log = controllerLogPath(trajectoryPath(o));
  LoadRequest req;
  req.path = o.scene;
  req.text = o.scene_text ? &*o.scene_text : nullptr;
  req.overrides = o.simulation.overrides;
  Model model;
  const bool loaded = loadModel(req, reg, &model, &load_);
  inputs_ = o.inputs;
  for (const std::string& f : load_.files) inputs_.push_back({f == o.scene ? "the scene" : "the import", f});
  for (const Override& ov : o.simulation.overrides)
    if (ov.line > 0) inputs_.push_back({"the DocumentIni", ov.place});
  if (loaded)
    for (const std::string& t : textureFiles(model, o.simulation.texture_folder)) inputs_.push_back({"the texture", t});
  if (listener_.inputs) listener_.inputs(inputs_);
  if (Error e = outputCollision(o.outputs, inputs_); !e.message.empty()) return refuse(e);
  const Diagnostics& d = load_.diagnostics;
  if (o.warnings)
    for (const Error& w : d.warnings()) note(RunNote::Warning, w.message, w.loc);
  if (!loaded) {
    for (const Error& e : d.errors())
      if (listener_.note) listener_.note({RunNote::Error, e});
    *refusal = decidingError(d.errors());
    return false;
  }
  for (const BodyDef& b : model.bodies)
    if (norm(b.pose.p) > o.simulation.runaway_limit) {
      Model one;  // `simbob check` words it (lintModel); a one-body model keeps that cheap
      one.settings = model.settings;
      one.bodies = {b};
      Diagnostics far;
      lintModel(one, far);
      if (!far.ok()) return refuse(far.errors().front());
    }
  const double dt = resolvedStep(o.simulation.dt, model.settings.max_time_step);
  if (!clockTimeProblem("", dt).empty())
    return refuse({ErrorKind::InvalidInput,
                   {o.scene, 0},
                   "SceneSettings MaxTimeStep " + formatNumber(dt) + " s is outside 1e-9 to 1e9 s (give --dt)"});
  Diagnostics sd;
  model_ = std::move(model);
  if (!(sim_ = Simulation::fromModel(model_, o.simulation, sd))) return refuse(sd.errors().front());
  return true;
}

// Every output is checked against the inputs (never written over one) and opened under a
// temporary name before the run starts; then what the run says before it starts.
bool Run::openOutputs(Error* refusal) {
  auto refuse = [&](const Error& e) {
    if (listener_.note) listener_.note({RunNote::Error, e});
    *refusal = e;
    return false;
  };
  if (!opts_.write_outputs) return true;
  std::vector<NamedPath> outputs = runOutputFiles(opts_);
  outputs.insert(outputs.end(), opts_.outputs.begin(), opts_.outputs.end());
  if (!opts_.video.empty()) outputs.push_back({"--video", opts_.video});
  if (Error e = outputCollision(outputs, inputs_); !e.message.empty()) return refuse(e);
  if (Error e = recordFolderCollision(opts_.record, outputs, inputs_); !e.message.empty()) return refuse(e);
  Error err;
  if (!(outputs_ = RunOutputs::open(model_, outputPaths(opts_), &err))) return refuse(err);
  if (!opts_.record.empty() || !opts_.video.empty()) {  // the renderer (a GL context) exists only then
    RecordingRequest q;
    q.render = opts_.render;
    q.fps = opts_.fps;
    q.record_dir = opts_.record;
    q.video = opts_.video;
    q.video_temp = outputs_->videoTempPath();
    if (std::string n = drawFallbackNote(model_, q.render); !n.empty()) note(RunNote::Info, n);
    if (!(recording_ = Recording::open(model_, q, toSimTime(model_.settings.min_time_step).value_or(0), &err)))
      return refuse(err);
    note(RunNote::Debug, recording_->description());
  }
  beforeRun();
  return true;
}

// Said once, when every input and output has been accepted; then the outputs are attached: the
// sampler and run log first, around the scene's controllers and peers (the run log records the
// commands they gave at each sample time); the recorder (it sees what they did at t); the clamp
// notices (once per actuator at the end).
void Run::beforeRun() {
  const bool recording = !opts_.record.empty() || !opts_.video.empty();
  for (const std::string& n : gridNotes(sim_->stepSize(), opts_.sample_interval, recording ? opts_.fps : 0.0))
    note(RunNote::Info, n);
  if (opts_.warnings) {  // what `simbob check` warns about, judged at the step this run takes
    Diagnostics lint;
    lintModel(model_, lint, sim_->stepSize());
    for (const Error& w : lint.warnings()) note(RunNote::Warning, w.message, w.loc);
  }
  note(RunNote::Debug, "running " + opts_.scene + ": " + countOf(model_.bodies.size(), "mobile body", "mobile bodies") +
                           ", " + countOf(model_.geoms.size(), "geom", "geoms") + ", " +
                           countOf(model_.joints.size(), "joint", "joints"));
  if (opts_.check_determinism) first_ = std::make_unique<SampleRecord>(model_.bodies.size());
  outputs_->attach(*sim_, opts_.sample_interval, [this](double t, const double* p) {
    if (first_) first_->record(t, p);
    last_sample_ = t;
  });
  if (recording_) sim_->addParty(recording_->recorder());
  sim_->addParty(clampNotices(model_, [this](const Error& e) {
    if (listener_.note) listener_.note({RunNote::Warning, e});
  }));
}

namespace {
std::string jsonText(const nlohmann::ordered_json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}
}  // namespace

const RunOutcome& Run::finish() {
  if (finished_) return outcome_;
  finished_ = true;
  RunResult r = sim_->runToEnd();
  if (r.status == RunStatus::Diverged) explainDivergence(model_, r.divergence.body, r.divergence.joint, &r.error);
  if (r.physics_messages.count > 0)
    note(RunNote::Warning, physicsMessagesWarning(r.physics_messages), {opts_.scene, 0});
  sim_.reset();  // its parties are done with the outputs before they are committed
  if (!opts_.write_outputs) {
    outcome_.result = r;
    return outcome_;
  }
  if (r.status == RunStatus::Completed && opts_.check_determinism) outcome_.determinism = secondRun(&r);
  if (recording_ && r.status == RunStatus::Completed && recording_->recorder().failure()) {
    r.status = RunStatus::Failed;  // the recording could not be finished
    r.error = *recording_->recorder().failure();
  }
  RunSummaryInput si;
  si.scene = opts_.scene;
  si.scene_hash = load_.content_hash;
  si.duration = opts_.simulation.duration;
  si.sample_interval = opts_.sample_interval;
  si.seed = opts_.simulation.seed;
  for (const Override& o : opts_.simulation.overrides) si.overrides.push_back(o.text);
  nlohmann::ordered_json summary = runSummary(model_, r, si);
  const std::string& determinism = outcome_.determinism;
  if (!determinism.empty()) summary["determinism_check"] = determinism;
  if (recording_) {
    if (!opts_.video.empty()) summary["video"] = opts_.video;
    summary["record"] = opts_.record;
    summary["frames"] = recording_->recorder().frames();
  }
  outcome_.result = r;
  if (!determinism.empty() && determinism != "identical") {  // two runs that differ publish nothing
    outputs_->abandon();
    outcome_.summary = std::move(summary);
    outcome_.result.status = RunStatus::Diverged;
    outcome_.result.error = {ErrorKind::Diverged, {opts_.scene, 0}, "two runs in one process differ: " + determinism};
    if (listener_.note) listener_.note({RunNote::Error, outcome_.result.error});
  } else if (r.status == RunStatus::Completed) {
    publish(std::move(summary));
  } else {
    keepFailed(std::move(summary));
  }
  return outcome_;
}

// --check-determinism: the run again, in this process, with another thread count (1 after a run
// on several threads, else 2): the bytes must not depend on it either. "identical", or where
// the runs part; an interrupt of the second run is the run's interrupt ("" then: not a difference).
std::string Run::secondRun(RunResult* r) {
  SimulationOptions second = opts_.simulation;
  const int threads = second.threads > 0 ? second.threads : 1;
  second.threads = threads == 1 ? 2 : 1;
  note(RunNote::Debug, "determinism check: running the scene a second time, on " +
                           countOf(static_cast<size_t>(second.threads), "thread", "threads") + " (the first on " +
                           std::to_string(threads) + ")");
  DeterminismCheck c = checkDeterminism(model_, second, opts_.sample_interval, *first_,
                                        [this](double t, const double*) { last_sample_ = t; });
  if (c.second.status == RunStatus::Interrupted) {
    r->status = RunStatus::Interrupted;
    r->error = c.second.error;
    r->error.message += " (second run of --check-determinism)";
    return "";
  }
  if (c.same) note(RunNote::Info, "determinism check: two runs gave identical samples");
  return c.same ? "identical" : c.where;
}

void Run::publish(nlohmann::ordered_json summary) {
  const RunResult& r = outcome_.result;
  summary["trajectory"] = outputs_->paths().trajectory;
  summary["csv_bytes"] = outputs_->trajectoryBytes();
  if (!outputs_->paths().run_log.empty()) summary["run_log"] = outputs_->paths().run_log;
  Error err;
  if (!outputs_->commit(jsonText(summary), &err)) {
    outcome_.output_error = err;
    if (listener_.note) listener_.note({RunNote::Error, err});
    return;
  }
  outcome_.summary = std::move(summary);
  note(RunNote::Info, "wrote " + outputs_->paths().trajectory + " (" + countOf(r.samples, "sample", "samples") +
                          " of " + countOf(model_.bodies.size(), "body", "bodies") + ", " +
                          countOf(r.steps, "step", "steps") + " in " +
                          formatNumber(std::round(r.wall_seconds * 1000) / 1000) + " s)");
  if (!opts_.html.empty()) writePage();
}

// A failed run keeps what it computed, beside its outputs and never over them.
void Run::keepFailed(nlohmann::ordered_json summary) {
  const KeptOutputs kept = outputs_->keepPartial([&summary](const KeptOutputs& k) {
    if (!k.trajectory.empty()) summary["partial_trajectory"] = k.trajectory;
    if (!k.run_log.empty()) summary["partial_run_log"] = k.run_log;
    return jsonText(summary);
  });
  if (!kept.summary.empty()) summary["partial_summary"] = kept.summary;
  outcome_.summary = std::move(summary);
  if (listener_.note) {
    listener_.note({RunNote::Error, outcome_.result.error});
    for (const Error& e : kept.errors) listener_.note({RunNote::Error, e});
  }
  if (!kept.trajectory.empty()) note(RunNote::Info, "kept the trajectory so far in " + kept.trajectory);
  if (!kept.run_log.empty()) note(RunNote::Info, "kept the run log so far in " + kept.run_log);
}

// The replay page (simbob view) of the trajectory just written, read back as any page reads it.
void Run::writePage() {
  Trajectory actual;
  Error err;
  ViewPageInput in;
  in.model = &model_;
  in.actual = &actual;
  in.title = outputs_->paths().trajectory;
  in.scene_name = opts_.scene;
  in.texture_folder = opts_.simulation.texture_folder;
  if (!readTrajectory(outputs_->paths().trajectory, &actual, &err) || !writeViewPage(in, opts_.html, &err)) {
    outcome_.output_error = err;
    if (listener_.note) listener_.note({RunNote::Error, err});
    return;
  }
  note(RunNote::Info, "wrote " + opts_.html);
}

std::string Run::keepFromOtherThread(Error* err) { return outputs_ ? outputs_->keepFromOtherThread(err) : ""; }

}  // namespace simbob
