// Plug-in sensors and actuators (simbob/plugin_c.h, docs/plugins.md): the instance of each is
// made when the World is, a sensor's read() runs on the step grid like a built-in sensor's
// (updateSensors), an actuator's apply() before every step; both see the world through a
// SimbobHost whose context is their mount. A failure (create() returning NULL, a callback
// returning nonzero, a host call with an argument out of range) is recorded once as the World's
// failure (World::failure), naming the periphery, the plug-in and the type; the run stops there.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "simbob/plugin_c.h"
#include "simbob/transform.h"
#include "simbob/values.h"
#include "world_impl.h"

namespace simbob {

namespace {

/// What a SimbobHost of a sensor or actuator points at.
struct MountContext {
  WorldImpl* im;
  int body;         ///< Model::bodies index, -1 = static
  int static_body;  ///< body -1: the static body it is mounted on (GeomDef::static_body)
  Transform pose;   ///< the mount relative to the body
  double time;      ///< s
  std::string* misuse;
};

/// The mount whose callback runs now on this thread (null between callbacks): host calls are
/// checked against it, so that a NULL host, or one kept from an earlier callback, is an error
/// naming the call rather than a read through a stale pointer.
thread_local MountContext* tCurrent = nullptr;

/// Sets tCurrent for the duration of one callback.
struct InCallback {
  explicit InCallback(MountContext* m) : saved(tCurrent) { tCurrent = m; }
  ~InCallback() { tCurrent = saved; }
  InCallback(const InCallback&) = delete;
  InCallback& operator=(const InCallback&) = delete;
  MountContext* saved;
};

/// Records the first misuse of the callback running now.
void misuse(MountContext* m, const std::string& what) {
  if (m && m->misuse->empty()) *m->misuse = what;
}

/// The mount behind `h`, or null after recording why there is none: a NULL host, or a host
/// that is not the one the running callback got.
MountContext* ctx(const SimbobHost* h, const char* call) {
  if (!h) {
    misuse(tCurrent, std::string(call) + ": the host is NULL: pass the SimbobHost the callback got");
    return nullptr;
  }
  if (!tCurrent || h->context != tCurrent) {
    misuse(tCurrent, std::string(call) +
                         ": not the host of this callback (a host is valid only during the "
                         "callback that got it)");
    return nullptr;
  }
  return tCurrent;
}

Transform mountFrame(const MountContext& m) {
  return m.body < 0 ? m.pose : compose(bodyState(*m.im, m.body).pose, m.pose);
}

double hostTime(const SimbobHost* h) {
  const MountContext* m = ctx(h, "time()");
  return m ? m->time : -1;
}

int notForPeripheries(const SimbobHost* h, int, double*, int) {
  misuse(ctx(h, "read_sensor()"), "read_sensor() is for controllers");
  return -1;
}
int noCommand(const SimbobHost* h, int, double) {
  misuse(ctx(h, "set_command()"), "set_command() is for controllers");
  return -1;
}

int hostMountPose(const SimbobHost* h, double position[3], double quaternion[4]) {
  MountContext* m = ctx(h, "mount_pose()");
  if (!m) return -1;
  if (!position || !quaternion) {
    misuse(m, "mount_pose(): position or quaternion is NULL");
    return -1;
  }
  const Transform f = mountFrame(*m);
  for (int k = 0; k < 3; ++k) position[k] = f.p[static_cast<size_t>(k)];
  for (int k = 0; k < 4; ++k) quaternion[k] = f.q[static_cast<size_t>(k)];
  return 0;
}

int hostBodyVelocity(const SimbobHost* h, double linear[3], double angular[3]) {
  MountContext* mc = ctx(h, "body_velocity()");
  if (!mc) return -1;
  if (!linear || !angular) {
    misuse(mc, "body_velocity(): linear or angular is NULL");
    return -1;
  }
  const MountContext& m = *mc;
  BodyState s;
  if (m.body >= 0) s = bodyState(*m.im, m.body);
  for (size_t k = 0; k < 3; ++k) {
    linear[k] = s.lin_vel[k];
    angular[k] = s.ang_vel[k];
  }
  return 0;
}

int hostBodyState(const SimbobHost* h, int ref, double* p, double* q, double* v, double* w) {
  MountContext* mc = ctx(h, "body_state()");
  if (!mc) return -1;
  MountContext& m = *mc;
  if (ref != -1) {
    misuse(&m, "body_state(" + std::to_string(ref) + "): a sensor or actuator reads its own body: ref -1");
    return -1;
  }
  BodyState s;
  if (m.body >= 0) s = bodyState(*m.im, m.body);
  copyBodyState(s, p, q, v, w);
  return 0;
}

double hostCastRay(const SimbobHost* h, const double origin[3], const double direction[3], double max_length) {
  MountContext* mc = ctx(h, "cast_ray()");
  if (!mc) return -1;
  MountContext& m = *mc;
  if (!origin || !direction) {
    misuse(&m, "cast_ray(): origin or direction is NULL");
    return -1;
  }
  const Vec3 d{direction[0], direction[1], direction[2]};
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(len > 0) || !std::isfinite(len) || !(max_length > 0) || !(max_length <= 1e6) ||
      !std::isfinite(origin[0] + origin[1] + origin[2])) {
    misuse(&m, "cast_ray(): the origin and direction must be finite, the direction not zero, max_length in (0, 1e6] m");
    return -1;
  }
  const Transform f = mountFrame(m);
  const Vec3 o = add(f.p, rotate(f.q, Vec3{origin[0], origin[1], origin[2]}));
  const Vec3 dir = rotate(f.q, Vec3{d[0] / len, d[1] / len, d[2] / len});
  gatherRayCandidates(*m.im, m.body, m.static_body, o, max_length);
  const double hit = castRay(*m.im, o, dir, max_length);
  return std::isfinite(hit) ? hit : -1;
}

SimbobHost hostFor(MountContext* m) {
  SimbobHost h{};
  h.size = sizeof(SimbobHost);
  h.context = m;
  h.time = hostTime;
  h.read_sensor = notForPeripheries;
  h.set_command = noCommand;
  h.mount_pose = hostMountPose;
  h.body_velocity = hostBodyVelocity;
  h.body_state = hostBodyState;
  h.cast_ray = hostCastRay;
  return h;
}

/// Records the World's first failure, at the periphery's scene element.
void fail(WorldImpl& im, const SourceLoc& loc, const std::string& what) {
  if (im.failure.message.empty()) im.failure = {ErrorKind::ControllerFailed, loc, what};
}

std::string messageOf(const char* buf) {
  const size_t n = strnlen(buf, SIMBOB_MESSAGE_SIZE);
  return n ? std::string(buf, n) : std::string("(no message)");
}

/// A message buffer with room to spare: a plug-in that writes past SIMBOB_MESSAGE_SIZE bytes
/// writes into the spare room (its message is cut at SIMBOB_MESSAGE_SIZE), not into simbob's stack.
/// Only the first SIMBOB_MESSAGE_SIZE bytes are cleared (messageOf reads no further): clearing
/// the spare room for every callback took a tenth of a small scene's step.
struct MessageBuffer {
  MessageBuffer() { std::fill_n(bytes.data(), SIMBOB_MESSAGE_SIZE, '\0'); }
  char* data() { return bytes.data(); }
  std::array<char, size_t{16} * SIMBOB_MESSAGE_SIZE> bytes;
};

/// Where a plug-in callback writes its output (a sensor's `out`, an actuator's force and torque):
/// n entries followed by kGuard entries of a guard pattern, so that a callback writing past its
/// n entries writes into this buffer, not into simbob's memory, and is caught. Writing past the
/// end goes forward from entry n, so the first kCheck guard entries show it; a write farther
/// than kGuard entries still corrupts memory (docs/testing.md). One per thread, reused.
class GuardedOut {
 public:
  static constexpr size_t kGuard = 4096;
  static constexpr size_t kCheck = 64;

