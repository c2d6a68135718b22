#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The .vtu writers (formats vtu and vtu-ascii) read by VTK itself and by
meshio, on files of known geometry (tests/tools/vm_sample.c: a 2x2x2-cell
lattice of (r, s, t) in [0,1]^3 under a known map) for every element
(hex8, hex20, hex27) and map (quad, apex, pyramid):

- VTK's vtkXMLUnstructuredGridReader: counts, cell types (12 hexahedron,
  13 wedge, 14 pyramid for hex8 cells at the collapsed face; 25 and 29 for
  hex20 and hex27, degenerate where collapsed), the point data u, v, w and
  cell data body, scaled_jacobian with their names and VTK types; every
  node at the map of its (u, v, w);
- VTK's own cells evaluated at interior parametric points
  (vtkCell.EvaluateLocation) against the exact map: hex27 interpolates
  the quadratic map exactly, hex20 too (the quad map x = r + 0.2 s^2,
  y = s + 0.1 r t, z = t + 0.15 r^2 lies in the serendipity space), hex8
  gives the trilinear interpolant of its corners; the apex and pyramid
  maps are trilinear, so every element reproduces them, and a point of a
  wedge or a pyramid maps back (inverse map) into its cell's parameter
  box. This checks the node permutation against VTK's definition of its
  cells, not against our writer;
- VTK's vtkCellValidator (faces oriented outward: the wedge and pyramid
  orientation) and vtkMeshQuality's hexahedron scaled Jacobian > 0 (of the
  corners of quadratic cells), for every cell that is not degenerate;
- meshio.read: the same points, the same node coordinates cell by cell,
  the same point and cell data (x = map(u, v, w));
- both encodings give the same data, bit for bit.

And coons2stl's own .vtu files (coons2stl EX -o x.vtu --resolution 4, hex8
and hex27) of every example but the two whose bodies overlap (chair.json,
union-three-bodies.json; the control lattices included), read by VTK and meshio: the point data u, v, w, det_j
and cell data body, scaled_jacobian; a sample of nodes at --eval's point of
their (u, v, w); vtkCellValidator; and the sum of the hex27 cells' volumes
(3x3x3 Gauss quadrature of the isoparametric cell, from the nodes, with
the triquadratic basis at VTK's parametric node positions) within 1e-4
relative of --info's exact volume at --resolution 6 on body1-density.json
and volume-nurbs.json.

Usage: test_volume_vtu.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)

try:
    import numpy as np
    import meshio
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
except ImportError as exc:  # a missing reader is a failure, not a skip
    T.check("numpy, meshio and VTK can be imported", False, str(exc))
    T.finish()

SAMPLE = os.path.join(T.build, "tests", "vm_sample")
ELEMENTS = ("hex8", "hex20", "hex27")
MAPS = ("quad", "apex", "pyramid")
FORMATS = ("vtu", "vtu-ascii")


def exact(which, q):
    """The sample's maps (vm_sample.c), q = (..., 3) parameters."""
    q = np.asarray(q, dtype=float)
    r, s, t = q[..., 0], q[..., 1], q[..., 2]
    if which == "apex":
        return np.stack([r, r * s, t], axis=-1)
    if which == "pyramid":
        return np.stack([r * (s - 0.5), r * (t - 0.5), r], axis=-1)
    return np.stack([r + 0.2 * s * s, s + 0.1 * r * t, t + 0.15 * r * r], axis=-1)


def inverse(which, x):
    """Parameters of a point of the apex or pyramid body (x inside)."""
    if which == "apex":
        return np.array([x[0], x[1] / x[0], x[2]])
    return np.array([x[2], x[0] / x[2] + 0.5, x[1] / x[2] + 0.5])


