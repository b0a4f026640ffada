// Tests of the compile step (component graph -> Model) against answers computed by hand in the
// tests: Euler convention, frame composition, joints, inertia, rods, clones, imports, global
// planes, materials and model-derived geoms.
#include <catch2/catch.hpp>

#include <cmath>
#include <set>

#include "compile/mass.h"
#include "test_registry.h"
#include "scene/scene_helpers.h"
#include "simbob/transform.h"

using namespace simbob;
using namespace scenetest;

namespace {

constexpr double kEps = 1e-12;
const double kDeg = kPi / 180.0;

using M3 = std::array<double, 9>;

M3 rx(double deg) {
  double c = std::cos(deg * kDeg), s = std::sin(deg * kDeg);
  return {1, 0, 0, 0, c, -s, 0, s, c};
}
M3 ry(double deg) {
  double c = std::cos(deg * kDeg), s = std::sin(deg * kDeg);
  return {c, 0, s, 0, 1, 0, -s, 0, c};
}
M3 rz(double deg) {
  double c = std::cos(deg * kDeg), s = std::sin(deg * kDeg);
  return {c, -s, 0, s, c, 0, 0, 0, 1};
}
M3 mul(const M3& a, const M3& b) {
  M3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r[i * 3 + j] += a[i * 3 + k] * b[k * 3 + j];
  return r;
}
Vec3 mat_apply(const M3& m, const Vec3& v) {
  return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
          m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}
/// R = Rz(c) Ry(b) Rx(a): the guide's convention, computed independently of transform.h.
M3 euler(double a, double b, double c) { return mul(rz(c), mul(ry(b), rx(a))); }

void checkVec(const Vec3& got, const Vec3& want, double eps = kEps) {
  INFO("got (" << got[0] << ", " << got[1] << ", " << got[2] << "), want (" << want[0] << ", " << want[1] << ", "
               << want[2] << ")");
  for (int i = 0; i < 3; ++i) CHECK(got[i] == Approx(want[i]).margin(eps));
}

void checkMat(const Mat3& got, const M3& want, double eps = kEps) {
  for (int i = 0; i < 9; ++i) {
    INFO("element " << i);
    CHECK(got[i] == Approx(want[i]).margin(eps));
  }
}

/// Orientation of a quaternion as a matrix, compared with the independent Euler matrices.
void checkRot(const Quat& q, const M3& want, double eps = kEps) {
  CHECK(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] == Approx(1.0).margin(1e-14));
  checkMat(toMatrix(q), want, eps);
}

const BodyDef& bodyNamed(const Model& m, const std::string& key) {
  for (const BodyDef& b : m.bodies)
    if (b.key == key) return b;
  FAIL("no body '" << key << "'");
  return m.bodies.front();
}

int bodyIndex(const Model& m, const std::string& key) {
  for (size_t i = 0; i < m.bodies.size(); ++i)
    if (m.bodies[i].key == key) return static_cast<int>(i);
  FAIL("no body '" << key << "'");
  return -1;
}

const JointDef& jointNamed(const Model& m, const std::string& key) {
  for (const JointDef& j : m.joints)
    if (j.key == key) return j;
  FAIL("no joint '" << key << "'");
  return m.joints.front();
}

std::vector<const GeomDef*> geomsOf(const Model& m, const std::string& key) {
  std::vector<const GeomDef*> out;
  for (const GeomDef& g : m.geoms)
    if (g.key == key) out.push_back(&g);
  return out;
}

const GeomDef& onlyGeom(const Model& m, const std::string& key) {
  std::vector<const GeomDef*> gs = geomsOf(m, key);
  INFO("geoms of '" << key << "'");
  REQUIRE(gs.size() == 1);
  return *gs[0];
}

std::string scene(const std::string& components) {
  return "<Simulation><ComponentList>\n" + components + "\n</ComponentList></Simulation>";
}

std::string globalPose(const std::string& p) {
  return "<RCGlobalCoordinates><Pose Value=\"" + p + "\"/></RCGlobalCoordinates>";
}
std::string localPose(const std::string& p) {
  return "<RCLocalCoordinates><Pose Value=\"" + p + "\"/></RCLocalCoordinates>";
}

std::string mobile(const std::string& key, const std::string& pose, const std::string& geom = "<RCSphereGeom/>",
                   const std::string& extra = "") {
  return "<RCMobileRigidBody Key=\"" + key + "\"><Pose>" + pose + "</Pose><Geom>" + geom + "</Geom>" + extra +
         "</RCMobileRigidBody>";
}

}  // namespace

// ---------------------------------------------------------------------------------- poses (6.8)

TEST_CASE("compile: Euler angles rotate about X, then Y, then Z (R = Rz Ry Rx, degrees)", "[scene][compile]") {
  Model m = mustCompile(scene(mobile("X90", globalPose("0 0 0 90 0 0")) + mobile("Z90", globalPose("0 0 0 0 0 90")) +
                              mobile("Y90", globalPose("0 0 0 0 90 0")) + mobile("ABC", globalPose("1 -2 3 30 45 60")) +
                              mobile("Neg", globalPose("0 0 0 -120 10 -200"))));
  // (90, 0, 0) turns local Y onto global Z and local Z onto global -Y.
  const Quat& x90 = bodyNamed(m, "X90").pose.q;
  checkVec(rotate(x90, {0, 1, 0}), {0, 0, 1});
  checkVec(rotate(x90, {0, 0, 1}), {0, -1, 0});
  checkVec(rotate(x90, {1, 0, 0}), {1, 0, 0});
  // (0, 0, 90) turns local X onto global Y.
  const Quat& z90 = bodyNamed(m, "Z90").pose.q;
  checkVec(rotate(z90, {1, 0, 0}), {0, 1, 0});
  checkVec(rotate(z90, {0, 1, 0}), {-1, 0, 0});
  // (0, 90, 0) turns local Z onto global X.
  checkVec(rotate(bodyNamed(m, "Y90").pose.q, {0, 0, 1}), {1, 0, 0});
  // A combined case against the matrix product computed here.
  const BodyDef& abc = bodyNamed(m, "ABC");
  checkVec(abc.pose.p, {1, -2, 3});
  checkRot(abc.pose.q, euler(30, 45, 60));
  // The order matters: Rx Ry Rz is a different rotation.
  M3 other = mul(rx(30), mul(ry(45), rz(60)));
  Mat3 got = toMatrix(abc.pose.q);
  double diff = 0;
  for (int i = 0; i < 9; ++i) diff = std::max(diff, std::fabs(got[i] - other[i]));
  CHECK(diff > 0.1);
  checkRot(bodyNamed(m, "Neg").pose.q, euler(-120, 10, -200));
}

TEST_CASE("compile: transform.h agrees with the independent rotation matrices", "[scene][compile]") {
  for (double a : {0.0, 17.0, -90.0, 135.0})
    for (double b : {0.0, 33.0, 90.0, -60.0})
      for (double c : {0.0, 45.0, -170.0}) {
        INFO(a << " " << b << " " << c);
        checkRot(quatFromEulerDeg({a, b, c}), euler(a, b, c));
      }
  // compose / inverse.
  Transform t1{{1, 2, 3}, quatFromEulerDeg({10, 20, 30})};
  Transform t2{{-4, 5, 0.5}, quatFromEulerDeg({-40, 0, 80})};
  Transform c = compose(t1, t2);
  checkVec(c.p, {mat_apply(euler(10, 20, 30), {-4, 5, 0.5})[0] + 1, mat_apply(euler(10, 20, 30), {-4, 5, 0.5})[1] + 2,
                 mat_apply(euler(10, 20, 30), {-4, 5, 0.5})[2] + 3});
  checkRot(c.q, mul(euler(10, 20, 30), euler(-40, 0, 80)));
  Transform id = compose(inverse(t1), t1);
  checkVec(id.p, {0, 0, 0});
  checkRot(id.q, {1, 0, 0, 0, 1, 0, 0, 0, 1});
  // quatZTo takes +Z onto the direction, including the antiparallel case.
  for (Vec3 d : {Vec3{0, 0, 1}, Vec3{0, 0, -1}, Vec3{1, 0, 0}, Vec3{0, 0.6, 0.8}, Vec3{-0.48, 0.6, -0.64}})
    checkVec(rotate(quatZTo(d), {0, 0, 1}), d);
}

TEST_CASE("compile: geoms of static bodies are placed globally", "[scene][compile]") {
  Model m = mustCompile(
      scene("<RCStaticRigidBody Key=\"S\"><Pose>" + globalPose("1 2 3 0 0 90") +
            "</Pose><Geom><RCTransformGeom><Pose>" + localPose("1 0 0 90 0 0") +
            "</Pose><SubGeom><RCCuboidGeom><Width Value=\"2\"/><Height Value=\"3\"/><Depth Value=\"4\"/></RCCuboidGeom>"
            "</SubGeom></RCTransformGeom></Geom></RCStaticRigidBody>"));
  CHECK(m.bodies.empty());
  const GeomDef& g = onlyGeom(m, "S");
  CHECK(g.body == -1);
  CHECK(g.shape == GeomShape::Box);
  checkVec(g.size, {2, 3, 4});
  // Body frame (1,2,3) turned 90 deg about Z; the geom 1 m along the body's X = global +Y.
  checkVec(g.offset.p, {1, 3, 3});
  checkRot(g.offset.q, mul(rz(90), rx(90)));
}

TEST_CASE("compile: RCLocalCoordinates compose through construction -> joint -> body", "[scene][compile]") {
  Model m = mustCompile(scene(R"(<RCConstruction Key="C">
  <Body><RCStaticRigidBody Key="Root"><Pose>)" +
                              globalPose("1 2 3 0 0 90") + R"(</Pose></RCStaticRigidBody></Body>
  <ChildList>
    <RCHingeJoint Key="J">
      <Pose>)" + localPose("1 0 0 90 0 0") +
                              R"(</Pose>
      <Body>
        <RCConstruction Key="Arm">
          <Body>)" + mobile("Upper", localPose("0 1 0 0 0 0")) +
                              R"(</Body>
          <ChildList>
            <RCBallSocketJoint Key="Elbow">
              <Pose>)" + localPose("0 0 2 0 -90 0") +
                              R"(</Pose>
              <Body>)" + mobile("Lower", localPose("0.5 0 0 0 0 0")) +
                              R"(</Body>
            </RCBallSocketJoint>
          </ChildList>
        </RCConstruction>
      </Body>
    </RCHingeJoint>
  </ChildList>
