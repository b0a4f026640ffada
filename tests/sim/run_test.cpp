// The run loop and its parties (guide 7.2): who is granted the world when, how many steps the
// clock takes, and the trajectory sampler's times.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "physics/model_builder.h"
#include "simbob/physics.h"
#include "simbob/loop.h"
#include "sim/loop_helpers.h"
#include "simbob/scene_run.h"

using namespace simbob;
using namespace simbob::test;

namespace {

constexpr SimTime kMs = 1000000;  // ns

using Grants = std::vector<std::pair<std::string, SimTime>>;

// One falling ball (MaxTimeStep 1 ms, MinTimeStep 1 us).
Model ballModel() {
  Model m = baseModel(0.001);
  addBody(m, {0, 10, 0}, 1.0, sphereInertia(1.0, 0.1));
  return m;
}

// Asks first at `first`, then every `period` after each grant; stops asking after `grants` grants.
class Periodic : public Party {
 public:
  Periodic(std::string name, SimTime first, SimTime period, Grants* log, int grants = -1)
      : name_(std::move(name)), first_(first), period_(period), log_(log), left_(grants) {}
  SimTime first() override { return first_; }
  SimTime onGrant(SimTime now, World& world) override {
    log_->push_back({name_, now});
    heights.push_back(world.body(0).pose.p[1]);
    if (left_ > 0 && --left_ == 0) return kNever;
    return now + period_;
  }
  void finish(SimTime end, World&) override { finished_at = end; }
  std::vector<double> heights;
  SimTime finished_at = -1;

 private:
  std::string name_;
  SimTime first_, period_;
  Grants* log_;
  int left_;
};

LoopOptions options(double duration, double dt = 0) {
  LoopOptions o;
  o.duration = duration;
  o.dt = dt;
  return o;
}

}  // namespace

TEST_CASE("run: two parties are served in time order, ties in list order", "[sim][run]") {
  const Model m = ballModel();
  const Grants expected = {{"3ms", 0},        {"5ms", 0},       {"3ms", 3 * kMs},  {"5ms", 5 * kMs},
                           {"3ms", 6 * kMs},  {"3ms", 9 * kMs}, {"5ms", 10 * kMs}, {"3ms", 12 * kMs},
                           {"3ms", 15 * kMs}, {"5ms", 15 * kMs}};
  {
    Grants log;
    Periodic a("3ms", 0, 3 * kMs, &log), b("5ms", 0, 5 * kMs, &log);
    const RunResult r = runParties(m, options(0.015), {&a, &b});
    REQUIRE(r.status == RunStatus::Completed);
    CHECK(log == expected);
    CHECK(r.steps == 15u);
    CHECK(r.sim_time == 0.015);
    CHECK(a.finished_at == 15 * kMs);
    CHECK(b.finished_at == 15 * kMs);
  }
  // The other list order swaps the ties only.
  Grants log;
  Periodic a("3ms", 0, 3 * kMs, &log), b("5ms", 0, 5 * kMs, &log);
  REQUIRE(runParties(m, options(0.015), {&b, &a}).status == RunStatus::Completed);
  Grants swapped = expected;
  std::swap(swapped[0], swapped[1]);
  std::swap(swapped[8], swapped[9]);
  CHECK(log == swapped);
}

TEST_CASE("run: the world advances in whole steps; requests between grid instants wait for the next one",
          "[sim][run]") {
  // 2 ms steps, a party asking 3 ms after each grant: granted at 0, 4 (asked 3), 8 (asked 7),
  // 12, 16 (asked 15; the 15 ms end is reached at the 16 ms instant). No step is ever split:
  // before the fixed grid the clock stepped 0-2-3-5-6-8-9-10-12-14-15.
  const Model m = ballModel();
  Grants log;
  Periodic p("3ms", 0, 3 * kMs, &log);
  const RunResult r = runParties(m, options(0.015, 0.002), {&p});
  REQUIRE(r.status == RunStatus::Completed);
  CHECK(log == Grants{{"3ms", 0}, {"3ms", 4 * kMs}, {"3ms", 8 * kMs}, {"3ms", 12 * kMs}, {"3ms", 16 * kMs}});
  CHECK(r.steps == 8u);
  CHECK(r.sim_time == 0.016);
  CHECK(r.dt == 0.002);
  CHECK(p.finished_at == 16 * kMs);
  // The ball is where eight whole 2 ms steps put it, whoever watched (semi-implicit Euler).
  const double h = 0.002;
  CHECK(std::fabs(p.heights.back() - (10 - 9.81 * h * h * 8 * 9 / 2)) < 1e-12);
}

TEST_CASE("run: a party acts on the world at its time, alone", "[sim][run]") {
  // The ball's height at each grant is free fall at exactly that time: the world stood still
  // while the parties acted (semi-implicit Euler: y = 10 - g h^2 n (n + 1) / 2).
  const Model m = ballModel();
  Grants log;
  Periodic a("a", 0, 3 * kMs, &log), b("b", 0, 5 * kMs, &log);
  REQUIRE(runParties(m, options(0.015), {&a, &b}).status == RunStatus::Completed);
  auto y = [](SimTime t) {
    const double n = static_cast<double>(t / kMs), h = 0.001;
    return 10 - 9.81 * h * h * n * (n + 1) / 2;
  };
  size_t ia = 0, ib = 0;
  for (const auto& [name, t] : log) {
    const double got = name == "a" ? a.heights[ia++] : b.heights[ib++];
    CHECK(std::fabs(got - y(t)) < 1e-12);
  }
}

