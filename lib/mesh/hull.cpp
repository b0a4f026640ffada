// Convex hulls by qhull's reentrant C library (libqhull_r), laid out for ODE's dGeomConvex:
// qhull merges coplanar facets (its default 'C-0'), so a box comes out as six quadrilaterals;
// each face's vertices are put in counterclockwise order about its outward normal.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <utility>
#include <vector>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include "simbob/cr_math.h"
#include "simbob/mesh.h"

namespace simbob {

namespace {

// qhull's messages go to a memory stream, read back as the reason of a failure.
class MessageStream {
 public:
  MessageStream() : file_(open_memstream(&text_, &size_)) {}
  ~MessageStream() {
    if (file_) std::fclose(file_);
    std::free(text_);
  }
  MessageStream(const MessageStream&) = delete;
  MessageStream& operator=(const MessageStream&) = delete;
  FILE* file() const { return file_; }
  std::string firstLine() {
    if (!file_) return "";
    std::fflush(file_);
    std::string s(text_ ? text_ : "", size_);
    s = s.substr(0, s.find('\n'));
    return s;
  }

 private:
  char* text_ = nullptr;
  size_t size_ = 0;
  FILE* file_ = nullptr;
};

// Appends one facet to the hull: its plane and its vertices counterclockwise about the normal.
void addFacet(qhT* qh, facetT* facet, const std::vector<double>& coords, std::map<int, unsigned>* index,
              ConvexHull* hull) {
  const Vec3 n{facet->normal[0], facet->normal[1], facet->normal[2]};
  std::vector<int> ids;
  vertexT *vertex, **vertexp;
  FOREACHvertex_(facet->vertices) ids.push_back(qh_pointid(qh, vertex->point));
  Vec3 c{0, 0, 0};
  for (int id : ids)
    for (size_t k = 0; k < 3; ++k) c[k] += coords[static_cast<size_t>(id) * 3 + k] / static_cast<double>(ids.size());
  auto rel = [&](int id) {
    return Vec3{coords[static_cast<size_t>(id) * 3] - c[0], coords[static_cast<size_t>(id) * 3 + 1] - c[1],
                coords[static_cast<size_t>(id) * 3 + 2] - c[2]};
  };
  const Vec3 u = rel(ids[0]);
  const Vec3 w{n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
  std::vector<std::pair<double, int>> around;
  for (int id : ids) {
    const Vec3 r = rel(id);
    // crAtan2: libm's atan2 rounds a few angles differently on other CPUs, and two vertices a
    // last bit apart would sort the other way round there.
    around.emplace_back(crAtan2(r[0] * w[0] + r[1] * w[1] + r[2] * w[2], r[0] * u[0] + r[1] * u[1] + r[2] * u[2]), id);
  }
  std::sort(around.begin(), around.end());
  hull->planes.insert(hull->planes.end(), {n[0], n[1], n[2], -facet->offset});
  hull->polygons.push_back(static_cast<unsigned>(around.size()));
  for (const auto& [angle, id] : around) {
    auto [it, added] = index->emplace(id, static_cast<unsigned>(hull->pointCount()));
    if (added)
      for (size_t k = 0; k < 3; ++k) hull->points.push_back(coords[static_cast<size_t>(id) * 3 + k]);
    hull->polygons.push_back(it->second);
  }
}

}  // namespace

bool convexHull(const std::vector<Vec3>& points, ConvexHull* hull, std::string* problem) {
  *hull = ConvexHull{};
  if (points.size() < 4) {
    *problem = "its " + std::to_string(points.size()) + " points span no volume";
    return false;
  }
  std::vector<double> coords;
  coords.reserve(points.size() * 3);
  for (const Vec3& p : points) coords.insert(coords.end(), p.begin(), p.end());
  MessageStream messages;
  qhT qh_qh;
  qhT* qh = &qh_qh;
  qh_zero(qh, messages.file());
  char command[] = "qhull Pp";  // Pp: no precision warnings on the message stream
  const int code =
      qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False, command, nullptr, messages.file());
  bool ok = code == 0;
  if (ok) {
    std::map<int, unsigned> index;  // qhull point id -> hull point
    facetT* facet;
    FORALLfacets addFacet(qh, facet, coords, &index, hull);
  } else {
    const std::string why = messages.firstLine();
    *problem = why.find("QH6154") != std::string::npos || why.find("QH6271") != std::string::npos
                   ? "its points span no volume (they lie in one plane)"
                   : "qhull failed: " + why;
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  if (!ok) *hull = ConvexHull{};
  return ok;
}

}  // namespace simbob
