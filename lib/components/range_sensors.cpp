// Range sensors (simbob's own periphery types): RCRangeSensor, one ray (an IR, sonar or laser
// distance sensor), and RCLaserScanner, a fan of rays in the sensor's plane. Both are attached
// like RCProximitySensor to the construction's root body with a Pose and lower to Model::sensors
// (SensorKind::Range, Scanner); lib/physics/rays.cpp casts the rays. Reading conventions:
// docs/sensors.md.
#include <cmath>

#include "compile/context.h"
#include "components/families.h"

namespace simbob {

namespace {

constexpr LinkParam kPose{"Pose"};
constexpr ValueParam<double> kMinRange{"MinRange"};
constexpr ValueParam<double> kMaxRange{"MaxRange"};
constexpr ValueParam<double> kNoise{"Noise"};
constexpr ValueParam<double> kResolution{"Resolution"};
constexpr ValueParam<double> kPeriod{"Period"};
constexpr ValueParam<int64_t> kRays{"Rays"};
constexpr ValueParam<double> kFieldOfView{"FieldOfView"};

constexpr int64_t kMaxRays = 100000;
constexpr double kMaxRangeLimit = 1e6;  // m: beyond this a ray's arithmetic loses the 1e-9 m it promises

}  // namespace

void lowerRangeSensor(CompileContext& ctx, const Component& c, const Built& parent) {
  const std::string key = ctx.modelKey(c);
  ctx.recordSensor(key, kFailedActuator);  // until it is lowered: controllers referring to it say nothing more
  if (!parent.ok) return;
  SensorDef s;
  s.key = key;
  s.loc = c.loc;
  s.kind =
      static_cast<PeripheryKind>(c.type->kind) == PeripheryKind::LaserScanner ? SensorKind::Scanner : SensorKind::Range;
  s.body = parent.index;
  s.static_body = parent.static_id;
  s.min_range = c.get(kMinRange);
  s.max_range = c.get(kMaxRange);
  s.noise = c.get(kNoise);
  s.period = c.get(kPeriod);
  bool ok = true;
  if (!(s.max_range > 0 && s.max_range <= kMaxRangeLimit)) {
    ctx.errorAt(c.slotOf(kMaxRange), c,
                "parameter 'MaxRange' must be greater than 0 and at most 1e6 m, got " + formatNumber(s.max_range));
    ok = false;
  } else if (!(s.min_range < s.max_range)) {
    ctx.errorAt(
        c.slotOf(kMinRange), c,
        "MinRange (" + formatNumber(s.min_range) + ") must be less than MaxRange (" + formatNumber(s.max_range) + ")");
    ok = false;
  }
  if (!checkSensorPeriod(ctx, c, c.slotOf(kPeriod), s.period)) ok = false;
  if (s.kind == SensorKind::Range) {
    s.resolution = c.get(kResolution);
  } else {
    const int64_t rays = c.get(kRays);
    if (rays > kMaxRays) {
      ctx.errorAt(c.slotOf(kRays), c, "parameter 'Rays' must be at most 100000, got " + std::to_string(rays));
      ok = false;
    }
    s.rays = static_cast<int>(std::min(rays, kMaxRays));
    s.field_of_view = c.get(kFieldOfView);
    if (!(s.field_of_view > 0 && s.field_of_view <= 360)) {
      ctx.errorAt(c.slotOf(kFieldOfView), c,
                  "parameter 'FieldOfView' must be greater than 0 and at most 360 degrees, got " +
                      formatNumber(s.field_of_view));
      ok = false;
    }
  }
  if (!lowerSensorPose(ctx, c, c.get(kPose), parent, &s.pose)) ok = false;
  if (!ok) return;
  ctx.recordSensor(key, static_cast<int>(ctx.model.sensors.size()));
  ctx.model.sensors.push_back(std::move(s));
}

void registerRangeSensors(Registry& r) {
  const ParamSpec pose = componentParam(kPose, {Family::Pose}, "",
                                        "pose of the sensor: local coordinates relative to the construction's root "
                                        "body (default: its frame), or global");
  const ParamSpec min_range =
      number(kMinRange, 0.0, "m", "closest distance it measures: a nearer hit reads MinRange", Range::NonNegative);
  const ParamSpec max_range = number(kMaxRange, 5.0, "m",
                                     "farthest distance it measures, and the reading when "
                                     "nothing is hit",
                                     Range::Positive);
  const ParamSpec noise =
      number(kNoise, 0.0, "m", "standard deviation of the Gaussian noise added to a hit", Range::NonNegative);
  const ParamSpec period =
      number(kPeriod, 0.0, "s", "time between readings (0: every step); held in between", Range::NonNegative);
  TypeSpec range{
      "RCRangeSensor",
      Family::Periphery,
      int(PeripheryKind::RangeSensor),
      {pose, min_range, max_range, noise,
       number(kResolution, 0.0, "m", "the reading is rounded to a multiple of it (0: not rounded)", Range::NonNegative),
       period},
      {},
      "One ray along the sensor's local -Z (an IR, sonar or laser distance sensor): reads the distance "
      "to the first geom of another body (docs/sensors.md)."};
  range.interfaces = {"RCRangeSensor"};
  r.add(range);
  TypeSpec scanner{"RCLaserScanner",
                   Family::Periphery,
                   int(PeripheryKind::LaserScanner),
                   {pose, integer(kRays, 36, "number of rays (1 to 100000)", Range::Positive),
                    number(kFieldOfView, 180.0, "deg", "angle the rays cover in the sensor's X-Z plane (up to 360)",
                           Range::Positive),
                    min_range, max_range, noise, period},
                   {},
                   "Rays evenly over FieldOfView in the sensor's X-Z plane, centred on its local -Z, from its "
                   "right to its left: one distance per ray (docs/sensors.md)."};
  scanner.interfaces = {"RCLaserScanner"};
  r.add(scanner);
}

}  // namespace simbob
