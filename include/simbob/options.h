// How a simulation runs, as plain data: the one options struct of the Simulation API and of the
// run loop under it, with its defaults (simbob/scene_run.h adds what a whole run writes). The
// CLI binds its options to these fields and Python its keyword arguments, so a default is
// written once, here, and nothing is copied field by field between layers.
#pragma once

#include <csignal>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "simbob/overrides.h"
#include "simbob/visuals.h"

namespace simbob {

struct SimulationOptions {
  std::vector<Override> overrides;  ///< applied to the scene before compiling (--set)
  uint32_t seed = 0;                ///< ODE's random generator (QuickStep constraint order)
  double dt = 0.0;                  ///< s; 0 = the scene's MaxTimeStep (resolvedStep)
  /// Threads one world's step may use, 1 to 64 (--threads); 0 = the scene's SceneSettings
  /// Threads (default 1). Never changes a result: every thread count gives the same bytes.
  int threads = 0;
  double duration = 1e9;         ///< s: the end a run to completion stops at (runToEnd)
  double max_access_time = 0.0;  ///< s of wall clock one grant may take; 0 = the scene's MaxAccessTime
  double peer_timeout = 10.0;    ///< s a socket peer may take to connect or answer
  int port_offset = 0;           ///< added to every RCLocalSocketCommunicator's Port
  /// "KEY=COMMAND": the Controller of communicator KEY, in place of the scene's (run --controller;
  /// paths relative to the current folder; "KEY=" = none, its peer is started by hand).
  std::vector<std::string> controllers;
  /// The file that takes the stdout and stderr of the controllers simbob starts ("" = simbob's
  /// stderr); with several, ".KEY" is added to the name of each.
  std::string controller_log;
  /// Refuse a scene whose communicators would start a program (--no-controllers): for scenes
  /// from others; a peer of one's own connects with controllers = {"KEY="}.
  bool no_controllers = false;
  double runaway_limit = 1e6;      ///< |position| in m or |velocity| in m/s, rad/s beyond which a run diverged
  double joint_apart_limit = 0.1;  ///< m between a joint's anchors on its two bodies beyond which it came apart
  /// Set asynchronously (SIGINT/SIGTERM) to stop at the next step.
  const volatile std::sig_atomic_t* stop = nullptr;
  /// Called about every 1% of `duration` with the simulated time reached.
  std::function<void(double)> progress;
  /// Camera sensors' renderer (RCCameraSensor): GL back end and global TextureFolder.
  GlBackend gl = GlBackend::Auto;
  std::string texture_folder;
};

/// The step a run takes (s): the --dt option when given (> 0), else the scene's MaxTimeStep.
inline double resolvedStep(double dt_option, double max_time_step) { return dt_option > 0 ? dt_option : max_time_step; }

/// Times the nanosecond clock holds with room (simbob/clock.h): options and parameters that are
/// a time in seconds lie in [kMinClockTime, kMaxClockTime].
constexpr double kMinClockTime = 1e-9;
constexpr double kMaxClockTime = 1e9;

/// "" when `seconds` is a time the clock holds (finite, in [kMinClockTime, kMaxClockTime], or 0
/// with `zero_allowed`: "not given"), else what is wrong: "NAME must be between 1e-9 and 1e9 s,
/// got X".
std::string clockTimeProblem(const std::string& name, double seconds, bool zero_allowed = false);

}  // namespace simbob
