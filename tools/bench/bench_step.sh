#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Exact-solid benchmark (issue 26, BENCHMARKS.md): 100 bodies to STEP.
#  a. 100 body0 cells on a 10 x 10 x 1 lattice of points (10 mm cells, inner
#     points moved; neighbours share faces), "operation": "none": 100 solids;
#  b. the same cells with "operation": "union": one solid (Open CASCADE's
#     Boolean, shared faces glued);
#  c. 100 curved bodies: quadratic Bezier volumes (27 control points, bent),
#     apart, "operation": "none";
# each timed as coons2stl model -> .step (load, exact faces, sewing, check,
# translation, atomic write), minimum of REPEAT runs, against the same model
# to binary STL (the mesh path) in the same run. The machine is shared: the
# load average is printed; compare ratios.
# Usage: tools/bench/bench_step.sh [BUILD_DIR [REPEAT]]
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$here/build}" && pwd)
repeat=${2:-3}
bin=$build/tools/coons2stl
cmake --build "$build" --target coons2stl >/dev/null
work=$(mktemp -d "$build/bench-step.XXXXXX")
trap 'rm -rf "$work"' EXIT
now() { date +%s.%N; }
min() { printf '%s\n' "$@" | sort -g | head -1; }

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

python3 - "$work" <<'PY'
import json, math, sys
work = sys.argv[1]
n, h = 10, 10.0
def p(i, j, k):
    d = [0.0, 0.0, 0.0]
    if 0 < i < n and 0 < j < n:
        d = [1.5 * math.sin(1.3 * i + 2.1 * j), 1.5 * math.cos(0.9 * i - 1.7 * j), 0.0]
    return [i * h + d[0], j * h + d[1], k * h + d[2]]
cells = [{"type": "body0", "name": "c%d_%d" % (i, j),
          "corners": [p(i + a, j + b, e) for a in (0, 1) for b in (0, 1) for e in (0, 1)]}
         for i in range(n) for j in range(n)]
for op in ("none", "union"):
    json.dump({"coons": 1, "units": "mm", "operation": op, "bodies": cells},
              open("%s/cells-%s.json" % (work, op), "w"))
curved = []
for i in range(n):
    for j in range(n):
        def q(a, b, c):
            x, y, z = 12 * i + 4 * a, 12 * j + 4 * b, 4 * c
            return [x + 0.8 * math.sin(y + z), y + 0.8 * math.cos(x), z + 0.6 * math.sin(x + y)]
        pts = [[[q(a, b, c) for c in range(3)] for b in range(3)] for a in range(3)]
        curved.append({"type": "bezier-volume", "name": "b%d_%d" % (i, j), "points": pts})
json.dump({"coons": 1, "units": "mm", "operation": "none", "bodies": curved},
          open("%s/curved-none.json" % work, "w"))
PY

run() { # model ext -> minimum seconds of REPEAT runs
    local ts=()
    for _ in $(seq "$repeat"); do
        local s e
        s=$(now)
        "$bin" "$1" -o "$work/out.$2" >/dev/null
        e=$(now)
        ts+=("$(python3 -c "print('%.3f' % ($e - $s))")")
    done
    min "${ts[@]}"
}

printf '| model | to STEP | to STL | STEP size |\n|---|---|---|---|\n'
for m in cells-none cells-union curved-none; do
    step=$(run "$work/$m.json" step)
    size=$(stat -c %s "$work/out.step")
    stl=$(run "$work/$m.json" stl)
    printf '| %s | %s s | %s s | %s KB |\n' "$m" "$step" "$stl" "$((size / 1024))"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
