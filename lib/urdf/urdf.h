// The URDF import (issue 28): a URDF robot read into plain data (simbob's own reader on pugixml,
// following urdfdom's rules, every value with its line), and planned as the rigid bodies of
// a scene (fixed joints lumped, mass properties combined, URDF's Z-up mapped onto the scene's
// Y-up). No ODE, no GL: part of simbob_core. The loader (lib/scene/load.cpp) reads a robot when
// it meets an RCImportURDF or a bare .urdf file; the RCImportURDF family
// (lib/components/urdf_import.cpp) lowers it into the Model. docs/urdf.md has the mapping.
#pragma once

#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "simbob/error.h"
#include "simbob/frames.h"
#include "simbob/visuals.h"

namespace simbob {

/// A <visual> or <collision> of a link: one shape at an origin in the link frame (URDF axes).
struct UrdfShape {
  enum Kind : uint8_t { Box, Sphere, Cylinder, Mesh } kind = Box;
  int line = 0;          ///< the <visual> or <collision> element
  int shape_line = 0;    ///< the shape element (<box>, <mesh>, ...)
  Transform origin;      ///< in the link frame (m, unit quaternion)
  Vec3 size{0, 0, 0};    ///< Box: extents (m); Sphere: radius; Cylinder: radius, length along local Z
  std::string filename;  ///< Mesh: as written
  std::string path;      ///< Mesh: the file it names (package:// and relative names resolved)
  Vec3 scale{1, 1, 1};   ///< Mesh: scale per axis
  int material = -1;     ///< visual: index into UrdfRobot::materials (-1: none)
};

/// A material: robot-level (<robot><material>) or written inside a visual.
struct UrdfMaterial {
  std::string name;  ///< as written ("" for an unnamed inline material)
  int line = 0;
  bool has_color = false;
  Rgba color{0.8, 0.8, 0.8, 1};
  std::string texture;       ///< filename as written ("" = none)
  std::string texture_path;  ///< the file it names
};

struct UrdfInertial {
  int line = 0;                             ///< <inertial>
  int mass_line = 0;                        ///< <mass>
  int inertia_line = 0;                     ///< <inertia>
  Transform origin;                         ///< the centre of mass and the inertia's axes, in the link frame
  double mass = 0;                          ///< kg
  Mat3 inertia{0, 0, 0, 0, 0, 0, 0, 0, 0};  ///< kg m^2 about the centre of mass, origin's axes
};

/// One value of a <gazebo> tag (<mu1>0</mu1> or <mu1 value="0"/>): line 0 when the file gives none.
struct UrdfTag {
  int line = 0;
  double value = 0;
};

/// A link's <gazebo reference="LINK"> tags that Gazebo classic hands to ODE, with its meaning
/// (docs/urdf.md, "Surfaces"): friction, contact stiffness and damping, contact tolerances, self
/// collision and gravity. A later tag of the same name overrides an earlier one, as in Gazebo.
struct UrdfGazebo {
  UrdfTag mu1;           ///< friction coefficient along fdir1 (or ODE's first direction)
  UrdfTag mu2;           ///< friction coefficient along the second direction
  UrdfTag fdir1_tag;     ///< line of <fdir1>
  Vec3 fdir1{0, 0, 0};   ///< first friction direction in the collision's frame (0: ODE's choice)
  UrdfTag kp;            ///< contact stiffness, N/m
  UrdfTag kd;            ///< contact damping, N s/m
  UrdfTag min_depth;     ///< m of penetration without push-out
  UrdfTag max_vel;       ///< m/s, largest push-out velocity
  UrdfTag max_contacts;  ///< most contacts of one of its collisions with any other geom
  UrdfTag self_collide;  ///< 1: collides with the robot's other links (0/1)
  UrdfTag gravity;       ///< 0: gravity does not act on it (<gravity>, <turnGravityOff> inverted)
  /// Whether any contact surface value is given (mu1 ... maxContacts).
  bool surface() const {
    return mu1.line || mu2.line || fdir1_tag.line || kp.line || kd.line || min_depth.line || max_vel.line ||
           max_contacts.line;
  }
};

struct UrdfLink {
  std::string name;
  int line = 0;
  bool has_inertial = false;
  UrdfInertial inertial;
  std::vector<UrdfShape> visuals;     ///< document order
  std::vector<UrdfShape> collisions;  ///< document order
  UrdfGazebo gazebo;                  ///< its <gazebo reference> tags
};

struct UrdfJoint {
  enum Type : uint8_t { Revolute, Continuous, Prismatic, Fixed, Floating, Planar } type = Fixed;
  std::string name;
  int line = 0;
  int parent = -1;     ///< UrdfRobot::links index
  int child = -1;      ///< UrdfRobot::links index
  Transform origin;    ///< the child link's frame in the parent link's frame
  Vec3 axis{1, 0, 0};  ///< unit, in the child link's frame
  int axis_line = 0;
  bool has_limit = false;
  int limit_line = 0;
  double lower = 0, upper = 0;  ///< rad or m (revolute, prismatic)
  double effort = 0;            ///< N m or N; 0 = not given
  double velocity = 0;          ///< rad/s or m/s; 0 = not given
  int dynamics_line = 0;
  double damping = 0;   ///< N m s/rad or N s/m
  double friction = 0;  ///< N m or N (Coulomb)
  int mimic = -1;       ///< UrdfRobot::joints index of the joint it follows (-1: none)
  int mimic_line = 0;
  double multiplier = 1, offset = 0;  ///< q = multiplier * q_leader + offset
};

/// Something the file says that the import does not use: named once, with its first line.
struct UrdfNote {
  int line = 0;
  std::string text;
  int count = 1;  ///< how many times it occurs
};

/// A URDF robot as written: links and joints in document order, every value with its line.
struct UrdfRobot {
  std::string name;
  std::string file;  ///< the URDF file as named (messages)
  int line = 0;      ///< <robot>
  std::vector<UrdfLink> links;
  std::vector<UrdfJoint> joints;
  std::vector<UrdfMaterial> materials;  ///< robot-level first (document order), then inline ones
  int root = -1;                        ///< the link that is no joint's child
  std::vector<UrdfNote> ignored;        ///< elements and attributes it ignores, once each
  UrdfTag self_collide;                 ///< robot-level <gazebo><self_collide>: every link's default
  std::vector<std::string> files;       ///< meshes and textures it names (resolved), once each
};

/// Where package://NAME/... is looked for, after a package.xml above the URDF and
/// ROS_PACKAGE_PATH (docs/urdf.md): NAME -> folder, in order.
using UrdfPackages = std::vector<std::pair<std::string, std::string>>;

/// RCImportURDF's Drives: what every movable joint gets.
enum class UrdfDrives : uint32_t { None, Position, Velocity, Effort };
/// The type of the placeholder component of a drive ("URDFPositionDrive", ...); "" for None.
const char* urdfDriveType(uint32_t drives);
/// Whether a joint gets a drive: revolute, continuous or prismatic, and not a mimic.
bool urdfJointDriven(const UrdfJoint& j);
/// "revolute", "continuous", ... as a URDF writes the type.
const char* urdfJointTypeName(UrdfJoint::Type t);
/// A URDF name as a key part: '.' (the key separator) becomes '_'.
std::string urdfKey(const std::string& name);

/// Parses "NAME=DIR;NAME=DIR" (RCImportURDF's Packages, --package). False with `problem` set.
bool parseUrdfPackages(const std::string& text, UrdfPackages* out, std::string* problem);

/// Reads the URDF text of `file`. Problems go to diag with file:line (MissingInput for a mesh or
/// texture that is not there, InvalidInput for the rest); returns null after an error.
std::shared_ptr<const UrdfRobot> readUrdf(const std::string& text, const std::string& file,
                                          const UrdfPackages& packages, Diagnostics& diag);

/// Whether text or a file name looks like a URDF rather than a scene: the name ends in .urdf, or
/// the first element is <robot>.
bool looksLikeUrdf(const std::string& name, const std::string& text);

// --- planning: the bodies a robot becomes ----------------------------------------------------

/// One rigid body of the scene: a link and the links fixed to it (lumped), or the links fixed to
/// the world (`fixed`).
struct UrdfBody {
  int root = -1;                            ///< the link whose frame is the body's frame
  std::vector<int> links;                   ///< every link in it, document order (root included)
  bool fixed = false;                       ///< part of the world (root link 'world', FixedBase)
  double mass = 0;                          ///< kg, of every link's <inertial>
  Vec3 com{0, 0, 0};                        ///< centre of mass in the root link's frame (m)
  Mat3 inertia{0, 0, 0, 0, 0, 0, 0, 0, 0};  ///< kg m^2 about com, root link axes
  int massive_links = 0;                    ///< links with an <inertial> in it
};

struct UrdfPlan {
  std::vector<UrdfBody> bodies;         ///< document order of their root links
  std::vector<int> link_body;           ///< per link: its UrdfPlan::bodies index
  std::vector<Transform> link_global;   ///< per link: its frame at the zero configuration, robot frame (Z up)
  std::vector<Transform> link_in_body;  ///< per link: its frame in its body's root link frame
};

/// The deepest a URDF tree may be (joints from the root to the farthest link), checked before
/// anything else is read: a limit from urdfdom's days (it freed a tree recursively, which
/// overflowed an 8 MB stack near 120,000 levels; docs/urdf.md, docs/testing.md).
constexpr int kMaxUrdfDepth = 50000;

/// Lumps the robot's fixed joints and combines mass properties (parallel-axis theorem, rotated
/// tensors). `fixed_base`: the root link is fixed to the world (as a root named 'world' is).
UrdfPlan planUrdf(const UrdfRobot& robot, bool fixed_base);

/// The scene frame of a robot-frame transform for a robot placed at `place`: URDF's +Z becomes
/// the scene's +Y (a rotation of -90 degrees about X), positions permuted exactly.
Transform urdfToScene(const Transform& place, const Transform& t);
/// The same for a direction.
Vec3 urdfDirToScene(const Transform& place, const Vec3& v);
/// An <origin rpy="roll pitch yaw"> as a quaternion: urdfdom's formula, term for term, with
/// correctly rounded sin and cos (read.cpp).
Quat quatFromRpy(double roll, double pitch, double yaw);

}  // namespace simbob
