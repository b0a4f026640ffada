// Worker processes of `batch` and `sweep run` (workers.h).
#include "workers.h"

#include "simbob/scene_run.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <map>

#include "cli.h"

namespace simbob::cli {

pid_t spawnSelf(std::vector<std::string> args, const std::string& log) {
  const pid_t parent = getpid();
  pid_t pid = fork();
  if (pid != 0) return pid;
  prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (getppid() != parent) _exit(kExitSigTerm);
  int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    dup2(fd, 1);
    dup2(fd, 2);
    close(fd);
  }
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (auto& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);
  execv("/proc/self/exe", argv.data());
  std::fprintf(stderr, "simbob: error: cannot start worker: %s\n", std::strerror(errno));
  _exit(kExitSoftware);
}

WorkerOutcome workerOutcome(int wstatus) {
  WorkerOutcome o;
  if (WIFSIGNALED(wstatus)) {
    const int sig = WTERMSIG(wstatus);
    if (g_stop && (sig == SIGINT || sig == SIGTERM)) {
      o.status = "interrupted";  // the signal came before the worker could catch it
      return o;
    }
    o.status = "crashed";
    o.error = "worker killed by signal " + std::to_string(sig) + " (" + strsignal(sig) + ")";
    return o;
  }
  o.exit_code = WEXITSTATUS(wstatus);
  switch (o.exit_code) {
    case kExitOk:
      o.status = "ok";
      break;
    case kExitResultWrong:
      o.status = "diverged";
      break;
    case kExitSigInt:
    case kExitSigTerm:
      o.status = "interrupted";
      break;
    default:
      o.status = "failed";
      break;
  }
  return o;
}

std::string absolutePath(const std::string& p) {
  std::error_code ec;
  std::filesystem::path a = std::filesystem::absolute(p, ec);
  return (ec ? std::filesystem::path(p) : a).lexically_normal().string();
}

std::vector<std::string> workerOptions(const Common& common) {
  std::vector<std::string> args;
  for (const std::string& p : common.plugins) {
    args.emplace_back("--plugin");
    args.push_back(absolutePath(p));
  }
  for (const std::string& p : common.packages) {
    const size_t eq = p.find('=');
    args.emplace_back("--package");
    args.push_back(eq == std::string::npos ? p : p.substr(0, eq + 1) + absolutePath(p.substr(eq + 1)));
  }
  if (!common.settings.empty()) {
    args.emplace_back("--settings");
    args.push_back(absolutePath(common.settings));
  }
  if (common.no_controllers) args.emplace_back("--no-controllers");
  return args;
}

std::string firstErrorLine(const std::string& log_path) {
  std::ifstream in(log_path);
  std::string line, last;
  while (std::getline(in, line)) {
    if (line.find(": error: ") != std::string::npos) return line;
    if (!line.empty()) last = line;
  }
  return last;
}

std::string workerError(const std::string& trajectory, const std::string& log, std::filesystem::file_time_type since) {
  if (const std::string partial = partialSummaryOf(trajectory); !partial.empty()) {
    std::error_code ec;
    const auto written = std::filesystem::last_write_time(partial, ec);
    if (!ec && written >= since) {
      std::ifstream in(partial);
      const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
      if (summary.is_object() && summary.contains("error") && summary["error"].contains("text") &&
          summary["error"]["text"].is_string())
        return summary["error"]["text"].get<std::string>();
    }
  }
  return firstErrorLine(log);
}

void runWorkerPool(size_t count, int jobs, const std::function<pid_t(size_t)>& start,
                   const std::function<void(size_t, int)>& finished, const std::function<void()>& tick) {
  size_t next = 0, running = 0;
  std::map<pid_t, size_t> by_pid;
  bool forwarded = false;
  for (;;) {
    if (g_stop && !forwarded) {
      // Workers stop as a run does on a signal: they keep their partial trajectories.
      for (const auto& [pid, index] : by_pid) kill(pid, static_cast<int>(g_stop));
      forwarded = true;
    }
    while (!g_stop && running < static_cast<size_t>(jobs) && next < count) {
      const size_t i = next++;
      const pid_t pid = start(i);
      if (pid > 0) {
        by_pid[pid] = i;
        ++running;
      }
    }
    if (running == 0) return;
    int wstatus = 0;
    const pid_t pid = waitpid(-1, &wstatus, tick ? WNOHANG : 0);
    if (pid == 0) {  // polling (tick): none ended yet
      tick();
      usleep(50'000);
      continue;
    }
    if (pid < 0) {
      if (errno == EINTR) continue;  // a signal: stop starting new tasks, keep reaping
      return;
    }
    auto it = by_pid.find(pid);
    if (it == by_pid.end()) continue;
    const size_t i = it->second;
    by_pid.erase(it);
    --running;
    finished(i, wstatus);
  }
}

}  // namespace simbob::cli
