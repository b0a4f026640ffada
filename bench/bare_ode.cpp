// bare_ode: the benchmark scene of bench/gen_scene.py built and stepped straight through the
// ODE API -- the reference loop simbob is measured against. It links nothing of simbob; the only
// thing it shares with simbob is the trajectory CSV format (include/simbob/trajectory.h).
//
// Usage: bare_ode N DURATION OUT.csv [SAMPLE_INTERVAL]   (default 0.01 s, as simbob's --sample-interval)
//
// It does the same work as `simbob run bench.xml --duration DURATION --out OUT.csv` on the scene
// written by `bench/gen_scene.py N bench.xml`, in the same order, so that both programs produce
// the same doubles (tests/cli/bench_equal_work.sh checks this):
//   - ODE set-up as lib/physics/world.cpp does it: dInitODE2(0) and per-thread collision data,
//     dRandSetSeed(0) before dWorldCreate, gravity 0 -9.81 0, ERP 0.2, CFM 1e-10, 20 QuickStep
//     iterations, one hash space, one contact joint group;
//   - all bodies first (in scene order), then all geoms (the ground plane first: it comes first
//     in the scene), each geom tagged with its material;
//   - mass and inertia as simbob's RCInertiaByGeom computes them for a 0.2 m box of density
//     500 kg/m^3: volume = x*y*z, I_xx = volume*(y*y + z*z)/12, scaled by the density;
//   - per colliding pair: skip geoms of one body and bodies joined by a joint, up to 4 contacts,
//     mode dContactBounce|dContactApprox1 with mu = max, bounce = max, bounce_vel = min of the
//     two materials;
//   - a step is dSpaceCollide, dWorldQuickStep, dJointGroupEmpty;
//   - time kept in integer nanoseconds, steps of at most 1 ms towards the next sample time,
//     samples at t = 0, 0.01, 0.02, ... and at the end, a time within 1 us counts as reached
//     (simbob's clock with MaxTimeStep 1 ms, MinTimeStep 1 us and one periodic sampler);
//   - CSV rows `time,body,x,y,z,qw,qx,qy,qz`, numbers in shortest round-trip form.
// On stdout it prints one JSON line: bodies, steps, samples, loop seconds (world creation plus
// the stepping loop, the span simbob's run summary reports as wall_seconds), steps/s, CSV bytes
// and the part of the loop spent taking, formatting and writing samples.
#include <ode/ode.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

static_assert(sizeof(dReal) == sizeof(double), "bare_ode needs ODE built in double precision");

// ---- the scene (bench/boxgrid.py holds the same numbers) ----
constexpr int64_t kSpacingMm = 300;
constexpr int64_t kDropYMm = 101;
constexpr double kSize = 0.2;       // m, cube edge
constexpr double kDensity = 500.0;  // kg/m^3
constexpr double kFriction = 0.8;
constexpr double kBounce = 0.1;
constexpr double kMinBounceVel = 0.1;  // m/s

// ---- world and clock settings (simbob's SceneSettings defaults, MaxTimeStep 1 ms) ----
constexpr double kGravityY = -9.81;
constexpr double kErp = 0.2;
constexpr double kCfm = 1e-10;
constexpr int kIterations = 20;
constexpr int kMaxContacts = 4;
constexpr int64_t kStepNs = 1000000;             // 1 ms
constexpr int64_t kMinStepNs = 1000;             // 1 us: a time this close counts as reached
constexpr double kDefaultSampleInterval = 0.01;  // s
constexpr unsigned kSeed = 0;

int64_t gridSide(int64_t n) {
  int64_t s = static_cast<int64_t>(std::sqrt(static_cast<double>(n)));
  while (s * s > n) --s;
  while (s * s < n) ++s;
  return s;
}

struct Material {
  double friction, bounce, min_bounce_vel;
};

struct Sim {
  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  dJointGroupID contacts = nullptr;
  std::vector<dBodyID> bodies;
  std::vector<Material> geom_material;  // indexed by the number kept in dGeomSetData
  std::vector<dContact> contact_buf;    // zero-initialised once, reused by every pair
};

