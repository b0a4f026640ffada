// HashSpacePairs (lib/physics/broadphase.h) against ODE's own dHashSpace: on random scenes of
// geoms of every size class (cells from 1/128 m to 64 m, planes, boxes too big for the space's
// levels), static and on bodies, several geoms per body, disabled geoms and category bits, the
// sequence of (geom, geom) calls must equal dSpaceCollide's exactly -- order and argument order
// included, since the order of the contact joints decides QuickStep's result. The scene moves
// between checks, in random order, because the order of the space's list (and so dHashSpace's
// order) depends on which geoms moved in which order.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "physics/broadphase.h"
#include "physics/workers.h"

namespace {

using Calls = std::vector<std::pair<dGeomID, dGeomID>>;

void record(void* data, dGeomID a, dGeomID b) { static_cast<Calls*>(data)->emplace_back(a, b); }

struct Scene {
  dWorldID world = dWorldCreate();
  dSpaceID space = dHashSpaceCreate(nullptr);
  std::vector<dBodyID> bodies;
  std::vector<dGeomID> geoms;
  ~Scene() {
    dSpaceDestroy(space);
    dWorldDestroy(world);
  }
};

/// A random scene: `n` geoms with largest extents log-uniform in [0.005, 60] m in a box of
/// `spread` m (y from 0 to 2), one in five static, a third of the bodies with two geoms.
void build(Scene& s, std::mt19937_64& rng, int n, double spread) {
  std::uniform_real_distribution<double> u(0, 1);
  auto size = [&] { return 0.005 * std::pow(60 / 0.005, u(rng)); };
  dBodyID shared = nullptr;
  for (int i = 0; i < n; ++i) {
    dGeomID g = nullptr;
    const double kind = u(rng);
    if (kind < 0.4) {
      g = dCreateBox(s.space, size(), size(), size());
    } else if (kind < 0.7) {
      g = dCreateSphere(s.space, size() / 2);
    } else {
      g = dCreateCapsule(s.space, size() / 4, size());
    }
    const double place = u(rng);
    if (place < 0.2) {
      dGeomSetPosition(g, spread * (u(rng) - 0.5), 2 * u(rng), spread * (u(rng) - 0.5));
    } else if (place < 0.35 && shared) {
      dGeomSetBody(g, shared);  // a second geom on the last body
      dGeomSetOffsetPosition(g, 0.1, 0, 0);
      shared = nullptr;
    } else {
      dBodyID b = dBodyCreate(s.world);
      dBodySetPosition(b, spread * (u(rng) - 0.5), 2 * u(rng), spread * (u(rng) - 0.5));
      dGeomSetBody(g, b);
      s.bodies.push_back(b);
      shared = b;
    }
    if (u(rng) < 0.05) dGeomDisable(g);
    if (u(rng) < 0.1) {
      dGeomSetCategoryBits(g, 1 + (rng() & 1));
      dGeomSetCollideBits(g, 1 + (rng() & 1));
    }
    s.geoms.push_back(g);
  }
  s.geoms.push_back(dCreatePlane(s.space, 0, 1, 0, 0));
  if (u(rng) < 0.5) s.geoms.push_back(dCreatePlane(s.space, 1, 0, 0, -spread));
}

/// Moves a random half of the bodies, in random order, by up to `step` m.
void move(Scene& s, std::mt19937_64& rng, double step) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<dBodyID> order = s.bodies;
  std::shuffle(order.begin(), order.end(), rng);
  order.resize(order.size() / 2);
  for (dBodyID b : order) {
    const dReal* p = dBodyGetPosition(b);
    dBodySetPosition(b, p[0] + step * u(rng), std::abs(p[1] + step * u(rng)), p[2] + step * u(rng));
  }
}

/// Checks `steps` times that HashSpacePairs calls exactly what dSpaceCollide calls; returns the
/// number of calls seen (so a scene where nothing meets cannot pass unnoticed). With a pool, the
/// sweep is split among its threads in chunks of `grain` boxes.
size_t compare(Scene& s, std::mt19937_64& rng, int steps, double step, simbob::WorkerPool* pool = nullptr,
               size_t grain = 256) {
  simbob::HashSpacePairs pairs;
  size_t seen = 0;
  for (int k = 0; k < steps; ++k) {
    Calls ours, odes;
    pairs.collide(s.space, &ours, &record, pool, grain);  // first: it leaves the geoms clean, as ODE would
    dSpaceCollide(s.space, &odes, &record);
    REQUIRE(ours.size() == odes.size());
    for (size_t i = 0; i < ours.size(); ++i) {
      INFO("step " << k << ", call " << i << " of " << ours.size());
      REQUIRE(ours[i] == odes[i]);
    }
    seen += odes.size();
    move(s, rng, step);
  }
  return seen;
}

