// Model checks (simbob check): warnings about legal scenes that make ODE unstable or wrong. They work on the compiled Model
// (plain data), so they see exactly what the physics layer will get.
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <set>

#include <Eigen/Eigenvalues>

#include "simbob/compile.h"
#include "simbob/transform.h"
#include "simbob/values.h"

namespace simbob {

namespace {

constexpr double kMassRatio = 100.0;      // QuickStep converges poorly beyond this
constexpr double kInertiaRatio = 1e-5;    // own inertia below this fraction of m d^2: joints come apart
constexpr double kStepsPerPeriod = 40.0;  // fewer steps per swing loses energy visibly or comes apart
constexpr double kAnchorFar = 10.0;       // anchor farther than this many body sizes
constexpr double kAnchorFarMin = 2.0;     // m; pendulum rods up to this length are normal
constexpr double kOverlap = 1e-3;         // m of penetration that counts as overlap
constexpr int kMaxPerKind = 20;
constexpr double kRunaway = 1e6;  // m and m/s: SimulationOptions::runaway_limit

double boundingRadius(const GeomDef& g) {
  switch (g.shape) {
    case GeomShape::Box:
    case GeomShape::ConvexHull:  // a mesh is checked as its bounding box (meshBox)
    case GeomShape::TriMesh:
      return 0.5 * norm(g.size);
    case GeomShape::Sphere:
      return g.size[0];
    case GeomShape::Cylinder:
      return std::hypot(g.size[0], g.size[1] / 2);
    case GeomShape::Capsule:
      return g.size[0] + g.size[1] / 2;
    case GeomShape::Plane:
      return 0;
  }
  return 0;
}

double thickness(const GeomDef& g) {
  switch (g.shape) {
    case GeomShape::Box:
    case GeomShape::ConvexHull:
    case GeomShape::TriMesh:
      return std::min({g.size[0], g.size[1], g.size[2]});
    case GeomShape::Sphere:
    case GeomShape::Cylinder:
    case GeomShape::Capsule:
      return 2 * g.size[0];
    case GeomShape::Plane:
      return 0;
  }
  return 0;
}

// Half extents of the geom's axis-aligned bounds in the global frame.
Vec3 halfExtents(const GeomDef& g, const Quat& q) {
  Vec3 local{0, 0, 0};  // every shape sets it; the switch has no default
  switch (g.shape) {
    case GeomShape::Box:
    case GeomShape::ConvexHull:
    case GeomShape::TriMesh:
      local = scale(g.size, 0.5);
      break;
    case GeomShape::Sphere:
      return {g.size[0], g.size[0], g.size[0]};
    case GeomShape::Cylinder:
      local = {g.size[0], g.size[0], g.size[1] / 2};
      break;
    case GeomShape::Capsule:
      local = {g.size[0], g.size[0], g.size[1] / 2 + g.size[0]};
      break;
    case GeomShape::Plane:
      return {0, 0, 0};
  }
  Mat3 r = toMatrix(q);
  Vec3 out;
  for (size_t i = 0; i < 3; ++i)
    out[i] = std::fabs(r[i * 3]) * local[0] + std::fabs(r[i * 3 + 1]) * local[1] + std::fabs(r[i * 3 + 2]) * local[2];
  return out;
}

// Lowest signed distance of the geom's surface below a plane (negative = penetrating).
double planeClearance(const GeomDef& g, const Transform& t, const std::array<double, 4>& plane) {
  Vec3 n{plane[0], plane[1], plane[2]};
  double center = dot(n, t.p) - plane[3];
  switch (g.shape) {
    case GeomShape::Sphere:
      return center - g.size[0];
    case GeomShape::Capsule: {
      Vec3 axis = rotate(t.q, {0, 0, 1});
      return center - std::fabs(dot(n, axis)) * g.size[1] / 2 - g.size[0];
    }
    case GeomShape::Box:
    case GeomShape::ConvexHull:
    case GeomShape::TriMesh:
    case GeomShape::Cylinder: {
      Vec3 h = halfExtents(g, {1, 0, 0, 0});
      Mat3 r = toMatrix(t.q);
      // Support of the rotated box (a cylinder is treated as its bounding box) along -n.
      double reach = 0;
      for (int k = 0; k < 3; ++k) reach += std::fabs(n[0] * r[k] + n[1] * r[3 + k] + n[2] * r[6 + k]) * h[k];
      return center - reach;
    }
    case GeomShape::Plane:
      return 1e300;
  }
  return 1e300;
}

// What the checks see of a mesh geom: its bounding box (size = the extents, offset moved to the
// box's centre), so every check of a geom's extent works on it as on a box.
GeomDef meshBox(const Model& m, const GeomDef& g) {
  GeomDef box = g;
  if (g.mesh < 0 || static_cast<size_t>(g.mesh) >= m.meshes.size()) return box;
  const MeshData& mesh = *m.meshes[static_cast<size_t>(g.mesh)].data;
  box.size = sub(mesh.hi, mesh.lo);
  box.offset = compose(g.offset, Transform{scale(add(mesh.lo, mesh.hi), 0.5), {1, 0, 0, 0}});
  return box;
}

struct Placed {
  const GeomDef* g;
  Transform t;  // global
  Vec3 lo, hi;  // global bounds
};

// The geoms of a scene in the cells of a grid over x and z (y is up), for the overlap search. A
// sweep along x alone looks at every pair of a grid's column (5,000 boxes on a floor: 175,000
// pairs); the cells give each geom its neighbours. Geoms are named by their position in the
// sweep's order. A geom in more than kMaxCells cells is a neighbour of every other instead.
class CellGrid {
 public:
  CellGrid(const std::vector<Placed>& placed, const std::vector<size_t>& order) : n_(order.size()) {
    if (n_ < 2) return;
    // Cells as wide as the median geom (the grid suits the many small ones), never so narrow
    // that the scene is more than kMaxCellsAcross of them across.
    std::vector<double> widths(n_);
    double x1 = -1e300, z1 = -1e300;
    for (size_t r = 0; r < n_; ++r) {
      const Placed& p = placed[order[r]];
      widths[r] = std::max(p.hi[0] - p.lo[0], p.hi[2] - p.lo[2]);
      x0_ = std::min(x0_, p.lo[0]);
      z0_ = std::min(z0_, p.lo[2]);
      x1 = std::max(x1, p.hi[0]);
      z1 = std::max(z1, p.hi[2]);
    }
    std::nth_element(widths.begin(), widths.begin() + static_cast<ptrdiff_t>(n_ / 2), widths.end());
    cell_ = std::max({widths[n_ / 2], (x1 - x0_) / kMaxCellsAcross, (z1 - z0_) / kMaxCellsAcross, 1e-9});
    ranges_.resize(n_);
    wide_.assign(n_, 0);
    size_t listed = 0;
    for (size_t r = 0; r < n_; ++r) {
      const Placed& p = placed[order[r]];
      // Bounds that merely touch share a cell: the sweep's own tests decide.
      const Range c{cellOf(p.lo[0], x0_), cellOf(p.hi[0], x0_), cellOf(p.lo[2], z0_), cellOf(p.hi[2], z0_)};
      ranges_[r] = c;
      const uint64_t cells = uint64_t{c.x1 - c.x0 + 1} * (c.z1 - c.z0 + 1);
      if (cells > kMaxCells) {
        wide_[r] = 1;
        wide_list_.push_back(static_cast<uint32_t>(r));
      } else {
        listed += cells;
      }
    }
    // Each cell's geoms as a chain through entries_, from an open-addressing table of cells.
    size_t slots = 16;
    while (slots < listed * 2) slots *= 2;
    table_.assign(slots, {0, kNone});
    entries_.reserve(listed);
    for (size_t r = n_; r-- > 0;) {  // last first: each chain ends up in ascending order
      if (wide_[r]) continue;
      const Range& c = ranges_[r];
      for (uint32_t x = c.x0; x <= c.x1; ++x)
        for (uint32_t z = c.z0; z <= c.z1; ++z) {
          Slot& s = table_[find(key(x, z))];
          s.key = key(x, z);
          entries_.push_back({static_cast<uint32_t>(r), s.head});
          s.head = static_cast<uint32_t>(entries_.size() - 1);
        }
    }
  }

