// Tests of reading scenes (guide 4.1 INI, 4.2 XML, chapter 5) into the component graph:
// values, inline / Ref / Macro components, lists, qualified keys, settings, cameras, imports,
// and write -> read round trips in both formats.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "simbob/tool/document_ini.h"
#include "test_registry.h"
#include "scene/scene_helpers.h"

using namespace simbob;
using namespace scenetest;

namespace {

const char* kValuesScene = R"(<?xml version="1.0"?>
<Simulation>
  <SceneSettings>
    <Gravity Value="0 0 -9.81"/>
    <MaxTimeStep Value="0.002"/>
    <Solver Value="step"/>
    <SolverIterations Value="50"/>
    <ClearColor Value="0.1 0.2 0.3"/>
    <FogSettings>
      <Mode Value="Linear"/>
      <End Value="250"/>
    </FogSettings>
  </SceneSettings>
  <ComponentList>
    <RCMobileRigidBody Key="Ball">
      <Pose><RCGlobalCoordinates><Pose Value="(1, 2, 3); 10 20 30"/></RCGlobalCoordinates></Pose>
      <Geom><RCSphereGeom><Radius Value=".25"/></RCSphereGeom></Geom>
      <Inertia><RCInertiaByGeom><Density Value="2e3"/></RCInertiaByGeom></Inertia>
    </RCMobileRigidBody>
    <RCEllipsoidModel Key="Egg">
      <Triangles Value="on"/>
      <Accuracy Value="3"/>
      <RadiusX Value="1.5"/>
    </RCEllipsoidModel>
    <RCColoredSkin Key="Red">
      <Color Value="1 0 0 1"/>
      <Ambient Value="invalid"/>
      <ColorMode Value="TransparentLighing"/>
    </RCColoredSkin>
    <RCCuboidModel Key="Box">
      <Cuboid Value="-1 -2 -3 1 2 3"/>
      <SideMask Value="Top|Bottom"/>
    </RCCuboidModel>
    <RCTexturedSkin Key="Wood">
      <Texture Value="wood\tgrain\\1.bmp"/>
    </RCTexturedSkin>
  </ComponentList>
</Simulation>
)";

}  // namespace

TEST_CASE("load: XML value parameters, set flags and defaults", "[scene][load]") {
  Scene s = mustLoad(kValuesScene);
  REQUIRE(s.settings >= 0);
  const Component& ss = s.at(s.settings);
  CHECK(ss.type->name == "SceneSettings");
  CHECK(ss.get(ValueParam<Triple>{"Gravity"}) == Triple{0, 0, -9.81});
  CHECK(ss.slot("Gravity").set);
  CHECK(ss.slot("Gravity").loc.line == 4);
  CHECK(ss.get(ValueParam<double>{"MaxTimeStep"}) == 0.002);
  CHECK(ss.get(EnumParam{"Solver"}) == 1);  // enum keys are case-insensitive
  CHECK(ss.get(ValueParam<int64_t>{"SolverIterations"}) == 50);
  CHECK(std::get<Color>(ss.slot("ClearColor").value()) == Color{{0.1, 0.2, 0.3, 1}, true});
  // Unset parameters keep their defaults and are marked unset.
  CHECK_FALSE(ss.slot("ERP").set);
  CHECK(ss.get(ValueParam<double>{"ERP"}) == 0.2);
  CHECK(ss.get(ValueParam<int64_t>{"MaxContacts"}) == 4);
  const Component& fog = s.at(ss.get(LinkParam{"FogSettings"}).comp);
  CHECK(fog.type->name == "FogSettings");
  CHECK(fog.get(EnumParam{"Mode"}) == 1);
  CHECK(fog.get(ValueParam<double>{"End"}) == 250);
  CHECK(fog.get(ValueParam<double>{"Start"}) == 10);

  const Component& ball = comp(s, "Ball");
  CHECK(ball.type->name == "RCMobileRigidBody");
  CHECK(ball.has_key);
  const Component& pose = comp(s, "Ball.Pose");
  CHECK(pose.type->name == "RCGlobalCoordinates");
  CHECK(pose.get(ValueParam<Pose>{"Pose"}) == Pose{{1, 2, 3}, {10, 20, 30}});
  CHECK_FALSE(pose.has_key);
  CHECK(comp(s, "Ball.Geom").get(ValueParam<double>{"Radius"}) == 0.25);
  CHECK(comp(s, "Ball.Inertia").get(ValueParam<double>{"Density"}) == 2000);
  CHECK(comp(s, "Ball.Inertia").get(ValueParam<double>{"Mass"}) == -1);

  const Component& egg = comp(s, "Egg");
  CHECK(egg.get(ValueParam<bool>{"Triangles"}));
  CHECK(egg.get(ValueParam<int64_t>{"Accuracy"}) == 3);
  CHECK(egg.get(ValueParam<double>{"RadiusX"}) == 1.5);
  CHECK(egg.get(ValueParam<double>{"RadiusY"}) == 0.5);
  const Component& red = comp(s, "Red");
  CHECK(std::get<Color>(red.slot("Color").value()) == Color{{1, 0, 0, 1}, true});
  CHECK_FALSE(std::get<Color>(red.slot("Ambient").value()).valid);
  CHECK(red.get(EnumParam{"ColorMode"}) == 3);
  const Component& box = comp(s, "Box");
  CHECK(std::get<Cuboid>(box.slot("Cuboid").value()) == Cuboid{{-1, -2, -3}, {1, 2, 3}});
  CHECK(box.get(EnumParam{"SideMask"}) == (4u | 8u));
  // String escapes of 4.3: \t is a tab, \\ a backslash.
  CHECK(comp(s, "Wood").get(ValueParam<std::string>{"Texture"}) == "wood\tgrain\\1.bmp");
}

