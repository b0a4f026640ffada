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

/// Creates the contact joints of the pair's n contacts (guide 7.1).
void addContacts(WorldImpl& im, dGeomID g1, dGeomID g2, const dContactGeom* contacts, int n, size_t stride) {
  const GeomInfo& i1 = infoOf(im, g1);
  const GeomInfo& i2 = infoOf(im, g2);
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
  const int maxContacts = static_cast<int>(im.contactBuffer.size());
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
[[gnu::noinline]] void collideChunk(NarrowPhase& np, size_t c, size_t begin, size_t end, size_t most) {
  std::vector<dContactGeom>& out = np.buffers[c];
  out.clear();
  for (size_t i = begin; i < end; ++i) {
    const auto [g1, g2] = np.pairs[i];
    if (!statelessCollider(g1) || !statelessCollider(g2)) {
      np.counts[i] = -1;  // collided when committed, on the stepping thread
      continue;
    }
    const size_t at = out.size();
    out.resize(at + most);
    const int got = collideGeoms(g1, g2, static_cast<int>(most), &out[at], sizeof(dContactGeom));
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
  im.pool->run(n, grain, [&](size_t c, size_t begin, size_t end, int) { collideChunk(np, c, begin, end, most); });
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
