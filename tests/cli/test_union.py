#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Repair and union through the real coons2stl, checked by this test's own
readers and geometry (nothing here trusts the library's own verdicts unless
said so):

- two overlapping body0 boxes -> STL and OFF read back: closed (every edge
  used twice, in opposite directions), one shell, volume = the
  inclusion-exclusion value computed here;
- two boxes sharing a face, --resolution N -> one box: volume 2, 20 N^2
  triangles and 10 N^2 + 2 vertices (a single box sampled on a 2N x N x N
  lattice), no vertex left on the shared face;
- operation "none": both shells kept (two shells, volume = the sum);
- the three-examples model (spool + nail + deformed cube) -> .scad rendered
  by the real `openscad`: no warning, the volume of OpenSCAD's STL equal to
  ours within what its 6-digit output allows, and between the largest body's
  volume and the sum; --info's "solid" is the mesh that -o writes;
- a folded Bezier body (z = w t(u, v), t = 1 - 6 B1(u) B1(v), B1 = 2s(1-s))
  -> repaired: no two triangles intersect (an exact integer-arithmetic test
  written here), volume = integral of |t| (midpoint rule) within the
  sampling bound area * tolerance; --no-repair writes the self-crossing
  shell, signed volume = integral of t = 1/3;
- exit status 3, a message naming the body and nothing written (an existing
  file byte-for-byte unchanged, no temporary file) for a body whose repair
  CGAL 5.5 cannot do (tests/data/csg/folded-back-side.json) and for the
  injected failure (a test-only coons2stl, tests/tools/coons2stl_csg_failure.c);
- progress: nothing on a pipe, a line on a terminal (pty) or with
  --progress, none with -q; warnings never share its line;
- usage errors of the new options.
Without CGAL: the union of overlapping bodies is refused (exit 3), "none"
and disjoint bodies still work; the rest is skipped.

Usage: test_union.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import math
import os
import pty
import select
import shutil
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402

T = Runner(__doc__)
CSG = os.path.join(T.data, "csg")
TMP = tempfile.mkdtemp(prefix="coons-union-")


# ---- readers -------------------------------------------------------------------

def read_stl(path):
    """(vertices, faces) of an ASCII or binary STL, welded by exact position."""
    with open(path, "rb") as f:
        data = f.read()
    flat = []
    if data[:5] == b"solid" and b"facet" in data[:1024]:
        for line in data.decode("ascii").splitlines():
            w = line.split()
            if w and w[0] == "vertex":
                flat.append(tuple(float(x) for x in w[1:4]))
    else:
        (n,) = struct.unpack_from("<I", data, 80)
        if len(data) != 84 + 50 * n:
            raise ValueError(f"{path}: {len(data)} bytes for {n} triangles")
        for i in range(n):
            t = struct.unpack_from("<12f", data, 84 + 50 * i)
            flat += [t[3:6], t[6:9], t[9:12]]
    index, verts, faces = {}, [], []
    for i in range(0, len(flat), 3):
        f = []
        for p in flat[i:i + 3]:
            if p not in index:
                index[p] = len(verts)
                verts.append(p)
            f.append(index[p])
        faces.append(tuple(f))
    return verts, faces


def read_off(path):
    """(vertices, faces) of an OFF file, indices as written (doubles exact:
    the writer prints 17 significant digits)."""
    with open(path) as f:
        words = f.read().split()
    assert words[0] == "OFF", words[:1]
    nv, nf = int(words[1]), int(words[2])
    i = 4
    verts = []
    for _ in range(nv):
        verts.append(tuple(float(x) for x in words[i:i + 3]))
        i += 3
    faces = []
    for _ in range(nf):
        assert words[i] == "3"
        faces.append(tuple(int(x) for x in words[i + 1:i + 4]))
        i += 4
    return verts, faces


# ---- mesh facts ------------------------------------------------------------------

def volume(verts, faces):
    v = 0.0
    for a, b, c in faces:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = verts[a], verts[b], verts[c]
        v += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
    return v / 6.0


def area(verts, faces):
    s = 0.0
    for a, b, c in faces:
        u = [verts[b][k] - verts[a][k] for k in range(3)]
        w = [verts[c][k] - verts[a][k] for k in range(3)]
        n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
        s += 0.5 * math.sqrt(sum(x * x for x in n))
    return s


def directed_edges(faces):
    count = {}
    for f in faces:
        for k in range(3):
            e = (f[k], f[(k + 1) % 3])
            count[e] = count.get(e, 0) + 1
    return count