def expected_nodes(element, which):
    """Distinct images of the half-step lattice points the element uses."""
    pts = set()
    for i in range(5):
        for j in range(5):
            for k in range(5):
                odd = (i % 2) + (j % 2) + (k % 2)
                if element == "hex8" and odd > 0 or element == "hex20" and odd > 1:
                    continue
                x = exact(which, [i / 4, j / 4, k / 4])
                pts.add(tuple(np.round(x, 12) + 0.0))
    return len(pts)


def expected_types(element, which):
    """Cells in vm_sample's order: part lo (r < 1/2) first, then hi."""
    if element == "hex8":
        lo = {"quad": 12, "apex": 13, "pyramid": 14}[which]
        return [lo] * 4 + [12] * 4
    return [25 if element == "hex20" else 29] * 8


VTK_TYPE_NAME = {vtk.VTK_DOUBLE: "Float64", vtk.VTK_INT: "Int32"}
MESHIO_TYPE = {12: "hexahedron", 13: "wedge", 14: "pyramid", 25: "hexahedron20",
               29: "hexahedron27"}


def read_vtk(path):
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    return r.GetErrorCode(), r.GetOutput()


def arrays(data):
    out = []
    for i in range(data.GetNumberOfArrays()):
        a = data.GetArray(i)
        out.append((a.GetName(), VTK_TYPE_NAME.get(a.GetDataType(), a.GetDataTypeAsString()),
                    vtk_to_numpy(a).copy()))
    return out


def trilinear(corner_x, p):
    """Trilinear interpolation of the 8 box corners corner_x[a][b][c]."""
    x = np.zeros(3)
    for a in (0, 1):
        for b in (0, 1):
            for c in (0, 1):
                w = ((p[0] if a else 1 - p[0]) * (p[1] if b else 1 - p[1]) *
                     (p[2] if c else 1 - p[2]))
                x += w * corner_x[a][b][c]
    return x


# Interior parametric points of VTK's cells: hexahedra [0,1]^3, wedges
# r, s >= 0, r + s <= 1, t in [0,1]; pyramids base [0,1]^2, apex t = 1.
HEX_PC = [(0.5, 0.5, 0.5), (0.2, 0.7, 0.4), (0.8, 0.3, 0.9), (0.1, 0.1, 0.1),
          (0.9, 0.6, 0.25), (0.35, 0.85, 0.65)]
WEDGE_PC = [(1 / 3, 1 / 3, 0.5), (0.2, 0.6, 0.25), (0.6, 0.2, 0.75), (0.1, 0.1, 0.9)]
PYRAMID_PC = [(0.5, 0.5, 0.3), (0.25, 0.7, 0.5), (0.8, 0.3, 0.2), (0.5, 0.5, 0.9)]


def evaluate(cell, pc):
    x = [0.0, 0.0, 0.0]
    weights = [0.0] * cell.GetNumberOfPoints()
    sub = vtk.reference(0)
    cell.EvaluateLocation(sub, list(pc), x, weights)
    return np.array(x)


