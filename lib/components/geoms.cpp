// GeomComponents (guide 6.5): collision shapes. Cylinders and capsules lie along local Z.
#include "components/families.h"

namespace simbob {

static const EnumTable kWrapGeomType{"GeomType",
                                     {{"Cuboid", 0}, {"Sphere", 1}, {"Cylinder", 2}, {"CappedCylinder", 3}}};
static const EnumTable kAlignment{"Alignment", {{"XAligned", 0}, {"YAligned", 1}, {"ZAligned", 2}}};

void registerGeoms(Registry& r) {
  r.add({"RCTransformGeom",
         Family::Geom,
         int(GeomKind::Transform),
         {componentParam("Pose", {Family::Pose}, "", "pose of SubGeom in the body frame"),
          componentParam("SubGeom", {Family::Geom}, "", "the transformed geom")},
         {},
         "Offsets another geom from the body origin."});
  r.add({"RCCuboidGeom",
         Family::Geom,
         int(GeomKind::Cuboid),
         {number("Width", 1.0, "m", "extent along X", Range::Positive),
          number("Height", 1.0, "m", "extent along Y", Range::Positive),
          number("Depth", 1.0, "m", "extent along Z", Range::Positive)},
         {},
         "Box centred on the body origin."});
  r.add({"RCPlaneGeom",
         Family::Geom,
         int(GeomKind::Plane),
         {componentParam("Pose", {Family::Pose}, "", "a point of the plane; the local Y axis is its normal")},
         {},
         "Infinite plane; static bodies only."});
  r.add({"RCSphereGeom",
         Family::Geom,
         int(GeomKind::Sphere),
         {number("Radius", 0.5, "m", "radius", Range::Positive)},
         {},
         "Sphere."});
  r.add({"RCCylinderGeom",
         Family::Geom,
         int(GeomKind::Cylinder),
         {number("Radius", 0.5, "m", "radius", Range::Positive),
          number("Length", 1.0, "m", "length along local Z", Range::Positive)},
         {},
         "Flat-ended cylinder along local Z."});
  r.add({"RCCappedCylinderGeom",
         Family::Geom,
         int(GeomKind::CappedCylinder),
         {number("Radius", 0.5, "m", "radius", Range::Positive),
          number("Length", 1.0, "m", "length of the cylindrical part along local Z (caps add Radius at each end)",
                 Range::Positive)},
         {},
         "Capsule along local Z."});
  r.add({"RCModelMatchGeom",
         Family::Geom,
         int(GeomKind::ModelMatch),
         {flag("IgnoreChilds", false, "use only the root model")},
         {"RCMoelMatchGeom"},
         "The geom that exactly matches the body's model (cuboid, sphere, cylinder, capped cylinder).",
         true});
  r.add({"RCModelWrapGeom",
         Family::Geom,
         int(GeomKind::ModelWrap),
         {enumParam("GeomType", ValueType::Enum, &kWrapGeomType, 0, "shape that wraps the model"),
          enumParam("Alignment", ValueType::Enum, &kAlignment, 2, "axis of a cylindric wrap"),
          flag("IgnoreChilds", false, "wrap only the root model")},
         {"RCMoelWrapGeom"},
         "The smallest geom of GeomType that wraps the body's model.",
         true});
  r.add({"RCEmptyGeom",
         Family::Geom,
         int(GeomKind::Empty),
         {},
         {},
         "No collision shape (what the NoGeom macro creates)."});
  r.addMacro({"NoGeom", Family::Geom, "RCEmptyGeom", {}, "a body without collision shape"});
}

}  // namespace simbob
