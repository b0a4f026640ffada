// Private to lib/robot: the peer program an RCLocalSocketCommunicator starts itself (its
// Controller), and everything that program starts, ended with the run (peer_process.cpp says how).
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace simbob::robot {

class PeerProcess {
 public:
  /// The log keeps this much of the head and of the tail of the output (bytes each).
  static constexpr size_t kLogHead = size_t{4} << 20, kLogTail = size_t{4} << 20;

  PeerProcess() = default;
  ~PeerProcess() { end(); }
  PeerProcess(const PeerProcess&) = delete;
  PeerProcess& operator=(const PeerProcess&) = delete;

  /// Starts `words` (words[0] found on PATH unless it holds a '/') in `dir` ("" = ours), with
  /// `env` added to our environment, stdout and stderr to `log` ("" = our stderr), of which the
  /// first `log_head` and the last `log_tail` bytes are kept. Empty on success, else why it
  /// could not start (one line).
  std::string start(const std::vector<std::string>& words, const std::string& dir,
                    const std::vector<std::pair<std::string, std::string>>& env, const std::string& log,
                    size_t log_head = kLogHead, size_t log_tail = kLogTail);
  bool started() const { return keeper_ > 0; }
  /// True once the program has exited, with `how` = "exited with status N" or "was killed by
  /// signal N (NAME)".
  bool exited(std::string* how);
  /// Ends the program and every process it started, whatever session or group they moved to:
  /// waits up to `linger` s for all of them to exit by themselves, then they get SIGTERM, and
  /// SIGKILL after `grace` s. Returns once none is left and the log is complete.
  void end(double linger = 0, double grace = 2.0);

 private:
  bool keeperGone(double seconds);

  pid_t keeper_ = -1;   ///< the process that started the program and reaps all it started
  int control_ = -1;    ///< our end of the keeper's control pipe: closing it ends everything
  int status_fd_ = -1;  ///< the keeper writes the program's wait status here
  bool reaped_ = false;
  int status_ = 0;
};

}  // namespace simbob::robot
