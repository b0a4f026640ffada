// bench/ray_bench: the cost of one ray of an RCLaserScanner against 10, 100 and 1,000 geoms
// (issue #21). A model built directly (as tests/physics/rays_test.cpp does, no scene file): N
// static boxes of 0.3 m at seeded random places in a 20 m x 20 m square around a carrier body
// (no gravity, nothing collides with it) that holds one scanner of R rays over 360 degrees with
// MaxRange 10 m, read every step. The same model without the scanner is the baseline; the
// cost per ray is (time with - time without) / (steps x R). The two alternate, R times each;
// medians are printed. Times are wall-clock around World::step only (creation excluded).
//
//   build/bench/ray_bench [--rays 360] [--steps 500] [--repeats 5]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "simbob/model.h"
#include "simbob/physics.h"

using namespace simbob;

namespace {

Model scene(int geoms, int rays) {
  Model m;
  m.settings.max_time_step = 0.001;
  m.settings.gravity = {0, 0, 0};
  m.materials.push_back(MaterialDef{});
  BodyDef b;
  b.key = "carrier";
  b.mass = 1;
  b.inertia = {0.004, 0, 0, 0, 0.004, 0, 0, 0, 0.004};
  m.bodies.push_back(b);
  uint64_t s = 12345;  // a fixed linear congruential sequence: the same boxes every run
  auto uniform = [&s]() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(s >> 11) / 9007199254740992.0;
  };
  for (int i = 0; i < geoms; ++i) {
    GeomDef g;
    g.shape = GeomShape::Box;
    g.body = -1;
    double x, z;
    do {
      x = uniform() * 20 - 10;
      z = uniform() * 20 - 10;
    } while (x * x + z * z < 1);  // none on the carrier
    g.offset.p = {x, 0, z};
    g.size = {0.3, 0.3, 0.3};
    m.geoms.push_back(g);
  }
  if (rays > 0) {
    SensorDef sc;
    sc.key = "scanner";
    sc.kind = SensorKind::Scanner;
    sc.body = 0;
    sc.rays = rays;
    sc.field_of_view = 360;
    sc.max_range = 10;
    m.sensors.push_back(sc);
  }
  return m;
}

double stepSeconds(const Model& m, int steps) {
  auto w = World::create(m, 0);
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) w->step(0.001);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : (v[v.size() / 2 - 1] + v[v.size() / 2]) / 2;
}

}  // namespace

int main(int argc, char** argv) {
  int rays = 360, steps = 500, repeats = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    const int v = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--rays"))
      rays = v;
    else if (!std::strcmp(argv[i], "--steps"))
      steps = v;
    else if (!std::strcmp(argv[i], "--repeats"))
      repeats = v;
    else {
      std::fprintf(stderr, "usage: ray_bench [--rays N] [--steps N] [--repeats N]\n");
      return 64;
    }
  }
  if (rays < 1 || steps < 1 || repeats < 1) {
    std::fprintf(stderr, "ray_bench: --rays, --steps and --repeats must be >= 1\n");
    return 64;
  }
  std::printf("geoms,rays,steps,repeats,median_step_us_without,median_step_us_with,ns_per_ray\n");
  for (int geoms : {10, 100, 1000}) {
    const Model with = scene(geoms, rays), without = scene(geoms, 0);
    std::vector<double> a, b;
    for (int r = 0; r < repeats; ++r) {
      b.push_back(stepSeconds(without, steps));
      a.push_back(stepSeconds(with, steps));
    }
    const double ta = median(a), tb = median(b);
    std::printf("%d,%d,%d,%d,%.3f,%.3f,%.1f\n", geoms, rays, steps, repeats, tb / steps * 1e6, ta / steps * 1e6,
                (ta - tb) / (double(steps) * rays) * 1e9);
  }
  return 0;
}
