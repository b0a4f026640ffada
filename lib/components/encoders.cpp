// RCEncoder (simbob's own periphery type): a rotary encoder on a hinge joint of the construction,
// counting Resolution ticks per turn of the hinge's total (unwrapped) angle. Lowers to
// Model::sensors (SensorKind::Encoder); lib/physics/sensors.cpp computes the reading.
#include "compile/context.h"
#include "components/families.h"

namespace simbob {

namespace {

constexpr LinkParam kJoint{"Joint"};
constexpr ValueParam<int64_t> kResolution{"Resolution"};
constexpr ValueParam<double> kPeriod{"Period"};

constexpr int64_t kMaxResolution = 1000000000;

}  // namespace

void lowerEncoder(CompileContext& ctx, const Component& c, const Built& parent) {
  const std::string key = ctx.modelKey(c);
  ctx.recordSensor(key, kFailedActuator);
  if (!parent.ok) return;
  const Link& jl = c.get(kJoint);
  if (jl.comp < 0) {
    if (!jl.isRef()) ctx.error(c, "parameter 'Joint' is required (a Ref to the hinge joint it measures)");
    return;
  }
  const Component& joint = ctx.at(jl.comp);
  JointKind kind;
  if (joint.type->family != Family::Joint || !jointKindOf(ctx, joint, &kind)) return;  // reported by the loader
  bool ok = true;
  if (kind != JointKind::Hinge) {
    ctx.error(jl, c, "parameter 'Joint' must be a hinge joint, but " + CompileContext::describe(joint) + " is not");
    ok = false;
  }
  SensorDef s;
  s.key = key;
  s.loc = c.loc;
  s.kind = SensorKind::Encoder;
  s.body = parent.index;
  const int64_t res = c.get(kResolution);
  if (res > kMaxResolution) {
    ctx.errorAt(c.slotOf(kResolution), c,
                "parameter 'Resolution' must be at most 1000000000 ticks per turn, got " + std::to_string(res));
    ok = false;
  }
  s.resolution = static_cast<double>(res);
  s.period = c.get(kPeriod);
  if (!checkSensorPeriod(ctx, c, c.slotOf(kPeriod), s.period)) ok = false;
  if (!ok) return;
  s.joint = ctx.jointIndex(ctx.modelKey(joint));
  if (s.joint < 0) {
    if (!ctx.failedQuietly())
      ctx.error(jl, c,
                "parameter 'Joint' refers to " + CompileContext::describe(joint) +
                    ", which is not built before this periphery: put the encoder in the ChildList of the "
                    "construction that holds the joint (after it)");
    return;
  }
  ctx.recordSensor(key, static_cast<int>(ctx.model.sensors.size()));
  ctx.model.sensors.push_back(std::move(s));
}

void registerEncoders(Registry& r) {
  TypeSpec enc{
      "RCEncoder",
      Family::Periphery,
      int(PeripheryKind::Encoder),
      {componentParam(kJoint, {Family::Joint}, "", "hinge joint it measures (Ref)"),
       integer(kResolution, 1024, "ticks per turn (1 to 1e9)", Range::Positive),
       number(kPeriod, 0.0, "s", "time between readings (0: every step); held in between", Range::NonNegative)},
      {},
      "Rotary encoder on a hinge: ticks = floor(total angle / 2 pi * Resolution), the angle unwrapped "
      "across turns (docs/sensors.md)."};
  enc.interfaces = {"RCEncoder"};
  r.add(enc);
}

}  // namespace simbob
