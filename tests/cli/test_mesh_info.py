#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""coons2stl --info's "mesh" facts and the sampling options --resolution and
--max-triangles, checked against counts worked out here: a box on a fixed
N x N x N lattice has flat faces, meshed from their boundary polygons
(src/mesh/flat.c): its vertices are the 12 (N - 1) + 8 lattice points on
its edges plus s >= 0 Steiner points inside the faces, 2 V - 4 triangles
(Euler 2), never more than the lattice's 12 N^2, and its mesh volume is
exact; a pyramid (body 0 with its four top corners at one apex) keeps one
apex vertex; every example body's mesh is closed, manifold,
oriented, with the Euler characteristic expected and a measured deviation
within the tolerance (or the tolerance given with -t).

Usage: test_mesh_info.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)


def info(path, extra=()):
    rc, out, err = T.run(["--info"] + list(extra) + [path])
    try:
        return rc, json.loads(out), err
    except ValueError:
        return rc, None, err + out


def body0(corners, name="b"):
    return {"type": "body0", "name": name, "corners": corners}


def model_file(tmp, name, bodies, **top):
    doc = {"coons": 1, "bodies": bodies}
    doc.update(top)
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        json.dump(doc, f)
    return path


BOX = [[2 * i, 3 * j, 5 * k] for i in (0, 1) for j in (0, 1) for k in (0, 1)]
PYRAMID = [[2 * i - 1, 2 * j - 1, 0] if k == 0 else [0, 0, 2]
           for i in (0, 1) for j in (0, 1) for k in (0, 1)]

with tempfile.TemporaryDirectory() as tmp:
    box = model_file(tmp, "box.json", [body0(BOX)])
    for n in (1, 3, 7):
        rc, j, err = info(box, ["--resolution", str(n)])
        m = j and j["bodies"][0].get("mesh")
        T.check(f"box --resolution {n}: 12 (N-1) + 8 + s vertices, 2 V - 4 <= 12 N^2 "
                "triangles, lattice N^3",
                rc == 0 and m and m["vertices"] >= 12 * (n - 1) + 8
                and m["triangles"] == 2 * m["vertices"] - 4
                and m["triangles"] <= 12 * n * n and (n < 3 or m["triangles"] < 12 * n * n)
                and m["lattice"] == [n, n, n], f"{rc} {m} {err}")
        T.check(f"box --resolution {n}: closed, manifold, oriented, Euler 2, exact volume 30",
                m and m["closed"] and m["manifold"] and m["oriented"] and m["euler"] == 2
                and m["expected_euler"] == 2 and m["shells"] == 1
                and abs(m["volume"] - 30) < 1e-12 and abs(m["area"] - 62) < 1e-12
                and m["deviation"] <= 1e-12, str(m))

    rc, j, err = info(box, ["-t", "0.5"])
    m = j and j["bodies"][0]["mesh"]
    T.check("-t sets the mesh tolerance in --info", rc == 0 and m and m["tolerance"] == 0.5, str(m))

    pyr = model_file(tmp, "pyr.json", [body0(PYRAMID, "pyramid")])
    rc, j, err = info(pyr, ["--resolution", "4"])
    m = j and j["bodies"][0]["mesh"]
    # 4 x 4 lattice: the top face's 25 points become one apex; the flat
    # faces keep their boundary points only: 16 around the base, 3 inside
    # each slanted edge, the apex, plus s >= 0 Steiner points.
    T.check("pyramid: apex merged (vertices = 16 + 4*3 + 1 + s), volume 8/3",
            rc == 0 and m and m["vertices"] >= 16 + 4 * 3 + 1
            and m["triangles"] == 2 * m["vertices"] - 4 and abs(m["volume"] - 8 / 3) < 1e-12
            and m["closed"] and m["manifold"] and m["euler"] == 2, f"{m} {err}")

    rc, out, err = T.run(["--info", "--max-triangles", "100", box])
    T.check("--max-triangles too small: exit 3, message names the limit and the option",
            rc == 3 and "100" in err and "--max-triangles" in err, f"{rc} {err}")
    rc, out, err = T.run(["--info", "--resolution", "3", "--max-triangles", "108", box])
    T.check("--max-triangles exactly enough", rc == 0, err)
    for bad in (["--resolution", "0"], ["--resolution", "x"], ["--resolution", "-3"],
                ["--max-triangles", "0"], ["--max-triangles", "1e6"], ["--resolution"]):
        rc, out, err = T.run(["--info"] + bad + [box])
        T.check(f"bad {' '.join(bad)}: usage error (exit 2)", rc == 2 and out == "", f"{rc} {err}")
    rc, out, err = T.run(["--eval", "--resolution", "3", box], stdin="0 0 0\n")
    T.check("--resolution with --eval: usage error", rc == 2, f"{rc} {err}")

    # A fixed resolution coarser than the tolerance: warned, not refused.
    curved = model_file(tmp, "bez.json", [{
        "type": "bezier-volume", "name": "pillow",
        "points": [[[[i / 2 + (0.3 if (j == 1 and k == 1 and i != 1) else 0) * (1 if i else -1),
                      j / 2, k / 2] for k in range(3)] for j in range(3)] for i in range(3)]}],
        tolerance=1e-4)
    rc, j, err = info(curved, ["--resolution", "2"])
    m = j and j["bodies"][0]["mesh"]
    T.check("coarse --resolution: deviation > tolerance reported and warned",
            rc == 0 and m and m["deviation"] > 1e-4 and "warning" in err and "resolution" in err,
            f"{m} {err}")
    rc, j, err = info(curved, ["--resolution", "2", "-q"])
    T.check("-q silences that warning", rc == 0 and err == "", err)
    rc, j, err = info(curved)
    m = j and j["bodies"][0]["mesh"]
    T.check("adaptive: deviation within the tolerance", rc == 0 and m and 0 < m["deviation"] <= 1e-4,
            str(m))

examples = T.examples()  # the representative subset under valgrind or ASan
for path in examples:
    rc, j, err = info(path, ["-q"])
    name = os.path.basename(path)
    if not T.check(f"{name}: --info runs", rc == 0 and j is not None, err):
        continue
    for b in j["bodies"]:
        m = b["mesh"]
        T.check(f"{name} {b['name']}: {m['triangles']} triangles, closed, manifold, oriented, "
                f"Euler {m['euler']} (expected {m['expected_euler']}), "
                f"deviation {m['deviation']:.3g} <= {m['tolerance']:.3g}",
                m["closed"] and m["manifold"] and m["oriented"] and m["euler"] == m["expected_euler"]
                and m["boundary_edges"] == 0 and m["nonmanifold_edges"] == 0
                and m["nonmanifold_vertices"] == 0 and m["misoriented_edges"] == 0
                and m.get("openmesh_rejected", 0) == 0
                and m["deviation"] <= m["tolerance"] == j["tolerance"] and m["volume"] > 0, str(m))

T.finish()
