#include "simbob/tool/replay_page.h"
#include "simbob/mesh.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace {

using simbob::Trajectory;

std::vector<uint8_t> unbase64(const std::string& s) {
  std::vector<uint8_t> out;
  uint32_t acc = 0;
  int bits = 0;
  for (char c : s) {
    int v = c >= 'A' && c <= 'Z'   ? c - 'A'
            : c >= 'a' && c <= 'z' ? c - 'a' + 26
            : c >= '0' && c <= '9' ? c - '0' + 52
            : c == '+'             ? 62
            : c == '/'             ? 63
                                   : -1;
    if (v < 0) break;
    acc = (acc << 6) | static_cast<uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<uint8_t>(acc >> bits));
    }
  }
  return out;
}

std::vector<float> floats(const std::string& b64) {
  const std::vector<uint8_t> bytes = unbase64(b64);
  std::vector<float> v(bytes.size() / 4);
  std::memcpy(v.data(), bytes.data(), v.size() * 4);
  return v;
}

/// The page's data block, parsed.
nlohmann::json pageData(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"simbob-data\">";
  const size_t a = html.find(open) + open.size();
  const size_t b = html.find("</script>", a);
  return nlohmann::json::parse(html.substr(a, b - a));
}

}  // namespace

TEST_CASE("view page: poses as float32, far bodies relative to an origin of their own") {
  Trajectory t;
  t.addBody("Near");
  t.addBody("Far</script><b>");  // a key that would end the data block if written as it is
  const double near[7] = {1.2345678901, -0.5, 3.25, 1, 0, 0, 0};
  for (int s = 0; s < 3; ++s) {
    t.times.push_back(0.1 * s);
    t.finalize();
    const double far[7] = {50000.123456 + s * 0.0001, 2, -7000.5, 0.5, 0.5, 0.5, 0.5};
    t.setPose(static_cast<size_t>(s), 0, near);
    t.setPose(static_cast<size_t>(s), 1, far);
  }
  simbob::Model model;
  simbob::ViewPageInput in;
  in.model = &model;
  in.actual = &t;
  std::string html;
  simbob::Error err;
  REQUIRE(simbob::buildViewPage(in, &html, &err));
  // Only the page's own script ends: the data, three.js with OrbitControls, the viewer.
  size_t ends = 0;
  for (size_t at = html.find("</script"); at != std::string::npos; at = html.find("</script", at + 1)) ++ends;
  CHECK(ends == 3);
  const nlohmann::json d = pageData(html);
  const nlohmann::json& a = d["actual"];
  REQUIRE(a["bodies"][1] == "Far</script><b>");
  const std::vector<float> poses = floats(a["poses"]);
  REQUIRE(poses.size() == 2 * 3 * 7);
  // Near the world origin: the CSV's values as float32, origin 0.
  CHECK(a["origins"][0] == nlohmann::json::array({0, 0, 0}));
  for (int k = 0; k < 7; ++k) CHECK(poses[static_cast<size_t>(k)] == static_cast<float>(near[k]));
  // 50 km out: float32 alone would be off by up to 2 mm; with the origin, within 0.1 mm.
  const double ox = a["origins"][1][0], oz = a["origins"][1][2];
  CHECK(ox != 0);
  CHECK(oz != 0);
  CHECK(a["origins"][1][1] == 0);
  for (int s = 0; s < 3; ++s) {
    const float* p = &poses[static_cast<size_t>((3 + s) * 7)];
    CHECK(std::fabs(ox + p[0] - (50000.123456 + s * 0.0001)) < 1e-4);
    CHECK(std::fabs(oz + p[2] - -7000.5) < 1e-4);
    CHECK(p[3] == 0.5F);
  }
  CHECK(std::fabs(static_cast<double>(static_cast<float>(50000.123456)) - 50000.123456) > 1e-4);  // why it is needed
}

TEST_CASE("view page: a missing row is NaN, times are float64") {
  Trajectory t;
  t.addBody("A");
  t.addBody("B");
  const double p[7] = {0, 0, 0, 1, 0, 0, 0};
  t.times = {0, 0.1 + 1e-12};
  t.finalize();
  t.setPose(0, 0, p);
  t.setPose(1, 0, p);
  t.setPose(1, 1, p);  // B has no row at t = 0
  simbob::Model model;
  simbob::ViewPageInput in;
  in.model = &model;
  in.actual = &t;
  std::string html;
  simbob::Error err;
  REQUIRE(simbob::buildViewPage(in, &html, &err));
  const nlohmann::json d = pageData(html);
  const std::vector<float> poses = floats(d["actual"]["poses"]);
  CHECK(std::isnan(poses[2 * 7]));  // B, sample 0
  CHECK(poses[3 * 7 + 3] == 1.0F);  // B, sample 1
  const std::vector<uint8_t> tb = unbase64(d["actual"]["times"]);
  REQUIRE(tb.size() == 16);
  double t1 = 0;
  std::memcpy(&t1, tb.data() + 8, 8);
  CHECK(t1 == 0.1 + 1e-12);
}

