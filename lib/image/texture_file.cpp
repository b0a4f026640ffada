// BMP and PNG readers for textures.
#include "image/texture_file.h"

#include "simbob/tool/png.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <vector>

namespace simbob {

namespace {

constexpr int kMaxTextureSide = 16384;

bool bad(Error* err, const std::string& path, const std::string& why) {
  err->kind = ErrorKind::InvalidInput;
  err->loc = SourceLoc{path, 0};
  err->message = why;
  return false;
}

uint32_t le32(const std::vector<uint8_t>& b, size_t at) {
  return static_cast<uint32_t>(b[at]) | static_cast<uint32_t>(b[at + 1]) << 8 | static_cast<uint32_t>(b[at + 2]) << 16 |
         static_cast<uint32_t>(b[at + 3]) << 24;
}
uint16_t le16(const std::vector<uint8_t>& b, size_t at) { return static_cast<uint16_t>(b[at] | b[at + 1] << 8); }

bool cannotOpen(Error* err, const std::string& path) {
  err->kind = ErrorKind::MissingInput;
  err->loc = SourceLoc{path, 0};
  err->message = "cannot open the texture file";
  return false;
}

bool tooLarge(Error* err, const std::string& path, uint64_t size) {
  return bad(err, path,
             "texture file of " + std::to_string(size) + " bytes is larger than " +
                 std::to_string(kMaxTextureFileBytes) + " (a 16384 x 16384 BMP at 32 bits)");
}

// Up to `n` bytes from the start of `in` (fewer if the file is shorter).
void readUpTo(std::ifstream& in, uint64_t n, std::vector<uint8_t>* out) {
  in.clear();
  in.seekg(0);
  out->resize(static_cast<size_t>(n));
  in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(n));
  out->resize(static_cast<size_t>(in.gcount()));
}

bool readPngFile(const std::string& path, Image* out, Error* err) {
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxTextureFileBytes) return tooLarge(err, path, size);
  Error e = readPng(path, *out);
  if (!e.message.empty()) {
    *err = e;
    return false;
  }
  if (out->width > kMaxTextureSide || out->height > kMaxTextureSide)
    return bad(err, path, "texture larger than 16384 pixels per side");
  return true;
}

}  // namespace

bool readBmp(const std::string& path, Image* out, Error* err) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return cannotOpen(err, path);
  const auto end = in.tellg();
  if (end < 0) return cannotOpen(err, path);
  const auto size = static_cast<uint64_t>(end);
  if (size > kMaxTextureFileBytes) return tooLarge(err, path, size);
  // The headers first; then the pixel rows they describe, and nothing after them.
  std::vector<uint8_t> b;
  readUpTo(in, 54, &b);
  if (b.size() < 54 || b[0] != 'B' || b[1] != 'M') return bad(err, path, "not a BMP file");
  const uint32_t offset = le32(b, 10);
  const uint32_t header = le32(b, 14);
  if (header < 40) return bad(err, path, "BMP: unsupported header (OS/2 bitmaps are not read)");
  const auto w = static_cast<int32_t>(le32(b, 18));
  const auto h_signed = static_cast<int32_t>(le32(b, 22));
  const uint16_t bpp = le16(b, 28);
  const uint32_t compression = le32(b, 30);
  const bool top_down = h_signed < 0;
  const int64_t h = top_down ? -static_cast<int64_t>(h_signed) : h_signed;
  if (w <= 0 || h <= 0 || w > kMaxTextureSide || h > kMaxTextureSide)
    return bad(err, path, "BMP: size must be 1 to 16384 pixels per side");
  // BI_RGB, or BI_BITFIELDS with the usual 32-bit masks.
  if (compression != 0 && !(compression == 3 && bpp == 32))
    return bad(err, path, "BMP: compressed bitmaps are not read (save it uncompressed)");
  if (bpp != 24 && bpp != 32 && bpp != 8) return bad(err, path, "BMP: only 8, 24 and 32 bits per pixel are read");
  const size_t row = ((static_cast<size_t>(w) * bpp + 31) / 32) * 4;
  if (offset < 54 || offset > size || size - offset < row * static_cast<size_t>(h))
    return bad(err, path, "BMP: file is shorter than its pixels");
  readUpTo(in, offset + row * static_cast<uint64_t>(h), &b);
  if (b.size() - offset < row * static_cast<size_t>(h)) return bad(err, path, "BMP: file is shorter than its pixels");
  std::vector<std::array<uint8_t, 3>> palette;
  if (bpp == 8) {
    uint32_t colors = le32(b, 46);
    if (colors == 0) colors = 256;
    const size_t pal = 14 + static_cast<size_t>(header);
    if (colors > 256 || pal + static_cast<size_t>(colors) * 4 > offset) return bad(err, path, "BMP: bad palette");
    for (size_t i = 0; i < colors; ++i) palette.push_back({b[pal + i * 4 + 2], b[pal + i * 4 + 1], b[pal + i * 4]});
  }
  Image im(w, static_cast<int>(h));
  for (int64_t y = 0; y < h; ++y) {
    const uint8_t* src = b.data() + offset + row * static_cast<size_t>(top_down ? y : h - 1 - y);
    uint8_t* dst = im.pixel(0, static_cast<int>(y));
    for (int x = 0; x < w; ++x, dst += 3) {
      if (bpp == 8) {
        const uint8_t i = src[x];
        if (i >= palette.size()) return bad(err, path, "BMP: pixel outside the palette");
        std::memcpy(dst, palette[i].data(), 3);
      } else {
        const uint8_t* p = src + static_cast<size_t>(x) * (bpp / 8);
        dst[0] = p[2];
        dst[1] = p[1];
        dst[2] = p[0];
      }
    }
  }
  *out = std::move(im);
  return true;
}