def check_cells(name, g, element, which, uvw):
    """EvaluateLocation of every cell against the exact map."""
    worst = 0.0
    outside = 0
    for c in range(g.GetNumberOfCells()):
        cell = g.GetCell(c)
        ids = [cell.GetPointId(k) for k in range(cell.GetNumberOfPoints())]
        ctype = cell.GetCellType()
        if ctype in (12, 25, 29):
            # The parameter box from VTK's corners 0 (0,0,0), 1 (1,0,0),
            # 2 (1,1,0), 5 (1,0,1): corners 1, 2, 5 are on the side r > 0,
            # which never collapses (merged nodes keep one node's u, v, w).
            lo = np.array([uvw[ids[0]][0], uvw[ids[1]][1], uvw[ids[1]][2]])
            hi = np.array([uvw[ids[1]][0], uvw[ids[2]][1], uvw[ids[5]][2]])
            if np.any(hi <= lo):
                outside += 1
                continue
            corners = [[[exact(which, lo + np.array([a, b, cc]) * (hi - lo))
                         for cc in (0, 1)] for b in (0, 1)] for a in (0, 1)]
            for pc in HEX_PC:
                got = evaluate(cell, pc)
                if ctype == 12:
                    want = trilinear(corners, pc)
                else:
                    want = exact(which, lo + np.array(pc) * (hi - lo))
                worst = max(worst, float(np.max(np.abs(got - want))))
        else:
            # A wedge or a pyramid: the point maps back into the cell's box.
            q = np.array([uvw[i] for i in ids])
            real = q[:, 0] > 0  # nodes off the collapsed face carry their (v, w)
            lo = np.array([0.0, q[real, 1].min(), q[:, 2].min() if which == "apex"
                           else q[real, 2].min()])
            hi = np.array([q[:, 0].max(), q[real, 1].max(), q[:, 2].max() if which == "apex"
                           else q[real, 2].max()])
            for pc in WEDGE_PC if ctype == 13 else PYRAMID_PC:
                got = evaluate(cell, pc)
                p = inverse(which, got)
                if np.any(p < lo - 1e-12) or np.any(p > hi + 1e-12):
                    outside += 1
                worst = max(worst, float(np.max(np.abs(exact(which, p) - got))))
    T.check(f"{name}: VTK's cells at interior points are on the map (worst {worst:.1e})",
            worst < 1e-12 and outside == 0, f"worst {worst}, {outside} points outside")


def degenerate(cell):
    n = cell.GetNumberOfPoints()
    corners = [cell.GetPointId(k) for k in range(min(n, 8))]
    return len(set(corners)) < len(corners)


def check_quality(name, g):
    """vtkCellValidator and the scaled Jacobian of every non-degenerate cell."""
    v = vtk.vtkCellValidator()
    v.SetInputData(g)
    # It prints every cell it finds invalid to standard output (C++
    # std::cout): keep that out of the test's report.
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
    # Linear hexahedra of the corners (shared corner order), for
    # vtkMeshQuality, which in VTK 9.1 measures only linear hexahedra.
    lin = vtk.vtkUnstructuredGrid()
    lin.SetPoints(g.GetPoints())
    kept = []
    bad = []
    for c in range(g.GetNumberOfCells()):
        cell = g.GetCell(c)
        if degenerate(cell):
            continue
        # 32: faces oriented incorrectly (an inverted or misordered cell).
        # 16 (non-convex) is not counted: VTK 9.1's convexity test flags
        # cells with exactly coplanar nodes (these frusta and pyramids).
        if int(state[c]) & ~16:
            bad.append((c, int(state[c])))
        if cell.GetCellType() in (12, 25, 29):
            ids = vtk.vtkIdList()
            for k in range(8):
                ids.InsertNextId(cell.GetPointId(k))
            lin.InsertNextCell(12, ids)
            kept.append(c)
    T.check(f"{name}: vtkCellValidator finds every non-degenerate cell valid", not bad, str(bad))
    q = vtk.vtkMeshQuality()
    q.SetInputData(lin)
    q.SetHexQualityMeasureToScaledJacobian()
    q.Update()
    sj = vtk_to_numpy(q.GetOutput().GetCellData().GetArray("Quality"))
    T.check(f"{name}: VTK's scaled Jacobian > 0 for {len(kept)} hexahedra",
            len(kept) > 0 and bool(np.all(sj > 0)), str(sj))


