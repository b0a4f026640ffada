// Imported URDF robots against analytic answers (lib/components/urdf_import.cpp, lib/urdf):
// a pendulum whose mass is away from its link origin, a prismatic stop, a fixed child lumped into
// its parent, a mimic joint, and a two-link arm that gives the same bytes as the arm written in
// simbob XML. Tolerances say where they come from.
#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "simbob/transform.h"
#include "urdf/urdf_test_util.h"

using namespace urdftest;

namespace {

constexpr double kG = 9.81;

}  // namespace

TEST_CASE("urdf import: a pendulum with its mass away from the link origin swings with the elliptic period", "[urdf]") {
  // The bob's <inertial> sits 1 m from the pivot (the link origin), 60 degrees from the vertical.
  const double L = 1.0, m = 2.0, Ic = 0.01, theta0 = kPi / 3;
  char origin[128];
  std::snprintf(origin, sizeof origin, "%.17g 0 %.17g", L * std::sin(theta0), -L * std::cos(theta0));
  const std::string urdf = std::string(R"(<robot name="pendulum">
  <link name="world"/>
  <joint name="pivot" type="continuous">
    <parent link="world"/><child link="bob"/>
    <origin xyz="0 0 2"/><axis xyz="0 1 0"/>
  </joint>
  <link name="bob">
    <inertial><origin xyz=")") +
                           origin + R"("/><mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
</robot>)";
  Model model = mustCompile(urdf);
  REQUIRE(model.bodies.size() == 1);
  CHECK(model.bodies[0].key == "pendulum.bob");
  CHECK(model.bodies[0].com == Vec3{L * std::sin(theta0), 0, -L * std::cos(theta0)});  // link frame, as written
  auto sim = simulate(model);
  const int j = sim->joint("pendulum.pivot");
  REQUIRE(j >= 0);
  // theta'' = -(m g L / (Ic + m L^2)) sin(theta): T = 4 K(sin(theta0/2)) / w0.
  const double w0 = std::sqrt(m * kG * L / (Ic + m * L * L));
  const double expected = 4 * ellipticK(std::sin(theta0 / 2)) / w0;
  // The mass hangs straight down at q = theta0 (turning about +Y carries URDF x into -z): it
  // passes there twice a period, at its fastest. The row is the link frame: it stays at the pivot
  // while the mass swings.
  const Swing sw = swing(*sim, j, theta0, 0, {0, 2, 0}, 8000);
  REQUIRE(sw.crossings >= 6);
  const double period = sw.period, worst_pivot = sw.worst_pivot;
  INFO("period " << period << " s, expected " << expected << " s");
  // Semi-implicit Euler at 1 ms shifts the period by O(h w0) of it; 0.5 % is generous for that.
  CHECK(std::fabs(period - expected) / expected < 0.005);
  // The joint's constraint error (ODE corrects it with ERP 0.2 per step), not the 0.87 m the
  // mass travels: a few mm at most.
  CHECK(worst_pivot < 5e-3);
}

TEST_CASE("urdf import: a prismatic joint falls freely and stops at its lower limit", "[urdf]") {
  Model model = mustCompile(R"(<robot name="slide">
  <link name="world"/>
  <joint name="rail" type="prismatic">
    <parent link="world"/><child link="cart"/>
    <origin xyz="0 0 1"/><axis xyz="0 0 1"/>
    <limit lower="-0.25" upper="0.5" effort="10" velocity="1"/>
  </joint>
  <link name="cart">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
</robot>)");
  REQUIRE(model.joints.size() == 1);
  CHECK(model.joints[0].kind == JointKind::Slider);
  CHECK(model.joints[0].lo_stop == -0.25);
  CHECK(model.joints[0].hi_stop == 0.5);
  CHECK(model.actuators.empty());  // passive: no hidden motor
  auto sim = simulate(model);
  const int j = sim->joint("slide.rail");
  sim->runUntil(0.1);
  // Free fall along the axis: -g t^2 / 2, to Euler's O(g h t) = 1e-3 m.
  CHECK(sim->world().joint(j).position == Approx(-kG * 0.01 / 2).margin(1.5e-3));
  sim->runUntil(2.0);
  // Resting on the stop: the stop holds within ERP's residual (m g CFM and a fraction of a step's fall).
  CHECK(sim->world().joint(j).position == Approx(-0.25).margin(1e-3));
  CHECK(std::fabs(sim->world().joint(j).velocity) < 1e-3);
}

