// Images and where rendered frames go (issue #12, Record). Plain data between the renderer
// (lib/render, the only GL code) and the writers (lib/image: PNG files, PNG sequences, video
// through FFmpeg's libraries). Nothing here includes GL, ODE or FFmpeg headers.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "simbob/error.h"

namespace simbob {

/// An 8-bit RGB image, rows top to bottom, 3 bytes per pixel, no row padding.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  ///< width * height * 3 bytes

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<size_t>(w) * static_cast<size_t>(h) * 3, 0) {}
  uint8_t* pixel(int x, int y) { return rgb.data() + (static_cast<size_t>(y) * width + x) * 3; }
  const uint8_t* pixel(int x, int y) const { return rgb.data() + (static_cast<size_t>(y) * width + x) * 3; }
};

/// Where a recording's frames go, in order: frame n shows simulated time n / fps.
/// add() may hand the frame to another thread; errors surface from a later add() or finish().
class FrameSink {
 public:
  virtual ~FrameSink() = default;
  /// Takes the next frame. A returned error (kind IoError / CannotCreate) stops the recording.
  virtual const Error* add(Image&& frame) = 0;
  /// Flushes and closes: after it returns without error, every output is complete under its
  /// final name. Null on success.
  virtual const Error* finish() = 0;
};

}  // namespace simbob
