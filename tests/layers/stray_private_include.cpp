// Deliberately wrong: CLI code that reaches for a library-private header (a component family's
// parameter names). cmd/ sees only the public headers of include/simbob; the layer check builds
// this file with the CLI's include paths and expects the build to fail (tests/layers/check.cmake).
#include "components/families.h"

int strayPrivateUse() { return static_cast<int>(sizeof(simbob::kTextureFolderParam)); }
