// Tests of bad scene input: every class of error is reported with file:line and a message
// that says what is wrong; loading never crashes; independent errors are collected in one pass.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>

#include "test_registry.h"
#include "scene/scene_helpers.h"

using namespace simbob;
using namespace scenetest;

namespace {

struct Result {
  bool loaded = false;
  bool compiled = false;
  Diagnostics diag;
};

/// Load (and, when loading succeeds, compile) a scene; collect every message.
Result run(const std::string& text, Format format = Format::Xml, const std::string& name = "bad.xml") {
  Result r;
  Scene s;
  r.loaded = loadSceneFromText(text, name, format, testRegistry(), &s, r.diag);
  CHECK(r.loaded == r.diag.ok());
  if (r.loaded) {
    Model m;
    r.compiled = compileScene(s, &m, r.diag);
    CHECK(r.compiled == r.diag.ok());
  }
  return r;
}

/// Some error reads exactly `expected` ("file:line: message").
void expectExact(const Result& r, const std::string& expected) {
  INFO("errors:\n" << errorText(r.diag));
  bool found =
      std::any_of(r.diag.errors().begin(), r.diag.errors().end(), [&](const Error& e) { return e.str() == expected; });
  CHECK(found);
}

/// Some error starts with `where` ("file:line: ") and contains every phrase.
void expectError(const Result& r, const std::string& where, std::initializer_list<std::string> phrases) {
  INFO("errors:\n" << errorText(r.diag));
  INFO("expected at '" << where << "' an error containing all of the phrases");
  bool found = std::any_of(r.diag.errors().begin(), r.diag.errors().end(), [&](const Error& e) {
    std::string s = e.str();
    if (s.compare(0, where.size(), where) != 0) return false;
    for (const auto& p : phrases)
      if (s.find(p) == std::string::npos) return false;
    return true;
  });
  CHECK(found);
}

std::string inList(const std::string& components) {
  return "<Simulation>\n<ComponentList>\n" + components + "</ComponentList>\n</Simulation>\n";
}

}  // namespace

// ---------------------------------------------------------------------------------- syntax

TEST_CASE("errors: malformed XML names the line", "[scene][errors]") {
  // An element left open is named where it opens, with the end tag that came first.
  Result r = run("<Simulation>\n  <ComponentList>\n    <RCGround>\n  </ComponentList>\n</Simulation>\n");
  CHECK_FALSE(r.loaded);
  REQUIRE(r.diag.errors().size() == 1);
  expectExact(r, "bad.xml:3: malformed XML: <RCGround> is not closed (</ComponentList> on line 4 comes first)");
  Result eof = run("<Simulation>\n<!-- <Skip> -->\n<ComponentList>\n<RCGround Key=\"a>b\"/>\n");
  expectExact(eof, "bad.xml:3: malformed XML: <ComponentList> is not closed (the file ends first)");

  Result attr = run("<Simulation>\n<ComponentList>\n<RCGround Key=\"x/>\n</ComponentList></Simulation>");
  CHECK_FALSE(attr.loaded);
  REQUIRE(attr.diag.errors().size() == 1);
  expectError(attr, "bad.xml:", {"malformed XML"});
}

TEST_CASE("errors: empty and blank files", "[scene][errors]") {
  for (const char* text : {"", "   \n\n", "<?xml version=\"1.0\"?>\n", "<!-- only a comment -->"}) {
    INFO("'" << text << "'");
    Result r = run(text);
    CHECK_FALSE(r.loaded);
    REQUIRE(r.diag.errors().size() == 1);
    expectError(r, "bad.xml:", {"No document element"});
  }
  // INI: an empty file is an empty scene, which is valid.
  Result ini = run("", Format::Ini, "empty.ini");
  CHECK(ini.loaded);
}

TEST_CASE("errors: wrong root element", "[scene][errors]") {
  Result r = run("<?xml version=\"1.0\"?>\n<Scene>\n</Scene>\n");
  CHECK_FALSE(r.loaded);
  expectExact(r, "bad.xml:2: root element is <Scene>, expected <Simulation>");
  Result body = run("<Body><RCStaticRigidBody/></Body>");
  expectExact(body, "bad.xml:1: root element is <Body>, expected <Simulation>");
}

TEST_CASE("errors: unknown component types with did-you-mean", "[scene][errors]") {
  Result r =
      run(inList("<RCGrond/>\n"                                                                 // line 3
                 "<RCStaticRigidBody><Geom><RCSphereGeon/></Geom></RCStaticRigidBody>\n"        // 4
                 "<RCStaticRigidBody Key=\"B\"><Geom><Zzzzzzzz/></Geom></RCStaticRigidBody>\n"  // 5
                 "<Component><RCMobilRigidBody/></Component>\n"));                              // 6
  CHECK_FALSE(r.loaded);
  expectError(r, "bad.xml:3: ", {"unknown component type 'RCGrond' (did you mean 'RCGround'?)"});
  expectError(r, "bad.xml:4: ", {"unknown component type 'RCSphereGeon' (did you mean 'RCSphereGeom'?)"});
  expectError(r, "bad.xml:5: ", {"unknown component type 'Zzzzzzzz'"});
  expectError(r, "bad.xml:6: ", {"unknown component type 'RCMobilRigidBody' (did you mean 'RCMobileRigidBody'?)"});
  CHECK(r.diag.errors().size() == 4);

  Result ini = run("ComponentCount = 1\nComponent0.Type = RCGrund\n", Format::Ini, "bad.ini");
  expectError(ini, "bad.ini:2: ", {"unknown component type 'RCGrund' (did you mean 'RCGround'?)"});
}

TEST_CASE("errors: an unknown type far from every name suggests the nearest of its family", "[scene][errors]") {
  // "Box" is three edits from no type name; the family word "Geom" still says what was meant.
  Result r =
      run(inList("<RCStaticRigidBody Key=\"S\"><Geom><RCBoxGeom/></Geom></RCStaticRigidBody>\n"  // 3
                 "<RCCubeGeom Key=\"M\"/>\n"));                                                  // 4
  // RCMeshGeom is as near as RCCuboidGeom: both are offered.
  expectExact(r,
              "bad.xml:3: RCStaticRigidBody 'S': unknown component type 'RCBoxGeom' (did you mean 'RCCuboidGeom' or "
              "'RCMeshGeom'?)");
  expectExact(r, "bad.xml:4: unknown component type 'RCCubeGeom' (did you mean 'RCCuboidGeom'?)");
  Result ini = run("ComponentCount = 1\nComponent0.Type = RCBoxGeom\n", Format::Ini, "bad.ini");
  expectError(ini,
              "bad.ini:2: ", {"unknown component type 'RCBoxGeom' (did you mean 'RCCuboidGeom' or 'RCMeshGeom'?)"});
}

TEST_CASE("errors: an unknown controller type says a plug-in may define it", "[scene][errors]") {
  Result r =
      run(inList("<RCRobot Key=\"R\"><ControllerList>\n"
                 "<SquareDriver Key=\"Square\"><Side Value=\"2\"/></SquareDriver>\n"
                 "</ControllerList></RCRobot>\n"));
  expectExact(r,
              "bad.xml:4: RCRobot 'R': unknown component type 'SquareDriver'; if a plug-in defines it, load the "
              "plug-in with --plugin FILE");
  // Where no plug-in type can go, no word of plug-ins.
  Result geom = run(inList("<RCStaticRigidBody Key=\"S\"><Geom><SquareDriver/></Geom></RCStaticRigidBody>\n"));
  expectExact(geom, "bad.xml:3: RCStaticRigidBody 'S': unknown component type 'SquareDriver'");
}

TEST_CASE("errors: attribute names in the wrong case are named as such", "[scene][errors]") {
  Result r =
      run(inList("<RCSky Key=\"Sky\"><Height value=\"3\"/></RCSky>\n"                // 3
                 "<RCSky key=\"Low\"/>\n"                                            // 4
                 "<RCSky Key=\"Top\"><Material ref=\"Sky.Material\"/></RCSky>\n"));  // 5
  CHECK_FALSE(r.loaded);
  expectExact(r,
              "bad.xml:3: RCSky 'Sky': parameter 'Height': attribute 'value' must be written 'Value' (XML names are "
              "case-sensitive)");
  expectExact(r, "bad.xml:4: RCSky: attribute 'key' must be written 'Key' (XML names are case-sensitive)");
  expectExact(r,
              "bad.xml:5: RCSky 'Top': <Material>: attribute 'ref' must be written 'Ref' (XML names are "
              "case-sensitive)");
}

TEST_CASE("errors: a component of the wrong family for its parameter", "[scene][errors]") {
  Result r =
      run(inList("<RCStaticRigidBody Key=\"S\"><Geom><RCHingeJoint/></Geom></RCStaticRigidBody>\n"
                 "<RCHingeJoint/>\n"));
  expectExact(r,
              "bad.xml:3: RCStaticRigidBody 'S': parameter 'Geom' needs a GeomComponent, got RCHingeJoint (a "
              "JointComponent)");
  expectError(r, "bad.xml:4: ", {"parameter 'ComponentList' needs a BodyComponent", "got RCHingeJoint"});
  // Struct types are no components.
  Result s = run(inList("<SceneSettings/>\n"));
  expectError(s, "bad.xml:3: ", {"unknown component type 'SceneSettings'"});
}

