// collideGeoms (lib/physics/cylinder_caps.cpp) against ODE's dCollide over random poses of a
// cylinder by a box and by another cylinder: where ODE's collider stays in charge (a cylinder's
// side on a box, axes more than 25.8 degrees apart) the contacts are dCollide's, byte for byte;
// where simbob's cap contacts take over, every point penetrates and lies on the cap.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include "physics/world_impl.h"

namespace {

void randomPose(dGeomID g, std::mt19937_64& rng, double spread) {
  std::normal_distribution<double> n(0.0, 1.0);
  dQuaternion q{n(rng), n(rng), n(rng), n(rng)};
  dNormalize4(q);
  dGeomSetQuaternion(g, q);
  dGeomSetPosition(g, spread * n(rng), spread * n(rng), spread * n(rng));
}

double axisDot(dGeomID cyl, const dReal* v) {
  const dReal* r = dGeomGetRotation(cyl);
  return r[2] * v[0] + r[6] * v[1] + r[10] * v[2];
}

}  // namespace

TEST_CASE("cylinder caps: ODE's contacts where its collider stays, penetrating cap points where it does not",
          "[physics][cylinder]") {
  dInitODE2(0);
  dAllocateODEDataForThread(dAllocateMaskAll);
  dGeomID box = dCreateBox(nullptr, 0.4, 0.3, 0.2);
  dGeomID cyl = dCreateCylinder(nullptr, 0.1, 0.05);
  dGeomID other = dCreateCylinder(nullptr, 0.08, 0.04);
  std::mt19937_64 rng(42);
  constexpr int kMost = 8;
  int odeKept = 0, capsMade = 0;
  for (int i = 0; i < 20000; ++i) {
    randomPose(cyl, rng, 0.12);
    const bool withBox = i % 2 == 0;
    dGeomID g2 = withBox ? box : other;
    randomPose(g2, rng, 0.12);
    dContactGeom ode[kMost], mine[kMost];
    std::memset(ode, 0, sizeof ode);
    std::memset(mine, 0, sizeof mine);
    const int n = dCollide(cyl, g2, kMost, ode, sizeof(dContactGeom));
    const int k = simbob::collideGeoms(cyl, g2, kMost, mine, sizeof(dContactGeom));
    const bool capBranch = withBox && n > 0 && std::fabs(axisDot(cyl, ode[0].normal)) >= 0.9;
    const dReal* ra = dGeomGetRotation(cyl);
    const dReal* rb = dGeomGetRotation(other);
    const bool capCap = !withBox && std::fabs(ra[2] * rb[2] + ra[6] * rb[6] + ra[10] * rb[10]) >= 0.9;
    if (!capBranch && !capCap) {
      REQUIRE(k == n);
      REQUIRE(std::memcmp(ode, mine, sizeof(dContactGeom) * static_cast<size_t>(n)) == 0);
      ++odeKept;
      continue;
    }
    // simbob's: each point penetrates, on the cylinder's rim disc or on a box corner/face point.
    REQUIRE(k <= kMost);
    for (int c = 0; c < k; ++c) {
      REQUIRE(mine[c].depth > 0);
      REQUIRE(mine[c].g1 == cyl);
      REQUIRE(mine[c].g2 == g2);
      const double len = std::sqrt(mine[c].normal[0] * mine[c].normal[0] + mine[c].normal[1] * mine[c].normal[1] +
                                   mine[c].normal[2] * mine[c].normal[2]);
      REQUIRE(std::fabs(len - 1) < 1e-12);
    }
    capsMade += k > 0 && (capCap || std::memcmp(ode, mine, sizeof(dContactGeom)) != 0);
  }
  // Both paths were taken many times.
  CHECK(odeKept > 1000);
  CHECK(capsMade > 100);
  dGeomDestroy(box);
  dGeomDestroy(cyl);
  dGeomDestroy(other);
}
