// A run's files: see simbob/run_outputs.h.
#include <filesystem>

#include "simbob/clock.h"
#include "simbob/model.h"
#include "simbob/loop.h"
#include "simulation/outputs.h"
#include "loop/run_log.h"
#include "simbob/simulation.h"

namespace simbob {

namespace {

std::string withExtension(const std::string& path, const std::string& ext) {
  std::filesystem::path p(path);
  p.replace_extension(ext);
  return p.string();
}

}  // namespace

bool writeRefusedSummary(const std::string& trajectory, const std::string& scene, const Error& refusal, Error* err) {
  const RunOutputPaths paths = defaultOutputPaths(trajectory, false);
  if (paths.summary.empty()) return true;
  nlohmann::ordered_json summary;
  summary["simbob_version"] = SIMBOB_VERSION;
  summary["scene"] = scene;
  summary["status"] = "refused";
  summary["error"] = {{"file", refusal.loc.file},
                      {"line", refusal.loc.line},
                      {"message", refusal.message},
                      {"text", refusal.errorLine()}};
  return writeFileAtomically(partialSummaryPath(paths.summary), summary.dump(2) + "\n", err);
}

std::string partialSummaryPath(const std::string& summary) {
  std::filesystem::path p(summary);
  const std::string ext = p.extension().string();
  p.replace_extension(".partial" + ext);
  return p.string();
}

RunOutputPaths defaultOutputPaths(const std::string& trajectory, bool with_log) {
  RunOutputPaths p;
  p.trajectory = trajectory;
  if (!isStreamOutput(trajectory)) p.summary = withExtension(trajectory, ".json");
  if (with_log) p.run_log = withExtension(trajectory, ".log.csv");
  return p;
}

std::unique_ptr<RunOutputs> RunOutputs::open(const Model& model, const RunOutputPaths& paths, Error* err) {
  std::unique_ptr<RunOutputs> o(new RunOutputs());
  o->paths_ = paths;
  // Partial files are renamed onto later; a directory in the way would fail only then.
  std::error_code ec;
  for (const std::string& out : {paths.trajectory, paths.run_log})
    if (!out.empty() && !isStreamOutput(out) && std::filesystem::is_directory(partialPath(out), ec)) {
      *err = {ErrorKind::CannotCreate, {partialPath(out), 0}, "cannot create: is a directory"};
      return nullptr;
    }
  std::vector<std::string> keys;
  keys.reserve(model.bodies.size());
  for (const BodyDef& b : model.bodies) keys.push_back(b.key);
  for (const FrameDef& f : model.frames) keys.push_back(f.key);  // lumped URDF links: rows of their own
  o->trajectory_ = TrajectoryWriter::open(paths.trajectory, keys, err, paths.velocity_columns);
  if (!o->trajectory_) return nullptr;
  auto openFile = [err](const std::string& path, std::unique_ptr<OutputFile>* f) {
    if (path.empty()) return true;
    *f = OutputFile::open(path, err);
    return *f != nullptr;
  };
  if (!openFile(paths.summary, &o->summary_) || !openFile(paths.run_log, &o->log_)) return nullptr;
  if (!paths.video.empty() && !isStreamOutput(paths.video) && !openFile(paths.video, &o->video_)) return nullptr;
  return o;
}

RunOutputs::~RunOutputs() = default;  // each file not committed or kept is abandoned by its owner

void RunOutputs::attach(Simulation& sim, double sample_interval, std::function<void(double, const double*)> on_sample) {
  sim.sampleTrajectory(trajectory_.get(), sample_interval, std::move(on_sample));
  if (!log_) return;
  const Model& model = sim.model();
  const SimTime interval = std::max<SimTime>(toSimTime(sample_interval).value_or(1), 1);
  const SimTime min_step = toSimTime(model.settings.min_time_step).value_or(0);
  log_party_ = std::make_unique<RunLogParty>(model, paths_.run_log_what, interval, min_step, log_.get());
  sim.addParty(*log_party_);
}

std::string RunOutputs::videoTempPath() const { return video_ ? video_->tempPath() : std::string(); }

uint64_t RunOutputs::trajectoryBytes() const { return trajectory_->bytesWritten(); }

bool RunOutputs::streamed() const { return trajectory_->isStream(); }

bool RunOutputs::commit(const std::string& summary_text, Error* err) {
  if (log_party_) log_party_->flush();
  std::vector<OutputFile*> also;
  if (summary_) {
    summary_->write(summary_text);
    also.push_back(summary_.get());
  }
  if (log_) also.push_back(log_.get());
  if (video_) also.push_back(video_.get());
  // The trajectory and everything that describes it replace the old set together, or none does.
  return trajectory_->commit(err, also);
}

KeptOutputs RunOutputs::keepPartial(const std::function<std::string(const KeptOutputs&)>& summary_text) {
  KeptOutputs k;
  if (video_) video_->abandon();
  if (log_party_) log_party_->flush();
  Error e;
  if (!trajectory_->isStream()) {
    if (trajectory_->keepPartial(partialPath(paths_.trajectory), &e))
      k.trajectory = partialPath(paths_.trajectory);
    else
      k.errors.push_back(e);
  } else if (!trajectory_->keepPartial("", &e)) {  // what went through stays; nothing to rename
    k.errors.push_back(e);
  }
  if (log_ && !log_->isStream()) {
    if (log_->close(&e) && log_->rename(partialPath(paths_.run_log), &e))
      k.run_log = partialPath(paths_.run_log);
    else
      k.errors.push_back(e);
  }
  if (summary_) {
    // The summary's new version is not published over the old one: it goes beside it.
    const std::string path = partialSummaryPath(paths_.summary);
    summary_->write(summary_text(k));
    if (summary_->close(&e) && summary_->rename(path, &e))
      k.summary = path;
    else
      k.errors.push_back(e);
  }
  return k;
}

void RunOutputs::abandon() {
  trajectory_->abandon();
  for (OutputFile* f : {summary_.get(), log_.get(), video_.get()})
    if (f) f->abandon();
}

std::string RunOutputs::keepFromOtherThread(Error* err) {
  for (OutputFile* f : {summary_.get(), log_.get(), video_.get()})
    if (f) f->abandon();  // the run's thread may be writing the log: keep none of it
  const std::string partial = partialPath(paths_.trajectory);
  if (!trajectory_->keepPartialFromOtherThread(partial, err)) return "";
  return trajectory_->isStream() ? "" : partial;
}

}  // namespace simbob
