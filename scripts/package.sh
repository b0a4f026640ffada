#!/usr/bin/env bash
# Builds simbob (scripts/build.sh; extra arguments go to cmake) and its Debian package,
# build/simbob_VERSION_ARCH.deb, for `apt install ./simbob_*.deb` on Debian 12 nodes
# (docs/install.md, "Installing on cluster nodes"). dpkg-shlibdeps (dpkg-dev, part of build-essential)
# works out the package's Depends.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh "$@"
cd build
cpack -G DEB
ls -1 "$PWD"/simbob_*.deb
