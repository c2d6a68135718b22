#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs what is missing, builds libcoons and runs every test.
# This is the README's test command; .ci/run runs exactly this.
#
# Stages (each must pass; all run by default):
#   release  the full library (C core + OpenMesh + CGAL), -Werror, all tests
#   core     the C core alone, without any C++: it must build and pass on
#            its own; with the release stage in the same run, the tests
#            labelled same_without_cxx (they reach no C++ layer, so both
#            builds run the same code: tests/CMakeLists.txt) are left to it
#   asan     everything (CGAL included) at -O1 with AddressSanitizer and
#            UndefinedBehaviorSanitizer, all tests; those that repeat the
#            same work over every example take the representative subset
#            (COONS_TEST_REPRESENTATIVE=1, tests/data/representative-examples.txt)
#   memcheck the core build's tests and the CLI paths that avoid CGAL under
#            valgrind memcheck, representative examples (tools/memcheck.sh)
#   fuzz     the loader fuzz target for COONS_FUZZ_SECONDS (default 60) s
#            (tools/fuzz.sh)
#   python   the Python package (python/, issue 28): a wheel built from the
#            tree (the full library: unions through CGAL), installed into a
#            fresh virtual environment, its pytest suite (python/tests) run
#            there; then a C-core wheel in a second environment, where the
#            calls that need CGAL must raise saying so
#   web      the page (issue 29): tools/build-web.sh builds the C core to
#            WebAssembly into build-web; tests/web/test_wasm.js checks every
#            example's outputs against the C-only coons2stl (the core
#            build's, built here if the core stage did not run), byte for
#            byte; tests/web/test_page.js drives the page in Debian's
#            headless chromium (puppeteer-core): render, the cells, a
#            mouse drag and its previews' times, the exported STL
#            (screenshots in build-web/test-output)
# The tests: tests/unit/<stage>/test_<concept>.c (cmocka; ctest name
# <stage>/test_<concept>, e.g. ctest -R '^csg/'), tests/cli/test_<concept>.py
# (one harness, tests/cli/clitest.py; ctest name cli/test_<concept>), the fuzz
# replays (fuzz_*). A missing client program (openscad, gmsh, ccx,
# prusa-slicer, admesh, VTK, meshio, a locale) fails a test, never skips it.
# Time (2 cores): 1889-2465 s before the cuts above (release ~225 s, core
# ~145 s, asan ~770 s, memcheck ~665 s, fuzz ~90 s); the cuts, measured in
# CPU-seconds on a shared machine: test_alloc_failures 17.0 -> 5.8 over the
# representative examples (release build; 176 s under ASan before), the
# OpenSCAD, PrusaSlicer, admesh, --info and --eval example loops 41 -> 23,
# the core stage: 18 tests (23.7 of its ~160) left to the release stage;
# memcheck: valgrind's --info over the examples 163 -> 73, the whole stage
# 663 CPU-seconds after (wall time there is about CPU / 2).
# Aim: under 25 minutes, leaving room for new stages within 35.
# COONS_TEST_STAGES="release core" runs a subset; COONS_BUILD_DIR sets the
# build directory prefix (default: build, build-core, build-asan, build-fuzz).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"
bash tools/setup.sh
build=${COONS_BUILD_DIR:-build}
jobs=$(nproc 2>/dev/null || echo 2)
stages=" ${COONS_TEST_STAGES:-release core asan memcheck fuzz python web} "
t_all=$SECONDS
times=()

want() { case $stages in *" $1 "*) return 0 ;; *) return 1 ;; esac; }
begin() {
  t_stage=$SECONDS
  echo "==== test.sh: $1 ($(date +%T))" >&2
}
end() {
  times+=("$1 $((SECONDS - t_stage)) s")
  echo "==== test.sh: $1 took $((SECONDS - t_stage)) s" >&2
}

# 1. The full library (C core + OpenMesh + CGAL), warnings as errors.
if want release; then
  begin "release build and tests"
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOONS_WERROR=ON
  cmake --build "$build" -j "$jobs"
  ctest --test-dir "$build" --output-on-failure -j "$jobs"
  end release
fi

# 2. The C core alone, without any C++: it must build and pass on its own.
if want core || want memcheck; then
  begin "C-only build and tests"
  cmake -S . -B "$build-core" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOONS_WERROR=ON \
    -DCOONS_WITH_OPENMESH=OFF -DCOONS_WITH_CGAL=OFF
  cmake --build "$build-core" -j "$jobs"
  if want core; then
    same=()
    want release && same=(-LE same_without_cxx)
    ctest --test-dir "$build-core" --output-on-failure -j "$jobs" "${same[@]}"
  fi
  end core
fi

