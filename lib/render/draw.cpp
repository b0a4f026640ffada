// Frame drawers (issue #12 point 7): the recorder's frames drawn on the run loop's thread, or on
// a render thread that owns the GL context while the physics steps on.
//
// With a render thread and the encoder thread of makeAsyncSink, a recording is a pipeline of
// three stages -- step the world to the frame's time, draw it, encode it -- each on its own
// thread, linked by bounded queues. The frames stay in order and the renderer stays one object
// with one camera history, so the bytes are those of the sequential loop.
#include <thread>

#include "image/work_queue.h"
#include "simbob/tool/frame_sinks.h"
#include "simbob/renderer.h"

namespace simbob {

namespace {

class InlineDrawer : public FrameDrawer {
 public:
  InlineDrawer(Renderer& renderer, FrameSink& sink) : renderer_(renderer), sink_(sink) {}

  const Error* draw(const std::vector<Transform>& poses, double t, const std::vector<double>& rays) override {
    Image img;
    renderer_.setSensorRays(rays);
    if (const Error* e = renderer_.render(poses, t, &img)) return e;
    return sink_.add(std::move(img));
  }
  const Error* finish() override { return sink_.finish(); }

 private:
  Renderer& renderer_;
  FrameSink& sink_;
};

struct FrameJob {
  std::vector<Transform> poses;
  double t = 0;
  std::vector<double> rays;
};

class RenderThread : public FrameDrawer {
 public:
  RenderThread(Renderer& renderer, FrameSink& sink, size_t capacity)
      : renderer_(renderer), sink_(sink), queue_(capacity) {
    renderer_.release();  // the context moves to the worker
    worker_ = std::thread([this] { run(); });
  }

  ~RenderThread() override {
    if (!joined_) {
      queue_.abandon();
      join();
    }
    // The sink is left unfinished: its owner destroys it, which removes its temporary output.
  }

  const Error* draw(const std::vector<Transform>& poses, double t, const std::vector<double>& rays) override {
    return queue_.push(FrameJob{poses, t, rays});
  }

  const Error* finish() override {
    if (joined_) return queue_.failure();
    queue_.close();
    join();
    if (const Error* e = queue_.failure()) return e;
    if (const Error* e = sink_.finish()) {
      queue_.fail(*e);
      return queue_.failure();
    }
    return nullptr;
  }

 private:
  void run() {
    if (const Error* e = renderer_.acquire()) {
      queue_.fail(*e);
      return;
    }
    queue_.serve([this](FrameJob& job) -> const Error* {
      Image img;
      renderer_.setSensorRays(job.rays);
      if (const Error* e = renderer_.render(job.poses, job.t, &img)) return e;
      return sink_.add(std::move(img));
    });
    renderer_.release();
  }

  // Waits for the worker and takes the context back, so the renderer can be used (and
  // destroyed, which deletes its textures) on this thread again.
  void join() {
    worker_.join();
    joined_ = true;
    if (const Error* e = renderer_.acquire()) queue_.fail(*e);
  }

  Renderer& renderer_;
  FrameSink& sink_;
  WorkQueue<FrameJob> queue_;
  bool joined_ = false;  // producer side only
  std::thread worker_;
};

}  // namespace

std::unique_ptr<FrameDrawer> drawInline(Renderer& renderer, FrameSink& sink) {
  return std::make_unique<InlineDrawer>(renderer, sink);
}

std::unique_ptr<FrameDrawer> drawOnRenderThread(Renderer& renderer, FrameSink& sink, size_t queue_frames) {
  return std::make_unique<RenderThread>(renderer, sink, queue_frames);
}

}  // namespace simbob
