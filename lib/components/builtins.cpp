// The one list of built-in families. Order here is the order of `simbob types`.
#include "components/families.h"

namespace simbob {

bool registerBuiltins(Registry& r) {
  registerSettings(r);
  registerPoses(r);
  registerMotions(r);
  registerMaterials(r);
  registerInertias(r);
  registerGeoms(r);
  registerModelGeoms(r);
  registerSkins(r);
  registerModels(r);
  registerBodies(r);
  registerClones(r);
  registerUrdfImport(r);
  registerJoints(r);
  registerGlobals(r);
  registerPeripheries(r);
  registerRangeSensors(r);
  registerImuSensors(r);
  registerEncoders(r);
  registerCameraSensors(r);
  registerControllers(r);
  registerCameras(r);
  return r.problems().empty();
}

}  // namespace simbob
