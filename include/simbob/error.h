// Errors as values with a place. Nothing in lib/ exits or aborts; the CLI maps
// an ErrorKind to an exit status (sysexits.h).
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace simbob {

/// A file name kept once per process: copying one copies a pointer, so the thousands of
/// places a scene records (every component, parameter and link) share one string per file.
/// Reads as a `const std::string&`. Names stay until the process ends (one per file read).
class FileName {
 public:
  FileName() = default;  ///< ""
  FileName(const std::string& name) : s_(intern(name)) {}
  FileName(const char* name) : s_(intern(name)) {}

  const std::string& str() const { return s_ ? *s_ : emptyName(); }
  operator const std::string&() const { return str(); }
  bool empty() const { return !s_; }
  size_t size() const { return s_ ? s_->size() : 0; }
  const char* c_str() const { return s_ ? s_->c_str() : ""; }

  friend bool operator==(const FileName& a, const FileName& b) { return a.s_ == b.s_; }
  friend bool operator!=(const FileName& a, const FileName& b) { return a.s_ != b.s_; }
  friend bool operator==(const FileName& a, const std::string& b) { return a.str() == b; }
  friend bool operator==(const std::string& a, const FileName& b) { return a == b.str(); }
  friend bool operator==(const FileName& a, const char* b) { return a.str() == b; }
  friend bool operator!=(const FileName& a, const std::string& b) { return a.str() != b; }
  friend bool operator!=(const FileName& a, const char* b) { return a.str() != b; }
  friend std::string operator+(const FileName& a, const std::string& b) { return a.str() + b; }
  friend std::string operator+(const FileName& a, const char* b) { return a.str() + b; }
  friend std::string operator+(const FileName& a, char b) { return a.str() + b; }
  friend std::string operator+(const std::string& a, const FileName& b) { return a + b.str(); }
  friend std::string operator+(std::string&& a, const FileName& b) { return std::move(a) + b.str(); }
  friend std::string operator+(const char* a, const FileName& b) { return a + b.str(); }

 private:
  static const std::string* intern(const std::string& name);  ///< nullptr for ""
  static const std::string& emptyName();
  // The interned name; nullptr for "" (the default), so that the location in every slot of a
  // large scene is made and copied without a call into the pool.
  const std::string* s_ = nullptr;
};

/// Where something came from: a file and a 1-based line (0 = unknown line).
struct SourceLoc {
  FileName file;
  int line = 0;
};

/// What went wrong, coarse enough for the CLI to choose an exit status.
enum class ErrorKind {
  InvalidInput,  ///< the scene or a data file is wrong (EX_DATAERR 65)
  MissingInput,  ///< an input file does not exist or cannot be read (EX_NOINPUT 66)
  CannotCreate,  ///< an output file cannot be created (EX_CANTCREAT 73)
  IoError,       ///< writing an output failed (EX_IOERR 74)
  Diverged,      ///< the simulation produced a non-finite or runaway state, or a joint came apart (exit 1)
  Interrupted,   ///< the run was asked to stop (SIGINT/SIGTERM; exit 130/143)
  ControllerFailed,  ///< a controller, plug-in or controller program failed: reported an error, misused the API, threw (exit 2)
  Internal,          ///< a bug in simbob (EX_SOFTWARE 70)
  Unavailable,  ///< a party held the simulation past MaxAccessTime, or a socket peer never connected, went away or fell silent (EX_UNAVAILABLE 69)
  Protocol,     ///< a socket peer sent a line the protocol does not allow (EX_PROTOCOL 76)
  Usage,        ///< a caller passed an option or argument that cannot be used (EX_USAGE 64)
};

struct Error {
  ErrorKind kind = ErrorKind::InvalidInput;
  SourceLoc loc;
  std::string message;

  /// One line: "file:line: message" (or "file: message" when the line is unknown).
  std::string str() const;
  /// The line simbob prints for it: "file:line: error: message" ("simbob: error: message" when
  /// it has no file), so that editors and CI logs can jump to the place.
  std::string errorLine() const;
};

/// An error about a whole file (no line): what outputs and image files report.
inline Error fileError(ErrorKind kind, const std::string& file, std::string message) {
  return {kind, {file, 0}, std::move(message)};
}

/// Input text as it may appear inside a message: control characters and invalid UTF-8 as \xNN,
/// invisible characters (a byte order mark, zero-width spaces, direction marks) as \u{FEFF}, and
/// anything beyond max_bytes cut, saying how long it was: "abc... (52428800 bytes)".
std::string quoteInput(std::string_view text, size_t max_bytes = 80);

/// A file a command reads or writes, and what it is ("the scene", "--out"), for messages.
struct NamedPath {
  std::string what;
  std::string path;
};

/// Collects errors and warnings so one pass can report every problem.
class Diagnostics {
 public:
  void error(SourceLoc loc, std::string message, ErrorKind kind = ErrorKind::InvalidInput) {
    errors_.push_back({kind, loc, std::move(message)});
  }
  void warning(SourceLoc loc, std::string message) {
    warnings_.push_back({ErrorKind::InvalidInput, loc, std::move(message)});
  }
  bool ok() const { return errors_.empty(); }
  const std::vector<Error>& errors() const { return errors_; }
  const std::vector<Error>& warnings() const { return warnings_; }
  void clear() {
    errors_.clear();
    warnings_.clear();
  }

 private:
  std::vector<Error> errors_;
  std::vector<Error> warnings_;
};

}  // namespace simbob
