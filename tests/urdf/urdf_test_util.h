// Shared helpers of the URDF tests: compiling URDF text (as a bare robot or through a scene's
// RCImportURDF), stepping it, and the paths of Debian's dart-doc robots.
#pragma once

#include <catch2/catch.hpp>

#include <filesystem>
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

/// The first error's "file:line: message", or "" (for exact-message checks).
inline std::string firstError(const Diagnostics& d) { return d.errors().empty() ? "" : d.errors()[0].str(); }

}  // namespace urdftest
