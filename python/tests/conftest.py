"""Shared set-up of python/tests.

In the sanitizer build (scripts/sanitize.sh) ctest runs these tests in Debian's python3 with the
ASan runtime preloaded (LD_PRELOAD; tests/CMakeLists.txt) and names it in SIMBOB_ASAN_RUNTIME.
The preload is already in this interpreter, so it is taken out of the environment the tests' child
processes inherit: the simbob binary links its own copy of the runtime (two copies refuse to
start). child_env() puts it back for child Python interpreters that import the module.
"""
import os

ASAN_RUNTIME = os.environ.get("SIMBOB_ASAN_RUNTIME")
if ASAN_RUNTIME:
    os.environ.pop("LD_PRELOAD", None)


def child_env():
    """The environment for a child python3 that imports simbob."""
    env = dict(os.environ)
    if ASAN_RUNTIME:
        env["LD_PRELOAD"] = ASAN_RUNTIME
    return env
