#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The progress report (coons2stl(1), --progress; issue 24 "progress that
moves"), read from standard error with --progress:

- volume meshes: the stages lattice, evaluate and cells, each to 100%;
- a writing stage after the mesh is made: "writing FILE: SIZE", whose last
  figure is the size of the file written (checked against the file), on
  the same line as the stages before it (one line, ended by one newline);
  for surface meshes, volume meshes and standard output (-o -);
- one body: "sampling body 1 of 1 (NAME)" followed by the share of the
  current measuring pass;
- --frames: "frame k of N: " before the stages of frame k, for every k;
- sampling on threads (-j 2) still names each body in order, and the
  output is the same bytes as with -j 1;
- --deform: "deforming: N%" with N never decreasing and ending at 100,
  before the writing stage; nothing with -q, even with --progress;
- nothing with -q alone, nothing when standard error is not a terminal.

Usage: test_progress.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import os
import re
import shutil
import struct
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
TMP = tempfile.mkdtemp(prefix="coons-progress-")


def box(name, x0):
    return {"type": "body0", "name": name, "corners": [
        [x0, 0, 0], [x0, 0, 1], [x0, 1, 0], [x0, 1, 1.3], [x0 + 1, 0, 0], [x0 + 1, 0, 1],
        [x0 + 1, 1, 0], [x0 + 1, 1, 1]]}


MODEL = os.path.join(TMP, "three.json")
with open(MODEL, "w") as fh:
    json.dump({"coons": 1, "operation": "none",
               "bodies": [box("a", 0), box("b", 3), box("c", 6)]}, fh)
MORPH = os.path.join(TMP, "morph.json")
with open(MORPH, "w") as fh:
    json.dump({"coons": 1, "bodies": [{"type": "morph", "name": "m", "keys": [
        box("k0", 0), box("k1", 2)]}]}, fh)


def run(args):
    rc, out, err = T.run(args, binary=True)
    return rc, out, err.decode("utf-8", "replace")


def last_written(err, shown):
    """The last "writing SHOWN: X kB|MB" figure in bytes (to its rounding)."""
    got = re.findall(r"writing " + re.escape(shown) + r": ([0-9.]+) (kB|MB)", err)
    if not got:
        return None
    x, unit = got[-1]
    return float(x) * (1e3 if unit == "kB" else 1e6), 0.05 * (1e3 if unit == "kB" else 1e6)


for name, args in (("surface .stl", ["-o", os.path.join(TMP, "a.stl")]),
                   ("surface .off", ["-o", os.path.join(TMP, "a.off")]),
                   ("volume .vtu", ["--resolution", "30", "-o", os.path.join(TMP, "a.vtu")])):
    path = args[-1]
    rc, _, err = run(["--progress"] + args + [MODEL])
    w = last_written(err, path)
    size = os.path.getsize(path) if os.path.exists(path) else -1
    T.check(f"{name}: a writing stage whose last figure is the file's size ({size} bytes)",
            rc == 0 and w is not None and abs(w[0] - size) <= w[1], repr(err[-200:]))
    T.check(f"{name}: one progress line, ended by one newline, the writing stage last",
            err.endswith("\n") and err.count("\n") == 1
            and err.rstrip().split("\r")[-1].startswith("coons2stl: writing "), repr(err[-200:]))

rc, _, err = run(["--progress", "--resolution", "8", "-o", os.path.join(TMP, "v.inp"), MODEL])
stages = re.findall(r"coons2stl: (volume mesh: [a-z]+|writing)", err)
firsts = [s for i, s in enumerate(stages) if i == 0 or stages[i - 1] != s]
T.check("volume mesh: its stages lattice, evaluate, cells (each to 100%), then writing",
        rc == 0 and firsts == ["volume mesh: lattice", "volume mesh: evaluate",
                               "volume mesh: cells", "writing"]
        and all(f"volume mesh: {s} 100%" in err for s in ("lattice", "evaluate", "cells")),
        repr(err))

