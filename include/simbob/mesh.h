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

/// The frame a mesh is read into and how a COLLADA file's `<up_axis>` is taken (docs/meshes.md).
/// Y: a scene's frame (Y-up); the file's up axis (Y_UP by default) is turned onto +Y. Z: a URDF's
/// frame (Z-up); the vertices are taken as written, the file's up axis not applied, as RViz,
/// MoveIt and Gazebo classic read a URDF's meshes. STL and OBJ have none and are taken as written
/// in both; COLLADA's `<unit>` is applied in both.
enum class UpAxis : uint8_t { Y, Z };

/// Largest mesh loadMesh accepts (vertices after merging identical ones, triangles after
/// triangulating polygons and after COLLADA's instancing); a bigger one is refused with a message
/// naming the limit. The others are checked in the file before assimp reads it.
constexpr size_t kMaxMeshVertices = 1000000;
constexpr size_t kMaxMeshTriangles = 2000000;
constexpr size_t kMaxMeshFileBytes = size_t{256} << 20;  ///< a mesh file's size
constexpr size_t kMaxMeshFaceCorners = 256;              ///< corners of one polygon (OBJ, COLLADA)
constexpr size_t kMaxMeshNodes = 100000;                 ///< COLLADA nodes after instancing
constexpr size_t kMaxMeshNodeDepth = 100;                ///< COLLADA nodes nested, counting <instance_node>
constexpr size_t kMaxMeshXmlDepth = 256;                 ///< COLLADA elements nested
constexpr double kMaxMeshCoordinate = 1e9;               ///< m, a vertex after unit, transforms and scale

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
/// own unit (COLLADA `<unit meter>`), then, in a scene (UpAxis::Y), the turn from a COLLADA
/// file's up axis onto +Y, then `scale` are applied to every vertex, once.
struct MeshData {
  std::string file;       ///< the path it was read from, as given to loadMesh
  Vec3 scale{1, 1, 1};    ///< the scale it was read with (per axis of the caller's frame)
  UpAxis up = UpAxis::Y;  ///< the up axis of the caller's frame
  /// COLLADA's `<up_axis>` as the file states it ("Y_UP", "Z_UP", "X_UP"); "" when it states
  /// none (or is STL or OBJ). With `up`, what `check` reports was done with it.
  std::string file_up_axis;
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
  /// kind MissingInput (exit 66) when the file does not exist, cannot be read or is not a regular
  /// file, InvalidInput (65) when it is not one of the formats, cannot be parsed, holds no
  /// triangles, a vertex that is not a finite float, is over the limits or `scale` has a zero or
  /// non-finite component; loc.file is the mesh file, the message says why (no "file:" in it;
  /// "line N: " first where the mesh file's line is known).
  Error error;
  bool ok() const { return mesh != nullptr; }
};

/// Reads a mesh file (format by its extension, .stl, .obj or .dae, and its contents; any other
/// is refused, and no other file is opened) and converts it to metres in the frame `up` names. `scale` multiplies
/// each axis of that frame (after the file's unit and up-axis turn); a negative product flips the winding back so triangles
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