void nearCallback(void* data, dGeomID g1, dGeomID g2) {
  Sim& sim = *static_cast<Sim*>(data);
  dBodyID b1 = dGeomGetBody(g1);
  dBodyID b2 = dGeomGetBody(g2);
  if (b1 == b2) return;
  if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;
  const Material& m1 = sim.geom_material[reinterpret_cast<uintptr_t>(dGeomGetData(g1))];
  const Material& m2 = sim.geom_material[reinterpret_cast<uintptr_t>(dGeomGetData(g2))];
  const int n = dCollide(g1, g2, static_cast<int>(sim.contact_buf.size()), &sim.contact_buf[0].geom, sizeof(dContact));
  if (n <= 0) return;
  const double mu = std::max(m1.friction, m2.friction);
  const double bounce = std::max(m1.bounce, m2.bounce);
  const double bounce_vel = std::min(m1.min_bounce_vel, m2.min_bounce_vel);
  for (int k = 0; k < n; ++k) {
    dContact& c = sim.contact_buf[static_cast<size_t>(k)];
    c.surface.mode = dContactBounce | dContactApprox1;
    c.surface.mu = mu;
    c.surface.bounce = bounce;
    c.surface.bounce_vel = bounce_vel;
    dJointAttach(dJointCreateContact(sim.world, sim.contacts, &c), b1, b2);
  }
}

void build(Sim& sim, int n) {
  dRandSetSeed(kSeed);
  sim.world = dWorldCreate();
  dWorldSetGravity(sim.world, 0, kGravityY, 0);
  dWorldSetERP(sim.world, kErp);
  dWorldSetCFM(sim.world, kCfm);
  dWorldSetQuickStepNumIterations(sim.world, kIterations);
  sim.space = dHashSpaceCreate(nullptr);
  sim.contacts = dJointGroupCreate(0);
  sim.contact_buf.resize(kMaxContacts);

  // Mass of a uniform box about its centre, as RCInertiaByGeom computes it.
  const double x = kSize, y = kSize, z = kSize;
  const double volume = x * y * z;
  const double ixx = volume * (y * y + z * z) / 12;
  const double iyy = volume * (x * x + z * z) / 12;
  const double izz = volume * (x * x + y * y) / 12;

  const int64_t side = gridSide(n);
  const int64_t half = (side - 1) * (kSpacingMm / 2);
  sim.bodies.reserve(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const int64_t row = i / side, col = i % side;
    dBodyID b = dBodyCreate(sim.world);
    dMass m;
    dMassSetParameters(&m, kDensity * volume, 0, 0, 0, kDensity * ixx, kDensity * iyy, kDensity * izz, 0, 0, 0);
    dBodySetMass(b, &m);
    dBodySetPosition(b, static_cast<double>(col * kSpacingMm - half) / 1000.0, static_cast<double>(kDropYMm) / 1000.0,
                     static_cast<double>(row * kSpacingMm - half) / 1000.0);
    const dQuaternion q = {1, 0, 0, 0};
    dBodySetQuaternion(b, q);
    dBodySetLinearVel(b, 0, 0, 0);
    dBodySetAngularVel(b, 0, 0, 0);
    sim.bodies.push_back(b);
  }

  const Material mat{kFriction, kBounce, kMinBounceVel};
  sim.geom_material.reserve(static_cast<size_t>(n) + 1);
  dGeomID ground = dCreatePlane(sim.space, 0, 1, 0, 0);
  dGeomSetData(ground, reinterpret_cast<void*>(uintptr_t{0}));
  sim.geom_material.push_back(mat);
  for (int i = 0; i < n; ++i) {
    dGeomID g = dCreateBox(sim.space, kSize, kSize, kSize);
    dGeomSetBody(g, sim.bodies[static_cast<size_t>(i)]);
    dGeomSetData(g, reinterpret_cast<void*>(static_cast<uintptr_t>(sim.geom_material.size())));
    sim.geom_material.push_back(mat);
  }
}

void step(Sim& sim, double h) {
  dSpaceCollide(sim.space, &sim, &nearCallback);
  dWorldQuickStep(sim.world, h);
  dJointGroupEmpty(sim.contacts);
}

class CsvOut {
 public:
  explicit CsvOut(FILE* f) : f_(f) { buf_.reserve(kFlush + 4096); }
  void number(double d) {
    char tmp[32];
    auto r = std::to_chars(tmp, tmp + sizeof tmp, d);
    buf_.append(tmp, r.ptr);
  }
  void text(const char* s, size_t len) { buf_.append(s, len); }
  void ch(char c) { buf_ += c; }
  bool maybeFlush() { return buf_.size() < kFlush || flush(); }
  bool flush() {
    bool ok = std::fwrite(buf_.data(), 1, buf_.size(), f_) == buf_.size();
    bytes_ += buf_.size();
    buf_.clear();
    return ok;
  }
  uint64_t bytes() const { return bytes_ + buf_.size(); }

