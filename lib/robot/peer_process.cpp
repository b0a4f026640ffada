// The peer program simbob starts for an RCLocalSocketCommunicator (its Controller parameter or
// run --controller). fork + execvpe, no shell: the command line was split by splitCommandLine.
//
// simbob forks a keeper, which forks the program. The keeper is a child subreaper
// (PR_SET_CHILD_SUBREAPER): whatever the program starts -- a child that calls setsid, the jobs of
// a shell with job control, Python's Popen(start_new_session=True) -- is re-parented to the keeper
// when its own parent exits, never to PID 1, so the keeper can find every descendant (the parent
// of each process in /proc) and end them all: SIGTERM, then SIGKILL after a grace time, reaping
// until it has no child left. It does so when simbob closes the control pipe, which the kernel
// also does when simbob dies in any way (SIGKILL included) -- unlike PR_SET_PDEATHSIG, which
// follows the thread that forked (a Python thread that made a Simulation and exited took its
// controller with it). The keeper also writes the program's output to the log, keeping its head
// and tail (the rest is dropped, with a line that says how much). A cgroup would contain
// descendants as well, but needs a delegated, writable cgroup tree, which a user's shell, a
// container or a Slurm step seldom grants; a subreaper needs no privilege.
//
// The keeper is a fork of a process that may have other threads (Python's): until it exits it
// makes only async-signal-safe calls (system calls, memcpy) on memory allocated before the fork.
#include "robot/peer_process.h"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <memory>
#include <thread>

extern char** environ;

namespace simbob::robot {

namespace {

using Wall = std::chrono::steady_clock;

constexpr size_t kChunk = size_t{64} << 10;  ///< bytes the keeper reads at a time
constexpr size_t kMaxPids = 8192;            ///< descendants the keeper can track in one sweep
constexpr uint32_t kOrphanGraceMs = 1000;    ///< grace when simbob is gone without asking

volatile sig_atomic_t g_keeper_stop = 0;
void onKeeperSignal(int) { g_keeper_stop = 1; }

long long nowMs() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<long long>(ts.tv_sec) * 1000 + ts.tv_nsec / 1000000;
}

/// Writes all `n` bytes; a failure (a full disk) loses log text, never the run.
void writeAll(int fd, const char* p, size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return;
    p += w;
    n -= static_cast<size_t>(w);
  }
}

/// Decimal digits of v into out (at least 21 chars); their count.
size_t digits(unsigned long long v, char* out) {
  char tmp[24];
  size_t n = 0;
  do {
    tmp[n++] = static_cast<char>('0' + v % 10);
    v /= 10;
  } while (v != 0);
  for (size_t i = 0; i < n; ++i) out[i] = tmp[n - 1 - i];
  return n;
}

/// The log as the keeper writes it: the first `head` bytes as they come; after them, as they
/// come too while everything fits in head + tail; past that the file is cut back to the head
/// and only the last `tail` bytes are kept (in `ring`), written with a line naming the cut.
struct CappedLog {
  int fd = -1;
  size_t head = 0, tail = 0;
  char* ring = nullptr;  ///< tail bytes: byte k past the head at ring[k % tail]
  unsigned long long total = 0;
  bool cut = false;

  void add(const char* p, size_t n) {
    if (total < head) {
      const size_t k = std::min<unsigned long long>(n, head - total);
      writeAll(fd, p, k);
      total += k;
      p += k;
      n -= k;
    }
    if (n == 0) return;
    if (!cut && total + n > static_cast<unsigned long long>(head) + tail) {
      cut = true;  // from now on the file holds the head; the tail waits in the ring
      (void)!::ftruncate(fd, static_cast<off_t>(head));
      ::lseek(fd, static_cast<off_t>(head), SEEK_SET);
    }
    if (!cut) writeAll(fd, p, n);
    if (tail == 0) {
      total += n;
      return;
    }
    for (size_t i = n > tail ? n - tail : 0; i < n;) {  // only the last `tail` bytes matter
      const size_t at = static_cast<size_t>((total + i - head) % tail);
      const size_t k = std::min(n - i, tail - at);
      std::memcpy(ring + at, p + i, k);
      i += k;
    }
    total += n;
  }