TEST_CASE("errors: unknown parameter names with did-you-mean", "[scene][errors]") {
  Result r =
      run(inList("<RCConstruction Key=\"C\"><Body><RCStaticRigidBody/></Body><ChildList>\n"
                 "<RCHingeJoint Key=\"J\"><Hing/></RCHingeJoint>\n"
                 "<RCSliderJoint Key=\"S\"><Axiss><RCLocalCoordinates/></Axiss><Color Value=\"1\"/></RCSliderJoint>\n"
                 "</ChildList></RCConstruction>\n"));
  CHECK_FALSE(r.loaded);
  expectExact(r, "bad.xml:4: RCHingeJoint 'C.J': parameter 'Hing' unknown (did you mean 'Hinge'?)");
  expectExact(r, "bad.xml:5: RCSliderJoint 'C.S': parameter 'Axiss' unknown (did you mean 'Axis'?)");
  // Nothing near: the message lists what the type takes.
  expectExact(r, "bad.xml:5: RCSliderJoint 'C.S': parameter 'Color' unknown (RCSliderJoint takes Pose, Body, Axis)");
  CHECK(r.diag.errors().size() == 3);

  // Exact case in XML; INI names are case-insensitive but still checked.
  Result xcase = run(inList("<RCSky Key=\"Sky\"><height Value=\"3\"/></RCSky>\n"));
  expectExact(xcase, "bad.xml:3: RCSky 'Sky': parameter 'height' unknown (did you mean 'Height'?)");
  Result ini = run("ComponentCount = 1\nComponent0.Type = RCSky\nComponent0.Hieght = 3\n", Format::Ini, "bad.ini");
  expectExact(ini, "bad.ini:3: RCSky 'RCSky': parameter 'Hieght' unknown (did you mean 'Height'?)");
  Result settings = run("<Simulation><SceneSettings>\n<Gravty Value=\"0\"/></SceneSettings></Simulation>");
  expectError(settings, "bad.xml:2: ", {"parameter 'Gravty' unknown (did you mean 'Gravity'?)"});
  Result root = run("<Simulation>\n<ComponentLists/>\n</Simulation>");
  expectError(root, "bad.xml:2: ", {"parameter 'ComponentLists' unknown (did you mean 'ComponentList'?)"});
}

TEST_CASE("errors: malformed parameter elements", "[scene][errors]") {
  Result r =
      run(inList("<RCSky Key=\"A\"><Height/></RCSky>\n"                                                      // 3
                 "<RCSky Key=\"B\"><Height Value=\"1\" Unit=\"m\"/></RCSky>\n"                               // 4
                 "<RCSky Key=\"C\"><Height Value=\"1\"><X/></Height></RCSky>\n"                              // 5
                 "<RCSky Key=\"D\"><Material><RCGenericMaterial/><RCGenericMaterial/></Material></RCSky>\n"  // 6
                 "<RCSky Key=\"E\"><Material/></RCSky>\n"                                                    // 7
                 "<RCSky Key=\"F\"><Material Ref=\"\"/></RCSky>\n"                                           // 8
                 "<RCSky Key=\"G\"><Material Ref=\"x\" Macro=\"DefaultMaterial\"/></RCSky>\n"                // 9
                 "<RCSky Key=\"H\"><Material><RCGenericMaterial Key=\"a.b\"/></Material></RCSky>\n"          // 10
                 "<RCSky Key=\"I\"><Material><RCGenericMaterial Name=\"x\"/></Material></RCSky>\n"));        // 11
  CHECK_FALSE(r.loaded);
  expectError(r, "bad.xml:3: ", {"'Height' needs a Value attribute"});
  expectError(r, "bad.xml:4: ", {"'Height'", "unknown attribute 'Unit'"});
  expectError(r, "bad.xml:5: ", {"'Height' is a value and takes no child elements"});
  expectError(r, "bad.xml:6: ", {"<Material> must hold exactly one component element, a Ref or a Macro"});
  expectError(r, "bad.xml:7: ", {"<Material> must hold exactly one component element, a Ref or a Macro"});
  expectError(r, "bad.xml:8: ", {"empty Ref"});
  expectError(r, "bad.xml:9: ", {"has both Ref and Macro"});
  expectError(r, "bad.xml:10: ", {"Key 'a.b' must be non-empty and contain no '.'"});
  expectError(r, "bad.xml:11: ", {"unknown attribute 'Name'"});
  CHECK(r.diag.errors().size() == 9);
}

TEST_CASE("errors: unknown Macro and Macro of the wrong family", "[scene][errors]") {
  Result r = run(
      inList("<RCStaticRigidBody Key=\"S\"><Geom Macro=\"NoGeon\"/><Model Macro=\"NoGeom\"/></RCStaticRigidBody>\n"));
  expectExact(r, "bad.xml:3: RCStaticRigidBody 'S': unknown Macro 'NoGeon' (did you mean 'NoGeom'?)");
  expectExact(r,
              "bad.xml:3: RCStaticRigidBody 'S': Macro 'NoGeom' makes a GeomComponent, parameter 'Model' needs a "
              "ModelComponent");
}

// ---------------------------------------------------------------------------------- values

TEST_CASE("errors: wrong value syntax", "[scene][errors]") {
  Result r =
      run(inList("<RCStaticRigidBody Key=\"S\">\n"                                      // 3
                 "<Geom><RCSphereGeom><Radius Value=\"abc\"/></RCSphereGeom></Geom>\n"  // 4
                 "</RCStaticRigidBody>\n"
                 "<RCCuboidModel Key=\"M\"><Wire Value=\"maybe\"/></RCCuboidModel>\n"             // 6
                 "<RCEllipsoidModel Key=\"E\"><Accuracy Value=\"2.5\"/></RCEllipsoidModel>\n"     // 7
                 "<RCCuboidModel Key=\"N\"><SideMask Value=\"Top|Sideways\"/></RCCuboidModel>\n"  // 8
                 "<RCColoredSkin Key=\"K\"><ColorMode Value=\"Glow\"/></RCColoredSkin>\n"         // 9
                 "<RCGround Key=\"G\"><Extension Value=\"1,5\"/></RCGround>\n"));                 // 10
  CHECK_FALSE(r.loaded);
  expectExact(r, "bad.xml:4: RCSphereGeom 'S.Geom': parameter 'Radius': expected a number, got 'abc'");
  expectError(r, "bad.xml:6: ", {"RCCuboidModel 'M': parameter 'Wire': expected a boolean", "'maybe'"});
  expectError(r, "bad.xml:7: ", {"RCEllipsoidModel 'E': parameter 'Accuracy': expected an integer, got '2.5'"});
  expectError(r, "bad.xml:8: ", {"RCCuboidModel 'N': parameter 'SideMask'", "Sideways"});
  expectError(r, "bad.xml:9: ", {"RCColoredSkin 'K': parameter 'ColorMode'", "Glow"});
  expectError(r, "bad.xml:10: ", {"RCGround 'G': parameter 'Extension': expected a number, got '1,5'"});
  CHECK(r.diag.errors().size() == 6);
}

TEST_CASE("errors: a number with blanks around it (guide 4.3)", "[scene][errors][audit]") {
  // Before: " 7" and "3 " were trimmed and accepted.
  Result r =
      run(inList("<RCSky Key=\"S\"><Height Value=\" 7\"/></RCSky>\n"                                    // 3
                 "<RCEllipsoidModel Key=\"E\"><Accuracy Value=\"3 \"/></RCEllipsoidModel>\n"            // 4
                 "<RCCuboidModel Key=\"C\"><Cuboid Value=\" -1 -1 -1  1 1 1 \"/></RCCuboidModel>\n"));  // a list: fine
  CHECK_FALSE(r.loaded);
  INFO(errorText(r.diag));
  CHECK(r.diag.errors().size() == 2);
  expectExact(r,
              "bad.xml:3: RCSky 'S': parameter 'Height': expected a number without blanks around it, got ' 7' (guide "
              "4.3: a number starts with a sign, a digit or '.')");
  expectExact(r,
              "bad.xml:4: RCEllipsoidModel 'E': parameter 'Accuracy': expected an integer without blanks around it, "
              "got '3 ' (guide 4.3: a number starts with a sign, a digit or '.')");
  // INI values are trimmed around '='; a quoted value keeps its blanks (guide 4.1).
  CHECK(run("ComponentCount = 1\nComponent0.Type = RCSky\nComponent0.Height =   7  \n", Format::Ini, "b.ini").loaded);
  Result ini = run("ComponentCount = 1\nComponent0.Type = RCSky\nComponent0.Height = \" 7\"\n", Format::Ini, "b.ini");
  expectError(ini, "b.ini:3: ", {"parameter 'Height': expected a number without blanks around it, got ' 7'"});
}

TEST_CASE("errors: wrong arity", "[scene][errors]") {
  Result r =
      run(inList("<RCStaticRigidBody Key=\"S\">\n"                                                    // 3
                 "<Pose><RCGlobalCoordinates><Pose Value=\"1 2 3\"/></RCGlobalCoordinates></Pose>\n"  // 4
                 "</RCStaticRigidBody>\n"
                 "<RCMobileRigidBody Key=\"M\"><Motion><RCGlobalMotion>\n"                                   // 6
                 "<AngVelocity Value=\"1 2 3 4\"/></RCGlobalMotion></Motion>\n"                              // 7
                 "<Inertia><RCGenericInertia><Inertia Value=\"1 2 3 4 5\"/></RCGenericInertia></Inertia>\n"  // 8
                 "</RCMobileRigidBody>\n"
                 "<RCCuboidModel Key=\"C\"><Cuboid Value=\"0 0 0 1 1\"/></RCCuboidModel>\n"));  // 10
  CHECK_FALSE(r.loaded);
  expectExact(r, "bad.xml:4: RCGlobalCoordinates 'S.Pose': parameter 'Pose': expected 6 numbers for a Pose, got 3");
  expectExact(r,
              "bad.xml:7: RCGlobalMotion 'M.Motion': parameter 'AngVelocity': expected 1 to 3 numbers for a "
              "Triple, got 4");
  expectExact(
      r, "bad.xml:8: RCGenericInertia 'M.Inertia': parameter 'Inertia': matrix needs 3, 9, 12 or 16 numbers, got 5");
  expectExact(r, "bad.xml:10: RCCuboidModel 'C': parameter 'Cuboid': expected 6 numbers for a Cuboid, got 5");
  CHECK(r.diag.errors().size() == 4);
}

TEST_CASE("errors: NaN and infinities", "[scene][errors]") {
  Result r =
      run(inList("<RCMobileRigidBody Key=\"M\"><Motion><RCGlobalMotion>\n"  // 3
                 "<LinVelocity Value=\"1 nan 0\"/>\n"                       // 4
                 "</RCGlobalMotion></Motion>\n"
                 "<Geom><RCSphereGeom><Radius Value=\"NaN\"/></RCSphereGeom></Geom>\n"  // 6
                 "</RCMobileRigidBody>\n"
                 "<RCSky Key=\"S\"><Height Value=\"Infinite\"/></RCSky>\n"         // 8
                 "<RCSky Key=\"T\"><Height Value=\"-1e400\"/></RCSky>\n"           // 9
                 "<RCGround Key=\"G\"><Extension Value=\"inf\"/></RCGround>\n"));  // 10
  CHECK_FALSE(r.loaded);
  expectExact(r, "bad.xml:4: RCGlobalMotion 'M.Motion': parameter 'LinVelocity': NaN is not allowed: 'nan'");
  expectExact(r, "bad.xml:6: RCSphereGeom 'M.Geom': parameter 'Radius': NaN is not allowed: 'NaN'");
  expectExact(r, "bad.xml:8: RCSky 'S': parameter 'Height': infinite value not allowed here: 'Infinite'");
  expectExact(r, "bad.xml:9: RCSky 'T': parameter 'Height': number out of range: '-1e400'");
  expectExact(r, "bad.xml:10: RCGround 'G': parameter 'Extension': expected a number, got 'inf'");
  CHECK(r.diag.errors().size() == 5);
  // Drive limits are the documented exception.
  Result ok =
      run(inList("<RCConstruction Key=\"C\"><ChildList><RCGenericServo Key=\"D\">"
                 "<MinPos Value=\"-Infinite\"/><MaxPos Value=\"Infinite\"/></RCGenericServo></ChildList>"
                 "</RCConstruction>\n"));
  CHECK(ok.loaded);
}

