// A whole run of a scene: the one object that `simbob run` (and so the workers of `batch` and
// `sweep run`), `render --at`, and Python's simbob.run() go through, as MuJoCo's mjModel/mjData
// serve its C API, its Python and its viewer. A Run
//   - loads the scene (loadModel: files read, content hash, warnings),
//   - refuses what cannot run, before any output exists (a body beyond the runaway limit at t = 0,
//     a time the clock cannot hold, an output that would replace an input or another output),
//   - owns the Simulation and its outputs: trajectory, summary, run log, controllers' log,
//     recording (PNG frames, video) and the replay page, opened under temporary names,
//   - runs it, checks determinism when asked, explains a divergence from the scene's own checks,
//     and commits every output together -- or, for a run that failed, keeps what it computed
//     beside them (.partial files) with a summary that says why.
// What it has to say (notes, warnings) goes to a listener as it happens; what came of it is a
// RunOutcome, errors as values with their place. The caller decides exit statuses and prints.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "simbob/compile.h"
#include "simbob/error.h"
#include "simbob/options.h"
#include "simbob/registry.h"
#include "simbob/renderer.h"
#include "simbob/loop.h"
#include "simbob/simulation.h"

namespace simbob {

/// Everything a run takes: what runs, how, and what it writes. Each default is written here
/// once; the CLI binds its options to these fields and Python its keyword arguments.
struct RunOptions {
  // ---- what runs ----
  std::string scene;                      ///< the scene file (XML, INI by extension); with scene_text, its name
  std::optional<std::string> scene_text;  ///< the scene's text in memory, instead of reading `scene`
  SimulationOptions simulation;           ///< overrides, seed, step, duration, peers, limits
  double sample_interval = 0.01;          ///< s of simulated time between trajectory samples
  bool check_determinism = false;         ///< run twice in this process; publish only identical runs
  /// Say the scene's warnings: the loader's, and `simbob check`'s for the step taken (batch
  /// workers: false, their parent shows what matters).
  bool warnings = true;

