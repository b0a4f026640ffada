// A plug-in's controller (simbob/plugin_c.h, docs/plugins.md): its instance is made from its
// numbers when the run's parties are, and its act() runs at 0, Period, 2 Period, ... with a
// SimbobHost that reads the sensors and commands the actuators its refs name
// (PluginControllerDef::refs). A failure -- create() returning NULL, act() returning nonzero, a host
// call with a ref out of range or of the wrong kind, or a World index out of range
// (World::misuse) -- stops the run with an error naming the controller, the plug-in and the
// type, where the controller is defined (exit 1, the trajectory so far kept).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "robot/controllers.h"
#include "simbob/physics.h"
#include "simbob/plugin_c.h"

namespace simbob::robot {

namespace {

class PluginController : public Party {
 public:
  explicit PluginController(const ControllerDef& c)
      : key_(c.key),
        loc_(c.loc),
        def_(c.as<PluginControllerDef>()),
        type_(*def_.plugin_type),
        tick_(def_.period),
        who_("plug-in '" + def_.plugin + "', type '" + def_.type + "'") {
    if (!type_.create) return;
    std::array<char, size_t{16} * SIMBOB_MESSAGE_SIZE> msg{};  // room to spare, as in onGrant
    user_ = type_.create(def_.numbers.data(), msg.data());
    if (!user_) fail("create() failed: " + messageOf(msg.data()));
  }
  ~PluginController() override {
    if (user_ && type_.destroy) type_.destroy(user_);
  }
  PluginController(const PluginController&) = delete;
  PluginController& operator=(const PluginController&) = delete;

  SimTime first() override { return 0; }  // a failed create() stops the run at t = 0
  SimTime onGrant(SimTime now, World& world) override {
    if (!error_.message.empty()) return kNever;
    world_ = &world;
    time_ = toSeconds(now);
    SimbobHost h{};
    h.size = sizeof(SimbobHost);
    h.context = this;
    h.time = [](const SimbobHost* host) {
      PluginController* c = self(host, "time()");
      return c ? c->time_ : -1.0;
    };
    h.read_sensor = [](const SimbobHost* host, int ref, double* out, int n) {
      PluginController* c = self(host, "read_sensor()");
      return c ? c->read(ref, out, n) : -1;
    };
    h.set_command = [](const SimbobHost* host, int ref, double v) {
      PluginController* c = self(host, "set_command()");
      return c ? c->command(ref, v) : -1;
    };
    h.mount_pose = [](const SimbobHost* host, double*, double*) { return misuse(host, "mount_pose()"); };
    h.body_velocity = [](const SimbobHost* host, double*, double*) { return misuse(host, "body_velocity()"); };
    h.body_state = [](const SimbobHost* host, int ref, double* p, double* q, double* v, double* w) {
      PluginController* c = self(host, "body_state()");
      return c ? c->bodyState(ref, p, q, v, w) : -1;
    };
    h.cast_ray = [](const SimbobHost* host, const double*, const double*, double) {
      return static_cast<double>(misuse(host, "cast_ray()"));
    };
    // Room to spare: a message written past SIMBOB_MESSAGE_SIZE is cut there, not written into
    // the stack. Only what messageOf reads is cleared.
    std::array<char, size_t{16} * SIMBOB_MESSAGE_SIZE> msg;  // NOLINT(cppcoreguidelines-pro-type-member-init)
    std::fill_n(msg.data(), SIMBOB_MESSAGE_SIZE, '\0');
    PluginController* const outer = tCurrent;
    tCurrent = this;
    const int rc = type_.act(user_, &h, time_, msg.data());
    tCurrent = outer;
    world_ = nullptr;
    if (rc != 0) fail("act() failed: " + messageOf(msg.data()));
    if (!world.misuse().empty()) fail(world.misuse());
    return error_.message.empty() ? tick_.next(now) : kNever;
  }
  const Error* failure() const override { return error_.message.empty() ? nullptr : &error_; }

