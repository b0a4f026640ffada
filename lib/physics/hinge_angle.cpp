// A hinge's angle, read by simbob itself rather than by dJointGetHingeAngle: ODE's getHingeAngle
// (hinge.cpp in ODE 0.16) with the same quaternion products in the same order, turned into an
// angle by 2 atan2(|v|, w) -- but with the correctly rounded crAtan2 in place of libm's atan2,
// whose CPU-specific variants give another last bit for a few arguments (docs/ci.md, "Hinge
// angles and libm's atan2"). With libm's atan2 in its place this returns dJointGetHingeAngle's
// bits (checked when this was written, over every step of the servo and URDF scenes).
#include <cmath>

#include "simbob/cr_math.h"
#include "world_impl.h"

namespace simbob {

HingeFrame hingeFrame(dJointID j, const Vec3& axis) {
  HingeFrame f;
  // dJointAttach with a null first body swaps the bodies and marks the joint reversed.
  dBodyID b1 = dJointGetBody(j, 0), b2 = dJointGetBody(j, 1);
  f.reverse = b1 == nullptr;
  f.body0 = b1 ? b1 : b2;
  f.body1 = b1 ? b2 : nullptr;
  // As dJointSetHingeAxis leaves them: computeInitialRelativeRotation and setAxes.
  const dReal* q0 = dBodyGetQuaternion(f.body0);
  if (f.body1) {
    dQMultiply1(f.q_initial, q0, dBodyGetQuaternion(f.body1));
  } else {
    f.q_initial[0] = q0[0];
    f.q_initial[1] = -q0[1];
    f.q_initial[2] = -q0[2];
    f.q_initial[3] = -q0[3];
  }
  dVector3 n{axis[0], axis[1], axis[2], 0};
  dNormalize3(n);
  dMultiply1_331(f.axis1, dBodyGetRotation(f.body0), n);
  return f;
}

double hingeAngleInternal(const HingeFrame& f) {
  dQuaternion qrel;
  if (f.body1) {
    dQuaternion qq;
    dQMultiply1(qq, dBodyGetQuaternion(f.body0), dBodyGetQuaternion(f.body1));
    dQMultiply2(qrel, qq, f.q_initial);
  } else {
    dQMultiply3(qrel, dBodyGetQuaternion(f.body0), f.q_initial);
  }
  const double cost2 = qrel[0];
  const double sint2 = std::sqrt(qrel[1] * qrel[1] + qrel[2] * qrel[2] + qrel[3] * qrel[3]);
  double theta = dCalcVectorDot3(qrel + 1, f.axis1) >= 0 ? 2 * crAtan2(sint2, cost2) : 2 * crAtan2(sint2, -cost2);
  if (theta > M_PI) theta -= static_cast<double>(2 * M_PI);
  return -theta;
}

double hingeAngle(const HingeFrame& f) {
  const double theta = hingeAngleInternal(f);
  return f.reverse ? -theta : theta;
}

}  // namespace simbob
