#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Generates the metamorphosis examples (seed 000 section 4, Fig. 10) in
examples/ and verifies each one.

    python3 examples/gen_morph.py            write examples/morph-*.json, verify
    python3 examples/gen_morph.py --check    verify that the files on disk are exactly
                                             what this script writes (nothing is written)

- morph-cube-spool.json: a cube (body 0) becoming the spool (body 2 of
  examples/spool.json, built by gen_examples.py), Fig. 10; the cube's
  corners are the spool's, so every frame keeps the corners in place.
- morph-three-keys.json: three keys on a smooth path (C1 in time): the
  cube, a tapered and twisted block at t = 0.4, the spool.
- morph-bspline.json: a morph of two B-spline volumes of the same
  structure, which must equal the B-spline volume whose control points are
  blended with the path's weights (the seed's reading: each grid point
  moves along its path).

Checks, with the independent evaluator coons_ref.py on the JSON as
written: the morph at each key time is that key; the cube's and the
spool's corners agree; the B-spline morph equals the blended volume at
random (u, v, w, t); det J > 0 at sampled points and times (no frame
folds). Standard library only; output deterministic.
"""

import json
import math
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import coons_ref as R  # noqa: E402

FAILS = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        FAILS.append(what)


def spool():
    with open(os.path.join(HERE, "spool.json"), encoding="utf-8") as f:
        b = json.load(f)["bodies"][0]
    b.pop("name", None)
    return b


# The spool's corners F(i,j,k) at 4i+2j+k (a square of half-diagonal 6
# turned by 45 degrees, 10 high); the cube (seed 000 Fig. 10) has them too.
CUBE_CORNERS = [[0, -6, 0], [0, -6, 10], [-6, 0, 0], [-6, 0, 10],
                [6, 0, 0], [6, 0, 10], [0, 6, 0], [0, 6, 10]]


def cube():
    return {"type": "body0", "corners": CUBE_CORNERS}


def twisted():
    """The cube tapered to 60% at the top and turned by 30 degrees there."""
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    out = []
    for x, y, z in CUBE_CORNERS:
        if z:
            x, y = 0.6 * (c * x - s * y), 0.6 * (s * x + c * y)
        out.append([round(x, 12) + 0.0, round(y, 12) + 0.0, z])
    return {"type": "body0", "corners": out}


def bspline_net(f):
    """A 4 x 3 x 4 net of degrees (2, 2, 3) over a 20 x 10 x 15 box, each
    point moved by f(i, j, k)."""
    pts = []
    for i in range(4):
        pts.append([])
        for j in range(3):
            pts[-1].append([])
            for k in range(4):
                d = f(i, j, k)
                pts[-1][-1].append([round(20 * i / 3 + d[0], 6), round(10 * j / 2 + d[1], 6),
                                    round(15 * k / 3 + d[2], 6)])
    return {"type": "bspline-volume", "degree": [2, 2, 3], "points": pts,
            "knots": [[0, 0, 0, 0.5, 1, 1, 1], [0, 0, 0, 1, 1, 1], [0, 0, 0, 0, 1, 1, 1, 1]]}


def bspline_keys():
    a = bspline_net(lambda i, j, k: (0, 0, 0))
    b = bspline_net(lambda i, j, k: (2 * math.sin(k), 3 * (i - 1.5) * k / 3,
                                     1.5 * math.cos(i + j)))
    return a, b


def model(name, morph):
    return {"coons": 1, "units": "mm", "bodies": [dict({"type": "morph", "name": name}, **morph)]}


def build():
    out = {}
    out["morph-cube-spool.json"] = model("cube-to-spool", {"keys": [cube(), spool()], "t": 0.5})
    out["morph-three-keys.json"] = model("three-keys", {
        "keys": [cube(), twisted(), spool()], "at": [0, 0.4, 1], "path": "smooth", "t": 0.7})
    a, b = bspline_keys()
    out["morph-bspline.json"] = model("bspline-morph", {"keys": [a, b], "t": 0.35})
    return out


def dump(m):
    return json.dumps(m, indent=1) + "\n"


def verify(name, m):
    body = m["bodies"][0]
    rng = random.Random(name)
    keys, n = body["keys"], len(body["keys"])
    at = body.get("at") or [k / (n - 1) for k in range(n)]
    worst = 0.0
    for k in range(n):
        for _ in range(8):
            q = [rng.random() for _ in range(3)]
            p = R.morph_eval(body, *q, t=at[k])
            worst = max(worst, R.dist(p, R.body_eval(keys[k], *q)))
    check(worst < 1e-12, f"{name}: at each key time the morph is that key ({worst:.2g})")
    if name == "morph-cube-spool.json":
        wc = max(R.dist(R.body_corner(keys[1], i >> 2, (i >> 1) & 1, i & 1),
                        R.body_corner(keys[0], i >> 2, (i >> 1) & 1, i & 1)) for i in range(8))
        check(wc < 1e-12, f"{name}: the spool has the cube's corners ({wc:.2g})")
    mindet = math.inf
    for step in range(11):
        t = step / 10
        for _ in range(12):
            q = [0.02 + 0.96 * rng.random() for _ in range(3)]
            b = dict(body, t=t)
            mindet = min(mindet, R.body_jacobian_det(b, *q))
    check(mindet > 0, f"{name}: det J > 0 at sampled points of 11 frames (min {mindet:.4g})")


def verify_bspline_blend(m):
    body = m["bodies"][0]
    a, b = body["keys"]
    rng = random.Random(7)
    worst = 0.0
    for _ in range(40):
        t = rng.random()
        q = [rng.random() for _ in range(3)]
        blended = dict(a, points=[[[R.add(R.mul(1 - t, pa), R.mul(t, pb))
                                    for pa, pb in zip(ra, rb)] for ra, rb in zip(sa, sb)]
                                  for sa, sb in zip(a["points"], b["points"])])
        worst = max(worst, R.dist(R.morph_eval(body, *q, t=t), R.volume_eval(blended, *q)))
    check(worst < 1e-9, f"morph-bspline.json: equals the volume of blended control points "
                        f"at 40 random (u, v, w, t) ({worst:.2g})")


def main(argv):
    check_only = "--check" in argv
    models = build()
    for name, m in models.items():
        text = dump(m)
        path = os.path.join(HERE, name)
        if check_only:
            try:
                with open(path, encoding="utf-8") as f:
                    current = f.read() == text
            except OSError:
                current = False
            check(current, f"{name} is what gen_morph.py writes")
        else:
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
        verify(name, json.loads(text))
    verify_bspline_blend(json.loads(dump(models["morph-bspline.json"])))
    print(f"{len(FAILS)} failed")
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
