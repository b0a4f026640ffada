// Contacts: the near callback of dSpaceCollide. Colliding geom pairs get up to MaxContacts
// contact joints with the material rules of the Simulator Bob guide 7.1.
#include <algorithm>
#include <cstdint>

#include "world_impl.h"

namespace simbob {

namespace {

const GeomInfo& infoOf(const WorldImpl& im, dGeomID g) {
  return im.geomInfo[static_cast<size_t>(reinterpret_cast<intptr_t>(dGeomGetData(g)))];
}

void collidePair(WorldImpl& im, dGeomID g1, dGeomID g2) {
  dBodyID b1 = dGeomGetBody(g1);
  dBodyID b2 = dGeomGetBody(g2);
  // Two geoms of one body, or two static geoms (both bodies null): nothing to resolve.
  if (b1 == b2) return;
  // Bodies joined by a joint do not collide with each other (the usual ODE idiom).
  if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;
  const GeomInfo& i1 = infoOf(im, g1);
  const GeomInfo& i2 = infoOf(im, g2);
  // Sensors create no contact joints (their geoms are in a space of their own: never reached).
  if (i1.sensor || i2.sensor) return;
  // The links of one URDF robot (without SelfCollision) do not collide with each other.
  if (i1.group >= 0 && i1.group == i2.group) return;

  const int maxContacts = static_cast<int>(im.contactBuffer.size());
  const int n = dCollide(g1, g2, maxContacts, &im.contactBuffer[0].geom, sizeof(dContact));
  if (n <= 0) return;

  // Guide 7.1: the larger friction, the larger bounceness, the smaller MinBounceVel.
  const double mu = std::max(i1.friction, i2.friction);
  const double bounce = std::max(i1.bounceness, i2.bounceness);
  const double bounceVel = std::min(i1.minBounceVel, i2.minBounceVel);
  for (int k = 0; k < n; ++k) {
    dContact& c = im.contactBuffer[static_cast<size_t>(k)];
    // Approx1: Coulomb friction with the friction pyramid, bound = mu * normal force.
    // No SoftERP/SoftCFM: without them ODE applies the world's ERP and CFM to contacts,
    // which are exactly the settings' values, so the flags would change nothing.
    c.surface.mode = dContactBounce | dContactApprox1;
    c.surface.mu = mu;
    c.surface.bounce = bounce;
    c.surface.bounce_vel = bounceVel;
    dJointID j = dJointCreateContact(im.world, im.contactGroup, &c);
    dJointAttach(j, b1, b2);
    ++im.lastContacts;
  }
}

void nearCallback(void* data, dGeomID g1, dGeomID g2) { collidePair(*static_cast<WorldImpl*>(data), g1, g2); }

}  // namespace

void collide(WorldImpl& im) {
  im.lastContacts = 0;
  if (dSpaceGetClass(im.space) == dHashSpaceClass) {
    im.hashPairs.collide(im.space, &im, &nearCallback);  // the same pairs in the same order, faster
  } else {
    dSpaceCollide(im.space, &im, &nearCallback);
  }
}

}  // namespace simbob
