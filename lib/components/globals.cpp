// GlobalSimComponents (guide 6.2).
#include "components/families.h"

namespace simbob {

void registerGlobals(Registry& r) {
  const ParamSpec material = componentParam("Material", {Family::Material}, "RCGenericMaterial", "contact properties");
  const ParamSpec skin = componentParam("Skin", {Family::Skin}, "", "surface appearance");
  const ParamSpec extension = number("Extension", 100.0, "m", "visible extension (physics: infinite)", Range::Positive);
  const ParamSpec tex = number("TexScale", 1.0, "", "texture scale (negative: relative to the extension)");
  const ParamSpec cell = number("MaxCellSize", -1.0, "m", "largest cell (negative: one cell)");
  r.add({"RCGround",
         Family::GlobalSim,
         int(GlobalKind::Ground),
         {material, skin, extension, tex, cell},
         {},
         "Static horizontal plane y = 0."});
  r.add({"RCSky",
         Family::GlobalSim,
         int(GlobalKind::Sky),
         {material, skin, extension, number("Height", 10.0, "m", "y of the plane"), tex, cell,
          number("MotionX", 0.0, "m/s", "texture motion (visual only)"),
          number("MotionY", 0.0, "m/s", "texture motion (visual only)")},
         {},
         "Static horizontal plane at Height facing down; cuts off everything above."});
  r.add({"RCSandBox",
         Family::GlobalSim,
         int(GlobalKind::SandBox),
         {number("Width", 10.0, "m", "extent along X", Range::Positive),
          number("Depth", 10.0, "m", "extent along Z", Range::Positive),
          number("Thickness", 0.1, "m", "visible wall thickness (physics: none)", Range::Positive),
          number("Height", 1.0, "m", "visible wall height (physics: infinite)", Range::Positive),
          componentParam("Wall", {Family::Skin}, "", "wall appearance"), tex, material},
         {},
         "Four vertical planes at x = +-Width/2 and z = +-Depth/2 facing inwards."});
  r.add({"RCRobot",
         Family::GlobalSim,
         int(GlobalKind::Robot),
         {componentParam("Construction", {Family::Body}, "", "mechanics and peripheries"),
          listParam("ControllerList", {Family::Controller}, "software of the robot")},
         {},
         "Hardware plus the controllers that drive it."});
  r.add({"RCImportRefList",
         Family::GlobalSim,
         int(GlobalKind::ImportRefList),
         {text("File", "", "XML file with root <RefList> of materials, skins and models; relative to this file")},
         {},
         "Components to Ref from several scenes; their keys are <this Key>.<their Key>.",
         false,
         "RefList"});
}

}  // namespace simbob
