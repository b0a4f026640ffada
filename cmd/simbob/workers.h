// Worker processes shared by `batch` and `sweep run`: each scene or case runs as a `simbob run`
// (or `sweep run --case`) of its own, so a crash takes down only its worker and parallel runs
// never share ODE's process-wide state.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace simbob::cli {

struct Common;

/// Starts this binary with `args` (argv[0] included), its stdout and stderr to `log`. The child
/// gets SIGTERM when its parent dies, so workers never outlive a killed batch or sweep. -1 if
/// fork failed.
pid_t spawnSelf(std::vector<std::string> args, const std::string& log);

/// How a worker ended, from its wait status: "ok", "diverged" (1), "interrupted" (a stop signal,
/// or 130/143), "crashed" (killed by a signal) or "failed" (any other exit status).
struct WorkerOutcome {
  std::string status;
  int exit_code = -1;  ///< -1 when killed by a signal
  std::string error;   ///< for "crashed": the signal, in words
};
WorkerOutcome workerOutcome(int wstatus);

/// `p` absolute and normal (a worker or a Slurm task may start elsewhere).
std::string absolutePath(const std::string& p);

/// The options every worker of batch and sweep runs with: the plug-ins and global settings the
/// command was given (--plugin, --settings), as absolute paths.
std::vector<std::string> workerOptions(const Common& common);

/// The first "file:line: error: ..." line of a worker's log (its last line when there is none).
std::string firstErrorLine(const std::string& log_path);

/// Why a worker's run failed, in one line: the error its run summary records (`error.text` of
/// the partial summary beside `trajectory`, written since `since`: a failed run's, or a refused
/// one's, which workers write with run --refusal-summary); only for a worker that left no summary
/// (it crashed, or could not write one) the first error line of its log.
std::string workerError(const std::string& trajectory, const std::string& log, std::filesystem::file_time_type since);

/// Runs tasks 0 .. count-1 on at most `jobs` workers: start(i) spawns one (a pid, or -1 when it
/// could not), finished(i, wait status) hears of its end. A stop signal (g_stop) is forwarded to
/// the running workers once and no new task starts; the pool returns when none is running.
/// With `tick`, the pool polls for ended workers and calls tick() about every 50 ms between
/// them (batch --timeout: a pid it signals there has not been reaped, so it is still the worker's).
void runWorkerPool(size_t count, int jobs, const std::function<pid_t(size_t)>& start,
                   const std::function<void(size_t, int)>& finished, const std::function<void()>& tick = {});

}  // namespace simbob::cli
