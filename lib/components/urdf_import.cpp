// RCImportURDF (issue 28, docs/urdf.md): a robot read from a URDF file becomes bodies, geoms,
// visuals, skins, joints, drives and trajectory frames of the Model. The loader has read the
// robot (Scene::urdf) and made a placeholder component per link (URDFLink) and per drive, so that
// Refs reach them; this file lowers what lib/urdf planned: one body per link and the links fixed
// to it (lumped), URDF's Z-up turned into the scene's Y-up, the file's inertia kept as written.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <limits>

#include "compile/context.h"
#include "compile/mass.h"
#include "components/bodies.h"
#include "components/families.h"
#include "simbob/transform.h"
#include "urdf/urdf.h"

namespace simbob {

namespace {

constexpr LinkParam kPose{"Pose"};
constexpr LinkParam kMaterial{"Material"};
constexpr ValueParam<bool> kFixedBase{"FixedBase"};
constexpr EnumParam kDrives{"Drives"};
const EnumTable kDrivesTable{"Drives", {{"none", 0}, {"position", 1}, {"velocity", 2}, {"effort", 3}}};
constexpr ValueParam<double> kMaxForce{"MaxForce"};
constexpr ValueParam<double> kMaxVelocity{"MaxVelocity"};
constexpr ValueParam<double> kSmooth{"Smooth"};
constexpr ValueParam<std::string> kPackages{"Packages"};
constexpr EnumParam kCollisions{"Collisions"};
const EnumTable kCollisionsTable{"Collisions", {{"hull", 0}, {"mesh", 1}}};
constexpr ValueParam<bool> kAboveGround{"AboveGround"};
constexpr ValueParam<bool> kSelfCollision{"SelfCollision"};

using ContextFixedShape = CompileContext::FixedUrdfShape;

/// The lowering of one import: what it has made so far and what it says.
class Import {
 public:
  Import(CompileContext& ctx, const Component& c, const UrdfRobot& robot)
      : ctx_(ctx), c_(c), robot_(robot), key_(ctx.modelKey(c)) {}

  Built lower(const Transform* parent);

 private:
  SourceLoc at(int line) const { return {robot_.file, line}; }
  void error(int line, const std::string& msg) {
    ctx_.diag.error(at(line), msg);
    ok_ = false;
  }
  void note(int line, const std::string& msg) { report_.notes.push_back({ErrorKind::InvalidInput, at(line), msg}); }
  const UrdfLink& link(int i) const { return robot_.links[static_cast<size_t>(i)]; }
  /// The placeholder component of a link or a drive (the loader made it), or null.
  const Component* placeholder(const std::string& name) const {
    const int i = ctx_.scene.find(c_.qkey + "." + urdfKey(name));
    return i < 0 || ctx_.at(i).parent != ctx_.indexOf(c_) ? nullptr : &ctx_.at(i);
  }
  std::string keyOf(const std::string& name) const {
    const Component* p = placeholder(name);
    return p ? ctx_.modelKey(*p) : key_ + "." + urdfKey(name);
  }
  void checkInertia();
  void surfaces();
  int linkMaterial(int li) const {
    return link_material_.empty() ? material_ : link_material_[static_cast<size_t>(li)];
  }
  bool selfCollides(const UrdfLink& l) const;
  void bodyGravity();
  double lowestPoint(const UrdfShape& s, const Transform& t);
  void raiseAboveGround();
  void addBodies();
  void addShapes(int li);
  int meshOf(const UrdfShape& s);
  void addVisual(int li, const UrdfShape& s);
  int skinOf(int material);
  void addJoints();
  void addJoint(size_t ji);
  void addDrives();
  void remember();
  void summarise();

