// Tests of the component registry against the user guide (chapter 6, cameras of 3.5): every
// documented type is registered in the right family with the documented parameters, family
// parameters are inherited, tables are consistent, defaults round-trip, suggestions work.
#include <catch2/catch.hpp>

#include <algorithm>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "test_registry.h"
#include "simbob/name_table.h"
#include "simbob/registry.h"
#include "simbob/values.h"

using namespace simbob;

namespace {

struct GuideType {
  const char* name;
  Family family;
  std::vector<const char*> params;  // the parameters the guide documents (own and inherited)
};

// Chapter 6 of the guide, type by type, with the parameter names as documented ("Sub Geom" is
// spelled SubGeom, as every other parameter name). Cameras from 3.5.
const std::vector<GuideType>& guideTypes() {
  static const std::vector<GuideType> types = {
      // 6.1 BodyComponents
      {"RCStaticRigidBody", Family::Body, {"Pose", "Geom", "Material", "Model"}},
      {"RCMobileRigidBody", Family::Body, {"Pose", "Motion", "Geom", "Inertia", "Material", "Model"}},
      {"RCRodBody",
       Family::Body,
       {"Pos1", "Pos2", "Radius", "Capped", "HullPositions", "Motion", "Mass", "Material", "Skin"}},
      {"RCConstruction", Family::Body, {"Body", "ChildList"}},
      {"RCImportBody", Family::Body, {"Pose", "Motion", "File"}},
      {"RigidBodyClone", Family::Body, {"Pose", "Original"}},
      // 6.2 GlobalSimComponents
      {"RCGround", Family::GlobalSim, {"Material", "Skin", "Extension", "TexScale", "MaxCellSize"}},
      {"RCSky",
       Family::GlobalSim,
       {"Material", "Skin", "Extension", "Height", "TexScale", "MaxCellSize", "MotionX", "MotionY"}},
      {"RCSandBox", Family::GlobalSim, {"Width", "Depth", "Thickness", "Height", "Wall", "TexScale", "Material"}},
      {"RCRobot", Family::GlobalSim, {"Construction", "ControllerList"}},
      {"RCImportRefList", Family::GlobalSim, {"File"}},
      // 6.3 ModelComponents (Pose, Skin, ChildList common to all)
      {"RCCuboidModel", Family::Model, {"Pose", "Skin", "ChildList", "Cuboid", "TexScale", "SideMask", "Wire"}},
      {"RCPlaneModel",
       Family::Model,
       {"Pose", "Skin", "ChildList", "ExtensionX", "ExtensionY", "IsShadowPlane", "TexScale", "MaxCellSize"}},
      {"RCEllipsoidModel",
       Family::Model,
       {"Pose", "Skin", "ChildList", "Triangles", "Accuracy", "RadiusX", "RadiusY", "RadiusZ"}},
      {"RCCylinderModel",
       Family::Model,
       {"Pose", "Skin", "ChildList", "Radius", "Length", "AngTexScale", "LinTexScale", "ComponentMask", "Accuracy"}},
      {"RCConeModel",
       Family::Model,
       {"Pose", "Skin", "ChildList", "Radius", "Length", "LinTexScale", "DrawBase", "Accuracy"}},
      {"RCEmptyModel", Family::Model, {"Pose", "Skin", "ChildList"}},
      // 6.4 SkinComponents
      {"RCColoredSkin",
       Family::Skin,
       {"Color", "Ambient", "Diffuse", "Specular", "Emission", "ColorMode", "Shininess"}},
      {"RCTexturedSkin", Family::Skin, {"Texture", "ColorMode", "Shininess"}},
      {"RCColTexSkin",
       Family::Skin,
       {"Color", "Ambient", "Diffuse", "Specular", "Emission", "Texture", "ColorMode", "Shininess"}},
      // 6.5 GeomComponents
      {"RCTransformGeom", Family::Geom, {"Pose", "SubGeom"}},
      {"RCCuboidGeom", Family::Geom, {"Width", "Height", "Depth"}},
      {"RCPlaneGeom", Family::Geom, {"Pose"}},
      {"RCSphereGeom", Family::Geom, {"Radius"}},
      {"RCCylinderGeom", Family::Geom, {"Radius", "Length"}},
      {"RCCappedCylinderGeom", Family::Geom, {"Radius", "Length"}},
      {"RCModelMatchGeom", Family::Geom, {"IgnoreChilds"}},
      {"RCModelWrapGeom", Family::Geom, {"GeomType", "Alignment", "IgnoreChilds"}},
      // 6.6 JointComponents (Pose, Body common to all)
      {"RCBallSocketJoint", Family::Joint, {"Pose", "Body", "Anchor"}},
      {"RCHingeJoint", Family::Joint, {"Pose", "Body", "Hinge"}},
      {"RCSliderJoint", Family::Joint, {"Pose", "Body", "Axis"}},
      {"RCFixJoint", Family::Joint, {"Pose", "Body"}},
      {"RCImportJoint", Family::Joint, {"Pose", "Body", "File"}},  // listed under 6.11.5
      // 6.7 - 6.10
      {"RCGenericMaterial", Family::Material, {"Friction", "Bounceness", "MinBounceVel"}},
      {"RCGlobalCoordinates", Family::Pose, {"Pose"}},
      {"RCLocalCoordinates", Family::Pose, {"Pose"}},
      {"RCGlobalMotion", Family::Motion, {"LinVelocity", "AngVelocity"}},
      {"RCGenericInertia", Family::Inertia, {"Mass", "Inertia"}},
      {"RCInertiaByGeom", Family::Inertia, {"Mass", "Density"}},
      // 6.11 PeripheryComponents
      {"RCGenericDrive", Family::Periphery, {"Joint", "MaxPower", "MaxVelocity", "MinPos", "MaxPos", "Stall"}},
      {"RCGenericServo", Family::Periphery, {"Joint", "MaxPower", "MaxVelocity", "MinPos", "MaxPos", "Smooth"}},
      {"RCGenericVelControlledDrive", Family::Periphery, {"Joint", "MaxPower", "MaxVelocity", "MinPos", "MaxPos"}},
      {"RCProximitySensor", Family::Periphery, {"Pose", "Geom"}},
      {"RCLocalSocketCommunicator", Family::Periphery, {"IsServer", "Port", "Period"}},  // Period: simbob's own
      // 6.12 ControllerComponents
      {"RCDriveTest", Family::Controller, {"Drive", "Period", "Variation"}},
      {"RCServoTest", Family::Controller, {"PosControl", "Period", "Variation"}},
      {"RCTwoWheelMotionControl", Family::Controller, {"ControlLeft", "ControlRight", "WheelDistance", "Variation"}},
      // 3.5 CameraComponents
      {"StaticCamera", Family::Camera, {}},
      {"MountedCamera", Family::Camera, {}},
      {"SpotlightCamera", Family::Camera, {}},
      {"TrackingCamera", Family::Camera, {}},
  };
  return types;
}

std::vector<std::string> paramNames(const TypeSpec& t) {
  std::vector<std::string> names;
  for (const auto& p : t.params) names.push_back(p.name);
  return names;
}

bool holds(ValueType t, const Value& v) {
  switch (t) {
    case ValueType::Bool:
      return std::holds_alternative<bool>(v);
    case ValueType::Int:
      return std::holds_alternative<int64_t>(v);
    case ValueType::Number:
      return std::holds_alternative<double>(v);
    case ValueType::String:
      return std::holds_alternative<std::string>(v);
    case ValueType::Triple:
      return std::holds_alternative<Triple>(v);
    case ValueType::Vector:
      return std::holds_alternative<Vector4>(v);
    case ValueType::Quaternion:
      return std::holds_alternative<Quaternion>(v);
    case ValueType::Pose:
      return std::holds_alternative<Pose>(v);
    case ValueType::Matrix:
      return std::holds_alternative<Matrix4>(v);
    case ValueType::Cuboid:
      return std::holds_alternative<Cuboid>(v);
    case ValueType::Color:
      return std::holds_alternative<Color>(v);
    case ValueType::Enum:
      return std::holds_alternative<EnumValue>(v);
    case ValueType::Bitmask:
      return std::holds_alternative<BitmaskValue>(v);
  }
  return false;
}

}  // namespace

