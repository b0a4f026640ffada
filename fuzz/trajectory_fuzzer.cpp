// libFuzzer target. Trajectory CSV: readTrajectory from a per-process temp file; a trajectory that
// reads is compared with itself.
// The work is in fuzz/entry.h, shared with tests/fuzz/fuzz_regression_test.cpp.
#include "fuzz/entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return simbob::fuzz::fuzzOne(simbob::fuzz::runTrajectory, data, size);
}
