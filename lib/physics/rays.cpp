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

/// Whose geoms a sensor's rays pass through: its own body's and those of the bodies joined to
/// it (docs/sensors.md). A sensor on a static mount skips its own static body's geoms and the
/// mobile bodies jointed to that static body, and sees every other geom, static or mobile.
struct RayOwner {
  dBodyID own;                         ///< the sensor's mobile body, or null for a static mount
  int static_body;                     ///< a static mount: its static body (GeomDef::static_body), or -1
  const std::vector<dBodyID>* joined;  ///< a static mount: the mobile bodies joined to its static body
  const std::vector<GeomInfo>* info;

  bool skips(dGeomID g, dBodyID body) const {
    if (own) return body == own || (body && dAreConnected(own, body));
    if (!body) {
      const auto gi = static_cast<size_t>(reinterpret_cast<intptr_t>(dGeomGetData(g)));
      return static_body >= 0 && (*info)[gi].staticBody == static_body;
    }
    return joined && std::find(joined->begin(), joined->end(), body) != joined->end();
  }
};

RayOwner rayOwner(const WorldImpl& im, int body, int static_body) {
  dBodyID own = body >= 0 ? im.bodies[static_cast<size_t>(body)] : nullptr;
  const std::vector<dBodyID>* joined = nullptr;
  if (!own && static_body >= 0 && static_cast<size_t>(static_body) < im.staticJoined.size())
    joined = &im.staticJoined[static_cast<size_t>(static_body)];
  return {own, static_body, joined, &im.geomInfo};
}

struct ReachProbe {
  dGeomID reach;
  RayOwner owner;
  std::vector<dGeomID>* out;
};

