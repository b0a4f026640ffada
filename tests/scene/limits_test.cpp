// Limits of the loader: absurd values, deep nesting, long import chains end with a clear error
// naming file and line, never a crash or a stack overflow.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sys/stat.h>
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

// Issue #10, items 10, 11 and 15: limits that hold, with the place where they were crossed.

namespace {

struct ScratchDir {
  std::filesystem::path path;
  explicit ScratchDir(const std::string& name) {
    path = std::filesystem::temp_directory_path() / ("simbob_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return (path / name).string();
  }
};

std::vector<Error> loadFileErrors(const std::string& path) {
  Scene scene;
  Diagnostics d;
  loadScene(path, testRegistry(), &scene, d);
  return d.errors();
}

}  // namespace

TEST_CASE("files importing the next one twice end at the import limit, not in memory", "[scene][limits]") {
  // Fifteen files under 1 KB would expand to 2^15 bodies.
  ScratchDir dir("fanout");
  for (int i = 0; i < 15; ++i) {
    std::string next = "f" + std::to_string(i + 1) + ".xml";
    dir.write("f" + std::to_string(i) + ".xml",
              i == 14 ? "<Body><RCMobileRigidBody Key=\"B\"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody></Body>\n"
                      : "<Body><RCConstruction Key=\"C\"><Body><RCMobileRigidBody Key=\"R\"/></Body><ChildList>\n"
                        "<RCBallSocketJoint Key=\"J1\"><Body><RCImportBody Key=\"I1\"><File Value=\"" +
                            next +
                            "\"/></RCImportBody></Body></RCBallSocketJoint>\n"
                            "<RCBallSocketJoint Key=\"J2\"><Body><RCImportBody Key=\"I2\"><File Value=\"" +
                            next +
                            "\"/></RCImportBody></Body></RCBallSocketJoint>\n</ChildList></RCConstruction></Body>\n");
  }
  std::string top = dir.write("top.xml",
                              "<Simulation><ComponentList>\n<RCImportBody Key=\"T\"><File Value=\"f0.xml\"/>"
                              "</RCImportBody>\n</ComponentList></Simulation>\n");
  auto e = loadFileErrors(top);
  REQUIRE(e.size() == 1);
  CHECK(e[0].kind == ErrorKind::InvalidInput);
  CHECK(e[0].str().find(".xml:2: RCImportBody 'T.C.J") != std::string::npos);
  CHECK(e[0].message.find("more than 5000 imports in all (files that import the same file several times multiply)") !=
        std::string::npos);
}

TEST_CASE("a scene that expands beyond 300000 components is rejected where it crosses", "[scene][limits]") {
  std::string xml = "<Simulation><ComponentList>\n<RCStaticRigidBody Key=\"S\"><Model><RCEmptyModel><ChildList>\n";
  for (int i = 0; i <= 300000; ++i) xml += "<RCEmptyModel Key=\"k" + std::to_string(i) + "\"/>";
  xml += "\n</ChildList></RCEmptyModel></Model></RCStaticRigidBody>\n</ComponentList></Simulation>\n";
  auto e = loadErrors(xml);
  REQUIRE(e.size() == 1);
  CHECK(e[0] == "limits.xml:3: the scene expands to more than 300000 components (imports or lists that multiply?)");
}

TEST_CASE("an INI list count beyond 1e7 names the limit", "[scene][limits]") {
  Scene scene;
  Diagnostics d;
  loadSceneFromText("ComponentCount = 1e8\n", "big.ini", Format::Ini, testRegistry(), &scene, d);
  REQUIRE(d.errors().size() == 1);
  CHECK(d.errors()[0].str() == "big.ini:1: ComponentCount 1e8 is beyond the limit of 10000000 items");
}

TEST_CASE("a scene over 64 MiB is an input-limit error (65), not a missing file", "[scene][limits]") {
  ScratchDir dir("size");
  std::string path = (dir.path / "huge.xml").string();
  std::filesystem::resize_file(dir.write("huge.xml", "<Simulation/>"), (size_t{64} << 20) + 1);
  auto e = loadFileErrors(path);
  REQUIRE(e.size() == 1);
  CHECK(e[0].kind == ErrorKind::InvalidInput);
  CHECK(e[0].str() == path + ": cannot read scene: larger than 64 MiB");
}

TEST_CASE("a FIFO as the scene is refused at once, as an import is", "[scene][limits]") {
  ScratchDir dir("fifo");
  std::string path = (dir.path / "scene.xml").string();
  REQUIRE(::mkfifo(path.c_str(), 0600) == 0);
  auto e = loadFileErrors(path);  // would block forever in open() without a writer
  REQUIRE(e.size() == 1);
  CHECK(e[0].kind == ErrorKind::MissingInput);
  CHECK(e[0].str() == path + ": cannot read scene: not a regular file");
}

TEST_CASE("constructions nested too deep give one error, not one per parameter", "[scene][limits]") {
  std::string xml = "<Simulation><ComponentList>\n";
  for (int i = 0; i < 300; ++i)
    xml += "<RCConstruction Key=\"C" + std::to_string(i) +
           "\"><Body><RCMobileRigidBody Key=\"B\"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody></Body>"
           "<ChildList><RCBallSocketJoint Key=\"J\"><Body>\n";
  xml += "<RCMobileRigidBody Key=\"L\"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody>";
  for (int i = 0; i < 300; ++i) xml += "</Body></RCBallSocketJoint></ChildList></RCConstruction>\n";
  xml += "</ComponentList></Simulation>\n";
  auto e = loadErrors(xml);
  REQUIRE(e.size() == 1);
  CHECK(e[0] == "limits.xml:101: components nested deeper than 200 levels");
}
