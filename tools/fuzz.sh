#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Fuzzes the model loader and the evaluation of whatever loads
# (tests/fuzz/fuzz_model.c) with libFuzzer, AddressSanitizer and
# UndefinedBehaviorSanitizer for SECONDS seconds (default 60).
#
#   tools/fuzz.sh [SECONDS] [extra libFuzzer options...]
#   tools/fuzz.sh solid [SECONDS] [extra libFuzzer options...]
#   tools/fuzz.sh mesh [SECONDS] [extra libFuzzer options...]
#
# The second form fuzzes the target through repair and union
# (tests/fuzz/fuzz_solid.c, CGAL instrumented too: the first build takes
# several minutes; build directory build-fuzz-solid). The third fuzzes the
# mesh reader of --deform and the deformation (tests/fuzz/fuzz_mesh.c,
# seeds and findings in tests/fuzz/mesh/).
#
# Seeds: examples/*.json, tests/data/**/*.json and tests/fuzz/regressions/.
# New interesting inputs accumulate in $COONS_FUZZ_BUILD/corpus (default
# build-fuzz/corpus) and are reused by the next run. Any crash, leak,
# sanitizer report, failed check, timeout (> 10 s for one input) or
# allocation above 512 MB stops the run with a non-zero status; the input
# is saved as tests/fuzz/regressions/<kind>-<sha1>. Fix the bug, keep the
# file (rename it to say what it is): ctest's fuzz_regressions replays it.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"
target=fuzz_model
case "${1:-}" in
  solid) target=fuzz_solid; shift ;;
  mesh) target=fuzz_mesh; shift ;;
esac
secs=${1:-60}
shift || true
if [ $target = fuzz_solid ]; then
  build=${COONS_FUZZ_BUILD:-build-fuzz-solid}
elif [ $target = fuzz_mesh ]; then
  build=${COONS_FUZZ_BUILD:-build-fuzz-mesh}
else
  build=${COONS_FUZZ_BUILD:-build-fuzz}
fi
case $build in /*) ;; *) build="$here/$build" ;; esac

command -v clang >/dev/null || { echo "fuzz.sh: clang is missing (tools/setup.sh)" >&2; exit 2; }
if [ $target = fuzz_solid ]; then
  CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCOONS_FUZZ=ON -DCOONS_WITH_LIB3MF=OFF >/dev/null
else
  # A C-only build: the model target reaches no C++ code, and clang with
  # -fsanitize=fuzzer-no-link on CGAL would cost minutes.
  CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCOONS_FUZZ=ON -DCOONS_WITH_OPENMESH=OFF -DCOONS_WITH_CGAL=OFF >/dev/null
fi
cmake --build "$build" --target $target -j "${COONS_JOBS:-2}" >/dev/null

seeds="$build/seeds"
rm -rf "$seeds"
mkdir -p "$seeds" "$build/corpus"
dict=tests/fuzz/model.dict
findings=tests/fuzz/regressions/
if [ $target = fuzz_mesh ]; then
  dict=tests/fuzz/mesh.dict
  findings=tests/fuzz/mesh/
  cp tests/fuzz/mesh/* "$seeds/"
else
  find examples tests/data -name '*.json' -type f 2>/dev/null | while read -r f; do
    cp "$f" "$seeds/$(echo "$f" | tr / _)"
  done
  cp tests/fuzz/regressions/* "$seeds/" 2>/dev/null || true
fi

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:allocator_may_return_null=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
echo "fuzz.sh: fuzzing for ${secs} s ($(ls "$seeds" | wc -l) seeds, $(ls "$build/corpus" | wc -l) in the corpus)" >&2
log="$build/fuzz.log"
set +e
"$build/tests/$target" "$build/corpus" "$seeds" \
  -dict="$dict" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 \
  -malloc_limit_mb=512 -max_len=16384 -print_final_stats=1 \
  -artifact_prefix="$findings" "$@" >"$log" 2>&1
rc=$?
set -e
grep -E '^(stat::|#[0-9]+ *DONE)' "$log" >&2 || true
if [ $rc -ne 0 ]; then
  tail -n 60 "$log" >&2
  echo "fuzz.sh: FAILED (status $rc); the input is in $findings, full log: $log" >&2
  exit 1
fi
echo "fuzz.sh: no finding in ${secs} s" >&2