def check_vtk(path, name, element, which):
    rc, g = read_vtk(path)
    if not T.check(f"{name}: VTK reads it", rc == 0 and g.GetNumberOfPoints() > 0, f"error {rc}"):
        return None
    types = [g.GetCellType(c) for c in range(g.GetNumberOfCells())]
    T.check(f"{name}: {len(types)} cells of VTK types {sorted(set(types))}",
            types == expected_types(element, which), str(types))
    nn = expected_nodes(element, which)
    T.check(f"{name}: {nn} nodes", g.GetNumberOfPoints() == nn, str(g.GetNumberOfPoints()))
    pd, cd = arrays(g.GetPointData()), arrays(g.GetCellData())
    T.check(f"{name}: point data u, v, w (Float64)",
            [(a, t) for a, t, _ in pd] == [("u", "Float64"), ("v", "Float64"), ("w", "Float64")],
            str([(a, t) for a, t, _ in pd]))
    T.check(f"{name}: cell data body (Int32), scaled_jacobian (Float64)",
            [(a, t) for a, t, _ in cd] == [("body", "Int32"), ("scaled_jacobian", "Float64")],
            str([(a, t) for a, t, _ in cd]))
    x = vtk_to_numpy(g.GetPoints().GetData())
    uvw = np.stack([a for _, _, a in pd[:3]], axis=1)
    err = float(np.max(np.abs(exact(which, uvw) - x)))
    T.check(f"{name}: every node at the map of its (u, v, w)", err < 1e-15, f"{err}")
    body = cd[0][2]
    T.check(f"{name}: body is 0 for the 4 cells of part lo, then 1",
            list(body) == [0] * 4 + [1] * 4, str(body))
    check_cells(name, g, element, which, uvw)
    check_quality(name, g)
    return g


def cell_sets(g):
    pts = vtk_to_numpy(g.GetPoints().GetData())
    out = []
    for c in range(g.GetNumberOfCells()):
        cell = g.GetCell(c)
        out.append(sorted(tuple(pts[cell.GetPointId(k)]) for k in range(cell.GetNumberOfPoints())))
    return out


def check_meshio(path, name, which, g):
    try:
        m = meshio.read(path)
    except Exception as exc:  # noqa: BLE001 - any failure to read is the finding
        T.check(f"{name}: meshio reads it", False, repr(exc))
        return
    T.check(f"{name}: meshio reads it", True)
    x = vtk_to_numpy(g.GetPoints().GetData())
    T.check(f"{name}: meshio's points are VTK's", m.points.shape == x.shape and
            np.array_equal(m.points, x))
    blocks = [(b.type, b.data) for b in m.cells]
    types = [t for t, d in blocks for _ in d]
    want = [MESHIO_TYPE[g.GetCellType(c)] for c in range(g.GetNumberOfCells())]
    T.check(f"{name}: meshio's cell types", types == want, f"{types} vs {want}")
    mine = [sorted(tuple(m.points[i]) for i in row) for _, d in blocks for row in d]
    T.check(f"{name}: meshio's cells have VTK's node coordinates", mine == cell_sets(g))
    pd = m.point_data
    ok = list(pd) == ["u", "v", "w"] and all(pd[k].dtype == np.float64 for k in pd)
    T.check(f"{name}: meshio's point data u, v, w are Float64", ok, str(list(pd)))
    if ok:
        uvw = np.stack([pd["u"], pd["v"], pd["w"]], axis=1)
        err = float(np.max(np.abs(exact(which, uvw) - m.points)))
        T.check(f"{name}: meshio: points = map(u, v, w)", err < 1e-15, str(err))
    cd = m.cell_data
    ok = list(cd) == ["body", "scaled_jacobian"]
    if ok:
        body = np.concatenate(cd["body"])
        sj = np.concatenate(cd["scaled_jacobian"])
        ok = (body.dtype == np.int32 and sj.dtype == np.float64 and
              np.array_equal(body, vtk_to_numpy(g.GetCellData().GetArray("body"))) and
              np.array_equal(sj, vtk_to_numpy(g.GetCellData().GetArray("scaled_jacobian"))))
    T.check(f"{name}: meshio's cell data body (int32), scaled_jacobian (float64)", ok,
            str({k: [a.dtype for a in v] for k, v in cd.items()}))


