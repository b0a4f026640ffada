// Writing output files so that a failure never leaves a truncated file under the final name.
#pragma once

#include <cstddef>
#include <string>

#include "simbob/error.h"

namespace simbob {

/// Writes all of [data, data + size) to fd, retrying on EINTR and short writes.
/// Returns 0, or an errno value (ENOSPC when write() makes no progress).
int writeAll(int fd, const char* data, size_t size);

/// Writes bytes to "<path>.tmp.<pid>" and renames it to path. On failure the temporary file is
/// removed and *err (if given) says why: ErrorKind::CannotCreate when the file cannot be created
/// or renamed, ErrorKind::IoError when writing fails.
bool writeFileAtomically(const std::string& path, const std::string& bytes, Error* err);

}  // namespace simbob
