#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""coons2stl --info against values computed here: exact volumes (a box, an
affine box = |det A|, a trilinear hexahedron by 3-point Gauss quadrature of
the trilinear Jacobian written out here, a NURBS tube = pi (r1^2 - r0^2) h),
boxes, the default tolerance (1/1000 of the control box diagonal), the
model settings, --body, and the warning for det J < 0.

Usage: test_info.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
OK = os.path.join(T.data, "ok")


def info(path, extra=()):
    rc, out, err = T.run(["--info"] + list(extra) + [path])
    try:
        return rc, json.loads(out), err
    except ValueError:
        return rc, None, err + out


def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def det3(A):
    return (A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1])
            - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0])
            + A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]))


def trilinear_volume(P):
    """det J of T(P; u, v, w) is of degree <= 2 in each variable: 3-point
    Gauss-Legendre per direction integrates it exactly."""
    g = [(0.5 - 0.5 * math.sqrt(0.6), 5 / 18), (0.5, 8 / 18), (0.5 + 0.5 * math.sqrt(0.6), 5 / 18)]
    vol = 0.0
    for u, wu in g:
        for v, wv in g:
            for w, ww in g:
                d = [[0.0] * 3 for _ in range(3)]
                for n in range(8):
                    i, j, k = n >> 2, (n >> 1) & 1, n & 1
                    bu, bv, bw = (u if i else 1 - u), (v if j else 1 - v), (w if k else 1 - w)
                    su, sv, sw = (1 if i else -1), (1 if j else -1), (1 if k else -1)
                    for r in range(3):
                        d[r][0] += su * bv * bw * P[n][r]
                        d[r][1] += bu * sv * bw * P[n][r]
                        d[r][2] += bu * bv * sw * P[n][r]
                vol += wu * wv * ww * det3(d)
    return vol


BOX = """{"coons": 1, "bodies": [{"type": "body0", "name": "box", "corners":
 [[0, 0, 0], [0, 0, 30], [0, 20, 0], [0, 20, 30], [10, 0, 0], [10, 0, 30], [10, 20, 0], [10, 20, 30]]}]}
"""
tmp = tempfile.mkdtemp(prefix="coons_info_")
box = os.path.join(tmp, "box.json")
with open(box, "w") as f:
    f.write(BOX)

rc, j, err = info(box)
ok = rc == 0 and j is not None
T.check("--info prints JSON (exit 0)", ok, err)
if ok:
    b = j["bodies"][0]
    T.check("box 10 x 20 x 30: volume 6000", rel(b["volume"], 6000.0) < 1e-13, str(b["volume"]))
    T.check("box: total_volume 6000, body_count 1",
            rel(j["total_volume"], 6000.0) < 1e-13 and j["body_count"] == 1, str(j))
    T.check("box: sampled bbox and control bbox",
            b["bbox"] == {"min": [0, 0, 0], "max": [10, 20, 30]}
            and b["control_bbox"] == {"min": [0, 0, 0], "max": [10, 20, 30]}, str(b))
    T.check("box: name, type, index", (b["name"], b["type"], b["index"]) == ("box", "body0", 0), str(b))
    T.check("defaults: units mm, operation union, tolerance = diagonal / 1000",
            j["units"] == "mm" and j["operation"] == "union"
            and rel(j["tolerance"], math.sqrt(100 + 400 + 900) / 1000) < 1e-15, str(j))
    T.check("box: min det J = 6000 (constant)", rel(b["min_det_jacobian"], 6000.0) < 1e-13, str(b))

# affine box: volume = det A
m = json.load(open(os.path.join(OK, "affine-box.json")))
P = [clitest.pt3(p) for p in m["bodies"][0]["corners"]]
A = [[P[4][r] - P[0][r], P[2][r] - P[0][r], P[1][r] - P[0][r]] for r in range(3)]
rc, j, err = info(os.path.join(OK, "affine-box.json"))
T.check("affine box: volume = det A", j is not None and rel(j["bodies"][0]["volume"], det3(A)) < 1e-12,
        f"{j and j['bodies'][0]['volume']} vs {det3(A)} {err}")

