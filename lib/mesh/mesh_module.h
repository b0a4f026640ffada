// The assimp side of lib/mesh, built as a module of its own (libsimbob_mesh.so) and opened by
// load.cpp the first time a mesh file is read: a run without meshes never loads assimp, whose
// 44,000 relocations were most of the dynamic linker's work at every start (bench/README.md,
// "Loading at the parser's pace, third round"). The module uses only inline code of simbob's
// headers, so it needs nothing from the program that opens it. The Python module links
// assimp_read.cpp in instead: load.cpp then finds simbob_mesh_module() already there.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "simbob/frames.h"

namespace simbob {

/// A mesh file's triangles as assimp gives them: the vertices through the node transforms,
/// identical positions merged in order of first use, degenerate triangles dropped.
struct MeshFile {
  std::string error;  ///< why assimp could not read it (read() returned false)
  size_t faces = 0;   ///< faces in the file; over max_triangles, nothing more is read
  bool collada = false;
  std::vector<Vec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
};

/// What simbob_mesh_module() returns; `abi` is kMeshModuleAbi of the module's build.
struct MeshModule {
  int abi;
  /// False when assimp cannot read the file (out->error says why).
  bool (*read)(const std::string& path, size_t max_triangles, MeshFile* out);
};
constexpr int kMeshModuleAbi = 1;

}  // namespace simbob

extern "C" const simbob::MeshModule* simbob_mesh_module();
