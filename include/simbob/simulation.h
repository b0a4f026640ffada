// The Simulation API: one object owns a run -- the compiled scene, the world, the clock on its
// fixed step grid, and the parties that watch and drive it (trajectory sampler, controllers,
// socket peers, run log, recorder, and the caller's own). The CLI (`simbob run`), tests and the
// Python module are its clients, as MuJoCo's mjModel/mjData serve its C API, Python and viewer.
//
// A Simulation is stepped in whole steps of h (step(n), runUntil(t)); at each grid instant it
// reaches, every party due there is served first (sampler, camera sensors, then controllers and
// peers in scene order, then parties added here, in the order added). Between calls the caller
// reads the state and sets commands: a command set between calls applies from the current instant
// on, after the controllers served there (as a socket peer's does). Same scene + seed = same
// bytes, however the simulation is stepped or watched.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "simbob/error.h"
#include "simbob/graph.h"
#include "simbob/renderer.h"
#include "simbob/model.h"
#include "simbob/options.h"
#include "simbob/overrides.h"
#include "simbob/physics.h"
#include "simbob/registry.h"
#include "simbob/loop.h"
#include "simbob/trajectory.h"

namespace simbob {

/// What the run summary says of a run beyond its model and result.
struct RunSummaryInput {
  std::string scene;       ///< the scene path as given
  std::string scene_hash;  ///< hash of the scene and its imports (fnv1a64w, docs/formats.md), hex
  double duration = 0;     ///< s asked for
  double sample_interval = 0;
  uint32_t seed = 0;
  std::vector<std::string> overrides;  ///< KEY.PARAM=VALUE, as applied
};

/// "completed", "diverged", "interrupted" or "failed".
const char* runStatusName(RunStatus s);

/// The folder communicator `d`'s Controller runs in, absolute (the scene's folder, or the
/// current one for --controller).
std::string controllerFolder(const SocketDef& d);

/// The run summary JSON (docs/formats.md): version, scene, status, step, times, settings,
/// counts, speed (waiting for peers excluded) and what reproducibility depends on. Clients
/// add what only they know (outputs written, frames, a determinism check).
nlohmann::ordered_json runSummary(const Model& model, const RunResult& r, const RunSummaryInput& in);

class CameraSensors;

class Simulation {
 public:
  /// Loads a scene file (XML or INI), applies the overrides, compiles and checks it. Null on
  /// failure, with the errors (file:line) in diag; warnings (load and `simbob check`'s) go to
  /// diag too.
  static std::unique_ptr<Simulation> fromFile(const std::string& path, const Registry& reg,
                                              const SimulationOptions& opts, Diagnostics& diag);
  /// The same from scene text in memory; `name` stands for the file in messages and imports.
  /// The format is the name's (sceneFormatOf: INI for .ini).
  static std::unique_ptr<Simulation> fromText(const std::string& text, const std::string& name, const Registry& reg,
                                              const SimulationOptions& opts, Diagnostics& diag);
  /// From a compiled Model (the CLI compiles it itself to report inputs). Null with the error in
  /// diag when an option does not fit the model (a port beyond 65535, a step beyond the clock).
  static std::unique_ptr<Simulation> fromModel(Model model, const SimulationOptions& opts, Diagnostics& diag);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  const Model& model() const { return model_; }
  const SimulationOptions& options() const { return opts_; }

  // ---- outputs and parties (before the first step; they run from t = 0) ----
  /// Samples every body's pose at t = 0, interval, 2 interval, ... (each at the first grid
  /// instant at or after it) and at the end, to `writer` (may be null) and `on_sample` (may be
  /// empty); the writer must outlive the Simulation. The sampler is always the first party.
  void sampleTrajectory(TrajectoryWriter* writer, double interval,
                        std::function<void(double, const double*)> on_sample = nullptr);
  /// A party of the caller's, served after the scene's controllers and peers, in the order
  /// added. May be added at any time: it asks for its first request at the current instant.
  void addParty(std::unique_ptr<Party> party);
  /// The same for a party owned elsewhere (it must outlive the run).
  void addParty(Party& party);

  // ---- running ----
  /// Serves the current instant, then takes n whole steps, serving each instant reached.
  /// False once the run has stopped (diverged, failed, interrupted): result() says why.
  bool step(uint64_t n = 1);
  /// Serves and steps to the first grid instant at or after t (s). False once stopped.
  bool runUntil(double t);
  /// Runs to options().duration and completes the run: runUntil(duration), then finish().
  const RunResult& runToEnd();
  /// Ends the run: every party hears of the end (the sampler records the final state) or, if
  /// the run stopped, why. Nothing can be stepped afterwards until reset().
  const RunResult& finish();
  /// Back to t = 0 with a new seed: a fresh world and fresh scene controllers; the caller's
  /// parties stay and are asked for their first request again; the trajectory output is
  /// detached (a run's files belong to one run). False if the world cannot be built.
  bool reset(uint32_t seed);

  /// The result so far (status Completed only after finish() of a run that did not stop).
  const RunResult& result() const;
  /// True until the run has stopped (diverged, failed, interrupted) or finished.
  bool running() const;

  // ---- state (at the current grid instant) ----
  double time() const;
  SimTime now() const;
  uint64_t steps() const;
  double stepSize() const;  ///< s: the step h actually taken
  const World& world() const;
  World& world();
  /// Index of the body, joint, actuator or sensor with this fully qualified key; -1 if none.
  int body(const std::string& key) const;
  int joint(const std::string& key) const;
  int actuator(const std::string& key) const;
  int sensor(const std::string& key) const;
  /// The latest image of the RCCameraSensor with this fully qualified key (RGB, rows top first,
  /// Width x Height): drawn at the grid instants at or after t = 0, Period, 2 Period, ... before
  /// the controllers there are served, and held in between. Null if there is no such sensor.
  const Image* cameraImage(const std::string& key) const;
  /// Commands actuator i from the current instant on (clamped by its limits, as controllers'
  /// commands are). An index out of range is an error value, not a crash.
  Error setCommand(int actuator, double value);

 private:
  explicit Simulation(Model model, SimulationOptions opts);
  bool start();

  Model model_;
  SimulationOptions opts_;
  std::unique_ptr<TrajectorySampler> sampler_;
  TrajectoryWriter* writer_ = nullptr;
  double sample_interval_ = 0.01;
  std::function<void(double, const double*)> on_sample_;
  bool sampling_ = false;
  std::vector<std::unique_ptr<Party>> robot_;  ///< the scene's controllers and peers
  std::vector<std::unique_ptr<Party>> owned_;  ///< the caller's parties this owns
  std::vector<Party*> extra_;                  ///< the caller's parties, in the order added
  RunResult final_;                            ///< what finish() returned (samples counted)
  std::unique_ptr<Runner> runner_;
  std::unique_ptr<CameraSensors> cameras_;  ///< null unless the scene has camera sensors
};

}  // namespace simbob