TEST_CASE("errors: values out of their range", "[scene][errors]") {
  Result r =
      run(inList("<RCMobileRigidBody Key=\"A\">\n"                                                 // 3
                 "<Geom><RCSphereGeom><Radius Value=\"0\"/></RCSphereGeom></Geom>\n"               // 4
                 "<Inertia><RCGenericInertia><Mass Value=\"-1\"/></RCGenericInertia></Inertia>\n"  // 5
                 "<Material><RCGenericMaterial><Bounceness Value=\"1.5\"/>\n"                      // 6
                 "<Friction Value=\"-0.1\"/></RCGenericMaterial></Material>\n"                     // 7
                 "</RCMobileRigidBody>\n"
                 "<RCStaticRigidBody Key=\"B\"><Geom><RCCuboidGeom><Width Value=\"-2\"/>"  // 9
                 "</RCCuboidGeom></Geom></RCStaticRigidBody>\n"
                 "<RCRodBody Key=\"R\"><Mass Value=\"0\"/><Radius Value=\"-0\"/></RCRodBody>\n"  // 10
                 "<RCEllipsoidModel Key=\"E\"><Accuracy Value=\"0\"/></RCEllipsoidModel>\n"));   // 11
  CHECK_FALSE(r.loaded);
  expectExact(r, "bad.xml:4: RCSphereGeom 'A.Geom': parameter 'Radius' must be > 0, got '0'");
  expectExact(r, "bad.xml:5: RCGenericInertia 'A.Inertia': parameter 'Mass' must be > 0, got '-1'");
  expectExact(r, "bad.xml:6: RCGenericMaterial 'A.Material': parameter 'Bounceness' must be in [0, 1], got '1.5'");
  expectExact(r, "bad.xml:7: RCGenericMaterial 'A.Material': parameter 'Friction' must be >= 0, got '-0.1'");
  expectExact(r, "bad.xml:9: RCCuboidGeom 'B.Geom': parameter 'Width' must be > 0, got '-2'");
  expectExact(r, "bad.xml:10: RCRodBody 'R': parameter 'Mass' must be > 0, got '0'");
  expectExact(r, "bad.xml:10: RCRodBody 'R': parameter 'Radius' must be > 0, got '-0'");
  expectExact(r, "bad.xml:11: RCEllipsoidModel 'E': parameter 'Accuracy' must be > 0, got '0'");
  CHECK(r.diag.errors().size() == 8);
}

TEST_CASE("errors: RCInertiaByGeom with Mass 0", "[scene][errors]") {
  Result r =
      run(inList("<RCMobileRigidBody Key=\"A\">\n"
                 "<Geom><RCSphereGeom/></Geom>\n"
                 "<Inertia><RCInertiaByGeom><Mass Value=\"0\"/></RCInertiaByGeom></Inertia>\n"
                 "</RCMobileRigidBody>\n"));
  CHECK(r.loaded);
  CHECK_FALSE(r.compiled);
  expectError(r, "bad.xml:5: ", {"RCInertiaByGeom 'A.Inertia'", "'Mass' must be > 0"});
}

TEST_CASE("errors: inertia tensors that are not positive definite or not symmetric", "[scene][errors]") {
  Result r =
      run(inList("<RCMobileRigidBody Key=\"A\"><Inertia><RCGenericInertia>\n"  // 3
                 "<Inertia Value=\"1 1 -1\"/>\n"                               // 4
                 "</RCGenericInertia></Inertia></RCMobileRigidBody>\n"
                 "<RCMobileRigidBody Key=\"B\"><Inertia><RCGenericInertia>\n"  // 6
                 "<Inertia Value=\"1 0.5 0 0 1 0 0 0 1\"/>\n"                  // 7
                 "</RCGenericInertia></Inertia></RCMobileRigidBody>\n"
                 "<RCMobileRigidBody Key=\"C\"><Inertia><RCGenericInertia>\n"  // 9
                 "<Inertia Value=\"1 2 0 2 1 0 0 0 1\"/>\n"                    // 10: symmetric, indefinite
                 "</RCGenericInertia></Inertia></RCMobileRigidBody>\n"
                 "<RCMobileRigidBody Key=\"D\"><Inertia><RCGenericInertia>\n"  // 12
                 "<Inertia Value=\"0 0 0\"/>\n"                                // 13
                 "</RCGenericInertia></Inertia></RCMobileRigidBody>\n"));
  CHECK(r.loaded);
  CHECK_FALSE(r.compiled);
  expectExact(r, "bad.xml:4: RCGenericInertia 'A.Inertia': parameter 'Inertia' is not positive definite");
  expectExact(r, "bad.xml:7: RCGenericInertia 'B.Inertia': parameter 'Inertia' must be symmetric");
  expectExact(r, "bad.xml:10: RCGenericInertia 'C.Inertia': parameter 'Inertia' is not positive definite");
  expectExact(r, "bad.xml:13: RCGenericInertia 'D.Inertia': parameter 'Inertia' is not positive definite");
  CHECK(r.diag.errors().size() == 4);
}

// ---------------------------------------------------------------------------------- references

TEST_CASE("errors: dangling Ref with did-you-mean", "[scene][errors]") {
  Result r =
      run(inList("<RCGenericMaterial Key=\"Rubber\"/>\n"
                 "<RCStaticRigidBody Key=\"S\"><Material Ref=\"Rubbr\"/></RCStaticRigidBody>\n"                // 4
                 "<RCStaticRigidBody Key=\"T\"><Material Ref=\"Nothing.Here\"/></RCStaticRigidBody>\n"         // 5
                 "<RCCuboidModel Key=\"M\"><ChildList><Child Ref=\"Gone\"/></ChildList></RCCuboidModel>\n"));  // 6
  CHECK_FALSE(r.loaded);
  expectExact(r, "bad.xml:4: RCStaticRigidBody 'S': Ref 'Rubbr' names no component (did you mean 'Rubber'?)");
  expectExact(r, "bad.xml:5: RCStaticRigidBody 'T': Ref 'Nothing.Here' names no component");
  expectExact(r, "bad.xml:6: RCCuboidModel 'M': Ref 'Gone' names no component");
  CHECK(r.diag.errors().size() == 3);
}

// by_qkey is a hash table: of keys equally near a misspelt Ref, the message names the first in
// key order, whatever order the table holds them in. "Mat2" and "Mat8" are both one edit from
// "Mat5"; with 200 more keys the table's order is not the keys' order.
TEST_CASE("errors: dangling Ref names the first of equally near keys in key order", "[scene][errors]") {
  std::string list;
  for (int i = 0; i < 200; ++i) list += "<RCGenericMaterial Key=\"Other" + std::to_string(i) + "\"/>";
  Result r = run(inList(list + "<RCGenericMaterial Key=\"Mat8\"/><RCGenericMaterial Key=\"Mat2\"/>\n" +
                        "<RCStaticRigidBody Key=\"S\"><Material Ref=\"Mat5\"/></RCStaticRigidBody>\n"));  // 4
  CHECK_FALSE(r.loaded);
  expectExact(r, "bad.xml:4: RCStaticRigidBody 'S': Ref 'Mat5' names no component (did you mean 'Mat2'?)");
}

TEST_CASE("errors: Ref to the wrong kind of component", "[scene][errors]") {
  Result r =
      run(inList("<RCMobileRigidBody Key=\"Ball\"><Geom><RCSphereGeom/></Geom>"
                 "<Material><RCGenericMaterial/></Material></RCMobileRigidBody>\n"
                 "<RCStaticRigidBody Key=\"S\"><Material Ref=\"Ball\"/></RCStaticRigidBody>\n"       // 4
                 "<RCStaticRigidBody Key=\"T\"><Geom Ref=\"Ball.Material\"/></RCStaticRigidBody>\n"  // 5
                 "<Component Ref=\"Ball.Geom\"/>\n"));                                               // 6
  CHECK_FALSE(r.loaded);
  expectExact(r,
              "bad.xml:4: RCStaticRigidBody 'S': Ref 'Ball' names a RCMobileRigidBody, parameter 'Material' "
              "needs a MaterialComponent");
  expectExact(r,
              "bad.xml:5: RCStaticRigidBody 'T': Ref 'Ball.Material' names a RCGenericMaterial, parameter "
              "'Geom' needs a GeomComponent");
  expectError(r, "bad.xml:6: ",
              {"Ref 'Ball.Geom' names a RCSphereGeom, parameter 'ComponentList' needs a "
               "BodyComponent, GlobalSimComponent, MaterialComponent, SkinComponent or "
               "ModelComponent"});
  CHECK(r.diag.errors().size() == 3);
}