TEST_CASE("urdf import: a fixed child with an offset inertia moves as the single equivalent body", "[urdf]") {
  const std::string urdf = R"(<robot name="lump">
  <link name="world"/>
  <joint name="hinge" type="continuous">
    <parent link="world"/><child link="base"/><origin xyz="0 0 2"/><axis xyz="0 1 0"/>
  </joint>
  <link name="base">
    <inertial><origin xyz="0.2 0 0"/><mass value="2"/>
      <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.04"/></inertial>
  </link>
  <joint name="weld" type="fixed">
    <parent link="base"/><child link="tip"/><origin xyz="0.5 0.2 -0.1" rpy="0.3 -0.2 0.5"/>
  </joint>
  <link name="tip">
    <inertial><origin xyz="0.1 0 0.05" rpy="0.1 0.4 -0.3"/><mass value="1"/>
      <inertia ixx="0.01" ixy="0.001" ixz="0" iyy="0.02" iyz="0.002" izz="0.015"/></inertial>
  </link>
</robot>)";
  Model model = mustCompile(urdf);
  REQUIRE(model.bodies.size() == 1);  // the tip is lumped into the base
  REQUIRE(model.frames.size() == 1);  // and keeps a trajectory row of its own
  CHECK(model.frames[0].key == "lump.tip");

  // The equivalent body, computed here with Eigen's own rotations (URDF rpy: Rz(y) Ry(p) Rx(r)).
  auto rpy = [](double r, double p, double y) {
    return Eigen::Matrix3d(
        (Eigen::AngleAxisd(y, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(p, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(r, Eigen::Vector3d::UnitX())));
  };
  const Eigen::Matrix3d Rw = rpy(0.3, -0.2, 0.5), Ri = rpy(0.1, 0.4, -0.3);
  const Eigen::Vector3d c_base(0.2, 0, 0);
  const Eigen::Vector3d c_tip = Eigen::Vector3d(0.5, 0.2, -0.1) + Rw * Eigen::Vector3d(0.1, 0, 0.05);
  Eigen::Matrix3d I_base = Eigen::Vector3d(0.02, 0.03, 0.04).asDiagonal();
  Eigen::Matrix3d I_tip;
  I_tip << 0.01, 0.001, 0, 0.001, 0.02, 0.002, 0, 0.002, 0.015;
  I_tip = (Rw * Ri) * I_tip * (Rw * Ri).transpose();
  const Eigen::Vector3d com = (2 * c_base + 1 * c_tip) / 3;
  auto shift = [&](double mass, const Eigen::Vector3d& c) {
    const Eigen::Vector3d d = c - com;
    return Eigen::Matrix3d(mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose()));
  };
  const Eigen::Matrix3d I = I_base + shift(2, c_base) + I_tip + shift(1, c_tip);
  const BodyDef& b = model.bodies[0];
  CHECK(b.mass == Approx(3.0));
  for (int k = 0; k < 3; ++k) CHECK(b.com[static_cast<size_t>(k)] == Approx(com[k]).margin(1e-14));
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) CHECK(b.inertia[static_cast<size_t>(r * 3 + c)] == Approx(I(r, c)).margin(1e-14));

  // The same body written by hand swings exactly alike; the tip's row rides along.
  Model hand = model;
  hand.frames.clear();
  hand.bodies[0].com = {com[0], com[1], com[2]};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) hand.bodies[0].inertia[static_cast<size_t>(r * 3 + c)] = I(r, c);
  auto a = simulate(model), h = simulate(hand);
  double worst = 0;
  for (int step = 0; step < 2000; ++step) {
    a->step();
    h->step();
    const BodyState sa = a->world().body(0), sh = h->world().body(0);
    for (size_t k = 0; k < 3; ++k) worst = std::max(worst, std::fabs(sa.pose.p[k] - sh.pose.p[k]));
  }
  INFO("largest difference " << worst << " m");
  CHECK(worst < 1e-9);  // the mass properties agree to rounding (1e-14); 2 s of swinging keep that small
  CHECK(std::fabs(a->world().joint(0).position) > 0.1);  // it did swing (about its link frame's origin)
}

