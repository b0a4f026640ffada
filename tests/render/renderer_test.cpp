// Rendering (lib/render): reference images, the pinhole model, quality levels and cameras.
//
// Reference comparison (imagesMatch): a pixel differs when one of its channels is off by more
// than kChannelTolerance (24 of 255); images match when at most kDifferingFraction (0.5 %) of
// the pixels differ. A one-bit rasterizer difference changes a channel by 1 or moves an edge
// pixel; a wrong colour changes a whole object's pixels (thousands), a missing object all of
// its pixels, a camera turned by 1 degree moves every edge (tests below show each is caught).
// Re-bless with scripts/update-frames.sh (SIMBOB_BLESS_FRAMES=1) and look at the images.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "simbob/compile.h"
#include "simbob/graph.h"
#include "simbob/image_compare.h"
#include "simbob/png.h"
#include "simbob/render.h"
#include "simbob/transform.h"
#include "simbob/values.h"
#include "render/reference_frames.h"
#include "test_registry.h"

using namespace simbob;
using namespace simbob::test;

namespace {

Model compileFile(const std::string& rel) {
  Scene s;
  Diagnostics d;
  REQUIRE(loadScene(std::string(SIMBOB_SOURCE_DIR) + "/" + rel, testRegistry(), &s, d));
  Model m;
  REQUIRE(compileScene(s, &m, d));
  return m;
}

Model compileText(const std::string& xml) {
  Scene s;
  Diagnostics d;
  Model m;
  const bool ok = loadSceneFromText(xml, "test.xml", Format::Xml, testRegistry(), &s, d) && compileScene(s, &m, d);
  INFO((d.errors().empty() ? std::string() : d.errors()[0].str()));
  REQUIRE(ok);
  return m;
}

Image draw(const Model& m, int w, int h, const std::string& camera = "", Quality q = Quality::Shadows) {
  RenderOptions o;
  o.width = w;
  o.height = h;
  o.backend = backend();
  o.camera = camera;
  o.quality = q;
  Error err;
  std::unique_ptr<Renderer> r = Renderer::create(m, o, &err);
  INFO(err.message);
  REQUIRE(r);
  Image img;
  const Error* e = r->render(initialPoses(m), 0, &img);
  REQUIRE(e == nullptr);
  return img;
}

const uint8_t* at(const Image& img, int x, int y) { return img.pixel(x, y); }

// A 2 m x 2 m board textured with scenes/textures/checker.bmp (8 squares across the image), seen
// face-on from 2 m and lit from the front. Returns how often a row near the centre changes
// between light and dark squares across the board, and the image.
int checkerEdges(double tex_scale, Image* img) {
  const std::string xml = R"(<Simulation>
  <CameraList><RCStaticCamera Key="Face">
    <Pose><RCGlobalCoordinates><Pose Value="0 0 2 0 0 0"/></RCGlobalCoordinates></Pose><ViewAngle Value="60"/>
  </RCStaticCamera></CameraList>
  <SceneSettings><ClearColor Value="0 0 0"/><LightPos Value="0 0 10 1"/></SceneSettings>
  <ComponentList>
    <RCTexturedSkin Key="Checker"><Texture Value="textures/checker.bmp"/></RCTexturedSkin>
    <RCStaticRigidBody Key="Board">
      <Pose><RCGlobalCoordinates><Pose Value="0 0 0 0 0 0"/></RCGlobalCoordinates></Pose>
      <Model><RCPlaneModel><Skin Ref="Checker"/><ExtensionX Value="2"/><ExtensionY Value="2"/>
        <TexScale Value=")" +
                          formatNumber(tex_scale) + R"("/></RCPlaneModel></Model>
    </RCStaticRigidBody>
  </ComponentList>
</Simulation>)";
  const Model m = compileText(xml);
  RenderOptions o;
  o.width = 320;
  o.height = 240;
  o.backend = backend();
  o.quality = Quality::Textures;
  o.texture_folder = std::string(SIMBOB_SOURCE_DIR) + "/scenes";
  Error err;
  std::unique_ptr<Renderer> r = Renderer::create(m, o, &err);
  INFO(err.message);
  REQUIRE(r);
  REQUIRE(r->render(initialPoses(m), 0, img) == nullptr);
  if (const char* dir = std::getenv("SIMBOB_DEBUG_FRAMES"))
    writePng(std::string(dir) + "/checker_" + formatNumber(tex_scale) + ".png", *img);
  // The board's pixels on a row 4 pixels below the centre (the centre line is an edge between
  // rows of squares; 4 pixels is inside a square at both scales here, whose squares are 17 and
  // 8.7 pixels tall), split at the middle of their range into light and dark. The background
  // is black.
  const int y = img->height / 2 + 4;
  std::vector<int> g;
  for (int x = 0; x < img->width; ++x)
    if (img->pixel(x, y)[1] > 20) g.push_back(img->pixel(x, y)[1]);
  REQUIRE(g.size() > 250);  // 2 m of the 2.31 m in view: about 277 pixels
  const auto [lo, hi] = std::minmax_element(g.begin(), g.end());
  REQUIRE(*hi - *lo > 40);  // the texture's greys are 120 and 200
  const int mid = (*lo + *hi) / 2;
  int edges = 0;
  for (size_t i = 1; i < g.size(); ++i) edges += (g[i] > mid) != (g[i - 1] > mid);
  return edges;
}

}  // namespace

