// Component graph -> Model. Dispatches on each family's kind enum (lib/components/families.h);
// switches have no default so a new kind without a case does not compile.
#include "simbob/compile.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "compile/mass.h"
#include "components/families.h"
#include "simbob/transform.h"

namespace simbob {

namespace {

constexpr int kMaxCloneDepth = 8;
// Bounds on what a small file can make the compiler do (found by fuzzing): bodies chained
// through joint Refs recurse once per link, and Refs shared in model trees or clones of clones
// multiply the work.
constexpr int kMaxBodyChain = 500;         // bodies being compiled inside one another
constexpr size_t kMaxModelParts = 10000;   // models collected for one model-derived geom
constexpr size_t kMaxModelItems = 100000;  // bodies + geoms + joints of the whole model

std::string describe(const Component& c) { return c.type->name + " '" + c.qkey + "'"; }

template <class E>
E kindOf(const Component& c) {
  return static_cast<E>(c.type->kind);
}

class Compiler {
 public:
  Compiler(const Scene& s, Model& m, Diagnostics& d) : scene_(s), model_(m), diag_(d) {}

  bool run() {
    settings();
    // [0]: the registry's defaults, for geoms made without a material (none today: every
    // body and global has a Material parameter with a default).
    model_.materials.push_back(MaterialDef{});
    std::vector<int> clones;
    for (const Link& l : scene_.components) {
      if (l.comp < 0) continue;
      const Component& c = scene_.at(l.comp);
      switch (c.type->family) {
        case Family::Body:
          // Clones come last: the bodies their originals join to must exist outside the copy.
          if (l.isRef()) break;
          if (kindOf<BodyKind>(c) == BodyKind::Clone)
            clones.push_back(l.comp);
          else
            body(l.comp, nullptr);
          break;
        case Family::GlobalSim:
          global(l.comp);
          break;
        case Family::Material:
        case Family::Skin:
        case Family::Model:
          break;  // listed to be referred to
        case Family::Geom:
        case Family::Joint:
        case Family::Pose:
        case Family::Motion:
        case Family::Inertia:
        case Family::Periphery:
        case Family::Controller:
        case Family::Camera:
        case Family::Struct:
          error(c, "a " + std::string(familyName(c.type->family)) + " cannot stand in the ComponentList");
          break;
      }
    }
    for (int ci : clones) body(ci, nullptr);
    return diag_.ok();
  }

 private:
  // ---------------------------------------------------------------- helpers
  void error(const Component& c, const std::string& msg) { diag_.error(c.loc, describe(c) + ": " + msg); }
  void error(const Link& l, const Component& owner, const std::string& msg) {
    diag_.error(l.loc.line ? l.loc : owner.loc, describe(owner) + ": " + msg);
  }

  const Component& at(int i) const { return scene_.at(i); }

  std::string bodyKey(const Component& c) const {
    // Only the original and the components below it: "Ball" renames "Ball.Arm", not "Ballast".
    const std::string& from = clone_.from;
    if (clone_.active && c.qkey.compare(0, from.size(), from) == 0 &&
        (c.qkey.size() == from.size() || c.qkey[from.size()] == '.'))
      return clone_.to + c.qkey.substr(from.size());
    return c.qkey;
  }

  // ---------------------------------------------------------------- settings
  void settings() {
    SolverSettings& s = model_.settings;
    if (scene_.settings < 0) return;
    const Component& c = at(scene_.settings);
    const Triple& g = c.triple("Gravity");
    s.gravity = {g[0], g[1], g[2]};
    s.max_time_step = c.number("MaxTimeStep");
    s.min_time_step = c.number("MinTimeStep");
    s.quickstep = c.enumValue("Solver") == 0;
    if (c.integer("SolverIterations") > 100000 || c.integer("MaxContacts") > 64)
      diag_.error(c.loc, "SceneSettings: SolverIterations must be at most 100000 and MaxContacts at most 64");
    s.iterations = static_cast<int>(std::min<int64_t>(c.integer("SolverIterations"), 100000));
    s.erp = c.number("ERP");
    s.cfm = c.number("CFM");
    s.max_contacts = static_cast<int>(std::min<int64_t>(c.integer("MaxContacts"), 64));
    s.space = static_cast<SpaceKind>(c.enumValue("Space"));
    s.auto_disable = c.boolean("AutoDisable");
    if (s.min_time_step > s.max_time_step)
      diag_.error(c.slot("MinTimeStep").loc, "SceneSettings: MinTimeStep must not exceed MaxTimeStep");
  }

