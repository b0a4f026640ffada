#include "simbob/tool/png.h"

#include <png.h>

#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>

#include "simbob/tool/files.h"

namespace simbob {

namespace {

constexpr size_t kPngMessageSize = 200;

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

// libpng's full writing API, for the one setting the simplified API lacks: zlib level 1. A
// 640x480 frame of bench/record_bench then takes 5.7 ms instead of 17 ms at libpng's default
// level (6), for a file half as large again (16.0 kB instead of 10.5 kB), which keeps writing
// a PNG sequence from being the bottleneck of a recording. libpng reports errors by longjmp:
// nothing between setjmp and the calls below has a destructor to skip.
void onPngError(png_structp png, png_const_charp message) {
  char* buf = static_cast<char*>(png_get_error_ptr(png));
  std::snprintf(buf, kPngMessageSize, "%s", message);
  png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}

void appendPngBytes(png_structp png, png_bytep data, png_size_t size) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), size);
}

void flushPngBytes(png_structp) {}

bool writePngBytes(const Image& img, std::string* bytes, std::string* why) {
  char message[kPngMessageSize] = "";
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, message, onPngError, onPngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    *why = "out of memory";
    return false;
  }
  // Room for the raw pixels: the appends below then never reallocate inside libpng's frames.
  bytes->reserve(img.rgb.size() + img.rgb.size() / 8 + 1024);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    bytes->clear();
    *why = message[0] ? message : "unknown libpng error";
    return false;
  }
  png_set_write_fn(png, bytes, appendPngBytes, flushPngBytes);
  png_set_IHDR(png, info, static_cast<png_uint_32>(img.width), static_cast<png_uint_32>(img.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 1);
  png_write_info(png, info);
  const size_t stride = static_cast<size_t>(img.width) * 3;
  for (int y = 0; y < img.height; ++y) png_write_row(png, img.rgb.data() + stride * static_cast<size_t>(y));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
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
  return writePngBytes(img, bytes, why);
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
  if (!encodePng(img, &bytes, &why)) return fileError(ErrorKind::InvalidInput, path, "cannot write PNG: " + why);
  Error err;
  if (!writeFileAtomically(path, bytes, &err)) return err;
  return Error();
}

Error readPng(const std::string& path, Image& out) {
  out = Image();
  std::string bytes, why;
  // A 2^28-pixel image compresses well, but no sane PNG input is over 1 GiB.
  if (!readFile(path, size_t{1} << 30, &bytes, &why, true)) return fileError(ErrorKind::MissingInput, path, why);
  if (!decodePng(bytes, out, &why)) return fileError(ErrorKind::InvalidInput, path, why);
  return Error();
}

}  // namespace simbob
