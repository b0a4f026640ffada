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
  for (const Link& l : scene.cameras)
    if (l.comp >= 0) lowerCamera(ctx, l.comp);
  checkUniqueKeys(ctx);
  return diag.ok() && !ctx.failedQuietly();
}

}  // namespace simbob