 private:
  /// The controller whose act() runs now on this thread (null between calls): host calls are
  /// checked against it, so a NULL host or one kept from an earlier call is an error, not a crash.
  static thread_local PluginController* tCurrent;
  /// The controller behind `h`, or null after recording (on the running one) why there is none.
  static PluginController* self(const SimbobHost* h, const char* call) {
    if (!h) {
      if (tCurrent) tCurrent->fail(std::string(call) + ": the host is NULL: pass the SimbobHost the callback got");
      return nullptr;
    }
    if (!tCurrent || h->context != tCurrent) {
      if (tCurrent)
        tCurrent->fail(std::string(call) +
                       ": not the host of this callback (a host is valid only during the callback that got it)");
      return nullptr;
    }
    return tCurrent;
  }
  static int misuse(const SimbobHost* h, const char* call) {
    if (PluginController* c = self(h, call))
      c->fail(std::string(call) + " is for sensors and actuators, not controllers");
    return -1;
  }
  static std::string messageOf(const char* buf) {
    const size_t n = strnlen(buf, SIMBOB_MESSAGE_SIZE);
    return n ? std::string(buf, n) : std::string("(no message)");
  }
  /// The Model index behind ref `ref` if it is of the wanted kind (PluginControllerDef::ref_kind); -1
  /// after recording the misuse.
  int refIndex(const char* call, int ref, uint8_t kind) {
    const int count = static_cast<int>(def_.refs.size());
    if (ref < 0 || ref >= count) {
      fail(std::string(call) + "(" + std::to_string(ref) + "): there is no ref " + std::to_string(ref) +
           " (the type has " + std::to_string(count) + ")");
      return -1;
    }
    static const char* const kKinds[] = {"an actuator", "a sensor", "a body"};
    const uint8_t is = def_.ref_kind[static_cast<size_t>(ref)];
    if (is != kind) {
      fail(std::string(call) + "(" + std::to_string(ref) + "): ref " + std::to_string(ref) + " is " + kKinds[is] +
           ", not " + kKinds[kind]);
      return -1;
    }
    return def_.refs[static_cast<size_t>(ref)];
  }
  int read(int ref, double* out, int n) {
    const int i = refIndex("read_sensor", ref, 1);
    if (i < 0) return -1;
    const std::string call = "read_sensor(" + std::to_string(ref) + "): ";
    if (n < 0) {
      fail(call + "n is " + std::to_string(n) + ": it is the number of entries out has room for");
      return -1;
    }
    if (!out && n > 0) {
      fail(call + "out is NULL but n is " + std::to_string(n));
      return -1;
    }
    const std::vector<double>& r = world_->sensorReading(i);
    for (int k = 0; k < n && k < static_cast<int>(r.size()); ++k) out[k] = r[static_cast<size_t>(k)];
    return static_cast<int>(r.size());
  }
  int command(int ref, double value) {
    const int i = refIndex("set_command", ref, 0);
    if (i < 0) return -1;
    if (!std::isfinite(value)) {  // as Python's set_command: never clamped or taken as 0
      fail("set_command(" + std::to_string(ref) + "): the command is not finite (" +
           (std::isnan(value) ? "nan"
            : value > 0       ? "inf"
                              : "-inf") +
           ")");
      return -1;
    }
    world_->setCommand(i, value);
    return 0;
  }
  int bodyState(int ref, double* p, double* q, double* v, double* w) {
    const int i = refIndex("body_state", ref, 2);
    if (i < 0) return -1;
    const BodyState s = world_->body(i);
    copyBodyState(s, p, q, v, w);
    return 0;
  }
  void fail(const std::string& what) {
    if (error_.message.empty())
      error_ = {ErrorKind::ControllerFailed, loc_, "controller '" + key_ + "' (" + who_ + "): " + what};
  }

  const std::string key_;
  const SourceLoc loc_;
  const PluginControllerDef def_;  // a copy, so the party points into nothing of the Model
  const SimbobType& type_;
  Periodic tick_;
  std::string who_;
  void* user_ = nullptr;
  World* world_ = nullptr;
  double time_ = 0;
  Error error_;
};

thread_local PluginController* PluginController::tCurrent = nullptr;

}  // namespace

std::unique_ptr<Party> makePluginController(const ControllerDef& c) { return std::make_unique<PluginController>(c); }

}  // namespace simbob::robot
