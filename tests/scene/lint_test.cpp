// lintModel: each warning fires on the scene it describes and stays silent on a sound one.
#include <catch2/catch.hpp>

#include <cmath>

#include <fstream>
#include <sstream>

#include "test_registry.h"
#include "simbob/compile.h"
#include "simbob/graph.h"
#include "simbob/transform.h"

using namespace simbob;

namespace {

Model base() {
  Model m;
  m.materials.push_back(MaterialDef{});
  GeomDef ground;
  ground.shape = GeomShape::Plane;
  ground.key = "Ground";
  ground.plane = {0, 1, 0, 0};
  m.geoms.push_back(ground);
  return m;
}

int addBody(Model& m, const std::string& key, Vec3 p, GeomShape shape, Vec3 size, double mass = 1.0) {
  BodyDef b;
  b.key = key;
  b.loc = {"lint.xml", static_cast<int>(m.bodies.size()) + 10};
  b.pose.p = p;
  b.mass = mass;
  b.inertia = {0.01 * mass, 0, 0, 0, 0.01 * mass, 0, 0, 0, 0.01 * mass};
  m.bodies.push_back(b);
  GeomDef g;
  g.key = key;
  g.shape = shape;
  g.size = size;
  g.body = static_cast<int>(m.bodies.size()) - 1;
  m.geoms.push_back(g);
  return g.body;
}

std::vector<std::string> warnings(const Model& m) {
  Diagnostics d;
  lintModel(m, d);
  REQUIRE(d.ok());
  std::vector<std::string> out;
  for (const auto& w : d.warnings()) out.push_back(w.str());
  return out;
}

bool anyContains(const std::vector<std::string>& ws, const std::string& part) {
  for (const auto& w : ws)
    if (w.find(part) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("a sound scene gives no warnings", "[scene][lint]") {
  Model m = base();
  // Boxes exactly resting on the ground and on each other: touching is not overlapping.
  addBody(m, "Low", {0, 0.1, 0}, GeomShape::Box, {0.2, 0.2, 0.2});
  addBody(m, "High", {0, 0.3, 0}, GeomShape::Box, {0.2, 0.2, 0.2});
  addBody(m, "Ball", {1, 0.1, 0}, GeomShape::Sphere, {0.1, 0, 0});
  CHECK(warnings(m).empty());
}

TEST_CASE("overlapping bodies and bodies inside a plane are reported", "[scene][lint]") {
  Model m = base();
  addBody(m, "A", {0, 1, 0}, GeomShape::Box, {0.4, 0.4, 0.4});
  addBody(m, "B", {0.1, 1.1, 0}, GeomShape::Box, {0.4, 0.4, 0.4});
  addBody(m, "Sunk", {3, 0.05, 0}, GeomShape::Sphere, {0.1, 0, 0});
  auto ws = warnings(m);
  CHECK(anyContains(ws, "lint.xml:10: bodies 'A' and 'B' overlap by about 0.3 m"));
  CHECK(anyContains(ws, "lint.xml:12: body 'Sunk' starts 0.05 m inside the plane of 'Ground'"));
  // Joined bodies may overlap: that is how a joint holds them.
  JointDef j;
  j.kind = JointKind::Fixed;
  j.body1 = 0;
  j.body2 = 1;
  m.joints.push_back(j);
  CHECK_FALSE(anyContains(warnings(m), "'A' and 'B' overlap"));
}

TEST_CASE("a large mass ratio across a joint is reported", "[scene][lint]") {
  Model m = base();
  int a = addBody(m, "Heavy", {0, 2, 0}, GeomShape::Sphere, {0.1, 0, 0}, 500.0);
  int b = addBody(m, "Light", {1, 2, 0}, GeomShape::Sphere, {0.1, 0, 0}, 1.0);
  JointDef j;
  j.key = "Link";
  j.loc = {"lint.xml", 40};
  j.kind = JointKind::BallSocket;
  j.body1 = a;
  j.body2 = b;
  j.anchor = {0.5, 2, 0};
  m.joints.push_back(j);
  CHECK(anyContains(warnings(m), "lint.xml:40: joint 'Link' connects masses 500 kg and 1 kg (ratio 500 > 100)"));
  m.bodies[0].mass = 50;
  CHECK_FALSE(anyContains(warnings(m), "ratio"));
}

TEST_CASE("thin fast bodies that can tunnel are reported", "[scene][lint]") {
  Model m = base();
  int i = addBody(m, "Bullet", {0, 0.5, 0}, GeomShape::Sphere, {0.01, 0, 0});
  m.bodies[static_cast<size_t>(i)].lin_vel = {100, 0, 0};
  // 100 m/s plus the fall from 0.5 m, times 1 ms, is about 0.1 m per step: more than half of 0.02 m.
  CHECK(anyContains(warnings(m), "body 'Bullet' is 0.02 m thin and may move 103 m/s"));
  m.bodies[static_cast<size_t>(i)].lin_vel = {1, 0, 0};
  m.bodies[static_cast<size_t>(i)].pose.p = {0, 0.011, 0};
  CHECK_FALSE(anyContains(warnings(m), "thin"));
}

TEST_CASE("a step too large for a pendulum is reported", "[scene][lint]") {
  Model m = base();
  // A point-like bob 0.01 m below its hinge: period 2 pi sqrt(0.01/9.81) = 0.2 s.
  int b = addBody(m, "Bob", {0, 1.99, 0}, GeomShape::Sphere, {0.002, 0, 0}, 1.0);
  m.bodies[static_cast<size_t>(b)].inertia = {1e-9, 0, 0, 0, 1e-9, 0, 0, 0, 1e-9};
  JointDef j;
  j.key = "Hinge";
  j.kind = JointKind::Hinge;
  j.body1 = -1;
  j.body2 = b;
  j.anchor = {0, 2, 0};
  j.axis = {0, 0, 1};
  m.joints.push_back(j);
  m.settings.max_time_step = 0.001;  // 200 steps per period: fine
  CHECK_FALSE(anyContains(warnings(m), "pendulum"));
  m.settings.max_time_step = 0.02;  // 10 steps per period
  CHECK(anyContains(warnings(m), "joint 'Hinge' makes a pendulum of period 0.201 s but the step is 0.02 s"));
  // The warning starts exactly where its own advice ends: 40 steps per swing. (It used to warn
  // from 20 steps while advising 40, and was silent at 0.05 s where the chain comes apart.)
  const double period = 2 * 3.141592653589793 * std::sqrt((1e-9 + 1.0 * 0.01 * 0.01) / (1.0 * 9.81 * 0.01));
  const double advice = period / 40;
  m.settings.max_time_step = advice * 1.001;
  CHECK(anyContains(warnings(m), "use --dt " + formatApprox(advice) + " or smaller"));
  m.settings.max_time_step = advice * 0.999;
  CHECK_FALSE(anyContains(warnings(m), "pendulum"));
  // What a diverged run recommends is the smallest advice of all checks: here the falling bob's
  // tunnelling bound, 0.5 x 4 mm / sqrt(2 g 1.99 m), is below the pendulum's.
  CHECK(recommendedStep(m) == Approx(0.5 * 0.004 / std::sqrt(2 * 9.81 * 1.99)).epsilon(1e-6));
  // check --dt: the step of the run, not the scene's MaxTimeStep.
  Diagnostics d;
  lintModel(m, d, advice * 1.001);
  bool pendulum = false;
  for (const auto& w : d.warnings()) pendulum = pendulum || w.message.find("pendulum") != std::string::npos;
  CHECK(pendulum);
}

TEST_CASE("a joint anchored far from its body is reported", "[scene][lint]") {
  Model m = base();
  int b = addBody(m, "Arm", {0, 1, 0}, GeomShape::Sphere, {0.05, 0, 0});
  JointDef j;
  j.key = "Far";
  j.kind = JointKind::BallSocket;
  j.body1 = -1;
  j.body2 = b;
  j.anchor = {10, 1, 0};
  m.joints.push_back(j);
  CHECK(anyContains(warnings(m), "joint 'Far' has its anchor 10 m from body 'Arm'"));
  m.joints[0].anchor = {0, 2, 0};  // a 1 m pendulum rod is normal
  CHECK_FALSE(anyContains(warnings(m), "anchor"));
}

TEST_CASE("a body whose inertia is tiny against m*d^2 at its joint is reported", "[scene][lint]") {
  // The audit's case: a 1 kg bob 1 m from its hinge with inertia 1e-6 kg m^2. Its own inertia
  // is 1e-6 of m*d^2 = 1 kg m^2, so QuickStep lets the hinge drift apart (tests/sim/run_test).
  Model m = base();
  int bob = addBody(m, "Bob", {1, 2, 0}, GeomShape::Sphere, {0.01, 0, 0}, 1.0);
  m.bodies[static_cast<size_t>(bob)].inertia = {1e-6, 0, 0, 0, 1e-6, 0, 0, 0, 1e-6};
  JointDef j;
  j.key = "Hinge";
  j.loc = {"lint.xml", 41};
  j.kind = JointKind::Hinge;
  j.body1 = -1;
  j.body2 = bob;
  j.anchor = {0, 2, 0};
  j.axis = {0, 0, 1};
  m.joints.push_back(j);
  CHECK(anyContains(warnings(m),
                    "lint.xml:10: body 'Bob' (1 kg) sits 1 m from joint 'Hinge' but its smallest moment of inertia is "
                    "1e-06 kg m^2, 1e-06 of m*d^2 (below 1e-05)"));
  // A solid 1 cm ball's own inertia (4e-5 kg m^2) is 4e-5 of m*d^2: fine.
  m.bodies[static_cast<size_t>(bob)].inertia = {4e-5, 0, 0, 0, 4e-5, 0, 0, 0, 4e-5};
  CHECK_FALSE(anyContains(warnings(m), "smallest moment of inertia"));
}

TEST_CASE("thousands of coincident bodies stop the overlap search instead of taking quadratic time", "[scene][lint]") {
  // 200 coincident spheres make 19,900 overlapping pairs; the search stops at 10,000 and says so
  // (before: every pair was collected, 2,047 bodies took 8 s in `check`).
  Model m = base();
  for (int i = 0; i < 200; ++i) addBody(m, "B" + std::to_string(i), {0, 2, 0}, GeomShape::Sphere, {0.1, 0, 0});
  std::vector<std::string> w = warnings(m);
  CHECK(anyContains(w, "stopped looking for overlaps after 10000 overlapping pairs of bodies"));
  CHECK(anyContains(w, "more warnings like 'overlap'"));
}

namespace {

// scenes/two_wheel_robot.xml with its wheel hinges' frames turned as given ("0 180 0" in the
// scene: each axle points to the robot's left).
Model twoWheel(const std::string& left_turn, const std::string& right_turn) {
  std::ifstream in(std::string(SIMBOB_SOURCE_DIR) + "/scenes/two_wheel_robot.xml");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"0.1 -0.02 -0.19 0 180 0", "0.1 -0.02 -0.19 " + left_turn},
        {"0.1 -0.02 0.19 0 180 0", "0.1 -0.02 0.19 " + right_turn}}) {
    const size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    text.replace(at, from.size(), to);
  }
  Scene s;
  Diagnostics d;
  REQUIRE(loadSceneFromText(text, "two_wheel.xml", Format::Xml, testRegistry(), &s, d));
  Model m;
  REQUIRE(compileScene(s, &m, d));
  return m;
}

}  // namespace