</RCConstruction>)"));
  // Root frame: p0 = (1,2,3), R0 = Rz(90).
  M3 r0 = rz(90);
  Vec3 p0{1, 2, 3};
  // Joint frame: R0 * local.
  M3 rj = mul(r0, rx(90));
  Vec3 pj = add(p0, mat_apply(r0, {1, 0, 0}));
  checkVec(pj, {1, 3, 3});
  // Upper body, relative to the joint frame.
  Vec3 pu = add(pj, mat_apply(rj, {0, 1, 0}));
  checkVec(pu, {1, 3, 4});
  const BodyDef& upper = bodyNamed(m, "C.J.Arm.Upper");
  checkVec(upper.pose.p, pu);
  checkRot(upper.pose.q, rj);
  // The hinge without Hinge parameter: anchor at the joint origin, axis the joint's local Z.
  const JointDef& j = jointNamed(m, "C.J");
  CHECK(j.kind == JointKind::Hinge);
  CHECK(j.body1 == -1);
  CHECK(j.body2 == bodyIndex(m, "C.J.Arm.Upper"));
  checkVec(j.anchor, pj);
  checkVec(j.axis, mat_apply(rj, {0, 0, 1}));
  checkVec(j.axis, {1, 0, 0});
  // Elbow: relative to the Upper body (the Arm construction's root).
  M3 re = mul(rj, ry(-90));
  Vec3 pe = add(pu, mat_apply(rj, {0, 0, 2}));
  const JointDef& elbow = jointNamed(m, "C.J.Arm.Elbow");
  CHECK(elbow.kind == JointKind::BallSocket);
  CHECK(elbow.body1 == bodyIndex(m, "C.J.Arm.Upper"));
  CHECK(elbow.body2 == bodyIndex(m, "C.J.Arm.Elbow.Lower"));
  checkVec(elbow.anchor, pe);
  const BodyDef& lower = bodyNamed(m, "C.J.Arm.Elbow.Lower");
  checkVec(lower.pose.p, add(pe, mat_apply(re, {0.5, 0, 0})));
  checkRot(lower.pose.q, re);
  // Geoms follow their bodies (offset relative to the body).
  const GeomDef& g = onlyGeom(m, "C.J.Arm.Elbow.Lower");
  CHECK(g.body == bodyIndex(m, "C.J.Arm.Elbow.Lower"));
  checkVec(g.offset.p, {0, 0, 0});
  // A global pose inside a construction ignores the parent frame.
  Model g2 =
      mustCompile(scene("<RCConstruction Key=\"C\"><Body><RCStaticRigidBody><Pose>" + globalPose("5 5 5 0 0 45") +
                        "</Pose></RCStaticRigidBody></Body><ChildList><RCFixJoint Key=\"F\"><Body>" +
                        mobile("B", globalPose("0 1 0 0 0 0")) + "</Body></RCFixJoint></ChildList></RCConstruction>"));
  checkVec(bodyNamed(g2, "C.F.B").pose.p, {0, 1, 0});
  CHECK(jointNamed(g2, "C.F").kind == JointKind::Fixed);
  // The joint frame defaults to the parent body's frame.
  checkVec(jointNamed(g2, "C.F").anchor, {5, 5, 5});
}

// ---------------------------------------------------------------------------------- joints (6.6)

TEST_CASE("compile: hinge anchor and axis from the Hinge pose's local Z", "[scene][compile]") {
  auto hinge = [](const std::string& hinge_param) {
    return scene("<RCConstruction Key=\"C\"><Body>" + mobile("Base", globalPose("0 1 0 0 0 0")) +
                 "</Body><ChildList><RCHingeJoint Key=\"H\"><Pose>" + localPose("2 0 0 0 0 90") + "</Pose>" +
                 hinge_param + "<Body>" + mobile("Arm", localPose("0 -1 0 0 0 0")) +
                 "</Body></RCHingeJoint></ChildList></RCConstruction>");
  };
  // Joint frame: (2,1,0) turned 90 deg about Z.
  M3 rj = rz(90);
  Vec3 pj{2, 1, 0};
  {
    Model m = mustCompile(hinge("<Hinge>" + localPose("0 0 0.5 0 90 0") + "</Hinge>"));
    const JointDef& j = jointNamed(m, "C.H");
    CHECK(j.kind == JointKind::Hinge);
    CHECK(j.body1 == bodyIndex(m, "C.Base"));
    CHECK(j.body2 == bodyIndex(m, "C.H.Arm"));
    checkVec(j.anchor, add(pj, mat_apply(rj, {0, 0, 0.5})));
    checkVec(j.axis, mat_apply(mul(rj, ry(90)), {0, 0, 1}));
    checkVec(j.axis, {0, 1, 0});
    checkVec(bodyNamed(m, "C.H.Arm").pose.p, {3, 1, 0});
  }
  {
    // A global Hinge pose is taken as it is.
    Model m = mustCompile(hinge("<Hinge>" + globalPose("7 8 9 -90 0 0") + "</Hinge>"));
    const JointDef& j = jointNamed(m, "C.H");
    checkVec(j.anchor, {7, 8, 9});
    checkVec(j.axis, {0, 1, 0});
  }
  {
    // No Hinge: the joint frame.
    Model m = mustCompile(hinge(""));
    checkVec(jointNamed(m, "C.H").anchor, pj);
    checkVec(jointNamed(m, "C.H").axis, {0, 0, 1});
  }
}

TEST_CASE("compile: slider axis, ball-socket anchor, fixed joint", "[scene][compile]") {
  Model m = mustCompile(
      scene("<RCConstruction Key=\"C\"><Body>" + mobile("Base", globalPose("0 0 0 0 0 0")) + "</Body><ChildList>" +
            "<RCSliderJoint Key=\"S\"><Pose>" + localPose("1 0 0 0 0 90") + "</Pose><Axis>" +
            localPose("5 5 5 -90 0 0") + "</Axis><Body>" + mobile("A", localPose("0 0 0 0 0 0")) +
            "</Body></RCSliderJoint>" + "<RCBallSocketJoint Key=\"B\"><Pose>" + localPose("0 2 0 0 0 0") +
            "</Pose><Anchor>" + localPose("0 0 1 45 45 45") + "</Anchor><Body>" +
            mobile("D", localPose("0 0 0 0 0 0")) + "</Body></RCBallSocketJoint>" + "<RCFixJoint Key=\"F\"><Body>" +
            mobile("E", globalPose("0 -3 0 0 0 0")) + "</Body></RCFixJoint>" + "</ChildList></RCConstruction>"));
  const JointDef& s = jointNamed(m, "C.S");
  CHECK(s.kind == JointKind::Slider);
  // Axis: Rz(90) Rx(-90) applied to Z = Rz(90) (0,1,0) = (-1,0,0); its position does not matter.
  checkVec(s.axis, mat_apply(mul(rz(90), rx(-90)), {0, 0, 1}));
  checkVec(s.axis, {-1, 0, 0});
  const JointDef& b = jointNamed(m, "C.B");
  CHECK(b.kind == JointKind::BallSocket);
  checkVec(b.anchor, {0, 2, 1});
  const JointDef& f = jointNamed(m, "C.F");
  CHECK(f.kind == JointKind::Fixed);
  CHECK(f.body1 == bodyIndex(m, "C.Base"));
  CHECK(f.body2 == bodyIndex(m, "C.F.E"));
  // Joints are in document order.
  REQUIRE(m.joints.size() == 3);
  CHECK(m.joints[0].key == "C.S");
  CHECK(m.joints[2].key == "C.F");
}

TEST_CASE("compile: a joint's Body may be a Ref to an existing body", "[scene][compile]") {
  Model m = mustCompile(scene(mobile("Free", globalPose("0 5 0 0 0 0")) + "<RCConstruction Key=\"C\"><Body>" +
                              mobile("Base", globalPose("0 0 0 0 0 0")) +
                              "</Body><ChildList><RCBallSocketJoint Key=\"J\"><Body Ref=\"Free\"/></RCBallSocketJoint>"
                              "</ChildList></RCConstruction>"));
  REQUIRE(m.bodies.size() == 2);  // the referred body is not created twice
  const JointDef& j = jointNamed(m, "C.J");
  CHECK(j.body1 == bodyIndex(m, "C.Base"));
  CHECK(j.body2 == bodyIndex(m, "Free"));
  checkVec(bodyNamed(m, "Free").pose.p, {0, 5, 0});
}

// ---------------------------------------------------------------------------------- inertia (6.10)

namespace {

struct Principal {
  double mass, ixx, iyy, izz;
};

Principal boxP(double rho, double x, double y, double z) {
  double m = rho * x * y * z;
  return {m, m * (y * y + z * z) / 12, m * (x * x + z * z) / 12, m * (x * x + y * y) / 12};
}
Principal sphereP(double rho, double r) {
  double m = rho * 4.0 / 3.0 * kPi * r * r * r;
  return {m, 0.4 * m * r * r, 0.4 * m * r * r, 0.4 * m * r * r};
}
Principal cylinderP(double rho, double r, double l) {
  double m = rho * kPi * r * r * l;
  double t = m * (3 * r * r + l * l) / 12;
  return {m, t, t, m * r * r / 2};
}
/// Capsule along Z: cylinder plus two hemispheres. A hemisphere's inertia about a diameter of
/// its flat face is (2/5) m r^2; its centre of mass lies 3r/8 from the face.
Principal capsuleP(double rho, double r, double l) {
  Principal c = cylinderP(rho, r, l);
  double mh = rho * 2.0 / 3.0 * kPi * r * r * r;  // one hemisphere
  double a = 3 * r / 8;
  double about_own_com = 0.4 * mh * r * r - mh * a * a;
  double transverse = about_own_com + mh * (l / 2 + a) * (l / 2 + a);
  return {c.mass + 2 * mh, c.ixx + 2 * transverse, c.iyy + 2 * transverse, c.izz + 2 * 0.4 * mh * r * r};
}

void checkPrincipal(const BodyDef& b, const Principal& p) {
  CHECK(b.mass == Approx(p.mass).epsilon(1e-12));
  CHECK(b.inertia[0] == Approx(p.ixx).epsilon(1e-12));
  CHECK(b.inertia[4] == Approx(p.iyy).epsilon(1e-12));
  CHECK(b.inertia[8] == Approx(p.izz).epsilon(1e-12));
  for (int k : {1, 2, 3, 5, 6, 7}) CHECK(b.inertia[k] == Approx(0).margin(1e-9 * p.ixx));
}

std::string byGeom(const std::string& params) {
  return "<Inertia><RCInertiaByGeom>" + params + "</RCInertiaByGeom></Inertia>";
}

}  // namespace