TEST_CASE("load: component parameters inline, by Ref and by Macro", "[scene][load]") {
  Scene s = mustLoad(R"(<Simulation>
  <ComponentList>
    <RCGenericMaterial Key="Rubber"><Friction Value="1.2"/></RCGenericMaterial>
    <RCMobileRigidBody Key="Ball">
      <Pose><RCGlobalCoordinates><Pose Value="0 1 0 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom Macro="NoGeom"/>
      <Model Macro="NoModel"/>
      <Motion Macro="NoMotion"/>
      <Material Ref="Rubber"/>
      <Inertia><RCGenericInertia><Mass Value="2"/></RCGenericInertia></Inertia>
    </RCMobileRigidBody>
    <RCStaticRigidBody Key="Wall">
      <Pose Ref="Ball.Pose"/>
      <Geom><RCCuboidGeom Key="Shape"><Width Value="3"/></RCCuboidGeom></Geom>
    </RCStaticRigidBody>
  </ComponentList>
</Simulation>)");
  const Component& ball = comp(s, "Ball");
  // Ref: the link names the target, no component is created for the slot.
  const Link& mat = ball.get(LinkParam{"Material"});
  CHECK(mat.ref == "Rubber");
  CHECK(mat.isRef());
  CHECK(mat.comp == s.find("Rubber"));
  CHECK(s.find("Ball.Material") < 0);
  CHECK(ball.slot("Material").set);
  // Macro: a component of the macro's type, keyed like an inline component without Key.
  const Link& geom = ball.get(LinkParam{"Geom"});
  CHECK(geom.macro == "NoGeom");
  CHECK_FALSE(geom.isRef());
  REQUIRE(geom.comp >= 0);
  CHECK(s.at(geom.comp).type->name == "RCEmptyGeom");
  CHECK(s.at(geom.comp).qkey == "Ball.Geom");
  CHECK(s.at(geom.comp).parent == s.find("Ball"));
  CHECK(s.at(ball.get(LinkParam{"Model"}).comp).type->name == "RCEmptyModel");
  CHECK(s.at(ball.get(LinkParam{"Motion"}).comp).type->name == "RCGlobalMotion");
  // Inline.
  const Component& inertia = s.at(ball.get(LinkParam{"Inertia"}).comp);
  CHECK(inertia.type->name == "RCGenericInertia");
  CHECK(inertia.get(ValueParam<double>{"Mass"}) == 2);
  CHECK(inertia.qkey == "Ball.Inertia");
  // An inline component without Key is keyed by the parameter name.
  const Component& pose = comp(s, "Ball.Pose");
  CHECK(pose.type->name == "RCGlobalCoordinates");
  CHECK(ball.slot("Pose").set);
  // Unset component parameters link to the shared default of their type (no key).
  const Component& wallModel = s.at(comp(s, "Wall").get(LinkParam{"Model"}).comp);
  CHECK(wallModel.type->name == "RCEmptyModel");
  CHECK(wallModel.qkey.empty());
  CHECK(ball.get(LinkParam{"Model"}).comp != comp(s, "Wall").get(LinkParam{"Model"}).comp);  // Ball's came from a Macro
  CHECK_FALSE(comp(s, "Wall").slot("Model").set);
  // An inline component with a Key is known under it; a Ref names any keyed component.
  const Component& wall = comp(s, "Wall");
  CHECK(comp(s, "Wall.Shape").get(ValueParam<double>{"Width"}) == 3);
  CHECK(wall.get(LinkParam{"Geom"}).comp == s.find("Wall.Shape"));
  CHECK(s.find("Wall.Geom") < 0);
  CHECK(wall.get(LinkParam{"Pose"}).comp == s.find("Ball.Pose"));
  CHECK(s.find("Wall.Pose") < 0);
}

TEST_CASE("load: list items as type elements, wrappers around a type element, and Refs", "[scene][load]") {
  Scene s = mustLoad(R"(<Simulation>
  <ComponentList>
    <RCCuboidModel Key="M">
      <ChildList>
        <RCEllipsoidModel/>
        <Child><RCConeModel Key="Cone"/></Child>
        <Child Ref="Other"/>
        <Child Macro="NoModel"/>
      </ChildList>
    </RCCuboidModel>
    <Component><RCGround/></Component>
    <Component><RCCylinderModel Key="Other"/></Component>
  </ComponentList>
</Simulation>)");
  REQUIRE(s.components.size() == 3);
  CHECK(s.at(s.components[0].comp).qkey == "M");
  CHECK(s.at(s.components[1].comp).type->name == "RCGround");
  CHECK(s.at(s.components[1].comp).qkey == "RCGround");  // no Key: the type name
  CHECK_FALSE(s.at(s.components[1].comp).has_key);
  CHECK(s.at(s.components[2].comp).qkey == "Other");
  const std::vector<Link>& kids = comp(s, "M").get(ListParam{"ChildList"});
  REQUIRE(kids.size() == 4);
  CHECK(s.at(kids[0].comp).type->name == "RCEllipsoidModel");
  CHECK(s.at(kids[0].comp).qkey == "M.RCEllipsoidModel");
  CHECK(s.at(kids[1].comp).qkey == "M.Cone");
  CHECK(kids[2].ref == "Other");
  CHECK(kids[2].comp == s.find("Other"));
  CHECK(kids[3].macro == "NoModel");
  CHECK(s.at(kids[3].comp).type->name == "RCEmptyModel");
  CHECK(s.at(kids[3].comp).qkey == "M.RCEmptyModel");
  CHECK(comp(s, "M").slot("ChildList").set);
  CHECK(comp(s, "M.Cone").parent == s.find("M"));
}