  // ---------------------------------------------------------------- poses (6.8)
  /// The frame a pose link gives, relative to `parent` for local coordinates. An empty link is
  /// the parent frame itself (or the origin at the top level).
  bool pose(const Link& l, const Component& owner, const Transform* parent, Transform* out) {
    if (l.comp < 0) {
      *out = parent ? *parent : Transform{};
      return true;
    }
    const Component& c = at(l.comp);
    Transform local = fromPose(c.pose("Pose"));
    switch (kindOf<PoseKind>(c)) {
      case PoseKind::Global:
        *out = local;
        return true;
      case PoseKind::Local:
        if (!parent) {
          error(l, owner,
                "RCLocalCoordinates needs a parent frame (a joint, construction or body); use "
                "RCGlobalCoordinates at the top level");
          return false;
        }
        *out = compose(*parent, local);
        return true;
    }
    return false;
  }

  // ---------------------------------------------------------------- materials (6.7)
  int material(const Link& l) {
    if (l.comp < 0) return 0;
    const Component& c = at(l.comp);
    MaterialDef m;
    switch (kindOf<MaterialKind>(c)) {
      case MaterialKind::Generic:
        m.key = c.qkey;
        m.friction = c.number("Friction");
        m.bounceness = c.number("Bounceness");
        m.min_bounce_vel = c.number("MinBounceVel");
        break;
    }
    // Materials with equal properties share one entry: contacts only see the numbers.
    for (size_t i = 0; i < model_.materials.size(); ++i) {
      const MaterialDef& o = model_.materials[i];
      if (i > 0 && o.friction == m.friction && o.bounceness == m.bounceness && o.min_bounce_vel == m.min_bounce_vel)
        return static_cast<int>(i);
    }
    model_.materials.push_back(m);
    return static_cast<int>(model_.materials.size() - 1);
  }

  // ---------------------------------------------------------------- motion (6.9)
  void motion(const Link& l, BodyDef* b) {
    if (l.comp < 0) return;
    const Component& c = at(l.comp);
    switch (kindOf<MotionKind>(c)) {
      case MotionKind::Global: {
        const Triple& v = c.triple("LinVelocity");
        const Triple& w = c.triple("AngVelocity");
        b->lin_vel = {v[0], v[1], v[2]};
        b->ang_vel = {w[0], w[1], w[2]};
        break;
      }
    }
  }

  // ---------------------------------------------------------------- geoms (6.5)
  /// Append the geoms of `geom_link` for a body (index `body`, -1 static at `frame`).
  void geoms(const Link& l, const Component& owner, int body, const Transform& frame, const Transform& offset, int mat,
             const Link& model_link) {
    if (l.comp < 0) return;
    const Component& c = at(l.comp);
    GeomDef g;
    g.key = bodyKey(owner);
    g.body = body;
    g.material = mat;
    g.offset = offset;
    switch (kindOf<GeomKind>(c)) {
      case GeomKind::Transform: {
        Transform sub;
        pose(c.link("Pose"), c, &offset, &sub);
        geoms(c.link("SubGeom"), owner, body, frame, sub, mat, model_link);
        return;
      }
      case GeomKind::Cuboid:
        g.shape = GeomShape::Box;
        g.size = {c.number("Width"), c.number("Height"), c.number("Depth")};
        break;
      case GeomKind::Sphere:
        g.shape = GeomShape::Sphere;
        g.size = {c.number("Radius"), 0, 0};
        break;
      case GeomKind::Cylinder:
        g.shape = GeomShape::Cylinder;
        g.size = {c.number("Radius"), c.number("Length"), 0};
        break;
      case GeomKind::CappedCylinder:
        g.shape = GeomShape::Capsule;
        g.size = {c.number("Radius"), c.number("Length"), 0};
        break;
      case GeomKind::Plane: {
        if (body >= 0) {
          error(c, "a plane is infinite and can only belong to a static body");
          return;
        }
        Transform p;
        pose(c.link("Pose"), c, &offset, &p);
        Transform global = compose(frame, p);
        addPlane(rotate(global.q, {0, 1, 0}), global.p, mat, g.key);
        return;
      }
      case GeomKind::ModelMatch:
      case GeomKind::ModelWrap:
        modelGeoms(c, model_link, owner, g, frame);
        return;
      case GeomKind::Empty:
        return;
    }
    if (body < 0) g.offset = compose(frame, offset);
    model_.geoms.push_back(g);
  }

