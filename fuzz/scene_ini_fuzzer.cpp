// libFuzzer target. Scene INI: loadSceneFromText(Format::Ini), then compileScene and
// writeScene in both formats; what the writer writes must load again and be written the same.
// The work is in fuzz/entry.h, shared with tests/fuzz/fuzz_regression_test.cpp.
#include "fuzz/entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return simbob::fuzz::fuzzOne(simbob::fuzz::runSceneIni, data, size);
}
