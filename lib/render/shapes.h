// Tessellation of the model primitives (guide 6.3) into GL immediate-mode calls, in the
// visual's own frame: normals for lighting, texture coordinates for skins with textures.
#pragma once

#include <vector>

#include "render/gl_api.h"
#include "simbob/model.h"
#include "simbob/visuals.h"

namespace simbob::render {

/// The meshes of a Model (Model::meshes) as GL display lists: each mesh's triangles and its hull
/// are uploaded once, with one normal per face, the first time they are drawn (in the context
/// current then), and deleted by release().
class MeshLists {
 public:
  explicit MeshLists(const std::vector<MeshDef>& meshes) : meshes_(meshes) {}
  /// Draws Model::meshes[mesh]: its triangles, or its convex hull.
  void draw(const GlApi& gl, int mesh, bool hull);
  /// Bounds of what draw() draws (m, the mesh frame).
  void bounds(int mesh, Vec3* lo, Vec3* hi) const;
  /// Deletes the lists (the context they were made in must be current).
  void release(const GlApi& gl);

 private:
  const std::vector<MeshDef>& meshes_;
  std::vector<GLuint> lists_;  ///< 2 per mesh: triangles, hull (0: not made yet)
};

/// Draws the surface of `v` (Cuboid sides per SideMask, Plane cells, Ellipsoid, Cylinder parts
/// per ComponentMask, Cone with its base, a Mesh from `meshes`).
void drawShape(const GlApi& gl, const VisualDef& v, MeshLists& meshes);
/// Draws the twelve edges of the local bounding box of `v` (quality level Frame).
void drawBoundingBox(const GlApi& gl, const VisualDef& v, const MeshLists& meshes);

}  // namespace simbob::render
