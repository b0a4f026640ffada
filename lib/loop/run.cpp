// The run loop: see simbob/loop.h.
#include "simbob/loop.h"

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
    s += toSeconds(step) > rec
             ? " (`simbob check` recommends at most " + formatApprox(rec) + " s: try --dt " + formatApprox(rec) + ")"
             : " (within the " + formatApprox(rec) + " s that `simbob check` recommends)";
  return s;
}

}  // namespace

Runner::Runner(const Model& model, const SimulationOptions& opts, std::vector<Party*> parties)
    : model_(model), opts_(opts), parties_(std::move(parties)), wall0_(std::chrono::steady_clock::now()) {
  const double dt = resolvedStep(opts.dt, model.settings.max_time_step);
  res_.dt = dt;
  end_ = clockTime(opts.duration, "the duration", &res_.error);
  const SimTime step = clockTime(dt, "the step", &res_.error);
  const SimTime min_step = clockTime(model.settings.min_time_step, "MinTimeStep", &res_.error);
  if (!res_.error.message.empty()) {
    stopped_ = true;
    return;
  }
  world_ = World::create(model, opts.seed, opts.threads > 0 ? opts.threads : 1);
  if (!world_) {
    res_.error = {ErrorKind::Internal, {}, "cannot create the physics world"};
    stopped_ = true;
    return;
  }
  clock_ = Clock(std::max<SimTime>(step, 1), min_step);
  res_.dt = toSeconds(clock_.step());  // the step actually taken (the nanosecond grid)
  // MaxAccessTime (guide 7.2): every grant (onGrant) is timed; one that took longer stops the
  // run. (A blocking party bounds its own waits by accessDeadline().)
  limit_ = opts.max_access_time > 0 ? opts.max_access_time : model.settings.max_access_time;
  limit_d_ = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(std::min(limit_, 1e9)));
  // first() is not a grant: a party that waits there (a socket server for its peer) bounds that
  // wait itself (--peer-timeout).
  const auto waiting = std::chrono::steady_clock::now();
  for (Party* p : parties_) enroll(*p);
  res_.wait_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - waiting).count();
  progress_every_ = std::max<SimTime>(end_ / 100, 1);
  next_progress_ = progress_every_;
}

Runner::~Runner() = default;

void Runner::addParty(Party& p) {
  parties_.push_back(&p);
  if (world_) enroll(p);
}

void Runner::enroll(Party& p) {
  p.access_limit_ = limit_;
  p.access_deadline_ = std::chrono::steady_clock::time_point::max();
  p.stop_ = opts_.stop;
  clock_.addParty(p.first());
}

void Runner::stop(RunStatus status, Error e) {
  res_.status = status;
  res_.error = std::move(e);
  stopped_ = true;
}

bool Runner::grantDue() {
  if (stopped_) return false;
  if (const Error* e = world_ ? world_->failure() : nullptr) {  // a plug-in sensor or actuator failed
    stop(RunStatus::Failed, *e);
    return false;
  }
  // Grant every due request, earliest first, ties in list order; nothing else runs meanwhile.
  bool granted = false;
  int id = -1;
  while ((id = clock_.grantable()) >= 0) {
    Party& p = *parties_[static_cast<size_t>(id)];
    const auto started = std::chrono::steady_clock::now();
    p.access_limit_ = limit_;
    p.access_deadline_ = started + limit_d_;
    clock_.granted(id, p.onGrant(clock_.now(), *world_));
    granted = true;
    const auto took = std::chrono::steady_clock::now() - started;
    if (took > limit_d_ && !p.failure()) {  // a party that gave up at its deadline says why below
      char held[32];
      std::snprintf(held, sizeof held, "%.3g", std::chrono::duration<double>(took).count());
      stop(RunStatus::Failed, {ErrorKind::Unavailable, p.loc,
                               p.name + " held the simulation for " + held +
                                   " s of wall-clock time at t=" + formatNumber(toSeconds(clock_.now())) +
                                   " s, longer than MaxAccessTime (" + formatNumber(limit_) + " s)"});
      return false;
    }
  }
  if (granted)
    for (const Party* p : parties_)
      if (const Error* e = p->failure()) {
        stop(RunStatus::Failed, *e);
        return false;
      }
  return true;
}

