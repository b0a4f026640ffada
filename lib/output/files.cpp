#include "simbob/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace simbob {

bool readFile(const std::string& path, size_t max_bytes, std::string* out, std::string* reason) {
  out->clear();
  auto fail = [&](std::string why) {
    out->clear();
    out->shrink_to_fit();
    if (reason) *reason = std::move(why);
    return false;
  };
  auto tooLarge = [&] { return fail("larger than " + std::to_string(max_bytes >> 20) + " MiB"); };
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return fail(std::strerror(errno));
  struct stat st;
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
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

bool writeFileAtomically(const std::string& path, const std::string& bytes, Error* err) {
  auto fail = [&](ErrorKind kind, const std::string& what, int e) {
    if (err) *err = {kind, {path, 0}, what + ": " + std::strerror(e)};
    return false;
  };
  const std::string tmp = path + ".tmp." + std::to_string(static_cast<long>(::getpid()));
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) return fail(ErrorKind::CannotCreate, "cannot create", errno);
  int e = writeAll(fd, bytes.data(), bytes.size());
  if (::close(fd) != 0 && e == 0 && errno != EINTR) e = errno;
  if (e != 0) {
    ::unlink(tmp.c_str());
    return fail(ErrorKind::IoError, "write failed", e);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    e = errno;
    ::unlink(tmp.c_str());
    return fail(ErrorKind::CannotCreate, "cannot create", e);
  }
  return true;
}

}  // namespace simbob
