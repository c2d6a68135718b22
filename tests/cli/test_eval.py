#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""coons2stl --eval and --jacobian against values computed here:

- an affine body0 (x = o + A q: the Jacobian is A, det J = det A) at random
  parameters;
- a skew trilinear body0, the same hexahedron as a body1 with straight
  edges of four curve types and as a body2 of bilinear, Coons and ruled
  faces (seed 000: body 1 with straight edges = body 0, body 2 with
  bilinear faces = body 1), against the trilinear formula and its partial
  derivatives;
- a NURBS tube (bspline-volume): radius 1 + u and height 3 w exactly;
- a Bezier volume against the Bernstein formula;
- the 8 corners of every body of every model in examples/ and
  tests/data/ok/ against an independent evaluation of the model's curves,
  patches and nets (clitest.py);
- the line rules: comments, blank lines, clamping within 1e-12, errors that
  name the line.

Usage: test_eval.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import glob
import json
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
OK = os.path.join(T.data, "ok")


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def eval_lines(model_path, params, extra=()):
    text = "".join("%r %r %r\n" % tuple(q) for q in params)
    rc, out, err = T.run(["--eval"] + list(extra) + [model_path], stdin=text)
    if rc != 0:
        return None, err
    return [[float(x) for x in line.split()] for line in out.splitlines()], err


def close(a, b, tol):
    return all(abs(x - y) <= tol for x, y in zip(a, b)) and len(a) == len(b)


def trilinear(P, q):
    """T(P_ijk; u, v, w) and its partial derivatives d/du, d/dv, d/dw."""
    u, v, w = q
    x = [0.0] * 3
    d = [[0.0] * 3 for _ in range(3)]
    for n in range(8):
        i, j, k = n >> 2, (n >> 1) & 1, n & 1
        bu, bv, bw = (u if i else 1 - u), (v if j else 1 - v), (w if k else 1 - w)
        su, sv, sw = (1 if i else -1), (1 if j else -1), (1 if k else -1)
        for r in range(3):
            x[r] += bu * bv * bw * P[n][r]
            d[0][r] += su * bv * bw * P[n][r]
            d[1][r] += bu * sv * bw * P[n][r]
            d[2][r] += bu * bv * sw * P[n][r]
    # jac[r][c] = d x_r / d q_c
    jac = [[d[c][r] for c in range(3)] for r in range(3)]
    return x, jac


def det3(A):
    return (A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1])
            - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0])
            + A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]))


rng = random.Random(20261122)
params = [[rng.random(), rng.random(), rng.random()] for _ in range(200)]
params += [[0, 0, 0], [1, 1, 1], [1, 0, 0.5]]

# --- affine body0 --------------------------------------------------------------
m = load(os.path.join(OK, "affine-box.json"))
P = [clitest.pt3(p) for p in m["bodies"][0]["corners"]]
o = P[0]
A = [[P[4][r] - o[r], P[2][r] - o[r], P[1][r] - o[r]] for r in range(3)]  # columns u, v, w
rows, err = eval_lines(os.path.join(OK, "affine-box.json"), params, ["--jacobian"])
ok = rows is not None and len(rows) == len(params)
bad = ""
for q, row in zip(params, rows or []):
    x = [o[r] + sum(A[r][c] * q[c] for c in range(3)) for r in range(3)]
    J = [A[r][c] for r in range(3) for c in range(3)]
    if len(row) != 13 or not close(row[:3], x, 1e-13) or not close(row[3:12], J, 1e-13) \
            or abs(row[12] - det3(A)) > 1e-12:
        ok, bad = False, f"q={q}: got {row}, expected {x} {J} {det3(A)}"
        break
T.check("affine body0: x = o + A q, J = A, det J = det A at 203 parameters", ok, bad or err)

# --- trilinear body0 and the equivalent body1 ------------------------------------
m = load(os.path.join(OK, "trilinear.json"))
H = [clitest.pt3(p) for p in m["bodies"][0]["corners"]]
for name in ("trilinear.json", "body1-straight.json", "body2-bilinear.json"):
    rows, err = eval_lines(os.path.join(OK, name), params, ["--jacobian"])
    ok = rows is not None and len(rows) == len(params)
    bad = ""
    for q, row in zip(params, rows or []):
        x, jac = trilinear(H, q)
        J = [jac[r][c] for r in range(3) for c in range(3)]
        if len(row) != 13 or not close(row[:3], x, 1e-12) or not close(row[3:12], J, 1e-11) \
                or abs(row[12] - det3(jac)) > 1e-10:
            ok, bad = False, f"q={q}: got {row}, expected {x} {J}"
            break
    T.check(f"{name}: trilinear formula and its derivatives at 203 parameters", ok, bad or err)

# --- NURBS tube ---------------------------------------------------------------------
rows, err = eval_lines(os.path.join(OK, "tube-nurbs.json"), params)
ok = rows is not None and len(rows) == len(params)
bad = ""
for q, row in zip(params, rows or []):
    radius = (row[0] ** 2 + row[1] ** 2) ** 0.5
    if abs(radius - (1 + q[0])) > 1e-13 or abs(row[2] - 3 * q[2]) > 1e-13:
        ok, bad = False, f"q={q}: got {row}, radius {radius}, expected {1 + q[0]}, z {3 * q[2]}"
        break