// The key index holds component indices and compares the components' own keys: every key
// added is found again through the table's growth (64 slots, doubled at half full), a second
// component with a key already taken is refused with the first one's index, and a key that
// shares a prefix or a hash bucket with others is not mistaken for them.
TEST_CASE("load: the key index finds every key through its growth and refuses a second", "[scene][load]") {
  std::vector<Component> comps(1000);
  for (size_t i = 0; i < comps.size(); ++i) comps[i].qkey = "Box" + std::to_string(i) + ".Pose";
  KeyIndex index;
  for (int i = 0; i < 1000; ++i) REQUIRE(index.insert(i, comps) == -1);
  CHECK(index.size() == 1000);
  for (int i = 0; i < 1000; ++i) CHECK(index.find("Box" + std::to_string(i) + ".Pose", comps) == i);
  CHECK(index.find("Box1000.Pose", comps) == -1);
  CHECK(index.find("Box1", comps) == -1);
  CHECK(index.find("", comps) == -1);
  comps.emplace_back();
  comps.back().qkey = "Box7.Pose";
  CHECK(index.insert(1000, comps) == 7);
  CHECK(index.size() == 1000);
  std::vector<int> all = index.indices();
  std::sort(all.begin(), all.end());
  REQUIRE(all.size() == 1000);
  for (int i = 0; i < 1000; ++i) CHECK(all[static_cast<size_t>(i)] == i);
  CHECK(KeyIndex().find("A", comps) == -1);
}

TEST_CASE("load: fully qualified keys of nested components", "[scene][load]") {
  Scene s = mustLoad(R"(<Simulation>
  <ComponentList>
    <RCConstruction Key="Robot">
      <Body><RCMobileRigidBody Key="Base"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody></Body>
      <ChildList>
        <RCHingeJoint Key="Shoulder">
          <Body>
            <RCConstruction Key="Arm">
              <Body><RCMobileRigidBody Key="Upper"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody></Body>
              <ChildList>
                <RCBallSocketJoint>
                  <Body><RCMobileRigidBody Key="Hand"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody></Body>
                </RCBallSocketJoint>
              </ChildList>
            </RCConstruction>
          </Body>
        </RCHingeJoint>
        <RCGenericDrive Key="Motor"><Joint Ref="Robot.Shoulder"/></RCGenericDrive>
      </ChildList>
    </RCConstruction>
  </ComponentList>
</Simulation>)");
  for (const char* k :
       {"Robot", "Robot.Base", "Robot.Base.Geom", "Robot.Shoulder", "Robot.Shoulder.Arm", "Robot.Shoulder.Arm.Upper",
        "Robot.Shoulder.Arm.RCBallSocketJoint", "Robot.Shoulder.Arm.RCBallSocketJoint.Hand", "Robot.Motor"}) {
    INFO(k);
    CHECK(s.find(k) >= 0);
  }
  // Left-out parameters take one shared default component per type, which has no key.
  for (const char* k :
       {"Robot.Base.Pose", "Robot.Base.Inertia", "Robot.Shoulder.Arm.RCBallSocketJoint.Hand.Material"}) {
    INFO(k);
    CHECK(s.find(k) < 0);
  }
  // The joint's Pose has no default: nothing is created for it.
  CHECK(s.find("Robot.Shoulder.Pose") < 0);
  CHECK(comp(s, "Robot.Motor").get(LinkParam{"Joint"}).comp == s.find("Robot.Shoulder"));
  // by_qkey and the components agree; parents are the owning components.
  for (const std::string& k : s.sortedKeys()) CHECK(s.at(s.find(k)).qkey == k);
  const Component& hand = comp(s, "Robot.Shoulder.Arm.RCBallSocketJoint.Hand");
  CHECK(s.at(hand.parent).qkey == "Robot.Shoulder.Arm.RCBallSocketJoint");
  CHECK(hand.key() == "Hand");
}

TEST_CASE("load: CameraList with RC names and the guide's aliases", "[scene][load]") {
  Scene s = mustLoad(R"(<Simulation>
  <CameraList>
    <StaticCamera Key="Front">
      <ViewAngle Value="45"/>
      <Pose><RCGlobalCoordinates><Pose Value="0 1 10 0 0 0"/></RCGlobalCoordinates></Pose>
    </StaticCamera>
    <RCTrackingCamera Key="Chase"><Body Ref="Ball"/><Distance Value="3"/></RCTrackingCamera>
  </CameraList>
  <ComponentList>
    <RCMobileRigidBody Key="Ball"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody>
  </ComponentList>
</Simulation>)");
  REQUIRE(s.cameras.size() == 2);
  const Component& front = s.at(s.cameras[0].comp);
  CHECK(front.type->name == "RCStaticCamera");
  CHECK(front.qkey == "Front");
  CHECK(front.get(ValueParam<double>{"ViewAngle"}) == 45);
  CHECK(front.get(ValueParam<double>{"FarClip"}) == 1000);
  const Component& chase = s.at(s.cameras[1].comp);
  CHECK(chase.type->name == "RCTrackingCamera");
  CHECK(chase.get(LinkParam{"Body"}).comp == s.find("Ball"));
  CHECK(chase.get(ValueParam<double>{"Distance"}) == 3);
}

TEST_CASE("load: a scene without settings, cameras or components", "[scene][load]") {
  Scene s = mustLoad("<Simulation/>");
  CHECK(s.components.empty());
  CHECK(s.cameras.empty());
  REQUIRE(s.settings >= 0);  // defaults apply
  CHECK(s.at(s.settings).get(ValueParam<double>{"MaxTimeStep"}) == 0.001);
  CHECK(s.files == std::vector<std::string>{"test.xml"});
  CHECK(s.content_hash.size() == 16);
}