TEST_CASE("registry: every type of guide chapter 6 and 3.5 is registered in its family", "[scene][registry]") {
  const Registry& reg = testRegistry();
  for (const GuideType& g : guideTypes()) {
    INFO("type " << g.name);
    const TypeSpec* t = reg.find(g.name);
    REQUIRE(t != nullptr);
    CHECK(t->family == g.family);
    std::vector<std::string> names = paramNames(*t);
    for (const char* p : g.params) {
      INFO("parameter " << p);
      CHECK(std::find(names.begin(), names.end(), p) != names.end());
    }
  }
}

TEST_CASE("registry: the guide's misspelled geom names are aliases of the corrected ones", "[scene][registry]") {
  const Registry& reg = testRegistry();
  const TypeSpec* match = reg.find("RCModelMatchGeom");
  const TypeSpec* wrap = reg.find("RCModelWrapGeom");
  REQUIRE(match);
  REQUIRE(wrap);
  CHECK(reg.find("RCMoelMatchGeom") == match);
  CHECK(reg.find("RCMoelWrapGeom") == wrap);
  CHECK(match != wrap);
  // The canonical spelling is the one written back.
  CHECK(match->name == "RCModelMatchGeom");
  CHECK(wrap->name == "RCModelWrapGeom");
  // Camera aliases of 3.5 name the RC* types.
  CHECK(reg.find("StaticCamera") == reg.find("RCStaticCamera"));
  CHECK(reg.find("TrackingCamera")->name == "RCTrackingCamera");
  CHECK(reg.find("RigidBodyClone") == reg.find("RCRigidBodyClone"));
}

