#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# migrate-0.3: off (the 0.2 names in this test are its point)
"""tools/migrate-0.3.py and its table tools/abi-0.3-renames.txt.

- the table agrees with the headers: every new name is declared in
  include/ and no old or removed name is;
- on a 0.2 program, names are replaced as whole words only (an identifier
  that merely contains an old name stays), uses of removed names are listed
  with their line and left as they are, and a "migrate-0.3: off" ... "on"
  region is untouched; the migrated program compiles against the headers
  (gcc -fsyntax-only, -Werror) where the 0.2 one does not;
- applying the tool again changes nothing (no new name is an old one), so
  it can be re-applied to partly migrated code;
- the source tree holds no 0.2 name outside such regions (--check is clean).

Usage: test_migrate.py --bin <ignored> --src <source dir> --build <build dir>
"""
import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

PASSED = FAILED = 0


def check(name, ok, detail=""):
    global PASSED, FAILED
    if ok:
        PASSED += 1
        print(f"ok   {name}")
    else:
        FAILED += 1
        print(f"FAIL {name}" + (f"\n{detail}" if detail else ""))
    return ok


PROGRAM_02 = """#include <coons.h>
int kinds(const coons_curve *c, const coons_patch *p, const coons_body *b);
int kinds(const coons_curve *c, const coons_patch *p, const coons_body *b)
{
    int my_coons_body_get_type = 1; /* contains an old name: stays */
    return (int)coons_curve_get_type(c) + (int)coons_patch_get_type(p) +
           (int)coons_body_get_type(b) + my_coons_body_get_type;
}
/* OFF */
/* coons_body_get_type stays here */
/* ON */
""".replace("OFF", "migrate-0.3: " + "off").replace("ON", "migrate-0.3: " + "on")
REMOVED_USE = "st = coons_iso_parse(text, req, 8, &n, &err);\n"


def table(src):
    renames, removed = {}, set()
    with open(os.path.join(src, "tools", "abi-0.3-renames.txt")) as f:
        for line in f:
            words = line.split("#", 1)[0].split()
            if len(words) == 2:
                if words[1] == "-":
                    removed.add(words[0])
                else:
                    renames[words[0]] = words[1]
    return renames, removed


def declared(src, build):
    text = ""
    for h in glob.glob(os.path.join(src, "include", "coons", "*.h")) + \
            [os.path.join(src, "include", "coons.h")]:
        with open(h) as f:
            text += f.read()
    return set(re.findall(r"\b(coons_\w+|COONS_\w+)\b", text))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default="")
    ap.add_argument("--src", required=True)
    ap.add_argument("--build", default="")
    args = ap.parse_args()
    src = os.path.abspath(args.src)
    tool = os.path.join(src, "tools", "migrate-0.3.py")
    renames, removed = table(src)
    check("the table has renames and removals", len(renames) >= 3 and len(removed) >= 2)
    names = declared(src, args.build)
    check("every new name is declared in include/",
          all(n in names for n in renames.values()),
          str(sorted(n for n in renames.values() if n not in names)))
    check("no old or removed name is declared in include/",
          not (set(renames) | removed) & names, str(sorted((set(renames) | removed) & names)))

    tmp = tempfile.mkdtemp(prefix="coons-migrate-")
    try:
        prog = os.path.join(tmp, "prog.c")
        with open(prog, "w") as f:
            f.write(PROGRAM_02)
        use = os.path.join(tmp, "use.c")
        with open(use, "w") as f:
            f.write(REMOVED_USE)
        inc = ["-I", os.path.join(src, "include")]
        if args.build:
            inc += ["-I", os.path.join(os.path.abspath(args.build), "include")]
        cc = ["gcc", "-std=c11", "-Wall", "-Wextra", "-Werror", "-fsyntax-only"] + inc
        before = subprocess.run(cc + [prog], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True)
        check("the 0.2 program does not compile against the 0.3 headers",
              before.returncode != 0 and "get_type" in before.stdout, before.stdout[-800:])
        p = subprocess.run([sys.executable, tool, prog, use], stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, text=True)
        with open(prog) as f:
            got = f.read()
        want = (PROGRAM_02.replace("(int)coons_curve_get_type", "(int)coons_curve_kind")
                .replace("(int)coons_patch_get_type", "(int)coons_patch_kind")
                .replace("(int)coons_body_get_type", "(int)coons_body_kind"))
        check("whole words renamed, containing identifiers and the off region kept",
              p.returncode == 0 and got == want, p.stdout + got)
        check("a removed name is listed with its line and left as it is",
              f"{use}:1: coons_iso_parse: removed in 0.3" in p.stdout and
              open(use).read() == REMOVED_USE, p.stdout)
        after = subprocess.run(cc + [prog], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               text=True)
        check("the migrated program compiles against the 0.3 headers", after.returncode == 0,
              after.stdout[-800:])
        again = subprocess.run([sys.executable, tool, "--check", prog], stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True)
        check("applying it again changes nothing", again.returncode == 0 and
              open(prog).read() == want, again.stdout)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)

    tree = [os.path.join(src, d) for d in ("src", "include", "tools", "tests", "man",
                                            "examples", "README.md")
            if os.path.exists(os.path.join(src, d))]
    p = subprocess.run([sys.executable, tool, "--check"] + tree, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    check("the source tree uses no 0.2 name (migrate-0.3.py --check)",
          p.returncode == 0 and "removed in 0.3" not in p.stdout, p.stdout[-2000:])
    print(f"{PASSED} passed, {FAILED} failed")
    sys.exit(1 if FAILED else 0)


if __name__ == "__main__":
    main()
