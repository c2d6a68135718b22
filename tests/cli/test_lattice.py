# SPDX-License-Identifier: GPL-3.0-or-later
"""Control lattices through coons2stl (seed 000 §3; coons-model(5) "Bodies
that share faces"): each lattice example (examples/gen_lattices.py) written
as binary STL, read back here and checked from the file alone: welded by
exact float32 coordinates, every edge has exactly two triangles run in
opposite directions (closed, 2-manifold, oriented), the Euler characteristic
is the expected one (a ring of cells is a torus: 0), the enclosed volume
(divergence theorem) is the sum of the cells' exact volumes (--info, the
library's Gauss integral of det J; 1e-12 relative where every outer face is
flat, within tolerance x area elsewhere), and no vertex lies inside a shared
face. With CGAL, --info shows that no Boolean ran (no corefinement, no
soup pass, no patch classified); without CGAL (the C-only build), the same
union is written at all, which a Boolean would need CGAL for.
"""
import json
import os
import struct
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402

# example: (expected Euler characteristic, parts after joining, flat outside)
LATTICES = {
    "lattice-ffd.json": (2, 1, True),
    "chair-lattice.json": (2, 1, False),
    "lattice-l-bracket.json": (2, 1, False),
    "lattice-ring.json": (0, 1, False),
}


def read_stl(path):
    with open(path, "rb") as f:
        data = f.read()
    n = struct.unpack_from("<I", data, 80)[0]
    tris = []
    for i in range(n):
        v = struct.unpack_from("<12f", data, 84 + 50 * i)
        tris.append((v[3:6], v[6:9], v[9:12]))
    return tris


def topology(tris):
    ids, faces = {}, []
    for t in tris:
        faces.append(tuple(ids.setdefault(p, len(ids)) for p in t))
    edges = {}
    for f in faces:
        for k in range(3):
            a, b = f[k], f[(k + 1) % 3]
            edges.setdefault((min(a, b), max(a, b)), []).append((a, b))
    closed = all(len(e) == 2 for e in edges.values())
    oriented = closed and all(e[0] != e[1] for e in edges.values())
    return closed, oriented, len(ids) - len(edges) + len(faces)


def volume(tris):
    v = 0.0
    for a, b, c in tris:
        v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
              + a[2] * (b[0] * c[1] - b[1] * c[0]))
    return v / 6.0


def area(tris):
    s = 0.0
    for a, b, c in tris:
        u = [b[d] - a[d] for d in range(3)]
        w = [c[d] - a[d] for d in range(3)]
        x = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
        s += 0.5 * sum(q * q for q in x) ** 0.5
    return s


