// Layer boundary (CMakeLists.txt): only lib/physics may include ODE. This directory is searched
// before the system headers by every other target, so a stray #include <ode/ode.h> stops here.
#error \
    "layer boundary: only lib/physics may include ODE (<ode/ode.h>); expose what you need through include/simbob/physics.h"