  void addPlane(Vec3 n, const Vec3& point, int mat, const std::string& key) {
    n = scale(n, 1.0 / norm(n));
    GeomDef g;
    g.key = key;
    g.shape = GeomShape::Plane;
    g.body = -1;
    g.material = mat;
    g.plane = {n[0], n[1], n[2], dot(n, point)};
    model_.geoms.push_back(g);
  }

  // RCModelMatchGeom / RCModelWrapGeom: geoms derived from the body's model tree.
  struct ModelPart {
    const Component* c;
    Transform t;  // model frame in the body frame
  };

  void collectModels(const Link& l, const Transform& parent, bool children, std::vector<ModelPart>* out, int depth) {
    if (l.comp < 0 || depth > 64 || out->size() > kMaxModelParts) return;
    const Component& c = at(l.comp);
    Transform t;
    const Link& pl = c.link("Pose");
    if (pl.comp >= 0)
      t = compose(parent, fromPose(at(pl.comp).pose("Pose")));
    else
      t = parent;
    out->push_back({&c, t});
    if (children)
      for (const Link& child : c.list("ChildList")) collectModels(child, t, true, out, depth + 1);
  }

  void modelGeoms(const Component& geom, const Link& model_link, const Component& owner, GeomDef g,
                  const Transform& frame) {
    std::vector<ModelPart> parts;
    collectModels(model_link, g.offset, !geom.boolean("IgnoreChilds"), &parts, 0);
    if (parts.size() > kMaxModelParts) {
      error(geom, "the model of '" + owner.qkey + "' has more than " + std::to_string(kMaxModelParts) +
                      " parts (model Refs shared over and over?)");
      return;
    }
    bool wrap = kindOf<GeomKind>(geom) == GeomKind::ModelWrap;
    auto emit = [&](GeomDef d) {
      if (d.body < 0) d.offset = compose(frame, d.offset);
      model_.geoms.push_back(d);
    };
    if (!wrap) {
      bool any = false;
      for (const ModelPart& p : parts) {
        GeomDef d = g;
        d.offset = p.t;
        switch (kindOf<ModelKind>(*p.c)) {
          case ModelKind::Cuboid: {
            const Cuboid& cb = std::get<Cuboid>(p.c->slot("Cuboid").value);
            Vec3 center{(cb.a[0] + cb.b[0]) / 2, (cb.a[1] + cb.b[1]) / 2, (cb.a[2] + cb.b[2]) / 2};
            d.shape = GeomShape::Box;
            d.size = {std::fabs(cb.b[0] - cb.a[0]), std::fabs(cb.b[1] - cb.a[1]), std::fabs(cb.b[2] - cb.a[2])};
            d.offset = compose(p.t, Transform{center, {1, 0, 0, 0}});
            if (d.size[0] <= 0 || d.size[1] <= 0 || d.size[2] <= 0) {
              error(*p.c, "a cuboid with zero extent cannot be matched by a geom");
              continue;
            }
            break;
          }
          case ModelKind::Ellipsoid: {
            double rx = p.c->number("RadiusX"), ry = p.c->number("RadiusY"), rz = p.c->number("RadiusZ");
            if (rx != ry || ry != rz) {
              error(geom, "RCModelMatchGeom: ellipsoid '" + p.c->qkey + "' has unequal radii; only a sphere matches");
              continue;
            }
            d.shape = GeomShape::Sphere;
            d.size = {rx, 0, 0};
            break;
          }
          case ModelKind::Cylinder: {
            uint32_t mask = p.c->enumValue("ComponentMask");
            bool capped = (mask & (8u | 16u)) != 0;
            d.shape = capped ? GeomShape::Capsule : GeomShape::Cylinder;
            d.size = {p.c->number("Radius"), p.c->number("Length"), 0};
            break;
          }
          case ModelKind::Plane:
          case ModelKind::Cone:
            error(geom,
                  "RCModelMatchGeom: no geom matches " + p.c->type->name + " '" + p.c->qkey + "'; use RCModelWrapGeom");
            continue;
          case ModelKind::Empty:
            continue;
        }
        any = true;
        emit(d);
      }
      if (!any && diag_.ok()) error(geom, "RCModelMatchGeom: the body '" + owner.qkey + "' has no model to match");
      return;
    }
    // Wrap: axis-aligned bounds (body frame) of every part, then the smallest shape around them.
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    bool any = false;
    for (const ModelPart& p : parts) {
      Vec3 half, center;
      if (!modelBounds(*p.c, &center, &half)) continue;
      Mat3 r = toMatrix(p.t.q);
      Vec3 c = add(p.t.p, rotate(p.t.q, center));
      for (int i = 0; i < 3; ++i) {
        double e =
            std::fabs(r[i * 3]) * half[0] + std::fabs(r[i * 3 + 1]) * half[1] + std::fabs(r[i * 3 + 2]) * half[2];
        lo[i] = std::min(lo[i], c[i] - e);
        hi[i] = std::max(hi[i], c[i] + e);
      }
      any = true;
    }
    if (!any) {
      error(geom, "RCModelWrapGeom: the body '" + owner.qkey + "' has no visible model to wrap");
      return;
    }
    Vec3 center = scale(add(lo, hi), 0.5), half = scale(sub(hi, lo), 0.5);
    GeomDef d = g;
    d.offset = Transform{center, {1, 0, 0, 0}};
    int axis = static_cast<int>(geom.enumValue("Alignment"));
    switch (geom.enumValue("GeomType")) {
      case 0:
        d.shape = GeomShape::Box;
        d.size = scale(half, 2.0);
        break;
      case 1:
        d.shape = GeomShape::Sphere;
        d.size = {norm(half), 0, 0};
        break;
      default: {
        // Cylinders lie along local Z: rotate Z onto the chosen axis.
        int a = axis, b = (axis + 1) % 3, c2 = (axis + 2) % 3;
        double radius = std::hypot(half[b], half[c2]);
        bool capped = geom.enumValue("GeomType") == 3;
        d.shape = capped ? GeomShape::Capsule : GeomShape::Cylinder;
        // The bounds' edges along the axis lie at distance `radius` from it, so the cylindrical
        // part must span the whole extent (a capsule's caps then lie beyond the bounds).
        double len = 2 * half[a];
        d.size = {radius, len, 0};
        if (axis == 0) d.offset.q = quatAxisAngle({0, 1, 0}, kPi / 2);
        if (axis == 1) d.offset.q = quatAxisAngle({1, 0, 0}, -kPi / 2);
        break;
      }
    }
    emit(d);
  }

