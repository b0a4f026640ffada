// Where the files a URDF names are: relative to the URDF, or package://NAME/... (docs/urdf.md).
#pragma once

#include <string>

#include "urdf/urdf.h"

namespace simbob {

/// The path of file `name` written in `urdf_file`: absolute as written, file:// stripped,
/// relative to the URDF's folder, or package://NAME/rest from the first of: a package.xml whose
/// <name> is NAME in the URDF's folder or above, a package in ROS_PACKAGE_PATH, `packages`.
/// False with `problem` set when a package is not found (the file itself is not checked).
bool resolveUrdfPath(const std::string& name, const std::string& urdf_file, const UrdfPackages& packages,
                     std::string* path, std::string* problem);

}  // namespace simbob
