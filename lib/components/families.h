// Registration entry points of the component families and short forms for their tables.
// One file per family (lib/components/<family>.cpp) holds its types' parameter names and
// tables, defaults with units, its kind enum, and its part of the compile step (lowering and
// checks, through lib/compile/context.h).
#pragma once

#include "simbob/registry.h"

namespace simbob {

void registerBodies(Registry& r);
void registerClones(Registry& r);
void registerUrdfImport(Registry& r);
void registerGlobals(Registry& r);
void registerModels(Registry& r);
void registerSkins(Registry& r);
void registerGeoms(Registry& r);
void registerModelGeoms(Registry& r);
void registerJoints(Registry& r);
void registerMaterials(Registry& r);
void registerPoses(Registry& r);
void registerMotions(Registry& r);
void registerInertias(Registry& r);
void registerPeripheries(Registry& r);
void registerRangeSensors(Registry& r);
void registerCameraSensors(Registry& r);
void registerImuSensors(Registry& r);
void registerEncoders(Registry& r);
void registerControllers(Registry& r);
void registerCameras(Registry& r);
void registerSettings(Registry& r);

/// The kinds of the Periphery family, whose types live in several files: peripheries.cpp (drives,
/// servos, the proximity sensor, the socket communicator), range_sensors.cpp, imu_sensors.cpp,
/// encoders.cpp. peripheries.cpp dispatches on it (lowerPeriphery).
/// TypeSpec::kind of the controller family (controllers.cpp; plug-in controllers: Plugin).
enum class ControllerKind {
  DriveTest,
  ServoTest,
  TwoWheelMotionControl,
  CommandSchedule,
  WallStop,
  GoToPoint,
  Plugin,
  ObstacleAvoider,
  WallFollower
};

enum class PeripheryKind {
  GenericDrive,
  GenericServo,
  VelControlledDrive,
  ProximitySensor,
  LocalSocketCommunicator,
  RangeSensor,
  LaserScanner,
  ImuSensor,
  Encoder,
  CameraSensor,
  PluginSensor,    ///< a plug-in's sensor type (plugin_types.cpp)
  PluginActuator,  ///< a plug-in's actuator type (plugin_types.cpp)
  UrdfDrive,       ///< a drive an RCImportURDF makes (urdf_import.cpp)
};

// Parameter names read outside their family file: the loader reads the scene root and the
// File of imports, the CLI reads the global settings (all in settings.cpp but File).
constexpr ListParam kCameraListParam{"CameraList"};
constexpr LinkParam kSceneSettingsParam{"SceneSettings"};
constexpr ListParam kComponentListParam{"ComponentList"};
constexpr ValueParam<std::string> kFileParam{"File"};
constexpr ValueParam<bool> kDocumentIniParam{"DocumentIni"};
constexpr ValueParam<std::string> kLogFileParam{"LogFile"};
constexpr ValueParam<std::string> kDocumentFolderParam{"DocumentFolder"};
constexpr ValueParam<std::string> kExtensionFolderParam{"ExtensionFolder"};
constexpr ValueParam<std::string> kTextureFolderParam{"TextureFolder"};

// Short forms for the parameter tables; each takes the parameter's typed name.
inline ParamSpec number(ValueParam<double> name, double def, const std::string& unit, const std::string& doc,
                        Range range = Range::Any) {
  return valueParam(name, ValueType::Number, def, unit, doc, range);
}
inline ParamSpec integer(ValueParam<int64_t> name, int64_t def, const std::string& doc, Range range = Range::Any) {
  return valueParam(name, ValueType::Int, def, "", doc, range);
}
inline ParamSpec flag(ValueParam<bool> name, bool def, const std::string& doc) {
  return valueParam(name, ValueType::Bool, def, "", doc);
}
inline ParamSpec text(ValueParam<std::string> name, const std::string& def, const std::string& doc) {
  return valueParam(name, ValueType::String, def, "", doc);
}
inline ParamSpec triple(ValueParam<Triple> name, Triple def, const std::string& unit, const std::string& doc) {
  return valueParam(name, ValueType::Triple, def, unit, doc);
}
inline ParamSpec color(ValueParam<Color> name, Color def, const std::string& doc) {
  return valueParam(name, ValueType::Color, def, "", doc);
}
inline Color rgba(double r, double g, double b, double a = 1.0) { return Color{{r, g, b, a}, true}; }
inline Color noColor() { return Color{{0, 0, 0, 1}, false}; }
inline ParamSpec limit(ParamSpec p) {
  p.allow_infinite = true;
  return p;
}

}  // namespace simbob
