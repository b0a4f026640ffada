#!/usr/bin/env bash
# The documented sweep workflow word for word with relative paths (issue 31, item 11):
# docs/sweeps.md's "On a laptop" then docs/view.md's `sweep gather OUT --html OUT/index.html`,
# run from the folder that holds scenes/ (as from the repository's root). The gallery and every
# ok case's page are written, whatever folder gather is run from.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

mkdir root
cp -r "$SCENES" root/scenes
mkdir root/build
ln -s "$SIMBOB" root/build/simbob
cd root

check "docs/sweeps.md: plan, run -j 2, gather (relative paths, from the folder holding scenes/)"
expect_status 0 build/simbob sweep plan scenes/sliding_box.sweep.json -o box.jsonl
expect_status 0 build/simbob sweep run box.jsonl -j 2 -o box -q
expect_status 0 build/simbob sweep gather box -q

check "docs/view.md: sweep gather box --html box/index.html writes the gallery and 20 case pages"
expect_status 0 build/simbob sweep gather box --html box/index.html -q
expect_file box/index.html
[[ $(ls box/case-*/view.html | wc -l) -eq 20 ]] || fail "$(ls box/case-*/view.html | wc -l) case pages, expected 20"

check "the same from another folder, naming the sweep folder by a relative path"
mkdir elsewhere
cd elsewhere
expect_status 0 ../build/simbob sweep gather ../box --html gallery.html -q
expect_file gallery.html
say "ok"
