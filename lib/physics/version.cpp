#include <ode/ode.h>

#include "simbob/physics.h"

namespace simbob {

std::string physicsVersion() {
  // dGetConfiguration needs an initialised library; repeated init calls are reference-counted.
  dInitODE2(0);
  return dGetConfiguration();  // "ODE ODE_double_precision ..."
}

}  // namespace simbob
