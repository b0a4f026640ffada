#include "simbob/tool/plot.h"

#include <unistd.h>

// <cairo/cairo.h>: the test decodes the plots with cairo, through pkg-config, whose include
// directory is the parent of ours.
#include <cairo/cairo.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "simbob/trajectory.h"

// fontconfig (used by cairo's toy text API) keeps process-lifetime caches that LeakSanitizer
// reports in SIMBOB_SANITIZE builds; they are not leaks of simbob.
extern "C" const char* __lsan_default_suppressions() { return "leak:libfontconfig.so\n"; }

namespace fs = std::filesystem;
using simbob::Error;
using simbob::ErrorKind;
using simbob::PlotColor;
using simbob::PlotOptions;
using simbob::Trajectory;

namespace {

/// A fresh directory under the system temp dir, removed with its contents at scope exit.
struct PlotTempDir {
  fs::path path;
  PlotTempDir() {
    static int counter = 0;
    std::random_device rd;
    path = fs::temp_directory_path() / ("simbob_plot_test_" + std::to_string(::getpid()) + "_" +
                                        std::to_string(++counter) + "_" + std::to_string(rd()));
    fs::create_directories(path);
  }
  ~PlotTempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// A PNG decoded by cairo into 0xRRGGBB pixels.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint32_t> px;

  uint32_t at(int x, int y) const { return px[static_cast<size_t>(y) * width + x]; }
};

Image loadPng(const std::string& path) {
  Image img;
  cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
  REQUIRE(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS);
  cairo_surface_flush(s);
  img.width = cairo_image_surface_get_width(s);
  img.height = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  img.px.resize(static_cast<size_t>(img.width) * img.height);
  for (int y = 0; y < img.height; ++y) {
    const auto* row = reinterpret_cast<const uint32_t*>(data + static_cast<size_t>(y) * stride);
    for (int x = 0; x < img.width; ++x) img.px[static_cast<size_t>(y) * img.width + x] = row[x] & 0xFFFFFF;
  }
  cairo_surface_destroy(s);
  return img;
}

bool near(uint32_t p, PlotColor c, int tol = 6) {
  const int r = static_cast<int>((p >> 16) & 0xFF);
  const int g = static_cast<int>((p >> 8) & 0xFF);
  const int b = static_cast<int>(p & 0xFF);
  return std::abs(r - c.r) <= tol && std::abs(g - c.g) <= tol && std::abs(b - c.b) <= tol;
}

/// Rows in [y0, y1) holding at least min_count pixels of colour c.
std::vector<int> rowsWithColor(const Image& img, PlotColor c, int y0, int y1, int min_count) {
  std::vector<int> rows;
  for (int y = y0; y < y1; ++y) {
    int n = 0;
    for (int x = 0; x < img.width; ++x) n += near(img.at(x, y), c) ? 1 : 0;
    if (n >= min_count) rows.push_back(y);
  }
  return rows;
}

int countColor(const Image& img, PlotColor c, int x0, int x1, int y0, int y1) {
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) n += near(img.at(x, y), c) ? 1 : 0;
  return n;
}

/// n samples over [0, t_end]; pos(body, t) gives x y z (identity orientation).
Trajectory makeTraj(const std::vector<std::string>& bodies, size_t n, double t_end,
                    const std::function<void(size_t, double, double*)>& pos) {
  Trajectory tr;
  for (size_t s = 0; s < n; ++s) tr.times.push_back(n == 1 ? 0.0 : t_end * s / (n - 1));
  for (const std::string& b : bodies) tr.addBody(b);
  for (size_t s = 0; s < n; ++s) {
    for (size_t b = 0; b < bodies.size(); ++b) {
      double p[simbob::kPoseSize] = {0, 0, 0, 1, 0, 0, 0};
      pos(b, tr.times[s], p);
      tr.setPose(s, b, p);
    }
  }
  tr.finalize();
  return tr;
}

/// Bodies at constant positions: body b sits at (x[b], y[b], z[b]).
Trajectory constantTraj(const std::vector<std::string>& bodies, const std::vector<double>& xs) {
  return makeTraj(bodies, 50, 1.0, [&](size_t b, double, double* p) {
    p[0] = xs[b];
    p[1] = 2.0;
    p[2] = 3.0;
  });
}

Trajectory waveTraj() {
  return makeTraj({"base", "arm/link1"}, 200, 2.0, [](size_t b, double t, double* p) {
    p[0] = std::sin(3 * t) + b;
    p[1] = std::cos(2 * t) * (b + 1);
    p[2] = 0.5 * t * t;
  });
}

}  // namespace

