#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""coons2stl is a pure client of the library (issue 25): it links the
shared libcoons like any user (readelf: a NEEDED libcoons.so entry), holds
none of the library's internals (nm: no coons__ symbol, so no test hook
such as coons__csg_inject_failure; no coons_ function defined in it), and
keeps no global variables of its own (nm: no external data symbol; the
options travel in records). The installed command honours no testing
environment variable: COONS2STL_INJECT_CSG_FAILURE=1 changes nothing.

Usage: test_client.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)


def tool(args):
    p = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                       timeout=60)
    return p.returncode, p.stdout


rc, dyn = tool(["readelf", "-d", T.bin])
needed = [ln.split("[")[1].split("]")[0] for ln in dyn.split("\n") if "(NEEDED)" in ln]
T.check("readelf: coons2stl needs the shared libcoons", rc == 0
        and any(n.startswith("libcoons.so") for n in needed), str(needed))

rc, syms = tool(["nm", "--defined-only", T.bin])
rows = [ln.split() for ln in syms.split("\n") if len(ln.split()) == 3]
internal = [r[2] for r in rows if r[2].startswith("coons__")]
library = [r[2] for r in rows if r[2].startswith("coons_") and not r[2].startswith("coons__")
           and r[1] in "Tt"]
T.check("nm: no internal coons__ symbol in coons2stl (no test hook)", rc == 0 and not internal,
        str(internal[:10]))
T.check("nm: no library function defined in coons2stl (all from libcoons.so)",
        rc == 0 and not library, str(library[:10]))
# external data of the program itself (B, D, C; lower case is file-static)
data = [r[2] for r in rows if r[1] in "BDCGS" and r[2].startswith("cli_")]
T.check("nm: no global variable of the command (no cli_jobs)", rc == 0 and not data, str(data))

box = os.path.join(T.src, "examples", "fig13.json")
p = subprocess.run([T.bin, "--info", "--no-solid", box], stdout=subprocess.PIPE,
                   stderr=subprocess.PIPE, text=True, timeout=T.timeout,
                   env=dict(os.environ, COONS2STL_INJECT_CSG_FAILURE="1"))
T.check("COONS2STL_INJECT_CSG_FAILURE=1: --info works as without it", p.returncode == 0,
        p.stderr)
with open(os.path.join(T.src, "tools", "coons2stl", "solid.c")) as fh:
    solid = fh.read()
cli = "".join(open(os.path.join(T.src, "tools", "coons2stl", f)).read()
              for f in sorted(os.listdir(os.path.join(T.src, "tools", "coons2stl"))))
T.check("the command's sources read no testing variable and include no private header",
        "getenv" not in cli and "coons_test_hooks.h" not in cli and "INJECT" not in solid,
        "")
T.finish()