  static bool modelBounds(const Component& m, Vec3* center, Vec3* half) {
    *center = {0, 0, 0};
    switch (kindOf<ModelKind>(m)) {
      case ModelKind::Cuboid: {
        const Cuboid& cb = std::get<Cuboid>(m.slot("Cuboid").value);
        for (int i = 0; i < 3; ++i) {
          (*center)[i] = (cb.a[i] + cb.b[i]) / 2;
          (*half)[i] = std::fabs(cb.b[i] - cb.a[i]) / 2;
        }
        return true;
      }
      case ModelKind::Ellipsoid:
        *half = {m.number("RadiusX"), m.number("RadiusY"), m.number("RadiusZ")};
        return true;
      case ModelKind::Cylinder: {
        double r = m.number("Radius"), l = m.number("Length");
        bool capped = (m.enumValue("ComponentMask") & (8u | 16u)) != 0;
        *half = {r, r, l / 2 + (capped ? r : 0)};
        return true;
      }
      case ModelKind::Cone: {
        double r = m.number("Radius"), l = m.number("Length");
        *half = {r, r, l / 2};
        *center = {0, 0, l / 2};
        return true;
      }
      case ModelKind::Plane:
        *half = {m.number("ExtensionX") / 2, m.number("ExtensionY") / 2, 0};
        return true;
      case ModelKind::Empty:
        return false;
    }
    return false;
  }