TEST_CASE("run: a request within MinTimeStep is granted without another step", "[sim][run]") {
  const Model m = ballModel();  // MinTimeStep 1 us
  {
    Grants log;
    Periodic p("p", 1 * kMs + 500, kNever, &log, 1);  // 0.5 us past the first step
    const RunResult r = runParties(m, options(0.002), {&p});
    CHECK(log == Grants{{"p", 1 * kMs}});
    CHECK(r.steps == 2u);  // 0 -> 1 ms -> 2 ms
  }
  {
    Grants log;
    Periodic p("p", 1 * kMs + 1500, kNever, &log, 1);  // 1.5 us past: the next grid instant
    const RunResult r = runParties(m, options(0.002), {&p});
    CHECK(log == Grants{{"p", 2 * kMs}});
    CHECK(r.steps == 2u);  // 0 -> 1 ms -> 2 ms: never a short step
  }
  {
    // Asking again within MinTimeStep of the grant: once per instant, again after each step;
    // the clock neither stalls nor takes extra steps.
    Grants log;
    Periodic p("p", 0, 1, &log);
    const RunResult r = runParties(m, options(0.003), {&p});
    CHECK(log == Grants{{"p", 0}, {"p", 1 * kMs}, {"p", 2 * kMs}, {"p", 3 * kMs}});
    CHECK(r.steps == 3u);
  }
}

TEST_CASE("run: a party returning kNever stops asking", "[sim][run]") {
  const Model m = ballModel();
  Grants log;
  Periodic twice("twice", 0, 2 * kMs, &log, 2), never("never", kNever, kMs, &log), late("late", 20 * kMs, kMs, &log);
  const RunResult r = runParties(m, options(0.01), {&twice, &never, &late});
  REQUIRE(r.status == RunStatus::Completed);
  CHECK(log == Grants{{"twice", 0}, {"twice", 2 * kMs}});  // "late" asks beyond the end
  CHECK(r.steps == 10u);
  CHECK(never.finished_at == 10 * kMs);  // every party hears of the end
}

TEST_CASE("run: the run ends at the duration", "[sim][run]") {
  const Model m = ballModel();
  // A duration between grid instants ends at the next one: 2.5 ms at 1 ms steps runs 3 steps.
  for (const auto& [duration, steps] : std::vector<std::pair<double, uint64_t>>{{0.0025, 3}, {0.01, 10}, {0.0, 0}}) {
    Grants log;
    Periodic p("p", 0, 2 * kMs, &log);
    const RunResult r = runParties(m, options(duration), {&p});
    INFO("duration " << duration);
    REQUIRE(r.status == RunStatus::Completed);
    CHECK(r.sim_time == static_cast<double>(steps) * 0.001);
    CHECK(r.steps == steps);
    CHECK(p.finished_at == static_cast<SimTime>(steps) * kMs);
    CHECK(r.samples == 0u);  // no sampler among the parties
  }
  // The end within MinTimeStep of a step counts as reached, without a step.
  Grants log;
  Periodic p("p", 0, kNever, &log, 1);
  const RunResult r = runParties(m, options(0.0020005), {&p});
  CHECK(r.steps == 2u);
  CHECK(r.sim_time == 0.002);
  // Without parties the world still runs to the end.
  const RunResult none = runParties(m, options(0.005), {});
  CHECK(none.status == RunStatus::Completed);
  CHECK(none.steps == 5u);
}

TEST_CASE("run: a failing party stops the run", "[sim][run]") {
  class Failing : public Party {
   public:
    SimTime first() override { return 0; }
    SimTime onGrant(SimTime now, World&) override {
      if (now == 2 * kMs) error_ = {ErrorKind::IoError, {"out.csv", 0}, "cannot write"};
      return now + kMs;
    }
    const Error* failure() const override { return error_.message.empty() ? nullptr : &error_; }
    Error error_;
  } failing;
  const RunResult r = runParties(ballModel(), options(0.01), {&failing});
  CHECK(r.status == RunStatus::Failed);
  CHECK(r.error.kind == ErrorKind::IoError);
  CHECK(r.error.message == "cannot write");
  CHECK(r.sim_time == 0.002);
  CHECK(r.steps == 2u);
}

