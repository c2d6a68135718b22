#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Morph bodies through coons2stl (coons-model(5) "morph", coons2stl(1)
--time, --frames, --info):

- --time T --eval gives (1 - T) cube(u,v,w) + T spool(u,v,w) for the cube
  to spool morph (seed 000 Fig. 10), with the cube's trilinear map written
  out here and the spool evaluated alone from examples/spool.json; a
  smooth three-key path passes through its middle key at its time;
- --time reaches a morph inside a morph and one through a reference;
  --time outside [0,1] is a usage error (exit 2), nothing written;
- --frames N -o PATTERN: N files, frame k byte for byte the output of
  --time k/(N-1); bad patterns (no field, two fields, %s, a field in a
  directory) are usage errors and write nothing; a failure in frame k
  (a write error) leaves frames 0..k-1 and nothing else (no temporary
  files), exit 3; a triangle budget below the morph's one lattice for
  its whole path fails at frame 0;
- --frames with .vtu: the frames and a ParaView .pvd whose DataSets name
  them at times k/(N-1);
- --info "morph": the keys' types and times, the path; keys of opposite
  handedness give a sign change of det J between sampled times bracketing
  the time where det J = 0, and a warning.

Usage: test_morph.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import os
import shutil
import sys
import tempfile
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
TMP = tempfile.mkdtemp(prefix="coons-morph-")
SRC = T.src

with open(os.path.join(SRC, "examples", "spool.json")) as f:
    SPOOL = json.load(f)["bodies"][0]
SPOOL.pop("name", None)
# The spool's corners F(i,j,k) at 4i+2j+k: a square of half-diagonal 6
# turned by 45 degrees, 10 high.
CUBE_C = [[0, -6, 0], [0, -6, 10], [-6, 0, 0], [-6, 0, 10],
          [6, 0, 0], [6, 0, 10], [0, 6, 0], [0, 6, 10]]
CUBE = {"type": "body0", "corners": CUBE_C}


def write(name, obj):
    p = os.path.join(TMP, name)
    with open(p, "w") as f:
        json.dump(obj, f, indent=1)
    return p


def model(*bodies, define=None):
    m = {"coons": 1, "units": "mm", "bodies": list(bodies)}
    if define:
        m["define"] = define
    return m


def trilinear(c, u, v, w):
    out = [0.0, 0.0, 0.0]
    for n in range(8):
        i, j, k = n >> 2, (n >> 1) & 1, n & 1
        b = (u if i else 1 - u) * (v if j else 1 - v) * (w if k else 1 - w)
        for d in range(3):
            out[d] += b * c[n][d]
    return out


def eval_points(path, params, extra=()):
    text = "".join(f"{u} {v} {w}\n" for u, v, w in params)
    rc, out, err = T.run([path, "--eval", *extra], stdin=text)
    if rc != 0:
        return None, err
    return [[float(x) for x in line.split()] for line in out.splitlines()], err


PARAMS = [(0.1, 0.2, 0.3), (0.5, 0.5, 0.5), (0.9, 0.05, 0.7), (0, 1, 1), (0.33, 0.8, 0.12)]
spool_path = write("spool.json", model(SPOOL))
spool_pts, err = eval_points(spool_path, PARAMS)
T.check("the spool alone evaluates", spool_pts is not None, err)

m1 = write("m1.json", model({"type": "morph", "name": "c2s", "keys": [CUBE, SPOOL], "t": 0.9}))
for t in (0.0, 0.3, 0.5, 1.0):
    pts, err = eval_points(m1, PARAMS, ["--time", str(t)])
    ok = pts is not None and spool_pts is not None
    worst = 0.0
    if ok:
        for p, s, q in zip(pts, spool_pts, PARAMS):
            c = trilinear(CUBE_C, *q)
            worst = max(worst, max(abs(p[d] - ((1 - t) * c[d] + t * s[d])) for d in range(3)))
    T.check(f"--time {t}: the morph is (1 - t) cube + t spool", ok and worst < 1e-12,
            f"worst {worst} {err}")
pts, err = eval_points(m1, PARAMS)
worst = max(abs(p[d] - (0.1 * trilinear(CUBE_C, *q)[d] + 0.9 * s[d]))
            for p, s, q in zip(pts, spool_pts, PARAMS) for d in range(3))
T.check("without --time the morph's own t (0.9)", worst < 1e-12, f"worst {worst}")

# three keys on a smooth path: at a key time, the key itself
mid = {"type": "body0", "corners": [[x * 0.5, y * 0.5, z] for x, y, z in CUBE_C]}
m3 = write("m3.json", model({"type": "morph", "keys": [CUBE, mid, SPOOL], "at": [0, 0.3, 1],
                             "path": "smooth"}))