  // ---------------------------------------------------------------- inertia (6.10)
  bool inertia(const Link& l, const Component& owner, size_t first_geom, BodyDef* b) {
    if (l.comp < 0) {
      error(owner, "a mobile body needs an Inertia");
      return false;
    }
    const Component& c = at(l.comp);
    switch (kindOf<InertiaKind>(c)) {
      case InertiaKind::Generic: {
        b->mass = c.number("Mass");
        const Matrix4& m = c.matrix("Inertia");
        b->inertia = {m.m[0], m.m[1], m.m[2], m.m[4], m.m[5], m.m[6], m.m[8], m.m[9], m.m[10]};
        const Mat3& i = b->inertia;
        double tol = 1e-9 * (std::fabs(i[0]) + std::fabs(i[4]) + std::fabs(i[8]));
        if (std::fabs(i[1] - i[3]) > tol || std::fabs(i[2] - i[6]) > tol || std::fabs(i[5] - i[7]) > tol) {
          diag_.error(c.slot("Inertia").loc, describe(c) + ": parameter 'Inertia' must be symmetric");
          return false;
        }
        if (!isPositiveDefinite(i)) {
          diag_.error(c.slot("Inertia").loc, describe(c) + ": parameter 'Inertia' is not positive definite");
          return false;
        }
        return true;
      }
      case InertiaKind::ByGeom: {
        MassProps total;
        for (size_t gi = first_geom; gi < model_.geoms.size(); ++gi) {
          MassProps p = geomMassProps(model_.geoms[gi]);
          total.volume += p.volume;
          total.moment = add(total.moment, p.moment);
          for (int k = 0; k < 9; ++k) total.inertia[k] += p.inertia[k];
        }
        if (!(total.volume > 0)) {
          // Reported at the body: a left-out Inertia is a shared default with no place of its own.
          error(owner, "RCInertiaByGeom needs a geom with volume on body '" + owner.qkey +
                           "' (give it a Geom or use RCGenericInertia)");
          return false;
        }
        double mass = c.number("Mass");
        double density = mass < 0 ? c.number("Density") : mass / total.volume;
        if (mass == 0) {
          diag_.error(c.slot("Mass").loc, describe(c) + ": parameter 'Mass' must be > 0 (or negative to use Density)");
          return false;
        }
        b->mass = density * total.volume;
        // ODE wants the inertia about the centre of mass: undo the parallel-axis term of c.
        Vec3 cm = scale(total.moment, 1.0 / total.volume);
        b->com = cm;
        double c2 = dot(cm, cm);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            b->inertia[static_cast<size_t>(i * 3 + j)] =
                density *
                (total.inertia[static_cast<size_t>(i * 3 + j)] -
                 total.volume * ((i == j ? c2 : 0) - cm[static_cast<size_t>(i)] * cm[static_cast<size_t>(j)]));
        if (!isPositiveDefinite(b->inertia)) {
          error(c, "the inertia computed from the geometry is degenerate");
          return false;
        }
        return true;
      }
    }
    return false;
  }

  // ---------------------------------------------------------------- bodies (6.1)
  struct Built {
    int index = -1;   // model body index; -1 = static (world)
    Transform frame;  // global frame of the body
    bool ok = false;
  };

  /// Compile the body component `ci`; `parent` is the frame local coordinates refer to.
  Built body(int ci, const Transform* parent) {
    std::map<int, Built>& memo = clone_.active && clone_.inside.count(ci) ? clone_.memo : memo_;
    auto it = memo.find(ci);
    if (it != memo.end()) return it->second;
    if (!in_progress_.insert(ci).second) {
      error(at(ci), "body is part of its own construction (a joint's Body refers back to it)");
      return {};
    }
    if (in_progress_.size() > static_cast<size_t>(kMaxBodyChain)) {
      in_progress_.erase(ci);
      if (!too_big_)
        error(at(ci), "bodies nested more than " + std::to_string(kMaxBodyChain) +
                          " levels deep (constructions chained through joints)");
      too_big_ = true;
      return {};
    }
    if (model_.bodies.size() + model_.geoms.size() + model_.joints.size() > kMaxModelItems) {
      in_progress_.erase(ci);
      if (!too_big_)
        error(at(ci), "the scene makes more than " + std::to_string(kMaxModelItems) +
                          " bodies, geoms and joints (clones of clones?)");
      too_big_ = true;
      return {};
    }
    Built b = bodyUncached(ci, parent);
    in_progress_.erase(ci);
    memo[ci] = b;
    return b;
  }

