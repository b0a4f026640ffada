// The registry the tests load scenes with: the built-in types, registered once per test binary
// (the library itself keeps no global registry; `main` builds one and passes it down).
#pragma once

#include "simbob/registry.h"

inline const simbob::Registry& testRegistry() {
  static const simbob::Registry reg = [] {
    simbob::Registry r;
    simbob::registerBuiltins(r);
    return r;
  }();
  return reg;
}