  void finish() {
    if (!cut) return;
    char line[200];
    static const char kA[] = "\n[simbob: ";
    static const char kB[] = " bytes of the controller's output cut here; this log keeps the first ";
    size_t n = 0;
    auto put = [&](const char* s, size_t k) {
      std::memcpy(line + n, s, k);
      n += k;
    };
    auto size = [&](size_t v) {  // "4 MiB", or "1000 bytes"
      const bool mib = v != 0 && v % (size_t{1} << 20) == 0;
      n += digits(mib ? v >> 20 : v, line + n);
      put(mib ? " MiB" : " bytes", mib ? 4 : 6);
    };
    put(kA, sizeof kA - 1);
    n += digits(total - head - tail, line + n);
    put(kB, sizeof kB - 1);
    size(head);
    put(" and the last ", 14);
    size(tail);
    put("]\n", 2);
    writeAll(fd, line, n);
    if (tail == 0) return;
    const size_t start = static_cast<size_t>((total - head) % tail);
    writeAll(fd, ring + start, tail - start);
    writeAll(fd, ring, start);
  }
};

/// The parent of process `pid` from /proc/PID/stat ("pid (comm) state ppid ..."), or -1.
pid_t parentOf(const char* pid_text) {
  char path[48] = "/proc/";
  size_t n = 6;
  while (*pid_text && n < 32) path[n++] = *pid_text++;
  std::memcpy(path + n, "/stat", 6);
  const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return -1;
  char buf[512];
  const ssize_t got = ::read(fd, buf, sizeof buf - 1);
  ::close(fd);
  if (got <= 0) return -1;
  buf[got] = 0;
  const char* p = nullptr;
  for (ssize_t i = got - 1; i >= 0 && !p; --i)
    if (buf[i] == ')') p = buf + i;  // the name may hold ')': the last one ends it
  if (!p || p[1] != ' ' || p[2] == 0 || p[3] != ' ') return -1;
  pid_t ppid = 0;
  for (p += 4; *p >= '0' && *p <= '9'; ++p) ppid = ppid * 10 + (*p - '0');
  return ppid;
}

/// Sends `sig` to every descendant of this process: the processes whose parent is this one or
/// one of them, found by sweeping /proc until no new one turns up. `pids` is scratch.
void signalDescendants(int sig, pid_t* pids) {
  size_t n = 0;
  pids[n++] = ::getpid();
  for (bool grew = true; grew;) {
    grew = false;
    const int dir = ::open("/proc", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir < 0) return;
    alignas(8) char buf[4096];
    ssize_t got;
    while ((got = ::getdents64(dir, buf, sizeof buf)) > 0) {
      for (ssize_t off = 0; off < got;) {
        const auto* d = reinterpret_cast<const dirent64*>(buf + off);
        off += d->d_reclen;
        if (d->d_name[0] < '1' || d->d_name[0] > '9') continue;
        pid_t pid = 0;
        for (const char* c = d->d_name; *c >= '0' && *c <= '9'; ++c) pid = pid * 10 + (*c - '0');
        if (std::find(pids, pids + n, pid) != pids + n) continue;
        const pid_t ppid = parentOf(d->d_name);
        if (n < kMaxPids && std::find(pids, pids + n, ppid) != pids + n) {
          pids[n++] = pid;
          grew = true;
        }
      }
    }
    ::close(dir);
  }
  for (size_t i = 1; i < n; ++i) ::kill(pids[i], sig);
}

/// Closes every descriptor but 0, 1, 2 and those in keep (sorted, ascending).
void closeAllBut(const int* keep, size_t count) {
  int from = 3;
  for (size_t i = 0; i <= count; ++i) {
    const int to = i < count ? keep[i] - 1 : -1;  // -1: to the end
    if (i < count && keep[i] < from) continue;
    if (to < 0 || to >= from) {
      if (::close_range(static_cast<unsigned>(from), to < 0 ? ~0U : static_cast<unsigned>(to), 0) != 0) {
        rlimit lim{};
        ::getrlimit(RLIMIT_NOFILE, &lim);
        const int last = to < 0 ? static_cast<int>(std::min<rlim_t>(lim.rlim_cur, 65536)) - 1 : to;
        for (int fd = from; fd <= last; ++fd) ::close(fd);
      }
    }
    if (i < count) from = keep[i] + 1;
  }
}

/// What the keeper and the program need, all of it built before the fork.
struct Launch {
  char* const* argv;
  char* const* envp;
  const char* dir;  ///< nullptr: ours
  int control = -1, status = -1, report = -1, log = -1;
  size_t head = 0, tail = 0;
  char* scratch = nullptr;  ///< tail + kChunk bytes, then kMaxPids pids
};

