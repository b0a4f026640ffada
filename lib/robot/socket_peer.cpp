// RCLocalSocketCommunicator (guide 6.11.6): another program on this computer (the peer) reads
// the robot's state and sets its commands over a TCP connection on 127.0.0.1, in lockstep with
// simulated time. At every Period simbob sends the state and waits for the peer's commands and
// "step" before the simulation goes on; the line protocol is docs/socket-protocol.md.
// Every wait is a poll(2) with a wall-clock deadline (SocketDef::timeout): a peer that never
// connects, goes away or falls silent fails the run (ErrorKind::Unavailable), a line the
// protocol does not allow fails it too (ErrorKind::Protocol). No threads.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "robot/controllers.h"
#include "robot/peer_process.h"
#include "simbob/image.h"
#include "simbob/physics.h"
#include "simbob/values.h"

namespace simbob::robot {

namespace {

// 2: sensor lines (version 1 did not promise to skip unknown lines). 3: negotiated by the peer
// (`version`), subscriptions, body velocities, sensor readings as vectors, camera images (binary
// blocks after an `image` line, to peers that subscribed to that camera only).
constexpr int kFirstVersion = 2;  ///< every peer gets this hello first
constexpr int kNewestVersion = 3;
constexpr size_t kMaxLine = 4096;  ///< bytes of one line from the peer, newline excluded

using Wall = std::chrono::steady_clock;

const char* actuatorKind(ActuatorDef::Kind k) {
  switch (k) {
    case ActuatorDef::Drive:
      return "voltage";
    case ActuatorDef::Servo:
      return "position";
    case ActuatorDef::VelDrive:
      return "velocity";
    case ActuatorDef::Plugin:
      return "command";
  }
  return "?";
}

const char* jointKind(JointKind k) {
  switch (k) {
    case JointKind::Hinge:
      return "hinge";
    case JointKind::Slider:
      return "slider";
    case JointKind::BallSocket:
      return "ball";
    case JointKind::Fixed:
      return "fixed";
  }
  return "?";
}

/// One finite number, the whole of `s`.
bool parseDouble(std::string_view s, double* out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const char* end = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), end, *out);
  return ec == std::errc() && p == end && !s.empty() && std::isfinite(*out);
}

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> w;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
    if (j > i) w.push_back(line.substr(i, j - i));
    i = j;
  }
  return w;
}

/// A key as one word (every version): bytes that could split or break a line -- blanks, control
/// characters, bytes outside ASCII (UTF-8) -- and '%' and ',' become %XX (upper-case hex).
std::string escapeKey(const std::string& key) {
  static const char* kHex = "0123456789ABCDEF";
  std::string s;
  for (unsigned char ch : key) {
    if (ch <= 0x20 || ch >= 0x7f || ch == '%' || ch == ',') {
      s += '%';
      s += kHex[ch >> 4];
      s += kHex[ch & 15];
    } else {
      s += static_cast<char>(ch);
    }
  }
  return s;
}

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

/// The key a word stands for; false if a '%' is not followed by two hex digits.
bool unescapeKey(std::string_view word, std::string* key) {
  key->clear();
  for (size_t i = 0; i < word.size(); ++i) {
    if (word[i] != '%') {
      *key += word[i];
      continue;
    }
    const int hi = i + 2 < word.size() ? hexDigit(word[i + 1]) : -1;
    const int lo = hi >= 0 ? hexDigit(word[i + 2]) : -1;
    if (lo < 0) return false;
    *key += static_cast<char>(hi * 16 + lo);
    i += 2;
  }
  return true;
}

/// What a sensor reads now, as the vector its `sensor` line carries (proximity: 1 touching, 0 not).
const char* sensorKind(const SensorDef& d) {
  switch (d.kind) {
    case SensorKind::Proximity:
      return "proximity";
    case SensorKind::Range:
      return "range";
    case SensorKind::Scanner:
      return "scanner";
    case SensorKind::Imu:
      return "imu";
    case SensorKind::Encoder:
      return "encoder";
    case SensorKind::Plugin:
      return "plugin";
  }
  return "proximity";
}

