// RCCameraSensor (simbob's own periphery type): a camera attached like RCProximitySensor to the
// construction's root body with a Pose, whose image the Simulation renders at each Period
// instant (lib/simulation/camera_sensors.cpp). Lowers to Model::camera_sensors, never to the
// physics' sensor list: a World has no GL. Conventions: docs/sensors.md.
#include <algorithm>

#include "compile/context.h"
#include "components/families.h"

namespace simbob {

namespace {

constexpr LinkParam kPose{"Pose"};
constexpr ValueParam<int64_t> kWidth{"Width"};
constexpr ValueParam<int64_t> kHeight{"Height"};
constexpr ValueParam<double> kViewAngle{"ViewAngle"};
constexpr ValueParam<double> kNearClip{"NearClip"};
constexpr ValueParam<double> kFarClip{"FarClip"};
constexpr ValueParam<double> kPeriod{"Period"};

constexpr int64_t kMaxSide = 8192;  // pixels: the renderer's kMaxSide
/// Pixels of all camera sensors' images together: one full-size image. Each pixel costs about
/// 12 bytes (the image, its GL colour and depth buffers, the read-back copy): 800 MB.
constexpr int64_t kMaxPixels = kMaxSide * kMaxSide;

}  // namespace

void lowerCameraSensor(CompileContext& ctx, const Component& c, const Built& parent) {
  if (!parent.ok) return;
  CameraSensorDef s;
  s.key = ctx.modelKey(c);
  s.loc = c.loc;
  s.period = c.get(kPeriod);
  bool ok = checkSensorPeriod(ctx, c, c.slotOf(kPeriod), s.period);
  for (const auto* p : {&kWidth, &kHeight}) {
    const int64_t v = c.get(*p);
    if (v > kMaxSide) {
      ctx.errorAt(c.slotOf(*p), c,
                  std::string("parameter '") + p->name + "' must be at most " + std::to_string(kMaxSide) +
                      " pixels, got " + std::to_string(v));
      ok = false;
    }
  }
  s.width = static_cast<int>(std::min<int64_t>(c.get(kWidth), kMaxSide));
  s.height = static_cast<int>(std::min<int64_t>(c.get(kHeight), kMaxSide));
  CameraDef& cam = s.camera;
  cam.key = s.key;
  cam.view_angle = c.get(kViewAngle);
  cam.near_clip = c.get(kNearClip);
  cam.far_clip = c.get(kFarClip);
  if (!(cam.view_angle < 180)) {
    ctx.errorAt(c.slotOf(kViewAngle), c,
                "parameter 'ViewAngle' must be below 180 degrees, got " + formatNumber(cam.view_angle));
    ok = false;
  }
  if (!(cam.near_clip < cam.far_clip)) {
    ctx.errorAt(c.slotOf(kFarClip), c,
                "NearClip (" + formatNumber(cam.near_clip) + " m) must be closer than FarClip (" +
                    formatNumber(cam.far_clip) + " m)");
    ok = false;
  }
  if (!lowerSensorPose(ctx, c, c.get(kPose), parent, &cam.pose)) ok = false;
  int64_t pixels = int64_t{s.width} * s.height;
  for (const CameraSensorDef& other : ctx.model.camera_sensors) pixels += int64_t{other.width} * other.height;
  if (ok && pixels > kMaxPixels) {
    ctx.errorAt(c.slotOf(kWidth), c,
                "the camera sensors' images together would be " + std::to_string(pixels) + " pixels, more than " +
                    std::to_string(kMaxPixels) + " (one 8192 x 8192 image)");
    ok = false;
  }
  // On a mobile body the pose rides with it; on a static root it is global.
  cam.body = parent.index;
  cam.kind = parent.index >= 0 ? CameraDef::Mounted : CameraDef::Static;
  if (!ok) return;
  ctx.model.camera_sensors.push_back(std::move(s));
}

void registerCameraSensors(Registry& r) {
  TypeSpec cam{
      "RCCameraSensor",
      Family::Periphery,
      int(PeripheryKind::CameraSensor),
      {componentParam(kPose, {Family::Pose}, "",
                      "pose of the camera: local coordinates relative to the construction's root body (default: "
                      "its frame), or global; it looks along its local -Z with +Y up"),
       integer(kWidth, 160, "image width in pixels (1 to 8192)", Range::Positive),
       integer(kHeight, 120, "image height in pixels (1 to 8192)", Range::Positive),
       number(kViewAngle, 60.0, "deg", "horizontal view angle, below 180", Range::Positive),
       number(kNearClip, 0.05, "m", "near clipping distance", Range::Positive),
       number(kFarClip, 100.0, "m", "far clipping distance (beyond NearClip)", Range::Positive),
       number(kPeriod, 0.1, "s", "time between images (0: every step); held in between", Range::NonNegative)},
      {},
      "A camera on the robot: an RGB image (rows top first) rendered at each Period instant by the "
      "renderer of `simbob render`, read through World::cameraImage (controllers), Simulation::cameraImage or "
      "Python's sim.camera_image (docs/sensors.md)."};
  cam.interfaces = {"RCCameraSensor"};
  r.add(cam);
}

}  // namespace simbob
