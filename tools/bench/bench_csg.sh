#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Union benchmark, all in one run (README "Benchmarks"): three overlapping
# bodies (spool, nail, deformed cube) sampled at about 100k triangles each,
#  1. libcoons: model file -> sampled shells -> repair + union (CGAL, exact
#     kernel) -> binary STL (bench_csg, minimum of 3 runs);
#  2. manifold3d (pip-installed into a virtual environment in the build
#     directory) uniting the same three STL shells: whole process (start,
#     read, weld, union, write STL) and the Boolean alone;
#  3. OpenSCAD 2021 rendering union(){import(...)} of the same STLs
#     (stopped after OPENSCAD_TIMEOUT seconds, default 1800).
# Usage: tools/bench/bench_csg.sh [BUILD_DIR [N]]  (default build, N = 92)
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$here/build}" && pwd)
res=${2:-92}
model=$here/tests/data/ok/three-examples-union.json
cmake --build "$build" --target bench_csg >/dev/null
work=$(mktemp -d "$build/bench-csg.XXXXXX")
trap 'rm -rf "$work"' EXIT
now() { date +%s.%N; }

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "== libcoons: model -> union -> binary STL (min of 3) =="
"$build/tools/bench/bench_csg" "$model" --resolution "$res" --dir "$work" | tee "$work/ours.txt"
get() { awk -v k="$1" '$1 == k {print $2}' "$work/ours.txt"; }

echo
echo "== manifold3d: the same three STL shells =="
venv=$build/bench-venv
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c 'import manifold3d' 2>/dev/null; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q numpy manifold3d
fi
cat > "$work/mf.py" <<'PY'
import sys, time, numpy as np
from manifold3d import Manifold, Mesh
def read_stl(p):
    d = open(p, 'rb').read()
    n = int.from_bytes(d[80:84], 'little')
    rec = np.frombuffer(d, dtype=np.dtype([('n', '<f4', 3), ('v', '<f4', (3, 3)), ('a', '<u2')]), count=n, offset=84)
    v = rec['v'].reshape(-1, 3)
    u, inv = np.unique(v, axis=0, return_inverse=True)
    return Manifold(Mesh(vert_properties=u.astype(np.float32), tri_verts=inv.reshape(-1, 3).astype(np.uint32)))
def write_stl(p, m):
    mesh = m.to_mesh()
    v = np.asarray(mesh.vert_properties)[:, :3]; t = np.asarray(mesh.tri_verts)
    rec = np.zeros(len(t), dtype=np.dtype([('n', '<f4', 3), ('v', '<f4', (3, 3)), ('a', '<u2')]))
    rec['v'] = v[t]
    with open(p, 'wb') as f:
        f.write(b'manifold3d'.ljust(80, b' ')); f.write(len(t).to_bytes(4, 'little')); f.write(rec.tobytes())
    return len(t)
ms = [read_stl(p) for p in sys.argv[2:]]
t0 = time.perf_counter()
u = ms[0]
for m in ms[1:]:
    u = u + m
n = len(u.to_mesh().tri_verts)   # forces the lazy Boolean
t1 = time.perf_counter()
write_stl(sys.argv[1], u)
print("boolean_s %.4f" % (t1 - t0)); print("triangles_out %d" % n); print("volume %.9g" % u.volume())
PY
best=1e9
for i in 1 2 3; do
  t0=$(now)
  "$venv/bin/python" "$work/mf.py" "$work/mf.stl" "$work"/body*.stl > "$work/mf.txt"
  t1=$(now)
  best=$(python3 -c "print(min($best, $t1 - $t0))")
done
cat "$work/mf.txt"; echo "process_s $best"
mf_bool=$(awk '$1=="boolean_s"{print $2}' "$work/mf.txt")

echo
echo "== OpenSCAD $(openscad --version 2>&1 | awk '{print $NF}'): union(){import(...)} =="
{ echo "union() {"; for f in "$work"/body*.stl; do echo "  import(\"$f\");"; done; echo "}"; } > "$work/u.scad"
t0=$(now)
if timeout "${OPENSCAD_TIMEOUT:-1800}" openscad -o "$work/os.stl" "$work/u.scad" > "$work/os.log" 2>&1; then
  t1=$(now); os=$(python3 -c "print('%.2f' % ($t1 - $t0))"); echo "openscad_s $os"
else
  os=""; echo "openscad: failed or timed out after ${OPENSCAD_TIMEOUT:-1800} s"; tail -3 "$work/os.log"
fi

echo
echo "== ratios =="
python3 - "$(get total_s)" "$(get union_s)" "$best" "$mf_bool" "${os:-nan}" <<'PY'
import sys
tot, uni, mfp, mfb, os_ = map(float, sys.argv[1:])
print("libcoons model->STL %.3f s vs manifold3d process %.3f s: %.2fx" % (tot, mfp, mfp / tot))
print("Boolean: libcoons %.3f s vs manifold3d %.3f s: libcoons takes %.2fx" % (uni, mfb, uni / mfb))
if os_ == os_:
    print("OpenSCAD %.1f s: libcoons is %.0fx faster" % (os_, os_ / tot))
PY
