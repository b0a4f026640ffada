#include "simbob/run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "simbob/clock.h"
#include "simbob/compile.h"
#include "simbob/physics.h"
#include "simbob/values.h"

namespace simbob {

Party::~Party() = default;
void Party::finish(SimTime, World&) {}
const Error* Party::failure() const { return nullptr; }
void Party::abandon(const Error&) {}

std::string partialPath(const std::string& out) {
  const std::string ext = ".csv";
  if (out.size() > ext.size() && out.compare(out.size() - ext.size(), ext.size(), ext) == 0)
    return out.substr(0, out.size() - ext.size()) + ".partial.csv";
  return out + ".partial.csv";
}

namespace {

// Converts `seconds` for the clock, or sets *err naming `what` when it does not fit.
SimTime clockTime(double seconds, const char* what, Error* err) {
  const std::optional<SimTime> t = toSimTime(seconds);
  if (t) return *t;
  if (err->message.empty())
    *err = {ErrorKind::InvalidInput,
            {},
            std::string(what) + " " + formatNumber(seconds) +
                " s does not fit the clock (integer nanoseconds: at most about 9.2e9 s)"};
  return 0;
}

// "with a step of 0.05 s (`simbob check` recommends at most 0.041 s)": what a diverged run says.
std::string stepAdvice(const Model& model, SimTime step) {
  std::string s = "with a step of " + formatNumber(toSeconds(step)) + " s";
  const double rec = recommendedStep(model);
  if (std::isfinite(rec))
    s += toSeconds(step) > rec ? " (`simbob check` recommends at most " + formatApprox(rec) + " s: try --dt " +
                                     formatApprox(rec) + ")"
                               : " (within the " + formatApprox(rec) + " s that `simbob check` recommends)";
  return s;
}

}  // namespace

RunResult runParties(const Model& model, const RunOptions& opts, const std::vector<Party*>& parties) {
  RunResult res;
  auto wall0 = std::chrono::steady_clock::now();
  const double dt = opts.dt > 0 ? opts.dt : model.settings.max_time_step;
  res.dt = dt;
  const SimTime end = clockTime(opts.duration, "the duration", &res.error);
  const SimTime step = clockTime(dt, "the step", &res.error);
  const SimTime min_step = clockTime(model.settings.min_time_step, "MinTimeStep", &res.error);
  if (!res.error.message.empty()) return res;
  std::unique_ptr<World> world = World::create(model, opts.seed);
  if (!world) {
    res.error = {ErrorKind::Internal, {}, "cannot create the physics world (another one is alive in this process)"};
    return res;
  }
  Clock clock(std::max<SimTime>(step, 1), min_step);
  res.dt = toSeconds(clock.step());  // the step actually taken (the nanosecond grid)
  // MaxAccessTime (guide 7.2): every grant (onGrant) is timed; one that took longer stops the
  // run. (A blocking party bounds its own waits by accessDeadline().)
  const double limit = opts.max_access_time > 0 ? opts.max_access_time : model.settings.max_access_time;
  const auto limit_d = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(std::min(limit, 1e9)));
  auto overran = [&](Party& p, std::chrono::steady_clock::time_point started) {
    const auto took = std::chrono::steady_clock::now() - started;
    if (took <= limit_d) return false;
    if (p.failure()) return false;  // it gave up at its deadline and says why (checked below)
    res.status = RunStatus::Failed;
    char held[32];
    std::snprintf(held, sizeof held, "%.3g", std::chrono::duration<double>(took).count());
    res.error = {ErrorKind::Unavailable, p.loc,
                 p.name + " held the simulation for " + held +
                     " s of wall-clock time at t=" + formatNumber(toSeconds(clock.now())) +
                     " s, longer than MaxAccessTime (" + formatNumber(limit) + " s)"};
    return true;
  };
  auto open = [&](Party& p) {
    const auto started = std::chrono::steady_clock::now();
    p.access_limit_ = limit;
    p.access_deadline_ = started + limit_d;
    return started;
  };
  // first() is not a grant: a party that waits there (a socket server for its peer) bounds that
  // wait itself (--peer-timeout).
  const auto waiting = std::chrono::steady_clock::now();
  for (Party* p : parties) {
    p->access_limit_ = limit;
    p->access_deadline_ = std::chrono::steady_clock::time_point::max();
    p->stop_ = opts.stop;
    clock.addParty(p->first());
  }
  res.wait_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - waiting).count();

  const SimTime progress_every = std::max<SimTime>(end / 100, 1);
  SimTime next_progress = progress_every;
  while (true) {
    // Grant every due request, earliest first, ties in list order; nothing else runs meanwhile.
    bool granted = false;
    int id = -1;
    while (res.error.message.empty() && (id = clock.grantable()) >= 0) {
      Party& p = *parties[static_cast<size_t>(id)];
      const auto started = open(p);
      clock.granted(id, p.onGrant(clock.now(), *world));
      overran(p, started);
      granted = true;
    }
    if (!res.error.message.empty()) break;
    if (granted) {
      for (const Party* p : parties)
        if (const Error* e = p->failure()) {
          res.status = RunStatus::Failed;
          res.error = *e;
          break;
        }
      if (!res.error.message.empty()) break;
    }
    if (clock.reached(end)) break;  // the first grid instant at or after the duration
    if (opts.stop && *opts.stop) {
      res.status = RunStatus::Interrupted;
      res.error = {ErrorKind::Diverged, {}, "interrupted at t=" + formatNumber(toSeconds(clock.now())) + " s"};
      break;
    }
    world->step(toSeconds(clock.step()));
    clock.advance();
    ++res.steps;
    int bad = world->firstBadBody(opts.runaway_limit);
    if (bad >= 0) {
      res.status = RunStatus::Diverged;
      const BodyDef& b = model.bodies[static_cast<size_t>(bad)];
      res.error = {ErrorKind::Diverged, b.loc,
                   "body '" + b.key + "' diverged at t=" + formatNumber(toSeconds(clock.now())) +
                       " s (non-finite or beyond " + formatNumber(opts.runaway_limit) + " m or m/s) " +
                       stepAdvice(model, clock.step()) + "; softer joints (ERP/CFM) may help too"};
      break;
    }
    double apart = 0;
    int broken = world->firstBrokenJoint(opts.joint_apart_limit, &apart);
    if (broken >= 0) {
      res.status = RunStatus::Diverged;
      const JointDef& j = model.joints[static_cast<size_t>(broken)];
      res.error = {ErrorKind::Diverged, j.loc,
                   "joint '" + j.key + "' came apart at t=" + formatNumber(toSeconds(clock.now())) +
                       " s: its anchor on the two bodies is " + formatNumber(apart) + " m apart (more than " +
                       formatNumber(opts.joint_apart_limit) + " m) " + stepAdvice(model, clock.step())};
      break;
    }
    if (opts.progress && clock.now() >= next_progress) {
      opts.progress(toSeconds(clock.now()));
      next_progress += progress_every;
    }
  }
  if (res.status == RunStatus::Failed && res.error.message.empty()) {
    for (Party* p : parties) p->finish(clock.now(), *world);
    res.status = RunStatus::Completed;
  } else {
    for (Party* p : parties) p->abandon(res.error);
  }
  res.sim_time = toSeconds(clock.now());
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return res;
}

