// A World's worker threads (--threads N): a small fixed pool that runs one job at a time over
// the chunks of an index range, the calling thread taking part. What makes the results not
// depend on the thread count is the job's shape, not the pool: a job writes only the slots of
// its chunk (per-pair contacts, per-sensor readings), and the caller commits the slots in index
// order once run() has returned (STYLE.md, "Parallel, in a fixed order").
//
// Workers never call into ODE's global state: no dRand, no object creation or destruction, no
// space traversal; only dCollide on geoms whose colliders keep no shared cache (contacts.cpp,
// rays.cpp say which). They run while the caller holds the World's OdeSection.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace simbob {

class WorkerPool {
 public:
  /// A job: handles chunk `chunk`, the indices [begin, end), on worker `worker` (0 is the caller;
  /// a worker's scratch space is its own).
  using Job = std::function<void(size_t chunk, size_t begin, size_t end, int worker)>;

  /// `threads` threads in all: the caller and threads - 1 workers (none for 1).
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// Threads in all, the caller included.
  int size() const { return static_cast<int>(workers_.size()) + 1; }
  /// How many chunks run(n, grain, ...) makes: k = 0 for n = 0, else at most 8 per thread and
  /// at least `grain` indices each (1 with one thread); chunk c is [c * n / k, (c + 1) * n / k).
  size_t chunks(size_t n, size_t grain) const;
  /// Runs `job` on every chunk of [0, n) and returns when all are done; one chunk runs on the
  /// caller alone, waking nobody. Chunks go to whichever thread is free, so which worker does a
  /// chunk varies; chunk bounds depend only on n, grain and size(). Not reentrant. A chunk that
  /// throws (ODE's error, world.cpp) does not end its thread: the exception of the lowest such
  /// chunk is thrown again here once every chunk is done.
  void run(size_t n, size_t grain, const Job& job);

 private:
  void work(int worker);
  /// Claims and runs chunks of the current job until none is left.
  void drain(int worker);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const Job* job_ = nullptr;
  size_t n_ = 0, chunks_ = 0;
  std::atomic<size_t> next_{0};      ///< the next chunk to claim
  std::atomic<size_t> finished_{0};  ///< chunks done
  uint64_t generation_ = 0;          ///< bumped by run(): a worker wakes for each new job
  int active_ = 0;                   ///< workers inside drain(): run() waits for them to leave
  bool quit_ = false;
  std::exception_ptr error_;  ///< the exception of the lowest chunk that threw (under mutex_)
  size_t error_chunk_ = 0;
};

}  // namespace simbob