/// The program, in the keeper's fork: default signals, a process group of its own, its output
/// to `out` (the log's pipe, or -1: simbob's stderr), in its folder. Never returns.
[[noreturn]] void programMain(const Launch& l, int out) {
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGCHLD}) ::sigaction(sig, &dfl, nullptr);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  ::setpgid(0, 0);
  // The program's stdout is never simbob's: that may be the trajectory (--out -).
  ::dup2(out >= 0 ? out : 2, 1);
  if (out >= 0) ::dup2(out, 2);
  int err = 0;
  if (l.dir && ::chdir(l.dir) != 0)
    err = -errno;  // negative: the folder, not the program
  else
    ::execvpe(l.argv[0], l.argv, l.envp);
  if (err == 0) err = errno;
  (void)!::write(l.report, &err, sizeof err);
  ::_exit(127);
}

/// The keeper: starts the program, logs its output, reaps everything, ends everything when
/// simbob closes the control pipe (or dies), exits when nothing it started is left.
[[noreturn]] void keeperMain(const Launch& l) {
  struct sigaction sa {};
  sa.sa_handler = onKeeperSignal;
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(sig, &sa, nullptr);
  sa.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &sa, nullptr);  // simbob gone: its pipes fail, the keeper goes on
  sa.sa_handler = SIG_DFL;
  ::sigaction(SIGCHLD, &sa, nullptr);  // not SIG_IGN, which would reap behind waitpid's back
  ::setpgid(0, 0);                     // a terminal's SIGINT is simbob's alone
  ::prctl(PR_SET_CHILD_SUBREAPER, 1);
  int keep[4] = {l.control, l.status, l.report, l.log};
  std::sort(keep, keep + 4);
  closeAllBut(keep[0] < 0 ? keep + 1 : keep, keep[0] < 0 ? 3 : 4);
  int out[2] = {-1, -1};
  if (l.log >= 0 && ::pipe2(out, O_CLOEXEC) != 0) out[0] = out[1] = -1;
  const pid_t program = ::fork();
  if (program == 0) programMain(l, out[1]);
  if (program < 0) {
    const int err = errno;
    (void)!::write(l.report, &err, sizeof err);
    ::_exit(127);
  }
  ::close(l.report);
  if (out[1] >= 0) ::close(out[1]);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);

  CappedLog log{l.log, l.head, l.tail, l.scratch};
  char* chunk = l.scratch + l.tail;
  auto* pids = reinterpret_cast<pid_t*>(chunk + kChunk);
  int control = l.control;
  uint32_t grace_ms = kOrphanGraceMs;
  bool program_done = false, ending = false;
  long long kill_at = 0;
  while (true) {
    pollfd fds[2] = {{control, POLLIN, 0}, {out[0], POLLIN, 0}};
    ::poll(fds, 2, 20);
    if (out[0] >= 0 && fds[1].revents != 0) {
      const ssize_t got = ::read(out[0], chunk, kChunk);
      if (got > 0) log.add(chunk, static_cast<size_t>(got));
      if (got == 0 || (got < 0 && errno != EINTR && errno != EAGAIN)) out[0] = (::close(out[0]), -1);
    }
    if (control >= 0 && fds[0].revents != 0) {
      uint32_t ms = 0;
      const ssize_t got = ::read(control, &ms, sizeof ms);
      if (got == static_cast<ssize_t>(sizeof ms)) grace_ms = ms;
      if (got <= 0) control = (::close(control), -1);  // simbob asks for the end, or is gone
    }
    if (!ending && (control < 0 || g_keeper_stop)) {
      ending = true;
      kill_at = nowMs() + grace_ms;
      signalDescendants(SIGTERM, pids);
    }
    if (ending && nowMs() >= kill_at) signalDescendants(SIGKILL, pids);
    int st = 0;
    pid_t r;
    while ((r = ::waitpid(-1, &st, WNOHANG)) > 0)
      if (r == program) {
        program_done = true;
        (void)!::write(l.status, &st, sizeof st);
      }
    if (r < 0 && errno == ECHILD && program_done) break;  // nothing it started is left
  }
  while (out[0] >= 0) {  // every writer is gone: what is left in the pipe, then end of file
    const ssize_t got = ::read(out[0], chunk, kChunk);
    if (got > 0) log.add(chunk, static_cast<size_t>(got));
    if (got == 0 || (got < 0 && errno != EINTR)) out[0] = (::close(out[0]), -1);
  }
  log.finish();
  ::_exit(0);
}

}  // namespace

