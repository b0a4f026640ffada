// What a build and the machine it runs on are, for run summaries, `simbob --version` and CI
// reports (docs/ci.md says which of these the trajectory bytes depend on).
#pragma once

#include <string>

namespace simbob {

/// The compiler simbob was built with: "gcc 12.2.0", "clang 14.0.6".
std::string compilerVersion();

/// The C library running now (it provides libm, whose results the bytes depend on): "glibc 2.36".
std::string libcVersion();

/// The CPU's "model name" from /proc/cpuinfo ("AMD EPYC 7763 64-Core Processor"), "unknown" if
/// none is given. The bytes do not depend on it; a report records it to show they did not.
std::string cpuModel();

}  // namespace simbob
