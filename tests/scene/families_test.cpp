// Tests of the family files (lib/components/<family>.cpp) as a whole: every registered type,
// placed where its family may stand, is lowered by compileScene without an internal error.
// The family files read parameters through typed names (`c.get(kWidth)`); a name the type does
// not have throws std::logic_error("internal: <type> has no parameter ..."), and a typed name
// whose C++ type differs from the table's throws std::bad_variant_access. Only running every
// lowering on every type finds those, so this test builds one small scene per type.
#include <catch2/catch.hpp>

#include <exception>
#include <string>

#include "scene/scene_helpers.h"
#include "test_registry.h"

using namespace simbob;
using namespace scenetest;

namespace {

bool hasParam(const TypeSpec& t, const char* name) { return t.paramIndex(name) >= 0; }

const char* const kMobileBall =
    "<RCMobileRigidBody Key=\"Ball\"><Pose><RCGlobalCoordinates><Pose Value=\"0 1 0 0 0 0\"/></RCGlobalCoordinates>"
    "</Pose><Geom><RCSphereGeom/></Geom></RCMobileRigidBody>";

std::string mobileBody(const std::string& key, const std::string& inside = "") {
  return "<RCMobileRigidBody Key=\"" + key + "\"><Geom><RCSphereGeom/></Geom>" + inside + "</RCMobileRigidBody>";
}

/// A hinge H on a static root, and one drive of each kind on it (servo limits finite).
/// `qkey` is the construction's fully qualified key (the drives' Refs need it).
std::string driveConstruction(const std::string& key, const std::string& qkey, const std::string& more_children = "") {
  return "<RCConstruction Key=\"" + key +
         "\"><Body><RCStaticRigidBody/></Body><ChildList>"
         "<RCHingeJoint Key=\"H\"><Body>" +
         mobileBody("Wheel") +
         "</Body></RCHingeJoint>"
         "<RCGenericDrive Key=\"D\"><Joint Ref=\"" +
         qkey +
         ".H\"/></RCGenericDrive>"
         "<RCGenericServo Key=\"S\"><Joint Ref=\"" +
         qkey +
         ".H\"/><MinPos Value=\"-1\"/><MaxPos Value=\"1\"/></RCGenericServo>"
         "<RCGenericVelControlledDrive Key=\"V\"><Joint Ref=\"" +
         qkey +
         ".H\"/></RCGenericVelControlledDrive>"
         "<RCProximitySensor Key=\"P\"><Geom><RCSphereGeom/></Geom></RCProximitySensor>"
         "<RCRangeSensor Key=\"R\"/><RCLaserScanner Key=\"L\"/>" +
         more_children + "</ChildList></RCConstruction>";
}

/// The type element with Key "X" and the parameters it cannot do without (by parameter name,
/// so that a new type with the same needs is covered without touching this test), plus those
/// that make its lowering take the branch that reads the most.
std::string element(const TypeSpec& t, const std::string& construction_key) {
  std::string p;
  auto has = [&](const char* n) { return hasParam(t, n); };
  if (!t.import_root.empty() && has("File")) {
    const char* file = t.import_root == "Body"    ? "body.xml"
                       : t.import_root == "Joint" ? "joint.xml"
                       : t.import_root == "robot" ? "robot.urdf"
                                                  : "list.xml";
    p += std::string("<File Value=\"") + file + "\"/>";
  }
  // A type that reads a mesh (File and Scale): the test cube.
  if (t.import_root.empty() && has("File") && has("Scale"))
    p += "<File Value=\"" + std::string(SIMBOB_SOURCE_DIR) + "/tests/data/meshes/cube_100mm.stl\"/>";
  switch (t.family) {
    case Family::Body:
      if (has("Original")) p += "<Original Value=\"Ball\"/>";
      if (has("Inertia") && has("Geom")) p += "<Geom><RCSphereGeom/></Geom>";  // a mobile body needs volume
      if (has("Pos2")) p += "<Pos2><RCGlobalCoordinates><Pose Value=\"0 1 0 0 0 0\"/></RCGlobalCoordinates></Pos2>";
      if (has("Body") && has("ChildList"))
        p += "<Body><RCStaticRigidBody/></Body><ChildList><RCHingeJoint Key=\"J\"><Body>" + mobileBody("Arm") +
             "</Body></RCHingeJoint></ChildList>";
      if (!t.import_root.empty() && has("Motion"))
        p += "<Motion><RCGlobalMotion><LinVelocity Value=\"1 0 0\"/></RCGlobalMotion></Motion>";
      break;
    case Family::Joint:
      if (t.import_root.empty() && has("Body")) p += "<Body>" + mobileBody("Child") + "</Body>";
      break;
    case Family::Periphery:
      if (has("Joint")) p += "<Joint Ref=\"" + construction_key + ".H\"/>";
      if (has("Geom")) p += "<Geom><RCSphereGeom/></Geom>";
      break;
    case Family::Controller:
      if (has("Drive")) p += "<Drive Ref=\"Bot.C.D\"/>";
      if (has("PosControl")) p += "<PosControl Ref=\"Bot.C.S\"/>";
      if (has("ControlLeft")) p += "<ControlLeft Ref=\"Bot.C.V\"/>";
      if (has("ControlRight")) p += "<ControlRight Ref=\"Bot.C.V\"/>";
      if (has("Commands")) p += "<Target Ref=\"Bot.C.D\"/><Commands Value=\"0 0.5; 1 -0.5\"/>";
      if (has("Target") && !has("Commands")) p += "<Target Value=\"1 0\"/>";  // RCSimGoToPoint's point
      if (has("Body")) p += "<Body Ref=\"Bot.C.H.Wheel\"/>";
      if (has("Motion")) p += "<Motion Ref=\"Bot.M\"/>";
      if (has("Sensor")) p += "<Sensor Ref=\"Bot.C.P\"/>";
      if (has("Sensors")) p += "<Sensors><Sensor Ref=\"Bot.C.R\"/></Sensors>";
      if (has("Scanner")) p += "<Scanner Ref=\"Bot.C.L\"/>";
      break;
    case Family::Camera:
      if (has("Body")) p += "<Body Ref=\"Ball\"/>";
      break;
    case Family::GlobalSim:
      if (has("Construction")) p += "<Construction>" + driveConstruction("C", "X.C") + "</Construction>";
      break;
    case Family::Geom:
      if (has("GeomType")) p += "<GeomType Value=\"Cylinder\"/>";  // also reads Alignment
      if (has("SubGeom")) p += "<SubGeom><RCSphereGeom/></SubGeom>";
      break;
    case Family::Inertia:
      if (has("Density") && has("Mass")) p += "<Mass Value=\"-1\"/>";  // negative: Density x volume
      break;
    case Family::Model:
      // A visible child, so that wrapping an invisible model still has something to wrap.
      if (has("ChildList")) p += "<ChildList><RCCuboidModel/></ChildList>";
      break;
    case Family::Material:
    case Family::Skin:
    case Family::Pose:
    case Family::Motion:
    case Family::Struct:
      break;
  }
  return "<" + t.name + " Key=\"X\">" + p + "</" + t.name + ">";
}

/// A scene in which the type stands where its family may, and its family's lowering runs.
std::string sceneWith(const TypeSpec& t) {
  const std::string x = element(t, "K");
  std::string cameras, components = kMobileBall;
  switch (t.family) {
    case Family::Body:
    case Family::GlobalSim:
      components += x;
      break;
    case Family::Joint:
      components += "<RCConstruction Key=\"K\"><Body>" + mobileBody("Root") + "</Body><ChildList>" + x +
                    "</ChildList></RCConstruction>";
      break;
    case Family::Periphery:
      components += driveConstruction("K", "K", x);
      break;
    case Family::Controller:
      components += "<RCRobot Key=\"Bot\"><Construction>" + driveConstruction("C", "Bot.C") +
                    "</Construction><ControllerList>" + x +
                    "<RCTwoWheelMotionControl Key=\"M\"><ControlLeft Ref=\"Bot.C.V\"/><ControlRight "
                    "Ref=\"Bot.C.V\"/></RCTwoWheelMotionControl></ControllerList></RCRobot>";
      break;
    case Family::Camera:
      cameras = x;
      break;
    case Family::Geom:
      // A static body (a plane geom may only be static) with a model to match or wrap.
      components += "<RCStaticRigidBody Key=\"S\"><Geom>" + x + "</Geom><Model><RCCylinderModel/></Model>" +
                    "</RCStaticRigidBody>";
      break;
    case Family::Model:
      components +=
          "<RCStaticRigidBody Key=\"S\"><Geom><RCModelWrapGeom><GeomType Value=\"Cylinder\"/>"
          "</RCModelWrapGeom></Geom><Model>" +
          x + "</Model></RCStaticRigidBody>";
      break;
    case Family::Skin:
      components += "<RCStaticRigidBody Key=\"S\"><Model><RCCuboidModel><Skin>" + x +
                    "</Skin></RCCuboidModel></Model></RCStaticRigidBody>";
      break;
    case Family::Material:
      components +=
          "<RCStaticRigidBody Key=\"S\"><Geom><RCSphereGeom/></Geom><Material>" + x + "</Material></RCStaticRigidBody>";
      break;
    case Family::Pose:
      // Inside a geom, so that local coordinates have a frame.
      components += "<RCStaticRigidBody Key=\"S\"><Geom><RCTransformGeom><Pose>" + x +
                    "</Pose><SubGeom><RCSphereGeom/></SubGeom></RCTransformGeom></Geom></RCStaticRigidBody>";
      break;
    case Family::Motion:
      components += mobileBody("M", "<Motion>" + x + "</Motion>");
      break;
    case Family::Inertia:
      components += mobileBody("I", "<Inertia>" + x + "</Inertia>");
      break;
    case Family::Struct:
      // The structs of a scene file are read (and lowered) in every scene.
      break;
  }
  return "<Simulation><SceneSettings><FogSettings><Mode Value=\"Linear\"/></FogSettings></SceneSettings>"
         "<CameraList>" +
         cameras + "</CameraList><ComponentList>" + components + "</ComponentList></Simulation>";
}

}  // namespace