def same_data(a, b):
    pa, pb = vtk_to_numpy(a.GetPoints().GetData()), vtk_to_numpy(b.GetPoints().GetData())
    if not np.array_equal(pa.view(np.uint64), pb.view(np.uint64)):
        return False
    ca = vtk_to_numpy(a.GetCells().GetConnectivityArray())
    cb = vtk_to_numpy(b.GetCells().GetConnectivityArray())
    if not np.array_equal(ca, cb):
        return False
    for da, db in ((a.GetPointData(), b.GetPointData()), (a.GetCellData(), b.GetCellData())):
        for (n1, t1, v1), (n2, t2, v2) in zip(arrays(da), arrays(db)):
            if n1 != n2 or t1 != t2 or v1.tobytes() != v2.tobytes():
                return False
    return True


# ---- coons2stl's .vtu files ---------------------------------------------------

# vtkTriQuadraticHexahedron's parametric node positions (VTK's class
# documentation; the first 8 and 20 are vtkHexahedron's and
# vtkQuadraticHexahedron's).
VTK_PARAM27 = np.array([
    (0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1),
    (.5, 0, 0), (1, .5, 0), (.5, 1, 0), (0, .5, 0), (.5, 0, 1), (1, .5, 1), (.5, 1, 1),
    (0, .5, 1), (0, 0, .5), (1, 0, .5), (1, 1, .5), (0, 1, .5), (0, .5, .5), (1, .5, .5),
    (.5, 0, .5), (.5, 1, .5), (.5, .5, 0), (.5, .5, 1), (.5, .5, .5)])


def lagrange2(node, x):
    """The quadratic Lagrange polynomial on nodes 0, 1/2, 1 that is 1 at
    `node`, and its derivative, at x."""
    if node == 0:
        return 2 * (x - 0.5) * (x - 1), 4 * x - 3
    if node == 1:
        return 2 * x * (x - 0.5), 4 * x - 1
    return 4 * x * (1 - x), 4 - 8 * x


def gauss_derivatives():
    """3x3x3 Gauss points on [0,1]^3: weights (27,) and the triquadratic
    basis' gradients (27 points, 27 nodes, 3)."""
    g = [0.5 - 0.5 * (0.6 ** 0.5), 0.5, 0.5 + 0.5 * (0.6 ** 0.5)]
    gw = [5 / 18, 8 / 18, 5 / 18]
    w, d = [], []
    for a in range(3):
        for b in range(3):
            for c in range(3):
                x = (g[a], g[b], g[c])
                w.append(gw[a] * gw[b] * gw[c])
                rows = []
                for node in VTK_PARAM27:
                    l = [lagrange2(node[i], x[i]) for i in range(3)]
                    rows.append([l[0][1] * l[1][0] * l[2][0], l[0][0] * l[1][1] * l[2][0],
                                 l[0][0] * l[1][0] * l[2][1]])
                d.append(rows)
    return np.array(w), np.array(d)


GW, GD = gauss_derivatives()


def hex27_volume(nodes):
    """Sum over cells (nodes: (cells, 27, 3), VTK order) of the quadrature
    of det J of the isoparametric cell."""
    jac = np.einsum("cki,gkj->cgij", nodes, GD)
    return float(np.sum(np.linalg.det(jac) * GW))


def cli_info_volume(path):
    rc, out, err = T.run(["--info", "--no-solid", path])
    try:
        return float(json.loads(out)["bodies"][0]["volume"])
    except (ValueError, KeyError, IndexError, TypeError):
        T.check(f"{os.path.basename(path)}: --info gives the volume", False, err)
        return None


def cli_write(tmp, path, element, res):
    out = os.path.join(tmp, f"{os.path.basename(path)}-{element}-{res}.vtu")
    args = [path, "-o", out, "--resolution", str(res)]
    if element != "hex8":
        args += ["--element", element]
    rc, _, err = T.run(args)
    if not T.check(f"coons2stl {os.path.basename(path)} -o x.vtu --resolution {res} "
                   f"--element {element}: written", rc == 0 and os.path.exists(out), err):
        return None
    return out


