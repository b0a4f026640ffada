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
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "simbob/compile.h"
#include "simbob/graph.h"
#include "simbob/tool/image_compare.h"
#include "simbob/tool/png.h"
#include "simbob/renderer.h"
#include "simbob/trajectory.h"
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

namespace {

/// Where a world point shows on an image of w x h pixels drawn by a camera at `eye` looking
/// along -Z with +Y up and a horizontal field of view `va` degrees (x right, y down).
std::pair<int, int> project(const Vec3& p, const Vec3& eye, double va, int w, int h) {
  const double f = (w / 2.0) / std::tan(va * kPi / 360);
  const double depth = eye[2] - p[2];
  return {int(std::lround(w / 2.0 + f * (p[0] - eye[0]) / depth - 0.5)),
          int(std::lround(h / 2.0 - f * (p[1] - eye[1]) / depth - 0.5))};
}

}  // namespace

TEST_CASE("fog: a shadow is fogged like the ground it lies on, darker than the lit ground beside it") {
  // A grey ground, a 1 m box 10 m ahead, a point light 5 m up and 5 m to the right of it (its
  // shadow covers x in about [-1.9, -0.5] on the ground), linear fog from 2 to 30 m in a light
  // colour. GL fogs per vertex: the ground has 1 m cells, as the gallery has 2 m ones. (A point
  // light matters: its shadow matrix gives the projected vertices w != 1.)
  const Model boxed = compileText(R"(<Simulation>
  <CameraList><RCStaticCamera Key="C"><Pose><RCGlobalCoordinates><Pose Value="0 1.5 0 0 0 0"/></RCGlobalCoordinates></Pose>
    <ViewAngle Value="60"/></RCStaticCamera></CameraList>
  <SceneSettings><LightPos Value="5 5 -10 1"/><ClearColor Value="0 0 0"/><ShadowIntensity Value="0.5"/>
    <FogSettings><Mode Value="Linear"/><Start Value="2"/><End Value="30"/><Color Value="0.9 0.9 0.95"/></FogSettings>
  </SceneSettings>
  <ComponentList>
    <RCColoredSkin Key="Grey"><Color Value="0.6 0.6 0.6"/></RCColoredSkin>
    <RCGround Key="Ground"><Skin Ref="Grey"/><Extension Value="80"/><MaxCellSize Value="1"/></RCGround>
    <RCStaticRigidBody Key="Box"><Pose><RCGlobalCoordinates><Pose Value="0 0.5 -10 0 0 0"/></RCGlobalCoordinates></Pose>
      <Model><RCCuboidModel><Skin Ref="Grey"/></RCCuboidModel></Model></RCStaticRigidBody>
  </ComponentList>
</Simulation>)");
  Model open = boxed;  // the same ground without the box: no shadow
  open.visuals.erase(std::remove_if(open.visuals.begin(), open.visuals.end(),
                                    [](const VisualDef& v) { return v.shape == VisualDef::Cuboid; }),
                     open.visuals.end());
  REQUIRE(open.visuals.size() + 1 == boxed.visuals.size());
  const int w = 320, h = 240;
  const Vec3 eye{0, 1.5, 0};
  const auto [sx, sy] = project({-1.0, 0, -10}, eye, 60, w, h);  // in the shadow
  const auto [lx, ly] = project({-2.5, 0, -10}, eye, 60, w, h);  // lit ground, same distance
  const Image clear = draw(boxed, w, h, "C", Quality::Shadows);
  const Image fog = draw(boxed, w, h, "C", Quality::Fog);
  const Image open_clear = draw(open, w, h, "C", Quality::Shadows);
  const Image open_fog = draw(open, w, h, "C", Quality::Fog);
  if (const char* dir = std::getenv("SIMBOB_DEBUG_FRAMES")) {
    writePng(std::string(dir) + "/fog_shadow_clear.png", clear);
    writePng(std::string(dir) + "/fog_shadow_fog.png", fog);
  }
  for (int c = 0; c < 3; ++c) {
    const double ground = open_clear.pixel(sx, sy)[c], ground_fog = open_fog.pixel(sx, sy)[c];
    const double shade = clear.pixel(sx, sy)[c], shade_fog = fog.pixel(sx, sy)[c];
    const double lit_fog = fog.pixel(lx, ly)[c];
    const double fc = 255 * (c == 2 ? 0.95 : 0.9);
    INFO("channel " << c << ": ground there " << ground << ", fogged " << ground_fog << "; its shadow " << shade
                    << ", fogged " << shade_fog << "; the lit ground beside it fogged " << lit_fog);
    // Without fog the shadow halves the ground (ShadowIntensity 0.5).
    CHECK(std::abs(shade - ground / 2) <= 2);
    // With fog the ground there is f * ground + (1 - f) * fog colour, its shadow the same with
    // f * shade: darker than the ground by f * (ground - shade), and than the lit ground beside.
    const double f = (ground_fog - fc) / (ground - fc);
    REQUIRE(f > 0.3);
    REQUIRE(f < 0.9);
    CHECK(std::abs(shade_fog - (f * shade + (1 - f) * fc)) <= 3);
    CHECK(shade_fog < lit_fog - 10);
  }
}

