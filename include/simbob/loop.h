// The run loop (guide 7.2): a world built from a Model, stepped in whole steps on the clock's
// fixed grid, and the parties that need the simulation at given times -- the trajectory sampler,
// controllers, socket peers, recorders, the run log, a caller's own -- each granted the world
// alone at the first grid instant at or after its request. Every step is checked for a
// non-finite or runaway state. The Simulation API (simbob/simulation.h) drives a Runner.
#pragma once

#include <chrono>
#include <csignal>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "simbob/clock.h"
#include "simbob/error.h"
#include "simbob/model.h"
#include "simbob/options.h"
#include "simbob/physics.h"
#include "simbob/trajectory.h"

namespace simbob {

class World;
class Party;

enum class RunStatus { Completed, Diverged, Interrupted, Failed };

/// What diverged, as data: the body that ran away or the joint that came apart (the error's
/// message says it in words; explainDivergence looks for a cause with these indices).
struct RunDivergence {
  int body = -1;     ///< index into Model::bodies: non-finite or beyond the runaway limit (-1: none)
  int joint = -1;    ///< index into Model::joints: came apart (-1: none)
  double apart = 0;  ///< m between that joint's anchors on its two bodies
  double time = 0;   ///< s of simulated time it was found at
};

struct RunResult {
  RunStatus status = RunStatus::Failed;
  Error error;               ///< set unless Completed: Diverged, Interrupted, ControllerFailed, Unavailable, ...
  RunDivergence divergence;  ///< status Diverged: what diverged
  uint64_t steps = 0;
  double sim_time = 0.0;  ///< s reached
  uint64_t samples = 0;   ///< trajectory samples (counted by the Simulation's sampler)
  double wall_seconds = 0.0;
  /// Of wall_seconds, the part spent in the parties' first() calls: waiting for socket peers
  /// to connect (bounded by --peer-timeout, not MaxAccessTime). Not simulation work.
  double wait_seconds = 0.0;
  double dt = 0.0;                   ///< the step taken: dt (or MaxTimeStep) on the nanosecond grid
  PhysicsMessages physics_messages;  ///< what ODE reported during the run (World::physicsMessages)
};

/// Something that needs the simulation at given simulated times (guide 7.2): a sampler, a
/// controller, a recorder, an external peer. It says when it next needs the world; the run loop
/// grants it the world at that time, alone: nothing else runs while it acts.
class Party {
 public:
  virtual ~Party();
  /// Its first request (ns of simulated time), or kNever. Called once, after the world is built.
  virtual SimTime first() = 0;
  /// The clock reached `now`, within MinTimeStep of its request. It may read the world and act
  /// on it (never step it). Returns its next request (> now), or kNever to ask no more.
  virtual SimTime onGrant(SimTime now, World& world) = 0;
  /// Called once when the run completes (reached its duration `end`), after the last grant;
  /// not when it fails.
  virtual void finish(SimTime end, World& world);
  /// Non-null once the party cannot go on (its output failed, ...): the run stops with status
  /// Failed and this error. Checked after the grants of each instant (the last one too).
  virtual const Error* failure() const;
  /// Called once when the run ends without completing (diverged, interrupted, failed), with
  /// the reason: a party that talks to another program tells it (a socket peer's `error` line).
  virtual void abandon(const Error& why);

  /// MaxAccessTime (guide 7.2): the wall-clock seconds one call of first() or onGrant() may
  /// take; the run loop sets it before first(). The run loop measures every call and stops the
  /// run (ErrorKind::Unavailable) after one that took longer. It cannot cut a call short: a party
  /// that can block (a socket peer) must use accessDeadline() as its own timeout.
  double accessLimit() const { return access_limit_; }
  /// When the current call of first() or onGrant() must have returned (steady clock).
  std::chrono::steady_clock::time_point accessDeadline() const { return access_deadline_; }
  /// Whether the run was asked to stop (SIGINT/SIGTERM, SimulationOptions::stop): a party that waits
  /// for another program checks it while it waits and returns, so the run can end.
  bool stopRequested() const { return stop_ != nullptr && *stop_ != 0; }
  /// For messages: "controller 'Bot.Plan'", and where it is defined (empty: unknown).
  std::string name = "a party of the run";
  SourceLoc loc;

 private:
  friend class Runner;
  double access_limit_ = 1.0;
  std::chrono::steady_clock::time_point access_deadline_{};
  const volatile std::sig_atomic_t* stop_ = nullptr;
};

/// One run in progress: the world, the clock on its fixed grid and the parties, advanced piece
/// by piece (create / grant / advance / complete) so that a caller can step it in pieces
/// (Simulation, Python) or to the end. Not copyable; one thread at a time.
class Runner {
 public:
  /// Builds the world (seeded with opts.seed) and asks each party for its first request. A time
  /// that does not fit the clock or a world that cannot be built stops the run at once (see
  /// result()). The model must outlive the runner; so must the parties.
  Runner(const Model& model, const SimulationOptions& opts, std::vector<Party*> parties);
  ~Runner();
  Runner(const Runner&) = delete;
  Runner& operator=(const Runner&) = delete;

