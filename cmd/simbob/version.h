// The version line of `simbob --version`.
#pragma once

#include <string>

namespace simbob::cli {

/// The git revision the binary was built from (`git describe --always --dirty` when CMake
/// configured the build), or "unknown" for a build outside a git checkout.
extern const char* const kGitRevision;

/// "simbob 0.1.0 (git 2f00dde)".
std::string versionLine();

}  // namespace simbob::cli