TEST_CASE("urdf import: a mimic joint follows its leader's multiplier and offset", "[urdf]") {
  TempDir dir;
  dir.write("gear.urdf", R"(<robot name="gear">
  <link name="world"/>
  <joint name="a" type="continuous">
    <parent link="world"/><child link="wa"/><origin xyz="0 0 1"/><axis xyz="0 0 1"/>
    <limit effort="10" velocity="2"/>
  </joint>
  <link name="wa"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="b" type="continuous">
    <parent link="world"/><child link="wb"/><origin xyz="1 0 1"/><axis xyz="0 0 1"/>
    <limit effort="50" velocity="10"/>
    <mimic joint="a" multiplier="-2" offset="0.3"/>
  </joint>
  <link name="wb"><inertial><mass value="1"/>
    <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial></link>
</robot>)");
  const std::string scene = dir.write("gear.xml", R"(<Simulation><ComponentList>
  <RCImportURDF Key="gear"><File Value="gear.urdf"/><Drives Value="position"/></RCImportURDF>
</ComponentList></Simulation>)");
  Model model;
  Diagnostics d;
  REQUIRE(compileFile(scene, &model, d));
  REQUIRE(model.actuators.size() == 1);  // the mimic joint is held by its constraint, not a drive
  CHECK(model.actuators[0].key == "gear.a");
  auto sim = simulate(model);
  const int a = sim->joint("gear.a"), b = sim->joint("gear.b");
  REQUIRE(!sim->setCommand(sim->actuator("gear.a"), 1.0).message.size());
  double worst = 0;
  while (sim->time() < 3.0) {
    sim->step();
    const double lag = sim->world().joint(b).position - (-2 * sim->world().joint(a).position + 0.3);
    if (sim->time() > 0.1) worst = std::max(worst, std::fabs(lag));  // after closing the start offset
  }
  CHECK(sim->world().joint(a).position == Approx(1.0).margin(1e-3));
  CHECK(sim->world().joint(b).position == Approx(-1.7).margin(2e-3));
  // The motor closes the gap within 5 steps with the leader's velocity fed forward: the lag
  // stays below a few steps of the leader's 2 rad/s times the multiplier 2 (4 mrad per step).
  CHECK(worst < 0.02);
}

