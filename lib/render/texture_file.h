// Texture images: BMP (what the original read: uncompressed 24/32-bit and 8-bit palettes) and
// PNG (lib/image's readPng).
#pragma once

#include <string>

#include "simbob/error.h"
#include "simbob/image.h"

namespace simbob::render {

/// Reads a .bmp or .png file (chosen by its first bytes) into an RGB image, rows top first.
/// Errors name the file: MissingInput if it cannot be opened, InvalidInput if it is not a
/// supported image.
bool readTextureFile(const std::string& path, Image* out, Error* err);
/// Reads a BMP file (uncompressed 24 or 32 bits per pixel, or 8 bits with a palette).
bool readBmp(const std::string& path, Image* out, Error* err);

}  // namespace simbob::render