  CompileContext& ctx_;
  const Component& c_;
  const UrdfRobot& robot_;
  std::string key_;
  UrdfPlan plan_;
  Transform place_;
  std::vector<int> body_index_;   // per plan body: Model::bodies index (-1: fixed to the world)
  std::vector<int> joint_index_;  // per URDF joint: Model::joints index (-1: none)
  std::vector<int> skin_index_;   // per URDF material: Model::skins index (-1: not made yet)
  int material_ = 0;
  std::vector<int> link_material_;               // per URDF link: Model::materials index (empty: material_ for all)
  std::vector<ContextFixedShape> fixed_shapes_;  // moving links' collisions, if fixed to the world
  int drives_ = 0;
  int hulls_ = 0, trimeshes_ = 0;
  int group_ = 0;  // GeomDef::group of its geoms: the first geom index it makes (a copy gets its own)
  ImportReport report_;
  bool ok_ = true;
};

Built Import::lower(const Transform* parent) {
  if (!lowerPose(ctx_, c_.get(kPose), c_, parent, &place_)) return Built{};
  material_ = lowerMaterial(ctx_, c_.get(kMaterial));
  group_ = static_cast<int>(ctx_.model.geoms.size());
  plan_ = planUrdf(robot_, c_.get(kFixedBase));
  skin_index_.assign(robot_.materials.size(), -1);
  for (const UrdfNote& n : robot_.ignored)
    note(n.line, n.text + (n.count > 1 ? " (" + std::to_string(n.count) + " times)" : ""));
  // Every mesh first: one that cannot be read is the reason to name, before what follows from it.
  for (const UrdfLink& l : robot_.links)
    for (const auto* shapes : {&l.visuals, &l.collisions})
      for (const UrdfShape& s : *shapes)
        if (s.kind == UrdfShape::Mesh) meshOf(s);
  if (!ok_) return Built{};
  checkInertia();
  if (!ok_) return Built{};
  if (c_.get(kAboveGround)) raiseAboveGround();
  if (!ok_) return Built{};
  surfaces();
  addBodies();
  bodyGravity();
  for (size_t li = 0; li < robot_.links.size(); ++li) addShapes(static_cast<int>(li));
  addJoints();
  if (!ok_) return Built{};
  addDrives();
  remember();
  summarise();
  ctx_.model.imports.push_back(report_);
  const int root_body = plan_.link_body[static_cast<size_t>(robot_.root)];
  if (plan_.bodies[static_cast<size_t>(root_body)].fixed && !fixed_shapes_.empty())
    ctx_.fixed_urdf_robots.push_back({&robot_, c_.get(kAboveGround), std::move(fixed_shapes_)});
  Built out;
  out.index = body_index_[static_cast<size_t>(root_body)];
  out.frame = urdfToScene(place_, plan_.link_global[static_cast<size_t>(robot_.root)]);
  out.ok = ok_;
  return out;
}

/// The file's inertia, never replaced: what ODE cannot step is refused at its line, what no
/// body can have (the triangle inequality broken) is a warning at its line.
void Import::checkInertia() {
  bool fixed_mass = false;
  for (size_t li = 0; li < robot_.links.size(); ++li) {
    const UrdfLink& l = robot_.links[li];
    const int bi = plan_.link_body[li];
    if (bi < 0) continue;
    const bool moves = !plan_.bodies[static_cast<size_t>(bi)].fixed;
    if (!l.has_inertial) {
      if (moves && !l.collisions.empty())
        ctx_.diag.warning(at(l.line), "link '" + l.name + "' has <collision> but no <inertial>: it adds no mass");
      continue;
    }
    if (!moves) {
      fixed_mass = fixed_mass || l.inertial.mass != 0;
      continue;
    }
    const UrdfInertial& in = l.inertial;
    if (!(in.mass > 0) || !std::isfinite(in.mass))
      error(in.mass_line, "link '" + l.name + "': mass " + formatNumber(in.mass) +
                              " kg; a moving link needs a mass > 0 (ODE cannot step it)");
    const Mat3& I = in.inertia;
    if (!isPositiveDefinite(I)) {
      error(in.inertia_line, "link '" + l.name + "': the inertia tensor is not positive definite (ODE cannot step it)");
      continue;
    }
    // Ixx + Iyy >= Izz (and the like) holds for every body, in any axes: 2 int z^2 dm >= 0.
    const double tol = 1e-9 * (I[0] + I[4] + I[8]);
    if (I[0] + I[4] < I[8] - tol || I[4] + I[8] < I[0] - tol || I[0] + I[8] < I[4] - tol)
      ctx_.diag.warning(at(in.inertia_line), "link '" + l.name +
                                                 "': the inertia breaks the triangle inequality (Ixx + Iyy >= Izz "
                                                 "and the like): no rigid body has it; used as written");
  }
  if (fixed_mass) note(robot_.line, "the <inertial> of links fixed to the world are not used (they never move)");
  // Massless moving links: one line for all of them (a file without any <inertial> has many).
  std::vector<int> massless;
  for (const UrdfBody& b : plan_.bodies) {
    if (!b.fixed && !(b.mass > 0) && b.massive_links == 0) massless.push_back(b.root);
    // Each link's tensor was checked; what the lumping adds up must be steppable too.
    if (!b.fixed && b.mass > 0 && b.massive_links > 1 && !isPositiveDefinite(b.inertia))
      error(link(b.root).line, "link '" + link(b.root).name +
                                   "' and the links fixed to it add up to an inertia that is not positive definite "
                                   "(ODE cannot step it)");
  }
  if (massless.empty()) return;
  const UrdfLink& l = link(massless[0]);
  std::string more;
  for (size_t i = 1; i < massless.size(); ++i) more += (i > 1 ? ", '" : "'") + link(massless[i]).name + "'";
  error(l.line, "link '" + l.name + "' moves but has no mass (no <inertial> on it or the links fixed to it): " +
                    "ODE cannot step a body without mass; give it an <inertial>" +
                    (massless[0] == robot_.root ? " or import it with FixedBase" : "") +
                    (more.empty() ? "" : " (so do " + more + ")"));
}

/// The lowest y (m) of a collision shape placed at `t` in the scene: a box's lowest corner, a
/// sphere's centre less its radius, a cylinder's lowest rim point, a mesh's lowest vertex
/// (+infinity for a mesh that could not be read, refused already).
double Import::lowestPoint(const UrdfShape& s, const Transform& t) {
  double lowest = std::numeric_limits<double>::infinity();
  auto reach = [&](const Vec3& local) { lowest = std::min(lowest, add(t.p, rotate(t.q, local))[1]); };
  switch (s.kind) {
    case UrdfShape::Box:
      for (int k = 0; k < 8; ++k)
        reach({k & 1 ? s.size[0] / 2 : -s.size[0] / 2, k & 2 ? s.size[1] / 2 : -s.size[1] / 2,
               k & 4 ? s.size[2] / 2 : -s.size[2] / 2});
      return lowest;
    case UrdfShape::Sphere:
      return t.p[1] - s.size[0];
    case UrdfShape::Cylinder: {  // axis along the shape's z: each end's circle dips r sin(tilt)
      const double ay = rotate(t.q, Vec3{0, 0, 1})[1];
      const double rim = s.size[0] * std::sqrt(std::max(0.0, 1 - ay * ay));
      return t.p[1] - std::abs(ay) * s.size[1] / 2 - rim;
    }
    case UrdfShape::Mesh: {
      const int mi = meshOf(s);
      if (mi < 0) return lowest;
      for (const Vec3& v : ctx_.model.meshes[static_cast<size_t>(mi)].data->vertices) reach(v);
      return lowest;
    }
  }
  return lowest;
}

/// AboveGround (a bare robot.urdf): a floating robot whose collision shapes reach below y = 0 is
/// raised until the lowest touches it, rather than started inside the ground. A robot fixed to
/// the world is not raised (its base is bolted where the file puts it): checkFixedUrdfRobots
/// refuses it if its moving links start inside the ground, in a scene as in a bare run.
void Import::raiseAboveGround() {
  const int root_body = plan_.link_body[static_cast<size_t>(robot_.root)];
  if (root_body < 0 || plan_.bodies[static_cast<size_t>(root_body)].fixed) return;
  double lowest = std::numeric_limits<double>::infinity();
  for (size_t li = 0; li < robot_.links.size(); ++li)
    for (const UrdfShape& s : robot_.links[li].collisions)
      lowest = std::min(lowest, lowestPoint(s, urdfToScene(place_, compose(plan_.link_global[li], s.origin))));
  if (!(lowest < 0)) return;
  place_.p[1] -= lowest;
  note(robot_.line, "the robot is raised " + formatApprox(-lowest) +
                        " m so that its lowest collision shape touches the ground (AboveGround)");
}

/// Each link's <gazebo reference> surface (docs/urdf.md, "Surfaces") as a material of its own: the
/// import's Material with the file's values in Gazebo classic's meaning, each said at its line.
void Import::surfaces() {
  const MaterialDef base = ctx_.model.materials[static_cast<size_t>(material_)];
  const double h = ctx_.model.settings.max_time_step;
  if (robot_.self_collide.line)
    note(robot_.self_collide.line, std::string("robot: <self_collide> ") +
                                       (robot_.self_collide.value != 0 ? "true" : "false") +
                                       ": the default of every link without a <selfCollide> of its own" +
                                       (c_.get(kSelfCollision) ? " (SelfCollision true: every link collides)" : ""));
  for (size_t li = 0; li < robot_.links.size(); ++li) {
    const UrdfLink& l = robot_.links[li];
    const UrdfGazebo& gz = l.gazebo;
    const std::string who = "link '" + l.name + "': ";
    if (gz.self_collide.line)
      note(gz.self_collide.line,
           who + "<selfCollide> " + (gz.self_collide.value != 0 ? "true" : "false") + ": its collisions collide " +
               (gz.self_collide.value != 0 ? "with the robot's other links too (never those a joint connects)"
                                           : "only with the rest of the scene") +
               (c_.get(kSelfCollision) ? " (SelfCollision true: every link collides)" : ""));
    if (!gz.surface()) continue;
    if (l.collisions.empty()) {
      const int line = std::max({gz.mu1.line, gz.mu2.line, gz.fdir1_tag.line, gz.kp.line, gz.kd.line, gz.min_depth.line,
                                 gz.max_vel.line, gz.max_contacts.line});
      note(line, who + "its <gazebo> surface tags change nothing: it has no <collision>");
      continue;
    }
    if (link_material_.empty()) link_material_.assign(robot_.links.size(), material_);
    MaterialDef m = base;
    m.key = key_ + "." + urdfKey(l.name);
    if (gz.mu1.line || gz.mu2.line) {
      m.gazebo = true;
      m.friction = gz.mu1.line ? gz.mu1.value : base.friction;
      m.friction2 = gz.mu2.line ? gz.mu2.value : base.friction;
      const std::string rule =
          "; a contact of its collisions takes the smaller of the two geoms' values (Gazebo classic), not the larger";
      const std::string other = "not given: the Material's Friction " + formatNumber(base.friction);
      if (gz.mu1.line)
        note(gz.mu1.line, who + "<mu1> " + formatNumber(gz.mu1.value) + ": friction along " +
                              (gz.fdir1_tag.line ? "<fdir1>" : "ODE's first direction") + rule +
                              (gz.mu2.line ? "" : "; <mu2> " + other));
      if (gz.mu2.line)
        note(gz.mu2.line, who + "<mu2> " + formatNumber(gz.mu2.value) + ": friction across it" + rule +
                              (gz.mu1.line ? "" : "; <mu1> " + other));
    }
    if (gz.fdir1_tag.line) {
      m.fdir1 = gz.fdir1;
      note(gz.fdir1_tag.line,
           who + "<fdir1> " + formatNumber(gz.fdir1[0]) + " " + formatNumber(gz.fdir1[1]) + " " +
               formatNumber(gz.fdir1[2]) +
               (gz.fdir1 == Vec3{0, 0, 0} ? ": ODE chooses the friction directions (as Gazebo's zero does)"
                                          : ": the first friction direction, in the frame of each of its collisions, "
                                            "laid into each contact's plane"));
    }
    if (gz.kp.line || gz.kd.line) {
      m.kp = gz.kp.line ? gz.kp.value : 1e12;  // SDF's defaults where one of the two is missing
      m.kd = gz.kd.line ? gz.kd.value : 1.0;
      const double erp = h * m.kp / (h * m.kp + m.kd), cfm = 1.0 / (h * m.kp + m.kd);
      note(gz.kp.line ? gz.kp.line : gz.kd.line,
           who + "<kp> " + formatNumber(m.kp) + " N/m" + (gz.kp.line ? "" : " (not given: SDF's default)") + ", <kd> " +
               formatNumber(m.kd) + " N s/m" + (gz.kd.line ? "" : " (not given: SDF's default)") +
               ": its contacts' ERP " + formatApprox(erp) + " and CFM " + formatApprox(cfm) + " at the " +
               formatNumber(h) +
               " s step, as Gazebo classic computes them (against a geom with a <kp> too: the springs in "
               "series, the dampers added)");
    }
    if (gz.min_depth.line) {
      m.min_depth = gz.min_depth.value;
      note(gz.min_depth.line, who + "<minDepth> " + formatNumber(m.min_depth) +
                                  " m: its contacts push out only what goes deeper (the smaller of a pair's)");
    }
    if (gz.max_vel.line) {
      m.max_vel = gz.max_vel.value;
      note(gz.max_vel.line, who + "<maxVel> " + formatNumber(m.max_vel) +
                                " m/s: its contacts push out at most that fast (the smaller of a pair's)");
    }
    if (gz.max_contacts.line) {
      m.max_contacts = static_cast<int>(gz.max_contacts.value);
      note(gz.max_contacts.line, who + "<maxContacts> " + std::to_string(m.max_contacts) +
                                     ": at most that many contacts of one of its collisions with another geom (and "
                                     "at most MaxContacts)");
    }
    link_material_[li] = addMaterial(ctx_, m);
  }
}

/// Whether a link's collisions collide with the robot's other links: SelfCollision, else its
/// <selfCollide>, else the robot's <self_collide> (Gazebo classic: a pair collides when either does).
bool Import::selfCollides(const UrdfLink& l) const {
  if (c_.get(kSelfCollision)) return true;
  if (l.gazebo.self_collide.line) return l.gazebo.self_collide.value != 0;
  return robot_.self_collide.value != 0;
}

/// <gravity> false (or <turnGravityOff> true) on a link: gravity does not act on its body. The
/// links lumped into one body must agree; the first in the file decides.
void Import::bodyGravity() {
  for (size_t bi = 0; bi < plan_.bodies.size(); ++bi) {
    const UrdfBody& b = plan_.bodies[bi];
    const UrdfLink* first = nullptr;
    for (int li : b.links) {
      const UrdfLink& l = link(li);
      if (!l.gazebo.gravity.line) continue;
      const bool on = l.gazebo.gravity.value != 0;
      if (!first) {
        first = &l;
        if (b.fixed) {
          note(l.gazebo.gravity.line, "link '" + l.name +
                                          "': its <gazebo> gravity changes nothing: it is fixed to "
                                          "the world");
          continue;
        }
        ctx_.model.bodies[static_cast<size_t>(body_index_[bi])].gravity = on;
        note(l.gazebo.gravity.line, "link '" + l.name + "': gravity " + (on ? "acts" : "does not act") + " on body '" +
                                        ctx_.model.bodies[static_cast<size_t>(body_index_[bi])].key + "'");
      } else if (on != (first->gazebo.gravity.value != 0)) {
        ctx_.diag.warning(at(l.gazebo.gravity.line), "link '" + l.name + "': its <gazebo> gravity differs from link '" +
                                                         first->name + "''s, lumped into the same body: '" +
                                                         first->name + "''s is used");
      }
    }
  }
}

void Import::addBodies() {
  body_index_.assign(plan_.bodies.size(), -1);
  for (size_t bi = 0; bi < plan_.bodies.size(); ++bi) {
    const UrdfBody& b = plan_.bodies[bi];
    if (b.fixed) continue;
    const UrdfLink& l = link(b.root);
    BodyDef d;
    d.key = keyOf(l.name);
    d.loc = at(l.line);
    d.pose = urdfToScene(place_, plan_.link_global[static_cast<size_t>(b.root)]);
    d.mass = b.mass;
    d.com = b.com;  // body-frame quantities stay in the link's own (URDF) axes
    d.inertia = b.inertia;
    // The <inertia> to name in advice: the root link's, else the first lumped link's.
    for (int li : b.links)
      if (link(li).has_inertial && (li == b.root || !d.inertia_loc.line))
        d.inertia_loc = at(link(li).inertial.inertia_line);
    body_index_[bi] = static_cast<int>(ctx_.model.bodies.size());
    ctx_.model.bodies.push_back(d);
    ctx_.recordBody(d.key, body_index_[bi]);
  }
}

/// A link's collisions (geoms), visuals and, unless it is its body's root, its trajectory frame.
void Import::addShapes(int li) {
  const size_t l = static_cast<size_t>(li);
  const int pb = plan_.link_body[l];
  if (pb < 0) return;
  const int body = body_index_[static_cast<size_t>(pb)];
  const UrdfLink& ul = link(li);
  const std::string key = keyOf(ul.name);
  // Where a shape at `origin` in the link frame goes: body-relative, or global when fixed.
  auto where = [&](const Transform& origin) {
    return body >= 0 ? compose(plan_.link_in_body[l], origin)
                     : urdfToScene(place_, compose(plan_.link_global[l], origin));
  };
  auto scenePose = [&](const Transform& origin) { return urdfToScene(place_, compose(plan_.link_global[l], origin)); };
  for (const UrdfShape& s : ul.collisions) {
    GeomDef g;
    g.loc = at(s.line);
    // Its links collide with everything else but not with each other, unless asked (Gazebo's
    // self_collide, PyBullet's URDF_USE_SELF_COLLISION): CAD shapes of neighbours often overlap.
    g.group = selfCollides(ul) ? -1 : group_;
    if (s.kind == UrdfShape::Mesh) {
      g.mesh = meshOf(s);
      if (g.mesh < 0) continue;
      const MeshData& m = *ctx_.model.meshes[static_cast<size_t>(g.mesh)].data;
      // Moving links collide with the mesh's convex hull unless asked; fixed ones with its triangles.
      const bool hull = body >= 0 && c_.get(kCollisions) == 0;
      if (hull && m.hull.empty()) {
        error(s.shape_line, "link '" + ul.name + "': mesh '" + s.filename + "' has no convex hull (" + m.hull_problem +
                                "); give the link a primitive <collision>, or Collisions mesh");
        continue;
      }
      ++(hull ? hulls_ : trimeshes_);
      g.key = body >= 0 ? ctx_.model.bodies[static_cast<size_t>(body)].key : key;
      g.body = body;
      g.offset = where(s.origin);
      g.material = linkMaterial(li);
      g.shape = hull ? GeomShape::ConvexHull : GeomShape::TriMesh;
      if (body >= 0) fixed_shapes_.push_back({static_cast<int>(ctx_.model.geoms.size()), scenePose(s.origin), li});
      ctx_.model.geoms.push_back(g);
      continue;
    }
    g.key = body >= 0 ? ctx_.model.bodies[static_cast<size_t>(body)].key : key;
    g.body = body;
    g.offset = where(s.origin);
    g.material = linkMaterial(li);
    g.shape = s.kind == UrdfShape::Box ? GeomShape::Box
                                       : (s.kind == UrdfShape::Sphere ? GeomShape::Sphere : GeomShape::Cylinder);
    g.size = s.size;
    if (body >= 0) fixed_shapes_.push_back({static_cast<int>(ctx_.model.geoms.size()), scenePose(s.origin), li});
    ctx_.model.geoms.push_back(g);
  }
  for (const UrdfShape& s : ul.visuals) addVisual(li, s);
  const bool body_root = plan_.bodies[static_cast<size_t>(pb)].root == li;
  if (body_root && (body >= 0 || (li == robot_.root && ul.name == "world"))) return;  // the body's row, or the world
  FrameDef f;
  f.key = key;
  f.body = body;
  f.offset = body >= 0 ? plan_.link_in_body[l] : urdfToScene(place_, plan_.link_global[l]);
  ctx_.model.frames.push_back(f);
}

void Import::addVisual(int li, const UrdfShape& s) {
  const size_t l = static_cast<size_t>(li);
  const int body = body_index_[static_cast<size_t>(plan_.link_body[l])];
  VisualDef v;
  v.body = body;
  v.pose = body >= 0 ? compose(plan_.link_in_body[l], s.origin)
                     : urdfToScene(place_, compose(plan_.link_global[l], s.origin));
  switch (s.kind) {
    case UrdfShape::Box:
      v.shape = VisualDef::Cuboid;
      v.a = {-s.size[0] / 2, -s.size[1] / 2, -s.size[2] / 2};
      v.b = {s.size[0] / 2, s.size[1] / 2, s.size[2] / 2};
      break;
    case UrdfShape::Sphere:
      v.shape = VisualDef::Ellipsoid;
      v.size = {s.size[0], s.size[0], s.size[0]};
      break;
    case UrdfShape::Cylinder:
      v.shape = VisualDef::Cylinder;
      v.size = {s.size[0], s.size[1], 0};
      v.mask = 7;  // the jacket and both flat ends
      break;
    case UrdfShape::Mesh:
      v.shape = VisualDef::Mesh;
      v.mesh = meshOf(s);
      if (v.mesh < 0) return;
      break;
  }
  v.skin = skinOf(s.material);
  v.key = keyOf(link(li).name);
  ctx_.model.visuals.push_back(v);
}

/// The Model::meshes index of a mesh shape (read once per file and scale, URDF's Z up), or -1
/// after an error at its line (66 for a file that cannot be read, 65 for one that cannot be parsed).
int Import::meshOf(const UrdfShape& s) {
  const MeshLoad ml = ctx_.mesh_cache.load(s.path, s.scale, UpAxis::Z);
  if (!ml.ok()) {
    ctx_.diag.error(at(s.shape_line), "mesh '" + s.filename + "': " + ml.error.message, ml.error.kind);
    ok_ = false;
    return -1;
  }
  return ctx_.meshIndex(ml.mesh, at(s.shape_line));
}

/// A URDF material as a skin, once each: its colour as RCColoredSkin's Color (guide 6.4.1:
/// ambient and diffuse half of it), its texture as RCTexturedSkin's.
int Import::skinOf(int material) {
  if (material < 0) return 0;
  const size_t m = static_cast<size_t>(material);
  if (skin_index_[m] >= 0) return skin_index_[m];
  const UrdfMaterial& u = robot_.materials[m];
  SkinDef d;
  d.key = key_ + ".material." + (u.name.empty() ? std::to_string(m) : urdfKey(u.name));
  const Rgba base = u.has_color ? u.color : Rgba{0.8, 0.8, 0.8, 1};
  auto times = [&](double k) { return Rgba{base[0] * k, base[1] * k, base[2] * k, base[3]}; };
  d.color = base;
  d.ambient = times(0.5);
  d.diffuse = times(0.5);
  d.specular = times(2.0);
  d.emission = {0, 0, 0, base[3]};
  if (!u.texture_path.empty()) {
    std::error_code ec;
    d.texture = std::filesystem::absolute(u.texture_path, ec).string();
    d.base_dir = ".";
  }
  skin_index_[m] = static_cast<int>(ctx_.model.skins.size());
  ctx_.model.skins.push_back(d);
  return skin_index_[m];
}

void Import::addJoints() {
  joint_index_.assign(robot_.joints.size(), -1);
  for (size_t ji = 0; ji < robot_.joints.size(); ++ji) addJoint(ji);
  for (size_t ji = 0; ji < robot_.joints.size(); ++ji) {  // mimics: after every joint they may follow
    const UrdfJoint& j = robot_.joints[ji];
    if (j.mimic < 0 || joint_index_[ji] < 0) continue;
    const int leader = joint_index_[static_cast<size_t>(j.mimic)];
    JointDef& jd = ctx_.model.joints[static_cast<size_t>(joint_index_[ji])];
    if (!std::isfinite(j.multiplier) || !std::isfinite(j.offset)) {
      error(j.mimic_line, "joint '" + j.name + "': <mimic> multiplier and offset must be finite");
      continue;
    }
    if (leader < 0) {
      error(j.mimic_line, "joint '" + j.name + "': <mimic> follows joint '" +
                              robot_.joints[static_cast<size_t>(j.mimic)].name + "', which does not move");
      continue;
    }
    jd.mimic = leader;
    jd.mimic_multiplier = j.multiplier;
    jd.mimic_offset = j.offset;
    jd.mimic_max_force = j.effort > 0 ? j.effort : c_.get(kMaxForce);
    note(j.mimic_line, "joint '" + j.name + "' follows '" + robot_.joints[static_cast<size_t>(j.mimic)].name +
                           "' (q = " + formatNumber(j.multiplier) + " q_leader + " + formatNumber(j.offset) +
                           "), held by its motor with at most " + formatNumber(jd.mimic_max_force) +
                           (jd.kind == JointKind::Hinge ? " N m" : " N"));
  }
}

void Import::addJoint(size_t ji) {
  const UrdfJoint& j = robot_.joints[ji];
  const int parent_body = body_index_[static_cast<size_t>(plan_.link_body[static_cast<size_t>(j.parent)])];
  const int child_body = body_index_[static_cast<size_t>(plan_.link_body[static_cast<size_t>(j.child)])];
  switch (j.type) {
    case UrdfJoint::Fixed:
      if (j.child != robot_.root)
        note(j.line, "link '" + link(j.child).name + "' is fixed to '" + link(j.parent).name + "' (joint '" + j.name +
                         "'): lumped into " +
                         (child_body >= 0 ? "body '" + ctx_.model.bodies[static_cast<size_t>(child_body)].key + "'"
                                          : std::string("the world")) +
                         ", its trajectory row kept");
      return;
    case UrdfJoint::Floating:
      note(j.line, "joint '" + j.name + "' is floating: link '" + link(j.child).name + "' is a free body");
      return;
    case UrdfJoint::Planar:
      error(j.line, "joint '" + j.name +
                        "': planar joints are not supported (use two prismatic joints and a "
                        "continuous one through massive links)");
      return;
    case UrdfJoint::Revolute:
    case UrdfJoint::Continuous:
    case UrdfJoint::Prismatic:
      break;
  }
  JointDef d;
  d.key = key_ + "." + urdfKey(j.name);
  d.loc = at(j.line);
  d.kind = j.type == UrdfJoint::Prismatic ? JointKind::Slider : JointKind::Hinge;
  d.body1 = parent_body;
  d.body2 = child_body;
  const Transform& child = plan_.link_global[static_cast<size_t>(j.child)];
  d.anchor = urdfToScene(place_, child).p;
  d.axis = urdfDirToScene(place_, rotate(child.q, j.axis));
  if (j.type != UrdfJoint::Continuous && j.has_limit) {
    if (!(j.lower <= j.upper) || std::isnan(j.lower) || std::isnan(j.upper)) {
      error(j.limit_line, "joint '" + j.name + "': lower limit " + formatNumber(j.lower) + " is above upper " +
                              formatNumber(j.upper));
      return;
    }
    d.lo_stop = j.lower;
    d.hi_stop = j.upper;
  }
  if (!(j.damping >= 0 && j.friction >= 0 && std::isfinite(j.damping) && std::isfinite(j.friction))) {
    error(j.dynamics_line, "joint '" + j.name + "': damping and friction must be finite and >= 0");
    return;
  }
  d.damping = j.damping;
  d.friction = j.friction;
  joint_index_[ji] = static_cast<int>(ctx_.model.joints.size());
  ctx_.recordJoint(d.key, joint_index_[ji]);
  ctx_.model.joints.push_back(d);
}

void Import::addDrives() {
  const auto drives = static_cast<UrdfDrives>(c_.get(kDrives));
  if (drives == UrdfDrives::None) return;
  for (size_t ji = 0; ji < robot_.joints.size(); ++ji) {
    const UrdfJoint& j = robot_.joints[ji];
    if (!urdfJointDriven(j) || joint_index_[ji] < 0) continue;
    const bool hinge = j.type != UrdfJoint::Prismatic;
    ActuatorDef a;
    a.key = keyOf(j.name);
    a.loc = at(j.line);
    a.kind = drives == UrdfDrives::Position   ? ActuatorDef::Servo
             : drives == UrdfDrives::Velocity ? ActuatorDef::VelDrive
                                              : ActuatorDef::Effort;
    a.joint = joint_index_[ji];
    const int line = j.limit_line ? j.limit_line : j.line;
    a.max_power = j.effort > 0 ? j.effort : c_.get(kMaxForce);
    if (!(j.effort > 0))
      note(line, "joint '" + j.name + "': " + (j.has_limit ? "effort=\"0\"" : "no <limit effort>") +
                     " (what exporters write when nobody set it): its drive takes MaxForce " +
                     formatNumber(a.max_power) + (hinge ? " N m" : " N"));
    a.max_velocity = j.velocity > 0 ? j.velocity : c_.get(kMaxVelocity);
    if (!(j.velocity > 0))
      note(line, "joint '" + j.name + "': no velocity limit: its drive takes MaxVelocity " +
                     formatNumber(a.max_velocity) + (hinge ? " rad/s" : " m/s"));
    const JointDef& jd = ctx_.model.joints[static_cast<size_t>(a.joint)];
    a.min_pos = jd.lo_stop;
    a.max_pos = jd.hi_stop;
    a.smooth = c_.get(kSmooth);
    ctx_.recordActuator(a.key, static_cast<int>(ctx_.model.actuators.size()));
    ctx_.model.actuators.push_back(a);
    ++drives_;
  }
}

/// Every link's key leads to its body (Refs of cameras, constructions and sensors).
void Import::remember() {
  BuiltMemo& memo = ctx_.clone.active && ctx_.clone.inside.count(ctx_.indexOf(c_)) ? ctx_.clone.memo : ctx_.memo;
  for (size_t li = 0; li < robot_.links.size(); ++li) {
    const int pb = plan_.link_body[li];
    if (pb < 0) continue;
    const UrdfBody& b = plan_.bodies[static_cast<size_t>(pb)];
    Built built;
    built.index = body_index_[static_cast<size_t>(pb)];
    built.frame = urdfToScene(place_, plan_.link_global[static_cast<size_t>(b.root)]);
    built.ok = true;
    if (built.index >= 0) ctx_.recordBody(keyOf(robot_.links[li].name), built.index);
    if (const Component* p = placeholder(robot_.links[li].name)) memo.set(ctx_.indexOf(*p), built);
  }
}

void Import::summarise() {
  report_.key = key_;
  report_.loc = at(robot_.line);
  std::map<std::string, int> by_type;
  for (const UrdfJoint& j : robot_.joints) ++by_type[urdfJointTypeName(j.type)];
  int lumped = 0, meshes = 0, moving = 0;
  double mass = 0;
  for (const UrdfBody& b : plan_.bodies) {
    lumped += static_cast<int>(b.links.size()) - 1;
    if (!b.fixed) {
      ++moving;
      mass += b.mass;
    }
  }
  size_t vertices = 0;
  std::set<const MeshData*> seen;
  for (const MeshDef& m : ctx_.model.meshes)
    if (m.loc.file == robot_.file && seen.insert(m.data.get()).second) vertices += m.data->vertices.size();
  for (const UrdfLink& l : robot_.links)
    for (const auto* shapes : {&l.visuals, &l.collisions})
      for (const UrdfShape& s : *shapes) meshes += s.kind == UrdfShape::Mesh;
  std::string joints;
  for (const auto& [type, n] : by_type) joints += (joints.empty() ? "" : ", ") + std::to_string(n) + " " + type;
  report_.text = "robot '" + robot_.name + "': " + std::to_string(robot_.links.size()) + " links (" +
                 std::to_string(moving) + " moving bodies, " + std::to_string(lumped) + " lumped), " +
                 std::to_string(robot_.joints.size()) + " joints" + (joints.empty() ? "" : " (" + joints + ")") + ", " +
                 std::to_string(drives_) + " drives, " + std::to_string(meshes) + " mesh shapes" +
                 (meshes == 0 ? std::string()
                              : " (" + std::to_string(seen.size()) + " meshes, " + std::to_string(vertices) +
                                    " vertices; collisions: " + std::to_string(hulls_) + " convex hulls, " +
                                    std::to_string(trimeshes_) + " triangle meshes)") +
                 ", total mass " + formatApprox(mass) + " kg";
  std::stable_sort(report_.notes.begin(), report_.notes.end(),
                   [](const Error& a, const Error& b) { return a.loc.line < b.loc.line; });
}

/// The lowest point of a collision geom placed at `t` along the direction `n` (unit): a box's
/// lowest corner, a sphere's centre less its radius, a cylinder's lowest rim point, a mesh's
/// lowest vertex.
double lowestAlong(const Model& model, const GeomDef& g, const Transform& t, const Vec3& n) {
  double lowest = std::numeric_limits<double>::infinity();
  auto reach = [&](const Vec3& local) { lowest = std::min(lowest, dot(n, add(t.p, rotate(t.q, local)))); };
  switch (g.shape) {
    case GeomShape::Box:
      for (int k = 0; k < 8; ++k)
        reach({k & 1 ? g.size[0] / 2 : -g.size[0] / 2, k & 2 ? g.size[1] / 2 : -g.size[1] / 2,
               k & 4 ? g.size[2] / 2 : -g.size[2] / 2});
      return lowest;
    case GeomShape::Sphere:
      return dot(n, t.p) - g.size[0];
    case GeomShape::Cylinder:
    case GeomShape::Capsule: {  // axis along the shape's z: each end's circle dips r sin(tilt)
      const double an = dot(n, rotate(t.q, Vec3{0, 0, 1}));
      const double rim = g.size[0] * std::sqrt(std::max(0.0, 1 - an * an));
      return dot(n, t.p) - std::abs(an) * g.size[1] / 2 - (g.shape == GeomShape::Capsule ? g.size[0] : rim);
    }
    case GeomShape::ConvexHull:
    case GeomShape::TriMesh:
      if (g.mesh < 0) return lowest;
      for (const Vec3& v : model.meshes[static_cast<size_t>(g.mesh)].data->vertices) reach(v);
      return lowest;
    case GeomShape::Plane:
      return lowest;
  }
  return lowest;
}

}  // namespace

/// A robot fixed to the world is bolted where it is put (never raised): one whose moving links
/// start more than 1 mm inside a static plane (the ground) is refused at the deepest link's line,
/// as ODE would tear it apart at the first step; a bare .urdf and a scene's RCImportURDF alike
/// (KR5's file lays its arm along URDF +Y, in the ground).
void checkFixedUrdfRobots(CompileContext& ctx) {
  std::vector<const GeomDef*> planes;
  for (const GeomDef& g : ctx.model.geoms)
    if (g.shape == GeomShape::Plane && g.body < 0 && !g.sensor) planes.push_back(&g);
  for (const CompileContext::FixedUrdfRobot& r : ctx.fixed_urdf_robots) {
    double deepest = -0.001;
    const CompileContext::FixedUrdfShape* at = nullptr;
    const GeomDef* in = nullptr;
    for (const CompileContext::FixedUrdfShape& s : r.shapes)
      for (const GeomDef* p : planes) {
        const Vec3 n{p->plane[0], p->plane[1], p->plane[2]};
        const double c = lowestAlong(ctx.model, ctx.model.geoms[static_cast<size_t>(s.geom)], s.at, n) - p->plane[3];
        if (c < deepest) {
          deepest = c;
          at = &s;
          in = p;
        }
      }
    if (!at) continue;
    const UrdfLink& l = r.robot->links[static_cast<size_t>(at->link)];
    ctx.diag.error({r.robot->file, l.line},
                   "link '" + l.name + "' of a robot fixed to the world starts " + formatApprox(-deepest) +
                       " m inside " + (r.bare ? std::string("the ground") : "the plane of '" + in->key + "'") +
                       ": a robot fixed to the world is not raised; " +
                       (r.bare ? "place it with RCImportURDF's Pose in a scene" : "move it with RCImportURDF's Pose") +
                       " (is the file's up axis +Z?)");
  }
}

void registerUrdfImport(Registry& r) {
  r.add({"RCImportURDF",
         Family::Body,
         int(BodyKind::Urdf),
         {componentParam(kPose, {Family::Pose}, "",
                         "where the robot's root link goes (default: the origin; URDF's +Z becomes the scene's +Y)"),
          text(kFileParam, "", "URDF file; relative to this file"),
          flag(kFixedBase, false, "fix the root link to the world (a root link named 'world' always is)"),
          enumParam(kDrives, ValueType::Enum, &kDrivesTable, 0,
                    "a drive on every movable joint, keyed IMPORTKEY.joint: none (passive), position (RCPosControl), "
                    "velocity (RCVelControl) or effort (RCDriver; its command is the force or torque)"),
          number(kMaxForce, 100.0, "N or N m",
                 "a drive's largest force or torque where the URDF gives no effort (or 0)", Range::Positive),
          number(kMaxVelocity, 1.0, "m/s or rad/s", "a drive's largest velocity where the URDF gives none (or 0)",
                 Range::Positive),
          number(kSmooth, 0.05, "s", "position drives: time constant of the final approach (RCGenericServo's Smooth)",
                 Range::Positive),
          text(kPackages, "",
               "'NAME=DIR;NAME=DIR' (relative to this file): where package://NAME/... is, after a package.xml above "
               "the URDF and ROS_PACKAGE_PATH"),
          componentParam(kMaterial, {Family::Material}, "RCGenericMaterial", "contact properties of every collision"),
          enumParam(kCollisions, ValueType::Enum, &kCollisionsTable, 0,
                    "mesh collisions of moving links: their convex hull (hull) or their triangles (mesh); links fixed "
                    "to the world always collide with the triangles"),
          flag(kSelfCollision, false,
               "its links collide with each other (those a joint connects never do); off: only with the rest of "
               "the scene"),
          flag(kAboveGround, false,
               "raise a floating robot whose collision shapes reach below y = 0 until the lowest touches it (a bare "
               ".urdf file sets it)")},
         {},
         "A robot read from a URDF file (docs/urdf.md): a body per link and the links fixed to it, keyed "
         "IMPORTKEY.link; passive joints unless Drives says otherwise.",
         false,
         "robot"});
  r.add({"URDFLink",
         Family::Body,
         int(BodyKind::UrdfLink),
         {},
         {},
         "A link of an RCImportURDF, keyed IMPORTKEY.link: made by the import (never written), for Refs."});
  const char* names[] = {"URDFPositionDrive", "URDFVelocityDrive", "URDFEffortDrive"};
  const char* interfaces[] = {"RCPosControl", "RCVelControl", "RCDriver"};
  for (int i = 0; i < 3; ++i) {
    TypeSpec t{names[i],
               Family::Periphery,
               int(PeripheryKind::UrdfDrive),
               {},
               {},
               "A drive of an RCImportURDF (Drives), keyed IMPORTKEY.joint: made by the import, for Refs."};
    t.interfaces = {interfaces[i]};
    r.add(t);
  }
}

Built lowerUrdfImport(CompileContext& ctx, const Component& c, const Transform* parent) {
  auto it = ctx.scene.urdf.find(ctx.indexOf(c));
  if (it == ctx.scene.urdf.end() || !it->second) return Built{};  // reading it failed and was reported
  Import im(ctx, c, *it->second);
  return im.lower(parent);
}

Built lowerUrdfLink(CompileContext& ctx, const Component& c) {
  const Component* owner = c.parent >= 0 ? &ctx.at(c.parent) : nullptr;
  if (!owner || owner->type->family != Family::Body || static_cast<BodyKind>(owner->type->kind) != BodyKind::Urdf) {
    ctx.error(c, "made by an RCImportURDF for each link; it cannot be written in a scene");
    return Built{};
  }
  lowerBody(ctx, c.parent, nullptr);  // remembers every link
  const int ci = ctx.indexOf(c);
  const BuiltMemo& memo = ctx.clone.active && ctx.clone.inside.count(ci) ? ctx.clone.memo : ctx.memo;
  const Built* built = memo.find(ci);
  return built ? *built : Built{};
}

}  // namespace simbob
