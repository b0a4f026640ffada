// GlobalSimComponents (guide 6.2): ground, sky and sandbox planes, robots, shared RefLists.
#include <cmath>

#include "compile/context.h"
#include "components/families.h"
#include "simbob/transform.h"

namespace simbob {

namespace {

enum class GlobalKind { Ground, Sky, SandBox, Robot, ImportRefList };

constexpr LinkParam kMaterial{"Material"};
constexpr LinkParam kSkin{"Skin"};
constexpr ValueParam<double> kExtension{"Extension"};
constexpr ValueParam<double> kTexScale{"TexScale"};
constexpr ValueParam<double> kMaxCellSize{"MaxCellSize"};
constexpr ValueParam<double> kHeight{"Height"};
constexpr ValueParam<double> kMotionX{"MotionX"};
constexpr ValueParam<double> kMotionY{"MotionY"};
constexpr ValueParam<double> kWidth{"Width"};
constexpr ValueParam<double> kDepth{"Depth"};
constexpr ValueParam<double> kThickness{"Thickness"};
constexpr LinkParam kWall{"Wall"};
constexpr LinkParam kConstruction{"Construction"};
constexpr ListParam kControllerList{"ControllerList"};

/// A horizontal square plane model at height y facing up (+1) or down (-1).
void addFloorVisual(CompileContext& ctx, const Component& c, double y, double facing) {
  VisualDef v;
  v.shape = VisualDef::Plane;
  v.pose.p = {0, y, 0};
  v.pose.q = quatAxisAngle({1, 0, 0}, -facing * kPi / 2);  // local +Z onto +Y (or -Y)
  v.size = {c.get(kExtension), c.get(kExtension), 0};
  v.tex_scale = c.get(kTexScale);
  v.max_cell = c.get(kMaxCellSize);
  v.shadow_plane = facing > 0;  // the ground catches the shadows
  v.skin = lowerSkin(ctx, c.get(kSkin));
  v.key = c.qkey;
  ctx.model.visuals.push_back(v);
}

/// The sandbox's walls: boxes of Thickness outside the planes, Height tall from y = 0.
void addSandBoxVisuals(CompileContext& ctx, const Component& c) {
  const double w = c.get(kWidth) / 2, d = c.get(kDepth) / 2, t = c.get(kThickness), h = c.get(kHeight);
  const int skin = lowerSkin(ctx, c.get(kWall));
  auto wall = [&](const Vec3& a, const Vec3& b) {
    VisualDef v;
    v.shape = VisualDef::Cuboid;
    v.a = a;
    v.b = b;
    v.tex_scale = c.get(kTexScale);
    v.skin = skin;
    v.key = c.qkey;
    ctx.model.visuals.push_back(v);
  };
  wall({-w - t, 0, -d - t}, {-w, h, d + t});
  wall({w, 0, -d - t}, {w + t, h, d + t});
  wall({-w, 0, -d - t}, {w, h, -d});
  wall({-w, 0, d}, {w, h, d + t});
}

}  // namespace

void registerGlobals(Registry& r) {
  const ParamSpec material = componentParam(kMaterial, {Family::Material}, "RCGenericMaterial", "contact properties");
  const ParamSpec skin = componentParam(kSkin, {Family::Skin}, "", "surface appearance");
  const ParamSpec extension = number(kExtension, 100.0, "m", "visible extension (physics: infinite)", Range::Positive);
  const ParamSpec tex =
      number(kTexScale, 1.0, "", "size of one texture image in m (negative: as a fraction of the extension)");
  const ParamSpec cell = number(kMaxCellSize, -1.0, "m", "largest cell (negative: one cell)");
  r.add({"RCGround",
         Family::GlobalSim,
         int(GlobalKind::Ground),
         {material, skin, extension, tex, cell},
         {},
         "Static horizontal plane y = 0."});
  r.add({"RCSky",
         Family::GlobalSim,
         int(GlobalKind::Sky),
         {material, skin, extension, number(kHeight, 10.0, "m", "y of the plane"), tex, cell,
          number(kMotionX, 0.0, "m/s", "texture motion (visual only)"),
          number(kMotionY, 0.0, "m/s", "texture motion (visual only)")},
         {},
         "Static horizontal plane at Height facing down; cuts off everything above."});
  r.add({"RCSandBox",
         Family::GlobalSim,
         int(GlobalKind::SandBox),
         {number(kWidth, 10.0, "m", "extent along X", Range::Positive),
          number(kDepth, 10.0, "m", "extent along Z", Range::Positive),
          number(kThickness, 0.1, "m", "visible wall thickness (physics: none)", Range::Positive),
          number(kHeight, 1.0, "m", "visible wall height (physics: infinite)", Range::Positive),
          componentParam(kWall, {Family::Skin}, "", "wall appearance"), tex, material},
         {},
         "Four vertical planes at x = +-Width/2 and z = +-Depth/2 facing inwards."});
  r.add({"RCRobot",
         Family::GlobalSim,
         int(GlobalKind::Robot),
         {componentParam(kConstruction, {Family::Body}, "", "mechanics and peripheries"),
          listParam(kControllerList, {Family::Controller}, "software of the robot")},
         {},
         "Hardware plus the controllers that drive it."});
  r.add({"RCImportRefList",
         Family::GlobalSim,
         int(GlobalKind::ImportRefList),
         {text(kFileParam, "", "XML file with root <RefList> of materials, skins and models; relative to this file")},
         {},
         "Components to Ref from several scenes; their keys are <this Key>.<their Key>.",
         false,
         "RefList"});
}

void lowerGlobal(CompileContext& ctx, int gi) {
  const Component& c = ctx.at(gi);
  switch (static_cast<GlobalKind>(c.type->kind)) {
    case GlobalKind::Ground:
      addPlane(ctx, {0, 1, 0}, {0, 0, 0}, lowerMaterial(ctx, c.get(kMaterial)), c.qkey);
      addFloorVisual(ctx, c, 0, 1);
      break;
    case GlobalKind::Sky:
      addPlane(ctx, {0, -1, 0}, {0, c.get(kHeight), 0}, lowerMaterial(ctx, c.get(kMaterial)), c.qkey);
      addFloorVisual(ctx, c, c.get(kHeight), -1);
      break;
    case GlobalKind::SandBox: {
      int mat = lowerMaterial(ctx, c.get(kMaterial));
      double w = c.get(kWidth) / 2, d = c.get(kDepth) / 2;
      addPlane(ctx, {1, 0, 0}, {-w, 0, 0}, mat, c.qkey);
      addPlane(ctx, {-1, 0, 0}, {w, 0, 0}, mat, c.qkey);
      addPlane(ctx, {0, 0, 1}, {0, 0, -d}, mat, c.qkey);
      addPlane(ctx, {0, 0, -1}, {0, 0, d}, mat, c.qkey);
      addSandBoxVisuals(ctx, c);
      break;
    }
    case GlobalKind::Robot: {
      const Link& l = c.get(kConstruction);
      if (l.comp < 0) {
        if (!l.isRef()) ctx.error(c, "parameter 'Construction' is required");
        break;
      }
      lowerBody(ctx, l.comp, nullptr);
      for (const Link& ctl : c.get(kControllerList))
        if (ctl.comp >= 0) lowerController(ctx, ctx.at(ctl.comp));
      break;
    }
    case GlobalKind::ImportRefList:
      break;  // its components are there to be referred to
  }
}

}  // namespace simbob
