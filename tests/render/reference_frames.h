// What the render tests share: the back end under test and the comparison with the reference
// frames in golden/frames/ (the tolerance is explained in renderer_test.cpp's header).
#pragma once

#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>

#include "simbob/tool/image_compare.h"
#include "simbob/tool/png.h"
#include "simbob/renderer.h"

namespace simbob::test {

constexpr int kChannelTolerance = 24;
constexpr double kDifferingFraction = 0.005;

inline GlBackend backend() {
  GlBackend b = GlBackend::Auto;
  parseGlBackend(std::getenv("SIMBOB_GL") ? std::getenv("SIMBOB_GL") : "", &b);
  return b;
}

/// lib/image's rule with the tolerance above.
inline ImageComparison compared(const Image& a, const Image& b) {
  return compareImages(a, b, ImageTolerance{kChannelTolerance, kDifferingFraction});
}

inline bool imagesMatch(const Image& a, const Image& b) { return compared(a, b).matches; }

/// Compares with golden/frames/NAME.png, or writes it when SIMBOB_BLESS_FRAMES is set.
inline void checkReference(const Image& img, const std::string& name) {
  const std::string path = std::string(SIMBOB_SOURCE_DIR) + "/golden/frames/" + name + ".png";
  if (std::getenv("SIMBOB_BLESS_FRAMES")) {
    Error e = writePng(path, img);
    REQUIRE(e.message.empty());
    WARN("blessed " + path);
    return;
  }
  Image ref;
  Error err;
  INFO(path + " (re-bless with scripts/update-frames.sh)");
  err = readPng(path, ref);
  REQUIRE(err.message.empty());
  INFO(compared(img, ref).summary());
  CHECK(imagesMatch(img, ref));
}

}  // namespace simbob::test