SimTime frameTime(uint64_t n, double fps) { return toSimTime(static_cast<double>(n) / fps).value_or(kNever); }

std::vector<std::string> gridNotes(double step_s, double sample_interval_s, double fps) {
  std::vector<std::string> notes;
  const SimTime step = std::max<SimTime>(toSimTime(step_s).value_or(1), 1);
  const SimTime interval = std::max<SimTime>(toSimTime(sample_interval_s).value_or(1), 1);
  const std::string h = formatNumber(toSeconds(step)) + " s";
  if (interval < step)
    notes.push_back("the sample interval " + formatNumber(sample_interval_s) + " s is below the step " + h +
                    ": a sample is taken every step");
  else if (interval % step != 0)
    notes.push_back("the sample interval " + formatNumber(sample_interval_s) + " s is not a multiple of the step " + h +
                    ": sample n is taken at the first step at or after n x " + formatNumber(sample_interval_s) +
                    " s and its row shows that time");
  if (fps > 0) {
    bool aligned = true;
    for (uint64_t n = 1; n <= 1000 && aligned; ++n) {
      const SimTime t = frameTime(n, fps);
      aligned = t != kNever && t % step == 0;
    }
    if (!aligned)
      notes.push_back("frames at " + formatNumber(fps) + " fps do not fall on the step " + h +
                      ": frame n shows the first step at or after n/" + formatNumber(fps) +
                      " s (a video keeps the n/fps timestamps)");
  }
  return notes;
}

RunResult runModel(const Model& model, const RunOptions& opts, TrajectoryWriter* writer) {
  Error err;
  const SimTime interval = clockTime(opts.sample_interval, "the sample interval", &err);
  const SimTime min_step = clockTime(model.settings.min_time_step, "MinTimeStep", &err);
  if (!err.message.empty()) {
    RunResult res;
    res.dt = opts.dt > 0 ? opts.dt : model.settings.max_time_step;
    res.error = err;
    return res;
  }
  TrajectorySampler sampler(static_cast<int>(model.bodies.size()), std::max<SimTime>(interval, 1), min_step, writer,
                            opts.on_sample);
  std::vector<std::unique_ptr<Party>> more;
  if (opts.make_parties) more = opts.make_parties();
  sampler.name = "the trajectory sampler";
  std::vector<Party*> parties{&sampler};
  for (auto& p : more) parties.push_back(p.get());
  RunResult res = runParties(model, opts, parties);
  res.samples = sampler.samples();
  return res;
}

}  // namespace simbob