TEST_CASE("compile: RCInertiaByGeom for box, sphere, cylinder and capsule", "[scene][compile]") {
  const std::string origin = globalPose("0 0 0 0 0 0");
  Model m = mustCompile(
      scene(mobile("Box", origin,
                   "<RCCuboidGeom><Width Value=\"1\"/><Height Value=\"2\"/><Depth Value=\"3\"/></RCCuboidGeom>") +
            mobile("Sphere", origin, "<RCSphereGeom><Radius Value=\"0.5\"/></RCSphereGeom>",
                   byGeom("<Density Value=\"7800\"/>")) +
            mobile("Cyl", origin, "<RCCylinderGeom><Radius Value=\"0.5\"/><Length Value=\"2\"/></RCCylinderGeom>") +
            mobile("Cap", origin,
                   "<RCCappedCylinderGeom><Radius Value=\"0.25\"/><Length Value=\"1.5\"/></RCCappedCylinderGeom>",
                   byGeom("<Density Value=\"500\"/>")) +
            mobile("BoxMass", origin,
                   "<RCCuboidGeom><Width Value=\"1\"/><Height Value=\"2\"/><Depth Value=\"3\"/></RCCuboidGeom>",
                   byGeom("<Mass Value=\"12\"/><Density Value=\"1\"/>")) +
            mobile("Generic", origin, "<RCSphereGeom/>",
                   "<Inertia><RCGenericInertia><Mass Value=\"3\"/><Inertia Value=\"1 0.1 0 0.1 2 0 0 0 "
                   "3\"/></RCGenericInertia></Inertia>")));
  // Default density 1000 kg/m^3.
  checkPrincipal(bodyNamed(m, "Box"), boxP(1000, 1, 2, 3));
  CHECK(bodyNamed(m, "Box").mass == Approx(6000));
  CHECK(bodyNamed(m, "Box").inertia[0] == Approx(6500));
  checkPrincipal(bodyNamed(m, "Sphere"), sphereP(7800, 0.5));
  checkPrincipal(bodyNamed(m, "Cyl"), cylinderP(1000, 0.5, 2));
  checkPrincipal(bodyNamed(m, "Cap"), capsuleP(500, 0.25, 1.5));
  // A given Mass scales the density; the inertia scales with it.
  Principal bm = boxP(1000, 1, 2, 3);
  double f = 12 / bm.mass;
  checkPrincipal(bodyNamed(m, "BoxMass"), {12, bm.ixx * f, bm.iyy * f, bm.izz * f});
  const BodyDef& g = bodyNamed(m, "Generic");
  CHECK(g.mass == 3);
  CHECK(g.inertia == Mat3{1, 0.1, 0, 0.1, 2, 0, 0, 0, 3});
  // geomMassProps directly: volume and inertia per unit density.
  GeomDef sphere;
  sphere.shape = GeomShape::Sphere;
  sphere.size = {2, 0, 0};
  MassProps mp = geomMassProps(sphere);
  CHECK(mp.volume == Approx(4.0 / 3.0 * kPi * 8));
  CHECK(mp.inertia[0] == Approx(0.4 * mp.volume * 4));
  GeomDef plane;
  plane.shape = GeomShape::Plane;
  CHECK(geomMassProps(plane).volume == 0);
}

TEST_CASE("compile: RCInertiaByGeom with RCTransformGeom offsets (parallel axis theorem)", "[scene][compile]") {
  const std::string origin = globalPose("0 0 0 0 0 0");
  auto offset = [](const std::string& pose, const std::string& sub) {
    return "<RCTransformGeom><Pose>" + localPose(pose) + "</Pose><SubGeom>" + sub + "</SubGeom></RCTransformGeom>";
  };
  const std::string cube = "<RCCuboidGeom/>";
  const std::string cyl = "<RCCylinderGeom><Radius Value=\"0.5\"/><Length Value=\"2\"/></RCCylinderGeom>";
  Model m = mustCompile(scene(mobile("Up", origin, offset("0 2 0 0 0 0", cube)) +
                              mobile("Diag", origin, offset("1 2 0 0 0 0", cube)) +
                              mobile("Turned", origin, offset("0 0 0 90 0 0", cyl)) +
                              mobile("Nested", origin, offset("0 0 1 0 0 0", offset("0 0 0 0 90 0", cyl)))));
  // Unit cube, 1000 kg, moved 2 m along Y: the centre of mass moves with it, and the inertia
  // about the centre of mass is the cube's own (ODE takes it about the centre of mass).
  const double mc = 1000;
  const double ic = mc * 2 / 12;
  const BodyDef& up = bodyNamed(m, "Up");
  CHECK(up.mass == Approx(mc));
  checkVec(up.com, {0, 2, 0});
  checkMat(up.inertia, {ic, 0, 0, 0, ic, 0, 0, 0, ic}, 1e-9);
  const BodyDef& diag = bodyNamed(m, "Diag");
  checkVec(diag.com, {1, 2, 0});
  checkMat(diag.inertia, {ic, 0, 0, 0, ic, 0, 0, 0, ic}, 1e-9);
  // A cylinder turned 90 deg about X lies along Y.
  Principal c = cylinderP(1000, 0.5, 2);
  checkMat(bodyNamed(m, "Turned").inertia, {c.ixx, 0, 0, 0, c.izz, 0, 0, 0, c.iyy}, 1e-9);
  checkVec(bodyNamed(m, "Turned").com, {0, 0, 0});
  // Nested transforms compose: along X, 1 m up Z.
  checkVec(bodyNamed(m, "Nested").com, {0, 0, 1});
  checkMat(bodyNamed(m, "Nested").inertia, {c.izz, 0, 0, 0, c.iyy, 0, 0, 0, c.ixx}, 1e-9);
  // The geoms carry their offsets relative to the body.
  checkVec(onlyGeom(m, "Up").offset.p, {0, 2, 0});
  checkVec(onlyGeom(m, "Nested").offset.p, {0, 0, 1});
  checkVec(rotate(onlyGeom(m, "Nested").offset.q, {0, 0, 1}), {1, 0, 0});
  checkVec(rotate(onlyGeom(m, "Turned").offset.q, {0, 0, 1}), {0, -1, 0});
}

// ---------------------------------------------------------------------------------- rods (6.1.3)

TEST_CASE("compile: RCRodBody midpoint, orientation and length for Capped x HullPositions", "[scene][compile]") {
  auto rod = [](const std::string& key, bool capped, bool hull) {
    return "<RCRodBody Key=\"" + key + "\"><Pos1>" + globalPose("1 0 0 0 0 0") + "</Pos1><Pos2>" +
           globalPose("1 3 4 10 20 30") + "</Pos2><Radius Value=\"0.5\"/><Mass Value=\"2\"/><Capped Value=\"" +
           (capped ? "True" : "False") + "\"/><HullPositions Value=\"" + (hull ? "True" : "False") + "\"/></RCRodBody>";
  };
  Model m = mustCompile(scene(rod("FlatHull", false, true) + rod("Flat", false, false) + rod("CapHull", true, true) +
                              rod("Cap", true, false)));
  struct Case {
    const char* key;
    GeomShape shape;
    double len;  // of the flat cylinder, or of the capsule's cylindrical part
  };
  // Ends 5 m apart, radius 0.5.
  for (const Case& c : {Case{"FlatHull", GeomShape::Cylinder, 5}, Case{"Flat", GeomShape::Cylinder, 6},
                        Case{"CapHull", GeomShape::Capsule, 4}, Case{"Cap", GeomShape::Capsule, 5}}) {
    INFO(c.key);
    const BodyDef& b = bodyNamed(m, c.key);
    checkVec(b.pose.p, {1, 1.5, 2});
    // Local Z along Pos1 -> Pos2; the end poses' orientations do not matter.
    checkVec(rotate(b.pose.q, {0, 0, 1}), {0, 0.6, 0.8});
    const GeomDef& g = onlyGeom(m, c.key);
    CHECK(g.shape == c.shape);
    CHECK(g.body == bodyIndex(m, c.key));
    CHECK(g.size[0] == 0.5);
    CHECK(g.size[1] == Approx(c.len).epsilon(1e-14));
    checkVec(g.offset.p, {0, 0, 0});
    // Mass as given, inertia of the shape with that mass (in the body frame, axis Z).
    CHECK(b.mass == 2);
    Principal p = c.shape == GeomShape::Cylinder ? cylinderP(1, 0.5, c.len) : capsuleP(1, 0.5, c.len);
    double f = 2 / p.mass;
    checkPrincipal(b, {2, p.ixx * f, p.iyy * f, p.izz * f});
  }
}

TEST_CASE("compile: RCRodBody ends in local coordinates of a joint", "[scene][compile]") {
  Model m = mustCompile(
      scene("<RCConstruction Key=\"C\"><Body><RCStaticRigidBody><Pose>" + globalPose("0 1 0 0 0 90") +
            "</Pose></RCStaticRigidBody></Body><ChildList><RCHingeJoint Key=\"J\"><Body><RCRodBody Key=\"R\">"
            "<Pos1>" +
            localPose("0 0 0 0 0 0") + "</Pos1><Pos2>" + localPose("2 0 0 0 0 0") +
            "</Pos2></RCRodBody></Body></RCHingeJoint></ChildList></RCConstruction>"));
  // The frame is turned 90 deg about Z: local X is global Y.
  const BodyDef& r = bodyNamed(m, "C.J.R");
  checkVec(r.pose.p, {0, 2, 0});
  checkVec(rotate(r.pose.q, {0, 0, 1}), {0, 1, 0});
  CHECK(onlyGeom(m, "C.J.R").size[1] == Approx(2));
}

// ---------------------------------------------------------------------------------- clones (6.1.6)

namespace {

const char* kPendulum = R"(<RCConstruction Key="P">
  <Body><RCStaticRigidBody Key="Pivot"><Pose>)";

std::string pendulum() {
  return std::string(kPendulum) + globalPose("0 2 0 0 0 0") + R"(</Pose>
    <Geom><RCCuboidGeom/></Geom></RCStaticRigidBody></Body>
  <ChildList>
    <RCHingeJoint Key="H">
      <Pose>)" +
         localPose("0 0 0 0 0 30") + R"(</Pose>
      <Body>)" +
         mobile("Bob", localPose("0 -1 0 0 0 0"), "<RCSphereGeom><Radius Value=\"0.1\"/></RCSphereGeom>",
                "<Motion><RCGlobalMotion><LinVelocity Value=\"1 0 0\"/><AngVelocity Value=\"0 0 2\"/>"
                "</RCGlobalMotion></Motion>") +
         R"(</Body>
    </RCHingeJoint>
  </ChildList>
</RCConstruction>)";
}

}  // namespace