  Built bodyUncached(int ci, const Transform* parent) {
    const Component& c = at(ci);
    Built out;
    switch (kindOf<BodyKind>(c)) {
      case BodyKind::StaticRigid: {
        if (!pose(c.link("Pose"), c, parent, &out.frame)) return out;
        int mat = material(c.link("Material"));
        geoms(c.link("Geom"), c, -1, out.frame, Transform{}, mat, c.link("Model"));
        out.ok = true;
        return out;
      }
      case BodyKind::MobileRigid: {
        BodyDef b;
        b.key = bodyKey(c);
        b.loc = c.loc;
        if (!pose(c.link("Pose"), c, parent, &b.pose)) return out;
        motion(c.link("Motion"), &b);
        int index = static_cast<int>(model_.bodies.size());
        size_t first_geom = model_.geoms.size();
        int mat = material(c.link("Material"));
        geoms(c.link("Geom"), c, index, b.pose, Transform{}, mat, c.link("Model"));
        if (!inertia(c.link("Inertia"), c, first_geom, &b)) return out;
        model_.bodies.push_back(b);
        out.index = index;
        out.frame = b.pose;
        out.ok = true;
        return out;
      }
      case BodyKind::Rod:
        return rod(c, parent);
      case BodyKind::Construction: {
        const Link& root = c.link("Body");
        if (root.comp < 0) {
          error(c, "parameter 'Body' (the root body) is required");
          return out;
        }
        out = body(root.comp, parent);
        if (!out.ok) return out;
        for (const Link& child : c.list("ChildList")) {
          if (child.comp < 0) continue;
          const Component& cc = at(child.comp);
          if (cc.type->family == Family::Joint)
            joint(child.comp, out, nullptr, nullptr);
          else
            periphery(cc);
        }
        return out;
      }
      case BodyKind::Import: {
        if (c.imported.empty()) return out;
        return rigidCopy(c, c.imported[0], parent, c.link("Pose"), c.link("Motion"), false);
      }
      case BodyKind::Clone: {
        const std::string& original = c.string("Original");
        auto f = scene_.by_qkey.find(original);
        if (f == scene_.by_qkey.end() || at(f->second).type->family != Family::Body) {
          std::vector<std::string> keys;
          for (const auto& [k, i] : scene_.by_qkey)
            if (at(i).type->family == Family::Body) keys.push_back(k);
          std::string near = didYouMean(original, keys);
          diag_.error(c.slot("Original").loc, describe(c) + ": parameter 'Original' '" + original + "' names no body" +
                                                  (near.empty() ? "" : " (did you mean '" + near + "'?)"));
          return out;
        }
        return rigidCopy(c, f->second, parent, c.link("Pose"), Link{}, true);
      }
    }
    return out;
  }

  Built rod(const Component& c, const Transform* parent) {
    Built out;
    Transform p1, p2;
    if (!pose(c.link("Pos1"), c, parent, &p1) || !pose(c.link("Pos2"), c, parent, &p2)) return out;
    Vec3 d = sub(p2.p, p1.p);
    double dist = norm(d);
    double r = c.number("Radius");
    bool capped = c.boolean("Capped");
    bool hull = c.boolean("HullPositions");
    // Cylinder length between the flat ends, or of the cylindrical part of a capsule.
    double len = capped ? (hull ? dist - 2 * r : dist) : (hull ? dist : dist + 2 * r);
    if (!(dist > 0) || !(len > 0)) {
      error(c, "Pos1 and Pos2 are too close for a rod of Radius " + formatNumber(r) +
                   (capped && hull ? " with caps inside the end points" : ""));
      return out;
    }
    BodyDef b;
    b.key = bodyKey(c);
    b.loc = c.loc;
    b.pose.p = scale(add(p1.p, p2.p), 0.5);
    b.pose.q = quatZTo(scale(d, 1.0 / dist));
    motion(c.link("Motion"), &b);
    int index = static_cast<int>(model_.bodies.size());
    GeomDef g;
    g.key = b.key;
    g.body = index;
    g.shape = capped ? GeomShape::Capsule : GeomShape::Cylinder;
    g.size = {r, len, 0};
    g.material = material(c.link("Material"));
    MassProps mp = geomMassProps(g);
    b.mass = c.number("Mass");
    for (int k = 0; k < 9; ++k) b.inertia[k] = mp.inertia[k] * b.mass / mp.volume;
    model_.geoms.push_back(g);
    model_.bodies.push_back(b);
    out.index = index;
    out.frame = b.pose;
    out.ok = true;
    return out;
  }

