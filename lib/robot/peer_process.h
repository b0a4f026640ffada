// Private to lib/robot: the peer program an RCLocalSocketCommunicator starts itself (its
// Controller): a child process in a process group of its own, ended with the run.
#pragma once

#include <sys/types.h>

#include <string>
#include <utility>
#include <vector>

namespace simbob::robot {

class PeerProcess {
 public:
  PeerProcess() = default;
  ~PeerProcess() { end(); }
  PeerProcess(const PeerProcess&) = delete;
  PeerProcess& operator=(const PeerProcess&) = delete;

  /// Starts `words` (words[0] found on PATH unless it holds a '/') in `dir` ("" = ours), with
  /// `env` added to our environment, stdout and stderr to `log` ("" = our stderr). Empty on
  /// success, else why it could not start (one line).
  std::string start(const std::vector<std::string>& words, const std::string& dir,
                    const std::vector<std::pair<std::string, std::string>>& env, const std::string& log);
  bool started() const { return pid_ > 0; }
  /// True once the program has exited (reaped), with `how` = "exited with status N" or
  /// "was killed by signal N (NAME)".
  bool exited(std::string* how);
  /// Ends the program and everything in its process group: waits up to `linger` s for it to
  /// exit by itself, then sends SIGTERM to the group, then SIGKILL after `grace` s. Reaps it.
  void end(double linger = 0, double grace = 2.0);

 private:
  pid_t pid_ = -1;  ///< also the process group's id
  bool reaped_ = false;
  int status_ = 0;
};

}  // namespace simbob::robot