  /// The buffer for n entries, the guard after them intact.
  double* prepare(size_t n) {
    if (buf_.size() < n + kGuard) {
      buf_.assign(n + kGuard, kGuardBits);
      dirty_ = 0;
    }
    if (dirty_ > n)
      std::fill(buf_.begin() + static_cast<std::ptrdiff_t>(n), buf_.begin() + static_cast<std::ptrdiff_t>(dirty_),
                kGuardBits);
    n_ = n;
    dirty_ = n;
    return reinterpret_cast<double*>(buf_.data());  // NOLINT(cppcoreguidelines-pro-type-reinterpret-cast)
  }
  /// False if the callback wrote past its n entries (the guard is restored).
  bool intact() {
    const auto first = buf_.begin() + static_cast<std::ptrdiff_t>(n_);
    if (std::all_of(first, first + kCheck, [](uint64_t b) { return b == kGuardBits; })) return true;
    std::fill(first, first + static_cast<std::ptrdiff_t>(kGuard), kGuardBits);
    return false;
  }

 private:
  static constexpr uint64_t kGuardBits = 0x7ff4deadbeefcafeULL;  // a NaN payload no arithmetic produces
  std::vector<uint64_t> buf_;
  size_t n_ = 0;
  size_t dirty_ = 0;  ///< entries [0, dirty_) may hold what a callback wrote
};

GuardedOut& guardedOut() {
  thread_local GuardedOut out;
  return out;
}

std::string numberText(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return formatNumber(v);
}

/// Makes the instance; false after recording why.
bool createInstance(WorldImpl& im, const SimbobType& t, const std::vector<double>& numbers, const std::string& who,
                    const SourceLoc& loc, std::shared_ptr<void>* user) {
  if (!t.create) return true;
  MessageBuffer msg;
  void* u = t.create(numbers.data(), msg.data());
  if (!u) {
    fail(im, loc, who + ": create() failed: " + messageOf(msg.data()));
    return false;
  }
  void (*destroy)(void*) = t.destroy;
  *user = std::shared_ptr<void>(u, [destroy](void* p) {
    if (destroy) destroy(p);
  });
  return true;
}

/// The velocity (m/s) or angular velocity (rad/s) beyond which a run has diverged
/// (SimulationOptions::runaway_limit's default).
constexpr double kRunaway = 1e6;

/// "" or why the force f and torque tau (mount frame) on body `body` for a step of h s make it
/// run away: when they alone change its velocity by more than kRunaway m/s (|f| h / m) or its
/// angular velocity by more than kRunaway rad/s (|tau| h / the smallest diagonal entry of its
/// inertia), the run diverges in that step, and the actuator is to blame, not the body.
/// A derived quantity in a message: 3 significant digits (1e300 * 0.01 is 1.0000000000000001e+298).
std::string threeDigits(double v) {
  std::array<char, 32> buf{};
  std::snprintf(buf.data(), buf.size(), "%.3g", v);
  return buf.data();
}

std::string runawayPush(WorldImpl& im, int body, const double* f, const double* tau, double h) {
  dMass mass;
  dBodyGetMass(im.bodies[static_cast<size_t>(body)], &mass);
  const double force = std::hypot(f[0], f[1], f[2]), torque = std::hypot(tau[0], tau[1], tau[2]);
  const double inertia = std::min({mass.I[0], mass.I[5], mass.I[10]});
  const double dv = force * h / mass.mass, dw = inertia > 0 ? torque * h / inertia : 0;
  if (dv > kRunaway)
    return "apply() gave a force of " + formatNumber(force) + " N, which alone changes the velocity of its body by " +
           threeDigits(dv) + " m/s in one step of " + formatNumber(h) + " s, beyond the runaway limit (" +
           formatNumber(kRunaway) + " m/s): the run would diverge";
  if (dw > kRunaway)
    return "apply() gave a torque of " + formatNumber(torque) +
           " N m, which alone changes the angular velocity of its body by " + threeDigits(dw) +
           " rad/s in one step of " + formatNumber(h) + " s, beyond the runaway limit (" + formatNumber(kRunaway) +
           " rad/s): the run would diverge";
  return "";
}

}  // namespace

