#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Volume-mesh benchmark (issue 10, BENCHMARKS.md), all in one run:
#  1. coons2stl: a body 2 whose six faces are bicubic B-spline surfaces
#     (5 x 5 control points each: the boundary nets of a curved 5 x 5 x 5
#     control lattice, so the faces agree along their edges) meshed into
#     N^3 hex8 cells (--resolution N; N = 100: 10^6 cells, 1,030,301 nodes)
#     and written as binary .vtu: the whole command, load, mesh (every node
#     on the body's map), scaled Jacobian per cell, and the atomic write
#     (temporary file, fsync, rename);
#     The same command with --info --volume-mesh instead of -o (the same
#     mesh and quality, nothing written) separates the writing;
#  2. the I/O floor: the same number of bytes copied from /dev/zero to a
#     file in the same directory and fsync'ed (dd conv=fsync);
#  3. Gmsh 4.8 meshing a transfinite volume of the same size: a box with
#     Transfinite Curve = N + 1 points on its 12 edges, Transfinite and
#     Recombine Surface on its 6 faces, Transfinite Volume, written as
#     binary legacy VTK (gmsh -3 -bin box.geo -o box.vtk).
# Why the Gmsh time is a fair lower bound for Gmsh on our six faces: a box
# of planar faces and straight edges is the simplest input its transfinite
# mesher has. Every node is a transfinite interpolation of straight lines,
# with no curve or surface evaluation at all, whereas coons2stl evaluates
# the body-2 map through six bicubic B-spline faces at every node. Giving
# Gmsh the same faces (as its own B-spline surfaces) adds their evaluation
# to the same interpolation, so it can only be slower. Gmsh also writes
# without fsync, which again favours it.
# The machine is shared: the load average is printed; use the minimum of
# REPEAT runs of each.
# Usage: tools/bench/bench_volume.sh [BUILD_DIR [N [REPEAT]]]
#        (default build, N = 100, REPEAT = 2)
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$here/build}" && pwd)
res=${2:-100}
repeat=${3:-2}
bin=$build/tools/coons2stl
cmake --build "$build" --target coons2stl >/dev/null
work=$(mktemp -d "$build/bench-volume.XXXXXX")   # on the build directory's disk
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }
elapsed() { python3 -c "print('%.3f' % ($2 - $1))"; }
min() { printf '%s\n' "$@" | sort -g | head -1; }
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "disk: $(df -T "$work" | awk 'NR==2 {print $2, $1}')"
echo "cells: $res^3 = $((res * res * res)) hex8"

# The model: control points P[i][j][k] of a box 10 x 8 x 6 with every
# face net bulged outward (a cubic B-spline lattice, clamped uniform
# knots); face F's net is the lattice's boundary layer, in the parameter
# order of model-format.md (u0: points[j][k] = P[0][j][k], ...).
python3 - "$work/body2-bspline.json" <<'PY'
import json, math, sys
n = 5
size = (10.0, 8.0, 6.0)
def P(i, j, k):
    q = [i / (n - 1), j / (n - 1), k / (n - 1)]
    x = [q[a] * size[a] for a in range(3)]
    for a in range(3):  # bulge: outward on the faces a = 0 and a = 1
        if q[a] in (0.0, 1.0):
            b, c = (a + 1) % 3, (a + 2) % 3
            x[a] += (0.8 if q[a] else -0.8) * math.sin(math.pi * q[b]) * math.sin(math.pi * q[c])
    return x
def face(f):
    a, side = "uvw".index(f[0]), (n - 1) * int(f[1])
    rows = []
    for s in range(n):
        row = []
        for t in range(n):
            idx = [0, 0, 0]
            b, c = [d for d in range(3) if d != a]
            idx[a], idx[b], idx[c] = side, s, t
            row.append(P(*idx))
        rows.append(row)
    return {"type": "bspline-surface", "degree": [3, 3], "points": rows}
faces = {f: face(f) for f in ("u0", "u1", "v0", "v1", "w0", "w1")}
json.dump({"coons": 1, "units": "mm",
           "bodies": [{"type": "body2", "name": "bspline-box", "faces": faces}]},
          open(sys.argv[1], "w"), indent=1)
PY

echo
echo "== coons2stl: body 2 with bicubic B-spline faces to binary .vtu (min of $repeat) =="
ours=()
for r in $(seq "$repeat"); do
  rm -f "$work/out.vtu"
  t0=$(now)
  "$bin" "$work/body2-bspline.json" -o "$work/out.vtu" --resolution "$res"
  t1=$(now)
  ours+=("$(elapsed "$t0" "$t1")")