def check_cli_file(tmp, path, element, nbodies=1):
    ex = os.path.basename(path)
    name = f"coons2stl {ex} {element}"
    out = cli_write(tmp, path, element, 4)
    if out is None:
        return
    rc, g = read_vtk(out)
    if not T.check(f"{name}: VTK reads it", rc == 0 and g.GetNumberOfPoints() > 0, f"error {rc}"):
        return
    types = {g.GetCellType(c) for c in range(g.GetNumberOfCells())}
    allowed = {12, 13, 14} if element == "hex8" else {29}
    # 4^3 cells per body, but cells without volume (fewer than 4 distinct
    # corners: at a body's collapsed corner) are left out.
    T.check(f"{name}: at most {64 * nbodies} cells of VTK types {sorted(types)}",
            56 * nbodies <= g.GetNumberOfCells() <= 64 * nbodies and types <= allowed,
            f"{g.GetNumberOfCells()} {types}")
    pd, cd = arrays(g.GetPointData()), arrays(g.GetCellData())
    T.check(f"{name}: point data u, v, w, det_j (Float64)",
            [(a, t) for a, t, _ in pd] == [(k, "Float64") for k in ("u", "v", "w", "det_j")],
            str([(a, t) for a, t, _ in pd]))
    T.check(f"{name}: cell data body (Int32), scaled_jacobian (Float64)",
            [(a, t) for a, t, _ in cd] == [("body", "Int32"), ("scaled_jacobian", "Float64")],
            str([(a, t) for a, t, _ in cd]))
    x = vtk_to_numpy(g.GetPoints().GetData())
    uvw = np.stack([a for _, _, a in pd[:3]], axis=1)
    # Isoparametric: a sample of nodes at --eval's point of their (u, v, w).
    # (each node with the lowest-numbered body of the cells that use it,
    # whose parameters a node shared by bodies carries: --eval --body k)
    owner = np.full(len(x), 1 << 30, dtype=int)
    body = dict((a, v) for a, _, v in cd)["body"]
    for c in range(g.GetNumberOfCells()):
        ids = g.GetCell(c).GetPointIds()
        for k in range(ids.GetNumberOfIds()):
            owner[ids.GetId(k)] = min(owner[ids.GetId(k)], body[c])
    sel = list(range(0, len(x), max(1, len(x) // 150)))
    got, rc, err = np.zeros((len(sel), 3)), 0, ""
    for k in sorted(set(owner[sel].tolist())):
        mine = [j for j, i in enumerate(sel) if owner[i] == k]
        r, ev, e = T.run(["--eval", "--body", str(k), path],
                         stdin="".join("%r %r %r\n" % tuple(uvw[sel[j]]) for j in mine))
        rc, err = rc or r, err + e
        try:
            got[mine] = np.array([[float(t) for t in ln.split()] for ln in ev.splitlines()])
        except ValueError:
            rc = rc or 1
    scale = float(np.abs(x).max()) or 1.0
    T.check(f"{name}: {len(sel)} nodes at --eval of their (u, v, w) in their body",
            rc == 0 and float(np.abs(got - x[sel]).max()) <= 1e-12 * scale, err)
    if element == "hex8":
        check_quality(name, g)
    try:
        m = meshio.read(out)
    except Exception as exc:  # noqa: BLE001
        T.check(f"{name}: meshio reads it", False, repr(exc))
        return
    same = (np.array_equal(m.points, x) and list(m.point_data) == ["u", "v", "w", "det_j"] and
            all(np.array_equal(m.point_data[k], a) for k, _, a in pd))
    T.check(f"{name}: meshio reads VTK's points and point data", same)
    mine = [sorted(tuple(m.points[i]) for i in row) for b in m.cells for row in b.data]
    T.check(f"{name}: meshio's cells have VTK's node coordinates", mine == cell_sets(g))


def check_cli_volume(tmp, path):
    ex = os.path.basename(path)
    exact_v = cli_info_volume(path)
    if exact_v is None:
        return
    errs = {}
    for res in (4, 6):
        out = cli_write(tmp, path, "hex27", res)
        if out is None:
            return
        rc, g = read_vtk(out)
        conn = vtk_to_numpy(g.GetCells().GetConnectivityArray()).reshape(-1, 27)
        nodes = vtk_to_numpy(g.GetPoints().GetData())[conn]
        errs[res] = abs(hex27_volume(nodes) - exact_v) / abs(exact_v)
    T.check(f"{ex}: hex27 cell volumes sum to --info's volume {exact_v:.10g} "
            f"(relative error {errs[4]:.1e} at --resolution 4, {errs[6]:.1e} at 6)",
            errs[6] < 1e-4 and errs[6] < errs[4], str(errs))


def cli_tests(tmp):
    if not T.check("coons2stl exists", bool(T.bin) and os.access(T.bin, os.X_OK), str(T.bin)):
        return
    # The quadrature itself: the reference cell has volume 1, a stretched
    # and sheared one its determinant.
    a = np.array([[2.0, 0.3, 0.0], [0.0, 1.5, 0.2], [0.1, 0.0, 0.5]])
    T.check("the test's hex27 quadrature: unit cell 1, affine cell det A",
            abs(hex27_volume(VTK_PARAM27[None]) - 1) < 1e-14 and
            abs(hex27_volume((VTK_PARAM27 @ a.T)[None]) - np.linalg.det(a)) < 1e-14)
    ex_dir = os.path.join(T.src, "examples")
    # Every example but the two whose bodies overlap (a union of solids),
    # which are refused: one body, or bodies meeting along whole shared
    # faces, whole edges or at corners (control lattices).
    done = set()
    for ex in sorted(os.listdir(ex_dir)):
        if not ex.endswith(".json"):
            continue
        path = os.path.join(ex_dir, ex)
        rc, _, err = T.run(["--info", "--no-solid", "--volume-mesh", "--resolution", "1", path])
        if rc == 3 and "without sharing" in err and ex in ("chair.json",
                                                          "union-three-bodies.json"):
            print(f"note: {ex}: not conformal ({err.strip()})")
            continue
        with open(path) as f:
            nb = len(json.load(f)["bodies"])
        for element in ("hex8", "hex27"):
            check_cli_file(tmp, path, element, nb)
        done.add(ex)
    for ex in ("nail.json", "spool.json", "body1-density.json", "volume-nurbs.json",
               "lattice-ffd.json", "chair-lattice.json", "lattice-l-bracket.json",
               "lattice-ring.json", "lattice-instanced.json"):
        T.check(f"{ex} is among the examples meshed", ex in done)
    for ex in ("body1-density.json", "volume-nurbs.json"):
        check_cli_volume(tmp, os.path.join(ex_dir, ex))


def main():
    if not T.check("vm_sample exists", os.access(SAMPLE, os.X_OK), SAMPLE):
        T.finish()
    with tempfile.TemporaryDirectory() as tmp:
        for element in ELEMENTS:
            for which in MAPS:
                grids = {}
                for fmt in FORMATS:
                    name = f"{element} {which} {fmt}"
                    path = os.path.join(tmp, f"{element}-{which}-{fmt}.vtu")
                    p = subprocess.run([SAMPLE, path, element, which, fmt],
                                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                    if not T.check(f"{name}: vm_sample writes it", p.returncode == 0, p.stderr):
                        continue
                    with open(path, "rb") as f:
                        head = f.read(4096)
                    T.check(f"{name}: {'appended base64' if fmt == 'vtu' else 'ascii'} data",
                            (b'format="appended"' in head) == (fmt == "vtu") and
                            (b'format="ascii"' in head) == (fmt == "vtu-ascii"))
                    g = check_vtk(path, name, element, which)
                    if g is not None:
                        grids[fmt] = g
                        check_meshio(path, name, which, g)
                if len(grids) == 2:
                    T.check(f"{element} {which}: vtu and vtu-ascii hold the same data",
                            same_data(grids["vtu"], grids["vtu-ascii"]))
        cli_tests(tmp)
    T.finish()


main()
