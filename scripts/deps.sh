#!/usr/bin/env bash
# Installs simbob's dependencies from Debian 12's packages (only what is missing).
#   scripts/deps.sh run    what building and running simbob needs (build.sh, demo.sh)
#   scripts/deps.sh test   that plus what the tests and style checks need (test.sh, sanitize.sh)
set -euo pipefail

RUN_PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libode-dev            # physics
  libeigen3-dev         # rotations and inertia tensors in the compile step
  libpugixml-dev        # XML scenes
  libcli11-dev          # command line
  nlohmann-json3-dev    # run summaries and reports
  libcairo2-dev         # trajectory plots (PNG, SVG)
  libpng-dev libavformat-dev libavcodec-dev libavutil-dev libswscale-dev  # frames and videos (lib/image)
  libgl-dev libegl-dev libosmesa6-dev  # GL, EGL and OSMesa headers (lib/render; opened with dlopen)
  libegl-mesa0 libgl1-mesa-dri libosmesa6  # the back ends themselves: Mesa's llvmpipe without a GPU
  libjs-three           # three.js, inlined into `simbob view` pages at run time (lib/view)
  libassimp-dev libqhull-dev  # mesh files (STL, OBJ, DAE) and their convex hulls (lib/mesh)
  libmpfr-dev           # correctly rounded sin, cos and log: the same bits on every CPU (lib/compile/cr_math.cpp)
  git                   # simbob.revision: `git describe` when CMake configures (cmake/git_revision.cmake; docs/ci.md)
  ccache                # rebuilds compile only what changed (scripts/build.sh; the CI recipes keep its cache)
)
TEST_PACKAGES=(
  catch2                # unit tests
  python3               # test helpers (tests/cli/scene_expectations.py)
  valgrind              # memcheck of the example scenes (tests/cli/valgrind.sh)
  clang libclang-rt-14-dev  # sanitizer and fuzz builds (scripts/sanitize.sh, scripts/fuzz.sh)
  clang-format clang-tidy   # scripts/check-style.sh
  ffmpeg                # ffprobe checks the recorded videos (tests/image/ffprobe.sh)
  slurmctld slurmd slurm-client munge  # a real one-node Slurm cluster (tests/cluster/slurm_*.sh)
  procps iproute2 util-linux  # its daemons' job steps (pgrep), listening ports (ss), a UTS namespace (unshare)
  file dpkg-dev         # cpack -G DEB: CPackDeb finds the ELF files with file, Depends with dpkg-shlibdeps
  pybind11-dev python3-dev python3-numpy python3-pytest  # the optional Python module (python/) and its tests
  chromium chromium-driver python3-selenium  # view pages driven in headless Chromium (tests/view/)
  libxml2-utils         # xmllint validates the JUnit reports against the schemas in tests/ci (docs/ci.md)
  python3-yaml          # tests/ci/recipes.py reads the CI recipes (.github/workflows, .gitlab-ci.yml)
  dart-doc              # real URDF robots with STL and DAE meshes (/usr/share/doc/dart/data/urdf; tests/urdf, tests/mesh)
)

case "${1:-}" in
  run) packages=("${RUN_PACKAGES[@]}") ;;
  test) packages=("${RUN_PACKAGES[@]}" "${TEST_PACKAGES[@]}") ;;
  *) echo "usage: scripts/deps.sh run|test" >&2; exit 64 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "simbob: installing ${missing[*]}" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# The browser tests: chromedriver reaches Chromium's DevTools at "localhost". Every Debian install
# maps it in /etc/hosts; a minimal chroot or container may have no /etc/hosts at all. Then the
# standard line is added (nothing else changes, and nothing listens beyond 127.0.0.1).
if [ "${1:-}" = test ] && ! getent hosts localhost >/dev/null; then
  echo "simbob: localhost does not resolve; adding '127.0.0.1 localhost' to /etc/hosts" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  echo "127.0.0.1 localhost" | $SUDO tee -a /etc/hosts >/dev/null
fi
