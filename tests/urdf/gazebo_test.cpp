// <gazebo reference="LINK"> surface tags with Gazebo classic's meaning (lib/urdf/read.cpp,
// lib/components/urdf_import.cpp, lib/physics/contacts.cpp; docs/urdf.md "Surfaces"): read at
// their lines, the rest named as ignored, and each one's effect against an analytic answer. The
// sliding-caster diff-drive of issue 42 drives straight at r w.
#include <cmath>
#include <cstdio>

#include "simbob/transform.h"
#include "urdf/urdf.h"
#include "urdf/urdf_test_util.h"

using namespace urdftest;

namespace {

constexpr double kG = 9.81;

const char* kInertia = R"(<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>)";

/// A scene with a ground plane and the sphere of ball.urdf with its centre at height `z`.
std::string ball(double z) {
  char pose[64];
  std::snprintf(pose, sizeof pose, "0 %.17g 0 0 0 0", z);
  return std::string(R"(<Simulation><ComponentList><RCGround Key="Ground"/>
  <RCImportURDF Key="b"><File Value="ball.urdf"/><Pose><RCGlobalCoordinates><Pose Value=")") +
         pose + R"("/></RCGlobalCoordinates></Pose></RCImportURDF></ComponentList></Simulation>)";
}

/// A free sphere of radius 0.1 m and 1 kg with `tags` in its <gazebo reference="ball">.
std::string ballUrdf(const std::string& tags) {
  return std::string(R"(<robot name="b"><link name="ball"><inertial><mass value="1"/>)") + kInertia +
         R"(</inertial><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
<gazebo reference="ball">)" +
         tags + "</gazebo></robot>";
}

Model compileBall(TempDir& dir, double z, const std::string& tags) {
  dir.write("ball.urdf", ballUrdf(tags));
  const std::string scene = dir.write("ball.xml", ball(z));
  Model m;
  Diagnostics d;
  INFO(errorText(d));
  REQUIRE(compileFile(scene, &m, d));
  return m;
}

/// The usual ROS diff-drive: a 4 kg base (its centre of mass 0.1 m behind the axle: the caster
/// carries half of it), two driven wheels (r = 0.1 m, 0.34 m apart) and a fixed sphere caster
/// 0.2 m behind them, with `caster` in the caster's <gazebo reference>.
std::string diffDrive(const std::string& caster) {
  const std::string wheel = R"(<inertial><mass value="0.5"/>
      <inertia ixx="0.0013" ixy="0" ixz="0" iyy="0.0025" iyz="0" izz="0.0013"/></inertial>
    <collision><origin rpy="1.5707963267948966 0 0"/><geometry><cylinder radius="0.1" length="0.04"/></geometry></collision>)";
  return std::string(R"(<robot name="bot">
  <link name="base">
    <inertial><origin xyz="-0.1 0 0.05"/><mass value="4"/><inertia ixx="0.05" ixy="0" ixz="0" iyy="0.06" iyz="0" izz="0.1"/></inertial>
    <collision><origin xyz="-0.1 0 0.05"/><geometry><box size="0.4 0.26 0.06"/></geometry></collision>
  </link>
  <joint name="left_wheel" type="continuous"><parent link="base"/><child link="left"/>
    <origin xyz="0 0.17 0"/><axis xyz="0 1 0"/><limit effort="10" velocity="10"/></joint>
  <link name="left">)") +
         wheel + R"(</link>
  <joint name="right_wheel" type="continuous"><parent link="base"/><child link="right"/>
    <origin xyz="0 -0.17 0"/><axis xyz="0 1 0"/><limit effort="10" velocity="10"/></joint>
  <link name="right">)" +
         wheel + R"(</link>
  <joint name="caster_joint" type="fixed"><parent link="base"/><child link="caster"/>
    <origin xyz="-0.2 0 -0.05"/></joint>
  <link name="caster">
    <inertial><mass value="0.1"/><inertia ixx="0.0001" ixy="0" ixz="0" iyy="0.0001" iyz="0" izz="0.0001"/></inertial>
    <collision><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <gazebo reference="caster">)" +
         caster + R"(</gazebo>