TEST_CASE("registry: lookups are exact-case, findIgnoreCase is not", "[scene][registry]") {
  const Registry& reg = testRegistry();
  CHECK(reg.find("rcspheregeom") == nullptr);
  CHECK(reg.find("RCSphereGeom ") == nullptr);
  CHECK(reg.find("") == nullptr);
  CHECK(reg.findIgnoreCase("rcspheregeom") == reg.find("RCSphereGeom"));
  CHECK(reg.findIgnoreCase("RCMOELWRAPGEOM") == reg.find("RCModelWrapGeom"));
  CHECK(reg.findIgnoreCase("NoSuchType") == nullptr);
}

TEST_CASE("registry: the guide's enum and bitmask keys are accepted", "[scene][registry]") {
  const Registry& reg = testRegistry();
  auto param = [&](const char* type, const char* name) -> const ParamSpec& {
    const TypeSpec* t = reg.find(type);
    REQUIRE(t);
    int i = t->paramIndex(name);
    REQUIRE(i >= 0);
    return t->params[static_cast<size_t>(i)];
  };
  auto parses = [](const ParamSpec& p, const char* text) {
    INFO(p.name << " = " << text);
    ParseResult r = parseValue(p.type, text, p.table);
    CHECK(r);
    return r;
  };
  const ParamSpec& geom_type = param("RCModelWrapGeom", "GeomType");
  for (const char* k : {"Cuboid", "Sphere", "Cylinder", "CappedCylinder"}) parses(geom_type, k);
  const ParamSpec& align = param("RCModelWrapGeom", "Alignment");
  for (const char* k : {"XAligned", "YAligned", "ZAligned"}) parses(align, k);
  const ParamSpec& mode = param("RCColoredSkin", "ColorMode");
  for (const char* k : {"Color", "Shading", "TransparentColor", "TransparentLighting", "TransparentLighing"})
    parses(mode, k);
  // The guide's typo is an alias of the same value; the correct spelling is written.
  CHECK(*parseValue(mode.type, "TransparentLighing", mode.table).value ==
        *parseValue(mode.type, "TransparentLighting", mode.table).value);
  CHECK(formatValue(mode.type, *parseValue(mode.type, "TransparentLighing", mode.table).value, mode.table) ==
        "TransparentLighting");
  const ParamSpec& sides = param("RCCuboidModel", "SideMask");
  for (const char* k : {"Left", "MinX", "Right", "MaxX", "Bottom", "MinY", "Top", "MaxY", "Back", "MinZ", "Front",
                        "MaxZ", "X", "Y", "Z", "All"})
    parses(sides, k);
  CHECK(std::get<BitmaskValue>(*parses(sides, "Left|Top").value).bits == (1u | 8u));
  CHECK(std::get<BitmaskValue>(*parses(sides, "All").value).bits == 63u);
  const ParamSpec& mask = param("RCCylinderModel", "ComponentMask");
  for (const char* k :
       {"None", "Jacket", "FlatFront", "FlatBack", "CappedFront", "CappedBack", "FlatCylinder", "CappedCylinder"})
    parses(mask, k);
  CHECK(std::get<BitmaskValue>(*parses(mask, "FlatCylinder").value).bits ==
        std::get<BitmaskValue>(*parses(mask, "Jacket|FlatFront|FlatBack").value).bits);
}

