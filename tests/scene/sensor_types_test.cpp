// simbob's own sensor types (lib/components/range_sensors.cpp, imu_sensors.cpp, encoders.cpp):
// lowered to Model::sensors with their kind, pose relative to the body, parameters and quantity
// names; bad parameters are errors at the parameter's line.
#include <catch2/catch.hpp>

#include <cmath>

#include "scene/scene_helpers.h"

using namespace scenetest;

namespace {

/// A robot construction: a chassis at (1, 0.5, 0) turned 90 degrees about Y, a wheel on a hinge,
/// and `sensors` in its ChildList.
std::string robot(const std::string& sensors) {
  return R"(<Simulation><ComponentList>
<RCConstruction Key="Bot">
  <Body><RCMobileRigidBody Key="Chassis">
    <Pose><RCGlobalCoordinates><Pose Value="1 0.5 0 0 90 0"/></RCGlobalCoordinates></Pose>
    <Geom><RCCuboidGeom><Width Value="0.4"/><Height Value="0.1"/><Depth Value="0.3"/></RCCuboidGeom></Geom>
  </RCMobileRigidBody></Body>
  <ChildList>
    <RCHingeJoint Key="Axle">
      <Pose><RCLocalCoordinates><Pose Value="0 0 0.2 0 0 0"/></RCLocalCoordinates></Pose>
      <Body><RCMobileRigidBody Key="Wheel"><Pose Macro="Origin"/>
        <Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom></RCMobileRigidBody></Body>
    </RCHingeJoint>
    <RCSliderJoint Key="Lift">
      <Body><RCMobileRigidBody Key="Fork"><Pose Macro="Origin"/>
        <Geom><RCSphereGeom><Radius Value="0.05"/></RCSphereGeom></Geom></RCMobileRigidBody></Body>
    </RCSliderJoint>
)" + sensors +
         R"(
  </ChildList>
</RCConstruction>
</ComponentList></Simulation>
)";
}

std::vector<std::string> compileErrors(const std::string& text) {
  Scene s;
  Diagnostics d;
  loadText(text, &s, d);
  Model m;
  if (d.errors().empty()) compileScene(s, &m, d);
  std::vector<std::string> out;
  for (const auto& e : d.errors()) out.push_back(e.str());
  return out;
}

}  // namespace