  /// The positions after `oi` of the geoms that share a cell with it, ascending, into *out.
  void later(uint32_t oi, std::vector<uint32_t>* out) const {
    out->clear();
    if (oi >= ranges_.size()) return;  // one geom alone (or none): no grid, no pairs
    if (wide_[oi]) {
      for (size_t r = oi + 1; r < n_; ++r) out->push_back(static_cast<uint32_t>(r));
      return;
    }
    const Range& a = ranges_[oi];
    for (uint32_t x = a.x0; x <= a.x1; ++x)
      for (uint32_t z = a.z0; z <= a.z1; ++z) {
        for (uint32_t e = table_[find(key(x, z))].head; e != kNone; e = entries_[e].next) {
          const uint32_t r = entries_[e].pos;
          if (r <= oi) continue;
          // A pair that shares several cells is taken in the first of them only.
          const Range& b = ranges_[r];
          if (x == std::max(a.x0, b.x0) && z == std::max(a.z0, b.z0)) out->push_back(r);
        }
      }
    for (uint32_t w : wide_list_)
      if (w > oi) out->push_back(w);
    std::sort(out->begin(), out->end());
  }

 private:
  static constexpr uint64_t kMaxCells = 16;
  static constexpr double kMaxCellsAcross = 65536;  // cell numbers stay small integers
  static constexpr uint32_t kNone = 0xffffffffu;
  struct Range {
    uint32_t x0, x1, z0, z1;
  };
  struct Entry {
    uint32_t pos;   ///< the geom's position in the sweep's order
    uint32_t next;  ///< the next entry of the same cell, kNone at the end
  };
  struct Slot {
    uint64_t key;
    uint32_t head;  ///< first entry of the cell; kNone: the slot is empty
  };

