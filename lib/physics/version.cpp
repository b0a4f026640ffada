#include <ode/ode.h>

#include <mutex>

#include "world_impl.h"

namespace simbob {

std::string physicsVersion() {
  // dGetConfiguration needs an initialised library; repeated init calls are reference-counted.
  std::lock_guard<std::mutex> lock(odeMutex());  // dInitODE2's counter is not thread-safe
  dInitODE2(0);
  return dGetConfiguration();  // "ODE ODE_double_precision ..."
}

std::string odeVersion() { return dODE_VERSION; }

}  // namespace simbob
