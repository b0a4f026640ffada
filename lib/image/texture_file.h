// Texture images: BMP (what the original read: uncompressed 24/32-bit and 8-bit palettes) and
// PNG (readPng), as the renderer and the replay page (lib/view) read them. No GL here.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "simbob/error.h"
#include "simbob/image.h"
#include "simbob/visuals.h"

namespace simbob {

/// Reads a .bmp or .png file (chosen by its first bytes) into an RGB image, rows top first.
/// Errors name the file: MissingInput if it cannot be opened, InvalidInput if it is not a
/// supported image.
bool readTextureFile(const std::string& path, Image* out, Error* err);
/// The file a skin's texture names, looked up as the renderer does: in `texture_folder` (the
/// global TextureFolder) first, then beside the scene; the name as written, then with .bmp,
/// then .png. "" when none exists, with *where = the folders searched ("A or B").
std::string findTextureFile(const SkinDef& s, const std::string& texture_folder, std::string* where);
/// The width and height of a .bmp or .png texture file from its header alone (what
/// readTextureFile would decode, were the rest sound). Errors as readTextureFile's.
bool readTextureSize(const std::string& path, int* width, int* height, Error* err);
/// Reads a BMP file (uncompressed 24 or 32 bits per pixel, or 8 bits with a palette). Only the
/// headers and the pixel rows they describe are read; a file larger than kMaxTextureFileBytes is
/// refused before that (InvalidInput).
bool readBmp(const std::string& path, Image* out, Error* err);

/// The largest texture file read: a 16384 x 16384 BMP at 32 bits per pixel with its headers
/// (PNG files, compressed, have the same cap).
constexpr uint64_t kMaxTextureFileBytes = (uint64_t{1} << 30) + (uint64_t{1} << 20);
/// The decoded texture images of one renderer together (RGB, 3 bytes a pixel, each file once):
/// one 16384 x 16384 texture (768 MiB) and room for smaller ones.
constexpr size_t kMaxTextureBytes = size_t{1} << 30;

/// The texture files of one renderer: each file is read and decoded once, however many skins
/// name it, and the decoded images together stay within a budget.
class TextureFiles {
 public:
  explicit TextureFiles(size_t max_bytes = kMaxTextureBytes) : max_bytes_(max_bytes) {}
  /// The slot of the file at `path` (slots count distinct files from 0). The first call for a
  /// file reads it into *image and sets *fresh; later calls (the same file, however spelled) only
  /// look it up. False with *err naming the file when it cannot be read, or when its image would
  /// take the total past the budget (InvalidInput: "texture memory").
  bool load(const std::string& path, size_t* slot, Image* image, bool* fresh, Error* err);
  /// Bytes of the decoded images so far.
  size_t bytes() const { return bytes_; }

 private:
  size_t max_bytes_;
  size_t bytes_ = 0;
  std::map<std::string, size_t> slots_;  ///< canonical path -> slot
};

}  // namespace simbob