</robot>)";
}

struct Drive {
  double heading_deg;  ///< the base's turn about the vertical after 4 s
  double speed;        ///< m/s along its start heading, from 1 s to 4 s
};

/// Both wheels at 5 rad/s (velocity drives) for 4 s, on a ground plane.
Drive driveStraight(const std::string& caster) {
  TempDir dir;
  dir.write("bot.urdf", diffDrive(caster));
  // The axles 0.1 m up: the wheels touch the ground, and so does the caster (0.05 m below the base
  // frame, radius 0.05 m).
  const std::string scene = dir.write("bot.xml", R"(<Simulation><ComponentList><RCGround Key="Ground"/>
  <RCImportURDF Key="bot"><File Value="bot.urdf"/><Drives Value="velocity"/>
    <Pose><RCGlobalCoordinates><Pose Value="0 0.1 0 0 0 0"/></RCGlobalCoordinates></Pose></RCImportURDF>
</ComponentList></Simulation>)");
  Model m;
  Diagnostics d;
  INFO(errorText(d));
  REQUIRE(compileFile(scene, &m, d));
  auto sim = simulate(m);
  REQUIRE(!sim->setCommand(sim->actuator("bot.left_wheel"), 5.0).message.size());
  REQUIRE(!sim->setCommand(sim->actuator("bot.right_wheel"), 5.0).message.size());
  const int base = bodyIndex(m, "bot.base");
  sim->runUntil(1.0);
  const double x1 = sim->world().body(base).pose.p[0];
  sim->runUntil(4.0);
  const BodyState s = sim->world().body(base);
  // URDF +X (forward) is the scene's +X; URDF +Y (left) the scene's -Z.
  const Vec3 forward = rotate(s.pose.q, Vec3{1, 0, 0});
  return {std::atan2(-forward[2], forward[0]) * 180 / kPi, (s.pose.p[0] - x1) / 3.0};
}

}  // namespace

TEST_CASE("urdf gazebo: surface tags are read at their lines, in value or text form; the rest is named as ignored",
          "[urdf][gazebo]") {
  Diagnostics d;
  const std::string text = R"(<robot name="r">
  <link name="a"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
  <link name="b"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <gazebo reference="a">
    <mu1>0</mu1>
    <mu2 value="0.25"/>
    <fdir1>1 0 0</fdir1>
    <kp>1e6</kp>
    <kd> 100 </kd>
    <minDepth>0.001</minDepth>
    <maxVel>0.1</maxVel>
    <maxContacts>2</maxContacts>
    <selfCollide>true</selfCollide>
    <turnGravityOff>true</turnGravityOff>
    <material>Gazebo/Red</material>
    <sensor name="s" type="camera"/>
  </gazebo>
  <gazebo reference="b"><gravity>false</gravity><laserRetro>1</laserRetro></gazebo>
  <gazebo reference="j"><stopCfm>0.1</stopCfm></gazebo>
  <gazebo reference="nowhere"><mu1>1</mu1></gazebo>
  <gazebo><self_collide>1</self_collide><plugin name="p" filename="x.so"/><static>true</static></gazebo>
</robot>)";
  auto robot = readUrdf(text, "r.urdf", {}, d);
  INFO(errorText(d));
  REQUIRE(robot);
  const UrdfGazebo& a = robot->links[0].gazebo;
  CHECK(a.mu1.line == 6);
  CHECK(a.mu1.value == 0);
  CHECK(a.mu2.line == 7);
  CHECK(a.mu2.value == 0.25);
  CHECK(a.fdir1_tag.line == 8);
  CHECK(a.fdir1 == Vec3{1, 0, 0});
  CHECK(a.kp.line == 9);
  CHECK(a.kp.value == 1e6);
  CHECK(a.kd.value == 100);
  CHECK(a.min_depth.value == 0.001);
  CHECK(a.max_vel.value == 0.1);
  CHECK(a.max_contacts.value == 2);
  CHECK(a.self_collide.value == 1);
  CHECK(a.gravity.line == 15);
  CHECK(a.gravity.value == 0);  // turnGravityOff true
  CHECK(robot->links[1].gazebo.gravity.line == 19);
  CHECK(robot->links[1].gazebo.gravity.value == 0);
  CHECK(robot->self_collide.line == 22);
  CHECK(robot->self_collide.value == 1);
  // The rest, once each at its line.
  std::string ignored;
  for (const UrdfNote& n : robot->ignored) ignored += std::to_string(n.line) + ": " + n.text + "\n";
  INFO(ignored);
  CHECK(ignored.find("16: <gazebo> <material> ignored") != std::string::npos);
  CHECK(ignored.find("17: <gazebo> <sensor> ignored") != std::string::npos);
  CHECK(ignored.find("19: <gazebo> <laserRetro> of a link ignored") != std::string::npos);
  CHECK(ignored.find("20: <gazebo> <stopCfm> of a joint ignored") != std::string::npos);
  CHECK(ignored.find("22: <gazebo> <plugin> ignored") != std::string::npos);
  CHECK(ignored.find("22: <gazebo> <static> ignored") != std::string::npos);
  REQUIRE(d.warnings().size() == 1);
  CHECK(d.warnings()[0].str() ==
        "r.urdf:21: <gazebo reference=\"nowhere\"> names no link or joint of the robot: its tags are ignored");
}