// The content hash (docs/formats.md, "fnv1a64w") is pinned: a summary's scene_hash must not
// change between builds or hosts for the same bytes. Values computed by hand from the definition
// (FNV-1a's step over little-endian 8-byte words, h ^= h >> 32 after each, the tail byte-wise).
TEST_CASE("load: the content hash of known bytes", "[scene][load]") {
  auto hashOf = [](const std::string& text) {
    Scene s;
    Diagnostics d;
    REQUIRE(loadSceneFromText(text, "test.xml", Format::Xml, testRegistry(), &s, d));
    return s.content_hash;
  };
  auto reference = [](const std::string& bytes) {
    uint64_t h = 1469598103934665603ull;
    size_t i = 0;
    for (; i + 8 <= bytes.size(); i += 8) {
      uint64_t w = 0;
      for (int k = 7; k >= 0; --k) w = (w << 8) | static_cast<unsigned char>(bytes[i + static_cast<size_t>(k)]);
      h = (h ^ w) * 1099511628211ull;
      h ^= h >> 32;
    }
    for (; i < bytes.size(); ++i) h = (h ^ static_cast<unsigned char>(bytes[i])) * 1099511628211ull;
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
    return std::string(hex);
  };
  const std::string text = "<Simulation/>";  // one word and five tail bytes
  CHECK(hashOf(text) == reference(text));
  CHECK(hashOf(text) == "f97199525c9dcf19");
  // A change in a word's high byte (which FNV's multiply alone would keep out of the low bits) changes it.
  // Byte 23 is the high byte of the third word.
  const std::string a = "<Simulation><!--abcdefgh--></Simulation>", b = "<Simulation><!--abcdefgX--></Simulation>";
  CHECK(a[23] == 'h');
  CHECK(hashOf(a) == reference(a));
  CHECK(hashOf(a) != hashOf(b));
  CHECK(hashOf("<Simulation/> ") != hashOf(text));
}

// ---------------------------------------------------------------------------------- INI (4.1)

TEST_CASE("load: INI sections, dotted keys, lists, Type/Key, case-insensitive keys, quotes", "[scene][load][ini]") {
  const char* ini = R"(; a comment
# another comment
componentcount = 5

[SceneSettings]
Gravity = 0 0 -9.81
MAXTIMESTEP = 0.002
fogsettings.mode = Linear

[Component0]
Type = RCMobileRigidBody
Key = Ball
Pose.Type = RCGlobalCoordinates
Pose.Pose = 1 2 3 0 0 0
geom.type = rcspheregeom
Geom.RADIUS = 0.25
Material.Ref = Rubber
Model.Macro = nomodel

[component1]
TYPE = RCGenericMaterial
key = Rubber
friction = 1.2

[Component2]
Type = RCCuboidModel
Key = M
ChildCount = 2
Child0.Type = RCConeModel
Child0.Key = Cone
Child0.Radius = 2
Child1.Ref = Other

[Component3]
Type = RCTexturedSkin
Key = " padded key "
Texture = ""

[Component4]
Type = RCCylinderModel
Key = Other
)";
  Scene s = mustLoad(ini, Format::Ini, "test.ini");

  const char* xml = R"(<Simulation>
  <SceneSettings>
    <Gravity Value="0 0 -9.81"/>
    <MaxTimeStep Value="0.002"/>
    <FogSettings><Mode Value="Linear"/></FogSettings>
  </SceneSettings>
  <ComponentList>
    <RCMobileRigidBody Key="Ball">
      <Pose><RCGlobalCoordinates><Pose Value="1 2 3 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCSphereGeom><Radius Value="0.25"/></RCSphereGeom></Geom>
      <Material Ref="Rubber"/>
      <Model Macro="nomodel"/>
    </RCMobileRigidBody>
    <RCGenericMaterial Key="Rubber"><Friction Value="1.2"/></RCGenericMaterial>
    <RCCuboidModel Key="M">
      <ChildList>
        <RCConeModel Key="Cone"><Radius Value="2"/></RCConeModel>
        <Child Ref="Other"/>
      </ChildList>
    </RCCuboidModel>
    <RCTexturedSkin Key=" padded key "><Texture Value=""/></RCTexturedSkin>
    <RCCylinderModel Key="Other"/>
  </ComponentList>
</Simulation>)";
  Scene x = mustLoad(xml);
  requireSameGraph(s, x);

  CHECK(comp(s, "Ball.Geom").type->name == "RCSphereGeom");
  CHECK(comp(s, "Ball.Geom").get(ValueParam<double>{"Radius"}) == 0.25);
  CHECK(comp(s, "Ball").get(LinkParam{"Material"}).comp == s.find("Rubber"));
  CHECK(s.at(s.settings).get(ValueParam<Triple>{"Gravity"}) == Triple{0, 0, -9.81});
  CHECK(s.at(s.at(s.settings).get(LinkParam{"FogSettings"}).comp).get(EnumParam{"Mode"}) == 1);
  CHECK(comp(s, "M.Cone").get(ValueParam<double>{"Radius"}) == 2);
  CHECK(comp(s, "M").get(ListParam{"ChildList"})[1].comp == s.find("Other"));
  // Quotes keep leading and trailing blanks and allow empty values.
  const Component& skin = comp(s, " padded key ");
  CHECK(skin.slot("Texture").set);
  CHECK(skin.get(ValueParam<std::string>{"Texture"}).empty());
  // Lines are the lines of the assignments.
  CHECK(comp(s, "Ball.Geom").slot("Radius").loc.line == 16);
  CHECK(comp(s, "Ball.Geom").slot("Radius").loc.file == "test.ini");
}

