// Contacts: the near callback of dSpaceCollide. Colliding geom pairs get up to MaxContacts
// contact joints with the material rules of the Simulator Bob guide 7.1.
//
// With more than one thread (--threads) the narrow phase runs in parallel and the joints are
// still created in the broad phase's pair order, which QuickStep's result depends on:
//  1. the broad phase's pairs are gathered in its order (serial: it walks the space);
//  2. the pairs are split into chunks; each chunk's pairs are collided (dCollide) into that
//     chunk's own contact buffer, on whichever thread is free;
//  3. the contact joints are created from the buffers chunk by chunk, pair by pair: today's order.
// dCollide only reads the two geoms (the space was cleaned by the broad phase, so no geom's
// position or box is recomputed) for the primitive classes simbob creates: sphere, box, capsule,
// cylinder and plane, whose colliders keep no state. Debian's ODE is built without thread-local
// collision caches (dGetConfiguration lacks ODE_EXT_mt_collisions), so a pair with any other
// class (a triangle mesh, a heightfield) is collided in step 3, on the stepping thread.
// dCollide is called through collideGeoms (cylinder_caps.cpp): a flat cylinder cap against a box
// face or another cap gets simbob's own contacts, every other pair ODE's.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "world_impl.h"

namespace simbob {

namespace {

const GeomInfo& infoOf(const WorldImpl& im, dGeomID g) {
  return im.geomInfo[static_cast<size_t>(reinterpret_cast<intptr_t>(dGeomGetData(g)))];
}

/// Whether the pair may get contact joints at all.
bool mayTouch(const WorldImpl& im, dGeomID g1, dGeomID g2) {
  dBodyID b1 = dGeomGetBody(g1);
  dBodyID b2 = dGeomGetBody(g2);
  // Two geoms of one body, or two static geoms (both bodies null): nothing to resolve.
  if (b1 == b2) return false;
  // Bodies joined by a joint do not collide with each other (the usual ODE idiom).
  if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return false;
  // Sensors create no contact joints (their geoms are in a space of their own: never reached).
  const GeomInfo& i1 = infoOf(im, g1);
  const GeomInfo& i2 = infoOf(im, g2);
  if (i1.sensor || i2.sensor) return false;
  // The links of one URDF robot (without SelfCollision) do not collide with each other.
  return i1.group < 0 || i1.group != i2.group;
}

/// The most contacts of a pair: the settings' MaxContacts, or fewer where a geom's Gazebo surface
/// says so (<maxContacts>: the smaller of the pair's, as Gazebo classic takes it).
int mostContacts(const WorldImpl& im, dGeomID g1, dGeomID g2, int most) {
  for (const GeomInfo* i : {&infoOf(im, g1), &infoOf(im, g2)})
    if (i->surface >= 0) {
      const int m = im.surfaces[static_cast<size_t>(i->surface)].max_contacts;
      if (m > 0) most = std::min(most, m);
    }
  return most;
}

/// The contact joints of a pair where a geom has a Gazebo classic surface (a URDF link's
/// <gazebo reference> tags, docs/urdf.md "Surfaces"), with Gazebo classic's rules
/// (ODEPhysics::Collide and its ODE's per-body max_vel and min_depth) on Debian's ODE. A geom
/// without a surface counts as its material: Friction both ways, rigid, no tolerances.
void addSurfaceContacts(WorldImpl& im, dGeomID g1, dGeomID g2, const dContactGeom* contacts, int n, size_t stride) {
  const GeomInfo& i1 = infoOf(im, g1);
  const GeomInfo& i2 = infoOf(im, g2);
  const MaterialDef* s1 = i1.surface >= 0 ? &im.surfaces[static_cast<size_t>(i1.surface)] : nullptr;
  const MaterialDef* s2 = i2.surface >= 0 ? &im.surfaces[static_cast<size_t>(i2.surface)] : nullptr;
  auto second = [](const GeomInfo& i, const MaterialDef* s) {
    return s && s->friction2 >= 0 ? s->friction2 : i.friction;
  };
  // Friction: Gazebo's smaller of the pair's per direction where a surface gives mu1 or mu2,
  // else guide 7.1's larger; bounce as guide 7.1.
  const bool gazebo = (s1 && s1->gazebo) || (s2 && s2->gazebo);
  const double mu = gazebo ? std::min(i1.friction, i2.friction) : std::max(i1.friction, i2.friction);
  const double mu2 = gazebo ? std::min(second(i1, s1), second(i2, s2)) : std::max(second(i1, s1), second(i2, s2));
  const double bounce = std::max(i1.bounceness, i2.bounceness);
  const double bounceVel = std::min(i1.minBounceVel, i2.minBounceVel);
  // fdir1 in the world: the first geom's, or the second's where it has one and the first has
  // none or a larger mu1 (Gazebo's rule).
  const dReal* fdir_rot = nullptr;
  const Vec3* fdir = nullptr;
  if (s1 && s1->fdir1 != Vec3{0, 0, 0}) {
    fdir = &s1->fdir1;
    fdir_rot = dGeomGetRotation(g1);
  }
  if (s2 && s2->fdir1 != Vec3{0, 0, 0} && (!fdir || i1.friction > i2.friction)) {
    fdir = &s2->fdir1;
    fdir_rot = dGeomGetRotation(g2);
  }
  Vec3 fd{0, 0, 0};
  if (fdir)
    for (size_t r = 0; r < 3; ++r)  // ODE's rotation: 3 rows of 4
      fd[r] = fdir_rot[r * 4] * (*fdir)[0] + fdir_rot[r * 4 + 1] * (*fdir)[1] + fdir_rot[r * 4 + 2] * (*fdir)[2];
  // kp and kd: springs in series, dampers side by side; as ERP and CFM at the step size.
  double inv_kp = 0, kd = 0;
  for (const MaterialDef* m : {s1, s2})
    if (m && m->kp > 0) {
      inv_kp += 1.0 / m->kp;
      kd += m->kd;
    }
  const double h = im.stepSize;
  const bool soft = inv_kp > 0;
  const double kp = soft ? 1.0 / inv_kp : 0;
  const double erp = soft ? h * kp / (h * kp + kd) : dWorldGetERP(im.world);
  const double cfm = soft ? 1.0 / (h * kp + kd) : 0;
  // minDepth and maxVel: the smaller of those given, applied through the depth ODE sees (the
  // world's surface layer is 0 and its largest correcting velocity unbounded).
  double min_depth = -1, max_vel = -1;
  for (const MaterialDef* m : {s1, s2}) {
    if (m && m->min_depth >= 0) min_depth = min_depth < 0 ? m->min_depth : std::min(min_depth, m->min_depth);
    if (m && m->max_vel >= 0) max_vel = max_vel < 0 ? m->max_vel : std::min(max_vel, m->max_vel);
  }
  const double push = h > 0 ? erp / h : 0;  // ODE's push-out velocity per m of depth
  dBodyID b1 = dGeomGetBody(g1);
  dBodyID b2 = dGeomGetBody(g2);
  for (int k = 0; k < n; ++k) {
    dContact c{};
    c.geom = *reinterpret_cast<const dContactGeom*>(reinterpret_cast<const char*>(contacts) + k * stride);
    c.surface.mode = dContactBounce | dContactApprox1 | dContactMu2;
    c.surface.mu = mu;
    c.surface.mu2 = mu2;
    c.surface.bounce = bounce;
    c.surface.bounce_vel = bounceVel;
    if (soft) {
      c.surface.mode |= dContactSoftERP | dContactSoftCFM;
      c.surface.soft_erp = erp;
      c.surface.soft_cfm = cfm;
    }
    if (min_depth > 0) c.geom.depth -= min_depth;  // ODE pushes out nothing below 0
    if (max_vel >= 0 && push > 0 && c.geom.depth * push > max_vel) c.geom.depth = max_vel / push;
    if (fdir) {  // in the contact plane (ODE takes fdir1 as it is: off the plane it is no tangent)
      const dReal* nrm = c.geom.normal;
      const double along = fd[0] * nrm[0] + fd[1] * nrm[1] + fd[2] * nrm[2];
      const Vec3 t{fd[0] - along * nrm[0], fd[1] - along * nrm[1], fd[2] - along * nrm[2]};
      const double len = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
      if (len > 1e-9) {
        c.surface.mode |= dContactFDir1;
        c.fdir1[0] = t[0] / len;
        c.fdir1[1] = t[1] / len;
        c.fdir1[2] = t[2] / len;
      }
    }
    dJointID j = dJointCreateContact(im.world, im.contactGroup, &c);
    dJointAttach(j, b1, b2);
    ++im.lastContacts;
  }
}

/// Creates the contact joints of the pair's n contacts (guide 7.1).
void addContacts(WorldImpl& im, dGeomID g1, dGeomID g2, const dContactGeom* contacts, int n, size_t stride) {
  const GeomInfo& i1 = infoOf(im, g1);
  const GeomInfo& i2 = infoOf(im, g2);
  if (i1.surface >= 0 || i2.surface >= 0) {
    addSurfaceContacts(im, g1, g2, contacts, n, stride);
    return;
  }
  // Guide 7.1: the larger friction, the larger bounceness, the smaller MinBounceVel.
  const double mu = std::max(i1.friction, i2.friction);
  const double bounce = std::max(i1.bounceness, i2.bounceness);
  const double bounceVel = std::min(i1.minBounceVel, i2.minBounceVel);
  dBodyID b1 = dGeomGetBody(g1);
  dBodyID b2 = dGeomGetBody(g2);
  for (int k = 0; k < n; ++k) {
    dContact c{};
    c.geom = *reinterpret_cast<const dContactGeom*>(reinterpret_cast<const char*>(contacts) + k * stride);
    // Approx1: Coulomb friction with the friction pyramid, bound = mu * normal force.
    // No SoftERP/SoftCFM: without them ODE applies the world's ERP and CFM to contacts,
    // which are exactly the settings' values, so the flags would change nothing.
    c.surface.mode = dContactBounce | dContactApprox1;
    c.surface.mu = mu;
    c.surface.bounce = bounce;
    c.surface.bounce_vel = bounceVel;
    dJointID j = dJointCreateContact(im.world, im.contactGroup, &c);
    dJointAttach(j, b1, b2);
    ++im.lastContacts;
  }
}

/// Collides one pair on the stepping thread and adds its contact joints.
void collidePair(WorldImpl& im, dGeomID g1, dGeomID g2) {
  const int maxContacts = mostContacts(im, g1, g2, static_cast<int>(im.contactBuffer.size()));
  const int n = collideGeoms(g1, g2, maxContacts, &im.contactBuffer[0].geom, sizeof(dContact));
  if (n > 0) addContacts(im, g1, g2, &im.contactBuffer[0].geom, n, sizeof(dContact));
}

void nearCallback(void* data, dGeomID g1, dGeomID g2) {
  WorldImpl& im = *static_cast<WorldImpl*>(data);
  if (mayTouch(im, g1, g2)) collidePair(im, g1, g2);
}

void gatherPair(void* data, dGeomID g1, dGeomID g2) {
  WorldImpl& im = *static_cast<WorldImpl*>(data);
  if (mayTouch(im, g1, g2)) im.narrow.pairs.push_back({g1, g2});
}

/// The broad phase: calls `callback` for the space's pairs in the space's order.
void broadPhase(WorldImpl& im, dNearCallback* callback) {
  if (dSpaceGetClass(im.space) == dHashSpaceClass) {
    // dHashSpace's pairs in its order, faster (the sweep on the pool's threads, if any).
    const size_t grain = parallelTestHooks().grain > 0 ? parallelTestHooks().grain : kSweepGrain;
    im.hashPairs.collide(im.space, &im, callback, im.pool.get(), grain);
  } else {
    dSpaceCollide(im.space, &im, callback);
  }
}

// One chunk's pairs into its buffer (a job of the pool; not inlined, so that a profile shows
// what runs in parallel: bench/threads_bench.py --profile).
[[gnu::noinline]] void collideChunk(const WorldImpl& im, NarrowPhase& np, size_t c, size_t begin, size_t end,
                                    size_t most) {
  std::vector<dContactGeom>& out = np.buffers[c];
  out.clear();
  for (size_t i = begin; i < end; ++i) {
    const auto [g1, g2] = np.pairs[i];
    if (!statelessCollider(g1) || !statelessCollider(g2)) {
      np.counts[i] = -1;  // collided when committed, on the stepping thread
      continue;
    }
    const size_t at = out.size();
    const int pair_most = mostContacts(im, g1, g2, static_cast<int>(most));
    out.resize(at + static_cast<size_t>(pair_most));
    const int got = collideGeoms(g1, g2, pair_most, &out[at], sizeof(dContactGeom));
    out.resize(at + static_cast<size_t>(std::max(got, 0)));
    np.counts[i] = std::max(got, 0);
  }
}

void collideInParallel(WorldImpl& im) {
  NarrowPhase& np = im.narrow;
  np.pairs.clear();
  broadPhase(im, &gatherPair);
  const size_t n = np.pairs.size();
  const ParallelTestHooks& hooks = parallelTestHooks();
  const size_t grain = hooks.grain > 0 ? hooks.grain : kPairGrain;
  const size_t chunks = im.pool->chunks(n, grain);
  const size_t most = im.contactBuffer.size();
  np.counts.assign(n, 0);
  if (np.buffers.size() < chunks) np.buffers.resize(chunks);
  im.pool->run(n, grain, [&](size_t c, size_t begin, size_t end, int) { collideChunk(im, np, c, begin, end, most); });
  // Where each pair's contacts are: its chunk's buffer, after those of the pairs before it.
  np.first.resize(n);
  for (size_t c = 0; c < chunks; ++c) {
    const dContactGeom* at = np.buffers[c].data();
    for (size_t i = c * n / chunks; i < (c + 1) * n / chunks; ++i) {
      np.first[i] = at;
      at += std::max(np.counts[i], 0);
    }
  }
  // Commit in pair order (the test hook: last pair first, as a commit in completion order could).
  for (size_t k = 0; k < n; ++k) {
    const size_t i = hooks.reverse_commit ? n - 1 - k : k;
    const auto [g1, g2] = np.pairs[i];
    if (np.counts[i] < 0) {
      collidePair(im, g1, g2);
    } else {
      addContacts(im, g1, g2, np.first[i], np.counts[i], sizeof(dContactGeom));
    }
  }
}

}  // namespace

bool statelessCollider(dGeomID g) {
  switch (dGeomGetClass(g)) {
    case dSphereClass:
    case dBoxClass:
    case dCapsuleClass:
    case dCylinderClass:
    case dPlaneClass:
    case dRayClass:
      return true;
    default:
      return false;
  }
}

ParallelTestHooks& parallelTestHooks() {
  static ParallelTestHooks hooks;
  return hooks;
}

void collide(WorldImpl& im) {
  im.lastContacts = 0;
  if (im.pool) {
    collideInParallel(im);
  } else {
    broadPhase(im, &nearCallback);
  }
}

}  // namespace simbob
