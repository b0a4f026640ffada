// WorkerPool: see workers.h.
#include "workers.h"

#include <algorithm>

namespace simbob {

WorkerPool::WorkerPool(int threads) {
  for (int w = 1; w < threads; ++w) workers_.emplace_back([this, w] { work(w); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

size_t WorkerPool::chunks(size_t n, size_t grain) const {
  if (n == 0) return 0;
  if (workers_.empty()) return 1;
  const size_t most = 8 * static_cast<size_t>(size());
  return std::max<size_t>(1, std::min(most, n / std::max<size_t>(grain, 1)));
}

void WorkerPool::drain(int worker) {
  for (;;) {
    const size_t c = next_.fetch_add(1, std::memory_order_relaxed);
    if (c >= chunks_) return;
    try {
      (*job_)(c, c * n_ / chunks_, (c + 1) * n_ / chunks_, worker);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_ || c < error_chunk_) {
        error_ = std::current_exception();
        error_chunk_ = c;
      }
    }
    finished_.fetch_add(1, std::memory_order_acq_rel);
  }
}

void WorkerPool::run(size_t n, size_t grain, const Job& job) {
  const size_t k = chunks(n, grain);
  if (k == 0) return;
  if (k == 1) {
    job(0, 0, n, 0);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    job_ = &job;
    n_ = n;
    chunks_ = k;
    next_.store(0, std::memory_order_relaxed);
    finished_.store(0, std::memory_order_relaxed);
    ++generation_;
  }
  wake_.notify_all();
  drain(0);
  std::unique_lock<std::mutex> lock(mutex_);
  // Every chunk done, and no worker still inside drain() of this job (it must not claim a chunk
  // of the next one with this one's bounds).
  done_.wait(lock, [&] { return finished_.load(std::memory_order_acquire) == chunks_ && active_ == 0; });
  job_ = nullptr;
  if (error_) {
    std::exception_ptr e = error_;
    error_ = nullptr;
    std::rethrow_exception(e);
  }
}

void WorkerPool::work(int worker) {
  std::unique_lock<std::mutex> lock(mutex_);
  uint64_t seen = 0;
  for (;;) {
    wake_.wait(lock, [&] { return quit_ || generation_ != seen; });
    if (quit_) return;
    seen = generation_;
    if (!job_) continue;  // woke after that job was done
    ++active_;
    lock.unlock();
    drain(worker);
    lock.lock();
    if (--active_ == 0) done_.notify_one();
  }
}

}  // namespace simbob