  uint32_t cellOf(double v, double origin) const {
    const double c = std::floor((v - origin) / cell_);
    return static_cast<uint32_t>(c >= 0 ? std::min(c, kMaxCellsAcross + 1) : 0);  // NaN: 0
  }
  static uint64_t key(uint32_t x, uint32_t z) { return uint64_t{x} << 32 | z; }
  // The index of the cell's slot: its own, or the empty one where it would go.
  size_t find(uint64_t k) const {
    const size_t mask = table_.size() - 1;
    for (size_t i = static_cast<size_t>((k * 0x9E3779B97F4A7C15ull) >> 32) & mask;; i = (i + 1) & mask)
      if (table_[i].head == kNone || table_[i].key == k) return i;
  }

  size_t n_ = 0;
  double x0_ = 1e300, z0_ = 1e300, cell_ = 1;
  std::vector<Range> ranges_;
  std::vector<char> wide_;
  std::vector<uint32_t> wide_list_;
  std::vector<Entry> entries_;
  std::vector<Slot> table_;
};

/// Calls f(joint, body, d, smallest, reference) for each body at distance d from a hinge or ball
/// joint whose smallest moment of inertia is below kInertiaRatio of m d^2 (reference).
template <class F>
void forEachUnholdable(const Model& m, F f) {
  for (const JointDef& j : m.joints) {
    if (j.kind != JointKind::Hinge && j.kind != JointKind::BallSocket) continue;
    for (int bi : {j.body1, j.body2}) {
      if (bi < 0) continue;
      const BodyDef& b = m.bodies[static_cast<size_t>(bi)];
      const Vec3 com = add(b.pose.p, rotate(b.pose.q, b.com));
      const double d = norm(sub(com, j.anchor));
      const Eigen::Matrix3d inertia = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(b.inertia.data());
      const double smallest =
          Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia, Eigen::EigenvaluesOnly).eigenvalues()[0];
      const double reference = b.mass * d * d;
      if (reference > 0 && smallest < kInertiaRatio * reference) f(j, bi, d, smallest, reference);
    }
  }
}

class Linter {
 public:
  Linter(const Model& m, Diagnostics& d, double dt) : m_(m), d_(d), dt_(dt > 0 ? dt : m.settings.max_time_step) {}