TEST_CASE("registry: family parameters are inherited, first and in order", "[scene][registry]") {
  const Registry& reg = testRegistry();
  size_t models = 0, joints = 0, cameras = 0;
  for (const TypeSpec& t : reg.types()) {
    INFO("type " << t.name);
    if (t.family == Family::Model) {
      ++models;
      REQUIRE(t.params.size() >= 3);
      CHECK(t.params[0].name == "Pose");
      CHECK(t.params[0].kind == ParamKind::Component);
      CHECK(t.params[0].families == std::vector<Family>{Family::Pose});
      CHECK(t.params[1].name == "Skin");
      CHECK(t.params[1].kind == ParamKind::Component);
      CHECK(t.params[1].families == std::vector<Family>{Family::Skin});
      CHECK(t.params[2].name == "ChildList");
      CHECK(t.params[2].kind == ParamKind::List);
      CHECK(t.params[2].families == std::vector<Family>{Family::Model});
    }
    if (t.family == Family::Joint) {
      ++joints;
      REQUIRE(t.params.size() >= 2);
      CHECK(t.params[0].name == "Pose");
      CHECK(t.params[0].kind == ParamKind::Component);
      CHECK(t.params[0].families == std::vector<Family>{Family::Pose});
      CHECK(t.params[1].name == "Body");
      CHECK(t.params[1].kind == ParamKind::Component);
      CHECK(t.params[1].families == std::vector<Family>{Family::Body});
      // A joint's Pose has no default: empty means the parent body's frame.
      CHECK(t.params[0].default_type.empty());
      CHECK(t.params[1].default_type.empty());
    }
    if (t.family == Family::Camera) {
      ++cameras;
      REQUIRE(t.params.size() >= 3);
      CHECK(t.params[0].name == "ViewAngle");
      CHECK(t.params[1].name == "NearClip");
      CHECK(t.params[2].name == "FarClip");
    }
  }
  CHECK(models == 7);  // cuboid, plane, ellipsoid, cylinder, cone, mesh, empty
  CHECK(joints == 5);
  CHECK(cameras == 4);
  // Other families have no inherited parameters: a geom starts with its own.
  CHECK(reg.find("RCSphereGeom")->params.size() == 1);
  CHECK(reg.find("RCEmptyGeom")->params.empty());
  CHECK(reg.find("RCEmptyModel")->params.size() == 3);
  CHECK(reg.find("RCFixJoint")->params.size() == 2);
}

TEST_CASE("registry: family parameters of a custom registry go in front of the type's own", "[scene][registry]") {
  Registry r;
  r.setFamilyParams(Family::Geom, {valueParam(ValueParam<double>{"Common"}, ValueType::Number, 1.0, "", "")});
  r.add({"MyGeom",
         Family::Geom,
         0,
         {valueParam(ValueParam<double>{"Own"}, ValueType::Number, 2.0, "", "")},
         {"MyAlias"},
         "doc"});
  const TypeSpec* t = r.find("MyGeom");
  REQUIRE(t);
  REQUIRE(t->params.size() == 2);
  CHECK(t->params[0].name == "Common");
  CHECK(t->params[1].name == "Own");
  CHECK(t->paramIndex("Own") == 1);
  CHECK(t->paramIndex("own") == -1);
  CHECK(t->paramIndexIgnoreCase("own") == 1);
  CHECK(t->paramIndex("Missing") == -1);
  CHECK(r.find("MyAlias") == t);
  CHECK(r.types().size() == 1);
}

TEST_CASE("registry: parameter names are unique per type and every table is consistent", "[scene][registry]") {
  const Registry& reg = testRegistry();
  std::set<std::string> type_names;
  for (const TypeSpec& t : reg.types()) {
    INFO("type " << t.name);
    CHECK(type_names.insert(t.name).second);
    for (const auto& a : t.aliases) CHECK(type_names.insert(a).second);
    CHECK_FALSE(t.doc.empty());
    CHECK(reg.find(t.name) == &t);
    std::set<std::string> lower;
    for (const ParamSpec& p : t.params) {
      INFO("parameter " << p.name);
      std::string l;
      for (char ch : p.name) l += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      // INI matches names case-insensitively, so they must differ beyond case.
      CHECK(lower.insert(l).second);
      CHECK_FALSE(p.name.empty());
      CHECK(p.name.find('.') == std::string::npos);
      CHECK(p.name != "Type");
      CHECK(p.name != "Key");
      CHECK(p.name != "Ref");
      CHECK(p.name != "Macro");
      switch (p.kind) {
        case ParamKind::Value:
          CHECK(holds(p.type, p.default_value));
          if (p.type == ValueType::Enum || p.type == ValueType::Bitmask) CHECK(p.table != nullptr);
          break;
        case ParamKind::Component:
          CHECK_FALSE(p.families.empty());
          if (!p.default_type.empty()) {
            const TypeSpec* d = reg.find(p.default_type);
            REQUIRE(d);
            CHECK(std::find(p.families.begin(), p.families.end(), d->family) != p.families.end());
          }
          break;
        case ParamKind::List:
          CHECK_FALSE(p.families.empty());
          break;
        case ParamKind::Struct: {
          const TypeSpec* s = reg.find(p.struct_type);
          REQUIRE(s);
          CHECK(s->family == Family::Struct);
          break;
        }
      }
    }
    if (!t.import_root.empty()) {
      CHECK(t.paramIndex("File") >= 0);
      CHECK((t.import_root == "Body" || t.import_root == "Joint" || t.import_root == "RefList" ||
             t.import_root == "robot"));  // RCImportURDF: a URDF robot (docs/urdf.md)
    }
  }
  CHECK(reg.find("RCImportBody")->import_root == "Body");
  CHECK(reg.find("RCImportJoint")->import_root == "Joint");
  CHECK(reg.find("RCImportRefList")->import_root == "RefList");
  CHECK(reg.find("RCImportURDF")->import_root == "robot");
  CHECK(reg.find("RCMobileRigidBody")->import_root.empty());
}