bool readTextureFile(const std::string& path, Image* out, Error* err) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    err->kind = ErrorKind::MissingInput;
    err->loc = SourceLoc{path, 0};
    err->message = "cannot open the texture file";
    return false;
  }
  char magic[8] = {};
  in.read(magic, sizeof magic);
  if (magic[0] == 'B' && magic[1] == 'M') return readBmp(path, out, err);
  if (std::memcmp(magic, "\x89PNG", 4) == 0) return readPngFile(path, out, err);
  return bad(err, path, "texture is neither a BMP nor a PNG file");
}

std::string findTextureFile(const SkinDef& s, const std::string& texture_folder, std::string* where) {
  where->clear();
  for (const std::string& dir : {texture_folder, s.base_dir}) {
    if (dir.empty()) continue;
    *where += (where->empty() ? "" : " or ") + dir;
    for (const char* ext : {"", ".bmp", ".png"}) {
      std::string p = (s.texture[0] == '/' ? "" : dir + "/") + s.texture + ext;
      std::error_code ec;
      if (std::filesystem::is_regular_file(p, ec)) return p;
    }
  }
  return "";
}

bool readTextureSize(const std::string& path, int* width, int* height, Error* err) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return cannotOpen(err, path);
  std::vector<uint8_t> b;
  readUpTo(in, 26, &b);
  if (b.size() >= 26 && b[0] == 'B' && b[1] == 'M') {
    const auto w = static_cast<int32_t>(le32(b, 18));
    const auto h = static_cast<int32_t>(le32(b, 22));
    const int64_t ah = h < 0 ? -static_cast<int64_t>(h) : h;
    if (w <= 0 || ah <= 0 || w > kMaxTextureSide || ah > kMaxTextureSide)
      return bad(err, path, "BMP: size must be 1 to 16384 pixels per side");
    *width = w;
    *height = static_cast<int>(ah);
    return true;
  }
  // PNG: the signature, then IHDR's length and name, then width and height big-endian.
  if (b.size() >= 24 && std::memcmp(b.data(), "\x89PNG", 4) == 0) {
    auto be32 = [&](size_t at) {
      return static_cast<uint32_t>(b[at]) << 24 | static_cast<uint32_t>(b[at + 1]) << 16 |
             static_cast<uint32_t>(b[at + 2]) << 8 | b[at + 3];
    };
    const uint32_t w = be32(16), h = be32(20);
    if (w == 0 || h == 0 || w > kMaxTextureSide || h > kMaxTextureSide)
      return bad(err, path, "texture larger than 16384 pixels per side");
    *width = static_cast<int>(w);
    *height = static_cast<int>(h);
    return true;
  }
  return bad(err, path, "texture is neither a BMP nor a PNG file");
}

bool TextureFiles::load(const std::string& path, size_t* slot, Image* image, bool* fresh, Error* err) {
  std::error_code ec;
  std::string key = std::filesystem::weakly_canonical(path, ec).string();
  if (ec || key.empty()) key = path;
  if (auto it = slots_.find(key); it != slots_.end()) {
    *slot = it->second;
    *fresh = false;
    return true;
  }
  if (!readTextureFile(path, image, err)) return false;
  const size_t bytes = image->rgb.size();
  if (bytes > max_bytes_ - std::min(bytes_, max_bytes_)) {
    auto amount = [](size_t n) {
      return n >= (1u << 20) ? std::to_string(n >> 20) + " MiB" : std::to_string(n) + " bytes";
    };
    const std::string why = "texture memory: this " + std::to_string(image->width) + " x " +
                            std::to_string(image->height) + " texture (" + amount(bytes) +
                            " decoded) takes the scene's textures past " + amount(max_bytes_);
    *image = Image{};
    return bad(err, path, why);
  }
  bytes_ += bytes;
  *slot = slots_.size();
  slots_.emplace(key, *slot);
  *fresh = true;
  return true;
}

}  // namespace simbob