// Version 2 promised proximity sensors only (`sensor KEY 0|1`); version 3 carries every sensor.
bool carried(const SensorDef& d, int version) { return version >= 3 || d.kind == SensorKind::Proximity; }

void appendNumbers(std::string& s, const double* v, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    s += ' ';
    appendNumber(s, v[i]);
  }
}

class SocketPeer : public Party {
 public:
  SocketPeer(const SocketDef& d, const Model& model, std::vector<std::pair<std::string, MotionControl2D*>> motions)
      : def_(d), model_(model), motions_(std::move(motions)), periodic_(d.period) {
    subscribed_[kBodies].assign(model.bodies.size(), 1);
    subscribed_[kJoints].assign(model.joints.size(), 1);
    subscribed_[kSensors].assign(model.sensors.size(), 1);
    subscribed_[kCameras].assign(model.camera_sensors.size(), 0);  // images only on request
  }
  ~SocketPeer() override {
    closeFd(&conn_);
    closeFd(&listen_);
    process_.end(0, kStopGrace);
  }
  SocketPeer(const SocketPeer&) = delete;
  SocketPeer& operator=(const SocketPeer&) = delete;

  SimTime first() override {
    // Connecting is not a grant: it is bounded by --peer-timeout alone, not by MaxAccessTime
    // (runParties does not time first(), and counts it apart from the simulation's wall time).
    if (def_.is_server) {
      listen();
      if (error_.message.empty() && startController()) accept();
    } else if (startController()) {
      connect();
    }
    return 0;
  }

  SimTime onGrant(SimTime now, World& world) override {
    if (!error_.message.empty() || done_ || stopped_ || conn_ < 0) return kNever;
    if (!hello_sent_) {
      hello_sent_ = true;
      if (!send(hello())) return kNever;
    }
    if (!send(state(now, world)) || !exchange(now, world)) return kNever;
    if (stopped_) return kNever;  // the run ends (interrupted); abandon() tells the peer
    if (done_) {
      closeFd(&conn_);
      return kNever;
    }
    return periodic_.next(now);
  }

  void finish(SimTime end, World& /*world*/) override {
    if (conn_ >= 0 && error_.message.empty()) send("bye " + formatNumber(toSeconds(end)) + "\n");
    closeFd(&conn_);
    closeFd(&listen_);
    process_.end(kLinger);  // it heard 'bye' (or end of file): a moment to exit by itself
  }

  const Error* failure() const override { return error_.message.empty() ? nullptr : &error_; }

  /// The run diverged, was interrupted or failed elsewhere: README promises the peer an `error`
  /// line before the connection closes, not a bare EOF.
  void abandon(const Error& why) override {
    if (conn_ >= 0) {
      std::string what = why.message;
      for (char& ch : what)
        if (ch == '\n' || ch == '\r') ch = ' ';
      const std::string line = "error " + what + "\n";
      (void)::send(conn_, line.data(), line.size(), MSG_NOSIGNAL);
    }
    closeFd(&conn_);
    closeFd(&listen_);
    // Quick: after SIGINT/SIGTERM simbob's run has 1 s to return before it exits anyway.
    process_.end(kStopLinger, kStopGrace);
  }

 private:
  static constexpr double kLinger = 1.0;                        ///< s a started controller may take to exit after 'bye'
  static constexpr double kStopLinger = 0.3, kStopGrace = 0.4;  ///< the same after 'error'; s to SIGKILL

