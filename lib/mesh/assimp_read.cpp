// The assimp side of mesh reading (assimp_read.h): assimp reads the bytes load.cpp read and
// checked, with only the importer of the format load.cpp chose (the other ~40 are dropped, so a
// glTF or any other format is never parsed), through an IOSystem that serves those bytes and
// nothing else (an OBJ's mtllib, a COLLADA image or any other file a mesh names is not opened).
// The triangles of every mesh come out through the node transforms. assimp 5.2's COLLADA importer
// applies the file's <unit meter> in the root node's transform, and its up_axis (turned to +Y)
// unless AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION is set (URDF meshes, as ROS reads them);
// nothing here scales or turns a COLLADA file again (dart#287).
#include <assimp/BaseImporter.h>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <memory>
#include <unordered_map>
#include <utility>

#include "mesh/assimp_read.h"

namespace simbob {

namespace {

struct VertexHash {
  size_t operator()(const Vec3& v) const {
    size_t h = 0;
    for (double x : v) h = h * 1000003u ^ std::hash<double>()(x);
    return h;
  }
};

// The one file assimp may open: the request's bytes under a made-up name whose extension picks
// the importer. Every other name does not exist.
class OneFile : public Assimp::IOSystem {
 public:
  OneFile(std::string name, const char* data, size_t size) : name_(std::move(name)), data_(data), size_(size) {}
  bool Exists(const char* file) const override { return file && name_ == file; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (!Exists(file) || !mode || mode[0] != 'r') return nullptr;
    return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(data_), size_);
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }

 private:
  std::string name_;
  const char* data_;
  size_t size_;
};

// Triangles of every mesh under the root, vertices through the node transforms (float in assimp,
// composed in double), identical positions merged in order of first use. Nodes are visited in
// pre-order with a stack of their own (an instanced hierarchy can be deep), and collection stops
// once more than `max_triangles` triangles came out.
struct Collector {
  std::vector<Vec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::unordered_map<Vec3, uint32_t, VertexHash> index;
  size_t faces = 0;

  uint32_t vertex(const Vec3& p) {
    auto [it, added] = index.emplace(p, static_cast<uint32_t>(vertices.size()));
    if (added) vertices.push_back(p);
    return it->second;
  }

  void meshes(const aiScene* scene, const aiNode* node, const aiMatrix4x4& m, size_t max_triangles) {
    for (unsigned i = 0; i < node->mNumMeshes && faces <= max_triangles; ++i) {
      const aiMesh* mesh = scene->mMeshes[node->mMeshes[i]];
      faces += mesh->mNumFaces;
      if (faces > max_triangles) return;
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
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;  // degenerate
        triangles.push_back(t);
      }
    }
  }

  void collect(const aiScene* scene, size_t max_triangles) {
    std::vector<std::pair<const aiNode*, aiMatrix4x4>> stack{{scene->mRootNode, aiMatrix4x4()}};
    while (!stack.empty() && faces <= max_triangles) {
      const auto [node, parent] = stack.back();
      stack.pop_back();
      const aiMatrix4x4 m = parent * node->mTransformation;
      meshes(scene, node, m, max_triangles);
      for (unsigned c = node->mNumChildren; c-- > 0;) stack.emplace_back(node->mChildren[c], m);
    }
  }
};

bool readMeshFile(const MeshRequest& request, MeshFile* out) {
  static const char* const kExtensions[] = {"stl", "obj", "dae"};
  const char* ext = kExtensions[static_cast<size_t>(request.format)];
  const std::string name = std::string("mesh.") + ext;
  Assimp::Importer importer;
  // Only the format's own importer stays registered: assimp cannot fall back on another one
  // that recognises the bytes (glTF, whose buffers name other files, among them).
  Assimp::BaseImporter* keep = importer.GetImporter(ext);
  for (size_t i = importer.GetImporterCount(); i-- > 0;) {
    Assimp::BaseImporter* other = importer.GetImporter(i);
    if (other == keep) continue;
    importer.UnregisterLoader(other);
    delete other;  // UnregisterLoader hands it back; the Importer no longer owns it
  }
  importer.SetIOHandler(new OneFile(name, request.data, request.size));  // the Importer owns it
  importer.SetPropertyInteger(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, request.ignore_up_axis ? 1 : 0);
  const aiScene* scene = keep ? importer.ReadFile(name, aiProcess_Triangulate) : nullptr;
  if (!scene || !scene->mRootNode) {
    out->error = keep ? importer.GetErrorString() : std::string("assimp has no ") + ext + " importer";
    return false;
  }
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) out->faces += scene->mMeshes[i]->mNumFaces;
  if (out->faces > request.max_triangles) return true;
  Collector c;
  c.collect(scene, request.max_triangles);
  out->faces = c.faces;
  if (out->faces > request.max_triangles) return true;
  out->vertices = std::move(c.vertices);
  out->triangles = std::move(c.triangles);
  return true;
}

}  // namespace

bool readWithAssimp(const MeshRequest& request, MeshFile* out) { return readMeshFile(request, out); }

}  // namespace simbob
