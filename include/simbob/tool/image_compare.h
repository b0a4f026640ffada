// Comparing a rendered image with a reference image (issue #12: tests against golden/frames/).
//
// The tolerance rule. A pixel DIFFERS when any of its three channels differs from the
// reference by more than `channel_tolerance` (default 8 of 255). An image MATCHES when both
// have the same size and at most `max_fraction` of its pixels differ (default 0.5%).
//
// Why these numbers: a software rasteriser (Mesa's llvmpipe) or another GPU may round a shade
// by a step or two and move an antialiased or rasterised edge by one pixel. A one-step shade
// change is far below 8, and a one-pixel shift of every edge of a small scene touches well
// under 0.5% of a 160x120 image. A wrong colour (a channel off by more than 8 over a whole
// object), a missing object (every pixel it covered differs) or a wrong camera pose (the whole
// scene moves) changes many more pixels than that. The limit of the rule: an object covering
// fewer than max_fraction of the pixels (under 96 pixels of a 160x120 frame, i.e. smaller than
// about 10x10) can go missing unnoticed, so reference scenes must draw what they check large
// enough, or the test lowers max_fraction.
#pragma once

#include <cstdint>
#include <string>

#include "simbob/image.h"

namespace simbob {

struct ImageTolerance {
  int channel_tolerance = 8;    ///< 0..255: a channel difference above this makes a pixel differ
  double max_fraction = 0.005;  ///< 0..1: share of differing pixels an image may have and match
};

struct ImageComparison {
  bool same_size = false;     ///< false: nothing else was compared, every pixel counts as differing
  int width = 0, height = 0;  ///< the actual image's size
  int reference_width = 0, reference_height = 0;
  uint64_t pixels = 0;     ///< pixels compared (those of the reference)
  uint64_t differing = 0;  ///< pixels with a channel difference above the tolerance
  int max_difference = 0;  ///< largest channel difference over all pixels (0..255)
  int first_x = -1;        ///< the first differing pixel in reading order, or -1
  int first_y = -1;
  bool matches = false;  ///< the rule above
  /// Same size as the reference: the reference darkened to a quarter of its grey level where
  /// pixels are within the tolerance, pure red (255, 0, 0) where they differ. Empty when the
  /// sizes differ.
  Image diff;

  /// One line for a test failure: "12 of 19200 pixels (0.06%) differ by more than 8, max
  /// difference 255, first at (10, 4)", or "size 160x120, the reference is 320x240".
  std::string summary() const;
};

/// Compares actual with reference under the rule above.
ImageComparison compareImages(const Image& actual, const Image& reference, const ImageTolerance& tolerance = {});

}  // namespace simbob