TEST_CASE("compile: RigidBodyClone renames keys and moves the copy rigidly", "[scene][compile]") {
  Model m = mustCompile(scene(pendulum() + "<RigidBodyClone Key=\"P2\"><Original Value=\"P\"/><Pose>" +
                              globalPose("3 2 0 0 90 0") + "</Pose></RigidBodyClone>"));
  REQUIRE(m.bodies.size() == 2);
  REQUIRE(m.joints.size() == 2);
  const BodyDef& bob = bodyNamed(m, "P.H.Bob");
  const BodyDef& copy = bodyNamed(m, "P2.H.Bob");
  // Original: pivot (0,2,0), bob 1 m down the joint frame turned 30 deg about Z.
  checkVec(bob.pose.p, {0.5, 2 - std::cos(30 * kDeg), 0});
  // The copy: the original's root frame (0,2,0) is moved onto (3,2,0) turned 90 deg about Y.
  M3 t = ry(90);
  Vec3 rel = sub(bob.pose.p, {0, 2, 0});
  checkVec(copy.pose.p, add({3, 2, 0}, mat_apply(t, rel)));
  checkRot(copy.pose.q, mul(t, rz(30)));
  // Velocities turn with the copy.
  checkVec(copy.lin_vel, mat_apply(t, {1, 0, 0}));
  checkVec(copy.ang_vel, mat_apply(t, {0, 0, 2}));
  CHECK(copy.mass == Approx(bob.mass));
  // Joints of the copy connect the copy's bodies and move with it; their keys are the clone's.
  const JointDef& jo = m.joints[0];
  const JointDef& jc = m.joints[1];
  CHECK(jo.key == "P.H");
  CHECK(jc.key == "P2.H");
  CHECK(jc.body1 == -1);
  CHECK(jc.body2 == bodyIndex(m, "P2.H.Bob"));
  checkVec(jc.anchor, {3, 2, 0});
  checkVec(jc.axis, mat_apply(t, {0, 0, 1}));
  // Static geoms of the copy are moved too; mobile geoms stay relative to their body.
  const GeomDef& pivot_copy = onlyGeom(m, "P2.Pivot");
  checkVec(pivot_copy.offset.p, {3, 2, 0});
  checkRot(pivot_copy.offset.q, t);
  checkVec(onlyGeom(m, "P.Pivot").offset.p, {0, 2, 0});
  CHECK(onlyGeom(m, "P2.H.Bob").body == bodyIndex(m, "P2.H.Bob"));
  // Every key in the model is unique.
  std::set<std::string> keys;
  for (const auto& b : m.bodies) CHECK(keys.insert(b.key).second);
  for (const auto& j : m.joints) CHECK(keys.insert(j.key).second);
}

TEST_CASE("compile: RigidBodyClone of a single body, before and after the original", "[scene][compile]") {
  const std::string ball = mobile("Ball", globalPose("0 1 0 0 0 0"), "<RCSphereGeom/>",
                                  "<Motion><RCGlobalMotion><LinVelocity Value=\"1 0 0\"/></RCGlobalMotion></Motion>");
  const std::string clone = "<RigidBodyClone Key=\"Ball2\"><Original Value=\"Ball\"/><Pose>" +
                            globalPose("0 1 5 0 90 0") + "</Pose></RigidBodyClone>";
  for (const std::string& text : {scene(ball + clone), scene(clone + ball)}) {
    Model m = mustCompile(text);
    REQUIRE(m.bodies.size() == 2);
    checkVec(bodyNamed(m, "Ball").pose.p, {0, 1, 0});
    checkVec(bodyNamed(m, "Ball").lin_vel, {1, 0, 0});
    const BodyDef& c = bodyNamed(m, "Ball2");
    checkVec(c.pose.p, {0, 1, 5});
    checkRot(c.pose.q, ry(90));
    checkVec(c.lin_vel, {0, 0, -1});
    CHECK(onlyGeom(m, "Ball2").body == bodyIndex(m, "Ball2"));
    CHECK(geomsOf(m, "Ball").size() == 1);
  }
  // Without a Pose the copy lands on the original, with a warning.
  Scene s = mustLoad(scene(ball + "<RigidBodyClone Key=\"Ball2\"><Original Value=\"Ball\"/></RigidBodyClone>"));
  Model m;
  Diagnostics d;
  REQUIRE(compileScene(s, &m, d));
  REQUIRE(d.warnings().size() == 1);
  CHECK(d.warnings()[0].message.find("overlaps the original") != std::string::npos);
  checkVec(bodyNamed(m, "Ball2").pose.p, {0, 1, 0});
}

// ---------------------------------------------------------------------------------- imports (6.1.5)

TEST_CASE("compile: RCImportBody pose and motion override", "[scene][compile][import]") {
  TempDir dir;
  dir.write("ball.xml", "<Body>" +
                            mobile("Ball", globalPose("0 1 0 0 0 0"),
                                   "<RCTransformGeom><Pose>" + localPose("0 0.5 0 0 0 0") +
                                       "</Pose><SubGeom><RCSphereGeom/></SubGeom></RCTransformGeom>",
                                   "<Motion><RCGlobalMotion><LinVelocity Value=\"0 3 0\"/></RCGlobalMotion></Motion>") +
                            "</Body>");
  dir.write("arm.xml", "<Body><RCConstruction Key=\"Arm\"><Body><RCStaticRigidBody Key=\"Base\"><Pose>" +
                           globalPose("0 1 0 0 0 0") +
                           "</Pose></RCStaticRigidBody></Body><ChildList><RCHingeJoint "
                           "Key=\"J\"><Body>" +
                           mobile("Link", localPose("1 0 0 0 0 0")) +
                           "</Body></RCHingeJoint></ChildList></RCConstruction></Body>");
  dir.write("joint.xml", "<Joint><RCHingeJoint Key=\"H\"><Pose>" + localPose("0 0 1 0 0 0") + "</Pose><Body>" +
                             mobile("B", localPose("0 -1 0 0 0 0")) + "</Body></RCHingeJoint></Joint>");
  std::string main =
      dir.write("main.xml", scene("<RCImportBody Key=\"Plain\"><File Value=\"ball.xml\"/></RCImportBody>"
                                  "<RCImportBody Key=\"Moved\"><File Value=\"ball.xml\"/><Pose>" +
                                  globalPose("5 0 0 0 0 90") +
                                  "</Pose>"
                                  "<Motion><RCGlobalMotion><LinVelocity Value=\"0 0 1\"/><AngVelocity Value=\"0 2 "
                                  "0\"/></RCGlobalMotion></Motion>"
                                  "</RCImportBody>"
                                  "<RCImportBody Key=\"Arm2\"><File Value=\"arm.xml\"/><Pose>" +
                                  globalPose("0 1 10 0 0 0") +
                                  "</Pose></RCImportBody>"
                                  "<RCConstruction Key=\"C\"><Body><RCStaticRigidBody/></Body><ChildList>"
                                  "<RCImportJoint Key=\"IJ\"><File Value=\"joint.xml\"/></RCImportJoint>"
                                  "<RCImportJoint Key=\"IJ2\"><File Value=\"joint.xml\"/><Pose>" +
                                  localPose("3 0 0 0 90 0") +
                                  "</Pose></RCImportJoint>"
                                  "</ChildList></RCConstruction>"));
  Scene s;
  Diagnostics d;
  REQUIRE(loadScene(main, testRegistry(), &s, d));
  Model m;
  bool ok = compileScene(s, &m, d);
  INFO(errorText(d));
  REQUIRE(ok);
  // As in the file.
  const BodyDef& plain = bodyNamed(m, "Plain.Ball");
  checkVec(plain.pose.p, {0, 1, 0});
  checkVec(plain.lin_vel, {0, 3, 0});
  // Pose replaced, motion replaced.
  const BodyDef& moved = bodyNamed(m, "Moved.Ball");
  checkVec(moved.pose.p, {5, 0, 0});
  checkRot(moved.pose.q, rz(90));
  checkVec(moved.lin_vel, {0, 0, 1});
  checkVec(moved.ang_vel, {0, 2, 0});
  // The geom stays where it is on the body.
  checkVec(onlyGeom(m, "Moved.Ball").offset.p, {0, 0.5, 0});
  // A whole construction moves rigidly: root (0,1,0) -> (0,1,10).
  checkVec(bodyNamed(m, "Arm2.Arm.J.Link").pose.p, {1, 1, 10});
  checkVec(jointNamed(m, "Arm2.Arm.J").anchor, {0, 1, 10});
  // Imported joint: its own pose, or the importing component's Pose.
  checkVec(jointNamed(m, "C.IJ.H").anchor, {0, 0, 1});
  checkVec(bodyNamed(m, "C.IJ.H.B").pose.p, {0, -1, 1});
  const JointDef& j2 = jointNamed(m, "C.IJ2.H");
  checkVec(j2.anchor, {3, 0, 0});
  checkVec(j2.axis, {1, 0, 0});
  checkVec(bodyNamed(m, "C.IJ2.H.B").pose.p, {3, -1, 0});
}

// ---------------------------------------------------------------------------------- globals (6.2)

TEST_CASE("compile: RCGround, RCSky and RCSandBox planes", "[scene][compile]") {
  Model m =
      mustCompile(scene("<RCGround/><RCSky><Height Value=\"7\"/></RCSky>"
                        "<RCSandBox><Width Value=\"4\"/><Depth Value=\"6\"/></RCSandBox>"));
  REQUIRE(m.geoms.size() == 6);
  for (const GeomDef& g : m.geoms) {
    CHECK(g.shape == GeomShape::Plane);
    CHECK(g.body == -1);
  }
  using P = std::array<double, 4>;
  // Points p with n.p = d; normals point into the free space.
  CHECK(m.geoms[0].plane == P{0, 1, 0, 0});
  CHECK(m.geoms[0].key == "RCGround");
  CHECK(m.geoms[1].plane == P{0, -1, 0, -7});
  CHECK(m.geoms[2].plane == P{1, 0, 0, -2});
  CHECK(m.geoms[3].plane == P{-1, 0, 0, -2});
  CHECK(m.geoms[4].plane == P{0, 0, 1, -3});
  CHECK(m.geoms[5].plane == P{0, 0, -1, -3});
  // The origin is inside every half space n.p >= d.
  for (const GeomDef& g : m.geoms) CHECK(0.0 >= g.plane[3]);
  // A plane geom on a static body: its local Y is the normal.
  Model p = mustCompile(scene("<RCStaticRigidBody Key=\"Ramp\"><Pose>" + globalPose("0 1 0 0 0 0") +
                              "</Pose><Geom><RCPlaneGeom><Pose>" + localPose("0 0 0 0 0 45") +
                              "</Pose></RCPlaneGeom></Geom></RCStaticRigidBody>"));
  const GeomDef& ramp = onlyGeom(p, "Ramp");
  double h = std::sqrt(0.5);
  CHECK(ramp.plane[0] == Approx(-h));
  CHECK(ramp.plane[1] == Approx(h));
  CHECK(ramp.plane[2] == Approx(0).margin(kEps));
  CHECK(ramp.plane[3] == Approx(h));
}

