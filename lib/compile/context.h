// The compile step's shared context: what every family's lowering (component graph -> Model)
// needs, and the one function per family that lowers it. The family files
// (lib/components/<family>.cpp) never include each other: a body lowers its geoms and joints by
// calling the functions declared here, which the geom and joint family files define.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "simbob/graph.h"
#include "simbob/mesh.h"
#include "simbob/model.h"
#include "simbob/name_table.h"

namespace simbob {

/// What lowering a body produced: its index in Model::bodies (-1 = static, part of the world)
/// and its global frame.
constexpr int kFailedActuator = -2;

struct Built {
  int index = -1;
  Transform frame;
  bool ok = false;
  int static_id = -1;  ///< a static body: its number among the scene's static bodies (GeomDef::static_body)
};

/// Where a geom lands: the body that owns it and the frames its pose is relative to.
struct GeomTarget {
  const Component* owner = nullptr;  ///< the body component (for keys and messages)
  int body = -1;                     ///< Model::bodies index; -1 = static geom (global pose)
  Transform frame;                   ///< the owner's global frame
  int material = 0;                  ///< Model::materials index
  const Link* model = nullptr;       ///< the owner's Model (for model-derived geoms)
  int static_body = -1;              ///< body == -1: the owner's number among the static bodies
};

/// Bodies already lowered, by component index. A slot per component up to the highest asked
/// for, instead of a map: a tree node per body cost an allocation and a walk of the tree each.
class BuiltMemo {
 public:
  const Built* find(int comp) const {
    const auto c = static_cast<size_t>(comp);
    return c < at_.size() && at_[c] >= 0 ? &built_[static_cast<size_t>(at_[c])].second : nullptr;
  }
  void set(int comp, const Built& b) {
    const auto c = static_cast<size_t>(comp);
    if (c >= at_.size()) at_.resize(c + 1, -1);
    if (at_[c] >= 0) {
      built_[static_cast<size_t>(at_[c])].second = b;
      return;
    }
    at_[c] = static_cast<int32_t>(built_.size());
    built_.emplace_back(comp, b);
  }
  /// Room for `bodies` bodies among `comps` components, so that a large scene's lists do not
  /// double (and hold both copies) near their end.
  void reserve(size_t comps, size_t bodies) {
    at_.reserve(comps);
    built_.reserve(bodies);
  }
  void clear() {
    for (const auto& [comp, b] : built_) at_[static_cast<size_t>(comp)] = -1;
    built_.clear();
  }

 private:
  std::vector<int32_t> at_;                   ///< component -> index into built_, -1 none
  std::vector<std::pair<int, Built>> built_;  ///< (component, what it built), in lowering order
};

/// A set of component indices, as flags: membership and size in constant time.
class ComponentSet {
 public:
  /// Adds `comp`; false if it was in already.
  bool insert(int comp) {
    const auto c = static_cast<size_t>(comp);
    if (c >= in_.size()) in_.resize(c + 1, 0);
    if (in_[c]) return false;
    in_[c] = 1;
    ++size_;
    return true;
  }
  void erase(int comp) {
    const auto c = static_cast<size_t>(comp);
    if (c < in_.size() && in_[c]) {
      in_[c] = 0;
      --size_;
    }
  }
  size_t size() const { return size_; }

 private:
  std::vector<char> in_;
  size_t size_ = 0;
};

class CompileContext {
 public:
  CompileContext(const Scene& s, Model& m, Diagnostics& d) : scene(s), model(m), diag(d) {}

  const Scene& scene;
  Model& model;
  Diagnostics& diag;

  const Component& at(int i) const { return scene.at(i); }

  /// "RCHingeJoint 'Arm.Elbow'": how messages name a component.
  static std::string describe(const Component& c) { return c.type->name + " '" + c.qkey + "'"; }
  /// An error at the component's line.
  /// Errors about a component that failed to load are left out: its load error says it all, and
  /// what follows from it (a missing geom leaves no volume) would only be noise (`check` compiles
  /// scenes that failed to load to report every other problem in the same pass).
  void error(const Component& c, const std::string& msg) { report(c, c.loc, msg); }
  /// An error at the line of a link (a parameter's element) when it has one, else the owner's.
  void error(const Link& l, const Component& owner, const std::string& msg) {
    report(owner, l.loc.line ? l.loc : owner.loc, msg);
  }
  /// An error at the line of one parameter of `c` (its slot), else the component's.
  void errorAt(const Slot& s, const Component& c, const std::string& msg, ErrorKind kind = ErrorKind::InvalidInput) {
    report(c, s.loc.line ? s.loc : c.loc, msg, kind);
  }
  void warning(const Component& c, const std::string& msg) { diag.warning(c.loc, describe(c) + ": " + msg); }