TEST_CASE("load: INI without sections and with the global section after items", "[scene][load][ini]") {
  Scene s = mustLoad(R"(Component0.Type = RCGround
Component0.Extension = 50
CameraCount = 1
Camera0.Type = StaticCamera
Camera0.Key = Main
ComponentCount = 1
SceneSettings.ERP = 0.5
)",
                     Format::Ini, "flat.ini");
  REQUIRE(s.components.size() == 1);
  CHECK(comp(s, "RCGround").get(ValueParam<double>{"Extension"}) == 50);
  REQUIRE(s.cameras.size() == 1);
  CHECK(s.at(s.cameras[0].comp).type->name == "RCStaticCamera");
  CHECK(comp(s, "Main").type->name == "RCStaticCamera");
  CHECK(s.at(s.settings).get(ValueParam<double>{"ERP"}) == 0.5);
}

TEST_CASE("load: INI sections may name nested components and come in any order", "[scene][load][ini]") {
  Scene s = mustLoad(R"(ComponentCount = 1
[Component0.Geom]
Radius = 0.3
type = RCSphereGeom
[Component0]
Key = Wall
Type = RCStaticRigidBody
Pose.Type = RCGlobalCoordinates
[component0.POSE]
Pose = 1 0 0 0 0 0
)",
                     Format::Ini, "sections.ini");
  CHECK(comp(s, "Wall.Geom").type->name == "RCSphereGeom");
  CHECK(comp(s, "Wall.Geom").get(ValueParam<double>{"Radius"}) == 0.3);
  CHECK(comp(s, "Wall.Geom").slot("Radius").loc.line == 3);
  CHECK(comp(s, "Wall.Pose").get(ValueParam<Pose>{"Pose"}) == Pose{{1, 0, 0}, {0, 0, 0}});
  Scene x = mustLoad(R"(<Simulation><ComponentList><RCStaticRigidBody Key="Wall">
    <Pose><RCGlobalCoordinates><Pose Value="1 0 0 0 0 0"/></RCGlobalCoordinates></Pose>
    <Geom><RCSphereGeom><Radius Value="0.3"/></RCSphereGeom></Geom>
    </RCStaticRigidBody></ComponentList></Simulation>)");
  requireSameGraph(s, x);
}

TEST_CASE("load: loadScene picks the format from the file name", "[scene][load][ini]") {
  TempDir dir;
  std::string ini = dir.write("scene.INI", "ComponentCount = 1\nComponent0.Type = RCSky\nComponent0.Height = 7\n");
  std::string xml = dir.write("scene.xml",
                              "<Simulation><ComponentList><RCSky><Height Value=\"7\"/></RCSky>"
                              "</ComponentList></Simulation>");
  Scene a, b;
  Diagnostics da, db;
  REQUIRE(loadScene(ini, testRegistry(), &a, da));
  REQUIRE(loadScene(xml, testRegistry(), &b, db));
  requireSameGraph(a, b);
  CHECK(comp(a, "RCSky").get(ValueParam<double>{"Height"}) == 7);
  CHECK(a.path == ini);
  CHECK(a.files == std::vector<std::string>{ini});
  // Different bytes, different hash.
  CHECK(a.content_hash != b.content_hash);
}

TEST_CASE("load: loadStructIni reads the global settings INI", "[scene][load][ini]") {
  TempDir dir;
  std::string path = dir.write("settings.ini", "; global settings\nTextureFolder = \" textures \"\nDocumentIni = on\n");
  Scene holder;
  int c = -1;
  Diagnostics d;
  REQUIRE(loadStructIni(path, testRegistry(), "GlobalSettings", &holder, &c, d));
  REQUIRE(c >= 0);
  CHECK(holder.at(c).get(ValueParam<std::string>{"TextureFolder"}) == " textures ");
  CHECK(holder.at(c).get(ValueParam<bool>{"DocumentIni"}));
  CHECK(holder.at(c).get(ValueParam<std::string>{"LogFile"}).empty());

  std::string bad = dir.write("bad.ini", "TextureFolder = x\nTexturFolder = y\n");
  Diagnostics d2;
  CHECK_FALSE(loadStructIni(bad, testRegistry(), "GlobalSettings", &holder, &c, d2));
  REQUIRE(d2.errors().size() == 1);
  CHECK(d2.errors()[0].str() ==
        bad + ":2: GlobalSettings: parameter 'TexturFolder' unknown (did you mean 'TextureFolder'?)");

  Diagnostics d3;
  CHECK_FALSE(loadStructIni((dir.path() / "missing.ini").string(), testRegistry(), "GlobalSettings", &holder, &c, d3));
  REQUIRE(d3.errors().size() == 1);
  CHECK(d3.errors()[0].kind == ErrorKind::MissingInput);
}

// ---------------------------------------------------------------------------------- imports

