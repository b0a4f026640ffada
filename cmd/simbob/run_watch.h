// What `simbob run` shows and guards while it runs: the progress bar on a terminal, and the
// watchdog that keeps the partial trajectory when a stop signal finds a step that will not end.
#pragma once

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <thread>

#include <unistd.h>

#include "cli.h"

namespace simbob::cli {

class Progress {
 public:
  Progress(double duration, bool enabled) : duration_(duration), enabled_(enabled && isatty(2)) {
    start_ = std::chrono::steady_clock::now();
  }
  void update(double t) {
    if (!enabled_) return;
    double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (wall < 1.0) return;  // runs shorter than a second print no bar
    int pct = static_cast<int>(std::lround(100.0 * t / duration_));
    int bar = pct * 30 / 100;
    std::fprintf(stderr, "\r[%.*s%*s] %3d%% t=%.2f/%.2f s", bar, "##############################", 30 - bar, "", pct, t,
                 duration_);
    shown_ = true;
  }
  void done() {
    if (shown_) std::fprintf(stderr, "\n");
  }

 private:
  double duration_;
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_;
};

// The run loop sees SIGINT/SIGTERM only between steps, and one step of a pathological scene
// can take minutes. If the loop has not returned within kStopGrace of the signal, this thread
// keeps the partial trajectory (whole samples only), says so and ends the process.
class StopWatchdog {
 public:
  static constexpr auto kStopGrace = std::chrono::milliseconds(1000);

  explicit StopWatchdog(std::function<void()> on_timeout) : on_timeout_(std::move(on_timeout)) {
    thread_ = std::thread([this] { watch(); });
  }
  ~StopWatchdog() {
    quit_ = true;
    thread_.join();
  }
  StopWatchdog(const StopWatchdog&) = delete;
  StopWatchdog& operator=(const StopWatchdog&) = delete;

  /// The run loop returned: from now on the main thread finishes the command. If the watchdog
  /// has already taken over, it is ending the process: wait for that.
  void loopReturned() {
    int expected = kWatching;
    if (!state_.compare_exchange_strong(expected, kMainOwns))
      for (;;) ::pause();
  }

 private:
  enum { kWatching, kMainOwns, kWatchdogOwns };

  void watch() {
    std::chrono::steady_clock::time_point seen{};
    bool stopping = false;
    while (!quit_ && state_ == kWatching) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      if (!g_stop) continue;
      const auto now = std::chrono::steady_clock::now();
      if (!stopping) {
        stopping = true;
        seen = now;
      } else if (now - seen >= kStopGrace) {
        int expected = kWatching;
        if (state_.compare_exchange_strong(expected, kWatchdogOwns)) on_timeout_();  // does not return
        return;
      }
    }
  }

  std::function<void()> on_timeout_;
  std::atomic<int> state_{kWatching};
  std::atomic<bool> quit_{false};
  std::thread thread_;
};

}  // namespace simbob::cli