TEST_CASE("errors: cyclic Refs", "[scene][errors]") {
  SECTION("a model whose ChildList refers to itself") {
    Result r = run(inList("<RCCuboidModel Key=\"M\"><ChildList>\n<Child Ref=\"M\"/>\n</ChildList></RCCuboidModel>\n"));
    CHECK_FALSE(r.loaded);
    REQUIRE(r.diag.errors().size() == 1);
    expectError(r, "bad.xml:4: ", {"RCCuboidModel 'M': cyclic Ref 'M'"});
  }
  SECTION("a model whose child refers to an ancestor") {
    Result r =
        run(inList("<RCCuboidModel Key=\"P\"><ChildList>\n"
                   "<RCConeModel Key=\"Q\"><ChildList><RCConeModel Key=\"R\"><ChildList>\n"
                   "<Child Ref=\"P\"/>\n"  // line 5
                   "</ChildList></RCConeModel></ChildList></RCConeModel></ChildList></RCCuboidModel>\n"));
    CHECK_FALSE(r.loaded);
    REQUIRE(r.diag.errors().size() == 1);
    expectError(r, "bad.xml:5: ", {"RCConeModel 'P.Q.R': cyclic Ref 'P'"});
  }
  SECTION("two top-level models referring to each other") {
    Result r =
        run(inList("<RCCuboidModel Key=\"A\"><ChildList><Child Ref=\"B\"/></ChildList></RCCuboidModel>\n"
                   "<RCCuboidModel Key=\"B\"><ChildList><Child Ref=\"A\"/></ChildList></RCCuboidModel>\n"));
    CHECK_FALSE(r.loaded);
    REQUIRE(r.diag.errors().size() == 1);
    expectError(r, "bad.xml:", {"cyclic Ref"});
  }
  SECTION("a transform geom whose SubGeom is itself") {
    Result r =
        run(inList("<RCStaticRigidBody Key=\"S\"><Geom><RCTransformGeom Key=\"T\">\n"
                   "<SubGeom Ref=\"S.T\"/></RCTransformGeom></Geom></RCStaticRigidBody>\n"));
    CHECK_FALSE(r.loaded);
    expectError(r, "bad.xml:4: ", {"RCTransformGeom 'S.T': cyclic Ref 'S.T'"});
  }
  SECTION("shared models are no cycle") {
    Result r =
        run(inList("<RCCuboidModel Key=\"Leaf\"/>\n"
                   "<RCCuboidModel Key=\"A\"><ChildList><Child Ref=\"Leaf\"/><Child Ref=\"Leaf\"/></ChildList>"
                   "</RCCuboidModel>\n"
                   "<RCStaticRigidBody Key=\"S\"><Model Ref=\"A\"/></RCStaticRigidBody>\n"
                   "<RCStaticRigidBody Key=\"T\"><Model Ref=\"A\"/></RCStaticRigidBody>\n"));
    CHECK(r.loaded);
    CHECK(r.compiled);
  }
  SECTION("a construction whose Body is itself") {
    Result r = run(inList("<RCConstruction Key=\"Self\"><Body Ref=\"Self\"/></RCConstruction>\n"));
    CHECK_FALSE(r.compiled);
    expectError(r, "bad.xml:3: ", {"RCConstruction 'Self'", "part of its own construction"});
  }
  SECTION("a joint whose Body is the construction's root") {
    Result r =
        run(inList("<RCConstruction Key=\"C\"><Body><RCMobileRigidBody Key=\"R\"><Geom><RCSphereGeom/></Geom>"
                   "</RCMobileRigidBody></Body>\n<ChildList><RCFixJoint Key=\"J\"><Body Ref=\"C.R\"/>"
                   "</RCFixJoint></ChildList></RCConstruction>\n"));
    CHECK(r.loaded);
    CHECK_FALSE(r.compiled);
    expectError(r, "bad.xml:4: ", {"RCFixJoint 'C.J'", "connects a body with itself"});
  }
}

TEST_CASE("errors: duplicate keys", "[scene][errors]") {
  Result r =
      run(inList("<RCStaticRigidBody Key=\"A\"/>\n"
                 "<RCGenericMaterial Key=\"A\"/>\n"));  // line 4
  CHECK_FALSE(r.loaded);
  expectExact(r, "bad.xml:4: RCGenericMaterial: duplicate key 'A' (first used at bad.xml:3); give it a different Key");
  // A Key that collides with the key a keyless component takes from its parameter name.
  Result d =
      run(inList("<RCStaticRigidBody Key=\"S\"><Pose><RCGlobalCoordinates/></Pose>"
                 "<Geom><RCSphereGeom Key=\"Pose\"/></Geom></RCStaticRigidBody>\n"));
  expectError(d, "bad.xml:3: ", {"duplicate key 'S.Pose'"});
  // List items without Key are keyed by their type name.
  Result t = run(inList("<RCGround/>\n<RCGround/>\n"));
  expectError(t, "bad.xml:4: ", {"duplicate key 'RCGround'"});
  // The same key below different parents is fine.
  Result ok =
      run(inList("<RCStaticRigidBody Key=\"A\"><Geom><RCSphereGeom Key=\"G\"/></Geom></RCStaticRigidBody>\n"
                 "<RCStaticRigidBody Key=\"B\"><Geom><RCSphereGeom Key=\"G\"/></Geom></RCStaticRigidBody>\n"));
  CHECK(ok.loaded);
}

TEST_CASE("errors: a duplicate key is reported once, not once per default child", "[scene][errors]") {
  Result r = run(inList("<RCStaticRigidBody Key=\"A\"/>\n<RCStaticRigidBody Key=\"A\"/>\n"));
  CHECK_FALSE(r.loaded);
  INFO(errorText(r.diag));
  CHECK(r.diag.errors().size() == 1);
  expectExact(r, "bad.xml:4: RCStaticRigidBody: duplicate key 'A' (first used at bad.xml:3); give it a different Key");
}

TEST_CASE("errors: a parameter given twice", "[scene][errors]") {
  Result r =
      run(inList("<RCStaticRigidBody Key=\"S\"><Geom><RCSphereGeom>\n"
                 "<Radius Value=\"1\"/>\n"
                 "<Radius Value=\"2\"/>\n"  // line 5
                 "</RCSphereGeom></Geom>\n"
                 "<Geom Macro=\"NoGeom\"/>\n"  // line 7
                 "</RCStaticRigidBody>\n"));
  CHECK_FALSE(r.loaded);
  expectExact(r, "bad.xml:5: RCSphereGeom 'S.Geom': parameter 'Radius' given twice");
  expectExact(r, "bad.xml:7: RCStaticRigidBody 'S': parameter 'Geom' given twice");
  CHECK(r.diag.errors().size() == 2);
  // INI: the same key twice (in any case) is caught by the INI reader.
  Result ini = run("ComponentCount = 1\nComponent0.Type = RCSky\nComponent0.Height = 1\ncomponent0.HEIGHT = 2\n",
                   Format::Ini, "bad.ini");
  expectError(ini, "bad.ini:4: ", {"assigned twice", "first on line 3"});
}

TEST_CASE("errors: a Ref with child elements", "[scene][errors]") {
  Result r =
      run(inList("<RCStaticRigidBody Key=\"S\">\n"
                 "<Material Ref=\"M\"><RCGenericMaterial/></Material>\n"  // line 4
                 "</RCStaticRigidBody>\n"
                 "<RCGenericMaterial Key=\"M\"/>\n"
                 "<RCCuboidModel Key=\"C\"><ChildList><Child Ref=\"C2\"><RCConeModel/></Child></ChildList>"
                 "</RCCuboidModel>\n"  // line 7
                 "<RCCuboidModel Key=\"C2\"/>\n"));
  CHECK_FALSE(r.loaded);
  expectExact(r, "bad.xml:4: RCStaticRigidBody 'S': <Material> with Ref or Macro takes no child elements");
  expectExact(r, "bad.xml:7: RCCuboidModel 'C': <Child> with Ref or Macro takes no child elements");
  CHECK(r.diag.errors().size() == 2);
  Result ini =
      run("ComponentCount = 1\nComponent0.Type = RCSky\nComponent0.Material.Ref = X\n"
          "Component0.Material.Friction = 1\n",
          Format::Ini, "bad.ini");
  expectError(ini, "bad.ini:", {"'Material' with Ref or Macro takes no other entries"});
}

// ---------------------------------------------------------------------------------- imports

TEST_CASE("errors: cyclic import", "[scene][errors][import]") {
  TempDir dir;
  dir.write("a.xml", "<Body>\n<RCImportBody Key=\"X\"><File Value=\"sub/b.xml\"/></RCImportBody>\n</Body>\n");
  std::string b =
      dir.write("sub/b.xml", "<Body>\n\n<RCImportBody Key=\"Y\"><File Value=\"../a.xml\"/></RCImportBody>\n</Body>\n");
  std::string main = dir.write("main.xml", inList("<RCImportBody Key=\"I\"><File Value=\"a.xml\"/></RCImportBody>\n"));
  Scene s;
  Diagnostics d;
  CHECK_FALSE(loadScene(main, testRegistry(), &s, d));
  INFO(errorText(d));
  REQUIRE(d.errors().size() == 1);
  const Error& e = d.errors()[0];
  CHECK(e.kind == ErrorKind::InvalidInput);
  CHECK(e.loc.file == std::filesystem::path(b).lexically_normal().string());
  CHECK(e.loc.line == 3);
  CHECK(e.message.find("RCImportBody 'I.X.Y': cyclic import: ") == 0);
  CHECK(e.message.find("main.xml -> ") != std::string::npos);
  CHECK(e.message.find("a.xml -> ") != std::string::npos);

  // A scene importing itself (through a Body import of a Simulation file) is a cycle too.
  std::string self =
      dir.write("self.xml", inList("<RCImportBody Key=\"I\"><File Value=\"self.xml\"/></RCImportBody>\n"));
  Diagnostics d2;
  CHECK_FALSE(loadScene(self, testRegistry(), &s, d2));
  REQUIRE(d2.errors().size() == 1);
  CHECK(d2.errors()[0].str().find(self + ":3: RCImportBody 'I': cyclic import") == 0);
}

TEST_CASE("errors: missing import and import without File", "[scene][errors][import]") {
  TempDir dir;
  std::string main =
      dir.write("main.xml", inList("<RCImportBody Key=\"M\"><File Value=\"missing.xml\"/></RCImportBody>\n"
                                   "<RCImportBody Key=\"E\"/>\n"
                                   "<RCImportRefList Key=\"D\"><File Value=\".\"/></RCImportRefList>\n"));
  Scene s;
  Diagnostics d;
  CHECK_FALSE(loadScene(main, testRegistry(), &s, d));
  INFO(errorText(d));
  REQUIRE(d.errors().size() == 3);
  const Error& missing = d.errors()[0];
  CHECK(missing.kind == ErrorKind::MissingInput);
  CHECK(missing.str() == main + ":3: RCImportBody 'M': cannot read import '" + (dir.path() / "missing.xml").string() +
                             "': No such file or directory");
  CHECK(d.errors()[1].str() == main + ":4: RCImportBody 'E': parameter 'File' is required");
  CHECK(d.errors()[1].kind == ErrorKind::InvalidInput);
  CHECK(d.errors()[2].kind == ErrorKind::MissingInput);
  CHECK(d.errors()[2].str().find("Is a directory") != std::string::npos);

  // The scene itself missing.
  Diagnostics d2;
  CHECK_FALSE(loadScene((dir.path() / "nope.xml").string(), testRegistry(), &s, d2));
  REQUIRE(d2.errors().size() == 1);
  CHECK(d2.errors()[0].kind == ErrorKind::MissingInput);
  CHECK(d2.errors()[0].str().find("nope.xml: cannot read scene") != std::string::npos);
}

