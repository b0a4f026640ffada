// Private to lib/physics: the ODE handles behind a World and the functions that build and step
// it, one file per concern. World::create calls them in a fixed order; that order is the order
// of ODE calls, which is part of reproducibility (golden trajectories, bench/bare_ode.cpp).
//
//   bodies.cpp    mobile bodies, centre-of-mass offset, body state
//   geoms.cpp     the collision space, geoms and their contact data
//   broadphase.cpp  the default hash space's candidate pairs, in dHashSpace's order (faster)
//   joints.cpp    joints and joint state (simbob's sign convention)
//   contacts.cpp  the near callback: contact joints per the material rules of guide 7.1; the
//                 narrow phase in parallel (--threads), joints committed in the pair order
//   cylinder_caps.cpp  dCollide, with simbob's own contacts for flat cylinder caps on boxes and caps
//   workers.cpp   WorkerPool: the World's threads beyond the stepping one (--threads)
//   actuators.cpp drives, servos and velocity drives on hinge and slider joints
//   sensors.cpp   sensors: their readings on the step grid; proximity sensors (sensor geoms, in a
//                 space of their own, that only detect) and encoders
//   rays.cpp      range sensors and laser scanners: ODE rays cast against the collision space
//   imu.cpp       inertial measurement units: specific force and angular velocity
//   sensor_noise.cpp  each sensor's own random generator (run seed and sensor key)
//   plugin_peripheries.cpp  plug-in sensors and actuators (simbob/plugin_c.h) and World::failure
//   world.cpp     World: create, step, accessors
//   version.cpp   physicsVersion(): ODE's version and configuration, for run summaries
//
// Actuators and sensors join as files of their own: a create function called by World::create
// after createJoints, which may append to WorldImpl::beforeStep what it must do every step.
#pragma once

#include <ode/ode.h>

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "simbob/physics.h"
#include "broadphase.h"
#include "parallel_test_hooks.h"
#include "sensor_noise.h"
#include "workers.h"

