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
# Each is the minimum of REPEAT runs, as wall time and as CPU time (user +
# system, /usr/bin/time); the machine is shared, so the load average is
# printed: compare ratios, and CPU times.
# Usage: tools/bench/bench_deform.sh [BUILD_DIR [N [REPEAT]]]
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$here/build}" && pwd)
n=${2:-289}
repeat=${3:-3}
bin=$build/tools/coons2stl
cmake --build "$build" --target coons2stl coons >/dev/null
work=$(mktemp -d "$build/bench-deform.XXXXXX")
trap 'rm -rf "$work"' EXIT
min() { printf '%s\n' "$@" | sort -g | head -1; }
# timed VAR CMD...: runs CMD, appends its wall time to VAR_wall and its CPU
# time to VAR_cpu
timed() {
  local var=$1 t
  shift
  /usr/bin/time -f "%e %U %S" -o "$work/time" "$@" >/dev/null
  read -r w u s <"$work/time"
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
cc -O2 -I"$here/include" -I"$build/include" "$work/rw.c" -o "$work/rw" \
  -L"$build/src" -Wl,-rpath,"$build/src" -lcoons
tris=$(python3 -c "import struct,sys; print(struct.unpack_from('<I', open(sys.argv[1],'rb').read(84), 80)[0])" "$work/cube.stl")
echo "input: $tris triangles, $(stat -c %s "$work/cube.stl") bytes"

floor_wall=() floor_cpu=() spool_wall=() spool_cpu=() ident_wall=() ident_cpu=()
for _ in $(seq "$repeat"); do
  timed floor "$work/rw" "$work/cube.stl" "$work/copy.stl"
  timed spool "$bin" -q "$here/examples/spool.json" --deform "$work/cube.stl" --body spool \
    -o "$work/spool.stl"
  timed ident "$bin" -q "$work/identity.json" --deform "$work/cube.stl" -o "$work/ident.stl"
done
out_tris=$(python3 -c "import struct,sys; print(struct.unpack_from('<I', open(sys.argv[1],'rb').read(84), 80)[0])" "$work/spool.stl")
info=$("$bin" -q "$here/examples/spool.json" --deform "$work/cube.stl" --body spool --info)
dev=$(python3 -c "import json,sys; d=json.loads(sys.argv[1])['deform']; print('%.4g of tolerance %.4g, %d rounds, output closed: %s' % (d['deviation'], d['tolerance'], d['rounds'], d['output_mesh']['closed']))" "$info")
python3 - "$tris" "$out_tris" "$dev" "$(min "${floor_wall[@]}")" "$(min "${floor_cpu[@]}")" \
  "$(min "${spool_wall[@]}")" "$(min "${spool_cpu[@]}")" "$(min "${ident_wall[@]}")" \
  "$(min "${ident_cpu[@]}")" <<'PY'
import sys
tris, out, dev = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
fw, fc, sw, sc, iw, ic = map(float, sys.argv[4:10])
print(f"{'':38s} {'wall':>8s} {'CPU':>8s} {'tri/s (wall)':>13s} {'tri/s (CPU)':>12s} "
      f"{'x floor (wall)':>15s} {'x floor (CPU)':>14s}")
for name, w, c in (("I/O floor: read + write the STL", fw, fc),
                   ("--deform through the spool (body 2)", sw, sc),
                   ("--deform through the identity body 0", iw, ic)):
    print(f"{name:38s} {w:7.2f}s {c:7.2f}s {tris / w:13.0f} {tris / max(c, 1e-9):12.0f} "
          f"{w / fw:15.1f} {c / max(fc, 1e-9):14.1f}")
print(f"spool: {tris} triangles in, {out} out; deviation {dev}")
PY
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
