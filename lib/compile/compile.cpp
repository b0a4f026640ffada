// The compile step's walk: component graph -> Model. Each family lowers its own components
// (lib/components/<family>.cpp, through compile/context.h); this file only decides the order:
// settings, then the ComponentList in document order (clones last, so the bodies their
// originals join to exist outside the copy), then the cameras, then whole-model checks.
#include "simbob/compile.h"

#include "compile/context.h"

namespace simbob {

namespace {

void lowerComponentList(CompileContext& ctx) {
  std::vector<int> clones;
  for (const Link& l : ctx.scene.components) {
    if (l.comp < 0) continue;
    const Component& c = ctx.at(l.comp);
    switch (c.type->family) {
      case Family::Body:
        if (l.isRef()) break;  // listed elsewhere: lowered where it is written
        if (isClone(c))
          clones.push_back(l.comp);
        else
          lowerBody(ctx, l.comp, nullptr);
        break;
      case Family::GlobalSim:
        lowerGlobal(ctx, l.comp);
        break;
      case Family::Material:
      case Family::Skin:
      case Family::Model:
        break;  // listed to be referred to
      case Family::Geom:
      case Family::Joint:
      case Family::Pose:
      case Family::Motion:
      case Family::Inertia:
      case Family::Periphery:
      case Family::Controller:
      case Family::Camera:
      case Family::Struct:
        ctx.error(c, "a " + std::string(familyName(c.type->family)) + " cannot stand in the ComponentList");
        break;
    }
  }
  for (int ci : clones) lowerBody(ctx, ci, nullptr);
}

/// Every body and joint of the Model needs a key of its own: the trajectory names bodies by it.
void checkUniqueKeys(CompileContext& ctx) {
  NameTable seen;
  seen.reserve(ctx.model.bodies.size());
  for (size_t i = 0; i < ctx.model.bodies.size(); ++i) {
    const BodyDef& b = ctx.model.bodies[i];
    if (!seen.add(b.key, static_cast<int>(i)))
      ctx.diag.error(b.loc, "two bodies get the key '" + b.key +
                                "' (the second from here); give the copy a Key of "
                                "its own");
  }
}

/// The most moving bodies a bare URDF run steps with Step (docs/urdf.md, "The solver of a bare
/// run"): ODE's exact solve costs about the cube of the constraint rows, 0.02 ms a step for a
/// 6-link arm and 1.8 ms for DRC-Hubo's 52 bodies, against 0.19 ms with QuickStep.
constexpr size_t kBareUrdfStepBodies = 16;

/// A bare URDF run has no scene in which to choose a solver: unless --set chose one, it steps a
/// small robot, or one with a link QuickStep cannot hold at its joint, with Step (exact, as
/// MuJoCo's and DART's solvers are for an articulated robot) and a large robot with QuickStep.
void chooseBareUrdfSolver(const Scene& scene, Model* model) {
  if (!scene.bare_urdf || model->imports.empty()) return;
  if (scene.settings >= 0 && scene.at(scene.settings).slot("Solver").set) return;
  SolverSettings& s = model->settings;
  const size_t n = model->bodies.size();
  const int weak = n > kBareUrdfStepBodies ? firstBodyQuickStepCannotHold(*model) : -1;
  std::string why;
  if (n <= kBareUrdfStepBodies) {
    s.quickstep = false;
    s.solver_rule = "bare URDF run: " + std::to_string(n) + " moving bodies, at most " +
                    std::to_string(kBareUrdfStepBodies) + ": Step";
    why = "steps with Solver Step, ODE's exact solver (" + std::to_string(n) + " moving bodies, at most " +
          std::to_string(kBareUrdfStepBodies) + ")";
  } else if (weak >= 0) {
    const BodyDef& b = model->bodies[static_cast<size_t>(weak)];
    s.quickstep = false;
    s.solver_rule = "bare URDF run: QuickStep cannot hold body '" + b.key + "': Step";
    why = "steps with Solver Step, ODE's exact solver: QuickStep cannot hold body '" + b.key +
          "' at its joint (its smallest moment of inertia is far below m*d^2)";
  } else {
    s.quickstep = true;
    s.solver_rule = "bare URDF run: " + std::to_string(n) + " moving bodies, more than " +
                    std::to_string(kBareUrdfStepBodies) + ": QuickStep";
    why = "steps with Solver QuickStep, " + std::to_string(s.iterations) + " iterations (" + std::to_string(n) +
          " moving bodies, more than " + std::to_string(kBareUrdfStepBodies) + ", where Step's exact solve is slow)";
  }
  ImportReport& r = model->imports.front();
  r.notes.insert(r.notes.begin(), Error{ErrorKind::InvalidInput, r.loc,
                                        "a bare URDF run " + why + "; --set SceneSettings.Solver=" +
                                            (s.quickstep ? "Step" : "QuickStep") + " chooses the other"});
}

}  // namespace

bool compileScene(const Scene& scene, Model* model, Diagnostics& diag) {
  *model = Model{};
  // Room for a body per body component and a geom per geom component, the usual count, and a
  // little more (a ground's plane is a geom without a component): a large scene's lists would
  // otherwise double near their end and hold both copies at the peak.
  size_t body_comps = 0, geom_comps = 0;
  for (const Component& c : scene.comps) {
    body_comps += c.type->family == Family::Body;
    geom_comps += c.type->family == Family::Geom;
  }
  model->bodies.reserve(body_comps + body_comps / 32 + 16);
  model->geoms.reserve(geom_comps + geom_comps / 32 + 16);
  CompileContext ctx(scene, *model, diag);
  ctx.reserveBodies(body_comps);
  lowerSettings(ctx, scene.settings);
  // [0]: the registry's defaults, for geoms made without a material (none today: every body
  // and global has a Material parameter with a default).
  model->materials.push_back(MaterialDef{});
  model->skins.push_back(SkinDef{});  // [0]: what a model without a skin wears
  lowerComponentList(ctx);
  checkFixedUrdfRobots(ctx);
  chooseBareUrdfSolver(scene, model);
  for (const Link& l : scene.cameras)
    if (l.comp >= 0) lowerCamera(ctx, l.comp);
  checkUniqueKeys(ctx);
  return diag.ok() && !ctx.failedQuietly();
}

}  // namespace simbob