  /// The largest step no check warns about (infinity: none limits it).
  double recommendedStep() const { return recommended_; }

  void run() {
    farAway();
    place();
    massRatios();
    inertiaRatios();
    pendulums();
    anchors();
    tunneling();
    overlaps();
    wheelAxles();
    triMeshPairs();
    for (const auto& [kind, n] : suppressed_)
      if (n > 0)
        d_.warning(
            {}, "... and " + countOf(static_cast<size_t>(n), "more warning", "more warnings") + " like '" + kind + "'");
  }

  /// What a warning is about, as data: indices into Model::bodies and Model::joints.
  struct Subjects {
    std::vector<int> bodies, joints;
  };

  /// The first warning said about body `body` or joint `joint` (-1: none), or "".
  std::string firstAbout(int body, int joint) const {
    for (const auto& [s, message] : findings_)
      if ((body >= 0 && std::count(s.bodies.begin(), s.bodies.end(), body)) ||
          (joint >= 0 && std::count(s.joints.begin(), s.joints.end(), joint)))
        return message;
    return "";
  }

 private:
  void warn(const std::string& kind, const SourceLoc& loc, Subjects about, const std::string& msg) {
    if (++counts_[kind] > kMaxPerKind) {
      ++suppressed_[kind];
      return;
    }
    d_.warning(loc, msg);
    findings_.emplace_back(std::move(about), msg);
  }

  int jointIndex(const JointDef& j) const { return static_cast<int>(&j - m_.joints.data()); }

  // A run stops as diverged when a body is beyond kRunaway m (SimulationOptions::runaway_limit): a
  // body that starts there can never run, whatever the step. An error, not a warning. (A start
  // that fast only diverges at the first step, as it should.)
  void farAway() {
    for (const BodyDef& b : m_.bodies) {
      const double r = norm(b.pose.p);
      if (r > kRunaway)
        d_.error(b.loc, "body '" + b.key + "' starts " + formatApprox(r) +
                            " m from the origin, beyond the 1e+06 m at which a run stops as diverged; move the scene "
                            "nearer the origin");
    }
  }

  void place() {
    size_ = std::vector<double>(m_.bodies.size(), 0.0);
    thin_ = std::vector<double>(m_.bodies.size(), 1e300);
    for (const GeomDef& geom : m_.geoms) {
      if (geom.sensor) continue;  // sensor volumes push nothing: overlapping is what they are for
      if (geom.shape == GeomShape::Plane) {
        planes_.push_back(&geom);
        continue;
      }
      const bool mesh = geom.shape == GeomShape::ConvexHull || geom.shape == GeomShape::TriMesh;
      const GeomDef& g = mesh ? mesh_boxes_.emplace_back(meshBox(m_, geom)) : geom;
      Placed p;
      p.g = &g;
      p.t = g.body >= 0 ? compose(m_.bodies[static_cast<size_t>(g.body)].pose, g.offset) : g.offset;
      Vec3 h = halfExtents(g, p.t.q);
      p.lo = sub(p.t.p, h);
      p.hi = add(p.t.p, h);
      placed_.push_back(p);
      if (g.body >= 0) {
        auto b = static_cast<size_t>(g.body);
        size_[b] = std::max(size_[b], norm(g.offset.p) + boundingRadius(g));
        thin_[b] = std::min(thin_[b], thickness(g));
      }
    }
    for (const JointDef& j : m_.joints) {
      int a = std::min(j.body1, j.body2), b = std::max(j.body1, j.body2);
      if (a >= 0) joined_.insert({a, b});
    }
  }