namespace simbob {

static_assert(sizeof(dReal) == sizeof(double), "simbob needs ODE built in double precision");

/// Contact-relevant data of one geom, looked up by the index stored with dGeomSetData.
struct GeomInfo {
  double friction;      ///< Coulomb coefficient mu
  double bounceness;    ///< restitution in [0,1]
  double minBounceVel;  ///< m/s
  bool sensor;          ///< creates no contact joints
  int staticBody;       ///< a static geom: the static body it belongs to (GeomDef::static_body), else -1
  int group;            ///< GeomDef::group: >= 0, no contacts within it
  int surface = -1;     ///< WorldImpl::surfaces index: its material's Gazebo surface (MaterialDef::surface), -1: none
};

/// What a hinge keeps to read its angle as ODE does (hinge_angle.cpp): its bodies in ODE's order,
/// their relative rotation when the axis was set and the axis in body0's frame.
struct HingeFrame {
  dBodyID body0 = nullptr, body1 = nullptr;
  dQuaternion q_initial{1, 0, 0, 0};
  dVector3 axis1{1, 0, 0, 0};
  bool reverse = false;  ///< ODE's dJOINT_REVERSE: attached with a null first body
};

/// What joint state needs beyond the ODE joint: its kind and ODE's reading at the start pose.
struct JointInfo {
  JointKind kind;
  double zero;         ///< ODE's position (rad or m) at creation, subtracted so that the start pose reads 0
  double total = 0.0;  ///< Hinge: the angle unwrapped (rad): the sum of the per-step changes
  double last = 0.0;   ///< Hinge: the wrapped angle (rad) when total was last updated
  /// The sense of ODE's motor and stops against simbob's (ActuatorState::motor_sign).
  double motor_sign = -1.0;
  HingeFrame hinge{};  ///< Hinge: how its angle is read (hinge_angle.cpp)
  /// Hinge with a stop: the angular motor in user mode that carries its stops (joints.cpp,
  /// setHingeStops), given simbob's own reading of the angle before every step; null otherwise.
  dJointID stops = nullptr;
  /// Where ODE records the force of `stops` after every step (World::stopTorque); null without.
  std::unique_ptr<dJointFeedback> stopFeedback{};
};

/// A sensor: its definition, its reading and what computing the next one needs (World::sensorReading).
struct SensorState {
  SensorState(const SensorDef& d, uint32_t seed) : def(d), quantities(sensorQuantities(d)), noise(seed, d.key) {}
  SensorDef def;
  std::vector<std::string> quantities;  ///< names of the reading's entries (sensorQuantities)
  std::vector<double> reading;          ///< the held reading, quantities.size() entries
  SensorNoise noise;                    ///< drawn only when the reading is computed
  int64_t period_ns = 0;                ///< 0: every step
  int64_t last_slot = -1;               ///< the period index (time / period) of the last update
  std::vector<dGeomID> geoms;           ///< Proximity: in WorldImpl::sensorSpace, never in the collision space
  bool touching = false;                ///< Proximity: one of its geoms touched another body at the last update
  std::vector<Vec3> ray_dirs;           ///< Scanner: each ray's direction in the sensor frame (crSin, crCos: set once)
  Vec3 prev_vel{0, 0, 0};               ///< Imu: global velocity of the sensor point after the previous step
  bool has_prev = false;                ///< Imu: prev_vel is set (false at creation)
  std::shared_ptr<void> user;           ///< Plugin: its instance (destroyed by the plug-in's destroy())
  bool broken = false;                  ///< Plugin: it failed (World::failure); never called again
};

/// An actuator's definition and its current command (see World::setCommand).
struct ActuatorState {
  ActuatorDef def;
  double command = 0.0;  ///< voltage, target position or target velocity (clamped)
  bool commanded = false;
  double effort = 0.0;  ///< Drive: force or torque applied in the last step (simbob's sense)
  /// The sense of ODE's motor and stops against simbob's: -1, or +1 for a hinge whose parent is
  /// the world (ODE swaps its bodies and flips its readings but not its motor and stops).
  double motor_sign = -1.0;
  uint64_t clamped = 0;        ///< commands beyond the actuator's limits (clamped), for a notice
  double first_clamped = 0;    ///< the first of them, as asked
  std::shared_ptr<void> user;  ///< Plugin: its instance (destroyed by the plug-in's destroy())
  bool broken = false;         ///< Plugin: it failed (World::failure); never called again
};

/// The narrow phase's buffers with more than one thread (contacts.cpp), kept from step to step.
struct NarrowPhase {
  std::vector<std::pair<dGeomID, dGeomID>> pairs;  ///< this step's pairs, in the broad phase's order
  std::vector<int> counts;                         ///< contacts of each pair; -1: collided when committed
  std::vector<std::vector<dContactGeom>> buffers;  ///< each chunk's contacts, in its pairs' order
  std::vector<const dContactGeom*> first;          ///< each pair's first contact in its chunk's buffer
};

/// A geom rays may hit, as read before the sensors' rays are cast in parallel (rays.cpp).
struct RayTarget {
  dGeomID geom;
  dBodyID body;
  dReal aabb[6];
};

/// Range sensors' and scanners' buffers with more than one thread (rays.cpp).
struct RayScene {
  dGeomID cleaner = nullptr;                              ///< collides with nothing: cleans the space
  std::vector<RayTarget> targets;                         ///< the collision space's geoms, in list order
  std::vector<dGeomID> rays;                              ///< one ray per thread (dGeomRaySet writes it)
  std::vector<std::vector<const RayTarget*>> candidates;  ///< per thread: a sensor's candidates
  std::vector<SensorState*> due;                          ///< this update's ray sensors, in Model order
};

/// Pairs per chunk at least: fewer are not worth waking a thread for. A box-box dCollide takes
/// a microsecond or two, a sphere-plane a tenth of that, a wake-up and sleep of a worker tens of
/// microseconds of CPU: with 32 the 100-robot scanner scene (300 cheap pairs a step) spent 6 %
/// more CPU on 2 threads than on one; with 256 it collides inline and a 1,000-box pile still
/// splits its thousands of pairs.
constexpr size_t kPairGrain = 256;
/// Boxes per chunk of the broad phase's sweep at least: a box's sweep is a few box tests.
constexpr size_t kSweepGrain = 256;
/// Ray sensors per chunk at least.
constexpr size_t kRaySensorGrain = 2;

struct WorldImpl {
  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  /// Sensor geoms live here, so the collision space (and the order in which it reports pairs)
  /// is the same with or without sensors. Created with the first sensor geom.
  dSpaceID sensorSpace = nullptr;
  dJointGroupID contactGroup = nullptr;
  std::vector<dBodyID> bodies;
  std::vector<Vec3> com;  ///< centre of mass in the body frame, per body (m)
  std::vector<dGeomID> geoms;
  std::vector<GeomInfo> geomInfo;
  /// The meshes the geoms use (ODE keeps pointers into their hulls' and triangles' arrays, never
  /// copies), held as long as the World, and one triangle-mesh data per Model::meshes entry that
  /// a TriMesh geom uses (built on first use, destroyed after the geoms).
  std::vector<std::shared_ptr<const MeshData>> meshes;
  std::vector<dTriMeshDataID> triMeshData;
  /// A hull whose mesh frame origin lies outside it, moved for ODE (geoms.cpp), per mesh.
  struct OdeHull {
    std::vector<double> planes, points;
    Vec3 shift{0, 0, 0};  ///< the mean of its vertices in the mesh frame: the moved hull's origin
  };
  std::vector<OdeHull> odeHulls;
  std::vector<dJointID> joints;
  std::vector<JointInfo> jointInfo;
  std::vector<size_t> stopJoints;  ///< hinges whose stops a motor carries (JointInfo::stops), in creation order
  std::vector<ActuatorState> actuators;
  std::vector<SensorState> sensors;
  HashSpacePairs hashPairs;            ///< broadphase.h: the default space's pairs, faster
  dGeomID ray = nullptr;               ///< rays.cpp: the one ray of range sensors and scanners, in no space
  dGeomID rayReach = nullptr;          ///< rays.cpp: a box about a sensor's reach, in no space
  std::vector<dGeomID> rayCandidates;  ///< rays.cpp: the geoms within a sensor's reach
  /// Per static body (GeomDef::static_body): the mobile bodies joined to it, which the rays of a
  /// sensor mounted on it do not see (joints.cpp).
  std::vector<std::vector<dBodyID>> staticJoined;
  Vec3 gravity{0, 0, 0};                ///< m/s^2 (imu.cpp: specific force = acceleration - gravity)
  int64_t time_ns = 0;                  ///< simulated time: the sum of the steps taken (ns)
  std::vector<dContact> contactBuffer;  ///< sized max_contacts once; reused by every collision
  std::vector<MaterialDef> surfaces;    ///< contacts.cpp: the materials with a Gazebo surface (GeomInfo::surface)
  double stepSize = 0;                  ///< s, the step under way (contacts.cpp: a surface's kp and kd as ERP and CFM)
  int lastContacts = 0;
  bool quickstep = true;
  /// This World's state of ODE's random generator, swapped in around every call into ODE
  /// (world.cpp, OdeSection): starts at the seed, advanced by QuickStep's draws.
  unsigned long rng = 0;
  /// Set while a thread is in World::step; a second thread is refused meanwhile.
  std::atomic<bool> stepping{false};
  /// The first call of World with an index out of range, in words (World::misuse).
  std::string misuse;
  /// The first failure of a plug-in sensor or actuator, or ODE's error (World::failure).
  Error failure;
  /// ODE reported an error or a failed internal check in this World (world.cpp, odeFatal): its
  /// objects may be half updated, so it is never stepped again.
  bool odeFailed = false;
  /// Tests only: the step (1-based) at whose start ODE is made to fail (SIMBOB_TEST_ODE_FAULT_AT_STEP,
  /// world.cpp); 0: never.
  uint64_t faultStep = 0;
  uint64_t stepsTaken = 0;
  /// ODE's messages while this World held the ODE section (World::physicsMessages); written by
  /// ODE's message handler, on whichever of the World's threads ODE calls it, under the lock.
  PhysicsMessages messages;
  bool firstMessageInStep = false;  ///< the first message came in the step under way: its time is its end
  mutable std::mutex messagesMutex;
  /// The threads beyond the stepping one (--threads N > 1); null with one thread, when the
  /// narrow phase and the sensors run as they always have.
  std::unique_ptr<WorkerPool> pool;
  NarrowPhase narrow;  ///< contacts.cpp, with a pool
  RayScene rayScene;   ///< rays.cpp, with a pool
  /// Run in order at the start of every step (before collision) with the step size in s: where
  /// motors, applied forces and sensors that act every step hook in. Empty today.
  std::vector<std::function<void(WorldImpl&, double)>> beforeStep;

