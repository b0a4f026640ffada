#!/usr/bin/env bash
# `simbob --version` names the version and the git revision (cmake/git_revision.cmake):
#   - the binary prints "simbob VERSION (git REVISION)";
#   - the module yields `git describe --always --dirty` in a checkout, "-dirty" after an edit,
#     "unknown" in a plain directory (a release tarball) and in a tarball unpacked inside some
#     other git repository, and a packager's -DSIMBOB_GIT_REVISION wins.
#
#   bash tests/cluster/version.sh /path/to/simbob /path/to/repo /path/to/build
set -euo pipefail
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
source "$HERE/../cli/lib.sh"
BUILD=$(realpath "${3:?usage: version.sh SIMBOB REPO BUILD}")
cli_setup "$1" "$2"

check "the binary prints the project version and the configured revision"
version=$(sed -n 's/^CMAKE_PROJECT_VERSION:[A-Z]*=//p' "$BUILD/CMakeCache.txt")
revision=$(sed -n 's/^ *const char\* const kGitRevision = "\(.*\)";$/\1/p' "$BUILD/generated/version.cpp")
[[ -n "$version" && -n "$revision" ]] || fail "no version ('$version') or revision ('$revision') in $BUILD"
expect_status 0 "$SIMBOB" --version
expect_eq "--version" "$(head -n 1 "$LAST_OUT")" "simbob $version (git $revision)"
# Then what the trajectory bytes depend on (docs/ci.md): ODE, the compiler, the C library.
expect_match "--version's ODE line" "$LAST_OUT" "^ODE 0\.16\.[0-9]+ \(ODE .*ODE_double_precision"
expect_match "--version's compiler line" "$LAST_OUT" "^compiler (gcc|clang) [0-9]"
expect_match "--version's C library line" "$LAST_OUT" "^glibc [0-9]+\.[0-9]+$"

if ! command -v git >/dev/null; then
  printf 'SKIP: git is not installed; the revision module cannot be checked\n'
  exit 77
fi

# revision_of DIR [CMAKE ARGS...]: runs the module on source DIR as a configure step would and
# prints the revision written into the generated file.
revision_of() {
  local src=$1
  shift
  rm -rf "$WORK/bin"
  cmake "$@" -DPROJECT_SOURCE_DIR="$src" -DPROJECT_BINARY_DIR="$WORK/bin" -DPROJECT_VERSION=9.9.9 \
    -P "$src/cmake/git_revision.cmake" >"$WORK/cmake.log" 2>&1 || fail "the module failed: $(cat "$WORK/cmake.log")"
  sed -n 's/^ *const char\* const kGitRevision = "\(.*\)";$/\1/p' "$WORK/bin/generated/version.cpp"
}

# A source tree with just what the module reads.
make_tree() {
  mkdir -p "$1/cmake" "$1/cmd/simbob"
  cp "$REPO/cmake/git_revision.cmake" "$1/cmake/"
  cp "$REPO/cmd/simbob/version.cpp.in" "$1/cmd/simbob/"
}
git_quiet() { git -c user.name=t -c user.email=t@localhost -c init.defaultBranch=main "$@" >/dev/null 2>&1; }

check "a plain directory (a release tarball): unknown"
make_tree "$WORK/tarball"
expect_eq "tarball" "$(revision_of "$WORK/tarball")" unknown

check "a git checkout: its abbreviated commit; after an edit: -dirty"
make_tree "$WORK/checkout"
git_quiet -C "$WORK/checkout" init
git_quiet -C "$WORK/checkout" add .
git_quiet -C "$WORK/checkout" commit -m one
head=$(git -C "$WORK/checkout" rev-parse --short HEAD)
expect_eq "clean checkout" "$(revision_of "$WORK/checkout")" "$head"
echo "# edit" >>"$WORK/checkout/cmake/git_revision.cmake"
expect_eq "edited checkout" "$(revision_of "$WORK/checkout")" "$head-dirty"

check "a tarball unpacked inside another repository does not take that repository's revision"
make_tree "$WORK/checkout/vendor/simbob"
expect_eq "nested tarball" "$(revision_of "$WORK/checkout/vendor/simbob")" unknown

check "-DSIMBOB_GIT_REVISION=... from a packager wins"
expect_eq "given revision" "$(revision_of "$WORK/checkout" -DSIMBOB_GIT_REVISION=debian-1)" debian-1
say "ok"
