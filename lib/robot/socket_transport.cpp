// The socket peer's transport: see socket_transport.h.
#include "robot/socket_transport.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

namespace simbob::robot {

namespace {

/// Milliseconds left until `deadline` (0 when past it), for poll(2); at most kSliceMs, so that a
/// wait calls its check (a stop request, a controller that exited) soon.
constexpr long long kSliceMs = 50;
int msLeft(Wall::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Wall::now()).count();
  return left <= 0 ? 0 : static_cast<int>(std::min<long long>(left, kSliceMs));
}

sockaddr_in loopback(int port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  return a;
}

void closeFd(int* fd) {
  if (*fd >= 0) ::close(*fd);
  *fd = -1;
}

IoResult failed(const char* call, int err) { return {IoResult::Failed, call, err}; }

// Lockstep exchanges are small: no Nagle delay.
void noDelay(int fd) {
  const int one = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
}

}  // namespace

PeerSocket::~PeerSocket() { close(); }

void PeerSocket::close() {
  closeFd(&conn_);
  closeFd(&listen_);
  in_.clear();
}

IoResult PeerSocket::listen(int port) {
  listen_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (listen_ < 0) return failed("socket", errno);
  const int one = 1;
  ::setsockopt(listen_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in a = loopback(port);
  if (::bind(listen_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::listen(listen_, 1) != 0) {
    const int err = errno;
    closeFd(&listen_);
    return failed("listen", err);
  }
  socklen_t len = sizeof a;
  port_ = ::getsockname(listen_, reinterpret_cast<sockaddr*>(&a), &len) == 0 ? ntohs(a.sin_port) : port;
  return {};
}

IoResult PeerSocket::accept(Wall::time_point until, const Check& check) {
  if (listen_ < 0) return failed("accept", EBADF);
  pollfd p{listen_, POLLIN, 0};
  while (true) {
    if (check()) return {IoResult::Stopped};
    const int r = ::poll(&p, 1, msLeft(until));
    if (r < 0 && errno == EINTR) continue;
    if (r == 0 && Wall::now() < until) continue;
    if (r <= 0) return {IoResult::Timeout};
    conn_ = ::accept4(listen_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
    if (conn_ >= 0) break;
    if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR && errno != ECONNABORTED)
      return failed("accept", errno);
  }
  closeFd(&listen_);  // one peer per run
  noDelay(conn_);
  return {};
}

IoResult PeerSocket::connect(int port, Wall::time_point until, const Check& check) {
  closeFd(&conn_);
  conn_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (conn_ < 0) return failed("socket", errno);
  sockaddr_in a = loopback(port);
  int err = 0;
  if (::connect(conn_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    err = errno;
    if (err == EINPROGRESS) {
      pollfd p{conn_, POLLOUT, 0};
      int r;
      while (((r = ::poll(&p, 1, msLeft(until))) < 0 && errno == EINTR) || (r == 0 && Wall::now() < until))
        if (check()) {
          closeFd(&conn_);
          return {IoResult::Stopped};
        }
      if (r <= 0) {
        closeFd(&conn_);
        return {IoResult::Timeout};
      }
      socklen_t len = sizeof err;
      ::getsockopt(conn_, SOL_SOCKET, SO_ERROR, &err, &len);
    }
  }
  if (err != 0) {
    closeFd(&conn_);
    return err == ECONNREFUSED ? IoResult{IoResult::Refused, "connect", err} : failed("connect", err);
  }
  noDelay(conn_);
  return {};
}

IoResult PeerSocket::send(const std::string& text, Wall::time_point until, const Check& check) {
  size_t off = 0;
  while (off < text.size()) {
    const ssize_t n = ::send(conn_, text.data() + off, text.size() - off, MSG_NOSIGNAL);
    if (n > 0) {
      off += static_cast<size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      pollfd p{conn_, POLLOUT, 0};
      if (::poll(&p, 1, msLeft(until)) == 0 && Wall::now() >= until) return {IoResult::Timeout};
      if (check()) return {IoResult::Stopped};
      continue;
    }
    return failed("send", n < 0 ? errno : EPIPE);
  }
  return {};
}

void PeerSocket::sendNow(const std::string& text) {
  if (conn_ >= 0) (void)::send(conn_, text.data(), text.size(), MSG_NOSIGNAL);
}

IoResult PeerSocket::receiveLine(std::string* line, size_t max_line, Wall::time_point until, const Check& check) {
  while (true) {
    // On every line, not only when poll times out: a peer streaming lines must not hold the
    // caller past its deadline.
    if (Wall::now() >= until) return {IoResult::Timeout};
    if (check()) return {IoResult::Stopped};
    const size_t nl = in_.find('\n');
    if (nl != std::string::npos) {
      line->assign(in_, 0, nl);
      in_.erase(0, nl + 1);
      if (!line->empty() && line->back() == '\r') line->pop_back();
      return {};
    }
    if (in_.size() > max_line) return {IoResult::TooLong};
    pollfd p{conn_, POLLIN, 0};
    const int r = ::poll(&p, 1, msLeft(until));
    if (r <= 0) continue;  // EINTR or a slice without data: the deadline is checked above
    char buf[4096];
    const ssize_t n = ::recv(conn_, buf, sizeof buf, 0);
    if (n < 0 && (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK)) continue;
    if (n <= 0) return {IoResult::Closed, "recv", n < 0 ? errno : 0};
    in_.append(buf, static_cast<size_t>(n));
  }
}

}  // namespace simbob::robot
