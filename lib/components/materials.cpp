// MaterialComponents (guide 6.7). Contact pairs combine max friction, max bounceness,
// min MinBounceVel (guide 7.1); the combination happens in the physics layer (contacts.cpp).
#include "compile/context.h"
#include "components/families.h"

namespace simbob {

namespace {

enum class MaterialKind { Generic };

constexpr ValueParam<double> kFriction{"Friction"};
constexpr ValueParam<double> kBounceness{"Bounceness"};
constexpr ValueParam<double> kMinBounceVel{"MinBounceVel"};

}  // namespace

void registerMaterials(Registry& r) {
  r.add({"RCGenericMaterial",
         Family::Material,
         int(MaterialKind::Generic),
         {number(kFriction, 0.5, "", "Coulomb friction coefficient", Range::NonNegative),
          number(kBounceness, 0.0, "", "restitution, 0 = no bounce, 1 = elastic", Range::Unit),
          number(kMinBounceVel, 0.1, "m/s", "slower impacts do not bounce", Range::NonNegative)},
         {},
         "Contact properties of a body."});
  r.addMacro({"DefaultMaterial", Family::Material, "RCGenericMaterial", {}, "the default material"});
}

int lowerMaterial(CompileContext& ctx, const Link& l) {
  if (l.comp < 0) return 0;
  const Component& c = ctx.at(l.comp);
  MaterialDef m;
  switch (static_cast<MaterialKind>(c.type->kind)) {
    case MaterialKind::Generic:
      m.key = c.qkey;
      m.friction = c.get(kFriction);
      m.bounceness = c.get(kBounceness);
      m.min_bounce_vel = c.get(kMinBounceVel);
      break;
  }
  return addMaterial(ctx, m);
}

int addMaterial(CompileContext& ctx, const MaterialDef& m) {
  // Materials with equal properties share one entry: contacts only see the numbers.
  std::vector<MaterialDef>& all = ctx.model.materials;
  for (size_t i = 1; i < all.size(); ++i) {
    const MaterialDef& o = all[i];
    if (o.friction == m.friction && o.bounceness == m.bounceness && o.min_bounce_vel == m.min_bounce_vel &&
        o.gazebo == m.gazebo && o.friction2 == m.friction2 && o.fdir1 == m.fdir1 && o.kp == m.kp && o.kd == m.kd &&
        o.min_depth == m.min_depth && o.max_vel == m.max_vel && o.max_contacts == m.max_contacts)
      return static_cast<int>(i);
  }
  all.push_back(m);
  return static_cast<int>(all.size() - 1);
}

}  // namespace simbob