TEST_CASE("registry: macros create components of a registered type of their family", "[scene][registry]") {
  const Registry& reg = testRegistry();
  for (const char* name : {"NoGeom", "NoModel", "NoMotion", "Origin", "DefaultMaterial"}) {
    INFO("macro " << name);
    const MacroSpec* m = reg.findMacro(name);
    REQUIRE(m);
    const TypeSpec* t = reg.find(m->type);
    REQUIRE(t);
    CHECK(t->family == m->family);
    for (const auto& [pname, ptext] : m->params) CHECK(t->paramIndex(pname) >= 0);
  }
  CHECK(reg.findMacro("NoGeom")->type == "RCEmptyGeom");
  CHECK(reg.findMacro("NoModel")->type == "RCEmptyModel");
  CHECK(reg.findMacro("nogeom") == reg.findMacro("NoGeom"));
  CHECK(reg.findMacro("NoSuchMacro") == nullptr);
}

TEST_CASE("registry: every default value formats and re-parses to itself", "[scene][registry]") {
  const Registry& reg = testRegistry();
  size_t checked = 0;
  for (const TypeSpec& t : reg.types()) {
    for (const ParamSpec& p : t.params) {
      if (p.kind != ParamKind::Value) continue;
      INFO(t.name << "." << p.name);
      REQUIRE(holds(p.type, p.default_value));
      std::string text = formatValue(p.type, p.default_value, p.table);
      INFO("formatted as '" << text << "'");
      ParseOptions opts;
      opts.allow_infinite = p.allow_infinite;
      ParseResult r = parseValue(p.type, text, p.table, opts);
      REQUIRE(r);
      CHECK(*r.value == p.default_value);
      CHECK(formatValue(p.type, *r.value, p.table) == text);
      ++checked;
    }
  }
  CHECK(checked > 100);
}

TEST_CASE("registry: selected defaults match the documented values", "[scene][registry]") {
  const Registry& reg = testRegistry();
  auto def = [&](const char* type, const char* name) {
    const TypeSpec* t = reg.find(type);
    REQUIRE(t);
    int i = t->paramIndex(name);
    REQUIRE(i >= 0);
    const ParamSpec& p = t->params[static_cast<size_t>(i)];
    return formatValue(p.type, p.default_value, p.table);
  };
  CHECK(def("SceneSettings", "Gravity") == "(0, -9.81)");
  CHECK(def("RCInertiaByGeom", "Mass") == "-1");
  CHECK(def("RCGenericDrive", "MinPos") == "-Infinite");
  CHECK(def("RCGenericDrive", "MaxPos") == "Infinite");
  CHECK(def("RCColoredSkin", "Ambient") == "invalid");
  CHECK(def("RCRodBody", "HullPositions") == "True");
  CHECK(def("RCRodBody", "Capped") == "False");
  CHECK(def("RCCuboidModel", "SideMask") == "All");
  CHECK(def("RCModelWrapGeom", "Alignment") == "ZAligned");
  // The component defaults of bodies.
  const TypeSpec* mobile = reg.find("RCMobileRigidBody");
  CHECK(mobile->params[static_cast<size_t>(mobile->paramIndex("Inertia"))].default_type == "RCInertiaByGeom");
  CHECK(mobile->params[static_cast<size_t>(mobile->paramIndex("Pose"))].default_type == "RCGlobalCoordinates");
  CHECK(mobile->params[static_cast<size_t>(mobile->paramIndex("Geom"))].default_type == "RCEmptyGeom");
  CHECK(mobile->params[static_cast<size_t>(mobile->paramIndex("Material"))].default_type == "RCGenericMaterial");
}