namespace {

struct ImportFixture {
  TempDir dir;
  std::string main;
  ImportFixture() {
    main = dir.write("main.xml", R"(<Simulation>
  <ComponentList>
    <RCImportRefList Key="Materials"><File Value="lib/materials.xml"/></RCImportRefList>
    <RCImportBody Key="Ball1">
      <File Value="parts/ball.xml"/>
      <Pose><RCGlobalCoordinates><Pose Value="5 0 0 0 0 0"/></RCGlobalCoordinates></Pose>
    </RCImportBody>
    <RCImportBody Key="Ball2"><File Value="parts/ball.xml"/></RCImportBody>
    <RCConstruction Key="Arm">
      <Body><RCStaticRigidBody Key="Base"/></Body>
      <ChildList>
        <RCImportJoint Key="J"><File Value="parts/joint.xml"/></RCImportJoint>
      </ChildList>
    </RCConstruction>
    <RCStaticRigidBody Key="Floor">
      <Geom><RCCuboidGeom/></Geom>
      <Material Ref="Materials.Rubber"/>
    </RCStaticRigidBody>
  </ComponentList>
</Simulation>
)");
    dir.write("lib/materials.xml", R"(<?xml version="1.0"?>
<RefList>
  <RCGenericMaterial Key="Rubber"><Friction Value="1.5"/></RCGenericMaterial>
  <RCColoredSkin Key="Red"><Color Value="1 0 0"/></RCColoredSkin>
  <Model><RCCuboidModel Key="Crate"/></Model>
</RefList>
)");
    dir.write("parts/ball.xml", R"(<Body>
  <RCMobileRigidBody Key="Ball">
    <Pose><RCGlobalCoordinates><Pose Value="0 1 0 0 0 0"/></RCGlobalCoordinates></Pose>
    <Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom>
    <Material Ref="Materials.Rubber"/>
  </RCMobileRigidBody>
</Body>
)");
    // Relative to parts/joint.xml, not to main.xml.
    dir.write("parts/joint.xml", R"(<Joint>
  <RCHingeJoint Key="Hinge">
    <Pose><RCLocalCoordinates><Pose Value="0 0 1 0 0 0"/></RCLocalCoordinates></Pose>
    <Body><RCImportBody Key="Link"><File Value="sub/link.xml"/></RCImportBody></Body>
  </RCHingeJoint>
</Joint>
)");
    dir.write("parts/sub/link.xml", R"(<Body>
  <RCMobileRigidBody Key="L">
    <Pose><RCLocalCoordinates><Pose Value="0 -1 0 0 0 0"/></RCLocalCoordinates></Pose>
    <Geom><RCCuboidGeom/></Geom>
  </RCMobileRigidBody>
</Body>
)");
  }
};

}  // namespace

TEST_CASE("load: RCImportBody, RCImportJoint and RCImportRefList read their files", "[scene][load][import]") {
  ImportFixture fx;
  Scene s;
  Diagnostics d;
  bool ok = loadScene(fx.main, testRegistry(), &s, d);
  INFO(errorText(d));
  REQUIRE(ok);

  // Imported components hang below the importing component.
  const Component& mats = comp(s, "Materials");
  REQUIRE(mats.imported.size() == 3);
  CHECK(s.at(mats.imported[0]).qkey == "Materials.Rubber");
  CHECK(s.at(mats.imported[1]).qkey == "Materials.Red");
  CHECK(s.at(mats.imported[2]).qkey == "Materials.Crate");  // wrapper element around a type element
  CHECK(comp(s, "Materials.Rubber").get(ValueParam<double>{"Friction"}) == 1.5);
  CHECK(comp(s, "Materials.Rubber").parent == s.find("Materials"));
  CHECK(comp(s, "Materials.Rubber").loc.file == (fx.dir.path() / "lib/materials.xml").string());
  CHECK(comp(s, "Materials.Rubber").loc.line == 3);

  const Component& b1 = comp(s, "Ball1");
  REQUIRE(b1.imported.size() == 1);
  CHECK(b1.imported[0] == s.find("Ball1.Ball"));
  CHECK(comp(s, "Ball1.Ball.Geom").get(ValueParam<double>{"Radius"}) == 0.1);
  // The same file imported twice gives two independent copies.
  CHECK(s.find("Ball2.Ball") >= 0);
  CHECK(s.find("Ball2.Ball") != s.find("Ball1.Ball"));
  // Refs into an imported RefList, from the scene and from another import.
  CHECK(comp(s, "Floor").get(LinkParam{"Material"}).comp == s.find("Materials.Rubber"));
  CHECK(comp(s, "Ball1.Ball").get(LinkParam{"Material"}).comp == s.find("Materials.Rubber"));

  const Component& j = comp(s, "Arm.J");
  REQUIRE(j.imported.size() == 1);
  CHECK(s.at(j.imported[0]).qkey == "Arm.J.Hinge");
  // An import inside an import, resolved relative to the importing file.
  const Component& link = comp(s, "Arm.J.Hinge.Link");
  REQUIRE(link.imported.size() == 1);
  CHECK(s.at(link.imported[0]).qkey == "Arm.J.Hinge.Link.L");
  CHECK(comp(s, "Arm.J.Hinge.Link.L").loc.file == (fx.dir.path() / "parts/sub/link.xml").string());

  // Every file read is listed once per read, the scene first.
  REQUIRE(s.files.size() == 6);
  CHECK(s.files[0] == fx.main);
  auto listed = [&](const std::string& rel) {
    return std::count(s.files.begin(), s.files.end(), (fx.dir.path() / rel).lexically_normal().string());
  };
  CHECK(listed("lib/materials.xml") == 1);
  CHECK(listed("parts/ball.xml") == 2);
  CHECK(listed("parts/joint.xml") == 1);
  CHECK(listed("parts/sub/link.xml") == 1);

  // The content hash covers the imports: changing an imported file changes it.
  std::string hash = s.content_hash;
  fx.dir.write("parts/sub/link.xml", readText((fx.dir.path() / "parts/sub/link.xml").string()) + "\n");
  Scene s2;
  Diagnostics d2;
  REQUIRE(loadScene(fx.main, testRegistry(), &s2, d2));
  CHECK(s2.content_hash != hash);
  requireSameGraph(s, s2);
}

