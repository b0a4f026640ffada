// Deliberately wrong: core code that reaches for ODE. The layer check builds this file with the
// core's include paths and expects the build to fail (tests/layers/check.cmake).
#include <ode/ode.h>

int strayOdeUse() { return static_cast<int>(sizeof(dReal)); }
