// Off-screen rendering of a compiled model (issue #12, Record): lib/render, the only code with
// GL headers. A Renderer owns one GL context (EGL without a display, or OSMesa), draws the
// model's visuals at given body poses through one camera and returns an Image. The Recorder is
// a party of the run loop that renders at t = n / fps and hands the frames to a FrameSink.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "simbob/error.h"
#include "simbob/image.h"
#include "simbob/model.h"
#include "simbob/run.h"

namespace simbob {

/// Which GL implementation renders: Auto tries EGL (surfaceless, then device platform), then
/// OSMesa.
enum class GlBackend { Auto, Egl, OsMesa };

/// View quality levels of guide 3.3.3; each level adds to the ones before it.
enum class Quality { Frame, Wire, Plane, Flat, Smooth, Textures, Shadows, Transparency, Fog };

/// "frame", "wire", ... "fog" (case-insensitive) -> level; false if unknown.
bool parseQuality(const std::string& text, Quality* out);
const char* qualityName(Quality q);
/// "egl", "osmesa", "auto" -> back end; false if unknown.
bool parseGlBackend(const std::string& text, GlBackend* out);

struct RenderOptions {
  int width = 640;   ///< pixels
  int height = 480;  ///< pixels
  GlBackend backend = GlBackend::Auto;
  Quality quality = Quality::Shadows;  ///< Smooth with textures and shadows
  std::string camera;                  ///< a camera's qualified key; "" = the first, else a default view
  std::string texture_folder;          ///< global setting TextureFolder ("" = only beside the scene)
};

constexpr int kMaxImageSide = 8192;  ///< pixels, per side

/// Body poses at t = 0 (Model::bodies order), for stills and the default camera.
std::vector<Transform> initialPoses(const Model& model);

class Renderer {
 public:
  /// Creates the GL context and loads the textures. Errors: MissingInput (no GL back end, naming
  /// the package to install; a texture file not found), InvalidInput (unknown camera, bad size,
  /// unreadable texture).
  static std::unique_ptr<Renderer> create(const Model& model, const RenderOptions& opts, Error* err);
  virtual ~Renderer();
  /// Draws the model with body i at poses[i] at simulated time `t` (s) into `out` (rows top first).
  /// A tracking camera moves and a spotlight with AutoViewAngle takes its first distance here,
  /// so the picture depends on the frames drawn before it.
  virtual const Error* render(const std::vector<Transform>& poses, double t, Image* out) = 0;
  /// Moves the camera as drawing a frame at these poses would, without drawing: a still at T
  /// follows the frames a recording would have drawn before T.
  virtual void follow(const std::vector<Transform>& poses) = 0;
  /// "EGL (surfaceless)", "EGL (device)" or "OSMesa".
  virtual std::string backendName() const = 0;
  /// GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  virtual std::string glRenderer() const = 0;
  /// The camera drawn through: its key, or "(default)".
  virtual std::string cameraName() const = 0;
};

/// The time of the frame after the one just drawn as frame number `drawn - 1` at `now`: frame n
/// shows t = n / fps, skipping frames closer than `min_step` to now (the clock cannot reach them
/// apart from it). Advances *drawn past the skipped frames; kNever beyond the clock's range.
SimTime nextFrameTime(uint64_t* drawn, double fps, SimTime now, SimTime min_step);

/// The recorder: a party that renders frame n at t = n / fps (each at the time the clock
/// reached, within MinTimeStep of the request) and hands it to `sink`. It only reads the world.
class Recorder : public Party {
 public:
  Recorder(Renderer& renderer, FrameSink& sink, double fps, SimTime min_step, int body_count);
  SimTime first() override;
  SimTime onGrant(SimTime now, World& world) override;
  void finish(SimTime end, World& world) override;
  const Error* failure() const override;
  uint64_t frames() const { return frames_; }

 private:
  Renderer& renderer_;
  FrameSink& sink_;
  double fps_;
  SimTime min_step_;
  std::vector<Transform> poses_;
  uint64_t frames_ = 0;
  Error error_;
  bool failed_ = false;
};

}  // namespace simbob