TEST_CASE("a two-wheel robot whose axle turns its wheel backwards is named", "[scene][lint]") {
  // As shipped: both axles point to the robot's left (-Z): no warning.
  CHECK(warnings(twoWheel("0 180 0", "0 180 0")).empty());
  // Both frames unturned: the axles point to +Z, the robot's right; a forward command drives the
  // robot backwards. Each axle is named, where it is defined.
  const std::vector<std::string> both = warnings(twoWheel("0 0 0", "0 0 0"));
  REQUIRE(both.size() == 2);
  CHECK(both[0] ==
        "two_wheel.xml:42: joint 'Bot.Cart.LeftAxle' (the left wheel of RCTwoWheelMotionControl 'Bot.Motion') turns "
        "its wheel backwards on a forward command: the wheel turns about the robot's right; point the hinge axis from "
        "the right wheel to the left one (now 0 0 1)");
  CHECK(both[1].rfind("two_wheel.xml:58: joint 'Bot.Cart.RightAxle' (the right wheel of", 0) == 0);
  // One axle reversed: the robot would spin on a forward command; only that one is named.
  const std::vector<std::string> one = warnings(twoWheel("0 180 0", "0 0 0"));
  REQUIRE(one.size() == 1);
  CHECK(anyContains(one, "joint 'Bot.Cart.RightAxle'"));
}

