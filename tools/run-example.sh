#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The README's first command: installs what is missing, builds libcoons
# (Release, in ./build) and runs the main job on a bundled example, the spool
# of seed 000 Fig. 7 (examples/spool.json):
#
#     build/tools/coons2stl examples/spool.json -o spool.stl
#
# It builds only what it runs: the library (shared and static) and
# coons2stl, not the tests (`cmake --build build` builds those too), and
# says how long set-up, configuring, building and the run took.
# If this build of coons2stl cannot write meshes yet, it says so and shows
# what it can do instead: the --info report and a few --eval points.
# Environment: COONS_BUILD_DIR (default build), COONS_EXAMPLE (default
# examples/spool.json), COONS_OUTPUT (default spool.stl).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"

build=${COONS_BUILD_DIR:-build}
example=${COONS_EXAMPLE:-examples/spool.json}
output=${COONS_OUTPUT:-spool.stl}
jobs=$(nproc 2>/dev/null || echo 2)

say() { printf 'run-example: %s\n' "$*" >&2; }

# Wall-clock seconds with a tenth (bash's $EPOCHREALTIME), per stage.
now() { local t=${EPOCHREALTIME/,/.}; echo "${t%????}"; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }
t0=$(now)
timing() {
  local t_end
  t_end=$(now)
  say "took $(secs "$t0" "$t_end") s: set-up $(secs "$t0" "$t1") s, configure $(secs "$t1" "$t2") s," \
    "build $(secs "$t2" "$t3") s, run $(secs "$t3" "$t_end") s"
}

say "installing missing packages (tools/setup.sh)"
bash tools/setup.sh
t1=$(now)

say "configuring ($build, Release)"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
t2=$(now)
say "building the library and coons2stl"
cmake --build "$build" -j "$jobs" --target coons coons_static coons2stl
t3=$(now)

bin="$build/tools/coons2stl"
if [ ! -x "$bin" ]; then
  say "this checkout has no coons2stl yet (tools/coons2stl/): the library is built, nothing to run"
  exit 1
fi

say "meshing: $bin $example -o $output"
set +e
"$bin" "$example" -o "$output" 2>"$build/run-example.err"
rc=$?
set -e
if [ $rc -eq 0 ] && [ -s "$output" ]; then
  cat "$build/run-example.err" >&2
  size=$(wc -c <"$output")
  say "wrote $output ($size bytes) from $example"
  timing
  exit 0
fi

# Meshing is not available (or failed): say what coons2stl said, then do
# the best this build can do.
say "coons2stl could not write a mesh (exit status $rc):"
sed 's/^/    /' "$build/run-example.err" >&2
say "showing instead what this build can do with $example"

say "report: $bin --info $example"
"$bin" --info "$example"

say "evaluation: $bin --eval $example  (lines 'u v w' in, points 'x y z' out)"
printf '%s\n' "0 0 0" "1 1 1" "0.5 0.5 0" "0.5 0.5 0.5" "0.5 0.5 1" "0 0.5 0.5" | "$bin" --eval "$example"
say "the spool is round: (0 0.5 0.5) lies at distance r(0.5) = 2.5 from the z axis"
timing
exit 0
