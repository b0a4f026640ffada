// Mobile bodies: mass, inertia, initial pose and velocity. ODE's body frame sits at the centre
// of mass; simbob's at the body origin (both share axes), so poses and velocities are shifted by
// the centre-of-mass offset on the way in and out.
#include "simbob/transform.h"
#include "world_impl.h"

namespace simbob {

void createBodies(WorldImpl& im, const Model& model) {
  im.bodies.reserve(model.bodies.size());
  for (const BodyDef& bd : model.bodies) {
    dBodyID b = dBodyCreate(im.world);
    dMass m;
    const Mat3& I = bd.inertia;
    // COM at the body origin; full inertia tensor (row-major: I12 = [1], I13 = [2], I23 = [5]).
    dMassSetParameters(&m, bd.mass, 0, 0, 0, I[0], I[4], I[8], I[1], I[2], I[5]);
    dBodySetMass(b, &m);
    Vec3 p = bd.pose.p, v = bd.lin_vel;
    const bool offset = bd.com != Vec3{0, 0, 0};
    if (offset) {
      Vec3 rc = rotate(bd.pose.q, bd.com);
      p = add(p, rc);
      v = add(v, cross(bd.ang_vel, rc));
    }
    dBodySetPosition(b, p[0], p[1], p[2]);
    const dQuaternion q = {bd.pose.q[0], bd.pose.q[1], bd.pose.q[2], bd.pose.q[3]};
    dBodySetQuaternion(b, q);
    dBodySetLinearVel(b, v[0], v[1], v[2]);
    dBodySetAngularVel(b, bd.ang_vel[0], bd.ang_vel[1], bd.ang_vel[2]);
    if (!bd.gravity) dBodySetGravityMode(b, 0);
    im.bodies.push_back(b);
    im.com.push_back(bd.com);
  }
}

void copyBodyState(const BodyState& s, double* p, double* q, double* v, double* w) {
  for (size_t k = 0; k < 3; ++k) {
    if (p) p[k] = s.pose.p[k];
    if (v) v[k] = s.lin_vel[k];
    if (w) w[k] = s.ang_vel[k];
  }
  for (size_t k = 0; k < 4 && q; ++k) q[k] = s.pose.q[k];
}

BodyState bodyState(const WorldImpl& im, int i) {
  dBodyID b = im.bodies[static_cast<size_t>(i)];
  const dReal* p = dBodyGetPosition(b);
  const dReal* q = dBodyGetQuaternion(b);
  const dReal* v = dBodyGetLinearVel(b);
  const dReal* w = dBodyGetAngularVel(b);
  BodyState s;
  s.pose.p = {p[0], p[1], p[2]};
  s.pose.q = {q[0], q[1], q[2], q[3]};
  s.lin_vel = {v[0], v[1], v[2]};
  s.ang_vel = {w[0], w[1], w[2]};
  const Vec3& c = im.com[static_cast<size_t>(i)];
  if (c != Vec3{0, 0, 0}) {
    // Report the body origin, not ODE's centre-of-mass frame.
    Vec3 rc = rotate(s.pose.q, c);
    s.pose.p = sub(s.pose.p, rc);
    s.lin_vel = sub(s.lin_vel, cross(s.ang_vel, rc));
  }
  return s;
}

}  // namespace simbob