TEST_CASE("families: every registered type is lowered without an internal error", "[scene][families]") {
  TempDir dir;
  dir.write("body.xml", "<Body>" + mobileBody("Imported") + "</Body>");
  dir.write("joint.xml", "<Joint><RCHingeJoint Key=\"IJ\"><Body>" + mobileBody("B") + "</Body></RCHingeJoint></Joint>");
  dir.write("list.xml", "<RefList><RCGenericMaterial Key=\"M\"/></RefList>");
  dir.write("robot.urdf",
            "<robot name=\"r\"><link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" ixy=\"0\" "
            "ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link></robot>");
  size_t walked = 0;
  for (const TypeSpec& t : testRegistry().types()) {
    // GlobalSettings is the global settings INI (guide 3.3.1): read by the CLI, never lowered.
    if (t.family == Family::Struct && t.name == "GlobalSettings") continue;
    const std::string text = sceneWith(t);
    INFO("type " << t.name << " in:\n" << text);
    const std::string main = dir.write(t.name + ".xml", text);
    Scene s;
    Diagnostics d;
    bool loaded = loadScene(main, testRegistry(), &s, d);
    INFO(errorText(d));
    REQUIRE(loaded);
    bool placed = false;
    for (const Component& c : s.comps) placed = placed || c.type == &t;
    CHECK(placed);
    Model m;
    bool compiled = false;
    try {
      compiled = compileScene(s, &m, d);
    } catch (const std::exception& e) {
      FAIL_CHECK("compiling a scene with " << t.name << " threw: " << e.what());
    }
    INFO(errorText(d));
    // The placeholders an RCImportURDF makes for its links and drives are never written in a
    // scene: one written there is refused with a message, not an internal error.
    const bool placeholder = t.name.rfind("URDF", 0) == 0;
    CHECK(compiled != placeholder);
    if (placeholder) CHECK(errorText(d).find("made by an RCImportURDF") != std::string::npos);
    ++walked;
  }
  CHECK(walked + 1 == testRegistry().types().size());
}

TEST_CASE("families: a typed read of a parameter the type does not have is an internal error", "[scene][families]") {
  // The check the walk above relies on.
  Scene s = mustLoad("<Simulation><ComponentList><RCGround Key=\"G\"/></ComponentList></Simulation>");
  const Component& g = comp(s, "G");
  CHECK(g.get(ValueParam<double>{"Extension"}) == 100);
  CHECK_THROWS_WITH(g.get(ValueParam<double>{"Radius"}), "internal: RCGround has no parameter 'Radius'");
  CHECK_THROWS_AS(g.get(ValueParam<int64_t>{"Extension"}), std::bad_variant_access);
}
