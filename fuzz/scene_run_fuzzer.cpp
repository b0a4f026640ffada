// libFuzzer target. Scene XML run through a Run for a few steps, on 1 and on 3 threads
// (fuzz/entry.h, runSceneSteps): whatever loads and compiles must step, or stop with a message,
// without a crash or a hang, and end in the same bits on both.
#include "fuzz/entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return simbob::fuzz::fuzzOne(simbob::fuzz::runSceneSteps, data, size);
}
