// The compile step: component graph -> Model. Resolves frames (global/local poses), joints of
// constructions, imports, clones, inertia, materials and settings; validates everything ODE
// would otherwise abort on. No ODE here.
#pragma once

#include <string>
#include <vector>

#include "simbob/graph.h"
#include "simbob/model.h"
#include "simbob/overrides.h"

namespace simbob {

/// Fill *model from scene. Returns false (with messages in diag) if the scene is invalid.
bool compileScene(const Scene& scene, Model* model, Diagnostics& diag);

/// Warnings about legal scenes that make ODE unstable or wrong (`simbob check`): mass ratios
/// across joints, bodies thin and fast enough to tunnel, a step too large for the fastest
/// pendulum, joints far from their bodies, bodies overlapping at t = 0. Each says why and what
/// to change. `dt` is the step the run takes (0: the scene's MaxTimeStep).
void lintModel(const Model& model, Diagnostics& diag, double dt = 0);

/// One line per mesh of the model (`simbob check`): its file and scale, vertices and triangles,
/// whether it is closed, and what uses it: hulls (with their points and faces), triangle meshes,
/// models. "mesh cube.stl (scale 0.001 0.001 0.001): 8 vertices, 12 triangles, closed; hull of
/// 1 geom (8 points, 6 faces)".
std::vector<std::string> describeMeshes(const Model& model);

/// The largest step that lintModel accepts without a step-size or tunnelling warning, in s
/// (infinity when nothing in the scene limits it): what a diverged run recommends.
double recommendedStep(const Model& model);

/// The checks of lintModel usually know why a run diverged: appends "; likely cause: " and the
/// first of their warnings about the body that ran away or the joint that came apart (indices
/// into Model::bodies and Model::joints, -1 for none), if any.
void explainDivergence(const Model& model, int body, int joint, Error* error);

/// What to load: a scene file, or its text in memory, and what is done to it.
struct LoadRequest {
  std::string path;                   ///< the scene file (XML, INI by extension); with `text`, its name
  const std::string* text = nullptr;  ///< the scene text, or null to read `path`
  std::vector<Override> overrides;    ///< applied to the graph before compiling (--set, a DocumentIni)
  /// `simbob check`: a scene that failed to load is compiled too (a failed load still leaves a
  /// consistent graph), so that one pass reports every problem the compile step can still see.
  bool collect_all = false;
  bool lint = false;  ///< add lintModel's warnings, judged at the step `dt` (0: MaxTimeStep)
  double dt = 0;
};

/// What loading read and found.
struct LoadReport {
  std::vector<std::string> files;  ///< every file read: the scene first, then its imports
  std::string content_hash;        ///< hash of their bytes (fnv1a64w, docs/formats.md), hex
  Diagnostics diagnostics;         ///< every error (file:line) and warning
};

/// The one way a scene becomes a Model, for every command, the Simulation API and Python: read
/// the file or text, apply the overrides, compile, and (when asked) add the checks' warnings.
/// False when the scene cannot run (its errors are in report->diagnostics).
bool loadModel(const LoadRequest& request, const Registry& reg, Model* model, LoadReport* report);

}  // namespace simbob
