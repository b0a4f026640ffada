// Mesh files named by components (RCMeshModel, RCMeshGeom): found relative to the file the
// component is written in, read once per compile (CompileContext::mesh_cache), Y-up.
#include "compile/context.h"

namespace simbob {

int lowerMeshFile(CompileContext& ctx, const Component& c, const Slot& file_slot, const std::string& file,
                  const Vec3& scale) {
  if (file.empty()) {
    ctx.errorAt(file_slot, c, "parameter 'File' names no mesh file (.stl, .obj or .dae)");
    return -1;
  }
  std::string path = file;
  if (file[0] != '/') {
    const std::string& here = c.loc.file.str();
    const size_t slash = here.find_last_of('/');
    if (slash != std::string::npos) path = here.substr(0, slash + 1) + file;
  }
  const MeshLoad load = ctx.mesh_cache.load(path, scale, UpAxis::Y);
  if (!load.ok()) {
    ctx.errorAt(file_slot, c, "mesh '" + path + "': " + load.error.message, load.error.kind);
    return -1;
  }
  return ctx.meshIndex(load.mesh, file_slot.loc.line ? file_slot.loc : c.loc);
}

}  // namespace simbob
