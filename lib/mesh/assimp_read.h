// The assimp side of lib/mesh (assimp_read.cpp): the one file that includes assimp. load.cpp
// reads and checks a mesh file's bytes (scan.cpp), then hands them here. Linked into the program
// (it was a module opened at run time until issue 44: it saved about 6 ms a process and cost a
// search path and a runtime failure).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "simbob/frames.h"

namespace simbob {

/// The mesh formats simbob reads (docs/meshes.md); load.cpp chooses one from the file's
/// extension and contents before assimp sees the file.
enum class MeshFormat : uint8_t { Stl, Obj, Collada };

/// What to read: the file's bytes (assimp opens no file at all: an OBJ's `mtllib` or any
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

/// Reads the request's bytes with assimp; false when assimp cannot (out->error says why).
bool readWithAssimp(const MeshRequest& request, MeshFile* out);

}  // namespace simbob
