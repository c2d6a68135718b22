#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Free-form deformation benchmark (issue 12, BENCHMARKS.md):
# a unit cube whose faces are N x N grids of squares, two triangles each
# (default N = 289: 1 002 252 triangles, a 50 MB binary STL), deformed
#  1. through the spool (examples/spool.json, a body 2 of NURBS faces) at the
#     default tolerance (1/1000 of the image's box diagonal):
#     coons2stl --deform cube.stl --body spool -o out.stl;
#  2. through the identity body 0 (the unit cube's corners), which splits
#     nothing: the same command with a trilinear map;
# against the I/O floor: a small program (built here against the library)
# that reads the same STL with coons_mesh_read_file() and writes it back with
# coons_mesh_write() (the atomic writer, fsync included), as coons2stl does.
# and against the raw I/O floor: the same bytes read and written back with
# fsync by a plain C program (no parsing, no welding).
# With --blender (or BLENDER=1), also Blender's Lattice modifier (a 5 x 5 x 5
# B-spline lattice over the same cube, pinched like the spool) on the same
# STL, headless (tools/bench/blender_lattice.py): its modifier alone (the
# evaluation with the modifier minus without it) and its whole process
# (start, STL import, deform, STL export). Blender is installed with apt
# when asked and missing; the test command never runs this.
# Each is the minimum of REPEAT runs, as wall time and as CPU time (user +
# system, /usr/bin/time); the machine is shared, so the load average is
# printed: compare ratios, and CPU times.
# Usage: tools/bench/bench_deform.sh [--blender] [BUILD_DIR [N [REPEAT]]]
set -euo pipefail
blender=${BLENDER:-0}
if [ "${1:-}" = --blender ]; then blender=1; shift; fi
here=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$here/build}" && pwd)
n=${2:-289}
repeat=${3:-3}
bin=$build/tools/coons2stl
cmake --build "$build" --target coons2stl coons >/dev/null
if [ "$blender" = 1 ] && ! command -v blender >/dev/null; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get -o DPkg::Lock::Timeout=600 install -y -qq --no-install-recommends blender >/dev/null
fi
work=$(mktemp -d "$build/bench-deform.XXXXXX")
trap 'rm -rf "$work"' EXIT
min() { printf '%s\n' "$@" | sort -g | head -1; }
# timed VAR CMD...: runs CMD, appends its wall time to VAR_wall and its CPU
# time to VAR_cpu
timed() {
  local var=$1 t
  shift
  local t0=$EPOCHREALTIME
  /usr/bin/time -f "%e %U %S" -o "$work/time" "$@" >/dev/null
  local t1=$EPOCHREALTIME
  read -r w u s <"$work/time"
  w=$(python3 -c "print('%.4f' % ($t1 - $t0))")
  eval "${var}_wall+=($w)"
  t=$(python3 -c "print('%.2f' % ($u + $s))")
  eval "${var}_cpu+=($t)"
}

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

python3 - "$work/cube.stl" "$n" <<'PY'
import struct, sys
path, n = sys.argv[1], int(sys.argv[2])
out = bytearray(b"unit cube, %d x %d squares per face" % (n, n))
out += b" " * (80 - len(out)) + struct.pack("<I", 12 * n * n)
rec = struct.Struct("<12fH")
g = [i / n for i in range(n + 1)]
for d in range(3):
    a, b = (d + 1) % 3, (d + 2) % 3
    for side in (0.0, 1.0):
        for i in range(n):
            for j in range(n):
                c = []
                for (s, t) in ((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)):
                    p = [0.0, 0.0, 0.0]
                    p[d], p[a], p[b] = side, g[s], g[t]
                    c.append(p)
                if side == 0.0:  # outward: the normal is -e_d
                    c = [c[0], c[3], c[2], c[1]]
                for tri in ((c[0], c[1], c[2]), (c[0], c[2], c[3])):
                    out += rec.pack(0, 0, 0, *tri[0], *tri[1], *tri[2], 0)
with open(path, "wb") as f:
    f.write(out)
