// InertiaComponents (guide 6.10).
#include "components/families.h"

namespace simbob {

void registerInertias(Registry& r) {
  r.add({"RCGenericInertia",
         Family::Inertia,
         int(InertiaKind::Generic),
         {number("Mass", 1.0, "kg", "mass", Range::Positive),
          valueParam("Inertia", ValueType::Matrix, Matrix4{{0.01, 0, 0, 0, 0, 0.01, 0, 0, 0, 0, 0.01, 0, 0, 0, 0, 1}},
                     "kg m^2", "3x3 inertia tensor about the centre of mass (the body origin), body axes")},
         {},
         "Mass and inertia given explicitly."});
  r.add({"RCInertiaByGeom",
         Family::Inertia,
         int(InertiaKind::ByGeom),
         {number("Mass", -1.0, "kg", "mass; negative = computed from Density and the geometry"),
          number("Density", 1000.0, "kg/m^3", "used when Mass is negative", Range::Positive)},
         {},
         "Mass, centre of mass and inertia computed from the body's geoms (uniform density).",
         true});
}

}  // namespace simbob