TEST_CASE("urdf gazebo: a value that is not a number, or out of range, is refused at its line", "[urdf][gazebo]") {
  const std::string head = R"(<robot name="r"><link name="a"/>
<gazebo reference="a">)";
  struct Case {
    const char* tag;
    const char* error;
  } cases[] = {
      {"<mu1>slippery</mu1>", "r.urdf:2: link 'a': <mu1> 'slippery' is not a number"},
      {"<mu2>-1</mu2>", "r.urdf:2: link 'a': <mu2> -1 must be finite and >= 0"},
      {"<kp>0</kp>", "r.urdf:2: link 'a': <kp> 0 must be finite and > 0"},
      {"<maxContacts>2.5</maxContacts>",
       "r.urdf:2: link 'a': <maxContacts> 2.5 must be a whole number from 1 to 1000000"},
      {"<fdir1>1 0</fdir1>", "r.urdf:2: link 'a': <fdir1> '1 0' must be three finite numbers"},
      {"<gravity>maybe</gravity>", "r.urdf:2: link 'a': <gravity> 'maybe' is not true or false"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.tag);
    Diagnostics d;
    CHECK(!readUrdf(head + c.tag + "</gazebo></robot>", "r.urdf", {}, d));
    CHECK(firstError(d) == c.error);
  }
}

TEST_CASE("urdf gazebo: the sliding-caster diff-drive (mu1 = mu2 = 0) drives straight at r w", "[urdf][gazebo]") {
  const Drive d = driveStraight("<mu1>0</mu1><mu2>0</mu2>");
  INFO("heading " << d.heading_deg << " deg, speed " << d.speed << " m/s");
  // Issue 42: under 0.5 degrees in 4 s, and r w = 0.1 m * 5 rad/s within 1 % (the wheels sink a
  // fraction of a mm into the ground at ERP 0.2: their rolling radius is 0.1 m less that).
  CHECK(std::fabs(d.heading_deg) < 0.5);
  CHECK(d.speed == Approx(0.5).epsilon(0.01));
}

TEST_CASE("urdf gazebo: the caster's surface matters: without its tags it drags (the same robot, the same drives)",
          "[urdf][gazebo]") {
  // The control of the test above: the caster's friction (the import's Friction 0.5, the larger
  // of the pair's) holds the base back, so the straight-at-r-w check can fail.
  const Drive d = driveStraight("");
  INFO("heading " << d.heading_deg << " deg, speed " << d.speed << " m/s");
  CHECK((std::fabs(d.heading_deg) >= 0.5 || std::fabs(d.speed - 0.5) > 0.005));
}

