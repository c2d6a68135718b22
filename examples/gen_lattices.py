#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Generates the control-lattice examples (seed 000 §3: "each cell of the
control lattice is defined by six faces ... Each cell defines a Coons body";
neighbouring cells share faces) and verifies each one.

    python3 examples/gen_lattices.py            write the files, verify, summarise
    python3 examples/gen_lattices.py --check    verify that the files on disk are exactly
                                                what this script writes (nothing is written)

Cells share faces by construction: body 0 cells take their corners from one
global lattice of points, body 2 cells are Bezier or NURBS volumes whose
touching boundary layers are the same control points. The checks (with the
independent evaluator coons_ref.py, on the JSON text as written): every
shared face is the same map from both sides at 11 x 11 parameters, det J > 0
inside every cell, and each model's total volume against a closed form where
there is one. Standard library only; helpers from gen_examples.py.
"""

import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import coons_ref as R  # noqa: E402
import gen_examples as G  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def body0(name, corner):
    """A body 0 whose corner P_ijk (at 4i + 2j + k) is corner(i, j, k)."""
    return {"type": "body0", "name": name,
            "corners": [G.P(*corner(i, j, k)) for i in (0, 1) for j in (0, 1) for k in (0, 1)]}


# ---------------------------------------------------------------- the models

def m_ffd_lattice():
    """A 4 x 4 x 4 lattice of body 0 cells (a free-form deformation lattice,
    seed 000 §1/§5) whose 27 inner points moved: the outer boundary is the
    40 mm cube's, so the solid's volume is exactly 64000 mm^3 whatever the
    inner points do; the volume mesh shows them."""
    n, h = 4, 10.0
    moved = {}
    for i in range(1, n):
        for j in range(1, n):
            for k in range(1, n):
                # a smooth swirl about the vertical axis, growing with height
                a = 0.35 * (k / n) * math.sin(math.pi * i / n) * math.sin(math.pi * j / n)
                x, y = (i - n / 2) * h, (j - n / 2) * h
                moved[i, j, k] = [n / 2 * h + x * math.cos(a) - y * math.sin(a),
                                  n / 2 * h + x * math.sin(a) + y * math.cos(a),
                                  k * h + 1.5 * math.sin(math.pi * i / n)]

    def point(i, j, k):
        return moved.get((i, j, k), [i * h, j * h, k * h])
    bodies = [body0("c%d%d%d" % (i, j, k),
                    lambda a, b, c, i=i, j=j, k=k: point(i + a, j + b, k + c))
              for i in range(n) for j in range(n) for k in range(n)]
    return "lattice-ffd.json", G.model(bodies, operation="union"), [exact_volume(64000.0)]


def m_chair_lattice():
    """Seed 000 Fig. 9 as a control lattice: the chair's seat (3 x 4 cells,
    dished), back (3 x 2 cells, leaning back), column (2 cells) and base (a
    cross of 5 cells with tapered legs) are body 0 cells on one lattice of
    points, sharing faces where they meet: the solid needs no Boolean."""
    xs = [-21, -7, 7, 21]
    ys = [-21, -7, 7, 15, 21]
    zs = [0, 8, 26, 44, 48, 70, 92]

    def point(i, j, k):
        x, y, z = float(xs[i]), float(ys[j]), float(zs[k])
        if k in (1, 2, 3) and i in (1, 2) and j in (1, 2):  # the column: 8 mm square
            x, y = 4.0 * (1 if i == 2 else -1), 4.0 * (1 if j == 2 else -1)
        if k == 1 and (i in (0, 3) or j in (0, 4)):  # leg tips taper down
            z = 4.0
        if k == 4 and i in (1, 2) and j in (1, 2, 3):  # dished seat
            z -= 1.5
        if k >= 5:  # the back leans back
            y += 3.0 * (k - 4)
        return [x, y, z]

    cells = []
    base = [(1, 1), (0, 1), (2, 1), (1, 0), (1, 2)]
    for (i, j) in base:  # a cross: centre and four legs (y legs on rows 0 and 2..3)
        jj = [j] if j != 2 else [2, 3]
        for j2 in jj:
            cells.append(("base%d%d" % (i, j2), i, j2, 0))
    for k in (1, 2):
        cells.append(("column%d" % k, 1, 1, k))
    for i in range(3):
        for j in range(4):
            cells.append(("seat%d%d" % (i, j), i, j, 3))
    for i in range(3):
        for k in (4, 5):
            cells.append(("back%d%d" % (i, k - 4), i, 3, k))
    bodies = [body0(nm, lambda a, b, c, i=i, j=j, k=k: point(i + a, j + b, k + c))
              for (nm, i, j, k) in cells]
    return "chair-lattice.json", G.model(bodies, operation="union"), []


def bezier_volume_net(f, ni, nj, nk):
    """Control net of the degree (ni-1, nj-1, nk-1) Bezier volume that is the
    polynomial map f when f is of that degree (by interpolation would need
    a solve; here f is given on the control lattice directly)."""
    return [[[G.P(*f(i / (ni - 1), j / (nj - 1), k / (nk - 1))) for k in range(nk)]
             for j in range(nj)] for i in range(ni)]


def m_l_bracket():
    """An L-shaped bracket of three body 2 cells (Bezier faces: the boundary
    layers of one quadratic control volume each): a corner block and two
    arms whose ends are rounded; the arms' first layers are the corner's
    last, so each arm shares a whole face with the corner."""
    t, w, L = 8.0, 12.0, 40.0  # arm thickness, width (z), length

    def corner(i, j, k):
        return [t * i, t * j, w * k]

    def arm_x(i, j, k):  # x from t to L, rounded end: the middle layer bulges
        x = t + (L - t) * i
        if i == 1:
            x += 3.0 * (1 - (2 * j - 1) ** 2) * (1 - 0.3 * (2 * k - 1) ** 2)
        return [x, t * j, w * k]

    def arm_y(i, j, k):
        y = t + (L - t) * j
        if j == 1:
            y += 3.0 * (1 - (2 * i - 1) ** 2) * (1 - 0.3 * (2 * k - 1) ** 2)
        return [t * i, y, w * k]

    def net(f, n):
        return [[[G.P(*f(a / (n[0] - 1), b / (n[1] - 1), c / (n[2] - 1))) for c in range(n[2])]
                 for b in range(n[1])] for a in range(n[0])]
    c = G.body2_from_volume(net(corner, (3, 3, 3)), name="corner")
    ax = G.body2_from_volume(net(arm_x, (3, 3, 3)), name="arm-x")
    ay = G.body2_from_volume(net(arm_y, (3, 3, 3)), name="arm-y")
    return "lattice-l-bracket.json", G.model([c, ax, ay], operation="union"), []


def m_ring():
    """A ring of 8 body 2 cells around the z axis, each a 45-degree NURBS
    sector (rational quadratic arcs, exact circles of radii 20 and 30,
    height 10): a closed loop of cells, the last sharing a face with the
    first. Volume pi (30^2 - 20^2) 10."""
    r0, r1, h = 20.0, 30.0, 10.0
    wm = math.cos(math.pi / 8)

    def pt(r, a, z):
        return [r * math.cos(a), r * math.sin(a), z]
    bodies = []
    for k in range(8):
        a0, a1 = 2 * math.pi * k / 8, 2 * math.pi * (k + 1) / 8
        am = 0.5 * (a0 + a1)
        net, wts = [], []
        # u radial, v around (a rational quadratic arc), w up: right-handed
        for r in (r0, r1):
            row, wrow = [], []
            for i, (a, rad) in enumerate([(a0, 1.0), (am, 1.0 / wm), (a1, 1.0)]):
                col, wcol = [], []
                for z in (0.0, h):
                    col.append(G.P(*pt(r * rad, a if k + 1 < 8 or i < 2 else 0.0, z)))
                    wcol.append(wm if i == 1 else 1)
                row.append(col)
                wrow.append(wcol)
            net.append(row)
            wts.append(wrow)
        bodies.append(G.body2_from_volume(net, degree=[1, 2, 1], weights=wts,
                                          name="sector%d" % k))
    return "lattice-ring.json", G.model(bodies, operation="union"), \
        [exact_volume(math.pi * (r1 * r1 - r0 * r0) * h)]


def m_instanced():
    """An instanced part: one foot (a body 2 of Bezier faces with a domed
    top) defined once and placed three times by references with transforms,
    one of them mirrored (left-handed: still written outward). The
    instances stand apart, so the union is a plain collection."""
    def foot(a, b, c):
        z = 10 * c + (4.0 if a == 0.5 and b == 0.5 and c == 1 else 0.0)
        return G.P(8 * a + (1.0 if c == 1 and a == 1 else 0.0), 8 * b, z)
    net = [[[foot(a, b, c) for c in (0, 1)] for b in (0, 0.5, 1)] for a in (0, 0.5, 1)]
    m = {"coons": 1, "units": "mm", "operation": "union",
         "define": {"foot": G.body2_from_volume(net, name="foot")},
         "bodies": [{"ref": "foot", "name": "foot-a"},
                    {"ref": "foot", "name": "foot-b",
                     "transform": [[1, 0, 0, 14], [0, 1, 0, 0], [0, 0, 1, 0]]},
                    {"ref": "foot", "name": "foot-mirror",
                     "transform": [[-1, 0, 0, 38], [0, 1, 0, 0], [0, 0, 1, 0]]}]}
    return "lattice-instanced.json", m, []


# ---------------------------------------------------------------- checks

GAUSS = None


def gauss(n=8):
    """Gauss-Legendre nodes and weights on [0, 1] (Newton on P_n)."""
    xs, ws = [], []
    for i in range(1, n + 1):
        x = math.cos(math.pi * (i - 0.25) / (n + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for k in range(2, n + 1):
                p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < 1e-16:
                break
        xs.append(0.5 * (1 - x))
        ws.append(1.0 / ((1 - x * x) * dp * dp))
    return xs, ws


def body_volume(b):
    """The integral of |det J| over the parameter cube (Gauss-Legendre, 8
    points per direction: exact for body 0 and polynomial cells of degree
    up to 5 per direction, converged to rounding for the NURBS sectors)."""
    xs, ws = gauss(8)
    v = 0.0
    for i, u in enumerate(xs):
        for j, vv in enumerate(xs):
            for k, w in enumerate(xs):
                v += ws[i] * ws[j] * ws[k] * abs(R.body_jacobian_det(b, u, vv, w))
    return v


def exact_volume(v):
    def check(m):
        got = sum(body_volume(b) for b in expanded(m)["bodies"])
        return "sum of cell volumes %.6f = %.6f" % (got, v), abs(got - v), v
    return check


def expanded(m):
    return R.expand(m)


FACE_FIX = {"u0": (0, 0), "u1": (0, 1), "v0": (1, 0), "v1": (1, 1), "w0": (2, 0), "w1": (2, 1)}


def face_point(b, f, s, t):
    fixed, val = FACE_FIX[f]
    p = [s, t]
    p.insert(fixed, float(val))
    return R.body_eval(b, *p)


def shared_faces(m, rep, name):
    """Pairs of faces that are the same map (in one of the 8 orientations),
    found by brute force at 5 x 5 points, then checked at 11 x 11."""
    bodies = expanded(m)["bodies"]
    tol = 1e-9 * R.control_diagonal(expanded(m), include_cross=False)
    syms = [(sw, fa, fb) for sw in (0, 1) for fa in (0, 1) for fb in (0, 1)]

    def mapped(s, t, sym):
        sw, fa, fb = sym
        a, b = (t, s) if sw else (s, t)
        return (1 - a if fa else a), (1 - b if fb else b)
    pairs = []
    centre = [{f: face_point(b, f, 0.5, 0.5) for f in FACE_FIX} for b in bodies]
    for i in range(len(bodies)):
        for j in range(i + 1, len(bodies)):
            for f in FACE_FIX:
                for g in FACE_FIX:
                    c0, c1 = centre[i][f], centre[j][g]
                    if max(abs(c0[d] - c1[d]) for d in range(3)) > 1e3 * tol:
                        continue
                    for sym in syms:
                        worst = 0.0
                        for a in range(11):
                            for bb in range(11):
                                s, t = a / 10, bb / 10
                                p = face_point(bodies[i], f, s, t)
                                q = face_point(bodies[j], g, *mapped(s, t, sym))
                                worst = max(worst, max(abs(p[d] - q[d]) for d in range(3)))
                        if worst <= tol:
                            pairs.append((i, f, j, g))
                            break
    return pairs


BUILDERS = [m_ffd_lattice, m_chair_lattice, m_l_bracket, m_ring, m_instanced]
# shared faces each model must have (found by brute force above)
EXPECTED_SHARED = {"lattice-ffd.json": 3 * 4 * 4 * 3, "chair-lattice.json": 35,
                   "lattice-l-bracket.json": 2, "lattice-ring.json": 8,
                   "lattice-instanced.json": 0}


def main(argv):
    check_only = "--check" in argv
    rep = G.Report()
    stale = []
    for build in BUILDERS:
        name, m, extra = build()
        text = G.dump(m) + "\n"
        path = os.path.join(HERE, name)
        if check_only:
            try:
                with open(path, encoding="utf-8") as fh:
                    if fh.read() != text:
                        stale.append(name)
            except OSError:
                stale.append(name)
        else:
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(text)
        m = json.loads(text)
        e = expanded(m)
        # G.verify wants right-handed bodies: a mirrored instance is checked
        # apart, as the mirror image of its definition (det J negated)
        mirrored = [b for b in m["bodies"] if "transform" in b and R.det3(b["transform"]) < 0]
        right = dict(e)
        right["bodies"] = [x for x, b in zip(e["bodies"], m["bodies"]) if b not in mirrored]
        G.verify(name, right, extra, rep)
        for b in mirrored:
            x = e["bodies"][m["bodies"].index(b)]
            d = m["define"][b["ref"]]
            worst = max(abs(R.body_jacobian_det(x, *p) + R.body_jacobian_det(d, *p))
                        for p in [(0.5, 0.5, 0.5), (0.2, 0.7, 0.4), (0.9, 0.1, 0.6)])
            rep.check(name, "%s: det J = -det J of '%s'" % (b["name"], b["ref"]), worst, 1e-9)
        pairs = shared_faces(m, rep, name)
        want = EXPECTED_SHARED[name]
        rep.check(name, "%d shared faces (want %d)" % (len(pairs), want),
                  abs(len(pairs) - want), 0)
    for line in rep.lines:
        print(line)
    for n in stale:
        print("STALE %s: differs from what gen_lattices.py writes" % n)
    print("%d checks, %d failed%s" % (len(rep.lines), rep.failed,
                                      ", %d stale files" % len(stale) if stale else ""))
    return 1 if rep.failed or stale else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
