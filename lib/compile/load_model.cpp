// The one load path: scene text -> component graph -> Model (see simbob/compile.h).
#include "simbob/compile.h"

namespace simbob {

bool loadModel(const LoadRequest& request, const Registry& reg, Model* model, LoadReport* report) {
  Diagnostics& d = report->diagnostics;
  Scene scene;
  const bool read = request.text
                        ? loadSceneFromText(*request.text, request.path, sceneFormatOf(request.path), reg, &scene, d)
                        : loadScene(request.path, reg, &scene, d);
  const bool loaded = read && applyOverrides(scene, request.overrides, d);
  report->files = scene.files;
  report->content_hash = scene.content_hash;
  // The graph of a scene that failed to load is still consistent (bad links are empty).
  const bool compiled =
      (loaded || (request.collect_all && !scene.comps.empty())) && compileScene(scene, model, d) && loaded;
  if (compiled && request.lint) lintModel(*model, d, request.dt);
  return compiled;
}

}  // namespace simbob
