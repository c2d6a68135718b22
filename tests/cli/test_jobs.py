#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""coons2stl -j N (issue 14): sampling, the input checks and the unions of
groups of bodies that do not meet run on N threads, and the written file is
the same, byte for byte, for every N: multi-body models (bodies that
overlap, bodies apart, a body in another's box but apart from it, the three
examples; "union" and "none"; without CGAL the models that need no
Boolean, and the others are refused on any -j) written as binary STL with -j 1, -j 2, -j 3
and the default (the number of cores) are compared byte for byte; the STL
is also checked to hold the expected number of triangles. Volume meshes
(.vtu, .msh) of a few examples are the same bytes for every -j too. -j 0
and -j x are usage errors (exit 2) that write nothing.

Usage: test_jobs.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import os
import shutil
import struct
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402
from clitest import Runner  # noqa: E402

T = Runner(__doc__)
TMP = tempfile.mkdtemp(prefix="coons-jobs-")


def box(name, lo, hi, shear=0.0):
    c = []
    for n in range(8):
        i, j, k = n >> 2, (n >> 1) & 1, n & 1
        c.append([(lo, hi)[i][0] + k * shear, (lo, hi)[j][1], (lo, hi)[k][2]])
    return {"type": "body0", "name": name, "corners": c}


def write_model(name, bodies, **extra):
    path = os.path.join(TMP, name)
    m = {"coons": 1, "bodies": bodies}
    m.update(extra)
    with open(path, "w") as f:
        json.dump(m, f)
    return path


def stl_triangles(data):
    return struct.unpack_from("<I", data, 80)[0] if len(data) >= 84 else -1


bodies = [box("a", [0, 0, 0], [1, 1, 1]), box("b", [0.5, 0.5, 0.5], [1.5, 1.5, 1.5]),
          box("c", [4, 0, 0], [5, 1, 1], 3.0), box("d", [7, 0, 0], [7.5, 1, 0.2]),
          box("e", [10, 0, 0], [11, 1, 1]), box("f", [10, 3, 0], [11, 4, 1])]
apart = [box("p", [0, 0, 0], [1, 1, 1]), box("q", [3, 0, 0], [4, 1, 1]),
         box("r", [0, 3, 0], [1, 4, 1])]
models = [
    ("boxes none", write_model("boxes-none.json", bodies, operation="none"),
     ["--resolution", "6"]),
    ("boxes apart", write_model("apart.json", apart), ["--resolution", "5"]),
    # one body: its faces evaluated on the threads (issue 27), on a fixed
    # lattice and adaptively (the measuring passes)
    ("spool fixed", os.path.join(T.src, "examples", "spool.json"), ["--resolution", "70"]),
    ("nail adaptive", os.path.join(T.src, "examples", "nail.json"), []),
]
rc, out, err = T.run(["--info", models[1][1]])
try:
    HAVE_CGAL = json.loads(out)["solid"].get("csg") is not None
except (ValueError, KeyError, TypeError):
    HAVE_CGAL = False
print(f"# CGAL in this build: {HAVE_CGAL}")
union_models = [
    ("boxes union", write_model("boxes.json", bodies), ["--resolution", "6"]),
    ("three examples", os.path.join(T.data, "ok", "three-examples-union.json"),
     ["--resolution", "16"]),
]
if HAVE_CGAL:
    models += union_models
else:
    # without CGAL these unions are refused (exit 3, nothing written) on any -j
    for label, path, extra in union_models:
        dst = os.path.join(TMP, "refused.stl")
        rc, _, err = T.run(["-q", "-o", dst, "-j", "2"] + extra + [path])
        T.check(f"no CGAL: {label} with -j 2 refused (exit 3), nothing written",
                rc == 3 and not os.path.exists(dst), err)
for label, path, extra in models:
    files = {}
    # Under a sanitizer one and several threads (-j 2 and the default are
    # the same threaded path as -j 3 there; release runs them all).
    for j in (["1", "3"] if clitest.REPRESENTATIVE else ["1", "2", "3", None]):
        dst = os.path.join(TMP, f"{label.replace(' ', '_')}-{j}.stl")
        args = ["-q", "-o", dst] + extra + ([] if j is None else ["-j", j]) + [path]
        rc, _, err = T.run(args)
        if not T.check(f"{label}: -j {j or '(default)'} exits 0", rc == 0, err):
            continue
        with open(dst, "rb") as f:
            files[j] = f.read()
    if "1" in files:
        n = stl_triangles(files["1"])
        T.check(f"{label}: a binary STL of {n} triangles", n > 0 and len(files["1"]) == 84 + 50 * n)
        for j, data in files.items():
            if j != "1":
                T.check(f"{label}: -j {j or '(default)'} writes the same bytes as -j 1",
                        data == files["1"], f"{len(data)} vs {len(files['1'])} bytes")

# Volume meshes (issue 27): nodes, det J, cells and the scaled Jacobian on
# N threads; the .vtu and .msh files are the same bytes for every -j. A
# collapsed apex (nail), bodies sharing faces (L bracket), a tube closed on
# itself, and hex27 cells; a resolution whose u layers split unevenly.
EX = os.path.join(T.src, "examples")
volume_cases = [
    ("nail", os.path.join(EX, "nail.json"), ["--resolution", "5"]),
    ("l-bracket", os.path.join(EX, "lattice-l-bracket.json"), ["--resolution", "3"]),
    ("tube hex27", os.path.join(EX, "thick-cylinder.json"),
     ["--resolution", "3", "--element", "hex27"]),
]
for label, path, extra in volume_cases:
    for ext in ("vtu", "msh"):
        files = {}
        for j in (["1", "3"] if clitest.REPRESENTATIVE else ["1", "2", "3"]):
            dst = os.path.join(TMP, f"vol-{label.replace(' ', '_')}-{j}.{ext}")
            rc, _, err = T.run(["-q", "-o", dst, "-j", j] + extra + [path])
            if T.check(f"{label} .{ext}: -j {j} exits 0", rc == 0, err):
                with open(dst, "rb") as f:
                    files[j] = f.read()
        if "1" in files:
            T.check(f"{label} .{ext}: a volume mesh was written", len(files["1"]) > 200)
            for j, data in files.items():
                if j != "1":
                    T.check(f"{label} .{ext}: -j {j} writes the same bytes as -j 1",
                            data == files["1"], f"{len(data)} vs {len(files['1'])} bytes")

for bad in ["0", "x", "1025"]:
    dst = os.path.join(TMP, f"bad-{bad}.stl")
    rc, _, err = T.run(["-o", dst, "-j", bad, models[0][1]])
    T.check(f"-j {bad}: usage error (exit 2), nothing written",
            rc == 2 and not os.path.exists(dst), f"rc {rc}: {err}")

shutil.rmtree(TMP, ignore_errors=True)
T.finish()
