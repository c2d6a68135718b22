#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes the network and shell examples (coons-model(5), "Networks of
curves", "Shells"; seed 001 section 1.2.2).

    python3 examples/gen_network.py            write the files
    python3 examples/gen_network.py --check    verify that the files on disk are
                                               exactly what this script writes,
                                               and verify them

The examples:
- hood-zero.json, hood-adini.json, hood-bessel.json: a car-hood-like panel
  filled from a network of 3 rows (clamped cubic B-splines across the
  width) and 4 columns (cubic Bezier curves front to back), the top face w1
  of a body 2 standing on a flat bottom (printable); the three twist rules.
  The curves are iso-lines of one smooth surface, B-spline in s and Bezier
  in t, so rows and columns meet exactly at the nodes.
- hood-shell.json: the same panel made a 2 mm shell below its surface.
- sleeve.json: the side surface of spool.json (its four side faces) made a
  1 mm shell outside it: a printable sleeve.
- fig13.json: seed 001 Fig. 1.3, a network of two cells filled bilinearly
  (blend linear, C0: a crease along the middle curve) and by Hermite cells
  (blend cubic, C1), each the top of a body 2 on a flat bottom, side by side.
Verification (by examples/coons_ref.py, independent of libcoons): every
node agrees, every network interpolates its curves, the body 2's faces
agree along their shared edges, and the shells' faces at the seams of the
sleeve coincide.
"""
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import coons_ref as R  # noqa: E402


def num(x):
    x = round(float(x), 12)
    return int(x) if x == int(x) and abs(x) < 1e15 else x


def P(*c):
    return [num(v) for v in c]


def dump(x, ind=0):
    s = json.dumps(x, separators=(", ", ": "))
    if len(s) + ind <= 96 or not isinstance(x, (dict, list)) or \
            (isinstance(x, list) and all(isinstance(v, (int, float)) for v in x)):
        return s
    pad = " " * (ind + 2)
    if isinstance(x, dict):
        items = [pad + json.dumps(k) + ": " + dump(v, ind + 2) for k, v in x.items()]
        return "{\n" + ",\n".join(items) + "\n" + " " * ind + "}"
    items = [pad + dump(v, ind + 2) for v in x]
    return "[\n" + ",\n".join(items) + "\n" + " " * ind + "]"


# ---------------------------------------------------------------- the hood

# x(s, t) = sum_k N_k(s) sum_l B_l(t) Q[k][l]: clamped cubic B-spline in s
# (6 control columns at the Greville abscissae, so x runs linearly in s)
# and cubic Bezier in t (y at thirds, so y runs linearly in t).
HOOD_W, HOOD_D = 120.0, 80.0
GREVILLE = [0, 1 / 9, 1 / 3, 2 / 3, 8 / 9, 1]
HOOD_Z = [  # z of Q[k][l], k across (x), l front (y = 0) to back
    [14, 16, 19, 22],
    [19, 23, 27, 30],
    [21, 27, 31, 33],
    [21, 27, 31, 33],
    [19, 23, 27, 30],
    [14, 16, 19, 22]]
S_NODES = [0, 0.3, 0.7, 1]
T_NODES = [0, 0.45, 1]


def hood_q(k, l):
    return (-HOOD_W / 2 + HOOD_W * GREVILLE[k], HOOD_D * l / 3, HOOD_Z[k][l])


def hood_row(t):
    """x(s, t): a clamped cubic B-spline (control points sum_l B_l(t) Q[k][l])."""
    B = R.bernstein(3, t)
    pts = [P(*[sum(B[l] * hood_q(k, l)[d] for l in range(4)) for d in range(3)]) for k in range(6)]
    return {"type": "bspline", "degree": 3, "points": pts}


def hood_col(s):
    """x(s, t) at fixed s: a cubic Bezier curve in t."""
    N = R.bspline_basis(3, R.default_knots(3, 6), 6, s)
    pts = [P(*[sum(N[k] * hood_q(k, l)[d] for k in range(6)) for d in range(3)]) for l in range(4)]
    return {"type": "bezier", "points": pts}


def hood_network(twist):
    return {"type": "network", "rows": [hood_row(t) for t in T_NODES],
            "columns": [hood_col(s) for s in S_NODES],
            "s_nodes": S_NODES, "t_nodes": T_NODES, "twist": twist}


def line(a, b):
    return {"type": "line", "points": [P(*a), P(*b)]}


def body2_under(top, name, z0=0.0):
    """Body 2: w1 the network `top` (its border curves must run linearly in
    x and y over the rectangle of its corners), w0 the flat bottom z = z0,
    the four sides ruled between the bottom's edges and the border curves."""
    rows, cols = top["rows"], top["columns"]
    X = [R.curve_eval(rows[0], 0), R.curve_eval(rows[0], 1), R.curve_eval(rows[-1], 0),
         R.curve_eval(rows[-1], 1)]
    c = [(p[0], p[1], z0) for p in X]
    faces = {
        "u0": {"type": "ruled", "curves": [line(c[0], c[2]), cols[0]]},
        "u1": {"type": "ruled", "curves": [line(c[1], c[3]), cols[-1]]},
        "v0": {"type": "ruled", "curves": [line(c[0], c[1]), rows[0]]},
        "v1": {"type": "ruled", "curves": [line(c[2], c[3]), rows[-1]]},
        "w0": {"type": "bilinear", "corners": [P(*c[0]), P(*c[1]), P(*c[2]), P(*c[3])]},
        "w1": top,
    }
    return {"type": "body2", "name": name, "faces": faces}