namespace {

/// A 32 x 32 white texture with a red 8 x 8 marker in its top-left corner, as PNG and as a
/// bottom-up 24-bit BMP (the usual layout), in a fresh folder.
std::string markerTextures() {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("simbob_marker_textures_" + std::to_string(getpid()))).string();
  std::filesystem::create_directories(dir);
  Image img(32, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      uint8_t* p = img.pixel(x, y);
      const bool marker = x < 8 && y < 8;
      p[0] = 255;
      p[1] = p[2] = marker ? 0 : 255;
    }
  REQUIRE(writePng(dir + "/marker.png", img).message.empty());
  std::vector<uint8_t> b(54 + 32 * 32 * 3, 0);
  auto le32 = [&](size_t at, uint32_t v) {
    for (int k = 0; k < 4; ++k) b[at + k] = static_cast<uint8_t>(v >> (8 * k));
  };
  b[0] = 'B';
  b[1] = 'M';
  le32(2, static_cast<uint32_t>(b.size()));
  le32(10, 54);
  le32(14, 40);
  le32(18, 32);
  le32(22, 32);  // positive height: bottom row first
  b[26] = 1;
  b[28] = 24;
  for (int row = 0; row < 32; ++row)
    for (int x = 0; x < 32; ++x) {
      const uint8_t* p = img.pixel(x, 31 - row);
      uint8_t* q = b.data() + 54 + (static_cast<size_t>(row) * 32 + x) * 3;
      q[0] = p[2];
      q[1] = p[1];
      q[2] = p[0];
    }
  std::FILE* f = std::fopen((dir + "/marker.bmp").c_str(), "wb");
  REQUIRE(f);
  REQUIRE(std::fwrite(b.data(), 1, b.size(), f) == b.size());
  std::fclose(f);
  return dir;
}

/// Where the red marker is on the textured (non-black) part of the image: "top-left",
/// "top-right", "bottom-left" or "bottom-right" of that part's bounding box; "none" if no marker.
std::string markerCorner(const Image& img) {
  int x0 = img.width, x1 = -1, y0 = img.height, y1 = -1;
  double mx = 0, my = 0;
  int red = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const uint8_t* p = img.pixel(x, y);
      if (p[0] < 40) continue;  // background
      x0 = std::min(x0, x);
      x1 = std::max(x1, x);
      y0 = std::min(y0, y);
      y1 = std::max(y1, y);
      if (p[0] > 100 && p[1] < 60 && p[2] < 60) {
        mx += x;
        my += y;
        ++red;
      }
    }
  if (red < 20) return "none";
  mx /= red;
  my /= red;
  return std::string(my < (y0 + y1) / 2.0 ? "top" : "bottom") + (mx < (x0 + x1) / 2.0 ? "-left" : "-right");
}

Image drawTextured(const Model& m, const std::string& camera, const std::string& folder) {
  RenderOptions o;
  o.width = 160;
  o.height = 120;
  o.backend = backend();
  o.camera = camera;
  o.quality = Quality::Textures;
  o.texture_folder = folder;
  Error err;
  std::unique_ptr<Renderer> r = Renderer::create(m, o, &err);
  INFO(err.message);
  REQUIRE(r);
  Image img;
  REQUIRE(r->render(initialPoses(m), 0, &img) == nullptr);
  if (const char* dir = std::getenv("SIMBOB_DEBUG_FRAMES")) writePng(std::string(dir) + "/" + camera + ".png", img);
  return img;
}

CameraDef cameraAt(const std::string& key, const Vec3& p, const Quat& q) {
  CameraDef c;
  c.key = key;
  c.pose = Transform{p, q};
  return c;
}

}  // namespace

