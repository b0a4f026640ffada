// The trajectory sampler's velocity block (run --columns pose,velocity): what it writes is the
// bodies' velocity in the world frame, checked against free fall and free spin; files with it
// read back and compare like files without it.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "physics/model_builder.h"
#include "simbob/tool/comparison.h"
#include "simbob/loop.h"
#include "simbob/trajectory.h"
#include "sim/loop_helpers.h"

using namespace simbob;
using namespace simbob::test;

namespace {

namespace fs = std::filesystem;

struct TempFile {
  std::string path;
  explicit TempFile(const std::string& name)
      : path(
            (fs::temp_directory_path() / ("simbob_sampler_test_" + std::to_string(::getpid()) + "_" + name)).string()) {
  }
  ~TempFile() {
    std::error_code ec;
    fs::remove(path, ec);
  }
};

// A ball falling freely from y = 10 m while spinning at 2 rad/s about X; MaxTimeStep 1 ms.
Model fallingBall() {
  Model m = baseModel(0.001);
  addBody(m, {0, 10, 0}, 1.0, sphereInertia(1.0, 0.1));
  m.bodies[0].ang_vel = {2, 0, 0};
  return m;
}

Trajectory runTo(const Model& m, const std::string& path, bool velocity) {
  Error err;
  std::unique_ptr<TrajectoryWriter> w = TrajectoryWriter::open(path, {m.bodies[0].key}, &err, velocity);
  REQUIRE(w);
  LoopOptions o;
  o.duration = 0.5;
  o.sample_interval = 0.01;
  const RunResult r = runModel(m, o, w.get());
  REQUIRE(r.status == RunStatus::Completed);
  REQUIRE(w->commit(&err));
  Trajectory t;
  REQUIRE(readTrajectory(path, &t, &err));
  return t;
}

std::string firstLine(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace

TEST_CASE("sampler: the velocity block of a free fall is vy = -g t", "[sim][sampler]") {
  TempFile file("velocity.csv");
  const Trajectory t = runTo(fallingBall(), file.path, true);
  CHECK(firstLine(file.path) == "time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz");
  REQUIRE(t.has_velocity);
  REQUIRE(t.sampleCount() == 51);
  const double g = 9.81;
  for (size_t s = 0; s < t.sampleCount(); ++s) {
    const double time = t.times[s];
    const double* v = t.velocity(s, 0);
    REQUIRE(v != nullptr);
    INFO("t = " << time);
    // Gravity alone: the velocity grows by -g h each step, exactly -g t on the step grid.
    CHECK(v[1] == Approx(-g * time).margin(1e-12));
    CHECK(v[0] == 0.0);
    CHECK(v[2] == 0.0);
    // No torque on a free sphere: it keeps spinning at 2 rad/s about the world X axis.
    CHECK(v[3] == Approx(2.0).margin(1e-12));
    CHECK(v[4] == Approx(0.0).margin(1e-12));
    CHECK(v[5] == Approx(0.0).margin(1e-12));
  }
}

TEST_CASE("sampler: without the velocity block the file is the pose file of before", "[sim][sampler]") {
  TempFile plain("plain.csv"), with("with.csv");
  const Trajectory a = runTo(fallingBall(), plain.path, false);
  const Trajectory b = runTo(fallingBall(), with.path, true);
  CHECK(firstLine(plain.path) == kTrajectoryHeader);
  CHECK_FALSE(a.has_velocity);
  CHECK(a.velocity(0, 0) == nullptr);
  // Each row of the velocity file is the pose row, then six more fields.
  std::ifstream pa(plain.path), pb(with.path);
  std::string la, lb;
  std::getline(pa, la);
  std::getline(pb, lb);
  size_t rows = 0;
  while (std::getline(pa, la)) {
    REQUIRE(std::getline(pb, lb));
    CHECK(lb.compare(0, la.size() + 1, la + ",") == 0);
    CHECK(std::count(lb.begin(), lb.end(), ',') == 14);
    ++rows;
  }
  CHECK(rows == 51);
  CHECK_FALSE(std::getline(pb, lb));
  // compare reads both and finds the same poses.
  CHECK(compareTrajectories(b, a).pass);
  CHECK(compareTrajectories(a, b).pass);
}