TEST_CASE("load: loadSceneFromText resolves imports relative to the given name", "[scene][load][import]") {
  ImportFixture fx;
  Scene a, b;
  Diagnostics da, db;
  REQUIRE(loadScene(fx.main, testRegistry(), &a, da));
  REQUIRE(loadSceneFromText(readText(fx.main), fx.main, Format::Xml, testRegistry(), &b, db));
  requireSameGraph(a, b);
  CHECK(a.content_hash == b.content_hash);
}

TEST_CASE("load: absolute import paths", "[scene][load][import]") {
  TempDir dir;
  std::string part = dir.write("elsewhere/part.xml", "<Body><RCStaticRigidBody Key=\"P\"/></Body>");
  std::string main = dir.write("scenes/main.xml", "<Simulation><ComponentList><RCImportBody Key=\"I\"><File Value=\"" +
                                                      part + "\"/></RCImportBody></ComponentList></Simulation>");
  Scene s;
  Diagnostics d;
  REQUIRE(loadScene(main, testRegistry(), &s, d));
  CHECK(comp(s, "I.P").type->name == "RCStaticRigidBody");
}

// ---------------------------------------------------------------------------------- round trips

namespace {

/// A scene with one component of every registered type that needs no file (imports are tested
/// with files), each in a place where its family is accepted.
std::string everyTypeScene() {
  const Registry& reg = testRegistry();
  std::string cameras, components, geoms, joints, peripheries, controllers, poses, motions, inertias;
  int n = 0;
  for (const TypeSpec& t : reg.types()) {
    if (!t.import_root.empty()) continue;
    std::string key = "K" + std::to_string(n++);
    std::string el = "<" + t.name + " Key=\"" + key + "\"/>";
    switch (t.family) {
      case Family::Body:
        if (t.name == "RigidBodyClone")
          components += "<RigidBodyClone Key=\"" + key + "\"><Original Value=\"Root\"/></RigidBodyClone>";
        else
          components += el;
        break;
      case Family::GlobalSim:
      case Family::Material:
      case Family::Skin:
      case Family::Model:
        components += el;
        break;
      case Family::Geom:
        geoms += "<RCStaticRigidBody Key=\"G" + key + "\"><Geom>" + el + "</Geom></RCStaticRigidBody>";
        break;
      case Family::Joint:
        joints += el;
        break;
      case Family::Periphery:
        peripheries += el;
        break;
      case Family::Controller:
        controllers += el;
        break;
      case Family::Camera:
        cameras += el;
        break;
      case Family::Pose:
        poses += "<RCStaticRigidBody Key=\"P" + key + "\"><Pose>" + el + "</Pose></RCStaticRigidBody>";
        break;
      case Family::Motion:
        motions += "<RCMobileRigidBody Key=\"M" + key + "\"><Motion>" + el + "</Motion></RCMobileRigidBody>";
        break;
      case Family::Inertia:
        inertias += "<RCMobileRigidBody Key=\"I" + key + "\"><Inertia>" + el + "</Inertia></RCMobileRigidBody>";
        break;
      case Family::Struct:
        break;
    }
  }
  return "<Simulation><CameraList>" + cameras + "</CameraList><ComponentList>" + components + geoms + poses + motions +
         inertias + "<RCConstruction Key=\"Root\"><Body><RCStaticRigidBody/></Body><ChildList>" + joints + peripheries +
         "</ChildList></RCConstruction><RCRobot Key=\"Bot\"><ControllerList>" + controllers +
         "</ControllerList></RCRobot></ComponentList></Simulation>";
}

const char* kTrickyStrings = R"(<Simulation>
  <ComponentList>
    <RCTexturedSkin Key="a=b c"><Texture Value=" padded "/></RCTexturedSkin>
    <RCTexturedSkin Key="Quoted"><Texture Value="&quot;x&quot;"/></RCTexturedSkin>
    <RCTexturedSkin Key="Empty"><Texture Value=""/></RCTexturedSkin>
    <RCTexturedSkin Key="Special"><Texture Value="; not a comment # either = [x] \n tab\t \\ &lt;&amp;&gt;"/></RCTexturedSkin>
    <RCTexturedSkin Key="Quote"><Texture Value="&quot;"/></RCTexturedSkin>
    <RCColTexSkin Key="Negative"><Color Value="-0 0.1 1e-300 1"/><Shininess Value="-0"/></RCColTexSkin>
    <RCConstruction Key="C">
      <ChildList>
        <RCGenericDrive Key="Limits"><MinPos Value="-infinite"/><MaxPos Value="+Infinite"/></RCGenericDrive>
      </ChildList>
    </RCConstruction>
  </ComponentList>
</Simulation>)";

void checkRoundTrip(const std::string& xml, const std::string& name) {
  Scene s1 = mustLoad(xml, Format::Xml, name);
  for (bool fill : {false, true}) {
    INFO(name << (fill ? " (fill defaults)" : " (as written)"));
    std::string x1 = writeScene(s1, Format::Xml, fill);
    std::string i1 = writeScene(s1, Format::Ini, fill);
    INFO("XML:\n" << x1 << "\nINI:\n" << i1);
    REQUIRE_FALSE(x1.empty());
    // XML -> graph -> INI -> graph -> XML gives the same XML.
    Scene s2 = mustLoad(i1, Format::Ini, name);
    CHECK(writeScene(s2, Format::Xml, fill) == x1);
    CHECK(writeScene(s2, Format::Ini, fill) == i1);
    // Parse -> write -> parse gives the same graph (writing everything marks everything set).
    Scene s3 = mustLoad(x1, Format::Xml, name);
    CHECK(writeScene(s3, Format::Xml, fill) == x1);
    if (!fill) {
      requireSameGraph(s1, s2);
      requireSameGraph(s1, s3);
    } else {
      requireSameGraph(s2, s3);
      Scene s4 = mustLoad(writeScene(s3, Format::Xml, false), Format::Xml, name);
      requireSameGraph(s3, s4);
    }
  }
}

}  // namespace