bool Runner::advance() {
  if (stopped_) return false;
  if (opts_.stop && *opts_.stop) {
    stop(RunStatus::Interrupted,
         {ErrorKind::Interrupted, {}, "interrupted at t=" + formatNumber(toSeconds(clock_.now())) + " s"});
    return false;
  }
  world_->step(toSeconds(clock_.step()));
  if (const Error* e = world_->failure(); e && e->kind == ErrorKind::Internal) {  // ODE failed inside the step
    stop(RunStatus::Failed, *e);
    return false;
  }
  clock_.advance();
  ++res_.steps;
  const int bad = world_->firstBadBody(opts_.runaway_limit);
  if (bad >= 0) {
    const BodyDef& b = model_.bodies[static_cast<size_t>(bad)];
    res_.divergence = {bad, -1, 0.0, toSeconds(clock_.now())};
    stop(RunStatus::Diverged, {ErrorKind::Diverged, b.loc,
                               "body '" + b.key + "' diverged at t=" + formatNumber(toSeconds(clock_.now())) +
                                   " s (non-finite or beyond " + formatNumber(opts_.runaway_limit) + " m or m/s) " +
                                   stepAdvice(model_, clock_.step()) + "; softer joints (ERP/CFM) may help too"});
    return false;
  }
  double apart = 0;
  const int broken = world_->firstBrokenJoint(opts_.joint_apart_limit, &apart);
  if (broken >= 0) {
    const JointDef& j = model_.joints[static_cast<size_t>(broken)];
    res_.divergence = {-1, broken, apart, toSeconds(clock_.now())};
    stop(RunStatus::Diverged,
         {ErrorKind::Diverged, j.loc,
          "joint '" + j.key + "' came apart at t=" + formatNumber(toSeconds(clock_.now())) +
              " s: its anchor on the two bodies is " + formatNumber(apart) + " m apart (more than " +
              formatNumber(opts_.joint_apart_limit) + " m) " + stepAdvice(model_, clock_.step())});
    return false;
  }
  if (opts_.progress && clock_.now() >= next_progress_) {
    opts_.progress(toSeconds(clock_.now()));
    next_progress_ += progress_every_;
  }
  return true;
}

bool Runner::runUntil(SimTime t) {
  while (grantDue()) {
    if (clock_.reached(t)) return true;  // the first grid instant at or after t
    if (!advance()) return false;
  }
  return false;
}

bool Runner::step(uint64_t n) {
  if (!grantDue()) return false;
  for (uint64_t k = 0; k < n; ++k)
    if (!advance() || !grantDue()) return false;
  return true;
}

const RunResult& Runner::complete() {
  if (!completed_) {
    completed_ = true;
    if (!stopped_ && world_) {
      for (Party* p : parties_) p->finish(clock_.now(), *world_);
      res_.status = RunStatus::Completed;
    } else {
      for (Party* p : parties_) p->abandon(res_.error);
    }
    stopped_ = true;
  }
  res_.sim_time = toSeconds(clock_.now());
  if (world_) res_.physics_messages = world_->physicsMessages();
  res_.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
  return res_;
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

std::string physicsMessagesWarning(const PhysicsMessages& m) {
  std::string text = "ODE reported " + countOf(m.count, "problem", "problems") +
                     " while stepping; the first, in the step to t = " + formatNumber(m.first_time) + " s: '" +
                     m.first + "'";
  // ODE 0.16's one message during a step: dWorldStep's LCP solver (Solver Step) met constraints
  // it could not meet exactly (redundant or conflicting ones with little or no CFM).
  if (m.first.find("LCP") != std::string::npos)
    return text +
           ". Solver Step could not meet the constraints exactly there (redundant contacts or joints with "
           "little CFM), so the motion may be off; a CFM above 0 (1e-5, say) or Solver QuickStep avoids it";
  return text + ". The motion may be off from then on";
}

}  // namespace simbob