def main():
    r = Runner(__doc__)
    ex = os.path.join(r.src, "examples")
    with tempfile.TemporaryDirectory() as tmp:
        for name, (euler, parts, flat) in LATTICES.items():
            path = os.path.join(ex, name)
            out = os.path.join(tmp, name + ".stl")
            st, _, err = r.run(["-o", out, path])
            if not r.check(f"{name}: coons2stl -o .stl", st == 0, err):
                continue
            tris = read_stl(out)
            closed, oriented, chi = topology(tris)
            r.check(f"{name}: closed, 2-manifold, oriented", closed and oriented)
            r.check(f"{name}: Euler characteristic {chi} = {euler}", chi == euler)
            st, js, err = r.run(["--info", path])
            if not r.check(f"{name}: --info", st == 0, err):
                continue
            info = json.loads(js)
            exact = sum(abs(b["volume"]) for b in info["bodies"])
            v = volume(tris)
            bound = 1e-12 * exact if flat else info["tolerance"] * area(tris)
            # float32 storage moves each vertex by up to 2^-24 of its size
            bound += 3 * 2.0 ** -24 * area(tris) * max(
                max(abs(c) for c in p) for t in tris for p in t)
            r.check(f"{name}: volume {v:.9g} = sum of the cells' {exact:.9g} "
                    f"(bound {bound:.3g})", abs(v - exact) <= bound)
            r.check(f"{name}: {len(info['interfaces'])} shared faces found",
                    len(info["interfaces"]) > 0)
            solid = info.get("solid")
            if solid is not None and solid.get("csg") is not None:  # built with CGAL
                c = solid["csg"]
                r.check(f"{name}: joined by index into {parts} part(s)",
                        c["parts_in"] == parts, json.dumps(c))
                r.check(f"{name}: no Boolean ran (no corefinement, soup pass or patch)",
                        c["fast_unions"] == 0 and c["fallbacks"] == 0 and c["patches"] == 0
                        and c["passed_through"] == parts, json.dumps(c))
                r.check(f"{name}: solid exact and crossing-free after float32 rounding",
                        solid["self_intersections"] == 0
                        and solid["self_intersections_float32"] == 0)
        # A shared face's interior is inside the solid: no vertex of the FFD
        # lattice's boundary lies strictly inside the 40 mm cube.
        out = os.path.join(tmp, "ffd.stl")
        st, _, err = r.run(["-o", out, os.path.join(ex, "lattice-ffd.json")])
        if r.check("lattice-ffd.json: written again", st == 0, err):
            inside = [p for t in read_stl(out) for p in t
                      if all(1e-4 < c < 40 - 1e-4 for c in p)]
            r.check("lattice-ffd.json: every vertex on the cube's boundary", not inside,
                    repr(inside[:3]))
        # operation "none": each cell its own closed shell, shared faces kept
        with open(os.path.join(ex, "lattice-l-bracket.json")) as f:
            m = json.load(f)
        m["operation"] = "none"
        none = os.path.join(tmp, "none.json")
        with open(none, "w") as f:
            json.dump(m, f)
        out = os.path.join(tmp, "none.stl")
        st, _, err = r.run(["-o", out, none])
        joined = os.path.join(tmp, "joined.stl")
        st2, _, err2 = r.run(["-o", joined, os.path.join(ex, "lattice-l-bracket.json")])
        if r.check("operation none: written", st == 0 and st2 == 0, err + err2):
            # corner/arm-x share the face x = 8, 0 <= y <= 8: written by both
            # cells with "none", left out when joined
            def on_face(tris):
                return sum(1 for t in tris if all(abs(p[0] - 8) < 1e-6 and p[1] < 8 + 1e-6
                                                  for p in t))
            nn, nj = on_face(read_stl(out)), on_face(read_stl(joined))
            r.check(f"operation none keeps the shared face ({nn} triangles on it), "
                    f"the union leaves it out ({nj})", nn > 0 and nj == 0)
        # A lattice that also overlaps another body: the joined part and the
        # box go to the Boolean union (CGAL), the shared faces never do.
        with open(os.path.join(ex, "lattice-l-bracket.json")) as f:
            m = json.load(f)
        box = [[x, y, z] for x in (20, 30) for y in (4, 12) for z in (4, 16)]
        m["bodies"].append({"type": "body0", "name": "box", "corners": box})
        over = os.path.join(tmp, "over.json")
        with open(over, "w") as f:
            json.dump(m, f)
        out = os.path.join(tmp, "over.stl")
        st, js, err = r.run(["--info", over])
        info = json.loads(js) if st == 0 else {}
        solid = info.get("solid")
        st, _, err = r.run(["-o", out, over])
        if solid is None or solid.get("csg") is None:  # no CGAL: refused, named
            r.check("lattice + overlapping box without CGAL: refused (exit 3), naming the box",
                    st == 3 and "box" in err, err)
        elif r.check("lattice + overlapping box: united", st == 0, err):
            c = solid["csg"]
            r.check("lattice + overlapping box: 2 parts in (the lattice joined), a Boolean ran",
                    c["parts_in"] == 2 and c["fast_unions"] + c["fallbacks"] >= 1, json.dumps(c))
            tris = read_stl(out)
            closed, oriented, chi = topology(tris)
            r.check("lattice + overlapping box: closed, oriented, one sphere",
                    closed and oriented and chi == 2, f"{chi}")
            # box 10 x 8 x 12 = 960, of which [20,30] x [4,8] x [4,12] = 320
            # lies inside the flat part of arm-x
            lattice = sum(abs(b["volume"]) for b in info["bodies"][:3])
            want = lattice + 960 - 320
            v = volume(tris)
            r.check(f"lattice + overlapping box: volume {v:.7g} = {want:.7g}",
                    abs(v - want) <= info["tolerance"] * area(tris), f"{v} {want}")
    r.finish()


if __name__ == "__main__":
    main()
