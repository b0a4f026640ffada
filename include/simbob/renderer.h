// Off-screen rendering of a compiled model (issue #12, Record): lib/render, the only code with
// GL headers. A Renderer owns one GL context (EGL without a display, or OSMesa), draws the
// model's visuals at given body poses through one camera and returns an Image. The Recorder is
// a party of the run loop that asks for a frame at t = n / fps; a FrameDrawer draws it and hands
// it to a FrameSink, on the run loop's thread or on a render thread of its own.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "simbob/error.h"
#include "simbob/image.h"
#include "simbob/model.h"
#include "simbob/loop.h"

namespace simbob {

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
  Quality quality = Quality::Transparency;  ///< textures, shadows and transparent skins; no fog
  std::string camera;                       ///< a camera's qualified key; "" = the first, else a default view
  std::string texture_folder;               ///< global setting TextureFolder ("" = only beside the scene)
  bool draw_models = true;                  ///< the models (visuals) of the scene
  bool draw_geoms = false;                  ///< the collision shapes: filled alone, wire frames over models
  /// draw_models and draw_geoms are the caller's choice (--draw). Otherwise, when the models show
  /// no body (modelsShowNoBody), the renderer draws the collision shapes alone instead: a
  /// picture of nothing helps nobody.
  bool draw_chosen = false;
  /// Range sensors' and laser scanners' rays, from the sensor to its reading (setSensorRays),
  /// red, and the hit points (readings below MaxRange), yellow, drawn over the scene.
  bool draw_sensors = false;
};

class World;
/// The lengths the rays of RenderOptions::draw_sensors end at: the reading (m) of every ray of
/// every RCRangeSensor and RCLaserScanner, in Model::sensors order, concatenated.
std::vector<double> sensorRays(const Model& model, const World& world);

/// True when the models show none of the bodies there are (no model on any mobile body, or no
/// model at all while there are collision shapes): drawing them alone gives an empty picture.
bool modelsShowNoBody(const Model& model);

/// What to say when a renderer with these options draws the collision shapes instead of models
/// that show no body (RenderOptions::draw_chosen), or "" when it draws what it was asked to.
std::string drawFallbackNote(const Model& model, const RenderOptions& options);

/// Every texture file the model's skins may be read from: each place the renderer looks
/// (TextureFolder, then beside the scene file; as written, .bmp, .png) that holds a file. Inputs
/// no output may replace.
std::vector<std::string> textureFiles(const Model& model, const std::string& texture_folder);

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
  /// The ray lengths (sensorRays) the next render() draws with draw_sensors; until set, every
  /// ray is drawn to its MaxRange without a hit point.
  virtual void setSensorRays(const std::vector<double>& lengths) = 0;
  /// Moves the camera as drawing a frame at these poses would, without drawing: a still at T
  /// follows the frames a recording would have drawn before T.
  virtual void follow(const std::vector<Transform>& poses) = 0;
  /// The GL context is current on one thread at a time: the creating thread, until it calls
  /// release(); then the thread that calls acquire(). Drawing happens on that thread only.
  /// acquire() fails (null return is success) if the back end refuses the context.
  virtual const Error* acquire() = 0;
  virtual void release() = 0;
  /// "EGL (surfaceless)", "EGL (device)" or "OSMesa".
  virtual std::string backendName() const = 0;
  /// GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  virtual std::string glRenderer() const = 0;
  /// The camera drawn through: its key, or "(default)".
  virtual std::string cameraName() const = 0;
};

/// How many frames from number `drawn` on are due at grid instant `now` (at or before now +
/// min_step): each of them shows `now`. More than one when frames come faster than the step.
uint64_t framesDue(uint64_t drawn, double fps, SimTime now, SimTime min_step);