TEST_CASE("plot: PNG has the requested size and is not blank", "[plot]") {
  PlotTempDir dir;
  const std::string out = dir.file("wave.png");
  PlotOptions opt;
  opt.width = 800;
  opt.height = 600;
  opt.title = "wave";
  Error err;
  REQUIRE(simbob::plotTrajectory(waveTraj(), nullptr, opt, out, &err));
  const Image img = loadPng(out);
  CHECK(img.width == 800);
  CHECK(img.height == 600);
  size_t ink = 0;
  for (uint32_t p : img.px) ink += p != 0xFFFFFF ? 1 : 0;
  CHECK(ink > img.px.size() / 50);  // axes, grid, text and two lines per panel
  CHECK(countColor(img, simbob::plotColor(0), 0, 800, 0, 600) > 300);
  CHECK(countColor(img, simbob::plotColor(1), 0, 800, 0, 600) > 300);
  CHECK_FALSE(fs::exists(out + ".tmp." + std::to_string(::getpid())));
}

TEST_CASE("plot: height 0 means 300 px per panel", "[plot]") {
  PlotTempDir dir;
  const std::string out = dir.file("default.png");
  PlotOptions opt;
  opt.width = 640;
  Error err;
  REQUIRE(simbob::plotTrajectory(waveTraj(), nullptr, opt, out, &err));
  const Image img = loadPng(out);
  CHECK(img.width == 640);
  CHECK(img.height == 900);
}

TEST_CASE("plot: a constant x is one horizontal band in the upper panel", "[plot]") {
  PlotTempDir dir;
  const std::string out = dir.file("const.png");
  PlotOptions opt;
  opt.width = 600;
  opt.height = 900;
  Error err;
  // x = 1 for "low" and x = 2 for "high": the upper panel must put "high" above "low".
  REQUIRE(simbob::plotTrajectory(constantTraj({"low", "high"}, {1.0, 2.0}), nullptr, opt, out, &err));
  const Image img = loadPng(out);
  const int min_run = img.width / 2;  // a line across the panel, not the legend swatch
  const std::vector<int> low = rowsWithColor(img, simbob::plotColor(0), 0, img.height / 3, min_run);
  const std::vector<int> high = rowsWithColor(img, simbob::plotColor(1), 0, img.height / 3, min_run);
  REQUIRE_FALSE(low.empty());
  REQUIRE_FALSE(high.empty());
  CHECK(low.back() - low.front() <= 3);  // a 2 px line: one narrow band of rows
  CHECK(high.back() - high.front() <= 3);
  CHECK(high.back() < low.front());      // larger x is higher up
  CHECK(low.front() > img.height / 12);  // below the title and legend
}

TEST_CASE("plot: a ramp rises from left to right", "[plot]") {
  PlotTempDir dir;
  const std::string out = dir.file("ramp.png");
  const Trajectory tr = makeTraj({"r"}, 101, 10.0, [](size_t, double t, double* p) { p[0] = t; });
  Error err;
  PlotOptions opt;
  REQUIRE(simbob::plotTrajectory(tr, nullptr, opt, out, &err));
  const Image img = loadPng(out);
  const PlotColor c = simbob::plotColor(0);
  // Topmost line pixel in a column near the left and one near the right of the upper panel.
  auto topRow = [&](int x) {
    for (int y = img.height / 10; y < img.height / 3; ++y)
      if (near(img.at(x, y), c)) return y;
    return -1;
  };
  const int left = topRow(img.width / 5);
  const int right = topRow(img.width * 9 / 10);
  REQUIRE(left > 0);
  REQUIRE(right > 0);
  CHECK(right < left - 50);
}