  // ---- what it writes ----
  bool write_outputs = true;  ///< false: no trajectory, summary or logs at all (render --at)
  /// The trajectory CSV: "" = the scene's name with .csv in the current folder; "-" stdout (or a
  /// device, a FIFO: written through). Its summary goes beside it as .json.
  std::string out;
  bool velocity_columns = false;  ///< the trajectory's velocity block (--columns pose,velocity)
  RunLogWhat log;                 ///< what the run log records (nothing: no run log)
  std::string log_out;            ///< the run log ("" = the trajectory's name with .log.csv)
  /// The controllers simbob starts print to OUT.controller.log (their stderr when the trajectory
  /// is a stream); false: to simbob's stderr.
  bool controller_log = true;
  std::string record;    ///< frames as DIR/frame_000000.png ("" = none)
  std::string video;     ///< FILE.avi (MJPEG) or FILE.mp4 (H.264) ("" = none)
  RenderOptions render;  ///< the recording's view (size, camera, quality, back end, what to draw)
  double fps = 30;       ///< frames per simulated second of --record and --video
  std::string html;      ///< the replay page of the run, written after it ("" = none)
  /// A run refused before it starts writes a partial summary with its error (batch and sweep
  /// workers: their parent reads every outcome from summaries).
  bool refusal_summary = false;
  /// Other files the caller reads (--settings) and writes (--log-file): no output of the run may
  /// be one of them.
  std::vector<NamedPath> inputs, outputs;
};

/// What a run says as it goes, in order: level and text, with a place when there is one.
struct RunNote {
  enum Level { Debug, Info, Warning, Error } level = Info;
  simbob::Error what;  ///< message and place (for an error, its kind too)
};

/// Who hears what a run says. Both may be empty.
struct RunListener {
  std::function<void(const RunNote&)> note;
  /// Every file the run reads (scene, imports, textures, the caller's inputs), once the scene is
  /// loaded and before anything else is said: a caller that appends to a file of its own (a log)
  /// stops when it is one of them.
  std::function<void(const std::vector<NamedPath>&)> inputs;
};

/// What came of a run.
// Its implicit constructor is noexcept; clang-tidy finds a throw inside nlohmann::ordered_json's
// noexcept default constructor (an allocation for other kinds of value), not in this struct.
// NOLINTNEXTLINE(bugprone-exception-escape)
struct RunOutcome {
  RunResult result;  ///< status, error (with its place and kind), divergence, steps, times
  /// The run summary as written (docs/formats.md); for a failed run, as kept (.partial.json).
  nlohmann::ordered_json summary;
  /// --check-determinism: "identical", or where the two runs part ("" when not asked, or the
  /// second run was interrupted).
  std::string determinism;
  /// A completed run whose outputs could not be written (the commit, the replay page): why.
  std::optional<simbob::Error> output_error;
};

/// The files a run with these options writes, named as the CLI's messages name them: the
/// trajectory ("--out"), its summary and partial files, the controllers' log, the run log, the
/// video and the replay page. For checking them against other files before the run.
std::vector<NamedPath> runOutputFiles(const RunOptions& opts);

/// What is wrong with the options themselves, before any scene is read ("" if nothing): times
/// the clock cannot hold, a peer timeout or port offset out of range, a page that cannot read a
/// streamed trajectory back. Run::open refuses them; the CLI checks a batch manifest's lines
/// with it.
std::string runOptionsProblem(const RunOptions& opts);

/// Where a run whose trajectory is `trajectory` writes its summary when it fails or is refused
/// ("out.csv" -> "out.partial.json"; "" for a streamed trajectory, which has no summary).
std::string partialSummaryOf(const std::string& trajectory);

class Run {
 public:
  /// Loads and compiles the scene, refuses what cannot run and opens every output under a
  /// temporary name. nullptr with the reason in *refusal (kind and place; nothing written but the
  /// refusal summary, when asked for). Notes and warnings go to `listener` (may be empty).
  static std::unique_ptr<Run> open(RunOptions opts, const Registry& reg, RunListener listener, Error* refusal);
  ~Run();
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  const RunOptions& options() const { return opts_; }
  const LoadReport& load() const { return load_; }
  const Model& model() const { return model_; }
  /// The Simulation: add parties before finish() (render's still, a test's probe). It is gone
  /// once finish() returns.
  Simulation& simulation() { return *sim_; }

  /// Runs to the duration, checks determinism when asked, and commits every output (a
  /// completed run) or keeps the partial ones (a run that stopped), then writes the replay page.
  /// Once; later calls return the same outcome.
  const RunOutcome& finish();

  /// The time of the last whole sample written (s), readable from any thread.
  double lastSampleTime() const { return last_sample_; }
  /// From another thread, while finish() may be stuck inside a step (a stop signal that does not
  /// end it): keeps the trajectory's complete samples, abandons the rest. Only right before the
  /// process ends. The kept path, or "" (and *err when keeping failed).
  std::string keepFromOtherThread(Error* err);

 private:
  Run() = default;  // NOLINT(bugprone-exception-escape): see RunOutcome
  bool prepare(const Registry& reg, Error* refusal);
  bool openOutputs(Error* refusal);
  void beforeRun();
  std::string secondRun(RunResult* r);
  void publish(nlohmann::ordered_json summary);
  void keepFailed(nlohmann::ordered_json summary);
  void writePage();
  void note(RunNote::Level level, const std::string& text, SourceLoc loc = {});

  RunOptions opts_;
  RunListener listener_;
  LoadReport load_;
  Model model_;                    ///< as compiled (the Simulation has its own copy, gone after the run)
  std::vector<NamedPath> inputs_;  ///< every file the run reads: no output may replace one
  std::unique_ptr<Simulation> sim_;
  std::unique_ptr<class RunOutputs> outputs_;
  std::unique_ptr<class Recording> recording_;
  std::unique_ptr<class SampleRecord> first_;  ///< --check-determinism: the first run's samples
  std::atomic<double> last_sample_{0.0};
  RunOutcome outcome_;
  bool finished_ = false;
};

}  // namespace simbob