def hood_body(twist):
    return body2_under(hood_network(twist), "hood-" + twist)


# ---------------------------------------------------------------- the sleeve


def spool_faces():
    with open(os.path.join(HERE, "spool.json"), encoding="utf-8") as fh:
        spool = json.load(fh)
    return spool["bodies"][0]["faces"]


def sleeve_bodies():
    """Shells of the spool's side faces u0, u1, v0, v1, 1 mm outside it.
    A body 2 face's normal x_s x x_t points into the body on u0, v1 and out
    of it on u1, v0 (the (s,t) of each face follow the body's parameters),
    so the solid lies on the back of u0, v1 and on the front of u1, v0."""
    F = spool_faces()
    side = {"u0": "back", "u1": "front", "v0": "front", "v1": "back"}
    return [{"type": "shell", "name": "sleeve-" + k, "surface": F[k], "thickness": 1,
             "side": side[k]} for k in ("u0", "u1", "v0", "v1")]


# ---------------------------------------------------------------- Fig. 1.3


def fig13_network(blend, dx):
    """Two cells side by side: rows front and back rising to a ridge in the
    middle, columns at the three nodes; the middle column bulges up."""
    def row(y, zmid):
        return {"type": "bezier", "points": [P(dx, y, 0), P(dx + 10, y, 0), P(dx + 16, y, zmid),
                                              P(dx + 20, y, zmid), P(dx + 24, y, zmid),
                                              P(dx + 30, y, 0), P(dx + 40, y, 0)]}
    r0, r1 = row(0, 9), row(30, 9)
    zm = R.curve_eval(r0, 0.5)[2]

    def col(x, z, bulge):
        return {"type": "bezier", "points": [P(x, 0, z), P(x, 10, z + bulge),
                                             P(x, 20, z + bulge), P(x, 30, z)]}
    # the outer profiles are straight, the middle one bulges: a bilinear
    # cell takes its cross slope from the difference of its two profiles,
    # which changes sign across the middle one
    cols = [col(dx, 0, 0), col(dx + 20, zm, 6), col(dx + 40, 0, 0)]
    return {"type": "network", "rows": [r0, r1], "columns": cols, "blend": blend}


def fig13_bodies():
    """Each fill as the top of a block 3 mm deep at its border (a body 2:
    a shell of the creased fill would tear along the crease, where the
    normal jumps)."""
    return [body2_under(fig13_network("linear", 0), "bilinear", -3),
            body2_under(fig13_network("cubic", 50), "hermite", -3)]


def model(bodies, operation=None, tolerance=None):
    m = {"coons": 1, "units": "mm"}
    if tolerance:
        m["tolerance"] = tolerance
    if operation:
        m["operation"] = operation
    m["bodies"] = bodies
    return m


EXAMPLES = [
    ("hood-zero.json", lambda: model([hood_body("zero")])),
    ("hood-adini.json", lambda: model([hood_body("adini")])),
    ("hood-bessel.json", lambda: model([hood_body("bessel")])),
    ("hood-shell.json", lambda: model([{"type": "shell", "name": "hood-shell",
                                        "surface": hood_network("bessel"), "thickness": 2,
                                        "side": "back"}])),
    # 0.05 mm is finer than a print's layers and halves the triangles
    ("sleeve.json", lambda: model(sleeve_bodies(), tolerance=0.05)),
    ("fig13.json", lambda: model(fig13_bodies(), operation="none")),
]


