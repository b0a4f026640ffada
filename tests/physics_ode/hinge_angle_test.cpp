// simbob reads a hinge's angle itself (lib/physics/hinge_angle.cpp): ODE's getHingeAngle, same
// quaternion products in the same order, with the correctly rounded crAtan2 in place of libm's
// atan2. Against ODE's own dJointGetHingeAngle over random poses of both bodies, both attach
// orders (a null first body makes ODE swap the bodies and flip the sign): the same value but for
// the last bits of the few atan2 arguments that glibc does not round correctly.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "physics/world_impl.h"

namespace {

void randomPose(dBodyID b, std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  dQuaternion q{n(rng), n(rng), n(rng), n(rng)};
  dNormalize4(q);
  dBodySetQuaternion(b, q);
  dBodySetPosition(b, n(rng), n(rng), n(rng));
}

}  // namespace

TEST_CASE("hinge angle: simbob's reading is ODE's dJointGetHingeAngle up to atan2's last bit", "[physics][hinge]") {
  dInitODE2(0);
  dWorldID world = dWorldCreate();
  std::mt19937_64 rng(28);
  for (bool null_first : {false, true}) {
    CAPTURE(null_first);
    dBodyID a = dBodyCreate(world), b = dBodyCreate(world);
    randomPose(a, rng);
    randomPose(b, rng);
    dJointID j = dJointCreateHinge(world, nullptr);
    if (null_first)
      dJointAttach(j, nullptr, b);
    else
      dJointAttach(j, a, b);
    const simbob::Vec3 axis{0.3, -0.5, 0.8};
    dJointSetHingeAxis(j, axis[0], axis[1], axis[2]);
    const simbob::HingeFrame f = simbob::hingeFrame(j, axis);
    CHECK(f.reverse == null_first);
    int equal = 0;
    constexpr int kPoses = 20000;
    for (int i = 0; i < kPoses; ++i) {
      randomPose(a, rng);
      randomPose(b, rng);
      const double mine = simbob::hingeAngle(f), ode = dJointGetHingeAngle(j);
      // 2 atan2(...) and a shift by 2 pi: one ulp of atan2 is at most 2 ulps of pi here.
      REQUIRE(std::fabs(mine - ode) <= 4 * 0x1p-52 * M_PI);
      equal += mine == ode;
      // The angle ODE's own stops would test is the reading before its flip for a reversed joint.
      REQUIRE(simbob::hingeAngleInternal(f) == (null_first ? -mine : mine));
    }
    // glibc's atan2 is correctly rounded for all but about one argument in a thousand.
    CHECK(equal >= kPoses * 995 / 1000);
    dJointDestroy(j);
    dBodyDestroy(a);
    dBodyDestroy(b);
  }
  dWorldDestroy(world);
  dCloseODE();
}
