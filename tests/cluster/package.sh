#!/usr/bin/env bash
# The install rules and the .deb (cmake/package.cmake):
#   - `cmake --install BUILD --prefix P` puts bin/simbob, the example scenes with the parts they
#     import, the README and docs/ under P, and the installed binary runs a scene from there;
#   - `cpack -G DEB` builds simbob_VERSION_ARCH.deb whose Depends is exactly the Debian packages
#     of the libraries the binary links (dpkg-shlibdeps), none of them -dev or from outside
#     Debian; `apt-get --simulate install ./simbob_*.deb` accepts it on this machine;
#   - the package unpacked into a temporary root (`dpkg -x`: a real chroot would need
#     debootstrap and a network) runs `simbob --version` and an example scene, byte-identical
#     to the build tree's binary;
#   - when the build has the Python module: both put the package simbob/ into
#     lib/python3/dist-packages, and Debian's /usr/bin/python3 imports it from the unpacked root
#     (nothing of the build tree on its path) and steps a scene to the build tree's numbers.
#
#   bash tests/cluster/package.sh /path/to/simbob /path/to/repo /path/to/build
set -euo pipefail
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
source "$HERE/../cli/lib.sh"
BUILD=$(realpath "${3:?usage: package.sh SIMBOB REPO BUILD}")
cli_setup "$1" "$2"
[[ -f "$BUILD/CPackConfig.cmake" ]] || fail "$BUILD has no CPackConfig.cmake: configure it with CMake first"

# scripts/deps.sh test installs every one (file and dpkg-dev by name: CPackDeb needs both).
for c in cpack dpkg-deb dpkg-shlibdeps objdump file; do
  command -v "$c" >/dev/null || fail "$c is not installed: run scripts/deps.sh test"
done
check "scripts/deps.sh test names the packages of what cpack -G DEB runs (a fresh machine has neither)"
for c in file dpkg-shlibdeps; do
  owner=$(dpkg -S "$(realpath "$(command -v "$c")")" 2>/dev/null | head -n 1 | cut -d: -f1)
  [[ -n "$owner" ]] || owner=$(dpkg -S "$(command -v "$c")" 2>/dev/null | head -n 1 | cut -d: -f1)
  [[ -n "$owner" ]] || fail "no package owns $(command -v "$c")"
  grep -Eq "^ +[^#]*(^|[ (])$owner( |\$)" "$REPO/scripts/deps.sh" ||
    fail "$c comes from $owner, which scripts/deps.sh does not install"
done

version=$(sed -n 's/^CMAKE_PROJECT_VERSION:[A-Z]*=//p' "$BUILD/CMakeCache.txt")
[[ "$version" =~ ^[0-9]+\.[0-9]+\.[0-9]+$ ]] || fail "no project version in $BUILD/CMakeCache.txt: '$version'"
expect_status 0 "$SIMBOB" --version
version_text=$(cat "$LAST_OUT")
version_line=$(head -n 1 "$LAST_OUT")

# A scene that imports parts/ (so the installed scenes must bring their data files along).
SCENE=imported_bodies
expect_status 0 "$SIMBOB" run "$SCENES/$SCENE.xml" --duration 1 --quiet --out "$WORK/reference.csv"

