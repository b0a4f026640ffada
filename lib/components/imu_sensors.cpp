// RCImuSensor (simbob's own periphery type): an inertial measurement unit attached like
// RCProximitySensor to the construction's root body with a Pose. Lowers to Model::sensors
// (SensorKind::Imu); lib/physics/imu.cpp computes the reading. Conventions: docs/sensors.md.
#include "compile/context.h"
#include "components/families.h"

namespace simbob {

namespace {

constexpr LinkParam kPose{"Pose"};
constexpr ValueParam<double> kAccelNoise{"AccelNoise"};
constexpr ValueParam<double> kGyroNoise{"GyroNoise"};
constexpr ValueParam<Triple> kAccelBias{"AccelBias"};
constexpr ValueParam<Triple> kGyroBias{"GyroBias"};
constexpr ValueParam<double> kPeriod{"Period"};

}  // namespace

void lowerImuSensor(CompileContext& ctx, const Component& c, const Built& parent) {
  const std::string key = ctx.modelKey(c);
  ctx.recordSensor(key, kFailedActuator);
  if (!parent.ok) return;
  SensorDef s;
  s.key = key;
  s.loc = c.loc;
  s.kind = SensorKind::Imu;
  s.body = parent.index;
  s.noise = c.get(kAccelNoise);
  s.gyro_noise = c.get(kGyroNoise);
  const Triple& ab = c.get(kAccelBias);
  const Triple& gb = c.get(kGyroBias);
  s.accel_bias = {ab[0], ab[1], ab[2]};
  s.gyro_bias = {gb[0], gb[1], gb[2]};
  s.period = c.get(kPeriod);
  bool ok = checkSensorPeriod(ctx, c, c.slotOf(kPeriod), s.period);
  if (!lowerSensorPose(ctx, c, c.get(kPose), parent, &s.pose)) ok = false;
  if (!ok) return;
  ctx.recordSensor(key, static_cast<int>(ctx.model.sensors.size()));
  ctx.model.sensors.push_back(std::move(s));
}

void registerImuSensors(Registry& r) {
  TypeSpec imu{
      "RCImuSensor",
      Family::Periphery,
      int(PeripheryKind::ImuSensor),
      {componentParam(kPose, {Family::Pose}, "",
                      "pose of the sensor: local coordinates relative to the construction's root body "
                      "(default: its frame), or global"),
       number(kAccelNoise, 0.0, "m/s^2", "standard deviation of the accelerometer's Gaussian noise",
              Range::NonNegative),
       number(kGyroNoise, 0.0, "rad/s", "standard deviation of the gyro's Gaussian noise", Range::NonNegative),
       triple(kAccelBias, {0, 0, 0}, "m/s^2", "constant accelerometer bias, sensor frame"),
       triple(kGyroBias, {0, 0, 0}, "rad/s", "constant gyro bias, sensor frame"),
       number(kPeriod, 0.0, "s", "time between readings (0: every step); held in between", Range::NonNegative)},
      {},
      "Inertial measurement unit: specific force ax ay az (m/s^2; +g upwards at rest) and angular "
      "velocity gx gy gz (rad/s), in the sensor frame (docs/sensors.md)."};
  imu.interfaces = {"RCImuSensor"};
  r.add(imu);
}

}  // namespace simbob