TEST_CASE("plot: golden lines are drawn dashed and change the image", "[plot]") {
  PlotTempDir dir;
  const Trajectory actual = makeTraj({"a"}, 100, 1.0, [](size_t, double t, double* p) { p[0] = t; });
  const Trajectory golden = makeTraj({"a"}, 100, 1.0, [](size_t, double t, double* p) { p[0] = 1.0 - t; });
  PlotOptions opt;
  opt.width = 600;
  Error err;
  REQUIRE(simbob::plotTrajectory(actual, nullptr, opt, dir.file("plain.png"), &err));
  REQUIRE(simbob::plotTrajectory(actual, &golden, opt, dir.file("golden.png"), &err));
  const Image plain = loadPng(dir.file("plain.png"));
  const Image with = loadPng(dir.file("golden.png"));
  REQUIRE(plain.px.size() == with.px.size());
  size_t diff = 0;
  for (size_t i = 0; i < plain.px.size(); ++i) diff += plain.px[i] != with.px[i] ? 1 : 0;
  CHECK(diff > 500);
  // More line colour with the golden line than without, in the upper panel.
  const PlotColor c = simbob::plotColor(0);
  const int third = plain.height / 3;
  CHECK(countColor(with, c, 0, with.width, 0, third) > countColor(plain, c, 0, plain.width, 0, third) + 100);

  SECTION("dashed: the golden line is broken into many runs along its row") {
    const Trajectory flat = makeTraj({"a"}, 100, 1.0, [](size_t, double, double* p) { p[0] = 5.0; });
    const Trajectory flat_golden = makeTraj({"a"}, 100, 1.0, [](size_t, double, double* p) { p[0] = 1.0; });
    REQUIRE(simbob::plotTrajectory(flat, &flat_golden, opt, dir.file("dash.png"), &err));
    const Image img = loadPng(dir.file("dash.png"));
    // Antialiased 1.5 px dashes rarely hit the exact colour, so look for blue-tinted pixels.
    auto bluish = [&](int x, int y) {
      const uint32_t p = img.at(x, y);
      return static_cast<int>(p & 0xFF) - static_cast<int>((p >> 16) & 0xFF) > 20;
    };
    auto runs = [&](int y) {
      int n = 0;
      for (int x = 1; x < img.width; ++x) n += (bluish(x, y) && !bluish(x - 1, y)) ? 1 : 0;
      return n;
    };
    auto count = [&](int y) {
      int n = 0;
      for (int x = 0; x < img.width; ++x) n += bluish(x, y) ? 1 : 0;
      return n;
    };
    // Bands of line pixels in the upper panel: the upper one is actual (x = 5), the lower golden.
    int actual_row = -1, golden_row = -1;
    for (int y = img.height / 10; y < img.height / 3; ++y) {
      if (count(y) < 100) continue;
      if (actual_row < 0) actual_row = y;
      if (y > actual_row + 10 && (golden_row < 0 || count(y) > count(golden_row))) golden_row = y;
    }
    REQUIRE(actual_row > 0);
    REQUIRE(golden_row > 0);
    CHECK(runs(actual_row) <= 2);   // solid
    CHECK(runs(golden_row) >= 20);  // 7 px on, 4 px off across ~500 px
  }
}

TEST_CASE("plot: bodies missing in golden and golden-only bodies are fine", "[plot]") {
  PlotTempDir dir;
  const Trajectory actual = constantTraj({"a", "b"}, {1.0, 2.0});
  const Trajectory golden = constantTraj({"b", "c"}, {2.5, 7.0});
  Error err;
  REQUIRE(simbob::plotTrajectory(actual, &golden, PlotOptions(), dir.file("p.png"), &err));
  CHECK(fs::file_size(dir.file("p.png")) > 1000);
}

TEST_CASE("plot: a single sample and missing rows", "[plot]") {
  PlotTempDir dir;
  Error err;
  SECTION("one sample draws a dot") {
    const Trajectory one = makeTraj({"solo"}, 1, 0.0, [](size_t, double, double* p) { p[0] = 0.25; });
    REQUIRE(simbob::plotTrajectory(one, nullptr, PlotOptions(), dir.file("one.png"), &err));
    const Image img = loadPng(dir.file("one.png"));
    // Legend swatch (2 px x 28 px) plus a dot in each panel.
    CHECK(countColor(img, simbob::plotColor(0), 0, img.width, img.height / 10, img.height) >= 3 * 15);
  }
  SECTION("a body with rows only in the first half has no line in the second half") {
    Trajectory tr = constantTraj({"part", "full"}, {1.0, 2.0});
    for (size_t s = 25; s < tr.sampleCount(); ++s) tr.present[0][s] = 0;
    REQUIRE(simbob::plotTrajectory(tr, nullptr, PlotOptions(), dir.file("part.png"), &err));
    const Image img = loadPng(dir.file("part.png"));
    const PlotColor c = simbob::plotColor(0);
    CHECK(countColor(img, c, img.width / 10, img.width * 4 / 10, img.height / 10, img.height) > 300);
    CHECK(countColor(img, c, img.width * 6 / 10, img.width, 0, img.height) == 0);
  }
}