TEST_CASE("textures: an image's top-left corner shows top-left on every cuboid face seen from outside, PNG and BMP") {
  const std::string folder = markerTextures();
  for (const std::string file : {"marker.png", "marker.bmp"}) {
    INFO(file);
    const std::string skin =
        R"(<RCTexturedSkin Key="Marker"><Texture Value=")" + file + R"("/><ColorMode Value="Color"/></RCTexturedSkin>)";
    Model cube =
        compileText(R"(<Simulation><SceneSettings><ClearColor Value="0 0 0"/></SceneSettings><ComponentList>)" + skin +
                    R"(<RCStaticRigidBody Key="Cube">
      <Model><RCCuboidModel><Skin Ref="Marker"/><TexScale Value="-1"/></RCCuboidModel></Model></RCStaticRigidBody>
      </ComponentList></Simulation>)");
    // Each camera 3 m out on an axis looking at the cube: the four sides with +Y up, the top
    // from above with -Z up, the bottom from below with +Z up.
    cube.cameras = {cameraAt("PlusZ", {0, 0, 3}, {1, 0, 0, 0}),
                    cameraAt("PlusX", {3, 0, 0}, quatAxisAngle({0, 1, 0}, kPi / 2)),
                    cameraAt("MinusZ", {0, 0, -3}, quatAxisAngle({0, 1, 0}, kPi)),
                    cameraAt("MinusX", {-3, 0, 0}, quatAxisAngle({0, 1, 0}, -kPi / 2)),
                    cameraAt("PlusY", {0, 3, 0}, quatAxisAngle({1, 0, 0}, -kPi / 2)),
                    cameraAt("MinusY", {0, -3, 0}, quatAxisAngle({1, 0, 0}, kPi / 2))};
    for (const CameraDef& c : cube.cameras) {
      INFO("cube face seen by " << c.key);
      CHECK(markerCorner(drawTextured(cube, c.key, folder)) == "top-left");
    }
  }
}

TEST_CASE("textures: a plane model, the ground and the sky show the image upright from their front side") {
  const std::string folder = markerTextures();
  for (const std::string file : {"marker.png", "marker.bmp"}) {
    INFO(file);
    const std::string head = R"(<Simulation><SceneSettings><ClearColor Value="0 0 0"/></SceneSettings><ComponentList>
      <RCTexturedSkin Key="Marker"><Texture Value=")" +
                             file + R"("/><ColorMode Value="Color"/></RCTexturedSkin>)";
    const std::string tail = "</ComponentList></Simulation>";
    // A plane model: local X right, local Y up, seen from its +Z side.
    Model plane = compileText(head + R"(<RCStaticRigidBody Key="Board"><Model><RCPlaneModel><Skin Ref="Marker"/>
      <ExtensionX Value="1"/><ExtensionY Value="1"/><TexScale Value="-1"/></RCPlaneModel></Model></RCStaticRigidBody>)" +
                              tail);
    plane.cameras = {cameraAt("Front", {0, 0, 3}, {1, 0, 0, 0})};
    CHECK(markerCorner(drawTextured(plane, "Front", folder)) == "top-left");
    // The ground seen from above with -Z (away from the default view) up, like a cuboid's top.
    Model ground = compileText(
        head + R"(<RCGround Key="Ground"><Skin Ref="Marker"/><Extension Value="1"/><TexScale Value="-1"/></RCGround>)" +
        tail);
    ground.cameras = {cameraAt("Above", {0, 3, 0}, quatAxisAngle({1, 0, 0}, -kPi / 2))};
    CHECK(markerCorner(drawTextured(ground, "Above", folder)) == "top-left");
    // The sky seen from below with +Z up, like a cuboid's bottom.
    Model sky = compileText(
        head +
        R"(<RCSky Key="Sky"><Skin Ref="Marker"/><Height Value="4"/><Extension Value="1"/><TexScale Value="-1"/></RCSky>)" +
        tail);
    sky.cameras = {cameraAt("Below", {0, 1, 0}, quatAxisAngle({1, 0, 0}, kPi / 2))};
    CHECK(markerCorner(drawTextured(sky, "Below", folder)) == "top-left");
  }
}

