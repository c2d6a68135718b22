#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# migrate-0.2: off (the 0.1 call in this test is its point)
"""The public API is callable from C with ordinary arrays and no cast.

- tests/api/calls.c (every public function that takes an array, called with
  plain C arrays) holds no cast;
- it compiles with gcc and with clang as -std=c11, -std=c17 and -std=c2x under
  -Wall -Wextra -Wpedantic -Werror, with and without the deprecated 0.1 names
  (COONS_NO_DEPRECATED), links against the built library and runs: its own
  checks (values worked out by hand) pass;
- the harness catches a signature that needs a cast: the 0.1 form
  `coons_patch_coons(b, ...)` with a plain `coons_curve *b[4]` fails to
  compile under the same flags, while the 0.2 call does not;
- 0.1 code (the deprecated names, with the casts 0.1 needed) still builds
  warning-free under -Werror, and -DCOONS_DEPRECATION_WARNINGS makes gcc and
  clang warn at the use.

In a sanitizer build the programs are compiled only, and linked and run with
gcc and the same sanitizers.

Usage: test_api_calls.py --bin <ignored> --src <source dir> --build <build dir>
"""
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

NEEDS_CAST_01 = r"""
#include <coons.h>
int probe(coons_curve *b[4], coons_patch **p, coons_error *e);
int probe(coons_curve *b[4], coons_patch **p, coons_error *e)
{
    return coons_patch_coons(b, COONS_BLEND_LINEAR, 0.0, p, e);
}
"""
FINE_02 = NEEDS_CAST_01.replace("coons_patch_coons(", "coons_patch_new_coons(")
# A 0.1 program as 0.1 wanted it (with the cast): builds warning-free in 0.2,
# and warns when COONS_DEPRECATION_WARNINGS asks for it.
OLD_01 = NEEDS_CAST_01.replace("coons_patch_coons(b,", "coons_patch_coons((const coons_curve *const *)b,")




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
                for nodep in (False, True):
                    tag = f"{cc} -std={std}" + (" -DCOONS_NO_DEPRECATED" if nodep else "")
                    extra = ["-DCOONS_NO_DEPRECATED"] if nodep else []
                    out = os.path.join(tmp, f"calls-{cc}-{std}-{int(nodep)}")
                    link = not san or cc == "gcc"
                    rc, log = compile_c(cc, std, src, out, r.build, inc, extra + san_flags
                                        if link else extra, link=link)
                    if not r.check(f"{tag}: calls.c compiles warning-free" +
                                   (" and links" if link else ""), rc == 0 and not log.strip(),
                                   log):
                        continue
                    if link:
                        p = subprocess.run([out], stdout=subprocess.PIPE,
                                           stderr=subprocess.STDOUT, text=True, timeout=300)
                        r.check(f"{tag}: calls runs, every check passes", p.returncode == 0,
                                p.stdout)
            # The harness sees a signature that needs a cast.
            for name, body, want_ok in (("0.1 coons_patch_coons(coons_curve *b[4])",
                                         NEEDS_CAST_01, False),
                                        ("0.2 coons_patch_new_coons(coons_curve *b[4])",
                                         FINE_02, True)):
                c = os.path.join(tmp, "probe.c")
                with open(c, "w") as f:
                    f.write(body)
                rc, log = compile_c(cc, "c11", c, os.path.join(tmp, "probe.o"), r.build, inc,
                                    ["-Wno-deprecated-declarations"], link=False)
                r.check(f"{cc}: {name} " + ("compiles" if want_ok else "is refused (needs a cast)"),
                        (rc == 0) == want_ok, log)
            c = os.path.join(tmp, "old.c")
            with open(c, "w") as f:
                f.write(OLD_01)
            for extra, want_ok in (([], True), (["-DCOONS_DEPRECATION_WARNINGS"], False)):
                rc, log = compile_c(cc, "c11", c, os.path.join(tmp, "old.o"), r.build, inc, extra,
                                    link=False)
                r.check(f"{cc}: 0.1 code " + ("builds warning-free" if want_ok else
                                              "warns with -DCOONS_DEPRECATION_WARNINGS"),
                        (rc == 0) == want_ok and (want_ok or "deprecated" in log), log)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    r.finish()


if __name__ == "__main__":
    main()
# migrate-0.2: on
