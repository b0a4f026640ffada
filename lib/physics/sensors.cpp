// Proximity sensors (guide 6.11.4): geoms that only detect. Their geoms sit in a space of their
// own, so they never reach the contact callback and the collision space reports its pairs in the
// same order as without them; after every step each sensor geom is collided with the collision
// space, and a sensor touches when one of its geoms meets a geom of another body.
#include "world_impl.h"

namespace simbob {

namespace {

struct Probe {
  dGeomID sensor;
  bool touching = false;
};

void probePair(void* data, dGeomID a, dGeomID b) {
  Probe& p = *static_cast<Probe*>(data);
  if (p.touching) return;
  dGeomID other = a == p.sensor ? b : a;
  dBodyID own = dGeomGetBody(p.sensor);
  dBodyID body = dGeomGetBody(other);
  // Its own body, and static geoms for a static sensor, are not "another body"; neither are the
  // bodies joined to its body (they do not collide with it either).
  if (own == body) return;
  if (own && body && dAreConnected(own, body)) return;
  dContactGeom c;
  if (dCollide(p.sensor, other, 1, &c, sizeof(dContactGeom)) > 0) p.touching = true;
}

}  // namespace

void createSensors(WorldImpl& im, const Model& model) {
  im.sensors.reserve(model.sensors.size());
  for (const SensorDef& d : model.sensors) {
    SensorState s;
    for (int gi : d.geoms) s.geoms.push_back(im.geoms[static_cast<size_t>(gi)]);
    im.sensors.push_back(std::move(s));
  }
  if (!im.sensors.empty()) updateSensors(im);
}

void updateSensors(WorldImpl& im) {
  for (SensorState& s : im.sensors) {
    s.touching = false;
    for (dGeomID g : s.geoms) {
      Probe p{g};
      dSpaceCollide2(g, reinterpret_cast<dGeomID>(im.space), &p, &probePair);
      if (p.touching) {
        s.touching = true;
        break;
      }
    }
  }
}

}  // namespace simbob
