// Registration entry points and compile-time kinds of each component family.
// One file per family (lib/components/<family>.cpp) holds its parameter tables, defaults with
// units, validation and its part of the compile step.
#pragma once

#include "simbob/registry.h"

namespace simbob {

// Kinds: TypeSpec::kind holds one of these for the type's family; compile switches on them.
enum class BodyKind { StaticRigid, MobileRigid, Rod, Construction, Import, Clone };
enum class GlobalKind { Ground, Sky, SandBox, Robot, ImportRefList };
enum class ModelKind { Cuboid, Plane, Ellipsoid, Cylinder, Cone, Empty };
enum class SkinKind { Colored, Textured, ColTex };
enum class GeomKind { Transform, Cuboid, Plane, Sphere, Cylinder, CappedCylinder, ModelMatch, ModelWrap, Empty };
enum class JointCompKind { BallSocket, Hinge, Slider, Fix, Import };
enum class MaterialKind { Generic };
enum class PoseKind { Global, Local };
enum class MotionKind { Global };
enum class InertiaKind { Generic, ByGeom };
enum class PeripheryKind { GenericDrive, GenericServo, VelControlledDrive, ProximitySensor, LocalSocketCommunicator };
enum class ControllerKind { DriveTest, ServoTest, TwoWheelMotionControl };
enum class CameraKind { Static, Mounted, Spotlight, Tracking };
enum class StructKind { SceneSettings, FogSettings, GlobalSettings, Simulation };

void registerBodies(Registry& r);
void registerGlobals(Registry& r);
void registerModels(Registry& r);
void registerSkins(Registry& r);
void registerGeoms(Registry& r);
void registerJoints(Registry& r);
void registerMaterials(Registry& r);
void registerPoses(Registry& r);
void registerMotions(Registry& r);
void registerInertias(Registry& r);
void registerPeripheries(Registry& r);
void registerControllers(Registry& r);
void registerCameras(Registry& r);
void registerSettings(Registry& r);

// Short forms for the parameter tables.
inline ParamSpec number(std::string name, double def, std::string unit, std::string doc, Range range = Range::Any) {
  return valueParam(std::move(name), ValueType::Number, def, std::move(unit), std::move(doc), range);
}
inline ParamSpec integer(std::string name, int64_t def, std::string doc, Range range = Range::Any) {
  return valueParam(std::move(name), ValueType::Int, def, "", std::move(doc), range);
}
inline ParamSpec flag(std::string name, bool def, std::string doc) {
  return valueParam(std::move(name), ValueType::Bool, def, "", std::move(doc));
}
inline ParamSpec text(std::string name, std::string def, std::string doc) {
  return valueParam(std::move(name), ValueType::String, std::move(def), "", std::move(doc));
}
inline ParamSpec triple(std::string name, Triple def, std::string unit, std::string doc) {
  return valueParam(std::move(name), ValueType::Triple, def, std::move(unit), std::move(doc));
}
inline ParamSpec color(std::string name, Color def, std::string doc) {
  return valueParam(std::move(name), ValueType::Color, def, "", std::move(doc));
}
inline Color rgba(double r, double g, double b, double a = 1.0) { return Color{{r, g, b, a}, true}; }
inline Color noColor() { return Color{{0, 0, 0, 1}, false}; }
inline ParamSpec limit(ParamSpec p) {
  p.allow_infinite = true;
  return p;
}

}  // namespace simbob
