// Joints: ball-and-socket, hinge, slider and fixed joints between a parent (JointDef::body1, ODE
// body 1) and a child (JointDef::body2, ODE body 2), and their state in simbob's convention.
#include <cmath>

#include "world_impl.h"

namespace simbob {

namespace {

constexpr double kPi = 3.14159265358979323846;

// ODE's reading of a hinge angle or slider position: body 1 (the parent) relative to body 2
// (the child), zero when the axis was set -- up to rounding. 0 for joints without an axis.
double odePosition(dJointID j, JointKind kind) {
  switch (kind) {
    case JointKind::Hinge:
      return dJointGetHingeAngle(j);
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
    im.jointInfo.push_back({jd.kind, odePosition(j, jd.kind)});
  }
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

JointState wrappedJointState(const WorldImpl& im, int i) {
  dJointID j = im.joints[static_cast<size_t>(i)];
  const JointInfo& info = im.jointInfo[static_cast<size_t>(i)];
  // ODE measures body 1 (parent) relative to body 2 (child), and handles a null body by
  // swapping internally and flipping the sign; simbob measures the child relative to the parent.
  JointState s;
  s.position = info.zero - odePosition(j, info.kind);
  s.velocity = -odeRate(j, info.kind);
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
