// The peer program simbob starts for an RCLocalSocketCommunicator (its Controller parameter or
// run --controller). fork + execvpe, no shell: the command line was split by splitCommandLine.
// The child leads a process group of its own, so SIGINT at a terminal reaches simbob alone and
// simbob ends the whole group (the program and anything it started) when the run ends; with
// PR_SET_PDEATHSIG it also gets SIGTERM if simbob itself dies without ending it.
#include "robot/peer_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

extern char** environ;

namespace simbob::robot {

namespace {

using Wall = std::chrono::steady_clock;

/// True once no process of group `pgid` is left (the leader must have been reaped first).
bool groupGone(pid_t pgid) { return ::kill(-pgid, 0) != 0 && errno == ESRCH; }

}  // namespace

std::string PeerProcess::start(const std::vector<std::string>& words, const std::string& dir,
                               const std::vector<std::pair<std::string, std::string>>& env, const std::string& log) {
  if (words.empty()) return "the command line holds no program";
  // Everything the child needs is built here: between fork and exec only async-signal-safe calls.
  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e) {
    bool replaced = false;
    for (const auto& kv : env)
      if (std::strncmp(*e, kv.first.c_str(), kv.first.size()) == 0 && (*e)[kv.first.size()] == '=') replaced = true;
    if (!replaced) env_text.emplace_back(*e);
  }
  for (const auto& kv : env) env_text.push_back(kv.first + "=" + kv.second);
  std::vector<char*> envp, argv;
  for (std::string& s : env_text) envp.push_back(s.data());
  envp.push_back(nullptr);
  std::vector<std::string> args = words;
  for (std::string& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);

  int out = 2;
  if (!log.empty()) {
    out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (out < 0) return "cannot create " + log + ": " + std::strerror(errno);
  }
  int report[2];  // the child writes exec's errno here; closed by a successful exec
  if (::pipe2(report, O_CLOEXEC) != 0) {
    if (out != 2) ::close(out);
    return std::string("cannot create a pipe: ") + std::strerror(errno);
  }
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    // simbob's handlers (and a test framework's) are not the child's: a SIGTERM before exec ends it.
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    for (int sig : {SIGINT, SIGTERM, SIGPIPE, SIGCHLD}) ::sigaction(sig, &dfl, nullptr);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::_exit(127);  // simbob died before the line above
    // The child's stdout is never simbob's: that may be the trajectory (--out -).
    ::dup2(out, 1);
    ::dup2(out, 2);
    int err = 0;
    if (!dir.empty() && ::chdir(dir.c_str()) != 0)
      err = -errno;  // negative: the folder, not the program
    else
      ::execvpe(argv[0], argv.data(), envp.data());
    if (err == 0) err = errno;
    (void)!::write(report[1], &err, sizeof err);
    ::_exit(127);
  }
  const int fork_err = errno;
  ::close(report[1]);
  if (out != 2) ::close(out);
  if (pid < 0) {
    ::close(report[0]);
    return std::string("cannot fork: ") + std::strerror(fork_err);
  }
  ::setpgid(pid, pid);  // also here, so that the group exists whichever runs first
  pid_ = pid;
  reaped_ = false;
  int err = 0;
  ssize_t n;
  while ((n = ::read(report[0], &err, sizeof err)) < 0 && errno == EINTR) {
  }
  ::close(report[0]);
  if (n == static_cast<ssize_t>(sizeof err)) {
    end();
    if (err < 0) return "cannot enter the folder " + dir + ": " + std::strerror(-err);
    return "cannot run " + words[0] + ": " + std::strerror(err);
  }
  return "";
}

bool PeerProcess::exited(std::string* how) {
  if (pid_ <= 0) return false;
  if (!reaped_) {
    pid_t r;
    while ((r = ::waitpid(pid_, &status_, WNOHANG)) < 0 && errno == EINTR) {
    }
    if (r != pid_) return false;
    reaped_ = true;
  }
  if (how) {
    if (WIFEXITED(status_))
      *how = "exited with status " + std::to_string(WEXITSTATUS(status_));
    else if (WIFSIGNALED(status_))
      *how = "was killed by signal " + std::to_string(WTERMSIG(status_)) + " (" + ::strsignal(WTERMSIG(status_)) + ")";
    else
      *how = "ended";
  }
  return true;
}

void PeerProcess::end(double linger, double grace) {
  if (pid_ <= 0) return;
  auto waitGone = [&](double seconds) {
    const Wall::time_point until =
        Wall::now() + std::chrono::duration_cast<Wall::duration>(std::chrono::duration<double>(seconds));
    while (true) {
      exited(nullptr);
      if (reaped_ && groupGone(pid_)) return true;
      if (Wall::now() >= until) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  };
  if (!waitGone(linger)) {
    ::kill(-pid_, SIGTERM);
    if (!waitGone(grace)) {
      ::kill(-pid_, SIGKILL);
      waitGone(grace);
    }
  }
  pid_ = -1;
}

}  // namespace simbob::robot
