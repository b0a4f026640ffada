// Texture files (lib/image/texture_file.cpp): a BMP costs what its header describes, not what
// the file holds; a file past the cap is refused unread; each file is decoded once per renderer
// and the decoded images together stay within a budget. The large files are sparse (a header,
// then a hole): nothing here writes or allocates gigabytes unless the reader does.
#include <sys/resource.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "image/texture_file.h"

using namespace simbob;
namespace fs = std::filesystem;

namespace {

// A 24-bit BMP of w x h grey pixels (value v), rows padded to 4 bytes; only its 54-byte header
// when `pixels_too` is false.
std::string bmpBytes(int32_t w, int32_t h, uint8_t v, bool pixels_too = true) {
  const uint32_t row = ((static_cast<uint32_t>(w) * 24 + 31) / 32) * 4;
  const uint32_t pixels = row * static_cast<uint32_t>(h);
  std::string b(54, '\0');
  auto put32 = [&](size_t at, uint32_t x) {
    for (int i = 0; i < 4; ++i) b[at + i] = static_cast<char>((x >> (8 * i)) & 0xFF);
  };
  b[0] = 'B';
  b[1] = 'M';
  put32(2, 54 + pixels);
  put32(10, 54);
  put32(14, 40);
  put32(18, static_cast<uint32_t>(w));
  put32(22, static_cast<uint32_t>(h));
  b[26] = 1;   // planes
  b[28] = 24;  // bits per pixel
  put32(34, pixels);
  return pixels_too ? b + std::string(pixels, static_cast<char>(v)) : b;
}

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("simbob-texture-test-" + std::to_string(::getpid()));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

// `bytes`, then a hole up to `size` bytes (sparse: no disk is spent on it).
std::string writeFile(const fs::path& p, const std::string& bytes, uintmax_t size = 0) {
  std::ofstream(p, std::ios::binary) << bytes;
  if (size > bytes.size()) fs::resize_file(p, size);
  return p.string();
}

// The peak resident set of this process so far, in MiB.
long peakMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024;
}

}  // namespace

TEST_CASE("texture files: a BMP is read as far as its header describes, and a file past the cap not at all") {
  TempDir dir;
  const long peak0 = peakMiB();

  SECTION("a 16 x 16 BMP padded to 1 GiB (within the cap) reads as 16 x 16, without reading the padding") {
    const std::string p = writeFile(dir.path / "padded.bmp", bmpBytes(16, 16, 77), uintmax_t{1} << 30);
    Image im;
    Error err;
    REQUIRE(readBmp(p, &im, &err));
    CHECK(im.width == 16);
    CHECK(im.height == 16);
    CHECK(im.rgb[0] == 77);
    CHECK(peakMiB() - peak0 < 64);
  }
  SECTION("a 16 x 16 BMP padded to 2 GiB is refused unread (65: what the file holds)") {
    const std::string p = writeFile(dir.path / "huge.bmp", bmpBytes(16, 16, 77), uintmax_t{2} << 30);
    Image im;
    Error err;
    REQUIRE_FALSE(readTextureFile(p, &im, &err));
    CHECK(err.kind == ErrorKind::InvalidInput);
    CHECK(err.loc.file == p);
    CHECK(err.message == "texture file of 2147483648 bytes is larger than 1074790400 (a 16384 x 16384 BMP at 32 bits)");
    CHECK(peakMiB() - peak0 < 64);
  }
  SECTION("a BMP declaring 16384 x 16384 in a truncated file is refused before its pixels are allocated") {
    const std::string head = bmpBytes(16384, 16384, 0, false);
    const std::string p = writeFile(dir.path / "truncated.bmp", head, 4096);
    Image im;
    Error err;
    REQUIRE_FALSE(readBmp(p, &im, &err));
    CHECK(err.kind == ErrorKind::InvalidInput);
    CHECK(err.message == "BMP: file is shorter than its pixels");
    CHECK(peakMiB() - peak0 < 64);
  }
}

TEST_CASE("texture files: each file is decoded once however it is spelled, within the memory budget") {
  TempDir dir;
  const std::string a = writeFile(dir.path / "a.bmp", bmpBytes(16, 16, 10));
  const std::string b = writeFile(dir.path / "b.bmp", bmpBytes(8, 8, 20));
  fs::create_directories(dir.path / "sub");
  const std::string a_again = (dir.path / "sub" / ".." / "." / "a.bmp").string();

  TextureFiles files(16 * 16 * 3 + 100);  // room for a, not for a and b
  size_t slot = 9;
  bool fresh = false;
  Image im;
  Error err;
  REQUIRE(files.load(a, &slot, &im, &fresh, &err));
  CHECK(fresh);
  CHECK(slot == 0);
  CHECK(im.width == 16);
  CHECK(files.bytes() == 16 * 16 * 3);
  // The file changes (or vanishes) after the first read: the second skin still gets the image
  // read once, so the file was not read again.
  fs::remove(a);
  for (const std::string& p : {a, a_again}) {
    Image again;
    REQUIRE(files.load(p, &slot, &again, &fresh, &err));
    CHECK_FALSE(fresh);
    CHECK(slot == 0);
    CHECK(again.rgb.empty());
  }
  CHECK(files.bytes() == 16 * 16 * 3);

  // b would take the total past the budget: refused, naming b.
  Image big;
  REQUIRE_FALSE(files.load(b, &slot, &big, &fresh, &err));
  CHECK(err.kind == ErrorKind::InvalidInput);
  CHECK(err.loc.file == b);
  CHECK(err.message ==
        "texture memory: this 8 x 8 texture (192 bytes decoded) takes the scene's textures past 868 bytes");
  CHECK(big.rgb.empty());
  CHECK(files.bytes() == 16 * 16 * 3);
}
