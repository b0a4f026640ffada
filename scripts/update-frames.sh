#!/usr/bin/env bash
# Re-bless the reference frames of the render tests (golden/frames/*.png) from this build and
# back end (default EGL). Look at every changed image before committing it: the tests only
# know the references are what you blessed.
#   scripts/update-frames.sh [egl|osmesa]
set -euo pipefail
cd "$(dirname "$0")/.."
gl=${1:-egl}
cmake --build build --target simbob_render_tests
SIMBOB_GL="$gl" SIMBOB_BLESS_FRAMES=1 build/tests/simbob_render_tests
git status --short golden/frames
