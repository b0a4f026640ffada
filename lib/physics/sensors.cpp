// Sensors: every sensor's reading on the fixed step grid (World::sensorReading), and the
// proximity sensors (guide 6.11.4) and encoders themselves. Range sensors and scanners are in
// rays.cpp, IMUs in imu.cpp.
//
// Proximity sensors are geoms that only detect. Their geoms sit in a space of their own, so they
// never reach the contact callback and the collision space reports its pairs in the same order as
// without them; after every step each sensor geom is collided with the collision space, and a
// sensor touches when one of its geoms meets a geom of another body.
#include <algorithm>
#include <cmath>

#include "simbob/cr_math.h"
#include "simbob/transform.h"
#include "world_impl.h"

namespace simbob {

namespace {

struct Probe {
  dGeomID sensor;
  bool touching = false;
};

void probePair(void* data, dGeomID a, dGeomID b) {
  Probe& p = *static_cast<Probe*>(data);
  if (p.touching) return;
  dGeomID other = a == p.sensor ? b : a;
  dBodyID own = dGeomGetBody(p.sensor);
  dBodyID body = dGeomGetBody(other);
  // Its own body, and static geoms for a static sensor, are not "another body"; neither are the
  // bodies joined to its body (they do not collide with it either).
  if (own == body) return;
  if (own && body && dAreConnected(own, body)) return;
  dContactGeom c;
  if (dCollide(p.sensor, other, 1, &c, sizeof(dContactGeom)) > 0) p.touching = true;
}

void readProximity(WorldImpl& im, SensorState& s) {
  s.touching = false;
  for (dGeomID g : s.geoms) {
    Probe p{g};
    dSpaceCollide2(g, reinterpret_cast<dGeomID>(im.space), &p, &probePair);
    if (p.touching) {
      s.touching = true;
      break;
    }
  }
  s.reading[0] = s.touching ? 1.0 : 0.0;
}

void readEncoder(const WorldImpl& im, SensorState& s) {
  const double turns = jointState(im, s.def.joint).position / (2 * kPi);
  s.reading[0] = std::floor(turns * s.def.resolution);
}

}  // namespace

Transform sensorFrame(const WorldImpl& im, const SensorDef& d) {
  if (d.body < 0) return d.pose;
  return compose(bodyState(im, d.body).pose, d.pose);
}

void createSensors(WorldImpl& im, const Model& model, uint32_t seed) {
  im.sensors.reserve(model.sensors.size());
  for (const SensorDef& d : model.sensors) {
    SensorState s(d, seed);
    s.reading.assign(s.quantities.size(), 0.0);
    if (d.period > 0) s.period_ns = std::max<int64_t>(1, std::llround(d.period * 1e9));
    for (int gi : d.geoms) s.geoms.push_back(im.geoms[static_cast<size_t>(gi)]);
    if (d.kind == SensorKind::Plugin) createPluginSensor(im, s);
    if (d.kind == SensorKind::Scanner)
      for (int k = 0; k < d.rays; ++k) {
        const double a = scannerRayAngle(d, k);
        s.ray_dirs.push_back({-crSin(a), 0, -crCos(a)});
      }
    im.sensors.push_back(std::move(s));
  }
  if (!im.sensors.empty()) updateSensors(im, 0.0);
}

void updateSensors(WorldImpl& im, double h) {
  // With a pool the rays are cast after the loop, sensor by sensor on whichever thread is free:
  // a ray sensor's reading depends on the poses and its own generator only, not on the others.
  std::vector<SensorState*>& rays = im.rayScene.due;
  rays.clear();
  for (SensorState& s : im.sensors) {
    // Due at the first step boundary at or after each multiple of the period (every step without one).
    const int64_t slot = s.period_ns > 0 ? im.time_ns / s.period_ns : im.time_ns;
    const bool due = slot > s.last_slot;
    if (due) s.last_slot = slot;
    switch (s.def.kind) {
      case SensorKind::Proximity:
        if (due) readProximity(im, s);
        break;
      case SensorKind::Range:
      case SensorKind::Scanner:
        if (due && im.pool)
          rays.push_back(&s);
        else if (due)
          readRays(im, s);
        break;
      case SensorKind::Imu:
        readImu(im, s, h, due);  // tracks the velocity every step, reads when due
        break;
      case SensorKind::Encoder:
        if (due) readEncoder(im, s);
        break;
      case SensorKind::Plugin:
        if (due) readPluginSensor(im, s);
        break;
    }
  }
  if (!rays.empty()) readRaysInParallel(im, rays);
}

}  // namespace simbob