TEST_CASE("registry: did-you-mean suggestions", "[scene][registry]") {
  const Registry& reg = testRegistry();
  CHECK(reg.suggestType("RCSphereGeon") == "RCSphereGeom");
  CHECK(reg.suggestType("RCMobilRigidBody") == "RCMobileRigidBody");
  CHECK(reg.suggestType("rcground") == "RCGround");  // case does not count
  CHECK(reg.suggestType("RCGrond") == "RCGround");
  CHECK(reg.suggestType("CompletelyDifferent") == "");
  CHECK(reg.suggestType("") == "");

  const std::vector<std::string> hinge_params = {"Pose", "Body", "Hinge"};
  CHECK(didYouMean("Hing", hinge_params) == "Hinge");
  CHECK(didYouMean("Hnge", hinge_params) == "Hinge");
  CHECK(didYouMean("hinge", hinge_params) == "Hinge");
  CHECK(didYouMean("Bodyy", hinge_params) == "Body");
  CHECK(didYouMean("Pos", hinge_params) == "Pose");
  // Distance 3 is too far.
  CHECK(didYouMean("Hi", hinge_params) == "");
  CHECK(didYouMean("Anchor", hinge_params) == "");
  CHECK(didYouMean("anything", {}) == "");
  // The nearest wins.
  CHECK(didYouMean("Radius", {"RadiusX", "Radius", "Radii"}) == "Radius");
  CHECK(didYouMean("RadiusY", {"RadiusX", "RadiusY", "RadiusZ"}) == "RadiusY");
}

TEST_CASE("registry: family names are the guide's ComponentBaseTypes", "[scene][registry]") {
  CHECK(std::string(familyName(Family::Body)) == "BodyComponent");
  CHECK(std::string(familyName(Family::GlobalSim)) == "GlobalSimComponent");
  CHECK(std::string(familyName(Family::Model)) == "ModelComponent");
  CHECK(std::string(familyName(Family::Skin)) == "SkinComponent");
  CHECK(std::string(familyName(Family::Geom)) == "GeomComponent");
  CHECK(std::string(familyName(Family::Joint)) == "JointComponent");
  CHECK(std::string(familyName(Family::Material)) == "MaterialComponent");
  CHECK(std::string(familyName(Family::Pose)) == "PoseComponent");
  CHECK(std::string(familyName(Family::Motion)) == "MotionComponent");
  CHECK(std::string(familyName(Family::Inertia)) == "InertiaComponent");
  CHECK(std::string(familyName(Family::Periphery)) == "PeripheryComponent");
  CHECK(std::string(familyName(Family::Controller)) == "ControllerComponent");
  CHECK(std::string(familyName(Family::Camera)) == "CameraComponent");
}

TEST_CASE("registry: the scene root and settings structs", "[scene][registry]") {
  const Registry& reg = testRegistry();
  const TypeSpec* sim = reg.find("Simulation");
  REQUIRE(sim);
  CHECK(sim->family == Family::Struct);
  REQUIRE(sim->params.size() == 3);
  CHECK(sim->params[0].name == "CameraList");
  CHECK(sim->params[1].name == "SceneSettings");
  CHECK(sim->params[2].name == "ComponentList");
  const ParamSpec& list = sim->params[2];
  // 5.3: BodyComponents and GlobalSimComponents (and materials, skins, models to refer to).
  for (Family f : {Family::Body, Family::GlobalSim, Family::Material, Family::Skin, Family::Model})
    CHECK(std::find(list.families.begin(), list.families.end(), f) != list.families.end());
  CHECK(std::find(list.families.begin(), list.families.end(), Family::Joint) == list.families.end());
  const TypeSpec* ss = reg.find("SceneSettings");
  REQUIRE(ss);
  CHECK(ss->paramIndex("Gravity") >= 0);
  CHECK(ss->paramIndex("MaxTimeStep") >= 0);
  CHECK(ss->paramIndex("FogSettings") >= 0);
  // RCConstruction's ChildList holds joints and peripheries only.
  const TypeSpec* con = reg.find("RCConstruction");
  const ParamSpec& children = con->params[static_cast<size_t>(con->paramIndex("ChildList"))];
  CHECK(children.families == std::vector<Family>{Family::Joint, Family::Periphery});
}

