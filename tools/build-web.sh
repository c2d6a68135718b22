#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the page of issue 29 into build-web/ (COONS_WEB_DIR): the C core
# compiled to WebAssembly by Debian's emscripten (coons.js + coons.wasm,
# one MODULARIZE'd CommonJS/UMD script that both the page and node load),
# three.js copied from web/node_modules, the page (web/*.html, *.js,
# *.css) and the examples. Installs what is missing: the Debian packages
# emscripten (and npm when there is no npm), the npm packages of
# web/package-lock.json (npm ci; puppeteer-core downloads no browser).
# Serve build-web/ with any static server:
#   python3 -m http.server -d build-web 8000   # then open http://localhost:8000/
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
cd "$here"
out=${COONS_WEB_DIR:-build-web}
t0=$SECONDS

need=()
command -v emcc >/dev/null || need+=(emscripten)
command -v npm >/dev/null || need+=(npm)
if [ ${#need[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO=sudo
  echo "build-web: installing ${need[*]}" >&2
  $SUDO apt-get -o DPkg::Lock::Timeout=600 update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get -o DPkg::Lock::Timeout=600 install -y -qq \
    --no-install-recommends "${need[@]}" >/dev/null
fi
# Debian's emscripten runs its JavaScript parts with the system node, which
# finds Debian's acorn only through NODE_PATH.
export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}

if [ ! -d web/node_modules/three ] || [ web/package-lock.json -nt web/node_modules/.package-lock.json ]; then
  (cd web && npm ci --no-audit --no-fund --loglevel=error)
fi

# The C core alone (no C++), static; only the library target is built.
mkdir -p "$out"
emcmake cmake -S . -B "$out/cmake" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCOONS_WITH_OPENMESH=OFF -DCOONS_WITH_CGAL=OFF -DCOONS_WITH_LIB3MF=OFF \
  -DBUILD_TESTING=OFF -DCOONS_WERROR=ON -Wno-dev >"$out/cmake.log"
cmake --build "$out/cmake" --target coons_static -j "${COONS_JOBS:-2}" >>"$out/cmake.log"

# The module: the glue (web/src) against libcoons.a. -sMODULARIZE without
# ES6 output: node (CommonJS require) and the page (a <script>) load the
# same file; createCoons() resolves to the module.
emcc -O2 -std=c11 -Wall -Wextra -Werror \
  -I include -I "$out/cmake/include" web/src/*.c "$out/cmake/src/libcoons.a" \
  -o "$out/coons.js" \
  -sMODULARIZE=1 -sEXPORT_NAME=createCoons -sENVIRONMENT=web,worker,node \
  -sALLOW_MEMORY_GROWTH=1 \
  -sEXPORTED_FUNCTIONS=_malloc,_free \
  -sEXPORTED_RUNTIME_METHODS=UTF8ToString,stringToUTF8,lengthBytesUTF8,HEAPU8,HEAPU32,HEAPF64

# The page, three.js and the examples (with their list, examples/index.json).
cp web/index.html web/app.js web/worker.js web/coons-api.js web/links.js web/style.css "$out/"
mkdir -p "$out/three" "$out/examples"
cp web/node_modules/three/build/three.module.js web/node_modules/three/build/three.core.js \
   web/node_modules/three/examples/jsm/controls/OrbitControls.js web/node_modules/three/LICENSE \
   "$out/three/"
cp examples/*.json "$out/examples/"
python3 - "$out/examples" <<'PY'
import json, os, sys
d = sys.argv[1]
names = sorted(f for f in os.listdir(d) if f.endswith('.json') and f != 'index.json')
json.dump(names, open(os.path.join(d, 'index.json'), 'w'), indent=0)
PY
# The source offer of the footer (GPL): the tree the page was built from.
if git -C "$here" rev-parse --git-dir >/dev/null 2>&1; then
  # uncommitted changes to tracked files included (git stash create), else HEAD
  tree=$(git -C "$here" stash create 2>/dev/null || true)
  git -C "$here" archive --format=tar.gz --prefix=libcoons/ -o "$out/libcoons-source.tar.gz" \
    "${tree:-HEAD}"
else
  tar -czf "$out/libcoons-source.tar.gz" --exclude='./build*' --exclude='./web/node_modules' \
    --transform 's,^\.,libcoons,' .
fi
wasm=$(stat -c %s "$out/coons.wasm")
echo "build-web: $out/index.html ready in $((SECONDS - t0)) s (coons.wasm $wasm bytes, coons.js $(stat -c %s "$out/coons.js") bytes)" >&2