# The Python package, when the build has it (CMake found python3-dev and pybind11-dev).
PYMOD=$(find "$BUILD/python/simbob" -maxdepth 1 -name '_simbob*.so' 2>/dev/null | head -n 1)
PYFILES=()
if [[ -n "$PYMOD" ]]; then
  PYFILES=("$(basename "$PYMOD")" $(cd "$REPO/python/simbob" && ls -1 ./*.py | sed 's|^\./||'))
  # One scene stepped 1000 times; prints where simbob came from and a digest of every pose.
  PYRUN='import hashlib, sys
sys.path.insert(0, sys.argv[1])
import simbob
sim = simbob.Simulation(sys.argv[2])
h = hashlib.sha256()
for _ in range(100):
    sim.step(10)
    h.update(sim.poses().tobytes())
print(simbob.__file__)
print(simbob.__version__, sim.time, h.hexdigest())'
  expect_status 0 env -u PYTHONPATH ${SIMBOB_ASAN_RUNTIME:+LD_PRELOAD=$SIMBOB_ASAN_RUNTIME ASAN_OPTIONS=detect_leaks=0} /usr/bin/python3 -s -c "$PYRUN" "$BUILD/python" "$SCENES/$SCENE.xml"
  py_reference=$(tail -n 1 "$LAST_OUT")
  say "build tree module: $py_reference"
else
  say "note: the build has no Python module (python3-dev, pybind11-dev missing?): its install is not checked"
fi

# Debian's python3 imports simbob from DIST (a dist-packages directory) and gets the build tree's numbers.
expect_installed_python() {
  local dist=$1 f
  [[ -n "$PYMOD" ]] || return 0
  for f in "${PYFILES[@]}"; do
    [[ -f "$dist/simbob/$f" ]] || fail "no $dist/simbob/$f"
  done
  expect_status 0 env -u PYTHONPATH ${SIMBOB_ASAN_RUNTIME:+LD_PRELOAD=$SIMBOB_ASAN_RUNTIME ASAN_OPTIONS=detect_leaks=0} /usr/bin/python3 -s -c "$PYRUN" "$dist" "$SCENES/$SCENE.xml"
  expect_eq "simbob imported from" "$(head -n 1 "$LAST_OUT")" "$dist/simbob/__init__.py"
  expect_eq "installed module's run" "$(tail -n 1 "$LAST_OUT")" "$py_reference"
}

check "cmake --install --prefix puts the binary, the scenes with their parts, the README and docs/ there"
t0=$SECONDS
expect_status 0 cmake --install "$BUILD" --prefix "$WORK/prefix"
say "cmake --install took $((SECONDS - t0)) s"
P=$WORK/prefix
[[ -x "$P/bin/simbob" ]] || fail "no executable $P/bin/simbob"
for f in "$SCENES"/*.xml "$SCENES"/parts/*; do
  expect_same_file "$f" "$P/share/simbob/scenes/${f#"$SCENES"/}"
done
expect_same_file "$REPO/README.md" "$P/share/doc/simbob/README.md"
for f in "$REPO"/docs/*.md; do
  expect_same_file "$f" "$P/share/doc/simbob/docs/${f#"$REPO"/docs/}"
done
expect_status 0 "$P/bin/simbob" run "$P/share/simbob/scenes/$SCENE.xml" --duration 1 --quiet --out "$WORK/prefix.csv"
expect_same_file "$WORK/prefix.csv" "$WORK/reference.csv"
expect_installed_python "$P/lib/python3/dist-packages"

check "cpack -G DEB builds simbob_${version}_*.deb"
t0=$SECONDS
expect_status 0 cpack --config "$BUILD/CPackConfig.cmake" -G DEB -B "$WORK/pkg"
say "cpack took $((SECONDS - t0)) s"
debs=("$WORK"/pkg/simbob_"$version"_*.deb)
[[ ${#debs[@]} -eq 1 && -f "${debs[0]}" ]] || fail "expected one simbob_${version}_*.deb in $WORK/pkg: $(ls "$WORK/pkg")"
deb=${debs[0]}
say "$(basename "$deb"): $(wc -c <"$deb") bytes"
expect_eq "Package" "$(dpkg-deb -f "$deb" Package)" simbob
expect_eq "Version" "$(dpkg-deb -f "$deb" Version)" "$version"
expect_eq "Architecture" "$(dpkg-deb -f "$deb" Architecture)" "$(dpkg --print-architecture)"
expect_eq "file name" "$(basename "$deb")" "simbob_${version}_$(dpkg --print-architecture).deb"

say "at $SECONDS s"
check "the package holds the binary, every scene and part, the README and docs/ under /usr"
dpkg-deb -c "$deb" | awk '{print $6}' | sed 's|^\./|/|' >"$WORK/contents"
for f in /usr/bin/simbob /usr/share/doc/simbob/README.md /usr/share/doc/simbob/docs/scene-format.md; do
  grep -qxF "$f" "$WORK/contents" || fail "the package lacks $f"
done
for f in "$SCENES"/*.xml "$SCENES"/parts/*; do
  grep -qxF "/usr/share/simbob/scenes/${f#"$SCENES"/}" "$WORK/contents" || fail "the package lacks scene file ${f#"$SCENES"/}"
done
for f in "${PYFILES[@]}"; do
  grep -qxF "/usr/lib/python3/dist-packages/simbob/$f" "$WORK/contents" || fail "the package lacks the Python file simbob/$f"
done

say "at $SECONDS s"
check "Depends: exactly the Debian packages of the libraries the binary links, no -dev"
depends=$(dpkg-deb -f "$deb" Depends)
say "Depends: $depends"
[[ -n "$depends" ]] || fail "the package has no Depends (CPACK_DEBIAN_PACKAGE_SHLIBDEPS is off?)"
# Package names only: drop version constraints, split alternatives.
tr ',|' '\n\n' <<<"$depends" | sed 's/(.*)//; s/^ *//; s/ *$//' | sed '/^$/d' | sort -u >"$WORK/depends"
if grep -E -- '-(dev|dbg)$' "$WORK/depends"; then fail "Depends names a development package"; fi
# The packages that own the libraries the binary needs (NEEDED entries, resolved by ldd).
# The binary and the module it opens on demand (libsimbob_video.so: FFmpeg) all count.
# And the Python module, when there is one (it links no libpython: the interpreter provides it).
ELVES=("$SIMBOB")
for module in video; do
  ELVES+=("$(dirname "$SIMBOB")/libsimbob_$module.so")
  [[ -f "${ELVES[-1]}" ]] || fail "no $module module beside the binary: ${ELVES[-1]}"
done
[[ -z "$PYMOD" ]] || ELVES+=("$PYMOD")
for elf in "${ELVES[@]}"; do objdump -p "$elf" | awk '/NEEDED/ && $2 !~ /^ld-linux/ {print $2}'; done | sort -u >"$WORK/needed"
[[ -s "$WORK/needed" ]] || fail "objdump found no NEEDED libraries in $SIMBOB"
for elf in "${ELVES[@]}"; do ldd "$elf"; done >"$WORK/ldd"
# Each library under every name dpkg may know it by (merged /usr: /lib/... or /usr/lib/...),
# all asked in one dpkg -S call (each call reads the whole file database).
: >"$WORK/spellings"
while read -r lib; do
  path=$(awk -v l="$lib" '$1 == l && $3 ~ /^\// {print $3; exit}' "$WORK/ldd")
  [[ -n "$path" ]] || fail "ldd does not resolve $lib"
  real=$(realpath "$path")
  for p in "$path" "$real"; do printf '%s %s\n%s %s\n%s %s\n' "$lib" "$p" "$lib" "${p#/usr}" "$lib" "/usr${p#/usr}"; done
done <"$WORK/needed" | sort -u >"$WORK/spellings"
dpkg -S $(awk '{print $2}' "$WORK/spellings") >"$WORK/dpkg-S" 2>/dev/null || true
: >"$WORK/owners"
while read -r lib; do
  owner=$(awk -v l="$lib" 'NR == FNR { if ($1 == l) want[$2] = 1; next }
    ($2 in want) { sub(/:.*/, "", $1); print $1; exit }' "$WORK/spellings" "$WORK/dpkg-S")
  [[ -n "$owner" ]] || fail "no package owns $lib ($(grep "^$lib " "$WORK/spellings" | head -n 1))"
  printf '%s\n' "$owner" >>"$WORK/owners"
done <"$WORK/needed"
# Plus what the binary reads at run time: three.js for `simbob view` pages (cmake/package.cmake).
printf 'libjs-three\n' >>"$WORK/owners"
sort -u -o "$WORK/owners" "$WORK/owners"
expect_eq "Depends vs the owners of the NEEDED libraries" "$(tr '\n' ' ' <"$WORK/depends")" "$(tr '\n' ' ' <"$WORK/owners")"
# Each comes from Debian's archive (when this machine has apt lists to tell). One apt-cache
# call for all: it reads the lists each time.
apt-cache policy $(cat "$WORK/depends") >"$WORK/policy" 2>&1 || true
# PACKAGE ORIGIN-URL lines: the archives apt knows each package from.
awk '/^[^ ]+:$/ {p = substr($1, 1, length($1) - 1)} $2 ~ /^https?:/ {print p, $2}' "$WORK/policy" >"$WORK/origins"
if grep -q '^libc6 .*debian\.org/debian' "$WORK/origins"; then
  while read -r p; do
    grep -q "^$p .*debian\.org/debian" "$WORK/origins" || fail "$p is not in a Debian archive known to apt: $(cat "$WORK/policy")"
  done <"$WORK/depends"
else
  say "note: apt knows no Debian archive for libc6 here (no apt-get update?); the origin of Depends is not checked"
fi

say "at $SECONDS s"
check "apt-get --simulate install ./$(basename "$deb") resolves on this machine"
if command -v apt-get >/dev/null; then
  (cd "$WORK/pkg" && expect_status 0 apt-get --simulate -o Debug::NoLocking=1 install "./$(basename "$deb")")
  expect_match "apt installs simbob" "$WORK/last.out" "^Inst simbob "
  if grep -E '^Inst [^ ]+-dev ' "$WORK/last.out"; then fail "apt would install a -dev package for simbob"; fi
else
  say "note: no apt-get here; the apt install simulation is not run"
fi

say "at $SECONDS s"
check "the package unpacked into a temporary root runs --version and an example scene"
mkdir "$WORK/root"
expect_status 0 dpkg -x "$deb" "$WORK/root"
R=$WORK/root
expect_status 0 "$R/usr/bin/simbob" --version
expect_eq "installed --version" "$(cat "$LAST_OUT")" "$version_text"
[[ "$version_line" =~ ^simbob\ $version\ \(git\ [^\ ]+\)$ ]] || fail "--version prints '$version_line'"
expect_status 0 "$R/usr/bin/simbob" run "$R/usr/share/simbob/scenes/$SCENE.xml" --duration 1 --quiet --out "$WORK/deb.csv"
expect_same_file "$WORK/deb.csv" "$WORK/reference.csv"
expect_eq "scene in the installed run's summary" "$(json_get "$WORK/deb.json" 'j["scene"]')" "$R/usr/share/simbob/scenes/$SCENE.xml"
check "the unpacked binary opens its module from /usr/lib/simbob; a mesh scene, a URDF scene (its meshes) and a plot run"
for module in video; do
  grep -qxF "/usr/lib/simbob/libsimbob_$module.so" "$WORK/contents" || fail "the package lacks libsimbob_$module.so"
done
expect_status 0 "$R/usr/bin/simbob" check "$R/usr/share/simbob/scenes/mesh_drop.xml"
expect_status 0 "$R/usr/bin/simbob" check "$R/usr/share/simbob/scenes/kr5.xml"
! grep -qF "libsimbob_urdf" "$WORK/contents" || fail "the package still holds libsimbob_urdf.so (URDF is read by simbob itself)"
expect_status 0 "$R/usr/bin/simbob" plot "$WORK/deb.csv" --out "$WORK/deb.png"
[[ -s "$WORK/deb.png" ]] || fail "the installed plot wrote no $WORK/deb.png"
if [[ -n "$PYMOD" ]]; then
  check "Debian's python3 imports simbob from the unpacked root's dist-packages and runs a scene"
  expect_installed_python "$R/usr/lib/python3/dist-packages"
  recommends=$(dpkg-deb -f "$deb" Recommends)
  [[ "$recommends" == *python3-numpy* ]] || fail "Recommends lacks python3-numpy: $recommends"
fi
say "ok ($SECONDS s)"
