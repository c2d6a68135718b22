# SPDX-License-Identifier: GPL-3.0-or-later
"""Exact solids (issue 26): coons2stl -o FILE.step / .igs / .brep, read back
by programs other than the writer.

Readers: Open CASCADE's own STEP, IGES and BREP readers, checker and
adaptive volume integration (tests/tools/occt_check.cpp, built here, not
the library), FreeCAD headless (Part.read, isValid, check) and gmsh's OCC
kernel (importShapes). A missing reader fails, never skips.

For every example, the model is written with "operation": "none" (one
solid per body) and checked:
- one valid solid per body, its face count what the body's own evaluation
  (coons2stl --eval) says: 6, less one per collapsed face (an apex: the
  face's 3 x 3 grid is one point), less two per pair of faces that coincide
  (a closed body);
- its volume within 1e-9 relative of coons_body_volume (--info) for
  polynomial faces, 1e-6 for rational ones (or the integral's own error
  estimate when larger), within the fitted faces' deviation times the area
  for fitted ones;
- 1000 boundary points per body (coons2stl --eval on the six faces) within
  1e-9 of the body's size of the read-back faces (the fitted faces: within
  twice their measured deviation);
- FreeCAD finds every solid valid and its check clean; gmsh counts the
  volumes.
The union examples are also written as they are (but the two large
lattices, whose unions take seconds each: chair-lattice, lattice-ffd;
BENCHMARKS.md times those): one valid solid per
connected group of bodies, whose volume agrees with the mesh union's
(coons2stl -o x.stl, with CGAL) within the mesh tolerance times its area.
IGES and BREP read back with the same volumes; AP242 carries its schema;
names, units (inches: Open CASCADE's reader scales to millimetres) and 17
digits are in the file; the library prints nothing; a solid that is not
valid is exit 3 and no file; a coons2stl whose faces have a wrong spline on
purpose (tests/tools/coons2stl_wrong_spline.c) writes a file Open CASCADE
finds valid, and the point check here fails on it.
"""
import json
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402

T = Runner(__doc__)
FREECAD_LIB = "/usr/lib/freecad-python3/lib"
SLOW = {"chair-lattice", "lattice-ffd"}
NPOINTS = 1000


def cache_has(flag):
    try:
        with open(os.path.join(T.build, "CMakeCache.txt")) as f:
            return f"{flag}:BOOL=ON" in f.read()
    except OSError:
        return True


def occt_check(path, points=None, gprop=False):
    """Solids [(faces, valid, volume by BRepGProp (with gprop), volume by
    spans)] and distances of points (x, y, z, a, b)."""
    args = [os.path.join(T.build, "tests", "occt_check"), path] + (["--gprop"] if gprop else [])
    text = None
    if points is not None:
        args.append("--points")
        text = "\n".join(" ".join("%.17g" % x for x in p) for p in points)
    p = subprocess.run(args, input=text, capture_output=True, text=True, timeout=300)
    solids, dist = [], []
    for line in p.stdout.splitlines():
        w = line.split()
        if w[0] == "solid":
            solids.append((int(w[1]), w[2] == "1", float(w[3]), float(w[4])))
        elif w[0] == "dist":
            dist.append(float(w[1]))
    return p.returncode, solids, dist


def evaluate(model, body, params):
    rc, out, err = T.run([model, "--eval", "--body", str(body)],
                         stdin="\n".join("%.17g %.17g %.17g" % tuple(q) for q in params))
    if rc != 0:
        raise RuntimeError(err)
    return [[float(t) for t in line.split()] for line in out.splitlines() if line.strip()]


