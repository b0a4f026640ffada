// libFuzzer target. URDF files, read as `simbob check robot.urdf` reads one (a bare robot over
// the ground, with the checks' warnings): loaded, or refused at a line; never an internal error.
// The work is in fuzz/entry.h, shared with tests/fuzz/fuzz_regression_test.cpp.
#include "fuzz/entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return simbob::fuzz::fuzzOne(simbob::fuzz::runUrdf, data, size);
}
