// simbob render (one still at a simulated time), simbob info (the GL back ends), and the view
// options shared with `run --record` (issue #12).
#include <CLI/CLI.hpp>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "cli.h"
#include "commands.h"
#include "simbob/renderer.h"
#include "simbob/physics.h"
#include "simbob/tool/png.h"
#include "simbob/robot.h"
#include "simbob/loop.h"
#include "simbob/scene_run.h"
#include "simbob/tool/document_ini.h"
#include "simbob/values.h"
#include "version.h"

namespace simbob::cli {

namespace {

/// The party of `render --at T`: keeps the poses at T (and the sensor rays, for --draw sensors).
class Still : public Party {
 public:
  Still(SimTime at, size_t bodies, const Model* rays_of) : at_(at), poses_(bodies), rays_of_(rays_of) {}
  SimTime first() override { return at_; }
  SimTime onGrant(SimTime /*now*/, World& world) override {
    for (int i = 0; i < world.bodyCount(); ++i) poses_[static_cast<size_t>(i)] = world.body(i).pose;
    if (rays_of_) rays_ = sensorRays(*rays_of_, world);
    taken_ = true;
    return kNever;
  }
  bool taken() const { return taken_; }
  const std::vector<Transform>& poses() const { return poses_; }
  const std::vector<double>& rays() const { return rays_; }

 private:
  SimTime at_;
  std::vector<Transform> poses_;
  const Model* rays_of_;
  std::vector<double> rays_;
  bool taken_ = false;
};

/// The frames a recording at --fps draws before --at, replayed without drawing, so that a
/// camera that moves (RCTrackingCamera) or remembers (AutoViewAngle) is where it would be.
class Follower : public Party {
 public:
  Follower(Renderer& renderer, double fps, SimTime at, SimTime min_step, size_t bodies)
      : renderer_(renderer), fps_(fps), at_(at), min_step_(min_step), poses_(bodies) {}
  SimTime first() override { return at_ > 0 ? 0 : kNever; }
  SimTime onGrant(SimTime now, World& world) override {
    for (int i = 0; i < world.bodyCount(); ++i) poses_[static_cast<size_t>(i)] = world.body(i).pose;
    // Every frame due at this instant shows it, as Recorder draws them.
    const uint64_t due = framesDue(frames_, fps_, now, min_step_);
    for (uint64_t k = 0; k < due; ++k) renderer_.follow(poses_);
    frames_ += due;
    const SimTime next = frameTime(frames_, fps_);
    return next < at_ ? next : kNever;
  }

