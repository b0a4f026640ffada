// The socket protocol's codec (docs/socket-protocol.md): what simbob says to a peer -- the hello,
// the state blocks with their images -- and what a peer's line asks for, or the protocol error
// it is, in words. Pure: no sockets, no clocks, no processes (socket_transport.h moves the bytes,
// socket_peer.cpp is the party that does both), so every line is tested on its own
// (tests/robot/socket_codec_test.cpp).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "simbob/clock.h"
#include "simbob/model.h"
#include "simbob/physics.h"
#include "simbob/robot.h"

namespace simbob::robot::protocol {

// 2: sensor lines (version 1 did not promise to skip unknown lines). 3: negotiated by the peer
// (`version`), subscriptions, body velocities, sensor readings as vectors, camera images (binary
// blocks after an `image` line, to peers that subscribed to that camera only).
constexpr int kFirstVersion = 2;  ///< every peer gets this hello first
constexpr int kNewestVersion = 3;
constexpr size_t kMaxLine = 4096;  ///< bytes of one line from the peer, newline excluded

/// A key as one word (every version): bytes that could split or break a line -- blanks, control
/// characters, bytes outside ASCII (UTF-8) -- and '%' and ',' become %XX (upper-case hex).
std::string escapeKey(const std::string& key);
/// The key a word stands for; false if a '%' is not followed by two hex digits.
bool unescapeKey(std::string_view word, std::string* key);
/// The words of a line, split at blanks and tabs.
std::vector<std::string_view> words(std::string_view line);
/// One finite number, the whole of `s` (a leading '+' allowed).
bool parseNumber(std::string_view s, double* out);

/// What a peer's line asks simbob to do.
struct Request {
  enum Kind {
    Nothing,    ///< a blank line
    Negotiate,  ///< `version V...`: answer `version N`, then the hello and state of that version
    Subscribe,  ///< `subscribe ...` (applied to the codec's subscriptions)
    Step,       ///< `step`: the simulation goes on
    Done,       ///< `done`: the peer has finished; simbob closes the connection
    Command,    ///< `set KEY VALUE`: actuator `index` to values[0]
    Motion,     ///< `set KEY LINEAR ANGULAR`: motion control `index` (order of the codec's motions)
    Error,      ///< a line the protocol does not allow: `problem` says why
  } kind = Nothing;
  int index = -1;
  std::vector<double> values;
  /// Error: what is wrong, in two parts around where the caller says when it happened: the
  /// peer's line ("the peer sent 'jump'") and what was expected (": expected ..."; may be "").
  std::string problem, expected;
};

/// One conversation's protocol state: the version spoken, what the peer subscribed to.
class Codec {
 public:
  enum Kind { kBodies, kJoints, kSensors, kCameras };

  /// The peer of communicator `key` (period s between exchanges) of `model`, which may command
  /// every actuator and the motion controls named in `motions` (keys, in order).
  Codec(const Model& model, std::string key, double period, std::vector<std::string> motions);

  int version() const { return version_; }
  /// The hello of the current version: `simbob V KEY PERIOD`, what the peer may choose
  /// (version 2), the actuators, motions, joints, sensors, cameras (3) and bodies, `end`.
  std::string hello() const;
  /// The state block at `now`: `t`, the subscribed joints, sensors, camera images (3: an `image`
  /// line and its RGB bytes) and bodies (3: with velocities), `end`.
  std::string state(SimTime now, const World& world, const CameraImages* images) const;
  /// What `line` (without its newline) asks for; `first` when it is the peer's first line
  /// (`version` is allowed only there). Negotiate and Subscribe take effect here.
  Request read(std::string_view line, bool first);

 private:
  Request negotiate(const std::vector<std::string_view>& w);
  Request subscribe(const std::vector<std::string_view>& w);
  Request set(const std::vector<std::string_view>& w) const;
  int indexOfKey(int kind, const std::string& key) const;

  const Model& model_;
  std::string key_;
  double period_;
  std::vector<std::string> motions_;
  int version_ = kFirstVersion;
  std::vector<char> subscribed_[4];  ///< per kind, per Model index: in the state blocks
};

}  // namespace simbob::robot::protocol