TEST_CASE("urdf import: a two-link arm gives the same trajectory bytes as the arm written in simbob XML", "[urdf]") {
  // The arm in the scene format: links of 1 m x 0.1 m x 0.1 m boxes whose mass the geometry
  // places at their middle, hinged about the scene's Z at (0, 2, 0) and (1, 2, 0); each body
  // frame is its link's URDF frame (turned -90 degrees about X: URDF Z up, scene Y up).
  const std::string xml = R"(<Simulation><ComponentList>
  <RCConstruction Key="arm">
    <Body><RCStaticRigidBody Key="world"/></Body>
    <ChildList>
      <RCHingeJoint Key="shoulder">
        <Pose><RCGlobalCoordinates><Pose Value="0 2 0 0 0 0"/></RCGlobalCoordinates></Pose>
        <Body><RCConstruction Key="upperC">
          <Body><RCMobileRigidBody Key="upper">
            <Pose><RCGlobalCoordinates><Pose Value="0 2 0 -90 0 0"/></RCGlobalCoordinates></Pose>
            <Geom><RCTransformGeom>
              <Pose><RCLocalCoordinates><Pose Value="0.5 0 0 0 0 0"/></RCLocalCoordinates></Pose>
              <SubGeom><RCCuboidGeom><Width Value="1"/><Height Value="0.1"/><Depth Value="0.1"/></RCCuboidGeom></SubGeom>
            </RCTransformGeom></Geom>
            <Inertia><RCInertiaByGeom><Mass Value="1"/></RCInertiaByGeom></Inertia>
          </RCMobileRigidBody></Body>
          <ChildList>
            <RCHingeJoint Key="elbow">
              <Pose><RCGlobalCoordinates><Pose Value="1 2 0 0 0 0"/></RCGlobalCoordinates></Pose>
              <Body><RCMobileRigidBody Key="lower">
                <Pose><RCGlobalCoordinates><Pose Value="1 2 0 -90 0 0"/></RCGlobalCoordinates></Pose>
                <Geom><RCTransformGeom>
                  <Pose><RCLocalCoordinates><Pose Value="0.5 0 0 0 0 0"/></RCLocalCoordinates></Pose>
                  <SubGeom><RCCuboidGeom><Width Value="1"/><Height Value="0.1"/><Depth Value="0.1"/></RCCuboidGeom></SubGeom>
                </RCTransformGeom></Geom>
                <Inertia><RCInertiaByGeom><Mass Value="0.5"/></RCInertiaByGeom></Inertia>
              </RCMobileRigidBody></Body>
            </RCHingeJoint>
          </ChildList>
        </RCConstruction></Body>
      </RCHingeJoint>
    </ChildList>
  </RCConstruction>
</ComponentList></Simulation>)";
  const Model hand = scenetest::mustCompile(xml);
  REQUIRE(hand.bodies.size() == 2);
  REQUIRE(hand.joints.size() == 2);
  // The URDF says the same arm with the numbers the scene format computed (printed exactly):
  // the elbow joint first, as the scene's nesting creates it first.
  auto inertial = [&](const BodyDef& b) {
    char s[512];
    std::snprintf(s, sizeof s,
                  "<inertial><origin xyz=\"%.17g %.17g %.17g\"/><mass value=\"%.17g\"/><inertia ixx=\"%.17g\" "
                  "ixy=\"%.17g\" ixz=\"%.17g\" iyy=\"%.17g\" iyz=\"%.17g\" izz=\"%.17g\"/></inertial>",
                  b.com[0], b.com[1], b.com[2], b.mass, b.inertia[0], b.inertia[1], b.inertia[2], b.inertia[4],
                  b.inertia[5], b.inertia[8]);
    return std::string(s);
  };
  const std::string box =
      R"(<collision><origin xyz="0.5 0 0"/><geometry><box size="1 0.1 0.1"/></geometry></collision>)";
  TempDir dir;
  dir.write("arm.urdf", R"(<robot name="arm">
  <link name="world"/>
  <joint name="elbow" type="continuous"><parent link="upper"/><child link="lower"/>
    <origin xyz="1 0 0"/><axis xyz="0 -1 0"/></joint>
  <joint name="shoulder" type="continuous"><parent link="world"/><child link="upper"/>
    <origin xyz="0 0 2"/><axis xyz="0 -1 0"/></joint>
  <link name="upper">)" + inertial(hand.bodies[0]) +
                            box + R"(</link>
  <link name="lower">)" + inertial(hand.bodies[1]) +
                            box + R"(</link>
</robot>)");
  const std::string scene = dir.write("arm.xml", R"(<Simulation><ComponentList>
  <RCImportURDF Key="arm"><File Value="arm.urdf"/></RCImportURDF></ComponentList></Simulation>)");
  Model imported;
  Diagnostics d;
  INFO(errorText(d));
  REQUIRE(compileFile(scene, &imported, d));
  REQUIRE(imported.bodies.size() == 2);
  for (size_t i = 0; i < 2; ++i) {
    INFO("body " << i);
    CHECK(std::memcmp(&imported.bodies[i].pose, &hand.bodies[i].pose, sizeof(Transform)) == 0);
    CHECK(imported.bodies[i].com == hand.bodies[i].com);
    CHECK(imported.bodies[i].inertia == hand.bodies[i].inertia);
    CHECK(imported.joints[i].anchor == hand.joints[i].anchor);
    CHECK(imported.joints[i].axis == hand.joints[i].axis);
  }
  auto a = simulate(imported), h = simulate(hand);
  bool same = true;
  for (int step = 0; step < 3000 && same; ++step) {
    a->step();
    h->step();
    for (int i = 0; i < 2; ++i) {
      const BodyState sa = a->world().body(i), sh = h->world().body(i);
      same = same && std::memcmp(&sa.pose, &sh.pose, sizeof(Transform)) == 0;
    }
  }
  CHECK(same);  // bit for bit, 3 s of a double pendulum (chaotic: any rounding would show)
  CHECK(std::fabs(a->world().joint(1).position) > 0.1);  // it did swing
}

