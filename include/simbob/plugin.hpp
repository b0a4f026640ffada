// C++ convenience over the C plug-in ABI (simbob/plugin_c.h, docs/plugins.md): a class per kind
// with a virtual method, a Host wrapping SimbobHost, and SIMBOB_PLUGIN, which defines the entry
// point. Header-only and independent of simbob's own headers and libraries: a plug-in built with
// it speaks only the C ABI, so any C++17 compiler will do. An exception thrown by a constructor
// or a method becomes the callback's error message (it never crosses into simbob).
//
//   class Beam : public simbob::plugin::Sensor {
//    public:
//     explicit Beam(const double* numbers) : max_(numbers[0]) {}
//     void read(simbob::plugin::Host& host, double t, double* out, int n) override { ... }
//   };
//   const SimbobNumber kBeamNumbers[] = {{"MaxRange", 5.0, "m", "farthest distance"}};
//   const char* const kBeamQuantities[] = {"distance"};
//   SIMBOB_PLUGIN("beam", simbob::plugin::sensor<Beam>("Beam", "one ray", kBeamNumbers, kBeamQuantities))
#pragma once

#include <cstddef>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "simbob/plugin_c.h"

namespace simbob::plugin {

/// The instance's view of simbob (SimbobHost); a failed call throws std::runtime_error-like
/// HostError, which the trampolines turn into the callback's error.
class HostError : public std::exception {
 public:
  explicit HostError(std::string what) : what_(std::move(what)) {}
  const char* what() const noexcept override { return what_.c_str(); }

 private:
  std::string what_;
};

class Host {
 public:
  explicit Host(const SimbobHost* h) : h_(h) {}
  double time() const { return h_->time(h_); }
  /// Controllers: the reading of the sensor behind ref `ref`.
  std::vector<double> readSensor(int ref) const {
    std::vector<double> out(16);
    int n = h_->read_sensor(h_, ref, out.data(), static_cast<int>(out.size()));
    if (n > static_cast<int>(out.size())) {
      out.resize(static_cast<size_t>(n));
      n = h_->read_sensor(h_, ref, out.data(), n);
    }
    if (n < 0) throw HostError("read_sensor(" + std::to_string(ref) + ") failed");
    out.resize(static_cast<size_t>(n));
    return out;
  }
  /// Controllers: commands the actuator behind ref `ref`.
  void setCommand(int ref, double value) const {
    if (h_->set_command(h_, ref, value) != 0) throw HostError("set_command(" + std::to_string(ref) + ") failed");
  }
  /// Sensors and actuators: the mount's global position and quaternion (w, x, y, z).
  void mountPose(double position[3], double quaternion[4]) const {
    if (h_->mount_pose(h_, position, quaternion) != 0) throw HostError("mount_pose() failed");
  }
  /// Sensors and actuators: their body's global linear and angular velocity.
  void bodyVelocity(double linear[3], double angular[3]) const {
    if (h_->body_velocity(h_, linear, angular) != 0) throw HostError("body_velocity() failed");
  }
  /// A body's global state (any pointer may be null): controllers the body behind ref `ref`
  /// (interface RCBody), sensors and actuators their own (ref -1).
  void bodyState(int ref, double position[3], double quaternion[4], double linear[3], double angular[3]) const {
    if (h_->body_state(h_, ref, position, quaternion, linear, angular) != 0)
      throw HostError("body_state(" + std::to_string(ref) + ") failed");
  }
  /// Sensors and actuators: distance along a ray in the mount frame, or -1 when nothing is hit.
  double castRay(const double origin[3], const double direction[3], double max_length) const {
    return h_->cast_ray(h_, origin, direction, max_length);
  }
  const SimbobHost* raw() const { return h_; }

