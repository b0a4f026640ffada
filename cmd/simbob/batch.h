// simbob batch, shared between its files: a job is one scene run by one worker.
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <sys/types.h>

#include "cli.h"
#include "commands.h"
#include "simbob/tool/comparison.h"
#include "simbob/tool/test_report.h"

namespace simbob::cli::batch {

struct Job {
  std::string scene;
  std::vector<std::string> args;  // extra `simbob run` arguments from the manifest
  std::string out;
  std::string log;
  SourceLoc loc;  // manifest line, if any
  // Results.
  pid_t pid = -1;
  std::string status = "not started";  // ok, failed, diverged, crashed, interrupted
  int exit_code = -1;
  double wall = 0;
  std::chrono::steady_clock::time_point started;
  std::filesystem::file_time_type since;  ///< when it started, as file times go (workerError)
  bool timed_out = false;                 ///< stopped by --timeout (SIGTERM, then SIGKILL)
  std::string error;                      // first error line of the worker
  std::string golden_status;              // pass, mismatch, no-golden, unreadable ("" without --golden)
  double max_pos = 0, max_rot = 0;
  std::string divergence;
  std::string golden_path;                  ///< GOLDEN/STEM.csv (with --golden)
  std::optional<CompareResult> comparison;  ///< with --golden, when both files could be read
};

/// The jobs of the scenes (globs expanded, sorted) and of --manifest FILE. 0, or the exit status
/// (reported): a manifest line `simbob run` would refuse is named here.
int readJobs(const BatchArgs& a, std::vector<Job>* jobs);
/// Each job's trajectory (OUT_DIR/STEM.csv unless its manifest line gives --out) and worker log,
/// checked: no two jobs write one file, and no output is an input. 0, or the exit status.
int assignOutputs(const BatchArgs& a, const Common& common, std::vector<Job>* jobs);

// CI reports (batch_ci.cpp, docs/ci.md).
/// 0, or 64 after reporting: --bless without --golden.
int checkCiOptions(const BatchArgs& a);

/// OUT.json: the summary beside a job's trajectory.
std::string summaryPath(const Job& j);
/// The logs of the controllers a job's run started (OUT.controller.log[.KEY]), sorted.
std::vector<std::string> controllerLogs(const Job& j);
/// A case's folder name in --artifacts DIR, safe and unique among `taken` (batch_artifacts.cpp).
std::string caseFolder(const std::string& name, std::set<std::string>* taken);
/// DIR/FOLDER/ of one case: what a reader needs to see why it is what it is. 0, or an exit status.
int caseArtifacts(const Job& j, const BatchArgs& a, const Common& common, const std::string& folder, TestCaseReport* c);
/// --junit, --summary-md and --artifacts once every job has finished: 0, or the exit status of
/// the first report that could not be written (reported; the others are still written).
int writeCiOutputs(const std::vector<Job>& jobs, const BatchArgs& a, const Common& common, double wall);
/// Compares a finished job's trajectory with GOLDEN/NAME.csv (--golden): sets golden_status,
/// golden_path, comparison and, on a mismatch, error and a NAME.compare.txt beside the trajectory.
void compareWithGolden(Job& j, const BatchArgs& a);
/// --bless-from DIR: the trajectories a batch left in DIR (its --out-dir, e.g. from a CI run's
/// artifacts) compared with --golden and blessed as --bless does, without running any scene.
/// The exit status.
int blessFrom(const BatchArgs& a);
/// --bless: refuses (1) when a scene did not run to the end; else prints each change (body,
/// largest difference) and then rewrites the golden files that differ or are new. The exit status.
int blessGoldens(const std::vector<Job>& jobs, const BatchArgs& a);

}  // namespace simbob::cli::batch
