// Mesh files through assimp. assimp 5.2's COLLADA importer already applies the file's
// <unit meter> and turns its up_axis to +Y in the root node's transform (checked by
// tests/mesh/load_test.cpp on a Z-up centimetre box), so the vertices are taken with their node
// transforms and nothing here scales or turns a COLLADA file again (dart#287). STL and OBJ carry
// no unit or up axis: their numbers are the caller's.
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <unordered_map>

#include "simbob/mesh.h"

namespace simbob {

namespace {

Error meshError(ErrorKind kind, const std::string& path, std::string message) {
  return Error{kind, SourceLoc{FileName(path), 0}, std::move(message)};
}

struct VertexHash {
  size_t operator()(const Vec3& v) const {
    size_t h = 0;
    for (double x : v) h = h * 1000003u ^ std::hash<double>()(x);
    return h;
  }
};

// Triangles of every mesh under `node`, vertices through the node transforms (float in assimp,
// composed in double), identical positions merged in order of first use.
struct Collector {
  std::vector<Vec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::unordered_map<Vec3, uint32_t, VertexHash> index;
  size_t degenerate = 0;

  uint32_t vertex(const Vec3& p) {
    auto [it, added] = index.emplace(p, static_cast<uint32_t>(vertices.size()));
    if (added) vertices.push_back(p);
    return it->second;
  }

  void collect(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent) {
    const aiMatrix4x4 m = parent * node->mTransformation;
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      const aiMesh* mesh = scene->mMeshes[node->mMeshes[i]];
      std::vector<uint32_t> ids(mesh->mNumVertices);
      for (unsigned k = 0; k < mesh->mNumVertices; ++k) {
        const aiVector3D& v = mesh->mVertices[k];
        Vec3 p;
        for (unsigned r = 0; r < 3; ++r)  // + 0.0 turns -0 into 0, so both merge (their hashes differ)
          p[r] = static_cast<double>(m[r][0]) * v.x + static_cast<double>(m[r][1]) * v.y +
                 static_cast<double>(m[r][2]) * v.z + static_cast<double>(m[r][3]) + 0.0;
        ids[k] = vertex(p);
      }
      for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        const aiFace& face = mesh->mFaces[f];
        if (face.mNumIndices != 3) continue;  // points and lines bound nothing
        const std::array<uint32_t, 3> t{ids[face.mIndices[0]], ids[face.mIndices[1]], ids[face.mIndices[2]]};
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
          ++degenerate;
          continue;
        }
        triangles.push_back(t);
      }
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) collect(scene, node->mChildren[c], m);
  }
};

// Every edge used once in each direction: the triangles close a volume, wound consistently.
bool isClosed(const std::vector<std::array<uint32_t, 3>>& triangles) {
  std::vector<uint64_t> edges;
  edges.reserve(triangles.size() * 3);
  for (const auto& t : triangles)
    for (size_t k = 0; k < 3; ++k) edges.push_back(uint64_t{t[k]} << 32 | t[(k + 1) % 3]);
  std::sort(edges.begin(), edges.end());
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
  for (uint64_t e : edges)
    if (!std::binary_search(edges.begin(), edges.end(), (e << 32) | (e >> 32))) return false;
  return true;
}

// Fan triangles of the hull's faces, for its mass.
std::vector<std::array<uint32_t, 3>> hullTriangles(const ConvexHull& h) {
  std::vector<std::array<uint32_t, 3>> out;
  for (size_t i = 0; i < h.polygons.size(); i += 1 + h.polygons[i]) {
    const unsigned n = h.polygons[i];
    for (unsigned k = 2; k < n; ++k) out.push_back({h.polygons[i + 1], h.polygons[i + k], h.polygons[i + k + 1]});
  }
  return out;
}

std::vector<Vec3> hullPoints(const ConvexHull& h) {
  std::vector<Vec3> p(h.pointCount());
  for (size_t i = 0; i < p.size(); ++i) p[i] = {h.points[i * 3], h.points[i * 3 + 1], h.points[i * 3 + 2]};
  return p;
}

std::string count(size_t n) { return std::to_string(n); }

}  // namespace

MeshLoad loadMesh(const std::string& path, const Vec3& scale, UpAxis up) {
  MeshLoad out;
  for (double s : scale)
    if (!std::isfinite(s) || s == 0) {
      out.error = meshError(ErrorKind::InvalidInput, path, "scale needs three finite, non-zero factors");
      return out;
    }
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) {
      out.error =
          meshError(ErrorKind::MissingInput, path, std::string("cannot read the mesh: ") + std::strerror(errno));
      return out;
    }
  }
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate);
  if (!scene || !scene->mRootNode) {
    out.error = meshError(ErrorKind::InvalidInput, path,
                          std::string("not a mesh assimp can read: ") + importer.GetErrorString());
    return out;
  }
  size_t faces = 0;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) faces += scene->mMeshes[i]->mNumFaces;
  if (faces > kMaxMeshTriangles) {
    out.error = meshError(ErrorKind::InvalidInput, path,
                          "has " + count(faces) + " triangles, more than the limit of " + count(kMaxMeshTriangles));
    return out;
  }
  Collector c;
  c.collect(scene, scene->mRootNode, aiMatrix4x4());
  if (c.vertices.size() > kMaxMeshVertices) {
    out.error =
        meshError(ErrorKind::InvalidInput, path,
                  "has " + count(c.vertices.size()) + " vertices, more than the limit of " + count(kMaxMeshVertices));
    return out;
  }
  if (c.triangles.empty()) {
    out.error = meshError(ErrorKind::InvalidInput, path, "holds no triangles");
    return out;
  }
  aiString format;
  const bool collada = scene->mMetaData && scene->mMetaData->Get("SourceAsset_Format", format) &&
                       std::strstr(format.C_Str(), "Collada") != nullptr;
  auto data = std::make_shared<MeshData>();
  data->file = path;
  data->scale = scale;
  data->up = up;
  data->vertices = std::move(c.vertices);
  data->triangles = std::move(c.triangles);
  for (Vec3& v : data->vertices) {
    // assimp left a COLLADA file Y-up; a Z-up caller turns it by +90 degrees about X.
    if (collada && up == UpAxis::Z) v = {v[0], -v[2], v[1]};
    for (size_t k = 0; k < 3; ++k) v[k] *= scale[k];
  }
  if (scale[0] * scale[1] * scale[2] < 0)
    for (auto& t : data->triangles) std::swap(t[1], t[2]);
  data->lo = data->hi = data->vertices[0];
  for (const Vec3& v : data->vertices)
    for (size_t k = 0; k < 3; ++k) {
      data->lo[k] = std::min(data->lo[k], v[k]);
      data->hi[k] = std::max(data->hi[k], v[k]);
    }
  data->closed = isClosed(data->triangles);
  data->mass = polyhedronMass(data->vertices, data->triangles);
  if (convexHull(data->vertices, &data->hull, &data->hull_problem))
    data->hull_mass = polyhedronMass(hullPoints(data->hull), hullTriangles(data->hull));
  out.mesh = std::move(data);
  return out;
}

MeshLoad MeshCache::load(const std::string& path, const Vec3& scale, UpAxis up) {
  auto key = std::make_tuple(path, scale, up);
  auto it = loaded_.find(key);
  if (it != loaded_.end()) return it->second;
  return loaded_.emplace(std::move(key), loadMesh(path, scale, up)).first->second;
}

}  // namespace simbob
