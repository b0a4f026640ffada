#include "simbob/trajectory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using simbob::Error;
using simbob::ErrorKind;
using simbob::Trajectory;
using simbob::TrajectoryWriter;

namespace {

/// A fresh directory under the system temp dir, removed with its contents at scope exit.
struct TempDir {
  fs::path path;
  TempDir() {
    static int counter = 0;
    std::random_device rd;
    path = fs::temp_directory_path() / ("simbob_traj_test_" + std::to_string(::getpid()) + "_" +
                                        std::to_string(++counter) + "_" + std::to_string(rd()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
  size_t entryCount() const {
    size_t n = 0;
    for (auto it = fs::directory_iterator(path); it != fs::directory_iterator(); ++it) ++n;
    return n;
  }
};

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void writeAll(const std::string& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out << content;
}

const std::string kHeader = "time,body,x,y,z,qw,qx,qy,qz\n";

/// Writes `content` to <dir>/traj.csv, reads it back and returns the error text ("" if none).
std::string readError(const TempDir& dir, const std::string& content, ErrorKind* kind = nullptr) {
  std::string path = dir.file("traj.csv");
  writeAll(path, content);
  Trajectory t;
  Error err;
  if (simbob::readTrajectory(path, &t, &err)) return "";
  if (kind) *kind = err.kind;
  return err.str();
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("trajectory writer produces the exact header and row bytes", "[trajectory]") {
  TempDir dir;
  std::string path = dir.file("traj.csv");
  Error err;
  auto w = TrajectoryWriter::open(path, {"a", "robot/arm.link1"}, &err);
  REQUIRE(w);
  const double s0[] = {1, 2, 3, 1, 0, 0, 0, -0.5, 1e-300, 2.5e10, 0.7071067811865476, 0, -0.0, 0.1};
  const double s1[] = {0.1, 0.2, 0.30000000000000004, 1, 0, 0, 0, 1, 1, 1, 1, 0, 0, 0};
  REQUIRE(w->addSample(0.01, s0));
  REQUIRE(w->addSample(0.02, s1));
  const std::string expected =
      "time,body,x,y,z,qw,qx,qy,qz\n"
      "0.01,a,1,2,3,1,0,0,0\n"
      "0.01,robot/arm.link1,-0.5,1e-300,2.5e+10,0.7071067811865476,0,-0,0.1\n"
      "0.02,a,0.1,0.2,0.30000000000000004,1,0,0,0\n"
      "0.02,robot/arm.link1,1,1,1,1,0,0,0\n";
  CHECK(w->bytesWritten() == expected.size());
  REQUIRE(w->commit(&err));
  CHECK(readAll(path) == expected);
  CHECK(dir.entryCount() == 1);
}

TEST_CASE("trajectory writer with no bodies writes only the header", "[trajectory]") {
  TempDir dir;
  std::string path = dir.file("empty.csv");
  Error err;
  auto w = TrajectoryWriter::open(path, {}, &err);
  REQUIRE(w);
  CHECK(w->addSample(0, nullptr));
  REQUIRE(w->commit(&err));
  CHECK(readAll(path) == kHeader);
}

TEST_CASE("trajectory writer creates nothing under the final name before commit", "[trajectory]") {
  TempDir dir;
  std::string path = dir.file("traj.csv");
  Error err;
  auto w = TrajectoryWriter::open(path, {"a"}, &err);
  REQUIRE(w);
  CHECK(w->tempPath() == path + ".tmp." + std::to_string(::getpid()));
  CHECK(w->finalPath() == path);
  const double pose[] = {1, 2, 3, 1, 0, 0, 0};
  bool all_ok = true;
  for (int i = 0; i < 100000; ++i) all_ok = w->addSample(i * 0.001, pose) && all_ok;  // flushes
  REQUIRE(all_ok);
  CHECK_FALSE(fs::exists(path));
  CHECK(fs::exists(w->tempPath()));
  CHECK(fs::file_size(w->tempPath()) > 0);
  REQUIRE(w->commit(&err));
  CHECK(fs::exists(path));
  CHECK_FALSE(fs::exists(w->tempPath()));
  CHECK(fs::file_size(path) == w->bytesWritten());
  // Closed: further samples are refused, a second commit is an error.
  CHECK_FALSE(w->addSample(1000, pose));
  CHECK_FALSE(w->commit(&err));
  CHECK(err.kind == ErrorKind::Internal);
}

TEST_CASE("trajectory writer commit replaces an existing file", "[trajectory]") {
  TempDir dir;
  std::string path = dir.file("traj.csv");
  writeAll(path, "old contents\n");
  Error err;
  auto w = TrajectoryWriter::open(path, {"a"}, &err);
  REQUIRE(w);
  const double pose[] = {0, 0, 0, 1, 0, 0, 0};
  w->addSample(0, pose);
  CHECK(readAll(path) == "old contents\n");  // untouched until commit
  REQUIRE(w->commit(&err));
  CHECK(readAll(path) == kHeader + "0,a,0,0,0,1,0,0,0\n");
  CHECK(dir.entryCount() == 1);
}

TEST_CASE("trajectory writer keepPartial renames to the partial path", "[trajectory]") {
  TempDir dir;
  std::string path = dir.file("traj.csv");
  std::string partial = dir.file("traj.partial.csv");
  Error err;
  auto w = TrajectoryWriter::open(path, {"a"}, &err);
  REQUIRE(w);
  const double pose[] = {0, 0, 0, 1, 0, 0, 0};
  w->addSample(0.5, pose);
  REQUIRE(w->keepPartial(partial, &err));
  CHECK_FALSE(fs::exists(path));
  CHECK_FALSE(fs::exists(w->tempPath()));
  CHECK(readAll(partial) == kHeader + "0.5,a,0,0,0,1,0,0,0\n");
  CHECK(dir.entryCount() == 1);
}

TEST_CASE("trajectory writer abandons its temp file when destroyed", "[trajectory]") {
  TempDir dir;
  std::string path = dir.file("traj.csv");
  Error err;
  {
    auto w = TrajectoryWriter::open(path, {"a"}, &err);
    REQUIRE(w);
    const double pose[] = {0, 0, 0, 1, 0, 0, 0};
    w->addSample(0, pose);
    CHECK(dir.entryCount() == 1);
  }
  CHECK(dir.entryCount() == 0);
  auto w = TrajectoryWriter::open(path, {"a"}, &err);
  REQUIRE(w);
  w->abandon();
  CHECK(dir.entryCount() == 0);
  CHECK_FALSE(w->commit(&err));
  CHECK_FALSE(fs::exists(path));
}

TEST_CASE("trajectory writer reports CannotCreate for a missing directory", "[trajectory]") {
  TempDir dir;
  std::string path = dir.file("no/such/dir/traj.csv");
  Error err;
  auto w = TrajectoryWriter::open(path, {"a"}, &err);
  CHECK_FALSE(w);
  CHECK(err.kind == ErrorKind::CannotCreate);
  // Named by its own name and folder, not by the temporary name it is written under.
  CHECK(err.str() == path + ": cannot create: folder '" + dir.file("no/such/dir") + "' does not exist");
}

TEST_CASE("trajectory writer rejects empty and duplicate body keys", "[trajectory]") {
  TempDir dir;
  Error err;
  CHECK_FALSE(TrajectoryWriter::open(dir.file("t.csv"), {"a", "b", "a"}, &err));
  CHECK(err.kind == ErrorKind::Internal);
  CHECK(err.message == "duplicate body key 'a'");
  CHECK_FALSE(TrajectoryWriter::open(dir.file("t.csv"), {""}, &err));
  CHECK(err.message == "empty body key");
  CHECK(dir.entryCount() == 0);
}

TEST_CASE("trajectory writer reports a short write as IoError and leaves no file", "[trajectory]") {
  TempDir dir;
  std::string path = dir.file("traj.csv");
  Error err;
  auto w = TrajectoryWriter::open(path, {"a", "b"}, &err);
  REQUIRE(w);
  const double pose[] = {0.125, 0.25, 0.5, 1, 0, 0, 0, 0.125, 0.25, 0.5, 1, 0, 0, 0};
  for (int i = 0; i < 1000; ++i) w->addSample(i * 0.001, pose);

  // Simulate a full disk with a file size limit; SIGXFSZ would otherwise kill the test.
  struct rlimit old_limit;
  REQUIRE(::getrlimit(RLIMIT_FSIZE, &old_limit) == 0);
  auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = old_limit;
  small.rlim_cur = 4096;
  REQUIRE(::setrlimit(RLIMIT_FSIZE, &small) == 0);
  bool committed = w->commit(&err);
  ::setrlimit(RLIMIT_FSIZE, &old_limit);
  std::signal(SIGXFSZ, old_handler);

  CHECK_FALSE(committed);
  CHECK(err.kind == ErrorKind::IoError);
  CHECK(err.str() == path + ": write failed: File too large");
  CHECK_FALSE(w->ok());
  CHECK(dir.entryCount() == 0);
}

TEST_CASE("trajectory write/read round trip is bit-exact", "[trajectory]") {
  TempDir dir;
  std::string path = dir.file("traj.csv");
  std::mt19937_64 rng(20240607);
  const std::vector<std::string> keys = {"world/base", "arm.link1", "arm.link2", "gripper", "w\"eird,key"};
  const size_t nb = keys.size();
  const size_t ns = 3000;  // > 1 MiB of text: exercises buffered flushing
  std::uniform_real_distribution<double> uni(-10, 10);
  std::vector<double> times(ns);
  std::vector<std::vector<double>> poses(ns, std::vector<double>(nb * simbob::kPoseSize));
  double t = -1;
  for (size_t s = 0; s < ns; ++s) {
    t += std::ldexp(static_cast<double>(rng() % 1000 + 1), -10);  // strictly increasing
    times[s] = t;
    for (double& v : poses[s]) {
      switch (rng() % 4) {
        case 0:
          v = uni(rng);
          break;
        case 1: {
          // Any finite bit pattern: denormals, huge and tiny exponents.
          uint64_t bits;
          do {
            bits = rng();
            std::memcpy(&v, &bits, sizeof v);
          } while (!std::isfinite(v));
          break;
        }
        case 2:
          v = uni(rng) * 1e-12;
          break;
        default: {
          const double special[] = {0.0,
                                    -0.0,
                                    std::numeric_limits<double>::max(),
                                    std::numeric_limits<double>::denorm_min(),
                                    std::numeric_limits<double>::min(),
                                    0.1,
                                    -1};
          v = special[rng() % 7];
        }
      }
    }
  }

  Error err;
  auto w = TrajectoryWriter::open(path, keys, &err);
  REQUIRE(w);
  bool all_ok = true;
  for (size_t s = 0; s < ns; ++s) all_ok = w->addSample(times[s], poses[s].data()) && all_ok;
  REQUIRE(all_ok);
  REQUIRE(w->commit(&err));
  CHECK(w->bytesWritten() > (size_t{1} << 20));

  Trajectory tr;
  REQUIRE(simbob::readTrajectory(path, &tr, &err));
  REQUIRE(tr.bodies == keys);
  REQUIRE(tr.times.size() == ns);
  size_t mismatches = 0;
  for (size_t s = 0; s < ns; ++s) {
    if (!sameBits(tr.times[s], times[s])) ++mismatches;
    for (size_t b = 0; b < nb; ++b) {
      const double* p = tr.pose(s, b);
      if (!p) {
        ++mismatches;
        continue;
      }
      for (size_t k = 0; k < simbob::kPoseSize; ++k)
        if (!sameBits(p[k], poses[s][b * simbob::kPoseSize + k])) ++mismatches;
    }
  }
  CHECK(mismatches == 0);
}

TEST_CASE("trajectory body keys with CSV specials are quoted and read back", "[trajectory]") {
  TempDir dir;
  std::string path = dir.file("traj.csv");
  const std::vector<std::string> keys = {"a,b", "say \"hi\"", "line\nbreak", "plain", "cr\rkey"};
  Error err;
  auto w = TrajectoryWriter::open(path, keys, &err);
  REQUIRE(w);
  std::vector<double> pose;
  for (size_t b = 0; b < keys.size(); ++b)
    for (double v : {double(b), 0.0, 0.0, 1.0, 0.0, 0.0, 0.0}) pose.push_back(v);
  w->addSample(0, pose.data());
  REQUIRE(w->commit(&err));
  CHECK(readAll(path) == kHeader +
                             "0,\"a,b\",0,0,0,1,0,0,0\n"
                             "0,\"say \"\"hi\"\"\",1,0,0,1,0,0,0\n"
                             "0,\"line\nbreak\",2,0,0,1,0,0,0\n"
                             "0,plain,3,0,0,1,0,0,0\n"
                             "0,\"cr\rkey\",4,0,0,1,0,0,0\n");
  Trajectory t;
  REQUIRE(simbob::readTrajectory(path, &t, &err));
  CHECK(t.bodies == keys);
  REQUIRE(t.pose(0, 2) != nullptr);
  CHECK(t.pose(0, 2)[0] == 2);
  CHECK(t.pose(0, 4)[0] == 4);
}

TEST_CASE("trajectory reader builds bodies, times and presence", "[trajectory]") {
  TempDir dir;
  std::string path = dir.file("traj.csv");
  // CRLF line ends, a quoted number, a missing row (b at 0.2), a body first seen late (c),
  // a blank line and no final newline.
  writeAll(path,
           "time,body,x,y,z,qw,qx,qy,qz\r\n"
           "0.1,a,1,0,0,1,0,0,0\r\n"
           "0.1,b,2,0,0,1,0,0,0\r\n"
           "0.2,a,3,0,0,1,0,0,0\r\n"
           "\r\n"
           "0.2,c,\"4\",0,0,1,0,0,0\r\n"
           "0.3,b,5,0,0,1,0,0,0\r\n"
           "0.3,a,6,0,0,0.5,0.5,0.5,0.5");
  Trajectory t;
  Error err;
  REQUIRE(simbob::readTrajectory(path, &t, &err));
  CHECK(t.bodies == std::vector<std::string>{"a", "b", "c"});
  CHECK(t.times == std::vector<double>{0.1, 0.2, 0.3});
  REQUIRE(t.poses.size() == 3);
  for (size_t b = 0; b < 3; ++b) {
    CHECK(t.present[b].size() == 3);
    CHECK(t.poses[b].size() == 3 * simbob::kPoseSize);
  }
  CHECK(t.pose(0, 0)[0] == 1);
  CHECK(t.pose(0, 1)[0] == 2);
  CHECK(t.pose(0, 2) == nullptr);
  CHECK(t.pose(1, 0)[0] == 3);
  CHECK(t.pose(1, 1) == nullptr);
  CHECK(t.pose(1, 2)[0] == 4);
  CHECK(t.pose(2, 0)[0] == 6);
  CHECK(t.pose(2, 0)[6] == 0.5);
  CHECK(t.pose(2, 1)[0] == 5);
  CHECK(t.pose(2, 2) == nullptr);
  CHECK(t.pose(9, 0) == nullptr);

  writeAll(path, kHeader);
  REQUIRE(simbob::readTrajectory(path, &t, &err));
  CHECK(t.bodies.empty());
  CHECK(t.times.empty());
}

TEST_CASE("trajectory with a NaN pose is written but rejected on reading", "[trajectory]") {
  TempDir dir;
  std::string path = dir.file("traj.csv");
  Error err;
  auto w = TrajectoryWriter::open(path, {"a"}, &err);
  REQUIRE(w);
  const double pose[] = {std::nan(""), 0, 0, 1, 0, 0, 0};
  w->addSample(0, pose);
  REQUIRE(w->keepPartial(path, &err));
  Trajectory t;
  CHECK_FALSE(simbob::readTrajectory(path, &t, &err));
  CHECK(err.str() == path + ":2: NaN in column x");
}

TEST_CASE("trajectory reader errors name file and line", "[trajectory]") {
  TempDir dir;
  const std::string p = dir.file("traj.csv");
  ErrorKind kind = ErrorKind::Internal;

  SECTION("missing file") {
    Trajectory t;
    Error err;
    CHECK_FALSE(simbob::readTrajectory(dir.file("nope.csv"), &t, &err));
    CHECK(err.kind == ErrorKind::MissingInput);
    CHECK(err.str() == dir.file("nope.csv") + ": cannot read: No such file or directory");
  }
  SECTION("a directory") {
    Trajectory t;
    Error err;
    CHECK_FALSE(simbob::readTrajectory(dir.path.string(), &t, &err));
    CHECK(err.kind == ErrorKind::MissingInput);
    CHECK(err.str() == dir.path.string() + ": cannot read: Is a directory");
  }
  SECTION("empty file") {
    CHECK(readError(dir, "", &kind) == p + ": empty file, expected header time,body,x,y,z,qw,qx,qy,qz");
    CHECK(kind == ErrorKind::InvalidInput);
  }
  SECTION("wrong header") {
    CHECK(readError(dir, "time,body,x,y,z\n0,a,1,2,3\n", &kind) ==
          p + ":1: expected header 'time,body,x,y,z,qw,qx,qy,qz' (or with ',vx,vy,vz,wx,wy,wz'), found "
              "'time,body,x,y,z'");
    CHECK(kind == ErrorKind::InvalidInput);
  }
  SECTION("wrong field count") {
    CHECK(readError(dir, kHeader + "0,a,1,2,3,1,0,0,0\n0,b,1,2,3,1,0,0\n") == p + ":3: expected 9 fields, found 8");
    CHECK(readError(dir, kHeader + "0,a,1,2,3,1,0,0,0,7\n") == p + ":2: expected 9 fields, found 10");
  }
  SECTION("bad number") {
    CHECK(readError(dir, kHeader + "0,a,1,abc,3,1,0,0,0\n", &kind) == p + ":2: bad number 'abc' in column y");
    CHECK(kind == ErrorKind::InvalidInput);
    CHECK(readError(dir, kHeader + "0,a,1,2,3,1,0,0,\n") == p + ":2: bad number '' in column qz");
    CHECK(readError(dir, kHeader + "x,a,1,2,3,1,0,0,0\n") == p + ":2: bad number 'x' in column time");
    CHECK(readError(dir, kHeader + "0,a,1,2,3,1,0,0,0\n0.1,a,Infinite,2,3,1,0,0,0\n") ==
          p + ":3: bad number 'Infinite' in column x");
  }
  SECTION("NaN") {
    CHECK(readError(dir, kHeader + "0,a,1,2,3,1,nan,0,0\n") == p + ":2: NaN in column qx");
    CHECK(readError(dir, kHeader + "NaN,a,1,2,3,1,0,0,0\n") == p + ":2: NaN in column time");
    CHECK(readError(dir, kHeader + "0,a,1,2,3,1,0,0,-nan\n") == p + ":2: NaN in column qz");
  }
  SECTION("time going backwards") {
    CHECK(readError(dir, kHeader + "0.01,a,1,2,3,1,0,0,0\n0.02,a,1,2,3,1,0,0,0\n"
                                   "0.01,b,1,2,3,1,0,0,0\n") == p + ":4: time 0.01 is before the previous time 0.02");
  }
  SECTION("duplicate row") {
    CHECK(readError(dir, kHeader + "0,a,1,2,3,1,0,0,0\n0,b,1,2,3,1,0,0,0\n"
                                   "0,a,1,2,3,1,0,0,0\n") == p + ":4: duplicate row for body 'a' at time 0");
  }
  SECTION("empty body key") {
    CHECK(readError(dir, kHeader + "0,,1,2,3,1,0,0,0\n") == p + ":2: empty body key");
    CHECK(readError(dir, kHeader + "0,\"\",1,2,3,1,0,0,0\n") == p + ":2: empty body key");
  }
  SECTION("quoting errors") {
    CHECK(readError(dir, kHeader + "0,\"a,1,2,3,1,0,0,0\n") == p + ":2: unterminated quoted field");
    CHECK(readError(dir, kHeader + "0,\"a\"x,1,2,3,1,0,0,0\n") == p + ":2: unexpected character after closing quote");
    CHECK(readError(dir, kHeader + "0,a\"b,1,2,3,1,0,0,0\n") == p + ":2: unexpected '\"' in unquoted field");
  }
  SECTION("line numbers count newlines inside quoted keys") {
    CHECK(readError(dir, kHeader + "0,\"two\nlines\",1,2,3,1,0,0,0\n0,b,1,2,3,1,0,0,zz\n") ==
          p + ":4: bad number 'zz' in column qz");
  }
}
