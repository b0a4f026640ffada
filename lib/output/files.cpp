#include "simbob/tool/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace simbob {

bool readFile(const std::string& path, size_t max_bytes, std::string* out, std::string* reason, bool regular_only,
              bool* too_large) {
  out->clear();
  if (too_large) *too_large = false;
  auto fail = [&](std::string why) {
    out->clear();
    out->shrink_to_fit();
    if (reason) *reason = std::move(why);
    return false;
  };
  auto tooLarge = [&] {
    if (too_large) *too_large = true;
    return fail("larger than " + std::to_string(max_bytes >> 20) + " MiB");
  };
  // Without O_NONBLOCK, opening a FIFO that has no writer blocks forever.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | (regular_only ? O_NONBLOCK : 0));
  if (fd < 0) return fail(std::strerror(errno));
  struct stat st;
  const bool is_stat = ::fstat(fd, &st) == 0;
  if (regular_only && !(is_stat && S_ISREG(st.st_mode))) {
    ::close(fd);
    return fail(is_stat && S_ISDIR(st.st_mode) ? std::strerror(EISDIR) : "not a regular file");
  }
  if (is_stat && S_ISREG(st.st_mode)) {
    if (static_cast<uint64_t>(st.st_size) > max_bytes) {
      ::close(fd);
      return tooLarge();
    }
    out->reserve(static_cast<size_t>(st.st_size));
  }
  char chunk[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int e = errno;
      ::close(fd);
      return fail(std::strerror(e));
    }
    if (n == 0) break;
    if (out->size() + static_cast<size_t>(n) > max_bytes) {
      ::close(fd);
      return tooLarge();
    }
    out->append(chunk, static_cast<size_t>(n));
  }
  ::close(fd);
  return true;
}

namespace {

namespace fs = std::filesystem;

// Follows a chain of symlinks (which may end in a name not yet taken) to the path that an
// output replaces. Bounded like the kernel's own limit on symlink hops.
std::string followLinks(const std::string& path) {
  std::string p = path;
  for (int hop = 0; hop < 40; ++hop) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p;
    std::vector<char> buf(PATH_MAX + 1);
    const ssize_t n = ::readlink(p.c_str(), buf.data(), PATH_MAX);
    if (n < 0) return p;
    fs::path link(std::string(buf.data(), static_cast<size_t>(n)));
    p = link.is_absolute() ? link.string() : (fs::path(p).parent_path() / link).string();
  }
  return p;
}

}  // namespace

int writeAll(int fd, const char* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    if (n == 0) return ENOSPC;
    data += n;
    size -= static_cast<size_t>(n);
  }
  return 0;
}

