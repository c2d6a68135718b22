#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs every Debian 12 package libcoons needs to build, test and benchmark.
# Non-interactive and idempotent: apt is skipped when everything is present.
set -euo pipefail

PKGS=(
  build-essential cmake ninja-build pkg-config
  libcmocka-dev
  libopenmesh-dev libcgal-dev libgmp-dev libmpfr-dev
  openscad mandoc groff-base valgrind
  clang libclang-rt-14-dev
  python3
  # test_write and test_json compile a de_DE locale to check locale independence.
  locales
  # Volume meshes are checked by the programs that read them (issue 10):
  # Gmsh (binary and Python module), CalculiX, meshio, VTK's Python module,
  # and an X server for OpenSCAD's preview renders (xvfb-run).
  gmsh python3-gmsh calculix-ccx python3-meshio python3-vtk9 python3-numpy
  xvfb xauth
  # For the people who print (issue 16): slicing and mesh checks by the
  # programs users run, the 3MF library, and ccache for faster rebuilds.
  prusa-slicer admesh lib3mf-dev ccache
  # Exact solids (issue 26): Open CASCADE for the STEP, IGES and BREP
  # writer (its CMake config needs TBB and the visualization package),
  # FreeCAD headless to read them back in the tests.
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-visualization-dev libocct-ocaf-dev libocct-data-exchange-dev libtbb-dev
  freecad-python3
  # The Python package (issue 28): test.sh's python stage makes a venv;
  # scikit-build-core, cffi and pytest come from PyPI into it.
  python3-venv
  # The page in the browser (issue 29): the C core in WebAssembly (emscripten),
  # node for its tests, Debian's chromium driven headless by puppeteer-core
  # (web/package.json; no browser is downloaded).
  emscripten chromium nodejs
)
# npm: Debian's package, unless the installed nodejs brings its own (the
# NodeSource build provides npm and conflicts with Debian's).
command -v npm >/dev/null 2>&1 || PKGS+=(npm)

missing=()
for p in "${PKGS[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
echo "setup: installing ${missing[*]}" >&2
$SUDO apt-get -o DPkg::Lock::Timeout=600 update -qq
$SUDO apt-get -o DPkg::Lock::Timeout=600 install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
