#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# migrate-0.2: off (the 0.1 names in this test are its point)
"""The public API is callable from C with ordinary arrays and no cast.

- tests/api/calls.c (every public function that takes an array, called with
  plain C arrays) holds no cast;
- it compiles with gcc and with clang as -std=c11, -std=c17 and -std=c2x under
  -Wall -Wextra -Wpedantic -Werror, links against the built library and runs:
  its own checks (values worked out by hand) pass;
- the harness catches a signature that needs a cast: a `coons_curve *b[4]`
  passed where `const coons_curve *const *` alone is taken without
  conversion (`const coons_curve **`, the shape 0.1 had) fails to compile
  under the same flags, while the public coons_patch_new_coons() call does
  not;
- the 0.1 names are gone in 0.3 (0.2 announced it): 0.1 code no longer
  compiles, and none of the 0.1 names is exported;
- libcoons.so exports exactly the functions the public headers declare
  COONS_EXPORT (the count is printed: 171 in 0.3).

In a sanitizer build the programs are compiled only, and linked and run with
gcc and the same sanitizers.

Usage: test_api_calls.py --bin <ignored> --src <source dir> --build <build dir>
"""
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402

FLAGS = ["-Wall", "-Wextra", "-Wpedantic", "-Werror"]
STDS = ["c11", "c17", "c2x"]

# A cast: "(" type ")" followed by an operand, where the type is a C or coons type.
CAST = re.compile(r"\(\s*(?:const\s+)?(?:coons_\w+|double|float|int|unsigned|size_t|uint32_t|"
                  r"long|char|void)\b[\s\w*()\[\]]*\)\s*[\w&(\[]")

NEEDS_CAST = r"""
#include <coons.h>
int takes(const coons_curve **b);
int probe(coons_curve *b[4]);
int probe(coons_curve *b[4])
{
    return takes(b);
}
"""
FINE = r"""
#include <coons.h>
int probe(coons_curve *b[4], coons_patch **p, coons_error *e);
int probe(coons_curve *b[4], coons_patch **p, coons_error *e)
{
    return coons_patch_new_coons(b, COONS_BLEND_LINEAR, 0.0, p, e);
}
"""
# A 0.1 program (the 0.1 names were removed in 0.3).
OLD_01 = FINE.replace("coons_patch_new_coons(b,", "coons_patch_coons((const coons_curve *const *)b,")
# Every 0.1 function name (tools/migrate-0.2.py's table): none is exported.
NAMES_01 = ("coons_curve_line coons_curve_polyline coons_curve_bezier coons_curve_hermite "
            "coons_curve_coons_cubic coons_curve_clamped_cubic coons_curve_bspline "
            "coons_cubic_open_to_clamped coons_patch_bilinear coons_patch_ruled coons_patch_coons "
            "coons_patch_hermite_coons coons_patch_bezier coons_patch_bspline coons_body_body0 "
            "coons_body_body1 coons_body_body2 coons_body_bezier coons_body_bspline "
            "coons_model_load coons_model_load_opts coons_model_load_buffer "
            "coons_model_load_buffer_opts coons_model_mesh coons_model_solid "
            "coons_mesh_self_intersections coons_mesh_self_intersections_float "
            "coons_csg_available").split()


def sanitized(build):
    try:
        with open(os.path.join(build, "CMakeCache.txt")) as f:
            return "COONS_SANITIZE:BOOL=ON" in f.read()
    except OSError:
        return False


def compile_c(cc, std, src, out, build, inc, extra=(), link=True):
    cmd = [cc, f"-std={std}"] + FLAGS + list(extra) + ["-I", inc,
                                                       "-I", os.path.join(build, "include")]
    if link:
        lib = os.path.join(build, "src")
        cmd += [src, "-L", lib, "-lcoons", f"-Wl,-rpath,{lib}", "-o", out]
    else:
        cmd += ["-c", src, "-o", out]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return p.returncode, p.stdout


