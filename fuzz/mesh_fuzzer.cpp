// libFuzzer target. Mesh files: the first byte picks .stl, .obj or .dae and the frame; the rest
// is the file, read by loadMesh (the byte scan, assimp, qhull): read within every documented
// limit, or refused with a message.
// The work is in fuzz/entry.h, shared with tests/fuzz/fuzz_regression_test.cpp.
#include "fuzz/entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return simbob::fuzz::fuzzOne(simbob::fuzz::runMesh, data, size);
}
