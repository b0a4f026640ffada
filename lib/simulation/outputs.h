// The files one run writes (docs/formats.md): the trajectory, its summary, the run log and the
// video. All are opened under temporary names before the run starts, so that a run never ends in
// "cannot create" after simulating for an hour. A completed run commits them together: every
// final path gets its new file, or none does. A run that fails keeps what it computed beside its
// outputs, never over them: the trajectory and run log so far as .partial files, and its summary
// (status and error) as the summary's .partial.json.
//
// The Run (simbob/scene_run.h) attaches these to its Simulation; the Simulation itself knows
// nothing of files.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "simbob/error.h"
#include "simbob/tool/files.h"
#include "simbob/loop.h"
#include "simbob/trajectory.h"

namespace simbob {

class Simulation;
struct Model;

/// Where a run's outputs go. Only `trajectory` is required.
struct RunOutputPaths {
  std::string trajectory;         ///< "-" (stdout), a device or FIFO is written through
  std::string summary;            ///< "" for none (a streamed trajectory has none)
  std::string run_log;            ///< "" without a run log
  RunLogWhat run_log_what;        ///< what the run log records
  std::string video;              ///< "" for none; committed with the others (a stream is written through)
  bool velocity_columns = false;  ///< the trajectory's velocity block (--columns pose,velocity)
};

/// The default paths beside a trajectory: "out.csv" -> summary "out.json", run log
/// "out.log.csv" (when `with_log`), and their partial names. A streamed trajectory has no summary.
RunOutputPaths defaultOutputPaths(const std::string& trajectory, bool with_log);

/// "out.json" -> "out.partial.json": where a failed run writes its summary.
std::string partialSummaryPath(const std::string& summary);

/// The partial summary of a run refused before it started (its scene does not load or cannot
/// run), beside `trajectory` as for a failed run: simbob_version, scene, status "refused" and
/// error. `simbob batch` and `sweep run` ask their workers for it (run --refusal-summary), so
/// they learn every failed worker's outcome from its summary. False (and `err`) if it cannot be
/// written; nothing for a streamed trajectory.
bool writeRefusedSummary(const std::string& trajectory, const std::string& scene, const Error& refusal, Error* err);

/// What a failed run kept, for its summary and its messages.
struct KeptOutputs {
  std::string trajectory;     ///< the .partial.csv kept ("" if none: a stream, or it failed)
  std::string run_log;        ///< the run log's .partial.csv ("" if none)
  std::string summary;        ///< the .partial.json written ("" if none)
  std::vector<Error> errors;  ///< what could not be kept, and why
};

class RunOutputs {
 public:
  /// Creates every output's temporary file now. nullptr and *err (ErrorKind::CannotCreate or
  /// IoError, naming the path) when one cannot be made; nothing is left behind then.
  static std::unique_ptr<RunOutputs> open(const Model& model, const RunOutputPaths& paths, Error* err);
  ~RunOutputs();
  RunOutputs(const RunOutputs&) = delete;
  RunOutputs& operator=(const RunOutputs&) = delete;

  /// Makes `sim` write here: its trajectory sampler (every `sample_interval` s; `on_sample`, if
  /// given, also sees each sample) and the run log as one of its parties. The Simulation must be
  /// of the model these outputs were opened for, and must not outlive them.
  void attach(Simulation& sim, double sample_interval, std::function<void(double, const double*)> on_sample = nullptr);

  const RunOutputPaths& paths() const { return paths_; }
  /// The file a video encoder should write ("" when there is no video or it is a stream).
  std::string videoTempPath() const;
  /// Bytes of trajectory produced so far (its size once committed).
  uint64_t trajectoryBytes() const;
  /// Whether the trajectory is written through (stdout, a device) rather than renamed.
  bool streamed() const;

  /// A completed run: writes `summary_text` into the summary and commits every output together.
  /// False and *err if a write failed or a rename did (then no final path changed).
  bool commit(const std::string& summary_text, Error* err);
  /// A failed run: abandons the video and the summary's new version, keeps the trajectory and run
  /// log as their .partial files, and writes summary_text(what was kept) -- the run's summary,
  /// with its status and error -- to the summary's .partial.json.
  KeptOutputs keepPartial(const std::function<std::string(const KeptOutputs&)>& summary_text);
  /// Nothing of this run is published (a failed determinism check): every temporary file goes.
  void abandon();
  /// From another thread, while the run's thread may be stopped anywhere (an interrupt whose step
  /// does not end): keeps the trajectory's complete samples, abandons the rest. Only right before
  /// the process ends. The kept path, or "" (and *err when keeping failed).
  std::string keepFromOtherThread(Error* err);

 private:
  RunOutputs() = default;
  RunOutputPaths paths_;
  std::unique_ptr<TrajectoryWriter> trajectory_;
  std::unique_ptr<OutputFile> summary_;
  std::unique_ptr<OutputFile> log_;
  std::unique_ptr<OutputFile> video_;
  std::unique_ptr<class RunLogParty> log_party_;
};

}  // namespace simbob