 private:
  Renderer& renderer_;
  double fps_;
  SimTime at_, min_step_;
  std::vector<Transform> poses_;
  uint64_t frames_ = 0;
};

}  // namespace

void addViewOptions(CLI::App* app, ViewArgs& v) {
  app->add_option("--size", v.size, "Image size WIDTHxHEIGHT in pixels (default 640x480)");
  app->add_option("--camera", v.camera,
                  "Camera key (default: the scene's first camera, else a view framing every body where it is drawn)");
  app->add_option(
      "--quality", v.quality,
      "View quality, each level adding to the one before: frame (bounding boxes), wire, plane (unlit fill), "
      "flat, smooth (lit), textures, shadows, transparency (default: all but fog), fog");
  app->add_option("--fps", v.fps,
                  "Frames per simulated second (default 30): of --record and --video; of the recording a still at "
                  "--at matches (moving cameras follow its frames)");
  app->add_option("--draw", v.draw,
                  "What to draw, a comma list: models (default), geoms (the collision shapes; wire frames over "
                  "models), sensors (range sensor and scanner rays to their readings, hit points); without it, geoms "
                  "when no body has a model");
  app->add_option("--gl", v.gl, "GL back end: egl or osmesa (default: $SIMBOB_GL, else EGL, falling back to OSMesa)");
}

int renderOptions(const ViewArgs& v, const Common& common, RenderOptions* o) {
  int w = 0, h = 0;
  char extra = 0;
  if (std::sscanf(v.size.c_str(), "%dx%d%c", &w, &h, &extra) != 2 || w < 1 || h < 1 || w > kMaxImageSide ||
      h > kMaxImageSide) {
    g_log.error({ErrorKind::InvalidInput,
                 {},
                 "--size must be WIDTHxHEIGHT with 1 to " + std::to_string(kMaxImageSide) + " pixels each, got '" +
                     v.size + "'"});
    return kExitUsage;
  }
  o->width = w;
  o->height = h;
  if (!(v.fps > 0 && v.fps <= 1000)) {
    g_log.error({ErrorKind::InvalidInput, {}, "--fps must be above 0 and at most 1000, got " + formatNumber(v.fps)});
    return kExitUsage;
  }
  if (!v.quality.empty() && !parseQuality(v.quality, &o->quality)) {
    g_log.error({ErrorKind::InvalidInput,
                 {},
                 "--quality must be frame, wire, plane, flat, smooth, textures, shadows, transparency or fog, got '" +
                     v.quality + "'"});
    return kExitUsage;
  }
  std::string gl = v.gl;
  std::string from = "--gl";
  if (gl.empty()) {
    const char* env = std::getenv("SIMBOB_GL");
    gl = env ? env : "";
    from = "SIMBOB_GL";
  }
  if (!parseGlBackend(gl, &o->backend)) {
    g_log.error({ErrorKind::InvalidInput, {}, from + " must be egl or osmesa, got '" + gl + "'"});
    return kExitUsage;
  }
  if (!v.draw.empty()) {
    o->draw_chosen = true;
    o->draw_models = o->draw_geoms = false;
    size_t start = 0;
    while (start <= v.draw.size()) {
      const size_t comma = std::min(v.draw.find(',', start), v.draw.size());
      const std::string item = v.draw.substr(start, comma - start);
      if (item == "models") {
        o->draw_models = true;
      } else if (item == "geoms") {
        o->draw_geoms = true;
      } else if (item == "sensors") {
        o->draw_sensors = true;
      } else {
        g_log.error({ErrorKind::InvalidInput,
                     {},
                     "--draw must be models, geoms, sensors or a list of them (models,sensors), got '" + v.draw + "'"});
        return kExitUsage;
      }
      start = comma + 1;
    }
  }
  o->camera = v.camera;
  o->texture_folder = common.texture_folder;
  return 0;
}

namespace {

// The still's arguments: a .png name, --at and --dt in range. 0, or 64 (reported).
int renderArgsProblem(const RenderArgs& a) {
  {
    // A still is PNG bytes: a name that says otherwise is refused, as `plot` refuses its formats.
    std::string ext = std::filesystem::path(a.out).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".png") {
      g_log.error({ErrorKind::InvalidInput,
                   {},
                   "--out " + quoteInput(a.out, 400) + ": a still is a .png, not " +
                       (ext.empty() ? std::string("a name without extension") : quoteInput(ext, 40))});
      return kExitUsage;
    }
  }
  if (!std::isfinite(a.at) || a.at < 0 || a.at > kMaxClockTime) {
    g_log.error({ErrorKind::InvalidInput, {}, "--at must be between 0 and 1e9 s, got " + formatNumber(a.at)});
    return kExitUsage;
  }
  if (std::string p = clockTimeProblem("--dt", a.dt, true); !p.empty()) {
    g_log.error({ErrorKind::InvalidInput, {}, p});
    return kExitUsage;
  }
  return 0;
}

// Simulates up to --at with the controllers acting, as `run` would: the Run's Simulation, whose
// parties (after the scene's) are the frames a recording would follow, then the still. 0, or the
// exit status (reported).
int simulateTo(const RenderArgs& a, Run& run, const RenderOptions& ro, Renderer& renderer,
               std::vector<Transform>* poses) {
  catchStopSignals();
  const Model& model = run.model();
  const std::optional<SimTime> at = toSimTime(a.at);
  Still still(at ? *at : kNever, model.bodies.size(), ro.draw_sensors ? &model : nullptr);
  Follower follower(renderer, a.view.fps, at ? *at : kNever, toSimTime(model.settings.min_time_step).value_or(0),
                    model.bodies.size());
  run.simulation().addParty(follower);
  run.simulation().addParty(still);
  const RunResult& r = run.finish().result;
  if (r.status != RunStatus::Completed || !still.taken()) {
    g_log.error(r.error.message.empty() ? Error{ErrorKind::Internal, {}, "the run ended before --at"} : r.error);
    if (r.status == RunStatus::Interrupted) return stopExitCode();
    return exitCodeFor(r.error.kind);
  }
  *poses = still.poses();
  renderer.setSensorRays(still.rays());
  return 0;
}

// The Run of a still: it writes nothing of its own; --out must not be any file it reads.
RunOptions stillRun(const RenderArgs& a, const Common& common) {
  RunOptions o;
  o.scene = a.scene;
  o.write_outputs = false;
  o.simulation.duration = a.at;
  o.simulation.dt = a.dt;
  o.simulation.seed = a.seed;
  o.simulation.stop = &g_stop;
  o.simulation.texture_folder = common.texture_folder;
  o.inputs = {{"--settings", common.settings}};
  if (common.document_ini) o.inputs.push_back({"the DocumentIni", documentIniPath(a.scene)});
  o.outputs = {{"--out", a.out}, {"--log-file", g_log.path}};
  return o;
}

}  // namespace

