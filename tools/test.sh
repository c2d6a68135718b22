#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs what is missing, builds libcoons and runs every test.
# This is the README's test command; .ci/run runs exactly this.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"
bash tools/setup.sh
build=${COONS_BUILD_DIR:-build}
jobs=$(nproc 2>/dev/null || echo 2)

# 1. The full library (C core + OpenMesh + CGAL), warnings as errors.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOONS_WERROR=ON
cmake --build "$build" -j "$jobs"
ctest --test-dir "$build" --output-on-failure -j "$jobs"

# 2. The C core alone, without any C++: it must build and pass on its own.
cmake -S . -B "$build-core" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOONS_WERROR=ON \
  -DCOONS_WITH_OPENMESH=OFF -DCOONS_WITH_CGAL=OFF
cmake --build "$build-core" -j "$jobs"
ctest --test-dir "$build-core" --output-on-failure -j "$jobs"
