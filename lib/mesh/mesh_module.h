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

/// The mesh formats simbob reads (docs/meshes.md); load.cpp chooses one from the file's
/// extension and contents before the module sees the file.
enum class MeshFormat : uint8_t { Stl, Obj, Collada };

/// What to read: the file's bytes (the module opens no file at all: an OBJ's `mtllib` or any
/// other reference a file makes finds nothing) with the one importer of `format`.
struct MeshRequest {
  const char* data = nullptr;
  size_t size = 0;
  MeshFormat format = MeshFormat::Stl;
  /// COLLADA: keep the vertices as written, the file's <up_axis> not applied (as ROS reads a
  /// URDF's meshes); false turns the file's up axis onto +Y (scenes). <unit> is applied either way.
  bool ignore_up_axis = false;
  size_t max_triangles = 0;  ///< stop once more triangles than this come out (after instancing)
};

/// A mesh file's triangles as assimp gives them: the vertices through the node transforms,
/// identical positions merged in order of first use, degenerate triangles dropped.
struct MeshFile {
  std::string error;  ///< why assimp could not read it (read() returned false)
  /// Triangles in the file (after instancing); over max_triangles, reading stopped there.
  size_t faces = 0;
  std::vector<Vec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
};

/// What simbob_mesh_module() returns; `abi` is kMeshModuleAbi of the module's build.
struct MeshModule {
  int abi;
  /// False when assimp cannot read the file (out->error says why).
  bool (*read)(const MeshRequest& request, MeshFile* out);
};
constexpr int kMeshModuleAbi = 2;

}  // namespace simbob

extern "C" const simbob::MeshModule* simbob_mesh_module();