  /// Starts the Controller, if any, now that the port is known; false after an error.
  bool startController() {
    if (def_.controller.empty()) return true;
    std::vector<std::string> words;
    std::string problem;
    if (!splitCommandLine(def_.controller, &words, &problem))
      return fail(ErrorKind::InvalidInput, "controller '" + def_.controller + "': " + problem);
    problem = process_.start(words, def_.controller_dir,
                             {{"SIMBOB_PORT", std::to_string(def_.port)},
                              {"SIMBOB_KEY", def_.key},
                              {"SIMBOB_SEED", std::to_string(def_.seed)}},
                             def_.controller_log);
    if (!problem.empty())
      return fail(ErrorKind::Unavailable, "cannot start controller '" + def_.controller + "': " + problem);
    return true;
  }

  /// A started controller that has exited can no longer connect: the run fails naming it.
  bool controllerGone() {
    std::string how;
    if (!process_.started() || !process_.exited(&how)) return false;
    fail(ErrorKind::Unavailable, "controller '" + def_.controller + "' " + how + " before connecting" +
                                     (def_.controller_log.empty() ? "" : " (its output: " + def_.controller_log + ")"));
    return true;
  }

  static void closeFd(int* fd) {
    if (*fd >= 0) ::close(*fd);
    *fd = -1;
  }

  std::string where() const {
    return "RCLocalSocketCommunicator '" + def_.key + "' (127.0.0.1:" + std::to_string(def_.port) + ")";
  }

  /// Fails the run; tells a connected peer why (best effort) and closes the connection.
  bool fail(ErrorKind kind, const std::string& what) {
    if (error_.message.empty()) error_ = {kind, def_.loc, where() + ": " + what};
    if (conn_ >= 0) {
      const std::string line = "error " + what + "\n";
      (void)::send(conn_, line.data(), line.size(), MSG_NOSIGNAL);
    }
    closeFd(&conn_);
    closeFd(&listen_);
    process_.end(kStopLinger, kStopGrace);
    return false;
  }

  /// A stop was requested while waiting for the peer: give up the wait, the run ends.
  bool stop() {
    stopped_ = true;
    return true;
  }

  std::string timeoutText() const { return formatNumber(def_.timeout) + " s"; }

