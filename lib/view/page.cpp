// The replay page (include/simbob/tool/replay_page.h): the Model's visuals, skins, cameras and collision
// shapes as JSON, the poses as float32 base64, three.js and the viewer (lib/view/viewer.js,
// lib/view/page.html, embedded at build time) in one HTML file.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <utility>
#include <vector>
#include <algorithm>
#include <nlohmann/json.hpp>

#include "image/texture_file.h"
#include "simbob/tool/files.h"
#include "simbob/tool/png.h"
#include "simbob/tool/replay_page.h"
#include "simbob/values.h"
#include "view/assets.h"

namespace simbob {

namespace {

using nlohmann::json;

/// Positions beyond this (m) lose more than 0.1 mm as float32 (half an ulp at 2048 m is 0.12 mm):
/// a body that goes that far is stored relative to an origin of its own.
constexpr double kFloat32Reach = 1000;

std::string base64(const void* data, size_t size) {
  static const char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* b = static_cast<const uint8_t*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < size; i += 3) {
    const uint32_t v = (uint32_t{b[i]} << 16) | (uint32_t{b[i + 1]} << 8) | b[i + 2];
    for (int k = 18; k >= 0; k -= 6) out += kDigits[(v >> k) & 63];
  }
  if (i < size) {
    const uint32_t v = (uint32_t{b[i]} << 16) | (i + 1 < size ? uint32_t{b[i + 1]} << 8 : 0);
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < size ? kDigits[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

/// Little-endian bytes of floats (x86 and ARM are little-endian; a big-endian host swaps).
template <typename T>
std::string base64Le(const std::vector<T>& v) {
  std::vector<uint8_t> bytes(v.size() * sizeof(T));
  for (size_t i = 0; i < v.size(); ++i) {
    uint8_t raw[sizeof(T)];
    std::memcpy(raw, &v[i], sizeof(T));
    const uint16_t probe = 1;
    const bool little = *reinterpret_cast<const uint8_t*>(&probe) == 1;
    for (size_t k = 0; k < sizeof(T); ++k) bytes[i * sizeof(T) + k] = raw[little ? k : sizeof(T) - 1 - k];
  }
  return base64(bytes.data(), bytes.size());
}

json vec(const double* v, size_t n) {
  json a = json::array();
  for (size_t i = 0; i < n; ++i) a.push_back(v[i]);
  return a;
}
json pose(const Transform& t) { return {{"p", vec(t.p.data(), 3)}, {"q", vec(t.q.data(), 4)}}; }

/// A trajectory's poses: {bodies, times (float64 base64), origins, poses (float32 base64,
/// [body][sample][x y z qw qx qy qz] with NaN where a row is missing)}.
json encodeTrajectory(const Trajectory& t) {
  json out;
  out["bodies"] = t.bodies;
  out["times"] = base64Le(t.times);
  std::vector<float> poses(t.bodyCount() * t.sampleCount() * kPoseSize, std::nanf(""));
  json origins = json::array();
  for (size_t b = 0; b < t.bodyCount(); ++b) {
    double reach[3] = {0, 0, 0}, lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    bool any = false;
    for (size_t s = 0; s < t.sampleCount(); ++s) {
      const double* p = t.pose(s, b);
      if (!p) continue;
      for (int k = 0; k < 3; ++k) {
        lo[k] = any ? std::min(lo[k], p[k]) : p[k];
        hi[k] = any ? std::max(hi[k], p[k]) : p[k];
        reach[k] = std::max(reach[k], std::fabs(p[k]));
      }
      any = true;
    }
    // Origin 0 keeps the stored values the CSV's rounded to float32; a far body is stored
    // relative to the middle of its range, rounded to a metre.
    double origin[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      if (reach[k] > kFloat32Reach) origin[k] = std::round((lo[k] + hi[k]) / 2);
    origins.push_back(vec(origin, 3));
    for (size_t s = 0; s < t.sampleCount(); ++s) {
      const double* p = t.pose(s, b);
      if (!p) continue;
      float* o = &poses[(b * t.sampleCount() + s) * kPoseSize];
      for (size_t k = 0; k < kPoseSize; ++k) o[k] = static_cast<float>(k < 3 ? p[k] - origin[k] : p[k]);
    }
  }
  out["origins"] = origins;
  out["poses"] = base64Le(poses);
  return out;
}

/// The golden comparison: compareTrajectories' verdict and first divergence, and per body in
/// both the position and rotation error at each golden sample time shared with the run.
json encodeComparison(const Trajectory& actual, const Trajectory& golden, const CompareOptions& opts) {
  const CompareResult r = compareTrajectories(actual, golden, opts);
  json out;
  out["pass"] = r.pass;
  out["tol_pos"] = opts.tol_pos;
  out["tol_rot"] = opts.tol_rot;
  if (r.first_divergence) {
    const Divergence& d = *r.first_divergence;
    out["divergence"] = {{"time", d.time}, {"body", d.body}, {"pos_err", d.pos_err}, {"rot_err", d.rot_err}};
  } else {
    out["divergence"] = nullptr;
  }
  // Sample pairs (golden s, actual s) with the same time, as compareTrajectories matches them.
  std::vector<std::pair<size_t, size_t>> shared;
  for (size_t g = 0, a = 0; g < golden.sampleCount() && a < actual.sampleCount();) {
    const double tg = golden.times[g], ta = actual.times[a];
    if (std::fabs(tg - ta) <= opts.time_eps) {
      shared.push_back({g, a});
      ++g, ++a;
    } else if (tg < ta) {
      ++g;
    } else {
      ++a;
    }
  }
  std::vector<double> times;
  times.reserve(shared.size());
  for (const auto& s : shared) times.push_back(golden.times[s.first]);
  out["times"] = base64Le(times);
  json errors = json::object();
  for (const BodyDiff& d : r.bodies) {
    size_t ab = 0, gb = 0;
    while (actual.bodies[ab] != d.body) ++ab;
    while (golden.bodies[gb] != d.body) ++gb;
    std::vector<float> pos, rot;
    pos.reserve(shared.size());
    rot.reserve(shared.size());
    for (const auto& s : shared) {
      const double* pa = actual.pose(s.second, ab);
      const double* pg = golden.pose(s.first, gb);
      pos.push_back(pa && pg ? static_cast<float>(positionError(pa, pg)) : std::nanf(""));
      rot.push_back(pa && pg ? static_cast<float>(rotationError(pa + 3, pg + 3)) : std::nanf(""));
    }
    errors[d.body] = {{"pos", base64Le(pos)}, {"rot", base64Le(rot)}};
  }
  out["errors"] = errors;
  return out;
}

/// The page's textures: each file once, decoded as the renderer decodes it (trailing bytes never
/// read), re-encoded as PNG, within kMaxPageTextureBytes; a skin refers to its file by index.
class PageTextures {
 public:
  explicit PageTextures(const std::string& texture_folder) : folder_(texture_folder) {}
  /// The index of skin s's texture in urls(); false with *err when it is missing or unreadable.
  bool add(const SkinDef& s, size_t* index, Error* err) {
    std::string where;
    const std::string path = findTextureFile(s, folder_, &where);
    if (path.empty()) {
      *err = {ErrorKind::MissingInput, {}, "texture '" + s.texture + "' of skin '" + s.key + "' not found in " + where};
      return false;
    }
    Image image;
    bool fresh = false;
    if (!files_.load(path, index, &image, &fresh, err)) return false;
    if (!fresh) return true;
    std::string png, why;
    if (!encodePng(image, &png, &why)) {
      *err = {ErrorKind::Internal, {path, 0}, "cannot encode the texture as PNG: " + why};
      return false;
    }
    urls_.push_back("data:image/png;base64," + base64(png.data(), png.size()));
    return true;
  }
  const std::vector<std::string>& urls() const { return urls_; }

 private:
  std::string folder_;
  TextureFiles files_{kMaxPageTextureBytes};
  std::vector<std::string> urls_;  ///< by slot: TextureFiles counts distinct files from 0
};

/// What a page embeds of each mesh of the Model: 1 its triangles (a visual or a TriMesh geom
/// draws them), 2 its hull (a ConvexHull geom draws it), 3 both, 0 nothing.
std::vector<uint8_t> pageMeshParts(const Model& m) {
  std::vector<uint8_t> use(m.meshes.size(), 0);
  for (const VisualDef& v : m.visuals)
    if (v.shape == VisualDef::Mesh) use[static_cast<size_t>(v.mesh)] |= 1;
  for (const GeomDef& g : m.geoms)
    if (!g.sensor && g.mesh >= 0) use[static_cast<size_t>(g.mesh)] |= g.shape == GeomShape::ConvexHull ? 2 : 1;
  return use;
}

/// The base64 characters the `parts` of mesh d take in a page, as encodeMeshes writes them:
/// float32 positions (3 a vertex) and uint32 indices (3 a triangle; a hull face of k points is
/// k - 2 triangles).
size_t pageMeshChars(const MeshData& d, uint8_t parts) {
  auto b64 = [](size_t bytes) { return (bytes + 2) / 3 * 4; };
  size_t chars = 0;
  if (parts & 1) chars += b64(d.vertices.size() * 3 * 4) + b64(d.triangles.size() * 3 * 4);
  if (parts & 2) {
    size_t triangles = 0;
    for (size_t at = 0; at < d.hull.polygons.size(); at += 1 + d.hull.polygons[at])
      if (d.hull.polygons[at] > 2) triangles += d.hull.polygons[at] - 2;
    chars += b64(d.hull.points.size() * 4) + b64(triangles * 3 * 4);
  }
  return chars;
}

/// Each mesh of the Model once: {file, triangles: {positions (float32 base64, x y z per vertex),
/// indices (uint32 base64, 3 per triangle)}, hull: the same for its hull's faces as triangles}.
/// The triangles go in only when a visual or a TriMesh geom draws them, the hull only when a
/// ConvexHull geom does. Past kMaxPageMeshChars it refuses, naming the mesh, before encoding it.
bool encodeMeshes(const Model& m, json* out, Error* err) {
  const std::vector<uint8_t> use = pageMeshParts(m);
  *out = json::array();
  size_t chars = 0;
  for (size_t i = 0; i < m.meshes.size(); ++i) {
    const MeshData& d = *m.meshes[i].data;
    chars += pageMeshChars(d, use[i]);
    if (chars > kMaxPageMeshChars) {
      *err = {ErrorKind::InvalidInput,
              {d.file, 0},
              "the scene's meshes would put more than " + std::to_string(kMaxPageMeshChars >> 20) +
                  " MiB into the replay page (the limit; docs/meshes.md): use coarser meshes for the page"};
      return false;
    }
    const size_t slash = d.file.find_last_of('/');
    json j = {{"file", slash == std::string::npos ? d.file : d.file.substr(slash + 1)}};
    auto put = [&](const char* name, const std::vector<float>& pos, const std::vector<uint32_t>& idx) {
      j[name] = {{"positions", base64Le(pos)}, {"indices", base64Le(idx)}};
    };
    if (use[i] & 1) {
      std::vector<float> pos;
      pos.reserve(d.vertices.size() * 3);
      for (const Vec3& v : d.vertices)
        for (double x : v) pos.push_back(static_cast<float>(x));
      std::vector<uint32_t> idx;
      idx.reserve(d.triangles.size() * 3);
      for (const auto& t : d.triangles) idx.insert(idx.end(), t.begin(), t.end());
      put("triangles", pos, idx);
    }
    if (use[i] & 2) {
      std::vector<float> pos(d.hull.points.begin(), d.hull.points.end());
      std::vector<uint32_t> idx;
      for (size_t at = 0; at < d.hull.polygons.size(); at += 1 + d.hull.polygons[at])
        for (unsigned k = 2; k < d.hull.polygons[at]; ++k)
          idx.insert(idx.end(), {d.hull.polygons[at + 1], d.hull.polygons[at + k], d.hull.polygons[at + k + 1]});
      put("hull", pos, idx);
    }
    out->push_back(std::move(j));
  }
  return true;
}

bool encodeModel(const Model& m, const std::string& texture_folder, json* out, Error* err) {
  json skins = json::array();
  PageTextures textures(texture_folder);
  for (const SkinDef& s : m.skins) {
    static const char* const kModes[] = {"color", "shading", "transparent_color", "transparent_lighting"};
    json j = {{"key", s.key},
              {"color", vec(s.color.data(), 4)},
              {"ambient", vec(s.ambient.data(), 4)},
              {"diffuse", vec(s.diffuse.data(), 4)},
              {"specular", vec(s.specular.data(), 4)},
              {"emission", vec(s.emission.data(), 4)},
              {"shininess", s.shininess},
              {"mode", kModes[s.mode]},
              {"colored", s.colored}};
    if (!s.texture.empty()) {
      size_t index = 0;
      if (!textures.add(s, &index, err)) return false;
      j["texture"] = index;
    }
    skins.push_back(j);
  }
  json visuals = json::array();
  for (const VisualDef& v : m.visuals) {
    static const char* const kShapes[] = {"cuboid", "plane", "ellipsoid", "cylinder", "cone", "mesh"};
    visuals.push_back({{"shape", kShapes[v.shape]},
                       {"body", v.body},
                       {"pose", pose(v.pose)},
                       {"a", vec(v.a.data(), 3)},
                       {"b", vec(v.b.data(), 3)},
                       {"size", vec(v.size.data(), 3)},
                       {"skin", v.skin},
                       {"mask", v.mask},
                       {"wire", v.wire},
                       {"one_sided", v.one_sided},
                       {"tex_scale", v.tex_scale},
                       {"tex_scale2", v.tex_scale2},
                       {"key", v.key}});
    if (v.shape == VisualDef::Mesh) visuals.back()["mesh"] = v.mesh;
  }
  json geoms = json::array();
  for (const GeomDef& g : m.geoms) {
    if (g.sensor) continue;  // detects contacts only; the renderer leaves them out too
    static const char* const kGeoms[] = {"box", "sphere", "cylinder", "capsule", "plane", "hull", "trimesh"};
    geoms.push_back({{"shape", kGeoms[static_cast<int>(g.shape)]},
                     {"body", g.body},
                     {"pose", pose(g.offset)},
                     {"size", vec(g.size.data(), 3)},
                     {"plane", vec(g.plane.data(), 4)}});
    if (g.mesh >= 0) geoms.back()["mesh"] = g.mesh;
  }
  json cameras = json::array();
  for (const CameraDef& c : m.cameras) {
    static const char* const kKinds[] = {"static", "mounted", "spotlight", "tracking"};
    cameras.push_back({{"key", c.key},
                       {"kind", kKinds[c.kind]},
                       {"pose", pose(c.pose)},
                       {"body", c.body},
                       {"target", vec(c.target.data(), 3)},
                       {"view_angle", c.view_angle},
                       {"near", c.near_clip},
                       {"far", c.far_clip},
                       {"auto_view_angle", c.auto_view_angle},
                       {"distance", c.distance}});
  }
  json meshes;
  if (!encodeMeshes(m, &meshes, err)) return false;
  json bodies = json::array();
  for (const BodyDef& b : m.bodies) bodies.push_back({{"key", b.key}, {"pose", pose(b.pose)}});
  static const char* const kFog[] = {"off", "linear", "exponential", "exponential2"};
  const ViewSettings& v = m.view;
  *out = {{"bodies", bodies},
          {"textures", textures.urls()},
          {"skins", skins},
          {"visuals", visuals},
          {"geoms", geoms},
          {"cameras", cameras},
          {"view",
           {{"light_pos", vec(v.light_pos.data(), 4)},
            {"light_color", vec(v.light_color.data(), 4)},
            {"clear_color", vec(v.clear_color.data(), 4)},
            {"fog", kFog[v.fog]},
            {"fog_density", v.fog_density},
            {"fog_start", v.fog_start},
            {"fog_end", v.fog_end},
            {"fog_color", vec(v.fog_color.data(), 4)}}}};
  if (!meshes.empty()) (*out)["meshes"] = std::move(meshes);  // pages without meshes stay as they were
  return true;
}

bool readThree(const std::string& rel, std::string* text, Error* err) {
  const std::string path = threeJsDir() + "/" + rel;
  std::string reason;
  if (readFile(path, size_t{64} << 20, text, &reason, true)) return true;
  *err = {ErrorKind::MissingInput, {path, 0}, "cannot read three.js: " + reason + " (install Debian's libjs-three)"};
  return false;
}

}  // namespace

void checkMeshBudget(const Model& m, Diagnostics& d) {
  const std::vector<uint8_t> use = pageMeshParts(m);
  size_t chars = 0;
  for (size_t i = 0; i < m.meshes.size(); ++i) {
    const size_t before = chars;
    chars += pageMeshChars(*m.meshes[i].data, use[i]);
    if (before <= kMaxPageMeshChars && chars > kMaxPageMeshChars)
      d.warning(m.meshes[i].loc, "mesh " + m.meshes[i].data->file + ": the scene's meshes come to " +
                                     std::to_string((chars + (1 << 20) - 1) >> 20) +
                                     " MiB of page data, more than the " + std::to_string(kMaxPageMeshChars >> 20) +
                                     " MiB a replay page embeds (view and --html will refuse; docs/meshes.md)");
  }
}

void checkTextureBudgets(const Model& m, const std::string& texture_folder, Diagnostics& d) {
  std::vector<std::string> seen;
  uint64_t total = 0;
  auto mib = [](uint64_t n) { return std::to_string((n + (1 << 20) - 1) >> 20) + " MiB"; };
  for (const SkinDef& s : m.skins) {
    std::string where;
    const std::string path = s.texture.empty() ? "" : findTextureFile(s, texture_folder, &where);
    if (path.empty()) continue;  // no texture, or none found: view and render say so
    std::error_code ec;
    std::string key = std::filesystem::weakly_canonical(path, ec).string();
    if (ec || key.empty()) key = path;
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
    seen.push_back(key);
    int w = 0, h = 0;
    Error err;
    if (!readTextureSize(path, &w, &h, &err)) continue;  // render and view give the reason
    const uint64_t bytes = uint64_t{3} * static_cast<uint64_t>(w) * static_cast<uint64_t>(h);
    const uint64_t before = total;
    total += bytes;
    for (const auto& [limit, who] :
         {std::pair<uint64_t, const char*>{kMaxPageTextureBytes, "a replay page embeds (view and --html will refuse)"},
          {kMaxTextureBytes, "the renderer holds (render, --record, camera sensors will refuse)"}})
      if (before <= limit && total > limit)
        d.warning(s.loc, s.type + " '" + s.key + "': its texture " + s.texture + " takes " + mib(bytes) +
                             " decoded: the scene's textures come to " + mib(total) + ", more than the " + mib(limit) +
                             " " + who);
  }
}

namespace view {

// The template with each `{{NAME}}` marker replaced by its value (markers are looked for in the
/// template only, never in the values put in).
std::string fill(const std::string& page, const std::vector<std::pair<std::string, std::string>>& values) {
  std::string out;
  size_t size = page.size();
  for (const auto& v : values) size += v.second.size();
  out.reserve(size);  // each marker once, as in simbob's templates: no copies made while it grows
  size_t at = 0;
  while (true) {
    const size_t open = page.find("{{", at);
    if (open == std::string::npos) break;
    const size_t close = page.find("}}", open);
    if (close == std::string::npos) break;
    const std::string name = page.substr(open + 2, close - open - 2);
    out.append(page, at, open - at);
    bool known = false;
    for (const auto& v : values)
      if (v.first == name) {
        out += v.second;
        known = true;
      }
    if (!known) out.append(page, open, close + 2 - open);
    at = close + 2;
  }
  out.append(page, at, std::string::npos);
  return out;
}

// Script text must not contain "</script" (nor "<!--"): JSON escapes '<' as \u003c.
std::string scriptSafe(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

}  // namespace view

std::string threeJsDir() {
  const char* env = std::getenv("SIMBOB_THREE_DIR");
  return env && *env ? env : "/usr/share/javascript/three";
}

bool buildViewPage(const ViewPageInput& in, std::string* html, Error* err) {
  if (!in.model || !in.actual) {
    *err = {ErrorKind::Internal, {}, "buildViewPage: no model or trajectory"};
    return false;
  }
  std::string three, orbit;
  if (!readThree("three.min.js", &three, err) || !readThree("examples/js/controls/OrbitControls.js", &orbit, err))
    return false;
  for (const std::string* js : {&three, &orbit})
    if (js->find("</script") != std::string::npos) {
      *err = {ErrorKind::InvalidInput, {threeJsDir(), 0}, "three.js holds '</script' and cannot be inlined"};
      return false;
    }
  json data;
  data["format"] = 1;
  data["title"] = in.title.empty() ? "simbob view" : in.title;
  data["scene"] = in.scene_name;
  if (!encodeModel(*in.model, in.texture_folder, &data["model"], err)) return false;
  data["actual"] = encodeTrajectory(*in.actual);
  if (in.golden) {
    data["golden"] = encodeTrajectory(*in.golden);
    data["compare"] = encodeComparison(*in.actual, *in.golden, in.compare);
  }
  // The embedded textures and meshes make the data most of the page: at most two copies of it
  // live at once (the data and its text, the text and the safe text, the safe text and the page).
  std::vector<std::pair<std::string, std::string>> values;
  values.emplace_back("TITLE", escapeXml(data["title"].get<std::string>()));
  values.emplace_back("THREE", three + "\n" + orbit);
  values.emplace_back("VIEWER", view::kViewerJs);
  std::string text = data.dump(-1, ' ', false, json::error_handler_t::replace);
  data = json();
  values.emplace_back("DATA", view::scriptSafe(text));
  std::string().swap(text);
  *html = view::fill(view::kPageHtml, values);
  return true;
}

bool writeViewPage(const ViewPageInput& in, const std::string& path, Error* err) {
  std::string html;
  if (!buildViewPage(in, &html, err)) return false;
  return writeFileAtomically(path, html, err);
}

}  // namespace simbob
