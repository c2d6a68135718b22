# SPDX-License-Identifier: GPL-3.0-or-later
"""Volume meshes of control lattices (seed 000 section 3: each cell of the
lattice a Coons body, cells sharing faces, edges and corners), checked
from the written files with meshio (an independent reader), never against
coons2stl's own numbers:

- a 2 x 2 x 2 lattice of body 2 cells with curved shared faces (the
  images of the cubes [i, i+1] x [j, j+1] x [k, k+1] under the map
  phi(x, y, z) = (x + 0.1 y^2, y + 0.1 z^2, z + 0.1 x^2), each face an
  exact biquadratic Bezier patch, so neighbours' faces are the same map):
  at --resolution 2 per cell, as .vtu and .msh, hex8 and hex27, every
  interior face of the 4 x 4 x 4 grid of cells is shared by exactly two
  cells (faces counted by their corner nodes: 3 * 4^2 * 5 faces, of which
  6 * 4^2 on the boundary) and the grid's (4 k + 1)^3 points are each one
  node; with the sampled lattice (no --resolution), every face used once
  lies on the image of the cube's boundary (each corner mapped back by
  Newton's method), none is used more than twice, and no two nodes
  coincide;
- two bodies that meet along one whole edge only (a box and a Bezier
  volume curved along z, so their sampled lattices along the shared edge
  differ): the edge's nodes are the same nodes seen from both bodies;
- two boxes touching along half a face, along a shifted face, with a
  corner on the middle of a face, or overlapping, and a box and a Bezier
  volume whose faces coincide but are parametrised differently: refused (exit 3) naming
  both, nothing written; sharing a whole face, a whole edge or a corner:
  meshed;
- every lattice example (lattice-ffd, chair-lattice, lattice-l-bracket,
  lattice-ring, lattice-instanced) as .vtu: no two nodes coincide and no
  face is used by more than two cells;
- the nail's mesh, as .vtu and .msh, reads in meshio as one block of
  cells per cell type of the body (at most 3 volume blocks per body), and
  at most 2 surface blocks (quadrangles, triangles) per face set in .msh;
  the hexahedra of the lattice-ffd lattice as at most 3 blocks per body.

Usage: test_volume_lattice.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402

T = Runner(__doc__)
try:
    import meshio
    import numpy as np
except ImportError as e:  # a missing reader fails the test, never skips it
    T.check("meshio and numpy for Python are installed (python3-meshio, python3-numpy)", False,
            str(e))
    T.finish()

SIDES = ("u0", "u1", "v0", "v1", "w0", "w1")
# Corner lists of the faces of each meshio volume cell type (first 8/6/5
# nodes: the corners; VTK's and Gmsh's corner orders agree).
FACES = {
    "hexahedron": ((0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6),
                   (3, 0, 4, 7)),
    "wedge": ((0, 1, 2), (3, 4, 5), (0, 1, 4, 3), (1, 2, 5, 4), (2, 0, 3, 5)),
    "pyramid": ((0, 1, 2, 3), (0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)),
}
VOLUME_TYPES = {"hexahedron": "hexahedron", "hexahedron20": "hexahedron",
                "hexahedron27": "hexahedron", "wedge": "wedge", "pyramid": "pyramid"}


def phi(p):
    x, y, z = p
    return [x + 0.1 * y * y, y + 0.1 * z * z, z + 0.1 * x * x]


def phi_inv(q):
    """Newton's method on phi(p) = q."""
    p = np.array(q, dtype=float)
    for _ in range(50):
        x, y, z = p
        f = np.array(phi(p)) - q
        j = np.array([[1, 0.2 * y, 0], [0, 1, 0.2 * z], [0.2 * x, 0, 1]])
        p = p - np.linalg.solve(j, f)
    return p


def bezier2(f):
    """Control points of the quadratic Bezier curve through f(0), f(1/2),
    f(1) (exact for a quadratic f)."""
    a, m, b = np.array(f(0.0)), np.array(f(0.5)), np.array(f(1.0))
    return [a, 2 * m - (a + b) / 2, b]


def face_patch(i, j, k, axis, side):
    """Face `axis` = side of cell (i, j, k): the biquadratic Bezier patch of
    phi on it, points[a][b] over the body's other two parameters in
    increasing order (model-format: uI over (v, w), vJ over (u, w), wK
    over (u, v))."""
    other = [d for d in range(3) if d != axis]
    o = (i, j, k)

    def point(s, t):
        p = [0.0, 0.0, 0.0]
        p[axis] = o[axis] + side
        p[other[0]] = o[other[0]] + s
        p[other[1]] = o[other[1]] + t
        return phi(p)

    # tensor product: Bezier along t for each s in {0, 1/2, 1}, then along s
    cols = [bezier2(lambda t, s=s: point(s, t)) for s in (0.0, 0.5, 1.0)]
    pts = [[None] * 3 for _ in range(3)]
    for b in range(3):
        row = bezier2(lambda s, b=b: {0.0: cols[0][b], 0.5: cols[1][b], 1.0: cols[2][b]}[s])
        for a in range(3):
            pts[a][b] = [float(v) for v in row[a]]
    return {"type": "bezier-surface", "points": pts}