TEST_CASE("errors: an element left open in a scene file is named where it opens, at any size", "[scene][errors]") {
  // The file is parsed in place and read again for this message: also past the 4 MiB up to
  // which a copy used to be kept for it.
  TempDir dir;
  std::string big = "<Simulation>\n<ComponentList>\n";
  while (big.size() < (size_t{5} << 20)) big += "<RCGround Key=\"G" + std::to_string(big.size()) + "\"/>\n";
  const int lines = static_cast<int>(std::count(big.begin(), big.end(), '\n'));
  big += "<RCGround>\n</ComponentList>\n</Simulation>\n";
  dir.write("open.xml", big);
  const std::string path = (dir.path() / "open.xml").string();
  Scene s;
  Diagnostics d;
  CHECK_FALSE(loadScene(path, testRegistry(), &s, d));
  REQUIRE(d.errors().size() == 1);
  CHECK(d.errors()[0].str() == path + ":" + std::to_string(lines + 1) +
                                   ": malformed XML: <RCGround> is not closed (</ComponentList> on line " +
                                   std::to_string(lines + 2) + " comes first)");
}

TEST_CASE("errors: imported files with the wrong root or bad content", "[scene][errors][import]") {
  TempDir dir;
  dir.write("joint.xml", "<Joint><RCFixJoint/></Joint>");
  dir.write("bad.xml",
            "<Body>\n<RCStaticRigidBody Key=\"B\">\n<Geom><RCSphereGeom><Radius Value=\"x\"/></RCSphereGeom>"
            "</Geom></RCStaticRigidBody></Body>");
  dir.write("broken.xml", "<Body>\n<RCStaticRigidBody>\n</Body>");
  dir.write("ref.xml", "<Body Ref=\"Other\"/>");
  dir.write("list.xml", "<RefList>\n<Item Ref=\"X\"/>\n<RCGenericMaterial Key=\"M\"/>\n<RCHingeJoint/>\n</RefList>");
  std::string main =
      dir.write("main.xml", inList("<RCImportBody Key=\"W\"><File Value=\"joint.xml\"/></RCImportBody>\n"
                                   "<RCImportBody Key=\"B\"><File Value=\"bad.xml\"/></RCImportBody>\n"
                                   "<RCImportBody Key=\"C\"><File Value=\"broken.xml\"/></RCImportBody>\n"
                                   "<RCImportBody Key=\"R\"><File Value=\"ref.xml\"/></RCImportBody>\n"
                                   "<RCImportRefList Key=\"L\"><File Value=\"list.xml\"/></RCImportRefList>\n"));
  Scene s;
  Diagnostics d;
  CHECK_FALSE(loadScene(main, testRegistry(), &s, d));
  INFO(errorText(d));
  std::string p = dir.path().string() + "/";
  Result r;
  r.diag = d;
  expectExact(r, p + "joint.xml:1: root element is <Joint>, expected <Body> (imported by " + main + ":3)");
  expectExact(r, p + "bad.xml:3: RCSphereGeom 'B.B.Geom': parameter 'Radius': expected a number, got 'x'");
  expectExact(r, p + "broken.xml:2: malformed XML: <RCStaticRigidBody> is not closed (</Body> on line 3 comes first)");
  expectError(r, p + "ref.xml:1: ", {"must hold a component, not a Ref"});
  expectError(r, p + "list.xml:2: ", {"<RefList> items must be components, not Refs"});
  expectError(r, p + "list.xml:4: ", {"RCHingeJoint", "JointComponent"});
}

// ---------------------------------------------------------------------------------- compile

TEST_CASE("errors: RCLocalCoordinates at the top level", "[scene][errors]") {
  Result r =
      run(inList("<RCMobileRigidBody Key=\"B\">\n<Pose><RCLocalCoordinates/></Pose>\n"
                 "<Geom><RCSphereGeom/></Geom></RCMobileRigidBody>\n"
                 "<RCStaticRigidBody Key=\"S\">\n<Pose Macro=\"Origin\"/></RCStaticRigidBody>\n"));
  CHECK(r.loaded);
  CHECK_FALSE(r.compiled);
  expectExact(r,
              "bad.xml:4: RCMobileRigidBody 'B': RCLocalCoordinates needs a parent frame, which only a joint gives (to "
              "its own poses and the body it carries); at the top level and for a construction's root body use "
              "RCGlobalCoordinates");
  expectError(r, "bad.xml:7: ", {"RCStaticRigidBody 'S': RCLocalCoordinates needs a parent frame"});
  // A construction's root body is at the top level too. The message used to name "construction"
  // among the frames that RCLocalCoordinates can refer to, which was not true for its root.
  Result root =
      run(inList("<RCConstruction Key=\"K\"><Body><RCMobileRigidBody Key=\"R\">\n"
                 "<Pose><RCLocalCoordinates/></Pose><Geom><RCSphereGeom/></Geom></RCMobileRigidBody></Body>"
                 "</RCConstruction>\n"));
  CHECK_FALSE(root.compiled);
  REQUIRE(root.diag.errors().size() == 1);
  expectExact(root,
              "bad.xml:4: RCMobileRigidBody 'K.R': RCLocalCoordinates needs a parent frame, which only a joint gives "
              "(to its own poses and the body it carries); at the top level and for a construction's root body use "
              "RCGlobalCoordinates");
}

TEST_CASE("errors: a plane geom on a mobile body", "[scene][errors]") {
  Result r =
      run(inList("<RCMobileRigidBody Key=\"C\">\n<Geom><RCPlaneGeom/></Geom>\n"
                 "<Inertia><RCGenericInertia/></Inertia></RCMobileRigidBody>\n"
                 "<RCMobileRigidBody Key=\"D\"><Geom><RCTransformGeom><SubGeom><RCPlaneGeom/></SubGeom>"
                 "</RCTransformGeom></Geom><Inertia><RCGenericInertia/></Inertia></RCMobileRigidBody>\n"));
  CHECK_FALSE(r.compiled);
  expectExact(r, "bad.xml:4: RCPlaneGeom 'C.Geom': a plane is infinite and can only belong to a static body");
  expectError(r, "bad.xml:6: ", {"RCPlaneGeom 'D.Geom.SubGeom'", "only belong to a static body"});
  CHECK(r.diag.errors().size() == 2);
}

TEST_CASE("errors: a joint without Body", "[scene][errors]") {
  Result r =
      run(inList("<RCConstruction Key=\"K\"><Body><RCStaticRigidBody/></Body><ChildList>\n"
                 "<RCHingeJoint Key=\"J\"/>\n"
                 "</ChildList></RCConstruction>\n"));
  CHECK(r.loaded);
  CHECK_FALSE(r.compiled);
  expectExact(r, "bad.xml:4: RCHingeJoint 'K.J': parameter 'Body' (the body the joint connects to) is required");
  Result nb = run(inList("<RCConstruction Key=\"K\"/>\n"));
  expectExact(nb, "bad.xml:3: RCConstruction 'K': parameter 'Body' (the root body) is required");
  Result statics =
      run(inList("<RCConstruction Key=\"K\"><Body><RCStaticRigidBody/></Body><ChildList>\n"
                 "<RCFixJoint Key=\"J\"><Body><RCStaticRigidBody Key=\"S\"/></Body></RCFixJoint>\n"
                 "</ChildList></RCConstruction>\n"));
  expectExact(statics, "bad.xml:4: RCFixJoint 'K.J': connects two static bodies; one of them must be mobile");
}

TEST_CASE("errors: a mobile body without volume and the default RCInertiaByGeom", "[scene][errors]") {
  Result r =
      run(inList("<RCMobileRigidBody Key=\"N\">\n<Geom Macro=\"NoGeom\"/>\n</RCMobileRigidBody>\n"
                 "<RCMobileRigidBody Key=\"E\"/>\n"));
  CHECK(r.loaded);
  CHECK_FALSE(r.compiled);
  // A left-out Inertia is the shared default RCInertiaByGeom: the error names the body.
  expectExact(r,
              "bad.xml:3: RCMobileRigidBody 'N': RCInertiaByGeom needs a geom with volume on body 'N' (give "
              "it a Geom or use RCGenericInertia)");
  expectError(r, "bad.xml:6: ", {"RCMobileRigidBody 'E'", "needs a geom with volume on body 'E'"});
  CHECK(r.diag.errors().size() == 2);
}

TEST_CASE("errors: rods whose ends are too close", "[scene][errors]") {
  Result r =
      run(inList("<RCRodBody Key=\"R\"><Capped Value=\"true\"/><Radius Value=\"0.5\"/>\n"
                 "<Pos2><RCGlobalCoordinates><Pose Value=\"0 0.8 0 0 0 0\"/></RCGlobalCoordinates></Pos2>"
                 "</RCRodBody>\n"
                 "<RCRodBody Key=\"Z\"/>\n"));
  CHECK(r.loaded);
  CHECK_FALSE(r.compiled);
  expectError(r, "bad.xml:3: ", {"RCRodBody 'R'", "too close"});
  expectError(r, "bad.xml:5: ", {"RCRodBody 'Z'", "too close"});
}

