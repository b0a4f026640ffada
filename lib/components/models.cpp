// ModelComponents (guide 6.3): visual hulls, no physical effect. The renderer draws them;
// RCModelMatchGeom / RCModelWrapGeom (model_geoms.cpp) derive collision shapes from them
// through the functions at the bottom.
#include <algorithm>
#include <cmath>

#include "compile/context.h"
#include "components/families.h"
#include "simbob/transform.h"

namespace simbob {

namespace {

enum class ModelKind { Cuboid, Plane, Ellipsoid, Cylinder, Cone, Empty, Mesh };

const EnumTable kSideMask{"SideMask",
                          {{"Left", 1},
                           {"MinX", 1},
                           {"Right", 2},
                           {"MaxX", 2},
                           {"Bottom", 4},
                           {"MinY", 4},
                           {"Top", 8},
                           {"MaxY", 8},
                           {"Back", 16},
                           {"MinZ", 16},
                           {"Front", 32},
                           {"MaxZ", 32},
                           {"X", 3},
                           {"Y", 12},
                           {"Z", 48},
                           {"All", 63}}};
const EnumTable kCylinderMask{"ComponentMask",
                              {{"None", 0},
                               {"Jacket", 1},
                               {"FlatFront", 2},
                               {"FlatBack", 4},
                               {"CappedFront", 8},
                               {"CappedBack", 16},
                               {"FlatCylinder", 7},
                               {"CappedCylinder", 25}}};
constexpr uint32_t kCapBits = 8u | 16u;

// Every model
constexpr LinkParam kPose{"Pose"};
constexpr LinkParam kSkin{"Skin"};
constexpr ListParam kChildList{"ChildList"};
// Type parameters
constexpr ValueParam<Cuboid> kCuboid{"Cuboid"};
constexpr ValueParam<double> kTexScale{"TexScale"};
constexpr EnumParam kSideMaskParam{"SideMask"};
constexpr ValueParam<bool> kWire{"Wire"};
constexpr ValueParam<double> kExtensionX{"ExtensionX"};
constexpr ValueParam<double> kExtensionY{"ExtensionY"};
constexpr ValueParam<bool> kIsShadowPlane{"IsShadowPlane"};
constexpr ValueParam<double> kMaxCellSize{"MaxCellSize"};
constexpr ValueParam<bool> kTriangles{"Triangles"};
constexpr ValueParam<int64_t> kAccuracy{"Accuracy"};
constexpr ValueParam<double> kRadiusX{"RadiusX"};
constexpr ValueParam<double> kRadiusY{"RadiusY"};
constexpr ValueParam<double> kRadiusZ{"RadiusZ"};
constexpr ValueParam<double> kRadius{"Radius"};
constexpr ValueParam<double> kLength{"Length"};
constexpr ValueParam<double> kAngTexScale{"AngTexScale"};
constexpr ValueParam<double> kLinTexScale{"LinTexScale"};
constexpr EnumParam kComponentMask{"ComponentMask"};
constexpr ValueParam<bool> kDrawBase{"DrawBase"};
constexpr ValueParam<Triple> kScale{"Scale"};

ModelKind kindOf(const Component& c) { return static_cast<ModelKind>(c.type->kind); }

}  // namespace

void registerModels(Registry& r) {
  r.setFamilyParams(Family::Model,
                    {componentParam(kPose, {Family::Pose}, "",
                                    "pose relative to the body (root model; local coordinates only) or the parent "
                                    "model (children; global coordinates: relative to the body)"),
                     componentParam(kSkin, {Family::Skin}, "", "surface appearance"),
                     listParam(kChildList, {Family::Model}, "child models")});
  const ParamSpec tex =
      number(kTexScale, 1.0, "", "size of one texture image in m (negative: as a fraction of the extension)");
  const ParamSpec accuracy = integer(kAccuracy, 2, "tessellation level", Range::Positive);
  r.add({"RCCuboidModel",
         Family::Model,
         int(ModelKind::Cuboid),
         {valueParam(kCuboid, ValueType::Cuboid, Cuboid{{-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}}, "m",
                     "two opposite corners"),
          tex, enumParam(kSideMaskParam, ValueType::Bitmask, &kSideMask, 63, "visible sides"),
          flag(kWire, false, "always drawn as wire frame")},
         {},
         "A cuboid."});
  r.add({"RCPlaneModel",
         Family::Model,
         int(ModelKind::Plane),
         {number(kExtensionX, 1.0, "m", "extension along local X", Range::Positive),
          number(kExtensionY, 1.0, "m", "extension along local Y", Range::Positive),
          flag(kIsShadowPlane, false, "shadows are projected on it"), tex,
          number(kMaxCellSize, -1.0, "m", "largest cell (negative: one cell)")},
         {},
         "A bounded plane perpendicular to local Z."});
  r.add({"RCEllipsoidModel",
         Family::Model,
         int(ModelKind::Ellipsoid),
         {flag(kTriangles, false, "triangles instead of quadrangles"), accuracy,
          number(kRadiusX, 0.5, "m", "radius along local X", Range::Positive),
          number(kRadiusY, 0.5, "m", "radius along local Y", Range::Positive),
          number(kRadiusZ, 0.5, "m", "radius along local Z", Range::Positive)},
         {},
         "An ellipsoid."});
  r.add({"RCCylinderModel",
         Family::Model,
         int(ModelKind::Cylinder),
         {number(kRadius, 0.5, "m", "radius", Range::Positive),
          number(kLength, 1.0, "m", "length along local Z", Range::Positive),
          number(kAngTexScale, 1.0, "", "texture scale along the perimeter"),
          number(kLinTexScale, 1.0, "", "texture scale along the axis"),
          enumParam(kComponentMask, ValueType::Bitmask, &kCylinderMask, 7, "visible parts"), accuracy},
         {},
         "A cylinder along local Z."});
  r.add({"RCConeModel",
         Family::Model,
         int(ModelKind::Cone),
         {number(kRadius, 0.5, "m", "base radius", Range::Positive),
          number(kLength, 1.0, "m", "length along local Z", Range::Positive),
          number(kLinTexScale, 1.0, "", "texture scale"), flag(kDrawBase, true, "base visible"), accuracy},
         {},
         "A cone along local Z."});
  r.add({"RCMeshModel",
         Family::Model,
         int(ModelKind::Mesh),
         {text(kFileParam, "", "mesh file (.stl, .obj, .dae), relative to this file; docs/meshes.md"),
          triple(kScale, {1, 1, 1}, "", "factors along local X, Y, Z (0.001 for a file in millimetres)")},
         {},
         "A triangle mesh from a file (Y up; a COLLADA file's unit and up axis are applied). RCModelMatchGeom "
         "gives its convex hull."});
  r.add({"RCEmptyModel", Family::Model, int(ModelKind::Empty), {}, {}, "An invisible model."});
  r.addMacro({"NoModel", Family::Model, "RCEmptyModel", {}, "an invisible model"});
}

bool collectModelParts(CompileContext& ctx, const Link& root, const Transform& base, bool children,
                       std::vector<ModelPart>* out) {
  // Iterative walk in document order (depth first); `base` is the body frame the root model's
  // pose is relative to.
  struct Item {
    const Link* link;
    Transform parent;
    bool is_root;
  };
  std::vector<Item> stack{{&root, base, true}};
  while (!stack.empty()) {
    Item it = stack.back();
    stack.pop_back();
    if (it.link->comp < 0 || it.link->comp >= static_cast<int>(ctx.scene.comps.size())) continue;
    if (out->size() >= kMaxModelParts) return false;
    const Component& c = ctx.at(it.link->comp);
    const Link& pl = c.get(kPose);
    Transform t = it.parent;
    if (pl.comp >= 0) {
      // Guide 6.3: a child's "global" coordinates are the root's frame, i.e. the body's. (A
      // root model's global pose is an error reported by checkModelTree.)
      bool global = !isLocalPose(ctx, pl);
      t = compose(global && !it.is_root ? base : it.parent, poseValue(ctx, pl));
    }
    out->push_back({&c, t});
    if (!children) continue;
    const std::vector<Link>& kids = c.get(kChildList);
    for (auto k = kids.rbegin(); k != kids.rend(); ++k) stack.push_back({&*k, t, false});
  }
  return true;
}

void checkModelTree(CompileContext& ctx, const Link& root) {
  if (root.comp < 0 || !ctx.firstCheck(root.comp)) return;  // a shared model is checked once
  const Component& c = ctx.at(root.comp);
  const Link& pl = c.get(kPose);
  if (pl.comp >= 0 && !isLocalPose(ctx, pl))
    ctx.error(pl, c,
              "a root model's Pose must be RCLocalCoordinates: a model may be drawn for several bodies, so global "
              "coordinates have no meaning for it (guide 6.3)");
}

ModelShape modelShape(const Component& m) {
  ModelShape s;
  switch (kindOf(m)) {
    case ModelKind::Cuboid: {
      const Cuboid& cb = m.get(kCuboid);
      s.kind = ModelShape::Box;
      for (int i = 0; i < 3; ++i) {
        s.center[i] = (cb.a[i] + cb.b[i]) / 2;
        s.size[i] = std::fabs(cb.b[i] - cb.a[i]);
      }
      return s;
    }
    case ModelKind::Ellipsoid:
      s.kind = ModelShape::Ellipsoid;
      s.size = {m.get(kRadiusX), m.get(kRadiusY), m.get(kRadiusZ)};
      return s;
    case ModelKind::Cylinder:
      s.kind = (m.get(kComponentMask) & kCapBits) != 0 ? ModelShape::Capsule : ModelShape::Cylinder;
      s.size = {m.get(kRadius), m.get(kLength), 0};
      return s;
    case ModelKind::Cone:
      s.kind = ModelShape::Cone;
      s.size = {m.get(kRadius), m.get(kLength), 0};
      return s;
    case ModelKind::Plane:
      s.kind = ModelShape::Plane;
      s.size = {m.get(kExtensionX), m.get(kExtensionY), 0};
      return s;
    case ModelKind::Empty:
      return s;
    case ModelKind::Mesh:
      s.kind = ModelShape::Mesh;
      return s;
  }
  return s;
}

int lowerModelMesh(CompileContext& ctx, const Component& model) {
  const Triple& s = model.get(kScale);
  for (double f : s)
    if (!std::isfinite(f) || f == 0) {
      ctx.errorAt(model.slotOf(kScale), model, "parameter 'Scale' needs three finite, non-zero factors");
      return -1;
    }
  return lowerMeshFile(ctx, model, model.slotOf(kFileParam), model.get(kFileParam), {s[0], s[1], s[2]});
}

void lowerVisuals(CompileContext& ctx, const Link& root, int body, const Transform& frame, const std::string& key) {
  // Depth first in document order, like collectModelParts; a child without a skin wears its
  // parent's.
  struct Item {
    const Link* link;
    Transform parent;
    bool is_root;
    int skin;
  };
  std::vector<Item> stack{{&root, frame, true, 0}};
  size_t parts = 0;
  while (!stack.empty()) {
    Item it = stack.back();
    stack.pop_back();
    if (it.link->comp < 0 || ++parts > kMaxModelParts) continue;
    const Component& c = ctx.at(it.link->comp);
    const Link& pl = c.get(kPose);
    Transform t = it.parent;
    if (pl.comp >= 0) t = compose(!isLocalPose(ctx, pl) && !it.is_root ? frame : it.parent, poseValue(ctx, pl));
    const int skin = c.get(kSkin).comp >= 0 ? lowerSkin(ctx, c.get(kSkin)) : it.skin;
    VisualDef v;
    v.body = body;
    v.pose = t;
    v.skin = skin;
    v.key = key;
    bool visible = true;
    switch (kindOf(c)) {
      case ModelKind::Cuboid: {
        const Cuboid& cb = c.get(kCuboid);
        v.shape = VisualDef::Cuboid;
        v.a = {cb.a[0], cb.a[1], cb.a[2]};
        v.b = {cb.b[0], cb.b[1], cb.b[2]};
        v.mask = c.get(kSideMaskParam);
        v.wire = c.get(kWire);
        v.tex_scale = c.get(kTexScale);
        break;
      }
      case ModelKind::Plane:
        v.shape = VisualDef::Plane;
        v.size = {c.get(kExtensionX), c.get(kExtensionY), 0};
        v.shadow_plane = c.get(kIsShadowPlane);
        v.tex_scale = c.get(kTexScale);
        v.max_cell = c.get(kMaxCellSize);
        break;
      case ModelKind::Ellipsoid:
        v.shape = VisualDef::Ellipsoid;
        v.size = {c.get(kRadiusX), c.get(kRadiusY), c.get(kRadiusZ)};
        v.triangles = c.get(kTriangles);
        v.accuracy = static_cast<int>(std::min<int64_t>(c.get(kAccuracy), 16));
        break;
      case ModelKind::Cylinder:
        v.shape = VisualDef::Cylinder;
        v.size = {c.get(kRadius), c.get(kLength), 0};
        v.mask = c.get(kComponentMask);
        v.tex_scale = c.get(kAngTexScale);
        v.tex_scale2 = c.get(kLinTexScale);
        v.accuracy = static_cast<int>(std::min<int64_t>(c.get(kAccuracy), 16));
        break;
      case ModelKind::Cone:
        v.shape = VisualDef::Cone;
        v.size = {c.get(kRadius), c.get(kLength), 0};
        v.mask = c.get(kDrawBase) ? 1 : 0;
        v.tex_scale = c.get(kLinTexScale);
        v.accuracy = static_cast<int>(std::min<int64_t>(c.get(kAccuracy), 16));
        break;
      case ModelKind::Empty:
        visible = false;
        break;
      case ModelKind::Mesh:
        v.shape = VisualDef::Mesh;
        v.mesh = lowerModelMesh(ctx, c);
        visible = v.mesh >= 0;
        break;
    }
    if (visible) ctx.model.visuals.push_back(std::move(v));
    const std::vector<Link>& kids = c.get(kChildList);
    for (auto k = kids.rbegin(); k != kids.rend(); ++k) stack.push_back({&*k, t, false, skin});
  }
}

}  // namespace simbob