TEST_CASE("urdf dart-doc: KR5 with position drives holds every joint at 0 and reaches a target by the servo law",
          "[urdf][dart]") {
  TempDir dir;
  const std::string scene = dir.write("kr5.xml", R"(<Simulation><ComponentList>
  <RCImportURDF Key="kr5"><File Value=")" + kDart + R"(/KR5/KR5 sixx R650.urdf"/>
    <Drives Value="position"/><MaxForce Value="500"/><Smooth Value="0.05"/></RCImportURDF>
</ComponentList></Simulation>)");
  Model model;
  Diagnostics d;
  INFO(errorText(d));
  REQUIRE(compileFile(scene, &model, d));
  REQUIRE(model.actuators.size() == 6);
  CHECK(model.actuators[0].key == "kr5.shoulder_yaw");
  CHECK(model.actuators[0].max_power == 500);       // effort="0" in the file: MaxForce
  CHECK(model.actuators[0].max_velocity == 6.545);  // the file's velocity
  auto sim = simulate(model);
  std::vector<Vec3> start;
  for (int i = 0; i < sim->world().bodyCount(); ++i) start.push_back(sim->world().body(i).pose.p);
  double worst = 0;
  while (sim->time() < 5.0 - 1e-9) {
    sim->step();
    for (int i = 0; i < sim->world().bodyCount(); ++i)
      worst = std::max(worst, norm(sub(sim->world().body(i).pose.p, start[static_cast<size_t>(i)])));
  }
  INFO("largest displacement of a link frame " << worst << " m");
  CHECK(worst < 1e-3);
  // Shoulder yaw to 0.5 rad: the servo turns at MaxVelocity 6.545 rad/s until the error is
  // MaxVelocity * Smooth = 0.327 rad, then the error decays as exp(-t / Smooth).
  const int j = sim->joint("kr5.shoulder_yaw");
  REQUIRE(!sim->setCommand(sim->actuator("kr5.shoulder_yaw"), 0.5).message.size());
  const double t0 = sim->time(), vmax = 6.545, smooth = 0.05, knee = vmax * smooth;
  const double t1 = t0 + (0.5 - knee) / vmax;
  auto law = [&](double t) { return t < t1 ? vmax * (t - t0) : 0.5 - knee * std::exp(-(t - t1) / smooth); };
  for (double t : {t0 + 0.02, t1 + 0.05, t1 + 0.15, t0 + 1.0}) {
    sim->runUntil(t);
    INFO("t - t0 = " << sim->time() - t0);
    // 500 N m accelerates the arm to MaxVelocity in a few ms: the law holds to that lag (~0.02 rad).
    CHECK(sim->world().joint(j).position == Approx(law(sim->time())).margin(0.02));
  }
  // At rest the motor's constraint, solved by QuickStep's 20 iterations, leaves a steady error
  // against gravity's pull on the arm (lying on its side here): a fraction of a mrad.
  CHECK(sim->world().joint(j).position == Approx(0.5).margin(1e-3));
}

TEST_CASE("urdf import: a revolute stop beyond 180 degrees holds (the stops see the unwrapped angle)", "[urdf]") {
  TempDir dir;
  dir.write("turn.urdf", R"(<robot name="turn">
  <link name="world"/>
  <joint name="spin" type="revolute">
    <parent link="world"/><child link="wheel"/><origin xyz="0 0 1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="4" effort="0.5" velocity="100"/>
  </joint>
  <link name="wheel"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
</robot>)");
  const std::string scene = dir.write("turn.xml", R"(<Simulation><ComponentList>
  <RCImportURDF Key="turn"><File Value="turn.urdf"/><Drives Value="effort"/></RCImportURDF>
</ComponentList></Simulation>)");
  Model model;
  Diagnostics d;
  INFO(errorText(d));
  REQUIRE(compileFile(scene, &model, d));
  auto sim = simulate(model);
  const int j = sim->joint("turn.spin");
  // 0.5 N m on 0.01 kg m^2: 50 rad/s^2, 4 rad in 0.4 s; without the stop 25 rad after 1 s.
  REQUIRE(!sim->setCommand(sim->actuator("turn.spin"), 0.5).message.size());
  sim->runUntil(1.0);
  CHECK(sim->world().joint(j).position == Approx(4.0).margin(5e-3));
  REQUIRE(!sim->setCommand(sim->actuator("turn.spin"), -0.5).message.size());
  sim->runUntil(3.0);  // back through the wrap at -pi .. pi and on to the lower stop
  CHECK(sim->world().joint(j).position == Approx(-1.0).margin(5e-3));
}