TEST_CASE("errors: RigidBodyClone of nothing", "[scene][errors]") {
  Result r =
      run(inList("<RCStaticRigidBody Key=\"Wall\"/>\n<RigidBodyClone Key=\"C\">\n<Original Value=\"Wal\"/>\n"
                 "</RigidBodyClone>\n<RigidBodyClone Key=\"D\"/>\n"));
  CHECK(r.loaded);
  CHECK_FALSE(r.compiled);
  expectExact(r, "bad.xml:5: RigidBodyClone 'C': parameter 'Original' 'Wal' names no body (did you mean 'Wall'?)");
  // An empty Original is missing, not misspelled: no suggestion (it used to suggest the clone itself).
  expectExact(r,
              "bad.xml:7: RigidBodyClone 'D': parameter 'Original' is required (the fully qualified key of the body "
              "to copy)");
  // Written empty, and naming the clone itself.
  Result e =
      run(inList("<RCStaticRigidBody Key=\"E\"/>\n<RigidBodyClone Key=\"F\">\n<Original Value=\"\"/></RigidBodyClone>\n"
                 "<RigidBodyClone Key=\"G\">\n<Original Value=\"G\"/></RigidBodyClone>\n"));
  INFO(errorText(e.diag));
  CHECK(e.diag.errors().size() == 2);
  expectExact(e,
              "bad.xml:5: RigidBodyClone 'F': parameter 'Original' is required (the fully qualified key of the body "
              "to copy)");
  // It used to say "'G' names no body (a clone cannot copy itself) (did you mean 'E'?)": G is a
  // body, and E is no better.
  expectExact(e,
              "bad.xml:7: RigidBodyClone 'G': parameter 'Original' 'G' names the clone itself; a clone cannot "
              "copy itself");
}

TEST_CASE("errors: SceneSettings checks", "[scene][errors]") {
  Result r =
      run("<Simulation><SceneSettings>\n<MaxTimeStep Value=\"0.001\"/>\n<MinTimeStep Value=\"0.01\"/>\n"
          "<ERP Value=\"2\"/>\n<SolverIterations Value=\"0\"/>\n</SceneSettings></Simulation>");
  CHECK_FALSE(r.loaded);
  expectError(r, "bad.xml:4: ", {"'ERP' must be in [0, 1], got '2'"});
  expectError(r, "bad.xml:5: ", {"'SolverIterations' must be > 0, got '0'"});
  Result c =
      run("<Simulation><SceneSettings>\n<MaxTimeStep Value=\"0.001\"/>\n<MinTimeStep Value=\"0.01\"/>\n"
          "</SceneSettings></Simulation>");
  CHECK(c.loaded);
  CHECK_FALSE(c.compiled);
  expectExact(c, "bad.xml:3: SceneSettings: MinTimeStep must not exceed MaxTimeStep");
}

// ---------------------------------------------------------------------------------- INI syntax

TEST_CASE("errors: INI [] returns to the global section", "[scene][errors][ini]") {
  Result r = run("[Component0]\nType = RCSky\nKey = Sky\n[]\nComponentCount = 1\n[ ]\nComponent0.Height = 7\n",
                 Format::Ini, "b.ini");
  INFO(errorText(r.diag));
  CHECK(r.loaded);
  CHECK(r.diag.errors().empty());
  // "[" alone is still no header.
  expectExact(run("ComponentCount = 0\n[\n", Format::Ini, "b.ini"), "b.ini:2: malformed section header '['");
}

TEST_CASE("errors: INI syntax", "[scene][errors][ini]") {
  expectExact(run("ComponentCount = 1\n[Component0\nType = RCSky\n", Format::Ini, "b.ini"),
              "b.ini:2: malformed section header '[Component0'");
  expectExact(run("ComponentCount = 1\nComponent0.Type RCSky\n", Format::Ini, "b.ini"),
              "b.ini:2: expected 'key = value', got 'Component0.Type RCSky'");
  expectExact(run("\n\n = 3\n", Format::Ini, "b.ini"), "b.ini:3: empty key before '='");
  expectExact(run("Component0..Type = RCSky\n", Format::Ini, "b.ini"), "b.ini:1: empty name in key 'Component0..Type'");
  expectError(run("ComponentCount = 2\nComponent0.Type = RCSky\n", Format::Ini, "b.ini"),
              "b.ini:1: ", {"ComponentCount is 2 but Component1 is missing"});
  expectError(run("ComponentCount = -1\n", Format::Ini, "b.ini"),
              "b.ini:1: ", {"ComponentCount must be a whole number >= 0, got '-1'"});
  expectError(run("ComponentCount = 1.5\n", Format::Ini, "b.ini"),
              "b.ini:1: ", {"ComponentCount must be a whole number"});
  expectError(run("ComponentCount = 1\nComponent0 = RCSky\n", Format::Ini, "b.ini"),
              "b.ini:2: ", {"'Component0' is a component: write Component0.Type = ..."});
  expectError(run("ComponentCount = 1\nComponent0.Type = RCSky\nComponent0.Ref = X\n", Format::Ini, "b.ini"),
              "b.ini:", {"'Component0' needs exactly one of Component0.Type, Component0.Ref, Component0.Macro"});
  expectError(run("ComponentCount = 1\nComponent0.Key = X\n", Format::Ini, "b.ini"),
              "b.ini:", {"needs exactly one of"});
  expectError(run("ComponentCount = 1\nComponent0.Type = RCSky\nComponent0.Height.X = 1\n", Format::Ini, "b.ini"),
              "b.ini:3: ", {"parameter 'Height' is a value: write 'Height = ...'"});
  expectError(run("ComponentCount = 1\nComponent0.Type = RCSky\nComponent7.Type = RCSky\n", Format::Ini, "b.ini"),
              "b.ini:3: ", {"parameter 'Component7' unknown"});
}

TEST_CASE("errors: INI list items without their Count", "[scene][errors][ini][audit]") {
  // Before: "b.ini:1: parameter 'Component0' unknown", which hid that ComponentCount was missing.
  Result one = run("Component0.Type = RCSky\nComponent0.Height = 3\n", Format::Ini, "b.ini");
  CHECK_FALSE(one.loaded);
  REQUIRE(one.diag.errors().size() == 1);
  expectExact(one, "b.ini:1: ComponentCount is missing: Component0 needs 'ComponentCount = 1'");
  Result two = run("\n[Component0]\nType = RCSky\n[Component1]\nType = RCGround\n", Format::Ini, "b.ini");
  REQUIRE(two.diag.errors().size() == 1);
  expectExact(two, "b.ini:3: ComponentCount is missing: Component0 to Component1 need 'ComponentCount = 2'");
  // Any list: a model's ChildList.
  Result child =
      run("ComponentCount = 1\nComponent0.Type = RCCuboidModel\nComponent0.Key = M\nComponent0.Child0.Type = "
          "RCConeModel\n",
          Format::Ini, "b.ini");
  REQUIRE(child.diag.errors().size() == 1);
  expectExact(child, "b.ini:4: RCCuboidModel 'M': ChildCount is missing: Child0 needs 'ChildCount = 1'");
  // Items that do not start at 0 are still unknown names.
  Result gap = run("Component1.Type = RCSky\n", Format::Ini, "b.ini");
  expectExact(gap,
              "b.ini:1: parameter 'Component1' unknown (Simulation takes CameraCount, SceneSettings, ComponentCount)");
}

// ---------------------------------------------------------------------------------- many errors

TEST_CASE("errors: independent errors are all collected in one pass", "[scene][errors]") {
  Result r =
      run(inList("<RCStaticRigidBody Key=\"S\">\n"
                 "<Geom><RCCuboidGeom><Width Value=\"wide\"/><Height Value=\"-1\"/></RCCuboidGeom></Geom>\n"  // 4
                 "<Modle Macro=\"NoModel\"/>\n"                                                               // 5
                 "</RCStaticRigidBody>\n"
                 "<RCSky><Hieght Value=\"3\"/></RCSky>\n"  // 7
                 "<RCGrund/>\n"));                         // 8
  CHECK_FALSE(r.loaded);
  INFO(errorText(r.diag));
  CHECK(r.diag.errors().size() == 5);
  expectError(r, "bad.xml:4: ", {"'Width': expected a number, got 'wide'"});
  expectError(r, "bad.xml:4: ", {"'Height' must be > 0, got '-1'"});
  expectError(r, "bad.xml:5: ", {"parameter 'Modle' unknown (did you mean 'Model'?)"});
  expectError(r, "bad.xml:7: ", {"parameter 'Hieght' unknown (did you mean 'Height'?)"});
  expectError(r, "bad.xml:8: ", {"unknown component type 'RCGrund' (did you mean 'RCGround'?)"});

  // Compile errors of independent bodies are collected as well.
  Result c =
      run(inList("<RCMobileRigidBody Key=\"A\"><Geom><RCPlaneGeom/></Geom><Inertia><RCGenericInertia/>"
                 "</Inertia></RCMobileRigidBody>\n"
                 "<RCMobileRigidBody Key=\"B\"><Geom Macro=\"NoGeom\"/></RCMobileRigidBody>\n"
                 "<RCConstruction Key=\"K\"><Body><RCStaticRigidBody/></Body><ChildList><RCFixJoint/>"
                 "</ChildList></RCConstruction>\n"));
  CHECK(c.loaded);
  CHECK(c.diag.errors().size() == 3);
}

TEST_CASE("errors: loading never crashes on truncated or mutated input", "[scene][errors][fuzz]") {
  const std::string base = R"(<Simulation>
  <SceneSettings><Gravity Value="0 -9.81 0"/><FogSettings><Mode Value="Linear"/></FogSettings></SceneSettings>
  <CameraList><StaticCamera Key="C"/></CameraList>
  <ComponentList>
    <RCGenericMaterial Key="Rubber"><Friction Value="1"/></RCGenericMaterial>
    <RCCuboidModel Key="M"><ChildList><Child Ref="M2"/><RCConeModel/></ChildList></RCCuboidModel>
    <RCCuboidModel Key="M2"/>
    <RCGround/>
    <RCConstruction Key="P">
      <Body><RCStaticRigidBody Key="Pivot"><Pose><RCGlobalCoordinates><Pose Value="0 2 0 0 0 0"/></RCGlobalCoordinates></Pose></RCStaticRigidBody></Body>
      <ChildList>
        <RCHingeJoint Key="H">
          <Pose><RCLocalCoordinates><Pose Value="0 0 0 0 0 30"/></RCLocalCoordinates></Pose>
          <Body><RCMobileRigidBody Key="Bob"><Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom>
            <Material Ref="Rubber"/><Model Ref="M"/><Inertia><RCInertiaByGeom/></Inertia></RCMobileRigidBody></Body>
        </RCHingeJoint>
        <RCGenericDrive><Joint Ref="P.H"/></RCGenericDrive>
      </ChildList>
    </RCConstruction>
    <RigidBodyClone Key="P2"><Original Value="P"/><Pose><RCGlobalCoordinates><Pose Value="3 2 0 0 0 0"/></RCGlobalCoordinates></Pose></RigidBodyClone>
  </ComponentList>
</Simulation>
)";
  {
    Result whole = run(base);
    INFO(errorText(whole.diag));
    REQUIRE(whole.compiled);
  }
  Scene sc = mustLoad(base);
  const std::string ini = writeScene(sc, Format::Ini, true);
  size_t runs = 0;
  // Every prefix.
  for (size_t n = 0; n < base.size(); n += 7) {
    Result r = run(base.substr(0, n));
    ++runs;
    if (!r.loaded) CHECK_FALSE(r.diag.errors().empty());
  }
  for (size_t n = 0; n < ini.size(); n += 11) {
    Result r = run(ini.substr(0, n), Format::Ini, "fuzz.ini");
    ++runs;
  }
  // Single-character mutations at many places.
  const char replacements[] = {'<', '>', '"', '.', '0', '-', 'X', ' ', '/', '='};
  for (size_t i = 0; i < base.size(); i += 3) {
    std::string t = base;
    t[i] = replacements[i % sizeof replacements];
    run(t);
    ++runs;
  }
  for (size_t i = 0; i < ini.size(); i += 5) {
    std::string t = ini;
    t[i] = replacements[i % sizeof replacements];
    run(t, Format::Ini, "fuzz.ini");
    ++runs;
  }
  CHECK(runs > 500);
}

