// --draw sensors (RenderOptions::draw_sensors): range sensor and laser scanner rays drawn from
// the sensor to its reading, hit points where a reading is below MaxRange. Checked against the
// analytic projection of a camera looking straight down: every ray's pixels are where the
// pinhole model puts the segment, and every red pixel lies on one of the segments.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "render/reference_frames.h"
#include "simbob/compile.h"
#include "simbob/graph.h"
#include "simbob/physics.h"
#include "simbob/tool/png.h"
#include "simbob/renderer.h"
#include "test_registry.h"

using namespace simbob;
using namespace simbob::test;

namespace {

// Camera "Top" at (0, 10, -1) looking straight down (-Y), image top = -Z, 160x120, 60 degrees:
// a point (x, y, z) is at column 80 + f x / (10 - y), row 60 + f (z + 1) / (10 - y) from the
// top, f = 80 / tan 30 deg. A wall's front face at z = -1.9.
const char* kScene = R"(<Simulation>
  <CameraList>
    <RCStaticCamera Key="Top">
      <Pose><RCGlobalCoordinates><Pose Value="0 10 -1 -90 0 0"/></RCGlobalCoordinates></Pose>
    </RCStaticCamera>
  </CameraList>
  <SceneSettings><MaxTimeStep Value="0.001"/></SceneSettings>
  <ComponentList>
    <RCStaticRigidBody Key="Wall">
      <Pose><RCGlobalCoordinates><Pose Value="0 0.5 -2 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCCuboidGeom><Width Value="6"/><Height Value="1"/><Depth Value="0.2"/></RCCuboidGeom></Geom>
    </RCStaticRigidBody>
    <RCConstruction Key="Bot">
      <Body><RCMobileRigidBody Key="Chassis">
        <Pose><RCGlobalCoordinates><Pose Value="0.25 0.5 0 0 0 0"/></RCGlobalCoordinates></Pose>
        <Geom><RCCuboidGeom><Width Value="0.1"/><Height Value="0.1"/><Depth Value="0.1"/></RCCuboidGeom></Geom>
      </RCMobileRigidBody></Body>
      <ChildList>
        <RCRangeSensor Key="Front"><MaxRange Value="5"/></RCRangeSensor>
        <RCRangeSensor Key="Back">
          <Pose><RCLocalCoordinates><Pose Value="0 0 0 0 180 0"/></RCLocalCoordinates></Pose>
          <MaxRange Value="1.5"/>
        </RCRangeSensor>
        <RCLaserScanner Key="Scan">
          <Pose><RCLocalCoordinates><Pose Value="-1.75 0 0 0 0 0"/></RCLocalCoordinates></Pose>
          <Rays Value="3"/><FieldOfView Value="90"/><MaxRange Value="1"/>
        </RCLaserScanner>
      </ChildList>
    </RCConstruction>
  </ComponentList>
</Simulation>)";

struct Px {
  double u, v;
};
Px project(const Vec3& p) {
  const double f = 80 / std::tan(30 * 3.14159265358979323846 / 180);
  return {80 + f * p[0] / (10 - p[1]), 60 + f * (p[2] + 1) / (10 - p[1])};
}
bool isRed(const Image& img, int x, int y) {
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return false;
  const uint8_t* p = img.pixel(x, y);
  return p[0] > 200 && p[1] < 60 && p[2] < 60;
}
bool isYellow(const Image& img, int x, int y) {
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return false;
  const uint8_t* p = img.pixel(x, y);
  return p[0] > 200 && p[1] > 200 && p[2] < 60;
}
template <class F>
bool near(const Image& img, Px at, int r, F is) {
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx)
      if (is(img, static_cast<int>(std::floor(at.u)) + dx, static_cast<int>(std::floor(at.v)) + dy)) return true;
  return false;
}
double distToSegment(Px p, Px a, Px b) {
  const double dx = b.u - a.u, dy = b.v - a.v, l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((p.u - a.u) * dx + (p.v - a.v) * dy) / l2 : 0;
  t = std::max(0.0, std::min(1.0, t));
  return std::hypot(p.u - (a.u + t * dx), p.v - (a.v + t * dy));
}