TEST_CASE("compile: scene settings reach the model", "[scene][compile]") {
  Model m = mustCompile(
      "<Simulation><SceneSettings><Gravity Value=\"0 0 -1.62\"/><MaxTimeStep Value=\"0.004\"/>"
      "<MinTimeStep Value=\"1e-5\"/><Solver Value=\"Step\"/><SolverIterations Value=\"7\"/>"
      "<ERP Value=\"0.5\"/><CFM Value=\"1e-6\"/><MaxContacts Value=\"9\"/></SceneSettings></Simulation>");
  CHECK(m.settings.gravity == Vec3{0, 0, -1.62});
  CHECK(m.settings.max_time_step == 0.004);
  CHECK(m.settings.min_time_step == 1e-5);
  CHECK_FALSE(m.settings.quickstep);
  CHECK(m.settings.iterations == 7);
  CHECK(m.settings.erp == 0.5);
  CHECK(m.settings.cfm == 1e-6);
  CHECK(m.settings.max_contacts == 9);
  Model d = mustCompile("<Simulation/>");
  CHECK(d.settings.gravity == Vec3{0, -9.81, 0});
  CHECK(d.settings.quickstep);
  CHECK(d.bodies.empty());
  CHECK(d.geoms.empty());
}

// ---------------------------------------------------------------------------------- materials (6.7)

TEST_CASE("compile: material data per geom", "[scene][compile]") {
  Model m = mustCompile(
      scene("<RCGenericMaterial Key=\"Ice\"><Friction Value=\"0.05\"/><Bounceness Value=\"0.1\"/>"
            "<MinBounceVel Value=\"0.2\"/></RCGenericMaterial>"
            "<RCGenericMaterial Key=\"Rubber\"><Friction Value=\"1.2\"/><Bounceness Value=\"0.8\"/></RCGenericMaterial>"
            "<RCGround><Material Ref=\"Ice\"/></RCGround>" +
            mobile("A", globalPose("0 1 0 0 0 0"), "<RCSphereGeom/>", "<Material Ref=\"Rubber\"/>") +
            mobile("B", globalPose("2 1 0 0 0 0"), "<RCSphereGeom/>", "<Material Ref=\"Rubber\"/>") +
            mobile("C", globalPose("4 1 0 0 0 0"), "<RCSphereGeom/>") +
            mobile("D", globalPose("6 1 0 0 0 0"), "<RCSphereGeom/>",
                   "<Material><RCGenericMaterial><Friction Value=\"1.2\"/><Bounceness "
                   "Value=\"0.8\"/></RCGenericMaterial></Material>") +
            "<RCStaticRigidBody Key=\"S\"><Geom><RCCuboidGeom/></Geom><Material "
            "Macro=\"DefaultMaterial\"/></RCStaticRigidBody>"));
  auto mat = [&](const std::string& key) -> const MaterialDef& {
    const GeomDef& g = onlyGeom(m, key);
    REQUIRE(g.material >= 0);
    REQUIRE(static_cast<size_t>(g.material) < m.materials.size());
    return m.materials[static_cast<size_t>(g.material)];
  };
  CHECK(mat("RCGround").friction == 0.05);
  CHECK(mat("RCGround").bounceness == 0.1);
  CHECK(mat("RCGround").min_bounce_vel == 0.2);
  CHECK(mat("RCGround").key == "Ice");
  CHECK(mat("A").friction == 1.2);
  CHECK(mat("A").bounceness == 0.8);
  CHECK(mat("A").min_bounce_vel == 0.1);
  CHECK(onlyGeom(m, "A").material == onlyGeom(m, "B").material);
  // Equal numbers share an entry, whatever the component.
  CHECK(onlyGeom(m, "D").material == onlyGeom(m, "A").material);
  // The default material: friction 0.5, no bounce.
  CHECK(mat("C").friction == 0.5);
  CHECK(mat("C").bounceness == 0);
  CHECK(mat("C").min_bounce_vel == 0.1);
  CHECK(onlyGeom(m, "S").material == onlyGeom(m, "C").material);
  CHECK(onlyGeom(m, "C").material != onlyGeom(m, "A").material);
  CHECK(onlyGeom(m, "RCGround").material != onlyGeom(m, "A").material);
  // [0] is the default material.
  REQUIRE_FALSE(m.materials.empty());
  CHECK(m.materials[0].friction == 0.5);
  CHECK(m.materials[0].key.empty());
  // Distinct materials: default(0), Ice, Rubber, and the default component's entry at most.
  CHECK(m.materials.size() <= 4);
}

// ---------------------------------------------------------------------------------- model geoms (6.5.7, 6.5.8)

TEST_CASE("compile: RCModelMatchGeom matches cuboid, sphere and cylinder models", "[scene][compile]") {
  Model m = mustCompile(scene(
      mobile("Box", globalPose("0 0 0 0 0 0"), "<RCModelMatchGeom/>",
             "<Model><RCCuboidModel><Cuboid Value=\"-1 0 0 1 2 4\"/></RCCuboidModel></Model>") +
      mobile("Turned", globalPose("0 0 0 0 0 0"), "<RCMoelMatchGeom/>",
             "<Model><RCCuboidModel><Pose>" + localPose("1 0 0 0 0 90") +
                 "</Pose><Cuboid Value=\"0 0 0 2 1 1\"/></RCCuboidModel></Model>") +
      mobile("Tree", globalPose("0 0 0 0 0 0"), "<RCModelMatchGeom/>",
             "<Model><RCEllipsoidModel><RadiusX Value=\"0.3\"/><RadiusY Value=\"0.3\"/><RadiusZ Value=\"0.3\"/>"
             "<ChildList><RCCylinderModel Key=\"Capsule\"><Pose>" +
                 localPose("0 1 0 0 0 0") +
                 "</Pose><Radius Value=\"0.2\"/><Length Value=\"1\"/><ComponentMask Value=\"CappedCylinder\"/>"
                 "</RCCylinderModel><RCCylinderModel Key=\"Cylinder\"><Pose>" +
                 localPose("0 -1 0 0 0 0") +
                 "</Pose><Radius "
                 "Value=\"0.1\"/></RCCylinderModel><RCEmptyModel/></ChildList></RCEllipsoidModel></Model>") +
      mobile("Root", globalPose("0 0 0 0 0 0"), "<RCModelMatchGeom><IgnoreChilds Value=\"true\"/></RCModelMatchGeom>",
             "<Model><RCCuboidModel><ChildList><RCCuboidModel><Pose>" + localPose("0 5 0 0 0 0") +
                 "</Pose></RCCuboidModel></ChildList></RCCuboidModel></Model>")));
  // Cuboid -> box of the cuboid's size at the cuboid's centre.
  const GeomDef& box = onlyGeom(m, "Box");
  CHECK(box.shape == GeomShape::Box);
  checkVec(box.size, {2, 2, 4});
  checkVec(box.offset.p, {0, 1, 2});
  // The centre of mass is the box's centre d = (0, 1, 2); the inertia is the box's own about it.
  const double mb = 16000;
  CHECK(bodyNamed(m, "Box").mass == Approx(mb));
  checkVec(bodyNamed(m, "Box").com, {0, 1, 2});
  checkMat(bodyNamed(m, "Box").inertia, {mb * (4 + 16) / 12, 0, 0, 0, mb * (4 + 16) / 12, 0, 0, 0, mb * (4 + 4) / 12},
           1e-8);
  // The model's pose: the centre (1, 0.5, 0.5) in the model frame turned 90 deg about Z.
  const GeomDef& turned = onlyGeom(m, "Turned");
  checkVec(turned.size, {2, 1, 1});
  checkVec(turned.offset.p, add({1, 0, 0}, mat_apply(rz(90), {1, 0.5, 0.5})));
  checkRot(turned.offset.q, rz(90));
  // A model tree: sphere, capsule, cylinder (empty models give nothing).
  std::vector<const GeomDef*> tree = geomsOf(m, "Tree");
  REQUIRE(tree.size() == 3);
  CHECK(tree[0]->shape == GeomShape::Sphere);
  CHECK(tree[0]->size[0] == 0.3);
  CHECK(tree[1]->shape == GeomShape::Capsule);
  CHECK(tree[1]->size[0] == 0.2);
  CHECK(tree[1]->size[1] == 1);
  checkVec(tree[1]->offset.p, {0, 1, 0});
  CHECK(tree[2]->shape == GeomShape::Cylinder);
  CHECK(tree[2]->size[0] == 0.1);
  checkVec(tree[2]->offset.p, {0, -1, 0});
  // IgnoreChilds: only the root model.
  std::vector<const GeomDef*> root = geomsOf(m, "Root");
  REQUIRE(root.size() == 1);
  checkVec(root[0]->offset.p, {0, 0, 0});
  checkVec(root[0]->size, {1, 1, 1});
}

TEST_CASE("compile: RCModelMatchGeom on a static body and with a shared model", "[scene][compile]") {
  Model m = mustCompile(scene(
      "<RCCuboidModel Key=\"Crate\"><Cuboid Value=\"0 0 0 1 1 1\"/></RCCuboidModel>"
      "<RCStaticRigidBody Key=\"S\"><Pose>" +
      globalPose("10 0 0 0 0 0") + "</Pose><Geom><RCModelMatchGeom/></Geom><Model Ref=\"Crate\"/></RCStaticRigidBody>" +
      mobile("M", globalPose("0 3 0 0 0 0"), "<RCModelMatchGeom/>", "<Model Ref=\"Crate\"/>")));
  const GeomDef& s = onlyGeom(m, "S");
  CHECK(s.body == -1);
  checkVec(s.offset.p, {10.5, 0.5, 0.5});
  const GeomDef& mg = onlyGeom(m, "M");
  CHECK(mg.body == 0);
  checkVec(mg.offset.p, {0.5, 0.5, 0.5});
}

TEST_CASE("compile: RCModelMatchGeom errors for models without a matching geom", "[scene][compile]") {
  Scene s =
      mustLoad(scene(mobile("E", globalPose("0 0 0 0 0 0"), "<RCModelMatchGeom/>",
                            "<Model><RCEllipsoidModel><RadiusX Value=\"1\"/></RCEllipsoidModel></Model>") +
                     mobile("C", globalPose("0 0 0 0 0 0"), "<RCModelMatchGeom/>", "<Model><RCConeModel/></Model>")));
  Model m;
  Diagnostics d;
  CHECK_FALSE(compileScene(s, &m, d));
  std::string all = errorText(d);
  CHECK(all.find("ellipsoid 'E.Model' has unequal radii") != std::string::npos);
  CHECK(all.find("no geom matches RCConeModel 'C.Model'") != std::string::npos);
}

namespace {

/// Whether point p lies inside (or on) the geom g (offset relative to the body, which is at the
/// origin here).
bool inside(const GeomDef& g, const Vec3& p, double tol = 1e-9) {
  Vec3 l = rotate(quatConj(g.offset.q), sub(p, g.offset.p));
  switch (g.shape) {
    case GeomShape::Box:
      return std::fabs(l[0]) <= g.size[0] / 2 + tol && std::fabs(l[1]) <= g.size[1] / 2 + tol &&
             std::fabs(l[2]) <= g.size[2] / 2 + tol;
    case GeomShape::Sphere:
      return norm(l) <= g.size[0] + tol;
    case GeomShape::Cylinder:
      return std::hypot(l[0], l[1]) <= g.size[0] + tol && std::fabs(l[2]) <= g.size[1] / 2 + tol;
    case GeomShape::Capsule: {
      double z = std::max(-g.size[1] / 2, std::min(g.size[1] / 2, l[2]));
      return norm({l[0], l[1], l[2] - z}) <= g.size[0] + tol;
    }
    case GeomShape::Plane:
    case GeomShape::ConvexHull:  // no wrap makes a mesh
    case GeomShape::TriMesh:
      return false;
  }
  return false;
}

}  // namespace