  // RCTwoWheelMotionControl turns a wheel forward with a positive command: the wheel must turn
  // about the robot's left, the direction from the right wheel's hinge anchor to the left one's.
  // An axle the other way turns its wheel backwards on a forward command.
  void wheelAxles() {
    for (const ControllerDef& c : m_.controllers) {
      if (c.kind() != ControllerDef::TwoWheel) continue;
      const TwoWheelDef& wheels = c.as<TwoWheelDef>();
      const JointDef* j[2] = {};
      for (size_t k = 0; k < 2; ++k) {
        const int a = k == 0 ? wheels.left : wheels.right;
        if (a < 0 || static_cast<size_t>(a) >= m_.actuators.size()) break;
        const int ji = m_.actuators[static_cast<size_t>(a)].joint;
        if (ji >= 0 && m_.joints[static_cast<size_t>(ji)].kind == JointKind::Hinge)
          j[k] = &m_.joints[static_cast<size_t>(ji)];
      }
      if (!j[0] || !j[1]) continue;
      // The chassis is the body both hinges hold; each wheel is the other one.
      int chassis = -1;
      for (int b : {j[0]->body1, j[0]->body2})
        if (b >= 0 && (b == j[1]->body1 || b == j[1]->body2)) chassis = b;
      const Vec3 left = sub(j[0]->anchor, j[1]->anchor);
      if (chassis < 0 || norm(left) < 1e-9) continue;
      const char* side[2] = {"left", "right"};
      for (size_t k = 0; k < 2; ++k) {
        // A positive command turns the child relative to the parent about +axis.
        const Vec3 wheel_axis = j[k]->body2 == chassis ? scale(j[k]->axis, -1) : j[k]->axis;
        if (dot(wheel_axis, left) >= 0) continue;
        warn("wheel axle", j[k]->loc, {{}, {jointIndex(*j[k])}},
             "joint '" + j[k]->key + "' (the " + side[k] + " wheel of RCTwoWheelMotionControl '" + c.key +
                 "') turns its wheel backwards on a forward command: the wheel turns about the robot's right; "
                 "point the hinge axis from the right wheel to the left one (now " +
                 formatApprox(j[k]->axis[0]) + " " + formatApprox(j[k]->axis[1]) + " " + formatApprox(j[k]->axis[2]) +
                 ")");
      }
    }
  }

  double dt() const { return dt_; }
  const BodyDef& body(int i) const { return m_.bodies[static_cast<size_t>(i)]; }

  void massRatios() {
    for (const JointDef& j : m_.joints) {
      if (j.body1 < 0 || j.body2 < 0) continue;
      double a = body(j.body1).mass, b = body(j.body2).mass;
      double ratio = std::max(a, b) / std::min(a, b);
      if (ratio > kMassRatio)
        warn("mass ratio", j.loc, {{}, {jointIndex(j)}},
             "joint '" + j.key + "' connects masses " + formatApprox(a) + " kg and " + formatApprox(b) + " kg (ratio " +
                 formatApprox(std::round(ratio)) + " > " + formatApprox(kMassRatio) +
                 "): QuickStep converges slowly and joints stretch; bring the masses closer, raise "
                 "SolverIterations or use Solver Step");
    }
  }

  // A body swinging at distance d from a joint with an inertia far below m d^2 makes the joint's
  // effective-mass matrix nearly singular: QuickStep then lets the joint drift apart (Step, an
  // exact solve, holds it: no warning there).
  void inertiaRatios() {
    if (!m_.settings.quickstep) return;
    forEachUnholdable(m_, [&](const JointDef& j, int bi, double d, double smallest, double reference) {
      const BodyDef& b = body(bi);
      const std::string advice =
          b.inertia_loc.line > 0
              ? "give the link a realistic <inertia> (" + b.inertia_loc.file.str() + ":" +
                    std::to_string(b.inertia_loc.line) + ") or step with Solver Step (--set SceneSettings.Solver=Step)"
              : "give the body a realistic inertia (RCInertiaByGeom computes it from the geoms) or use Solver Step";
      warn("inertia ratio", b.loc, {{bi}, {jointIndex(j)}},
           "body '" + b.key + "' (" + formatApprox(b.mass) + " kg) sits " + formatApprox(d) + " m from joint '" +
               j.key + "' but its smallest moment of inertia is " + formatApprox(smallest) + " kg m^2, " +
               formatApprox(smallest / reference) + " of m*d^2 (below " + formatApprox(kInertiaRatio) +
               "): the solver cannot hold the joint together; " + advice);
    });
  }