bool isStreamOutput(const std::string& path) {
  if (path == "-") return true;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return false;
  return !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

std::string cannotCreateReason(const std::string& path, int e) {
  if (e == ENOENT) {
    const std::string folder = fs::path(path).parent_path().string();
    return "cannot create: folder '" + quoteInput(folder.empty() ? "." : folder, 400) + "' does not exist";
  }
  return std::string("cannot create: ") + std::strerror(e);
}

std::unique_ptr<OutputFile> OutputFile::open(const std::string& path, Error* err) {
  auto fail = [&](const std::string& what) {
    if (err) *err = fileError(ErrorKind::CannotCreate, path, what);
    return nullptr;
  };
  if (path.empty()) return fail("empty output file name");
  std::unique_ptr<OutputFile> f(new OutputFile());
  f->path_ = path;
  if (path == "-") {
    f->target_ = "-";
    f->stream_ = true;
    f->fd_ = STDOUT_FILENO;
    return f;
  }
  f->target_ = followLinks(path);
  struct stat st {};
  if (::stat(f->target_.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) return fail("cannot create: is a directory");
    if (!S_ISREG(st.st_mode)) {
      // Written through: renaming a file over /dev/null would replace the device node.
      f->stream_ = true;
      f->fd_ = ::open(f->target_.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
      if (f->fd_ < 0) return fail(std::string("cannot open: ") + std::strerror(errno));
      return f;
    }
  }
  f->temp_ = f->target_ + ".tmp." + std::to_string(static_cast<long>(::getpid()));
  f->fd_ = ::open(f->temp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (f->fd_ < 0) {
    f->done_ = true;  // nothing to clean up
    return fail(cannotCreateReason(f->target_, errno));
  }
  return f;
}

OutputFile::~OutputFile() { abandon(); }

bool OutputFile::write(const char* data, size_t size) {
  if (errno_ != 0 || closed_) return false;
  const int e = writeAll(fd_, data, size);
  if (e != 0) {
    errno_ = e;
    return false;
  }
  size_ += size;
  return true;
}

bool OutputFile::close(Error* err) {
  if (done_) {
    if (err) *err = fileError(ErrorKind::Internal, path_, "output already closed");
    return false;
  }
  if (!closed_) {
    closed_ = true;
    // close() can report a deferred write error (e.g. NFS, quota): it counts as a failed write.
    // Standard output stays open for the rest of the command.
    if (!(stream_ && fd_ == STDOUT_FILENO) && ::close(fd_) != 0 && errno != EINTR && errno_ == 0) errno_ = errno;
    fd_ = -1;
  }
  if (errno_ != 0) {
    const int e = errno_;
    abandon();
    if (err) *err = fileError(ErrorKind::IoError, path_, std::string("write failed: ") + std::strerror(e));
    return false;
  }
  return true;
}

bool OutputFile::rename(const std::string& to, Error* err) {
  if (stream_) {
    done_ = true;
    return true;
  }
  const std::string& target = to.empty() ? target_ : to;
  if (std::rename(temp_.c_str(), target.c_str()) != 0) {
    const int e = errno;
    abandon();
    if (err)
      *err = fileError(ErrorKind::CannotCreate, target,
                       "cannot rename " + temp_ + " to " + target + ": " + std::strerror(e));
    return false;
  }
  done_ = true;
  return true;
}

void OutputFile::abandon() {
  if (done_) return;
  if (fd_ >= 0 && !(stream_ && fd_ == STDOUT_FILENO)) ::close(fd_);
  fd_ = -1;
  closed_ = true;
  if (!stream_) ::unlink(temp_.c_str());
  done_ = true;
}

bool commitOutputs(const std::vector<OutputFile*>& files, Error* err) {
  auto abandonAll = [&]() {
    for (OutputFile* f : files) f->abandon();
  };
  for (OutputFile* f : files)
    if (!f->close(err)) {
      abandonAll();
      return false;
    }
  // Keep each old target under a second name (a hard link, no copy) until all are replaced.
  const std::string pid = std::to_string(static_cast<long>(::getpid()));
  struct Undo {
    OutputFile* f;
    std::string backup;  // "" if the target did not exist
  };
  std::vector<Undo> done;
  std::vector<std::string> backups(files.size());
  for (size_t i = 0; i < files.size(); ++i) {
    OutputFile* f = files[i];
    if (f->stream_) continue;
    const std::string backup = f->target_ + ".old." + pid;
    ::unlink(backup.c_str());
    if (::link(f->target_.c_str(), backup.c_str()) == 0) backups[i] = backup;
  }
  bool ok = true;
  for (size_t i = 0; i < files.size() && ok; ++i) {
    OutputFile* f = files[i];
    if (!f->rename("", err)) {
      ok = false;
      break;
    }
    if (!f->stream_) done.push_back({f, backups[i]});
  }
  if (!ok) {
    for (const Undo& u : done) {
      if (u.backup.empty())
        ::unlink(u.f->target_.c_str());
      else
        std::rename(u.backup.c_str(), u.f->target_.c_str());
    }
    abandonAll();
  }
  for (const std::string& b : backups)
    if (!b.empty()) ::unlink(b.c_str());
  return ok;
}

bool writeFileAtomically(const std::string& path, const std::string& bytes, Error* err) {
  std::unique_ptr<OutputFile> f = OutputFile::open(path, err);
  if (!f) return false;
  f->write(bytes);
  return commitOutputs({f.get()}, err);
}

bool sameExistingFile(const std::string& a, const std::string& b) {
  if (a.empty() || b.empty() || a == "-" || b == "-") return false;
  struct stat sa {
  }, sb{};
  if (::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return false;
  return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

bool sameOutputPlace(const std::string& a, const std::string& b) {
  if (a.empty() || b.empty()) return false;
  if (a == "-" || b == "-") return a == b;
  if (sameExistingFile(a, b)) return true;
  std::error_code ea, eb;
  const fs::path pa = fs::weakly_canonical(fs::absolute(followLinks(a)), ea);
  const fs::path pb = fs::weakly_canonical(fs::absolute(followLinks(b)), eb);
  return !ea && !eb && pa == pb;
}

Error outputCollision(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    const NamedPath& o = outputs[i];
    if (o.path.empty() || isStreamOutput(o.path)) continue;
    for (const NamedPath& in : inputs)
      if (sameExistingFile(o.path, in.path))
        return {ErrorKind::Usage,
                {},
                o.what + " " + quoteInput(o.path, 400) + " is " + in.what + " " + quoteInput(in.path, 400) +
                    ": an output must not overwrite an input"};
    for (size_t k = 0; k < i; ++k)
      if (!outputs[k].path.empty() && sameOutputPlace(o.path, outputs[k].path))
        return {ErrorKind::Usage,
                {},
                o.what + " " + quoteInput(o.path, 400) + " and " + outputs[k].what + " " +
                    quoteInput(outputs[k].path, 400) + " are the same file: outputs of one command must not collide"};
  }
  return {};
}

}  // namespace simbob
