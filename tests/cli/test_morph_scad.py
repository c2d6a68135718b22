#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The OpenSCAD animation of morph bodies (outputs.md "Metamorphosis"),
checked with the real OpenSCAD:

- `openscad -D '$t=T' -o x.stl morph.scad` gives the vertices of
  `coons2stl --time T --resolution N -o y.stl` (N the file's lattice): the
  same count, and every coordinate equal to the 6 significant digits
  OpenSCAD prints; at key times and between them, for a linear path of
  two keys (cube to spool, seed 000 Fig. 10) and a smooth path of three;
- the one lattice keeps every frame within the tolerance, also between
  keys: exact boundary points (coons2stl --eval --time T, a grid of
  parameters on each face offset from the lattice) lie within the
  tolerance of OpenSCAD's triangles;
- one face list: the file holds one faces array per morph and no other;
- a body that is no morph is a plain polyhedron, united by union() with
  the morph (modules named MODEL and MODEL_BODY, as for every .scad), and
  the model renders to a closed mesh;
- with --time the .scad is a plain mesh (no $t).

Usage: test_morph_scad.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
TMP = tempfile.mkdtemp(prefix="coons-morph-scad-")
OPENSCAD = shutil.which("openscad")
T.check("openscad is installed", OPENSCAD is not None)
if not OPENSCAD:
    T.finish()

with open(os.path.join(T.src, "examples", "spool.json")) as f:
    SPOOL = json.load(f)["bodies"][0]
SPOOL.pop("name", None)
CUBE_C = [[0, -6, 0], [0, -6, 10], [-6, 0, 0], [-6, 0, 10],
          [6, 0, 0], [6, 0, 10], [0, 6, 0], [0, 6, 10]]
CUBE = {"type": "body0", "corners": CUBE_C}
MID = {"type": "body0", "corners": [[x * 0.5, y * 0.5, z * 1.2] for x, y, z in CUBE_C]}


def write(name, bodies):
    p = os.path.join(TMP, name)
    with open(p, "w") as f:
        json.dump({"coons": 1, "units": "mm", "bodies": bodies}, f)
    return p


LINEAR = write("linear.json", [{"type": "morph", "name": "cube to spool", "keys": [CUBE, SPOOL]}])
SMOOTH = write("smooth.json", [{"type": "morph", "name": "m3", "keys": [CUBE, MID, SPOOL],
                                "at": [0, 0.3, 1], "path": "smooth"}])


def openscad_stl(scad, t, out):
    p = subprocess.run([OPENSCAD, "-D", f"$t={t!r}", "-o", out, scad], capture_output=True,
                       text=True)
    return p.returncode, p.stderr


def read_ascii_stl(path):
    tris, cur = [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if w and w[0] == "vertex":
                cur.append(tuple(float(x) for x in w[1:4]))
                if len(cur) == 3:
                    tris.append(cur)
                    cur = []
    return tris


def read_binary_stl(path):
    import struct
    with open(path, "rb") as f:
        data = f.read()
    n = struct.unpack_from("<I", data, 80)[0]
    tris = []
    for i in range(n):
        v = struct.unpack_from("<12f", data, 84 + 50 * i)
        tris.append([tuple(v[3:6]), tuple(v[6:9]), tuple(v[9:12])])
    return tris


def printed(x):
    """OpenSCAD's 6 significant digits."""
    return float(f"{x:.6g}")


def lattice_of(scad):
    with open(scad) as f:
        m = re.search(r"one lattice of (\d+) intervals", f.read())
    return int(m.group(1)) if m else None


def same_vertices(scad_tris, ours_tris):
    a = sorted({v for t in scad_tris for v in t})
    b = sorted({tuple(printed(x) for x in v) for t in ours_tris for v in t})
    nb = len({v for t in ours_tris for v in t})
    if len(a) != nb:
        return False, f"{len(a)} vertices from OpenSCAD, {nb} from coons2stl"
    # float32 (binary STL) then 6 digits: a coordinate may round the
    # other way at a tie; allow one unit of the 6th digit
    bad = 0
    for p, q in zip(a, b):
        for x, y in zip(p, q):
            unit = 10 ** (math.floor(math.log10(abs(y))) - 5) if y else 1e-300
            if abs(x - y) > unit * 1.01 and abs(x - y) > 1e-12:
                bad += 1
    return bad == 0, f"{bad} coordinates differ beyond the printed digits"


for label, model, times in (("linear", LINEAR, (0.0, 0.35, 0.5, 1.0)),
                            ("smooth", SMOOTH, (0.0, 0.15, 0.3, 0.62, 1.0))):
    scad = os.path.join(TMP, f"{label}.scad")
    rc, _, err = T.run([model, "--resolution", "6", "-o", scad])
    T.check(f"{label}: -o .scad writes the animation", rc == 0 and os.path.isfile(scad), err)
    if rc:
        continue
    with open(scad) as f:
        text = f.read()
    T.check(f"{label}: one faces array, the top-level call passes $t",
            len(re.findall(r"_faces\(\) = \[", text)) == 1
            and re.search(r"^\w+\(\$t\);\s*$", text, re.M) is not None, text[-300:])
    n = lattice_of(scad)
    T.check(f"{label}: the file names its lattice (6 intervals, as asked)", n == 6, str(n))
    for t in times:
        x = os.path.join(TMP, "x.stl")
        y = os.path.join(TMP, "y.stl")
        rc1, err1 = openscad_stl(scad, t, x)
        rc2, _, err2 = T.run([model, "--time", repr(t), "--resolution", "6", "-o", y])
        ok, why = (False, err1 + err2)
        if rc1 == 0 and rc2 == 0:
            ok, why = same_vertices(read_ascii_stl(x), read_binary_stl(y))
        T.check(f"{label}: openscad -D '$t={t}' gives the vertices of coons2stl --time {t}",
                ok, why)


# ---- the lattice keeps every frame within the tolerance ------------------
def point_mesh_distance(points, tris, reach):
    """Distance from each point to the nearest triangle, searched within
    `reach` through a bucket grid (inf when none is that close)."""
    h = reach
    buckets = {}
    for t in tris:
        lo = [min(v[d] for v in t) for d in range(3)]
        hi = [max(v[d] for v in t) for d in range(3)]
        for i in range(math.floor(lo[0] / h), math.floor(hi[0] / h) + 1):
            for j in range(math.floor(lo[1] / h), math.floor(hi[1] / h) + 1):
                for k in range(math.floor(lo[2] / h), math.floor(hi[2] / h) + 1):
                    buckets.setdefault((i, j, k), []).append(t)
    out = []
    for p in points:
        c = [math.floor(p[d] / h) for d in range(3)]
        best = math.inf
        for i in (-1, 0, 1):
            for j in (-1, 0, 1):
                for k in (-1, 0, 1):
                    for t in buckets.get((c[0] + i, c[1] + j, c[2] + k), ()):
                        best = min(best, tri_dist(p, *t))
        out.append(best)
    return out


def sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def tri_dist(p, a, b, c):
    """Distance from p to triangle abc (closest point by regions)."""
    ab, ac, ap = sub(b, a), sub(c, a), sub(p, a)
    d1, d2 = dot(ab, ap), dot(ac, ap)
    if d1 <= 0 and d2 <= 0:
        return math.sqrt(dot(ap, ap))
    bp = sub(p, b)
    d3, d4 = dot(ab, bp), dot(ac, bp)
    if d3 >= 0 and d4 <= d3:
        return math.sqrt(dot(bp, bp))
    vc = d1 * d4 - d3 * d2
    if vc <= 0 and d1 >= 0 and d3 <= 0:
        v = d1 / (d1 - d3)
        q = [a[i] + v * ab[i] - p[i] for i in range(3)]
        return math.sqrt(dot(q, q))
    cp = sub(p, c)
    d5, d6 = dot(ab, cp), dot(ac, cp)
    if d6 >= 0 and d5 <= d6:
        return math.sqrt(dot(cp, cp))
    vb = d5 * d2 - d1 * d6
    if vb <= 0 and d2 >= 0 and d6 <= 0:
        w = d2 / (d2 - d6)
        q = [a[i] + w * ac[i] - p[i] for i in range(3)]
        return math.sqrt(dot(q, q))
    va = d3 * d6 - d5 * d4
    if va <= 0 and d4 - d3 >= 0 and d5 - d6 >= 0:
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        q = [b[i] + w * (c[i] - b[i]) - p[i] for i in range(3)]
        return math.sqrt(dot(q, q))
    den = 1.0 / (va + vb + vc)
    v, w = vb * den, vc * den
    q = [a[i] + ab[i] * v + ac[i] * w - p[i] for i in range(3)]
    return math.sqrt(dot(q, q))


TOL = 0.1
K = 9  # exact points per face and direction, at (i + 0.37) / K: off the lattice
params = []
for f in range(6):
    d, side = f // 2, f % 2
    for i in range(K):
        for j in range(K):
            q = [(i + 0.37) / K, (j + 0.61) / K]
            q.insert(d, float(side))
            params.append(q)
stdin = "".join(f"{u!r} {v!r} {w!r}\n" for u, v, w in params)
for label, model, times in (("linear", LINEAR, (0.37, 0.81)), ("smooth", SMOOTH, (0.12, 0.55))):
    scad = os.path.join(TMP, f"{label}-adaptive.scad")
    rc, _, err = T.run([model, "-t", repr(TOL), "-o", scad])
    n = lattice_of(scad) if rc == 0 else None
    T.check(f"{label}: -t {TOL}: the animation's lattice is chosen (N = {n})", n is not None, err)
    if n is None:
        continue
    for t in times:
        x = os.path.join(TMP, "tol.stl")
        rc1, err1 = openscad_stl(scad, t, x)
        rc2, out, err2 = T.run([model, "--eval", "--time", repr(t)], stdin=stdin)
        if rc1 or rc2:
            T.check(f"{label}: frame at t = {t} renders and evaluates", False, err1 + err2)
            continue
        pts = [[float(v) for v in line.split()] for line in out.splitlines()]
        dist = point_mesh_distance(pts, read_ascii_stl(x), TOL)
        worst = max(dist)
        # OpenSCAD prints 6 digits: 1e-5 of the 10 mm model on top
        T.check(f"{label}: frame t = {t} (between keys) within the tolerance {TOL} "
                f"(worst {worst:.4g} at {len(pts)} exact points)", worst <= TOL + 1e-4,
                f"worst {worst}")

# ---- a morph and a plain body, united by OpenSCAD ---------------------------
box = {"type": "body0", "name": "box",
       "corners": [[x + 20, y, z] for x, y, z in
                   [[0, 0, 0], [0, 0, 3], [0, 3, 0], [0, 3, 3], [3, 0, 0], [3, 0, 3], [3, 3, 0],
                    [3, 3, 3]]]}
mixed = write("mixed.json", [{"type": "morph", "name": "m", "keys": [CUBE, SPOOL]}, box])
scad = os.path.join(TMP, "mixed.scad")
rc, _, err = T.run([mixed, "--resolution", "4", "-o", scad])
with open(scad) if rc == 0 else open(os.devnull) as f:
    text = f.read()
T.check("a plain body is a polyhedron module called in the union() with the morph",
        rc == 0 and re.search(r"module mixed_box\(\) \{\n  polyhedron", text) is not None
        and re.search(r"module mixed\(t = \$t\) \{\n  union\(\) \{\n    mixed_m\(t\);\n"
                      r"    mixed_box\(\);\n  \}", text) is not None,
        err + text[-200:])
x = os.path.join(TMP, "mixed.stl")
rc1, err1 = openscad_stl(scad, 0.5, x)
tris = read_ascii_stl(x) if rc1 == 0 else []
edges = {}
for t in tris:
    for i in range(3):
        e = tuple(sorted((t[i], t[(i + 1) % 3])))
        edges[e] = edges.get(e, 0) + 1
T.check("the union renders to a closed mesh reaching both bodies",
        rc1 == 0 and tris and all(c == 2 for c in edges.values())
        and max(v[0] for t in tris for v in t) == 23.0
        and min(v[0] for t in tris for v in t) < -5, err1)

rc, _, err = T.run([LINEAR, "--time", "0.5", "--resolution", "4", "-o", scad])
with open(scad) as f:
    text = f.read()
T.check("--time T -o .scad: a plain mesh, no animation", rc == 0 and "$t" not in text, err)

shutil.rmtree(TMP, ignore_errors=True)
T.finish()