T.check("NURBS tube: radius 1 + u and height 3 w", ok, bad or err)

# --- Bezier volume ---------------------------------------------------------------------
m = load(os.path.join(OK, "bezier-volume.json"))
rows, err = eval_lines(os.path.join(OK, "bezier-volume.json"), params)
ok = rows is not None and len(rows) == len(params)
bad = ""
for q, row in zip(params, rows or []):
    x = clitest.tensor_eval(m["bodies"][0], q)
    if not close(row, x, 1e-13):
        ok, bad = False, f"q={q}: got {row}, expected {x}"
        break
T.check("bezier-volume: Bernstein formula", ok, bad or err)

# --- --body by index and by name ------------------------------------------------------
lid = m["bodies"][1]
for sel in ("1", lid["name"]):
    rows, err = eval_lines(os.path.join(OK, "bezier-volume.json"), [[0.25, 0.5, 0.75]], ["--body", sel])
    x, _ = trilinear([clitest.pt3(p) for p in lid["corners"]], [0.25, 0.5, 0.75])
    T.check(f"--body {sel!r} selects body 1", rows is not None and close(rows[0], x, 1e-15),
            f"{rows} {err}")

# --- corners of every model -------------------------------------------------------------
models = T.examples() + sorted(glob.glob(os.path.join(OK, "*.json")))
corner_params = [[n >> 2, (n >> 1) & 1, n & 1] for n in range(8)]
count = 0
for path in models:
    try:
        m = load(path)
    except (ValueError, OSError) as e:
        T.check(f"{path} is JSON", False, str(e))
        continue
    if not isinstance(m, dict) or "bodies" not in m:
        continue  # not a model (e.g. a curve or patch snippet)
    size = clitest.model_scale(m)
    for bi, b in enumerate(m["bodies"]):
        if "ref" in b:  # a reference: its definition's corners, mapped by its transform
            d = m["define"][b["ref"]]
            T3 = b.get("transform", [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]])
            expect = [[sum(T3[r][c] * x[c] for c in range(3)) + T3[r][3] for r in range(3)]
                      for x in clitest.body_corners(d)]
            b = d
        else:
            expect = clitest.body_corners(b)
        rows, err = eval_lines(path, corner_params, ["--body", str(bi)])
        ok = rows is not None and all(close(r, e, 1e-9 * size + 1e-12) for r, e in zip(rows, expect))
        T.check(f"corners of {os.path.relpath(path, T.src)} body {bi} ({b['type']})", ok,
                f"got {rows}, expected {expect}; {err.strip()}")
        count += 1
T.check(f"corners checked for {count} bodies", count >= 6)

# --- line rules -------------------------------------------------------------------------
box = os.path.join(OK, "affine-box.json")
rc, out, err = T.run(["--eval", box], stdin="# a comment\n\n  0 0 0  # origin\n\t\n1 1 1\n")
lines = out.splitlines()
T.check("comments and blank lines are skipped", rc == 0 and len(lines) == 2, f"{rc} {out!r} {err}")
rc, out2, err = T.run(["--eval", box], stdin="1.0000000000005 -5e-13 0\n1 0 0\n")
l2 = out2.splitlines()
T.check("values within 1e-12 outside [0,1] are clamped", rc == 0 and len(l2) == 2 and l2[0] == l2[1],
        f"{rc} {out2!r} {err}")
for text, lineno, what in (("0 0 0\n# c\n0.5 0.5\n", 3, "two numbers"),
                           ("0 0 0\n0.5 0.5 0.5 0.5\n", 2, "four numbers"),
                           ("abc 0 0\n", 1, "not a number"),
                           ("0 0 nan\n", 1, "nan"),
                           ("0.5x 0 0\n", 1, "trailing letters"),
                           ("\n\n0 1.5 0\n", 3, "out of range"),
                           ("0 0 -1e-11\n", 1, "just beyond the clamp")):
    rc, out, err = T.run(["--eval", box], stdin=text)
    T.check(f"--eval rejects {what} naming line {lineno} (exit 1)",
            rc == 1 and f"<stdin>:{lineno}:" in err, f"{rc} {err!r}")
rc, out, err = T.run(["--eval", box], stdin="0 0 0\n0 0 2\n")
T.check("lines before a bad line are answered", rc == 1 and len(out.splitlines()) == 1, f"{out!r}")
rc, out, err = T.run(["--eval", box], stdin="")
T.check("empty input: no output, exit 0", rc == 0 and out == "", f"{rc} {out!r}")
rc, out, err = T.run(["--eval", box], stdin="0.1 0.2 0.3\n")
vals = out.split()
T.check("numbers are printed with %.17g", rc == 0 and len(vals) == 3
        and all("%.17g" % float(v) == v for v in vals)
        and any(len(v.lstrip("-").replace(".", "").lstrip("0")) >= 16 for v in vals), out)

T.finish()
