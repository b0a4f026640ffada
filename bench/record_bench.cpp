// bench/record_bench: frames per second of recording as `simbob run --record/--video` does it
// -- the physics on the run loop's thread, drawing on a render thread (drawOnRenderThread),
// encoding on a third (makeAsyncSink) -- against the sequential loop
// step -> render -> encode -> step -> ... on the same scene (issue #12 point 7). See
// bench/README.md, "Recording".
//
//   build/bench/record_bench [--scene bench/scenes/boxes100.xml] [--frames 120] [--fps 30]
//                            [--size 640x480] [--format avi|mp4|png] [--gl auto|egl|osmesa]
//                            [--repeats 5] [--queue 4] [--out DIR]
//
// Every timed run goes through the real pieces: the scene is loaded and compiled once, one
// Renderer (GL context) is created once, and each run is runParties() with a Recorder party,
// which at t = n / fps reads the poses and hands them to a FrameDrawer: drawInline (sequential:
// drawing and encoding happen inside the grant, the physics waits) or drawOnRenderThread
// around makeAsyncSink (pipelined: the grant returns once the poses are queued). The two
// alternate; the program prints one line per run, the medians and their ratio. Before that it
// times each stage alone on the same frames (physics, render, encode per frame, in process CPU
// time and in wall time). Exits 0, or 1 when loading, rendering or a sink fails.
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "simbob/clock.h"
#include "simbob/compile.h"
#include "simbob/tool/frame_sinks.h"
#include "simbob/graph.h"
#include "simbob/physics.h"
#include "simbob/registry.h"
#include "simbob/renderer.h"
#include "simbob/loop.h"
#include "simbob/simulation.h"

