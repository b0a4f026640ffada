// AsyncSink: frames are handed to the wrapped sinks on one worker thread through a bounded
// queue, so that encoding overlaps rendering and physics (issue #12 point 7).
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

#include "simbob/frame_sinks.h"

namespace simbob {

namespace {

class AsyncSink : public FrameSink {
 public:
  AsyncSink(std::vector<std::unique_ptr<FrameSink>> sinks, size_t capacity)
      : sinks_(std::move(sinks)), capacity_(capacity == 0 ? 1 : capacity) {
    worker_ = std::thread([this] { run(); });
  }

  ~AsyncSink() override {
    {
      std::lock_guard<std::mutex> lock(mu_);
      abandon_ = true;
      queue_.clear();
    }
    wake_worker_.notify_all();
    if (worker_.joinable()) worker_.join();
    // The wrapped sinks are destroyed unfinished: each removes its temporary output.
  }

  const Error* add(Image&& frame) override {
    std::unique_lock<std::mutex> lock(mu_);
    wake_producer_.wait(lock, [&] { return failed_ || queue_.size() < capacity_; });
    if (failed_) return &error_;
    if (closing_) return setError(internalError("frame added after finish()"));
    queue_.push_back(std::move(frame));
    lock.unlock();
    wake_worker_.notify_one();
    return nullptr;
  }

  const Error* finish() override {
    {
      std::lock_guard<std::mutex> lock(mu_);
      if (closing_) return failed_ ? &error_ : nullptr;
      closing_ = true;
    }
    wake_worker_.notify_all();
    worker_.join();
    // The worker is gone: what follows runs on this thread alone.
    if (failed_) return &error_;
    for (auto& sink : sinks_)
      if (const Error* e = sink->finish()) {
        error_ = *e;
        failed_ = true;
        return &error_;
      }
    return nullptr;
  }

 private:
  static Error internalError(std::string message) {
    Error e;
    e.kind = ErrorKind::Internal;
    e.message = std::move(message);
    return e;
  }

  // Called with mu_ held. The first error wins; the queue is dropped and the producer woken.
  const Error* setError(Error e) {
    if (!failed_) {
      error_ = std::move(e);
      failed_ = true;
    }
    queue_.clear();
    wake_producer_.notify_all();
    return &error_;
  }

  void run() {
    for (;;) {
      Image frame;
      {
        std::unique_lock<std::mutex> lock(mu_);
        wake_worker_.wait(lock, [&] { return abandon_ || failed_ || closing_ || !queue_.empty(); });
        if (abandon_ || failed_ || queue_.empty()) return;  // empty here means closing
        frame = std::move(queue_.front());
        queue_.pop_front();
      }
      wake_producer_.notify_one();
      // Every sink but the last gets a copy; the last takes the frame itself.
      const Error* e = nullptr;
      for (size_t i = 0; !e && i + 1 < sinks_.size(); ++i) e = sinks_[i]->add(Image(frame));
      if (!e && !sinks_.empty()) e = sinks_.back()->add(std::move(frame));
      if (e) {
        std::lock_guard<std::mutex> lock(mu_);
        setError(*e);
        return;
      }
    }
  }

  std::vector<std::unique_ptr<FrameSink>> sinks_;
  const size_t capacity_;
  std::mutex mu_;
  std::condition_variable wake_worker_, wake_producer_;
  std::deque<Image> queue_;  // guarded by mu_
  bool closing_ = false;     // guarded by mu_: finish() was called
  bool abandon_ = false;     // guarded by mu_: destroyed without finish()
  bool failed_ = false;      // guarded by mu_ while the worker runs
  Error error_;              // written once, under mu_, before failed_ is set
  std::thread worker_;
};

}  // namespace

std::unique_ptr<FrameSink> makeAsyncSink(std::vector<std::unique_ptr<FrameSink>> sinks, size_t queue_frames) {
  return std::make_unique<AsyncSink>(std::move(sinks), queue_frames);
}

}  // namespace simbob