  /// Compile `source` (an imported or cloned body) and move everything it created rigidly so
  /// that its root lands on `pose_link` (when given); `motion_link` replaces its motion.
  Built rigidCopy(const Component& c, int source, const Transform* parent, const Link& pose_link,
                  const Link& motion_link, bool is_clone) {
    Built out;
    size_t b0 = model_.bodies.size(), g0 = model_.geoms.size(), j0 = model_.joints.size();
    Clone saved = clone_;
    if (is_clone) {
      if (clone_depth_ >= kMaxCloneDepth) {
        error(c, "clones nested deeper than " + std::to_string(kMaxCloneDepth));
        return out;
      }
      clone_.active = true;
      clone_.from = at(source).qkey;
      clone_.to = c.qkey;
      clone_.memo.clear();
      clone_.inside.clear();
      markInside(source);
      ++clone_depth_;
    }
    Built inner = body(source, parent);
    if (is_clone) {
      --clone_depth_;
      clone_ = saved;
    }
    if (!inner.ok) return out;
    out = inner;
    if (pose_link.comp >= 0) {
      Transform target;
      if (!pose(pose_link, c, parent, &target)) return Built{};
      Transform t = compose(target, inverse(inner.frame));
      for (size_t i = b0; i < model_.bodies.size(); ++i) {
        BodyDef& b = model_.bodies[i];
        b.pose = compose(t, b.pose);
        b.lin_vel = rotate(t.q, b.lin_vel);
        b.ang_vel = rotate(t.q, b.ang_vel);
      }
      for (size_t i = g0; i < model_.geoms.size(); ++i) {
        GeomDef& g = model_.geoms[i];
        if (g.body >= 0) continue;
        if (g.shape == GeomShape::Plane) {
          Vec3 n = rotate(t.q, {g.plane[0], g.plane[1], g.plane[2]});
          Vec3 p = add(t.p, rotate(t.q, scale({g.plane[0], g.plane[1], g.plane[2]}, g.plane[3])));
          g.plane = {n[0], n[1], n[2], dot(n, p)};
        } else {
          g.offset = compose(t, g.offset);
        }
      }
      for (size_t i = j0; i < model_.joints.size(); ++i) {
        JointDef& j = model_.joints[i];
        j.anchor = add(t.p, rotate(t.q, j.anchor));
        j.axis = rotate(t.q, j.axis);
      }
      out.frame = target;
    } else if (is_clone) {
      diag_.warning(c.loc, describe(c) + ": no Pose given; the copy overlaps the original");
    }
    if (motion_link.comp >= 0) {
      BodyDef m;
      motion(motion_link, &m);
      // A rigid motion of the whole copy: v_i = v + w x (p_i - p_root).
      for (size_t i = b0; i < model_.bodies.size(); ++i) {
        BodyDef& b = model_.bodies[i];
        b.lin_vel = add(m.lin_vel, cross(m.ang_vel, sub(b.pose.p, out.frame.p)));
        b.ang_vel = m.ang_vel;
      }
    }
    return out;
  }

  void markInside(int ci) {
    if (!clone_.inside.insert(ci).second) return;
    const Component& c = at(ci);
    for (size_t pi = 0; pi < c.slots.size(); ++pi) {
      const Slot& s = c.slots[pi];
      if (s.link.comp >= 0 && !s.link.isRef()) markInside(s.link.comp);
      for (const Link& l : s.list)
        if (l.comp >= 0 && !l.isRef()) markInside(l.comp);
    }
    for (int i : c.imported) markInside(i);
  }

