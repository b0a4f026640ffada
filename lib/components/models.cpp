// ModelComponents (guide 6.3): visual hulls, no physical effect. Kept for the renderer and for
// RCModelMatchGeom / RCModelWrapGeom.
#include "components/families.h"

namespace simbob {

static const EnumTable kSideMask{"SideMask",
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
static const EnumTable kCylinderMask{"ComponentMask",
                                     {{"None", 0},
                                      {"Jacket", 1},
                                      {"FlatFront", 2},
                                      {"FlatBack", 4},
                                      {"CappedFront", 8},
                                      {"CappedBack", 16},
                                      {"FlatCylinder", 7},
                                      {"CappedCylinder", 25}}};

void registerModels(Registry& r) {
  r.setFamilyParams(Family::Model,
                    {componentParam("Pose", {Family::Pose}, "", "pose in the frame of the body (or parent model)"),
                     componentParam("Skin", {Family::Skin}, "", "surface appearance"),
                     listParam("ChildList", {Family::Model}, "child models")});
  const ParamSpec tex = number("TexScale", 1.0, "", "texture scale (negative: relative to the extension)");
  const ParamSpec accuracy = integer("Accuracy", 2, "tessellation level", Range::Positive);
  r.add({"RCCuboidModel",
         Family::Model,
         int(ModelKind::Cuboid),
         {valueParam("Cuboid", ValueType::Cuboid, Cuboid{{-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}}, "m",
                     "two opposite corners"),
          tex, enumParam("SideMask", ValueType::Bitmask, &kSideMask, 63, "visible sides"),
          flag("Wire", false, "always drawn as wire frame")},
         {},
         "A cuboid."});
  r.add({"RCPlaneModel",
         Family::Model,
         int(ModelKind::Plane),
         {number("ExtensionX", 1.0, "m", "extension along local X", Range::Positive),
          number("ExtensionY", 1.0, "m", "extension along local Y", Range::Positive),
          flag("IsShadowPlane", false, "shadows are projected on it"), tex,
          number("MaxCellSize", -1.0, "m", "largest cell (negative: one cell)")},
         {},
         "A bounded plane perpendicular to local Z."});
  r.add({"RCEllipsoidModel",
         Family::Model,
         int(ModelKind::Ellipsoid),
         {flag("Triangles", false, "triangles instead of quadrangles"), accuracy,
          number("RadiusX", 0.5, "m", "radius along local X", Range::Positive),
          number("RadiusY", 0.5, "m", "radius along local Y", Range::Positive),
          number("RadiusZ", 0.5, "m", "radius along local Z", Range::Positive)},
         {},
         "An ellipsoid."});
  r.add({"RCCylinderModel",
         Family::Model,
         int(ModelKind::Cylinder),
         {number("Radius", 0.5, "m", "radius", Range::Positive),
          number("Length", 1.0, "m", "length along local Z", Range::Positive),
          number("AngTexScale", 1.0, "", "texture scale along the perimeter"),
          number("LinTexScale", 1.0, "", "texture scale along the axis"),
          enumParam("ComponentMask", ValueType::Bitmask, &kCylinderMask, 7, "visible parts"), accuracy},
         {},
         "A cylinder along local Z."});
  r.add({"RCConeModel",
         Family::Model,
         int(ModelKind::Cone),
         {number("Radius", 0.5, "m", "base radius", Range::Positive),
          number("Length", 1.0, "m", "length along local Z", Range::Positive),
          number("LinTexScale", 1.0, "", "texture scale"), flag("DrawBase", true, "base visible"), accuracy},
         {},
         "A cone along local Z."});
  r.add({"RCEmptyModel", Family::Model, int(ModelKind::Empty), {}, {}, "An invisible model."});
  r.addMacro({"NoModel", Family::Model, "RCEmptyModel", {}, "an invisible model"});
}

}  // namespace simbob