TEST_CASE("errors: deep nesting is an error, not a stack overflow", "[scene][errors]") {
  std::string open, close;
  for (int i = 0; i < 400; ++i) {
    open += "<RCCuboidModel><ChildList>";
    close += "</ChildList></RCCuboidModel>";
  }
  Result r = run(inList(open + close + "\n"));
  CHECK_FALSE(r.loaded);
  expectError(r, "bad.xml:3: ", {"nested deeper than"});
}

// ---------------------------------------------------------------------------------- audit #9

namespace {

/// What `simbob check` does: load, and compile even when loading failed (as long as there is
/// a graph), so that one pass reports every problem.
Result checkAll(const std::string& text, const std::string& name = "bad.xml") {
  Result r;
  Scene s;
  r.loaded = loadSceneFromText(text, name, Format::Xml, testRegistry(), &s, r.diag);
  if (r.loaded || !s.comps.empty()) {
    Model m;
    r.compiled = compileScene(s, &m, r.diag);
  }
  return r;
}

/// Every error line, sorted (the order of load and compile messages is not the point).
std::vector<std::string> sortedErrors(const Diagnostics& d) {
  std::vector<std::string> out;
  for (const Error& e : d.errors()) out.push_back(e.str());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("errors: check reports load and compile errors of several bodies in one pass", "[scene][errors][audit]") {
  // Before: a scene that failed to load was not compiled, so only the unknown geom type (line
  // 7) was reported; the mass, inertia and clone errors came one fix-and-rerun later each.
  Result r =
      checkAll(inList("<RCMobileRigidBody Key=\"A\"><Geom Macro=\"NoGeom\"/></RCMobileRigidBody>\n"  // 3
                      "<RCMobileRigidBody Key=\"B\"><Inertia><RCGenericInertia>"
                      "<Inertia Value=\"1 2 0 2 1 0 0 0 1\"/></RCGenericInertia></Inertia></RCMobileRigidBody>\n"  // 4
                      "<RCMobileRigidBody Key=\"C\"><Geom><RCSphereGeom/></Geom><Inertia><RCInertiaByGeom>"
                      "<Mass Value=\"0\"/></RCInertiaByGeom></Inertia></RCMobileRigidBody>\n"         // 5
                      "<RCMobileRigidBody Key=\"G\"><Inertia><RCGenericInertia><Mass Value=\"-2\"/>"  // 6
                      "</RCGenericInertia></Inertia><Geom><RCSphereGeom/></Geom></RCMobileRigidBody>\n"
                      "<RCMobileRigidBody Key=\"D\"><Geom><RCSphereGeon/></Geom></RCMobileRigidBody>\n"  // 7
                      "<RigidBodyClone Key=\"E\"><Original Value=\"Nobody\"/></RigidBodyClone>\n"));     // 8
  CHECK_FALSE(r.loaded);
  CHECK_FALSE(r.compiled);
  INFO(errorText(r.diag));
  CHECK(sortedErrors(r.diag) ==
        std::vector<std::string>{
            "bad.xml:3: RCMobileRigidBody 'A': RCInertiaByGeom needs a geom with volume on body 'A' (give it a Geom "
            "or use RCGenericInertia)",
            "bad.xml:4: RCGenericInertia 'B.Inertia': parameter 'Inertia' is not positive definite",
            "bad.xml:5: RCInertiaByGeom 'C.Inertia': parameter 'Mass' must be > 0 (or negative to use Density)",
            "bad.xml:6: RCGenericInertia 'G.Inertia': parameter 'Mass' must be > 0, got '-2'",
            "bad.xml:7: RCMobileRigidBody 'D': unknown component type 'RCSphereGeon' (did you mean 'RCSphereGeom'?)",
            "bad.xml:8: RigidBodyClone 'E': parameter 'Original' 'Nobody' names no body",
        });
}

TEST_CASE("errors: a body whose geom type is unknown reports only that", "[scene][errors][audit]") {
  // The failed geom leaves the body without volume; "needs a geom with volume" would be noise.
  Result r = checkAll(inList("<RCMobileRigidBody Key=\"D\">\n<Geom><RCSphereGeon/></Geom></RCMobileRigidBody>\n"));
  CHECK_FALSE(r.compiled);
  INFO(errorText(r.diag));
  REQUIRE(r.diag.errors().size() == 1);
  expectExact(r,
              "bad.xml:4: RCMobileRigidBody 'D': unknown component type 'RCSphereGeon' (did you mean 'RCSphereGeom'?)");
}

TEST_CASE("errors: a missing import does not hide a clone error elsewhere", "[scene][errors][audit][import]") {
  // Before: `check` stopped at the missing file; the misspelt Original was never reported.
  TempDir dir;
  std::string main =
      dir.write("main.xml", inList("<RCImportBody Key=\"M\"><File Value=\"missing.xml\"/></RCImportBody>\n"
                                   "<RCMobileRigidBody Key=\"Ball\"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody>\n"
                                   "<RigidBodyClone Key=\"E\"><Original Value=\"Bal\"/></RigidBodyClone>\n"));
  Scene s;
  Diagnostics d;
  CHECK_FALSE(loadScene(main, testRegistry(), &s, d));
  REQUIRE_FALSE(s.comps.empty());
  Model m;
  CHECK_FALSE(compileScene(s, &m, d));
  INFO(errorText(d));
  REQUIRE(d.errors().size() == 2);
  CHECK(d.errors()[0].kind == ErrorKind::MissingInput);
  CHECK(d.errors()[0].str() == main + ":3: RCImportBody 'M': cannot read import '" +
                                   (dir.path() / "missing.xml").string() + "': No such file or directory");
  CHECK(d.errors()[1].str() ==
        main + ":5: RigidBodyClone 'E': parameter 'Original' 'Bal' names no body (did you mean 'Ball'?)");
}

TEST_CASE("errors: a root model's Pose must be RCLocalCoordinates (guide 6.3)", "[scene][errors][audit]") {
  // Before: accepted, and the global pose was silently used as a pose relative to the body.
  Result r =
      run(inList("<RCMobileRigidBody Key=\"A\"><Geom><RCSphereGeom/></Geom>\n"
                 "<Model><RCCuboidModel><Pose>\n"
                 "<RCGlobalCoordinates><Pose Value=\"1 0 0 0 0 0\"/></RCGlobalCoordinates>\n"  // 5
                 "</Pose></RCCuboidModel></Model></RCMobileRigidBody>\n"));
  CHECK(r.loaded);
  CHECK_FALSE(r.compiled);
  REQUIRE(r.diag.errors().size() == 1);
  expectExact(r,
              "bad.xml:5: RCCuboidModel 'A.Model': a root model's Pose must be RCLocalCoordinates: a model may be "
              "drawn for several bodies, so global coordinates have no meaning for it (guide 6.3)");
  // A shared model is reported once, however many bodies draw it; a local root pose is fine.
  Result shared =
      run(inList("<RCCuboidModel Key=\"M\"><Pose><RCGlobalCoordinates/></Pose></RCCuboidModel>\n"  // 3
                 "<RCStaticRigidBody Key=\"S\"><Model Ref=\"M\"/></RCStaticRigidBody>\n"
                 "<RCStaticRigidBody Key=\"T\"><Model Ref=\"M\"/></RCStaticRigidBody>\n"
                 "<RCStaticRigidBody Key=\"U\"><Model><RCCuboidModel><Pose><RCLocalCoordinates/></Pose>"
                 "</RCCuboidModel></Model></RCStaticRigidBody>\n"));
  INFO(errorText(shared.diag));
  CHECK(shared.diag.errors().size() == 1);
  expectError(shared, "bad.xml:3: ", {"RCCuboidModel 'M': a root model's Pose must be RCLocalCoordinates"});
}

TEST_CASE("errors: drives, servos, sockets and controllers that refer to the wrong thing", "[scene][errors][audit]") {
  // Before: every one of these passed `check` (with only the "read but no effect" warnings).
  Result r = run(inList(
      "<RCRobot Key=\"Bot\"><Construction><RCConstruction Key=\"C\"><Body><RCMobileRigidBody Key=\"Base\">"
      "<Geom><RCSphereGeom/></Geom></RCMobileRigidBody></Body><ChildList>\n"  // 3
      "<RCBallSocketJoint Key=\"Ball\"><Body><RCMobileRigidBody Key=\"L1\"><Pose><RCLocalCoordinates>"
      "<Pose Value=\"1 0 0 0 0 0\"/></RCLocalCoordinates></Pose><Geom><RCSphereGeom/></Geom></RCMobileRigidBody>"
      "</Body></RCBallSocketJoint>\n"  // 4
      "<RCHingeJoint Key=\"H\"><Body><RCMobileRigidBody Key=\"L2\"><Pose><RCLocalCoordinates>"
      "<Pose Value=\"-1 0 0 0 0 0\"/></RCLocalCoordinates></Pose><Geom><RCSphereGeom/></Geom></RCMobileRigidBody>"
      "</Body></RCHingeJoint>\n"                                                                         // 5
      "<RCGenericDrive Key=\"OnBall\">\n<Joint Ref=\"Bot.C.Ball\"/></RCGenericDrive>\n"                  // 6, 7
      "<RCGenericDrive Key=\"NoJoint\"/>\n"                                                              // 8
      "<RCGenericServo Key=\"Servo\"><Joint Ref=\"Bot.C.H\"/></RCGenericServo>\n"                        // 9
      "<RCGenericVelControlledDrive Key=\"Vel\"><Joint Ref=\"Bot.C.H\"/>\n<MinPos Value=\"2\"/>\n"       // 10, 11
      "<MaxPos Value=\"1\"/></RCGenericVelControlledDrive>\n"                                            // 12
      "<RCGenericDrive Key=\"Drive\"><Joint Ref=\"Bot.C.H\"/></RCGenericDrive>\n"                        // 13
      "<RCLocalSocketCommunicator Key=\"Sock\">\n<Port Value=\"70000\"/></RCLocalSocketCommunicator>\n"  // 14, 15
      "</ChildList></RCConstruction></Construction><ControllerList>\n"                                   // 16
      "<RCDriveTest Key=\"DT\">\n<Drive Ref=\"Bot.C.Servo\"/></RCDriveTest>\n"                           // 17, 18
      "<RCTwoWheelMotionControl Key=\"TW\">\n<ControlLeft Ref=\"Bot.C.Drive\"/>\n"                       // 19, 20
      "<ControlRight Ref=\"Bot.C.Vel\"/></RCTwoWheelMotionControl>\n"                                    // 21
      "<RCServoTest Key=\"ST\"><PosControl Ref=\"Bot.C.Servo\"/></RCServoTest>\n"                        // 22
      "</ControllerList></RCRobot>\n"));
  CHECK(r.loaded);
  CHECK_FALSE(r.compiled);
  INFO(errorText(r.diag));
  CHECK(sortedErrors(r.diag) ==
        std::vector<std::string>{
            "bad.xml:12: RCGenericVelControlledDrive 'Bot.C.Vel': MinPos (2) is greater than MaxPos (1)",
            "bad.xml:15: RCLocalSocketCommunicator 'Bot.C.Sock': parameter 'Port' must be at most 65535, got 70000",
            "bad.xml:18: RCDriveTest 'Bot.DT': parameter 'Drive' must refer to a component implementing RCDriver, "
            "but RCGenericServo 'Bot.C.Servo' does not",
            "bad.xml:20: RCTwoWheelMotionControl 'Bot.TW': parameter 'ControlLeft' must refer to a component "
            "implementing RCVelControl, but RCGenericDrive 'Bot.C.Drive' does not",
            "bad.xml:22: RCServoTest 'Bot.ST': RCServoTest moves its servo between MinPos and MaxPos, but "
            "RCGenericServo 'Bot.C.Servo' has an infinite limit",
            "bad.xml:7: RCGenericDrive 'Bot.C.OnBall': parameter 'Joint' must be a hinge or slider joint, but "
            "RCBallSocketJoint 'Bot.C.Ball' is not (guide 6.11)",
            "bad.xml:8: RCGenericDrive 'Bot.C.NoJoint': parameter 'Joint' is required (a Ref to the hinge or slider "
            "joint it drives)",
        });
}

TEST_CASE("errors: the example robot scene checks clean", "[scene][errors][audit]") {
  Scene s;
  Diagnostics d;
  REQUIRE(loadScene(std::string(SIMBOB_SOURCE_DIR) + "/scenes/robot.xml", testRegistry(), &s, d));
  Model m;
  bool ok = compileScene(s, &m, d);
  INFO(errorText(d));
  CHECK(ok);
  CHECK(d.errors().empty());
}

TEST_CASE("errors: camera clip planes, view angle and cameras without a Body", "[scene][errors][audit]") {
  // Before: all of these passed `check`.
  Result r =
      run("<Simulation><CameraList>\n"
          "<RCStaticCamera Key=\"Clip\"><NearClip Value=\"10\"/>\n<FarClip Value=\"5\"/></RCStaticCamera>\n"  // 2, 3
          "<RCStaticCamera Key=\"Same\"><NearClip Value=\"5\"/><FarClip Value=\"5\"/></RCStaticCamera>\n"     // 4
          "<RCStaticCamera Key=\"Wide\">\n<ViewAngle Value=\"500\"/></RCStaticCamera>\n"                      // 5, 6
          "<MountedCamera Key=\"M\"/>\n"                                                                      // 7
          "<SpotlightCamera Key=\"S\"/>\n"                                                                    // 8
          "<TrackingCamera Key=\"T\"/>\n"                                                                     // 9
          "<RCStaticCamera Key=\"Fine\"><ViewAngle Value=\"179\"/></RCStaticCamera>\n"
          "</CameraList></Simulation>\n");
  CHECK(r.loaded);
  CHECK_FALSE(r.compiled);
  INFO(errorText(r.diag));
  CHECK(sortedErrors(r.diag) ==
        std::vector<std::string>{
            "bad.xml:3: RCStaticCamera 'Clip': NearClip (10 m) must be closer than FarClip (5 m)",
            "bad.xml:4: RCStaticCamera 'Same': NearClip (5 m) must be closer than FarClip (5 m)",
            "bad.xml:6: RCStaticCamera 'Wide': parameter 'ViewAngle' must be below 180 degrees, got 500",
            "bad.xml:7: RCMountedCamera 'M': parameter 'Body' is required (a Ref to the body it follows)",
            "bad.xml:8: RCSpotlightCamera 'S': parameter 'Body' is required (a Ref to the body it follows)",
            "bad.xml:9: RCTrackingCamera 'T': parameter 'Body' is required (a Ref to the body it follows)",
        });
}

TEST_CASE("errors: Motion on an RCImportBody whose imported body is static", "[scene][errors][audit][import]") {
  // Before: accepted and silently ignored (a static body has no velocity).
  TempDir dir;
  dir.write("wall.xml",
            "<Body><RCStaticRigidBody Key=\"Wall\"><Geom><RCCuboidGeom/></Geom></RCStaticRigidBody></Body>");
  dir.write("ball.xml",
            "<Body><RCMobileRigidBody Key=\"Ball\"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody></Body>");
  const std::string motion = "<Motion><RCGlobalMotion><LinVelocity Value=\"1 0 0\"/></RCGlobalMotion></Motion>";
  std::string main = dir.write("main.xml", inList("<RCImportBody Key=\"I\"><File Value=\"wall.xml\"/>\n" + motion +
                                                  "</RCImportBody>\n"  // 3, 4
                                                  "<RCImportBody Key=\"J\"><File Value=\"ball.xml\"/>" +
                                                  motion + "</RCImportBody>\n"));
  Scene s;
  Diagnostics d;
  REQUIRE(loadScene(main, testRegistry(), &s, d));
  Model m;
  CHECK_FALSE(compileScene(s, &m, d));
  INFO(errorText(d));
  REQUIRE(d.errors().size() == 1);
  CHECK(d.errors()[0].str() ==
        main + ":4: RCImportBody 'I': parameter 'Motion' is given but the imported body is static: it cannot move");
}

// Issue #10, items 12-14: input forms.

TEST_CASE("a UTF-8 byte order mark is accepted in INI as in XML", "[scene][errors]") {
  const std::string bom = "\xEF\xBB\xBF";
  Result ini = run(bom + "ComponentCount = 1\nComponent0.Type = RCGround\n", Format::Ini, "bom.ini");
  INFO(errorText(ini.diag));
  CHECK(ini.loaded);
  Result xml = run(bom + inList("<RCGround/>\n"), Format::Xml, "bom.xml");
  CHECK(xml.loaded);
}

TEST_CASE("invisible and control characters in messages are escaped", "[scene][errors]") {
  // A zero-width space inside a name and a BOM in the middle of the file.
  Result r =
      run("ComponentCount = 0\nCamera\xE2\x80\x8B"
          "Count = 1\n\xEF\xBB\xBF"
          "Foo = 1\n",
          Format::Ini, "bad.ini");
  expectExact(r,
              "bad.ini:2: parameter 'Camera\\u{200B}Count' unknown (Simulation takes CameraCount, SceneSettings, "
              "ComponentCount)");
  expectExact(
      r, "bad.ini:3: parameter '\\u{FEFF}Foo' unknown (Simulation takes CameraCount, SceneSettings, ComponentCount)");
  Result c = run("ComponentCount = 0\nx\x01y\n", Format::Ini, "ctl.ini");
  expectExact(c, "ctl.ini:2: expected 'key = value', got 'x\\x01y'");
}

TEST_CASE("a huge bad line is cut in the message", "[scene][errors]") {
  const std::string line(50 << 20, 'x');
  Result r = run("ComponentCount = 0\n" + line + "\n", Format::Ini, "huge.ini");
  REQUIRE(r.diag.errors().size() == 1);
  const std::string msg = r.diag.errors()[0].str();
  CHECK(msg == "huge.ini:2: expected 'key = value', got '" + std::string(80, 'x') + "... (52428800 bytes)'");
}

TEST_CASE("XML with a duplicated attribute or two root elements is rejected", "[scene][errors]") {
  Result dup = run(inList("<RCGround Key=\"a\" Key=\"b\"/>\n"));
  CHECK_FALSE(dup.loaded);
  expectExact(dup, "bad.xml:3: malformed XML: attribute 'Key' given twice in <RCGround>");
  Result val = run(inList("<RCSky>\n<Height Value=\"1\" Value=\"2\"/>\n</RCSky>\n"));
  expectExact(val, "bad.xml:4: malformed XML: attribute 'Value' given twice in <Height>");
  // The root element is looked at too, and of several such elements the first in the file is named.
  Result root = run("<Simulation A=\"1\" A=\"2\">\n<ComponentList/>\n</Simulation>\n");
  expectExact(root, "bad.xml:1: malformed XML: attribute 'A' given twice in <Simulation>");
  Result two = run(inList("<RCGround Key=\"a\" Key=\"b\"/>\n<RCSky>\n<Height Value=\"1\" Value=\"2\"/>\n</RCSky>\n"));
  REQUIRE(two.diag.errors().size() == 1);
  expectExact(two, "bad.xml:3: malformed XML: attribute 'Key' given twice in <RCGround>");
  Result roots = run(inList("<RCGround/>\n") + "<Simulation/>\n");
  CHECK_FALSE(roots.loaded);
  expectExact(roots, "bad.xml:6: malformed XML: a second root element <Simulation> (a document has one)");
}