rc, out, err = run(["--progress", "-o", "-", MODEL])
w = last_written(err, "<stdout>")
T.check("-o -: the writing stage names <stdout> and counts the bytes sent",
        rc == 0 and w is not None and abs(w[0] - len(out)) <= w[1], repr(err[-200:]))

rc, _, err = run(["--progress", "--frames", "3", "-o", os.path.join(TMP, "f%d.stl"), MORPH])
T.check("--frames 3: 'frame k of 3: ' before each frame's stages, k = 1, 2, 3",
        rc == 0 and all(f"coons2stl: frame {k} of 3: sampling body 1 of 1 (m)" in err
                        for k in (1, 2, 3))
        and all(f"coons2stl: frame {k} of 3: writing " in err for k in (1, 2, 3)),
        repr(err[-300:]))

SPOOL = os.path.join(T.src, "examples", "spool.json")
rc, _, err = run(["--progress", "-j", "1", "-t", "0.002", "-o", os.path.join(TMP, "s.stl"), SPOOL])
pcts = [int(x) for x in re.findall(r"sampling body 1 of 1 \(spool\) +(\d+)%", err)]
T.check("one body: its line moves with the share of the measuring pass (a percentage)",
        rc == 0 and len(pcts) >= 1 and all(0 <= p <= 100 for p in pcts), repr(err[:300]))

outs = []
for j in ("1", "2"):
    out = os.path.join(TMP, f"j{j}.stl")
    rc, _, err = run(["--progress", "-j", j, "-o", out, MODEL])
    T.check(f"-j {j}: each body named in order (sampling body i of 3)",
            rc == 0 and sorted(set(int(i) for i in re.findall(r"sampling body (\d) of 3", err)))
            == [1, 2, 3] and sorted(re.findall(r"sampling body (\d) of 3", err))
            == re.findall(r"sampling body (\d) of 3", err),
            repr(err))
    outs.append(open(out, "rb").read() if os.path.exists(out) else None)
T.check("-j 1 and -j 2 write the same bytes", outs[0] is not None and outs[0] == outs[1])

# --deform: a cube (12 triangles, binary STL) through body "a", whose moved
# corner makes it trilinear, not affine: refined over several rounds
CUBE = os.path.join(TMP, "cube.stl")
with open(CUBE, "wb") as fh:
    V = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    F = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
         (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    fh.write(b"\0" * 80 + struct.pack("<I", len(F)))
    for f in F:
        fh.write(struct.pack("<3f", 0, 0, 0))
        for i in f:
            fh.write(struct.pack("<3f", *V[i]))
        fh.write(b"\0\0")
DEFORMED = os.path.join(TMP, "deformed.stl")
rc, _, err = run(["--progress", "--deform", CUBE, "--body", "a", "-t", "1e-4", "-o", DEFORMED,
                  MODEL])
pcts = [int(x) for x in re.findall(r"coons2stl: deforming: +(\d+)%", err)]
T.check("--deform: 'deforming: N%', N never decreasing, ending at 100, then writing",
        rc == 0 and len(pcts) >= 2 and pcts == sorted(pcts) and pcts[-1] == 100
        and err.rfind("deforming: 100%") < err.find("coons2stl: writing ")
        and err.count("\n") == 1, repr(err[-300:]))
for args in (["-q"], ["-q", "--progress"]):
    rc, _, err = run(args + ["--deform", CUBE, "--body", "a", "-t", "1e-4", "-o", DEFORMED, MODEL])
    T.check(f"--deform {' '.join(args)}: nothing on standard error", rc == 0 and err == "",
            repr(err))

rc, _, err = run(["-q", "-o", os.path.join(TMP, "q.stl"), MODEL])
T.check("-q: nothing on standard error", rc == 0 and err == "", repr(err))
rc, _, err = run(["-o", os.path.join(TMP, "p.stl"), MODEL])
T.check("standard error not a terminal, no --progress: nothing", rc == 0 and err == "", repr(err))

shutil.rmtree(TMP)
T.finish()
