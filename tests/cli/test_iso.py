#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Isoparametric surfaces (coons_model_iso_surfaces) read by other programs,
written by tests/tools/iso_sample.c until coons2stl has --iso:

- VTK's vtkXMLUnstructuredGridReader reads the surface .vtu without error:
  point data u, v, w (Float64), cell data part (Int32), only triangles
  (cell type 5), the triangle count of a fixed lattice (2 N^2 per surface,
  12 N^2 per boundary), every point at the body map of its (u, v, w)
  computed by the independent Python evaluator examples/coons_ref.py,
  every point of a surface at the requested value, every point of a
  boundary part on a face of the parameter cube, no zero-area triangle
  where the body collapses (the nail's tip, the cylinder's axis), and each
  triangle's normal along +d F/d(direction) times sign(det J) (complex-step
  derivatives of the reference);
- the real `openscad`: every surface module alone (`use <f.scad>` and a
  call) exports an STL with the surface's triangle count, the boundary
  module exports a closed solid with positive volume, the model module
  calls the boundary with `%`, and `xvfb-run -a openscad --preview` writes
  a PNG (read back by VTK's vtkPNGReader: the right size, not blank).

Usage: test_iso.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import clitest  # noqa: E402

T = clitest.Runner(__doc__)
sys.path.insert(0, os.path.join(T.src, "examples"))
import coons_ref  # noqa: E402

try:
    import vtk
except ImportError as exc:  # a missing reader is a failure, not a skip
    T.check("VTK can be imported", False, str(exc))
    T.finish()

SAMPLE = os.path.join(T.build, "tests", "iso_sample")
EX = os.path.join(T.src, "examples")
REQ = ["u=0.25,0.5", "w=0", "v=1"]
REQ_LIST = [(0, 0.25), (0, 0.5), (2, 0.0), (1, 1.0)]


class Errors(object):
    """Collects VTK error events of a reader."""

    def __init__(self, obj):
        self.seen = []
        obj.AddObserver("ErrorEvent", self)
        obj.AddObserver("WarningEvent", self)

    def __call__(self, caller, event):
        self.seen.append(event)


def sample(model, out, *args):
    p = subprocess.run([SAMPLE, model, out] + list(args), stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True, timeout=300)
    return p.returncode, p.stderr


def read_vtu(path):
    r = vtk.vtkXMLUnstructuredGridReader()
    errs = Errors(r)
    r.SetFileName(path)
    r.Update()
    return r.GetOutput(), errs.seen


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def check_vtu(name, model_path, args, boundary, resolution, collapsed):
    model = json.load(open(model_path))
    bodies = model["bodies"]
    scale = coons_ref.control_diagonal(model) or 1.0
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "iso.vtu")
        rc, err = sample(model_path, out, *args)
        if not T.check(f"{name}: iso_sample writes the .vtu", rc == 0, err):
            return
        g, errs = read_vtu(out)
    T.check(f"{name}: VTK reads it without errors or warnings", not errs, str(errs))
    pd, cd = g.GetPointData(), g.GetCellData()
    arrays = {}
    for nm in ("u", "v", "w"):
        a = pd.GetArray(nm)
        ok = a is not None and a.GetDataType() == vtk.VTK_DOUBLE and a.GetNumberOfComponents() == 1
        T.check(f"{name}: point data {nm} is Float64", ok)
        if not ok:
            return
        arrays[nm] = a
    part = cd.GetArray("part")
    T.check(f"{name}: cell data part is Int32",
            part is not None and part.GetDataType() == vtk.VTK_INT)
    if part is None:
        return
    nc = g.GetNumberOfCells()
    T.check(f"{name}: only triangles", nc > 0 and all(g.GetCellType(c) == vtk.VTK_TRIANGLE
                                                      for c in range(nc)))
    per_body = len(REQ_LIST) + (1 if boundary else 0)
    nparts = per_body * len(bodies)
    counts = [0] * nparts
    cells_of = [[] for _ in range(nparts)]
    for c in range(nc):
        p = int(part.GetValue(c))
        if 0 <= p < nparts:
            counts[p] += 1
            cells_of[p].append(c)
    T.check(f"{name}: {nparts} parts, cells in part order",
            sum(counts) == nc and all(part.GetValue(c) <= part.GetValue(c + 1)
                                      for c in range(nc - 1)), str(counts))
    if resolution:
        n = resolution
        want = []
        for _ in bodies:
            want += ([12 * n * n] if boundary else []) + [2 * n * n] * len(REQ_LIST)
        # A boundary with flat faces (meshed from their boundary polygon,
        # src/mesh/flat.c) has fewer: then it must be a closed genus-0
        # shell by Euler's formula, T = 2 V - 4 (V its distinct points).
        for p in range(nparts):
            if boundary and p % per_body == 0 and counts[p] < want[p]:
                nv = len({g.GetCell(c).GetPointIds().GetId(r) for c in cells_of[p]
                          for r in range(3)})
                if counts[p] == 2 * nv - 4:
                    want[p] = counts[p]
        T.check(f"{name}: triangle counts of the {n}-interval lattice", counts == want,
                f"{counts} != {want}")
    pts = g.GetPoints()
    uvw = [(arrays["u"].GetValue(i), arrays["v"].GetValue(i), arrays["w"].GetValue(i))
           for i in range(g.GetNumberOfPoints())]
    worst, bad_value, bad_face, bad_area, bad_normal, checked = 0.0, [], [], 0, [], 0
    seen_pts = set()
    for p in range(nparts):
        b = bodies[p // per_body]
        k = p % per_body - (1 if boundary else 0)
        for c in cells_of[p]:
            ids = g.GetCell(c).GetPointIds()
            corner = [ids.GetId(r) for r in range(3)]
            xs = [pts.GetPoint(i) for i in corner]
            for i in corner:
                q = uvw[i]
                if i not in seen_pts:
                    seen_pts.add(i)
                    x = coons_ref.realv(coons_ref.body_eval(b, *q))
                    worst = max(worst, coons_ref.dist(x, pts.GetPoint(i)) / scale)
                if k >= 0:
                    d, val = REQ_LIST[k]
                    if q[d] != val:
                        bad_value.append((p, q))
                elif not any(t in (0.0, 1.0) for t in q):
                    bad_face.append((p, q))
            e1 = [xs[1][r] - xs[0][r] for r in range(3)]
            e2 = [xs[2][r] - xs[0][r] for r in range(3)]
            nrm = cross(e1, e2)
            if dot(nrm, nrm) == 0.0:
                bad_area += 1
            if k < 0:
                continue
            qs = [uvw[i] for i in corner]
            if any(abs(qs[r][a] - qs[(r + 1) % 3][a]) > 0.5 for r in range(3) for a in range(3)):
                continue  # across a glued seam: the centroid is elsewhere
            qc = [sum(q[a] for q in qs) / 3 for a in range(3)]
            d = REQ_LIST[k][0]
            if qc[d] in (0.0, 1.0):
                qc[d] = min(max(qc[d], 1e-9), 1 - 1e-9)
            def f(z, a=d):
                qq = list(qc)
                qq[a] = z
                return coons_ref.body_eval(b, *qq)
            fd = coons_ref.deriv(f, qc[d])
            det = coons_ref.body_jacobian_det(b, *qc)
            checked += 1
            if not dot(nrm, fd) * (1 if det > 0 else -1) > 0:
                bad_normal.append((p, c))
    T.check(f"{name}: every point is the reference body map at its (u, v, w)",
            worst < 1e-9, f"worst relative distance {worst:.3g}")
    T.check(f"{name}: every surface point lies at its requested value", not bad_value,
            str(bad_value[:3]))
    if boundary:
        T.check(f"{name}: every boundary point lies on a face of the parameter cube",
                not bad_face, str(bad_face[:3]))
    T.check(f"{name}: no zero-area triangle" + (" at the collapse" if collapsed else ""),
            bad_area == 0, f"{bad_area} triangles")
    T.check(f"{name}: normals along +F_d sign(det J) ({checked} triangles)",
            checked > 0 and not bad_normal, str(bad_normal[:5]))


def read_stl(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:5] == b"solid" and b"facet" in data[:1024]:
        tris, cur = [], []
        for line in data.decode("ascii").splitlines():
            w = line.split()
            if w and w[0] == "vertex":
                cur.extend(float(x) for x in w[1:4])
                if len(cur) == 9:
                    tris.append(tuple(cur))
                    cur = []
        return tris
    (n,) = struct.unpack_from("<I", data, 80)
    return [struct.unpack_from("<12f", data, 84 + 50 * i)[3:] for i in range(n)]


def volume(tris):
    v = 0.0
    for t in tris:
        ax, ay, az, bx, by, bz, cx, cy, cz = t
        v += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
    return v / 6.0


def check_openscad():
    oscad = shutil.which("openscad")
    xvfb = shutil.which("xvfb-run")
    if not T.check("openscad and xvfb-run are installed", oscad and xvfb):
        return
    model = os.path.join(EX, "body1-density.json")
    with tempfile.TemporaryDirectory() as tmp:
        scad, vtu = os.path.join(tmp, "iso.scad"), os.path.join(tmp, "iso.vtu")
        args = ["-b", "u=0.25,0.5,0.75", "w=0.5"]
        rc1, e1 = sample(model, scad, *args)
        rc2, e2 = sample(model, vtu, *args)
        if not T.check("iso_sample writes the .scad and the .vtu", rc1 == 0 and rc2 == 0, e1 + e2):
            return
        text = open(scad).read()
        mods = re.findall(r"^module (\w+)\(\) \{$", text, re.M)
        want = ["coons_model_" + p for p in ["fig4", "fig4_u_0_25", "fig4_u_0_5", "fig4_u_0_75",
                                             "fig4_w_0_5"]] + ["coons_model"]
        T.check("a module per part, named MODEL_BODY_u_0_25 ...", mods == want, str(mods))
        T.check("the model module calls the boundary with %",
                "module coons_model() {\n  %coons_model_fig4();\n  coons_model_fig4_u_0_25();\n"
                in text)
        g, errs = read_vtu(vtu)
        part = g.GetCellData().GetArray("part")
        counts = [0] * len(want[:-1])
        for c in range(g.GetNumberOfCells()):
            counts[int(part.GetValue(c))] += 1
        for i, mod in enumerate(want[:-1]):
            use = os.path.join(tmp, f"use_{mod}.scad")
            with open(use, "w") as f:
                f.write(f"use <iso.scad>\n{mod}();\n")
            stl = os.path.join(tmp, f"{mod}.stl")
            p = subprocess.run([oscad, "-o", stl, use], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, timeout=300, cwd=tmp)
            ok = p.returncode == 0 and "ERROR" not in p.stderr and "WARNING" not in p.stderr \
                and os.path.exists(stl)
            if not T.check(f"openscad -o {mod}.stl", ok, p.stderr[-600:]):
                continue
            tris = read_stl(stl)
            if i == 0:
                T.check(f"{mod}: the boundary is a solid ({len(tris)} triangles)",
                        volume(tris) > 0 and len(tris) == counts[0], f"{volume(tris)}")
            else:
                T.check(f"{mod}: {counts[i]} triangles, as in the .vtu", len(tris) == counts[i],
                        f"{len(tris)}")
        png = os.path.join(tmp, "iso.png")
        p = subprocess.run([xvfb, "-a", oscad, "--preview", "--imgsize=400,300", "--autocenter",
                            "--viewall", "-o", png, scad], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True, timeout=300, cwd=tmp)
        ok = p.returncode == 0 and os.path.exists(png) and os.path.getsize(png) > 0
        if not T.check("xvfb-run -a openscad --preview writes a PNG", ok, p.stderr[-600:]):
            return
        r = vtk.vtkPNGReader()
        r.SetFileName(png)
        r.Update()
        img = r.GetOutput()
        dims = img.GetDimensions()
        sc = img.GetPointData().GetScalars()
        colours = set(tuple(int(sc.GetComponent(i, c)) for c in range(min(3, sc.GetNumberOfComponents())))
                      for i in range(0, sc.GetNumberOfTuples(), 7))
        T.check("the PNG is 400 x 300 and not blank", dims[0] == 400 and dims[1] == 300
                and len(colours) > 20, f"{dims}, {len(colours)} colours")


if not os.path.exists(SAMPLE):
    T.check("tests/iso_sample is built", False, SAMPLE)
    T.finish()
for fname, res, collapsed in (("body-blend-cubic.json", 6, False),
                              ("volume-bezier.json", 5, False),
                              ("volume-nurbs.json", 6, True),
                              ("nail.json", 4, True)):
    for bnd in (True, False):
        args = (["-b"] if bnd else []) + ["-r", str(res)] + REQ
        check_vtu(f"{fname}{' + boundary' if bnd else ''}", os.path.join(EX, fname), args, bnd,
                  None if collapsed else res, collapsed)
check_vtu("body1-density.json, adaptive", os.path.join(EX, "body1-density.json"),
          ["-b"] + REQ, True, None, False)
check_openscad()
T.finish()
