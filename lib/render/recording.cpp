// `run --record` / `--video`: the renderer, its render thread, the sinks and the Recorder party,
// built and checked together before the run (see Recording in simbob/renderer.h).
#include <filesystem>

#include "simbob/tool/frame_sinks.h"
#include "simbob/renderer.h"

namespace simbob {

namespace {

bool addVideoSink(const RecordingRequest& q, std::vector<std::unique_ptr<FrameSink>>* sinks, Error* err) {
  std::string why;
  const std::string encoder = videoEncoderFor(q.video, &why);
  if (encoder.empty()) {
    *err = {ErrorKind::Usage, {q.video, 0}, why};
    return false;
  }
  if (encoder != "mjpeg" && (q.render.width % 2 != 0 || q.render.height % 2 != 0)) {
    *err = {ErrorKind::Usage, {}, "--size must be even in both directions for H.264 (--video .mp4)"};
    return false;
  }
  std::unique_ptr<FrameSink> video = makeVideoSink(q.video, q.fps, err, q.video_temp);
  if (!video) return false;
  sinks->push_back(std::move(video));
  return true;
}

}  // namespace

std::unique_ptr<Recording> Recording::open(const Model& model, const RecordingRequest& request, SimTime min_step,
                                           Error* err) {
  const RecordingRequest& q = request;
  std::unique_ptr<Recording> r(new Recording());
  std::vector<std::unique_ptr<FrameSink>> sinks;
  if (!q.record_dir.empty()) {
    std::error_code ec;
    if (std::filesystem::exists(std::filesystem::path(q.record_dir) / "frame_000000.png", ec)) {
      *err = {ErrorKind::CannotCreate,
              {q.record_dir, 0},
              "already holds a recording (frame_000000.png); remove it or record elsewhere"};
      return nullptr;
    }
    std::unique_ptr<FrameSink> pngs = makePngSequenceSink(q.record_dir, err);
    if (!pngs) return nullptr;
    sinks.push_back(std::move(pngs));
  }
  if (!q.video.empty() && !addVideoSink(q, &sinks, err)) return nullptr;
  r->renderer_ = Renderer::create(model, q.render, err);
  if (!r->renderer_) return nullptr;
  r->sink_ = makeAsyncSink(std::move(sinks));
  r->drawer_ = drawOnRenderThread(*r->renderer_, *r->sink_);
  r->recorder_ = std::make_unique<Recorder>(*r->drawer_, q.fps, min_step, static_cast<int>(model.bodies.size()),
                                            q.render.draw_sensors ? &model : nullptr);
  return r;
}

// The recorder stops feeding the drawer, the drawer gives the context back, then the sink and
// the renderer go: members are destroyed in reverse order of declaration.
Recording::~Recording() = default;

std::string Recording::description() const {
  return "recording through " + renderer_->backendName() + " (" + renderer_->glRenderer() + "), camera " +
         renderer_->cameraName();
}

}  // namespace simbob
