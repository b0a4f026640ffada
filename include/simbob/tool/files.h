// Reading input files whole, with a size cap; writing output files so that a failure never
// leaves a truncated file under the final name, and so that an output never replaces what it
// should not (a device node, a symlink, an input).
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

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
/// With `regular_only` (scenes, imports, settings), anything but a regular file is refused
/// ("not a regular file") without blocking: a FIFO with no writer or /dev/zero never ends.
/// *too_large (if given) tells a file over max_bytes from one that cannot be read.
bool readFile(const std::string& path, size_t max_bytes, std::string* out, std::string* reason,
              bool regular_only = false, bool* too_large = nullptr);

/// Writes all of [data, data + size) to fd, retrying on EINTR and short writes.
/// Returns 0, or an errno value (ENOSPC when write() makes no progress).
int writeAll(int fd, const char* data, size_t size);

/// One output of a command. A regular file (or a name not yet taken) is replaced atomically:
/// the bytes go to "<target>.tmp.<pid>" beside it and are renamed over it on commit. A symlink's
/// target is replaced, never the link. Anything else that is not a directory (a character
/// device such as /dev/null, a FIFO, a socket, /dev/stdout) is a stream: written through as the
/// bytes come, never replaced; "-" is standard output.
class OutputFile {
 public:
  /// Resolves `path` and creates the temporary file (or opens the stream) now, so that an
  /// output that cannot be created fails before any work is done: ErrorKind::CannotCreate
  /// (also when path names a directory or is empty). Returns nullptr and sets *err on failure.
  static std::unique_ptr<OutputFile> open(const std::string& path, Error* err);

  /// Abandons the output unless it was committed.
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// Appends bytes (to the temporary file, or through to the stream). Returns false once a
  /// write has failed; the error is reported by close()/commitOutputs().
  bool write(const char* data, size_t size);
  bool write(const std::string& bytes) { return write(bytes.data(), bytes.size()); }

  /// Closes the file (not yet renamed). False and *err (ErrorKind::IoError, "PATH: write
  /// failed: ...") if a write failed; the temporary file is then removed.
  bool close(Error* err);

  /// Renames the closed temporary file to `to` (its target when empty). A stream has nothing
  /// to rename. ErrorKind::CannotCreate on failure (the temporary file is then removed).
  bool rename(const std::string& to, Error* err);

  /// Closes and removes the temporary file; no-op once committed or abandoned.
  void abandon();

  bool isStream() const { return stream_; }
  bool ok() const { return errno_ == 0; }
  /// As given on the command line (for messages).
  const std::string& path() const { return path_; }
  /// The file replaced on commit (a symlink resolved), or the stream.
  const std::string& target() const { return target_; }
  /// "" for a stream.
  const std::string& tempPath() const { return temp_; }
  /// Bytes written so far.
  uint64_t size() const { return size_; }

 private:
  OutputFile() = default;
  friend bool commitOutputs(const std::vector<OutputFile*>& files, Error* err);

  std::string path_, target_, temp_;
  int fd_ = -1;
  bool stream_ = false;
  bool closed_ = false;
  bool done_ = false;  ///< renamed or abandoned
  int errno_ = 0;
  uint64_t size_ = 0;
};

/// Commits the outputs of one run together: closes each, then renames each temporary file over
/// its target. If any step fails, no target is left changed: targets already replaced get their
/// previous contents back (or are removed if they did not exist). All new, or all old.
bool commitOutputs(const std::vector<OutputFile*>& files, Error* err);

/// Writes bytes to `path` as an OutputFile and commits it. On failure *err (if given) says why:
/// ErrorKind::CannotCreate when the file cannot be created or renamed, ErrorKind::IoError when
/// writing fails.
bool writeFileAtomically(const std::string& path, const std::string& bytes, Error* err);

/// Whether two paths name the same existing file, by any spelling (relative, "..", symlink,
/// hard link): compares device and inode. A path that does not exist names no file.
bool sameExistingFile(const std::string& a, const std::string& b);

/// Whether two output paths would end up as the same file: the same existing file, or the same
/// place once symlinks in the existing part of the path are resolved.
bool sameOutputPlace(const std::string& a, const std::string& b);

/// Whether `path` is written through rather than replaced (see OutputFile): "-", or an existing
/// character device, FIFO or socket (after symlinks).
bool isStreamOutput(const std::string& path);

/// An output that would replace an input (by any spelling) or another output, as a usage error
/// naming both ("--out 'a.csv' is the scene 'a.csv': an output must not overwrite an input");
/// an empty Error (no message) when none does. Empty paths and streams never collide.
Error outputCollision(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs);

/// Why output `path` could not be created from errno `e`, naming only `path`'s own folder, never
/// the temporary name it is written under: "cannot create: folder 'out/run1' does not exist".
std::string cannotCreateReason(const std::string& path, int e);

}  // namespace simbob
