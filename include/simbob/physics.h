// The physics layer: builds an ODE world from a compiled Model and steps it.
// This header exposes no ODE type; only lib/physics (its .cpp files and world_impl.h) includes <ode/ode.h>.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "simbob/model.h"

namespace simbob {

/// "ODE <configuration>" of the linked ODE (precision and build options), for run summaries.
std::string physicsVersion();

/// The ODE release simbob was built against: "0.16.2" (CMake requires 0.16.x; the broad phase
/// reproduces 0.16's pair order).
std::string odeVersion();

/// State of one mobile body, global frame.
struct BodyState {
  Transform pose;
  Vec3 lin_vel{0, 0, 0};
  Vec3 ang_vel{0, 0, 0};
};

/// Writes `s` into the plug-in ABI's body_state() arrays (include/simbob/plugin_c.h): p[3]
/// position, q[4] quaternion (w x y z), v[3] linear and w[3] angular velocity; a NULL array is
/// skipped. One copy for the host's sensor/actuator mounts and for plug-in controllers.
void copyBodyState(const BodyState& s, double* p, double* q, double* v, double* w);

/// State of one joint: the motion of its child body (JointDef::body2) relative to its parent
/// (JointDef::body1; -1 is the static world), measured about (hinge) or along (slider) the joint
/// axis (JointDef::axis, global at the start; it moves with the parent). Zero at the pose the
/// scene starts in.
/// - Hinge: rad and rad/s, positive by the right-hand rule about the axis; the position is the
///   total angle, unwrapped (ten turns read 20 pi, so wheel odometry works across turns): each
///   step adds the change since the step before, so a hinge must not turn half a turn (pi) or
///   more in one step.
/// - Slider: m and m/s, positive along the axis.
/// - BallSocket, Fixed: always 0, 0 (no single axis).
struct JointState {
  double position = 0.0;  ///< rad (hinge) or m (slider)
  double velocity = 0.0;  ///< rad/s (hinge) or m/s (slider)
};

/// What ODE reported while a World's calls into it ran: its messages (dMessage), such as Solver
/// Step's "LCP internal error, s <= 0" when it meets constraints it cannot solve exactly. ODE
/// prints them to stderr and goes on; simbob keeps them here instead, for the run to report
/// once. Never part of the physics: a message changes no state.
struct PhysicsMessages {
  uint64_t count = 0;
  std::string first;      ///< the first message, one line ("ODE message 3: LCP internal error, ...")
  double first_time = 0;  ///< s: the simulated time at the end of the step the first came in
};

struct WorldImpl;  // ODE handles; private to lib/physics (world_impl.h)

/// An ODE world built from a Model. Any number of Worlds may live in one process, created,
/// stepped and destroyed in any order and interleaving: each keeps its own state of ODE's
/// process-wide random generator (which QuickStep uses to reorder constraints) and swaps it in
/// around its calls into ODE, so a World gives the same bytes as it would alone in its process.
/// Worlds may be used from different threads, but their calls into ODE are serialised by one
/// process-wide lock (the generator is one variable): physics of different Worlds does not run
/// in parallel within a process; for parallel worlds use processes. One World must be used from
/// one thread at a time: a step that overlaps another step of the same World is refused (see
/// step), and other calls must not overlap a step.
class World {
 public:
  /// Validates nothing: the Model must come from compile(). `seed` is the starting state of
  /// this World's random generator (dRandSetSeed), which QuickStep uses to reorder constraints.
  /// `threads` (1 to kMaxThreads; more counts as kMaxThreads) is how many threads a step may
  /// use: with more than one, the narrow phase and the rays of range sensors and scanners are
  /// split among threads the World owns, and their results committed in the order one thread
  /// uses, so every state and reading is the same bits for every thread count
  /// (docs/performance.md). Never returns nullptr.
  static std::unique_ptr<World> create(const Model& model, uint32_t seed, int threads = 1);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Advance by h seconds: collide, add contacts per the material rules, step, clear contacts.
  /// Throws std::logic_error, doing nothing, when another thread is stepping this World at the
  /// same moment (a programming error: a World is used from one thread at a time); a step
  /// cannot be skipped silently, so this is an exception rather than a value to ignore.
  void step(double h);

  /// Mobile bodies, in Model::bodies order.
  int bodyCount() const;
  /// State of body i (0 <= i < bodyCount()) at its origin, global frame.
  BodyState body(int i) const;