namespace {

using Clock = std::chrono::steady_clock;
using simbob::Error;
using simbob::FrameSink;
using simbob::Image;
using simbob::Model;
using simbob::Renderer;

struct Settings {
  std::string scene = SIMBOB_BENCH_SCENE;  // bench/scenes/boxes100.xml in the source tree
  int frames = 120;
  double fps = 30;
  int width = 640, height = 480;
  std::string format = "avi";
  std::string gl = "auto";
  int repeats = 5;
  size_t queue = 4;
  std::string out;
};

void fail(const Error& e) { std::fprintf(stderr, "record_bench: %s\n", e.str().c_str()); }

std::unique_ptr<FrameSink> makeSink(const Settings& s, const std::string& dir, Error* err) {
  if (s.format == "png") return simbob::makePngSequenceSink(dir + "/frames", err);
  return simbob::makeVideoSink(dir + "/video." + s.format, s.fps, err);
}

// Process CPU time (every thread: llvmpipe's rasterizer threads and the encoder's count), ms.
double cpuNowMs() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

// CPU time of the calling thread alone, ms.
double threadCpuNowMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

double wallNowMs() { return std::chrono::duration<double, std::milli>(Clock::now().time_since_epoch()).count(); }

// One stage's time, summed over the frames.
struct StageTime {
  double cpu = 0, wall = 0;
  template <class F>
  void add(F f) {
    const double c = cpuNowMs(), w = wallNowMs();
    f();
    cpu += cpuNowMs() - c;
    wall += wallNowMs() - w;
  }
};

// Each stage alone on the frames of a recording: the world stepped to t = n / fps (steps of the
// scene's MaxTimeStep, the last one shortened to land on t), the frame rendered, then encoded
// into a sink of the chosen format. Returns false (and prints why) if something fails.
bool timeStages(const Model& model, Renderer& renderer, const Settings& s, const std::string& dir, StageTime* physics,
                StageTime* render, StageTime* encode) {
  Error err;
  std::unique_ptr<FrameSink> sink = makeSink(s, dir, &err);
  if (!sink) {
    fail(err);
    return false;
  }
  std::unique_ptr<simbob::World> world = simbob::World::create(model, 0);
  const simbob::SimTime step = simbob::toSimTime(model.settings.max_time_step).value_or(1000000);
  simbob::SimTime now = 0;
  std::vector<simbob::Transform> poses(model.bodies.size());
  for (int n = 0; n < s.frames; ++n) {
    const simbob::SimTime target = simbob::toSimTime(n / s.fps).value_or(now);
    physics->add([&] {
      while (now < target) {
        const simbob::SimTime h = std::min(step, target - now);
        world->step(simbob::toSeconds(h));
        now += h;
      }
    });
    for (int i = 0; i < world->bodyCount(); ++i) poses[static_cast<size_t>(i)] = world->body(i).pose;
    Image img;
    const Error* e = nullptr;
    render->add([&] { e = renderer.render(poses, simbob::toSeconds(now), &img); });
    if (!e) encode->add([&] { e = sink->add(std::move(img)); });
    if (e) {
      fail(*e);
      return false;
    }
  }
  const Error* e = nullptr;
  encode->add([&] { e = sink->finish(); });
  if (e) fail(*e);
  return e == nullptr;
}

// One recording through the run loop, as `simbob run --video` makes it: a Recorder party
// hands frame n at t = n / fps to drawInline around the sink (sequential), or to
// drawOnRenderThread around makeAsyncSink around it (pipelined).
// Returns frames per second of wall time (world creation to the sink's finish), or -1.
double record(const Model& model, Renderer& renderer, const Settings& s, bool pipelined, const std::string& dir,
              double* loop_cpu_ms) {
  Error err;
  std::unique_ptr<FrameSink> sink = makeSink(s, dir, &err);
  if (!sink) {
    fail(err);
    return -1;
  }
  if (pipelined) {
    std::vector<std::unique_ptr<FrameSink>> inner;
    inner.push_back(std::move(sink));
    sink = simbob::makeAsyncSink(std::move(inner), s.queue);
  }
  std::unique_ptr<simbob::FrameDrawer> drawer =
      pipelined ? simbob::drawOnRenderThread(renderer, *sink, s.queue) : simbob::drawInline(renderer, *sink);
  simbob::Recorder recorder(*drawer, s.fps, simbob::toSimTime(model.settings.min_time_step).value_or(0),
                            static_cast<int>(model.bodies.size()));
  // The run as `simbob run --record` makes it: a Simulation with the recorder as its party.
  simbob::SimulationOptions opts;
  opts.duration = (s.frames - 1) / s.fps;  // frames at 0, 1/fps, ..., duration
  simbob::Diagnostics diag;
  std::unique_ptr<simbob::Simulation> sim = simbob::Simulation::fromModel(model, opts, diag);
  if (!sim) {
    fail(diag.errors().front());
    return -1;
  }
  sim->addParty(recorder);
  const Clock::time_point start = Clock::now();
  const double loop_cpu = threadCpuNowMs();
  const simbob::RunResult r = sim->runToEnd();
  *loop_cpu_ms = (threadCpuNowMs() - loop_cpu) / s.frames;
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (r.status != simbob::RunStatus::Completed) {
    fail(r.error);
    return -1;
  }
  if (recorder.frames() != static_cast<uint64_t>(s.frames)) {
    std::fprintf(stderr, "record_bench: recorded %llu frames, expected %d\n",
                 static_cast<unsigned long long>(recorder.frames()), s.frames);
    return -1;
  }
  return s.frames / seconds;
}

// The first three fields of /proc/loadavg (1, 5 and 15 minute load averages), or "?".
std::string loadAverage() {
  char text[64] = "?";
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    double a = 0, b = 0, c = 0;
    if (std::fscanf(f, "%lf %lf %lf", &a, &b, &c) == 3) std::snprintf(text, sizeof text, "%.2f %.2f %.2f", a, b, c);
    std::fclose(f);
  }
  return text;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The median CPU and the median wall time (each on its own) of several passes.
StageTime medianStage(const std::vector<StageTime>& passes) {
  std::vector<double> cpu, wall;
  for (const StageTime& t : passes) {
    cpu.push_back(t.cpu);
    wall.push_back(t.wall);
  }
  return {median(cpu), median(wall)};
}

// Reads the options into *s; false on a usage error.
bool parseArgs(int argc, char** argv, Settings* s) {
  if (argc % 2 == 0) return false;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const char* v = argv[i + 1];
    if (a == "--scene") {
      s->scene = v;
    } else if (a == "--frames") {
      s->frames = std::atoi(v);
    } else if (a == "--fps") {
      s->fps = std::atof(v);
    } else if (a == "--size") {
      if (std::sscanf(v, "%dx%d", &s->width, &s->height) != 2) return false;
    } else if (a == "--format") {
      s->format = v;
    } else if (a == "--gl") {
      s->gl = v;
    } else if (a == "--repeats") {
      s->repeats = std::atoi(v);
    } else if (a == "--queue") {
      s->queue = static_cast<size_t>(std::atoi(v));
    } else if (a == "--out") {
      s->out = v;
    } else {
      return false;
    }
  }
  return s->frames > 0 && s->fps > 0 && s->fps <= 1000 && s->width > 0 && s->height > 0 && s->repeats > 0 &&
         s->queue > 0 && (s->format == "avi" || s->format == "mp4" || s->format == "png");
}

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  if (!parseArgs(argc, argv, &s)) {
    std::fputs(
        "usage: record_bench [--scene FILE] [--frames N] [--fps F] [--size WxH] [--format avi|mp4|png]\n"
        "                    [--gl auto|egl|osmesa] [--repeats R] [--queue Q] [--out DIR]\n",
        stderr);
    return 64;
  }
  simbob::RenderOptions ro;
  ro.width = s.width;
  ro.height = s.height;
  if (!simbob::parseGlBackend(s.gl, &ro.backend)) {
    std::fprintf(stderr, "record_bench: --gl must be auto, egl or osmesa, got '%s'\n", s.gl.c_str());
    return 64;
  }

  simbob::Registry registry;
  if (!simbob::registerBuiltins(registry)) {
    std::fprintf(stderr, "record_bench: the built-in component types did not register\n");
    return 1;
  }
  simbob::Scene scene;
  Model model;
  simbob::Diagnostics diag;
  if (!simbob::loadScene(s.scene, registry, &scene, diag) || !simbob::compileScene(scene, &model, diag)) {
    for (const Error& e : diag.errors()) fail(e);
    return 1;
  }
  scene = simbob::Scene{};
  Error err;
  std::unique_ptr<Renderer> renderer = Renderer::create(model, ro, &err);
  if (!renderer) {
    fail(err);
    return 1;
  }

  namespace fs = std::filesystem;
  const bool own_out = s.out.empty();
  if (own_out) s.out = (fs::temp_directory_path() / ("simbob_record_bench_" + std::to_string(::getpid()))).string();
  fs::create_directories(s.out + "/stages");
  const char* lp_threads = std::getenv("LP_NUM_THREADS");
  std::printf("scene %s: %zu bodies; %d frames at %g fps, %dx%d, format %s, queue %zu\n", s.scene.c_str(),
              model.bodies.size(), s.frames, s.fps, s.width, s.height, s.format.c_str(), s.queue);
  std::printf("load average %s\n", loadAverage().c_str());
  std::printf("renderer %s, %s, camera %s; LP_NUM_THREADS=%s\n", renderer->backendName().c_str(),
              renderer->glRenderer().c_str(), renderer->cameraName().c_str(), lp_threads ? lp_threads : "(unset)");

  // Each stage alone: one untimed pass first (llvmpipe compiles its shader variants during the
  // first frames; x264 and zlib warm up too), then three timed passes; each stage's median.
  // With one thread per stage (physics, render, encode), the pipeline can at best reach
  // (P + R + E) / max(P, R, E) times the sequential rate, and on two cores no more than
  // (P + R + E) / max(P, R, E, (P + R + E) / 2).
  std::vector<StageTime> passes[3];
  for (int k = 0; k < 4; ++k) {
    StageTime stage[3];
    if (!timeStages(model, *renderer, s, s.out + "/stages", &stage[0], &stage[1], &stage[2])) return 1;
    if (k > 0)
      for (int i = 0; i < 3; ++i) passes[i].push_back(stage[i]);
  }
  const StageTime physics = medianStage(passes[0]), render = medianStage(passes[1]), encode = medianStage(passes[2]);
  const double f = s.frames, p = physics.cpu / f, r = render.cpu / f, e = encode.cpu / f;
  std::printf("per frame, CPU ms:  physics %.2f, render %.2f, encode %.2f\n", p, r, e);
  std::printf("per frame, wall ms: physics %.2f, render %.2f, encode %.2f\n", physics.wall / f, render.wall / f,
              encode.wall / f);
  std::printf("best achievable ratio (P+R+E)/max(P, R, E), from CPU times: %.2f\n", (p + r + e) / std::max({p, r, e}));
  // The renderer's CPU time may exceed its wall time (llvmpipe's rasterizer threads), and two
  // cores bound the pipelined rate by the total CPU work as well.
  const double seq_wall = (physics.wall + render.wall + encode.wall) / f;
  const double par_bound = std::max({(p + r + e) / 2, physics.wall / f, render.wall / f, encode.wall / f});
  std::printf("2-core bound: sequential %.2f ms / max((P+R+E)cpu/2, Pwall, Rwall, Ewall) %.2f ms = %.2f\n", seq_wall,
              par_bound, seq_wall / par_bound);

  std::vector<double> seq, par;
  for (int rep = 0; rep < s.repeats; ++rep) {
    // Alternate the order so that drift of the machine's load favours neither.
    for (int k = 0; k < 2; ++k) {
      const bool pipelined = (rep + k) % 2 == 1;
      double loop_cpu = 0;
      const double fps = record(model, *renderer, s, pipelined, s.out, &loop_cpu);
      if (fps < 0) return 1;
      (pipelined ? par : seq).push_back(fps);
      std::printf("run %d %-10s %7.1f fps  (%5.2f ms/frame wall, run-loop thread CPU %5.2f ms/frame)\n", rep,
                  pipelined ? "pipelined" : "sequential", fps, 1e3 / fps, loop_cpu);
    }
  }
  const double ms = median(seq), mp = median(par);
  std::printf("median sequential %.1f fps, pipelined %.1f fps, ratio %.2f\n", ms, mp, mp / ms);
  std::printf("load average %s\n", loadAverage().c_str());
  if (own_out) fs::remove_all(s.out);
  return 0;
}
