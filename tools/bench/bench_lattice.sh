#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Control-lattice benchmark (issue 11, BENCHMARKS.md), all in one run:
# two structured lattices of N x N x N cells (default N = 10: 1000 bodies),
#  a. body 0 cells on one lattice of points (10 mm cells, inner points moved:
#     they share faces by equal corners),
#  b. body 2 cells whose faces are Bezier surfaces: the boundary layers of
#     quadratic control volumes taken from one bent global lattice of points
#     (neighbours share a layer, so a face), curved outside,
# each measured as
#  1. coons2stl: model file -> boundary STL (load, shared faces found,
#     lattices shared, sampling, joining by index, CGAL's check of the one
#     joined shell, atomic write with fsync), minimum of REPEAT runs;
#  2. the I/O floor: reading the model file and writing the same number of
#     bytes as the STL with fsync (dd conv=fsync), minimum of REPEAT runs;
#  3. manifold3d (pip-installed into a virtual environment in the build
#     directory) uniting the same cells' shells (each written by coons2stl
#     --body I beforehand, untimed): the whole process (start, read, union,
#     write STL) and the Boolean alone.
# The machine is shared: the load average is printed; compare ratios.
# Usage: tools/bench/bench_lattice.sh [BUILD_DIR [N [REPEAT]]]
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$here/build}" && pwd)
n=${2:-10}
repeat=${3:-3}
bin=$build/tools/coons2stl
cmake --build "$build" --target coons2stl >/dev/null
work=$(mktemp -d "$build/bench-lattice.XXXXXX")
trap 'rm -rf "$work"' EXIT
now() { date +%s.%N; }
elapsed() { python3 -c "print('%.3f' % ($2 - $1))"; }
min() { printf '%s\n' "$@" | sort -g | head -1; }
ratio() { python3 -c "print('%.2f' % ($1 / $2))"; }

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

python3 - "$work" "$n" <<'PY'
import json, math, sys
work, n = sys.argv[1], int(sys.argv[2])
h = 10.0
def jitter(i, j, k):
    if 0 < i < n and 0 < j < n and 0 < k < n:
        return [1.5 * math.sin(1.3 * i + 2.1 * j + 0.7 * k), 1.5 * math.sin(0.9 * i - 1.7 * k),
                1.5 * math.cos(2.3 * j + 1.1 * k)]
    return [0.0, 0.0, 0.0]
def p0(i, j, k):
    d = jitter(i, j, k)
    return [i * h + d[0], j * h + d[1], k * h + d[2]]
bodies = []
for i in range(n):
    for j in range(n):
        for k in range(n):
            c = [p0(i + a, j + b, k + e) for a in (0, 1) for b in (0, 1) for e in (0, 1)]
            bodies.append({"type": "body0", "name": "c%d_%d_%d" % (i, j, k), "corners": c})
json.dump({"coons": 1, "units": "mm", "operation": "union", "bodies": bodies},
          open(work + "/body0.json", "w"))
L = n * h
def g(x, y, z):  # a bent bar: smooth, curved everywhere outside
    a = 0.6 * x / L
    r = 2 * L + z
    return [r * math.sin(a), y + 0.05 * L * math.sin(math.pi * x / L), r * math.cos(a) - 2 * L]
def f(v):
    return float("%.12g" % v)
bodies = []
for i in range(n):
    for j in range(n):
        for k in range(n):
            net = [[[[f(c) for c in g((i + a / 2) * h, (j + b / 2) * h, (k + e / 2) * h)]
                     for e in range(3)] for b in range(3)] for a in range(3)]
            def layer(ax, s):
                if ax == 0: return [[net[s][b][e] for e in range(3)] for b in range(3)]
                if ax == 1: return [[net[a][s][e] for e in range(3)] for a in range(3)]
                return [[net[a][b][s] for b in range(3)] for a in range(3)]
            faces = {"uvw"[ax] + str(side): {"type": "bezier-surface", "points": layer(ax, 2 * side)}
                     for ax in range(3) for side in (0, 1)}
            bodies.append({"type": "body2", "name": "b%d_%d_%d" % (i, j, k), "faces": faces})