std::string sensorWho(const SensorDef& d) { return "sensor '" + d.key + "' (" + d.plugin_who + ")"; }

void createPluginSensor(WorldImpl& im, SensorState& s) {
  const std::string who = sensorWho(s.def);
  if (!createInstance(im, *s.def.plugin, s.def.numbers, who, s.def.loc, &s.user)) s.broken = true;
}

void readPluginSensor(WorldImpl& im, SensorState& s) {
  if (s.broken) return;
  std::string misuse;
  MountContext m{&im, s.def.body, s.def.static_body, s.def.pose, static_cast<double>(im.time_ns) * 1e-9, &misuse};
  const SimbobHost h = hostFor(&m);
  MessageBuffer msg;
  const size_t n = s.reading.size();
  // read() writes into a guarded copy of the reading, which is kept only if it is whole and finite.
  GuardedOut& guard = guardedOut();
  double* out = guard.prepare(n);
  std::memcpy(out, s.reading.data(), n * sizeof(double));
  int rc;
  {
    InCallback in(&m);
    rc = s.def.plugin->read(s.user.get(), &h, m.time, out, static_cast<int>(n), msg.data());
  }
  const bool intact = guard.intact();
  std::string why;
  if (!misuse.empty()) {  // first: the callback may fail because of it
    why = misuse;
  } else if (rc != 0) {
    why = "read() failed: " + messageOf(msg.data());
  } else if (!intact) {
    why = "read() wrote past the end of out (it has room for n = " + std::to_string(n) + " entries)";
  } else {
    for (size_t k = 0; k < n && why.empty(); ++k)
      if (!std::isfinite(out[k]))
        why = "read() gave a reading that is not finite (" + s.quantities[k] + " = " + numberText(out[k]) + ")";
  }
  if (!why.empty()) {
    fail(im, s.def.loc, sensorWho(s.def) + ": " + why);
    s.broken = true;
    return;
  }
  std::memcpy(s.reading.data(), out, n * sizeof(double));
}

