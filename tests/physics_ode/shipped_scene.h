// The tests of tests/physics_ode build their Worlds from the scenes the project ships.
#pragma once

#include <catch2/catch.hpp>

#include <string>

#include "simbob/compile.h"
#include "simbob/registry.h"

namespace simbob::test {

/// scenes/NAME.xml, loaded and compiled as `simbob run` does.
inline Model shippedScene(const std::string& name) {
  Registry reg;
  REQUIRE(registerBuiltins(reg));
  LoadRequest rq;
  rq.path = std::string(SIMBOB_SOURCE_DIR) + "/scenes/" + name + ".xml";
  LoadReport report;
  Model m;
  REQUIRE(loadModel(rq, reg, &m, &report));
  return m;
}

}  // namespace simbob::test
