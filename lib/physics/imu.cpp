// Inertial measurement units (RCImuSensor): specific force and angular velocity in the sensor
// frame.
//
// The acceleration is the change of the sensor point's global velocity over the last step,
// divided by the step: ODE's integrator is semi-implicit Euler (v' = v + h a, then x' = x + h v'),
// so this difference is exactly the acceleration the step applied, constraint and contact forces
// included. ODE's force accumulators would miss the constraint forces (they hold only the forces
// added by dBodyAddForce and are cleared by the step). Specific force = acceleration - gravity:
// at rest on the ground it reads +g upwards. At creation no step has been taken: the
// acceleration counts as 0 (the sensor reads -gravity in its frame).
#include "simbob/transform.h"
#include "world_impl.h"

namespace simbob {

void readImu(WorldImpl& im, SensorState& s, double h, bool due) {
  const SensorDef& d = s.def;
  const Transform f = sensorFrame(im, d);
  Vec3 v{0, 0, 0}, w{0, 0, 0};
  if (d.body >= 0) {
    dBodyID b = im.bodies[static_cast<size_t>(d.body)];
    dVector3 pv;
    dBodyGetPointVel(b, f.p[0], f.p[1], f.p[2], pv);
    v = {pv[0], pv[1], pv[2]};
    const dReal* aw = dBodyGetAngularVel(b);
    w = {aw[0], aw[1], aw[2]};
  }
  Vec3 a{0, 0, 0};
  if (s.has_prev && h > 0) a = scale(sub(v, s.prev_vel), 1.0 / h);
  s.prev_vel = v;
  s.has_prev = true;
  if (!due) return;
  const Quat back = quatConj(f.q);
  const Vec3 force = add(rotate(back, sub(a, im.gravity)), d.accel_bias);
  const Vec3 rate = add(rotate(back, w), d.gyro_bias);
  for (size_t k = 0; k < 3; ++k) s.reading[k] = force[k] + s.noise.gaussian(d.noise);
  for (size_t k = 0; k < 3; ++k) s.reading[3 + k] = rate[k] + s.noise.gaussian(d.gyro_noise);
}

}  // namespace simbob
