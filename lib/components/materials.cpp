// MaterialComponents (guide 6.7). Contact pairs combine max friction, max bounceness,
// min MinBounceVel (guide 7.1); the combination happens in the physics layer.
#include "components/families.h"

namespace simbob {

void registerMaterials(Registry& r) {
  r.add({"RCGenericMaterial",
         Family::Material,
         int(MaterialKind::Generic),
         {number("Friction", 0.5, "", "Coulomb friction coefficient", Range::NonNegative),
          number("Bounceness", 0.0, "", "restitution, 0 = no bounce, 1 = elastic", Range::Unit),
          number("MinBounceVel", 0.1, "m/s", "slower impacts do not bounce", Range::NonNegative)},
         {},
         "Contact properties of a body."});
  r.addMacro({"DefaultMaterial", Family::Material, "RCGenericMaterial", {}, "the default material"});
}

}  // namespace simbob
