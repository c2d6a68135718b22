#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The metamorphosis examples (examples/morph-*.json):

- examples/gen_morph.py --check: the committed files are what the
  generator writes, and its checks pass (coons_ref.py: keys reproduced at
  their times, the cube's corners on the spool, det J > 0 over 11 frames,
  the B-spline morph equal to the volume of blended control points);
- through coons2stl: the B-spline morph at --time t evaluates (--eval) to
  the bspline-volume whose control points are (1 - t) a + t b, written
  here as its own model, at t = 0.2 and 0.9;
- every example's frames (--frames 3, OFF) are closed, manifold meshes
  (--info at each frame's time).

Usage: test_morph_examples.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
TMP = tempfile.mkdtemp(prefix="coons-morph-ex-")
EX = os.path.join(T.src, "examples")

p = subprocess.run([sys.executable, os.path.join(EX, "gen_morph.py"), "--check"],
                   capture_output=True, text=True)
T.check("gen_morph.py --check (files current, generator checks pass)", p.returncode == 0,
        p.stdout[-2000:] + p.stderr[-2000:])

with open(os.path.join(EX, "morph-bspline.json")) as f:
    bs = json.load(f)
a, b = bs["bodies"][0]["keys"]
params = [(0.1, 0.2, 0.3), (0.75, 0.5, 0.05), (0.33, 0.9, 0.66), (1, 0, 1)]
stdin = "".join(f"{u} {v} {w}\n" for u, v, w in params)
for t in (0.2, 0.9):
    blended = dict(a, points=[[[[(1 - t) * x + t * y for x, y in zip(pa, pb)]
                                for pa, pb in zip(ra, rb)] for ra, rb in zip(sa, sb)]
                              for sa, sb in zip(a["points"], b["points"])])
    path = os.path.join(TMP, "blended.json")
    with open(path, "w") as f:
        json.dump({"coons": 1, "bodies": [blended]}, f)
    rc1, out1, err1 = T.run([os.path.join(EX, "morph-bspline.json"), "--eval", "--time", str(t)],
                            stdin=stdin)
    rc2, out2, err2 = T.run([path, "--eval"], stdin=stdin)
    ok = rc1 == 0 and rc2 == 0
    worst = 0.0
    if ok:
        for l1, l2 in zip(out1.splitlines(), out2.splitlines()):
            worst = max(worst, max(abs(float(x) - float(y))
                                   for x, y in zip(l1.split(), l2.split())))
    T.check(f"morph of two B-spline volumes at t = {t} is the volume of blended control points",
            ok and worst < 1e-12, f"worst {worst} {err1} {err2}")

for name in ("morph-cube-spool.json", "morph-three-keys.json", "morph-bspline.json"):
    model = os.path.join(EX, name)
    d = os.path.join(TMP, name[:-5])
    os.mkdir(d)
    rc, _, err = T.run([model, "--frames", "3", "-o", os.path.join(d, "f%d.off")])
    T.check(f"{name}: --frames 3 writes three OFF frames",
            rc == 0 and sorted(os.listdir(d)) == ["f0.off", "f1.off", "f2.off"], err)
    for k in range(3):
        rc, out, err = T.run([model, "--info", "--no-solid", "--time", str(k / 2)])
        try:
            mesh = json.loads(out)["bodies"][0]["mesh"]
            ok = mesh["closed"] and mesh["manifold"] and mesh["oriented"]
        except (ValueError, KeyError, IndexError):
            ok = False
        T.check(f"{name}: frame at t = {k / 2} is closed, manifold and oriented", ok, err)

shutil.rmtree(TMP, ignore_errors=True)
T.finish()