PY
cat >"$work/identity.json" <<'JSON'
{"coons": 1, "units": "mm", "bodies": [{"type": "body0", "name": "identity", "corners":
 [[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]}
JSON
cat >"$work/rw.c" <<'C'
#include <coons.h>
#include <stdio.h>
int main(int argc, char **argv)
{
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *m = NULL;
    if (argc != 3 || coons_mesh_read_file(argv[1], NULL, &m, &err) != COONS_OK ||
        coons_mesh_write(m, argv[2], COONS_FORMAT_STL_BINARY, NULL, &err) != COONS_OK) {
        fprintf(stderr, "rw: %s\n", err.message);
        return 1;
    }
    printf("%zu\n", coons_mesh_triangle_count(m));
    coons_mesh_free(m);
    return 0;
}
C
cat >"$work/raw.c" <<'C'
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>
/* The raw I/O floor: the file's bytes read and written back, fsync'ed. */
int main(int argc, char **argv)
{
    struct stat st;
    int in = open(argv[1], O_RDONLY);
    if (argc != 3 || in < 0 || fstat(in, &st) != 0) return 1;
    char *buf = malloc((size_t)st.st_size + 1);
    size_t got = 0;
    ssize_t r;
    while (buf && (r = read(in, buf + got, (size_t)st.st_size - got)) > 0) got += (size_t)r;
    close(in);
    int out = open(argv[2], O_WRONLY | O_CREAT | O_TRUNC, 0644);
    size_t put = 0;
    ssize_t w;
    while (out >= 0 && put < got && (w = write(out, buf + put, got - put)) > 0) put += (size_t)w;
    if (out < 0 || put != got || fsync(out) != 0 || close(out) != 0) return 1;
    free(buf);
    return 0;
}
C
cat >"$work/map.c" <<'C'
#include <coons.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>
/* The mapping of vertices alone: the STL's vertices (welded, as --deform
 * reads them) as parameters of the frame of their box, evaluated through
 * the body with coons_body_eval_points, on one thread and on every core
 * (contiguous chunks); best of 5 each. Prints seconds and ns per vertex. */
typedef struct { const coons_body *b; size_t n; const double *q; double *x; } job;
static void *run(void *a)
{
    job *j = a;
    coons_body_eval_points(j->b, j->n, j->q, j->x, NULL, NULL, NULL);
    return NULL;
}
static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}
static double timed(const coons_body *b, size_t n, const double *q, double *x, int k)
{
    double best = 1e30;
    for (int r = 0; r < 5; r++) {
        pthread_t t[64];
        job j[64];
        double t0 = now();
        for (int c = 0; c < k; c++) {
            size_t lo = n * c / k, hi = n * (c + 1) / k;
            j[c] = (job){b, hi - lo, q + 3 * lo, x + 3 * lo};
            if (c) pthread_create(&t[c], NULL, run, &j[c]);
        }
        run(&j[0]);
        for (int c = 1; c < k; c++) pthread_join(t[c], NULL);
        double dt = now() - t0;
        if (dt < best) best = dt;
    }
    return best;
}
int main(int argc, char **argv)
{
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    coons_mesh *mesh = NULL;
    if (argc != 4 || coons_model_load_file(argv[1], NULL, &m, &err) != COONS_OK ||
        coons_mesh_read_file(argv[3], NULL, &mesh, &err) != COONS_OK) {
        fprintf(stderr, "map: %s\n", err.message);
        return 1;
    }
    const coons_body *b = coons_model_body(m, (size_t)coons_model_find_body(m, argv[2]));
    size_t n = coons_mesh_vertex_count(mesh);
    const double *v = coons_mesh_vertices(mesh);
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (size_t i = 0; i < 3 * n; i++) {
        if (v[i] < lo[i % 3]) lo[i % 3] = v[i];
        if (v[i] > hi[i % 3]) hi[i % 3] = v[i];
    }
    double *q = malloc(3 * n * sizeof *q), *x = malloc(3 * n * sizeof *x);
    for (size_t i = 0; i < 3 * n; i++) q[i] = (v[i] - lo[i % 3]) / (hi[i % 3] - lo[i % 3]);
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    int k = cores < 1 ? 1 : cores > 64 ? 64 : (int)cores;
    double t1 = timed(b, n, q, x, 1), tk = timed(b, n, q, x, k);
    printf("MAP %zu %.6f %.6f %d\n", n, t1, tk, k);
    return 0;
}
C
cc -O2 -I"$here/include" -I"$build/include" "$work/map.c" -o "$work/map" \
  -L"$build/src" -Wl,-rpath,"$build/src" -lcoons -lpthread
cc -O2 "$work/raw.c" -o "$work/raw"
cc -O2 -I"$here/include" -I"$build/include" "$work/rw.c" -o "$work/rw" \
  -L"$build/src" -Wl,-rpath,"$build/src" -lcoons
tris=$(python3 -c "import struct,sys; print(struct.unpack_from('<I', open(sys.argv[1],'rb').read(84), 80)[0])" "$work/cube.stl")
echo "input: $tris triangles, $(stat -c %s "$work/cube.stl") bytes"

floor_wall=() floor_cpu=() spool_wall=() spool_cpu=() ident_wall=() ident_cpu=()
raw_wall=() raw_cpu=() j1_wall=() j1_cpu=() blend_wall=() blend_cpu=()
for _ in $(seq "$repeat"); do
  timed raw "$work/raw" "$work/cube.stl" "$work/raw.stl"
  timed floor "$work/rw" "$work/cube.stl" "$work/copy.stl"
  timed j1 "$bin" -q -j 1 "$here/examples/spool.json" --deform "$work/cube.stl" --body spool \
    -o "$work/spool1.stl"
  if [ "$blender" = 1 ]; then
    timed blend blender -b --factory-startup --python "$here/tools/bench/blender_lattice.py" \
      -- "$work/cube.stl" "$work/blender.stl" 0
  fi
  timed spool "$bin" -q "$here/examples/spool.json" --deform "$work/cube.stl" --body spool \
    -o "$work/spool.stl"
  timed ident "$bin" -q "$work/identity.json" --deform "$work/cube.stl" -o "$work/ident.stl"
done
out_tris=$(python3 -c "import struct,sys; print(struct.unpack_from('<I', open(sys.argv[1],'rb').read(84), 80)[0])" "$work/spool.stl")
cmp -s "$work/spool.stl" "$work/spool1.stl" || { echo "bench_deform: -j 1 and all cores differ" >&2; exit 1; }
info=$("$bin" -q "$here/examples/spool.json" --deform "$work/cube.stl" --body spool --info)
dev=$(python3 -c "import json,sys; d=json.loads(sys.argv[1])['deform']; print('%.4g of tolerance %.4g, %d rounds, output closed: %s' % (d['deviation'], d['tolerance'], d['rounds'], d['output_mesh']['closed']))" "$info")
blend_line=""
if [ "$blender" = 1 ]; then
  blend_line=$(blender -b --factory-startup --python "$here/tools/bench/blender_lattice.py" \
    -- "$work/cube.stl" "$work/blender.stl" "$repeat" 2>&1 | grep '^BLENDER' || true)
fi
map_line=$("$work/map" "$here/examples/spool.json" spool "$work/cube.stl")
python3 - "$tris" "$out_tris" "$dev" "$blend_line" "$map_line" \
  "$(min "${raw_wall[@]}")" "$(min "${raw_cpu[@]}")" \
  "$(min "${floor_wall[@]}")" "$(min "${floor_cpu[@]}")" \
  "$(min "${spool_wall[@]}")" "$(min "${spool_cpu[@]}")" \
  "$(min "${j1_wall[@]}")" "$(min "${j1_cpu[@]}")" \
  "$(min "${ident_wall[@]}")" "$(min "${ident_cpu[@]}")" \
  "$(min "${blend_wall[@]:-0}")" "$(min "${blend_cpu[@]:-0}")" <<'PY'
import sys
tris, out, dev, bl, mp = int(sys.argv[1]), int(sys.argv[2]), *sys.argv[3:6]
rw, rc, fw, fc, sw, sc, jw, jc, iw, ic, bw, bc = map(float, sys.argv[6:18])
print(f"{'':44s} {'wall':>8s} {'CPU':>8s} {'tri/s (wall)':>13s} "
      f"{'x raw floor (wall)':>19s} {'x floor (wall)':>15s}")
rows = [("raw I/O floor: the bytes read, written, fsync", rw, rc),
        ("I/O floor: coons_mesh_read_file + write", fw, fc),
        ("--deform through the spool, all cores", sw, sc),
        ("--deform through the spool, -j 1", jw, jc),
        ("--deform through the identity body 0", iw, ic)]
if bw > 0:
    rows.append(("Blender: start, import, Lattice, export", bw, bc))
for name, w, c in rows:
    print(f"{name:44s} {w:7.3f}s {c:7.3f}s {tris / w:13.0f} {w / rw:19.1f} {w / fw:15.1f}")
print(f"spool: {tris} triangles in, {out} out; deviation {dev}")
f = mp.split()
mn, m1, mk, k = int(f[1]), float(f[2]), float(f[3]), int(f[4])
print(f"mapping {mn} vertices through the spool (coons_body_eval_points): "
      f"{m1:.4f} s on 1 thread ({m1 / mn * 1e9:.0f} ns per vertex), {mk:.4f} s on {k}")
if bl:
    f = bl.split()
    nv, mod = int(f[2]), float(f[4])
    print(f"Blender's Lattice modifier alone: {mod:.4f} s for {nv} vertices "
          f"({mod / nv * 1e9:.0f} ns per vertex); libcoons' mapping on {k} / Blender's: "
          f"{mk / mod:.2f}")
    print(f"coons2stl --deform (all cores) / Blender's whole process: {sw / bw:.3f}")
PY
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
