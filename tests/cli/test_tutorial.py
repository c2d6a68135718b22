# SPDX-License-Identifier: GPL-3.0-or-later
"""The models of docs/tutorial.md (docs/tutorial/*.json), run through the real
coons2stl, each checked against a value computed here from the file's own
control data, independently of libcoons:

- box-top.json, arched-top.json: a body 2 over a 40 x 30 rectangle with
  vertical sides, a flat bottom and a bicubic B-spline top. The test first
  checks that the top's x and y are linear in its parameters (its control
  points sit at the Greville abscissae: the tutorial's rule), so the solid is
  the region under the height field z(s, t) and its volume is
  area * sum_ij z_ij I_i I_j, with I_i the integral of the i-th B-spline
  basis function, (k_i+p+1 - k_i) / (p + 1) over the domain's length. The
  closed mesh (OFF) must have that volume within tolerance x area.
  --eval at (0.5, 0.5, 1) must be the top surface evaluated by clitest's
  reference (Cox-de Boor).
- box-top-even.json: the same top with evenly spaced edge control points:
  coons2stl must refuse it (exit status 1) naming the faces u0 and w1 and the
  edge v01, and write nothing.
- arch-lattice.json: four body 0 cells sharing faces: one closed oriented
  shell without the shared faces, volume the sum of the cells' trilinear
  volumes (Gauss quadrature of det J, exact for a trilinear map).
- morph.json: a linear morph between a body 0 block and the body 2 of
  box-top.json whose boundaries differ only in the top's height: the volume
  at time t is (1 - t) V0 + t V1, at the file's t, with --time and for each
  frame of --frames.
- arch-gravity.inp: the CalculiX job of the tutorial on the volume mesh
  `-o arch.inp --element hex20`: ccx solves it; the structure and the load
  are symmetric about x = 40 and y = 5, so at the crown (C1_U1) u_x = 0 and
  u_z(y) = u_z(10 - y), and the crown moves down. hex27 into .inp is refused.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner, clamped_knots, tensor_eval  # noqa: E402
from test_volume_ccx import read_dat, read_inp  # noqa: E402


# ---- closed meshes (OFF) -----------------------------------------------------

def read_off(path):
    """(vertices, triangles) of an OFF file."""
    with open(path) as f:
        words = f.read().split()
    nv, nf = int(words[1]), int(words[2])
    verts = [tuple(float(x) for x in words[4 + 3 * i:7 + 3 * i]) for i in range(nv)]
    i, faces = 4 + 3 * nv, []
    for _ in range(nf):
        faces.append(tuple(int(x) for x in words[i + 1:i + 1 + int(words[i])]))
        i += 1 + int(words[i])
    return verts, faces


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def volume(verts, faces):
    """Signed volume: the divergence theorem over the triangles."""
    return sum(sum(verts[a][k] * cross(verts[b], verts[c])[k] for k in range(3))
               for a, b, c in faces) / 6.0


def area(verts, faces):
    s = 0.0
    for a, b, c in faces:
        n = cross([verts[b][k] - verts[a][k] for k in range(3)],
                  [verts[c][k] - verts[a][k] for k in range(3)])
        s += 0.5 * math.sqrt(sum(x * x for x in n))
    return s


def closed_2manifold(faces):
    """Triangles only, every edge used exactly twice, once in each direction."""
    d = {}
    for f in faces:
        for k in range(len(f)):
            e = (f[k], f[(k + 1) % len(f)])
            d[e] = d.get(e, 0) + 1
    return all(len(f) == 3 for f in faces) and all(
        n == 1 and d.get((b, a)) == 1 for (a, b), n in d.items())


def shells(faces):
    """The number of edge-connected pieces (union-find over vertices)."""
    parent = {}

    def find(x):
        while parent.setdefault(x, x) != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x
    for f in faces:
        for v in f[1:]:
            parent[find(v)] = find(f[0])
    return len({find(f[0]) for f in faces})


def load(r, name):
    with open(os.path.join(r.src, "docs", "tutorial", name), encoding="utf-8") as f:
        return json.load(f)


def model_path(r, name):
    return os.path.join(r.src, "docs", "tutorial", name)


def mesh_off(r, tmp, name, args=()):
    """coons2stl NAME -o OUT.off ARGS; returns (verts, faces) or None."""
    out = os.path.join(tmp, name.replace(".json", "") + "-".join(args) + ".off")
    st, _, err = r.run([model_path(r, name), "-o", out, "-q"] + list(args))
    what = " ".join([name] + list(args))
    if not r.check(f"{what}: coons2stl writes an OFF", st == 0 and os.path.exists(out), err):
        return None
    return read_off(out)


def integrals(knots, p, n):
    """The integrals of the n B-spline basis functions over the domain mapped
    onto [0, 1]: (k_i+p+1 - k_i) / (p + 1) / (k_n - k_p)."""
    span = knots[n] - knots[p]
    return [(knots[i + p + 1] - knots[i]) / (p + 1) / span for i in range(n)]


def height_field_volume(r, name, top, lo, hi, z0):
    """Volume under the B-spline top over the rectangle lo..hi (z from z0),
    after checking that x and y are linear in (s, t)."""
    p, q = (int(d) for d in top["degree"])
    P = top["points"]
    ns, nt = len(P), len(P[0])
    worst = 0.0
    for s in (0.0, 0.13, 0.5, 0.77, 1.0):
        for t in (0.0, 0.29, 0.5, 0.91, 1.0):
            x = tensor_eval(top, [s, t])
            want = (lo[0] + s * (hi[0] - lo[0]), lo[1] + t * (hi[1] - lo[1]))
            worst = max(worst, abs(x[0] - want[0]), abs(x[1] - want[1]))
    r.check(f"{name}: the top's x, y are linear in (s, t) (Greville points), off by {worst:.1e}",
            worst < 1e-12)
    Is = integrals(clamped_knots(p, ns), p, ns)
    It = integrals(clamped_knots(q, nt), q, nt)
    mean = sum(Is[i] * It[j] * float(P[i][j][2]) for i in range(ns) for j in range(nt))
    return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (mean - z0)


def check_closed_volume(r, what, mesh, want, tol):
    verts, faces = mesh
    r.check(f"{what}: closed, oriented, one shell", closed_2manifold(faces) and
            shells(faces) == 1)
    v, a = volume(verts, faces), area(verts, faces)
    r.check(f"{what}: volume {v:.6f} vs {want:.6f}, within tolerance x area = {tol * a:.3g}",
            abs(v - want) <= tol * a, f"off by {v - want:.6g}")
    return v


def bodies2(r, tmp):
    for name in ("box-top.json", "arched-top.json"):
        m = load(r, name)
        top = m["bodies"][0]["faces"]["w1"]
        want = height_field_volume(r, name, top, (0, 0), (40, 30), 0.0)
        mesh = mesh_off(r, tmp, name)
        if mesh:
            check_closed_volume(r, name, mesh, want, m["tolerance"])
        st, out, err = r.run(["--eval", model_path(r, name)], stdin="0.5 0.5 1\n")
        ref = tensor_eval(top, [0.5, 0.5])
        got = [float(x) for x in out.split()] if st == 0 else []
        r.check(f"{name}: --eval 0.5 0.5 1 is the top at (0.5, 0.5), {ref}",
                len(got) == 3 and max(abs(got[k] - ref[k]) for k in range(3)) < 1e-12,
                out + err)


def even_spacing(r, tmp):
    out = os.path.join(tmp, "even.stl")
    st, _, err = r.run([model_path(r, "box-top-even.json"), "-o", out])
    r.check("box-top-even.json: refused with exit status 1, nothing written",
            st == 1 and not os.path.exists(out), f"status {st}")
    r.check("box-top-even.json: the message names faces u0 and w1 and the edge v01",
            all(w in err for w in ("u0", "w1", "v01", "disagree")), err)


def trilinear_volume(c):
    """Integral of det J of the body 0 with corners c[4i + 2j + k] (3-point
    Gauss per direction: exact, det J has degree <= 2 in each variable)."""
    g = [(0.5 - 0.5 * math.sqrt(0.6), 5 / 18), (0.5, 8 / 18), (0.5 + 0.5 * math.sqrt(0.6), 5 / 18)]
    P = [[float(x) for x in p] for p in c]

    def d(axis, u, v, w):
        out = [0.0, 0.0, 0.0]
        for n in range(8):
            i, j, k = n >> 2, (n >> 1) & 1, n & 1
            f = [(u if i else 1 - u), (v if j else 1 - v), (w if k else 1 - w)]
            f[axis] = 1.0 if (i, j, k)[axis] else -1.0
            for x in range(3):
                out[x] += f[0] * f[1] * f[2] * P[n][x]
        return out
    vol = 0.0
    for u, wu in g:
        for v, wv in g:
            for w, ww in g:
                a, b, e = d(0, u, v, w), d(1, u, v, w), d(2, u, v, w)
                det = (a[0] * (b[1] * e[2] - b[2] * e[1]) - a[1] * (b[0] * e[2] - b[2] * e[0])
                       + a[2] * (b[0] * e[1] - b[1] * e[0]))
                vol += wu * wv * ww * det
    return vol


def lattice(r, tmp):
    m = load(r, "arch-lattice.json")
    want = sum(trilinear_volume(b["corners"]) for b in m["bodies"])
    mesh = mesh_off(r, tmp, "arch-lattice.json")
    if not mesh:
        return
    check_closed_volume(r, "arch-lattice.json", mesh, want, m["tolerance"])
    verts, faces = mesh
    inner = [f for f in faces if any(all(abs(verts[i][0] - x) < 1e-9 for i in f)
                                     for x in (20.0, 40.0, 60.0))]
    r.check("arch-lattice.json: no triangle on the shared faces x = 20, 40, 60",
            not inner, f"{len(inner)} triangles")


def morph(r, tmp, v1):
    m = load(r, "morph.json")
    v0 = trilinear_volume(m["define"]["block"]["corners"])
    tol = m["tolerance"]
    t = m["bodies"][0]["t"]
    mesh = mesh_off(r, tmp, "morph.json")
    if mesh:
        check_closed_volume(r, f"morph.json at its t = {t}", mesh, (1 - t) * v0 + t * v1, tol)
    mesh = mesh_off(r, tmp, "morph.json", ["--time", "0.25"])
    if mesh:
        check_closed_volume(r, "morph.json --time 0.25", mesh, 0.75 * v0 + 0.25 * v1, tol)
    pattern = os.path.join(tmp, "rise-%d.off")
    st, _, err = r.run([model_path(r, "morph.json"), "--frames", "3", "-o", pattern, "-q"])
    r.check("morph.json --frames 3 writes three frames", st == 0 and all(
        os.path.exists(pattern % k) for k in range(3)), err)
    for k in range(3):
        if os.path.exists(pattern % k):
            t = k / 2
            check_closed_volume(r, f"morph.json frame {k} (t = {t})", read_off(pattern % k),
                                (1 - t) * v0 + t * v1, tol)


def calculix(r, tmp):
    d = os.path.join(tmp, "ccx")
    os.makedirs(d)
    st, _, err = r.run([model_path(r, "arch-lattice.json"), "-o",
                        os.path.join(d, "arch27.inp"), "--element", "hex27"])
    r.check("arch-lattice.json --element hex27 -o .inp is refused, nothing written",
            st != 0 and not os.path.exists(os.path.join(d, "arch27.inp")), err)
    st, _, err = r.run([model_path(r, "arch-lattice.json"), "-o", os.path.join(d, "arch.inp"),
                        "--element", "hex20", "-q"])
    if not r.check("arch-lattice.json: coons2stl writes arch.inp (hex20)", st == 0, err):
        return
    nodes, elems, nsets, _, _ = read_inp(os.path.join(d, "arch.inp"))
    r.check("arch.inp: C3D20 cells only", elems and all(t == "C3D20" for t, _ in elems.values()))
    shutil.copy(model_path(r, "arch-gravity.inp"), d)
    p = subprocess.run(["ccx", "-i", "arch-gravity"], cwd=d, capture_output=True, text=True,
                       timeout=600)
    if not r.check("arch-gravity.inp: ccx solves it", p.returncode == 0 and
                   "*ERROR" not in p.stdout, (p.stdout + p.stderr)[-2000:]):
        return
    rows = read_dat(os.path.join(d, "arch-gravity.dat")).get("displacements", [])
    u = {int(row[0]): row[1:4] for row in rows}
    crown = nsets.get("C1_U1", [])
    r.check(f"the crown's {len(crown)} nodes are printed, all at x = 40",
            crown and set(u) == set(crown) and all(abs(nodes[n][0] - 40) < 1e-9 for n in crown))
    if not crown or set(u) != set(crown):
        return
    uz = max(abs(u[n][2]) for n in crown)
    r.check(f"the crown moves down (|u_z| up to {uz:.3g})", all(u[n][2] < 0 for n in crown))
    ux = max(abs(u[n][0]) for n in crown)
    r.check(f"symmetry about x = 40: u_x = 0 at the crown ({ux:.1e} against u_z {uz:.1e})",
            ux <= 1e-9 * uz)
    by_pos = {(round(nodes[n][1], 9), round(nodes[n][2], 9)): n for n in crown}
    worst, pairs = 0.0, 0
    for (y, z), n in by_pos.items():
        m = by_pos.get((round(10 - y, 9), z))
        if m is not None:
            pairs += 1
            worst = max(worst, abs(u[n][2] - u[m][2]))
    r.check(f"symmetry about y = 5: u_z(y) = u_z(10 - y) over {pairs} nodes, off by {worst:.1e}",
            pairs == len(crown) and worst <= 1e-6 * uz)


def main():
    r = Runner(__doc__)
    tmp = tempfile.mkdtemp(prefix="coons-tutorial-")
    try:
        bodies2(r, tmp)
        domed = load(r, "morph.json")["define"]["domed"]["faces"]["w1"]
        v1 = height_field_volume(r, "morph.json's key 'domed'", domed, (0, 0), (40, 30), 0.0)
        even_spacing(r, tmp)
        lattice(r, tmp)
        morph(r, tmp, v1)
        calculix(r, tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    r.finish()


if __name__ == "__main__":
    main()