TEST_CASE("registry: registerBuiltins fills a fresh registry without problems", "[scene][registry]") {
  Registry r;
  CHECK(registerBuiltins(r));
  CHECK(r.problems().empty());
  CHECK(r.types().size() == testRegistry().types().size());
  CHECK(r.find("RCSphereGeom"));
  // Registering the builtins twice is refused, type by type, and changes nothing.
  const size_t n = r.types().size();
  CHECK_FALSE(registerBuiltins(r));
  CHECK(r.types().size() == n);
  CHECK(r.problems().size() >= n);
}

TEST_CASE("registry: a type whose name or alias is taken (in any case) is refused", "[scene][registry]") {
  // Before, the registry was one global map and a second registration replaced the first in
  // silence. Now add() refuses it and problems() says which name was taken.
  Registry r;
  REQUIRE(registerBuiltins(r));
  const size_t n = r.types().size();
  const TypeSpec* sphere = r.find("RCSphereGeom");
  const TypeSpec* match = r.find("RCModelMatchGeom");
  struct Case {
    TypeSpec spec;
    std::string problem;
  };
  std::vector<Case> cases;
  cases.push_back({{"RCSphereGeom", Family::Geom, 0, {}, {}, "same name"},
                   "component type 'RCSphereGeom': the name 'RCSphereGeom' is already registered"});
  cases.push_back({{"rcspheregeom", Family::Geom, 0, {}, {}, "same name, other case"},
                   "component type 'rcspheregeom': the name 'rcspheregeom' is already registered"});
  cases.push_back({{"MyGeom", Family::Geom, 0, {}, {"RCSPHEREGEOM"}, "alias = a name"},
                   "component type 'MyGeom': the name 'RCSPHEREGEOM' is already registered"});
  cases.push_back({{"rcmoelmatchgeom", Family::Geom, 0, {}, {}, "name = an alias"},
                   "component type 'rcmoelmatchgeom': the name 'rcmoelmatchgeom' is already registered"});
  cases.push_back({{"MyGeom2", Family::Geom, 0, {}, {"Unused", "RCMoelWrapGeom"}, "alias = an alias"},
                   "component type 'MyGeom2': the name 'RCMoelWrapGeom' is already registered"});
  cases.push_back({{"nogeom", Family::Geom, 0, {}, {}, "name = a macro"},
                   "component type 'nogeom': the name 'nogeom' is already registered"});
  cases.push_back({{"", Family::Geom, 0, {}, {}, "empty"}, "component type '': the name '' is empty"});
  for (Case& c : cases) {
    INFO(c.spec.doc);
    const size_t problems = r.problems().size();
    CHECK_FALSE(r.add(c.spec));
    REQUIRE(r.problems().size() == problems + 1);
    CHECK(r.problems().back() == c.problem);
  }
  // Nothing changed: the first registrations stand, the refused aliases were not added.
  CHECK(r.types().size() == n);
  CHECK(r.find("RCSphereGeom") == sphere);
  CHECK(r.findIgnoreCase("rcmoelmatchgeom") == match);
  CHECK(r.find("MyGeom") == nullptr);
  CHECK(r.find("Unused") == nullptr);
  // A free name goes in.
  CHECK(r.add({"MyGeom", Family::Geom, 0, {}, {"MyGeomAlias"}, "free"}));
  CHECK(r.types().size() == n + 1);
  CHECK(r.find("MyGeomAlias") == r.find("MyGeom"));
  // Macros too.
  CHECK_FALSE(r.addMacro({"NOGEOM", Family::Geom, "RCEmptyGeom", {}, ""}));
  CHECK(r.problems().back() == "macro 'NOGEOM': the name is already registered");
}

