// DocumentIni (guide 3.3.1): with the global setting on, camera settings in an INI file with the
// scene's name beside the scene ("robot.xml" -> "robot.ini") override the scene file's. The
// file's entries are overrides like `--set`, placed at the INI's file and line and limited to
// camera components: `[Side]` then `ViewAngle = 40` sets Side.ViewAngle.
#pragma once

#include <string>
#include <vector>

#include "simbob/error.h"
#include "simbob/overrides.h"

namespace simbob {

/// The INI beside the scene: its path with the extension replaced by ".ini" (added when there is
/// none). Empty when that is the scene itself (an INI scene has no DocumentIni).
std::string documentIniPath(const std::string& scene_path);

/// Reads the DocumentIni at path as camera-only overrides, in file order. A missing file is no
/// error (nothing is added); an unreadable or malformed one is, at its file and line.
bool readDocumentIni(const std::string& path, std::vector<Override>* out, Diagnostics& diag);

}  // namespace simbob