TEST_CASE("TexScale (guide 6.2.1): the size of one texture image in metres, or a fraction of the extension") {
  Image one_metre, half_metre, half_extent;
  // 1 m images: 2 across the board, 16 squares, 15 edges between them.
  CHECK(checkerEdges(1.0, &one_metre) == 15);
  // 0.5 m images: 4 across, 32 squares.
  CHECK(checkerEdges(0.5, &half_metre) == 31);
  // -0.5: the image twice across the 2 m extension, so 1 m images again, starting at the edge.
  CHECK(checkerEdges(-0.5, &half_extent) == 15);
  // The 1 m images start at the board's centre and the half-extent ones at its edge, 1 m (one
  // whole image) apart: the same picture.
  CHECK(imagesMatch(one_metre, half_extent));
  CHECK_FALSE(imagesMatch(one_metre, half_metre));
}

TEST_CASE("the basic scene matches its reference images from both cameras") {
  const Model m = compileFile("tests/data/render/basic.xml");
  checkReference(draw(m, 160, 120, "Front"), "basic_front");
  checkReference(draw(m, 160, 120, "Top"), "basic_top");
}

TEST_CASE("the comparison catches a wrong colour, a missing object and a camera turned by 1 degree") {
  const Model m = compileFile("tests/data/render/basic.xml");
  const Image ref = draw(m, 160, 120, "Front");
  CHECK(imagesMatch(ref, draw(m, 160, 120, "Front")));  // rendering twice gives the same image

  Model recoloured = m;
  for (SkinDef& s : recoloured.skins)
    if (s.key == "Blue") s.color = s.ambient = s.diffuse = {0.0, 0.4, 0.8, 1};
  CHECK_FALSE(imagesMatch(ref, draw(recoloured, 160, 120, "Front")));

  Model missing = m;
  missing.visuals.erase(std::remove_if(missing.visuals.begin(), missing.visuals.end(),
                                       [](const VisualDef& v) { return v.shape == VisualDef::Ellipsoid; }),
                        missing.visuals.end());
  CHECK_FALSE(imagesMatch(ref, draw(missing, 160, 120, "Front")));

  Model turned = m;
  for (CameraDef& c : turned.cameras)
    if (c.key == "Front") c.pose.q = quatMul(quatAxisAngle({0, 1, 0}, kPi / 180), c.pose.q);
  CHECK_FALSE(imagesMatch(ref, draw(turned, 160, 120, "Front")));
}

namespace {

/// A white unlit ball of radius r at distance d in front of a camera at the origin (looking
/// along -Z), on black.
std::string ballScene(double r, double d, double view_angle) {
  return R"(<Simulation><CameraList><RCStaticCamera Key="C"><ViewAngle Value=")" + std::to_string(view_angle) +
         R"("/><NearClip Value="0.1"/></RCStaticCamera></CameraList>
<SceneSettings><ClearColor Value="0 0 0"/></SceneSettings><ComponentList>
<RCColoredSkin Key="White"><Color Value="1 1 1"/><ColorMode Value="Color"/></RCColoredSkin>
<RCStaticRigidBody Key="Ball"><Pose><RCGlobalCoordinates><Pose Value="0 0 -)" +
         std::to_string(d) + R"( 0 0 0"/></RCGlobalCoordinates></Pose>
<Model><RCEllipsoidModel><Skin Ref="White"/><Accuracy Value="12"/><RadiusX Value=")" +
         std::to_string(r) + R"("/><RadiusY Value=")" + std::to_string(r) + R"("/><RadiusZ Value=")" +
         std::to_string(r) + R"("/></RCEllipsoidModel></Model></RCStaticRigidBody></ComponentList></Simulation>)";
}

int litRun(const Image& img, bool row, int index) {
  int n = 0;
  const int len = row ? img.width : img.height;
  for (int i = 0; i < len; ++i) {
    const uint8_t* p = row ? img.pixel(i, index) : img.pixel(index, i);
    if (p[0] > 127) ++n;
  }
  return n;
}

}  // namespace