TEST_CASE("overlaps among many bodies are found between neighbours and with wide bodies, in x order", "[scene][lint]") {
  // A floor of 1,600 boxes 0.2 m wide, 0.3 m apart (on negative coordinates too), none touching;
  // the search looks at neighbours in a grid of cells, and must still find what the sweep along
  // x finds, in its order (by where each pair's first body begins along x).
  Model m = base();
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      addBody(m, "F" + std::to_string(i) + "_" + std::to_string(j), {-6 + 0.3 * i, 0.1, -6 + 0.3 * j}, GeomShape::Box,
              {0.2, 0.2, 0.2});
  addBody(m, "P", {-6 + 0.3 * 10 + 0.1, 0.1, -6 + 0.3 * 7}, GeomShape::Box, {0.2, 0.2, 0.2});  // 0.1 m into F10_7
  // A slab 3 m across lies in some 200 cells (a body of many cells meets every other one); two
  // boxes sink 0.1 m into it.
  addBody(m, "Slab", {20, 0.5, 20}, GeomShape::Box, {3, 0.1, 3});
  addBody(m, "On2", {21.4, 0.5, 21.4}, GeomShape::Box, {0.2, 0.2, 0.2});
  addBody(m, "On1", {19, 0.5, 19}, GeomShape::Box, {0.2, 0.2, 0.2});
  // Two spheres 0.05 m into each other, and two large boxes that share several cells.
  addBody(m, "S1", {10, 2, 10}, GeomShape::Sphere, {0.1, 0, 0});
  addBody(m, "S2", {10.15, 2, 10}, GeomShape::Sphere, {0.1, 0, 0});
  addBody(m, "Q2", {-19.9, 1, -20}, GeomShape::Box, {0.5, 0.5, 0.5});
  addBody(m, "Q1", {-20, 1, -20}, GeomShape::Box, {0.5, 0.5, 0.5});
  // Each at the line of the pair's first body (the helper gives body i line i + 10).
  std::vector<std::string> overlaps;
  for (const std::string& w : warnings(m))
    if (w.find(" overlap by about ") != std::string::npos) overlaps.push_back(w.substr(0, w.find(" m at t = 0")));
  const std::vector<std::string> expected = {
      "lint.xml:1617: bodies 'Q1' and 'Q2' overlap by about 0.4",     // Q1 begins at x = -20.25
      "lint.xml:417: bodies 'F10_7' and 'P' overlap by about 0.1",    // F10_7 at x = -3.1
      "lint.xml:1614: bodies 'S1' and 'S2' overlap by about 0.05",    // S1 at x = 9.9
      "lint.xml:1611: bodies 'Slab' and 'On1' overlap by about 0.1",  // the slab at x = 18.5
      "lint.xml:1611: bodies 'Slab' and 'On2' overlap by about 0.1",
  };
  CHECK(overlaps == expected);
}
