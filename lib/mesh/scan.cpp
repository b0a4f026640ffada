// The checks of a mesh file before assimp reads it (scan.h).
#include "mesh/scan.h"

#include <pugixml.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "simbob/mesh.h"
#include "simbob/values.h"

namespace simbob {

namespace {

std::string count(uint64_t n) { return std::to_string(n); }

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

// Splits `text` at white space; calls f(token) for each until f returns false.
template <class F>
void eachToken(std::string_view text, F f) {
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && isSpace(text[i])) ++i;
    const size_t start = i;
    while (i < text.size() && !isSpace(text[i])) ++i;
    if (i > start && !f(text.substr(start, i - start))) return;
  }
}

size_t tokenCount(std::string_view text) {
  size_t n = 0;
  eachToken(text, [&](std::string_view) { return ++n, true; });
  return n;
}

// "" when `token` is a number a float holds (what assimp reads vertices into), else why not.
std::string floatProblem(std::string_view token, const char* what = "a vertex coordinate") {
  char buffer[64];
  const size_t n = std::min(token.size(), sizeof buffer - 1);
  std::memcpy(buffer, token.data(), n);
  buffer[n] = '\0';
  char* end = nullptr;
  const double v = std::strtod(buffer, &end);
  const std::string quoted = "'" + std::string(token.substr(0, 40)) + "'";
  if (end == buffer) return "";  // not a number at all: the importer's own error
  if (!std::isfinite(v)) return what + (" " + quoted) + " is not a finite number";
  if (std::fabs(v) > FLT_MAX) return what + (" " + quoted) + " is beyond the range of a float (3.4e38)";
  return "";
}

std::string atLine(size_t line, const std::string& what) { return "line " + std::to_string(line) + ": " + what; }

std::string overTriangles(size_t max_triangles) {
  return "the faces so far make more than the limit of " + count(max_triangles) + " triangles";
}

std::string overCorners(size_t corners) {
  return "a polygon of " + count(corners) + " corners, more than the limit of " + count(kMaxMeshFaceCorners);
}

// Logical lines of a text format (a line ending in '\' goes on on the next one, as assimp's OBJ
// reader joins them): f(first line number, text) until f returns false.
template <class F>
void eachLine(const std::string& bytes, F f) {
  size_t line = 1, i = 0;
  std::string joined;
  while (i < bytes.size()) {
    const size_t first = line;
    joined.clear();
    for (;;) {
      size_t end = bytes.find('\n', i);
      if (end == std::string::npos) end = bytes.size();
      std::string_view text(bytes.data() + i, end - i);
      i = end + 1;
      ++line;
      while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
      if (!text.empty() && text.back() == '\\' && i < bytes.size()) {
        joined.append(text.substr(0, text.size() - 1)).push_back(' ');
        continue;
      }
      joined.append(text);
      break;
    }
    if (!f(first, std::string_view(joined))) return;
  }
}

// The first token of a line and the rest.
std::string_view keyword(std::string_view text, std::string_view* rest) {
  size_t i = 0;
  while (i < text.size() && isSpace(text[i])) ++i;
  size_t end = i;
  while (end < text.size() && !isSpace(text[end])) ++end;
  *rest = text.substr(end);
  return text.substr(i, end - i);
}