TEST_CASE("run: times beyond the clock fail the run instead of wrapping", "[sim][run]") {
  Grants log;
  Periodic p("p", 0, kMs, &log);
  for (double bad : {1e10, -1e10, std::numeric_limits<double>::quiet_NaN()}) {
    const RunResult r = runParties(ballModel(), options(bad), {&p});
    CHECK(r.status == RunStatus::Failed);
    CHECK(r.error.kind == ErrorKind::InvalidInput);
    CHECK(r.error.message.find("the duration") != std::string::npos);
    CHECK(r.error.message.find("does not fit the clock") != std::string::npos);
  }
  CHECK(log.empty());
  // A whole run refuses a sample interval the clock cannot hold before it starts.
  RunOptions ro;
  ro.simulation.duration = 1;
  ro.sample_interval = 1e12;
  CHECK(runOptionsProblem(ro) == "--sample-interval must be between 1e-9 and 1e9 s, got 1e+12");
}

TEST_CASE("run: the sampler keeps its times", "[sim][run]") {
  auto times = [](Model m, LoopOptions o, RunResult* res = nullptr) {
    std::vector<double> t;
    o.on_sample = [&t](double time, const double*) { t.push_back(time); };
    RunResult r = runModel(m, o, nullptr);
    REQUIRE(r.status == RunStatus::Completed);
    CHECK(r.samples == t.size());
    if (res) *res = r;
    return t;
  };
  LoopOptions o = options(0.25);
  o.sample_interval = 0.1;
  // The final state is recorded even when the duration is no multiple of the interval.
  CHECK(times(ballModel(), o) == std::vector<double>{0, 0.1, 0.2, 0.25});
  o.duration = 0.3;
  CHECK(times(ballModel(), o) == std::vector<double>{0, 0.1, 0.2, 0.3});
  // 3 ms samples with 2 ms steps: each at the first grid instant at or after its request
  // (3 -> 4, 6 -> 6, 9 -> 10), the time written is the instant; the world takes 5 whole steps.
  RunResult r;
  o = options(0.01, 0.002);
  o.sample_interval = 0.003;
  CHECK(times(ballModel(), o, &r) == std::vector<double>{0, 0.004, 0.006, 0.01});
  CHECK(r.steps == 5u);
  // An interval below the step samples every step.
  o = options(0.006, 0.002);
  o.sample_interval = 0.001;
  CHECK(times(ballModel(), o, &r) == std::vector<double>{0, 0.002, 0.004, 0.006});
  CHECK(r.steps == 3u);
  // MinTimeStep 1.5 ms: a request up to 1.5 ms ahead is due; the next request is the first
  // multiple of the interval more than 1.5 ms later.
  Model m = ballModel();
  m.settings.min_time_step = 0.0015;
  o = options(0.01, 0.001);
  o.sample_interval = 0.002;
  CHECK(times(m, o, &r) == std::vector<double>{0, 0.001, 0.003, 0.005, 0.007, 0.009});
  // At 9 ms the 10 ms end is within MinTimeStep: reached without a tenth step.
  CHECK(r.steps == 9u);
}

TEST_CASE("run: a joint that comes apart stops the run as diverged, naming the joint", "[sim][run]") {
  // The audit's case: a 1 kg bob 1 m from its hinge with inertia 1e-6 kg m^2 (1e-6 of m*d^2)
  // under QuickStep. Its position stays finite, so only the anchor check catches it: the bob
  // used to end 38 m from the hinge with the run reported "completed".
  Model m = baseModel(0.001);
  int bob = addBody(m, {1, 0, 0}, 1.0, {1e-6, 0, 0, 0, 1e-6, 0, 0, 0, 1e-6});
  addJoint(m, JointKind::Hinge, -1, bob, {0, 0, 0}, {0, 0, 1});
  RunResult r = runModel(m, options(10.0), nullptr);
  REQUIRE(r.status == RunStatus::Diverged);
  CHECK(r.error.message.rfind("joint 'j0' came apart at t=", 0) == 0);
  // What came apart travels as data too (explainDivergence reads it, not the message).
  CHECK(r.divergence.joint == 0);
  CHECK(r.divergence.body == -1);
  CHECK(r.divergence.apart > 0.1);
  CHECK(r.error.message.find("m apart (more than 0.1 m)") != std::string::npos);
  // It names the step and what `simbob check` recommends for this scene (the hinge's pendulum).
  CHECK(r.error.message.find("m apart (more than 0.1 m) with a step of 0.001 s (") != std::string::npos);
  CHECK(r.error.message.find("that `simbob check` recommends)") != std::string::npos);
  CHECK(r.sim_time < 10.0);

  // The same pendulum with a realistic inertia (a 5 cm solid ball) swings for 10 s with the
  // hinge held: the bob stays on its 1 m circle.
  Model sound = baseModel(0.001);
  int ball = addBody(sound, {1, 0, 0}, 1.0, sphereInertia(1.0, 0.05));
  addJoint(sound, JointKind::Hinge, -1, ball, {0, 0, 0}, {0, 0, 1});
  double worst = 0;
  LoopOptions o = options(10.0);
  o.on_sample = [&](double, const double* p) { worst = std::max(worst, std::fabs(std::hypot(p[0], p[1]) - 1.0)); };
  RunResult ok = runModel(sound, o, nullptr);
  CHECK(ok.status == RunStatus::Completed);
  CHECK(worst < 1e-3);  // m: QuickStep's joint drift on a 1 m pendulum at 1 ms steps
}