def curved_lattice(path):
    bodies = []
    for i in range(2):
        for j in range(2):
            for k in range(2):
                faces = {}
                for axis in range(3):
                    for side in range(2):
                        faces[SIDES[2 * axis + side]] = face_patch(i, j, k, axis, side)
                bodies.append({"type": "body2", "name": f"c{i}{j}{k}", "faces": faces})
    with open(path, "w") as f:
        json.dump({"coons": 1, "units": "mm", "bodies": bodies}, f)


def volume_blocks(m):
    return [b for b in m.cells if b.type in VOLUME_TYPES]


def face_counts(m):
    """Faces of every volume cell by their sorted corner node ids -> uses."""
    count = {}
    for b in volume_blocks(m):
        faces = FACES[VOLUME_TYPES[b.type]]
        for row in b.data:
            for f in faces:
                key = tuple(sorted(int(row[c]) for c in f))
                count[key] = count.get(key, 0) + 1
    return count


def coincident_nodes(m):
    """Pairs of distinct points of the file within 1e-9 of its size."""
    used = sorted({int(n) for b in volume_blocks(m) for row in b.data for n in row})
    pts = m.points[used]
    scale = float(np.abs(pts).max()) or 1.0
    key = np.round(pts / (1e-7 * scale)).astype(np.int64)
    seen, dup = {}, 0
    for n, k in enumerate(map(tuple, key)):
        dup += k in seen
        seen[k] = n
    return dup


def write(path, out, args=()):
    rc, _, err = T.run([path, "-o", out] + list(args))
    return rc == 0 and os.path.exists(out), err


def curved_checks(tmp):
    path = os.path.join(tmp, "curved.json")
    curved_lattice(path)
    k = 2
    for element in ("hex8", "hex27"):
        for ext in ("vtu", "msh"):
            out = os.path.join(tmp, f"curved-{element}.{ext}")
            ok, err = write(path, out, ["--element", element, "--resolution", str(k)])
            label = f"2x2x2 curved body 2 lattice, {element}, .{ext}"
            if not T.check(f"{label}: written", ok, err):
                continue
            m = meshio.read(out)
            cnt = face_counts(m)
            n = 2 * k
            once = sum(1 for c in cnt.values() if c == 1)
            twice = sum(1 for c in cnt.values() if c == 2)
            cells = sum(len(b.data) for b in volume_blocks(m))
            side = (n * (2 if element == "hex27" else 1) + 1)
            T.check(f"{label}: {cells} cells, {len(cnt)} faces, {once} once, {twice} twice "
                    f"(a {n}^3 grid: {3 * n * n * (n + 1)} faces, {6 * n * n} on the "
                    "boundary, every other shared by exactly two cells)",
                    cells == n ** 3 and len(cnt) == 3 * n * n * (n + 1) and
                    once == 6 * n * n and once + twice == len(cnt))
            used = {int(v) for b in volume_blocks(m) for row in b.data for v in row}
            T.check(f"{label}: {len(used)} nodes, the grid's {side}^3 points once each",
                    len(used) == side ** 3 and coincident_nodes(m) == 0)
    out = os.path.join(tmp, "curved-sampled.vtu")
    ok, err = write(path, out)
    if T.check("2x2x2 curved lattice on the sampled lattice: written", ok, err):
        m = meshio.read(out)
        cnt = face_counts(m)
        bad = 0
        for key, c in cnt.items():
            if c != 1:
                continue
            q = [phi_inv(m.points[v]) for v in key]
            on = any(all(abs(p[d] - s) < 1e-7 for p in q) for d in range(3) for s in (0.0, 2.0))
            bad += not on
        T.check(f"2x2x2 curved lattice, sampled: {len(cnt)} faces, none used more than twice, "
                f"each used once on the cube's boundary ({bad} inside), no coincident nodes",
                max(cnt.values()) == 2 and bad == 0 and coincident_nodes(m) == 0, f"{bad}")


def edge_only(tmp):
    """A box [0,1]^3 and, across the edge x = y = 1, a Bezier volume over
    [1,2] x [1,2] x [0,1] curved along z away from that edge."""
    box = {"type": "body0", "name": "box",
           "corners": [[i >> 2 & 1, i >> 1 & 1, i & 1] for i in range(8)]}
    pts = []
    for i in range(2):
        pts.append([])
        for j in range(2):
            col = []
            for k in range(4):
                z = k / 3
                x, y = 1 + i, 1 + j
                bulge = 0.6 * (i + j) * (1 if k in (1, 2) else 0)
                col.append([x + bulge, y + bulge * (k == 1), z])
            pts[-1].append(col)
    model = {"coons": 1, "units": "mm",
             "bodies": [box, {"type": "bezier-volume", "name": "bent", "points": pts}]}
    path = os.path.join(tmp, "edge.json")
    with open(path, "w") as f:
        json.dump(model, f)
    out = os.path.join(tmp, "edge.vtu")
    ok, err = write(path, out)
    if not T.check("two bodies meeting along a whole edge only: written", ok, err):
        return
    m = meshio.read(out)
    body = np.concatenate([d for d, b in zip(m.cell_data["body"], m.cells)
                           if b.type in VOLUME_TYPES])
    rows = [row for b in volume_blocks(m) for row in b.data]
    on = {0: set(), 1: set()}
    for row, bd in zip(rows, body):
        for v in row:
            x, y, _ = m.points[v]
            if abs(x - 1) < 1e-12 and abs(y - 1) < 1e-12:
                on[int(bd)].add(int(v))
    T.check(f"edge-only neighbours: the shared edge's nodes are the same {len(on[1])} nodes "
            f"from both bodies (box {len(on[0])})",
            len(on[1]) > 2 and on[0] == on[1] and coincident_nodes(m) == 0,
            f"{sorted(on[0])} {sorted(on[1])}")