  // The fastest gravity pendulum formed by a hinge or ball joint and its child body.
  void pendulums() {
    double g = norm(m_.settings.gravity);
    if (g <= 0) return;
    for (const JointDef& j : m_.joints) {
      if (j.body2 < 0 || (j.kind != JointKind::Hinge && j.kind != JointKind::BallSocket)) continue;
      const BodyDef& b = body(j.body2);
      Vec3 r = sub(b.pose.p, j.anchor);
      Vec3 gdir = scale(m_.settings.gravity, 1.0 / g);
      double i_pivot = 0, lever = 0, g_eff = g;
      Mat3 rot = toMatrix(b.pose.q);
      auto inertiaAbout = [&](const Vec3& axis) {
        // axis^T R I R^T axis
        Vec3 local{0, 0, 0};
        for (int k = 0; k < 3; ++k) local[k] = rot[k] * axis[0] + rot[3 + k] * axis[1] + rot[6 + k] * axis[2];
        double s = 0;
        for (int p = 0; p < 3; ++p)
          for (int q = 0; q < 3; ++q) s += local[p] * b.inertia[p * 3 + q] * local[q];
        return s;
      };
      if (j.kind == JointKind::Hinge) {
        Vec3 axis = j.axis;
        Vec3 perp = sub(r, scale(axis, dot(r, axis)));
        lever = norm(perp);
        double ga = dot(gdir, axis);
        g_eff = g * std::sqrt(std::max(0.0, 1 - ga * ga));
        i_pivot = inertiaAbout(axis) + b.mass * lever * lever;
      } else {
        lever = norm(r);
        Vec3 axis = lever > 0 ? cross(scale(r, 1 / lever), gdir) : Vec3{1, 0, 0};
        double n = norm(axis);
        axis = n > 1e-9 ? scale(axis, 1 / n) : Vec3{1, 0, 0};
        i_pivot = inertiaAbout(axis) + b.mass * lever * lever;
      }
      if (lever < 1e-9 || g_eff <= 0 || i_pivot <= 0) continue;
      double period = 2 * kPi * std::sqrt(i_pivot / (b.mass * g_eff * lever));
      recommended_ = std::min(recommended_, period / kStepsPerPeriod);
      if (dt() > period / kStepsPerPeriod)
        warn("step size", j.loc, {{}, {jointIndex(j)}},
             "joint '" + j.key + "' makes a pendulum of period " + formatApprox(period) + " s but the step is " +
                 formatApprox(dt()) + " s (fewer than " + formatApprox(kStepsPerPeriod) +
                 " steps per swing): the motion loses energy or blows up; use --dt " +
                 formatApprox(period / kStepsPerPeriod) + " or smaller");
    }
  }

  void anchors() {
    for (const JointDef& j : m_.joints) {
      if (j.kind == JointKind::Slider || j.kind == JointKind::Fixed) continue;
      for (int bi : {j.body1, j.body2}) {
        if (bi < 0) continue;
        const BodyDef& b = body(bi);
        double size = std::max(size_[static_cast<size_t>(bi)], 0.01);
        double dist = norm(sub(b.pose.p, j.anchor));
        if (dist > kAnchorFar * size && dist > kAnchorFarMin)
          warn("anchor far", j.loc, {{bi}, {jointIndex(j)}},
               "joint '" + j.key + "' has its anchor " + formatApprox(dist) + " m from body '" + b.key + "' (about " +
                   formatApprox(size) +
                   " m in size): check the joint's Pose and Hinge/Anchor "
                   "(RCLocalCoordinates are relative to the joint frame)");
      }
    }
  }