pts, err = eval_points(m3, PARAMS, ["--time", "0.3"])
worst = max(abs(p[d] - trilinear(mid["corners"], *q)[d]) for p, q in zip(pts, PARAMS)
            for d in range(3)) if pts else 1
T.check("smooth path of three keys: at t = 0.3 the middle key", worst < 1e-12, f"{worst} {err}")

# nested and referenced morphs follow --time
inner = {"type": "morph", "keys": [CUBE, {"ref": "sp"}]}
mn = write("mn.json", model({"type": "morph", "keys": [{"ref": "c2s"}, inner]},
                            define={"sp": SPOOL, "c2s": {"type": "morph", "keys": [CUBE, SPOOL],
                                                         "t": 0.2}}))
pts, err = eval_points(mn, PARAMS, ["--time", "0.5"])
# outer = 0.5 (0.5 c + 0.5 s) + 0.5 (0.5 c + 0.5 s) = 0.5 c + 0.5 s
worst = max(abs(p[d] - (0.5 * trilinear(CUBE_C, *q)[d] + 0.5 * s[d]))
            for p, s, q in zip(pts, spool_pts, PARAMS) for d in range(3)) if pts else 1
T.check("--time sets morphs inside morphs and through references", worst < 1e-12,
        f"{worst} {err}")

out = os.path.join(TMP, "bad.stl")
for bad in ("1.5", "-0.1", "x", "nan"):
    rc, _, err = T.run([m1, "--time", bad, "-o", out])
    T.check(f"--time {bad}: usage error, nothing written",
            rc == 2 and not os.path.exists(out) and "--time" in err, f"rc={rc} {err}")
rc, _, err = T.run([spool_path, "--time", "0.5", "-o", out])
T.check("--time on a model without morphs: a warning", rc == 0 and "no morph" in err, err)

# ---- --frames
fdir = os.path.join(TMP, "frames")
os.mkdir(fdir)
rc, _, err = T.run([m1, "--frames", "3", "-o", os.path.join(fdir, "f-%03d.stl")])
names = sorted(os.listdir(fdir))
T.check("--frames 3: three files named by the pattern",
        rc == 0 and names == ["f-000.stl", "f-001.stl", "f-002.stl"], f"{names} {err}")
for k in range(3):
    single = os.path.join(TMP, f"single{k}.stl")
    rc, _, err = T.run([m1, "--time", repr(k / 2), "-o", single])
    with open(single, "rb") as a, open(os.path.join(fdir, f"f-{k:03d}.stl"), "rb") as b:
        same = a.read() == b.read()
    T.check(f"frame {k} is the output of --time {k / 2}, byte for byte", rc == 0 and same, err)

for pat, why in (("g.stl", "no integer field"), ("g-%d-%d.stl", "more than one"),
                 ("g-%s.stl", "other than an integer"), ("g%d/x.stl", "file name")):
    rc, _, err = T.run([m1, "--frames", "2", "-o", os.path.join(fdir, pat)])
    T.check(f"--frames pattern {pat!r}: usage error ({why})",
            rc == 2 and why in err and sorted(os.listdir(fdir)) == names, f"rc={rc} {err}")
rc, _, err = T.run([m1, "--frames", "1", "-o", os.path.join(fdir, "h%d.stl")])
T.check("--frames 1: usage error", rc == 2, err)
rc, _, err = T.run([m1, "--frames", "3", "--time", "0.5", "-o", os.path.join(fdir, "h%d.stl")])
T.check("--frames with --time: usage error", rc == 2, err)

# a failure in frame 1: its name is taken by a directory (a write error)
bdir = os.path.join(TMP, "budget")
os.mkdir(bdir)
os.mkdir(os.path.join(bdir, "b1.off"))
rc, _, err = T.run([m1, "--frames", "3", "-o", os.path.join(bdir, "b%d.off")])
left = sorted(os.listdir(bdir))
T.check("a failure in frame 1 leaves frame 0 and nothing else, exit 3",
        rc == 3 and left == ["b0.off", "b1.off"] and os.path.isfile(os.path.join(bdir, "b0.off"))
        and not os.listdir(os.path.join(bdir, "b1.off")) and "frame 1" in err,
        f"rc={rc} {left} {err}")
# every frame of a morph has the one lattice of its whole path: a budget it
# exceeds fails at frame 0 (t = 0, where the cube alone would fit), nothing
# written
cdir = os.path.join(TMP, "budget0")
os.mkdir(cdir)
rc, _, err = T.run([m1, "--frames", "3", "--max-triangles", "1000", "-o",
                    os.path.join(cdir, "b%d.off")])
