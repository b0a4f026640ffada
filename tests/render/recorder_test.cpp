// The recorder and its frame drawers (issue #12 point 7): a render thread owns the GL context
// while the physics steps on, and must give the very frames the sequential loop gives -- same
// bytes, same order, the tracking camera's history intact -- stop on the first error, and hand
// the context back whether it finished or not.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>
#include <vector>

#include "simbob/compile.h"
#include "simbob/graph.h"
#include "simbob/renderer.h"
#include "simbob/loop.h"
#include "render/reference_frames.h"
#include "test_registry.h"
#include "sim/loop_helpers.h"

using namespace simbob;
using namespace simbob::test;

namespace {

Model gallery() {
  Scene s;
  Diagnostics d;
  REQUIRE(loadScene(std::string(SIMBOB_SOURCE_DIR) + "/scenes/gallery.xml", testRegistry(), &s, d));
  Model m;
  REQUIRE(compileScene(s, &m, d));
  return m;
}

std::unique_ptr<Renderer> makeRenderer(const Model& m, const std::string& camera, int w = 96, int h = 72) {
  RenderOptions o;
  o.width = w;
  o.height = h;
  o.backend = backend();
  o.camera = camera;
  Error err;
  std::unique_ptr<Renderer> r = Renderer::create(m, o, &err);
  INFO(err.message);
  REQUIRE(r);
  return r;
}

// Keeps every frame; fails the add() numbered fail_at (0-based) when asked to.
class KeepingSink : public FrameSink {
 public:
  explicit KeepingSink(int fail_at = -1) : fail_at_(fail_at) {}
  const Error* add(Image&& frame) override {
    if (static_cast<int>(frames.size()) == fail_at_) {
      error_ = Error{ErrorKind::IoError, {"frames.avi", 0}, "no space left on device"};
      return &error_;
    }
    frames.push_back(std::move(frame));
    return nullptr;
  }
  const Error* finish() override {
    ++finished;
    return nullptr;
  }
  std::vector<Image> frames;
  int finished = 0;

 private:
  int fail_at_;
  Error error_;
};

// Records `duration` s of the gallery at 20 fps through the chosen drawer.
RunResult record(const Model& m, Renderer& r, KeepingSink& sink, bool threaded, double duration) {
  std::unique_ptr<FrameDrawer> drawer = threaded ? drawOnRenderThread(r, sink) : drawInline(r, sink);
  Recorder recorder(*drawer, 20, toSimTime(m.settings.min_time_step).value_or(0), static_cast<int>(m.bodies.size()));
  LoopOptions opts;
  opts.duration = duration;
  return runParties(m, opts, {&recorder});
}

// The static Overview camera's still at t = 0 from `r` on this thread equals a new renderer's:
// true only if r's GL context is current here again (else the read-back is empty).
bool drawsLikeAFreshRenderer(const Model& m, Renderer& r) {
  Image still, fresh;
  if (r.render(initialPoses(m), 0, &still) != nullptr) return false;
  std::unique_ptr<Renderer> other = makeRenderer(m, "Overview");
  if (other->render(initialPoses(m), 0, &fresh) != nullptr) return false;
  return still.rgb == fresh.rgb;
}

}  // namespace

TEST_CASE("a render thread draws the frames the sequential loop draws, byte for byte and in order") {
  const Model m = gallery();
  // The Chase camera follows the rolling ball, so each frame depends on the ones before it.
  std::unique_ptr<Renderer> inline_renderer = makeRenderer(m, "Chase");
  std::unique_ptr<Renderer> threaded_renderer = makeRenderer(m, "Chase");
  KeepingSink inline_sink, threaded_sink;
  REQUIRE(record(m, *inline_renderer, inline_sink, false, 1.0).status == RunStatus::Completed);
  REQUIRE(record(m, *threaded_renderer, threaded_sink, true, 1.0).status == RunStatus::Completed);
  REQUIRE(inline_sink.frames.size() == 21);  // t = 0, 0.05, ..., 1.0
  REQUIRE(threaded_sink.frames.size() == 21);
  CHECK(threaded_sink.finished == 1);
  for (size_t i = 0; i < inline_sink.frames.size(); ++i) {
    INFO("frame " << i);
    CHECK(threaded_sink.frames[i].rgb == inline_sink.frames[i].rgb);
  }
  // Not a still picture: the ball rolls 1 m in the second, so the first and last frames differ.
  CHECK(inline_sink.frames.front().rgb != inline_sink.frames.back().rgb);

  // The context is back on this thread: a still draws here again, the same picture as the
  // renderer that never left it (both cameras followed the same frames). Without a current
  // context the read-back would be empty.
  Image still, inline_still;
  CHECK(threaded_renderer->render(initialPoses(m), 0, &still) == nullptr);
  CHECK(inline_renderer->render(initialPoses(m), 0, &inline_still) == nullptr);
  CHECK(still.width == 96);
  CHECK(still.rgb == inline_still.rgb);
}

TEST_CASE("a sink that fails stops a threaded recording with its error; the context comes back") {
  const Model m = gallery();
  std::unique_ptr<Renderer> r = makeRenderer(m, "Overview");
  KeepingSink sink(/*fail_at=*/3);
  const RunResult result = record(m, *r, sink, true, 2.0);
  CHECK(result.status != RunStatus::Completed);
  CHECK(result.error.message == "no space left on device");
  CHECK(sink.frames.size() == 3);
  CHECK(sink.finished == 0);  // a failed recording is never committed
  CHECK(result.sim_time < 2.0);
  CHECK(drawsLikeAFreshRenderer(m, *r));
}

TEST_CASE("a render thread destroyed unfinished never finishes the sink, and gives the context back") {
  const Model m = gallery();
  std::unique_ptr<Renderer> r = makeRenderer(m, "Overview");
  KeepingSink sink;
  {
    std::unique_ptr<FrameDrawer> drawer = drawOnRenderThread(*r, sink, 2);
    const std::vector<Transform> poses = initialPoses(m);
    for (int i = 0; i < 5; ++i) REQUIRE(drawer->draw(poses, i / 20.0) == nullptr);
  }
  CHECK(sink.finished == 0);
  CHECK(drawsLikeAFreshRenderer(m, *r));
}

TEST_CASE("moving cameras in motion: the Chase and Spot frames at t = 1 s match their references") {
  // The references at t = 0 (renderer_test.cpp) fix where the cameras start; these fix where
  // they are after following the ball, which rolls 1 m along +X in that second (LinVelocity
  // 1 0 0 with the matching spin): Chase keeps its distance behind it, Spot stays put and
  // turns. A camera that did not follow would show the ball off centre or the wrong backdrop.
  const Model m = gallery();
  for (const char* camera : {"Chase", "Spot"}) {
    INFO(camera);
    std::unique_ptr<Renderer> r = makeRenderer(m, camera, 160, 120);
    KeepingSink sink;
    REQUIRE(record(m, *r, sink, true, 1.0).status == RunStatus::Completed);
    REQUIRE(sink.frames.size() == 21);
    checkReference(sink.frames.back(), std::string("gallery_") + (camera[0] == 'C' ? "chase" : "spot") + "_t1");
    // ... and it differs from where the camera started.
    CHECK_FALSE(imagesMatch(sink.frames.back(), sink.frames.front()));
  }
}