TEST_CASE("registry: the nearest type names of an unknown one", "[scene][registry]") {
  Registry reg;
  for (const char* name : {"RCOneGeom", "RCOnaGeom", "RCLongNameGeom", "RCOneModel"})
    REQUIRE(reg.add({name,
                     std::string(name).find("Geom") != std::string::npos ? Family::Geom : Family::Model,
                     0,
                     {},
                     {},
                     "test type"}));
  // Equally near names are all offered, in name order; a farther one is not.
  CHECK(reg.suggestTypes("RCOnxGeom") == std::vector<std::string>{"RCOnaGeom", "RCOneGeom"});
  CHECK(reg.unknownTypeMessage("RCOnxGeom", false) ==
        "unknown component type 'RCOnxGeom' (did you mean 'RCOnaGeom' or 'RCOneGeom'?)");
  // Another case is the nearest of all.
  CHECK(reg.suggestTypes("rconegeom") == std::vector<std::string>{"RCOneGeom"});
  // Far from every name: the types of the family its last word names, nearest first.
  CHECK(reg.suggestTypes("RCLongNamGeomXyzGeom") == std::vector<std::string>{"RCLongNameGeom"});
  CHECK(reg.suggestTypes("RCSomethingElseModel") == std::vector<std::string>{"RCOneModel"});
  CHECK(reg.suggestTypes("Zzzzzzzzzzzz").empty());
  CHECK(reg.unknownTypeMessage("Zzzzzzzzzzzz", true) ==
        "unknown component type 'Zzzzzzzzzzzz'; if a plug-in defines it, load the plug-in with --plugin FILE");
}

TEST_CASE("registry: NameTable finds every name added, keeps the first of equal names", "[scene][registry]") {
  NameTable t;
  CHECK(t.find("") == -1);                                                       // empty table
  for (int i = 0; i < 1000; ++i) REQUIRE(t.add("Name" + std::to_string(i), i));  // grows past its first size
  for (int i = 0; i < 1000; ++i) CHECK(t.find("Name" + std::to_string(i)) == i);
  CHECK_FALSE(t.add("Name7", 99));
  CHECK(t.find("Name7") == 7);
  CHECK(t.find("Name1000") == -1);
  CHECK(t.find("name7") == -1);  // exact case
  NameTable copy = t;            // holds its own names
  t.clear();
  CHECK(t.find("Name7") == -1);
  CHECK(copy.find("Name7") == 7);
  CHECK(copy.size() == 1000);
}

TEST_CASE("registry: NameTable set replaces a value, reserve keeps what is in", "[scene][registry]") {
  NameTable t;
  t.set("Arm", 1);
  t.set("Arm", 2);  // the last value stands
  CHECK(t.find("Arm") == 2);
  CHECK(t.size() == 1);
  t.reserve(1000);
  CHECK(t.find("Arm") == 2);  // still found after the slots are laid out again
  for (int i = 0; i < 1000; ++i) t.set("Key" + std::to_string(i), i);
  for (int i = 0; i < 1000; ++i) CHECK(t.find("Key" + std::to_string(i)) == i);
  CHECK(t.size() == 1001);
}

// A typed parameter name is hashed when the program is compiled, the names of a table when it
// runs: a name of every length up to three words and a tail must hash alike both ways.
constexpr uint64_t kHashed[] = {
    NameTable::hash(""),
    NameTable::hash("a"),
    NameTable::hash("Pose"),
    NameTable::hash("Density"),
    NameTable::hash("Friction"),
    NameTable::hash("Bounceness"),
    NameTable::hash("MinBounceVel"),
    NameTable::hash("RCMobileRigidBody"),
    NameTable::hash("RCGlobalCoordinates.Pose2"),
};

TEST_CASE("registry: names hash alike at compile time and at run time", "[scene][registry]") {
  const char* names[] = {"",
                         "a",
                         "Pose",
                         "Density",
                         "Friction",
                         "Bounceness",
                         "MinBounceVel",
                         "RCMobileRigidBody",
                         "RCGlobalCoordinates.Pose2"};
  for (size_t i = 0; i < std::size(names); ++i) {
    const std::string at_run_time = names[i];  // not a constant
    CHECK(NameTable::hash(at_run_time) == kHashed[i]);
  }
  CHECK(NameTable::hash("Friction") != NameTable::hash("Frictiom"));  // the last byte of a whole word counts
  CHECK(NameTable::hash("RCMobileRigidBody") != NameTable::hash("RCMobileRigidBodz"));  // and of the tail
}

TEST_CASE("registry: every type and alias is found by name, and its parameters by theirs", "[scene][registry]") {
  const Registry& reg = testRegistry();
  for (const TypeSpec& t : reg.types()) {
    CHECK(reg.find(t.name) == &t);
    for (const std::string& a : t.aliases) CHECK(reg.find(a) == &t);
    for (size_t i = 0; i < t.params.size(); ++i) {
      const int at = t.paramIndex(t.params[i].name);
      REQUIRE(at >= 0);
      CHECK(t.params[static_cast<size_t>(at)].name == t.params[i].name);  // the first of equal names
      CHECK(static_cast<size_t>(at) <= i);
    }
  }
  CHECK(reg.find("RCMobileRigidBodyy") == nullptr);
}
