#include "simbob/tool/comparison.h"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "simbob/trajectory.h"

using simbob::CompareOptions;
using simbob::CompareResult;
using simbob::Trajectory;

namespace {

const double kHalfPi = std::acos(0.0);

/// Every body at the origin with the identity orientation at every time.
Trajectory makeTraj(const std::vector<std::string>& bodies, const std::vector<double>& times) {
  Trajectory t;
  t.times = times;
  for (const std::string& b : bodies) t.addBody(b);
  const double identity[] = {0, 0, 0, 1, 0, 0, 0};
  for (size_t s = 0; s < times.size(); ++s)
    for (size_t b = 0; b < bodies.size(); ++b) t.setPose(s, b, identity);
  t.finalize();
  return t;
}

double* mutablePose(Trajectory& t, size_t s, size_t b) { return t.poses[b].data() + s * simbob::kPoseSize; }

/// Hamilton product a*b, quaternions w x y z.
void quatMul(const double* a, const double* b, double* out) {
  out[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  out[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  out[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
  out[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
}

/// Rotation by `angle` about the unit axis (ax, ay, az).
void axisAngle(double ax, double ay, double az, double angle, double* q) {
  const double s = std::sin(angle / 2);
  q[0] = std::cos(angle / 2);
  q[1] = ax * s;
  q[2] = ay * s;
  q[3] = az * s;
}

}  // namespace

TEST_CASE("compare: identical trajectories pass", "[compare]") {
  Trajectory t = makeTraj({"a", "b"}, {0, 0.1, 0.2});
  mutablePose(t, 1, 0)[0] = 1.5;
  CompareResult r = simbob::compareTrajectories(t, t);
  CHECK(r.pass);
  CHECK_FALSE(r.structuralMismatch());
  CHECK(r.shared_samples == 3);
  REQUIRE(r.bodies.size() == 2);
  CHECK(r.bodies[0].body == "a");
  CHECK(r.bodies[0].compared == 3);
  CHECK(r.bodies[0].max_pos_err == 0);
  CHECK(r.bodies[0].max_rot_err == 0);
  CHECK_FALSE(r.first_divergence);
  CHECK(r.text().find("result: PASS") != std::string::npos);
  CHECK(r.json()["pass"] == true);
  CHECK(r.json()["first_divergence"].is_null());
}

TEST_CASE("compare: default tolerances are 1e-6", "[compare]") {
  CompareOptions o;
  CHECK(o.tol_pos == 1e-6);
  CHECK(o.tol_rot == 1e-6);
  CHECK(o.time_eps == 1e-9);
}

TEST_CASE("compare: position tolerance edges", "[compare]") {
  Trajectory golden = makeTraj({"a"}, {0, 0.1});
  Trajectory actual = golden;
  SECTION("just below") {
    mutablePose(actual, 1, 0)[2] = 0.99e-6;
    CompareResult r = simbob::compareTrajectories(actual, golden);
    CHECK(r.pass);
    CHECK(r.bodies[0].max_pos_err == Approx(0.99e-6).epsilon(1e-12));
    CHECK(r.bodies[0].max_pos_time == 0.1);
  }
  SECTION("exactly at the tolerance passes") {
    mutablePose(actual, 1, 0)[0] = 1e-6;
    CompareResult r = simbob::compareTrajectories(actual, golden);
    CHECK(r.bodies[0].max_pos_err == 1e-6);
    CHECK(r.pass);
  }
  SECTION("just above") {
    mutablePose(actual, 1, 0)[1] = 1.01e-6;
    CompareResult r = simbob::compareTrajectories(actual, golden);
    CHECK_FALSE(r.pass);
    CHECK_FALSE(r.structuralMismatch());
    REQUIRE(r.bodies[0].first_exceed_time);
    CHECK(*r.bodies[0].first_exceed_time == 0.1);
    CHECK(r.bodies[0].first_exceed_pos_err == Approx(1.01e-6));
    REQUIRE(r.first_divergence);
    CHECK(r.first_divergence->pos_exceeded);
    CHECK_FALSE(r.first_divergence->rot_exceeded);
  }
  SECTION("Euclidean over all three axes") {
    double* p = mutablePose(actual, 0, 0);
    p[0] = 0.6e-6;
    p[1] = 0.6e-6;
    p[2] = 0.6e-6;  // each axis within 1e-6, the distance ~1.04e-6 is not
    CompareResult r = simbob::compareTrajectories(actual, golden);
    CHECK_FALSE(r.pass);
    CHECK(r.bodies[0].max_pos_err == Approx(std::sqrt(3.0) * 0.6e-6));
  }
  SECTION("custom tolerance") {
    mutablePose(actual, 1, 0)[0] = 0.5;
    CompareOptions o;
    o.tol_pos = 0.5;
    CHECK(simbob::compareTrajectories(actual, golden, o).pass);
    o.tol_pos = 0.49;
    CHECK_FALSE(simbob::compareTrajectories(actual, golden, o).pass);
  }
}

TEST_CASE("compare: rotation tolerance edges", "[compare]") {
  Trajectory golden = makeTraj({"a"}, {0, 0.1});
  Trajectory actual = golden;
  double* q = mutablePose(actual, 1, 0) + 3;
  SECTION("just below") {
    axisAngle(0, 0, 1, 0.99e-6, q);
    CompareResult r = simbob::compareTrajectories(actual, golden);
    CHECK(r.pass);
    CHECK(r.bodies[0].max_rot_err == Approx(0.99e-6).epsilon(1e-9));
  }
  SECTION("just above") {
    axisAngle(0, 1, 0, 1.01e-6, q);
    CompareResult r = simbob::compareTrajectories(actual, golden);
    CHECK_FALSE(r.pass);
    CHECK(r.bodies[0].max_rot_err == Approx(1.01e-6).epsilon(1e-9));
    REQUIRE(r.first_divergence);
    CHECK(r.first_divergence->rot_exceeded);
    CHECK_FALSE(r.first_divergence->pos_exceeded);
  }
}

TEST_CASE("compare: rotation error is sign invariant and accurate", "[compare]") {
  const double s = 1 / std::sqrt(30.0);
  const double q1[] = {1 * s, 2 * s, 3 * s, 4 * s};
  const double neg[] = {-q1[0], -q1[1], -q1[2], -q1[3]};
  CHECK(simbob::rotationError(q1, neg) == 0.0);
  CHECK(simbob::rotationError(q1, q1) == 0.0);

  // A tiny rotation composed onto a generic orientation is measured to ~1e-9 relative.
  const double ax = 0.6, ay = 0.0, az = 0.8;
  for (double angle : {1e-7, 1e-9, 3e-5, 0.5, 3.0}) {
    double dq[4], q2[4];
    axisAngle(ax, ay, az, angle, dq);
    quatMul(q1, dq, q2);
    CHECK(simbob::rotationError(q1, q2) == Approx(angle).epsilon(1e-6));
    const double q2neg[] = {-q2[0], -q2[1], -q2[2], -q2[3]};
    CHECK(simbob::rotationError(q1, q2neg) == Approx(angle).epsilon(1e-6));
    CHECK(simbob::rotationError(q2, q1) == Approx(angle).epsilon(1e-6));
  }
  // Unnormalised quaternions measure the same angle.
  const double id[] = {1, 0, 0, 0};
  double qz[4];
  axisAngle(0, 0, 1, kHalfPi, qz);
  const double scaled[] = {2 * qz[0], 2 * qz[1], 2 * qz[2], 2 * qz[3]};
  CHECK(simbob::rotationError(id, scaled) == Approx(kHalfPi));
  // A zero quaternion is not a rotation.
  const double zero[] = {0, 0, 0, 0};
  CHECK(std::isnan(simbob::rotationError(id, zero)));

  // In a comparison, a sign-flipped quaternion passes with zero rotation error.
  Trajectory golden = makeTraj({"a"}, {0});
  std::copy(q1, q1 + 4, mutablePose(golden, 0, 0) + 3);
  Trajectory actual = golden;
  std::copy(neg, neg + 4, mutablePose(actual, 0, 0) + 3);
  CompareResult r = simbob::compareTrajectories(actual, golden);
  CHECK(r.pass);
  CHECK(r.bodies[0].max_rot_err == 0.0);
}

TEST_CASE("compare: NaN in a pose fails", "[compare]") {
  Trajectory golden = makeTraj({"a"}, {0, 1});
  Trajectory actual = golden;
  mutablePose(actual, 1, 0)[0] = std::nan("");
  CompareResult r = simbob::compareTrajectories(actual, golden);
  CHECK_FALSE(r.pass);
  CHECK(std::isnan(r.bodies[0].max_pos_err));
  REQUIRE(r.first_divergence);
  CHECK(r.first_divergence->time == 1);
}

TEST_CASE("compare: bodies present in only one trajectory", "[compare]") {
  Trajectory golden = makeTraj({"a", "b", "c"}, {0, 0.1});
  Trajectory actual = makeTraj({"c", "a", "extra"}, {0, 0.1});
  CompareResult r = simbob::compareTrajectories(actual, golden);
  CHECK_FALSE(r.pass);
  CHECK(r.structuralMismatch());
  CHECK(r.only_golden == std::vector<std::string>{"b"});
  CHECK(r.only_actual == std::vector<std::string>{"extra"});
  REQUIRE(r.bodies.size() == 2);
  CHECK(r.bodies[0].body == "a");  // golden order
  CHECK(r.bodies[1].body == "c");
  CHECK(r.bodies[0].pass());
  CHECK_FALSE(r.first_divergence);
  std::string text = r.text();
  CHECK(text.find("bodies only in golden: b\n") != std::string::npos);
  CHECK(text.find("bodies only in actual: extra\n") != std::string::npos);
  CHECK(text.find("only in golden") != std::string::npos);
  CHECK(text.find("result: FAIL") != std::string::npos);
  nlohmann::json j = r.json();
  CHECK(j["pass"] == false);
  CHECK(j["bodies_only_golden"] == nlohmann::json{"b"});
  CHECK(j["bodies_only_actual"] == nlohmann::json{"extra"});
}

TEST_CASE("compare: sample times present in only one trajectory", "[compare]") {
  Trajectory golden = makeTraj({"a"}, {0, 0.1, 0.2, 0.3});
  Trajectory actual = makeTraj({"a"}, {0, 0.1 + 5e-10, 0.15, 0.25, 0.3, 0.4});
  CompareResult r = simbob::compareTrajectories(actual, golden);
  CHECK_FALSE(r.pass);
  CHECK(r.shared_samples == 3);  // 0, 0.1 (within 1e-9), 0.3
  CHECK(r.times_only_actual.count == 3);
  REQUIRE(r.times_only_actual.first_time);
  CHECK(*r.times_only_actual.first_time == 0.15);
  CHECK(r.times_only_golden.count == 1);
  CHECK(*r.times_only_golden.first_time == 0.2);
  CHECK(r.bodies[0].compared == 3);
  CHECK(r.bodies[0].pass());  // the body itself agrees where both have samples
  std::string text = r.text();
  CHECK(text.find("sample times only in actual: 3 (first at t=0.15)\n") != std::string::npos);
  CHECK(text.find("sample times only in golden: 1 (first at t=0.2)\n") != std::string::npos);
  nlohmann::json j = r.json();
  CHECK(j["samples"]["only_actual"]["count"] == 3);
  CHECK(j["samples"]["only_golden"]["first_time"] == 0.2);

  // A time difference just above time_eps is a mismatch.
  Trajectory shifted = makeTraj({"a"}, {0, 0.1 + 2e-9, 0.2, 0.3});
  CHECK_FALSE(simbob::compareTrajectories(shifted, golden).pass);
}

TEST_CASE("compare: missing rows for a body at a shared time", "[compare]") {
  Trajectory golden = makeTraj({"a", "b"}, {0, 0.1, 0.2});
  Trajectory actual;
  actual.times = {0, 0.1, 0.2};
  actual.addBody("a");
  actual.addBody("b");
  const double identity[] = {0, 0, 0, 1, 0, 0, 0};
  for (size_t s = 0; s < 3; ++s) actual.setPose(s, 0, identity);
  actual.setPose(0, 1, identity);  // b has no rows at 0.1 and 0.2
  actual.finalize();
  CompareResult r = simbob::compareTrajectories(actual, golden);
  CHECK_FALSE(r.pass);
  CHECK(r.structuralMismatch());
  CHECK(r.bodies[0].pass());
  CHECK(r.bodies[1].missing_in_actual == 2);
  CHECK(r.bodies[1].missing_in_golden == 0);
  REQUIRE(r.bodies[1].first_missing_time);
  CHECK(*r.bodies[1].first_missing_time == 0.1);
  CHECK(r.bodies[1].compared == 1);
  CHECK(r.text().find("missing rows for b: 2 in actual, 0 in golden (first at t=0.1)\n") != std::string::npos);
  CHECK(r.json()["bodies"][1]["status"] == "missing rows");

  // The other way round: the row is missing in golden.
  CompareResult r2 = simbob::compareTrajectories(golden, actual);
  CHECK(r2.bodies[1].missing_in_golden == 2);
  CHECK_FALSE(r2.pass);
}

TEST_CASE("compare: first divergence is the earliest exceedance over all bodies", "[compare]") {
  Trajectory golden = makeTraj({"a", "b", "c"}, {0, 0.1, 0.2, 0.3, 0.4, 0.5});
  Trajectory actual = golden;
  // a exceeds from 0.3 on (largest at 0.5); b exceeds in rotation only at 0.2; c within tol.
  mutablePose(actual, 3, 0)[0] = 2e-6;
  mutablePose(actual, 4, 0)[0] = 5e-6;
  mutablePose(actual, 5, 0)[0] = 3e-6;
  axisAngle(1, 0, 0, 1e-3, mutablePose(actual, 2, 1) + 3);
  mutablePose(actual, 1, 2)[1] = 5e-7;

  CompareResult r = simbob::compareTrajectories(actual, golden);
  CHECK_FALSE(r.pass);
  CHECK_FALSE(r.structuralMismatch());
  REQUIRE(r.first_divergence);
  CHECK(r.first_divergence->time == 0.2);
  CHECK(r.first_divergence->body == "b");
  CHECK(r.first_divergence->rot_err == Approx(1e-3));
  CHECK(r.first_divergence->pos_err == 0);

  const simbob::BodyDiff& a = r.bodies[0];
  REQUIRE(a.first_exceed_time);
  CHECK(*a.first_exceed_time == 0.3);
  CHECK(a.first_exceed_pos_err == 2e-6);
  CHECK(a.max_pos_err == 5e-6);
  CHECK(a.max_pos_time == 0.4);
  CHECK(a.max_rot_err == 0);
  CHECK_FALSE(a.pass());
  const simbob::BodyDiff& b = r.bodies[1];
  CHECK(*b.first_exceed_time == 0.2);
  CHECK(b.max_rot_time == 0.2);
  const simbob::BodyDiff& c = r.bodies[2];
  CHECK(c.pass());
  CHECK(c.max_pos_err == 5e-7);
  CHECK_FALSE(c.first_exceed_time);

  std::string text = r.text();
  CHECK(text.find("first divergence: t=0.2 body b: pos err 0 m, rot err 0.001 rad (exceeds)\n") != std::string::npos);
  CHECK(text.find("result: FAIL\n") != std::string::npos);
  // The table has a header and one row per body, with status per body.
  CHECK(text.find("body  max pos err (m)  max rot err (rad)  first exceed (s)  status\n") == 0);
  CHECK(text.find("a     5e-06            0                  0.3               exceeded\n") != std::string::npos);
  CHECK(text.find("c     5e-07            0                  -                 ok\n") != std::string::npos);
}

TEST_CASE("compare: JSON report fields", "[compare]") {
  Trajectory golden = makeTraj({"a", "b"}, {0, 0.1});
  Trajectory actual = makeTraj({"a"}, {0, 0.1, 0.2});
  mutablePose(actual, 1, 0)[0] = 1e-3;
  nlohmann::json j = simbob::compareTrajectories(actual, golden).json();
  for (const char* key : {"pass", "structural_mismatch", "tolerances", "samples", "bodies", "bodies_only_actual",
                          "bodies_only_golden", "first_divergence"})
    CHECK(j.contains(key));
  CHECK(j["pass"] == false);
  CHECK(j["structural_mismatch"] == true);
  CHECK(j["tolerances"]["pos"] == 1e-6);
  CHECK(j["tolerances"]["rot"] == 1e-6);
  CHECK(j["samples"]["actual"] == 3);
  CHECK(j["samples"]["golden"] == 2);
  CHECK(j["samples"]["shared"] == 2);
  CHECK(j["samples"]["only_actual"]["first_time"] == 0.2);
  CHECK(j["samples"]["only_golden"]["first_time"].is_null());
  REQUIRE(j["bodies"].size() == 1);
  const nlohmann::json& a = j["bodies"][0];
  for (const char* key : {"body", "compared", "max_pos_err", "max_pos_time", "max_rot_err", "max_rot_time",
                          "first_exceed_time", "first_exceed_pos_err", "first_exceed_rot_err", "missing_in_actual",
                          "missing_in_golden", "first_missing_time", "status", "pass"})
    CHECK(a.contains(key));
  CHECK(a["body"] == "a");
  CHECK(a["max_pos_err"] == 1e-3);
  CHECK(a["max_pos_time"] == 0.1);
  CHECK(a["first_exceed_time"] == 0.1);
  CHECK(a["first_missing_time"].is_null());
  CHECK(a["status"] == "exceeded");
  CHECK(a["pass"] == false);
  CHECK(j["first_divergence"]["body"] == "a");
  CHECK(j["first_divergence"]["time"] == 0.1);
  CHECK(j["first_divergence"]["pos_err"] == 1e-3);
  CHECK(j["first_divergence"]["pos_exceeded"] == true);
  // Round-trips through text.
  CHECK(nlohmann::json::parse(j.dump()) == j);
}

TEST_CASE("compare: empty trajectories pass", "[compare]") {
  Trajectory empty;
  CompareResult r = simbob::compareTrajectories(empty, empty);
  CHECK(r.pass);
  CHECK(r.text().find("result: PASS") != std::string::npos);
}

TEST_CASE("compare: files written and read back compare equal", "[compare]") {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() /
                 ("simbob_compare_test_" + std::to_string(::getpid()) + "_" + std::to_string(std::random_device{}()));
  fs::create_directories(dir);
  const std::string path = (dir / "golden.csv").string();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(-1, 1);
  simbob::Error err;
  {
    auto w = simbob::TrajectoryWriter::open(path, {"base", "arm,1"}, &err);
    REQUIRE(w);
    for (int s = 0; s < 200; ++s) {
      double poses[14];
      for (double& v : poses) v = uni(rng);
      REQUIRE(w->addSample(s * 0.01, poses));
    }
    REQUIRE(w->commit(&err));
  }
  Trajectory a, b;
  REQUIRE(simbob::readTrajectory(path, &a, &err));
  REQUIRE(simbob::readTrajectory(path, &b, &err));
  CompareResult r = simbob::compareTrajectories(a, b);
  CHECK(r.pass);
  CHECK(r.shared_samples == 200);
  CHECK(r.bodies[1].body == "arm,1");
  CHECK(r.bodies[1].max_pos_err == 0);
  std::error_code ec;
  fs::remove_all(dir, ec);
}

TEST_CASE("rotationError does not depend on the quaternions' scale", "[compare]") {
  // Components near 1e200 would overflow the products of the angle formula without scaling.
  const double big[4] = {1e200, 2e200, -3e200, 0.5e200};
  CHECK(simbob::rotationError(big, big) == 0.0);
  const double unit[4] = {1, 2, -3, 0.5};
  const double small[4] = {1e-200, 2e-200, -3e-200, 0.5e-200};
  CHECK(simbob::rotationError(unit, small) == Approx(0.0).margin(1e-15));
  const double other[4] = {0, 1, 0, 0};
  CHECK(simbob::rotationError(big, other) == Approx(simbob::rotationError(unit, other)).epsilon(1e-12));
}
