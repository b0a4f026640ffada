// The version lines of `simbob --version`.
#pragma once

#include <string>

namespace simbob::cli {

/// The git revision the binary was built from (`git describe --always --dirty` when CMake
/// configured the build), or "unknown" for a build outside a git checkout.
extern const char* const kGitRevision;

/// "simbob 0.1.0 (git 2f00dde)".
std::string versionLine();

/// `simbob --version` and the head of `simbob info` (ci_report.cpp): the version line, then ODE's
/// version and configuration, the compiler and the C library -- what the trajectory bytes depend
/// on (docs/ci.md). Lines end in '\n'.
std::string versionText();

}  // namespace simbob::cli
