// A bare URDF run (`simbob run robot.urdf`: no scene in which to choose a solver) picks its
// solver by the rule of docs/urdf.md ("The solver of a bare run", lib/compile/compile.cpp): Step
// for a small robot or one with a link QuickStep cannot hold, QuickStep for a large one; --set
// chooses otherwise. And what a user is told when a URDF link diverges under QuickStep, and when
// a command names a joint that has no drive.
#include <cmath>
#include <cstdio>

#include "simbob/overrides.h"
#include "simbob/transform.h"
#include "urdf/urdf_test_util.h"

using namespace urdftest;

namespace {

constexpr double kG = 9.81;

/// A pendulum whose link is a point mass (1 kg, <inertia> 1e-6 kg m^2, 0.5 m below the hinge),
/// as URDFs often write one; it starts 0.5 rad from the vertical. The <inertia> is on line 8.
const char* kPointMass = R"(<robot name="pm">
  <link name="world"/>
  <joint name="hinge" type="continuous">
    <parent link="world"/><child link="bob"/><origin xyz="0 0 2" rpy="0 0.5 0"/><axis xyz="0 1 0"/>
  </joint>
  <link name="bob">
    <inertial><origin xyz="0 0 -0.5"/><mass value="1"/>
      <inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/></inertial>
  </link>
</robot>)";

/// A chain of `n` links hanging from the world, each a 0.2 m rod of 1 kg with a realistic
/// inertia; with `point_mass_last`, the last link is a point mass 0.1 m from its hinge.
std::string chain(int n, bool point_mass_last) {
  std::string s = "<robot name=\"chain\">\n  <link name=\"world\"/>\n";
  for (int i = 0; i < n; ++i) {
    const bool pm = point_mass_last && i == n - 1;
    char link[512];
    std::snprintf(link, sizeof link,
                  "  <joint name=\"j%d\" type=\"continuous\"><parent link=\"%s\"/><child link=\"l%d\"/>"
                  "<origin xyz=\"0 0 %s\"/><axis xyz=\"0 1 0\"/></joint>\n"
                  "  <link name=\"l%d\"><inertial><origin xyz=\"0 0 -0.1\"/><mass value=\"1\"/>"
                  "<inertia ixx=\"%s\" ixy=\"0\" ixz=\"0\" iyy=\"%s\" iyz=\"0\" izz=\"%s\"/></inertial></link>\n",
                  i, i == 0 ? "world" : ("l" + std::to_string(i - 1)).c_str(), i, i == 0 ? "5" : "-0.2", i,
                  pm ? "1e-8" : "0.0034", pm ? "1e-8" : "0.0034", pm ? "1e-8" : "0.0001");
    s += link;
  }
  return s + "</robot>\n";
}

std::string notes(const Model& m) {
  std::string s;
  for (const ImportReport& r : m.imports)
    for (const Error& e : r.notes) s += e.str() + "\n";
  return s;
}

std::string warnings(const Diagnostics& d) {
  std::string s;
  for (const Error& e : d.warnings()) s += e.str() + "\n";
  return s;
}

}  // namespace

TEST_CASE("urdf bare run: a point-mass pendulum steps with Step and swings with the exact period", "[urdf]") {
  const Model model = mustCompile(kPointMass, "pm.urdf");
  CHECK_FALSE(model.settings.quickstep);
  CHECK(model.settings.solver_rule == "bare URDF run: 1 moving bodies, at most 16: Step");
  CHECK(notes(model).find("pm.urdf:1: a bare URDF run steps with Solver Step, ODE's exact solver (1 moving bodies, "
                          "at most 16); --set SceneSettings.Solver=QuickStep chooses the other\n") == 0);
  // With Step the inertia-ratio warning (a QuickStep problem) is not said.
  Diagnostics lint;
  lintModel(model, lint);
  CHECK(warnings(lint).find("inertia ratio") == std::string::npos);
  CHECK(warnings(lint).find("cannot hold") == std::string::npos);

  auto sim = simulate(model);
  const int j = sim->joint("pm.hinge");
  REQUIRE(j >= 0);
  // The point mass at L = 0.5 m, released 0.5 rad out: theta'' = -(m g L / (I + m L^2)) sin(theta),
  // T = 4 K(sin(theta0 / 2)) / w0. The joint position is 0 at the start, -theta0 at the bottom.
  const double L = 0.5, m = 1, I = 1e-6, theta0 = 0.5;
  const double w0 = std::sqrt(m * kG * L / (I + m * L * L));
  const double expected = 4 * ellipticK(std::sin(theta0 / 2)) / w0;
  const Swing sw = swing(*sim, j, -theta0, 0, {0, 2, 0}, 6000);
  REQUIRE(sw.crossings >= 8);
  const double period = sw.period, worst_pivot = sw.worst_pivot;
  INFO("period " << period << " s, expected " << expected << " s");
  // Semi-implicit Euler at 1 ms shifts the period by O(h w0) of it (w0 = 4.4 rad/s): 0.5 % is
  // generous for that. Under QuickStep this joint comes apart at t = 0.11 s.
  CHECK(std::fabs(period - expected) / expected < 0.005);
  // The link frame stays at the hinge: the joint holds (ODE's ERP 0.2 per step corrects drift).
  CHECK(worst_pivot < 1e-3);
}