  /// A party joining the run now: its first() is asked at the current instant (after the
  /// parties already there in tie order).
  void addParty(Party& p);
  /// Grants every due party at the current instant (idempotent: a party is granted at most
  /// once per instant) and checks their failures. False once the run has stopped.
  bool grantDue();
  /// One whole step of the world (unless a stop was requested), then the divergence checks.
  /// False once the run has stopped.
  bool advance();
  /// Serves and steps until the first grid instant at or after `t`, its grants included.
  bool runUntil(SimTime t);
  /// Serves the current instant, then `n` whole steps, each followed by the grants due there.
  bool step(uint64_t n);
  /// Ends the run once: finish() to every party if it has not stopped (status Completed), else
  /// abandon(why). The result, with wall time and the time reached.
  const RunResult& complete();

  /// False once stopped: diverged, failed, interrupted (result() says which and why).
  bool running() const { return !stopped_; }
  const RunResult& result() const { return res_; }
  /// opts.duration on the clock.
  SimTime end() const { return end_; }
  const Clock& clock() const { return clock_; }
  /// Null only when the world could not be built (result() says why).
  World* world() { return world_.get(); }
  const World* world() const { return world_.get(); }

 private:
  void enroll(Party& p);
  void stop(RunStatus status, Error e);

  const Model& model_;
  SimulationOptions opts_;
  std::vector<Party*> parties_;
  std::unique_ptr<World> world_;
  Clock clock_{1, 0};
  RunResult res_;
  SimTime end_ = 0;
  double limit_ = 1.0;
  std::chrono::steady_clock::duration limit_d_{};
  std::chrono::steady_clock::time_point wall0_;
  SimTime progress_every_ = 1, next_progress_ = 1;
  bool stopped_ = false;
  bool completed_ = false;
};

/// The trajectory sampler: sample n asks for t = n interval and records the first grid instant
/// at or after it (the time written is that instant); the next request is the first multiple of
/// the interval beyond MinTimeStep from it, so an interval below the step samples every step.
/// Once more at the end of a completed run unless a sample was just taken there.
class TrajectorySampler : public Party {
 public:
  /// `interval` >= 1 ns, `min_step` the scene's MinTimeStep in ns. Samples go to `writer`
  /// (may be null) and `on_sample` (may be empty). The rows of `frames` (Model::frames: lumped
  /// URDF links) follow the bodies' rows.
  TrajectorySampler(int body_count, SimTime interval, SimTime min_step, TrajectoryWriter* writer,
                    std::function<void(double, const double*)> on_sample, std::vector<FrameDef> frames = {});
  SimTime first() override;
  SimTime onGrant(SimTime now, World& world) override;
  void finish(SimTime end, World& world) override;
  /// IoError naming the output once a trajectory write failed.
  const Error* failure() const override;
  uint64_t samples() const { return samples_; }

 private:
  void sample(SimTime now, const World& world);

  SimTime interval_;
  SimTime min_step_;
  TrajectoryWriter* writer_;
  std::function<void(double, const double*)> on_sample_;
  std::vector<FrameDef> frames_;
  std::vector<double> poses_;
  SimTime next_ = 0;
  SimTime last_ = -1;  ///< time of the last sample, -1 before the first
  uint64_t samples_ = 0;
  Error error_;
};

/// What a run log records (`--log joints,sensors,commands`; docs/formats.md, "Log format").
struct RunLogWhat {
  bool joints = false;    ///< every hinge and slider joint: pos, vel (World::joint)
  bool sensors = false;   ///< every sensor: each quantity of its reading (World::sensorReading)
  bool commands = false;  ///< every actuator: command (World::command)
  bool any() const { return joints || sensors || commands; }
};

/// Parses "joints,sensors,commands" (any non-empty comma list of those words, repeats allowed).
/// On an unknown or empty word returns false and sets *problem to a one-line message.
bool parseRunLogWhat(const std::string& list, RunLogWhat* what, std::string* problem);

/// Frame n of a recording at `fps` asks for t = n / fps (kNever beyond the clock's range); it
/// shows the first grid instant at or after that time, while a video keeps the nominal n / fps
/// timestamps.
SimTime frameTime(uint64_t n, double fps);

/// What a run should say once about its observers and the step grid: a sample interval or a
/// frame rate (0: no recording) whose times are not whole multiples of `step` (samples and
/// frames show the first grid instant at or after their nominal times), and a sample interval
/// below the step (a sample every step). Empty when everything lands on the grid.
std::vector<std::string> gridNotes(double step, double sample_interval, double fps);

/// What a run says once when ODE reported anything while stepping (RunResult::physics_messages,
/// count > 0): how many, the first and when, and what it means for the motion.
std::string physicsMessagesWarning(const PhysicsMessages& m);

/// "out.csv" -> "out.partial.csv" (the trajectory kept by a failed or interrupted run).
std::string partialPath(const std::string& out);

}  // namespace simbob