done
bytes=$(stat -c %s "$work/out.vtu")
grep -m1 -o 'NumberOfPoints="[0-9]*" NumberOfCells="[0-9]*"' "$work/out.vtu"
echo "coons2stl_s $(min "${ours[@]}")   (runs: ${ours[*]})"
echo "vtu_bytes $bytes"
if [ -x /usr/bin/time ]; then
  /usr/bin/time -f "coons2stl_peak_rss_kib %M" "$bin" "$work/body2-bspline.json" \
    -o "$work/out.vtu" --resolution "$res"
fi

echo
echo "== coons2stl --info --volume-mesh: the same mesh, nothing written (min of $repeat) =="
meshonly=()
for r in $(seq "$repeat"); do
  t0=$(now)
  "$bin" --info --no-solid --volume-mesh --resolution "$res" "$work/body2-bspline.json" >/dev/null
  t1=$(now)
  meshonly+=("$(elapsed "$t0" "$t1")")
done
echo "mesh_only_s $(min "${meshonly[@]}")   (runs: ${meshonly[*]})"

echo
echo "== I/O floor: $bytes bytes from /dev/zero, fsync'ed, same directory (min of $repeat) =="
floor=()
for r in $(seq "$repeat"); do
  rm -f "$work/floor.bin"
  t0=$(now)
  dd if=/dev/zero of="$work/floor.bin" bs=1M count="$bytes" iflag=count_bytes conv=fsync \
    status=none
  t1=$(now)
  floor+=("$(elapsed "$t0" "$t1")")
done
rm -f "$work/floor.bin"
echo "io_floor_s $(min "${floor[@]}")   (runs: ${floor[*]})"

echo
echo "== Gmsh: transfinite box volume, $res^3 hexahedra, binary legacy VTK (min of $repeat) =="
gmsh --version 2>&1 | head -1
cat >"$work/box.geo" <<EOF
// A box whose faces are the simplest Gmsh's transfinite mesher knows:
// planar, with straight edges (see bench_volume.sh for why this is a
// lower bound of Gmsh's time on our six B-spline faces).
N = $res;
Point(1) = {0, 0, 0}; Point(2) = {10, 0, 0}; Point(3) = {10, 8, 0}; Point(4) = {0, 8, 0};
Point(5) = {0, 0, 6}; Point(6) = {10, 0, 6}; Point(7) = {10, 8, 6}; Point(8) = {0, 8, 6};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Line(9) = {1, 5}; Line(10) = {2, 6}; Line(11) = {3, 7}; Line(12) = {4, 8};
Curve Loop(1) = {1, 2, 3, 4};     Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8};     Plane Surface(2) = {2};
Curve Loop(3) = {1, 10, -5, -9};  Plane Surface(3) = {3};
Curve Loop(4) = {2, 11, -6, -10}; Plane Surface(4) = {4};
Curve Loop(5) = {3, 12, -7, -11}; Plane Surface(5) = {5};
Curve Loop(6) = {4, 9, -8, -12};  Plane Surface(6) = {6};
Surface Loop(1) = {1, 2, 3, 4, 5, 6};
Volume(1) = {1};
Transfinite Curve {1:12} = N + 1;
Transfinite Surface {1:6};
Recombine Surface {1:6};
Transfinite Volume {1};
EOF
peer=()
for r in $(seq "$repeat"); do
  rm -f "$work/box.vtk"
  t0=$(now)
  gmsh -3 -bin "$work/box.geo" -o "$work/box.vtk" >"$work/gmsh.log" 2>&1
  t1=$(now)
  peer+=("$(elapsed "$t0" "$t1")")
done
grep -E 'nodes .* elements|Error' "$work/gmsh.log" || true
echo "gmsh_s $(min "${peer[@]}")   (runs: ${peer[*]})"
echo "gmsh_vtk_bytes $(stat -c %s "$work/box.vtk")"

echo
echo "== ratios =="
python3 - "$(min "${ours[@]}")" "$(min "${meshonly[@]}")" "$(min "${floor[@]}")" \
  "$(min "${peer[@]}")" "$bytes" <<'PY'
import sys
ours, mesh, floor, gmsh, nbytes = (float(x) for x in sys.argv[1:])
write = ours - mesh
print("coons2stl / I/O floor:          %.2f  (aim <= 2)" % (ours / floor))
if write > 0:
    print("  of which writing (total - mesh only): %.3f s, %.2f x the floor, %.0f MB/s"
          % (write, write / floor, nbytes / write / 1e6))
else:
    print("  writing (total - mesh only) is within the noise of the meshing (%.3f s)" % write)
print("gmsh / coons2stl:               %.2f" % (gmsh / ours))
PY
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
