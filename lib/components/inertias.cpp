// InertiaComponents (guide 6.10): mass, centre of mass and inertia tensor of a mobile body.
#include <cmath>

#include "compile/context.h"
#include "compile/mass.h"
#include "components/families.h"
#include "simbob/transform.h"

namespace simbob {

namespace {

enum class InertiaKind { Generic, ByGeom };

constexpr ValueParam<double> kMass{"Mass"};
constexpr ValueParam<Matrix4> kInertia{"Inertia"};
constexpr ValueParam<double> kDensity{"Density"};

}  // namespace

void registerInertias(Registry& r) {
  r.add({"RCGenericInertia",
         Family::Inertia,
         int(InertiaKind::Generic),
         {number(kMass, 1.0, "kg", "mass", Range::Positive),
          valueParam(kInertia, ValueType::Matrix, Matrix4{{0.01, 0, 0, 0, 0, 0.01, 0, 0, 0, 0, 0.01, 0, 0, 0, 0, 1}},
                     "kg m^2", "3x3 inertia tensor about the centre of mass (the body origin), body axes")},
         {},
         "Mass and inertia given explicitly."});
  r.add({"RCInertiaByGeom",
         Family::Inertia,
         int(InertiaKind::ByGeom),
         {number(kMass, -1.0, "kg", "mass; negative = computed from Density and the geometry"),
          number(kDensity, 1000.0, "kg/m^3", "used when Mass is negative", Range::Positive)},
         {},
         "Mass, centre of mass and inertia computed from the body's geoms (uniform density).",
         true});
}

bool lowerInertia(CompileContext& ctx, const Link& l, const Component& owner, size_t first_geom, BodyDef* b) {
  if (l.comp < 0) {
    ctx.error(owner, "a mobile body needs an Inertia");
    return false;
  }
  const Component& c = ctx.at(l.comp);
  switch (static_cast<InertiaKind>(c.type->kind)) {
    case InertiaKind::Generic: {
      b->mass = c.get(kMass);
      const Matrix4& m = c.get(kInertia);
      b->inertia = {m.m[0], m.m[1], m.m[2], m.m[4], m.m[5], m.m[6], m.m[8], m.m[9], m.m[10]};
      const Mat3& i = b->inertia;
      double tol = 1e-9 * (std::fabs(i[0]) + std::fabs(i[4]) + std::fabs(i[8]));
      if (std::fabs(i[1] - i[3]) > tol || std::fabs(i[2] - i[6]) > tol || std::fabs(i[5] - i[7]) > tol) {
        ctx.errorAt(c.slotOf(kInertia), c, "parameter 'Inertia' must be symmetric");
        return false;
      }
      if (!isPositiveDefinite(i)) {
        ctx.errorAt(c.slotOf(kInertia), c, "parameter 'Inertia' is not positive definite");
        return false;
      }
      return true;
    }
    case InertiaKind::ByGeom: {
      MassProps total;
      for (size_t gi = first_geom; gi < ctx.model.geoms.size(); ++gi) {
        const GeomDef& g = ctx.model.geoms[gi];
        const MeshData* mesh = g.mesh >= 0 ? ctx.model.meshes[static_cast<size_t>(g.mesh)].data.get() : nullptr;
        if (g.shape == GeomShape::TriMesh && !mesh->closed) {
          // An open mesh bounds no volume: its "mass" would be whatever the gaps make of it.
          ctx.error(owner,
                    "RCInertiaByGeom: the triangle mesh '" + mesh->file + "' of body '" + owner.qkey +
                        "' is not closed, so it has no volume; use its hull (Hull=\"True\") or RCGenericInertia");
          return false;
        }
        MassProps p = geomMassProps(g, mesh);
        total.volume += p.volume;
        total.moment = add(total.moment, p.moment);
        for (int k = 0; k < 9; ++k) total.inertia[k] += p.inertia[k];
      }
      if (!(total.volume > 0)) {
        // Reported at the body: a left-out Inertia is a shared default with no place of its own.
        ctx.error(owner, "RCInertiaByGeom needs a geom with volume on body '" + owner.qkey +
                             "' (give it a Geom or use RCGenericInertia)");
        return false;
      }
      double mass = c.get(kMass);
      double density = mass < 0 ? c.get(kDensity) : mass / total.volume;
      if (mass == 0) {
        ctx.errorAt(c.slotOf(kMass), c, "parameter 'Mass' must be > 0 (or negative to use Density)");
        return false;
      }
      b->mass = density * total.volume;
      // ODE wants the inertia about the centre of mass: undo the parallel-axis term of c.
      Vec3 cm = scale(total.moment, 1.0 / total.volume);
      b->com = cm;
      double c2 = dot(cm, cm);
      for (size_t i = 0; i < 3; ++i)
        for (size_t j = 0; j < 3; ++j)
          b->inertia[i * 3 + j] =
              density * (total.inertia[i * 3 + j] - total.volume * ((i == j ? c2 : 0) - cm[i] * cm[j]));
      if (!isPositiveDefinite(b->inertia)) {
        ctx.error(c, "the inertia computed from the geometry is degenerate");
        return false;
      }
      return true;
    }
  }
  return false;
}

}  // namespace simbob
