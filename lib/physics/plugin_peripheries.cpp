// Plug-in sensors and actuators (simbob/plugin_c.h, docs/plugins.md): the instance of each is
// made when the World is, a sensor's read() runs on the step grid like a built-in sensor's
// (updateSensors), an actuator's apply() before every step; both see the world through a
// SimbobHost whose context is their mount. A failure (create() returning NULL, a callback
// returning nonzero, a host call with an argument out of range) is recorded once as the World's
// failure (World::failure), naming the periphery, the plug-in and the type; the run stops there.
#include <array>
#include <cmath>
#include <cstring>

#include "simbob/plugin_c.h"
#include "simbob/transform.h"
#include "world_impl.h"

namespace simbob {

namespace {

/// What a SimbobHost of a sensor or actuator points at.
struct MountContext {
  WorldImpl* im;
  int body;        ///< Model::bodies index, -1 = static
  Transform pose;  ///< the mount relative to the body
  double time;     ///< s
  std::string* misuse;
};

MountContext& ctx(const SimbobHost* h) { return *static_cast<MountContext*>(h->context); }

Transform mountFrame(const MountContext& m) {
  return m.body < 0 ? m.pose : compose(bodyState(*m.im, m.body).pose, m.pose);
}

double hostTime(const SimbobHost* h) { return ctx(h).time; }

int notForPeripheries(const SimbobHost* h, int, double*, int) {
  if (ctx(h).misuse->empty()) *ctx(h).misuse = "read_sensor() is for controllers";
  return -1;
}
int noCommand(const SimbobHost* h, int, double) {
  if (ctx(h).misuse->empty()) *ctx(h).misuse = "set_command() is for controllers";
  return -1;
}

int hostMountPose(const SimbobHost* h, double position[3], double quaternion[4]) {
  const Transform f = mountFrame(ctx(h));
  for (int k = 0; k < 3; ++k) position[k] = f.p[static_cast<size_t>(k)];
  for (int k = 0; k < 4; ++k) quaternion[k] = f.q[static_cast<size_t>(k)];
  return 0;
}

int hostBodyVelocity(const SimbobHost* h, double linear[3], double angular[3]) {
  const MountContext& m = ctx(h);
  BodyState s;
  if (m.body >= 0) s = bodyState(*m.im, m.body);
  for (size_t k = 0; k < 3; ++k) {
    linear[k] = s.lin_vel[k];
    angular[k] = s.ang_vel[k];
  }
  return 0;
}

int hostBodyState(const SimbobHost* h, int ref, double* p, double* q, double* v, double* w) {
  MountContext& m = ctx(h);
  if (ref != -1) {
    if (m.misuse->empty())
      *m.misuse = "body_state(" + std::to_string(ref) + "): a sensor or actuator reads its own body: ref -1";
    return -1;
  }
  BodyState s;
  if (m.body >= 0) s = bodyState(*m.im, m.body);
  for (size_t k = 0; k < 3; ++k) {
    if (p) p[k] = s.pose.p[k];
    if (v) v[k] = s.lin_vel[k];
    if (w) w[k] = s.ang_vel[k];
  }
  for (size_t k = 0; k < 4 && q; ++k) q[k] = s.pose.q[k];
  return 0;
}

double hostCastRay(const SimbobHost* h, const double origin[3], const double direction[3], double max_length) {
  MountContext& m = ctx(h);
  const Vec3 d{direction[0], direction[1], direction[2]};
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(len > 0) || !std::isfinite(len) || !(max_length > 0) || !(max_length <= 1e6)) {
    if (m.misuse->empty())
      *m.misuse = "cast_ray(): the direction must be finite and not zero, max_length in (0, 1e6] m";
    return -1;
  }
  const Transform f = mountFrame(m);
  const Vec3 o = add(f.p, rotate(f.q, Vec3{origin[0], origin[1], origin[2]}));
  const Vec3 dir = rotate(f.q, Vec3{d[0] / len, d[1] / len, d[2] / len});
  dBodyID own = m.body >= 0 ? m.im->bodies[static_cast<size_t>(m.body)] : nullptr;
  gatherRayCandidates(*m.im, own, o, max_length);
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

/// Makes the instance; false after recording why.
bool createInstance(WorldImpl& im, const SimbobType& t, const std::vector<double>& numbers, const std::string& who,
                    const SourceLoc& loc, std::shared_ptr<void>* user) {
  if (!t.create) return true;
  std::array<char, SIMBOB_MESSAGE_SIZE> msg{};
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

}  // namespace

std::string sensorWho(const SensorDef& d) { return "sensor '" + d.key + "' (" + d.plugin_who + ")"; }

void createPluginSensor(WorldImpl& im, SensorState& s) {
  const std::string who = sensorWho(s.def);
  if (!createInstance(im, *s.def.plugin, s.def.numbers, who, s.def.loc, &s.user)) s.broken = true;
}

void readPluginSensor(WorldImpl& im, SensorState& s) {
  if (s.broken) return;
  std::string misuse;
  MountContext m{&im, s.def.body, s.def.pose, static_cast<double>(im.time_ns) * 1e-9, &misuse};
  const SimbobHost h = hostFor(&m);
  std::array<char, SIMBOB_MESSAGE_SIZE> msg{};
  const int n = static_cast<int>(s.reading.size());
  const int rc = s.def.plugin->read(s.user.get(), &h, m.time, s.reading.data(), n, msg.data());
  if (rc != 0) {
    fail(im, s.def.loc, sensorWho(s.def) + ": read() failed: " + messageOf(msg.data()));
    s.broken = true;
  } else if (!misuse.empty()) {
    fail(im, s.def.loc, sensorWho(s.def) + ": " + misuse);
    s.broken = true;
  }
}

void createPluginActuator(WorldImpl& im, ActuatorState& a) {
  const std::string who = "actuator '" + a.def.key + "' (" + a.def.plugin_who + ")";
  if (!createInstance(im, *a.def.plugin, a.def.numbers, who, a.def.loc, &a.user)) a.broken = true;
}

void applyPluginActuator(WorldImpl& im, ActuatorState& a, double h) {
  if (a.broken) return;
  std::string misuse;
  MountContext m{&im, a.def.body, a.def.pose, static_cast<double>(im.time_ns) * 1e-9, &misuse};
  const SimbobHost host = hostFor(&m);
  std::array<char, SIMBOB_MESSAGE_SIZE> msg{};
  double f[3] = {0, 0, 0}, tau[3] = {0, 0, 0};
  const int rc = a.def.plugin->apply(a.user.get(), &host, m.time, h, a.command, f, tau, msg.data());
  const std::string who = "actuator '" + a.def.key + "' (" + a.def.plugin_who + ")";
  if (rc != 0 || !misuse.empty()) {
    fail(im, a.def.loc, who + ": " + (rc != 0 ? "apply() failed: " + messageOf(msg.data()) : misuse));
    a.broken = true;
    return;
  }
  for (double v : {f[0], f[1], f[2], tau[0], tau[1], tau[2]})
    if (!std::isfinite(v)) {
      fail(im, a.def.loc, who + ": apply() gave a force or torque that is not finite");
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
