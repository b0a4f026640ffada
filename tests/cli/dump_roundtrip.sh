#!/usr/bin/env bash
# `simbob dump` round trips: the normalized scene printed as INI or XML, saved and run, gives
# a trajectory byte-identical to the original XML scene's; dumping a dump changes nothing.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

# Imports are relative to the scene file: give the dumped scenes the same neighbours.
cp -r "$SCENES/parts" parts
cp -r "$SCENES/meshes" meshes  # and the mesh files (scenes/mesh_drop.xml)

while read -r scene; do
  name=$(basename "$scene" .xml)
  check "$name: dump --format ini and --format xml"
  expect_status 0 "$SIMBOB" dump "$scene" --format ini
  cp "$LAST_OUT" "$name.dump.ini"
  expect_status 0 "$SIMBOB" dump "$scene" --format xml
  cp "$LAST_OUT" "$name.dump.xml"
  expect_status 0 "$SIMBOB" dump "$scene"
  expect_same_file "$LAST_OUT" "$name.dump.xml"  # xml is the default format
  expect_match "$name: the INI dump lists components" "$name.dump.ini" "^ComponentCount = [0-9]+$"
  expect_match "$name: the XML dump is a <Simulation>" "$name.dump.xml" "^<Simulation>"

  check "$name: the dumps run to the same bytes as the scene"
  expect_status 0 "$SIMBOB" run -q "$scene" --duration 3 --out "$name.orig.csv"
  expect_status 0 "$SIMBOB" run -q "$name.dump.ini" --duration 3 --out "$name.ini.csv"
  expect_status 0 "$SIMBOB" run -q "$name.dump.xml" --duration 3 --out "$name.xml.csv"
  expect_same_file "$name.orig.csv" "$name.ini.csv"
  expect_same_file "$name.orig.csv" "$name.xml.csv"

  check "$name: dumping a dump is a fixed point, across formats too"
  expect_status 0 "$SIMBOB" dump "$name.dump.ini" --format ini
  expect_same_file "$LAST_OUT" "$name.dump.ini"
  expect_status 0 "$SIMBOB" dump "$name.dump.xml" --format xml
  expect_same_file "$LAST_OUT" "$name.dump.xml"
  expect_status 0 "$SIMBOB" dump "$name.dump.ini" --format xml
  expect_same_file "$LAST_OUT" "$name.dump.xml"
  expect_status 0 "$SIMBOB" dump "$name.dump.xml" --format ini
  expect_same_file "$LAST_OUT" "$name.dump.ini"
done < <(shipped_scenes)
say "ok"
