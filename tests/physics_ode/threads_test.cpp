// One World on several threads (World::create's `threads`; lib/physics/workers.h, contacts.cpp,
// rays.cpp): the shipped swarm, maze, box stack and chain scenes, stepped on 1, 2 and 3 threads,
// must give the same bits -- every body's pose and velocity, every sensor reading and the
// contact count after every step. The chunk grain is set to one pair so that even the smallest
// of these scenes is split among the threads. A second case commits the contacts out of order on
// purpose (ParallelTestHooks::reverse_commit: last pair first) and requires the bits to differ:
// the comparison can fail. (The controllers are not in a World: tests/cli/threads.sh runs the same scenes
// through `simbob run`, robots driving.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <cstring>
#include <string>
#include <vector>

#include "physics/world_impl.h"
#include "physics/workers.h"
#include "shipped_scene.h"

namespace {

using simbob::World;

struct Trace {
  std::vector<double> values;  ///< compared bit for bit
  long contacts = 0;           ///< contact joints over the run (the scene must have some)
};

Trace trace(const simbob::Model& m, int threads, int steps) {
  std::unique_ptr<World> w = World::create(m, 7, threads);
  Trace t;
  for (int s = 0; s < steps; ++s) {
    w->step(m.settings.max_time_step);
    for (int b = 0; b < w->bodyCount(); ++b) {
      const simbob::BodyState st = w->body(b);
      for (double v : st.pose.p) t.values.push_back(v);
      for (double v : st.pose.q) t.values.push_back(v);
      for (double v : st.lin_vel) t.values.push_back(v);
      for (double v : st.ang_vel) t.values.push_back(v);
    }
    for (int i = 0; i < w->sensorCount(); ++i)
      for (double v : w->sensorReading(i)) t.values.push_back(v);
    t.values.push_back(w->lastContactCount());
    t.contacts += w->lastContactCount();
  }
  return t;
}

bool sameBits(const Trace& a, const Trace& b) {
  return a.values.size() == b.values.size() &&
         std::memcmp(a.values.data(), b.values.data(), a.values.size() * sizeof(double)) == 0;
}

// Sets the process-wide test switches for one test case and puts them back after it.
struct Hooks {
  explicit Hooks(bool reverse) {
    simbob::parallelTestHooks().grain = 1;
    simbob::parallelTestHooks().reverse_commit = reverse;
  }
  ~Hooks() { simbob::parallelTestHooks() = {}; }
  Hooks(const Hooks&) = delete;
  Hooks& operator=(const Hooks&) = delete;
};

constexpr int kSteps = 1500;  // 1.5 s: the stack and the chain settle, the robots' scanners read

}  // namespace

TEST_CASE("threads: the swarm, maze, box stack and chain give the same bits on 1, 2 and 3 threads") {
  Hooks hooks(false);
  for (const char* name : {"swarm", "maze", "box_stack", "chain"}) {
    INFO(name);
    const simbob::Model m = simbob::test::shippedScene(name);
    const Trace one = trace(m, 1, kSteps);
    // The chain hangs free: no contacts, only its joints (the pool must leave them alone).
    CHECK((one.contacts > 0) == (std::string(name) != "chain"));
    CHECK(sameBits(one, trace(m, 2, kSteps)));
    CHECK(sameBits(one, trace(m, 3, kSteps)));
  }
}

// Only the box stack: ODE builds each island by walking its bodies and, per body, the joints
// attached to it, newest first, so the creation order of contact joints matters only among the
// contacts of one body -- the boxes' four corners on one another. A robot at rest has one
// contact per wheel and caster, and its trajectory is the same in any commit order.
TEST_CASE("threads: contacts committed out of order give other bits (the comparison above can fail)") {
  Hooks hooks(true);
  const simbob::Model m = simbob::test::shippedScene("box_stack");
  CHECK_FALSE(sameBits(trace(m, 1, kSteps), trace(m, 2, kSteps)));
  CHECK_FALSE(sameBits(trace(m, 1, kSteps), trace(m, 3, kSteps)));
}

TEST_CASE("threads: WorkerPool runs every index once, in chunks that depend on n and the grain only") {
  for (int threads : {1, 2, 3, 8}) {
    simbob::WorkerPool pool(threads);
    for (size_t n : {size_t(0), size_t(1), size_t(5), size_t(100), size_t(1000)}) {
      std::vector<int> hits(n, 0);
      std::vector<size_t> seen(pool.chunks(n, 4), 0);
      for (int round = 0; round < 3; ++round)
        pool.run(n, 4, [&](size_t c, size_t begin, size_t end, int worker) {
          CHECK(worker >= 0);
          CHECK(worker < threads);
          CHECK(begin == c * n / seen.size());
          CHECK(end == (c + 1) * n / seen.size());
          seen[c] += 1;
          for (size_t i = begin; i < end; ++i) hits[i] += 1;
        });
      for (size_t i = 0; i < n; ++i) CHECK(hits[i] == 3);
      for (size_t c : seen) CHECK(c == 3);
      CHECK(pool.chunks(n, 4) == (n == 0         ? 0
                                  : threads == 1 ? 1
                                                 : std::max<size_t>(1, std::min<size_t>(8 * threads, n / 4))));
    }
  }
}

TEST_CASE("threads: a chunk that throws does not end its worker; run() throws the lowest such chunk's exception") {
  // ODE's errors are thrown out of ODE (world.cpp) and may be thrown on a narrow-phase worker.
  for (int threads : {1, 2, 4}) {
    simbob::WorkerPool pool(threads);
    for (int round = 0; round < 3; ++round) {
      std::atomic<int> done{0};
      try {
        pool.run(1000, 4, [&](size_t, size_t b, size_t e, int) {
          done.fetch_add(1);
          for (size_t bad : {size_t(500), size_t(900)})
            if (b <= bad && bad < e) throw std::runtime_error("index " + std::to_string(bad));
        });
        FAIL("run() did not throw");
      } catch (const std::runtime_error& e) {
        CHECK(std::string(e.what()) == "index 500");
      }
      if (threads > 1) CHECK(done.load() == static_cast<int>(pool.chunks(1000, 4)));
    }
    // The pool still works afterwards.
    std::atomic<size_t> sum{0};
    pool.run(100, 4, [&](size_t, size_t b, size_t e, int) { sum.fetch_add(e - b); });
    CHECK(sum.load() == 100);
  }
}