// Issue 31, item 1: the gallery's links are relative paths no browser reads as a scheme, a query,
// a fragment or an escape.
TEST_CASE("sweepGalleryHtml: each case's link is './' and percent-encoded segments") {
  simbob::GalleryCase c{0, "ok", {"0"}, "javascript:self.x=1;void 0//#?%/case-0000/view.html"};
  simbob::GalleryCase none{1, "failed", {"1"}, ""};
  const std::string html = simbob::sweepGalleryHtml("t", {"case"}, {c, none});
  CHECK(html.find(R"("page":"./javascript%3Aself.x%3D1%3Bvoid%200//%23%3F%25/case-0000/view.html")") !=
        std::string::npos);
  CHECK(html.find(R"("page":"")") != std::string::npos);  // no page, no link
  CHECK(html.find("javascript:") == std::string::npos);
}

TEST_CASE("view page: each mesh is embedded once, float32 positions and uint32 indices; no key without meshes") {
  // Two visuals and a hull geom of one mesh: its triangles once, its hull once.
  auto mesh = std::make_shared<simbob::MeshData>();
  mesh->file = "/some/dir/tet ra.stl";
  mesh->vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1.5}};
  mesh->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::string problem;
  REQUIRE(simbob::convexHull(mesh->vertices, &mesh->hull, &problem));
  simbob::Model model;
  model.skins.emplace_back();
  model.meshes.push_back({mesh, {}});
  for (int k = 0; k < 2; ++k) {
    simbob::VisualDef v;
    v.shape = simbob::VisualDef::Mesh;
    v.mesh = 0;
    model.visuals.push_back(v);
  }
  simbob::GeomDef g;
  g.shape = simbob::GeomShape::ConvexHull;
  g.mesh = 0;
  model.geoms.push_back(g);
  Trajectory t;
  t.addBody("A");
  t.times = {0};
  t.finalize();
  const double p[7] = {0, 0, 0, 1, 0, 0, 0};
  t.setPose(0, 0, p);
  simbob::ViewPageInput in;
  in.model = &model;
  in.actual = &t;
  std::string html;
  simbob::Error err;
  REQUIRE(simbob::buildViewPage(in, &html, &err));
  const nlohmann::json d = pageData(html);
  REQUIRE(d["model"]["meshes"].size() == 1);
  const nlohmann::json& m = d["model"]["meshes"][0];
  CHECK(m["file"] == "tet ra.stl");
  const std::vector<float> pos = floats(m["triangles"]["positions"]);
  REQUIRE(pos.size() == 12);
  CHECK(pos[11] == 1.5F);
  const std::vector<uint8_t> idx = unbase64(m["triangles"]["indices"]);
  REQUIRE(idx.size() == 12 * 4);
  uint32_t last = 0;
  std::memcpy(&last, idx.data() + 11 * 4, 4);
  CHECK(last == 3);
  CHECK(floats(m["hull"]["positions"]).size() == 12);      // 4 hull points
  CHECK(unbase64(m["hull"]["indices"]).size() == 4 * 12);  // 4 triangular faces
  CHECK(d["model"]["visuals"][1]["mesh"] == 0);
  CHECK(d["model"]["geoms"][0]["shape"] == "hull");
  // A model without meshes writes no "meshes" key: its pages stay byte for byte as before.
  simbob::Model plain;
  plain.skins.emplace_back();
  in.model = &plain;
  REQUIRE(simbob::buildViewPage(in, &html, &err));
  CHECK_FALSE(pageData(html)["model"].contains("meshes"));
}

TEST_CASE(
    "view page: check warns at the mesh that takes the page's mesh data past its limit, and the page refuses it") {
  // Base64 of float32 positions and uint32 indices: 16 characters a vertex and 16 a triangle. A
  // visual draws each mesh's triangles (no hull). `big` alone is exactly the limit, 64 MiB.
  auto small = std::make_shared<simbob::MeshData>();
  small->file = "small.stl";
  small->vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  small->triangles = {{0, 1, 2}};
  auto big = std::make_shared<simbob::MeshData>();
  big->file = "big.stl";
  big->vertices = small->vertices;
  big->triangles.resize(simbob::kMaxPageMeshChars / 16 - 3);  // the limit, with its 3 vertices
  auto model = [](const std::vector<std::shared_ptr<simbob::MeshData>>& meshes) {
    simbob::Model m;
    m.skins.emplace_back();
    for (const auto& mesh : meshes) {
      m.meshes.push_back({mesh, {"scene.xml", static_cast<int>(m.meshes.size()) + 10}});
      simbob::VisualDef v;
      v.shape = simbob::VisualDef::Mesh;
      v.mesh = static_cast<int>(m.meshes.size()) - 1;
      m.visuals.push_back(v);
    }
    return m;
  };
  simbob::Diagnostics d;
  simbob::checkMeshBudget(model({big}), d);
  CHECK(d.warnings().empty());  // at the limit: allowed
  CHECK(d.errors().empty());

  // The small mesh first, then the big one: 32 characters past the limit, at the big mesh.
  const simbob::Model both = model({small, big});
  simbob::checkMeshBudget(both, d);
  REQUIRE(d.warnings().size() == 1);
  CHECK(d.errors().empty());
  CHECK(d.warnings()[0].loc.line == 11);
  CHECK(d.warnings()[0].message ==
        "mesh big.stl: the scene's meshes come to 65 MiB of page data, more than the 64 MiB a replay page embeds (view "
        "and --html will refuse; docs/meshes.md)");

  Trajectory t;
  t.addBody("A");
  t.times = {0};
  t.finalize();
  const double p[7] = {0, 0, 0, 1, 0, 0, 0};
  t.setPose(0, 0, p);
  simbob::ViewPageInput in;
  in.model = &both;
  in.actual = &t;
  std::string html;
  simbob::Error err;
  REQUIRE_FALSE(simbob::buildViewPage(in, &html, &err));
  CHECK(err.kind == simbob::ErrorKind::InvalidInput);
  CHECK(err.loc.file.str() == "big.stl");
  CHECK(err.message ==
        "the scene's meshes would put more than 64 MiB into the replay page (the limit; docs/meshes.md): use coarser "
        "meshes for the page");
}