def box(lo, hi, name):
    return {"type": "body0", "name": name,
            "corners": [[hi[d] if i >> (2 - d) & 1 else lo[d] for d in range(3)]
                        for i in range(8)]}


def refusals(tmp):
    """Bodies that meet other than along whole faces, whole edges or at
    corners of both: exit 3 naming both, nothing written; and the accepted
    kinds of contact for comparison."""
    a = box([0, 0, 0], [1, 1, 1], "a")
    cases = (("touching along half a face", box([1, 0, 0], [2, 0.5, 1], "b"), False),
             ("touching along a shifted face", box([1, 0.5, 0], [2, 1.5, 1], "b"), False),
             ("a corner on the middle of a face",
              box([1, 0.5, 0.5], [2, 1.5, 1.5], "b"), False),
             ("overlapping", box([0.5, 0.5, 0.5], [1.7, 1.7, 1.7], "b"), False),
             # b's face x = 1 is a's face u1, but with y = (0, 0.1, 1)-Bezier
             # in its parameter: only the edges along z coincide node for node
             ("touching along a face parametrised differently",
              {"type": "bezier-volume", "name": "b",
               "points": [[[[1 + i, y, z] for z in (0, 1)] for y in (0, 0.1, 1)]
                          for i in (0, 1)]}, False),
             ("sharing a whole face", box([1, 0, 0], [2, 1, 1], "b"), True),
             ("sharing a whole edge", box([1, 1, 0], [2, 2, 1], "b"), True),
             ("sharing a corner", box([1, 1, 1], [2, 2, 2], "b"), True))
    for what, b, ok in cases:
        path = os.path.join(tmp, "pair.json")
        with open(path, "w") as f:
            json.dump({"coons": 1, "units": "mm", "bodies": [a, b]}, f)
        out = os.path.join(tmp, "pair.vtu")
        if os.path.exists(out):
            os.unlink(out)
        rc, _, err = T.run([path, "-o", out, "--resolution", "2"])
        if ok:
            good = rc == 0 and os.path.exists(out)
            if good:
                m = meshio.read(out)
                good = coincident_nodes(m) == 0 and max(face_counts(m).values()) <= 2
            T.check(f"two boxes {what}: meshed, no coincident nodes", good, err)
        else:
            T.check(f"two boxes {what}: refused (exit 3) naming both, nothing written",
                    rc == 3 and "'a' and 'b'" in err and not os.path.exists(out), err)


def examples(tmp):
    ex = os.path.join(T.src, "examples")
    for name in ("lattice-ffd.json", "chair-lattice.json", "lattice-l-bracket.json",
                 "lattice-ring.json", "lattice-instanced.json"):
        out = os.path.join(tmp, name + ".vtu")
        ok, err = write(os.path.join(ex, name), out)
        if not T.check(f"{name}: .vtu written", ok, err):
            continue
        m = meshio.read(out)
        cnt = face_counts(m)
        nb = len(json.load(open(os.path.join(ex, name)))["bodies"])
        T.check(f"{name}: no two nodes coincide, no face used by more than two cells, at most "
                f"3 blocks per body ({len(m.cells)} blocks, {nb} bodies)",
                coincident_nodes(m) == 0 and max(cnt.values()) <= 2 and
                len(m.cells) <= 3 * nb)
    nail = os.path.join(ex, "nail.json")
    for ext in ("vtu", "msh"):
        out = os.path.join(tmp, "nail." + ext)
        ok, err = write(nail, out)
        if not T.check(f"nail.json: .{ext} written", ok, err):
            continue
        m = meshio.read(out)
        vol = volume_blocks(m)
        surf = [b for b in m.cells if b.type not in VOLUME_TYPES]
        T.check(f"nail .{ext}: meshio reads {len(vol)} volume blocks "
                f"({', '.join(b.type for b in vol[:4])}) and {len(surf)} surface blocks, at most "
                "3 volume blocks for its one body and 2 per face set",
                1 <= len(vol) <= 3 and len({b.type for b in vol}) == len(vol) and
                len(surf) <= 2 * 6, str([b.type for b in m.cells][:8]))


def main():
    with tempfile.TemporaryDirectory() as tmp:
        curved_checks(tmp)
        edge_only(tmp)
        refusals(tmp)
        examples(tmp)
    T.finish()


if __name__ == "__main__":
    main()
