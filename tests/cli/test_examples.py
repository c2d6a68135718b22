#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Every example model loads through coons2stl and evaluates correctly.

    python3 test_examples.py --bin build/tools/coons2stl --src . --build build

For every examples/*.json:
- `coons2stl --info` succeeds and reports each body's type and name.
- `coons2stl --eval --body i` at the 8 corners and at interior points of each
  body gives the point computed by examples/coons_ref.py, a reference
  evaluator of the format written in Python independently of libcoons. The
  allowed distance is 1e-9 of the diagonal of the model's control box.
Closed forms that need no evaluator at all: the trilinear body 0 (and the
body 2 of bilinear faces and body 1 of lines that equal it, seed 000), the
Bezier volume, the NURBS cylinder's and quarter tube's radius, the ring's
height; and, between two CLI runs, seed 000's equivalence "body 2 of Coons
faces = body 1 of their edges" and Fig. 4's "same outer shape".
Finally examples/gen_examples.py --check: the committed files are exactly
what the generator writes, and its own verification passes.
"""

import json
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)


def report(ok, what, detail=""):
    return T.check(what, ok, detail)


def run(args, stdin=None, timeout=600):
    return subprocess.run(args, input=stdin, capture_output=True, text=True, timeout=timeout)


def dist(a, b):
    return math.sqrt(sum((a[i] - b[i]) ** 2 for i in range(3)))


class Cli:
    def __init__(self, binary):
        self.bin = binary

    def eval(self, path, body, params):
        """Points of body `body` at the (u, v, w) in params, or (None, why)."""
        text = "".join("%r %r %r\n" % tuple(float(x) for x in q) for q in params)
        r = run([self.bin, "--eval", "--body", str(body), path], stdin=text)
        if r.returncode != 0:
            return None, "exit %d: %s" % (r.returncode, r.stderr.strip()[:400])
        lines = [l for l in r.stdout.splitlines() if l.strip()]
        if len(lines) != len(params):
            return None, "%d output lines for %d inputs" % (len(lines), len(params))
        try:
            pts = [[float(x) for x in l.split()] for l in lines]
        except ValueError:
            return None, "not numbers: %r" % lines[:2]
        if any(len(p) != 3 for p in pts):
            return None, "not three numbers per line: %r" % lines[:2]
        return pts, ""


def corners():
    return [(i, j, k) for i in (0, 1) for j in (0, 1) for k in (0, 1)]


INTERIOR = [(0.5, 0.5, 0.5), (0.25, 0.6, 0.8), (0.9, 0.1, 0.3), (0.125, 0.875, 0.5)]
# points on the faces (one per face) and on edges
SURFACE = [(0, 0.3, 0.7), (1, 0.6, 0.2), (0.4, 0, 0.9), (0.7, 1, 0.35), (0.2, 0.45, 0),
           (0.85, 0.15, 1), (0.5, 0, 0), (1, 0.5, 1), (0, 1, 0.25)]


def check_model(cli, R, path, name):
    with open(path, encoding="utf-8") as fh:
        model = json.load(fh)
    # references (coons-model(5) "Definitions and references") expanded by
    # the reference evaluator; a mirrored instance is left-handed by
    # definition (its det J is negative: checked below with its sign)
    mirrored = [i for i, b in enumerate(model["bodies"])
                if "transform" in b and R.det3(b["transform"]) < 0]
    model = R.expand(model)
    diag = R.control_diagonal(model, include_cross=False)
    tol = 1e-9 * diag

    r = run([cli.bin, "--info", path])
    ok = r.returncode == 0
    report(ok, "%s: --info" % name, "exit %d: %s" % (r.returncode, r.stderr.strip()[:400]))
    if ok:
        try:
            info = json.loads(r.stdout)
            bodies = info.get("bodies", [])
            good = len(bodies) == len(model["bodies"])
            for i, (bi, bm) in enumerate(zip(bodies, model["bodies"])):
                good = good and bi.get("type") == bm["type"]
                if "name" in bm:
                    good = good and bi.get("name") == bm["name"]
            report(good, "%s: --info lists the bodies with their types and names" % name,
                   r.stdout[:300])
            # every example is right-handed and unfolded: det J >= 0 up to
            # rounding (it is 0 on seams and at collapsed faces)
            dets = [b.get("min_det_jacobian") for i, b in enumerate(bodies) if i not in mirrored]
            report(all(isinstance(d, (int, float)) and d >= -1e-9 * diag ** 3 for d in dets),
                   "%s: --info min_det_jacobian >= 0 (to rounding)" % name, repr(dets))
            VOLUMES[name] = [b.get("volume") for b in bodies]
        except ValueError as e:
            report(False, "%s: --info prints JSON" % name, str(e))

    for bi, body in enumerate(model["bodies"]):
        params = corners() + INTERIOR + SURFACE
        got, why = cli.eval(path, bi, params)
        if got is None:
            report(False, "%s body %d: --eval" % (name, bi), why)
            continue
        worst_c, worst_i, where = 0.0, 0.0, None
        for n, (q, p) in enumerate(zip(params, got)):
            want = R.realv(R.body_eval(body, *q))
            d = dist(p, want)
            if n < 8:
                worst_c = max(worst_c, d)
            elif d > worst_i:
                worst_i, where = d, (q, p, want)
            if d > tol and where is None:
                where = (q, p, want)
        report(worst_c <= tol, "%s body %d: the 8 corners" % (name, bi),
               "off by %.3g > %.3g" % (worst_c, tol))
        report(worst_i <= tol, "%s body %d: interior and face points = reference" % (name, bi),
               "off by %.3g > %.3g at %r" % (worst_i, tol, where))
    return model, tol


def trilinear(P, u, v, w):
    out = [0.0, 0.0, 0.0]
    for i in range(2):
        for j in range(2):
            for k in range(2):
                c = (u if i else 1 - u) * (v if j else 1 - v) * (w if k else 1 - w)
                for d in range(3):
                    out[d] += c * P[4 * i + 2 * j + k][d]
    return out


VOLUMES = {}  # --info volumes by file name

GAUSS3 = [(-math.sqrt(0.6), 5 / 9), (0.0, 8 / 9), (math.sqrt(0.6), 5 / 9)]


def revolved_volume(R, face_u0):
    """Volume of a round body 2 whose face u0 is a NURBS surface with the
    same circle weights in every layer: pi * integral r(w)^2 z'(w) dw, with r
    and z the B-splines of the layer radii and heights (exact: 3-point
    Gauss per knot span of a polynomial of degree <= 5)."""
    col = [row[0] for row in zip(*face_u0["points"])]  # s = 0: P[0][0][k]
    deg = face_u0["degree"][1]
    kn = face_u0.get("knots", [None, None])[1] or R.default_knots(deg, len(col))
    cr = {"type": "bspline", "degree": deg, "knots": kn,
          "points": [[0, 0, math.hypot(p[0], p[1])] for p in col]}
    cz = {"type": "bspline", "degree": deg, "knots": kn, "points": [[0, 0, p[2]] for p in col]}
    k = [float(x) for x in kn]
    a, b = k[deg], k[len(col)]
    vol = 0.0
    for lo, hi in zip(k, k[1:]):
        if hi <= lo or lo < a or hi > b:
            continue
        for x, wt in GAUSS3:
            t = ((lo + hi) / 2 + x * (hi - lo) / 2 - a) / (b - a)
            r = R.curve_eval(cr, t)[2]
            dz = R.curve_deriv(cz, t)[2]
            vol += wt * (hi - lo) / 2 / (b - a) * math.pi * r * r * dz
    return vol


def volume_checks(R, ex):
    """--info volumes against exact ones."""
    def face(n):
        with open(os.path.join(ex, n), encoding="utf-8") as fh:
            return json.load(fh)["bodies"][0]["faces"]["u0"]
    exact = {
        "deformed-cube.json": 1000.0,  # the saddle top averages z = 10
        "curve-line.json": 1000.0,
        "patch-bilinear.json": 1000.0,
        "volume-bezier.json": 3200 / 3,  # 100 * integral (10 + 6 B1(u) B1(v))
        "patch-nurbs.json": 200 * math.pi,
        "volume-nurbs.json": 200 * math.pi,
        "curve-nurbs.json": 27 * math.pi,  # quarter of (6^2 - 3^2) pi, height 4
        # cone + shaft + conical underside + head
        "nail.json": math.pi * (0.75 ** 2 * 2.5 / 3 + 0.75 ** 2 * 8
                                + 0.5 * (2.5 ** 2 + 2.5 * 0.75 + 0.75 ** 2) / 3 + 2.5 ** 2),
        "spool.json": revolved_volume(R, face("spool.json")),
    }
    exact["nail-density.json"] = exact["nail.json"]  # the same shape, reparametrised
    exact["cantilever.json"] = 100.0 * 10 * 10
    # a quarter of a tube a = 10, b = 20, height 5: pi (20^2 - 10^2) 5 / 4
    exact["thick-cylinder.json"] = math.pi * (20 ** 2 - 10 ** 2) * 5 / 4
    exact["thick-cylinder-distorted.json"] = exact["thick-cylinder.json"]
    for n, v in sorted(exact.items()):
        if n not in VOLUMES:  # not among the representative examples run above
            r = run([T.bin, "--info", os.path.join(ex, n)])
            try:
                VOLUMES[n] = [b.get("volume") for b in json.loads(r.stdout)["bodies"]]
            except (ValueError, KeyError) as e:
                VOLUMES[n] = "exit %d, %s: %s" % (r.returncode, e, r.stderr.strip()[:300])
        got = VOLUMES.get(n)
        ok = bool(got) and isinstance(got[0], (int, float)) and abs(got[0] - v) <= 1e-6 * v
        report(ok, "%s: --info volume = %.10g" % (n, v), "got %r" % (got,))


GRID = [(i / 4, j / 4, k / 4) for i in range(5) for j in range(5) for k in range(5)]


def closed_forms(cli, ex):
    def path(n):
        return os.path.join(ex, n)

    def pts(n, body=0, params=GRID):
        p, why = cli.eval(path(n), body, params)
        if p is None:
            report(False, "%s: --eval" % n, why)
        return p

    def expect(what, worst, tol):
        report(worst <= tol, what, "worst %.3g > %.3g" % (worst, tol))

    with open(path("deformed-cube.json"), encoding="utf-8") as fh:
        P = json.load(fh)["bodies"][0]["corners"]
    for n in ("deformed-cube.json", "curve-line.json", "patch-bilinear.json"):
        p = pts(n)
        if p:
            expect("%s = trilinear map of the deformed cube's corners" % n,
                   max(dist(x, trilinear(P, *q)) for x, q in zip(p, GRID)), 1e-9 * 20)

    p = pts("volume-bezier.json")
    if p:
        expect("volume-bezier.json = (10u, 10v, 10w + 24 u(1-u) v(1-v) w)",
               max(dist(x, (10 * u, 10 * v, 10 * w + 24 * u * (1 - u) * v * (1 - v) * w))
                   for x, (u, v, w) in zip(p, GRID)), 1e-9 * 22)

    p = pts("curve-nurbs.json")
    if p:
        expect("curve-nurbs.json: radius 6 - 3v, height 4w",
               max(max(abs(math.hypot(x[0], x[1]) - (6 - 3 * v)), abs(x[2] - 4 * w))
                   for x, (u, v, w) in zip(p, GRID)), 1e-9 * 10)

    side = [q for q in GRID if q[0] in (0, 1) or q[1] in (0, 1)]
    for n in ("patch-nurbs.json", "volume-nurbs.json"):
        p = pts(n, params=side)
        if p:
            expect("%s: side faces at radius 5, z = 8w" % n,
                   max(max(abs(math.hypot(x[0], x[1]) - 5), abs(x[2] - 8 * q[2]))
                       for x, q in zip(p, side)), 1e-9 * 17)

    p = pts("curve-coons-cubic-closed.json")
    if p:
        expect("curve-coons-cubic-closed.json: the ring's height is 3w",
               max(abs(x[2] - 3 * q[2]) for x, q in zip(p, GRID)), 1e-9 * 18)

    # seed 000: body 2 of Coons faces = body 1 of the same edges (linear blend)
    a, b = pts("patch-coons.json"), pts("curve-bezier.json")
    if a and b:
        expect("patch-coons.json (body 2) = curve-bezier.json (body 1 of its edges)",
               max(dist(x, y) for x, y in zip(a, b)), 1e-9 * 26)

    # Fig. 4: the same outer shape, another interior
    a, b = pts("body1-density.json"), pts("body1-bspline-edges.json")
    if a and b:
        worst, moved = 0.0, 0.0
        for x, y, (u, v, w) in zip(a, b, GRID):
            worst = max(worst, abs(x[1] - y[1]), abs(x[2] - y[2]))  # (y, z) unchanged
            if u in (0, 1):
                worst = max(worst, abs(x[0] - y[0]))  # faces u0, u1 unchanged
            worst = max(worst, max(0.0, -x[0], x[0] - 10))  # x stays in [0, 10]
            moved = max(moved, abs(x[0] - y[0]))
        expect("body1-density.json has the outer shape of body1-bspline-edges.json",
               worst, 1e-9 * 23)
        report(moved > 1, "body1-density.json has another interior", "moved only %.3g" % moved)


def main():
    a = T
    ex = os.path.join(a.src, "examples")
    sys.path.insert(0, ex)
    import coons_ref as R  # noqa: E402  (examples/coons_ref.py)
    cli = Cli(a.bin)

    files = clitest.examples(T.src, every=True)
    report(len(files) >= 30, "examples/ holds the example models", "%d files" % len(files))
    # The representative subset (tests/data/representative-examples.txt),
    # which the sanitizer and valgrind runs take, uses every kind that any
    # example uses: a new kind of example must be added to it.
    kinds, rep = set(), set()
    for f in files:
        with open(f) as fp:
            kinds |= clitest.model_kinds(json.load(fp))
    for n in clitest.representative_names(T.src):
        with open(os.path.join(ex, n)) as fp:
            rep |= clitest.model_kinds(json.load(fp))
    report(kinds <= rep, "the representative examples use every kind the examples use",
           "missing: %s" % sorted(kinds - rep, key=str))
    for f in clitest.examples(T.src):
        check_model(cli, R, f, os.path.basename(f))
    closed_forms(cli, ex)
    volume_checks(R, ex)

    r = run([sys.executable, os.path.join(ex, "gen_examples.py"), "--check"])
    report(r.returncode == 0, "gen_examples.py --check (files current, generator checks pass)",
           (r.stdout[-1500:] + r.stderr[-500:]).strip())

    T.finish()


if __name__ == "__main__":
    main()
