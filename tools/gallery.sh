#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Renders the gallery (docs/gallery.md): seed 000's Figs. 2-9 made from coons2stl's
# own output by a real renderer, OpenSCAD's preview under a virtual X server
# (xvfb-run), as small PNGs in examples/img/:
#
#     tools/gallery.sh [-b BUILD_DIR] [-o OUT_DIR] [PICTURE...]
#     tools/gallery.sh --list          picture, model file, coons2stl arguments
#
# BUILD_DIR (default: build) holds tools/coons2stl; OUT_DIR defaults to
# examples/img. Without PICTURE, every picture is made. Each picture is
# `coons2stl MODEL ARGS -o NAME.scad` (a solid's boundary, or isoparametric
# surfaces with the boundary as a transparent `%` part), then
# `openscad --preview --imgsize=W,H --autocenter --viewall -o NAME.png`.
# Needs openscad and xvfb-run.
set -eu
src=$(cd "$(dirname "$0")/.." && pwd)
build=$src/build
out=$src/examples/img
W=480
H=360
ISO="--iso u=0.25,0.5,0.75 --iso w=0.5 --with-boundary"

# name | model (examples/) | coons2stl arguments | seed 000 figure
pictures() {
    cat <<EOF
fig2-deformed-cube|deformed-cube.json||2
fig3-body1-bspline-edges|body1-bspline-edges.json||3
fig4-body1-bspline-edges-iso|body1-bspline-edges.json|$ISO|4
fig4-body1-density-iso|body1-density.json|$ISO|4
fig5-patch-bspline|patch-bspline.json||5
fig6-nail|nail.json||6
fig6-nail-iso|nail.json|$ISO|6
fig6-nail-density-iso|nail-density.json|$ISO|6
fig7-spool|spool.json||7
fig8-union-three-bodies|union-three-bodies.json||8
fig9-chair|chair.json||9
EOF
}

if [ "${1:-}" = "--list" ]; then
    pictures | awk -F'|' '{ printf "%s\t%s\t%s\t%s\n", $1, $2, $3, $4 }'
    exit 0
fi
while [ $# -gt 0 ]; do
    case $1 in
        -b) build=$2; shift 2 ;;
        -o) out=$2; shift 2 ;;
        -h|--help) sed -n '3,15p' "$0"; exit 0 ;;
        -*) echo "gallery.sh: unknown option $1" >&2; exit 2 ;;
        *) break ;;
    esac
done
case $build in /*) ;; *) build=$(pwd)/$build ;; esac
case $out in /*) ;; *) out=$(pwd)/$out ;; esac
cli=$build/tools/coons2stl
for tool in openscad xvfb-run; do
    command -v "$tool" >/dev/null || { echo "gallery.sh: $tool is not installed" >&2; exit 1; }
done
[ -x "$cli" ] || { echo "gallery.sh: no $cli (build first)" >&2; exit 1; }
for want in "$@"; do
    pictures | grep -q "^$want|" || { echo "gallery.sh: no picture '$want' (see --list)" >&2; exit 2; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
pictures | while IFS='|' read -r name model args fig; do
    if [ $# -gt 0 ]; then
        found=0
        for want in "$@"; do [ "$want" = "$name" ] && found=1; done
        [ $found -eq 1 ] || continue
    fi
    # The .scad is named after the picture: its modules carry that name.
    scad=$tmp/$name.scad
    # shellcheck disable=SC2086
    "$cli" -q "$src/examples/$model" $args -o "$scad" ||
        { echo "gallery.sh: coons2stl failed on $model" >&2; exit 1; }
    # The preview draws `%` parts transparent; a render would leave them out.
    xvfb-run -a openscad --preview --imgsize=$W,$H --autocenter --viewall \
        -o "$out/$name.png" "$scad" >"$tmp/log" 2>&1 ||
        { cat "$tmp/log" >&2; echo "gallery.sh: openscad failed on $name" >&2; exit 1; }
    echo "$out/$name.png (seed 000 Fig. $fig)"
done