TEST_CASE("load: round trips of every scene in scenes/", "[scene][load][roundtrip]") {
  std::filesystem::path dir = std::filesystem::path(SIMBOB_SOURCE_DIR) / "scenes";
  std::vector<std::string> paths;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".xml") paths.push_back(e.path().string());
  std::sort(paths.begin(), paths.end());
  REQUIRE_FALSE(paths.empty());
  for (const std::string& p : paths) {
    INFO(p);
    checkRoundTrip(readText(p), p);
  }
}

TEST_CASE("load: round trips of the inline scenes", "[scene][load][roundtrip]") {
  checkRoundTrip(kValuesScene, "values.xml");
  checkRoundTrip(everyTypeScene(), "every.xml");
  checkRoundTrip(kTrickyStrings, "tricky.xml");
  checkRoundTrip(R"(<Simulation>
  <SceneSettings/>
  <CameraList/>
  <ComponentList>
    <RCCuboidModel Key="M">
      <ChildList>
        <RCEllipsoidModel/>
        <Child><RCConeModel Key="Cone"/></Child>
        <Child Ref="Other"/>
        <Child Macro="NoModel"/>
      </ChildList>
    </RCCuboidModel>
    <RCCylinderModel Key="Other"><ChildList/></RCCylinderModel>
    <RCMobileRigidBody Key="Ball">
      <Geom Macro="NoGeom"/>
      <Material Ref="Rubber"/>
      <Inertia><RCGenericInertia><Inertia Value="1 0.1 0 0.1 2 0 0 0 3"/></RCGenericInertia></Inertia>
      <Model Ref="M"/>
    </RCMobileRigidBody>
    <RCGenericMaterial Key="Rubber"/>
  </ComponentList>
</Simulation>)",
                 "lists.xml");
}

TEST_CASE("load: round trip of a scene with imports keeps the File parameters", "[scene][load][roundtrip][import]") {
  ImportFixture fx;
  checkRoundTrip(readText(fx.main), fx.main);
  Scene s = mustLoad(readText(fx.main), Format::Xml, fx.main);
  std::string x = writeScene(s, Format::Xml, false);
  CHECK(x.find("<File Value=\"parts/ball.xml\" />") != std::string::npos);
  // Imported components are not written into the scene.
  CHECK(x.find("Rubber") != std::string::npos);  // the Ref
  CHECK(x.find("<RCGenericMaterial") == std::string::npos);
}

TEST_CASE("load: the writers' exact output for a small scene", "[scene][load][roundtrip]") {
  Scene s = mustLoad(R"(<Simulation>
  <ComponentList>
    <RCMobileRigidBody Key="Ball">
      <Geom><RCSphereGeom><Radius Value="0.50"/></RCSphereGeom></Geom>
      <Material Ref="Rubber"/>
    </RCMobileRigidBody>
    <RCCuboidModel Key="M"><ChildList><Child Ref="M2"/></ChildList></RCCuboidModel>
    <RCCuboidModel Key="M2"/>
    <RCGenericMaterial Key="Rubber"/>
  </ComponentList>
</Simulation>)");
  CHECK(writeScene(s, Format::Xml, false) == R"(<?xml version="1.0" encoding="UTF-8"?>
<Simulation>
  <ComponentList>
    <RCMobileRigidBody Key="Ball">
      <Geom>
        <RCSphereGeom>
          <Radius Value="0.5" />
        </RCSphereGeom>
      </Geom>
      <Material Ref="Rubber" />
    </RCMobileRigidBody>
    <RCCuboidModel Key="M">
      <ChildList>
        <Child Ref="M2" />
      </ChildList>
    </RCCuboidModel>
    <RCCuboidModel Key="M2" />
    <RCGenericMaterial Key="Rubber" />
  </ComponentList>
</Simulation>
)");
  CHECK(writeScene(s, Format::Ini, false) == R"(ComponentCount = 4

Component0.Type = RCMobileRigidBody
Component0.Key = Ball
Component0.Geom.Type = RCSphereGeom
Component0.Geom.Radius = 0.5
Component0.Material.Ref = Rubber

Component1.Type = RCCuboidModel
Component1.Key = M
Component1.ChildCount = 1
Component1.Child0.Ref = M2

Component2.Type = RCCuboidModel
Component2.Key = M2

Component3.Type = RCGenericMaterial
Component3.Key = Rubber
)");
  // With defaults filled in, default components are written without Key.
  std::string full = writeScene(s, Format::Xml, true);
  CHECK(full.find("<Pose>\n        <RCGlobalCoordinates>\n          <Pose Value=\"0 0 0 0 0 0\" />") !=
        std::string::npos);
  CHECK(full.find("<MaxTimeStep Value=\"0.001\" />") != std::string::npos);
  CHECK(full.find("<CameraList />") != std::string::npos);
  CHECK(full.find("Key=\"Pose\"") == std::string::npos);
}

TEST_CASE("load: the DocumentIni beside a scene has the scene's name with .ini", "[scene][load]") {
  CHECK(documentIniPath("robot.xml") == "robot.ini");
  CHECK(documentIniPath("scenes/v1.2/robot.xml") == "scenes/v1.2/robot.ini");
  // A dot in a folder is no extension; a name without one gets .ini appended.
  CHECK(documentIniPath("scenes/v1.2/robot") == "scenes/v1.2/robot.ini");
  CHECK(documentIniPath(".hidden") == ".hidden.ini");
  // An INI scene would be its own DocumentIni: there is none.
  CHECK(documentIniPath("robot.ini").empty());
}