def closed_2manifold(faces):
    """Every edge used exactly twice, once in each direction."""
    d = directed_edges(faces)
    return all(n == 1 and d.get((b, a)) == 1 for (a, b), n in d.items())


def balanced(faces):
    """Closed and oriented, possibly pinched: each edge is run as often in
    one direction as in the other (solids touching along a curve)."""
    d = directed_edges(faces)
    return all(d.get((b, a), 0) == n for (a, b), n in d.items())


def shells(faces):
    parent = {}

    def find(x):
        while parent.setdefault(x, x) != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x
    for a, b, c in faces:
        ra = find(a)
        for v in (b, c):
            rv = find(v)
            if rv != ra:
                parent[rv] = ra
    return len({find(a) for f in faces for a in f})


# ---- exact self-intersection test (integer arithmetic) -------------------------
# Coordinates are dyadic rationals: scaled by a common power of two they
# become integers, and every predicate below is an exact integer sign.

def to_ints(verts):
    shift = 0
    for p in verts:
        for x in p:
            d = x.as_integer_ratio()[1]
            shift = max(shift, d.bit_length() - 1)
    out = []
    for p in verts:
        q = []
        for x in p:
            n, d = x.as_integer_ratio()
            q.append(n * ((1 << shift) // d))
        out.append(tuple(q))
    return out


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def orient(a, b, c, d):
    u, v, w = sub(b, a), sub(c, a), sub(d, a)
    x = (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
         + u[2] * (v[0] * w[1] - v[1] * w[0]))
    return (x > 0) - (x < 0)


def normal(a, b, c):
    u, v = sub(b, a), sub(c, a)
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def proj(p, ax):
    return (p[(ax + 1) % 3], p[(ax + 2) % 3])


def o2(a, b, c):
    x = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    return (x > 0) - (x < 0)


def on_seg2(a, b, p):
    return min(a[0], b[0]) <= p[0] <= max(a[0], b[0]) and min(a[1], b[1]) <= p[1] <= max(a[1], b[1])


def seg_seg2(a, b, c, d):
    d1, d2, d3, d4 = o2(c, d, a), o2(c, d, b), o2(a, b, c), o2(a, b, d)
    if d1 * d2 < 0 and d3 * d4 < 0:
        return True
    return ((d1 == 0 and on_seg2(c, d, a)) or (d2 == 0 and on_seg2(c, d, b))
            or (d3 == 0 and on_seg2(a, b, c)) or (d4 == 0 and on_seg2(a, b, d)))


def in_tri2(a, b, c, p):
    s = (o2(a, b, p), o2(b, c, p), o2(c, a, p))
    return not (1 in s and -1 in s)


def seg_tri(p, q, a, b, c):
    """Closed segment pq meets closed triangle abc (not degenerate)."""
    s1, s2 = orient(a, b, c, p), orient(a, b, c, q)
    if s1 * s2 > 0:
        return False
    if s1 == 0 and s2 == 0:
        n = normal(a, b, c)
        ax = max(range(3), key=lambda k: abs(n[k]))
        A, B, C, P, Q = (proj(x, ax) for x in (a, b, c, p, q))
        return (in_tri2(A, B, C, P) or in_tri2(A, B, C, Q) or seg_seg2(P, Q, A, B)
                or seg_seg2(P, Q, B, C) or seg_seg2(P, Q, C, A))
    s = (orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a))
    return not (1 in s and -1 in s)


def in_wedge(v, x, y, d):
    """Point d, in the plane of triangle (v, x, y), lies in its closed angle at v
    (off v): the direction v->d points into the triangle."""
    n = normal(v, x, y)
    ax = max(range(3), key=lambda k: abs(n[k]))
    V, X, Y, D = (proj(p, ax) for p in (v, x, y, d))
    s = o2(V, X, Y)
    a, b = o2(V, X, D) * s, o2(V, D, Y) * s
    if a < 0 or b < 0:
        return False
    if a == 0:  # along v->x: same direction?
        return (X[0] - V[0]) * (D[0] - V[0]) + (X[1] - V[1]) * (D[1] - V[1]) > 0
    if b == 0:
        return (Y[0] - V[0]) * (D[0] - V[0]) + (Y[1] - V[1]) * (D[1] - V[1]) > 0
    return True


def tri_pair_intersects(P, s, t):
    """Triangles s, t (vertex indices into P) meet other than along an edge
    or at a vertex they share by index."""
    shared = [i for i in s if i in t]
    if len(shared) >= 3:
        return True
    if len(shared) == 2:
        x = next(i for i in s if i not in shared)
        y = next(i for i in t if i not in shared)
        p, q = P[shared[0]], P[shared[1]]
        if orient(p, q, P[x], P[y]) != 0:
            return False
        n = normal(p, q, P[x])
        ax = max(range(3), key=lambda k: abs(n[k]))
        Pp, Qq, X, Y = (proj(P[i], ax) for i in (shared[0], shared[1], x, y))
        return o2(Pp, Qq, X) * o2(Pp, Qq, Y) > 0
    if len(shared) == 1:
        v = shared[0]
        a, b = [P[i] for i in s if i != v]
        c, d = [P[i] for i in t if i != v]
        V = P[v]
        if seg_tri(a, b, V, c, d) or seg_tri(c, d, V, a, b):
            return True
        for e, (x, y) in ((a, (c, d)), (b, (c, d)), (c, (a, b)), (d, (a, b))):
            if orient(V, x, y, e) == 0 and in_wedge(V, x, y, e):
                return True
        return False
    A, B, C = (P[i] for i in s)
    D, E, F = (P[i] for i in t)
    return (seg_tri(A, B, D, E, F) or seg_tri(B, C, D, E, F) or seg_tri(C, A, D, E, F)
            or seg_tri(D, E, A, B, C) or seg_tri(E, F, A, B, C) or seg_tri(F, D, A, B, C))


def self_intersections(verts, faces):
    """Pairs of triangles that intersect other than at shared edges/vertices:
    candidates from a uniform grid of boxes, then the exact test."""
    P = to_ints(verts)
    boxes = []
    for f in faces:
        boxes.append(([min(P[i][k] for i in f) for k in range(3)],
                      [max(P[i][k] for i in f) for k in range(3)]))
    span = max(max(b[1][k] for b in boxes) - min(b[0][k] for b in boxes) for k in range(3))
    cell = max(1, int(span / max(1.0, len(faces) ** (1 / 2.2))))
    grid = {}
    for n, (lo, hi) in enumerate(boxes):
        rng = [range(lo[k] // cell, hi[k] // cell + 1) for k in range(3)]
        for i in rng[0]:
            for j in rng[1]:
                for k in rng[2]:
                    grid.setdefault((i, j, k), []).append(n)
    seen, pairs = set(), 0
    for members in grid.values():
        for x in range(len(members)):
            for y in range(x + 1, len(members)):
                m, n = members[x], members[y]
                key = (m, n) if m < n else (n, m)
                if key in seen:
                    continue
                seen.add(key)
                (la, ha), (lb, hb) = boxes[m], boxes[n]
                if any(la[k] > hb[k] or lb[k] > ha[k] for k in range(3)):
                    continue
                if tri_pair_intersects(P, faces[m], faces[n]):
                    pairs += 1
    return pairs


# ---- models --------------------------------------------------------------------

def box(name, lo, hi):
    c = []
    for n in range(8):
        i, j, k = n >> 2, (n >> 1) & 1, n & 1
        c.append([(lo, hi)[i][0], (lo, hi)[j][1], (lo, hi)[k][2]])
    return {"type": "body0", "name": name, "corners": c}


def write_model(name, bodies, **extra):
    path = os.path.join(TMP, name)
    m = {"coons": 1, "bodies": bodies}
    m.update(extra)
    with open(path, "w") as f:
        json.dump(m, f)
    return path


def info(args):
    rc, out, err = T.run(["--info"] + list(args))
    try:
        return rc, json.loads(out), err
    except ValueError:
        return rc, None, err + out


def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def listing(d):
    return sorted(os.listdir(d))


A_LO, A_HI = [0, 0, 0], [2, 1.5, 1]
B_LO, B_HI = [0.5, 0.25, 0.5], [2.5, 1.25, 1.75]


def box_volume(lo, hi):
    return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])


def overlap_volume():
    v = 1.0
    for k in range(3):
        v *= max(0.0, min(A_HI[k], B_HI[k]) - max(A_LO[k], B_LO[k]))
    return v


over = write_model("over.json", [box("a", A_LO, A_HI), box("b", B_LO, B_HI)])
over_none = write_model("over-none.json", [box("a", A_LO, A_HI), box("b", B_LO, B_HI)],
                        operation="none")
share = write_model("share.json", [box("left", [0, 0, 0], [1, 1, 1]),
                                   box("right", [1, 0, 0], [2, 1, 1])])
V_A, V_B, V_AB = box_volume(A_LO, A_HI), box_volume(B_LO, B_HI), overlap_volume()

rc, j, err = info([over])
T.check("--info on two boxes: exit 0, a 'solid' object", rc == 0 and j is not None and "solid" in j, err)
HAVE_CGAL = bool(j and j.get("solid") and j["solid"].get("csg") is not None)
print(f"# CGAL in this build: {HAVE_CGAL}")

# ---- without CGAL ------------------------------------------------------------------
if not HAVE_CGAL:
    out = os.path.join(TMP, "x.stl")
    rc, _, err = T.run(["-o", out, over])
    T.check("no CGAL: overlapping union refused with exit 3, nothing written",
            rc == 3 and "CGAL" in err and not os.path.exists(out), err)
    rc, _, err = T.run(["-o", os.path.join(TMP, "n.off"), over_none])
    v, f = read_off(os.path.join(TMP, "n.off")) if rc == 0 else ([], [])
    T.check("no CGAL: operation none still writes both shells",
            rc == 0 and shells(f) == 2 and rel(volume(v, f), V_A + V_B) < 1e-12, err)
    rc, _, err = T.run(["--progress", "-o", os.path.join(TMP, "n.off"), over_none], binary=True)
    err = err.decode("utf-8", "replace")
    T.check("no CGAL: --progress reports the sampling of each body, one line",
            rc == 0 and "\rcoons2stl: sampling body 2 of 2 (b)" in err and err.endswith("\n")
            and err.count("\n") == 1, repr(err))
    rc, jf, err = info([os.path.join(CSG, "fold.json")])
    T.check("no CGAL: a lone folded body is written as sampled, --info says: not repaired",
            jf is not None and jf["solid"]["repair"] is False and jf["solid"]["csg"] is None
            and jf["solid"]["self_intersections"] is None, str(jf and jf["solid"]))
    T.check("no CGAL: --info solid says why no mesh can be made",
            j is not None and "error" in j["solid"] and "CGAL" in j["solid"]["error"], str(j and j["solid"]))
    shutil.rmtree(TMP)
    T.finish()

# ---- overlapping boxes --------------------------------------------------------
expect = V_A + V_B - V_AB
for fmt in ("stl", "off"):
    out = os.path.join(TMP, "over." + fmt)
    rc, _, err = T.run(["-o", out, over])
    ok = rc == 0 and os.path.exists(out)
    T.check(f"overlapping boxes -> {fmt}: exit 0, silent", ok and err == "", err)
    if not ok:
        continue
    v, f = read_stl(out) if fmt == "stl" else read_off(out)
    vol = volume(v, f)
    # float32 keeps 0.5, 0.25, 1.25, 1.75 ... exactly: both formats are exact here.
    T.check(f"overlapping boxes ({fmt}): closed, every edge twice in opposite directions, one shell",
            closed_2manifold(f) and shells(f) == 1, f"shells {shells(f)}")
    T.check(f"overlapping boxes ({fmt}): volume = {V_A} + {V_B} - {V_AB} = {expect}",
            rel(vol, expect) < 1e-12, f"{vol!r}")
    if fmt == "off":
        T.check("overlapping boxes: no self-intersection (exact test here)",
                self_intersections(v, f) == 0)
        s = j["solid"]
        T.check("--info solid is the mesh -o writes (triangles, vertices, volume)",
                s["triangles"] == len(f) and s["vertices"] == len(v)
                and rel(s["volume"], vol) < 1e-13 and s["united"] and s["repair"], str(s))
        T.check("--info solid: checks and CSG report (2 parts in, 1 group, union, no crossing)",
                s["closed"] and s["manifold"] and s["oriented"] and s["shells"] == 1
                and s["self_intersections"] == 0 and s["self_intersections_float32"] == 0
                and s["csg"]["parts_in"] == 2 and s["csg"]["groups"] == 1
                and s["csg"]["triangles_in"] == sum(b["mesh"]["triangles"] for b in j["bodies"])
                and s["csg"]["triangles_out"] == len(f) and s["csg"]["closed"], str(s))
        T.check("--info: each box's own shell does not cross itself",
                [b["mesh"]["self_intersections"] for b in j["bodies"]] == [0, 0], str(j["bodies"]))

out = os.path.join(TMP, "over-nr.off")
rc, _, err = T.run(["--no-repair", "-o", out, over])
if T.check("overlapping boxes, --no-repair: exit 0", rc == 0, err):
    v, f = read_off(out)
    T.check("overlapping boxes, --no-repair: still united (bodies that meet go through the union)",
            closed_2manifold(f) and shells(f) == 1 and rel(volume(v, f), expect) < 1e-12,
            f"{shells(f)} shells, volume {volume(v, f)}")
rc, jb, err = info(["--body", "b", over])
T.check("--info --body b: the solid is that body's shell alone (not united, its volume)",
        jb is not None and not jb["solid"]["united"] and jb["solid"]["parts"] == 1
        and rel(jb["solid"]["volume"], V_B) < 1e-12 and jb["solid"]["csg"]["parts_in"] == 1,
        str(jb and jb["solid"]))

# ---- boxes sharing a face -------------------------------------------------------
for N in (1, 3, 4):
    out = os.path.join(TMP, f"share{N}.off")
    rc, _, err = T.run(["--resolution", str(N), "-o", out, share])
    ok = rc == 0
    T.check(f"boxes sharing a face, --resolution {N}: exit 0", ok, err)
    if not ok:
        continue
    v, f = read_off(out)
    inner = [p for p in v if p[0] == 1 and 0 < p[1] < 1 and 0 < p[2] < 1]
    T.check(f"shared face (N={N}): one closed box of volume 2, area 10, no vertex left inside the "
            "shared face",
            closed_2manifold(f) and shells(f) == 1 and rel(volume(v, f), 2.0) < 1e-14
            and rel(area(v, f), 10.0) < 1e-14 and not inner, f"{volume(v, f)} {area(v, f)} {len(inner)}")
    # The faces are flat, so each is triangulated from its boundary polygon
    # (plus a few Steiner points): the shell is a closed genus-0 surface
    # (T = 2V - 4) holding at least every lattice point of the 12 edges of
    # the 2 x 1 x 1 box and of the line x = 1 where the two boxes' side
    # faces meet (8 + 4 (2N - 1) + 8 (N - 1) + 4 (N - 1) = 20N - 8), and no
    # more triangles than the lattice's 2 per cell: 4 (2N^2 + 2N^2 + N^2).
    T.check(f"shared face (N={N}): T = 2V - 4, V >= {20 * N - 8}, T <= {20 * N * N} (flat faces "
            f"from their boundary, at most a single box sampled on {2 * N}x{N}x{N})",
            len(f) == 2 * len(v) - 4 and len(v) >= 20 * N - 8 and len(f) <= 20 * N * N,
            f"{len(f)} triangles, {len(v)} vertices")

# ---- operation none --------------------------------------------------------------
out = os.path.join(TMP, "none.off")
rc, _, err = T.run(["-o", out, over_none])
if T.check("operation none: exit 0", rc == 0, err):
    v, f = read_off(out)
    T.check("operation none: both shells kept (2 shells, each closed), volume = the sum",
            shells(f) == 2 and closed_2manifold(f) and rel(volume(v, f), V_A + V_B) < 1e-12,
            f"{shells(f)} shells, volume {volume(v, f)}")
rc, j, err = info([over_none])
T.check("operation none: --info solid has 2 parts, not united, volume = the sum",
        j is not None and j["solid"]["parts"] == 2 and not j["solid"]["united"]
        and rel(j["solid"]["volume"], V_A + V_B) < 1e-12, str(j and j["solid"]))

# ---- the three examples through OpenSCAD ---------------------------------------
three = os.path.join(T.data, "ok", "three-examples-union.json")
TOL3 = "0.05"
rc, j, err = info(["-t", TOL3, three])
ok = rc == 0 and j is not None and "error" not in j["solid"]
T.check("three examples: --info with a solid", ok, err)
if ok:
    vols = [abs(b["volume"]) for b in j["bodies"]]
    scad, ours_off = os.path.join(TMP, "three.scad"), os.path.join(TMP, "three.off")
    rc1, _, e1 = T.run(["-t", TOL3, "-o", scad, three])
    rc2, _, e2 = T.run(["-t", TOL3, "-o", ours_off, three])
    ok = rc1 == 0 and rc2 == 0
    T.check("three examples: -o .scad and .off", ok, e1 + e2)
    v, f = read_off(ours_off) if ok else ([], [])
    ours = volume(v, f)
    s = j["solid"]
    T.check("three examples: one closed shell, no self-intersection (exact test here)",
            ok and closed_2manifold(f) and shells(f) == 1 and self_intersections(v, f) == 0)
    T.check("three examples: --info solid = the written mesh (volume, triangles)",
            ok and rel(s["volume"], ours) < 1e-13 and s["triangles"] == len(f), f"{s} {ours}")
    # the sampled surfaces are within tol of the exact ones: allow a tol-thick skin
    slack = area(v, f) * float(TOL3) if ok else 0
    T.check("three examples: largest body volume < union volume < sum (by more than the skin)",
            ok and max(vols) - slack < ours < sum(vols) - slack, f"{max(vols)} {ours} {sum(vols)} +- {slack}")
    if shutil.which("openscad") and ok:
        ostl = os.path.join(TMP, "openscad.stl")
        p = subprocess.run(["openscad", "-o", ostl, scad], cwd=TMP, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True, timeout=600)
        log = p.stdout + p.stderr
        bad = [w for w in ("WARNING", "ERROR", "not manifold", "may not be a valid 2-manifold",
                           "not closed") if w in log]
        T.check("three examples: openscad renders the .scad, exit 0, no warning", p.returncode == 0
                and not bad and os.path.exists(ostl), log)
        if os.path.exists(ostl):
            ov, of = read_stl(ostl)
            vo = volume(ov, of)
            # OpenSCAD 2021 prints 6 significant digits: each coordinate moves
            # by at most half a unit of its 6th digit, and the volume by at most
            # area * (that, as a vector) to first order.
            delta = max(0.5 * 10 ** (math.floor(math.log10(abs(x))) - 5) for p in ov for x in p if x)
            bound = area(ov, of) * delta * math.sqrt(3)
            T.check(f"three examples: OpenSCAD's volume = ours within its output rounding ({bound:.2g})",
                    abs(vo - ours) <= bound and closed_2manifold(of), f"{vo} vs {ours}")
    elif ok:
        T.need("openscad")  # a real client: missing, it fails

# ---- a folded body --------------------------------------------------------------
fold = os.path.join(CSG, "fold.json")
M = 2000  # midpoint rule, t is a polynomial: error ~ 1e-7 away from the zero curve
int_abs = int_t = 0.0
for a in range(M):
    x = (a + 0.5) / M
    bx = 2 * x * (1 - x)
    for b in range(M):
        y = (b + 0.5) / M
        t = 1 - 6 * bx * 2 * y * (1 - y)
        int_abs += abs(t)
        int_t += t
int_abs /= M * M
int_t /= M * M
TOLF = 0.004
rc, j, err = info(["-t", str(TOLF), fold])
ok = rc == 0 and j is not None
T.check("fold: --info warns that it folds and that its shell crosses itself", ok
        and "folds over itself" in err and "crosses itself" in err
        and j["bodies"][0]["mesh"]["self_intersections"] > 0, err)
if ok:
    s = j["solid"]
    # Where t = 0 the two sheets of the covered region touch along a curve:
    # the pinch (edges of four triangles) is split: closed and 2-manifold
    # (test_manifold.py checks the split itself).
    T.check("fold: --info solid repaired (pairs found, none left, no border edge, pinch split)",
            s["csg"]["intersecting_pairs"] > 0 and s["self_intersections"] == 0
            and s["boundary_edges"] == 0 and s["csg"]["closed"] and s["nonmanifold_edges"] == 0
            and s["csg"]["pinch_edges_split"] > 0 and s["repair"], str(s))
    T.check("fold: no warning that it is not closed or not a 2-manifold",
            "2-manifold" not in err and "not closed" not in err, err)
out = os.path.join(TMP, "fold.off")
rc, _, err = T.run(["-t", str(TOLF), "-o", out, fold])
if T.check("fold: -o exit 0", rc == 0, err):
    v, f = read_off(out)
    vol, ar = volume(v, f), area(v, f)
    T.check("fold repaired: closed and 2-manifold (each edge once each way)", closed_2manifold(f))
    T.check("fold repaired: -o is silent (the pinch split, no 2-manifold warning)", err == "", err)
    n = self_intersections(v, f)
    T.check("fold repaired: no two triangles intersect (exact test here)", n == 0, f"{n} pairs")
    T.check(f"fold repaired: volume = integral |t| = {int_abs:.6f} within area * tol",
            abs(vol - int_abs) <= ar * TOLF, f"{vol} vs {int_abs}, bound {ar * TOLF}")
out = os.path.join(TMP, "fold-raw.off")
rc, _, err = T.run(["--no-repair", "-t", str(TOLF), "-o", out, fold])
if T.check("fold --no-repair: exit 0", rc == 0, err):
    v, f = read_off(out)
    vol, ar = volume(v, f), area(v, f)
    T.check(f"fold --no-repair: the sampled shell, signed volume = integral t = {int_t:.6f} (1/3)",
            abs(vol - int_t) <= ar * TOLF and abs(int_t - 1 / 3) < 1e-6 and closed_2manifold(f),
            f"{vol} vs {int_t}")
    mine = self_intersections(v, f)
    T.check("fold --no-repair: it crosses itself (exact test here)", mine > 0, f"{mine}")
    rc, j, err = info(["--no-repair", "-t", str(TOLF), fold])
    T.check("fold --info --no-repair: solid not repaired, crossing reported",
            j is not None and not j["solid"]["repair"] and j["solid"]["self_intersections"] > 0
            and "crosses itself" in err, err)
    # Two independent exact counts (CGAL's in the library, this test's) agree.
    T.check("fold --no-repair: --info counts the same crossing pairs as this test",
            j is not None and j["solid"]["self_intersections"] == mine
            and j["bodies"][0]["mesh"]["self_intersections"] == mine,
            f"{j and j['solid']['self_intersections']} vs {mine}")
    stl = os.path.join(TMP, "fold-raw.stl")
    rc, _, err = T.run(["--no-repair", "-t", str(TOLF), "-o", stl, fold])
    if rc == 0:
        sv, sf = read_stl(stl)
        T.check("fold --no-repair: self_intersections_float32 = this test's count on the STL",
                j is not None and j["solid"]["self_intersections_float32"] == self_intersections(sv, sf))

# ---- exit 3: a repair CGAL cannot do, and an injected failure -------------------
def untouched_failure(name, model, env=None, args=(), binary=None):
    d = tempfile.mkdtemp(dir=TMP)
    keep = os.path.join(d, "keep.stl")
    with open(keep, "wb") as fh:
        fh.write(b"old content\n")
    before = listing(d)
    full = dict(os.environ)
    full.update(env or {})
    p = subprocess.run([binary or T.bin] + list(args) + ["-o", keep, model], stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True, env=full, timeout=120)
    with open(keep, "rb") as fh:
        same = fh.read() == b"old content\n"
    T.check(f"{name}: exit 3, existing file unchanged, no temporary file left",
            p.returncode == 3 and same and listing(d) == before, f"{p.returncode} {p.stderr}")
    fresh = os.path.join(d, "new.stl")
    p2 = subprocess.run([binary or T.bin] + list(args) + ["-o", fresh, model], stdout=subprocess.PIPE,
                        stderr=subprocess.PIPE, text=True, env=full, timeout=120)
    T.check(f"{name}: a new file is not created", p2.returncode == 3 and not os.path.exists(fresh)
            and listing(d) == before, p2.stderr)
    return p.stderr


fb = os.path.join(CSG, "folded-back-side.json")
err = untouched_failure("folded-back side (coplanar self-overlap)", fb)
T.check("folded-back side: the message names the body, the failed step and says nothing was written",
        "the repair of body 'folded-back' failed" in err and "nothing was written" in err
        and err.count("\n") == 1, err)
rc, _, err2 = T.run(["--no-repair", "-o", os.path.join(TMP, "fb.stl"), fb])
T.check("folded-back side: --no-repair writes it as sampled", rc == 0, err2)
rc, j, err2 = info([fb])
T.check("folded-back side: --info exits 0 with solid.error naming the body, and a warning",
        rc == 0 and j is not None and "'folded-back'" in j["solid"].get("error", "")
        and "warning" in err2, err2)
# A CGAL failure: coons2stl built for the test with the failure injected
# (tests/tools/coons2stl_csg_failure.c); the installed command has no hook.
INJ = os.path.join(T.build, "tests", "coons2stl_csg_failure")
T.check("the failing build of coons2stl exists", os.path.exists(INJ), INJ)
err = untouched_failure("injected CSG failure", over, binary=INJ)
T.check("injected failure: the message names the bodies and what failed",
        "'a'" in err and "'b'" in err and "CGAL could not complete" in err, err)
p = subprocess.run([T.bin, "-o", os.path.join(TMP, "zero.stl"), over], stdout=subprocess.PIPE,
                   stderr=subprocess.PIPE, text=True, timeout=120,
                   env=dict(os.environ, COONS2STL_INJECT_CSG_FAILURE="1"))
T.check("the installed coons2stl has no test hook: COONS2STL_INJECT_CSG_FAILURE=1 changes "
        "nothing", p.returncode == 0, p.stderr)
err = untouched_failure("injected failure with --body", over, args=["--body", "b"], binary=INJ)
T.check("injected failure with --body names that body", "'b'" in err, err)

# ---- progress ---------------------------------------------------------------------
def run_raw(args):
    """As T.run, standard error undecoded (text mode would turn \r into \n)."""
    rc, _, err = T.run(args, binary=True)
    return rc, err.decode("utf-8", "replace")


out = os.path.join(TMP, "p.stl")
rc, err = run_raw(["-o", out, over])
T.check("no progress when standard error is not a terminal", rc == 0 and err == "", repr(err))
rc, err = run_raw(["--progress", "-o", out, over])
segs = err.split("\r")
T.check("--progress: one line rewritten with \\r, each state 'coons2stl: ...', ended by a newline",
        rc == 0 and err.startswith("\rcoons2stl: ") and err.endswith("\n") and err.count("\n") == 1
        and all(s.startswith("coons2stl: ") for s in segs[1:]), repr(err))
T.check("--progress: sampling per body, then the repair and union stages up to 100%",
        "sampling body 1 of 2 (a)" in err and "sampling body 2 of 2 (b)" in err
        and "repair and union:" in err and "100%" in err, repr(err))
rc, err = run_raw(["--progress", "--body", "b", "-o", out, over])
T.check("--progress --body: that body's sampling", rc == 0 and "sampling body 2 of 2 (b)" in err, repr(err))
rc, err = run_raw(["-q", "-o", out, over])
T.check("-q: silent", rc == 0 and err == "", repr(err))
rc, err = run_raw(["--progress", "--info", "--no-repair", "-t", str(TOLF), fold])  # cheap: no repair
lines = err.split("\n")
T.check("--progress with warnings (--info on the fold): warnings on lines of their own",
        rc == 0 and all(("warning" not in ln) or ln.startswith("coons2stl: warning") for ln in lines)
        and sum(ln.startswith("coons2stl: warning") for ln in lines) >= 2
        and any(ln.startswith("\r") for ln in lines) and err.endswith("\n"), repr(err))
rc, err = run_raw(["--progress", "-q", "-o", out, over])
T.check("--progress -q: quiet wins, no progress and no warnings",
        rc == 0 and err == "", repr(err))


def run_on_pty(args):
    """Runs coons2stl with standard error on a pseudo-terminal; returns
    (status, what it wrote there)."""
    master, slave = pty.openpty()
    p = subprocess.Popen([T.bin] + args, stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    data = b""
    while True:
        r, _, _ = select.select([master], [], [], 60)
        if not r:
            break
        try:
            chunk = os.read(master, 4096)
        except OSError:
            break
        if not chunk:
            break
        data += chunk
    os.close(master)
    return p.wait(timeout=60), data.decode("utf-8", "replace")


rc, tty = run_on_pty(["-o", out, over])
T.check("on a terminal: progress by default", rc == 0 and "\rcoons2stl: sampling body 1 of 2" in tty
        and "repair and union:" in tty, repr(tty))
rc, tty = run_on_pty(["-q", "-o", out, over])
T.check("on a terminal, -q: no progress", rc == 0 and tty == "", repr(tty))

# ---- det J: no false fold on round bodies ------------------------------------------
for name in ("spool", "nail"):
    rc, j, err = info(["--no-solid", os.path.join(T.src, "examples", name + ".json")])
    ok = rc == 0 and j is not None
    if ok:
        b = j["bodies"][0]
        d = b["min_det_jacobian"]
        diag = math.dist(b["control_bbox"]["min"], b["control_bbox"]["max"])
    # det J is exactly 0 on the axis / at the tip: rounding leaves ~1e-16 d^3
    T.check(f"{name}: raw min det J reported ({d if ok else None}, within 1e-9 d^3 of 0), "
            "no 'folds over itself' warning",
            ok and abs(d) < 1e-9 * diag ** 3 and "folds" not in err and "det J" not in err, err)

# ---- usage ----------------------------------------------------------------------------
for args, what in ((["--no-solid", "-o", out, over], "--no-solid without --info"),
                   (["--eval", "--no-repair", over], "--eval --no-repair"),
                   (["--eval", "--progress", over], "--eval --progress"),
                   (["--no-repair=1", over], "--no-repair=1")):
    rc, _, err = T.run(args)
    T.check(f"usage error: {what} -> exit 2", rc == 2 and "Try" in err, err)
rc, j, err = info(["--no-solid", over])
T.check("--info --no-solid: solid and self_intersections null",
        rc == 0 and j is not None and j["solid"] is None
        and all(b["mesh"]["self_intersections"] is None for b in j["bodies"]), str(j))

shutil.rmtree(TMP)
T.finish()
