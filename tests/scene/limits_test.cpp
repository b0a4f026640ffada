// Limits of the loader: absurd values, deep nesting, long import chains end with a clear error
// naming file and line, never a crash or a stack overflow.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "test_registry.h"
#include "simbob/compile.h"
#include "simbob/graph.h"

using namespace simbob;

namespace {

std::vector<std::string> loadErrors(const std::string& xml, const std::string& name = "limits.xml") {
  Scene scene;
  Diagnostics d;
  Model model;
  if (loadSceneFromText(xml, name, Format::Xml, testRegistry(), &scene, d)) compileScene(scene, &model, d);
  std::vector<std::string> out;
  for (const auto& e : d.errors()) out.push_back(e.str());
  return out;
}

std::string sphereBody(const std::string& radius, const std::string& pose = "0 1 0 0 0 0") {
  return "<Simulation><ComponentList>\n"
         "<RCMobileRigidBody Key=\"B\">\n"
         "<Pose><RCGlobalCoordinates><Pose Value=\"" +
         pose +
         "\"/></RCGlobalCoordinates></Pose>\n"
         "<Geom><RCSphereGeom><Radius Value=\"" +
         radius +
         "\"/></RCSphereGeom></Geom>\n"
         "</RCMobileRigidBody></ComponentList></Simulation>\n";
}

}  // namespace

TEST_CASE("absurd magnitudes are rejected at load time with file and line", "[scene][limits]") {
  auto e = loadErrors(sphereBody("1e300"));
  REQUIRE(e.size() == 1);
  CHECK(e[0] ==
        "limits.xml:4: RCSphereGeom 'B.Geom': parameter 'Radius': 1e+300 is beyond the supported magnitude 1e+09");
  e = loadErrors(sphereBody("0.1", "1e12 0 0 0 0 0"));
  REQUIRE(e.size() == 1);
  CHECK(e[0].rfind("limits.xml:3: RCGlobalCoordinates 'B.Pose': parameter 'Pose': 1e+12 is beyond", 0) == 0);
  CHECK(loadErrors(sphereBody("1e9")).empty());  // the bound itself is accepted
}

TEST_CASE("degenerate quaternions and non-finite numbers are rejected", "[scene][limits]") {
  auto e = loadErrors(sphereBody("nan"));
  REQUIRE(e.size() == 1);
  CHECK(e[0].rfind("limits.xml:4: RCSphereGeom 'B.Geom': parameter 'Radius':", 0) == 0);
  e = loadErrors(sphereBody("inf"));
  REQUIRE(e.size() == 1);
  CHECK(e[0].rfind("limits.xml:4:", 0) == 0);
}

TEST_CASE("deep component nesting ends with an error, not a stack overflow", "[scene][limits]") {
  // Models nest through ChildList: 5000 levels of <ChildList><RCEmptyModel>.
  std::string xml = "<Simulation><ComponentList>\n<RCStaticRigidBody Key=\"S\"><Model><RCEmptyModel>";
  const int depth = 5000;
  for (int i = 0; i < depth; ++i) xml += "<ChildList><RCEmptyModel>";
  for (int i = 0; i < depth; ++i) xml += "</RCEmptyModel></ChildList>";
  xml += "</RCEmptyModel></Model></RCStaticRigidBody>\n</ComponentList></Simulation>\n";
  auto e = loadErrors(xml);
  REQUIRE_FALSE(e.empty());
  CHECK(e[0].find("nested deeper than") != std::string::npos);
  CHECK(e[0].rfind("limits.xml:2:", 0) == 0);
}

TEST_CASE("a long import chain ends with an error naming the file", "[scene][limits]") {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / ("simbob_limits_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const int files = 40;
  for (int i = 0; i < files; ++i) {
    std::ofstream f(dir / ("b" + std::to_string(i) + ".xml"));
    f << "<Body><RCConstruction Key=\"C\"><Body><RCImportBody Key=\"I\"><File Value=\"b" << (i + 1)
      << ".xml\"/></RCImportBody></Body></RCConstruction></Body>\n";
  }
  std::string top =
      "<Simulation><ComponentList>\n<RCImportBody Key=\"Top\"><File Value=\"b0.xml\"/></RCImportBody>\n"
      "</ComponentList></Simulation>\n";
  auto e = loadErrors(top, (dir / "top.xml").string());
  REQUIRE_FALSE(e.empty());
  CHECK(e[0].find("imports nested deeper than 16 files") != std::string::npos);
  CHECK(e[0].find(".xml:1:") != std::string::npos);
  fs::remove_all(dir);
}