struct Ode {
  Ode() { dInitODE2(0); }
  ~Ode() { dCloseODE(); }
};

}  // namespace

TEST_CASE("HashSpacePairs reports dHashSpace's pairs in dHashSpace's order", "[broadphase]") {
  Ode ode;
  for (uint64_t seed = 1; seed <= 60; ++seed) {
    INFO("seed " << seed);
    std::mt19937_64 rng(seed);
    Scene s;
    // Crowded (most geoms meet several others) on odd seeds, sparse on even ones; about the
    // origin, where dHashSpace's cell hashes wrap (see the next test), and away from it.
    build(s, rng, 150, seed % 2 ? 3.0 : 30.0);
    if (seed % 3 == 0) {
      for (dBodyID b : s.bodies) {
        const dReal* p = dBodyGetPosition(b);
        dBodySetPosition(b, p[0] - 500, p[1], p[2] + 70);
      }
    }
    CHECK(compare(s, rng, 10, 0.3) > 150);
  }
}

// --threads N: the sweep split into chunks (of one box, so that 150 geoms make many) on 2 and 3
// threads finds the same calls in the same order.
TEST_CASE("HashSpacePairs with its sweep split among threads reports dHashSpace's pairs in order", "[broadphase]") {
  Ode ode;
  for (int threads : {2, 3}) {
    simbob::WorkerPool pool(threads);
    for (uint64_t seed = 1; seed <= 10; ++seed) {
      INFO(threads << " threads, seed " << seed);
      std::mt19937_64 rng(seed);
      Scene s;
      build(s, rng, 150, seed % 2 ? 3.0 : 30.0);
      CHECK(compare(s, rng, 10, 0.3, &pool, 1) > 150);
    }
  }
}

TEST_CASE("HashSpacePairs follows the space's levels: boxes above the maximum are big boxes", "[broadphase]") {
  Ode ode;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    INFO("seed " << seed);
    std::mt19937_64 rng(100 + seed);
    Scene s;
    dHashSpaceSetLevels(s.space, -1, 2);  // cells from 0.5 m to 4 m: every larger geom is big
    build(s, rng, 100, 8.0);
    CHECK(compare(s, rng, 8, 0.5) > 100);
  }
}

TEST_CASE("Like dHashSpace, HashSpacePairs misses two overlapping boxes whose cell columns hash apart",
          "[broadphase]") {
  // Both boxes are at level 0 (1 m cells) in the column x = y = 0, whose hash base is 0. A's
  // cells start at z = 0, B's at z = -1: dHashSpace files B's column from the wrapped sum
  // 0 + (-1) and looks A's up from 0, so it never finds them in one cell. The boxes intersect,
  // yet ODE 0.16 reports no pair, and simbob, which must give dHashSpace's contacts, neither.
  Ode ode;
  Scene s;
  dBodyID ba = dBodyCreate(s.world);
  dBodyID bb = dBodyCreate(s.world);
  dBodySetPosition(ba, 0.5, 0.5, 0.5);  // box z from 0.2 to 0.8: cells 0..0
  dBodySetPosition(bb, 0.5, 0.5, 0.1);  // box z from -0.2 to 0.4: cells -1..0
  dGeomID a = dCreateBox(s.space, 0.6, 0.6, 0.6);
  dGeomID b = dCreateBox(s.space, 0.6, 0.6, 0.6);
  dGeomSetBody(a, ba);
  dGeomSetBody(b, bb);
  dContactGeom c[4];
  REQUIRE(dCollide(a, b, 4, c, sizeof(dContactGeom)) > 0);  // they do intersect
  Calls ours, odes;
  simbob::HashSpacePairs pairs;
  pairs.collide(s.space, &ours, &record);
  dSpaceCollide(s.space, &odes, &record);
  CHECK(odes.empty());
  CHECK(ours.empty());
  // Moved 1 m along x, both columns hash alike and the pair is met.
  dBodySetPosition(ba, 1.5, 0.5, 0.5);
  dBodySetPosition(bb, 1.5, 0.5, 0.1);
  pairs.collide(s.space, &ours, &record);
  dSpaceCollide(s.space, &odes, &record);
  CHECK(odes.size() == 1);
  CHECK(ours == odes);
}

TEST_CASE("HashSpacePairs on a space of fewer than two geoms calls nothing, as dHashSpace", "[broadphase]") {
  Ode ode;
  Scene s;
  dCreateSphere(s.space, 1);
  simbob::HashSpacePairs pairs;
  Calls ours;
  pairs.collide(s.space, &ours, &record);
  CHECK(ours.empty());
}
