// The Simulation API: one object owns a run, stepped in pieces or to the end, with the same
// bytes however it is stepped; reset, the caller's parties, commands and errors as values.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "simbob/simulation.h"
#include "test_registry.h"

using namespace simbob;

namespace {

const std::string kScenes = std::string(SIMBOB_SOURCE_DIR) + "/scenes/";

std::unique_ptr<Simulation> load(const std::string& scene, SimulationOptions o = {}) {
  Diagnostics d;
  auto sim = Simulation::fromFile(kScenes + scene, testRegistry(), o, d);
  REQUIRE(sim);
  return sim;
}

// Every body's pose as raw doubles, for bitwise comparison.
std::vector<double> poses(const Simulation& s) {
  std::vector<double> v;
  for (int i = 0; i < s.world().bodyCount(); ++i) {
    const BodyState b = s.world().body(i);
    v.insert(v.end(), {b.pose.p[0], b.pose.p[1], b.pose.p[2], b.pose.q[0], b.pose.q[1], b.pose.q[2], b.pose.q[3]});
  }
  return v;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// A caller's party that records when it was served.
class Watcher : public Party {
 public:
  explicit Watcher(SimTime period) : period_(period) {}
  SimTime first() override { return 0; }
  SimTime onGrant(SimTime now, World&) override {
    times.push_back(now);
    return now + period_;
  }
  std::vector<SimTime> times;

 private:
  SimTime period_;
};

}  // namespace

TEST_CASE("simulation: stepping in pieces gives the bytes of one run to the end", "[sim][simulation]") {
  // The chain's QuickStep contacts and joints make any difference in the step sequence show.
  auto whole = load("chain.xml");
  REQUIRE(whole->runUntil(1.0));
  auto pieces = load("chain.xml");
  REQUIRE(pieces->step(1));
  REQUIRE(pieces->step(249));
  REQUIRE(pieces->runUntil(0.5));
  REQUIRE(pieces->step(500));
  CHECK(pieces->steps() == 1000u);
  CHECK(pieces->now() == whole->now());
  CHECK(pieces->time() == 1.0);
  CHECK(sameBits(poses(*pieces), poses(*whole)));
  // runUntil between grid instants stops at the next one.
  REQUIRE(pieces->runUntil(1.0005));
  CHECK(pieces->steps() == 1001u);
}

TEST_CASE("simulation: reset with a seed is a fresh simulation with that seed", "[sim][simulation]") {
  SimulationOptions o;
  o.seed = 7;
  auto fresh = load("box_stack.xml", o);
  REQUIRE(fresh->runUntil(2.0));
  auto reused = load("box_stack.xml");
  REQUIRE(reused->runUntil(1.3));
  REQUIRE(reused->reset(7));
  CHECK(reused->time() == 0.0);
  REQUIRE(reused->runUntil(2.0));
  CHECK(sameBits(poses(*reused), poses(*fresh)));
}

TEST_CASE("simulation: the caller's parties are served on the grid, after the scene's", "[sim][simulation]") {
  SimulationOptions o;
  o.dt = 0.002;
  auto sim = load("pendulum.xml", o);
  Watcher w(3000000);  // asks every 3 ms: served at 0, 4, 8, ... (the next 2 ms instant)
  sim->addParty(w);
  REQUIRE(sim->runUntil(0.012));
  CHECK(w.times == std::vector<SimTime>{0, 4000000, 8000000, 12000000});
  // One added mid-run asks at the current instant.
  Watcher late(2000000);
  sim->addParty(late);
  REQUIRE(sim->step(2));
  CHECK(late.times == std::vector<SimTime>{12000000, 14000000, 16000000});
  const RunResult& r = sim->finish();
  CHECK(r.status == RunStatus::Completed);
  CHECK(r.dt == 0.002);
}

TEST_CASE("simulation: a trajectory sampled through the API equals the run's samples", "[sim][simulation]") {
  std::vector<double> api, loop;
  auto sim = load("bounce.xml");
  sim->sampleTrajectory(nullptr, 0.01, [&](double, const double* p) { api.insert(api.end(), p, p + kPoseSize); });
  SimulationOptions o;
  o.duration = 1.0;
  auto whole = load("bounce.xml", o);
  whole->sampleTrajectory(nullptr, 0.01, [&](double, const double* p) { loop.insert(loop.end(), p, p + kPoseSize); });
  whole->runToEnd();
  for (int k = 0; k < 100; ++k) REQUIRE(sim->step(10));
  sim->finish();
  CHECK(api.size() == 101 * kPoseSize);
  CHECK(sameBits(api, loop));
}

TEST_CASE("simulation: commands, keys and errors are values", "[sim][simulation]") {
  auto sim = load("two_wheel_robot.xml");
  const int left = sim->actuator("Bot.Cart.LeftDrive");
  REQUIRE(left >= 0);
  CHECK(sim->actuator("Bot.Cart.Nothing") == -1);
  CHECK(sim->setCommand(left, 0.5).message.empty());
  CHECK(sim->world().command(left) == 0.5);
  const Error bad = sim->setCommand(99999, 1.0);
  CHECK(bad.kind == ErrorKind::Usage);
  CHECK(bad.message == "no actuator 99999 (the scene has " + std::to_string(sim->model().actuators.size()) + ")");
  CHECK(sim->setCommand(left, std::nan("")).kind == ErrorKind::Usage);

  Diagnostics d;
  CHECK_FALSE(Simulation::fromText("<Simulation><Bogus/></Simulation>", "bad.xml", testRegistry(), {}, d));
  REQUIRE_FALSE(d.errors().empty());
  CHECK(d.errors()[0].loc.file == "bad.xml");
  CHECK(d.errors()[0].loc.line == 1);
}
