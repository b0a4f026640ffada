// The socket peer's transport: one TCP connection on 127.0.0.1, as a server (listen, accept) or a
// client (connect), whole texts sent and whole lines received with wall-clock deadlines. Every
// wait is a poll(2) in slices of at most 50 ms, calling back between slices so that the party
// sees a stop request (SIGINT, SIGTERM) or a controller that exited soon. No threads, no protocol
// (socket_codec.h), no messages: results carry what happened and the errno, the party words them.
#pragma once

#include <chrono>
#include <functional>
#include <string>

namespace simbob::robot {

using Wall = std::chrono::steady_clock;

/// What an operation of the transport came to.
struct IoResult {
  enum Status {
    Ok,       ///< done
    Timeout,  ///< the deadline passed
    Stopped,  ///< the caller's check asked to stop waiting
    Refused,  ///< connect: nobody listens on the port (yet)
    Closed,   ///< receive: the peer closed the connection (err 0) or it broke (err set)
    TooLong,  ///< receive: more than the line limit without a newline
    Failed,   ///< a system call failed: `call` and `err` say which and why
  } status = Ok;
  const char* call = "";  ///< "socket", "listen", "accept", "connect", "send", "recv"
  int err = 0;            ///< errno
};

class PeerSocket {
 public:
  /// Called between the slices of every wait: true stops the wait (IoResult::Stopped).
  using Check = std::function<bool()>;

  PeerSocket() = default;
  ~PeerSocket();
  PeerSocket(const PeerSocket&) = delete;
  PeerSocket& operator=(const PeerSocket&) = delete;

  /// Listens on 127.0.0.1:`port` (0: a free port the system picks); boundPort() says which.
  IoResult listen(int port);
  int boundPort() const { return port_; }
  /// Waits until `until` for one peer to connect; stops listening once it has.
  IoResult accept(Wall::time_point until, const Check& check);
  /// One attempt to connect to 127.0.0.1:`port`, waiting for the answer until `until`.
  IoResult connect(int port, Wall::time_point until, const Check& check);
  /// Sends all of `text`, waiting until `until` while the peer does not read.
  IoResult send(const std::string& text, Wall::time_point until, const Check& check);
  /// Sends what fits now and never waits (an `error` line before closing).
  void sendNow(const std::string& text);
  /// The next line (without its newline and a '\r' before it) into *line, waiting until `until`;
  /// a line over `max_line` bytes is TooLong.
  IoResult receiveLine(std::string* line, size_t max_line, Wall::time_point until, const Check& check);
  bool connected() const { return conn_ >= 0; }
  /// Closes the connection and the listening socket.
  void close();

 private:
  int listen_ = -1;
  int conn_ = -1;
  int port_ = 0;
  std::string in_;  ///< bytes received after the last line taken
};

}  // namespace simbob::robot