/// What the recorder hands each frame to: the body poses at simulated time t, to be drawn by a
/// Renderer and passed on to a FrameSink, in the order given.
class FrameDrawer {
 public:
  virtual ~FrameDrawer() = default;
  /// The frame at these poses, with these sensor ray lengths (sensorRays; empty when not
  /// drawn). The first error of drawing or of the sink, else null.
  virtual const Error* draw(const std::vector<Transform>& poses, double t, const std::vector<double>& rays) = 0;
  const Error* draw(const std::vector<Transform>& poses, double t) { return draw(poses, t, {}); }
  /// Every frame drawn and handed on, then the sink finished. Null on success.
  virtual const Error* finish() = 0;
};

/// Draws on the calling thread and hands each frame to the sink there: step, draw, encode, step.
std::unique_ptr<FrameDrawer> drawInline(Renderer& renderer, FrameSink& sink);

/// A render thread: the renderer's GL context moves to a thread of its own, which draws the
/// frames in order from a queue of at most `queue_frames` pose sets and hands each to the sink
/// there, so that the physics steps on while the last frame draws (issue #12 point 7). draw()
/// returns once the poses are queued (waiting only while the queue is full). finish() waits for
/// the queue to drain, gives the context back to the calling thread and finishes the sink;
/// destroying it unfinished drops what is queued and gives the context back too. Neither the
/// renderer nor the sink may be used elsewhere in between. The frames are the same bytes as
/// drawInline's: one renderer, the same poses, the same order.
std::unique_ptr<FrameDrawer> drawOnRenderThread(Renderer& renderer, FrameSink& sink, size_t queue_frames = 2);

/// The recorder: a party that asks for frame n at t = n / fps, is granted at the first grid
/// instant at or after it (frameTime, framesDue) and hands the poses to a FrameDrawer once per
/// frame due. It only reads the world.
class Recorder : public Party {
 public:
  /// `rays_of` (may be null): also hands the drawer this model's sensor ray lengths
  /// (RenderOptions::draw_sensors).
  Recorder(FrameDrawer& drawer, double fps, SimTime min_step, int body_count, const Model* rays_of = nullptr);
  SimTime first() override;
  SimTime onGrant(SimTime now, World& world) override;
  void finish(SimTime end, World& world) override;
  const Error* failure() const override;
  uint64_t frames() const { return frames_; }

 private:
  FrameDrawer& drawer_;
  double fps_;
  SimTime min_step_;
  std::vector<Transform> poses_;
  const Model* rays_of_ = nullptr;
  std::vector<double> rays_;
  uint64_t frames_ = 0;
  Error error_;
  bool failed_ = false;
};

/// `run --record DIR` and `--video FILE`: a renderer, its render thread, the frame sinks (PNG
/// sequence, video, both through one encoding thread) and the Recorder party that feeds them.
struct RecordingRequest {
  RenderOptions render;
  double fps = 30;
  std::string record_dir;  ///< "" for no PNG sequence
  std::string video;       ///< "" for no video (a file, or a stream written through)
  std::string video_temp;  ///< where the encoder writes a file video ("" : straight to `video`)
};

class Recording {
 public:
  /// Checks and creates everything before the run: the folder (which must not already hold a
  /// recording), the video's encoder (ErrorKind::Usage for an unknown extension or an odd size
  /// for H.264) and the GL context. nullptr and *err on failure.
  static std::unique_ptr<Recording> open(const Model& model, const RecordingRequest& request, SimTime min_step,
                                         Error* err);
  ~Recording();
  Recording(const Recording&) = delete;
  Recording& operator=(const Recording&) = delete;
  /// The party to add to the run (it draws on the render thread while the physics steps on).
  Recorder& recorder() { return *recorder_; }
  /// "recording through BACKEND (GL_RENDERER), camera NAME", for a debug line.
  std::string description() const;

 private:
  Recording() = default;
  std::unique_ptr<Renderer> renderer_;
  std::unique_ptr<FrameSink> sink_;
  std::unique_ptr<FrameDrawer> drawer_;
  std::unique_ptr<Recorder> recorder_;
};

}  // namespace simbob