  // ---------------------------------------------------------------- joints (6.6)
  void joint(int ji, const Built& parent, const Link* pose_override, const Link* body_override) {
    const Component& c = at(ji);
    if (kindOf<JointCompKind>(c) == JointCompKind::Import) {
      if (c.imported.empty()) return;
      const Slot& ps = c.slot("Pose");
      const Slot& bs = c.slot("Body");
      joint(c.imported[0], parent, ps.set ? &ps.link : pose_override, bs.set ? &bs.link : body_override);
      return;
    }
    Transform frame;
    if (!pose(pose_override ? *pose_override : c.link("Pose"), c, &parent.frame, &frame)) return;
    const Link& bl = body_override ? *body_override : c.link("Body");
    if (bl.comp < 0) {
      error(c, "parameter 'Body' (the body the joint connects to) is required");
      return;
    }
    Built child = body(bl.comp, &frame);
    if (!child.ok) return;
    JointDef j;
    j.key = bodyKey(c);  // renamed inside a RigidBodyClone, like the bodies
    j.loc = c.loc;
    j.body1 = parent.index;
    j.body2 = child.index;
    j.anchor = frame.p;
    j.axis = rotate(frame.q, {0, 0, 1});
    if (j.body1 < 0 && j.body2 < 0) {
      error(c, "connects two static bodies; one of them must be mobile");
      return;
    }
    if (j.body1 == j.body2) {
      error(c, "connects a body with itself");
      return;
    }
    switch (kindOf<JointCompKind>(c)) {
      case JointCompKind::BallSocket: {
        j.kind = JointKind::BallSocket;
        Transform a;
        if (!pose(c.link("Anchor"), c, &frame, &a)) return;
        j.anchor = a.p;
        break;
      }
      case JointCompKind::Hinge: {
        j.kind = JointKind::Hinge;
        Transform h;
        if (!pose(c.link("Hinge"), c, &frame, &h)) return;
        j.anchor = h.p;
        j.axis = rotate(h.q, {0, 0, 1});
        break;
      }
      case JointCompKind::Slider: {
        j.kind = JointKind::Slider;
        Transform a;
        if (!pose(c.link("Axis"), c, &frame, &a)) return;
        j.axis = rotate(a.q, {0, 0, 1});
        break;
      }
      case JointCompKind::Fix:
        j.kind = JointKind::Fixed;
        break;
      case JointCompKind::Import:
        return;  // handled above
    }
    model_.joints.push_back(j);
  }

  // ---------------------------------------------------------------- peripheries (6.11)
  void periphery(const Component& c) {
    switch (kindOf<PeripheryKind>(c)) {
      case PeripheryKind::GenericDrive:
      case PeripheryKind::GenericServo:
      case PeripheryKind::VelControlledDrive:
      case PeripheryKind::ProximitySensor:
      case PeripheryKind::LocalSocketCommunicator:
        // Parsed and validated; actuators and sensors act once the robot layer lands.
        diag_.warning(c.loc, describe(c) + ": peripheries are read but have no effect on the physics yet");
        break;
    }
  }

  // ---------------------------------------------------------------- globals (6.2)
  void global(int gi) {
    const Component& c = at(gi);
    switch (kindOf<GlobalKind>(c)) {
      case GlobalKind::Ground:
        addPlane({0, 1, 0}, {0, 0, 0}, material(c.link("Material")), c.qkey);
        break;
      case GlobalKind::Sky:
        addPlane({0, -1, 0}, {0, c.number("Height"), 0}, material(c.link("Material")), c.qkey);
        break;
      case GlobalKind::SandBox: {
        int mat = material(c.link("Material"));
        double w = c.number("Width") / 2, d = c.number("Depth") / 2;
        addPlane({1, 0, 0}, {-w, 0, 0}, mat, c.qkey);
        addPlane({-1, 0, 0}, {w, 0, 0}, mat, c.qkey);
        addPlane({0, 0, 1}, {0, 0, -d}, mat, c.qkey);
        addPlane({0, 0, -1}, {0, 0, d}, mat, c.qkey);
        break;
      }
      case GlobalKind::Robot: {
        const Link& l = c.link("Construction");
        if (l.comp < 0) {
          error(c, "parameter 'Construction' is required");
          break;
        }
        body(l.comp, nullptr);
        for (const Link& ctl : c.list("ControllerList"))
          if (ctl.comp >= 0)
            diag_.warning(at(ctl.comp).loc, describe(at(ctl.comp)) + ": controllers are read but do not run yet");
        break;
      }
      case GlobalKind::ImportRefList:
        break;  // its components are there to be referred to
    }
  }

  struct Clone {
    bool active = false;
    std::string from, to;
    std::map<int, Built> memo;
    std::set<int> inside;
  };

  const Scene& scene_;
  Model& model_;
  Diagnostics& diag_;
  std::map<int, Built> memo_;
  std::set<int> in_progress_;
  Clone clone_;
  int clone_depth_ = 0;
  bool too_big_ = false;  // a bound above was hit (reported once)
};

}  // namespace

bool compileScene(const Scene& scene, Model* model, Diagnostics& diag) {
  *model = Model{};
  Compiler c(scene, *model, diag);
  return c.run();
}

}  // namespace simbob
