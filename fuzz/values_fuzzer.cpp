// libFuzzer target. Values: parseValue for every ValueType (Enum/Bitmask with every table);
// formatValue then parse again must give the same value.
// The work is in fuzz/entry.h, shared with tests/fuzz/fuzz_regression_test.cpp.
#include "fuzz/entry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return simbob::fuzz::fuzzOne(simbob::fuzz::runValues, data, size);
}