std::string scanObj(const std::string& bytes, size_t max_triangles) {
  if (bytes.find('\0') != std::string::npos) return "is not an OBJ file (OBJ is text; this one holds NUL bytes)";
  std::string problem;
  size_t triangles = 0;
  eachLine(bytes, [&](size_t line, std::string_view text) {
    std::string_view rest;
    const std::string_view key = keyword(text, &rest);
    if (key == "v") {
      size_t k = 0;
      eachToken(rest, [&](std::string_view t) {
        problem = floatProblem(t);
        return problem.empty() && ++k < 3;
      });
      if (!problem.empty()) problem = atLine(line, problem);
    } else if (!key.empty() && key[0] == 'f') {
      // assimp 5.2 reads every line that starts with 'f' as a face ("fo", "f1 2 3" too).
      const bool glued = key.size() > 1 && ((key[1] >= '0' && key[1] <= '9') || key[1] == '-');  // "f1 2 3"
      const size_t corners = tokenCount(rest) + (glued ? 1 : 0);
      if (corners > kMaxMeshFaceCorners) problem = atLine(line, overCorners(corners));
      triangles += corners > 2 ? corners - 2 : 0;
      if (problem.empty() && triangles > max_triangles) problem = atLine(line, overTriangles(max_triangles));
    }
    return problem.empty();
  });
  return problem;
}

std::string scanStl(const std::string& bytes, size_t max_triangles) {
  if (bytes.size() >= 84) {
    uint32_t facets = 0;
    std::memcpy(&facets, bytes.data() + 80, 4);
    const uint64_t size = 84 + uint64_t{50} * facets;
    if (size == bytes.size()) {
      if (facets > max_triangles)
        return "has " + count(facets) + " facets, more than the limit of " + count(max_triangles) + " triangles";
      for (size_t f = 0; f < facets; ++f)
        for (size_t k = 0; k < 9; ++k) {
          float x;
          std::memcpy(&x, bytes.data() + 84 + f * 50 + 12 + k * 4, 4);
          if (!std::isfinite(x)) return "facet " + count(f + 1) + ": a vertex coordinate is not a finite number";
        }
      return "";
    }
    // assimp 5.2 computes the binary size in 32 bits: a facet count that wraps to the file's size
    // would be read as binary, far past the file's end.
    if (static_cast<uint32_t>(size) == static_cast<uint32_t>(bytes.size()))
      return "its binary facet count (" + count(facets) + ") does not match its size";
  }
  const size_t start = bytes.find_first_not_of(" \t\r\n");
  if (start == std::string::npos || bytes.compare(start, 5, "solid") != 0)
    return "is not an STL file (neither 84 + 50 bytes a facet, binary, nor text starting with 'solid')";
  std::string problem;
  size_t triangles = 0;
  eachLine(bytes, [&](size_t line, std::string_view text) {
    std::string_view rest;
    const std::string_view key = keyword(text, &rest);
    if (key == "vertex") {
      size_t k = 0;
      eachToken(rest, [&](std::string_view t) {
        problem = floatProblem(t);
        return problem.empty() && ++k < 3;
      });
      if (!problem.empty()) problem = atLine(line, problem);
    } else if (key == "facet" && ++triangles > max_triangles) {
      problem = atLine(line, overTriangles(max_triangles));
    }
    return problem.empty();
  });
  return problem;
}

// --- COLLADA ---

size_t lineAt(const std::string& bytes, ptrdiff_t offset) {
  if (offset < 0) return 0;
  const size_t end = std::min(bytes.size(), static_cast<size_t>(offset));
  return 1 + static_cast<size_t>(std::count(bytes.begin(), bytes.begin() + static_cast<ptrdiff_t>(end), '\n'));
}

// Saturating sums and products: instancing can multiply past any integer.
constexpr uint64_t kHuge = uint64_t{1} << 62;
uint64_t add(uint64_t a, uint64_t b) { return std::min(kHuge, a + b); }

std::string urlTarget(const pugi::xml_node& x, const char* attribute) {
  const char* url = x.attribute(attribute).value();
  return url[0] == '#' ? std::string(url + 1) : std::string();
}