TEST_CASE("urdf import: a RigidBodyClone of an import copies its bodies, joints, drives and rows", "[urdf]") {
  TempDir dir;
  dir.write("arm.urdf", R"(<robot name="arm">
  <link name="base"/>
  <joint name="turn" type="revolute"><parent link="base"/><child link="disc"/>
    <origin xyz="0 0 1"/><axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="5" velocity="1"/></joint>
  <link name="disc"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
</robot>)");
  const std::string scene = dir.write("two.xml", R"(<Simulation><ComponentList>
  <RCImportURDF Key="A"><File Value="arm.urdf"/><FixedBase Value="true"/><Drives Value="velocity"/></RCImportURDF>
  <RigidBodyClone Key="B"><Original Value="A"/>
    <Pose><RCGlobalCoordinates><Pose Value="3 0 0 0 0 0"/></RCGlobalCoordinates></Pose></RigidBodyClone>
</ComponentList></Simulation>)");
  Model m;
  Diagnostics d;
  INFO(errorText(d));
  REQUIRE(compileFile(scene, &m, d));
  REQUIRE(m.bodies.size() == 2);
  CHECK(m.bodies[1].key == "B.disc");
  CHECK(m.bodies[1].pose.p[0] == Approx(3.0));
  REQUIRE(m.joints.size() == 2);
  CHECK(m.joints[1].key == "B.turn");
  CHECK(m.joints[1].anchor[0] == Approx(3.0));
  REQUIRE(m.actuators.size() == 2);
  CHECK(m.actuators[1].key == "B.turn");
  CHECK(m.actuators[1].kind == ActuatorDef::VelDrive);
  REQUIRE(m.frames.size() == 2);  // each base is fixed to the world and keeps its row, moved with its copy
  CHECK(m.frames[0].key == "A.base");
  CHECK(m.frames[1].key == "B.base");
  CHECK(m.frames[1].offset.p[0] == Approx(3.0));
}

TEST_CASE("urdf import: a free STL cube modelled in millimetres, scale 0.001, comes to rest at half its size",
          "[urdf][mesh]") {
  TempDir dir;
  const std::string stl = std::string(SIMBOB_SOURCE_DIR) + "/tests/data/meshes/cube_100mm.stl";  // 100 mm, centred
  dir.write("cube.urdf", R"(<robot name="cube"><link name="cube">
  <inertial><mass value="1"/><inertia ixx="0.0016667" ixy="0" ixz="0" iyy="0.0016667" iyz="0" izz="0.0016667"/></inertial>
  <visual><geometry><mesh filename=")" +
                             stl + R"(" scale="0.001 0.001 0.001"/></geometry></visual>
  <collision><geometry><mesh filename=")" +
                             stl + R"(" scale="0.001 0.001 0.001"/></geometry></collision>
</link></robot>)");
  const std::string scene = dir.write("cube.xml", R"(<Simulation><ComponentList><RCGround Key="Ground"/>
  <RCImportURDF Key="cube"><File Value="cube.urdf"/>
    <Pose><RCGlobalCoordinates><Pose Value="0 0.3 0 0 0 0"/></RCGlobalCoordinates></Pose></RCImportURDF>
</ComponentList></Simulation>)");
  Model m;
  Diagnostics d;
  INFO(errorText(d));
  REQUIRE(compileFile(scene, &m, d));
  REQUIRE(m.meshes.size() == 1);  // the visual and the collision share one read
  CHECK(m.meshes[0].data->hi[0] == Approx(0.05));
  int hulls = 0;
  for (const GeomDef& g : m.geoms) hulls += g.shape == GeomShape::ConvexHull && g.body == 0;
  CHECK(hulls == 1);
  auto sim = simulate(m);
  sim->runUntil(2.0);
  const BodyState s = sim->world().body(0);
  // Resting on its face: the link frame (the cube's centre) half the 0.1 m size above the ground,
  // to ODE's contact softness (a fraction of a mm at ERP 0.2, CFM 1e-10).
  CHECK(s.pose.p[1] == Approx(0.05).margin(1e-3));
  CHECK(std::fabs(s.lin_vel[1]) < 1e-3);
}

