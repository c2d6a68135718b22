# SPDX-License-Identifier: GPL-3.0-or-later
"""coons2stl's volume meshes at the command line (outputs.md "Volume
meshes", "--info additions"), read back with VTK (an independent reader and
an independent implementation of the hexahedron's scaled Jacobian: VTK's
vtkMeshQuality, i.e. the Verdict library):

- every example that is one body or conformal meshes; the scaled Jacobian
  we report per cell equals VTK's on every cell with 8 distinct corners,
  and --info's "volume_mesh" minimum, mean and counts agree with the file;
- every node at --eval's point of its (u, v, w) point data (isoparametric);
- the folded test model is refused with exit 3 naming the body and the
  parameters, the existing output untouched, no file left; --allow-inverted
  writes it and the inverted cells are there;
- a left-handed body gets valid (positive) cells and negative det_j;
- two boxes that share a face: one conformal mesh; overlapping bodies and
  bodies touching along faces sampled differently: refused (exit 3);
- --resolution NU,NV,NW gives NU*NV*NW cells; --body meshes one body;
- the cell limit refuses at once.
Run with Debian's /usr/bin/python3 (python3-vtk9).
"""
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402

T = Runner(__doc__)
try:
    import numpy as np
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
except ImportError as e:  # a missing reader fails the test, never skips it
    T.check("VTK and numpy for Python are installed (python3-vtk9, python3-numpy)", False,
            str(e))
    T.finish()

work = tempfile.mkdtemp(prefix="coons_vol_")
EX = os.path.join(T.src, "examples")


def read_vtk(path):
    r = vtk.vtkUnstructuredGridReader()
    r.SetFileName(path)
    r.ReadAllScalarsOn()
    r.Update()
    return r.GetOutput()


def arr(g, where, name):
    data = g.GetPointData() if where == "point" else g.GetCellData()
    a = data.GetArray(name)
    return None if a is None else vtk_to_numpy(a)


def vtk_quality(g):
    q = vtk.vtkMeshQuality()
    q.SetInputData(g)
    q.SetHexQualityMeasureToScaledJacobian()
    q.Update()
    return vtk_to_numpy(q.GetOutput().GetCellData().GetArray("Quality"))


def distinct_corners(g, c):
    """Distinct corners of a cell (wedges 6, pyramids 5)."""
    ids = g.GetCell(c).GetPointIds()
    return len({ids.GetId(k) for k in range(min(8, ids.GetNumberOfIds()))})


def info(args):
    rc, out, err = T.run(["--info", "--no-solid"] + args)
    try:
        return rc, json.loads(out), err
    except ValueError:
        return rc, None, err


def model(bodies, name):
    path = os.path.join(work, name)
    with open(path, "w") as f:
        json.dump({"coons": 1, "bodies": bodies}, f)
    return path


def box(lo, hi, name):
    c = [[hi[0] if i & 4 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 1 else lo[2]]
         for i in range(8)]
    return {"type": "body0", "name": name, "corners": c}


