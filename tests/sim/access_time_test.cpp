// MaxAccessTime (guide 7.2): a party that holds the world longer than the scene's MaxAccessTime
// stops the run with ErrorKind::Unavailable naming it; parties read the limit and the deadline
// of the current grant (a blocking party uses them as its own timeout).
#include <catch2/catch.hpp>

#include <chrono>
#include <thread>

#include "physics/model_builder.h"
#include "simbob/physics.h"
#include "simbob/loop.h"
#include "sim/loop_helpers.h"

using namespace simbob;
using namespace simbob::test;

namespace {

constexpr SimTime kMs = 1000000;  // ns

// Asks every 10 ms; the grant at `slow_at` sleeps for `sleep`. Records the limit and deadline it saw.
class Sleeper : public Party {
 public:
  Sleeper(SimTime slow_at, std::chrono::milliseconds sleep) : slow_at_(slow_at), sleep_(sleep) {}
  SimTime first() override { return 0; }
  SimTime onGrant(SimTime now, World&) override {
    ++grants;
    limit_seen = accessLimit();
    deadline_ahead = accessDeadline() > std::chrono::steady_clock::now();
    if (now == slow_at_) std::this_thread::sleep_for(sleep_);
    return now + 10 * kMs;
  }
  int grants = 0;
  double limit_seen = 0;
  bool deadline_ahead = false;

 private:
  SimTime slow_at_;
  std::chrono::milliseconds sleep_;
};

Model model(double max_access_time) {
  Model m = baseModel(0.001);
  addBody(m, {0, 10, 0}, 1.0, sphereInertia(1.0, 0.1));
  m.settings.max_access_time = max_access_time;
  return m;
}

}  // namespace

TEST_CASE("run: a grant longer than MaxAccessTime stops the run with Unavailable", "[sim]") {
  // MaxAccessTime 0.05 s; the party sleeps 0.3 s (six times the limit) in its grant at t = 0.1 s.
  const Model m = model(0.05);
  Sleeper slow(100 * kMs, std::chrono::milliseconds(300));
  slow.name = "controller 'Bot.Slow'";
  slow.loc = {"robot.xml", 12};
  LoopOptions o;
  o.duration = 1.0;
  RunResult r = runParties(m, o, {&slow});
  CHECK(r.status == RunStatus::Failed);
  CHECK(r.error.kind == ErrorKind::Unavailable);
  CHECK(r.error.loc.file == "robot.xml");
  CHECK(r.error.loc.line == 12);
  // "... held the simulation for 0.3xx s of wall-clock time at t=0.1 s, longer than MaxAccessTime (0.05 s)"
  CHECK_THAT(r.error.message, Catch::StartsWith("controller 'Bot.Slow' held the simulation for "));
  CHECK_THAT(r.error.message, Catch::EndsWith(" s of wall-clock time at t=0.1 s, longer than MaxAccessTime (0.05 s)"));
  // Stopped right after the slow grant: nothing more was granted or stepped.
  CHECK(slow.grants == 11);
  CHECK(r.sim_time == 0.1);
  CHECK(slow.limit_seen == 0.05);
  CHECK(slow.deadline_ahead);
}

TEST_CASE("run: grants within MaxAccessTime complete; LoopOptions overrides the scene's limit", "[sim]") {
  // The same sleep under the scene default (1 s) completes.
  {
    const Model m = model(1.0);
    Sleeper slow(100 * kMs, std::chrono::milliseconds(20));
    LoopOptions o;
    o.duration = 0.3;
    RunResult r = runParties(m, o, {&slow});
    CHECK(r.status == RunStatus::Completed);
    CHECK(slow.limit_seen == 1.0);
  }
  // opts.max_access_time replaces the scene's value.
  {
    const Model m = model(1.0);
    Sleeper slow(0, std::chrono::milliseconds(300));
    LoopOptions o;
    o.duration = 0.3;
    o.max_access_time = 0.05;
    RunResult r = runParties(m, o, {&slow});
    CHECK(r.status == RunStatus::Failed);
    CHECK(r.error.kind == ErrorKind::Unavailable);
    CHECK_THAT(r.error.message, Catch::StartsWith("a party of the run held the simulation for "));
    CHECK(r.sim_time == 0.0);
  }
}
