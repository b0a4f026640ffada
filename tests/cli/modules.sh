#!/usr/bin/env bash
# The one module simbob opens at run time, libsimbob_video.so (FFmpeg; docs/architecture.md):
# found only beside the program or in its install prefix (../lib/simbob/), never one folder up
# where others may plant one, and never when any user can write it (issue 43). Meshes and plots
# need no module: assimp and cairo are linked into the program (issue 44).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

BASIC="$REPO/tests/data/render/basic.xml"
BUILT="$(dirname "$SIMBOB")"

# A video that cannot be written is refused before the run, as a usage error (64), like a bad --fps.
check "a module planted in the folder above the program is not opened; beside it, it is"
mkdir -p plant/bin
cp "$SIMBOB" plant/bin/simbob
cat >plant/evil.c <<'C'
#include <stdio.h>
__attribute__((constructor)) static void planted(void) { FILE* f = fopen("PLANTED_RAN", "w"); if (f) fclose(f); }
C
cc -shared -fPIC -o plant/libsimbob_video.so plant/evil.c || fail "cc"
expect_status 64 plant/bin/simbob run "$BASIC" --duration 0.2 --out v.csv --video clip.mp4 --fps 10 --size 32x24
expect_no_file PLANTED_RAN
expect_match "not looked for above" "$LAST_ERR" \
  "libsimbob_video.so not found at .*plant/bin/libsimbob_video.so, .*plant/bin/../lib/simbob/libsimbob_video.so$"
ln -s "$BUILT/libsimbob_video.so" plant/bin/libsimbob_video.so
expect_status 0 plant/bin/simbob run "$BASIC" --duration 0.2 --out v.csv --video clip.mp4 --fps 10 --size 32x24
expect_no_file PLANTED_RAN
[ -s clip.mp4 ] || fail "no clip.mp4 from the module beside the program"

check "a module that any user can write is not opened"
cp "$BUILT/libsimbob_video.so" plant/bin/libsimbob_video_copy.so
chmod o+w plant/bin/libsimbob_video_copy.so
expect_status 64 env SIMBOB_VIDEO_MODULE="$PWD/plant/bin/libsimbob_video_copy.so" "$SIMBOB" run "$BASIC" \
  --duration 0.2 --out w.csv --video clip2.mp4 --fps 10 --size 32x24
expect_match "writable" "$LAST_ERR" "libsimbob_video_copy.so is not opened: it can be written by any user"

check "meshes and plots open no module: a program alone in its folder reads a mesh and draws a plot"
mkdir -p alone
cp "$SIMBOB" alone/simbob
expect_status 0 alone/simbob check "$REPO/scenes/mesh_drop.xml"
expect_status 0 alone/simbob run "$REPO/scenes/pendulum.xml" --duration 0.5 --out p.csv -q
expect_status 0 alone/simbob plot p.csv --out p.png
[ -s p.png ] || fail "no plot"
say "ok"
