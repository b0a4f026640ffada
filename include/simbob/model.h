// The compiled model: plain data, every reference resolved, every value validated.
// The compile step (lib/compile, lib/components) produces it from the component graph; the physics
// layer (lib/physics) is the only consumer that talks to ODE. Nothing here includes ODE.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "simbob/error.h"
#include "simbob/frames.h"
#include "simbob/mesh.h"
#include "simbob/visuals.h"

struct SimbobType;  // simbob/plugin_c.h: a plug-in's type

namespace simbob {

/// Contact properties of one material (guide 6.7.1, combined per 7.1).
struct MaterialDef {
  std::string key;              ///< fully qualified key ("" for the default material)
  double friction = 0.5;        ///< Coulomb coefficient mu (dimensionless)
  double bounceness = 0.0;      ///< restitution in [0,1]
  double min_bounce_vel = 0.1;  ///< m/s; slower impacts do not bounce
  /// Gazebo classic's contact surface (a URDF link's <gazebo reference> tags, docs/urdf.md
  /// "Surfaces"); the defaults leave a contact as guide 7.1 makes it.
  bool gazebo = false;    ///< friction combines as Gazebo classic's (the smaller of the pair's, per direction)
  double friction2 = -1;  ///< friction along the second direction (mu2); < 0: `friction`
  Vec3 fdir1{0, 0, 0};    ///< first friction direction in the geom's frame; 0: ODE's choice
  double kp = 0;          ///< N/m contact stiffness; 0: the settings' ERP and CFM
  double kd = 0;          ///< N s/m contact damping (with kp)
  double min_depth = -1;  ///< m of penetration left alone; < 0: none
  double max_vel = -1;    ///< m/s largest push-out velocity; < 0: unbounded
  int max_contacts = 0;   ///< most contacts with any other geom; 0: the settings' MaxContacts
  /// Whether any Gazebo surface value is set (contacts then take Gazebo classic's rules).
  bool surface() const {
    return gazebo || friction2 >= 0 || fdir1 != Vec3{0, 0, 0} || kp > 0 || min_depth >= 0 || max_vel >= 0 ||
           max_contacts > 0;
  }
};

/// A mobile rigid body. Static bodies have no entry: their geoms are world geoms.
struct BodyDef {
  std::string key;  ///< fully qualified key, written to the trajectory
  SourceLoc loc;
  Transform pose;                           ///< initial pose, global (m, unit quaternion)
  Vec3 lin_vel{0, 0, 0};                    ///< m/s, global
  Vec3 ang_vel{0, 0, 0};                    ///< rad/s, global
  double mass = 1.0;                        ///< kg, > 0
  Vec3 com{0, 0, 0};                        ///< centre of mass in the body frame, m (offset geoms move it)
  Mat3 inertia{1, 0, 0, 0, 1, 0, 0, 0, 1};  ///< kg m^2 about the centre of mass, body axes
  bool gravity = true;                      ///< false: gravity does not act on it (a URDF link's <gravity>)
  /// Where an imported file writes this body's moment of inertia (a URDF link's <inertia>), for
  /// advice that names it; empty for a body of the scene format.
  SourceLoc inertia_loc;
};

enum class GeomShape : uint8_t {
  Box,         ///< size = full extents along local x, y, z (m)
  Sphere,      ///< size[0] = radius (m)
  Cylinder,    ///< size[0] = radius, size[1] = length along local Z (m)
  Capsule,     ///< size[0] = radius, size[1] = length of the cylindrical part along local Z (m)
  Plane,       ///< static only: plane = (nx, ny, nz, d), points p with n.p = d, n unit
  ConvexHull,  ///< the hull of Model::meshes[mesh] (MeshData::hull, a dGeomConvex); size unused
  TriMesh,     ///< the triangles of Model::meshes[mesh] (a dGeomTriMesh); size unused
};

/// A mesh that geoms and visuals use (simbob/mesh.h), loaded once per file, scale and up axis.
struct MeshDef {
  std::shared_ptr<const MeshData> data;  ///< never null in a compiled Model
  SourceLoc loc;                         ///< where it was first asked for (a scene or URDF line)
};

struct GeomDef {
  std::string key;  ///< qualified key of the owning body (for messages)
  GeomShape shape = GeomShape::Box;
  int body = -1;                            ///< index into Model::bodies; -1 = static (world) geom
  int static_body = -1;                     ///< body == -1: the static body it belongs to (its number)
  Transform offset;                         ///< relative to the body frame, or global when body == -1
  Vec3 size{0, 0, 0};                       ///< see GeomShape
  std::array<double, 4> plane{0, 1, 0, 0};  ///< Plane only, global
  int material = 0;                         ///< index into Model::materials
  bool sensor = false;                      ///< detects contacts but creates no contact joints
  int mesh = -1;                            ///< ConvexHull, TriMesh: index into Model::meshes
  int group = -1;                           ///< >= 0: never collides with its group (one URDF robot's links)
  SourceLoc loc;                            ///< where the geom is written (line 0: not known), for messages
};

enum class JointKind : uint8_t { BallSocket, Hinge, Slider, Fixed };

struct JointDef {
  std::string key;  ///< fully qualified key
  SourceLoc loc;
  JointKind kind = JointKind::BallSocket;
  int body1 = -1;        ///< parent body index, -1 = the static world
  int body2 = -1;        ///< child body index, -1 = the static world (not both -1)
  int static_body = -1;  ///< body1 or body2 == -1: the static body it joins (GeomDef::static_body), if known
  Vec3 anchor{0, 0, 0};  ///< global, m (BallSocket, Hinge)
  Vec3 axis{0, 0, 1};    ///< global unit vector (Hinge, Slider)
  // What a URDF joint adds (docs/urdf.md); the defaults leave a joint as the scene format makes it.
  double lo_stop = -std::numeric_limits<double>::infinity();  ///< Hinge, Slider: m or rad (JointState); -inf: none
  double hi_stop = std::numeric_limits<double>::infinity();   ///< Hinge, Slider: m or rad; inf: none
  double damping = 0.0;           ///< Hinge, Slider: N s/m or N m s/rad, a force against the joint's velocity
  double friction = 0.0;          ///< Hinge, Slider: N or N m, Coulomb friction (the most it resists with)
  int mimic = -1;                 ///< Model::joints index this joint follows: q = multiplier q_leader + offset
  double mimic_multiplier = 1.0;  ///< dimensionless (m/rad or rad/m across kinds)
  double mimic_offset = 0.0;      ///< m or rad
  double mimic_max_force = std::numeric_limits<double>::infinity();  ///< N or N m that holds the mimic
};

/// An extra trajectory row: a frame fixed to a body (a URDF link lumped into another link's
/// body keeps a row of its own, docs/urdf.md). Rows of frames follow the bodies' rows.
struct FrameDef {
  std::string key;   ///< fully qualified key, written to the trajectory
  int body = -1;     ///< Model::bodies index; -1 = fixed in the world
  Transform offset;  ///< relative to the body frame (global when body == -1)
};

/// What an importer (RCImportURDF) built, for `simbob check` to report (docs/urdf.md).
struct ImportReport {
  std::string key;           ///< the import's fully qualified key
  SourceLoc loc;             ///< the imported file
  std::string text;          ///< the summary, one line ("8 links, 6 revolute joints, ...")
  std::vector<Error> notes;  ///< what it ignored, lumped or approximated, once each, at its line
};

/// A drive on a hinge or slider joint (guide 6.11.1-6.11.3). Positions and velocities are the
/// joint's (JointState: the child relative to the parent, zero at the start pose).
struct ActuatorDef {
  std::string key;  ///< fully qualified key of the periphery
  SourceLoc loc;
  enum Kind : uint8_t {
    Drive,     ///< RCGenericDrive: command = voltage in [-1, 1] (RCDriver)
    Servo,     ///< RCGenericServo: command = target position, m or rad (RCPosControl)
    VelDrive,  ///< RCGenericVelControlledDrive: command = target velocity, m/s or rad/s (RCVelControl)
    Plugin,    ///< a plug-in's actuator type: command = whatever it says; a force and torque on `body`
    Effort,    ///< a URDF effort drive: command = force or torque (N or N m), clamped to +-max_power (RCDriver)
  } kind = Drive;
  int joint = -1;             ///< index into Model::joints (hinge or slider); -1 for Plugin
  double max_power = 10.0;    ///< N or N m, largest force or torque
  double max_velocity = 1.0;  ///< m/s or rad/s
  double min_pos = -std::numeric_limits<double>::infinity();  ///< m or rad; -inf: no stop
  double max_pos = std::numeric_limits<double>::infinity();   ///< m or rad; inf: no stop
  double stall = 0.8;                                         ///< Drive: power fades above stall * max_velocity
  double smooth = 1.0;                                        ///< Servo: s, time constant of the final approach
  // Plugin only:
  int body = -1;                       ///< index into Model::bodies it pushes; -1 = static (pushes nothing)
  int static_body = -1;                ///< body == -1: the static body it is mounted on (GeomDef::static_body)
  Transform pose;                      ///< its mount relative to the body's frame (global if body == -1)
  const SimbobType* plugin = nullptr;  ///< the plug-in's type (simbob/plugin_c.h)
  std::vector<double> numbers;         ///< its number parameters, in the order the type declares them
  std::string plugin_who;              ///< "plug-in 'p', type 'T'", for messages
};

/// What a sensor measures; see SensorDef and docs/sensors.md for each kind's reading.
enum class SensorKind : uint8_t {
  Proximity,  ///< RCProximitySensor: `touching` (0 or 1)
  Range,      ///< RCRangeSensor: `distance` (m) along one ray
  Scanner,    ///< RCLaserScanner: `range0` .. `range<Rays-1>` (m)
  Imu,        ///< RCImuSensor: `ax ay az` (m/s^2, specific force) `gx gy gz` (rad/s), sensor frame
  Encoder,    ///< RCEncoder: `ticks` on a hinge
  Plugin,     ///< a plug-in's sensor type: the quantities it declares (simbob/plugin_c.h)
};

/// A sensor (guide 6.11.4 and simbob's own sensors). Every sensor has a reading: a fixed-length
/// vector of doubles whose quantities sensorQuantities() names (World::sensorReading).
/// - Proximity (RCContactSensor): its geoms (GeomDef::sensor) report whether they touch another
///   body and never push (no contact joints). See World::touching.
/// - Range: one ray from the sensor's origin along its local -Z (the way cameras look).
/// - Scanner: `rays` rays in the sensor's local X-Z plane, see docs/sensors.md for the order.
/// - Imu: specific force and angular velocity in the sensor frame (Y up when upright).
/// - Encoder: integer ticks of the total (unwrapped) angle of a hinge.
struct SensorDef {
  std::string key;  ///< fully qualified key of the periphery
  SourceLoc loc;
  SensorKind kind = SensorKind::Proximity;
  int body = -1;           ///< index into Model::bodies it is attached to; -1 = static (fixed in the world)
  int static_body = -1;    ///< body == -1: the static body it is mounted on (GeomDef::static_body): rays skip its geoms
  std::vector<int> geoms;  ///< Proximity: indices into Model::geoms, each with sensor = true
  Transform pose;          ///< Range, Scanner, Imu: sensor frame relative to the body's frame (global if body == -1)
  double period = 0.0;     ///< s; > 0: the reading updates only at the grid instants at or after multiples of it
  double min_range = 0.0;  ///< m (Range, Scanner): hits closer than this read min_range
  double max_range = 5.0;  ///< m (Range, Scanner): the reading when nothing is hit
  double noise = 0.0;      ///< standard deviation: m (Range, Scanner), m/s^2 (Imu accelerometer)
  double resolution = 0.0;              ///< Range, Scanner: quantisation step (m, 0 = none); Encoder: ticks per turn
  int rays = 1;                         ///< Scanner: number of rays (>= 1)
  double field_of_view = 180.0;         ///< Scanner: degrees, (0, 360]
  double gyro_noise = 0.0;              ///< Imu: standard deviation of the gyro (rad/s)
  Vec3 accel_bias{0, 0, 0};             ///< Imu: constant accelerometer bias (m/s^2, sensor frame)
  Vec3 gyro_bias{0, 0, 0};              ///< Imu: constant gyro bias (rad/s, sensor frame)
  int joint = -1;                       ///< Encoder: index into Model::joints (a hinge)
  const SimbobType* plugin = nullptr;   ///< Plugin: the plug-in's type (simbob/plugin_c.h)
  std::vector<double> numbers;          ///< Plugin: its number parameters, in declaration order
  std::vector<std::string> quantities;  ///< Plugin: the names of its reading's entries
  std::string plugin_who;               ///< Plugin: "plug-in 'p', type 'T'", for messages
};

/// Scanner: the angle (rad) of ray k (0 <= k < rays) about the sensor's local +Y, from its -Z,
/// positive towards -X (counterclockwise seen from above, to the left of an upright sensor):
/// -FOV/2 + k FOV/(rays-1) (both edges; 0 for one ray), or -pi + k 2pi/rays for a full circle.
/// The ray's direction in the sensor frame is (-sin a, 0, -cos a).
inline double scannerRayAngle(const SensorDef& s, int k) {
  const double pi = 3.14159265358979323846;
  if (s.field_of_view >= 360) return -pi + k * (2 * pi / s.rays);
  if (s.rays <= 1) return 0.0;
  const double fov = s.field_of_view * pi / 180;
  return -fov / 2 + k * (fov / (s.rays - 1));
}

/// The names of the quantities of a sensor's reading, in reading order (fixed per sensor).
inline std::vector<std::string> sensorQuantities(const SensorDef& s) {
  switch (s.kind) {
    case SensorKind::Proximity:
      return {"touching"};
    case SensorKind::Range:
      return {"distance"};
    case SensorKind::Scanner: {
      std::vector<std::string> q;
      q.reserve(static_cast<size_t>(std::max(0, s.rays)));
      for (int k = 0; k < s.rays; ++k) q.push_back("range" + std::to_string(k));
      return q;
    }
    case SensorKind::Imu:
      return {"ax", "ay", "az", "gx", "gy", "gz"};
    case SensorKind::Encoder:
      return {"ticks"};
    case SensorKind::Plugin:
      return s.quantities;
  }
  return {};
}

/// An RCCameraSensor: a camera riding on a construction's root body whose image (RGB, rows top
/// first) the Simulation renders at each Period instant (docs/sensors.md). Not a physics sensor:
/// a World has no GL, so the image lives in the Simulation (Simulation::cameraImage).
struct CameraSensorDef {
  std::string key;  ///< fully qualified key of the periphery
  SourceLoc loc;
  CameraDef camera;     ///< a Mounted camera on the body (Static at a global pose on a static root); key = key
  int width = 160;      ///< pixels
  int height = 120;     ///< pixels
  double period = 0.1;  ///< s between images (0: every step); the image is held in between
};

// ---- Controllers (guide 6.12): one definition struct per kind, as Box2D keeps one per joint
// type. Each is lowered by its own function (lib/components/controllers.cpp) and made into a
// party of the run loop by its own file in lib/robot. Indices are into the Model's vectors. ----

/// RCDriveTest: a sine voltage on one drive.
struct DriveTestDef {
  int drive = -1;          ///< Model::actuators (an RCDriver)
  double period = 0.01;    ///< s, loop period
  double variation = 6.0;  ///< sine cycles per minute
};

/// RCServoTest: a triangle wave between the limits of one servo.
struct ServoTestDef {
  int servo = -1;          ///< Model::actuators (an RCPosControl with finite MinPos and MaxPos)
  double period = 0.01;    ///< s, loop period
  double variation = 6.0;  ///< oscillations per minute
};

/// RCTwoWheelMotionControl: (linear, angular) velocity -> the velocities of two wheels.
struct TwoWheelDef {
  int left = -1, right = -1;    ///< Model::actuators (RCVelControl), the left and right wheels
  double wheel_distance = 0.5;  ///< m between the wheels
  double wheel_radius = 0.1;    ///< m (the guide's parameter `Variation`)
};

/// RCCommandSchedule: timed commands to one actuator, or (linear, angular) to a motion control.
struct CommandScheduleDef {
  int actuator = -1;             ///< Model::actuators, when it commands an actuator
  int target = -1;               ///< Model::controllers (a TwoWheel), when it commands a motion control
  int values = 1;                ///< values per row: 1, or 2 (linear angular) for a motion control
  std::vector<double> commands;  ///< rows of (time s, values...), times increasing
};

/// RCWallStop: drives a motion control at `speed` until a contact sensor touches, then stops.
struct WallStopDef {
  int target = -1;       ///< Model::controllers (a TwoWheel)
  int sensor = -1;       ///< Model::sensors (a Proximity sensor)
  double period = 0.01;  ///< s
  double speed = 0.1;    ///< m/s
};

/// RCSimGoToPoint: steers a motion control until a body is within `tolerance` of the goal.
struct GoToPointDef {
  int target = -1;                ///< Model::controllers (a TwoWheel)
  int body = -1;                  ///< Model::bodies whose pose it reads
  double period = 0.01;           ///< s
  double speed = 0.1;             ///< m/s
  double turn_rate = 1.0;         ///< rad/s, largest angular velocity
  double tolerance = 0.05;        ///< m from the goal at which it stops
  double goal_x = 0, goal_z = 0;  ///< the target point on the ground plane (m)
};

/// RCObstacleAvoider: steers a motion control away from what its range sensors see.
struct ObstacleAvoiderDef {
  int target = -1;           ///< Model::controllers (a TwoWheel)
  std::vector<int> sensors;  ///< Model::sensors (RCRangeSensor)
  double period = 0.01;      ///< s
  double speed = 0.1;        ///< m/s
  double turn_rate = 1.0;    ///< rad/s
};

/// RCWallFollower: steers a motion control along a wall seen by a laser scanner.
struct WallFollowerDef {
  int target = -1;             ///< Model::controllers (a TwoWheel)
  int scanner = -1;            ///< Model::sensors (an RCLaserScanner)
  double period = 0.01;        ///< s
  double speed = 0.1;          ///< m/s
  double turn_rate = 1.0;      ///< rad/s
  double wall_distance = 0.3;  ///< m to keep between the scanner and the wall
  int side = 1;                ///< +1 the wall on the robot's left, -1 on its right
};

/// A plug-in's controller type: acts through its refs (simbob/plugin_c.h).
struct PluginControllerDef {
  std::string type;                         ///< the type name
  std::string plugin;                       ///< the plug-in's name (SimbobPlugin::name), for messages
  const SimbobType* plugin_type = nullptr;  ///< the plug-in's type
  double period = 0.01;                     ///< s
  std::vector<double> numbers;              ///< its number parameters, in the order it declared them
  /// Per ref of the type, an index into Model::actuators (RCDriver, RCPosControl, RCVelControl or
  /// an actuator type's interface), Model::sensors (a sensor interface) or Model::bodies (RCBody)...
  std::vector<int> refs;
  /// ... and which: 0 Model::actuators, 1 Model::sensors, 2 Model::bodies.
  std::vector<uint8_t> ref_kind;
};

/// A controller of the scene: its key, its place and its kind's definition.
struct ControllerDef {
  std::string key;  ///< fully qualified key
  SourceLoc loc;
  /// The kinds, in the order of `def`'s alternatives.
  enum Kind : uint8_t {
    DriveTest,
    ServoTest,
    TwoWheel,
    CommandSchedule,
    WallStop,
    Plugin,
    GoToPoint,
    ObstacleAvoider,
    WallFollower,
  };
  std::variant<DriveTestDef, ServoTestDef, TwoWheelDef, CommandScheduleDef, WallStopDef, PluginControllerDef,
               GoToPointDef, ObstacleAvoiderDef, WallFollowerDef>
      def;
  Kind kind() const { return static_cast<Kind>(def.index()); }
  /// The definition of kind T (which must be this controller's).
  template <typename T>
  const T& as() const {
    return std::get<T>(def);
  }
};

/// An RCLocalSocketCommunicator (guide 6.11.6): a peer program on 127.0.0.1 that reads the
/// robot's state and sets its commands in lockstep with simulated time (lib/robot/socket_peer.cpp,
/// docs/socket-protocol.md).
struct SocketDef {
  std::string key;  ///< fully qualified key of the periphery
  SourceLoc loc;
  bool is_server = false;  ///< true: simbob listens and waits for the peer; false: simbob connects
  int port = 5000;         ///< TCP port on 127.0.0.1 (the CLI adds --port-offset)
  double period = 0.01;    ///< s of simulated time between exchanges
  double timeout = 10.0;   ///< wall-clock s to wait for a connection or a reply (--peer-timeout)
  /// The peer program simbob starts itself (Controller, or run --controller KEY=COMMAND): a
  /// command line split by splitCommandLine; empty: the peer is started by someone else.
  std::string controller;
  std::string controller_dir;  ///< its working directory (the scene file's; "" = simbob's own)
  std::string controller_log;  ///< file for its stdout and stderr ("" = simbob's stderr)
  uint32_t seed = 0;           ///< the run's seed, passed to it as SIMBOB_SEED
};

/// Splits a Controller command line into words without a shell (docs/socket-protocol.md):
/// blanks separate words; '...' keeps everything literally; "..." keeps everything but \" and
/// \\; outside quotes a backslash keeps the next character. False with `problem` set for an
/// unclosed quote or a trailing backslash.
bool splitCommandLine(const std::string& line, std::vector<std::string>* words, std::string* problem);

/// ODE collision space: how candidate pairs are found. Results differ between spaces (pairs
/// arrive in another order), so the choice is part of a scene's reproducibility.
enum class SpaceKind : uint8_t { Hash, SweepAndPrune, QuadTree, Simple };

/// World and solver settings (SceneSettings in the scene file).
/// The most threads one world's step uses (SceneSettings Threads, --threads, World::create).
constexpr int kMaxThreads = 64;

struct SolverSettings {
  Vec3 gravity{0, -9.81, 0};     ///< m/s^2
  double max_time_step = 0.001;  ///< s, the step size (MaxTimeStep; --dt overrides)
  double min_time_step = 1e-6;   ///< s, a requested time this close counts as reached
  double max_access_time = 1.0;  ///< s of wall-clock time one grant (Party::onGrant) may take (MaxAccessTime)
  double erp = 0.2;              ///< error reduction parameter
  double cfm = 1e-10;            ///< constraint force mixing (ODE's double-precision default)
  int iterations = 20;           ///< QuickStep iterations
  int max_contacts = 4;          ///< contact points per colliding geom pair
  bool quickstep = true;         ///< false: dWorldStep (exact LCP)
  /// Why the solver is what it is when the scene did not say: "" (the scene's Solver, or its
  /// default), or the rule a bare URDF run follows (docs/urdf.md, "The solver of a bare run").
  std::string solver_rule;
  SpaceKind space = SpaceKind::Hash;
  bool auto_disable = false;  ///< let ODE disable resting bodies (changes trajectories slightly)
};

struct Model {
  SolverSettings settings;
  std::vector<MaterialDef> materials;           ///< [0] is the default material
  std::vector<BodyDef> bodies;                  ///< mobile bodies, document order
  std::vector<GeomDef> geoms;                   ///< document order
  std::vector<MeshDef> meshes;                  ///< the meshes of geoms and visuals, each once, in order of first use
  std::vector<JointDef> joints;                 ///< document order
  std::vector<ActuatorDef> actuators;           ///< document order (after the joints they drive)
  std::vector<SensorDef> sensors;               ///< document order (peripheries, after the joints)
  std::vector<CameraSensorDef> camera_sensors;  ///< document order; drawn by the Simulation, never by the physics
  std::vector<ControllerDef> controllers;       ///< document order; a schedule's TwoWheel target may come first
  std::vector<SocketDef> sockets;               ///< document order
  std::vector<FrameDef> frames;                 ///< trajectory rows after the bodies' (lumped URDF links)
  std::vector<ImportReport> imports;            ///< what each URDF import built (simbob check)
  // What the renderer draws (simbob/visuals.h); the physics never reads these.
  std::vector<VisualDef> visuals;  ///< document order
  std::vector<SkinDef> skins;      ///< [0] is the default skin
  std::vector<CameraDef> cameras;  ///< CameraList order
  ViewSettings view;
};

}  // namespace simbob