void createPluginActuator(WorldImpl& im, ActuatorState& a) {
  const std::string who = "actuator '" + a.def.key + "' (" + a.def.plugin_who + ")";
  if (!createInstance(im, *a.def.plugin, a.def.numbers, who, a.def.loc, &a.user)) a.broken = true;
}

void applyPluginActuator(WorldImpl& im, ActuatorState& a, double h) {
  if (a.broken) return;
  std::string misuse;
  MountContext m{&im, a.def.body, a.def.static_body, a.def.pose, static_cast<double>(im.time_ns) * 1e-9, &misuse};
  const SimbobHost host = hostFor(&m);
  MessageBuffer msg;
  // force[3] and torque[3] with the guard after them, as a sensor's out (a plug-in writing past
  // them would write into simbob's stack).
  GuardedOut& guard = guardedOut();
  double* f = guard.prepare(6);
  double* tau = f + 3;
  std::fill(f, f + 6, 0.0);
  int rc;
  {
    InCallback in(&m);
    rc = a.def.plugin->apply(a.user.get(), &host, m.time, h, a.command, f, tau, msg.data());
  }
  const bool intact = guard.intact();
  const std::string who = "actuator '" + a.def.key + "' (" + a.def.plugin_who + ")";
  std::string why;
  if (!misuse.empty())  // first: the callback may fail because of it
    why = misuse;
  else if (rc != 0)
    why = "apply() failed: " + messageOf(msg.data());
  else if (!intact)
    why = "apply() wrote past the end of force[3] or torque[3]";
  else if (!std::all_of(f, f + 6, [](double v) { return std::isfinite(v); }))
    why = "apply() gave a force or torque that is not finite";
  else if (a.def.body >= 0)
    why = runawayPush(im, a.def.body, f, tau, h);
  if (!why.empty()) {
    fail(im, a.def.loc, who + ": " + why);
    a.broken = true;
    return;
  }
  if (a.def.body < 0) return;  // a static mount pushes nothing
  const Transform frame = mountFrame(m);
  const Vec3 F = rotate(frame.q, Vec3{f[0], f[1], f[2]});
  const Vec3 T = rotate(frame.q, Vec3{tau[0], tau[1], tau[2]});
  dBodyID b = im.bodies[static_cast<size_t>(a.def.body)];
  dBodyAddForceAtPos(b, F[0], F[1], F[2], frame.p[0], frame.p[1], frame.p[2]);
  dBodyAddTorque(b, T[0], T[1], T[2]);
}

const Error* World::failure() const { return impl_->failure.message.empty() ? nullptr : &impl_->failure; }

}  // namespace simbob