 private:
  static constexpr size_t kFlush = size_t{1} << 20;
  FILE* f_;
  std::string buf_;
  uint64_t bytes_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4 && argc != 5) {
    std::fprintf(stderr, "usage: bare_ode N DURATION OUT.csv [SAMPLE_INTERVAL]\n");
    return 64;
  }
  char* endp = nullptr;
  const long n = std::strtol(argv[1], &endp, 10);
  if (*endp || n < 1 || n > 10000000) {
    std::fprintf(stderr, "bare_ode: N must be a whole number of boxes >= 1\n");
    return 64;
  }
  const double duration = std::strtod(argv[2], &endp);
  if (*endp || !(duration > 0) || duration > 1e9) {
    std::fprintf(stderr, "bare_ode: DURATION must be a positive number of seconds\n");
    return 64;
  }
  const double interval = argc == 5 ? std::strtod(argv[4], &endp) : kDefaultSampleInterval;
  if ((argc == 5 && *endp) || !(interval >= 1e-9) || interval > 1e9) {
    std::fprintf(stderr, "bare_ode: SAMPLE_INTERVAL must be at least 1e-9 s\n");
    return 64;
  }
  const int64_t sample_ns = std::max<int64_t>(std::llround(interval * 1e9), 1);
  FILE* f = std::fopen(argv[3], "wb");
  if (!f) {
    std::fprintf(stderr, "bare_ode: cannot create %s: %s\n", argv[3], std::strerror(errno));
    return 73;
  }

  // Body keys and the header go out before the clock starts, as simbob's writer does.
  std::vector<std::string> keys;
  keys.reserve(static_cast<size_t>(n));
  for (long i = 0; i < n; ++i) keys.push_back("Box" + std::to_string(i));
  CsvOut csv(f);
  const char header[] = "time,body,x,y,z,qw,qx,qy,qz\n";
  csv.text(header, sizeof header - 1);

  dInitODE2(0);
  dAllocateODEDataForThread(dAllocateMaskAll);

  const auto wall0 = std::chrono::steady_clock::now();
  Sim sim;
  build(sim, static_cast<int>(n));

  bool ok = true;
  uint64_t steps = 0, samples = 0;
  std::string time_text;
  double sample_seconds = 0;  // time spent taking, formatting and writing samples
  auto sample = [&](int64_t t_ns) {
    const auto s0 = std::chrono::steady_clock::now();
    char tmp[32];
    auto r = std::to_chars(tmp, tmp + sizeof tmp, static_cast<double>(t_ns) / 1e9);
    time_text.assign(tmp, r.ptr);
    for (long i = 0; i < n; ++i) {
      dBodyID b = sim.bodies[static_cast<size_t>(i)];
      const dReal* p = dBodyGetPosition(b);
      const dReal* q = dBodyGetQuaternion(b);
      csv.text(time_text.data(), time_text.size());
      csv.ch(',');
      csv.text(keys[static_cast<size_t>(i)].data(), keys[static_cast<size_t>(i)].size());
      for (int k = 0; k < 3; ++k) {
        csv.ch(',');
        csv.number(p[k]);
      }
      for (int k = 0; k < 4; ++k) {
        csv.ch(',');
        csv.number(q[k]);
      }
      csv.ch('\n');
    }
    ok = csv.maybeFlush() && ok;
    ++samples;
    sample_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - s0).count();
  };

  const int64_t end = std::llround(duration * 1e9);
  int64_t now = 0, next_sample = 0, last_sample = -1;
  while (true) {
    if (next_sample - now <= kMinStepNs && now <= end) {
      sample(now);
      last_sample = now;
      while (next_sample - now <= kMinStepNs) next_sample += sample_ns;
    }
    if (now >= end) break;
    const int64_t target = std::min(next_sample, end);
    const int64_t gap = target - now;
    if (gap <= kMinStepNs) {  // within MinTimeStep: reached without a step
      now += gap;
      continue;
    }
    const int64_t h = std::min(gap, kStepNs);
    step(sim, static_cast<double>(h) / 1e9);
    now += h;
    ++steps;
  }
  if (last_sample != now) sample(now);
  const double loop_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();

  ok = csv.flush() && ok;
  ok = std::fclose(f) == 0 && ok;
  if (!ok) {
    std::fprintf(stderr, "bare_ode: writing %s failed\n", argv[3]);
    return 74;
  }
  std::printf(
      "{\"bodies\": %ld, \"steps\": %llu, \"samples\": %llu, \"loop_seconds\": %.6f, \"steps_per_second\": %.1f, "
      "\"csv_bytes\": %llu, \"sample_seconds\": %.6f}\n",
      n, static_cast<unsigned long long>(steps), static_cast<unsigned long long>(samples), loop_seconds,
      loop_seconds > 0 ? static_cast<double>(steps) / loop_seconds : 0.0, static_cast<unsigned long long>(csv.bytes()),
      sample_seconds);

  dJointGroupDestroy(sim.contacts);
  dSpaceDestroy(sim.space);
  dWorldDestroy(sim.world);
  dCloseODE();
  return 0;
}