# skew hexahedron: exact trilinear volume; units from the file
m = json.load(open(os.path.join(OK, "trilinear.json")))
H = [clitest.pt3(p) for p in m["bodies"][0]["corners"]]
rc, j, err = info(os.path.join(OK, "trilinear.json"))
T.check("trilinear hexahedron: volume by exact Gauss quadrature, units 'in'",
        j is not None and rel(j["bodies"][0]["volume"], trilinear_volume(H)) < 1e-10 and j["units"] == "in",
        f"{j and j['bodies'][0]['volume']} vs {trilinear_volume(H)} {err}")

# NURBS tube
rc, j, err = info(os.path.join(OK, "tube-nurbs.json"))
ok = j is not None
T.check("NURBS tube: volume 9 pi to 1e-6", ok and rel(j["bodies"][0]["volume"], 9 * math.pi) < 1e-6,
        f"{j and j['bodies'][0]['volume']} {err}")
if ok:
    bb = j["bodies"][0]["bbox"]
    T.check("NURBS tube: sampled bbox [-2,-2,0]..[2,2,3]",
            all(abs(a - b) < 1e-12 for a, b in zip(bb["min"] + bb["max"], [-2, -2, 0, 2, 2, 3])), str(bb))
    T.check("NURBS tube: tolerance = sqrt(41) / 1000", rel(j["tolerance"], math.sqrt(41) / 1000) < 1e-15,
            str(j["tolerance"]))

# Bezier volume + body0: control box vs sampled box, operation none, totals
rc, j, err = info(os.path.join(OK, "bezier-volume.json"))
ok = j is not None and len(j["bodies"]) == 2
T.check("two bodies listed", ok, err)
if ok:
    b0 = j["bodies"][0]
    T.check("model control box includes the Bezier bulge point (y = -0.4)",
            j["control_bbox"] == {"min": [0, -0.4, 0], "max": [1, 1.3, 3]}, str(j["control_bbox"]))
    T.check("the sampled boundary stays inside the control box (y > -0.4)",
            -0.4 < b0["bbox"]["min"][1] < 0 and b0["control_bbox"]["min"][1] == -0.4, str(b0))
    T.check("tolerance from the control box of all bodies",
            rel(j["tolerance"], math.sqrt(1 + 1.7 ** 2 + 9) / 1000) < 1e-14, str(j["tolerance"]))
    T.check("operation none", j["operation"] == "none", j["operation"])
    T.check("total_volume is the sum", rel(j["total_volume"], b0["volume"] + j["bodies"][1]["volume"]) < 1e-14
            and rel(j["bodies"][1]["volume"], 1.0) < 1e-13, str(j))
    T.check("names: unnamed body is body0, escaped name decoded",
            b0["name"] == "body0" and j["bodies"][1]["name"] == 'caf\u00e9 "lid"', str(j))
rc, j, err = info(os.path.join(OK, "bezier-volume.json"), ["--body", "1"])
T.check("--info --body 1 lists only body 1", j is not None and [b["index"] for b in j["bodies"]] == [1]
        and j["body_count"] == 1, str(j))

# left-handed box: det J < 0 -> a warning, silenced by -q
mirror = os.path.join(tmp, "mirror.json")
with open(mirror, "w") as f:
    f.write(BOX.replace("[10,", "[-10,"))
rc, j, err = info(mirror)
T.check("left-handed box: volume -6000 and a warning on stderr",
        rc == 0 and j is not None and rel(j["bodies"][0]["volume"], -6000) < 1e-13
        and "warning" in err and "det J" in err, err)
rc, j, err = info(mirror, ["-q"])
T.check("-q silences the warning", rc == 0 and j is not None and err == "", err)
rc, j, err = info(box)
T.check("no warning for a right-handed box", err == "", err)

for f in os.listdir(tmp):
    os.remove(os.path.join(tmp, f))
os.rmdir(tmp)
T.finish()
