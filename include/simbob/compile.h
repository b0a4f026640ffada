// The compile step: component graph -> Model. Resolves frames (global/local poses), joints of
// constructions, imports, clones, inertia, materials and settings; validates everything ODE
// would otherwise abort on. No ODE here.
#pragma once

#include <string>
#include <vector>

#include "simbob/graph.h"
#include "simbob/model.h"

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

/// A diverged run's error names its body ('KEY'); the checks of lintModel usually know why it
/// diverged: appends "; likely cause: " and the first of their warnings about that body, if any.
void explainDivergence(const Model& model, Error* error);

}  // namespace simbob
