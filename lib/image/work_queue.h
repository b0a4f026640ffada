// A bounded queue between one producer and one worker thread, in order, where the first error
// stops everything: what the encoder thread (async_sink.cpp) and the render thread
// (lib/render/render_thread.cpp) share. The owner makes the thread; the worker calls serve().
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <string>
#include <utility>

#include "simbob/error.h"

namespace simbob {

template <class Job>
class WorkQueue {
 public:
  explicit WorkQueue(size_t capacity) : capacity_(capacity == 0 ? 1 : capacity) {}

  /// Producer: queues a job, waiting while the queue is full. The first failure, else null.
  const Error* push(Job&& job) {
    std::unique_lock<std::mutex> lock(mu_);
    wake_producer_.wait(lock, [&] { return failed_ || queue_.size() < capacity_; });
    if (failed_) return &error_;
    if (closing_) return failLocked(internalError("job queued after the queue was closed"));
    queue_.push_back(std::move(job));
    lock.unlock();
    wake_worker_.notify_one();
    return nullptr;
  }

  /// Producer: no more jobs. The worker drains the queue and serve() returns.
  void close() {
    {
      std::lock_guard<std::mutex> lock(mu_);
      closing_ = true;
    }
    wake_worker_.notify_all();
  }

  /// Producer: queued jobs are dropped; serve() returns after the job at hand.
  void abandon() {
    {
      std::lock_guard<std::mutex> lock(mu_);
      abandon_ = true;
      queue_.clear();
    }
    wake_worker_.notify_all();
  }

  /// Worker: runs handle(job) for each job in order until the queue is closed and drained,
  /// abandoned, or a job fails (handle returns an error, which becomes the queue's failure).
  template <class Handle>
  void serve(Handle handle) {
    for (;;) {
      Job job;
      {
        std::unique_lock<std::mutex> lock(mu_);
        wake_worker_.wait(lock, [&] { return abandon_ || failed_ || closing_ || !queue_.empty(); });
        if (abandon_ || failed_ || queue_.empty()) return;  // empty here means closing
        job = std::move(queue_.front());
        queue_.pop_front();
      }
      wake_producer_.notify_one();
      if (const Error* e = handle(job)) {
        fail(*e);
        return;
      }
    }
  }

  /// Either side: the first failure wins; queued jobs are dropped and the producer is woken.
  void fail(const Error& e) {
    std::lock_guard<std::mutex> lock(mu_);
    failLocked(e);
  }

  /// The failure, or null. Read it after the worker is joined (or from push's result).
  const Error* failure() {
    std::lock_guard<std::mutex> lock(mu_);
    return failed_ ? &error_ : nullptr;
  }

  static Error internalError(std::string message) {
    Error e;
    e.kind = ErrorKind::Internal;
    e.message = std::move(message);
    return e;
  }

 private:
  const Error* failLocked(const Error& e) {
    if (!failed_) {
      error_ = e;
      failed_ = true;
    }
    queue_.clear();
    wake_producer_.notify_all();
    return &error_;
  }

  const size_t capacity_;
  std::mutex mu_;
  std::condition_variable wake_worker_, wake_producer_;
  std::deque<Job> queue_;  // guarded by mu_
  bool closing_ = false;   // guarded by mu_: close() was called
  bool abandon_ = false;   // guarded by mu_
  bool failed_ = false;    // guarded by mu_
  Error error_;            // written once, under mu_, before failed_ is set
};

}  // namespace simbob