  /// The key a body or joint gets in the Model: inside a RigidBodyClone, the original's prefix
  /// is replaced by the clone's key ("Ball" renames "Ball.Arm", not "Ballast").
  std::string modelKey(const Component& c) const;

  /// Model index of the body or joint lowered under `model_key` (modelKey of its component),
  /// or -1. Peripheries find their joints and controllers their bodies through these.
  int bodyIndex(const std::string& model_key) const;
  int jointIndex(const std::string& model_key) const;
  void recordBody(const std::string& model_key, int index) { body_index_.set(model_key, index); }
  /// Room for the bodies of `body_comps` body components (see BuiltMemo::reserve).
  void reserveBodies(size_t body_comps) {
    memo.reserve(scene.comps.size(), body_comps);
    body_index_.reserve(body_comps);
  }
  /// The frame body component `comp` was first lowered in (its parent's), or nullptr.
  const Transform* parentFrame(int comp) const {
    auto it = parent_frame_.find(comp);
    return it == parent_frame_.end() ? nullptr : &it->second;
  }
  void recordParentFrame(int comp, const Transform& t) { parent_frame_.emplace(comp, t); }
  /// Whether an error was left out because its component failed to load.
  bool failedQuietly() const { return failed_quietly_; }
  /// True the first time it is asked about `comp`: checks of shared components report once.
  bool firstCheck(int comp) { return checked_.insert(comp); }
  /// Index of a component of the scene.
  int indexOf(const Component& c) const { return static_cast<int>(&c - scene.comps.data()); }
  void recordJoint(const std::string& model_key, int index) { joint_index_.set(model_key, index); }
  /// Model::actuators index of the periphery lowered under `model_key`, -1 if it was not lowered,
  /// kFailedActuator if its lowering reported an error.
  int actuatorIndex(const std::string& model_key) const { return actuator_index_.find(model_key); }
  void recordActuator(const std::string& model_key, int index) { actuator_index_.set(model_key, index); }
  /// Model::sensors index of the proximity sensor lowered under `model_key`, as actuatorIndex.
  int sensorIndex(const std::string& model_key) const { return sensor_index_.find(model_key); }
  void recordSensor(const std::string& model_key, int index) { sensor_index_.set(model_key, index); }
  /// Controllers lowered so far: component index -> Model::controllers index (-1 while it is
  /// being lowered or after an error).
  std::map<int, int> controller_index;
  /// Skins lowered so far: component index -> Model::skins index (skins.cpp).
  std::map<int, int> skin_index;

  /// Lowering state of bodies (bodies.cpp, clones.cpp): bodies already lowered (memo), bodies
  /// being lowered (cycle and depth checks), and the clone being copied.
  struct CloneScope {
    bool active = false;
    /// original key prefix -> copy key prefix, outermost clone first
    std::vector<std::pair<std::string, std::string>> renames;
    BuiltMemo memo;        ///< bodies lowered inside this copy
    std::set<int> inside;  ///< components that belong to the original
  };
  CloneScope clone;
  int clone_depth = 0;
  BuiltMemo memo;
  ComponentSet in_progress;
  int static_bodies = 0;  ///< static bodies lowered so far (Built::static_id)
  /// urdf_import.cpp: the collision shapes of the moving links of each robot fixed to the world,
  /// for checkFixedUrdfRobots.
  struct FixedUrdfShape {
    int geom;      ///< Model::geoms index
    Transform at;  ///< its pose in the scene
    int link;      ///< UrdfRobot::links index
  };
  struct FixedUrdfRobot {
    const UrdfRobot* robot = nullptr;  ///< Scene::urdf holds it
    bool bare = false;                 ///< a bare .urdf (AboveGround): the advice differs
    std::vector<FixedUrdfShape> shapes;
  };
  std::vector<FixedUrdfRobot> fixed_urdf_robots;
  bool too_big = false;  ///< a size bound was hit (reported once)

  /// The meshes of this compile (simbob/mesh.h): each file + scale + up axis is read once.
  MeshCache mesh_cache;
  /// The Model::meshes index of a loaded mesh, appended (with `loc`) on its first use.
  int meshIndex(const std::shared_ptr<const MeshData>& mesh, const SourceLoc& loc) {
    auto [it, added] = mesh_index_.emplace(mesh.get(), static_cast<int>(model.meshes.size()));
    if (added) model.meshes.push_back({mesh, loc});
    return it->second;
  }