// An upper bound of the triangles a <mesh> gives after triangulation (corners of every polygon
// less two, exact for assimp's fans), or a problem (a polygon over the corner limit).
uint64_t meshTriangles(const pugi::xml_node& mesh, std::string* problem, const std::string& bytes) {
  uint64_t triangles = 0;
  for (const pugi::xml_node& prim : mesh.children()) {
    const std::string_view kind = prim.name();
    const bool polys = kind == "polylist" || kind == "polygons";
    if (kind != "triangles" && kind != "trifans" && kind != "tristrips" && !polys) continue;
    uint64_t offsets = 1;
    for (const pugi::xml_node& in : prim.children("input"))
      offsets = std::max<uint64_t>(offsets, in.attribute("offset").as_ullong() + 1);
    auto corners = [&](const pugi::xml_node& p) { return tokenCount(p.child_value()) / offsets; };
    if (kind == "triangles") {
      for (const pugi::xml_node& p : prim.children("p")) triangles = add(triangles, corners(p) / 3);
    } else if (kind == "polylist") {
      eachToken(prim.child_value("vcount"), [&](std::string_view t) {
        const uint64_t n = std::strtoull(std::string(t).c_str(), nullptr, 10);
        if (n > kMaxMeshFaceCorners) *problem = atLine(lineAt(bytes, prim.offset_debug()), overCorners(n));
        triangles = add(triangles, n > 2 ? n - 2 : 0);
        return problem->empty();
      });
    } else {  // one polygon, fan or strip per <p> (and per <ph>'s <p>)
      for (const pugi::xml_node& e : prim.children()) {
        const pugi::xml_node p = std::string_view(e.name()) == "ph" ? e.child("p") : e;
        if (std::string_view(p.name()) != "p") continue;
        const uint64_t n = corners(p);
        if (polys && n > kMaxMeshFaceCorners) *problem = atLine(lineAt(bytes, p.offset_debug()), overCorners(n));
        triangles = add(triangles, n > 2 ? n - 2 : 0);
      }
    }
    if (!problem->empty()) return 0;
  }
  return triangles;
}