 private:
  const SimbobHost* h_;
};

/// A controller: act() at 0, Period, 2 Period, ... Constructed from its numbers.
class Controller {
 public:
  virtual ~Controller() = default;
  virtual void act(Host& host, double t) = 0;
};

/// A sensor: read() writes the reading (n entries) when it is due.
class Sensor {
 public:
  virtual ~Sensor() = default;
  virtual void read(Host& host, double t, double* out, int n) = 0;
};

/// An actuator: apply() gives the force and torque (mount frame) for the next step.
class Actuator {
 public:
  virtual ~Actuator() = default;
  virtual void apply(Host& host, double t, double dt, double command, double force[3], double torque[3]) = 0;
};

/// An array of static storage (or nothing), as the C descriptions take it.
template <class E>
struct List {
  const E* data = nullptr;
  int count = 0;
  List() = default;
  template <size_t N>
  List(const E (&a)[N]) : data(a), count(static_cast<int>(N)) {}  // NOLINT(google-explicit-constructor)
};

namespace detail {

inline void copyMessage(const char* what, char* message) {
  std::strncpy(message, what, SIMBOB_MESSAGE_SIZE - 1);
  message[SIMBOB_MESSAGE_SIZE - 1] = '\0';
}

/// Runs f; 0, or 1 with the exception's text in message.
template <class F>
int guarded(char* message, F&& f) {
  try {
    f();
    return 0;
  } catch (const std::exception& e) {
    copyMessage(e.what(), message);
  } catch (...) {
    copyMessage("an exception that is not a std::exception", message);
  }
  return 1;
}

template <class T>
void* create(const double* numbers, char* message) {
  void* out = nullptr;
  guarded(message, [&] { out = new T(numbers); });
  return out;
}

template <class T>
void destroy(void* user) {
  delete static_cast<T*>(user);
}

template <class T>
SimbobType base(uint32_t kind, const char* name, const char* doc, List<SimbobNumber> numbers) {
  SimbobType t{};
  t.kind = kind;
  t.name = name;
  t.doc = doc;
  t.numbers = numbers.data;
  t.number_count = numbers.count;
  t.create = &create<T>;
  t.destroy = &destroy<T>;
  return t;
}

}  // namespace detail

/// A controller type whose instances are T (a Controller constructed from `const double*`).
template <class T>
SimbobType controller(const char* name, const char* doc, List<SimbobNumber> numbers, List<SimbobRef> refs) {
  SimbobType t = detail::base<T>(SIMBOB_CONTROLLER, name, doc, numbers);
  t.refs = refs.data;
  t.ref_count = refs.count;
  t.act = [](void* user, const SimbobHost* h, double time, char* message) {
    Host host(h);
    return detail::guarded(message, [&] { static_cast<T*>(user)->act(host, time); });
  };
  return t;
}

/// A sensor type whose instances are T (a Sensor); `interface` as SimbobType::interface.
template <class T>
SimbobType sensor(const char* name, const char* doc, List<SimbobNumber> numbers, List<const char*> quantities,
                  const char* interface = nullptr) {
  SimbobType t = detail::base<T>(SIMBOB_SENSOR, name, doc, numbers);
  t.quantities = quantities.data;
  t.quantity_count = quantities.count;
  t.interface = interface;
  t.read = [](void* user, const SimbobHost* h, double time, double* out, int n, char* message) {
    Host host(h);
    return detail::guarded(message, [&] { static_cast<T*>(user)->read(host, time, out, n); });
  };
  return t;
}

/// An actuator type whose instances are T (an Actuator); `interface` as SimbobType::interface.
template <class T>
SimbobType actuator(const char* name, const char* doc, List<SimbobNumber> numbers, const char* interface = nullptr) {
  SimbobType t = detail::base<T>(SIMBOB_ACTUATOR, name, doc, numbers);
  t.interface = interface;
  t.apply = [](void* user, const SimbobHost* h, double time, double dt, double command, double force[3],
               double torque[3], char* message) {
    Host host(h);
    return detail::guarded(message, [&] { static_cast<T*>(user)->apply(host, time, dt, command, force, torque); });
  };
  return t;
}

}  // namespace simbob::plugin

/// Defines the entry point simbob_plugin_v2 of a plug-in called NAME with the given types
/// (SimbobType values, e.g. from simbob::plugin::controller<T>(...)).
#define SIMBOB_PLUGIN(NAME, ...)                                                        \
  extern "C" const SimbobPlugin* simbob_plugin_v2(void) {                               \
    static const SimbobType types[] = {__VA_ARGS__};                                    \
    static const SimbobPlugin plugin{SIMBOB_PLUGIN_ABI_VERSION, NAME, types,            \
                                     static_cast<int>(sizeof types / sizeof types[0])}; \
    return &plugin;                                                                     \
  }