 private:
  void report(const Component& c, const SourceLoc& loc, const std::string& msg,
              ErrorKind kind = ErrorKind::InvalidInput) {
    if (scene.load_failed.empty() || !scene.load_failed.count(indexOf(c)))
      diag.error(loc, describe(c) + ": " + msg, kind);
    else
      failed_quietly_ = true;
  }

  bool failed_quietly_ = false;
  // Model key -> index; a key recorded twice keeps the last index.
  NameTable body_index_;
  NameTable joint_index_;
  NameTable actuator_index_;
  NameTable sensor_index_;
  std::map<int, Transform> parent_frame_;
  std::map<const MeshData*, int> mesh_index_;
  ComponentSet checked_;
};

// --- one lowering per family; each is defined in lib/components/<family>.cpp -----------------

/// settings.cpp: SceneSettings -> Model::settings.
void lowerSettings(CompileContext& ctx, int comp);
/// poses.cpp: the frame a pose link gives, relative to `parent` for local coordinates. An empty
/// link is the parent frame itself (the origin at the top level). False after an error.
bool lowerPose(CompileContext& ctx, const Link& l, const Component& owner, const Transform* parent, Transform* out);
/// poses.cpp: whether a pose link is in local coordinates (an empty link counts as local), and
/// the transform it holds as written (not resolved against any frame).
bool isLocalPose(const CompileContext& ctx, const Link& l);
Transform poseValue(const CompileContext& ctx, const Link& l);
/// materials.cpp: the Model::materials index of a material link (0 = the default).
int lowerMaterial(CompileContext& ctx, const Link& l);
/// materials.cpp: the Model::materials index of a material (one entry per set of numbers).
int addMaterial(CompileContext& ctx, const MaterialDef& m);
/// motions.cpp: initial velocities from a motion link (none: at rest).
void lowerMotion(CompileContext& ctx, const Link& l, BodyDef* b);
/// geoms.cpp: the geoms of a geom link, at `offset` in the owner's frame.
void lowerGeom(CompileContext& ctx, const Link& l, const GeomTarget& t, const Transform& offset);
/// geoms.cpp: a static plane n.p = n.point (n need not be unit).
void addPlane(CompileContext& ctx, Vec3 n, const Vec3& point, int material, const std::string& key);
/// model_geoms.cpp: RCModelMatchGeom / RCModelWrapGeom, derived from the owner's model tree.
void lowerModelGeom(CompileContext& ctx, const Component& geom, const GeomTarget& t, const Transform& offset);
/// models.cpp: the models of a body's model tree in document order, each with its frame in the
/// body frame `base` (the root's pose is relative to it; children's local poses to their parent,
/// their global poses to `base`). False after an error or past kMaxModelParts parts.
struct ModelPart {
  const Component* model;
  Transform frame;
};
constexpr size_t kMaxModelParts = 10000;
bool collectModelParts(CompileContext& ctx, const Link& root, const Transform& base, bool children,
                       std::vector<ModelPart>* out);
/// models.cpp: checks a body's model tree (a root model's Pose must be local, guide 6.3).
void checkModelTree(CompileContext& ctx, const Link& root);
/// models.cpp: the primitive a model is, in its own frame: Box (size = extents, at center),
/// Ellipsoid (size = radii), Cylinder/Capsule/Cone (size = radius, length along Z), Plane
/// (size = extensions), Mesh (an RCMeshModel: lowerModelMesh reads it), None (nothing visible).
struct ModelShape {
  enum Kind { None, Box, Ellipsoid, Cylinder, Capsule, Cone, Plane, Mesh } kind = None;
  Vec3 center{0, 0, 0};
  Vec3 size{0, 0, 0};
};
ModelShape modelShape(const Component& model);
/// inertias.cpp: mass, centre of mass and inertia of a mobile body whose geoms start at
/// Model::geoms[first_geom]. False after an error.
bool lowerInertia(CompileContext& ctx, const Link& l, const Component& owner, size_t first_geom, BodyDef* b);
/// bodies.cpp: a body component (memoised: a body Ref'd twice is built once), `parent` the
/// frame local coordinates refer to (nullptr at the top level).
Built lowerBody(CompileContext& ctx, int ci, const Transform* parent);
/// clones.cpp: RCImportBody and RigidBodyClone (a rigid copy of another body's subtree).
Built lowerImportBody(CompileContext& ctx, const Component& c, const Transform* parent);
Built lowerClone(CompileContext& ctx, const Component& c, const Transform* parent);
/// urdf_import.cpp: RCImportURDF (a URDF robot, docs/urdf.md) and one of its links (URDFLink, a
/// placeholder the loader makes so that Refs reach a link: the body it is part of).
Built lowerUrdfImport(CompileContext& ctx, const Component& c, const Transform* parent);
Built lowerUrdfLink(CompileContext& ctx, const Component& c);
/// urdf_import.cpp: once every component is lowered, refuses a robot fixed to the world whose
/// moving links start inside a static plane (a bare .urdf and a scene alike, docs/urdf.md).
void checkFixedUrdfRobots(CompileContext& ctx);
bool isClone(const Component& c);
/// joints.cpp: a joint of a construction whose root is `parent`; the overrides come from an
/// RCImportJoint's own Pose and Body.
void lowerJoint(CompileContext& ctx, int ji, const Built& parent, const Link* pose_override, const Link* body_override);
/// joints.cpp: the kind of a joint component (following RCImportJoint); false if unknown.
bool jointKindOf(const CompileContext& ctx, const Component& joint, JointKind* kind);
/// peripheries.cpp: a periphery in a construction's ChildList (after its joints).
void lowerPeriphery(CompileContext& ctx, const Component& c, const Built& parent);
/// range_sensors.cpp, imu_sensors.cpp, encoders.cpp: sensors of a construction whose root is
/// `parent` (lowerPeriphery dispatches to them).
void lowerRangeSensor(CompileContext& ctx, const Component& c, const Built& parent);
void lowerImuSensor(CompileContext& ctx, const Component& c, const Built& parent);
void lowerEncoder(CompileContext& ctx, const Component& c, const Built& parent);
/// plugin_types.cpp: a plug-in's sensor or actuator (TypeSpec::plugin) on a construction whose
/// root is `parent`.
void lowerPluginPeriphery(CompileContext& ctx, const Component& c, const Built& parent);
/// camera_sensors.cpp: an RCCameraSensor (Model::camera_sensors).
void lowerCameraSensor(CompileContext& ctx, const Component& c, const Built& parent);
/// peripheries.cpp: the pose of a sensor (its Pose link, as RCProximitySensor's) relative to the
/// frame of the body it is attached to (global for a static body). False after an error.
bool lowerSensorPose(CompileContext& ctx, const Component& c, const Link& pose, const Built& parent, Transform* out);
/// peripheries.cpp: a sensor's Period (s; 0 = every step), checked; false after an error.
bool checkSensorPeriod(CompileContext& ctx, const Component& c, const Slot& slot, double period);
/// peripheries.cpp: the position limits (m or rad; infinite: none) of a drive or servo.
bool peripheryLimits(const Component& c, double* lo, double* hi);
/// controllers.cpp: a controller in an RCRobot's ControllerList.
void lowerController(CompileContext& ctx, const Component& c);
/// globals.cpp: a GlobalSimComponent of the ComponentList.
void lowerGlobal(CompileContext& ctx, int gi);
/// cameras.cpp: checks of a camera of the CameraList.
void lowerCamera(CompileContext& ctx, int comp);
/// skins.cpp: Model::skins index of a skin (0, the default skin, for none); each skin once.
int lowerSkin(CompileContext& ctx, const Link& l);
/// meshes.cpp: the mesh a component's File parameter (`file_slot`) names, relative to the file
/// the component is written in, read with `scale` into the scene's Y-up frame through the
/// compile's cache: its Model::meshes index, or -1 after an error at the File line (kind
/// MissingInput for a file that is not there).
int lowerMeshFile(CompileContext& ctx, const Component& c, const Slot& file_slot, const std::string& file,
                  const Vec3& scale);
/// models.cpp: the Model::meshes index of an RCMeshModel's mesh (-1 after an error).
int lowerModelMesh(CompileContext& ctx, const Component& model);
/// models.cpp: appends the visuals of a body's model tree to Model::visuals: `body` the
/// Model::bodies index (frame = identity) or -1 with `frame` the static body's global frame.
void lowerVisuals(CompileContext& ctx, const Link& root, int body, const Transform& frame, const std::string& key);
/// lint.cpp: the first body that QuickStep cannot hold at its hinge or ball joint (an inertia far
/// below m d^2: lint's "inertia ratio" warning), or -1.
int firstBodyQuickStepCannotHold(const Model& model);

}  // namespace simbob