TEST_CASE("urdf gazebo: kp and kd make a spring: a resting sphere sinks m g / kp", "[urdf][gazebo]") {
  TempDir dir;
  // kp 1e4 N/m, kd 50 N s/m: damping ratio kd / (2 sqrt(kp m)) = 0.25, settled long before 3 s.
  Model m = compileBall(dir, 0.1, "<kp>10000</kp><kd>50</kd>");
  auto sim = simulate(m);
  sim->runUntil(3.0);
  const BodyState s = sim->world().body(0);
  // One contact: at rest kp * depth = m g (Gazebo's ERP and CFM are the spring-damper's implicit
  // step, exact at rest); 2 % of the 0.98 mm depth is 2e-5 m.
  CHECK(s.pose.p[1] == Approx(0.1 - kG / 1e4).margin(2e-5));
}

TEST_CASE("urdf gazebo: minDepth leaves that much penetration alone", "[urdf][gazebo]") {
  for (bool tag : {true, false}) {
    CAPTURE(tag);
    const std::string tags = tag ? "<minDepth>0.005</minDepth>" : "<mu1>0.5</mu1>";
    {
      // 3 mm inside: ODE keeps the contact from closing further and, within 5 mm, pushes out
      // nothing; without the tag it is pushed out to the surface. What is left is ERP's 0.8^steps
      // and the contact's softness (CFM 1e-10 at 1 ms: m g CFM / h = 1e-6 m).
      TempDir dir;
      auto sim = simulate(compileBall(dir, 0.097, tags));
      sim->runUntil(2.0);
      CHECK(sim->world().body(0).pose.p[1] == Approx(tag ? 0.097 : 0.1).margin(1e-5));
    }
    {
      // 8 mm inside: the first step pushes out at ERP * (depth - minDepth) / h = 0.6 m/s (without
      // the tag 0.2 * 0.008 / 0.001 = 1.6 m/s), the contact's target velocity, to its softness.
      TempDir dir;
      auto sim = simulate(compileBall(dir, 0.092, tags));
      sim->step();
      CHECK(sim->world().body(0).lin_vel[1] == Approx(tag ? 0.6 : 1.6).margin(1e-6));
    }
  }
}

TEST_CASE("urdf gazebo: maxVel bounds the push-out of a sphere started 2 cm inside the ground", "[urdf][gazebo]") {
  for (bool bounded : {true, false}) {
    CAPTURE(bounded);
    TempDir dir;
    Model m = compileBall(dir, 0.08, bounded ? "<maxVel>0.1</maxVel>" : "<mu1>0.5</mu1>");
    auto sim = simulate(m);
    double fastest = 0;
    for (int k = 0; k < 100; ++k) {
      sim->step();
      fastest = std::max(fastest, sim->world().body(0).lin_vel[1]);
    }
    // Bounded: at most 0.1 m/s (ODE reaches the target velocity within the step). Unbounded:
    // ERP 0.2 of the 0.02 m per 1 ms step is 4 m/s.
    if (bounded) {
      CHECK(fastest <= 0.1 + 1e-9);
      CHECK(fastest > 0.09);
    } else {
      CHECK(fastest > 1.0);
    }
  }
}

TEST_CASE("urdf gazebo: maxContacts 1 leaves a box on the ground one contact; gravity false floats", "[urdf][gazebo]") {
  TempDir dir;
  dir.write("box.urdf", std::string(R"(<robot name="r">
  <link name="box"><inertial><mass value="1"/>)") +
                            kInertia + R"(</inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="float"><inertial><mass value="1"/>)" +
                            kInertia + R"(</inertial></link>
  <joint name="free" type="floating"><parent link="box"/><child link="float"/><origin xyz="1 0 1"/></joint>
  <gazebo reference="box"><maxContacts>1</maxContacts></gazebo>
  <gazebo reference="float"><gravity>false</gravity></gazebo>
</robot>)");
  const std::string scene = dir.write("box.xml", R"(<Simulation><ComponentList><RCGround Key="Ground"/>
  <RCImportURDF Key="r"><File Value="box.urdf"/><Pose><RCGlobalCoordinates><Pose Value="0 0.1 0 0 0 0"/></RCGlobalCoordinates></Pose></RCImportURDF>
</ComponentList></Simulation>)");
  Model m;
  Diagnostics d;
  INFO(errorText(d));
  REQUIRE(compileFile(scene, &m, d));
  REQUIRE(m.bodies.size() == 2);
  CHECK(m.bodies[0].gravity);
  CHECK(!m.bodies[1].gravity);
  auto sim = simulate(m);
  sim->runUntil(1.0);
  CHECK(sim->world().lastContactCount() == 1);  // the settings' MaxContacts is 4: a box face gives 4
  // No force acts on the floating link: it stays where it started, exactly.
  CHECK(sim->world().body(1).pose.p[1] == m.bodies[1].pose.p[1]);
}