# ---- examples: quality against VTK, info against the file, nodes against --eval
for ex, args in (("spool.json", []), ("nail.json", []), ("body1-density.json", []),
                 ("volume-nurbs.json", []), ("deformed-cube.json", ["--resolution", "5,3,4"]),
                 ("body1-bspline-edges.json", ["--element", "hex20", "--resolution", "3"])):
    path = os.path.join(EX, ex)
    out = os.path.join(work, ex + ".vtk")
    rc, _, err = T.run(args + ["-o", out, path])
    if not T.check(f"{ex} {args}: volume mesh written", rc == 0 and os.path.exists(out), err):
        continue
    g = read_vtk(out)
    ours = arr(g, "cell", "scaled_jacobian")
    theirs = vtk_quality(g)
    full = np.array([distinct_corners(g, c) == 8 for c in range(g.GetNumberOfCells())])
    # (vtkMeshQuality measures linear hexahedra only.)
    if "--element" not in args:
        T.check(f"{ex}: our scaled Jacobian = VTK's (Verdict) on the {full.sum()} cells with 8 "
                "distinct corners",
                full.any() and np.abs(ours[full] - theirs[full]).max() < 1e-12,
                f"max diff {np.abs(ours[full] - theirs[full]).max() if full.any() else None}")
    rc, j, err = info(args + ["--volume-mesh", path])
    vmi = j and j["bodies"][0].get("volume_mesh")
    ok = bool(vmi) and vmi["cells"] == g.GetNumberOfCells() and \
        abs(vmi["min_scaled_jacobian"] - ours.min()) < 1e-15 and \
        abs(vmi["mean_scaled_jacobian"] - ours.mean()) < 1e-12 and \
        vmi["inverted"] == 0 and vmi["below_0_2"] == int((ours < 0.2).sum()) and \
        vmi["collapsed"] == int((~full).sum()) and vmi["nodes"] == g.GetNumberOfPoints()
    T.check(f"{ex}: --info volume_mesh agrees with the file (cells, nodes, min, mean, counts)",
            ok, f"{vmi} vs {g.GetNumberOfCells()} cells {ours.min()} {ours.mean()}")
    if ex == "nail.json":
        types = {g.GetCellType(c) for c in range(g.GetNumberOfCells())}
        T.check("nail: the tip's cells are collapsed (written as VTK pyramids, 14), none "
                "inverted, all others valid",
                vmi["collapsed"] > 0 and ours[full].min() > 0 and 14 in types and
                int((~full).sum()) == sum(g.GetCellType(c) == 14
                                          for c in range(g.GetNumberOfCells())), str(vmi))
        v = vtk.vtkCellValidator()
        v.SetInputData(g)
        # It prints the cells it finds invalid to standard output (C++).
        sys.stdout.flush()
        saved = os.dup(1)
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), 1)
            try:
                v.Update()
            finally:
                os.dup2(saved, 1)
                os.close(saved)
        state = vtk_to_numpy(v.GetOutput().GetCellData().GetArray("ValidityState"))
        # (bit 16, "non-convex", flags exactly planar and curved cells alike)
        T.check("nail: VTK's cell validator finds every hexahedron and pyramid valid",
                ((state & ~16) == 0).all(), str(set(state.tolist())))
    # Isoparametric: every node is the body's point at its (u, v, w).
    u, v, w = (arr(g, "point", k) for k in ("u", "v", "w"))
    pts = vtk_to_numpy(g.GetPoints().GetData())
    step = max(1, len(u) // 400)
    sel = range(0, len(u), step)
    lines = "".join(f"{u[i]!r} {v[i]!r} {w[i]!r}\n" for i in sel)
    rc, out_eval, err = T.run(["--eval", path], stdin=lines)
    got = np.array([[float(x) for x in ln.split()] for ln in out_eval.splitlines()])
    want = pts[list(sel)]
    scale_ = np.abs(pts).max() or 1.0
    T.check(f"{ex}: {len(want)} nodes at --eval of their (u, v, w) point data",
            rc == 0 and got.shape == want.shape and np.abs(got - want).max() < 1e-8 * scale_,
            err)
    # The cell data body and the point data det_j are there.
    T.check(f"{ex}: cell data body = 0, point data det_j > 0 away from collapses",
            (arr(g, "cell", "body") == 0).all() and (arr(g, "point", "det_j") >= -1e-12).all())

# ---- --resolution NU,NV,NW and hex27 node count
cube = model([box([0, 0, 0], [1, 2, 3], "block")], "block.json")
rc, j, err = info(["--volume-mesh", "--resolution", "2,3,4", "--element", "hex27", cube])
vmi = j and j["bodies"][0]["volume_mesh"]
T.check("--resolution 2,3,4 --element hex27: 24 cells, 5*7*9 nodes, element hex27",
        rc == 0 and vmi and vmi["cells"] == 24 and vmi["nodes"] == 315 and
        vmi["element"] == "hex27" and abs(vmi["min_scaled_jacobian"] - 1) < 1e-12, f"{vmi} {err}")

# ---- the folded model: refused, untouched; --allow-inverted writes it
fold = os.path.join(T.data, "csg", "fold.json")
keep = os.path.join(work, "keep.vtk")
with open(keep, "wb") as f:
    f.write(b"keep me\n")
before = sorted(os.listdir(work))
rc, out, err = T.run(["-o", keep, fold])
with open(keep, "rb") as f:
    same = f.read() == b"keep me\n"
T.check("folded body: exit 3, names the body, the cell's (u, v, w) and --allow-inverted; "
        "output untouched, nothing else written",
        rc == 3 and "'fold'" in err and "inverted" in err and "(u, v, w)" in err and
        "--allow-inverted" in err and same and sorted(os.listdir(work)) == before, err)
rc, out, err = T.run(["--allow-inverted", "-o", keep, fold])
g = read_vtk(keep)
T.check("--allow-inverted: the folded body is written, with cells of scaled Jacobian <= 0",
        rc == 0 and (arr(g, "cell", "scaled_jacobian") <= 0).any(), err)
rc, j, err = info(["--volume-mesh", fold])
vmi = j and j["bodies"][0]["volume_mesh"]
T.check("--info --volume-mesh on the folded body reports the inverted cells (exit 0)",
        rc == 0 and vmi and vmi["inverted"] > 0 and vmi["min_scaled_jacobian"] <= 0, err)

# ---- a left-handed body: mirrored cells, negative det_j
left = model([{"type": "body0", "name": "lefty",
               "corners": [[1 - (i >> 2 & 1), i >> 1 & 1, i & 1] for i in range(8)]}],
             "left.json")
out = os.path.join(work, "left.vtk")
rc, _, err = T.run(["--resolution", "2", "-o", out, left])
g = read_vtk(out)
T.check("left-handed body: VTK's scaled Jacobian 1 on every cell, det_j = -1 at every node",
        rc == 0 and np.allclose(vtk_quality(g), 1) and np.allclose(arr(g, "point", "det_j"), -1),
        err)

# ---- conformal bodies; overlap and mismatched lattices refused
two = model([box([0, 0, 0], [1, 1, 1], "a"), box([1, 0, 0], [3, 1, 1], "b")], "two.json")
out = os.path.join(work, "two.vtk")
rc, _, err = T.run(["--resolution", "2", "-o", out, two])
g = read_vtk(out) if rc == 0 else None
T.check("two boxes sharing a face: one mesh of 16 cells, the shared face's 9 nodes once "
        "(45 nodes), cell data body 0 and 1",
        g is not None and g.GetNumberOfCells() == 16 and g.GetNumberOfPoints() == 45 and
        sorted(set(arr(g, "cell", "body").tolist())) == [0, 1], err)
out = os.path.join(work, "twoadapt.vtk")
rc, _, err = T.run(["-o", out, two])
g = read_vtk(out) if rc == 0 else None
# a is 1 long, b 2: the sampler gives b more intervals along x, and the
# shared face x = 1 one lattice in y and z: every node of a's side x = 1
# is one of b's (found by position in the file).
if g is not None:
    pts = vtk_to_numpy(g.GetPoints().GetData())
    body = arr(g, "cell", "body")
    side = {0: set(), 1: set()}
    for c in range(g.GetNumberOfCells()):
        ids = g.GetCell(c).GetPointIds()
        for k in range(ids.GetNumberOfIds()):
            p = ids.GetId(k)
            if abs(pts[p][0] - 1) < 1e-12:
                side[int(body[c])].add(p)
    ok = side[0] and side[0] == side[1] and \
        len({tuple(np.round(pts[p], 12)) for p in side[0]}) == len(side[0])
else:
    ok = False
T.check("two boxes on lattices sampled to the tolerance: the shared face's nodes are the "
        "same nodes from both sides, each once", ok, err)
# --info "interfaces": a is 1 long, b 2: across x = 1 the cross derivatives
# are 1 and 2 (c1_defect 1/2), parallel (g1_angle 0).
rc, j, err = info([two])
itf = j and j.get("interfaces")
T.check("--info interfaces: the shared face a.u1 / b.u0, c1_defect 0.5, g1_angle 0",
        rc == 0 and itf and len(itf) == 1 and itf[0]["bodies"] == ["a", "b"] and
        itf[0]["faces"] == ["u1", "u0"] and abs(itf[0]["c1_defect"] - 0.5) < 1e-12 and
        itf[0]["g1_angle"] < 1e-9, f"{itf} {err}")
over = model([box([0, 0, 0], [1, 1, 1], "a"), box([0.5, 0, 0], [2, 1, 1], "b")], "over.json")
rc, _, err = T.run(["--resolution", "2", "-o", os.path.join(work, "over.vtk"), over])
T.check("overlapping bodies: exit 3 naming both, nothing written",
        rc == 3 and "'a' and 'b'" in err and "nothing was written" in err and
        not os.path.exists(os.path.join(work, "over.vtk")), err)
rc, _, err = T.run(["--resolution", "2", "--body", "b", "-o", os.path.join(work, "b.vtk"), over])
T.check("--body b of the overlapping model: that body alone is meshed", rc == 0, err)

# ---- the cell limit refuses at once
rc, _, err = T.run(["--resolution", "1000", "-o", os.path.join(work, "big.vtk"), cube])
T.check("10^9 cells: refused at once naming the limit (exit 3)",
        rc == 3 and "limit" in err and not os.path.exists(os.path.join(work, "big.vtk")), err)

# ---- --info -o FILE.vtk reports and writes
out = os.path.join(work, "info.vtk")
rc, o2, err = T.run(["--info", "--no-solid", "--resolution", "2", "-o", out, cube])
T.check("--info -o FILE.vtk: the report with volume_mesh, and the file",
        rc == 0 and '"volume_mesh"' in o2 and os.path.exists(out), err)

T.finish()
