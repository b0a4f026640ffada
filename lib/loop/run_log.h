// The run log (`simbob run --log joints,sensors,commands`): what the robots did, sampled at the
// trajectory's times, as a long-format CSV `time,component,quantity,value` (docs/formats.md, "Log format").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "simbob/error.h"
#include "simbob/tool/files.h"
#include "simbob/model.h"
#include "simbob/loop.h"

namespace simbob {

/// The exact header line of a run log (without the line end).
inline constexpr const char* kRunLogHeader = "time,component,quantity,value";

/// A party that writes the log rows. Put it after every controller: at each sample time it
/// records the state after the controllers of that instant acted (the world does not move
/// within an instant, so joint positions are those of the trajectory's sample). It samples at
/// exactly the trajectory sampler's times (same interval and MinTimeStep, and the final
/// sample of a completed run) by running a sampler of its own for the timing.
class RunLogParty : public Party {
 public:
  /// `out` must outlive the party; `interval` and `min_step` in ns as for TrajectorySampler.
  RunLogParty(const Model& model, RunLogWhat what, SimTime interval, SimTime min_step, OutputFile* out);
  /// Flushes what is buffered: a failed run's log keeps every row recorded.
  ~RunLogParty() override;
  RunLogParty(const RunLogParty&) = delete;
  RunLogParty& operator=(const RunLogParty&) = delete;
  SimTime first() override;
  SimTime onGrant(SimTime now, World& world) override;
  void finish(SimTime end, World& world) override;
  /// IoError naming the log once a write failed.
  const Error* failure() const override;
  /// Writes what is still buffered (call before committing or keeping the output).
  bool flush();

 private:
  void record(double t, const World& world);

  RunLogWhat what_;
  std::vector<std::string> joint_keys_, sensor_keys_, actuator_keys_;  // CSV-encoded
  std::vector<std::vector<std::string>> sensor_quantities_;            // per sensor (sensorQuantities)
  std::vector<int> joints_;                                            // hinges and sliders
  TrajectorySampler timing_;
  OutputFile* out_;
  std::string buf_;
  bool pending_ = false;
  double pending_t_ = 0;
  Error error_;
};

}  // namespace simbob
