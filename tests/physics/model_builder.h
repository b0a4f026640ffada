// Small hand-built Models for physics and run tests: no scene file, no compile step.
#pragma once

#include <string>

#include "simbob/model.h"

namespace simbob::test {

/// One default material, MaxTimeStep `dt`, default gravity (0 -9.81 0).
inline Model baseModel(double dt = 0.001) {
  Model m;
  m.settings.max_time_step = dt;
  m.materials.push_back(MaterialDef{});
  return m;
}

inline Mat3 sphereInertia(double mass, double r) {
  const double i = 0.4 * mass * r * r;
  return {i, 0, 0, 0, i, 0, 0, 0, i};
}

/// A mobile body keyed "b<index>"; returns its index.
inline int addBody(Model& m, Vec3 p, double mass, Mat3 inertia, Quat q = {1, 0, 0, 0}) {
  BodyDef b;
  b.key = "b" + std::to_string(m.bodies.size());
  b.pose.p = p;
  b.pose.q = q;
  b.mass = mass;
  b.inertia = inertia;
  m.bodies.push_back(b);
  return static_cast<int>(m.bodies.size()) - 1;
}

/// A joint from parent `b1` to child `b2` (-1 = the static world); returns its index.
inline int addJoint(Model& m, JointKind kind, int b1, int b2, Vec3 anchor, Vec3 axis) {
  JointDef j;
  j.key = "j" + std::to_string(m.joints.size());
  j.kind = kind;
  j.body1 = b1;
  j.body2 = b2;
  j.anchor = anchor;
  j.axis = axis;
  m.joints.push_back(j);
  return static_cast<int>(m.joints.size()) - 1;
}

}  // namespace simbob::test