  void tunneling() {
    double g = norm(m_.settings.gravity);
    for (size_t i = 0; i < m_.bodies.size(); ++i) {
      const BodyDef& b = m_.bodies[i];
      if (thin_[i] >= 1e300) continue;
      double fall = 0;
      for (const GeomDef* p : planes_) {
        Vec3 n{p->plane[0], p->plane[1], p->plane[2]};
        if (g > 0 && dot(n, m_.settings.gravity) < 0) {
          double h = dot(n, b.pose.p) - p->plane[3];
          if (h > 0) fall = std::max(fall, std::sqrt(2 * g * h));
        }
      }
      double speed = norm(b.lin_vel) + norm(b.ang_vel) * size_[i] + fall;
      double travel = speed * dt();
      if (speed > 0) recommended_ = std::min(recommended_, 0.5 * thin_[i] / speed);
      if (travel > 0.5 * thin_[i])
        warn("tunneling", b.loc, {{static_cast<int>(i)}, {}},
             "body '" + b.key + "' is " + formatApprox(thin_[i]) + " m thin and may move " + formatApprox(speed) +
                 " m/s, " + formatApprox(travel) +
                 " m per step: it can pass through other bodies in one step; "
                 "use a step below " +
                 formatApprox(0.5 * thin_[i] / speed) + " s or a thicker geom");
    }
  }

  bool joined(int a, int b) const {
    if (a > b) std::swap(a, b);
    return joined_.count({a, b}) > 0;
  }

  std::string owner(const GeomDef& g) const { return g.key.empty() ? std::string("(static)") : g.key; }

  SourceLoc loc(const GeomDef& g) const {
    if (g.loc.line > 0) return g.loc;
    return g.body >= 0 ? body(g.body).loc : SourceLoc{};
  }

  // ODE's trimesh-trimesh contacts jitter, miss and explode: every pair of triangle meshes that
  // can meet (not both static, not on one body) is named, with where each is written.
  void triMeshPairs() {
    std::vector<const GeomDef*> meshes;
    for (const Placed& p : placed_)
      if (p.g->shape == GeomShape::TriMesh) meshes.push_back(p.g);
    for (size_t i = 0; i < meshes.size(); ++i)
      for (size_t j = i + 1; j < meshes.size(); ++j) {
        const GeomDef &a = *meshes[i], &b = *meshes[j];
        if (a.body == b.body || (a.body < 0 && b.body < 0)) continue;
        if (a.group >= 0 && a.group == b.group) continue;  // one URDF robot's links never meet
        auto where = [&](const GeomDef& g) {
          const SourceLoc l = loc(g);
          const std::string file = g.mesh >= 0 ? m_.meshes[static_cast<size_t>(g.mesh)].data->file : "";
          return "'" + owner(g) + "' (" + file.substr(file.find_last_of('/') + 1) +
                 (l.line > 0 ? ", " + l.file.str() + ":" + std::to_string(l.line) : std::string()) + ")";
        };
        warn("trimesh pair", loc(a.body >= 0 ? a : b), {{a.body, b.body}, {}},
             "the triangle meshes of " + where(a) + " and " + where(b) +
                 " can touch: ODE's contacts between two triangle meshes are unreliable; give the moving one "
                 "its convex hull (Hull=\"True\") or a primitive geom");
      }
  }