int cmdRender(const RenderArgs& a, const Common& common) {
  if (int c = renderArgsProblem(a)) return c;
  RenderOptions ro;
  if (int c = renderOptions(a.view, common, &ro)) return c;
  RunOptions o = stillRun(a, common);
  // A still at t = 0 (without sensor rays) runs nothing: --no-controllers has nothing to refuse.
  o.simulation.no_controllers = common.no_controllers && (a.at > 0 || ro.draw_sensors);
  if (int c = sceneOverrides(common, a.scene, {}, &o.simulation.overrides)) return c;
  exitOnStopSignals(a.scene, "loading");
  Error refusal;
  std::unique_ptr<Run> run = Run::open(o, *common.registry, runListener(), &refusal);
  if (!run) return exitCodeFor(refusal.kind);
  const Model& model = run->model();
  if (std::string n = drawFallbackNote(model, ro); !n.empty()) g_log.info(n);
  Error err;
  std::unique_ptr<Renderer> renderer = Renderer::create(model, ro, &err);
  if (!renderer) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  std::vector<Transform> poses = initialPoses(model);
  if (a.at > 0 || ro.draw_sensors)  // the rays need the readings: a world at T
    if (int c = simulateTo(a, *run, ro, *renderer, &poses)) return c;
  Image img;
  if (const Error* e = renderer->render(poses, a.at, &img)) {
    g_log.error(*e);
    return exitCodeFor(e->kind);
  }
  Error w = writePng(a.out, img);
  if (!w.message.empty()) {
    g_log.error(w);
    return exitCodeFor(w.kind);
  }
  g_log.info("wrote " + a.out + " (" + std::to_string(img.width) + "x" + std::to_string(img.height) + ", camera " +
             renderer->cameraName() + ", " + renderer->backendName() + ")");
  return kExitOk;
}

int cmdInfo(const std::string& gl, const Common& /*common*/) {
  std::fputs(versionText().c_str(), stdout);  // the lines of --version, git revision included
  std::vector<std::pair<const char*, GlBackend>> backends = {{"egl", GlBackend::Egl}, {"osmesa", GlBackend::OsMesa}};
  if (!gl.empty()) {
    GlBackend b;
    if (!parseGlBackend(gl, &b) || b == GlBackend::Auto) {
      g_log.error({ErrorKind::InvalidInput, {}, "--gl must be egl or osmesa, got '" + gl + "'"});
      return kExitUsage;
    }
    backends = {{b == GlBackend::Egl ? "egl" : "osmesa", b}};
  }
  Model empty;
  empty.skins.push_back(SkinDef{});
  bool any = false;
  for (const auto& [name, b] : backends) {
    RenderOptions o;
    o.width = o.height = 16;
    o.backend = b;
    Error err;
    std::unique_ptr<Renderer> r = Renderer::create(empty, o, &err);
    if (r) {
      std::printf("gl %s: %s, GL_RENDERER %s\n", name, r->backendName().c_str(), r->glRenderer().c_str());
      any = true;
    } else {
      std::printf("gl %s: unavailable (%s)\n", name, err.message.c_str());
    }
  }
  return any ? kExitOk : kExitNoInput;
}

}  // namespace simbob::cli
