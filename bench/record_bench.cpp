// bench/record_bench: frames per second of recording with the encoder on a worker thread
// (makeAsyncSink) against the sequential loop render -> encode -> render -> ... on the same
// frames (issue #12 point 7). See bench/README.md, "Recording".
//
//   build/bench/record_bench [--frames 120] [--size 640x480] [--format avi|mp4|png]
//                            [--repeats 5] [--queue 4] [--render-passes 1] [--out DIR]
//
// The frames come from `renderFrame` below: until lib/render is in main, a CPU stand-in that
// draws a 100-box scene (a 10 x 10 grid of shaded boxes over a gradient floor, moving a little
// each frame); --render-passes K draws it K times per frame, to give the stand-in the cost of a
// real renderer (llvmpipe on this scene). The real renderer plugs in at that one function; everything else (sinks, timing,
// medians) stays. Prints one line per run and the medians; exits 0, or 1 on a sink error.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "simbob/frame_sinks.h"

namespace {

using Clock = std::chrono::steady_clock;
using simbob::Image;

// A stand-in for one rendered frame of the 100-box scene at time step n: per-pixel work over
// the whole frame (floor shading with fog) plus 100 boxes with a lit top and two lit sides.
int g_render_passes = 1;

Image renderOnce(int w, int h, int n);

Image renderFrame(int w, int h, int n) {
  Image img = renderOnce(w, h, n);
  for (int k = 1; k < g_render_passes; ++k) img = renderOnce(w, h, n);
  return img;
}

Image renderOnce(int w, int h, int n) {
  Image img(w, h);
  const double horizon = 0.35 * h;
  for (int y = 0; y < h; ++y) {
    const double depth = y > horizon ? (h - horizon) / (y - horizon + 1.0) : 1e9;
    const double fog = 1.0 - std::exp(-0.05 * std::min(depth, 200.0));
    for (int x = 0; x < w; ++x) {
      uint8_t* p = img.pixel(x, y);
      if (y <= horizon) {
        p[0] = static_cast<uint8_t>(150 + 60.0 * y / horizon);
        p[1] = static_cast<uint8_t>(180 + 50.0 * y / horizon);
        p[2] = 235;
      } else {
        const double u = (x - w / 2.0) * depth / w, v = depth;
        const bool check = (static_cast<int>(std::floor(u)) + static_cast<int>(std::floor(v))) & 1;
        const double base = check ? 120 : 90;
        for (int c = 0; c < 3; ++c) p[c] = static_cast<uint8_t>(base * (1 - fog) + 200 * fog);
      }
    }
  }
  for (int i = 0; i < 100; ++i) {
    const int gx = i % 10, gy = i / 10;
    const double bob = 3.0 * std::sin(0.2 * n + i);
    const int size = 10 + gy * 2;
    const int x0 = static_cast<int>(w * (0.1 + 0.08 * gx) + (gx - 4.5) * gy * 2);
    const int y0 = static_cast<int>(horizon + 10 + gy * (h - horizon - 40) / 10.0 + bob);
    const uint8_t r = static_cast<uint8_t>(60 + 19 * gx), g = static_cast<uint8_t>(60 + 17 * gy), b = 160;
    for (int y = std::max(0, y0 - size / 3); y < std::min(h, y0 + size); ++y)
      for (int x = std::max(0, x0); x < std::min(w, x0 + size + size / 3); ++x) {
        uint8_t* p = img.pixel(x, y);
        const double shade = y < y0 ? 1.0 : (x >= x0 + size ? 0.55 : 0.8);
        p[0] = static_cast<uint8_t>(r * shade);
        p[1] = static_cast<uint8_t>(g * shade);
        p[2] = static_cast<uint8_t>(b * shade);
      }
  }
  return img;
}

std::unique_ptr<simbob::FrameSink> makeSink(const std::string& format, const std::string& out, simbob::Error* err) {
  if (format == "png") return simbob::makePngSequenceSink(out + "/frames", err);
  return simbob::makeVideoSink(out + "/video." + format, 30, err);
}

// Renders and records `frames` frames; returns frames per second of wall time, or -1.
double run(bool async, int frames, int w, int h, const std::string& format, size_t queue, const std::string& out) {
  simbob::Error err;
  std::unique_ptr<simbob::FrameSink> sink = makeSink(format, out, &err);
  if (!sink) {
    std::fprintf(stderr, "record_bench: %s\n", err.str().c_str());
    return -1;
  }
  if (async) {
    std::vector<std::unique_ptr<simbob::FrameSink>> inner;
    inner.push_back(std::move(sink));
    sink = simbob::makeAsyncSink(std::move(inner), queue);
  }
  const Clock::time_point start = Clock::now();
  for (int n = 0; n < frames; ++n) {
    if (const simbob::Error* e = sink->add(renderFrame(w, h, n))) {
      std::fprintf(stderr, "record_bench: %s\n", e->str().c_str());
      return -1;
    }
  }
  if (const simbob::Error* e = sink->finish()) {
    std::fprintf(stderr, "record_bench: %s\n", e->str().c_str());
    return -1;
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return frames / seconds;
}

// CPU time of the whole process spent in f, in ms.
template <class F>
double cpuMs(F f) {
  const std::clock_t t = std::clock();
  f();
  return 1000.0 * static_cast<double>(std::clock() - t) / CLOCKS_PER_SEC;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 120, w = 640, h = 480, repeats = 5;
  size_t queue = 4;
  std::string format = "avi", out;
  const char* usage =
      "usage: record_bench [--frames N] [--size WxH] [--format avi|mp4|png] [--repeats R] [--queue Q]\n"
      "                    [--render-passes K] [--out DIR]\n";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const char* v = argv[i + 1];
    if (a == "--frames") {
      frames = std::atoi(v);
    } else if (a == "--size") {
      if (std::sscanf(v, "%dx%d", &w, &h) != 2) w = 0;
    } else if (a == "--format") {
      format = v;
    } else if (a == "--repeats") {
      repeats = std::atoi(v);
    } else if (a == "--queue") {
      queue = static_cast<size_t>(std::atoi(v));
    } else if (a == "--render-passes") {
      g_render_passes = std::atoi(v);
    } else if (a == "--out") {
      out = v;
    } else {
      std::fputs(usage, stderr);
      return 64;
    }
  }
  if (argc % 2 == 0) {
    std::fputs(usage, stderr);
    return 64;
  }
  if (frames <= 0 || w <= 0 || h <= 0 || repeats <= 0 || g_render_passes <= 0) {
    std::fprintf(stderr, "record_bench: frames, size, repeats and render passes must be positive\n");
    return 64;
  }
  namespace fs = std::filesystem;
  const bool own_out = out.empty();
  if (own_out) out = (fs::temp_directory_path() / ("simbob_record_bench_" + std::to_string(::getpid()))).string();
  fs::create_directories(out);

  // Each stage alone, in CPU time of this process (less disturbed by other load than wall
  // time): R ms to render a frame, E ms to encode one. Overlapping them on two cores can at best
  // reach (R + E) / max(R, E) times the sequential rate.
  std::vector<Image> sample;
  const double render_ms = cpuMs([&] {
                             for (int n = 0; n < 20; ++n) sample.push_back(renderFrame(w, h, n));
                           }) /
                           20;
  simbob::Error err;
  fs::create_directories(out + "/probe");
  std::unique_ptr<simbob::FrameSink> probe = makeSink(format, out + "/probe", &err);
  if (!probe) {
    std::fprintf(stderr, "record_bench: %s\n", err.str().c_str());
    return 1;
  }
  const double encode_ms = cpuMs([&] {
                             for (Image& img : sample) probe->add(std::move(img));
                             probe->finish();
                           }) /
                           20;
  std::printf("frames %d, %dx%d, format %s, queue %zu, render passes %d\n", frames, w, h, format.c_str(), queue,
              g_render_passes);
  std::printf("CPU per frame: render %.2f ms, encode %.2f ms; best possible overlap ratio %.2f\n", render_ms, encode_ms,
              (render_ms + encode_ms) / std::max(render_ms, encode_ms));
  std::vector<double> seq, par;
  for (int r = 0; r < repeats; ++r) {
    // Alternate the order so that drift of the machine's load favours neither.
    for (int k = 0; k < 2; ++k) {
      const bool async = (r + k) % 2 == 1;
      const double fps = run(async, frames, w, h, format, queue, out);
      if (fps < 0) return 1;
      (async ? par : seq).push_back(fps);
      std::printf("run %d %-10s %7.1f fps\n", r, async ? "async" : "sequential", fps);
    }
  }
  const double ms = median(seq), mp = median(par);
  std::printf("median sequential %.1f fps, async %.1f fps, ratio %.2f\n", ms, mp, mp / ms);
  if (own_out) fs::remove_all(out);
  return 0;
}
