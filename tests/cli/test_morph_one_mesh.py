#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A morph is one mesh at every t (outputs.md "Honest output",
"Metamorphosis"; issue 24), whatever the way in, checked on every morph
example (examples/*morph*.json) with the real OpenSCAD:

- `coons2stl M.json --time T -o x.off`, frame k of `--frames 5` (T = k/4)
  and `openscad -D '$t=T'` of the animation `coons2stl M.json -o M.scad`
  give the same vertices to the 6 digits OpenSCAD prints (the same count,
  each coordinate within one unit of the 6th digit, for rounding ties),
  and the same enclosed volume (divergence theorem over each side's own
  triangles: OpenSCAD's faces are the animation's face list, ours the
  output's), to the printed digits' share of it;
- `-o x.off` without --time (the morph at the file's own "t") is the same
  mesh as OpenSCAD's $t = that t.

Before issue 24 only `--time T --resolution N` with the file's N matched
OpenSCAD: -o and --time chose their own lattice at each t (volumes 5e-4 to
1.4e-3 relative apart).

Usage: test_morph_one_mesh.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import glob
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
TMP = tempfile.mkdtemp(prefix="coons-morph-one-")
OPENSCAD = shutil.which("openscad")
T.check("openscad is installed", OPENSCAD is not None)
if not OPENSCAD:
    T.finish()

FRAMES = 5
KS = (1, 3)  # frames 1 and 3: t = 0.25, 0.75


def read_off(path):
    """(vertices, triangles) of an OFF file (polygons fanned)."""
    with open(path) as f:
        words = f.read().split()
    if not words or words[0] != "OFF":
        return None, None
    nv, nf = int(words[1]), int(words[2])
    at = 4
    verts = []
    for _ in range(nv):
        verts.append(tuple(float(x) for x in words[at:at + 3]))
        at += 3
    tris = []
    for _ in range(nf):
        n = int(words[at])
        idx = [int(x) for x in words[at + 1:at + 1 + n]]
        at += 1 + n
        for i in range(1, n - 1):
            tris.append((idx[0], idx[i], idx[i + 1]))
    return verts, tris


def volume(verts, tris):
    """|signed volume|: sum of det(a, b, c) / 6 over the triangles."""
    s = 0.0
    for a, b, c in tris:
        p, q, r = verts[a], verts[b], verts[c]
        s += (p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0])
              + p[2] * (q[0] * r[1] - q[1] * r[0]))
    return abs(s) / 6.0


def printed(x):
    """OpenSCAD's 6 significant digits."""
    return float(f"{x:.6g}")


def same_vertices(theirs, ours):
    """Same count; sorted, each coordinate within one unit of the 6th digit."""
    if len(theirs) != len(ours):
        return False, f"{len(theirs)} vertices against {len(ours)}"
    a = sorted(tuple(printed(x) for x in v) for v in theirs)
    b = sorted(tuple(printed(x) for x in v) for v in ours)
    bad, worst = 0, 0.0
    for p, q in zip(a, b):
        for x, y in zip(p, q):
            unit = 10 ** (math.floor(math.log10(abs(y))) - 5) if y else 1e-300
            if abs(x - y) > unit * 1.01 and abs(x - y) > 1e-12:
                bad += 1
                worst = max(worst, abs(x - y))
    return bad == 0, f"{bad} coordinates differ beyond the printed digits (worst {worst:.3g})"


def openscad_off(scad, t, out):
    p = subprocess.run([OPENSCAD, "-D", f"$t={t!r}", "-o", out, scad], capture_output=True,
                       text=True, timeout=T.timeout)
    return p.returncode, p.stderr


def compare(label, ours_path, theirs_path):
    ov, ot = read_off(ours_path)
    tv, tt = read_off(theirs_path)
    if ov is None or tv is None:
        T.check(label, False, "an OFF file could not be read")
        return
    ok, why = same_vertices(tv, ov)
    T.check(f"{label}: the same vertices to the printed digits", ok, why)
    va, vb = volume(ov, ot), volume(tv, tt)
    rel = abs(va - vb) / max(va, vb)
    # 6 digits on every coordinate: a few 1e-6 of the volume at most
    T.check(f"{label}: the same volume ({va:.9g} and {vb:.9g}, {rel:.2g} relative)",
            rel < 2e-5, f"{va} {vb}")


examples = sorted(glob.glob(os.path.join(T.src, "examples", "*morph*.json")))
T.check("the morph examples are found", len(examples) >= 3, str(examples))
for ex in examples:
    name = os.path.splitext(os.path.basename(ex))[0]
    with open(ex) as f:
        own_t = json.load(f)["bodies"][0].get("t", 0.0)
    d = os.path.join(TMP, name)
    os.mkdir(d)
    scad = os.path.join(d, "anim.scad")
    rc, _, err = T.run(["-q", ex, "-o", scad])
    if not T.check(f"{name}: the animation is written", rc == 0, err):
        continue
    rc, _, err = T.run(["-q", ex, "--frames", str(FRAMES), "-o", os.path.join(d, "f%d.off")])
    T.check(f"{name}: --frames {FRAMES} writes its frames", rc == 0, err)
    for k in KS:
        t = k / (FRAMES - 1)
        single = os.path.join(d, f"time{k}.off")
        rc, _, err = T.run(["-q", ex, "--time", repr(t), "-o", single])
        if not T.check(f"{name}: --time {t} -o .off", rc == 0, err):
            continue
        compare(f"{name}: --time {t} and frame {k} of --frames {FRAMES}", single,
                os.path.join(d, f"f{k}.off"))
        theirs = os.path.join(d, f"openscad{k}.off")
        rc, err = openscad_off(scad, t, theirs)
        if T.check(f"{name}: openscad -D '$t={t}' renders the animation", rc == 0, err):
            compare(f"{name}: --time {t} and openscad $t = {t}", single, theirs)
    # the file's own time
    own = os.path.join(d, "own.off")
    rc, _, err = T.run(["-q", ex, "-o", own])
    theirs = os.path.join(d, "openscad-own.off")
    rc2, err2 = openscad_off(scad, own_t, theirs)
    if T.check(f"{name}: -o at the file's t = {own_t} and openscad $t = {own_t} run",
               rc == 0 and rc2 == 0, err + err2):
        compare(f"{name}: -o (t = {own_t}) and openscad $t = {own_t}", own, theirs)

shutil.rmtree(TMP, ignore_errors=True)
T.finish()