T.check("a budget the path's lattice exceeds: frame 0 fails, nothing written, exit 3",
        rc == 3 and not os.listdir(cdir) and "frame 0" in err, f"rc={rc} {err}")

# ---- .vtu frames and the .pvd
vdir = os.path.join(TMP, "vtu")
os.mkdir(vdir)
rc, _, err = T.run([m1, "--frames", "4", "--resolution", "3", "-o",
                    os.path.join(vdir, "cs_%02d.vtu")])
files = sorted(os.listdir(vdir))
T.check("--frames 4 with .vtu: four frames and cs.pvd",
        rc == 0 and files == ["cs.pvd", "cs_00.vtu", "cs_01.vtu", "cs_02.vtu", "cs_03.vtu"],
        f"{files} {err}")
if "cs.pvd" in files:
    root = ET.parse(os.path.join(vdir, "cs.pvd")).getroot()
    ds = root.findall("./Collection/DataSet")
    T.check("the .pvd is a VTK Collection of the frames at t = k/3",
            root.get("type") == "Collection" and len(ds) == 4
            and all(d.get("file") == f"cs_{k:02d}.vtu" and abs(float(d.get("timestep")) - k / 3)
                    < 1e-15 for k, d in enumerate(ds)), ET.tostring(root)[:300])
    single = os.path.join(TMP, "single.vtu")
    rc, _, err = T.run([m1, "--time", repr(2 / 3), "--resolution", "3", "-o", single])
    with open(single, "rb") as a, open(os.path.join(vdir, "cs_02.vtu"), "rb") as b:
        T.check("volume frame 2 is the output of --time 2/3", rc == 0 and a.read() == b.read(),
                err)

# ---- --info
rc, out, err = T.run([m1, "--info", "--no-solid"])
try:
    info = json.loads(out)
    mo = info["bodies"][0]["morph"]
    T.check("--info morph: keys body0 at 0 and body2 at 1, path linear, t 0.9",
            [k["type"] for k in mo["keys"]] == ["body0", "body2"]
            and [k["at"] for k in mo["keys"]] == [0, 1] and mo["path"] == "linear"
            and mo["t"] == 0.9 and mo["det_sign_changes"] == [], mo)
except (ValueError, KeyError, IndexError) as e:
    T.check("--info of a morph is JSON with a morph object", False, f"{e} {out[:400]}")

# a unit cube and its mirror (linear path): det J = 1 - 2t, zero at t = 1/2
unit = {"type": "body0", "corners": [[n >> 2, (n >> 1) & 1, n & 1] for n in range(8)]}
mirror = {"ref": "u", "transform": [[-1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}
mf = write("mf.json", model({"type": "morph", "keys": [{"ref": "u"}, mirror]},
                            define={"u": unit}))
rc, out, err = T.run([mf, "--info", "--no-solid", "--time", "0.1"])
try:
    mo = json.loads(out)["bodies"][0]["morph"]
    ch = mo["det_sign_changes"]
    T.check("opposite handedness: one sign change of det J, between sampled times around 1/2",
            len(ch) == 1 and ch[0]["between"][0] <= 0.5 <= ch[0]["between"][1]
            and ch[0]["between"][1] - ch[0]["between"][0] <= 1 / 64 + 1e-12
            and ch[0]["min_det"][0] * ch[0]["min_det"][1] <= 0, ch)
    T.check("... and a warning that the morph folds", "folds" in err, err)
    T.check("... the minimum over time is det J at t = 1: -1",
            abs(mo["min_det_jacobian"] + 1) < 1e-12 and mo["min_det_jacobian_time"] == 1, mo)
except (ValueError, KeyError, IndexError) as e:
    T.check("--info of the mirrored morph", False, f"{e} {out[:400]} {err}")

# loader errors name the path
bad = write("badat.json", model({"type": "morph", "keys": [CUBE, SPOOL], "at": [0, 0.5]}))
rc, _, err = T.run([bad, "--info"])
T.check("\"at\" ending below 1: exit 1 naming /bodies/0/at/1",
        rc == 1 and "/bodies/0/at/1" in err and "must be 1" in err, err)
bad = write("badpath.json", model({"type": "morph", "keys": [CUBE, SPOOL], "path": "cubic"}))
rc, _, err = T.run([bad, "--info"])
T.check("unknown path: exit 1 naming /bodies/0/path", rc == 1 and "/bodies/0/path" in err
        and "\"linear\" or \"smooth\"" in err, err)

shutil.rmtree(TMP, ignore_errors=True)
T.finish()
