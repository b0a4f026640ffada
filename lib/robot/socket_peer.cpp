// RCLocalSocketCommunicator (guide 6.11.6): another program on this computer (the peer) reads
// the robot's state and sets its commands over a TCP connection on 127.0.0.1, in lockstep with
// simulated time. At every Period simbob sends the state and waits for the peer's commands and
// "step" before the simulation goes on; the line protocol is docs/socket-protocol.md.
// This file is the party of the run loop; what the lines say is the codec's
// (socket_codec.h), moving them is the transport's (socket_transport.h), starting the peer
// program is PeerProcess's (peer_process.h). Every wait has a wall-clock deadline
// (SocketDef::timeout): a peer that never connects, goes away or falls silent fails the run
// (ErrorKind::Unavailable), a line the protocol does not allow fails it too (ErrorKind::Protocol).
#include <poll.h>

#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "robot/controllers.h"
#include "robot/peer_process.h"
#include "robot/socket_codec.h"
#include "robot/socket_transport.h"
#include "simbob/physics.h"
#include "simbob/values.h"

namespace simbob::robot {

namespace {

using protocol::Codec;
using protocol::Request;

std::vector<std::string> motionKeys(const std::vector<std::pair<std::string, MotionControl2D*>>& motions) {
  std::vector<std::string> keys;
  keys.reserve(motions.size());
  for (const auto& m : motions) keys.push_back(m.first);
  return keys;
}

class SocketPeer : public Party {
 public:
  SocketPeer(const SocketDef& d, const Model& model, std::vector<std::pair<std::string, MotionControl2D*>> motions,
             const CameraImages* images)
      : def_(d),
        motions_(std::move(motions)),
        images_(images),
        codec_(model, d.key, d.period, motionKeys(motions_)),
        periodic_(d.period) {}
  ~SocketPeer() override {
    socket_.close();
    process_.end(0, kStopGrace);
  }
  SocketPeer(const SocketPeer&) = delete;
  SocketPeer& operator=(const SocketPeer&) = delete;

  SimTime first() override {
    // Connecting is not a grant: it is bounded by --peer-timeout alone, not by MaxAccessTime
    // (the run loop does not time first(), and counts it apart from the simulation's wall time).
    if (def_.is_server) {
      if (listen() && startController()) accept();
    } else if (startController()) {
      connect();
    }
    return 0;
  }

  SimTime onGrant(SimTime now, World& world) override {
    if (!error_.message.empty() || done_ || stopped_ || !socket_.connected()) return kNever;
    if (!hello_sent_) {
      hello_sent_ = true;
      if (!send(codec_.hello())) return kNever;
    }
    if (!send(codec_.state(now, world, images_)) || !exchange(now, world)) return kNever;
    if (stopped_) return kNever;  // the run ends (interrupted); abandon() tells the peer
    if (done_) {
      socket_.close();
      return kNever;
    }
    return periodic_.next(now);
  }

  void finish(SimTime end, World& /*world*/) override {
    if (socket_.connected() && error_.message.empty())
      socket_.send("bye " + formatNumber(toSeconds(end)) + "\n", deadline(), [this] { return stopRequested(); });
    socket_.close();
    process_.end(kLinger);  // it heard 'bye' (or end of file): a moment to exit by itself
  }

  const Error* failure() const override { return error_.message.empty() ? nullptr : &error_; }

  /// The run diverged, was interrupted or failed elsewhere: README promises the peer an `error`
  /// line before the connection closes, not a bare EOF.
  void abandon(const Error& why) override {
    std::string what = why.message;
    for (char& ch : what)
      if (ch == '\n' || ch == '\r') ch = ' ';
    socket_.sendNow("error " + what + "\n");
    socket_.close();
    // Quick: after SIGINT/SIGTERM simbob's run has 1 s to return before it exits anyway.
    process_.end(kStopLinger, kStopGrace);
  }