# 3. AddressSanitizer + UndefinedBehaviorSanitizer, CGAL included, at -O1:
#    a sanitized CGAL translation unit costs 4 times the CPU at -O2 than at
#    -O0, but at -O0 the tests that go through CGAL ran 2.8 times longer
#    (measured: build +2 min at -O1, tests 673 s -> 241 s). No -Werror:
#    gcc's warnings differ between optimisation levels, and the release
#    stage enforces them. Any report aborts the test (leaks too).
#    COONS_ASAN_OPT=-O0 builds at -O0 instead.
if want asan; then
  begin "AddressSanitizer + UBSan build and tests"
  cmake -S . -B "$build-asan" -G Ninja -DCMAKE_BUILD_TYPE=Sanitize -DCOONS_SANITIZE=ON \
    -DCMAKE_C_FLAGS_SANITIZE="${COONS_ASAN_OPT:--O1} -g1" \
    -DCMAKE_CXX_FLAGS_SANITIZE="${COONS_ASAN_OPT:--O1} -g1"
  cmake --build "$build-asan" -j "$jobs"
  # Every test except the install test, which links unsanitized programs
  # against the installed (sanitized) library; the representative examples.
  COONS_TEST_REPRESENTATIVE=1 \
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir "$build-asan" --output-on-failure -j "$jobs" --timeout 900 \
      -E '^cli/test_install$'

  end asan
fi

# 4. valgrind memcheck over the C-only build (valgrind cannot run CGAL).
if want memcheck; then
  begin "valgrind memcheck"
  COONS_JOBS=$jobs bash tools/memcheck.sh "$build-core"
  end memcheck
fi

# 5. A bounded fuzzing run; a finding fails and is kept in tests/fuzz/regressions.
if want fuzz; then
  begin "fuzzing for ${COONS_FUZZ_SECONDS:-60} s"
  COONS_FUZZ_BUILD="$build-fuzz" COONS_JOBS=$jobs bash tools/fuzz.sh "${COONS_FUZZ_SECONDS:-60}"
  end fuzz
fi

# 6. The Python package: `pip wheel ./python` builds the full library (the
#    union tests compare with coons2stl's unions), the wheel goes into a
#    fresh venv (Debian's numpy and meshio through --system-site-packages;
#    cffi and pytest from PyPI), pytest runs from outside the tree so that
#    the installed package is the one tested. Then the C core alone in a
#    second venv (`-k` the tests of meshing and of the missing parts, and
#    the lifetime torture under valgrind, which cannot run CGAL): a call
#    that needs CGAL must raise naming it. COONS_EXPECT_CGAL makes
#    the tests check which build they were given. Exit 5 (no tests ran)
#    fails.
if want python; then
  begin "Python package"
  pyenv_dir=$(mktemp -d)
  trap 'rm -rf "$pyenv_dir"' EXIT
  py_stage() {  # name, expect_cgal, pytest args..., with cmake defines in $defines
    local name=$1 expect=$2 rc=0
    shift 2
    /usr/bin/python3 -m venv --system-site-packages "$pyenv_dir/$name"
    local py="$pyenv_dir/$name/bin/python"
    "$py" -m pip install -q "scikit-build-core>=0.8" "cffi>=1.15" "pytest>=7"
    CMAKE_C_COMPILER_LAUNCHER=$(command -v ccache || true) \
    CMAKE_CXX_COMPILER_LAUNCHER=$(command -v ccache || true) \
      "$py" -m pip wheel -q --no-deps --no-build-isolation -w "$pyenv_dir/wheels-$name" \
        "${defines[@]}" --config-settings=build-dir="$here/$build-$name" ./python
    "$py" -m pip install -q --no-deps "$pyenv_dir/wheels-$name"/coons-*.whl
    (cd "$pyenv_dir" && COONS_EXAMPLES="$here/examples" COONS_EXPECT_CGAL=$expect \
       "$py" -m pytest -q -p no:cacheprovider "$@") || rc=$?
    if [ "$rc" -eq 5 ]; then echo "test.sh: python ($name): pytest collected no tests" >&2; fi
    [ "$rc" -eq 0 ] || exit 1
  }
  defines=()
  py_stage python 1 -k "not under_valgrind" "$here/python/tests"
  defines=(--config-settings=cmake.define.COONS_WITH_OPENMESH=OFF
           --config-settings=cmake.define.COONS_WITH_CGAL=OFF)
  py_stage python-core 0 -k "union or mesh_equals_cli or features or under_valgrind or solid" \
    "$here/python/tests/test_errors.py" "$here/python/tests/test_mesh.py" \
    "$here/python/tests/test_lifetime.py"
  end python
fi

# 7. The page: the WebAssembly module against the C-only coons2stl, in node
#    and in headless chromium. Debian's node needs its acorn (NODE_PATH)
#    for emscripten; the tests load the module from its file (no fetch).
if want web; then
  begin "WebAssembly module and page"
  # the C-only coons2stl, up to date (built already when the core stage ran)
  if [ ! -f "$build-core/CMakeCache.txt" ]; then
    cmake -S . -B "$build-core" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOONS_WERROR=ON \
      -DCOONS_WITH_OPENMESH=OFF -DCOONS_WITH_CGAL=OFF
  fi
  cmake --build "$build-core" -j "$jobs" --target coons2stl
  COONS_WEB_DIR="$build-web" COONS_JOBS=$jobs bash tools/build-web.sh
  rm -rf "$build-web/test-output"
  COONS_JOBS=$jobs node tests/web/test_wasm.js "$build-web" "$build-core/tools/coons2stl" examples \
    "$build-web/test-output/wasm"
  node tests/web/test_page.js "$build-web" "$build-core/tools/coons2stl" examples \
    "$build-web/test-output/page"
  end web
fi

echo "==== test.sh: all passed in $((SECONDS - t_all)) s (${times[*]/%/;})" >&2
