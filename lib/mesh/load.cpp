// Mesh files: read here (a regular file, within the size limit), checked by scan.cpp before
// assimp sees them, handed as bytes to assimp (assimp_read.cpp), and the rest is done here:
// limits, scale, bounds, closedness, masses and the convex hull. STL and OBJ carry no unit or up
// axis: their numbers are the caller's.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "mesh/assimp_read.h"
#include "mesh/scan.h"
#include "simbob/mesh.h"
#include "simbob/tool/platform.h"

// Weak: defined only where assimp_read.cpp is linked in (the Python module); null elsewhere.

namespace simbob {

namespace {

Error meshError(ErrorKind kind, const std::string& path, std::string message) {
  return Error{kind, SourceLoc{FileName(path), 0}, std::move(message)};
}

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

/// The file's bytes, or an error: MissingInput when it cannot be opened or is not a regular
/// file (a FIFO would block, a device never end), InvalidInput over the size limit.
bool readBytes(const std::string& path, std::string* bytes, Error* error) {
  // O_NONBLOCK: opening a FIFO does not wait for a writer; the fstat below then refuses it.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    *error = meshError(ErrorKind::MissingInput, path, std::string("cannot read the mesh: ") + std::strerror(errno));
    return false;
  }
  struct stat st {};
  bool ok = ::fstat(fd, &st) == 0;
  if (!ok) {
    *error = meshError(ErrorKind::MissingInput, path, std::string("cannot read the mesh: ") + std::strerror(errno));
  } else if (!S_ISREG(st.st_mode)) {
    *error = meshError(ErrorKind::MissingInput, path, "cannot read the mesh: not a regular file");
    ok = false;
  } else if (static_cast<uint64_t>(st.st_size) > kMaxMeshFileBytes) {
    *error = meshError(ErrorKind::InvalidInput, path,
                       "is " + count(static_cast<size_t>(st.st_size)) + " bytes, more than the limit of " +
                           count(kMaxMeshFileBytes) + " (256 MiB)");
    ok = false;
  } else {
    bytes->resize(static_cast<size_t>(st.st_size));
    size_t done = 0;
    while (ok && done < bytes->size()) {
      const ssize_t n = ::read(fd, bytes->data() + done, bytes->size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        *error = meshError(ErrorKind::MissingInput, path, std::string("cannot read the mesh: ") + std::strerror(errno));
        ok = false;
      } else if (n == 0) {
        bytes->resize(done);  // shrank while read: what is there
        break;
      } else {
        done += static_cast<size_t>(n);
      }
    }
  }
  ::close(fd);
  return ok;
}

}  // namespace

MeshLoad loadMesh(const std::string& path, const Vec3& scale, UpAxis up) {
  MeshLoad out;
  for (double s : scale)
    if (!std::isfinite(s) || s == 0) {
      out.error = meshError(ErrorKind::InvalidInput, path, "scale needs three finite, non-zero factors");
      return out;
    }
  std::string bytes;
  if (!readBytes(path, &bytes, &out.error)) return out;
  const MeshScan scan = scanMeshFile(path, bytes, kMaxMeshTriangles);
  if (!scan.problem.empty()) {
    out.error = meshError(ErrorKind::InvalidInput, path, scan.problem);
    return out;
  }
  MeshRequest request;
  request.data = bytes.data();
  request.size = bytes.size();
  request.format = scan.format;
  request.ignore_up_axis = up == UpAxis::Z;
  request.max_triangles = kMaxMeshTriangles;
  MeshFile file;
  if (!readWithAssimp(request, &file)) {
    out.error = meshError(ErrorKind::InvalidInput, path, "not a mesh assimp can read: " + file.error);
    return out;
  }
  bytes = std::string();
  if (file.faces > kMaxMeshTriangles) {
    out.error = meshError(ErrorKind::InvalidInput, path,
                          "has more than " + count(kMaxMeshTriangles) + " triangles, the limit (after instancing)");
    return out;
  }
  if (file.vertices.size() > kMaxMeshVertices) {
    out.error = meshError(
        ErrorKind::InvalidInput, path,
        "has " + count(file.vertices.size()) + " vertices, more than the limit of " + count(kMaxMeshVertices));
    return out;
  }
  if (file.triangles.empty()) {
    out.error = meshError(ErrorKind::InvalidInput, path, "holds no triangles");
    return out;
  }
  auto data = std::make_shared<MeshData>();
  data->file = path;
  data->scale = scale;
  data->up = up;
  data->file_up_axis = scan.up_axis;
  data->vertices = std::move(file.vertices);
  data->triangles = std::move(file.triangles);
  for (Vec3& v : data->vertices) {
    for (size_t k = 0; k < 3; ++k) {
      v[k] *= scale[k];
      // Node transforms and scale can take finite numbers out of range; qhull and ODE must not see them.
      if (!(std::fabs(v[k]) <= kMaxMeshCoordinate)) {
        out.error = meshError(ErrorKind::InvalidInput, path,
                              std::string("a vertex ") + (std::isfinite(v[k]) ? "lies beyond 1e9 m" : "is not finite") +
                                  " after the file's transforms and the scale");
        return out;
      }
    }
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