TEST_CASE("sensor types: range sensor, scanner, IMU and encoder lower to Model::sensors", "[scene][sensors]") {
  const Model m = mustCompile(robot(R"(
    <RCRangeSensor Key="Front">
      <Pose><RCLocalCoordinates><Pose Value="0.2 0 0 0 -90 0"/></RCLocalCoordinates></Pose>
      <MinRange Value="0.02"/><MaxRange Value="2"/><Noise Value="0.01"/><Resolution Value="0.001"/>
    </RCRangeSensor>
    <RCLaserScanner Key="Lidar"><Rays Value="90"/><FieldOfView Value="270"/><Period Value="0.1"/></RCLaserScanner>
    <RCImuSensor Key="Imu"><GyroNoise Value="0.001"/><AccelBias Value="0.1 0 0"/></RCImuSensor>
    <RCEncoder Key="Odo"><Joint Ref="Bot.Axle"/><Resolution Value="500"/></RCEncoder>)"));
  REQUIRE(m.sensors.size() == 4);
  const SensorDef& r = m.sensors[0];
  CHECK(r.key == "Bot.Front");
  CHECK(r.kind == SensorKind::Range);
  CHECK(r.body == 0);
  // Local pose relative to the chassis frame, as written.
  CHECK(std::fabs(r.pose.p[0] - 0.2) < 1e-12);
  CHECK(std::fabs(r.pose.p[2]) < 1e-12);
  CHECK(r.min_range == 0.02);
  CHECK(r.max_range == 2);
  CHECK(r.noise == 0.01);
  CHECK(r.resolution == 0.001);
  CHECK(sensorQuantities(r) == std::vector<std::string>{"distance"});
  const SensorDef& l = m.sensors[1];
  CHECK(l.kind == SensorKind::Scanner);
  CHECK(l.rays == 90);
  CHECK(l.field_of_view == 270);
  CHECK(l.period == 0.1);
  CHECK(sensorQuantities(l).size() == 90);
  CHECK(sensorQuantities(l)[89] == "range89");
  const SensorDef& i = m.sensors[2];
  CHECK(i.kind == SensorKind::Imu);
  CHECK(i.gyro_noise == 0.001);
  CHECK(i.accel_bias == Vec3{0.1, 0, 0});
  const SensorDef& e = m.sensors[3];
  CHECK(e.kind == SensorKind::Encoder);
  CHECK(e.joint == 0);
  CHECK(e.resolution == 500);
}

TEST_CASE("sensor types: bad parameters are errors at their line", "[scene][sensors]") {
  struct Case {
    const char* sensor;
    const char* message;
  };
  const Case cases[] = {
      {"<RCRangeSensor Key=\"S\"><MaxRange Value=\"-1\"/></RCRangeSensor>", "MaxRange"},
      {"<RCRangeSensor Key=\"S\"><MaxRange Value=\"0\"/></RCRangeSensor>", "MaxRange"},
      {"<RCRangeSensor Key=\"S\"><MinRange Value=\"3\"/><MaxRange Value=\"2\"/></RCRangeSensor>", "MinRange (3)"},
      {"<RCRangeSensor Key=\"S\"><Noise Value=\"-0.1\"/></RCRangeSensor>", "Noise"},
      {"<RCRangeSensor Key=\"S\"><Resolution Value=\"-0.1\"/></RCRangeSensor>", "Resolution"},
      {"<RCLaserScanner Key=\"S\"><Rays Value=\"0\"/></RCLaserScanner>", "Rays"},
      {"<RCLaserScanner Key=\"S\"><Rays Value=\"100001\"/></RCLaserScanner>", "Rays"},
      {"<RCLaserScanner Key=\"S\"><FieldOfView Value=\"361\"/></RCLaserScanner>", "FieldOfView"},
      {"<RCLaserScanner Key=\"S\"><Period Value=\"-1\"/></RCLaserScanner>", "Period"},
      {"<RCImuSensor Key=\"S\"><AccelNoise Value=\"-1\"/></RCImuSensor>", "AccelNoise"},
      {"<RCEncoder Key=\"S\"><Joint Ref=\"Bot.Lift\"/></RCEncoder>", "must be a hinge joint"},
      {"<RCEncoder Key=\"S\"><Joint Ref=\"Bot.Axle\"/><Resolution Value=\"0\"/></RCEncoder>", "Resolution"},
      {"<RCEncoder Key=\"S\"/>", "parameter 'Joint' is required"},
  };
  // robot() puts the sensors on the line after the slider's closing tag: line 17.
  for (const Case& c : cases) {
    const std::vector<std::string> errors = compileErrors(robot(c.sensor));
    INFO(c.sensor);
    INFO((errors.empty() ? std::string("no error") : errors[0]));
    REQUIRE(errors.size() == 1);
    CHECK(errors[0].find(c.message) != std::string::npos);
    CHECK(errors[0].rfind("test.xml:17: ", 0) == 0);
  }
}

TEST_CASE("RCCameraSensor lowers to Model::camera_sensors, a camera riding on the body", "[scene][sensors]") {
  const Model m = mustCompile(robot(R"(
    <RCCameraSensor Key="Eye">
      <Pose><RCLocalCoordinates><Pose Value="0.2 0.1 0 0 -90 0"/></RCLocalCoordinates></Pose>
      <Width Value="32"/><Height Value="24"/><ViewAngle Value="90"/><Period Value="0.05"/>
    </RCCameraSensor>)"));
  CHECK(m.sensors.empty());  // not a physics sensor
  CHECK(m.cameras.empty());  // nor a camera of the CameraList: the default view stays the default
  REQUIRE(m.camera_sensors.size() == 1);
  const CameraSensorDef& c = m.camera_sensors[0];
  CHECK(c.key == "Bot.Eye");
  CHECK(c.width == 32);
  CHECK(c.height == 24);
  CHECK(c.period == 0.05);
  CHECK(c.camera.key == "Bot.Eye");
  CHECK(c.camera.kind == CameraDef::Mounted);
  CHECK(c.camera.body == 0);
  CHECK(c.camera.view_angle == 90);
  // Relative to the chassis' frame, as the other sensors' poses.
  CHECK(std::fabs(c.camera.pose.p[0] - 0.2) < 1e-12);
  CHECK(std::fabs(c.camera.pose.p[1] - 0.1) < 1e-12);
}

TEST_CASE("RCCameraSensor: bad parameters are errors at their line", "[scene][sensors]") {
  const std::pair<const char*, const char*> cases[] = {
      {"<RCCameraSensor Key=\"S\"><Width Value=\"0\"/></RCCameraSensor>", "Width"},
      {"<RCCameraSensor Key=\"S\"><Height Value=\"8193\"/></RCCameraSensor>", "'Height' must be at most 8192"},
      {"<RCCameraSensor Key=\"S\"><ViewAngle Value=\"180\"/></RCCameraSensor>", "below 180 degrees"},
      {"<RCCameraSensor Key=\"S\"><NearClip Value=\"5\"/><FarClip Value=\"1\"/></RCCameraSensor>", "NearClip (5 m)"},
      {"<RCCameraSensor Key=\"S\"><Period Value=\"-1\"/></RCCameraSensor>", "Period"},
  };
  for (const auto& [sensor, message] : cases) {
    const std::vector<std::string> errors = compileErrors(robot(sensor));
    INFO(sensor);
    INFO((errors.empty() ? std::string("no error") : errors[0]));
    REQUIRE(errors.size() == 1);
    CHECK(errors[0].find(message) != std::string::npos);
    CHECK(errors[0].rfind("test.xml:17: ", 0) == 0);
  }
}