  void overlaps() {
    // Bodies penetrating static planes.
    for (const Placed& p : placed_) {
      if (p.g->body < 0) continue;
      for (const GeomDef* plane : planes_) {
        double c = planeClearance(*p.g, p.t, plane->plane);
        if (c < -kOverlap)
          warn("overlap", loc(*p.g), {{p.g->body}, {}},
               "body '" + owner(*p.g) + "' starts " + formatApprox(-c) + " m inside the plane of '" + owner(*plane) +
                   "': ODE pushes it out violently at the first step; move it out");
      }
    }
    // Pairs of geoms, looked at in the order of a sweep along x over sorted bounds: for each geom
    // in x order, the later ones whose x range begins inside its own. Only the pairs that share a
    // cell of a grid (CellGrid) are looked at, in the sweep's order: the warnings, and where the
    // search stops, are the sweep's.
    std::vector<size_t> order(placed_.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      return placed_[a].lo[0] < placed_[b].lo[0] || (placed_[a].lo[0] == placed_[b].lo[0] && a < b);
    });
    std::set<std::pair<int, int>> reported;
    // Thousands of coincident bodies overlap pairwise: stop looking once the point is made.
    constexpr size_t kMaxOverlapPairs = 10000;
    const CellGrid grid(placed_, order);
    std::vector<uint32_t> later;
    for (size_t oi = 0; oi < order.size(); ++oi) {
      if (reported.size() >= kMaxOverlapPairs) {
        d_.warning({}, "stopped looking for overlaps after " + std::to_string(kMaxOverlapPairs) +
                           " overlapping pairs of bodies");
        return;
      }
      const Placed& a = placed_[order[oi]];
      grid.later(static_cast<uint32_t>(oi), &later);
      for (const uint32_t oj : later) {
        const Placed& b = placed_[order[oj]];
        if (b.lo[0] > a.hi[0] - kOverlap) break;  // beyond the sweep's window, as all later ones
        const bool spheres = a.g->shape == GeomShape::Sphere && b.g->shape == GeomShape::Sphere;
        double depth = 1e300;
        if (!spheres) {
          for (int k = 2; k >= 0 && depth > kOverlap; --k)
            depth = std::min(depth, std::min(a.hi[k], b.hi[k]) - std::max(a.lo[k], b.lo[k]));
          if (depth <= kOverlap) continue;
        }
        if (a.g->body == b.g->body || (a.g->body < 0 && b.g->body < 0)) continue;
        if (a.g->body >= 0 && b.g->body >= 0 && joined(a.g->body, b.g->body)) continue;
        if (a.g->group >= 0 && a.g->group == b.g->group) continue;  // one URDF robot's links never collide
        // A triangle mesh's bounds say little of its surface: a ramp's box holds what rests on it.
        if (a.g->shape == GeomShape::TriMesh || b.g->shape == GeomShape::TriMesh) continue;
        if (spheres) {
          depth = a.g->size[0] + b.g->size[0] - norm(sub(a.t.p, b.t.p));
          if (depth <= kOverlap) continue;
        }
        std::pair<int, int> key{std::min(a.g->body, b.g->body), std::max(a.g->body, b.g->body)};
        if (!reported.insert(key).second) continue;
        const GeomDef& mob = a.g->body >= 0 ? *a.g : *b.g;
        warn("overlap", loc(mob), {{a.g->body, b.g->body}, {}},
             "bodies '" + owner(*a.g) + "' and '" + owner(*b.g) + "' overlap by about " + formatApprox(depth) +
                 " m at t = 0: ODE pushes them apart violently at the first step; move them apart (or join "
                 "them with a joint)");
      }
    }
  }

  const Model& m_;
  Diagnostics& d_;
  double dt_;
  double recommended_ = std::numeric_limits<double>::infinity();
  std::vector<double> size_, thin_;
  std::vector<Placed> placed_;
  std::deque<GeomDef> mesh_boxes_;  // meshBox of each mesh geom (Placed points at them)
  std::vector<const GeomDef*> planes_;
  std::set<std::pair<int, int>> joined_;
  std::map<std::string, int> counts_, suppressed_;
  std::vector<std::pair<Subjects, std::string>> findings_;  ///< every warning said, with its subjects
};

}  // namespace

void lintModel(const Model& model, Diagnostics& diag, double dt) { Linter(model, diag, dt).run(); }

int firstBodyQuickStepCannotHold(const Model& model) {
  int first = -1;
  forEachUnholdable(model, [&](const JointDef&, int bi, double, double, double) {
    if (first < 0) first = bi;
  });
  return first;
}

double recommendedStep(const Model& model) {
  Diagnostics unused;
  Linter l(model, unused, 0);
  l.run();
  return l.recommendedStep();
}

void explainDivergence(const Model& model, int body, int joint, Error* error) {
  Diagnostics lint;
  Linter l(model, lint, 0);
  l.run();
  const std::string cause = l.firstAbout(body, joint);
  if (!cause.empty()) error->message += "; likely cause: " + cause;
}

}  // namespace simbob
