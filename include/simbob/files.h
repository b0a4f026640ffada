// Reading input files whole, with a size cap; writing output files so that a failure never
// leaves a truncated file under the final name.
#pragma once

#include <cstddef>
#include <string>

#include "simbob/error.h"

namespace simbob {

/// Cap for scene, import and settings files: they are read whole, and /dev/zero or a runaway
/// generator must not eat the memory.
constexpr size_t kMaxSceneFileBytes = size_t{64} << 20;
/// Cap for trajectory CSVs, which legitimately run to hundreds of MiB (5000 bodies sampled
/// 1000 times is about 550 MiB).
constexpr size_t kMaxTrajectoryFileBytes = size_t{4} << 30;

/// Reads the whole file at path into *out (replacing its content). On failure returns false,
/// leaves *out empty and sets *reason (if given) to the system's words ("No such file or
/// directory", "Is a directory") or "larger than N MiB" when the file exceeds max_bytes.
bool readFile(const std::string& path, size_t max_bytes, std::string* out, std::string* reason);

/// Writes all of [data, data + size) to fd, retrying on EINTR and short writes.
/// Returns 0, or an errno value (ENOSPC when write() makes no progress).
int writeAll(int fd, const char* data, size_t size);

/// Writes bytes to "<path>.tmp.<pid>" and renames it to path. On failure the temporary file is
/// removed and *err (if given) says why: ErrorKind::CannotCreate when the file cannot be created
/// or renamed, ErrorKind::IoError when writing fails.
bool writeFileAtomically(const std::string& path, const std::string& bytes, Error* err);

}  // namespace simbob
