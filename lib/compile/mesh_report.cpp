// What `simbob check` says about a scene's meshes (describeMeshes, simbob/compile.h).
#include <string>
#include <vector>

#include "simbob/compile.h"
#include "simbob/values.h"

namespace simbob {

std::vector<std::string> describeMeshes(const Model& model) {
  std::vector<size_t> hulls(model.meshes.size(), 0), trimeshes(model.meshes.size(), 0), visuals(model.meshes.size(), 0);
  for (const GeomDef& g : model.geoms) {
    if (g.mesh < 0) continue;
    (g.shape == GeomShape::ConvexHull ? hulls : trimeshes)[static_cast<size_t>(g.mesh)]++;
  }
  for (const VisualDef& v : model.visuals)
    if (v.shape == VisualDef::Mesh) visuals[static_cast<size_t>(v.mesh)]++;
  std::vector<std::string> out;
  for (size_t i = 0; i < model.meshes.size(); ++i) {
    const MeshData& m = *model.meshes[i].data;
    std::string line = "mesh " + m.file + " (scale " + formatApprox(m.scale[0]) + " " + formatApprox(m.scale[1]) + " " +
                       formatApprox(m.scale[2]) + "): " + countOf(m.vertices.size(), "vertex", "vertices") + ", " +
                       countOf(m.triangles.size(), "triangle", "triangles") + (m.closed ? ", closed" : ", not closed");
    if (hulls[i])
      line += "; hull of " + countOf(hulls[i], "geom", "geoms") + " (" +
              countOf(m.hull.pointCount(), "point", "points") + ", " + countOf(m.hull.faceCount(), "face", "faces") +
              ")";
    if (trimeshes[i]) line += "; triangle mesh of " + countOf(trimeshes[i], "geom", "geoms");
    if (visuals[i]) line += "; drawn by " + countOf(visuals[i], "model", "models");
    // A COLLADA file that states its up axis: what was done with it (docs/meshes.md).
    if (!m.file_up_axis.empty())
      line += "; its up_axis " + m.file_up_axis +
              (m.up == UpAxis::Z          ? " not applied (a URDF's mesh: vertices as written, as ROS reads them)"
               : m.file_up_axis == "Y_UP" ? " is the scene's"
                                          : " turned onto the scene's +Y");
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace simbob
