#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Renders the network pictures of docs/gallery.md (seed 001 Fig. 1.3 and the
# hood panel):
#
#     tools/render-network.sh [BUILD_DIR]      (default: build)
#
# `coons2stl EX -o EX.scad`, then OpenSCAD's preview under a virtual X
# server into examples/img/EX.png. fig13.json holds both fills side by side
# (bilinear cells left, Hermite cells right). Needs openscad and xvfb-run.
set -eu
src=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$src/build}
case $build in /*) ;; *) build=$(pwd)/$build ;; esac
cli=$build/tools/coons2stl
for tool in openscad xvfb-run; do
    command -v "$tool" >/dev/null || { echo "render-network.sh: $tool is not installed" >&2; exit 1; }
done
[ -x "$cli" ] || { echo "render-network.sh: no $cli (build first)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$src/examples/img"
render() { # example, camera (eye x,y,z, centre x,y,z)
    scad=$tmp/$1.scad
    "$cli" "$src/examples/$1.json" -o "$scad"
    xvfb-run -a openscad --preview --imgsize=800,500 --camera="$2" --viewall --autocenter --colorscheme=Tomorrow \
        -o "$src/examples/img/$1.png" "$scad" >"$tmp/log" 2>&1 ||
        { cat "$tmp/log" >&2; exit 1; }
    echo "examples/img/$1.png"
}
render fig13 20,-35,70,45,15,3
render hood-bessel -110,-120,110,0,40,15