 private:
  static constexpr double kLinger = 1.0;                        ///< s a started controller may take to exit after 'bye'
  static constexpr double kStopLinger = 0.3, kStopGrace = 0.4;  ///< the same after 'error'; s to SIGKILL

  // A controller simbob starts listens on a port the system picks, another one every run: its
  // messages say $SIMBOB_PORT, so that one failure reads the same every run (docs/ci.md).
  std::string where() const {
    return "RCLocalSocketCommunicator '" + def_.key +
           "' (127.0.0.1:" + (def_.controller.empty() ? std::to_string(def_.port) : std::string("$SIMBOB_PORT")) + ")";
  }
  std::string timeoutText() const { return formatNumber(def_.timeout) + " s"; }
  Wall::time_point deadline() const {
    return Wall::now() + std::chrono::duration_cast<Wall::duration>(std::chrono::duration<double>(def_.timeout));
  }

  /// Fails the run; tells a connected peer why (best effort) and closes the connection.
  bool fail(ErrorKind kind, const std::string& what) {
    if (error_.message.empty()) error_ = {kind, def_.loc, where() + ": " + what};
    socket_.sendNow("error " + what + "\n");
    socket_.close();
    process_.end(kStopLinger, kStopGrace);
    return false;
  }
  bool failedCall(const IoResult& r, const std::string& prefix, const std::string& suffix = "") {
    return fail(ErrorKind::Unavailable, prefix + std::strerror(r.err) + suffix);
  }

  /// Between the slices of a wait for the peer to connect: a stop request, or a started
  /// controller that exited (it can no longer connect: the run fails naming it).
  bool connectCheck() {
    if (stopRequested()) {
      stopped_ = true;
      return true;
    }
    std::string how;
    if (!process_.started() || !process_.exited(&how)) return false;
    fail(ErrorKind::Unavailable, "controller '" + def_.controller + "' " + how + " before connecting" +
                                     (def_.controller_log.empty() ? "" : " (its output: " + def_.controller_log + ")"));
    return true;
  }
  /// Between the slices of a wait for a connected peer: a stop request.
  bool stopCheck() {
    stopped_ = stopRequested();
    return stopped_;
  }

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

  bool listen() {
    // A controller simbob starts learns the port from SIMBOB_PORT: the system picks a free one,
    // so that parallel runs (batch -j, sweeps, --check-determinism) never clash.
    const IoResult r = socket_.listen(def_.controller.empty() ? def_.port : 0);
    if (r.status != IoResult::Ok)
      return std::strcmp(r.call, "socket") == 0
                 ? failedCall(r, "cannot create a socket: ")
                 : failedCall(r, "cannot listen: ", " (another run on this port? --port-offset moves every port)");
    def_.port = socket_.boundPort();
    return true;
  }

  void accept() {
    const IoResult r = socket_.accept(deadline(), [this] { return connectCheck(); });
    if (r.status == IoResult::Timeout)
      fail(ErrorKind::Unavailable,
           "no peer connected within " + timeoutText() + " (--peer-timeout)" +
               (process_.started() ? "; controller '" + def_.controller + "' is running but did not connect"
                                   : std::string()));
    else if (r.status == IoResult::Failed)
      failedCall(r, "cannot accept a peer: ");
  }

  void connect() {
    const Wall::time_point until = deadline();
    while (true) {
      const IoResult r = socket_.connect(def_.port, until, [this] { return stopCheck(); });
      if (r.status == IoResult::Ok || r.status == IoResult::Stopped) return;
      if (r.status == IoResult::Timeout) {
        fail(ErrorKind::Unavailable, "no answer from a server within " + timeoutText());
        return;
      }
      if (r.status == IoResult::Failed && std::strcmp(r.call, "socket") == 0) {
        failedCall(r, "cannot create a socket: ");
        return;
      }
      // A controller simbob started needs a moment to listen: retry until --peer-timeout.
      if (r.status == IoResult::Refused && process_.started() && Wall::now() < until) {
        if (connectCheck()) return;
        ::poll(nullptr, 0, 20);
        continue;
      }
      failedCall(r, "cannot connect to a server: ",
                 process_.started() ? std::string(" (the controller did not listen within ") + timeoutText() + ")"
                                    : " (IsServer is false: start the peer's server first; simbob does not retry)");
      return;
    }
  }

