// The module side of mesh reading (mesh_module.h): assimp reads the file, the triangles of
// every mesh come out through the node transforms. assimp 5.2's COLLADA importer already applies
// the file's <unit meter> and turns its up_axis to +Y in the root node's transform (checked by
// tests/mesh/load_test.cpp on a Z-up centimetre box), so the vertices are taken with their node
// transforms and nothing here scales or turns a COLLADA file again (dart#287).
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cstring>
#include <unordered_map>

#include "mesh_module.h"  // (relative: the Python module builds this file without lib/ on its path)

namespace simbob {

namespace {

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

bool readMeshFile(const std::string& path, size_t max_triangles, MeshFile* out) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate);
  if (!scene || !scene->mRootNode) {
    out->error = importer.GetErrorString();
    return false;
  }
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) out->faces += scene->mMeshes[i]->mNumFaces;
  if (out->faces > max_triangles) return true;
  Collector c;
  c.collect(scene, scene->mRootNode, aiMatrix4x4());
  aiString format;
  out->collada = scene->mMetaData && scene->mMetaData->Get("SourceAsset_Format", format) &&
                 std::strstr(format.C_Str(), "Collada") != nullptr;
  out->vertices = std::move(c.vertices);
  out->triangles = std::move(c.triangles);
  return true;
}

const MeshModule kModule{kMeshModuleAbi, readMeshFile};

}  // namespace

}  // namespace simbob

extern "C" const simbob::MeshModule* simbob_mesh_module() { return &simbob::kModule; }
