// Helpers shared by the tests of lib/image.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

namespace simbob_test {

/// A fresh directory under the system's temporary directory, removed with everything in it.
struct ImageTempDir {
  std::filesystem::path path;
  ImageTempDir() {
    std::random_device rd;
    path = std::filesystem::temp_directory_path() /
           ("simbob_image_test_" + std::to_string(::getpid()) + "_" + std::to_string(rd()));
    std::filesystem::create_directories(path);
  }
  ~ImageTempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  ImageTempDir(const ImageTempDir&) = delete;
  ImageTempDir& operator=(const ImageTempDir&) = delete;
};

/// The whole file, or "" when it cannot be read.
inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace simbob_test

#include <cstdint>

#include "simbob/image.h"

namespace simbob_test {

/// Frame n of a synthetic recording: a dark grey floor, a red 16x16 square moving right by 4
/// pixels a frame and a blue 12x12 one moving down by 2, over a smooth green gradient.
inline simbob::Image movingSquares(int w, int h, int n) {
  simbob::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = img.pixel(x, y);
      p[0] = 40;
      p[1] = static_cast<uint8_t>(40 + (80 * x) / (w > 1 ? w - 1 : 1));
      p[2] = 40;
    }
  auto square = [&](int x0, int y0, int size, uint8_t r, uint8_t g, uint8_t b) {
    for (int y = y0; y < y0 + size; ++y)
      for (int x = x0; x < x0 + size; ++x)
        if (x >= 0 && y >= 0 && x < w && y < h) {
          uint8_t* p = img.pixel(x, y);
          p[0] = r;
          p[1] = g;
          p[2] = b;
        }
  };
  square((8 + 4 * n) % w, h / 4, 16, 230, 30, 30);
  square(w / 2, (4 + 2 * n) % h, 12, 30, 30, 230);
  return img;
}

}  // namespace simbob_test