  bool send(const std::string& text) {
    const IoResult r = socket_.send(text, deadline(), [this] { return stopCheck(); });
    if (r.status == IoResult::Timeout)
      return fail(ErrorKind::Unavailable, "the peer read nothing for " + timeoutText() + " (--peer-timeout)");
    if (r.status == IoResult::Failed)
      return fail(ErrorKind::Unavailable, std::string("the peer went away (") + std::strerror(r.err) + ")");
    return true;  // sent, or stopped (the run ends)
  }

  /// Reads and applies the peer's lines up to "step" or "done".
  bool exchange(SimTime now, World& world) {
    // Within a grant the peer also answers within MaxAccessTime (guide 7.2), whichever ends first.
    const Wall::time_point own = deadline();
    const bool by_access = accessDeadline() < own;
    const Wall::time_point until = by_access ? accessDeadline() : own;
    const std::string at = " at t=" + formatNumber(toSeconds(now)) + " s";
    std::string line;
    while (true) {
      const IoResult r = socket_.receiveLine(&line, protocol::kMaxLine, until, [this] { return stopCheck(); });
      switch (r.status) {
        case IoResult::Ok:
          break;
        case IoResult::Stopped:
          return true;
        case IoResult::Timeout:
          return fail(ErrorKind::Unavailable, "the peer sent no 'step' within " +
                                                  (by_access ? formatNumber(accessLimit()) + " s" : timeoutText()) +
                                                  at + (by_access ? " (MaxAccessTime)" : " (--peer-timeout)"));
        case IoResult::TooLong:
          return fail(ErrorKind::Protocol, "a line longer than " + std::to_string(protocol::kMaxLine) + " bytes" + at);
        case IoResult::Closed:
        case IoResult::Refused:
        case IoResult::Failed:
          return fail(ErrorKind::Unavailable,
                      "the peer disconnected" + at + " without 'done'" +
                          (r.err ? std::string(" (") + std::strerror(r.err) + ")" : std::string()));
      }
      const Request q = codec_.read(line, !replied_);
      if (q.kind != Request::Nothing) replied_ = true;
      switch (q.kind) {
        case Request::Nothing:
        case Request::Subscribe:
          break;
        case Request::Negotiate:
          if (!send("version " + std::to_string(codec_.version()) + "\n" + codec_.hello() +
                    codec_.state(now, world, images_)))
            return false;
          break;
        case Request::Step:
          return true;
        case Request::Done:
          done_ = true;
          return true;
        case Request::Command:
          world.setCommand(q.index, q.values[0]);
          break;
        case Request::Motion:
          motions_[static_cast<size_t>(q.index)].second->setMotion(q.values[0], q.values[1], world);
          break;
        case Request::Error:
          return fail(ErrorKind::Protocol, q.problem + at + q.expected);
      }
    }
  }

  SocketDef def_;
  std::vector<std::pair<std::string, MotionControl2D*>> motions_;
  const CameraImages* images_;  ///< the Simulation's camera sensors (null: none)
  Codec codec_;
  PeerSocket socket_;
  Periodic periodic_;
  bool hello_sent_ = false;
  bool replied_ = false;  ///< the peer has sent a line (`version` must be its first)
  bool done_ = false;
  bool stopped_ = false;  ///< a stop was requested while waiting for the peer
  Error error_;
  PeerProcess process_;  ///< the Controller simbob started, if any
};

}  // namespace

std::unique_ptr<Party> makeSocketPeer(const SocketDef& d, const Model& model,
                                      std::vector<std::pair<std::string, MotionControl2D*>> motions,
                                      const CameraImages* images) {
  return std::make_unique<SocketPeer>(d, model, std::move(motions), images);
}

}  // namespace simbob::robot