def main():
    r = Runner(__doc__)
    src = os.path.join(r.src, "tests", "api", "calls.c")
    inc = os.path.join(r.src, "include")
    text = open(src).read()
    code = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    code = re.sub(r'"(?:\\.|[^"\\])*"', '""', code)
    casts = [m.group(0) for m in CAST.finditer(code) if not m.group(0).startswith("(void)")]
    r.check("tests/api/calls.c holds no cast", not casts, " ".join(casts))
    san = sanitized(r.build)
    san_flags = ["-fsanitize=address,undefined"] if san else []
    compilers = [c for c in ("gcc", "clang") if shutil.which(c)]
    r.check("gcc and clang are installed", compilers == ["gcc", "clang"], str(compilers))
    tmp = tempfile.mkdtemp(prefix="coons-api-")
    try:
        for cc in compilers:
            for std in STDS:
                tag = f"{cc} -std={std}"
                out = os.path.join(tmp, f"calls-{cc}-{std}")
                link = not san or cc == "gcc"
                rc, log = compile_c(cc, std, src, out, r.build, inc, san_flags if link else [],
                                    link=link)
                if not r.check(f"{tag}: calls.c compiles warning-free" +
                               (" and links" if link else ""), rc == 0 and not log.strip(), log):
                    continue
                if link:
                    p = subprocess.run([out], stdout=subprocess.PIPE,
                                       stderr=subprocess.STDOUT, text=True, timeout=300)
                    r.check(f"{tag}: calls runs, every check passes", p.returncode == 0,
                            p.stdout)
            # The harness sees a signature that needs a cast.
            for name, body, want_ok in (("coons_curve *b[4] as const coons_curve **",
                                         NEEDS_CAST, False),
                                        ("coons_patch_new_coons(coons_curve *b[4])", FINE, True)):
                c = os.path.join(tmp, "probe.c")
                with open(c, "w") as f:
                    f.write(body)
                rc, log = compile_c(cc, "c11", c, os.path.join(tmp, "probe.o"), r.build, inc,
                                    link=False)
                r.check(f"{cc}: {name} " + ("compiles" if want_ok else "is refused (needs a cast)"),
                        (rc == 0) == want_ok, log)
            c = os.path.join(tmp, "old.c")
            with open(c, "w") as f:
                f.write(OLD_01)
            rc, log = compile_c(cc, "c11", c, os.path.join(tmp, "old.o"), r.build, inc,
                                link=False)
            r.check(f"{cc}: 0.1 code (coons_patch_coons) no longer compiles",
                    rc != 0 and "coons_patch_coons" in log, log)
        lib = os.path.join(r.build, "src", "libcoons.so")
        p = subprocess.run(["nm", "-D", "--defined-only", lib], stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, text=True)
        exported = {ln.split()[-1] for ln in p.stdout.splitlines() if " T " in ln}
        r.check("libcoons.so exports functions", p.returncode == 0 and len(exported) > 50,
                p.stdout[-500:])
        left = sorted(set(NAMES_01) & exported)
        r.check("no 0.1 name is exported", not left, " ".join(left))
        declared = set()
        for h in glob.glob(os.path.join(inc, "coons", "*.h")):
            with open(h) as f:
                declared |= set(re.findall(r"COONS_EXPORT\b[^;{(]*?\b(coons_\w+)\s*\(", f.read()))
        fns = {n for n in exported if n.startswith("coons_")}
        r.check(f"the exported functions are exactly those the headers declare "
                f"({len(fns)} exported)", fns == declared,
                "exported, not declared: " + " ".join(sorted(fns - declared)) +
                "\ndeclared, not exported: " + " ".join(sorted(declared - fns)))
        # The README states the count (issue 25): it must be this one.
        with open(os.path.join(r.src, "README.md"), encoding="utf-8") as f:
            m = re.search(r"libcoons exports (\d+) functions", f.read())
        r.check(f"README states the number of exported functions ({len(fns)})",
                m is not None and int(m.group(1)) == len(fns),
                m.group(0) if m else "no 'libcoons exports N functions' in README.md")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    r.finish()


if __name__ == "__main__":
    main()
# migrate-0.2: on
