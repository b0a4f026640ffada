// What load.cpp checks in a mesh file's bytes before assimp sees them (docs/meshes.md, "Limits"):
// the format from the extension and the contents, the limits that would otherwise cost assimp
// its time, memory or stack (triangles after COLLADA instancing, corners of one polygon, node
// nesting and instance cycles), and vertex numbers that are not finite floats, each at the mesh
// file's line. Linear in the file's size, no recursion.
#pragma once

#include <cstddef>
#include <string>

#include "mesh/assimp_read.h"

namespace simbob {

struct MeshScan {
  MeshFormat format = MeshFormat::Stl;
  /// COLLADA's <up_axis> as the file states it ("Y_UP", "Z_UP", "X_UP"); "" when it states none.
  std::string up_axis;
  std::string problem;  ///< why the file is refused, "" when it is not (no "file:" in it)
};

/// The format of `path` from its extension (.stl, .obj, .dae in any case), then the checks of
/// its `bytes` for that format, at most `max_triangles` triangles.
MeshScan scanMeshFile(const std::string& path, const std::string& bytes, size_t max_triangles);

}  // namespace simbob
