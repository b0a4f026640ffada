// RCDriveTest and RCServoTest (guide 6.12.1, 6.12.2) end to end on a flywheel: a body of
// inertia I = 1 kg m^2 on a hinge about +Y hanging on the static world, no gravity, no contacts.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "scene/scene_helpers.h"
#include "simbob/robot.h"
#include "simbob/loop.h"
#include "simbob/simulation.h"

using namespace simbob;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The flywheel robot with `periphery` on hinge Bot.C.H and `controller` in its ControllerList.
std::string flywheel(const std::string& periphery, const std::string& controller) {
  return R"(<Simulation><SceneSettings><Gravity Value="0 0 0"/></SceneSettings><ComponentList>
<RCRobot Key="Bot"><Construction><RCConstruction Key="C">
  <Body><RCStaticRigidBody Key="Base"/></Body>
  <ChildList>
    <RCHingeJoint Key="H">
      <Hinge><RCLocalCoordinates><Pose Value="0 0 0 -90 0 0"/></RCLocalCoordinates></Hinge>
      <Body><RCMobileRigidBody Key="Wheel">
        <Inertia><RCGenericInertia><Mass Value="1"/><Inertia Value="1 0 0 0 1 0 0 0 1"/></RCGenericInertia></Inertia>
      </RCMobileRigidBody></Body>
    </RCHingeJoint>
)" + periphery +
         R"(
  </ChildList></RCConstruction></Construction>
  <ControllerList>)" +
         controller + R"(</ControllerList></RCRobot>
</ComponentList></Simulation>)";
}

/// The wheel's angle about +Y (right-hand rule) at every sample.
std::vector<double> angles(const Model& m, double duration, double interval) {
  std::vector<double> out;
  SimulationOptions o;
  o.duration = duration;
  Diagnostics d;
  std::unique_ptr<Simulation> sim = Simulation::fromModel(m, o, d);
  REQUIRE(sim);
  double turns = 0, last = 0;
  sim->sampleTrajectory(nullptr, interval, [&](double, const double* p) {
    // Unwrapped: q = (cos a/2, 0, sin a/2, 0) for a turn a about Y.
    double a = 2 * std::atan2(p[5], p[3]);
    if (!out.empty() && a - last > kPi) turns -= 2 * kPi;
    if (!out.empty() && a - last < -kPi) turns += 2 * kPi;
    last = a;
    out.push_back(a + turns);
  });
  RunResult r = sim->runToEnd();
  REQUIRE(r.status == RunStatus::Completed);
  return out;
}

}  // namespace

TEST_CASE("robot: RCDriveTest turns a flywheel by the integral of its sine voltage", "[robot]") {
  // u(t) = sin(2 pi f t), f = Variation / 60 = 0.5 Hz (T = 2 s), torque u P with P = pi/2 N m
  // (MaxVelocity far away: no stall fade), I = 1: the angle is
  //   theta(t) = (P / I) / (2 pi f) * (t - sin(2 pi f t) / (2 pi f)),
  // so theta(T/2) = 0.5 rad and theta(T) = 1 rad. The controller holds u for its Period (1 ms)
  // and the step is 1 ms: a first-order error of about 1e-3 relative; tolerance 1 %.
  const std::string drive = R"(<RCGenericDrive Key="D"><Joint Ref="Bot.C.H"/><MaxPower Value="1.5707963267948966"/>
      <MaxVelocity Value="1000"/></RCGenericDrive>)";
  const std::string ctl = R"(<RCDriveTest Key="T"><Drive Ref="Bot.C.D"/><Period Value="0.001"/>
      <Variation Value="30"/></RCDriveTest>)";
  Model m = scenetest::mustCompile(flywheel(drive, ctl));
  REQUIRE(m.actuators.size() == 1);
  std::vector<double> a = angles(m, 2.0, 0.5);  // samples at 0, 0.5, 1, 1.5, 2 s
  REQUIRE(a.size() == 5);
  auto theta = [](double t) {
    const double w = 2 * kPi * 0.5;
    return (kPi / 2) / w * (t - std::sin(w * t) / w);
  };
  CHECK(a[0] == 0.0);
  for (size_t i = 1; i < a.size(); ++i) {
    INFO("t = " << 0.5 * static_cast<double>(i));
    CHECK(a[i] == Approx(theta(0.5 * static_cast<double>(i))).epsilon(0.01));
  }
  CHECK(a[2] == Approx(0.5).epsilon(0.01));
  CHECK(a[4] == Approx(1.0).epsilon(0.01));
}

TEST_CASE("robot: RCServoTest moves its servo between MinPos and MaxPos at constant speed", "[robot]") {
  // Limits [-0.5, 0.5] rad, Variation 6 per minute (T = 10 s): the target rises at 0.2 rad/s
  // from -0.5 at t = 0 to 0.5 at t = 5 s and falls back by t = 10 s. The servo follows with a
  // lag of Smooth x speed = 0.01 s x 0.2 rad/s = 0.002 rad (MaxPower and MaxVelocity ample);
  // tolerance 0.01 rad. The start pose is 0, so the servo first runs to -0.5 at MaxVelocity
  // 1 rad/s (0.5 s), and never leaves [MinPos, MaxPos] (stops), within 1e-3.
  const std::string servo = R"(<RCGenericServo Key="S"><Joint Ref="Bot.C.H"/><MaxPower Value="100"/>
      <MaxVelocity Value="1"/><MinPos Value="-0.5"/><MaxPos Value="0.5"/><Smooth Value="0.01"/></RCGenericServo>)";
  const std::string ctl = R"(<RCServoTest Key="T"><PosControl Ref="Bot.C.S"/><Period Value="0.01"/>
      <Variation Value="6"/></RCServoTest>)";
  Model m = scenetest::mustCompile(flywheel(servo, ctl));
  std::vector<double> a = angles(m, 10.0, 0.5);
  REQUIRE(a.size() == 21);
  auto target = [](double t) {
    const double f = t / 10 - std::floor(t / 10);
    return -0.5 + (f < 0.5 ? 2 * f : 2 - 2 * f);
  };
  for (size_t i = 2; i < a.size(); ++i) {  // from 1 s, after the run to the start of the ramp
    const double t = 0.5 * static_cast<double>(i);
    INFO("t = " << t);
    CHECK(a[i] == Approx(target(t)).margin(0.01));
  }
  for (double x : a) {
    CHECK(x >= -0.5 - 1e-3);
    CHECK(x <= 0.5 + 1e-3);
  }
  CHECK(a[10] == Approx(0.5).margin(0.01));  // t = 5 s: the top of the ramp
}