Image draw(const Model& m, const std::vector<double>& rays, bool sensors) {
  RenderOptions o;
  o.width = 160;
  o.height = 120;
  o.backend = backend();
  o.camera = "Top";
  o.draw_models = false;
  o.draw_geoms = false;
  o.draw_sensors = sensors;
  Error err;
  std::unique_ptr<Renderer> r = Renderer::create(m, o, &err);
  INFO(err.message);
  REQUIRE(r);
  r->setSensorRays(rays);
  Image img;
  REQUIRE(r->render(initialPoses(m), 0, &img) == nullptr);
  return img;
}

}  // namespace

TEST_CASE("--draw sensors: rays to their readings and hit points where the projection puts them") {
  Scene s;
  Diagnostics d;
  Model m;
  REQUIRE((loadSceneFromText(kScene, "rays.xml", Format::Xml, testRegistry(), &s, d) && compileScene(s, &m, d)));
  std::unique_ptr<World> w = World::create(m, 1);
  REQUIRE(w);
  const std::vector<double> rays = sensorRays(m, *w);
  // Front hits the wall 1.9 m ahead; Back and the scanner's rays (MaxRange) hit nothing.
  REQUIRE(rays.size() == 5);
  CHECK(rays[0] == Approx(1.9).margin(1e-9));
  CHECK(rays[1] == 1.5);
  CHECK(rays[2] == 1.0);
  CHECK(rays[3] == 1.0);
  CHECK(rays[4] == 1.0);

  const Image img = draw(m, rays, true);
  REQUIRE(writePng("sensor_rays.png", img).message.empty());  // for a look: build/sensor_rays.png
  // The segments in the world: Front to the wall, Back 1.5 m behind, the scanner's three rays
  // at -45, 0 and 45 degrees from its -Z (ray 0 to the right, +X).
  const double c = std::sqrt(0.5);
  const std::vector<std::pair<Vec3, Vec3>> segs = {{{0.25, 0.5, 0}, {0.25, 0.5, -1.9}},
                                                   {{0.25, 0.5, 0}, {0.25, 0.5, 1.5}},
                                                   {{-1.5, 0.5, 0}, {-1.5 + c, 0.5, -c}},
                                                   {{-1.5, 0.5, 0}, {-1.5, 0.5, -1}},
                                                   {{-1.5, 0.5, 0}, {-1.5 - c, 0.5, -c}}};
  for (const auto& [a, b] : segs)
    for (double t : {0.2, 0.35, 0.5, 0.65, 0.8}) {
      const Vec3 p{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
      const Px at = project(p);
      INFO("ray point " << p[0] << " " << p[2] << " at pixel " << at.u << " " << at.v);
      CHECK(near(img, at, 1, isRed));
    }
  // Every red pixel lies on a segment (within 1.5 pixels of its projection).
  int red = 0, stray = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      if (!isRed(img, x, y)) continue;
      ++red;
      double best = 1e9;
      for (const auto& [a, b] : segs) best = std::min(best, distToSegment({x + 0.5, y + 0.5}, project(a), project(b)));
      if (best > 1.5) ++stray;
    }
  CHECK(red > 60);
  CHECK(stray == 0);
  // A hit point (yellow) at Front's hit only: none at the ends of rays that hit nothing.
  CHECK(near(img, project({0.25, 0.5, -1.9}), 2, isYellow));
  CHECK_FALSE(near(img, project({0.25, 0.5, 1.5}), 3, isYellow));
  CHECK_FALSE(near(img, project({-1.5, 0.5, -1}), 3, isYellow));

  // Without draw_sensors nothing of it is drawn (so the checks above can fail).
  const Image plain = draw(m, rays, false);
  int plain_red = 0;
  for (int y = 0; y < plain.height; ++y)
    for (int x = 0; x < plain.width; ++x) plain_red += isRed(plain, x, y) || isYellow(plain, x, y);
  CHECK(plain_red == 0);
}
