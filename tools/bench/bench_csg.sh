#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Union benchmark, all in one run (BENCHMARKS.md): three overlapping
# bodies (spool, nail, deformed cube) sampled at about 100k triangles each,
#  1. libcoons: model file -> sampled shells -> repair + union (CGAL) ->
#     binary STL (bench_csg --model-path, minimum of 3 runs), on 1 and on 2
#     threads, with the time of each stage;
#  2. manifold3d (pip-installed into a virtual environment in the build
#     directory) uniting the same three STL shells: whole process (start,
#     read, weld, union, write STL) and the Boolean alone;
#  3. OpenSCAD 2021 rendering union(){import(...)} of the same STLs
#     (stopped after OPENSCAD_TIMEOUT seconds, default 1800).
#  4. two cubes sharing a face (a cube and its mirror image, 2 N^2 = 16,928
#     triangles on the shared face): libcoons glues them by index (no
#     Boolean), against manifold3d's Boolean of the two STL shells;
#  5. ten disjoint bodies: libcoons model -> STL against its own sampling
#     plus writing of the same shells (the floor).
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
echo "== libcoons: model -> union -> binary STL (min of 3), 1 thread =="
"$build/tools/bench/bench_csg" "$model" --model-path --threads 1 --resolution "$res" --dir "$work" | tee "$work/ours.txt"
echo "== the same, 2 threads =="
"$build/tools/bench/bench_csg" "$model" --model-path --threads 2 --resolution "$res" --dir "$work" | tee "$work/ours2.txt"
get() { awk -v k="$1" '$1 == k {print $2}' "$work/ours.txt"; }
get2() { awk -v k="$1" '$1 == k {print $2}' "$work/ours2.txt"; }

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
# manifold3d on DIR/body*.stl: best whole process of 3 into $best, its
# Boolean (the run's minimum) into $mf_bool.
run_mf() {
  best=1e9; mf_bool=1e9
  for i in 1 2 3; do
    t0=$(now)
    "$venv/bin/python" "$work/mf.py" "$work/mf.stl" "$1"/body*.stl > "$work/mf.txt"
    t1=$(now)
    best=$(python3 -c "print(min($best, $t1 - $t0))")
    mf_bool=$(python3 -c "print(min($mf_bool, $(awk '$1=="boolean_s"{print $2}' "$work/mf.txt")))")
  done
  cat "$work/mf.txt"; echo "process_s $best"; echo "boolean_min_s $mf_bool"
}
run_mf "$work"

echo
echo "== OpenSCAD $(openscad --version 2>&1 | awk '{print $NF}'): union(){import(...)} =="
{ echo "union() {"; for f in "$work"/body*.stl; do echo "  import(\"$f\");"; done; echo "}"; } > "$work/u.scad"
t0=$(now)
if timeout "${OPENSCAD_TIMEOUT:-1800}" openscad -o "$work/os.stl" "$work/u.scad" > "$work/os.log" 2>&1; then
  t1=$(now); os=$(python3 -c "print('%.2f' % ($t1 - $t0))"); echo "openscad_s $os"
else
  os=""; echo "openscad: failed or timed out after ${OPENSCAD_TIMEOUT:-1800} s"; tail -3 "$work/os.log"
fi

three_mfp=$best; three_mfb=$mf_bool

# ---- two cubes sharing a face, ten disjoint bodies ----------------------------
python3 - "$work" "$model" <<'PY'
import json, sys, copy
work, model = sys.argv[1:]
def box(name, lo, hi):
    c = []
    for n in range(8):
        i, j, k = n >> 2, (n >> 1) & 1, n & 1
        c.append([(lo, hi)[i][0], (lo, hi)[j][1], (lo, hi)[k][2]])
    return {"type": "body0", "name": name, "corners": c}
left = box("left", [0, 0, 0], [10, 10, 10])
# its mirror image in the plane x = 10 (left-handed: u runs towards -x)
right = {"type": "body0", "name": "right",
         "corners": [[20 - p[0], p[1], p[2]] for p in left["corners"]]}
json.dump({"coons": 1, "operation": "union", "bodies": [left, right]},
          open(work + "/share.json", "w"))
src = json.load(open(model))["bodies"]
def moved(b, dx):
    b = copy.deepcopy(b)
    def shift(x):
        if isinstance(x, list) and len(x) == 3 and all(isinstance(v, (int, float)) for v in x):
            return [x[0] + dx, x[1], x[2]]
        return [shift(y) for y in x] if isinstance(x, list) else x
    def walk(o):
        if isinstance(o, dict):
            for k, v in o.items():
                o[k] = shift(v) if k in ("points", "corners") else walk(v)
        return o
    return walk(b)
ten = []
for i in range(10):
    b = moved(src[[0, 2][i % 2]], 30.0 * i)
    b["name"] = "b%d" % i
    ten.append(b)