TEST_CASE("urdf bare run: QuickStep for a large robot, Step for a large one QuickStep cannot hold", "[urdf]") {
  const Model big = mustCompile(chain(20, false), "chain.urdf");
  REQUIRE(big.bodies.size() == 20);
  CHECK(big.settings.quickstep);
  CHECK(big.settings.solver_rule == "bare URDF run: 20 moving bodies, more than 16: QuickStep");
  CHECK(notes(big).find("a bare URDF run steps with Solver QuickStep, 20 iterations (20 moving bodies, more than 16, "
                        "where Step's exact solve is slow); --set SceneSettings.Solver=Step chooses the other") !=
        std::string::npos);
  const Model weak = mustCompile(chain(20, true), "chain.urdf");
  CHECK_FALSE(weak.settings.quickstep);
  CHECK(weak.settings.solver_rule == "bare URDF run: QuickStep cannot hold body 'chain.l19': Step");
  // Exactly 16 is still small.
  CHECK_FALSE(mustCompile(chain(16, false), "chain.urdf").settings.quickstep);
  CHECK(mustCompile(chain(17, false), "chain.urdf").settings.quickstep);
}

TEST_CASE("urdf bare run: --set SceneSettings.Solver wins over the rule", "[urdf]") {
  Scene s;
  Diagnostics d;
  REQUIRE(loadSceneFromText(kPointMass, "pm.urdf", Format::Xml, testRegistry(), &s, d));
  Override o;
  std::string problem;
  REQUIRE(parseOverride("SceneSettings.Solver=QuickStep", &o, &problem));
  REQUIRE(applyOverrides(s, {o}, d));
  Model m;
  REQUIRE(compileScene(s, &m, d));
  CHECK(m.settings.quickstep);
  CHECK(m.settings.solver_rule.empty());
  CHECK(notes(m).find("bare URDF run") == std::string::npos);
  // Now the QuickStep warning is said, with what a URDF user can do: the link's <inertia> line
  // and the --set that chooses Step.
  Diagnostics lint;
  lintModel(m, lint);
  CHECK(warnings(lint) ==
        "pm.urdf:6: body 'pm.bob' (1 kg) sits 0.5 m from joint 'pm.hinge' but its smallest moment of inertia is "
        "1e-06 kg m^2, 4e-06 of m*d^2 (below 1e-05): the solver cannot hold the joint together; give the link a "
        "realistic <inertia> (pm.urdf:8) or step with Solver Step (--set SceneSettings.Solver=Step)\n");
}

TEST_CASE("urdf import: the rule is for bare runs only, a scene keeps its Solver", "[urdf]") {
  TempDir dir;
  dir.write("pm.urdf", kPointMass);
  const std::string scene = dir.write("pm.xml", R"(<Simulation><ComponentList>
  <RCImportURDF Key="pm"><File Value="pm.urdf"/></RCImportURDF></ComponentList></Simulation>)");
  Model m;
  Diagnostics d;
  REQUIRE(compileFile(scene, &m, d));
  CHECK(m.settings.quickstep);
  CHECK(m.settings.solver_rule.empty());
}

TEST_CASE("urdf import: a command Ref to a joint without a drive says why", "[urdf]") {
  TempDir dir;
  dir.write("gear.urdf", R"(<robot name="gear">
  <link name="world"/>
  <joint name="a" type="continuous">
    <parent link="world"/><child link="wa"/><origin xyz="0 0 1"/><axis xyz="0 0 1"/>
  </joint>
  <link name="wa"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="b" type="continuous">
    <parent link="world"/><child link="wb"/><origin xyz="1 0 1"/><axis xyz="0 0 1"/>
    <mimic joint="a" multiplier="-2"/>
  </joint>
  <link name="wb"><inertial><mass value="1"/>
    <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial></link>
  <joint name="f" type="fixed"><parent link="wa"/><child link="tip"/></joint>
  <link name="tip"/>
</robot>)");
  auto scene = [&](const std::string& drives, const std::string& target) {
    return dir.write("gear.xml", R"(<Simulation><ComponentList>
  <RCRobot Key="Bot">
    <Construction><RCImportURDF Key="gear"><File Value="gear.urdf"/><Drives Value=")" +
                                     drives + R"("/></RCImportURDF></Construction>
    <ControllerList>
      <RCCommandSchedule Key="S"><Target Ref="Bot.gear.)" +
                                     target + R"("/><Commands Value="0 1"/></RCCommandSchedule>
    </ControllerList>
  </RCRobot>
</ComponentList></Simulation>)");
  };
  auto error = [&](const std::string& path) {
    Model m;
    Diagnostics d;
    CHECK_FALSE(compileFile(path, &m, d));
    return firstError(d);
  };
  const std::string file = (dir.path() / "gear.xml").string();
  CHECK(error(scene("position", "b")) ==
        file +
            ":5: RCCommandSchedule 'Bot.S': Ref 'Bot.gear.b' names joint 'b' of URDF robot 'Bot.gear', a mimic "
            "joint: it has no drive (it follows joint 'a'; command that one)");
  CHECK(error(scene("none", "a")) ==
        file +
            ":5: RCCommandSchedule 'Bot.S': Ref 'Bot.gear.a' names joint 'a' of URDF "
            "robot 'Bot.gear', which has no drive: RCImportURDF 'Bot.gear' has Drives none");
  CHECK(error(scene("position", "f")) == file +
                                             ":5: RCCommandSchedule 'Bot.S': Ref 'Bot.gear.f' names joint 'f' of URDF "
                                             "robot 'Bot.gear', which does not move: it has no drive");
  // A name that is no joint keeps the general message.
  CHECK(error(scene("position", "zz")).find("names no component") != std::string::npos);
}
