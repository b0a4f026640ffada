// PNG files for rendered frames and reference images (issue #12). libpng's simplified API
// behind two calls; nothing here includes libpng, GL or ODE headers.
#pragma once

#include <string>

#include "simbob/error.h"
#include "simbob/image.h"

namespace simbob {

/// Writes img as an 8-bit RGB PNG at path. The bytes go to a temporary file beside path that is
/// renamed over it only when complete (OutputFile), so a failure never leaves a half file under
/// the final name. The same image always gives the same bytes. Returns an Error whose message
/// is empty on success; otherwise kind CannotCreate (path cannot be created) or IoError (writing
/// failed) or InvalidInput (an empty image, or rgb.size() != width * height * 3), with
/// loc.file = path.
Error writePng(const std::string& path, const Image& img);

/// Reads the PNG at path into out, converting any colour type and bit depth (grey, palette,
/// 16-bit, with alpha) to 8-bit RGB; alpha is composited onto black; a gAMA chunk is honoured
/// (pixels come out as sRGB). Returns an Error whose message is empty on success; otherwise
/// kind MissingInput (cannot be read) or InvalidInput (not a PNG, or a broken one), with
/// loc.file = path. out is left empty on failure.
Error readPng(const std::string& path, Image& out);

/// Encodes img as PNG bytes in memory (what writePng writes). False and *why on failure.
bool encodePng(const Image& img, std::string* bytes, std::string* why);

/// Decodes PNG bytes (as readPng). False and *why on failure; out is then empty.
bool decodePng(const std::string& bytes, Image& out, std::string* why);

}  // namespace simbob