TEST_CASE("urdf gazebo: selfCollide on one link makes it collide with the robot's other links", "[urdf][gazebo]") {
  // 'tip' hangs on 'mid' on 'base' and its box overlaps the base's (as in urdf_import_test).
  const std::string box =
      R"(<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>)";
  for (const char* tag : {"", "<gazebo reference=\"tip\"><selfCollide>true</selfCollide></gazebo>",
                          "<gazebo><self_collide>true</self_collide></gazebo>"}) {
    CAPTURE(tag);
    const std::string urdf = R"(<robot name="fold">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/><origin xyz="0 0 1"/></joint>
  <link name="base">)" + box +
                             R"(</link>
  <joint name="j1" type="continuous"><parent link="base"/><child link="mid"/><origin xyz="0.5 0 0"/><axis xyz="0 0 1"/></joint>
  <link name="mid">)" + box + R"(</link>
  <joint name="j2" type="continuous"><parent link="mid"/><child link="tip"/><origin xyz="-0.4 0 0"/><axis xyz="0 0 1"/></joint>
  <link name="tip">)" + box + "</link>" +
                             tag + "</robot>";
    Model m = mustCompile(urdf);
    auto sim = simulate(m);
    sim->step();
    CHECK((sim->world().lastContactCount() > 0) == (*tag != 0));
  }
}

TEST_CASE("urdf gazebo: fdir1 turns the friction pyramid: mu1 = 0 along it slides, mu2 = 1 across it holds",
          "[urdf][gazebo]") {
  // Gravity tilted 20 degrees towards +x: a slope of 20 degrees under a 0.2 m box. With mu1 = 0
  // along fdir1 and mu2 = 1 across it, the box slides freely when fdir1 points down the slope
  // (URDF x = scene x) and holds (tan 20 deg = 0.36 < 1) when it points across (URDF y = scene -z).
  const double theta = 20 * kPi / 180, down = kG * std::sin(theta);
  char gravity[96];
  std::snprintf(gravity, sizeof gravity, "%.17g %.17g 0", down, -kG * std::cos(theta));
  for (const char* fdir : {"1 0 0", "0 1 0"}) {
    CAPTURE(fdir);
    TempDir dir;
    dir.write("box.urdf", std::string(R"(<robot name="r"><link name="box"><inertial><mass value="1"/>)") + kInertia +
                              R"(</inertial><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <gazebo reference="box"><mu1>0</mu1><mu2>1</mu2><fdir1>)" +
                              fdir + "</fdir1></gazebo></robot>");
    const std::string scene = dir.write("box.xml", std::string("<Simulation><SceneSettings><Gravity Value=\"") +
                                                       gravity + R"("/></SceneSettings><ComponentList>
  <RCGround Key="Ground"/>
  <RCImportURDF Key="r"><File Value="box.urdf"/><Pose><RCGlobalCoordinates><Pose Value="0 0.1 0 0 0 0"/></RCGlobalCoordinates></Pose></RCImportURDF>
</ComponentList></Simulation>)");
    Model m;
    Diagnostics d;
    INFO(errorText(d));
    REQUIRE(compileFile(scene, &m, d));
    auto sim = simulate(m);
    sim->runUntil(1.0);
    const double x = sim->world().body(0).pose.p[0];
    if (fdir[0] == '1') {
      // Free along the slope: g sin(theta) t^2 / 2; semi-implicit Euler over n = 1000 steps adds
      // 1/n of it (1.7 mm).
      CHECK(x == Approx(down / 2).margin(3e-3));
    } else {
      CHECK(std::fabs(x) < 1e-3);  // held by mu2 = 1 (ODE's friction pyramid: no creep at rest)
    }
  }
}