std::string PeerProcess::start(const std::vector<std::string>& words, const std::string& dir,
                               const std::vector<std::pair<std::string, std::string>>& env, const std::string& log,
                               size_t log_head, size_t log_tail) {
  if (words.empty()) return "the command line holds no program";
  end();
  // Everything the keeper and the program need is built here: after fork, only async-signal-safe calls.
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
  // Not touched here (no zeroing): the keeper's pages alone are filled.
  const std::unique_ptr<char[]> scratch(new char[log_tail + kChunk + kMaxPids * sizeof(pid_t)]);

  Launch l{argv.data(), envp.data(), dir.empty() ? nullptr : dir.c_str()};
  l.head = log_head;
  l.tail = log_tail;
  l.scratch = scratch.get();
  if (!log.empty()) {
    l.log = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (l.log < 0) return "cannot create " + log + ": " + std::strerror(errno);
  }
  int control[2], status[2], report[2];  // report: exec's errno; closed by a successful exec
  const bool piped = ::pipe2(control, O_CLOEXEC) == 0;
  const bool piped2 = piped && ::pipe2(status, O_CLOEXEC | O_NONBLOCK) == 0;
  const bool piped3 = piped2 && ::pipe2(report, O_CLOEXEC) == 0;
  if (!piped3) {
    const int err = errno;
    for (int fd :
         {piped ? control[0] : -1, piped ? control[1] : -1, piped2 ? status[0] : -1, piped2 ? status[1] : -1, l.log})
      if (fd >= 0) ::close(fd);
    return std::string("cannot create a pipe: ") + std::strerror(err);
  }
  l.control = control[0];
  l.status = status[1];
  l.report = report[1];
  // No signal handler of simbob's may run in the keeper before it sets its own.
  sigset_t all, old;
  sigfillset(&all);
  ::pthread_sigmask(SIG_SETMASK, &all, &old);
  const pid_t pid = ::fork();
  if (pid == 0) keeperMain(l);
  const int fork_err = errno;
  ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
  for (int fd : {control[0], status[1], report[1], l.log})
    if (fd >= 0) ::close(fd);
  if (pid < 0) {
    for (int fd : {control[1], status[0], report[0]}) ::close(fd);
    return std::string("cannot fork: ") + std::strerror(fork_err);
  }
  keeper_ = pid;
  control_ = control[1];
  status_fd_ = status[0];
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
  if (keeper_ <= 0 && !reaped_) return false;
  if (!reaped_ && status_fd_ >= 0) {
    int st = 0;
    ssize_t got;
    while ((got = ::read(status_fd_, &st, sizeof st)) < 0 && errno == EINTR) {
    }
    if (got == static_cast<ssize_t>(sizeof st)) {
      status_ = st;
      reaped_ = true;
    } else if (got == 0) {  // the keeper is gone without a word (killed): the program with it
      status_ = -1;
      reaped_ = true;
    }
  }
  if (!reaped_) return false;
  if (how) {
    if (status_ >= 0 && WIFEXITED(status_))
      *how = "exited with status " + std::to_string(WEXITSTATUS(status_));
    else if (status_ >= 0 && WIFSIGNALED(status_))
      *how = "was killed by signal " + std::to_string(WTERMSIG(status_)) + " (" + ::strsignal(WTERMSIG(status_)) + ")";
    else
      *how = "ended";
  }
  return true;
}

bool PeerProcess::keeperGone(double seconds) {
  const Wall::time_point until =
      Wall::now() + std::chrono::duration_cast<Wall::duration>(std::chrono::duration<double>(seconds));
  while (true) {
    exited(nullptr);  // keeps the status pipe drained
    int st = 0;
    const pid_t r = ::waitpid(keeper_, &st, WNOHANG);
    if (r == keeper_ || (r < 0 && errno == ECHILD)) return true;
    if (Wall::now() >= until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

void PeerProcess::end(double linger, double grace) {
  if (keeper_ <= 0) return;
  if (!keeperGone(linger)) {
    // The grace, then end of file: the keeper sends SIGTERM to all, SIGKILL after the grace.
    const auto ms = static_cast<uint32_t>(std::clamp(grace, 0.0, 3600.0) * 1000);
    (void)!::write(control_, &ms, sizeof ms);
    ::close(control_);
    control_ = -1;
    if (!keeperGone(grace + 2.0)) {  // a keeper that does not answer (stopped): it goes, its program may stay
      ::kill(keeper_, SIGKILL);
      keeperGone(2.0);
    }
  }
  exited(nullptr);
  for (int* fd : {&control_, &status_fd_})
    if (*fd >= 0) ::close(*fd), *fd = -1;
  keeper_ = -1;
}

}  // namespace simbob::robot