TEST_CASE("plot: long trajectories are decimated but keep spikes", "[plot]") {
  PlotTempDir dir;
  const size_t n = 1000000;
  const size_t spike = n / 2 + 17;
  Trajectory tr;
  tr.times.resize(n);
  for (size_t s = 0; s < n; ++s) tr.times[s] = s * 1e-4;
  tr.addBody("fast");
  for (size_t s = 0; s < n; ++s) {
    const double p[simbob::kPoseSize] = {s == spike ? 10.0 : 0.0, 0, 0, 1, 0, 0, 0};
    tr.setPose(s, 0, p);
  }
  tr.finalize();
  Error err;
  PlotOptions opt;
  opt.width = 800;
  REQUIRE(simbob::plotTrajectory(tr, nullptr, opt, dir.file("long.png"), &err));
  const Image img = loadPng(dir.file("long.png"));
  const PlotColor c = simbob::plotColor(0);
  // The single-sample spike reaches the top of the upper panel's data range.
  const std::vector<int> flat = rowsWithColor(img, c, 0, img.height / 3, img.width / 2);
  REQUIRE_FALSE(flat.empty());
  const int spike_pixels = countColor(img, c, img.width / 3, img.width * 2 / 3, img.height / 10, flat.front() - 20);
  CHECK(spike_pixels > 100);
}

TEST_CASE("plot: more than 8 bodies are capped, odd keys are drawable", "[plot]") {
  PlotTempDir dir;
  std::vector<std::string> keys;
  std::vector<double> xs;
  for (int i = 0; i < 11; ++i) {
    keys.push_back("body" + std::to_string(i));
    xs.push_back(i);
  }
  keys[3] = std::string("bad\xff\xfe utf8\nkey");  // invalid UTF-8 and a newline
  Error err;
  REQUIRE(simbob::plotTrajectory(constantTraj(keys, xs), nullptr, PlotOptions(), dir.file("many.png"), &err));
  const Image img = loadPng(dir.file("many.png"));
  // Text was drawn after the odd key (cairo did not stop): the last body's line is present.
  CHECK(countColor(img, simbob::plotColor(7), 0, img.width, 0, img.height) > 300);

  SECTION("naming more than 8 is an error") {
    PlotOptions opt;
    opt.bodies.assign(keys.begin(), keys.begin() + 9);
    CHECK_FALSE(simbob::plotTrajectory(constantTraj(keys, xs), nullptr, opt, dir.file("nine.png"), &err));
    CHECK(err.kind == ErrorKind::InvalidInput);
  }
}

TEST_CASE("plot: SVG output", "[plot]") {
  PlotTempDir dir;
  const std::string out = dir.file("wave.SVG");
  Error err;
  REQUIRE(simbob::plotTrajectory(waveTraj(), nullptr, PlotOptions(), out, &err));
  const std::string svg = readBytes(out);
  CHECK((svg.rfind("<?xml", 0) == 0 || svg.rfind("<svg", 0) == 0));
  CHECK(svg.find("<svg") != std::string::npos);
  CHECK(svg.find("</svg>") != std::string::npos);
  CHECK(svg.find("1200") != std::string::npos);
  // cairo numbers SVG surfaces per process; the output must not depend on that.
  REQUIRE(simbob::plotTrajectory(waveTraj(), nullptr, PlotOptions(), dir.file("again.svg"), &err));
  CHECK(svg == readBytes(dir.file("again.svg")));
}

