#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Renders the isoparametric-surface pictures of docs/gallery.md (seed 000 Fig. 4
# and 6: the same outer shape, a different interior "density"):
#
#     tools/render-iso.sh [BUILD_DIR]      (default: build)
#
# For each example, `coons2stl EX --iso u=0.25,0.5,0.75 --iso w=0.5
# --with-boundary -o EX-iso.scad` (the boundary is a transparent `%` part),
# then OpenSCAD's preview under a virtual X server into examples/img/EX-iso.png.
# Needs openscad and xvfb-run.
set -eu
src=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$src/build}
case $build in /*) ;; *) build=$(pwd)/$build ;; esac
cli=$build/tools/coons2stl
for tool in openscad xvfb-run; do
    command -v "$tool" >/dev/null || { echo "render-iso.sh: $tool is not installed" >&2; exit 1; }
done
[ -x "$cli" ] || { echo "render-iso.sh: no $cli (build first)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$src/examples/img"
for ex in body1-bspline-edges body1-density nail nail-density; do
    scad=$tmp/$ex-iso.scad
    "$cli" "$src/examples/$ex.json" --iso u=0.25,0.5,0.75 --iso w=0.5 --with-boundary -o "$scad"
    # The preview draws `%` parts transparent; -o FILE.stl would leave them out.
    xvfb-run -a openscad --preview --imgsize=800,600 --autocenter --viewall \
        -o "$src/examples/img/$ex-iso.png" "$scad" >"$tmp/log" 2>&1 ||
        { cat "$tmp/log" >&2; exit 1; }
    echo "examples/img/$ex-iso.png"
done