def face_params(face, a, b):
    q = [a, b]
    q.insert(face // 2, float(face % 2))
    return q


def body_points(model, body, size, seed):
    """One evaluation of the body: which faces the solid leaves out, and
    NPOINTS points on the others.

    Left out (6 less these is the solid's face count): the collapsed faces
    (an apex: the face's 3 x 3 grid is one point) and the pairs of faces
    that coincide under one of the 8 symmetries of the square (a closed
    body; their points are inside the solid). The points: x y z a b, a and
    b the point's parameters on its face."""
    grid = [(i / 2, j / 2) for i in range(3) for j in range(3)]
    rnd = random.Random(seed)
    ab = [(rnd.random(), rnd.random()) for k in range(NPOINTS)]
    pts = evaluate(model, body, [face_params(f, a, b) for f in range(6) for a, b in grid] +
                   [face_params(k % 6, a, b) for k, (a, b) in enumerate(ab)])
    faces = [[pts[9 * f + k] for k in range(9)] for f in range(6)]
    eps = 1e-9 * size

    def same(p, q):
        return max(abs(x - y) for x, y in zip(p, q)) <= eps

    collapsed = set(f for f in range(6) if all(same(faces[f][0], p) for p in faces[f]))
    dropped = set(collapsed)
    for f in range(6):
        for g in range(f + 1, 6):
            if f in dropped or g in dropped:
                continue
            for sym in range(8):
                ok = True
                for i in range(3):
                    for j in range(3):
                        x, y = (j, i) if sym & 1 else (i, j)
                        x = 2 - x if sym & 2 else x
                        y = 2 - y if sym & 4 else y
                        ok = ok and same(faces[f][3 * i + j], faces[g][3 * x + y])
                if ok:
                    dropped |= {f, g}
                    break
    inside = dropped - collapsed
    on = [p + [a, b] for k, (p, (a, b)) in enumerate(zip(pts[54:], ab)) if k % 6 not in inside]
    return len(dropped), on


def diagonal(box):
    return math.dist(box["min"], box["max"]) or 1.0


def freecad(paths):
    """FreeCAD's view of each file: solids, faces per solid, valid, check."""
    script = f"""
import json, sys
sys.path.append({FREECAD_LIB!r})
import FreeCAD, Part
out = {{}}
for p in sys.argv[1:]:
    s = Part.read(p)
    try:
        s.check()
        clean = True
    except Exception as e:
        clean = str(e)[:300]
    out[p] = {{"solids": len(s.Solids), "faces": [len(x.Faces) for x in s.Solids],
              "valid": s.isValid() and all(x.isValid() for x in s.Solids), "clean": clean}}
print(json.dumps(out))
"""
    p = subprocess.run(["/usr/bin/python3", "-c", script] + paths, capture_output=True,
                       text=True, timeout=600)
    if p.returncode != 0:
        return None, p.stderr[-500:]
    return json.loads(p.stdout.splitlines()[-1]), ""


def gmsh_volumes(paths):
    script = """
import json, sys
import gmsh
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
out = {}
for p in sys.argv[1:]:
    gmsh.clear()
    gmsh.model.occ.importShapes(p)
    gmsh.model.occ.synchronize()
    out[p] = len(gmsh.model.getEntities(3))
gmsh.finalize()
print(json.dumps(out))
"""
    p = subprocess.run(["/usr/bin/python3", "-c", script] + paths, capture_output=True,
                       text=True, timeout=600)
    if p.returncode != 0:
        return None, p.stderr[-500:]
    return json.loads(p.stdout.splitlines()[-1]), ""


def stl_volume_area(path):
    import struct
    with open(path, "rb") as f:
        data = f.read()
    n = struct.unpack_from("<I", data, 80)[0]
    vol = area = 0.0
    for k in range(n):
        v = struct.unpack_from("<12f", data, 84 + 50 * k)
        a, b, c = v[3:6], v[6:9], v[9:12]
        vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6
        u = [b[i] - a[i] for i in range(3)]
        w = [c[i] - a[i] for i in range(3)]
        cr = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
        area += math.sqrt(sum(x * x for x in cr)) / 2
    return vol, area


def check_bodies(name, model, path, info, tag=""):
    """The per-body checks of a file written with operation none."""
    bodies = info["bodies"]
    pts, limits = [], []
    drops = []
    for i, b in enumerate(bodies):
        size = diagonal(b["control_bbox"])
        nd, p = body_points(model, i, size, i + 1)
        drops.append(nd)
        pts += p
        faces = b["faces"]
        lim = 1e-9 * size if faces["exact"] else 2 * faces["deviation"] + 1e-9 * size
        limits += [lim] * len(p)
    rc, solids, dist = occt_check(path, pts)
    if not T.check(f"{name}{tag}: Open CASCADE reads {len(bodies)} solid(s)",
                   rc == 0 and len(solids) == len(bodies), f"rc {rc}, {len(solids)} solids"):
        return None
    worst = max(d / l for d, l in zip(dist, limits)) if dist else float("inf")
    T.check(f"{name}{tag}: {len(pts)} boundary points on the read-back faces "
            f"(worst {max(dist):.3g} = {worst:.3g} of the limit)",
            len(dist) == len(pts) and worst <= 1)
    for i, (b, s) in enumerate(zip(bodies, solids)):
        size = diagonal(b["control_bbox"])
        nf = 6 - drops[i]
        faces = b["faces"]
        v, vs = abs(b["volume"]), s[3]
        if faces["exact"]:
            rel = 1e-6 if faces["rational"] else 1e-9
            lim = max(rel * v, 2 * (b["volume_error"] or 0))
        else:
            lim = 4 * faces["deviation"] * size * size + 2 * (b["volume_error"] or 0)
        T.check(f"{name}{tag} body {i}: valid solid of {nf} faces, volume {vs:.12g} vs "
                f"{v:.12g} (rel {abs(vs - v) / v:.2g})",
                s[1] and s[0] == nf and abs(vs - v) <= lim,
                f"valid {s[1]}, faces {s[0]}, volume {vs} vs {v}, limit {lim}")
    return solids


def main():
    tmp = tempfile.mkdtemp(prefix="coons-step-")
    spool = os.path.join(T.src, "examples", "spool.json")
    if not cache_has("COONS_WITH_OCCT"):
        out = os.path.join(tmp, "x.step")
        rc, _, err = T.run([spool, "-o", out])
        T.check("without Open CASCADE, .step is refused naming it (exit 3, no file)",
                rc == 3 and "Open CASCADE" in err and not os.path.exists(out), err)
        shutil.rmtree(tmp, ignore_errors=True)
        T.finish()
    T.check("tests/tools/occt_check is built",
            os.path.exists(os.path.join(T.build, "tests", "occt_check")))
    fc = subprocess.run(["/usr/bin/python3", "-c", f"import sys; sys.path.append({FREECAD_LIB!r}); "
                         "import FreeCAD, Part"], capture_output=True, text=True)
    T.check("FreeCAD's Python modules import (freecad-python3; tools/setup.sh installs it)",
            fc.returncode == 0, fc.stderr[-300:])
    gm = subprocess.run(["/usr/bin/python3", "-c", "import gmsh"], capture_output=True)
    T.check("gmsh's Python module imports (python3-gmsh)", gm.returncode == 0)

    cgal = cache_has("COONS_WITH_CGAL")
    fc_files, gmsh_files = {}, {}
    for model in T.examples():
        name = os.path.basename(model)[:-5]
        rc, out, err = T.run([model, "--info", "--no-solid"])
        if not T.check(f"{name}: --info", rc == 0, err):
            continue
        info = json.loads(out)
        with open(model) as f:
            doc = json.load(f)
        doc["operation"] = "none"
        none_model = os.path.join(tmp, name + "-none.json")
        with open(none_model, "w") as f:
            json.dump(doc, f)
        path = os.path.join(tmp, name + ".step")
        rc, out, err = T.run([none_model, "-o", path])
        if not T.check(f"{name}: written as STEP, nothing printed", rc == 0 and out == "" and
                       os.path.exists(path), err):
            continue
        solids = check_bodies(name, none_model, path, info)
        if solids is not None:
            fc_files[path] = [s[0] for s in solids]
            gmsh_files[path] = len(solids)
        if info["operation"] == "union" and len(info["bodies"]) > 1 and name not in SLOW:
            upath = os.path.join(tmp, name + "-union.step")
            rc, out, err = T.run([model, "-o", upath])
            if not T.check(f"{name}: the union written as STEP", rc == 0 and out == "", err):
                continue
            rc, usolids, _ = occt_check(upath, gprop=True)
            mesh_parts = None
            if cgal:
                stl = os.path.join(tmp, name + ".stl")
                rc2, out2, err2 = T.run([model, "-o", stl])
                rc3, out3, _ = T.run([model, "--info"])
                mesh_parts = json.loads(out3)["solid"]["shells"] if rc3 == 0 else None
                if T.check(f"{name}: the mesh union (CGAL)", rc2 == 0, err2):
                    mv, area = stl_volume_area(stl)
                    tol = info["tolerance"]
                    uv = sum(s[2] for s in usolids)
                    T.check(f"{name}: the union's volume {uv:.10g} agrees with the mesh "
                            f"union's {mv:.10g} within the tolerance times the area "
                            f"({tol * area:.3g})", abs(uv - mv) <= 1.5 * tol * area)
            else:
                vols = [abs(b["volume"]) for b in info["bodies"]]
                uv = sum(s[2] for s in usolids)
                # BRepGProp on the union's trimmed faces: about 1e-5 relative
                T.check(f"{name}: (no CGAL: no mesh union) the union's volume {uv:.10g} lies "
                        f"between the largest body and the sum (1e-5 relative)",
                        max(vols) * (1 - 1e-5) <= uv <= sum(vols) * (1 + 1e-5))
            T.check(f"{name}: the union is valid solids ({len(usolids)}"
                    + (f", the mesh union has {mesh_parts} shells" if mesh_parts else "") + ")",
                    rc == 0 and usolids and all(s[1] for s in usolids)
                    and (mesh_parts is None or len(usolids) == mesh_parts))
            fc_files[upath] = [s[0] for s in usolids]
            gmsh_files[upath] = len(usolids)

    got, err = freecad(list(fc_files))
    if T.check("FreeCAD read every STEP file", got is not None, err):
        for p, faces in fc_files.items():
            g = got[p]
            T.check(f"FreeCAD: {os.path.basename(p)}: {g['solids']} valid solid(s), "
                    f"faces {g['faces']}, check clean",
                    g["valid"] and g["clean"] is True and g["faces"] == faces, str(g))
    got, err = gmsh_volumes(list(gmsh_files))
    if T.check("gmsh read every STEP file", got is not None, err):
        bad = [os.path.basename(p) for p, n in gmsh_files.items() if got[p] != n]
        T.check(f"gmsh counts the volumes of {len(gmsh_files)} files", not bad, str(bad))

    formats(tmp)
    wrong_spline(tmp)
    mirrored(tmp)
    info_faces()
    refusals(tmp)
    shutil.rmtree(tmp, ignore_errors=True)
    T.finish()


def formats(tmp):
    """IGES and BREP read back like STEP; AP242; names, units, digits."""
    for name in ["spool", "nail", "union-three-bodies"]:
        model = os.path.join(T.src, "examples", name + ".json")
        union = name.startswith("union")
        vols = {}
        for ext in ["step", "igs", "brep"]:
            path = os.path.join(tmp, f"{name}-f.{ext}")
            rc, out, err = T.run([model, "-o", path])
            rc2, solids, _ = occt_check(path, gprop=True)
            T.check(f"{name}: .{ext} written and read back as valid solids",
                    rc == 0 and out == "" and rc2 == 0 and solids and all(s[1] for s in solids),
                    err)
            # faces untrimmed: the volume by their spans; the union's trimmed
            # faces: BRepGProp's (which differs with the parameter curves
            # each reader makes, 3e-6 on the nail's apex)
            vols[ext] = sum(s[2] if union else s[3] for s in solids)
        rel = 1e-6 if union else 1e-12
        T.check(f"{name}: IGES and BREP have the STEP volume {vols['step']:.12g} "
                f"(relative {rel:g})",
                all(abs(v - vols["step"]) <= rel * abs(vols["step"]) for v in vols.values()),
                str(vols))
        got, err = freecad([os.path.join(tmp, f"{name}-f.igs"), os.path.join(tmp, f"{name}-f.brep")])
        T.check(f"{name}: FreeCAD reads the IGES and BREP files as valid solids",
                got is not None and all(g["valid"] and g["solids"] >= 1 for g in got.values()),
                err or str(got))
    spool = os.path.join(T.src, "examples", "spool.json")
    same = []
    for ext in ["step", "igs", "brep"]:
        texts = []
        for d in ["a", "b"]:
            os.makedirs(os.path.join(tmp, d), exist_ok=True)
            path = os.path.join(tmp, d, "spool." + ext)
            T.run([spool, "-o", path])
            with open(path, "rb") as f:
                texts.append(f.read())
        same.append(texts[0] == texts[1] and len(texts[0]) > 1000)
    T.check("STEP, IGES and BREP files are the same bytes for the same model (no clock, no "
            "user name)", all(same), str(same))
    p214, p242 = os.path.join(tmp, "s214.step"), os.path.join(tmp, "s242.stp")
    T.run([spool, "-o", p214])
    rc, _, err = T.run([spool, "-f", "step-ap242", "-o", p242])
    t214, t242 = open(p214).read(), open(p242).read() if rc == 0 else ""
    T.check("AP214 by default, AP242 with -f step-ap242 (FILE_SCHEMA)",
            "AUTOMOTIVE_DESIGN" in t214 and "AP242_MANAGED_MODEL_BASED_3D_ENGINEERING" in t242,
            err)
    _, s242, _ = occt_check(p242)
    T.check("the AP242 file reads back as a valid solid", len(s242) == 1 and s242[0][1])
    T.check("the body's name is the product's name", "PRODUCT('spool','spool'" in t214)
    T.check("millimetres are declared", "SI_UNIT(.MILLI.,.METRE.)" in t214)
    # 17 significant digits: the spool's weight sqrt(2)/4 as 0.35355339059327379
    T.check("reals have 17 significant digits", "0.35355339059327379" in t214)
    # inches: Open CASCADE's reader converts to millimetres, 25.4^3 the volume
    with open(spool) as f:
        doc = json.load(f)
    doc["units"] = "in"
    inch = os.path.join(tmp, "spool-in.json")
    with open(inch, "w") as f:
        json.dump(doc, f)
    pin = os.path.join(tmp, "spool-in.step")
    rc, _, err = T.run([inch, "-o", pin])
    _, smm, _ = occt_check(p214)
    _, sin, _ = occt_check(pin)
    T.check("a model in inches is a STEP file in inches (read back in mm: 25.4^3 the volume)",
            rc == 0 and "'INCH'" in open(pin).read() and sin and
            abs(sin[0][3] / smm[0][3] - 25.4 ** 3) <= 1e-9 * 25.4 ** 3, err)


def wrong_spline(tmp):
    """A wrong spline (tests/tools/coons2stl_wrong_spline.c) is still valid to
    Open CASCADE: only the point check finds it."""
    binary = os.path.join(T.build, "tests", "coons2stl_wrong_spline")
    if not T.check("tests/coons2stl_wrong_spline is built", os.path.exists(binary)):
        return
    model = os.path.join(T.src, "examples", "volume-bspline.json")
    path = os.path.join(tmp, "wrong.step")
    p = subprocess.run([binary, model, "-o", path], capture_output=True, text=True)
    rc, out, _ = T.run([model, "--info", "--no-solid"])
    b = json.loads(out)["bodies"][0]
    size = diagonal(b["control_bbox"])
    _, pts = body_points(model, 0, size, 1)
    rc2, solids, dist = occt_check(path, pts)
    print(f"     wrong spline: worst distance {max(dist) if dist else 0:.6g}")
    T.check(f"a wrong spline: Open CASCADE still finds the solid valid, but the point check "
            f"fails (worst {max(dist) if dist else 0:.3g}, limit {1e-9 * size:.3g})",
            p.returncode == 0 and rc2 == 0 and solids and solids[0][1]
            and dist and max(dist) > 1e-9 * size, p.stderr)


def mirrored(tmp):
    """A left-handed body (the spool mirrored: det J < 0, coons_body_volume
    negative) is written outward: the faces' own orientation gives a
    positive volume (an inside-out solid would integrate to the negative),
    and Open CASCADE finds it valid. Read from BREP, which keeps the
    orientation as written: Open CASCADE's STEP reader turns an inside-out
    solid outward itself, so a STEP file cannot show the mistake."""
    with open(os.path.join(T.src, "examples", "spool.json")) as f:
        doc = json.load(f)

    def flip(node, pts=False):
        """x -> -x in every point list (points, corners), weights kept."""
        if isinstance(node, list):
            if pts and len(node) == 3 and all(isinstance(x, (int, float)) for x in node):
                return [-node[0], node[1], node[2]]
            return [flip(x, pts) for x in node]
        if isinstance(node, dict):
            return {k: flip(v, pts or k in ("points", "corners")) for k, v in node.items()}
        return node

    doc["bodies"] = flip(doc["bodies"])
    model = os.path.join(tmp, "spool-mirrored.json")
    with open(model, "w") as f:
        json.dump(doc, f)
    rc, out, err = T.run([model, "--info", "--no-solid"])
    vol = json.loads(out)["bodies"][0]["volume"] if rc == 0 else 0
    path = os.path.join(tmp, "spool-mirrored.brep")
    rc, _, err = T.run([model, "-o", path])
    _, solids, _ = occt_check(path)
    T.check(f"a left-handed body (volume {vol:.10g}) is a valid solid with outward faces "
            f"(volume by its faces {solids[0][3] if solids else 0:.10g})",
            vol < 0 and rc == 0 and len(solids) == 1 and solids[0][1]
            and abs(solids[0][3] + vol) <= 1e-6 * abs(vol), err)


def info_faces():
    """--info's "faces": exact and rational (the spool: rational B-spline
    faces), fitted with a measured deviation (the hood shell: an offset
    surface, fitted within the finer of the tolerance and 1e-5 of the size)."""
    got = {}
    for name in ["spool", "deformed-cube", "hood-shell"]:
        rc, out, _ = T.run([os.path.join(T.src, "examples", name + ".json"), "--info", "--no-solid"])
        got[name] = json.loads(out)["bodies"][0] if rc == 0 else None
    sp, dc, hs = got["spool"]["faces"], got["deformed-cube"]["faces"], got["hood-shell"]
    T.check("--info: the spool's faces are exact and rational, none fitted",
            sp["exact"] and sp["rational"] and sp["fitted"] == [] and sp["deviation"] == 0, str(sp))
    T.check("--info: the deformed cube's faces are exact polynomials",
            dc["exact"] and not dc["rational"], str(dc))
    size = diagonal(hs["control_bbox"])
    f = hs["faces"]
    T.check(f"--info: the hood shell's six faces are fitted, deviation {f['deviation']:.3g} "
            f"within 1e-5 of its size",
            not f["exact"] and len(f["fitted"]) == 6 and 0 < f["deviation"] <= 1e-5 * size, str(f))


def refusals(tmp):
    """A body whose solid cannot be made: exit 3 naming it, nothing written;
    -o - refused."""
    flat = {"coons": 1, "bodies": [{"type": "body0", "name": "flat", "corners": [
        [0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]}]}
    model = os.path.join(tmp, "flat.json")
    with open(model, "w") as f:
        json.dump(flat, f)
    out = os.path.join(tmp, "flat.step")
    rc, _, err = T.run([model, "-o", out])
    T.check("a body with no volume: exit 3 naming the body, nothing written",
            rc == 3 and "flat" in err and not os.path.exists(out)
            and not [n for n in os.listdir(tmp) if n.startswith(".flat.step")], err)
    rc, _, err = T.run([os.path.join(T.src, "examples", "spool.json"), "-f", "step", "-o", "-"])
    T.check("STEP onto standard output is refused (exit 2)", rc == 2 and "-o FILE" in err, err)


main()
