#include "simbob/files.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace simbob {

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
