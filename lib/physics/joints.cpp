// Joints: ball-and-socket, hinge, slider and fixed joints between a parent (JointDef::body1, ODE
// body 1) and a child (JointDef::body2, ODE body 2), and their state in simbob's convention.
#include <cmath>
#include <memory>
#include <utility>

#include "world_impl.h"

namespace simbob {

namespace {

constexpr double kPi = 3.14159265358979323846;

// ODE's reading of a hinge angle or slider position: body 1 (the parent) relative to body 2
// (the child), zero when the axis was set -- up to rounding. 0 for joints without an axis. A
// hinge's angle is read as dJointGetHingeAngle reads it, but with a correctly rounded atan2
// (hinge_angle.cpp): the same bits on every CPU.
double odePosition(dJointID j, const JointInfo& info) {
  switch (info.kind) {
    case JointKind::Hinge:
      return hingeAngle(info.hinge);
    case JointKind::Slider:
      return dJointGetSliderPosition(j);
    case JointKind::BallSocket:
    case JointKind::Fixed:
      return 0;
  }
  return 0;
}

double odeRate(dJointID j, JointKind kind) {
  switch (kind) {
    case JointKind::Hinge:
      return dJointGetHingeAngleRate(j);
    case JointKind::Slider:
      return dJointGetSliderPositionRate(j);
    case JointKind::BallSocket:
    case JointKind::Fixed:
      return 0;
  }
  return 0;
}

}  // namespace

void createJoints(WorldImpl& im, const Model& model) {
  im.joints.reserve(model.joints.size());
  im.jointInfo.reserve(model.joints.size());
  for (const JointDef& jd : model.joints) {
    dJointID j = nullptr;
    switch (jd.kind) {
      case JointKind::BallSocket:
        j = dJointCreateBall(im.world, nullptr);
        break;
      case JointKind::Hinge:
        j = dJointCreateHinge(im.world, nullptr);
        break;
      case JointKind::Slider:
        j = dJointCreateSlider(im.world, nullptr);
        break;
      case JointKind::Fixed:
        j = dJointCreateFixed(im.world, nullptr);
        break;
    }
    // Index -1 is the static world, which ODE spells as a null body.
    dBodyID b1 = jd.body1 >= 0 ? im.bodies[static_cast<size_t>(jd.body1)] : nullptr;
    dBodyID b2 = jd.body2 >= 0 ? im.bodies[static_cast<size_t>(jd.body2)] : nullptr;
    dJointAttach(j, b1, b2);
    if (jd.static_body >= 0) {  // joined to a static body: its sensors' rays do not see this body (rays.cpp)
      if (im.staticJoined.size() <= static_cast<size_t>(jd.static_body))
        im.staticJoined.resize(static_cast<size_t>(jd.static_body) + 1);
      im.staticJoined[static_cast<size_t>(jd.static_body)].push_back(b1 ? b1 : b2);
    }
    // Anchors/axes after attach: ODE stores them relative to the attached bodies.
    switch (jd.kind) {
      case JointKind::BallSocket:
        dJointSetBallAnchor(j, jd.anchor[0], jd.anchor[1], jd.anchor[2]);
        break;
      case JointKind::Hinge:
        dJointSetHingeAnchor(j, jd.anchor[0], jd.anchor[1], jd.anchor[2]);
        dJointSetHingeAxis(j, jd.axis[0], jd.axis[1], jd.axis[2]);
        break;
      case JointKind::Slider:
        dJointSetSliderAxis(j, jd.axis[0], jd.axis[1], jd.axis[2]);
        break;
      case JointKind::Fixed:
        dJointSetFixed(j);
        break;
    }
    im.joints.push_back(j);
    // A pure read (changes no ODE state): the start pose is zero exactly, not up to rounding.
    JointInfo info{jd.kind, 0.0};
    if (jd.kind == JointKind::Hinge) info.hinge = hingeFrame(j, jd.axis);
    info.zero = odePosition(j, info);
    im.jointInfo.push_back(std::move(info));
    if (jd.kind == JointKind::Hinge && jd.body1 < 0 && jd.body2 >= 0) im.jointInfo.back().motor_sign = 1.0;
  }
  createJointDynamics(im, model);
}

namespace {

void setJointParam(dJointID j, JointKind kind, int param, double value) {
  if (kind == JointKind::Hinge)
    dJointSetHingeParam(j, param, value);
  else
    dJointSetSliderParam(j, param, value);
}

/// Damping (explicit: a force against the velocity of the step before) and mimic joints (the
/// joint's motor drives it to multiplier q_leader + offset, closing the gap within kMimicSteps
/// steps, with the leader's velocity fed forward). Copies of the JointDefs: the World may outlive
/// the Model it was made from.
void jointDynamics(WorldImpl& im, const std::vector<std::pair<size_t, JointDef>>& damped,
                   const std::vector<std::pair<size_t, JointDef>>& mimics, double h) {
  constexpr double kMimicSteps = 5;
  for (const auto& [i, jd] : damped) {
    const double f = -jd.damping * jointVelocity(im, static_cast<int>(i));
    if (jd.kind == JointKind::Hinge)
      dJointAddHingeTorque(im.joints[i], -f);
    else
      dJointAddSliderForce(im.joints[i], -f);
  }
  for (const auto& [i, jd] : mimics) {
    const JointState me = jointState(im, static_cast<int>(i));
    const JointState leader = jointState(im, jd.mimic);
    const double target = jd.mimic_multiplier * leader.position + jd.mimic_offset;
    const double v = jd.mimic_multiplier * leader.velocity + (target - me.position) / (kMimicSteps * h);
    setJointParam(im.joints[i], jd.kind, dParamVel, im.jointInfo[i].motor_sign * v);
    setJointParam(im.joints[i], jd.kind, dParamFMax, jd.mimic_max_force);
  }
}

}  // namespace

// ODE's hinge tests its own stops with libm's atan2 inside dWorldStep (getInfo1), and while a
// joint rests on a stop, the last bit of that angle reaches the stop row's error: the bytes would
// depend on the CPU. So a hinge's stops are carried by an angular motor in user mode on the same
// bodies and axis: ODE tests its stops against the angle simbob hands it before every step (its
// own, correctly rounded reading, unwrapped), with the same limit row as the hinge's own (ODE's
// addLimot). The hinge keeps its motor (drives, friction, mimics): at a stop, motor and stop are
// two rows of the solver, not ODE's one row with the motor's force added by hand.
namespace {
// A hinge's unwrapped angle in ODE's motor frame, the frame of its stops: hingeAngleInternal's
// sense, zero where ODE's reading was zero.
double stopFrameAngle(const JointInfo& info) {
  return info.motor_sign < 0 ? info.zero - info.total : info.total - info.zero;
}
}  // namespace

void setHingeStops(WorldImpl& im, size_t i, double lo, double hi) {
  JointInfo& info = im.jointInfo[i];
  if (!info.stops) {
    if (!std::isfinite(lo) && !std::isfinite(hi)) return;
    info.stops = dJointCreateAMotor(im.world, nullptr);
    // In ODE's order: body0 first, so that the motor is not reversed and its axis is the hinge's.
    dJointAttach(info.stops, info.hinge.body0, info.hinge.body1);
    dJointSetAMotorMode(info.stops, dAMotorUser);
    dJointSetAMotorNumAxes(info.stops, 1);
    dVector3 axis;
    dMultiply0_331(axis, dBodyGetRotation(info.hinge.body0), info.hinge.axis1);
    dJointSetAMotorAxis(info.stops, 0, 1, axis[0], axis[1], axis[2]);
    // ODE copies the motor's force here after every step (read only: the bytes stay).
    info.stopFeedback = std::make_unique<dJointFeedback>();
    dJointSetFeedback(info.stops, info.stopFeedback.get());
    im.stopJoints.push_back(i);
  }
  // Open first, so that lo <= hi holds at every moment (ODE ignores a stop that would break it).
  dJointSetAMotorParam(info.stops, dParamLoStop, -dInfinity);
  dJointSetAMotorParam(info.stops, dParamHiStop, hi);
  dJointSetAMotorParam(info.stops, dParamLoStop, lo);
  dJointSetAMotorAngle(info.stops, 0, stopFrameAngle(info));
}

void updateHingeStops(WorldImpl& im) {
  for (size_t i : im.stopJoints) {
    JointInfo& info = im.jointInfo[i];
    dJointSetAMotorAngle(info.stops, 0, stopFrameAngle(info));
    // ODE writes the feedback only of a joint that has rows in the step (off its stops the
    // motor has none): what it does not write reads 0.
    *info.stopFeedback = dJointFeedback{};
  }
}

double stopTorque(const WorldImpl& im, int i) {
  const JointInfo& info = im.jointInfo[static_cast<size_t>(i)];
  if (!info.stops) return 0;
  dVector3 axis;  // JointDef::axis as the bodies have turned it: simbob's positive sense
  dJointGetHingeAxis(im.joints[static_cast<size_t>(i)], axis);
  const dReal* t = info.stopFeedback->t1;  // on the motor's first body, ODE's body0 of the hinge
  const double along = t[0] * axis[0] + t[1] * axis[1] + t[2] * axis[2];
  // body0 is the child when ODE reversed the hinge (the parent is the world), else the parent,
  // which gets the opposite of the child's torque.
  return info.hinge.reverse ? along : -along;
}

void createJointDynamics(WorldImpl& im, const Model& model) {
  std::vector<std::pair<size_t, JointDef>> damped, mimics;
  for (size_t i = 0; i < model.joints.size(); ++i) {
    const JointDef& jd = model.joints[i];
    if (jd.kind != JointKind::Hinge && jd.kind != JointKind::Slider) continue;
    const JointInfo& info = im.jointInfo[i];
    // Stops in ODE's frame, as createActuators sets a drive's.
    const double lo = info.motor_sign < 0 ? info.zero - jd.hi_stop : jd.lo_stop - info.zero;
    const double hi = info.motor_sign < 0 ? info.zero - jd.lo_stop : jd.hi_stop - info.zero;
    if (jd.kind == JointKind::Hinge) {
      setHingeStops(im, i, lo, hi);
    } else {
      if (std::isfinite(lo)) setJointParam(im.joints[i], jd.kind, dParamLoStop, lo);
      if (std::isfinite(hi)) setJointParam(im.joints[i], jd.kind, dParamHiStop, hi);
    }
    if (jd.friction > 0) {  // Coulomb friction: a motor holding velocity 0 with at most that force
      setJointParam(im.joints[i], jd.kind, dParamVel, 0.0);
      setJointParam(im.joints[i], jd.kind, dParamFMax, jd.friction);
    }
    if (jd.damping > 0) damped.emplace_back(i, jd);
    if (jd.mimic >= 0) mimics.emplace_back(i, jd);
  }
  if (damped.empty() && mimics.empty()) return;
  im.beforeStep.push_back([damped, mimics](WorldImpl& w, double h) { jointDynamics(w, damped, mimics, h); });
}

double jointSeparation(const WorldImpl& im, int i) {
  dJointID j = im.joints[static_cast<size_t>(i)];
  dVector3 a, b;
  switch (im.jointInfo[static_cast<size_t>(i)].kind) {
    case JointKind::BallSocket:
      dJointGetBallAnchor(j, a);
      dJointGetBallAnchor2(j, b);
      break;
    case JointKind::Hinge:
      dJointGetHingeAnchor(j, a);
      dJointGetHingeAnchor2(j, b);
      break;
    case JointKind::Slider:
    case JointKind::Fixed:
      return 0;  // no shared anchor point to compare
  }
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

double jointVelocity(const WorldImpl& im, int i) {
  // ODE's rate is body 1 relative to body 2: the sign flips to simbob's child-relative-to-parent.
  return -odeRate(im.joints[static_cast<size_t>(i)], im.jointInfo[static_cast<size_t>(i)].kind);
}

JointState wrappedJointState(const WorldImpl& im, int i) {
  dJointID j = im.joints[static_cast<size_t>(i)];
  const JointInfo& info = im.jointInfo[static_cast<size_t>(i)];
  // ODE measures body 1 (parent) relative to body 2 (child), and handles a null body by
  // swapping internally and flipping the sign; simbob measures the child relative to the parent.
  JointState s;
  s.position = info.zero - odePosition(j, info);
  s.velocity = jointVelocity(im, i);
  if (info.kind == JointKind::Hinge) {
    // ODE wraps into [-pi, pi]; subtracting the zero may step just outside it.
    if (s.position > kPi) s.position -= 2 * kPi;
    if (s.position < -kPi) s.position += 2 * kPi;
  }
  return s;
}

JointState jointState(const WorldImpl& im, int i) {
  JointState s = wrappedJointState(im, i);
  const JointInfo& info = im.jointInfo[static_cast<size_t>(i)];
  if (info.kind == JointKind::Hinge) s.position = info.total;
  return s;
}

void updateJointTotals(WorldImpl& im) {
  for (size_t i = 0; i < im.joints.size(); ++i) {
    JointInfo& info = im.jointInfo[i];
    if (info.kind != JointKind::Hinge) continue;
    const double now = wrappedJointState(im, static_cast<int>(i)).position;
    // The change over one step, taken the short way round: exact while |change| < pi.
    info.total += std::remainder(now - info.last, 2 * kPi);
    info.last = now;
  }
}

}  // namespace simbob