TEST_CASE("urdf import: the links of one robot do not collide with each other unless SelfCollision", "[urdf]") {
  // 'tip' hangs on 'mid' on 'base' and its box overlaps the base's: CAD shapes of neighbours do.
  TempDir dir;
  const std::string box =
      R"(<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>)";
  dir.write("fold.urdf", R"(<robot name="fold">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/><origin xyz="0 0 1"/></joint>
  <link name="base">)" + box +
                             R"(</link>
  <joint name="j1" type="continuous"><parent link="base"/><child link="mid"/><origin xyz="0.5 0 0"/><axis xyz="0 0 1"/></joint>
  <link name="mid">)" + box + R"(</link>
  <joint name="j2" type="continuous"><parent link="mid"/><child link="tip"/><origin xyz="-0.4 0 0"/><axis xyz="0 0 1"/></joint>
  <link name="tip">)" + box + R"(</link>
</robot>)");
  for (bool self : {false, true}) {
    CAPTURE(self);
    const std::string scene = dir.write(
        "fold.xml", std::string("<Simulation><ComponentList><RCImportURDF Key=\"fold\"><File Value=\"fold.urdf\"/>") +
                        "<SelfCollision Value=\"" + (self ? "true" : "false") +
                        "\"/></RCImportURDF></ComponentList></Simulation>");
    Model m;
    Diagnostics d;
    INFO(errorText(d));
    REQUIRE(compileFile(scene, &m, d));
    auto sim = simulate(m);
    sim->step();
    // The tip overlaps the (static) base by 0.1 m: contacts only when the robot may touch itself.
    CHECK((sim->world().lastContactCount() > 0) == self);
  }
}

TEST_CASE("urdf import: a robot fixed to the world with a moving link in the ground is refused in a scene as bare",
          "[urdf]") {
  // Issue 42 point 5: one rule for a bare .urdf and a scene's RCImportURDF. The upper arm hangs
  // 0.4 m into the ground (its box from z = -0.4 to 0.1): ODE would tear the joint apart.
  TempDir dir;
  const std::string urdf = dir.write("arm.urdf", R"(<robot name="arm">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><origin xyz="0 0 0.1"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
  <link name="upper"><inertial><mass value="1"/><inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.001"/></inertial>
    <collision><origin xyz="0 0 -0.25"/><geometry><box size="0.05 0.05 0.5"/></geometry></collision></link>
</robot>)");
  const std::string tail = " (is the file's up axis +Z?)";
  {
    Model m;
    Diagnostics d;
    CHECK(!compileFile(urdf, &m, d));
    CHECK(firstError(d) == urdf +
                               ":6: link 'upper' of a robot fixed to the world starts 0.4 m inside the ground: a robot "
                               "fixed to the world is not raised; place it with RCImportURDF's Pose in a scene" +
                               tail);
    CHECK(d.errors().size() == 1);
  }
  // In a scene, the ground written before or after the robot: the same refusal, naming the plane.
  for (bool ground_first : {true, false}) {
    CAPTURE(ground_first);
    const std::string ground = R"(<RCGround Key="Floor"/>)";
    const std::string import = R"(<RCImportURDF Key="arm"><File Value="arm.urdf"/></RCImportURDF>)";
    const std::string scene =
        dir.write("arm.xml", "<Simulation><ComponentList>" + (ground_first ? ground + import : import + ground) +
                                 "</ComponentList></Simulation>");
    Model m;
    Diagnostics d;
    CHECK(!compileFile(scene, &m, d));
    CHECK(firstError(d) == urdf +
                               ":6: link 'upper' of a robot fixed to the world starts 0.4 m inside the plane of "
                               "'Floor': a robot fixed to the world is not raised; move it with RCImportURDF's Pose" +
                               tail);
    CHECK(d.errors().size() == 1);
  }
  // Stood 0.5 m up with its Pose, it loads.
  const std::string up = dir.write("up.xml", R"(<Simulation><ComponentList><RCGround Key="Floor"/>
  <RCImportURDF Key="arm"><File Value="arm.urdf"/>
    <Pose><RCGlobalCoordinates><Pose Value="0 0.5 0 0 0 0"/></RCGlobalCoordinates></Pose></RCImportURDF>
</ComponentList></Simulation>)");
  Model m;
  Diagnostics d;
  INFO(errorText(d));
  CHECK(compileFile(up, &m, d));
}
