// Interim PNG output of the render layer (libpng): one still for `simbob render` and the
// DIR/frame_000000.png sequence of --record. lib/image (the video branch) brings the shared
// writers; this file goes when it lands.
#include <png.h>

#include <cstdio>
#include <cstring>

#include "simbob/render.h"

namespace simbob {

Error writeImagePng(const std::string& path, const Image& img) {
  const std::string tmp = path + ".tmp";
  png_image p;
  std::memset(&p, 0, sizeof p);
  p.version = PNG_IMAGE_VERSION;
  p.width = static_cast<png_uint_32>(img.width);
  p.height = static_cast<png_uint_32>(img.height);
  p.format = PNG_FORMAT_RGB;
  if (!png_image_write_to_file(&p, tmp.c_str(), 0, img.rgb.data(), img.width * 3, nullptr)) {
    std::remove(tmp.c_str());
    return Error{ErrorKind::CannotCreate, {path, 0}, std::string("cannot write the PNG: ") + p.message};
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    return Error{ErrorKind::CannotCreate, {path, 0}, "cannot rename the PNG into place"};
  }
  return Error{ErrorKind::InvalidInput, {}, ""};
}

namespace {

class PngSequence : public FrameSink {
 public:
  explicit PngSequence(std::string dir) : dir_(std::move(dir)) {}
  const Error* add(Image&& frame) override {
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%06llu.png", static_cast<unsigned long long>(n_));
    error_ = writeImagePng(dir_ + name, frame);
    ++n_;
    return error_.message.empty() ? nullptr : &error_;
  }
  const Error* finish() override { return nullptr; }

 private:
  std::string dir_;
  uint64_t n_ = 0;
  Error error_;
};

}  // namespace

std::unique_ptr<FrameSink> pngSequenceSink(const std::string& dir) { return std::make_unique<PngSequence>(dir); }

}  // namespace simbob
