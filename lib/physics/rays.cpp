// Range sensors (RCRangeSensor) and laser scanners (RCLaserScanner): ODE rays cast against the
// collision space. The ray is one geom per World in no space: it is collided with the collision
// space through dSpaceCollide2 only, so the collision space, its pairs and the trajectory are
// the same with and without these sensors.
//
// Conventions (docs/sensors.md): a range sensor's ray leaves the sensor's origin along its local
// -Z (where cameras look). A scanner's rays lie in its local X-Z plane: ray k at angle a_k about
// the local +Y axis from -Z (right-hand rule: positive angles turn towards -X, to the left of
// an upright sensor), a_k = -FOV/2 + k FOV/(Rays-1) (both edges included; a_0 = 0 for one ray),
// or a_k = -180 + k 360/Rays degrees for a full circle (no ray twice). The reading of a ray is
// the distance to the first hit, MaxRange when nothing is hit within MaxRange; with noise and
// resolution: distance + N(0, Noise), rounded to a multiple of Resolution, clamped to
// [MinRange, MaxRange] -- a hit closer than MinRange reads MinRange.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "simbob/transform.h"
#include "world_impl.h"

namespace simbob {

namespace {

struct ReachProbe {
  dGeomID reach;
  dBodyID own;                         ///< the sensor's mobile body, or null for a static mount
  int static_body;                     ///< a static mount: its static body (GeomDef::static_body), or -1
  const std::vector<dBodyID>* joined;  ///< a static mount: the mobile bodies joined to its static body
  const std::vector<GeomInfo>* info;
  std::vector<dGeomID>* out;
};

void reachPair(void* data, dGeomID a, dGeomID b) {
  ReachProbe& p = *static_cast<ReachProbe*>(data);
  dGeomID other = a == p.reach ? b : a;
  dBodyID body = dGeomGetBody(other);
  // Not the sensor's own body, not the bodies joined to it; every other geom, static or mobile.
  if (p.own) {
    if (body == p.own || (body && dAreConnected(p.own, body))) return;
  } else if (!body) {
    const auto gi = static_cast<size_t>(reinterpret_cast<intptr_t>(dGeomGetData(other)));
    if (p.static_body >= 0 && (*p.info)[gi].staticBody == p.static_body) return;
  } else if (p.joined && std::find(p.joined->begin(), p.joined->end(), body) != p.joined->end()) {
    return;
  }
  p.out->push_back(other);
}

bool disjoint(const dReal a[6], const dReal b[6]) {
  return a[0] > b[1] || a[1] < b[0] || a[2] > b[3] || a[3] < b[2] || a[4] > b[5] || a[5] < b[4];
}

/// One ray's reading from its raw distance (+infinity: nothing hit).
double rayReading(SensorState& s, double d) {
  const SensorDef& def = s.def;
  if (!std::isfinite(d)) return def.max_range;
  d += s.noise.gaussian(def.noise);
  if (def.resolution > 0) d = std::round(d / def.resolution) * def.resolution;
  return std::min(def.max_range, std::max(def.min_range, d));
}

}  // namespace

// Why the candidates: ODE's dSpaceCollide2 of one geom against a hash space tests every geom of
// the space, so a scanner of 36 rays among 800 geoms tested 28,800 bounding boxes per scan. Its
// rays now test only the geoms within its reach, gathered by one dSpaceCollide2 per scan. The
// reading is the same: every geom a ray can hit is a candidate, and the nearest of the hits does
// not depend on the order they are found in.
void gatherRayCandidates(WorldImpl& im, int body, int static_body, const Vec3& origin, double reach) {
  if (!im.rayReach) im.rayReach = dCreateBox(nullptr, 1, 1, 1);  // axis-aligned: never rotated
  const double half = reach * (1 + 1e-9) + 1e-9;                 // a margin for the rounding of a ray's end
  dGeomBoxSetLengths(im.rayReach, 2 * half, 2 * half, 2 * half);
  dGeomSetPosition(im.rayReach, origin[0], origin[1], origin[2]);
  im.rayCandidates.clear();
  dBodyID own = body >= 0 ? im.bodies[static_cast<size_t>(body)] : nullptr;
  const std::vector<dBodyID>* joined = nullptr;
  if (!own && static_body >= 0 && static_cast<size_t>(static_body) < im.staticJoined.size())
    joined = &im.staticJoined[static_cast<size_t>(static_body)];
  ReachProbe p{im.rayReach, own, static_body, joined, &im.geomInfo, &im.rayCandidates};
  dSpaceCollide2(im.rayReach, reinterpret_cast<dGeomID>(im.space), &p, &reachPair);
}

double castRay(WorldImpl& im, const Vec3& origin, const Vec3& dir, double length) {
  if (!im.ray) {
    im.ray = dCreateRay(nullptr, length);
    dGeomRaySetFirstContact(im.ray, 0);  // not the first contact found: the nearest
    dGeomRaySetBackfaceCull(im.ray, 0);
    dGeomRaySetClosestHit(im.ray, 1);
  }
  dGeomRaySetLength(im.ray, length);
  dGeomRaySet(im.ray, origin[0], origin[1], origin[2], dir[0], dir[1], dir[2]);
  dReal rayBox[6];
  dGeomGetAABB(im.ray, rayBox);
  double nearest = std::numeric_limits<double>::infinity();
  for (dGeomID g : im.rayCandidates) {
    dReal box[6];
    dGeomGetAABB(g, box);
    if (disjoint(rayBox, box)) continue;
    dContactGeom c;
    if (dCollide(im.ray, g, 1, &c, sizeof(dContactGeom)) > 0 && c.depth < nearest) nearest = c.depth;
  }
  return nearest <= length ? nearest : std::numeric_limits<double>::infinity();
}

void readRays(WorldImpl& im, SensorState& s) {
  const SensorDef& d = s.def;
  const Transform f = sensorFrame(im, d);
  gatherRayCandidates(im, d.body, d.static_body, f.p, d.max_range);
  if (d.kind == SensorKind::Range) {
    s.reading[0] = rayReading(s, castRay(im, f.p, rotate(f.q, Vec3{0, 0, -1}), d.max_range));
    return;
  }
  for (int k = 0; k < d.rays; ++k) {
    const double a = scannerRayAngle(d, k);
    const Vec3 local{-std::sin(a), 0, -std::cos(a)};
    s.reading[static_cast<size_t>(k)] = rayReading(s, castRay(im, f.p, rotate(f.q, local), d.max_range));
  }
}

}  // namespace simbob