TEST_CASE("plot: errors", "[plot]") {
  PlotTempDir dir;
  const Trajectory tr = constantTraj({"base", "arm"}, {1.0, 2.0});
  Error err;

  SECTION("unsupported extension") {
    const std::string out = dir.file("plot.jpg");
    CHECK_FALSE(simbob::plotTrajectory(tr, nullptr, PlotOptions(), out, &err));
    CHECK(err.kind == ErrorKind::InvalidInput);
    CHECK(err.message.find("unsupported plot format") != std::string::npos);
    CHECK(err.message.find("use .png or .svg") != std::string::npos);
    CHECK_FALSE(fs::exists(out));
    CHECK_FALSE(simbob::plotTrajectory(tr, nullptr, PlotOptions(), dir.file("noext"), &err));
    CHECK(err.kind == ErrorKind::InvalidInput);
  }
  SECTION("unwritable path") {
    const std::string out = dir.file("missing_dir/plot.png");
    CHECK_FALSE(simbob::plotTrajectory(tr, nullptr, PlotOptions(), out, &err));
    CHECK(err.kind == ErrorKind::CannotCreate);
    CHECK(err.str().find(out) != std::string::npos);
  }
  SECTION("unknown body with a suggestion") {
    PlotOptions opt;
    opt.bodies = {"arm", "bsae"};
    CHECK_FALSE(simbob::plotTrajectory(tr, nullptr, opt, dir.file("p.png"), &err));
    CHECK(err.kind == ErrorKind::InvalidInput);
    CHECK(err.message.find("no body 'bsae'") != std::string::npos);
    CHECK(err.message.find("did you mean 'base'") != std::string::npos);
    CHECK_FALSE(fs::exists(dir.file("p.png")));
  }
  SECTION("unknown body without a close match lists the bodies") {
    PlotOptions opt;
    opt.bodies = {"gripper"};
    CHECK_FALSE(simbob::plotTrajectory(tr, nullptr, opt, dir.file("p.png"), &err));
    CHECK(err.kind == ErrorKind::InvalidInput);
    CHECK(err.message.find("bodies: base, arm") != std::string::npos);
  }
  SECTION("empty trajectory") {
    CHECK_FALSE(simbob::plotTrajectory(Trajectory(), nullptr, PlotOptions(), dir.file("e.png"), &err));
    CHECK(err.kind == ErrorKind::InvalidInput);
  }
  SECTION("bad size") {
    PlotOptions opt;
    opt.width = 10;
    CHECK_FALSE(simbob::plotTrajectory(tr, nullptr, opt, dir.file("s.png"), &err));
    CHECK(err.kind == ErrorKind::InvalidInput);
    opt.width = 1200;
    opt.height = -5;
    CHECK_FALSE(simbob::plotTrajectory(tr, nullptr, opt, dir.file("s.png"), &err));
    CHECK(err.kind == ErrorKind::InvalidInput);
  }
  SECTION("too small for the legend and three panels") {
    std::vector<std::string> keys;
    for (int i = 0; i < 8; ++i) keys.push_back("a_rather_long_body_key_number_" + std::to_string(i));
    PlotOptions opt;
    opt.width = 200;
    opt.height = 300;
    CHECK_FALSE(simbob::plotTrajectory(constantTraj(keys, std::vector<double>(8, 0.0)), nullptr, opt,
                                       dir.file("small.png"), &err));
    CHECK(err.kind == ErrorKind::InvalidInput);
    CHECK(err.message.find("too small") != std::string::npos);
    CHECK_FALSE(fs::exists(dir.file("small.png")));
  }
  SECTION("a null err is allowed") {
    CHECK_FALSE(simbob::plotTrajectory(tr, nullptr, PlotOptions(), dir.file("x.gif"), nullptr));
  }
}

TEST_CASE("plot: same input gives the same PNG bytes", "[plot]") {
  PlotTempDir dir;
  const Trajectory actual = waveTraj();
  const Trajectory golden = constantTraj({"base"}, {0.5});
  Error err;
  REQUIRE(simbob::plotTrajectory(actual, &golden, PlotOptions(), dir.file("a.png"), &err));
  REQUIRE(simbob::plotTrajectory(actual, &golden, PlotOptions(), dir.file("b.png"), &err));
  const std::string a = readBytes(dir.file("a.png"));
  CHECK(a.size() > 1000);
  CHECK(a == readBytes(dir.file("b.png")));
}

TEST_CASE("plot: the rotation panel shows the turn from the first orientation", "[plot]") {
  PlotTempDir dir;
  const std::string out = dir.file("rotation.png");
  // A body that stays put and turns about y from 0 to 1 rad (q = cos(a/2), 0, sin(a/2), 0).
  const Trajectory tr = makeTraj({"wheel"}, 101, 1.0, [](size_t, double t, double* p) {
    p[3] = std::cos(t / 2);
    p[5] = std::sin(t / 2);
  });
  Error err;
  PlotOptions opt;
  opt.rotation = true;
  REQUIRE(simbob::plotTrajectory(tr, nullptr, opt, out, &err));
  const Image img = loadPng(out);
  CHECK(img.height == 1200);  // four panels of 300 px
  const PlotColor c = simbob::plotColor(0);
  // In the bottom panel the line rises from left to right; in the three above it is flat.
  auto topRow = [&](int x, int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      if (near(img.at(x, y), c)) return y;
    return -1;
  };
  const int left = topRow(img.width / 5, img.height * 3 / 4, img.height);
  const int right = topRow(img.width * 9 / 10, img.height * 3 / 4, img.height);
  REQUIRE(left > 0);
  REQUIRE(right > 0);
  CHECK(right < left - 50);
  const int x_left = topRow(img.width / 5, img.height / 10, img.height / 4);
  const int x_right = topRow(img.width * 9 / 10, img.height / 10, img.height / 4);
  REQUIRE(x_left > 0);
  CHECK(std::abs(x_right - x_left) <= 1);
  // Without the option the same trajectory has three panels and no rotation.
  opt.rotation = false;
  REQUIRE(simbob::plotTrajectory(tr, nullptr, opt, out, &err));
  CHECK(loadPng(out).height == 900);
}
