// Shared helpers of the URDF tests: compiling URDF text (as a bare robot or through a scene's
// RCImportURDF), stepping it, and the paths of Debian's dart-doc robots.
#pragma once

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <memory>
#include <vector>
#include <string>

#include "scene/scene_helpers.h"
#include "simbob/physics.h"
#include "simbob/simulation.h"

namespace urdftest {

using namespace simbob;
using scenetest::errorText;
using scenetest::TempDir;

/// Where Debian's dart-doc (scripts/deps.sh test) puts its URDF robots.
inline const std::string kDart = "/usr/share/doc/dart/data/urdf";

/// Loads and compiles `text` as the file `name` (a bare URDF when it ends in .urdf); the
/// errors and warnings land in `diag`.
inline bool compileText(const std::string& text, const std::string& name, Model* m, Diagnostics& diag) {
  Scene s;
  if (!loadSceneFromText(text, name, Format::Xml, testRegistry(), &s, diag)) return false;
  return compileScene(s, m, diag);
}

inline Model mustCompile(const std::string& text, const std::string& name = "robot.urdf") {
  Model m;
  Diagnostics d;
  const bool ok = compileText(text, name, &m, d);
  INFO(errorText(d));
  REQUIRE(ok);
  return m;
}

/// Loads and compiles a scene file.
inline bool compileFile(const std::string& path, Model* m, Diagnostics& diag) {
  Scene s;
  if (!loadScene(path, testRegistry(), &s, diag)) return false;
  return compileScene(s, m, diag);
}

inline int bodyIndex(const Model& m, const std::string& key) {
  for (size_t i = 0; i < m.bodies.size(); ++i)
    if (m.bodies[i].key == key) return static_cast<int>(i);
  FAIL("no body '" << key << "'");
  return -1;
}

inline int jointIndex(const Model& m, const std::string& key) {
  for (size_t i = 0; i < m.joints.size(); ++i)
    if (m.joints[i].key == key) return static_cast<int>(i);
  FAIL("no joint '" << key << "'");
  return -1;
}

/// A Simulation of `m` with the default options (the test fails when it cannot be made).
inline std::unique_ptr<Simulation> simulate(const Model& m) {
  Diagnostics d;
  auto sim = Simulation::fromModel(m, SimulationOptions{}, d);
  INFO(errorText(d));
  REQUIRE(sim);
  return sim;
}

/// Complete elliptic integral of the first kind K(k) by the arithmetic-geometric mean: a
/// pendulum released at theta0 swings with the period 4 K(sin(theta0 / 2)) / w0.
inline double ellipticK(double k) {
  double a = 1, b = std::sqrt(1 - k * k);
  for (int i = 0; i < 30; ++i) {
    const double an = (a + b) / 2;
    b = std::sqrt(a * b);
    a = an;
  }
  return 3.14159265358979323846 / (2 * a);
}

/// What `steps` steps of a swinging pendulum showed: its period, from the times its joint's
/// position passes `bottom` (twice a period, interpolated within the step), and the farthest
/// body `body`'s frame strayed from `pivot` (the joint's constraint error).
struct Swing {
  double period = 0;
  size_t crossings = 0;
  double worst_pivot = 0;
};
inline Swing swing(Simulation& sim, int joint, double bottom, int body, const Vec3& pivot, int steps,
                   double dt = 0.001) {
  std::vector<double> times;
  Swing s;
  double last = sim.world().joint(joint).position - bottom;
  for (int step = 0; step < steps; ++step) {
    sim.step();
    const double q = sim.world().joint(joint).position - bottom;
    const BodyState b = sim.world().body(body);
    s.worst_pivot =
        std::max(s.worst_pivot, std::hypot(b.pose.p[0] - pivot[0], b.pose.p[1] - pivot[1], b.pose.p[2] - pivot[2]));
    if (last * q < 0) times.push_back(sim.time() - dt * q / (q - last));
    last = q;
  }
  s.crossings = times.size();
  if (times.size() >= 2) s.period = 2 * (times.back() - times.front()) / static_cast<double>(times.size() - 1);
  return s;
}

/// The first error's "file:line: message", or "" (for exact-message checks).
inline std::string firstError(const Diagnostics& d) { return d.errors().empty() ? "" : d.errors()[0].str(); }

}  // namespace urdftest