TEST_CASE("compile: RCModelWrapGeom wraps a cuboid model", "[scene][compile]") {
  const std::string model = "<Model><RCCuboidModel><Cuboid Value=\"-1 -0.5 0 1 0.5 3\"/></RCCuboidModel></Model>";
  auto wrap = [&](const std::string& key, const std::string& type, const std::string& align) {
    return mobile(
        key, globalPose("0 0 0 0 0 0"),
        "<RCModelWrapGeom><GeomType Value=\"" + type + "\"/><Alignment Value=\"" + align + "\"/></RCModelWrapGeom>",
        model);
  };
  Model m = mustCompile(scene(wrap("Box", "Cuboid", "ZAligned") + wrap("Sphere", "Sphere", "ZAligned") +
                              wrap("CylZ", "Cylinder", "ZAligned") + wrap("CylX", "Cylinder", "XAligned") +
                              wrap("CylY", "Cylinder", "YAligned") + wrap("CapZ", "CappedCylinder", "ZAligned") +
                              wrap("CapX", "CappedCylinder", "XAligned")));
  // Box: exactly the cuboid. Half extents (1, 0.5, 1.5), centre (0, 0, 1.5).
  const GeomDef& box = onlyGeom(m, "Box");
  CHECK(box.shape == GeomShape::Box);
  checkVec(box.size, {2, 1, 3});
  checkVec(box.offset.p, {0, 0, 1.5});
  // Sphere: the half diagonal.
  const GeomDef& sphere = onlyGeom(m, "Sphere");
  CHECK(sphere.shape == GeomShape::Sphere);
  CHECK(sphere.size[0] == Approx(std::sqrt(1 + 0.25 + 2.25)));
  checkVec(sphere.offset.p, {0, 0, 1.5});
  // Cylinder along Z: radius over X and Y, the full Z extent.
  const GeomDef& cz = onlyGeom(m, "CylZ");
  CHECK(cz.shape == GeomShape::Cylinder);
  CHECK(cz.size[0] == Approx(std::hypot(1, 0.5)));
  CHECK(cz.size[1] == Approx(3));
  checkVec(rotate(cz.offset.q, {0, 0, 1}), {0, 0, 1});
  // Cylinder along X: its local Z is turned onto X.
  const GeomDef& cx = onlyGeom(m, "CylX");
  CHECK(cx.size[0] == Approx(std::hypot(0.5, 1.5)));
  CHECK(cx.size[1] == Approx(2));
  Vec3 ax = rotate(cx.offset.q, {0, 0, 1});
  CHECK(std::fabs(ax[0]) == Approx(1));
  const GeomDef& cy = onlyGeom(m, "CylY");
  CHECK(cy.size[0] == Approx(std::hypot(1, 1.5)));
  CHECK(cy.size[1] == Approx(1));
  CHECK(std::fabs(rotate(cy.offset.q, {0, 0, 1})[1]) == Approx(1));
  CHECK(onlyGeom(m, "CapZ").shape == GeomShape::Capsule);
  // Every wrap contains every corner of the cuboid.
  for (const char* key : {"Box", "Sphere", "CylZ", "CylX", "CylY", "CapZ", "CapX"}) {
    const GeomDef& g = onlyGeom(m, key);
    for (double x : {-1.0, 1.0})
      for (double y : {-0.5, 0.5})
        for (double z : {0.0, 3.0}) {
          INFO(key << " corner (" << x << ", " << y << ", " << z << "), size (" << g.size[0] << ", " << g.size[1]
                   << ")");
          CHECK(inside(g, {x, y, z}));
        }
  }
}

TEST_CASE("compile: RCModelWrapGeom wraps a model tree unless IgnoreChilds", "[scene][compile]") {
  const std::string model = "<Model><RCCuboidModel><ChildList><RCCuboidModel><Pose>" + localPose("0 3 0 0 0 45") +
                            "</Pose></RCCuboidModel></ChildList></RCCuboidModel></Model>";
  Model m = mustCompile(scene(mobile("All", globalPose("0 0 0 0 0 0"), "<RCModelWrapGeom/>", model) +
                              mobile("Root", globalPose("0 0 0 0 0 0"),
                                     "<RCModelWrapGeom><IgnoreChilds Value=\"on\"/></RCModelWrapGeom>", model)));
  // The child cube turned 45 deg about Z spans +-sqrt(0.5) in X and Y around (0,3,0).
  double h = std::sqrt(0.5);
  const GeomDef& all = onlyGeom(m, "All");
  CHECK(all.shape == GeomShape::Box);
  checkVec(all.size, {2 * h, 3 + h + 0.5, 1});
  checkVec(all.offset.p, {0, (3 + h - 0.5) / 2, 0});
  const GeomDef& root = onlyGeom(m, "Root");
  checkVec(root.size, {1, 1, 1});
  checkVec(root.offset.p, {0, 0, 0});
}

TEST_CASE("compile: RCModelWrapGeom of round models is as small as the model allows", "[scene][compile]") {
  // A sphere model wrapped by a sphere is that sphere; a cylinder model by a cylinder is that cylinder.
  // (This test was marked [!mayfail]: the wrap was the box bounds' half diagonal, 0.866.)
  Model m = mustCompile(
      scene(mobile("S", globalPose("0 0 0 0 0 0"), "<RCModelWrapGeom><GeomType Value=\"Sphere\"/></RCModelWrapGeom>",
                   "<Model><RCEllipsoidModel/></Model>") +
            mobile("C", globalPose("0 0 0 0 0 0"), "<RCModelWrapGeom><GeomType Value=\"Cylinder\"/></RCModelWrapGeom>",
                   "<Model><RCCylinderModel/></Model>")));
  CHECK(onlyGeom(m, "S").shape == GeomShape::Sphere);
  CHECK(onlyGeom(m, "S").size[0] == 0.5);
  CHECK(onlyGeom(m, "C").shape == GeomShape::Cylinder);
  CHECK(onlyGeom(m, "C").size[0] == 0.5);
  CHECK(onlyGeom(m, "C").size[1] == 1);
}

TEST_CASE("compile: RCModelWrapGeom is exact for one sphere, cylinder or box and for a turned cylinder",
          "[scene][compile][model]") {
  // Before: every wrap was taken from the axis-aligned bounds (a sphere of the bounds' half
  // diagonal, a cylinder through the bounds' corners): a unit sphere got a wrap sphere of
  // radius sqrt(3) = 1.732, and `check` warned it started inside the ground.
  auto wrap = [](const std::string& key, const std::string& type, const std::string& align, const std::string& model) {
    return mobile(
        key, globalPose("0 0 0 0 0 0"),
        "<RCModelWrapGeom><GeomType Value=\"" + type + "\"/><Alignment Value=\"" + align + "\"/></RCModelWrapGeom>",
        "<Model>" + model + "</Model>");
  };
  const std::string unit_sphere =
      "<RCEllipsoidModel><RadiusX Value=\"1\"/><RadiusY Value=\"1\"/><RadiusZ Value=\"1\"/></RCEllipsoidModel>";
  const std::string cylinder = "<RCCylinderModel><Radius Value=\"0.3\"/><Length Value=\"2\"/></RCCylinderModel>";
  // Half extents (a, b, c) = (0.5, 1, 1.5), centre (1, 2, 3).
  const std::string box = "<RCCuboidModel><Cuboid Value=\"0.5 1 1.5 1.5 3 4.5\"/></RCCuboidModel>";
  // The cylinder turned 30 deg about X: its axis lies in the Y-Z plane.
  const std::string turned = "<RCCylinderModel><Pose>" + localPose("0 0 0 30 0 0") +
                             "</Pose><Radius Value=\"0.3\"/><Length Value=\"2\"/></RCCylinderModel>";
  Model m = mustCompile(
      scene(wrap("Sphere", "Sphere", "ZAligned", unit_sphere) + wrap("SphereBox", "Cuboid", "ZAligned", unit_sphere) +
            wrap("Cyl", "Cylinder", "ZAligned", cylinder) + wrap("CylCap", "CappedCylinder", "ZAligned", cylinder) +
            wrap("Box", "Cuboid", "ZAligned", box) + wrap("BoxSphere", "Sphere", "ZAligned", box) +
            wrap("Turned", "Cuboid", "ZAligned", turned)));
  const GeomDef& sphere = onlyGeom(m, "Sphere");
  CHECK(sphere.shape == GeomShape::Sphere);
  CHECK(sphere.size[0] == 1);
  checkVec(sphere.offset.p, {0, 0, 0});
  checkVec(onlyGeom(m, "SphereBox").size, {2, 2, 2});
  const GeomDef& cyl = onlyGeom(m, "Cyl");
  CHECK(cyl.shape == GeomShape::Cylinder);
  CHECK(cyl.size[0] == 0.3);
  CHECK(cyl.size[1] == 2);
  checkRot(cyl.offset.q, rz(0));
  // A capsule wrap has the cylinder's radius and length; its caps reach beyond the model.
  const GeomDef& cap = onlyGeom(m, "CylCap");
  CHECK(cap.shape == GeomShape::Capsule);
  CHECK(cap.size[0] == 0.3);
  CHECK(cap.size[1] == 2);
  const GeomDef& b = onlyGeom(m, "Box");
  CHECK(b.shape == GeomShape::Box);
  CHECK(b.size == Vec3{1, 2, 3});
  CHECK(b.offset.p == Vec3{1, 2, 3});
  const GeomDef& bs = onlyGeom(m, "BoxSphere");
  CHECK(bs.shape == GeomShape::Sphere);
  CHECK(bs.size[0] == Approx(std::sqrt(0.5 * 0.5 + 1 * 1 + 1.5 * 1.5)).epsilon(1e-15));
  checkVec(bs.offset.p, {1, 2, 3});
  // Turned cylinder: half extents r along X, |sin|.L/2 + r.|cos| along Y, |cos|.L/2 + r.|sin| along Z.
  const double c30 = std::cos(30 * kDeg), s30 = std::sin(30 * kDeg), r = 0.3, h = 1.0;
  const GeomDef& t = onlyGeom(m, "Turned");
  CHECK(t.shape == GeomShape::Box);
  checkVec(t.size, {2 * r, 2 * (s30 * h + r * c30), 2 * (c30 * h + r * s30)});
  checkVec(t.offset.p, {0, 0, 0});
}

