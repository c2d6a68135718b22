#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Free-form deformation benchmark (issue 12, README "Free-form deformation"):
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
# Each is the minimum of REPEAT runs; the machine is shared, so the load
# average is printed: compare ratios.
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
now() { date +%s.%N; }
elapsed() { python3 -c "print('%.3f' % ($2 - $1))"; }
min() { printf '%s\n' "$@" | sort -g | head -1; }

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

floor=() spool=() ident=()
for _ in $(seq "$repeat"); do
  t0=$(now); "$work/rw" "$work/cube.stl" "$work/copy.stl" >/dev/null; t1=$(now)
  floor+=("$(elapsed "$t0" "$t1")")
  t0=$(now); "$bin" -q "$here/examples/spool.json" --deform "$work/cube.stl" --body spool \
    -o "$work/spool.stl"; t1=$(now)
  spool+=("$(elapsed "$t0" "$t1")")
  t0=$(now); "$bin" -q "$work/identity.json" --deform "$work/cube.stl" -o "$work/ident.stl"; t1=$(now)
  ident+=("$(elapsed "$t0" "$t1")")
done
out_tris=$(python3 -c "import struct,sys; print(struct.unpack_from('<I', open(sys.argv[1],'rb').read(84), 80)[0])" "$work/spool.stl")
info=$("$bin" -q "$here/examples/spool.json" --deform "$work/cube.stl" --body spool --info)
dev=$(python3 -c "import json,sys; d=json.loads(sys.argv[1])['deform']; print('%.4g of tolerance %.4g, %d rounds, output closed: %s' % (d['deviation'], d['tolerance'], d['rounds'], d['output_mesh']['closed']))" "$info")
f=$(min "${floor[@]}") s=$(min "${spool[@]}") i=$(min "${ident[@]}")
python3 - "$tris" "$out_tris" "$f" "$s" "$i" "$dev" <<'PY'
import sys
tris, out, f, s, i = int(sys.argv[1]), int(sys.argv[2]), *map(float, sys.argv[3:6])
print(f"I/O floor (read + write the STL):           {f:7.3f} s")
print(f"--deform through the spool (body 2):        {s:7.3f} s  {tris / s:10.0f} input triangles/s, "
      f"{out} out, ratio to the floor {s / f:.2f}")
print(f"--deform through the identity body 0:       {i:7.3f} s  {tris / i:10.0f} input triangles/s, "
      f"ratio to the floor {i / f:.2f}")
print(f"spool: deviation {sys.argv[6]}")
PY
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
