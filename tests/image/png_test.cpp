// lib/image/png.cpp: PNG files written atomically and read back as 8-bit RGB from any colour type.
#include "simbob/tool/png.h"

#include <png.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "image_test_util.h"

namespace fs = std::filesystem;
using simbob::ErrorKind;
using simbob::Image;
using simbob::readPng;
using simbob::writePng;
using simbob_test::ImageTempDir;
using simbob_test::slurp;

namespace {

// Every byte value appears in every channel, and no two neighbouring pixels are alike.
Image patterned(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = img.pixel(x, y);
      p[0] = static_cast<uint8_t>(x * 7 + y);
      p[1] = static_cast<uint8_t>(y * 13 + x * 3);
      p[2] = static_cast<uint8_t>((x ^ y) * 5);
    }
  return img;
}

// Writes raw pixels of the given libpng format straight through libpng (not through simbob).
void writeRawPng(const std::string& path, int w, int h, png_uint_32 format, const void* pixels,
                 const void* colormap = nullptr, int colormap_entries = 0) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(w);
  image.height = static_cast<png_uint_32>(h);
  image.format = format;
  image.colormap_entries = static_cast<png_uint_32>(colormap_entries);
  REQUIRE(png_image_write_to_file(&image, path.c_str(), 0, pixels, 0, colormap) != 0);
}

}  // namespace

TEST_CASE("writePng/readPng round-trip every byte exactly", "[image][png]") {
  ImageTempDir dir;
  const Image img = patterned(67, 41);  // odd sizes: no row padding assumptions
  const std::string path = (dir.path / "a.png").string();
  const simbob::Error err = writePng(path, img);
  REQUIRE(err.message.empty());
  const std::string bytes = slurp(path);
  REQUIRE(bytes.size() > 8);
  CHECK(bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);

  Image back;
  REQUIRE(readPng(path, back).message.empty());
  CHECK(back.width == 67);
  CHECK(back.height == 41);
  CHECK(back.rgb == img.rgb);

  // Same image, same bytes; and nothing but a.png is left in the directory (no temporary file).
  const std::string again = (dir.path / "b.png").string();
  REQUIRE(writePng(again, img).message.empty());
  CHECK(slurp(again) == bytes);
  CHECK(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()) == 2);
}

TEST_CASE("readPng converts grey, palette, alpha and 16-bit PNGs to RGB8", "[image][png]") {
  ImageTempDir dir;
  Image out;

  SECTION("grey") {
    const uint8_t grey[] = {0, 77, 255, 128};
    const std::string p = (dir.path / "grey.png").string();
    writeRawPng(p, 2, 2, PNG_FORMAT_GRAY, grey);
    REQUIRE(readPng(p, out).message.empty());
    REQUIRE(out.width == 2);
    REQUIRE(out.height == 2);
    CHECK(out.rgb == std::vector<uint8_t>{0, 0, 0, 77, 77, 77, 255, 255, 255, 128, 128, 128});
  }
  SECTION("RGBA: opaque pixels keep their colour, transparent ones become black") {
    const uint8_t rgba[] = {10, 20, 30, 255, 200, 100, 50, 0};
    const std::string p = (dir.path / "rgba.png").string();
    writeRawPng(p, 2, 1, PNG_FORMAT_RGBA, rgba);
    REQUIRE(readPng(p, out).message.empty());
    CHECK(out.rgb == std::vector<uint8_t>{10, 20, 30, 0, 0, 0});
  }
  SECTION("palette") {
    const uint8_t colormap[] = {255, 0, 0, 0, 255, 0, 0, 0, 255};
    const uint8_t index[] = {2, 0, 1};
    const std::string p = (dir.path / "palette.png").string();
    writeRawPng(p, 3, 1, PNG_FORMAT_RGB_COLORMAP, index, colormap, 3);
    REQUIRE(readPng(p, out).message.empty());
    CHECK(out.rgb == std::vector<uint8_t>{0, 0, 255, 255, 0, 0, 0, 255, 0});
  }
  SECTION("16-bit linear: black and white stay black and white") {
    const uint16_t rgb16[] = {0, 65535, 0, 65535, 65535, 65535};
    const std::string p = (dir.path / "deep.png").string();
    writeRawPng(p, 2, 1, PNG_FORMAT_LINEAR_RGB, rgb16);
    REQUIRE(readPng(p, out).message.empty());
    CHECK(out.rgb == std::vector<uint8_t>{0, 255, 0, 255, 255, 255});
  }
}

TEST_CASE("readPng says why it cannot read a file", "[image][png]") {
  ImageTempDir dir;
  Image out(3, 3);

  const std::string missing = (dir.path / "missing.png").string();
  simbob::Error err = readPng(missing, out);
  CHECK(err.kind == ErrorKind::MissingInput);
  CHECK(err.str() == missing + ": No such file or directory");
  CHECK(out.width == 0);
  CHECK(out.rgb.empty());

  const std::string text = (dir.path / "text.png").string();
  std::ofstream(text) << "not a png at all";
  err = readPng(text, out);
  CHECK(err.kind == ErrorKind::InvalidInput);
  CHECK(err.str().rfind(text + ": not a readable PNG: ", 0) == 0);

  // A real PNG cut in half: the header reads, the pixels do not.
  const std::string whole = (dir.path / "whole.png").string();
  REQUIRE(writePng(whole, patterned(64, 64)).message.empty());
  const std::string bytes = slurp(whole);
  const std::string cut = (dir.path / "cut.png").string();
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  err = readPng(cut, out);
  CHECK(err.kind == ErrorKind::InvalidInput);
  CHECK(err.str().rfind(cut + ": broken PNG: ", 0) == 0);
  CHECK(out.rgb.empty());

  err = readPng(dir.path.string(), out);
  CHECK(err.kind == ErrorKind::MissingInput);
  CHECK(err.str() == dir.path.string() + ": Is a directory");
}

TEST_CASE("writePng never leaves a half file and never spoils an existing one", "[image][png]") {
  ImageTempDir dir;
  const std::string path = (dir.path / "keep.png").string();
  std::ofstream(path) << "previous";

  // A bad image is refused before anything is written.
  Image bad(4, 4);
  bad.rgb.resize(5);
  simbob::Error err = writePng(path, bad);
  CHECK(err.kind == ErrorKind::InvalidInput);
  CHECK(err.str() == path + ": cannot write PNG: image data has 5 bytes, 4x4 RGB needs 48");
  err = writePng(path, Image());
  CHECK(err.kind == ErrorKind::InvalidInput);
  CHECK(err.str() == path + ": cannot write PNG: empty image (0x0)");
  CHECK(slurp(path) == "previous");

  // A directory that does not exist: nothing can be created.
  const std::string nowhere = (dir.path / "no" / "such" / "dir.png").string();
  err = writePng(nowhere, patterned(2, 2));
  CHECK(err.kind == ErrorKind::CannotCreate);
  CHECK(err.str() == nowhere + ": cannot create: folder '" + (dir.path / "no" / "such").string() + "' does not exist");
  CHECK_FALSE(fs::exists(nowhere));

  // A good image replaces the old file whole.
  REQUIRE(writePng(path, patterned(2, 2)).message.empty());
  Image back;
  REQUIRE(readPng(path, back).message.empty());
  CHECK(back.rgb == patterned(2, 2).rgb);
  CHECK(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()) == 1);
}