namespace {

// A robot "Bot" whose construction "C" has hinges J (and K) with drives; `drives` and
// `controllers` are the ChildList tail and the ControllerList.
std::string robot(const std::string& drives, const std::string& controllers) {
  return scene("<RCRobot Key=\"Bot\"><Construction><RCConstruction Key=\"C\"><Body>" +
               mobile("Base", globalPose("0 0 0 0 0 0")) + "</Body><ChildList><RCHingeJoint Key=\"J\"><Body>" +
               mobile("W", localPose("1 0 0 0 0 0")) + "</Body></RCHingeJoint><RCHingeJoint Key=\"K\"><Body>" +
               mobile("V", localPose("-1 0 0 0 0 0")) + "</Body></RCHingeJoint>" + drives +
               "</ChildList></RCConstruction></Construction><ControllerList>" + controllers +
               "</ControllerList></RCRobot>");
}

std::string compileErrors(const std::string& text) {
  Scene s = mustLoad(text);
  Model m;
  Diagnostics d;
  CHECK_FALSE(compileScene(s, &m, d));
  return errorText(d);
}

}  // namespace

TEST_CASE("compile: drives become actuators and controllers ControllerDefs, without warnings", "[scene][compile]") {
  Diagnostics d;
  Scene s = mustLoad(robot(
      "<RCGenericDrive Key=\"D\"><Joint Ref=\"Bot.C.J\"/><MaxPower Value=\"3\"/><MaxVelocity Value=\"4\"/>"
      "<MinPos Value=\"-1\"/><Stall Value=\"0.5\"/></RCGenericDrive>"
      "<RCGenericVelControlledDrive Key=\"L\"><Joint Ref=\"Bot.C.J\"/></RCGenericVelControlledDrive>"
      "<RCGenericVelControlledDrive Key=\"R\"><Joint Ref=\"Bot.C.K\"/></RCGenericVelControlledDrive>",
      "<RCCommandSchedule Key=\"S\"><Target Ref=\"Bot.M\"/><Commands Value=\"0 1 0; 2 0 0.5\"/></RCCommandSchedule>"
      "<RCDriveTest><Drive Ref=\"Bot.C.D\"/><Period Value=\"0.02\"/></RCDriveTest>"
      "<RCTwoWheelMotionControl Key=\"M\"><ControlLeft Ref=\"Bot.C.L\"/><ControlRight Ref=\"Bot.C.R\"/>"
      "</RCTwoWheelMotionControl>"));
  Model m;
  REQUIRE(compileScene(s, &m, d));
  CHECK(d.warnings().empty());
  REQUIRE(m.actuators.size() == 3);
  const ActuatorDef& a = m.actuators[0];
  CHECK(a.key == "Bot.C.D");
  CHECK(a.kind == ActuatorDef::Drive);
  CHECK(a.joint == 0);
  CHECK(a.max_power == 3);
  CHECK(a.max_velocity == 4);
  CHECK(a.min_pos == -1);
  CHECK(std::isinf(a.max_pos));
  CHECK(a.stall == 0.5);
  CHECK(m.actuators[2].kind == ActuatorDef::VelDrive);
  CHECK(m.actuators[2].joint == 1);
  // The schedule's target is lowered first, so it comes before the schedule.
  REQUIRE(m.controllers.size() == 3);
  REQUIRE(m.controllers[0].kind() == ControllerDef::TwoWheel);
  CHECK(m.controllers[0].as<TwoWheelDef>().left == 1);
  CHECK(m.controllers[0].as<TwoWheelDef>().right == 2);
  REQUIRE(m.controllers[1].kind() == ControllerDef::CommandSchedule);
  const CommandScheduleDef& schedule = m.controllers[1].as<CommandScheduleDef>();
  CHECK(schedule.target == 0);
  CHECK(schedule.actuator == -1);
  CHECK(schedule.values == 2);
  CHECK(schedule.commands == std::vector<double>{0, 1, 0, 2, 0, 0.5});
  REQUIRE(m.controllers[2].kind() == ControllerDef::DriveTest);
  CHECK(m.controllers[2].as<DriveTestDef>().period == 0.02);
  CHECK(m.controllers[2].as<DriveTestDef>().drive == 0);
}

TEST_CASE("compile: command schedule errors name the row", "[scene][compile]") {
  const std::string drive = "<RCGenericDrive Key=\"D\"><Joint Ref=\"Bot.C.J\"/></RCGenericDrive>";
  auto sched = [](const std::string& commands) {
    return "<RCCommandSchedule Key=\"S\"><Target Ref=\"Bot.C.D\"/><Commands Value=\"" + commands +
           "\"/></RCCommandSchedule>";
  };
  CHECK_THAT(compileErrors(robot(drive, sched("0 1; 1 0; 1 0.5"))),
             Catch::Contains("RCCommandSchedule 'Bot.S': parameter 'Commands': row 3: time 1 s is not after the "
                             "previous row's 1 s (times must increase strictly)"));
  CHECK_THAT(compileErrors(robot(drive, sched("0 1 2"))),
             Catch::Contains("parameter 'Commands' must hold rows of 'time value' (2 numbers each), got 3 numbers"));
  CHECK_THAT(compileErrors(robot(drive, sched("0 1; -1 0"))), Catch::Contains("row 2: time -1 s must be in [0, 1e9]"));
  CHECK_THAT(compileErrors(robot(drive, sched("0 x"))), Catch::Contains("parameter 'Commands': "));
  // A target without a command interface.
  CHECK_THAT(compileErrors(robot("",
                                 "<RCCommandSchedule Key=\"S\"><Target><RCDriveTest/></Target>"
                                 "<Commands Value=\"0 1\"/></RCCommandSchedule>")),
             Catch::Contains("parameter 'Target' must refer to a component implementing RCDriver, RCPosControl, "
                             "RCVelControl or RC2DMotionControl, but RCDriveTest 'Bot.S.Target' does not"));
}

TEST_CASE("compile: a drive outside the construction of its joint is refused clearly", "[scene][compile]") {
  // The drive sits in another construction listed before the one holding the joint.
  const std::string text =
      scene("<RCConstruction Key=\"A\"><Body>" + mobile("P", globalPose("5 0 0 0 0 0")) +
            "</Body><ChildList><RCGenericDrive Key=\"D\"><Joint Ref=\"B.J\"/></RCGenericDrive></ChildList>"
            "</RCConstruction><RCConstruction Key=\"B\"><Body>" +
            mobile("Q", globalPose("0 0 0 0 0 0")) + "</Body><ChildList><RCHingeJoint Key=\"J\"><Body>" +
            mobile("W", localPose("1 0 0 0 0 0")) + "</Body></RCHingeJoint></ChildList></RCConstruction>");
  CHECK_THAT(compileErrors(text),
             Catch::Contains("RCGenericDrive 'A.D': parameter 'Joint' refers to RCHingeJoint 'B.J', which is not "
                             "built before this periphery"));
}

TEST_CASE("compile: the example pendulum", "[scene][compile]") {
  Scene s;
  Diagnostics d;
  REQUIRE(loadScene(std::string(SIMBOB_SOURCE_DIR) + "/scenes/pendulum.xml", testRegistry(), &s, d));
  Model m;
  REQUIRE(compileScene(s, &m, d));
  REQUIRE(m.bodies.size() == 1);
  const BodyDef& bob = m.bodies[0];
  CHECK(bob.key == "Pendulum.Hinge.Bob");
  checkVec(bob.pose.p, {std::sin(30 * kDeg), 2 - std::cos(30 * kDeg), 0});
  checkRot(bob.pose.q, rz(30));
  CHECK(bob.mass == 1);
  REQUIRE(m.joints.size() == 1);
  checkVec(m.joints[0].anchor, {0, 2, 0});
  checkVec(m.joints[0].axis, {0, 0, 1});
  CHECK(m.joints[0].body1 == -1);
  CHECK(m.joints[0].body2 == 0);
  CHECK(m.settings.max_time_step == 0.001);
}

namespace {

std::string cloneWithOutsideBody(bool clone_first) {
  const std::string clone = "<RigidBodyClone Key=\"Ball2\"><Original Value=\"Ball\"/><Pose>" +
                            globalPose("10 0 0 0 0 0") + "</Pose></RigidBodyClone>";
  const std::string original = "<RCConstruction Key=\"Ball\"><Body>" + mobile("Root", globalPose("0 0 0 0 0 0")) +
                               "</Body><ChildList><RCBallSocketJoint Key=\"J\"><Body Ref=\"Ballast\"/>"
                               "</RCBallSocketJoint></ChildList></RCConstruction>";
  const std::string outside = mobile("Ballast", globalPose("0 5 0 0 0 0"));
  return scene(clone_first ? clone + original + outside : original + outside + clone);
}

void checkCloneWithOutsideBody(const Model& m) {
  REQUIRE(m.bodies.size() == 3);
  // The body outside the original keeps its key and place; both copies' joints reach it.
  checkVec(bodyNamed(m, "Ballast").pose.p, {0, 5, 0});
  checkVec(bodyNamed(m, "Ball.Root").pose.p, {0, 0, 0});
  checkVec(bodyNamed(m, "Ball2.Root").pose.p, {10, 0, 0});
  CHECK(jointNamed(m, "Ball.J").body2 == bodyIndex(m, "Ballast"));
  CHECK(jointNamed(m, "Ball2.J").body2 == bodyIndex(m, "Ballast"));
  CHECK(jointNamed(m, "Ball2.J").body1 == bodyIndex(m, "Ball2.Root"));
}

}  // namespace

TEST_CASE("compile: a clone renames only keys below the original", "[scene][compile]") {
  Model m = mustCompile(cloneWithOutsideBody(false));
  checkCloneWithOutsideBody(m);
  for (const BodyDef& b : m.bodies) CHECK(b.key.find("Ball2ast") == std::string::npos);
}

TEST_CASE("compile: a clone before the original does not move bodies outside the original", "[scene][compile]") {
  // Top-level clones are built after every other top-level body, so a joint's Body Ref from
  // inside the original to a body outside it finds that body already built in place.
  checkCloneWithOutsideBody(mustCompile(cloneWithOutsideBody(true)));
}

// ---------------------------------------------------------------------------------- audit #9: clones

namespace {

/// Construction B (mobile root, hinge Arm to Link) and clones C1 of B and C2 of C1.
std::string cloneChain() {
  return scene("<RCConstruction Key=\"B\"><Body>" + mobile("Root", globalPose("0 1 0 0 0 0")) +
               "</Body><ChildList><RCHingeJoint Key=\"Arm\"><Body>" + mobile("Link", localPose("1 0 0 0 0 0")) +
               "</Body></RCHingeJoint></ChildList></RCConstruction>"
               "<RigidBodyClone Key=\"C1\"><Original Value=\"B\"/><Pose>" +
               globalPose("0 1 5 0 0 0") +
               "</Pose></RigidBodyClone>"
               "<RigidBodyClone Key=\"C2\"><Original Value=\"C1\"/><Pose>" +
               globalPose("0 1 10 0 90 0") + "</Pose></RigidBodyClone>");
}

void checkUniqueModelKeys(const Model& m) {
  std::set<std::string> bodies, joints;
  for (const auto& b : m.bodies) CHECK(bodies.insert(b.key).second);
  for (const auto& j : m.joints) CHECK(joints.insert(j.key).second);
}

}  // namespace

