// Actuators (guide 6.11.1-6.11.3): drives, servos and velocity drives on hinge and slider
// joints. Every law works in simbob's joint convention (World::joint: the child relative to the
// parent, zero at the start pose); ODE measures the parent relative to the child, so each value
// handed to ODE flips its sign (and stops are shifted by ODE's reading at the start pose) --
// except the motor and stops of a hinge whose parent is the world: ODE attaches it reversed,
// flips its readings and applied torques, but not its motor and stops.
#include <algorithm>
#include <cmath>

#include "world_impl.h"

namespace simbob {

namespace {

constexpr double kPi = 3.14159265358979323846;

void setParam(dJointID j, JointKind kind, int param, double value) {
  if (kind == JointKind::Hinge)
    dJointSetHingeParam(j, param, value);
  else
    dJointSetSliderParam(j, param, value);
}

/// Guide 6.11.1: 1 below Stall * MaxVelocity, 0 at MaxVelocity and beyond, linear between.
double stallFactor(double speed, double vmax, double stall) {
  if (speed >= vmax) return 0.0;
  const double vstall = stall * vmax;
  if (speed <= vstall) return 1.0;
  return (vmax - speed) / (vmax - vstall);
}

void act(WorldImpl& im, size_t i, double h) {
  ActuatorState& a = im.actuators[i];
  const ActuatorDef& d = a.def;
  if (d.kind == ActuatorDef::Plugin) {
    applyPluginActuator(im, a, h);
    return;
  }
  const size_t ji = static_cast<size_t>(d.joint);
  dJointID j = im.joints[ji];
  const JointKind kind = im.jointInfo[ji].kind;
  switch (d.kind) {
    case ActuatorDef::Drive: {
      // Pushing along the motion fades with speed; braking (against it) never does.
      const double u = a.command, velocity = jointVelocity(im, d.joint);
      const double fade = u * velocity > 0 ? stallFactor(std::fabs(velocity), d.max_velocity, d.stall) : 1.0;
      a.effort = u * d.max_power * fade;
      if (kind == JointKind::Hinge)
        dJointAddHingeTorque(j, -a.effort);
      else
        dJointAddSliderForce(j, -a.effort);
      break;
    }
    case ActuatorDef::Servo: {
      // The angle wrapped into [-pi, pi], as servos have always read it.
      double error = a.command - wrappedJointState(im, d.joint).position;
      // A hinge without both stops may turn either way: take the shorter way round.
      if (kind == JointKind::Hinge && !(std::isfinite(d.min_pos) && std::isfinite(d.max_pos)))
        error = std::remainder(error, 2 * kPi);
      const double v = std::clamp(error / d.smooth, -d.max_velocity, d.max_velocity);
      setParam(j, kind, dParamVel, a.motor_sign * v);
      setParam(j, kind, dParamFMax, d.max_power);
      break;
    }
    case ActuatorDef::VelDrive:
      setParam(j, kind, dParamVel, a.motor_sign * a.command);
      setParam(j, kind, dParamFMax, a.commanded ? d.max_power : 0.0);
      break;
    case ActuatorDef::Effort: {
      // URDF's velocity limit: no push along the motion at or beyond it (braking always works).
      const double velocity = jointVelocity(im, d.joint);
      const bool along = a.command * velocity > 0;
      a.effort = along && std::fabs(velocity) >= d.max_velocity ? 0.0 : a.command;
      if (kind == JointKind::Hinge)
        dJointAddHingeTorque(j, -a.effort);
      else
        dJointAddSliderForce(j, -a.effort);
      break;
    }
    case ActuatorDef::Plugin:
      break;  // above
  }
}

}  // namespace

void createActuators(WorldImpl& im, const Model& model) {
  im.actuators.reserve(model.actuators.size());
  for (const ActuatorDef& d : model.actuators) {
    ActuatorState a;
    a.def = d;
    if (d.kind == ActuatorDef::Plugin) {
      createPluginActuator(im, a);
      im.actuators.push_back(std::move(a));
      continue;
    }
    if (d.kind == ActuatorDef::Servo) a.command = std::clamp(0.0, d.min_pos, d.max_pos);
    const size_t ji = static_cast<size_t>(d.joint);
    const JointKind kind = im.jointInfo[ji].kind;
    const JointDef& jd = model.joints[ji];
    if (kind == JointKind::Hinge && jd.body1 < 0 && jd.body2 >= 0) a.motor_sign = 1.0;
    im.actuators.push_back(a);
    // Stops in ODE's motor frame: there the position is motor_sign * (p - zero), so [lo, hi]
    // becomes [zero - hi, zero - lo] (sign -1) or [lo - zero, hi - zero] (sign +1).
    const double zero = im.jointInfo[ji].zero;
    const double lo = a.motor_sign < 0 ? zero - d.max_pos : d.min_pos - zero;
    const double hi = a.motor_sign < 0 ? zero - d.min_pos : d.max_pos - zero;
    if (kind == JointKind::Hinge) {
      setHingeStops(im, ji, lo, hi);  // carried by a motor of simbob's (joints.cpp)
    } else {
      if (std::isfinite(lo)) setParam(im.joints[ji], kind, dParamLoStop, lo);
      if (std::isfinite(hi)) setParam(im.joints[ji], kind, dParamHiStop, hi);
    }
  }
  if (!im.actuators.empty())
    im.beforeStep.push_back([](WorldImpl& w, double h) {
      for (size_t i = 0; i < w.actuators.size(); ++i) act(w, i, h);
    });
}

void commandActuator(WorldImpl& im, int i, double value) {
  ActuatorState& a = im.actuators[static_cast<size_t>(i)];
  const ActuatorDef& d = a.def;
  if (std::isnan(value)) value = 0.0;
  const double asked = value;
  switch (d.kind) {
    case ActuatorDef::Drive:
      a.command = std::clamp(value, -1.0, 1.0);
      break;
    case ActuatorDef::Servo:
      a.command = std::clamp(value, d.min_pos, d.max_pos);
      break;
    case ActuatorDef::VelDrive:
      a.command = std::clamp(value, -d.max_velocity, d.max_velocity);
      break;
    case ActuatorDef::Effort:
      a.command = std::clamp(value, -d.max_power, d.max_power);
      break;
    case ActuatorDef::Plugin:
      a.command = value;  // the plug-in's apply() makes of it what it says
      break;
  }
  // Recorded, not reported: the run says it once per actuator (World::clampedCommands).
  if (a.command != asked && a.clamped++ == 0) a.first_clamped = asked;
  a.commanded = true;
}

uint64_t World::clampedCommands(int actuator, double* first) const {
  if (actuator < 0 || static_cast<size_t>(actuator) >= impl_->actuators.size()) return 0;
  const ActuatorState& a = impl_->actuators[static_cast<size_t>(actuator)];
  if (first) *first = a.first_clamped;
  return a.clamped;
}

}  // namespace simbob
