#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Runs a C-only build's tests under valgrind memcheck: every cmocka test
# (tests/unit/<stage>/), the fuzz target over its regression inputs and the
# malformed models, and the command-line tests of the paths that need no
# CGAL (--eval, --info, meshing without repair or union, volume meshes) with
# coons2stl under valgrind. Any memcheck error or definite leak fails.
# The tests that repeat the same work over every example take the
# representative subset (COONS_TEST_REPRESENTATIVE=1,
# tests/data/representative-examples.txt: every kind of curve, patch and
# body that any example uses); the release stage runs them over all.
#
#   tools/memcheck.sh BUILD_DIR
#
# BUILD_DIR must be configured with -DCOONS_WITH_OPENMESH=OFF
# -DCOONS_WITH_CGAL=OFF: valgrind does not emulate the rounding modes that
# CGAL's interval arithmetic sets, so the CGAL paths are left to the
# AddressSanitizer build (tools/test.sh).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:?usage: tools/memcheck.sh BUILD_DIR}" && pwd)
command -v valgrind >/dev/null || { echo "memcheck.sh: valgrind is missing (tools/setup.sh)" >&2; exit 2; }
if grep -q '^COONS_WITH_CGAL:BOOL=ON' "$build/CMakeCache.txt"; then
  echo "memcheck.sh: $build is built with CGAL; give a C-only build" >&2
  exit 2
fi
log="$build/memcheck"
rm -rf "$log"
mkdir -p "$log"
VG=(valgrind --tool=memcheck --error-exitcode=99 --leak-check=full --show-leak-kinds=definite
    --errors-for-leak-kinds=definite --track-fds=no -q)

# coons2stl under valgrind, for the CLI tests' --bin: each run logs to its
# own file; valgrind's exit status 99 makes the test see a wrong status.
wrap="$build/coons2stl-memcheck"
cat >"$wrap" <<WRAP
#!/bin/sh
exec ${VG[*]} --log-file="$log/coons2stl.%p.log" "$build/tools/coons2stl" "\$@"
WRAP
chmod +x "$wrap"

failed=0
jobs=()
# One line per step; the steps run two at a time (valgrind is single-threaded).
run_step() {
  local name=$1 t0=$SECONDS st=0
  shift
  "$@" >"$log/$name.out" 2>&1 || st=$?
  if [ $st -eq 0 ]; then
    echo "memcheck: ok   $name ($((SECONDS - t0)) s)"
  else
    echo "memcheck: FAIL $name (status $st, $((SECONDS - t0)) s)"
    tail -n 40 "$log/$name.out"
    return 1
  fi
}

# Left to the sanitizer build: tests that are long loops of arithmetic
# (exhaustive float formatting, fine sampling of every example, every
# allocation failing in turn over every example), which
# valgrind slows down 50-fold without reaching code the others do not.
export COONS_TEST_REPRESENTATIVE=1
skip=" ${MEMCHECK_SKIP-toolkit/test_fmt sample/test_examples model/test_alloc_failures} "
steps=()
for t in "$build"/tests/unit/*/test_*; do
  [ -x "$t" ] && [ -f "$t" ] || continue
  name=$(basename "$(dirname "$t")")/$(basename "$t")
  case $skip in *" $name "*) echo "memcheck: left to ASan $name"; continue ;; esac
  steps+=("${name/\//_}|${VG[*]} $t")
done
# The fuzz target on its regression inputs and the malformed models (the
# examples, which are large, go through the CLI tests).
steps+=("fuzz_regressions|${VG[*]} $build/tests/fuzz_replay $here/tests/fuzz/regressions $here/tests/data/bad $here/tests/data/hostile")
if [ -x "$build/tools/coons2stl" ]; then
  # The command-line tests of the paths without CGAL: argument and model
  # errors, --eval, hostile input, --info, -j, limits, the manifold split,
  # --info's mesh, outputs, references, union refusals, usage, and the
  # volume-mesh paths (mesher, every volume writer through VTK's reader).
  # Debian's Python, which sees python3-vtk9.
  for t in errors eval hostile info jobs limits manifold mesh_info output refs union usage volume; do
    steps+=("cli_test_$t|env COONS_TEST_UNDER_VALGRIND=1 /usr/bin/python3 $here/tests/cli/test_$t.py --bin $wrap --src $here --build $build")
  done
fi

run_one() {
  local name=${1%%|*} cmd=${1#*|}
  # shellcheck disable=SC2086
  CMOCKA_MESSAGE_OUTPUT=stdout run_step "$name" $cmd
}
export -f run_step run_one
export log
printf '%s\n' "${steps[@]}" | xargs -P "${COONS_JOBS:-2}" -I{} bash -c 'run_one "$@"' _ {} || failed=1

# Valgrind reports of coons2stl runs that a CLI test may have accepted.
if ls "$log"/coons2stl.*.log >/dev/null 2>&1; then
  bad=$(find "$log" -name 'coons2stl.*.log' -size +0c)
  if [ -n "$bad" ]; then
    echo "memcheck: FAIL coons2stl under valgrind reported:"
    for f in $bad; do head -n 40 "$f"; done
    failed=1
  fi
  echo "memcheck: $(ls "$log"/coons2stl.*.log | wc -l) coons2stl runs under valgrind"
fi
if [ $failed -ne 0 ]; then
  echo "memcheck: FAILED (logs in $log)" >&2
  exit 1
fi
echo "memcheck: no error, no definite leak"