  /// Milliseconds left until `deadline` (0 when past it), for poll(2); at most kSliceMs, so
  /// that a wait sees a stop request (SIGINT, SIGTERM) soon.
  static constexpr long long kSliceMs = 50;
  static int msLeft(Wall::time_point deadline) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Wall::now()).count();
    return left <= 0 ? 0 : static_cast<int>(std::min<long long>(left, kSliceMs));
  }

  Wall::time_point deadline() const {
    return Wall::now() + std::chrono::duration_cast<Wall::duration>(std::chrono::duration<double>(def_.timeout));
  }

  static sockaddr_in loopback(int port) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    return a;
  }

  void listen() {
    listen_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    if (listen_ < 0) {
      fail(ErrorKind::Unavailable, std::string("cannot create a socket: ") + std::strerror(errno));
      return;
    }
    const int one = 1;
    ::setsockopt(listen_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    // A controller simbob starts learns the port from SIMBOB_PORT: the system picks a free one,
    // so that parallel runs (batch -j, sweeps, --check-determinism) never clash.
    sockaddr_in a = loopback(def_.controller.empty() ? def_.port : 0);
    if (::bind(listen_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::listen(listen_, 1) != 0) {
      fail(ErrorKind::Unavailable, std::string("cannot listen: ") + std::strerror(errno) +
                                       " (another run on this port? --port-offset moves every port)");
      return;
    }
    socklen_t len = sizeof a;
    if (::getsockname(listen_, reinterpret_cast<sockaddr*>(&a), &len) == 0) def_.port = ntohs(a.sin_port);
  }

  bool accept() {
    if (listen_ < 0) return fail(ErrorKind::Internal, "not listening");
    pollfd p{listen_, POLLIN, 0};
    const Wall::time_point until = deadline();
    while (true) {
      if (stopRequested()) return stop();
      if (controllerGone()) return false;
      const int r = ::poll(&p, 1, msLeft(until));
      if (r < 0 && errno == EINTR) continue;
      if (r == 0 && Wall::now() < until) continue;
      if (r <= 0)
        return fail(ErrorKind::Unavailable,
                    "no peer connected within " + timeoutText() + " (--peer-timeout)" +
                        (process_.started() ? "; controller '" + def_.controller + "' is running but did not connect"
                                            : std::string()));
      conn_ = ::accept4(listen_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
      if (conn_ >= 0) break;
      if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR && errno != ECONNABORTED)
        return fail(ErrorKind::Unavailable, std::string("cannot accept a peer: ") + std::strerror(errno));
    }
    closeFd(&listen_);  // one peer per run
    configure();
    return true;
  }

  /// One connection attempt: 0 when connected, else the errno; -1 when it failed or stopped
  /// already (error_ or stopped_ says which).
  int connectOnce(Wall::time_point until) {
    conn_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    if (conn_ < 0) {
      fail(ErrorKind::Unavailable, std::string("cannot create a socket: ") + std::strerror(errno));
      return -1;
    }
    sockaddr_in a = loopback(def_.port);
    int err = 0;
    if (::connect(conn_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
      err = errno;
      if (err == EINPROGRESS) {
        pollfd p{conn_, POLLOUT, 0};
        int r;
        while (((r = ::poll(&p, 1, msLeft(until))) < 0 && errno == EINTR) || (r == 0 && Wall::now() < until))
          if (stopRequested()) {
            stop();
            return -1;
          }
        if (r <= 0) {
          fail(ErrorKind::Unavailable, "no answer from a server within " + timeoutText());
          return -1;
        }
        socklen_t len = sizeof err;
        ::getsockopt(conn_, SOL_SOCKET, SO_ERROR, &err, &len);
      }
    }
    return err;
  }

  bool connect() {
    const Wall::time_point until = deadline();
    while (true) {
      const int err = connectOnce(until);
      if (err < 0) return error_.message.empty();
      if (err == 0) break;
      closeFd(&conn_);
      // A controller simbob started needs a moment to listen: retry until --peer-timeout.
      if (err == ECONNREFUSED && process_.started() && Wall::now() < until) {
        if (stopRequested()) return stop();
        if (controllerGone()) return false;
        ::poll(nullptr, 0, 20);
        continue;
      }
      return fail(ErrorKind::Unavailable,
                  std::string("cannot connect to a server: ") + std::strerror(err) +
                      (process_.started() ? std::string(" (the controller did not listen within ") + timeoutText() + ")"
                                          : " (IsServer is false: start the peer's server first; simbob does "
                                            "not retry)"));
    }
    configure();
    return true;
  }

  void configure() {
    const int one = 1;
    ::setsockopt(conn_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  }

  bool send(const std::string& text) {
    const Wall::time_point until = deadline();
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
        if (::poll(&p, 1, msLeft(until)) == 0 && Wall::now() >= until)
          return fail(ErrorKind::Unavailable, "the peer read nothing for " + timeoutText() + " (--peer-timeout)");
        if (stopRequested()) return stop();
        continue;
      }
      return fail(ErrorKind::Unavailable,
                  std::string("the peer went away (") + std::strerror(n < 0 ? errno : EPIPE) + ")");
    }
    return true;
  }

  std::string hello() const {
    std::string s =
        "simbob " + std::to_string(version_) + " " + escapeKey(def_.key) + " " + formatNumber(def_.period) + "\n";
    if (version_ == kFirstVersion) s += "versions 2 3\n";  // what a peer may choose with `version`
    for (const ActuatorDef& a : model_.actuators)
      s += "actuator " + escapeKey(a.key) + " " + actuatorKind(a.kind) + "\n";
    for (const auto& m : motions_) s += "motion " + escapeKey(m.first) + "\n";
    for (const JointDef& j : model_.joints) s += "joint " + escapeKey(j.key) + " " + jointKind(j.kind) + "\n";
    for (const SensorDef& d : model_.sensors) {
      if (!carried(d, version_)) continue;
      s += "sensor " + escapeKey(d.key);
      if (version_ >= 3) s += std::string(" ") + sensorKind(d) + " " + std::to_string(sensorQuantities(d).size());
      s += "\n";
    }
    if (version_ >= 3)
      for (const CameraSensorDef& c : model_.camera_sensors)
        s += "camera " + escapeKey(c.key) + " " + std::to_string(c.width) + " " + std::to_string(c.height) + " " +
             formatNumber(c.period) + "\n";
    for (const BodyDef& b : model_.bodies) s += "body " + escapeKey(b.key) + "\n";
    s += "end\n";
    return s;
  }

  std::string state(SimTime now, const World& world) const {
    std::string s = "t " + formatNumber(toSeconds(now)) + "\n";
    for (size_t i = 0; i < model_.joints.size(); ++i) {
      if (!subscribed_[kJoints][i]) continue;
      const JointState js = world.joint(static_cast<int>(i));
      s += "joint " + escapeKey(model_.joints[i].key);
      const double v[2] = {js.position, js.velocity};
      appendNumbers(s, v, 2);
      s += '\n';
    }
    for (size_t i = 0; i < model_.sensors.size(); ++i) {
      if (!subscribed_[kSensors][i] || !carried(model_.sensors[i], version_)) continue;
      const std::vector<double>& r = world.sensorReading(static_cast<int>(i));
      s += "sensor " + escapeKey(model_.sensors[i].key);
      appendNumbers(s, r.data(), r.size());
      s += '\n';
    }
    for (size_t i = 0; i < model_.camera_sensors.size() && version_ >= 3; ++i) {
      if (!subscribed_[kCameras][i]) continue;
      // The camera's latest image, drawn before the controllers of its last Period instant.
      const std::string& key = model_.camera_sensors[i].key;
      const Image* img = world.cameraImage(key);
      const bool drawn = img && !img->rgb.empty();
      const int w = drawn ? img->width : 0, h = drawn ? img->height : 0;
      s += "image " + escapeKey(key) + " " + std::to_string(w) + " " + std::to_string(h) + " " +
           std::to_string(drawn ? img->rgb.size() : 0) + "\n";
      if (drawn) s.append(reinterpret_cast<const char*>(img->rgb.data()), img->rgb.size());
    }
    for (size_t i = 0; i < model_.bodies.size(); ++i) {
      if (!subscribed_[kBodies][i]) continue;
      const BodyState b = world.body(static_cast<int>(i));
      s += "body " + escapeKey(model_.bodies[i].key);
      appendNumbers(s, b.pose.p.data(), 3);
      appendNumbers(s, b.pose.q.data(), 4);
      if (version_ >= 3) {
        appendNumbers(s, b.lin_vel.data(), 3);
        appendNumbers(s, b.ang_vel.data(), 3);
      }
      s += '\n';
    }
    s += "end\n";
    return s;
  }

  /// `version V...` (the first line of the peer's first reply): simbob chooses the newest version
  /// both speak, answers `version N`, and starts over with that version's hello and state.
  bool negotiate(const std::vector<std::string_view>& w, SimTime now, const World& world) {
    int chosen = 0;
    for (size_t i = 1; i < w.size(); ++i) {
      int v = 0;
      auto [p, ec] = std::from_chars(w[i].data(), w[i].data() + w[i].size(), v);
      if (ec != std::errc() || p != w[i].data() + w[i].size()) {
        problem_ = "'version': '" + quoteInput(w[i]) + "' is not a version number";
        return false;
      }
      if (v >= kFirstVersion && v <= kNewestVersion && v > chosen) chosen = v;
    }
    if (chosen == 0) {
      problem_ = "no protocol version in common: simbob speaks 2 and 3";
      return false;
    }
    version_ = chosen;
    return send("version " + std::to_string(chosen) + "\n" + hello() + state(now, world));
  }

  /// `subscribe bodies|joints|sensors|cameras [KEY...]` (version 3): the state blocks from the next
  /// one on carry only these of that kind (cameras: their images); `*` for all, no key for none.
  bool subscribe(const std::vector<std::string_view>& w) {
    int kind = -1;
    if (w.size() >= 2) {
      if (w[1] == "bodies") kind = kBodies;
      if (w[1] == "joints") kind = kJoints;
      if (w[1] == "sensors") kind = kSensors;
      if (w[1] == "cameras") kind = kCameras;
    }
    if (kind < 0) {
      problem_ = "'subscribe' takes bodies, joints, sensors or cameras, then keys";
      return false;
    }
    std::vector<char> on(subscribed_[kind].size(), 0);
    for (size_t i = 2; i < w.size(); ++i) {
      if (w[i] == "*") {
        on.assign(on.size(), 1);
        continue;
      }
      std::string key;
      if (!unescapeKey(w[i], &key)) {
        problem_ =
            "'subscribe " + std::string(w[1]) + " " + quoteInput(w[i]) + "': a '%' not followed by two hex digits";
        return false;
      }
      const int found = indexOfKey(kind, key);
      if (found < 0) {
        static const char* kSingular[] = {"body", "joint", "sensor", "camera sensor"};
        problem_ =
            "'subscribe " + std::string(w[1]) + "': no " + kSingular[kind] + " has the key '" + quoteInput(w[i]) + "'";
        return false;
      }
      on[static_cast<size_t>(found)] = 1;
    }
    subscribed_[kind] = std::move(on);
    return true;
  }

  int indexOfKey(int kind, const std::string& key) const {
    auto find = [&](const auto& defs) {
      for (size_t i = 0; i < defs.size(); ++i)
        if (defs[i].key == key) return static_cast<int>(i);
      return -1;
    };
    if (kind == kBodies) return find(model_.bodies);
    if (kind == kJoints) return find(model_.joints);
    if (kind == kCameras) return find(model_.camera_sensors);
    return find(model_.sensors);
  }

  /// Reads and applies the peer's lines up to "step" or "done".
  bool exchange(SimTime now, World& world) {
    // Within a grant the peer also answers within MaxAccessTime (guide 7.2), whichever ends first.
    const Wall::time_point own = deadline();
    const bool by_access = accessDeadline() < own;
    const Wall::time_point until = by_access ? accessDeadline() : own;
    const std::string limit = by_access ? formatNumber(accessLimit()) + " s" : timeoutText();
    const std::string which = by_access ? " (MaxAccessTime)" : " (--peer-timeout)";
    const std::string at = " at t=" + formatNumber(toSeconds(now)) + " s";
    while (true) {
      // On every line, not only when poll times out: a peer streaming 'set' lines without
      // 'step' must not hold the run past its deadline.
      if (Wall::now() >= until)
        return fail(ErrorKind::Unavailable, "the peer sent no 'step' within " + limit + at + which);
      if (stopRequested()) return stop();
      const size_t nl = in_.find('\n');
      if (nl == std::string::npos) {
        if (in_.size() > kMaxLine)
          return fail(ErrorKind::Protocol, "a line longer than " + std::to_string(kMaxLine) + " bytes" + at);
        pollfd p{conn_, POLLIN, 0};
        const int r = ::poll(&p, 1, msLeft(until));
        if (r <= 0) continue;  // EINTR or a slice without data: the deadline is checked above
        char buf[4096];
        const ssize_t n = ::recv(conn_, buf, sizeof buf, 0);
        if (n < 0 && (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK)) continue;
        if (n <= 0)
          return fail(ErrorKind::Unavailable,
                      "the peer disconnected" + at + " without 'done'" +
                          (n < 0 ? std::string(" (") + std::strerror(errno) + ")" : std::string()));
        in_.append(buf, static_cast<size_t>(n));
        continue;
      }
      std::string line = in_.substr(0, nl);
      in_.erase(0, nl + 1);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.size() > kMaxLine)
        return fail(ErrorKind::Protocol, "a line longer than " + std::to_string(kMaxLine) + " bytes" + at);
      const std::vector<std::string_view> w = words(line);
      if (w.empty()) continue;
      const bool first_line = !replied_;
      replied_ = true;
      if (w[0] == "version" && first_line) {
        if (!negotiate(w, now, world)) return fail(ErrorKind::Protocol, problem_ + at);
        continue;
      }
      if (w[0] == "subscribe" && version_ >= 3) {
        if (!subscribe(w)) return fail(ErrorKind::Protocol, problem_ + at);
        continue;
      }
      if (w[0] == "step" && w.size() == 1) return true;
      if (w[0] == "done" && w.size() == 1) {
        done_ = true;
        return true;
      }
      if (w[0] == "set" && w.size() >= 3) {
        if (!set(w, world)) return fail(ErrorKind::Protocol, problem_ + at);
        continue;
      }
      return fail(ErrorKind::Protocol,
                  "the peer sent '" + quoteInput(line) + "'" + at +
                      (version_ >= 3 ? ": expected 'set KEY VALUE...', 'subscribe', 'step' or 'done'"
                                     : ": expected 'set KEY VALUE...', 'step' or 'done'"));
    }
  }

  bool set(const std::vector<std::string_view>& w, World& world) {
    std::string key;
    if (!unescapeKey(w[1], &key)) {
      problem_ = "'set " + quoteInput(w[1]) + "': a '%' not followed by two hex digits";
      return false;
    }
    std::vector<double> v(w.size() - 2);
    for (size_t i = 2; i < w.size(); ++i)
      if (!parseDouble(w[i], &v[i - 2])) {
        problem_ = "'set " + quoteInput(w[1]) + "': '" + quoteInput(w[i]) + "' is not a finite number";
        return false;
      }
    for (size_t i = 0; i < model_.actuators.size(); ++i)
      if (model_.actuators[i].key == key) {
        if (v.size() != 1) {
          problem_ = "'set " + std::string(w[1]) + "' takes one value, got " + std::to_string(v.size());
          return false;
        }
        world.setCommand(static_cast<int>(i), v[0]);
        return true;
      }
    for (const auto& m : motions_)
      if (m.first == key) {
        if (v.size() != 2) {
          problem_ =
              "'set " + std::string(w[1]) + "' takes two values (linear angular), got " + std::to_string(v.size());
          return false;
        }
        m.second->setMotion(v[0], v[1], world);
        return true;
      }
    problem_ = "'set " + quoteInput(w[1]) + "': no actuator or motion control has that key";
    return false;
  }

  SocketDef def_;
  const Model& model_;
  std::vector<std::pair<std::string, MotionControl2D*>> motions_;
  Periodic periodic_;
  int listen_ = -1;
  int conn_ = -1;
  bool hello_sent_ = false;
  bool replied_ = false;  ///< the peer has sent a line (`version` must be its first)
  int version_ = kFirstVersion;
  enum { kBodies, kJoints, kSensors, kCameras };
  std::vector<char> subscribed_[4];  ///< per kind, per Model index: in the state blocks
  bool done_ = false;
  bool stopped_ = false;  ///< a stop was requested while waiting for the peer
  std::string in_;
  std::string problem_;
  Error error_;
  PeerProcess process_;  ///< the Controller simbob started, if any
};

}  // namespace

std::unique_ptr<Party> makeSocketPeer(const SocketDef& d, const Model& model,
                                      std::vector<std::pair<std::string, MotionControl2D*>> motions) {
  return std::make_unique<SocketPeer>(d, model, std::move(motions));
}

}  // namespace simbob::robot
