#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Meshing + writing benchmark, all in one run (BENCHMARKS.md):
#  1. bench_mesh: sample one body (cubic Bezier volume, fixed lattice, 12 N^2
#     triangles; on every core, as coons2stl) and write binary STL, next to the I/O floor (the same number
#     of bytes written to the same directory; both with temp file, fsync and
#     rename), and the ASCII STL writer;
#  2. numpy-stl's ASCII writer on the same triangles (pip-installed into a
#     virtual environment in the build directory);
#  3. the peer: the same body sampled in OpenSCAD's language (list
#     comprehensions + polyhedron()), rendered by `openscad` to binary STL.
# Usage: tools/bench/bench_mesh.sh [BUILD_DIR [N]]   (default build, N = 289)
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$here/build}" && pwd)
res=${2:-289}
bin=$build/tools/bench/bench_mesh
cmake --build "$build" --target bench_mesh >/dev/null
work=$(mktemp -d "$build/bench-mesh.XXXXXX")   # on the build directory's disk
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "disk: $(df -T "$work" | awk 'NR==2 {print $2, $1}')"
echo
echo "== libcoons (min of 3 runs; both writes fsync'ed) =="
"$bin" --resolution "$res" --repeat 3 --dir "$work" --keep | tee "$work/ours.txt"
get() { awk -v k="$1" '$1 == k {print $2}' "$work/ours.txt"; }

echo
echo "== numpy-stl ASCII writer, same triangles =="
venv=$build/bench-venv
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c 'import stl' 2>/dev/null; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q numpy-stl
fi
"$venv/bin/python" - "$work" <<'PY' | tee "$work/numpy.txt"
import os, sys, time
import stl
from stl import mesh
work = sys.argv[1]
m = mesh.Mesh.from_file(os.path.join(work, "bench.stl"))
t = time.monotonic()
m.save(os.path.join(work, "numpy-ascii.stl"), mode=stl.Mode.ASCII)
fd = os.open(os.path.join(work, "numpy-ascii.stl"), os.O_RDONLY)
os.fsync(fd)
os.close(fd)
print("numpy_stl_ascii_s %.3f" % (time.monotonic() - t))
print("numpy_stl_triangles %d" % len(m.vectors))
PY
rm -f "$work/numpy-ascii.stl"

echo
echo "== OpenSCAD peer: the body sampled in OpenSCAD's language =="
"$bin" --emit-scad "$work/peer.scad" --resolution "$res"
openscad --version 2>&1 | head -1
t0=$(now)
openscad --export-format binstl -o "$work/peer.stl" "$work/peer.scad" >"$work/peer.log" 2>&1
t1=$(now)
grep -E 'Facets|WARNING|ERROR' "$work/peer.log" || true
echo "openscad_s $(python3 -c "print('%.3f' % ($t1 - $t0))")" | tee "$work/peer.txt"
"$venv/bin/python" - "$work" <<'PY'
import os, sys
import numpy as np
from stl import mesh
w = sys.argv[1]
def vol(p):
    v = mesh.Mesh.from_file(p).vectors.astype(np.float64)
    return np.einsum('ij,ij->i', v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6
a, b = vol(os.path.join(w, "bench.stl")), vol(os.path.join(w, "peer.stl"))
print("volume ours %.6f, OpenSCAD peer %.6f, relative difference %.1e" % (a, abs(b), abs(abs(b) - a) / a))
PY

echo
echo "== ratios =="
numpy=$(awk '$1 == "numpy_stl_ascii_s" {print $2}' "$work/numpy.txt")
peer=$(awk '$1 == "openscad_s" {print $2}' "$work/peer.txt")
python3 - "$(get triangles)" "$(get sample_s)" "$(get write_binary_s)" "$(get io_floor_s)" \
  "$(get write_ascii_s)" "$numpy" "$peer" <<'PY'
import sys
n, samp, wb, floor, wa, numpy, peer = (float(x) for x in sys.argv[1:])
print("binary STL write / I/O floor           %6.2f" % (wb / floor))
print("sampling + binary STL / I/O floor      %6.2f" % ((samp + wb) / floor))
print("sampling + binary STL, triangles/s     %10.0f" % (n / (samp + wb)))
print("numpy-stl ASCII / libcoons ASCII       %6.1f" % (numpy / wa))
print("OpenSCAD peer / libcoons sample+write  %6.1f" % (peer / (samp + wb)))
PY
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
