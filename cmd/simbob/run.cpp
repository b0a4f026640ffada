// simbob run: one scene, one trajectory, one summary. The run is a Run (simbob/scene_run.h):
// this file hands it the options, prints what it says, guards it against a step that will not
// end, and turns its outcome into an exit status.
#include <unistd.h>

#include <cstdio>

#include "cli.h"
#include "commands.h"
#include "run_watch.h"
#include "simbob/scene_run.h"
#include "simbob/values.h"

namespace simbob::cli {

namespace {}  // namespace

RunListener runListener() {
  RunListener l;
  l.note = [](const RunNote& n) {
    switch (n.level) {
      case RunNote::Debug:
        g_log.debug(n.what.message);
        return;
      case RunNote::Info:
        g_log.info(n.what.message);
        return;
      case RunNote::Warning:
        g_log.warning(n.what);
        return;
      case RunNote::Error:
        g_log.error(n.what);
        return;
    }
  };
  l.inputs = [](const std::vector<NamedPath>& inputs) { closeLogIfInput(inputs); };
  return l;
}

namespace {

int exitStatus(const RunOutcome& o) {
  if (o.output_error) return exitCodeFor(o.output_error->kind);
  switch (o.result.status) {
    case RunStatus::Completed:
      return kExitOk;
    case RunStatus::Interrupted:
      return stopExitCode();
    case RunStatus::Diverged:
    case RunStatus::Failed:
      break;
  }
  return exitCodeFor(o.result.error.kind);
}

}  // namespace

int cmdRun(RunArgs& a, const Common& common) {
  if (std::string p = runArgsProblem(a); !p.empty()) {
    g_log.error({ErrorKind::Usage, {}, p});
    return kExitUsage;
  }
  if (int c = completeRunOptions(a, common)) return c;
  Progress progress(a.run.simulation.duration, g_log.level != Level::Quiet);
  a.run.simulation.progress = [&](double t) { progress.update(t); };
  exitOnStopSignals(a.run.scene, "loading");
  Error refusal;
  std::unique_ptr<Run> run = Run::open(a.run, *common.registry, runListener(), &refusal);
  if (!run) return exitCodeFor(refusal.kind);
  catchStopSignals();
  StopWatchdog watchdog([&]() {
    g_log.error({ErrorKind::Interrupted,
                 {},
                 "interrupted at t=" + formatNumber(run->lastSampleTime()) +
                     " s (the last whole sample; the step under way was abandoned)"});
    Error perr;
    const std::string kept = run->keepFromOtherThread(&perr);
    if (!kept.empty()) g_log.info("kept the trajectory so far in " + kept);
    if (!perr.message.empty()) g_log.error(perr);
    _exit(stopExitCode());
  });
  const RunOutcome& outcome = run->finish();
  progress.done();
  watchdog.loopReturned();
  if (a.json && !outcome.summary.is_null()) std::fputs(jsonText(outcome.summary).c_str(), stdout);
  return exitStatus(outcome);
}

}  // namespace simbob::cli
