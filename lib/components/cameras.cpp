// CameraComponents (guide 3.5): the views of a scene; the renderer draws through them.
// Lowering checks what makes a view impossible (clip planes, view angle, missing bodies).
#include "compile/context.h"
#include "components/families.h"
#include "simbob/transform.h"

namespace simbob {

namespace {

enum class CameraKind { Static, Mounted, Spotlight, Tracking };

constexpr ValueParam<double> kViewAngle{"ViewAngle"};
constexpr ValueParam<double> kNearClip{"NearClip"};
constexpr ValueParam<double> kFarClip{"FarClip"};
constexpr LinkParam kPose{"Pose"};
constexpr LinkParam kBody{"Body"};
constexpr ValueParam<bool> kAutoViewAngle{"AutoViewAngle"};
constexpr ValueParam<double> kDistance{"Distance"};

constexpr double kMaxViewAngle = 180.0;  // deg: a pinhole camera sees less than a half space

}  // namespace

void registerCameras(Registry& r) {
  r.setFamilyParams(Family::Camera,
                    {number(kViewAngle, 60.0, "deg", "horizontal view angle, below 180", Range::Positive),
                     number(kNearClip, 0.1, "m", "near clipping distance", Range::Positive),
                     number(kFarClip, 1000.0, "m", "far clipping distance (beyond NearClip)", Range::Positive)});
  r.add({"RCStaticCamera",
         Family::Camera,
         int(CameraKind::Static),
         {componentParam(kPose, {Family::Pose}, "RCGlobalCoordinates", "camera pose; looks along its local -Z")},
         {"StaticCamera"},
         "A camera at a fixed global pose."});
  r.add({"RCMountedCamera",
         Family::Camera,
         int(CameraKind::Mounted),
         {componentParam(kPose, {Family::Pose}, "", "pose relative to Body"),
          componentParam(kBody, {Family::Body}, "", "carrier body (Ref)")},
         {"MountedCamera"},
         "A camera riding on a body.",
         true});
  r.add({"RCSpotlightCamera",
         Family::Camera,
         int(CameraKind::Spotlight),
         {componentParam(kPose, {Family::Pose}, "RCGlobalCoordinates", "camera position"),
          componentParam(kBody, {Family::Body}, "", "body to look at (Ref)"),
          flag(kAutoViewAngle, false, "keep the body's apparent size")},
         {"SpotlightCamera"},
         "A fixed camera that keeps looking at a body.",
         true});
  r.add({"RCTrackingCamera",
         Family::Camera,
         int(CameraKind::Tracking),
         {componentParam(kBody, {Family::Body}, "", "body to follow (Ref)"),
          number(kDistance, 5.0, "m", "distance kept from the body", Range::Positive)},
         {"TrackingCamera"},
         "A camera following a body at a fixed distance.",
         true});
}

void lowerCamera(CompileContext& ctx, int comp) {
  const Component& c = ctx.at(comp);
  if (c.get(kViewAngle) >= kMaxViewAngle)
    ctx.errorAt(c.slotOf(kViewAngle), c,
                "parameter 'ViewAngle' must be below 180 degrees, got " + formatNumber(c.get(kViewAngle)));
  if (c.get(kNearClip) >= c.get(kFarClip))
    ctx.errorAt(c.slotOf(kFarClip), c,
                "NearClip (" + formatNumber(c.get(kNearClip)) + " m) must be closer than FarClip (" +
                    formatNumber(c.get(kFarClip)) + " m)");
  CameraDef d;
  d.key = c.qkey;
  d.view_angle = c.get(kViewAngle);
  d.near_clip = c.get(kNearClip);
  d.far_clip = c.get(kFarClip);
  const auto kind = static_cast<CameraKind>(c.type->kind);
  d.kind = static_cast<CameraDef::Kind>(kind);
  switch (kind) {
    case CameraKind::Static:
      lowerPose(ctx, c.get(kPose), c, nullptr, &d.pose);
      break;
    case CameraKind::Mounted:
    case CameraKind::Spotlight:
    case CameraKind::Tracking: {
      const Link& b = c.get(kBody);
      if (b.comp < 0) {
        if (!b.isRef()) ctx.error(c, "parameter 'Body' is required (a Ref to the body it follows)");
        break;
      }
      d.body = ctx.bodyIndex(ctx.modelKey(ctx.at(b.comp)));
      if (d.body < 0) {
        // A static body (or one not lowered): follow the place it stands.
        const Built* built = ctx.memo.find(b.comp);
        if (!built || !built->ok) {
          ctx.error(b, c, "parameter 'Body' must refer to a body of the ComponentList");
          break;
        }
        d.target = built->frame.p;
        d.pose = built->frame;
      }
      if (kind == CameraKind::Mounted) {
        const Transform rel = poseValue(ctx, c.get(kPose));
        d.pose = d.body < 0 ? compose(d.pose, rel) : rel;
      } else if (kind == CameraKind::Spotlight) {
        lowerPose(ctx, c.get(kPose), c, nullptr, &d.pose);
        d.auto_view_angle = c.get(kAutoViewAngle);
      } else {
        d.distance = c.get(kDistance);
      }
      break;
    }
  }
  ctx.model.cameras.push_back(std::move(d));
}

}  // namespace simbob