TEST_CASE("compile: a clone of a clone renames twice: every copy has keys of its own", "[scene][compile][clone]") {
  // Before the fix, C2 (a clone of the clone C1) renamed only C1's own prefix, so C2's copy got
  // the keys 'C1.Root' and 'C1.Arm.Link' a second time: `check` passed, `run` stopped at the
  // CSV writer with "duplicate body key 'C1.Root'".
  Model m = mustCompile(cloneChain());
  REQUIRE(m.bodies.size() == 6);
  REQUIRE(m.joints.size() == 3);
  checkUniqueModelKeys(m);
  checkVec(bodyNamed(m, "B.Root").pose.p, {0, 1, 0});
  checkVec(bodyNamed(m, "B.Arm.Link").pose.p, {1, 1, 0});
  checkVec(bodyNamed(m, "C1.Root").pose.p, {0, 1, 5});
  checkVec(bodyNamed(m, "C1.Arm.Link").pose.p, {1, 1, 5});
  // C2 copies C1 (whose root is at (0,1,5)) onto (0,1,10) turned 90 deg about Y.
  checkVec(bodyNamed(m, "C2.Root").pose.p, {0, 1, 10});
  checkVec(bodyNamed(m, "C2.Arm.Link").pose.p, add({0, 1, 10}, mat_apply(ry(90), {1, 0, 0})));
  checkRot(bodyNamed(m, "C2.Arm.Link").pose.q, ry(90));
  // Each copy's joint connects that copy's bodies.
  for (const char* c : {"B", "C1", "C2"}) {
    std::string p = c;
    INFO("copy " << p);
    const JointDef& j = jointNamed(m, p + ".Arm");
    CHECK(j.body1 == bodyIndex(m, p + ".Root"));
    CHECK(j.body2 == bodyIndex(m, p + ".Arm.Link"));
  }
  checkVec(jointNamed(m, "C2.Arm").anchor, {0, 1, 10});
  checkVec(jointNamed(m, "C2.Arm").axis, mat_apply(ry(90), {0, 0, 1}));
}

TEST_CASE("compile: clones of an imported construction and of clones of it", "[scene][compile][clone][import]") {
  // Before the fix IC2 (a clone of the clone IC of the import I) repeated IC's keys.
  TempDir dir;
  dir.write("arm.xml", "<Body><RCConstruction Key=\"Arm\"><Body><RCStaticRigidBody Key=\"Base\"><Pose>" +
                           globalPose("0 1 0 0 0 0") +
                           "</Pose><Geom><RCCuboidGeom/></Geom></RCStaticRigidBody></Body><ChildList>"
                           "<RCHingeJoint Key=\"J\"><Body>" +
                           mobile("Link", localPose("1 0 0 0 0 0")) +
                           "</Body></RCHingeJoint></ChildList></RCConstruction></Body>");
  auto clone = [](const std::string& key, const std::string& original, const std::string& pose) {
    return "<RigidBodyClone Key=\"" + key + "\"><Original Value=\"" + original + "\"/><Pose>" + globalPose(pose) +
           "</Pose></RigidBodyClone>";
  };
  std::string main = dir.write("main.xml", scene("<RCImportBody Key=\"I\"><File Value=\"arm.xml\"/></RCImportBody>" +
                                                 clone("IC", "I", "0 1 5 0 0 0") + clone("IC2", "IC", "0 1 10 0 0 0") +
                                                 clone("AC", "I.Arm", "0 1 -5 0 0 0")));
  Scene s;
  Diagnostics d;
  REQUIRE(loadScene(main, testRegistry(), &s, d));
  Model m;
  bool ok = compileScene(s, &m, d);
  INFO(errorText(d));
  REQUIRE(ok);
  REQUIRE(m.bodies.size() == 4);
  REQUIRE(m.joints.size() == 4);
  checkUniqueModelKeys(m);
  checkVec(bodyNamed(m, "I.Arm.J.Link").pose.p, {1, 1, 0});
  checkVec(bodyNamed(m, "IC.Arm.J.Link").pose.p, {1, 1, 5});
  checkVec(bodyNamed(m, "IC2.Arm.J.Link").pose.p, {1, 1, 10});
  checkVec(bodyNamed(m, "AC.J.Link").pose.p, {1, 1, -5});
  checkVec(jointNamed(m, "IC2.Arm.J").anchor, {0, 1, 10});
  CHECK(jointNamed(m, "IC2.Arm.J").body2 == bodyIndex(m, "IC2.Arm.J.Link"));
  CHECK(jointNamed(m, "AC.J").body2 == bodyIndex(m, "AC.J.Link"));
  // The static base of every copy moves with it.
  checkVec(onlyGeom(m, "IC2.Arm.Base").offset.p, {0, 1, 10});
  checkVec(onlyGeom(m, "AC.Base").offset.p, {0, 1, -5});
}

TEST_CASE("compile: clones nest up to 8 deep", "[scene][compile][clone]") {
  auto chain = [](int n) {
    std::string s = mobile("B", globalPose("0 1 0 0 0 0"));
    std::string prev = "B";
    for (int i = 1; i <= n; ++i) {
      std::string key = "C" + std::to_string(i);
      s += "\n<RigidBodyClone Key=\"" + key + "\"><Original Value=\"" + prev + "\"/><Pose>" +
           globalPose("0 1 " + std::to_string(i) + " 0 0 0") + "</Pose></RigidBodyClone>";
      prev = key;
    }
    return scene(s);
  };
  Model m = mustCompile(chain(8));
  REQUIRE(m.bodies.size() == 9);
  checkUniqueModelKeys(m);
  checkVec(bodyNamed(m, "C8").pose.p, {0, 1, 8});
  // One more is an error (on the clone lowered 9 deep: C1, inside the copy of C9).
  Scene s = mustLoad(chain(9));
  Model m9;
  Diagnostics d;
  CHECK_FALSE(compileScene(s, &m9, d));
  INFO(errorText(d));
  REQUIRE(d.errors().size() == 1);
  CHECK(d.errors()[0].str() == "test.xml:3: RigidBodyClone 'C1': clones nested deeper than 8");
}

TEST_CASE("compile: two bodies with one key are an error at compile time", "[scene][compile][clone]") {
  // Before, a duplicate body key (what clones of clones made) passed `check` and stopped `run`
  // only when the CSV writer met it. Clones no longer make one, so force one into the graph.
  Scene s = mustLoad(scene(mobile("A", globalPose("0 1 0 0 0 0")) + "\n" + mobile("B", globalPose("0 2 0 0 0 0"))));
  const int b = s.find("B");
  REQUIRE(b >= 0);
  s.at(b).qkey = "A";
  Model m;
  Diagnostics d;
  CHECK_FALSE(compileScene(s, &m, d));
  INFO(errorText(d));
  REQUIRE(d.errors().size() == 1);
  CHECK(d.errors()[0].str() ==
        "test.xml:3: two bodies get the key 'A' (the second from here); give the copy a Key of its own");
}

TEST_CASE("compile: a clone of a joint's child body with a local Pose lands at the clone's Pose",
          "[scene][compile][clone]") {
  // Before the fix the original was lowered again without its joint's frame: "RCLocalCoordinates
  // needs a parent frame" on the original's Pose, and the scene did not compile.
  Model m = mustCompile(scene(pendulum() + "<RigidBodyClone Key=\"Bob2\"><Original Value=\"P.H.Bob\"/><Pose>" +
                              globalPose("5 3 0 0 0 90") + "</Pose></RigidBodyClone>"));
  REQUIRE(m.bodies.size() == 2);
  const BodyDef& bob = bodyNamed(m, "P.H.Bob");
  checkVec(bob.pose.p, {0.5, 2 - std::cos(30 * kDeg), 0});
  const BodyDef& copy = bodyNamed(m, "Bob2");
  checkVec(copy.pose.p, {5, 3, 0});
  checkRot(copy.pose.q, rz(90));
  // The copy is the body alone: no joint comes with it, and the original keeps its joint.
  REQUIRE(m.joints.size() == 1);
  CHECK(m.joints[0].body2 == bodyIndex(m, "P.H.Bob"));
  CHECK(onlyGeom(m, "Bob2").body == bodyIndex(m, "Bob2"));
}

// ---------------------------------------------------------------------------------- audit #9: models

TEST_CASE("compile: a child model's global Pose is relative to the body, not to its parent model (guide 6.3)",
          "[scene][compile][model]") {
  // Before: a child's RCGlobalCoordinates were composed onto the parent model's frame like local
  // ones, so the child cuboid below landed at body + (3, 0, 0) instead of body + (2, 0, 0).
  const std::string model = "<Model><RCCuboidModel><Pose>" + localPose("1 0 0 0 0 90") +
                            "</Pose><ChildList>"
                            "<RCCuboidModel Key=\"Global\"><Pose>" +
                            globalPose("2 0 0 0 0 0") +
                            "</Pose></RCCuboidModel>"
                            "<RCCuboidModel Key=\"Local\"><Pose>" +
                            localPose("2 0 0 0 0 0") + "</Pose></RCCuboidModel></ChildList></RCCuboidModel></Model>";
  Model m = mustCompile(scene(mobile("A", globalPose("10 0 0 0 90 0"), "<RCModelMatchGeom/>", model) +
                              "<RCStaticRigidBody Key=\"S\"><Pose>" + globalPose("10 0 0 0 0 0") +
                              "</Pose><Geom><RCModelMatchGeom/></Geom>" + model + "</RCStaticRigidBody>"));
  // Mobile body: geom offsets are in the body frame (document order: root, Global, Local).
  std::vector<const GeomDef*> a = geomsOf(m, "A");
  REQUIRE(a.size() == 3);
  checkVec(a[0]->offset.p, {1, 0, 0});
  checkRot(a[0]->offset.q, rz(90));
  checkVec(a[1]->offset.p, {2, 0, 0});
  checkRot(a[1]->offset.q, rz(0));
  // A local child follows its parent: (1,0,0) + Rz(90)(2,0,0).
  checkVec(a[2]->offset.p, {1, 2, 0});
  checkRot(a[2]->offset.q, rz(90));
  // Static body at (10,0,0): geoms are global.
  std::vector<const GeomDef*> s = geomsOf(m, "S");
  REQUIRE(s.size() == 3);
  checkVec(s[0]->offset.p, {11, 0, 0});
  checkVec(s[1]->offset.p, {12, 0, 0});
  checkVec(s[2]->offset.p, {11, 2, 0});
}
