// The socket protocol's codec: see socket_codec.h and docs/socket-protocol.md.
#include "robot/socket_codec.h"

#include <charconv>
#include <cmath>
#include <utility>

#include "simbob/image.h"
#include "simbob/values.h"

namespace simbob::robot::protocol {

namespace {

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
    case ActuatorDef::Effort:
      return "effort";
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

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

Request request(Request::Kind kind) {
  Request r;
  r.kind = kind;
  return r;
}

Request error(std::string problem) {
  Request r;
  r.kind = Request::Error;
  r.problem = std::move(problem);
  return r;
}

}  // namespace

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

bool parseNumber(std::string_view s, double* out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const char* end = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), end, *out);
  return ec == std::errc() && p == end && !s.empty() && std::isfinite(*out);
}

Codec::Codec(const Model& model, std::string key, double period, std::vector<std::string> motions)
    : model_(model), key_(std::move(key)), period_(period), motions_(std::move(motions)) {
  subscribed_[kBodies].assign(model.bodies.size(), 1);
  subscribed_[kJoints].assign(model.joints.size(), 1);
  subscribed_[kSensors].assign(model.sensors.size(), 1);
  subscribed_[kCameras].assign(model.camera_sensors.size(), 0);  // images only on request
}

std::string Codec::hello() const {
  std::string s = "simbob " + std::to_string(version_) + " " + escapeKey(key_) + " " + formatNumber(period_) + "\n";
  if (version_ == kFirstVersion) s += "versions 2 3\n";  // what a peer may choose with `version`
  for (const ActuatorDef& a : model_.actuators) s += "actuator " + escapeKey(a.key) + " " + actuatorKind(a.kind) + "\n";
  for (const std::string& m : motions_) s += "motion " + escapeKey(m) + "\n";
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

std::string Codec::state(SimTime now, const World& world, const CameraImages* images) const {
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
    const Image* img = images ? images->image(key) : nullptr;
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

Request Codec::read(std::string_view line, bool first) {
  if (line.size() > kMaxLine) return error("a line longer than " + std::to_string(kMaxLine) + " bytes");
  const std::vector<std::string_view> w = words(line);
  if (w.empty()) return {};
  if (w[0] == "version" && first) return negotiate(w);
  if (w[0] == "subscribe" && version_ >= 3) return subscribe(w);
  if (w[0] == "step" && w.size() == 1) return request(Request::Step);
  if (w[0] == "done" && w.size() == 1) return request(Request::Done);
  if (w[0] == "set" && w.size() >= 3) return set(w);
  Request r = error("the peer sent '" + quoteInput(line) + "'");
  r.expected = version_ >= 3 ? ": expected 'set KEY VALUE...', 'subscribe', 'step' or 'done'"
                             : ": expected 'set KEY VALUE...', 'step' or 'done'";
  return r;
}

// `version V...` (the first line of the peer's first reply): simbob chooses the newest version
// both speak; the peer then gets `version N` and that version's hello and state.
Request Codec::negotiate(const std::vector<std::string_view>& w) {
  int chosen = 0;
  for (size_t i = 1; i < w.size(); ++i) {
    int v = 0;
    auto [p, ec] = std::from_chars(w[i].data(), w[i].data() + w[i].size(), v);
    if (ec != std::errc() || p != w[i].data() + w[i].size())
      return error("'version': '" + quoteInput(w[i]) + "' is not a version number");
    if (v >= kFirstVersion && v <= kNewestVersion && v > chosen) chosen = v;
  }
  if (chosen == 0) return error("no protocol version in common: simbob speaks 2 and 3");
  version_ = chosen;
  return request(Request::Negotiate);
}

// `subscribe bodies|joints|sensors|cameras [KEY...]` (version 3): the state blocks from the next
// one on carry only these of that kind (cameras: their images); `*` for all, no key for none.
Request Codec::subscribe(const std::vector<std::string_view>& w) {
  int kind = -1;
  if (w.size() >= 2) {
    if (w[1] == "bodies") kind = kBodies;
    if (w[1] == "joints") kind = kJoints;
    if (w[1] == "sensors") kind = kSensors;
    if (w[1] == "cameras") kind = kCameras;
  }
  if (kind < 0) return error("'subscribe' takes bodies, joints, sensors or cameras, then keys");
  std::vector<char> on(subscribed_[kind].size(), 0);
  for (size_t i = 2; i < w.size(); ++i) {
    if (w[i] == "*") {
      on.assign(on.size(), 1);
      continue;
    }
    std::string key;
    if (!unescapeKey(w[i], &key))
      return error("'subscribe " + std::string(w[1]) + " " + quoteInput(w[i]) +
                   "': a '%' not followed by two hex digits");
    const int found = indexOfKey(kind, key);
    if (found < 0) {
      static const char* kSingular[] = {"body", "joint", "sensor", "camera sensor"};
      return error("'subscribe " + std::string(w[1]) + "': no " + kSingular[kind] + " has the key '" +
                   quoteInput(w[i]) + "'");
    }
    on[static_cast<size_t>(found)] = 1;
  }
  subscribed_[kind] = std::move(on);
  return request(Request::Subscribe);
}

int Codec::indexOfKey(int kind, const std::string& key) const {
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

Request Codec::set(const std::vector<std::string_view>& w) const {
  std::string key;
  if (!unescapeKey(w[1], &key)) return error("'set " + quoteInput(w[1]) + "': a '%' not followed by two hex digits");
  Request r;
  r.values.resize(w.size() - 2);
  for (size_t i = 2; i < w.size(); ++i)
    if (!parseNumber(w[i], &r.values[i - 2]))
      return error("'set " + quoteInput(w[1]) + "': '" + quoteInput(w[i]) + "' is not a finite number");
  for (size_t i = 0; i < model_.actuators.size(); ++i)
    if (model_.actuators[i].key == key) {
      if (r.values.size() != 1)
        return error("'set " + std::string(w[1]) + "' takes one value, got " + std::to_string(r.values.size()));
      r.kind = Request::Command;
      r.index = static_cast<int>(i);
      return r;
    }
  for (size_t i = 0; i < motions_.size(); ++i)
    if (motions_[i] == key) {
      if (r.values.size() != 2)
        return error("'set " + std::string(w[1]) + "' takes two values (linear angular), got " +
                     std::to_string(r.values.size()));
      r.kind = Request::Motion;
      r.index = static_cast<int>(i);
      return r;
    }
  return error("'set " + quoteInput(w[1]) + "': no actuator or motion control has that key");
}

}  // namespace simbob::robot::protocol
