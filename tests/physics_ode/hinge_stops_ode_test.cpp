// simbob's hinge stops (an angular motor in user mode fed simbob's reading, lib/physics/joints.cpp)
// against ODE's own hinge stops (dParamLoStop / dParamHiStop), which work within +-pi: the same
// arm swinging onto its stops in a World and in a bare ODE world built the same way.
#include <catch2/catch.hpp>

#include <cmath>

#include "physics/world_impl.h"

namespace {

using namespace simbob;

constexpr double kDt = 0.001;
constexpr double kMass = 1.0, kArm = 0.25, kIc = 0.02;
constexpr double kLo = -2.5, kHi = 2.5;  // rad, within ODE's +-pi

// An arm of 1 kg whose centre of mass is 0.25 m along +X from a hinge about +Z at the origin,
// the static world its parent, released horizontal: it falls (negatively) through the bottom and
// meets its stop at -2.5 rad (143 degrees) while still fast, stops dead (no bounce), swings back,
// and so on.
Model armModel(bool quickstep) {
  Model m;
  m.settings.max_time_step = kDt;
  m.settings.quickstep = quickstep;
  m.materials.push_back(MaterialDef{});
  BodyDef b;
  b.key = "arm";
  b.pose.p = {kArm, 0, 0};
  b.mass = kMass;
  b.inertia = {kIc, 0, 0, 0, kIc, 0, 0, 0, kIc};
  m.bodies.push_back(b);
  JointDef j;
  j.key = "hinge";
  j.kind = JointKind::Hinge;
  j.body1 = -1;
  j.body2 = 0;
  j.anchor = {0, 0, 0};
  j.axis = {0, 0, 1};
  j.lo_stop = kLo;
  j.hi_stop = kHi;
  m.joints.push_back(j);
  return m;
}

/// The same arm in a bare ODE world, as World::create builds it, with ODE's own stops. Returns
/// the angle in simbob's sense after every step: ODE attaches a hinge to the world reversed and
/// flips its reading, and its stops test the unflipped angle, which is simbob's.
std::vector<double> odeAngles(const Model& m, int steps) {
  const SolverSettings& s = m.settings;
  dInitODE2(0);  // counted: World's own initialisation, before or after, is not undone
  dWorldID world = dWorldCreate();
  dWorldSetGravity(world, s.gravity[0], s.gravity[1], s.gravity[2]);
  dWorldSetERP(world, s.erp);
  dWorldSetCFM(world, s.cfm);
  dWorldSetQuickStepNumIterations(world, s.iterations);
  dBodyID b = dBodyCreate(world);
  dMass mass;
  dMassSetParameters(&mass, kMass, 0, 0, 0, kIc, kIc, kIc, 0, 0, 0);
  dBodySetMass(b, &mass);
  dBodySetPosition(b, kArm, 0, 0);
  dJointID j = dJointCreateHinge(world, nullptr);
  dJointAttach(j, nullptr, b);
  dJointSetHingeAnchor(j, 0, 0, 0);
  dJointSetHingeAxis(j, 0, 0, 1);
  dJointSetHingeParam(j, dParamLoStop, kLo);
  dJointSetHingeParam(j, dParamHiStop, kHi);
  dRandSetSeed(0);
  std::vector<double> out;
  for (int i = 0; i < steps; ++i) {
    if (s.quickstep)
      dWorldQuickStep(world, kDt);
    else
      dWorldStep(world, kDt);
    out.push_back(-dJointGetHingeAngle(j));
  }
  dWorldDestroy(world);
  return out;
}

std::vector<double> simbobAngles(const Model& m, int steps) {
  auto w = World::create(m, 0);
  std::vector<double> out;
  for (int i = 0; i < steps; ++i) {
    w->step(kDt);
    out.push_back(w->joint(0).position);
  }
  return out;
}

double maxDiff(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::fabs(a[i] - b[i]));
  return worst;
}

}  // namespace

TEST_CASE("hinge stops: simbob's stop motor follows ODE's own hinge stops within +-pi", "[physics][stops]") {
  const int steps = 3000;  // 3 s: the arm meets the lower stop, swings back and meets it again
  const Model exact = armModel(false);
  const std::vector<double> ode = odeAngles(exact, steps);
  const std::vector<double> mine = simbobAngles(exact, steps);
  double lowest = 0;
  int atStop = 0;
  for (double a : ode) {
    lowest = std::min(lowest, a);
    atStop += a < kLo + 1e-3;
  }
  // The arm did reach the stop and rest against it for a while: the comparison covers stop rows.
  CHECK(lowest < kLo + 1e-3);
  CHECK(atStop > 10);
  SECTION("Step: the same LCP, rows in another order") {
    // ODE's Step solves the same rows exactly (the limit row is the same row on the hinge or on
    // the motor, with the same ERP and CFM); what differs is rounding: the rows' order, and the
    // last bit of the angle (libm's atan2 against crAtan2). 1e-9 rad is a million roundings of
    // a 2.5 rad angle; a stop held at another angle or in another step shows as 1e-3 or more.
    CHECK(maxDiff(ode, mine) < 1e-9);
  }
  SECTION("QuickStep: within QuickStep's own distance from the exact solution") {
    // QuickStep's 20 iterations leave a residual that depends on the rows and their order, and
    // the motor is a joint of its own (another order, other random reorderings). Both runs may
    // differ from the exact solution by that residual, so from each other by twice the larger:
    // each is measured here against Step.
    const Model quick = armModel(true);
    const std::vector<double> odeQuick = odeAngles(quick, steps);
    const std::vector<double> mineQuick = simbobAngles(quick, steps);
    const double residual = std::max(maxDiff(odeQuick, ode), maxDiff(mineQuick, mine));
    INFO("QuickStep against Step: " << residual << " rad");
    CHECK(maxDiff(odeQuick, mineQuick) <= 2 * residual);
    CHECK(residual < 1e-2);  // and that residual is small: the arm's motion is the same
  }
}
