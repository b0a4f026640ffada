#include "simbob/tool/image_compare.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace simbob {

ImageComparison compareImages(const Image& actual, const Image& reference, const ImageTolerance& tolerance) {
  ImageComparison r;
  r.width = actual.width;
  r.height = actual.height;
  r.reference_width = reference.width;
  r.reference_height = reference.height;
  r.pixels = static_cast<uint64_t>(std::max(reference.width, 0)) * static_cast<uint64_t>(std::max(reference.height, 0));
  const size_t bytes = static_cast<size_t>(r.pixels) * 3;
  r.same_size = actual.width == reference.width && actual.height == reference.height && actual.rgb.size() == bytes &&
                reference.rgb.size() == bytes;
  if (!r.same_size) {
    r.differing = r.pixels;
    r.max_difference = 255;
    r.matches = false;
    return r;
  }
  r.diff = Image(reference.width, reference.height);
  const int tol = std::clamp(tolerance.channel_tolerance, 0, 255);
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) {
      const uint8_t* a = actual.pixel(x, y);
      const uint8_t* b = reference.pixel(x, y);
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int{a[c]} - int{b[c]}));
      r.max_difference = std::max(r.max_difference, d);
      uint8_t* out = r.diff.pixel(x, y);
      if (d > tol) {
        if (r.differing == 0) {
          r.first_x = x;
          r.first_y = y;
        }
        ++r.differing;
        out[0] = 255;
        out[1] = 0;
        out[2] = 0;
      } else {
        // Integer luma (BT.601 weights summing to 256), darkened to a quarter.
        const int grey = (77 * b[0] + 150 * b[1] + 29 * b[2]) >> 10;
        out[0] = out[1] = out[2] = static_cast<uint8_t>(grey);
      }
    }
  // The fraction is compared exactly in integers: differing / pixels <= max_fraction.
  const double allowed = std::clamp(tolerance.max_fraction, 0.0, 1.0) * static_cast<double>(r.pixels);
  r.matches = static_cast<double>(r.differing) <= allowed;
  return r;
}

std::string ImageComparison::summary() const {
  char buf[200];
  if (!same_size) {
    std::snprintf(buf, sizeof buf, "size %dx%d, the reference is %dx%d", width, height, reference_width,
                  reference_height);
    return buf;
  }
  const double pct = pixels ? 100.0 * static_cast<double>(differing) / static_cast<double>(pixels) : 0.0;
  std::snprintf(buf, sizeof buf, "%llu of %llu pixels (%.2f%%) differ, max channel difference %d",
                static_cast<unsigned long long>(differing), static_cast<unsigned long long>(pixels), pct,
                max_difference);
  std::string s = buf;
  if (first_x >= 0) s += ", first at (" + std::to_string(first_x) + ", " + std::to_string(first_y) + ")";
  return s;
}

}  // namespace simbob
