// CameraComponents (guide 3.5). Parsed and kept for the renderer.
#include "components/families.h"

namespace simbob {

void registerCameras(Registry& r) {
  r.setFamilyParams(Family::Camera, {number("ViewAngle", 60.0, "deg", "horizontal view angle", Range::Positive),
                                     number("NearClip", 0.1, "m", "near clipping distance", Range::Positive),
                                     number("FarClip", 1000.0, "m", "far clipping distance", Range::Positive)});
  r.add({"RCStaticCamera",
         Family::Camera,
         int(CameraKind::Static),
         {componentParam("Pose", {Family::Pose}, "RCGlobalCoordinates", "camera pose; looks along its local -Z")},
         {"StaticCamera"},
         "A camera at a fixed global pose."});
  r.add({"RCMountedCamera",
         Family::Camera,
         int(CameraKind::Mounted),
         {componentParam("Pose", {Family::Pose}, "", "pose relative to Body"),
          componentParam("Body", {Family::Body}, "", "carrier body (Ref)")},
         {"MountedCamera"},
         "A camera riding on a body.",
         true});
  r.add({"RCSpotlightCamera",
         Family::Camera,
         int(CameraKind::Spotlight),
         {componentParam("Pose", {Family::Pose}, "RCGlobalCoordinates", "camera position"),
          componentParam("Body", {Family::Body}, "", "body to look at (Ref)"),
          flag("AutoViewAngle", false, "keep the body's apparent size")},
         {"SpotlightCamera"},
         "A fixed camera that keeps looking at a body.",
         true});
  r.add({"RCTrackingCamera",
         Family::Camera,
         int(CameraKind::Tracking),
         {componentParam("Body", {Family::Body}, "", "body to follow (Ref)"),
          number("Distance", 5.0, "m", "distance kept from the body", Range::Positive)},
         {"TrackingCamera"},
         "A camera following a body at a fixed distance.",
         true});
}

}  // namespace simbob