TEST_CASE("the default quality draws transparent skins: a glass panel does not hide the ball behind it") {
  // A red ball 5 m ahead behind a see-through white panel (alpha 0.3) 3 m ahead, on black.
  const Model m = compileText(R"(<Simulation>
  <CameraList><RCStaticCamera Key="C"><ViewAngle Value="60"/></RCStaticCamera></CameraList>
  <SceneSettings><ClearColor Value="0 0 0"/></SceneSettings>
  <ComponentList>
    <RCColoredSkin Key="Red"><Color Value="1 0 0"/><ColorMode Value="Color"/></RCColoredSkin>
    <RCColoredSkin Key="Glass"><Color Value="1 1 1 0.3"/><ColorMode Value="TransparentColor"/></RCColoredSkin>
    <RCStaticRigidBody Key="Ball"><Pose><RCGlobalCoordinates><Pose Value="0 0 -5 0 0 0"/></RCGlobalCoordinates></Pose>
      <Model><RCEllipsoidModel><Skin Ref="Red"/></RCEllipsoidModel></Model></RCStaticRigidBody>
    <RCStaticRigidBody Key="Panel"><Pose><RCGlobalCoordinates><Pose Value="0 0 -3 0 0 0"/></RCGlobalCoordinates></Pose>
      <Model><RCPlaneModel><Skin Ref="Glass"/><ExtensionX Value="4"/><ExtensionY Value="4"/></RCPlaneModel></Model>
    </RCStaticRigidBody>
  </ComponentList>
</Simulation>)");
  RenderOptions o;  // the default quality, as `render` and `run --record` use without --quality
  o.width = 120;
  o.height = 90;
  o.backend = backend();
  Error err;
  std::unique_ptr<Renderer> r = Renderer::create(m, o, &err);
  INFO(err.message);
  REQUIRE(r);
  Image img;
  REQUIRE(r->render(initialPoses(m), 0, &img) == nullptr);
  // The centre: 0.3 of the panel's white over 0.7 of the ball's red; beside the ball: 0.3 of
  // the white over the black background.
  const uint8_t* centre = img.pixel(60, 45);
  INFO("centre " << int(centre[0]) << " " << int(centre[1]) << " " << int(centre[2]));
  CHECK(std::abs(centre[0] - 255) <= 3);
  CHECK(std::abs(centre[1] - 77) <= 3);
  const uint8_t* beside = img.pixel(5, 45);
  CHECK(std::abs(beside[0] - 77) <= 3);
  CHECK(std::abs(beside[2] - 77) <= 3);
}

TEST_CASE("collision shapes: drawn when asked, and the default view frames the bodies where they are drawn") {
  const Model pendulum = compileFile("scenes/pendulum.xml");  // a sphere geom, no models
  CHECK(modelsShowNoBody(pendulum));
  CHECK_FALSE(modelsShowNoBody(compileFile("tests/data/render/basic.xml")));
  RenderOptions o;
  o.width = 120;
  o.height = 90;
  o.backend = backend();
  const uint8_t bg[3] = {77, 77, 128};  // the default ClearColor 0.3 0.3 0.5
  auto offBackground = [&](const Image& img, int x, int y) {
    const uint8_t* p = img.pixel(x, y);
    return std::abs(p[0] - bg[0]) > 8 || std::abs(p[1] - bg[1]) > 8 || std::abs(p[2] - bg[2]) > 8;
  };
  std::vector<Transform> moved = initialPoses(pendulum);
  moved[0].p = add(moved[0].p, Vec3{3, -2, 1});
  o.draw_chosen = true;  // exactly what is asked (--draw): models alone show nothing here
  for (bool geoms : {false, true}) {
    o.draw_geoms = geoms;
    o.draw_models = !geoms;
    Error err;
    std::unique_ptr<Renderer> r = Renderer::create(pendulum, o, &err);
    REQUIRE(r);
    Image at_start, at_moved;
    REQUIRE(r->render(initialPoses(pendulum), 0, &at_start) == nullptr);
    // A fresh renderer for the moved pose: a still frames the bodies of its own instant.
    std::unique_ptr<Renderer> r2 = Renderer::create(pendulum, o, &err);
    REQUIRE(r2);
    REQUIRE(r2->render(moved, 1, &at_moved) == nullptr);
    INFO("collision shapes drawn: " << geoms);
    CHECK(offBackground(at_start, 60, 45) == geoms);
    CHECK(offBackground(at_moved, 60, 45) == geoms);
  }
  // Not chosen: a renderer whose models show no body draws the collision shapes instead (the
  // one place that decides it, for render, recordings, camera sensors and Python alike).
  RenderOptions unchosen = o;
  unchosen.draw_chosen = false;
  unchosen.draw_models = true;
  unchosen.draw_geoms = false;
  CHECK(drawFallbackNote(pendulum, unchosen) ==
        "no body has a model: drawing the collision shapes (--draw geoms; --draw models for the models alone)");
  CHECK(drawFallbackNote(pendulum, o).empty());
  Error err;
  std::unique_ptr<Renderer> r = Renderer::create(pendulum, unchosen, &err);
  REQUIRE(r);
  Image fallback;
  REQUIRE(r->render(initialPoses(pendulum), 0, &fallback) == nullptr);
  CHECK(offBackground(fallback, 60, 45));
}

