// PngSequenceSink: DIR/frame_000000.png, ... through a staging directory (see frame_sinks.h).
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "simbob/tool/frame_sinks.h"
#include "simbob/tool/png.h"

namespace simbob {

namespace {

namespace fs = std::filesystem;

std::string frameName(uint64_t n) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%06llu.png", static_cast<unsigned long long>(n));
  return buf;
}

// The frame number of "frame_NNNNNN.png" (six or more digits), or -1.
long long frameNumber(const std::string& name) {
  const std::string prefix = "frame_", suffix = ".png";
  if (name.size() < prefix.size() + 6 + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return -1;
  const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.size() > 18) return -1;
  long long n = 0;
  for (char c : digits) {
    if (c < '0' || c > '9') return -1;
    n = n * 10 + (c - '0');
  }
  return n;
}

class PngSequenceSink : public FrameSink {
 public:
  PngSequenceSink(std::string dir, std::string staging, std::string created)
      : dir_(std::move(dir)), staging_(std::move(staging)), created_(std::move(created)) {}

  ~PngSequenceSink() override {
    if (!finished_) abandon();
  }

  const Error* add(Image&& frame) override {
    if (failed_) return &error_;
    if (finished_) return fail(fileError(ErrorKind::Internal, dir_, "frame added after finish()"));
    const std::string name = frameName(count_);
    Error e = writePng((fs::path(staging_) / name).string(), frame);
    if (!e.message.empty()) {
      // Name the frame as the user will look for it, not the staging path.
      e.loc.file = (fs::path(dir_) / name).string();
      if (e.kind == ErrorKind::CannotCreate) e.kind = ErrorKind::IoError;  // the directory was writable
      return fail(std::move(e));
    }
    ++count_;
    return nullptr;
  }

  const Error* finish() override {
    if (failed_) return &error_;
    if (finished_) return nullptr;
    for (uint64_t i = 0; i < count_; ++i) {
      const std::string name = frameName(i);
      const fs::path to = fs::path(dir_) / name;
      if (std::rename((fs::path(staging_) / name).c_str(), to.c_str()) != 0)
        return fail(
            fileError(ErrorKind::CannotCreate, to.string(), std::string("cannot create: ") + std::strerror(errno)));
    }
    // Frames of an earlier, longer recording would otherwise follow this one's.
    std::error_code ec;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir_, ec)) {
      const long long n = frameNumber(entry.path().filename().string());
      if (n >= 0 && static_cast<uint64_t>(n) >= count_) fs::remove(entry.path(), ec);
    }
    fs::remove(staging_, ec);
    finished_ = true;
    return nullptr;
  }

 private:
  const Error* fail(Error e) {
    error_ = std::move(e);
    failed_ = true;
    abandon();
    return &error_;
  }

  void abandon() {
    std::error_code ec;
    fs::remove_all(staging_, ec);
    if (!created_.empty()) {
      // Only directories this sink made, and only if nothing else was put there meanwhile.
      fs::path p = dir_;
      while (!p.empty() && fs::is_empty(p, ec) && !ec) {
        fs::remove(p, ec);
        if (p == fs::path(created_)) break;
        p = p.parent_path();
      }
      created_.clear();
    }
  }

  std::string dir_, staging_, created_;
  uint64_t count_ = 0;
  bool failed_ = false;
  bool finished_ = false;
  Error error_;
};

}  // namespace

bool isFrameFileName(const std::string& name) { return frameNumber(name) >= 0; }

std::unique_ptr<FrameSink> makePngSequenceSink(const std::string& dir, Error* err) {
  auto fail = [&](const std::string& file, const std::string& what) {
    if (err) *err = fileError(ErrorKind::CannotCreate, file, what);
    return nullptr;
  };
  if (dir.empty()) return fail(dir, "empty output directory name");
  // The outermost directory that does not exist yet: removed again if the recording fails.
  std::string created;
  std::error_code ec;
  for (fs::path p = fs::absolute(dir, ec); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    created = p.string();
    if (p == p.parent_path()) break;
  }
  struct stat st {};
  if (::stat(dir.c_str(), &st) == 0) {
    if (!S_ISDIR(st.st_mode)) return fail(dir, "cannot create frames: not a directory");
  } else {
    fs::create_directories(dir, ec);
    if (ec) return fail(dir, "cannot create directory: " + ec.message());
  }
  const std::string staging =
      (fs::path(dir) / (".simbob-frames.tmp." + std::to_string(static_cast<long>(::getpid())))).string();
  fs::remove_all(staging, ec);  // left by an earlier process of the same pid that was killed
  if (::mkdir(staging.c_str(), 0777) != 0) {
    const int e = errno;
    if (!created.empty()) fs::remove_all(created, ec);
    return fail(dir, std::string("cannot create frames: ") + std::strerror(e));
  }
  return std::make_unique<PngSequenceSink>(dir, staging, created);
}

}  // namespace simbob