  WorldImpl() = default;
  WorldImpl(const WorldImpl&) = delete;
  WorldImpl& operator=(const WorldImpl&) = delete;
  ~WorldImpl();
};

// world.cpp
/// The process-wide lock held by every call into ODE that touches its global state (its random
/// generator, initialisation): World's create, step and destruction, physicsVersion.
std::mutex& odeMutex();

// bodies.cpp
/// Creates one ODE body per Model body, in Model order, at its centre of mass.
void createBodies(WorldImpl& im, const Model& model);
/// Body i's state at its origin (not ODE's centre-of-mass frame).
BodyState bodyState(const WorldImpl& im, int i);

// geoms.cpp
/// The collision space chosen by the scene (SceneSettings Space, --space).
dSpaceID createSpace(const Model& model);
/// Creates one ODE geom per Model geom, in Model order, with its contact data.
void createGeoms(WorldImpl& im, const Model& model);

// joints.cpp
/// Creates one ODE joint per Model joint, in Model order, and records its zero position.
void createJoints(WorldImpl& im, const Model& model);
/// joints.cpp: stops, friction, damping and mimics of the joints that have them (URDF joints).
void createJointDynamics(WorldImpl& im, const Model& model);
/// Joint i's state in simbob's convention (see World::joint): a hinge's total angle, unwrapped.
JointState jointState(const WorldImpl& im, int i);
/// The same with a hinge's angle wrapped into [-pi, pi], as dJointGetHingeAngle reads it (the
/// actuators' input: servos work on it, as they always have; stops see the unwrapped total).
JointState wrappedJointState(const WorldImpl& im, int i);
/// Joint i's velocity alone (rad/s or m/s), simbob's sign: what a drive needs, without the
/// angle's reading.
double jointVelocity(const WorldImpl& im, int i);
/// Adds each hinge's change of angle over the last step to its total (after every step; a hinge
/// must turn less than half a turn per step).
void updateJointTotals(WorldImpl& im);
/// Sets hinge joint i's stops, in ODE's motor frame (see createJointDynamics) and unwrapped: a
/// stop may lie beyond +-pi (URDF limits such as +-6.25 rad). -inf / inf: none on that side.
void setHingeStops(WorldImpl& im, size_t i, double lo, double hi);
/// Hands every hinge's stop motor the hinge's current angle (before every step).
void updateHingeStops(WorldImpl& im);
/// The torque (N m) hinge i's stops applied in the last step, on its child about its axis in
/// simbob's sense; 0 without stops (World::stopTorque).
double stopTorque(const WorldImpl& im, int i);
/// Distance (m) between where joint i's anchor is on its first and on its second body; 0 for
/// joints without a shared anchor (slider, fixed).
double jointSeparation(const WorldImpl& im, int i);

// hinge_angle.cpp
HingeFrame hingeFrame(dJointID j, const Vec3& axis);
/// dJointGetHingeAngle's reading, computed as ODE does but with the correctly rounded crAtan2.
double hingeAngle(const HingeFrame& f);
/// The same before ODE's sign flip for a reversed joint: the angle ODE's own stops test.
double hingeAngleInternal(const HingeFrame& f);

// actuators.cpp
/// Sets each actuator's stops and appends the per-step drive action to beforeStep.
void createActuators(WorldImpl& im, const Model& model);
/// Records a command (clamped as World::setCommand says); the next step acts on it.
void commandActuator(WorldImpl& im, int i, double value);

// sensors.cpp
/// Builds each Model sensor's state (noise seeded from `seed` and its key) and its first reading.
void createSensors(WorldImpl& im, const Model& model, uint32_t seed);
/// Recomputes the readings of the sensors due at im.time_ns from the current poses (after each
/// step of `h` s; h = 0 at creation).
void updateSensors(WorldImpl& im, double h);
/// The sensor's frame, global (its body's origin frame composed with SensorDef::pose).
Transform sensorFrame(const WorldImpl& im, const SensorDef& d);

// rays.cpp
/// Collects in im.rayCandidates the geoms of the collision space whose bounding boxes meet the
/// cube of half side `reach` about `origin` and that belong neither to the sensor's own body nor
/// to a body joined to it -- mobile body `body`, or for a static mount (body -1) static body
/// `static_body` (GeomDef::static_body) -- : every geom a ray of length <= reach from `origin`
/// can hit.
void gatherRayCandidates(WorldImpl& im, int body, int static_body, const Vec3& origin, double reach);
/// Distance (m) along the ray from `origin` in unit direction `dir` to the nearest of
/// im.rayCandidates (gathered for this origin and a reach >= `length`), or +infinity when
/// nothing is hit within `length`.
double castRay(WorldImpl& im, const Vec3& origin, const Vec3& dir, double length);
/// Range sensor and laser scanner readings (SensorKind::Range, Scanner) into s.reading.
void readRays(WorldImpl& im, SensorState& s);
/// readRays of every sensor in `due`, split among im.pool's threads: the same readings.
void readRaysInParallel(WorldImpl& im, const std::vector<SensorState*>& due);

// imu.cpp
/// Tracks the sensor point's velocity every step of `h` s and, when `due`, writes the reading.
void readImu(WorldImpl& im, SensorState& s, double h, bool due);

// plugin_peripheries.cpp
/// Makes a plug-in sensor's or actuator's instance (a failure goes to WorldImpl::failure).
void createPluginSensor(WorldImpl& im, SensorState& s);
void createPluginActuator(WorldImpl& im, ActuatorState& a);
/// A plug-in sensor's reading into s.reading (when due).
void readPluginSensor(WorldImpl& im, SensorState& s);
/// A plug-in actuator's force and torque on its body for the next step of h s.
void applyPluginActuator(WorldImpl& im, ActuatorState& a, double h);

// cylinder_caps.cpp
/// dCollide(g1, g2, most, out, stride), except that a cylinder's cap against a box face or against
/// another cylinder's cap (axes within 25.8 degrees) gets simbob's own contacts, each point with
/// its own depth. Reads only the two geoms (a worker thread may call it).
int collideGeoms(dGeomID g1, dGeomID g2, int most, dContactGeom* out, int stride);

// contacts.cpp
/// Collides the space and creates this step's contact joints (guide 7.1); counts them in lastContacts.
void collide(WorldImpl& im);
/// Whether dCollide with geom g reads only the two geoms (ODE keeps no shared cache for its
/// class), so that it may run on a worker thread: see contacts.cpp.
bool statelessCollider(dGeomID g);

}  // namespace simbob
