// Triangle meshes read from STL (binary and ASCII), OBJ and COLLADA (DAE) files, with their
// convex hulls and mass properties, as plain data (issue 28, docs/meshes.md). lib/mesh reads
// them through assimp and computes hulls with qhull; neither library appears here, and nothing
// here includes ODE or GL: the physics turns a hull into a dGeomConvex and a mesh into a
// dGeomTriMesh, the renderer and the replay page draw the triangles.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "simbob/error.h"
#include "simbob/frames.h"

namespace simbob {

/// The axis that points up in a frame. Scenes are Y-up; URDF (and ROS) are Z-up. COLLADA files
/// say theirs (`<up_axis>`, Y_UP by default); STL and OBJ have none and are taken as they are.
enum class UpAxis : uint8_t { Y, Z };

/// Largest mesh loadMesh accepts (vertices after merging identical ones, triangles after
/// triangulating polygons); a bigger one is refused with a message naming the limit.
constexpr size_t kMaxMeshVertices = 1000000;
constexpr size_t kMaxMeshTriangles = 2000000;

/// A convex polyhedron in ODE's dGeomConvex layout (dCreateConvex(space, planes, planecount,
/// points, pointcount, polygons)): plain numbers, copied to dReal by the physics.
struct ConvexHull {
  /// 4 per face: its unit outward normal nx ny nz and d (m): the face's points p have n.p = d.
  std::vector<double> planes;
  std::vector<double> points;  ///< 3 per vertex, m, in the mesh frame
  /// Per face, in `planes` order: its vertex count, then its vertex indices, counterclockwise
  /// seen from outside.
  std::vector<unsigned> polygons;
  size_t faceCount() const { return planes.size() / 4; }
  size_t pointCount() const { return points.size() / 3; }
  bool empty() const { return planes.empty(); }
};

/// Volume, centre and inertia of a closed solid of unit density (multiply by the density in
/// kg/m^3 for kg and kg m^2).
struct MeshMass {
  double volume = 0;                        ///< m^3 (> 0 for a closed mesh wound outward)
  Vec3 centre{0, 0, 0};                     ///< centroid, m, mesh frame
  Mat3 inertia{0, 0, 0, 0, 0, 0, 0, 0, 0};  ///< m^5 (per unit density) about the centroid, mesh axes
};

/// One mesh as read from its file, in metres, in the frame the caller places it in: the file's
/// own unit (COLLADA `<unit meter>`), then the turn from the file's up axis to the caller's
/// (COLLADA only; STL and OBJ are taken as written), then `scale` are applied to every vertex, once.
struct MeshData {
  std::string file;                                ///< the path it was read from, as given to loadMesh
  Vec3 scale{1, 1, 1};                             ///< the scale it was read with (per axis of the caller's frame)
  UpAxis up = UpAxis::Y;                           ///< the up axis of the caller's frame
  std::vector<Vec3> vertices;                      ///< m
  std::vector<std::array<uint32_t, 3>> triangles;  ///< indices into vertices, counterclockwise seen from outside
  Vec3 lo{0, 0, 0}, hi{0, 0, 0};                   ///< bounds of the vertices (m)
  /// Every edge is shared by exactly two triangles, used in opposite directions: the mesh
  /// encloses a volume, and `mass` is its solid's.
  bool closed = false;
  MeshMass mass;  ///< of the triangle mesh taken as a solid (meaningful when closed)
  /// The convex hull of the vertices, what a hull collision geom (GeomShape::ConvexHull) uses;
  /// empty when the vertices span no volume (flat or a line), `hull_problem` then says so.
  ConvexHull hull;
  MeshMass hull_mass;        ///< of the hull as a solid
  std::string hull_problem;  ///< why `hull` is empty ("" when it is not)
};

/// What loadMesh gives: the mesh, or an error (then `mesh` is null).
struct MeshLoad {
  std::shared_ptr<const MeshData> mesh;
  /// kind MissingInput (exit 66) when the file does not exist or cannot be read, InvalidInput
  /// (65) when it cannot be parsed, holds no triangles, is over the limits or `scale` has a zero
  /// or non-finite component; loc.file is the mesh file, the message says why (no "file:" in it).
  Error error;
  bool ok() const { return mesh != nullptr; }
};

/// Reads a mesh file (format by its contents and extension: .stl, .obj, .dae) and converts it
/// to metres in a frame whose up axis is `up`. `scale` multiplies each axis of that frame (after
/// the file's unit and up-axis turn); a negative product flips the winding back so triangles
/// stay counterclockwise from outside. The hull and masses are computed here.
MeshLoad loadMesh(const std::string& path, const Vec3& scale, UpAxis up);

/// Loads each file + scale + up axis once (a compile holds one): the same request gives the
/// same shared MeshData, or the same error, without reading the file again.
class MeshCache {
 public:
  MeshLoad load(const std::string& path, const Vec3& scale, UpAxis up);
  size_t size() const { return loaded_.size(); }

 private:
  std::map<std::tuple<std::string, Vec3, UpAxis>, MeshLoad> loaded_;
};

/// Volume, centroid and inertia (unit density, about the centroid) of the solid a closed,
/// outward-wound triangle mesh bounds (signed tetrahedra from the origin, exact for polyhedra).
MeshMass polyhedronMass(const std::vector<Vec3>& vertices, const std::vector<std::array<uint32_t, 3>>& triangles);

/// The convex hull of `points` (qhull). False with `problem` set when they span no volume
/// (fewer than 4 points, or all in one plane) or qhull fails.
bool convexHull(const std::vector<Vec3>& points, ConvexHull* hull, std::string* problem);

}  // namespace simbob
