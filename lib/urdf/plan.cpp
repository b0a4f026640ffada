// Planning a URDF robot as rigid bodies: link frames at the zero configuration, fixed joints
// lumped (each group's mass, centre of mass and inertia combined with rotated tensors and the
// parallel-axis theorem), and the fixed map from URDF's Z-up robot frame to the scene's Y-up.
#include "simbob/transform.h"
#include "urdf/urdf.h"

namespace simbob {

namespace {

/// R I R^T for a rotation q (the identity passes through untouched, so that numbers written in
/// the file reach the physics exactly).
Mat3 rotateTensor(const Quat& q, const Mat3& I) {
  if (q == Quat{1, 0, 0, 0}) return I;
  const Mat3 R = toMatrix(q);
  Mat3 RI{}, out{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) RI[r * 3 + c] += R[r * 3 + k] * I[k * 3 + c];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) out[r * 3 + c] += RI[r * 3 + k] * R[c * 3 + k];
  return out;
}

/// Combines the <inertial> of every link of a body in its root link's frame.
void combineMass(const UrdfRobot& robot, const UrdfPlan& plan, UrdfBody* b) {
  struct Part {
    double m;
    Vec3 c;
    Mat3 I;
  };
  std::vector<Part> parts;
  for (int li : b->links) {
    const UrdfLink& l = robot.links[static_cast<size_t>(li)];
    if (!l.has_inertial) continue;
    const Transform in_root = compose(plan.link_in_body[static_cast<size_t>(li)], l.inertial.origin);
    parts.push_back({l.inertial.mass, in_root.p, rotateTensor(in_root.q, l.inertial.inertia)});
  }
  b->massive_links = static_cast<int>(parts.size());
  if (parts.empty()) return;
  if (parts.size() == 1) {  // one link's numbers, untouched
    b->mass = parts[0].m;
    b->com = parts[0].c;
    b->inertia = parts[0].I;
    return;
  }
  double m = 0;
  Vec3 mc{0, 0, 0};
  for (const Part& p : parts) {
    m += p.m;
    mc = add(mc, scale(p.c, p.m));
  }
  b->mass = m;
  b->com = m > 0 ? scale(mc, 1.0 / m) : Vec3{0, 0, 0};
  Mat3 I{};
  for (const Part& p : parts) {
    const Vec3 d = sub(p.c, b->com);
    const double dd = dot(d, d);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) I[r * 3 + c] += p.I[r * 3 + c] + p.m * ((r == c ? dd : 0.0) - d[r] * d[c]);
  }
  b->inertia = I;
}

}  // namespace

UrdfPlan planUrdf(const UrdfRobot& robot, bool fixed_base) {
  UrdfPlan plan;
  const size_t n = robot.links.size();
  plan.link_body.assign(n, -1);
  plan.link_global.assign(n, Transform{});
  plan.link_in_body.assign(n, Transform{});
  if (robot.root < 0) return plan;
  std::vector<std::vector<int>> children(n);  // joint indices, document order
  std::vector<int> parent_joint(n, -1);
  for (size_t j = 0; j < robot.joints.size(); ++j) {
    const UrdfJoint& jd = robot.joints[j];
    children[static_cast<size_t>(jd.parent)].push_back(static_cast<int>(j));
    parent_joint[static_cast<size_t>(jd.child)] = static_cast<int>(j);
  }
  // Group roots: the robot's root and every child of a joint that is not fixed. Parents before
  // children, depth first in document order, with a stack of its own: a chain may be 50,000
  // links deep (kMaxUrdfDepth).
  std::vector<int> group_root(n, -1);
  std::vector<int> todo{robot.root};
  while (!todo.empty()) {
    const int li = todo.back();
    todo.pop_back();
    const size_t l = static_cast<size_t>(li);
    const int pj = parent_joint[l];
    if (pj < 0) {
      group_root[l] = li;
    } else {
      const UrdfJoint& j = robot.joints[static_cast<size_t>(pj)];
      const size_t p = static_cast<size_t>(j.parent);
      plan.link_global[l] = compose(plan.link_global[p], j.origin);
      if (j.type == UrdfJoint::Fixed) {
        group_root[l] = group_root[p];
        plan.link_in_body[l] = compose(plan.link_in_body[p], j.origin);
      } else {
        group_root[l] = li;
      }
    }
    for (auto cj = children[l].rbegin(); cj != children[l].rend(); ++cj)
      todo.push_back(robot.joints[static_cast<size_t>(*cj)].child);
  }
  // Bodies in document order of their root links.
  std::vector<int> body_of_root(n, -1);
  for (size_t l = 0; l < n; ++l) {
    if (group_root[l] != static_cast<int>(l)) continue;
    body_of_root[l] = static_cast<int>(plan.bodies.size());
    UrdfBody b;
    b.root = static_cast<int>(l);
    b.fixed = static_cast<int>(l) == robot.root && (fixed_base || robot.links[l].name == "world");
    plan.bodies.push_back(b);
  }
  for (size_t l = 0; l < n; ++l) {
    if (group_root[l] < 0) continue;  // not reached from the root (reported by the reader)
    const int bi = body_of_root[static_cast<size_t>(group_root[l])];
    plan.link_body[l] = bi;
    plan.bodies[static_cast<size_t>(bi)].links.push_back(static_cast<int>(l));
  }
  for (UrdfBody& b : plan.bodies) combineMass(robot, plan, &b);
  return plan;
}

namespace {

/// -90 degrees about X, as the scene format computes "0 0 0 -90 0 0" (so that a scene written
/// by hand and an imported URDF give the same numbers).
const Quat& zUpToYUp() {
  static const Quat q = quatFromEulerDeg(Triple{{-90, 0, 0}});
  return q;
}

/// URDF (x, y, z) -> scene (x, z, -y): exactly the rotation zUpToYUp, without rounding (and
/// without the negative zeros a hand-written scene never has: 0 - 0 is +0).
Vec3 permute(const Vec3& v) { return {v[0] + 0.0, v[2] + 0.0, 0.0 - v[1]}; }

}  // namespace

Transform urdfToScene(const Transform& place, const Transform& t) {
  Transform robot;  // the robot frame in the scene: rotated, not moved
  robot.p = permute(t.p);
  robot.q = quatMul(zUpToYUp(), t.q);
  return compose(place, robot);
}

Vec3 urdfDirToScene(const Transform& place, const Vec3& v) {
  const Vec3 r = rotate(place.q, permute(v));
  return {r[0] + 0.0, r[1] + 0.0, r[2] + 0.0};
}

}  // namespace simbob