json.dump({"coons": 1, "units": "mm", "operation": "union", "bodies": bodies},
          open(work + "/body2.json", "w"))
PY

venv=$build/bench-venv
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c 'import manifold3d' 2>/dev/null; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q numpy manifold3d
fi
cat > "$work/mf.py" <<'PY'
import glob, sys, time, numpy as np
from manifold3d import Manifold, Mesh, OpType
def read_stl(p):
    d = open(p, 'rb').read()
    k = int.from_bytes(d[80:84], 'little')
    rec = np.frombuffer(d, dtype=np.dtype([('n', '<f4', 3), ('v', '<f4', (3, 3)), ('a', '<u2')]), count=k, offset=84)
    v = rec['v'].reshape(-1, 3)
    u, inv = np.unique(v, axis=0, return_inverse=True)
    return Manifold(Mesh(vert_properties=u.astype(np.float32), tri_verts=inv.reshape(-1, 3).astype(np.uint32)))
ms = [read_stl(p) for p in sorted(glob.glob(sys.argv[1] + "/cell-*.stl"))]
t0 = time.perf_counter()
u = Manifold.batch_boolean(ms, OpType.Add)
mesh = u.to_mesh()   # forces the lazy Boolean
t1 = time.perf_counter()
v = np.asarray(mesh.vert_properties)[:, :3]; t = np.asarray(mesh.tri_verts)
rec = np.zeros(len(t), dtype=np.dtype([('n', '<f4', 3), ('v', '<f4', (3, 3)), ('a', '<u2')]))
rec['v'] = v[t]
with open(sys.argv[2], 'wb') as f:
    f.write(b'manifold3d'.ljust(80, b' ')); f.write(len(t).to_bytes(4, 'little')); f.write(rec.tobytes())
print("boolean %.3f triangles %d" % (t1 - t0, len(t)))
PY

for kind in body0 body2; do
  model=$work/$kind.json
  echo
  echo "== $kind: $n x $n x $n cells ($((n * n * n)) bodies), model $(stat -c %s "$model") bytes =="
  ours=()
  for _ in $(seq "$repeat"); do
    t0=$(now); "$bin" "$model" -o "$work/ours.stl"; t1=$(now)
    ours+=("$(elapsed "$t0" "$t1")")
  done
  bytes=$(stat -c %s "$work/ours.stl")
  tris=$(( (bytes - 84) / 50 ))
  floor=()
  for _ in $(seq "$repeat"); do
    t0=$(now)
    cat "$model" >/dev/null
    dd if=/dev/zero of="$work/floor.bin" bs="$bytes" count=1 conv=fsync status=none
    t1=$(now)
    floor+=("$(elapsed "$t0" "$t1")")
  done
  # The cells' shells for manifold3d (untimed).
  cells=$((n * n * n))
  rm -f "$work"/cell-*.stl
  for i in $(seq 0 $((cells - 1))); do
    "$bin" "$model" --body "$i" -o "$(printf '%s/cell-%05d.stl' "$work" "$i")"
  done
  t0=$(now); mf=$("$venv/bin/python" "$work/mf.py" "$work" "$work/mf.stl"); t1=$(now)
  mf_all=$(elapsed "$t0" "$t1")
  mf_bool=$(echo "$mf" | awk '{print $2}')
  o=$(min "${ours[@]}"); fl=$(min "${floor[@]}")
  echo "coons2stl model -> STL:        $o s  ($tris triangles, $bytes bytes; runs: ${ours[*]})"
  echo "I/O floor (read + write+fsync): $fl s  (runs: ${floor[*]})"
  echo "manifold3d whole process:      $mf_all s  (Boolean alone $mf_bool s; $(echo "$mf" | awk '{print $4}') triangles)"
  echo "ratios: coons2stl / floor = $(ratio "$o" "$fl"), coons2stl / manifold3d whole = $(ratio "$o" "$mf_all"), coons2stl / manifold3d Boolean = $(ratio "$o" "$mf_bool")"
done
echo
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