# ---------------------------------------------------------------- checks


def networks_of(m):
    for b in m["bodies"]:
        if b["type"] == "shell" and b["surface"]["type"] == "network":
            yield b["surface"]
        if b["type"] == "body2":
            for f in b["faces"].values():
                if f["type"] == "network":
                    yield f


def check_network(p, tol):
    """Nodes agree; the patch passes through every row and column."""
    rows, cols = p["rows"], p["columns"]
    sn = R._nodes(p.get("s_nodes"), len(cols))
    tn = R._nodes(p.get("t_nodes"), len(rows))
    worst = 0.0
    for i, s in enumerate(sn):
        for j, t in enumerate(tn):
            worst = max(worst, R.dist(R.curve_eval(rows[j], s), R.curve_eval(cols[i], t)))
    for k in range(21):
        x = k / 20
        for j, t in enumerate(tn):
            worst = max(worst, R.dist(R.realv(R.patch_eval(p, x, t)), R.curve_eval(rows[j], x)))
        for i, s in enumerate(sn):
            worst = max(worst, R.dist(R.realv(R.patch_eval(p, s, x)), R.curve_eval(cols[i], x)))
    return worst <= tol, "network: nodes and curves off by %.3g" % worst


def check_body2(b, tol):
    worst = 0.0
    for k in range(17):
        x = k / 16
        for i in (0, 1):
            for j in (0, 1):
                # the three edge families, each seen from its two faces
                worst = max(worst,
                            R.dist(R.body2_edge(b["faces"], "u", i, j, x),
                                   R.body_eval(b, x, i, j)),
                            R.dist(R.body2_edge(b["faces"], "v", i, j, x),
                                   R.body_eval(b, i, x, j)),
                            R.dist(R.body2_edge(b["faces"], "w", i, j, x),
                                   R.body_eval(b, i, j, x)))
    return worst <= tol, "body2: edges off by %.3g" % worst


def check_sleeve(m, tol):
    """Neighbouring shells meet along their whole end faces (the same map
    up to w -> 1 - w: shared faces)."""
    B = {b["name"][7:]: b for b in m["bodies"]}
    # (face A at u = a, face B at u = b) share the spool's vertical edges
    pairs = [("u0", 0, "v0", 0), ("u0", 1, "v1", 0), ("u1", 0, "v0", 1), ("u1", 1, "v1", 1)]
    worst = 0.0
    for fa, a, fb, bb in pairs:
        for k in range(9):
            for w in (0.0, 0.5, 1.0):
                x = k / 8
                # opposite sides: the w of one runs against the other's
                wb = w if B[fa]["side"] == B[fb]["side"] else 1 - w
                pa = R._shell(B[fa], float(a), x, w)
                pb = R._shell(B[fb], float(bb), x, wb)
                worst = max(worst, R.dist(pa, pb))
    return worst <= tol, "sleeve: end faces apart by %.3g" % worst


def verify(name, m):
    pts = R.control_points(m, include_cross=False)
    lo = [min(p[d] for p in pts) for d in range(3)]
    hi = [max(p[d] for p in pts) for d in range(3)]
    tol = 1e-9 * math.dist(lo, hi)
    out = []
    for p in networks_of(m):
        out.append(check_network(p, tol))
    for b in m["bodies"]:
        if b["type"] == "body2":
            out.append(check_body2(b, tol))
    if name == "sleeve.json":
        out.append(check_sleeve(m, 1e-6))
    return out


def main(argv):
    check_only = "--check" in argv
    failed = 0
    for name, build in EXAMPLES:
        text = dump(build()) + "\n"
        path = os.path.join(HERE, name)
        if check_only:
            try:
                with open(path, encoding="utf-8") as fh:
                    same = fh.read() == text
            except OSError:
                same = False
            if not same:
                print("STALE %s: differs from what gen_network.py writes" % name)
                failed += 1
        else:
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(text)
        for ok, what in verify(name, json.loads(text)):
            print("%s %s: %s" % ("ok  " if ok else "FAIL", name, what))
            failed += not ok
    print("%d failed" % failed)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