json.dump({"coons": 1, "operation": "union", "bodies": ten}, open(work + "/ten.json", "w"))
PY
mkdir -p "$work/share" "$work/ten"
echo
echo "== two cubes sharing a face (left and its mirror image), libcoons 1 and 2 threads =="
"$build/tools/bench/bench_csg" "$work/share.json" --model-path --threads 1 --resolution "$res" --dir "$work/share" | tee "$work/sh1.txt"
"$build/tools/bench/bench_csg" "$work/share.json" --model-path --threads 2 --resolution "$res" --dir "$work/share" | tee "$work/sh2.txt"
echo "-- the same, 1 thread, --no-repair (no self-intersection check of the glued shell) --"
"$build/tools/bench/bench_csg" "$work/share.json" --model-path --threads 1 --no-repair --resolution "$res" --dir "$work/share" | tee "$work/sh3.txt"
echo "== manifold3d: the two cube shells =="
run_mf "$work/share"
share_mfb=$mf_bool; share_mfp=$best
echo
echo "== ten disjoint bodies (spools and cubes), libcoons 1 and 2 threads =="
"$build/tools/bench/bench_csg" "$work/ten.json" --model-path --threads 1 --resolution "$res" --dir "$work/ten" | tee "$work/ten1.txt"
"$build/tools/bench/bench_csg" "$work/ten.json" --model-path --threads 2 --resolution "$res" --dir "$work/ten" | tee "$work/ten2.txt"
echo "-- the same, 1 thread, --no-repair (no self-intersection checks) --"
"$build/tools/bench/bench_csg" "$work/ten.json" --model-path --threads 1 --no-repair --resolution "$res" --dir "$work/ten" | tee "$work/ten3.txt"
g() { awk -v k="$2" '$1 == k {print $2}' "$1"; }

echo
echo "== ratios =="
python3 - "$(get total_s)" "$(get union_s)" "$(get2 total_s)" "$(get2 union_s)" "$three_mfp" "$three_mfb" "${os:-nan}" \
  "$(g "$work/sh1.txt" total_s)" "$(g "$work/sh2.txt" total_s)" "$(g "$work/sh1.txt" fast_unions)" "$share_mfb" "$share_mfp" \
  "$(g "$work/ten1.txt" total_s)" "$(g "$work/ten1.txt" sample_s)" "$(g "$work/ten1.txt" write_s)" "$(g "$work/ten1.txt" load_s)" \
  "$(g "$work/ten2.txt" total_s)" "$(g "$work/ten2.txt" sample_s)" "$(g "$work/ten2.txt" write_s)" "$(g "$work/ten2.txt" load_s)" \
  "$(g "$work/sh3.txt" total_s)" "$(g "$work/ten3.txt" total_s)" "$(g "$work/ten3.txt" sample_s)" "$(g "$work/ten3.txt" write_s)" "$(g "$work/ten3.txt" load_s)" <<'PY'
import sys
a = sys.argv[1:]
tot, uni, tot2, uni2, mfp, mfb, os_ = map(float, a[:7])
sh1, sh2, shfu, shmfb, shmfp = float(a[7]), float(a[8]), int(a[9]), float(a[10]), float(a[11])
t1, s1, w1, l1, t2, s2, w2, l2 = map(float, a[12:20])
print("three bodies, model->STL: libcoons %.3f s (1 thread), %.3f s (2 threads) vs manifold3d "
      "process %.3f s: manifold3d takes %.2fx / %.2fx" % (tot, tot2, mfp, mfp / tot, mfp / tot2))
print("three bodies, repair+union: libcoons %.3f s / %.3f s vs manifold3d Boolean %.3f s: "
      "libcoons takes %.2fx / %.2fx" % (uni, uni2, mfb, uni / mfb, uni2 / mfb))
if os_ == os_:
    print("OpenSCAD %.1f s: libcoons is %.0fx / %.0fx faster" % (os_, os_ / tot, os_ / tot2))
print("shared face: libcoons model->STL %.3f s / %.3f s (%d corefinements) vs manifold3d Boolean "
      "%.3f s (process %.3f s): manifold3d's Boolean takes %.2fx / %.2fx" %
      (sh1, sh2, shfu, shmfb, shmfp, shmfb / sh1, shmfb / sh2))
sh3, t3, s3, w3, l3 = map(float, a[20:25])
print("shared face, --no-repair: libcoons model->STL %.3f s vs manifold3d Boolean %.3f s: "
      "manifold3d's Boolean takes %.2fx" % (sh3, shmfb, shmfb / sh3))
print("ten disjoint, --no-repair: %.3f s vs sampling+writing %.3f s: %.2fx" %
      (t3, l3 + s3 + w3, t3 / (l3 + s3 + w3)))
print("ten disjoint: libcoons model->STL %.3f s vs sampling+writing %.3f s: %.2fx (1 thread); "
      "%.3f s vs %.3f s: %.2fx (2 threads)" %
      (t1, l1 + s1 + w1, t1 / (l1 + s1 + w1), t2, l2 + s2 + w2, t2 / (l2 + s2 + w2)))
PY
