#include "simbob/png.h"

#include <png.h>

#include <cstring>
#include <limits>
#include <memory>

#include "simbob/files.h"

namespace simbob {

namespace {

Error makeError(ErrorKind kind, const std::string& file, std::string message) {
  Error e;
  e.kind = kind;
  e.loc.file = file;
  e.message = std::move(message);
  return e;
}

// Frees a png_image's reader/writer state on every path out.
struct ImageGuard {
  png_image* image;
  ~ImageGuard() { png_image_free(image); }
};

// libpng's simplified API stores its message in a fixed buffer; "libpng: " adds nothing.
std::string pngMessage(const png_image& image) {
  std::string m = image.message;
  return m.empty() ? "unknown libpng error" : m;
}

}  // namespace

bool encodePng(const Image& img, std::string* bytes, std::string* why) {
  bytes->clear();
  if (img.width <= 0 || img.height <= 0) {
    *why = "empty image (" + std::to_string(img.width) + "x" + std::to_string(img.height) + ")";
    return false;
  }
  // The PNG format limits each side to 2^31 - 1; the row stride (3 * width) must fit an int.
  if (img.width > std::numeric_limits<int>::max() / 3) {
    *why = "image too wide (" + std::to_string(img.width) + " pixels)";
    return false;
  }
  const size_t expect = static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 3;
  if (img.rgb.size() != expect) {
    *why = "image data has " + std::to_string(img.rgb.size()) + " bytes, " + std::to_string(img.width) + "x" +
           std::to_string(img.height) + " RGB needs " + std::to_string(expect);
    return false;
  }
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(img.width);
  image.height = static_cast<png_uint_32>(img.height);
  image.format = PNG_FORMAT_RGB;
  ImageGuard guard{&image};
  png_alloc_size_t size = 0;
  // First call measures, second writes.
  if (!png_image_write_to_memory(&image, nullptr, &size, 0, img.rgb.data(), 0, nullptr)) {
    *why = pngMessage(image);
    return false;
  }
  bytes->resize(size);
  if (!png_image_write_to_memory(&image, &(*bytes)[0], &size, 0, img.rgb.data(), 0, nullptr)) {
    bytes->clear();
    *why = pngMessage(image);
    return false;
  }
  bytes->resize(size);
  return true;
}

bool decodePng(const std::string& bytes, Image& out, std::string* why) {
  out = Image();
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  ImageGuard guard{&image};
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) {
    *why = "not a readable PNG: " + pngMessage(image);
    return false;
  }
  // Refuse sizes whose RGB buffer would not fit comfortably (a 16-byte header can claim 2^31 x 2^31).
  constexpr uint64_t kMaxPixels = uint64_t{1} << 28;
  if (static_cast<uint64_t>(image.width) * image.height > kMaxPixels || image.width > (1u << 30) ||
      image.height > (1u << 30)) {
    *why = "PNG too large (" + std::to_string(image.width) + "x" + std::to_string(image.height) + ")";
    return false;
  }
  image.format = PNG_FORMAT_RGB;
  Image result(static_cast<int>(image.width), static_cast<int>(image.height));
  const png_color black = {0, 0, 0};
  if (!png_image_finish_read(&image, &black, result.rgb.data(), 0, nullptr)) {
    *why = "broken PNG: " + pngMessage(image);
    return false;
  }
  out = std::move(result);
  return true;
}

Error writePng(const std::string& path, const Image& img) {
  std::string bytes, why;
  if (!encodePng(img, &bytes, &why)) return makeError(ErrorKind::InvalidInput, path, "cannot write PNG: " + why);
  Error err;
  if (!writeFileAtomically(path, bytes, &err)) return err;
  return Error();
}

Error readPng(const std::string& path, Image& out) {
  out = Image();
  std::string bytes, why;
  // A 2^28-pixel image compresses well, but no sane PNG input is over 1 GiB.
  if (!readFile(path, size_t{1} << 30, &bytes, &why, true)) return makeError(ErrorKind::MissingInput, path, why);
  if (!decodePng(bytes, out, &why)) return makeError(ErrorKind::InvalidInput, path, why);
  return Error();
}

}  // namespace simbob