TEST_CASE("meshes: scenes/mesh_drop.xml matches its reference; mesh models and mesh collision shapes are drawn") {
  // The ramp (a static triangle mesh), the cube (STL), the crate (COLLADA, turned Z-up to Y-up)
  // and the pyramid (OBJ), drawn from their display lists with one normal per face.
  const Model m = compileFile("scenes/mesh_drop.xml");
  REQUIRE(m.meshes.size() == 4);
  const Image img = draw(m, 320, 240);
  checkReference(img, "mesh_drop");
  // Without its mesh models the picture loses them (the comparison can fail).
  Model bare = m;
  bare.visuals.erase(std::remove_if(bare.visuals.begin(), bare.visuals.end(),
                                    [](const VisualDef& v) { return v.shape == VisualDef::Mesh; }),
                     bare.visuals.end());
  CHECK_FALSE(imagesMatch(img, draw(bare, 320, 240)));
  // The collision shapes alone (hulls and the ramp's triangles) look like the models: the
  // meshes are their own hulls but for the ramp's, drawn in the collision shapes' colours.
  RenderOptions o;
  o.width = 320;
  o.height = 240;
  o.backend = backend();
  o.draw_models = false;
  o.draw_geoms = true;
  Error err;
  std::unique_ptr<Renderer> r = Renderer::create(m, o, &err);
  INFO(err.message);
  REQUIRE(r);
  Image shapes;
  REQUIRE(r->render(initialPoses(m), 0, &shapes) == nullptr);
  checkReference(shapes, "mesh_drop_geoms");
}

namespace {

// The poses of golden/NAME.csv's sample at time t, by body key; bodies without a row keep their
// initial pose.
std::vector<Transform> goldenPoses(const Model& m, const std::string& name, double t) {
  Trajectory traj;
  Error err;
  INFO(err.message);
  REQUIRE(readTrajectory(std::string(SIMBOB_SOURCE_DIR) + "/golden/" + name + ".csv", &traj, &err));
  size_t s = 0;
  while (s + 1 < traj.sampleCount() && traj.times[s] < t) ++s;
  REQUIRE(traj.times[s] == Approx(t));
  std::vector<Transform> poses = initialPoses(m);
  int found = 0;
  for (size_t b = 0; b < traj.bodyCount(); ++b) {
    const double* p = traj.pose(s, b);
    for (size_t i = 0; p && i < m.bodies.size(); ++i)
      if (m.bodies[i].key == traj.bodies[b]) {
        poses[i].p = {p[0], p[1], p[2]};
        poses[i].q = {p[3], p[4], p[5], p[6]};
        ++found;
      }
  }
  CHECK(found == static_cast<int>(m.bodies.size()));
  return poses;
}

Image drawPoses(const Model& m, const std::vector<Transform>& poses, int w, int h) {
  RenderOptions o;
  o.width = w;
  o.height = h;
  o.backend = backend();
  Error err;
  std::unique_ptr<Renderer> r = Renderer::create(m, o, &err);
  INFO(err.message);
  REQUIRE(r);
  Image img;
  REQUIRE(r->render(poses, 0, &img) == nullptr);
  return img;
}

}  // namespace

TEST_CASE("urdf: scenes/kr5.xml and scenes/drchubo.xml match their references, at the start and at 10 s") {
  // Debian's dart-doc robots with their meshes (scripts/deps.sh test installs it): the KR5 arm
  // standing at its start pose and at the end of its golden run (three joints turned at 5 s),
  // DRC-Hubo in the air at the start and collapsed on the ground at 10 s (golden/drchubo.csv).
  for (const char* name : {"kr5", "drchubo"}) {
    CAPTURE(name);
    const Model m = compileFile(std::string("scenes/") + name + ".xml");
    const Image start = drawPoses(m, initialPoses(m), 320, 240);
    const Image end = drawPoses(m, goldenPoses(m, name, 10.0), 320, 240);
    checkReference(start, std::string(name) + "_start");
    checkReference(end, std::string(name) + "_10s");
    CHECK_FALSE(imagesMatch(start, end));  // the robot moved, and the comparison sees it
  }
}
