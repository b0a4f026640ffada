// Links only simbob_core: if the core used an ODE (or cairo) symbol, this program would not link.
// Built by default, so "the core library does not link ODE" is a build fact, not a comment.
#include <cstdio>

#include "simbob/compile.h"
#include "simbob/graph.h"
#include "simbob/registry.h"

int main() {
  simbob::Registry reg;
  if (!simbob::registerBuiltins(reg)) return 1;
  simbob::Scene scene;
  simbob::Model model;
  simbob::Diagnostics diag;
  const char* text =
      "<Simulation><ComponentList><RCMobileRigidBody Key=\"B\"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody>"
      "</ComponentList></Simulation>";
  if (!simbob::loadSceneFromText(text, "core_only.xml", simbob::Format::Xml, reg, &scene, diag)) return 1;
  if (!simbob::compileScene(scene, &model, diag)) {
    for (const simbob::Error& e : diag.errors()) std::fprintf(stderr, "%s\n", e.str().c_str());
    return 1;
  }
  std::printf("%zu body, %zu types\n", model.bodies.size(), reg.types().size());
  return model.bodies.size() == 1 ? 0 : 1;
}
