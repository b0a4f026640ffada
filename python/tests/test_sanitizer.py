"""In the sanitizer build (ctest python.pytest from build-fuzz/), the module's tests run with
AddressSanitizer's runtime in this interpreter: this test proves it, so that a sanitizer stage
without the preload cannot pass unnoticed."""

import pytest

import simbob
from conftest import ASAN_RUNTIME


def test_the_asan_runtime_is_loaded_in_the_sanitizer_build():
    if not ASAN_RUNTIME:
        pytest.skip("not the sanitizer build (SIMBOB_ASAN_RUNTIME unset)")
    with open("/proc/self/maps") as f:
        maps = f.read()
    assert ASAN_RUNTIME in maps
    # The module is instrumented: it needs the runtime's entry points (a plain module would not).
    with open(simbob._simbob.__file__, "rb") as f:
        assert b"__asan_report_load8" in f.read()
