// AsyncSink: frames are handed to the wrapped sinks on one worker thread through a bounded
// queue, so that encoding overlaps rendering and physics (issue #12 point 7).
#include <thread>

#include "image/work_queue.h"
#include "simbob/tool/frame_sinks.h"

namespace simbob {

namespace {

class AsyncSink : public FrameSink {
 public:
  AsyncSink(std::vector<std::unique_ptr<FrameSink>> sinks, size_t capacity)
      : sinks_(std::move(sinks)), queue_(capacity) {
    worker_ = std::thread([this] { queue_.serve([this](Image& frame) { return hand(frame); }); });
  }

  ~AsyncSink() override {
    queue_.abandon();
    if (worker_.joinable()) worker_.join();
    // The wrapped sinks are destroyed unfinished: each removes its temporary output.
  }

  const Error* add(Image&& frame) override { return queue_.push(std::move(frame)); }

  const Error* finish() override {
    if (finished_) return queue_.failure();
    finished_ = true;
    queue_.close();
    worker_.join();
    // The worker is gone: what follows runs on this thread alone.
    if (const Error* e = queue_.failure()) return e;
    for (auto& sink : sinks_)
      if (const Error* e = sink->finish()) {
        queue_.fail(*e);
        return queue_.failure();
      }
    return nullptr;
  }

 private:
  // On the worker: every sink but the last gets a copy; the last takes the frame itself.
  const Error* hand(Image& frame) {
    const Error* e = nullptr;
    for (size_t i = 0; !e && i + 1 < sinks_.size(); ++i) e = sinks_[i]->add(Image(frame));
    if (!e && !sinks_.empty()) e = sinks_.back()->add(std::move(frame));
    return e;
  }

  std::vector<std::unique_ptr<FrameSink>> sinks_;
  WorkQueue<Image> queue_;
  bool finished_ = false;  // producer side only
  std::thread worker_;
};

}  // namespace

std::unique_ptr<FrameSink> makeAsyncSink(std::vector<std::unique_ptr<FrameSink>> sinks, size_t queue_frames) {
  return std::make_unique<AsyncSink>(std::move(sinks), queue_frames);
}

}  // namespace simbob