void reachPair(void* data, dGeomID a, dGeomID b) {
  ReachProbe& p = *static_cast<ReachProbe*>(data);
  dGeomID other = a == p.reach ? b : a;
  if (!p.owner.skips(other, dGeomGetBody(other))) p.out->push_back(other);
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

void ignorePair(void*, dGeomID, dGeomID) {}

dGeomID newRay() {
  dGeomID ray = dCreateRay(nullptr, 1);
  dGeomRaySetFirstContact(ray, 0);  // not the first contact found: the nearest
  dGeomRaySetBackfaceCull(ray, 0);
  dGeomRaySetClosestHit(ray, 1);
  return ray;
}

dGeomID aimRay(dGeomID ray, const Vec3& origin, const Vec3& dir, double length) {
  dGeomRaySetLength(ray, length);
  dGeomRaySet(ray, origin[0], origin[1], origin[2], dir[0], dir[1], dir[2]);
  return ray;
}

/// The ray's distance to geom g, or +infinity.
double hitDepth(dGeomID ray, dGeomID g) {
  dContactGeom c;
  return dCollide(ray, g, 1, &c, sizeof(dContactGeom)) > 0 ? c.depth : std::numeric_limits<double>::infinity();
}

/// The readings of a range sensor or scanner with frame f, `cast` giving a ray's raw distance
/// along a global unit direction: ray by ray, in order (the noise is drawn in that order).
template <typename Cast>
void readingsOf(SensorState& s, const Transform& f, const Cast& cast) {
  const SensorDef& d = s.def;
  if (d.kind == SensorKind::Range) {
    s.reading[0] = rayReading(s, cast(rotate(f.q, Vec3{0, 0, -1})));
    return;
  }
  for (int k = 0; k < d.rays; ++k)
    s.reading[static_cast<size_t>(k)] = rayReading(s, cast(rotate(f.q, s.ray_dirs[static_cast<size_t>(k)])));
}

/// The reach box of gatherRayCandidates: ODE's box of an axis-aligned box of side 2 * half.
void reachBox(const Vec3& origin, double reach, dReal box[6]) {
  const double half = reach * (1 + 1e-9) + 1e-9;  // as gatherRayCandidates
  for (size_t k = 0; k < 3; ++k) {
    box[2 * k] = origin[k] - 0.5 * (2 * half);
    box[2 * k + 1] = origin[k] + 0.5 * (2 * half);
  }
}

/// gatherRayCandidates over a list of targets: the same geoms, in list order.
void gatherTargets(const std::vector<RayTarget>& targets, const RayOwner& owner, const Vec3& origin, double reach,
                   std::vector<const RayTarget*>& out) {
  dReal box[6];
  reachBox(origin, reach, box);
  out.clear();
  for (const RayTarget& t : targets) {
    if (disjoint(box, t.aabb)) continue;
    if (owner.skips(t.geom, t.body)) continue;  // reachPair's rule
    out.push_back(&t);
  }
}

/// castRay with a ray of the calling thread's own, among gathered targets.
double castAmong(dGeomID ray, const std::vector<const RayTarget*>& cand, const Vec3& origin, const Vec3& dir,
                 double length) {
  aimRay(ray, origin, dir, length);
  dReal rayBox[6];
  dGeomGetAABB(ray, rayBox);
  double nearest = std::numeric_limits<double>::infinity();
  for (const RayTarget* t : cand)
    if (!disjoint(rayBox, t->aabb)) nearest = std::min(nearest, hitDepth(ray, t->geom));
  return nearest <= length ? nearest : std::numeric_limits<double>::infinity();
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
  ReachProbe p{im.rayReach, rayOwner(im, body, static_body), &im.rayCandidates};
  dSpaceCollide2(im.rayReach, reinterpret_cast<dGeomID>(im.space), &p, &reachPair);
}

double castRay(WorldImpl& im, const Vec3& origin, const Vec3& dir, double length) {
  if (!im.ray) im.ray = newRay();
  dGeomID ray = aimRay(im.ray, origin, dir, length);
  dReal rayBox[6];
  dGeomGetAABB(ray, rayBox);
  double nearest = std::numeric_limits<double>::infinity();
  for (dGeomID g : im.rayCandidates) {
    dReal box[6];
    dGeomGetAABB(g, box);
    if (!disjoint(rayBox, box)) nearest = std::min(nearest, hitDepth(ray, g));
  }
  return nearest <= length ? nearest : std::numeric_limits<double>::infinity();
}

void readRays(WorldImpl& im, SensorState& s) {
  const SensorDef& d = s.def;
  const Transform f = sensorFrame(im, d);
  gatherRayCandidates(im, d.body, d.static_body, f.p, d.max_range);
  readingsOf(s, f, [&](const Vec3& dir) { return castRay(im, f.p, dir, d.max_range); });
}

namespace {

// Sensors [begin, end) of `due` on thread `worker` (a job of the pool; not inlined, so that a
// profile shows what runs in parallel: bench/threads_bench.py --profile).
[[gnu::noinline]] void readSensorChunk(WorldImpl& im, const std::vector<SensorState*>& due, size_t begin, size_t end,
                                       size_t worker) {
  RayScene& rs = im.rayScene;
  for (size_t i = begin; i < end; ++i) {
    SensorState& s = *due[i];
    const SensorDef& d = s.def;
    const Transform f = sensorFrame(im, d);
    std::vector<const RayTarget*>& cand = rs.candidates[worker];
    gatherTargets(rs.targets, rayOwner(im, d.body, d.static_body), f.p, d.max_range, cand);
    readingsOf(s, f, [&](const Vec3& dir) { return castAmong(rs.rays[worker], cand, f.p, dir, d.max_range); });
  }
}

}  // namespace

// With a pool (--threads N > 1): the sensors due are split among the threads. What a sensor's
// rays can hit is read first, on the stepping thread: every geom's box (dGeomGetAABB brings a
// moved geom's position and box up to date, so nothing is recomputed later) and what
// dSpaceCollide2 would test it by. Each thread then gathers a sensor's candidates from that
// list as gatherRayCandidates does, and casts with a ray geom of its own; the sensor's noise is
// drawn in ray order from its own generator. So each reading is what readRays gives.
void readRaysInParallel(WorldImpl& im, const std::vector<SensorState*>& due) {
  RayScene& rs = im.rayScene;
  // Clean the space first, as gatherRayCandidates's dSpaceCollide2 does: whether a geom is
  // clean decides where it goes in the space's list when it next moves (the pairs' order).
  if (!rs.cleaner) {
    rs.cleaner = dCreateSphere(nullptr, 1);
    dGeomSetCategoryBits(rs.cleaner, 0);
    dGeomSetCollideBits(rs.cleaner, 0);
  }
  dSpaceCollide2(rs.cleaner, reinterpret_cast<dGeomID>(im.space), nullptr, &ignorePair);
  rs.targets.clear();
  bool stateless = true;
  const int n = dSpaceGetNumGeoms(im.space);
  for (int i = 0; i < n; ++i) {  // from 0: dSpaceGetGeom walks the list once, in its order
    dGeomID g = dSpaceGetGeom(im.space, i);
    if (!dGeomIsEnabled(g)) continue;
    // dSpaceCollide2 meets a geom only if its bits match the probe's (all ones).
    if (dGeomGetCategoryBits(g) == 0 && dGeomGetCollideBits(g) == 0) continue;
    RayTarget t{g, dGeomGetBody(g), {}};
    dGeomGetAABB(g, t.aabb);
    stateless = stateless && statelessCollider(g);
    rs.targets.push_back(t);
  }
  if (!stateless) {  // a collider with ODE's shared caches (see contacts.cpp): on this thread
    for (SensorState* s : due) readRays(im, *s);
    return;
  }
  const size_t threads = static_cast<size_t>(im.pool->size());
  while (rs.rays.size() < threads) rs.rays.push_back(newRay());
  rs.candidates.resize(threads);
  im.pool->run(due.size(), kRaySensorGrain, [&](size_t, size_t begin, size_t end, int worker) {
    readSensorChunk(im, due, begin, end, static_cast<size_t>(worker));
  });
}

}  // namespace simbob