  /// Joints, in Model::joints order.
  int jointCount() const;
  /// Index of the first ball or hinge joint whose anchor, seen from its two bodies, is more than
  /// `limit` m apart (the joint came apart: the solver could not hold it), or -1. *separation
  /// gets that distance.
  int firstBrokenJoint(double limit, double* separation) const;
  /// State of joint i (0 <= i < jointCount()); see JointState for units and signs.
  JointState joint(int i) const;

  /// Actuators, in Model::actuators order.
  int actuatorCount() const;
  /// Commands actuator i (0 <= i < actuatorCount()) from now on (see docs/scene-format.md, "Actuators"):
  /// Drive: voltage, clamped to [-1, 1]; Servo: target position (m or rad), clamped to
  /// [MinPos, MaxPos]; VelDrive: target velocity (m/s or rad/s), clamped to +-MaxVelocity.
  /// Before its first command a drive has voltage 0, a servo holds its start position (0,
  /// clamped to its limits) and a velocity drive is idle (applies nothing).
  void setCommand(int actuator, double value);
  /// The force (N) or torque (N m) drive i applied in the last step, in the joint's sense
  /// (0 for servos and velocity drives, whose force comes from the solver).
  double driveEffort(int actuator) const;
  /// The torque (N m) hinge i's stops (MinPos/MaxPos, URDF limits) applied in the last step: on
  /// the child about the joint's axis, in the joint's sense (positive pushes the position up); 0
  /// for a joint without hinge stops, and while the hinge is off them. For tests and diagnostics.
  double stopTorque(int joint) const;
  /// Actuator i's current command as recorded by setCommand (clamped), or its value before the
  /// first command (0; a servo's start position). For logs (`run --log commands`).
  double command(int actuator) const;
  /// How many commands setCommand clamped for actuator i (beyond [-1, 1], [MinPos, MaxPos] or
  /// +-MaxVelocity); *first gets the first of them as it was asked (if any).
  uint64_t clampedCommands(int actuator, double* first) const;

  /// Sensors of every kind, in Model::sensors order.
  int sensorCount() const;
  /// Whether sensor i (0 <= i < sensorCount()) touches another body now: one of its geoms
  /// overlaps (or meets) a geom of a body other than the one it is attached to and the bodies
  /// joined to that one by a joint, static geoms (ground, walls) included; other sensors are
  /// not seen. Computed from the poses the world is in -- when it is created and after every
  /// step -- so a controller granted at t reads the state at t. A sensor never pushes anything.
  /// False for sensors other than proximity sensors.
  bool touching(int sensor) const;
  /// Sensor i's reading: a fixed number of values named by sensorQuantities(i) (docs/sensors.md):
  /// touching (0 or 1); distance (m); range0..rangeN-1 (m); ax ay az (m/s^2) gx gy gz (rad/s);
  /// ticks. Computed on the step grid -- at creation and after each step, for a sensor with a
  /// Period only at the first step boundary at or after each multiple of it (held in between) --
  /// so the value at an instant does not depend on who asks or how often. Noise is drawn when
  /// the reading is computed, from the sensor's own generator (run seed and sensor key).
  /// Out of range: an empty vector (and misuse()).
  const std::vector<double>& sensorReading(int sensor) const;
  /// Names of sensor i's quantities, in reading order (sensorQuantities of its SensorDef).
  const std::vector<std::string>& sensorQuantities(int sensor) const;
  /// Index of the first body whose state is non-finite or beyond `limit` (m or m/s, rad/s),
  /// or -1 when all are fine.
  int firstBadBody(double limit = 1e6) const;

  /// Contact joints created by the last step (for tests and diagnostics).
  int lastContactCount() const;

  /// ODE's messages from this World's creation and steps so far (see PhysicsMessages).
  PhysicsMessages physicsMessages() const;

  /// The first call with an index out of range (setCommand(99999), joint(-1), ...), in words,
  /// or "": such a call does nothing (a read gives zeros) and is recorded here, so that the
  /// party that made it (a plug-in) fails the run with a message instead of a crash.
  const std::string& misuse() const;

  /// The first failure of a plug-in sensor or actuator (create() gave no instance, a callback
  /// returned nonzero, a host call was given an argument out of range), at the periphery's scene
  /// element; null when there is none. From then on that periphery is not called again; the run
  /// stops with this error.
  const Error* failure() const;

 private:
  World();
  std::unique_ptr<WorldImpl> impl_;
};

}  // namespace simbob