// assimp sizes its arrays by what an index list or a count says: a `!` inside a <p> list (found
// by the mesh fuzz target) or a count of 1e9 makes it ask for gigabytes. Index lists hold whole
// numbers only.
std::string indexListProblem(const pugi::xml_node& x) {
  std::string problem;
  eachToken(x.child_value(), [&](std::string_view t) {
    const std::string_view d = !t.empty() && t[0] == '-' ? t.substr(1) : t;  // <v>'s -1: the bind shape
    const bool digits =
        !d.empty() && d.size() <= 10 && std::all_of(d.begin(), d.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (!digits)
      problem = "'" + quoteInput(std::string(t), 40) + "' in <" + std::string(x.name()) + "> is not a whole number";
    return digits;
  });
  return problem;
}

// A `count` no file of this size can hold (each item takes at least two bytes), or a `stride`
// beyond any mesh's, is refused before assimp reserves room for it.
std::string sizeProblem(const pugi::xml_node& x, size_t file_bytes) {
  const pugi::xml_attribute c = x.attribute("count"), st = x.attribute("stride");
  if (c && c.as_ullong() > file_bytes / 2 + 1)
    return "<" + std::string(x.name()) + " count=\"" + quoteInput(c.value(), 40) + "\"> is more than the file holds";
  if (st && st.as_ullong() > 64)
    return "<" + std::string(x.name()) + " stride=\"" + quoteInput(st.value(), 40) + "\"> is over 64";
  return {};
}

struct Expansion {
  uint64_t triangles = 0, nodes = 0, depth = 0;
  int state = 0;  // 0 not seen, 1 being expanded, 2 done
};

/// The elements a COLLADA file's instancing refers to, by id, and its scenes' root nodes.
struct ColladaIndex {
  std::unordered_map<std::string, pugi::xml_node> nodes, geometries, controllers;
  std::vector<pugi::xml_node> roots;
};

/// One pass over every element, without recursion: depth, ids, and the numbers of float arrays.
/// "" or what is wrong, at its line.
std::string indexCollada(const std::string& bytes, const pugi::xml_node& root, ColladaIndex* ix) {
  size_t depth = 2;  // of x; the root is 1
  for (pugi::xml_node x = root.first_child(); x && x != root;) {
    if (x.type() == pugi::node_element) {
      const std::string_view name = x.name();
      if (depth > kMaxMeshXmlDepth)
        return atLine(lineAt(bytes, x.offset_debug()),
                      "elements nested more than the limit of " + count(kMaxMeshXmlDepth) + " deep");
      const char* id = x.attribute("id").value();
      if (name == "node") {
        if (*id) ix->nodes.emplace(id, x);
        if (std::string_view(x.parent().name()) == "visual_scene") ix->roots.push_back(x);
      } else if (name == "geometry" && *id) {
        ix->geometries.emplace(id, x);
      } else if (name == "controller" && *id) {
        ix->controllers.emplace(id, x);
      } else if (name == "float_array") {
        std::string problem;
        eachToken(x.child_value(),
                  [&](std::string_view t) { return (problem = floatProblem(t, "a number of <float_array>")).empty(); });
        if (!problem.empty()) return atLine(lineAt(bytes, x.offset_debug()), problem);
      } else if (name == "p" || name == "v" || name == "vcount" || name == "h" || name == "int_array") {
        if (std::string problem = indexListProblem(x); !problem.empty())
          return atLine(lineAt(bytes, x.offset_debug()), problem);
      }
      if (std::string problem = sizeProblem(x, bytes.size()); !problem.empty())
        return atLine(lineAt(bytes, x.offset_debug()), problem);
      if (x.first_child()) {
        x = x.first_child();
        ++depth;
        continue;
      }
    }
    while (x != root && !x.next_sibling()) {
      x = x.parent();
      --depth;
    }
    if (x != root) x = x.next_sibling();
  }

  return "";
}

std::string scanCollada(const std::string& bytes, size_t max_triangles, std::string* up_axis) {
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_buffer(bytes.data(), bytes.size());
  if (!parsed) return atLine(lineAt(bytes, parsed.offset), std::string("not XML: ") + parsed.description());
  const pugi::xml_node root = doc.document_element();
  if (std::string_view(root.name()) != "COLLADA")
    return "is not a COLLADA file (its root element is <" + std::string(root.name()).substr(0, 40) + ">)";
  *up_axis = std::string(root.child("asset").child_value("up_axis"));
  while (!up_axis->empty() && isSpace(up_axis->back())) up_axis->pop_back();
  while (!up_axis->empty() && isSpace(up_axis->front())) up_axis->erase(0, 1);

  ColladaIndex ix;
  if (std::string problem = indexCollada(bytes, root, &ix); !problem.empty()) return problem;
  const auto& nodes = ix.nodes;
  const auto& geometries = ix.geometries;
  const auto& controllers = ix.controllers;
  const auto& roots = ix.roots;

  std::unordered_map<std::string, uint64_t> geometry_triangles;
  std::string problem;
  auto geometryTriangles = [&](const std::string& id) -> uint64_t {
    auto it = geometry_triangles.find(id);
    if (it != geometry_triangles.end()) return it->second;
    uint64_t n = 0;
    auto g = geometries.find(id);
    if (g != geometries.end()) n = meshTriangles(g->second.child("mesh"), &problem, bytes);
    return geometry_triangles[id] = n;
  };

  // Every node's instanced size (its meshes, children and instance_nodes, recursively), with a
  // stack of its own; a node met again while it is being expanded is a cycle.
  std::unordered_map<const void*, Expansion> done;
  auto children = [&](const pugi::xml_node& n) {
    std::vector<pugi::xml_node> out;
    for (const pugi::xml_node& c : n.children()) {
      const std::string_view name = c.name();
      if (name == "node") {
        out.push_back(c);
      } else if (name == "instance_node") {
        auto it = nodes.find(urlTarget(c, "url"));
        if (it != nodes.end()) out.push_back(it->second);
      }
    }
    return out;
  };
  auto own = [&](const pugi::xml_node& n) {
    uint64_t t = 0;
    for (const pugi::xml_node& c : n.children()) {
      const std::string_view name = c.name();
      if (name == "instance_geometry") {
        t = add(t, geometryTriangles(urlTarget(c, "url")));
      } else if (name == "instance_controller") {
        auto it = controllers.find(urlTarget(c, "url"));
        if (it == controllers.end()) continue;
        const pugi::xml_node skin = it->second.child("skin") ? it->second.child("skin") : it->second.child("morph");
        t = add(t, geometryTriangles(urlTarget(skin, "source")));
      }
    }
    return t;
  };
  Expansion total;
  for (const pugi::xml_node& r : roots) {
    std::vector<std::pair<pugi::xml_node, size_t>> stack{{r, 0}};  // node, children expanded so far
    std::vector<std::vector<pugi::xml_node>> kids{children(r)};
    done[r.internal_object()].state = 1;
    while (!stack.empty() && problem.empty()) {
      auto& [n, next] = stack.back();
      if (next < kids.back().size()) {
        const pugi::xml_node c = kids.back()[next++];
        Expansion& e = done[c.internal_object()];
        if (e.state == 1)
          return atLine(lineAt(bytes, c.offset_debug()), "node '" +
                                                             std::string(c.attribute("id").value()).substr(0, 40) +
                                                             "' contains itself (through <instance_node>)");
        if (e.state == 0) {
          e.state = 1;
          stack.emplace_back(c, 0);
          kids.push_back(children(c));
        }
        continue;
      }
      Expansion sum;
      sum.triangles = own(n);
      sum.nodes = 1;
      for (const pugi::xml_node& c : kids.back()) {
        const Expansion& e = done[c.internal_object()];
        sum.triangles = add(sum.triangles, e.triangles);
        sum.nodes = add(sum.nodes, e.nodes);
        sum.depth = std::max(sum.depth, e.depth);
      }
      sum.depth += 1;
      sum.state = 2;
      if (sum.depth > kMaxMeshNodeDepth)
        return atLine(
            lineAt(bytes, n.offset_debug()),
            "nodes nested more than the limit of " + count(kMaxMeshNodeDepth) + " deep (counting <instance_node>)");
      done[n.internal_object()] = sum;
      stack.pop_back();
      kids.pop_back();
    }
    if (!problem.empty()) return problem;
    const Expansion& e = done[r.internal_object()];
    total.triangles = add(total.triangles, e.triangles);
    total.nodes = add(total.nodes, e.nodes);
  }
  if (total.nodes > kMaxMeshNodes)
    return "has " + (total.nodes >= kHuge ? std::string("more than 4e18") : count(total.nodes)) +
           " nodes after instancing, more than the limit of " + count(kMaxMeshNodes);
  if (total.triangles > max_triangles)
    return "has " + (total.triangles >= kHuge ? std::string("more than 4e18") : count(total.triangles)) +
           " triangles after instancing, more than the limit of " + count(max_triangles);
  return "";
}

}  // namespace

MeshScan scanMeshFile(const std::string& path, const std::string& bytes, size_t max_triangles) {
  MeshScan out;
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos || (slash != std::string::npos && dot < slash) ? "" : path.substr(dot);
  for (char& c : ext) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  if (ext == ".stl") {
    out.format = MeshFormat::Stl;
    out.problem = scanStl(bytes, max_triangles);
  } else if (ext == ".obj") {
    out.format = MeshFormat::Obj;
    out.problem = scanObj(bytes, max_triangles);
  } else if (ext == ".dae") {
    out.format = MeshFormat::Collada;
    out.problem = scanCollada(bytes, max_triangles, &out.up_axis);
  } else {
    out.problem = (ext.empty() ? std::string("a file without an extension") : "'" + ext.substr(0, 20) + "'") +
                  " is not a mesh format simbob reads (STL .stl, OBJ .obj, COLLADA .dae)";
  }
  return out;
}

}  // namespace simbob
