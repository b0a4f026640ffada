// urdfdom's parser, built as a module of its own (libsimbob_urdf.so, urdfdom_parse.cpp) and
// opened by read.cpp on the first URDF file: a run without URDF robots does not load urdfdom,
// tinyxml and console_bridge. Only urdf::parseURDF and console_bridge are in those libraries;
// urdfdom's model types are headers, which read.cpp uses on what the module returns. The module
// needs nothing from the program that opens it; the Python module links urdfdom_parse.cpp in.
#pragma once

#include <urdf_model/model.h>
#include <urdf_world/types.h>

#include <string>

namespace simbob {

/// What simbob_urdf_module() returns; `abi` is kUrdfModuleAbi of the module's build.
struct UrdfModule {
  int abi;
  /// urdfdom's model of `text`, or null with *message saying why (urdfdom's first error).
  urdf::ModelInterfaceSharedPtr (*parse)(const std::string& text, std::string* message);
};
constexpr int kUrdfModuleAbi = 1;

}  // namespace simbob

extern "C" const simbob::UrdfModule* simbob_urdf_module();