TEST_CASE("pinhole: a ball of known radius at a known distance covers the width ViewAngle predicts") {
  // The silhouette of a ball of radius r seen from distance d has the angular radius
  // asin(r / d); on the image plane at focal length f = (W / 2) / tan(ViewAngle / 2) pixels
  // it is 2 f tan(asin(r / d)) pixels wide, and as many tall (square pixels).
  for (double va : {40.0, 60.0, 90.0}) {
    const double r = 0.5, d = 5, w = 240, h = 180;
    const Image img = draw(compileText(ballScene(r, d, va)), int(w), int(h));
    const double f = (w / 2) / std::tan(va * kPi / 360);
    const double expected = 2 * f * std::tan(std::asin(r / d));
    INFO("ViewAngle " << va << ": expected " << expected << " px");
    CHECK(std::abs(litRun(img, true, int(h) / 2) - expected) <= 2.0);
    CHECK(std::abs(litRun(img, false, int(w) / 2) - expected) <= 2.0);
    // Centred: the camera looks along its -Z.
    CHECK(at(img, int(w) / 2, int(h) / 2)[0] == 255);
    CHECK(at(img, 0, 0)[0] == 0);
  }
}

TEST_CASE("quality levels: Frame draws edges only, Plane fills unlit in the skin colour, Smooth shades") {
  const Model m = compileText(ballScene(0.5, 3, 60));
  const Image plane = draw(m, 120, 90, "", Quality::Plane);
  const Image frame = draw(m, 120, 90, "", Quality::Frame);
  // Plane: the ball's centre is its colour; Frame: the bounding box's outline only, the centre empty.
  CHECK(at(plane, 60, 45)[0] == 255);
  CHECK(at(frame, 60, 45)[0] == 0);
  int lit = 0;
  for (size_t i = 0; i < frame.rgb.size(); i += 3) lit += frame.rgb[i] > 127;
  CHECK(lit > 40);
}

TEST_CASE("a skin without ColorMode Color is lit: darker away from the light") {
  const Model m = compileFile("tests/data/render/basic.xml");
  const Image img = draw(m, 160, 120, "Top", Quality::Smooth);
  // Seen from above, the blue ball's top faces the light: bright; the ground is green.
  bool blue = false;
  for (int x = 0; x < 160; ++x) {
    const uint8_t* p = img.pixel(x, 60);
    if (p[2] > 150 && p[0] < 60 && p[1] < 60) blue = true;
  }
  CHECK(blue);
}

TEST_CASE("an unknown --camera names the cameras there are") {
  const Model m = compileFile("tests/data/render/basic.xml");
  RenderOptions o;
  o.backend = backend();
  o.camera = "Side";
  Error err;
  CHECK_FALSE(Renderer::create(m, o, &err));
  CHECK(err.message == "no camera 'Side' in the scene (cameras: Front, Top)");
}

TEST_CASE("the gallery matches its references: every model and skin, textures, transparency, fog; each camera type") {
  const Model m = compileFile("scenes/gallery.xml");
  checkReference(draw(m, 160, 120, "Overview", Quality::Fog), "gallery_fog");
  checkReference(draw(m, 160, 120, "Overview", Quality::Shadows), "gallery_shadows");
  checkReference(draw(m, 160, 120, "Overview", Quality::Flat), "gallery_flat");
  checkReference(draw(m, 160, 120, "Overview", Quality::Wire), "gallery_wire");
  checkReference(draw(m, 160, 120, "Overview", Quality::Frame), "gallery_frame");
  checkReference(draw(m, 160, 120, "Spot"), "gallery_spot");
  checkReference(draw(m, 160, 120, "Chase"), "gallery_chase");
  checkReference(draw(m, 160, 120, "OnBall"), "gallery_onball");
  // Fog, textures and wire frames each change the picture.
  CHECK_FALSE(
      imagesMatch(draw(m, 160, 120, "Overview", Quality::Fog), draw(m, 160, 120, "Overview", Quality::Shadows)));
  CHECK_FALSE(
      imagesMatch(draw(m, 160, 120, "Overview", Quality::Textures), draw(m, 160, 120, "Overview", Quality::Smooth)));
  CHECK_FALSE(imagesMatch(draw(m, 160, 120, "Overview", Quality::Wire), draw(m, 160, 120, "Overview", Quality::Plane)));
}

TEST_CASE("a scene without cameras gets a default view that frames every body") {
  Model m = compileFile("tests/data/render/basic.xml");
  m.cameras.clear();
  const Image img = draw(m, 160, 120, "", Quality::Plane);
  // Both objects are in view, and nothing of them touches the border.
  bool red = false, blue = false;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const uint8_t* p = img.pixel(x, y);
      const bool r = p[0] > 200 && p[1]<50, b = p[2]> 200 && p[0] < 50;
      red |= r;
      blue |= b;
      if (x == 0 || y == 0 || x == img.width - 1 || y == img.height - 1) CHECK_FALSE((r || b));
    }
  CHECK(red);
  CHECK(blue);
}
