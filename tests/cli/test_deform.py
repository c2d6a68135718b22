#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""coons2stl --deform IN (free-form deformation), checked against values
computed here, not by libcoons:

- an affine body (body0 of a parallelepiped o + A q): a sphere STL comes
  out with its triangles unsplit and every corner at o + A (p - lo)/(hi - lo)
  (lo, hi: the file's float32 bounding box, or --frame), computed here;
  a mirrored parallelepiped (left-handed) keeps the output outward;
- a bar bent by a body2 (a quarter of a thick ring: planar and NURBS arc
  faces, whose transfinite interpolant is exactly F(u,v,w) = ((R + T w)
  c(u), H v), c the rational quadratic unit arc written out here): closed,
  2-manifold, oriented, Euler characteristic 2; within the tolerance at
  2400 points of the bar's faces mapped by F (brute-force point-triangle
  distance); its volume equals the integral of det J = H T (R + T w)
  dtheta/du over the bar's parameter box, in closed form
  H dv (r1^2 - r0^2)/2 dtheta, up to tolerance x area;
- a sphere STL through the spool (examples/spool.json): closed and outward,
  and its STL read by admesh (nothing repaired), PrusaSlicer --info
  (manifold, nothing repaired, the file's facets and volume) and OpenSCAD
  (import() rendered to STL; the .scad output rendered too: the same
  volume);
- --info: the frame, the counts, the deviation within 0.9 x the tolerance,
  and an open input reported as open;
- bad input (a truncated STL, NaN coordinates, an out-of-range OFF index,
  points outside --frame, bad --frame): non-zero exit, the byte offset or
  line:column in the message, an existing output byte-for-byte unchanged
  and nothing else created.

Usage: test_deform.py --bin <coons2stl> --src <source dir> --build <build dir>
"""
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile

try:
    import numpy as np
except ImportError:
    # Debian's python3-numpy is seen by the system interpreter only (as for
    # the test_volume_* tests): run again with it.
    if os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3") and \
            os.path.exists("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    raise

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clitest import Runner  # noqa: E402

# ---- meshes written here ---------------------------------------------------------


def icosphere(level, radius, center):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
         (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        mid, nf = {}, []

        def m(a, b):
            k = (min(a, b), max(a, b))
            if k not in mid:
                p = [(v[a][i] + v[b][i]) / 2 for i in range(3)]
                n = math.sqrt(sum(x * x for x in p))
                v.append(tuple(x / n for x in p))
                mid[k] = len(v) - 1
            return mid[k]
        for a, b, c in f:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = nf
    V = np.array(v) * radius + np.array(center)
    return V, np.array(f)


def box(lo, hi):
    """12 triangles, outward."""
    V = np.array([[hi[0] if n & 4 else lo[0], hi[1] if n & 2 else lo[1],
                   hi[2] if n & 1 else lo[2]] for n in range(8)])
    F = np.array([(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
                  (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)])
    return V, F


def write_stl(path, V, F, ascii_=False):
    T = V[F]
    if ascii_:
        with open(path, "w") as fh:
            fh.write("solid test\n")
            for t in T:
                fh.write(" facet normal 0 0 0\n  outer loop\n")
                for p in t:
                    fh.write("   vertex %.17g %.17g %.17g\n" % tuple(p))
                fh.write("  endloop\n endfacet\n")
            fh.write("endsolid test\n")
        return
    with open(path, "wb") as fh:
        fh.write(b"test".ljust(80, b" ") + struct.pack("<I", len(T)))
        for t in T:
            fh.write(struct.pack("<12fH", 0, 0, 0, *t.reshape(-1), 0))


def read_stl(path):
    with open(path, "rb") as fh:
        d = fh.read()
    (n,) = struct.unpack_from("<I", d, 80)
    assert len(d) == 84 + 50 * n
    a = np.frombuffer(d[84:], dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)),
                                              ("a", "<u2")]))
    return a["v"].astype(float)


def weld(T):
    """Triangle soup -> (V, F) by exact coordinates."""
    idx, V, F = {}, [], []
    for t in T:
        f = []
        for p in t:
            k = tuple(p)
            if k not in idx:
                idx[k] = len(V)
                V.append(p)
            f.append(idx[k])
        F.append(f)
    return np.array(V), np.array(F)


def read_off(path):
    with open(path) as fh:
        lines = [ln.split("#")[0].split() for ln in fh]
    lines = [ln for ln in lines if ln]
    assert lines[0] == ["OFF"]
    nv, nf = int(lines[1][0]), int(lines[1][1])
    V = np.array([[float(x) for x in ln] for ln in lines[2:2 + nv]])
    F = np.array([[int(x) for x in ln[1:4]] for ln in lines[2 + nv:2 + nv + nf]])
    return V, F


def topology(V, F):
    """(closed and manifold and oriented, Euler characteristic)."""
    directed = {}
    for f in F:
        for k in range(3):
            e = (int(f[k]), int(f[(k + 1) % 3]))
            directed[e] = directed.get(e, 0) + 1
    ok = all(c == 1 and directed.get((e[1], e[0])) == 1 for e, c in directed.items())
    used = len(set(int(i) for i in F.reshape(-1)))
    return ok, used - len(directed) // 2 + len(F)


def volume(T):
    return float(np.einsum("ij,ij->i", T[:, 0], np.cross(T[:, 1], T[:, 2])).sum() / 6)


def area(T):
    return float(np.linalg.norm(np.cross(T[:, 1] - T[:, 0], T[:, 2] - T[:, 0]), axis=1).sum() / 2)


def seg_dist(P, A, B):
    """|P - AB| for points P (n,1,3) and segments A, B (1,m,3)."""
    ab = B - A
    s = np.clip(np.einsum("nmk,nmk->nm", P - A, np.broadcast_to(ab, (P.shape[0],) + ab.shape[1:]))
                / np.maximum(np.einsum("nmk,nmk->nm", ab, ab), 1e-300), 0, 1)
    return np.linalg.norm(A + s[..., None] * ab - P, axis=2)


def mesh_distance(P, T):
    """Distance from each point to the triangles T (brute force)."""
    out = []
    A, B, C = T[None, :, 0], T[None, :, 1], T[None, :, 2]
    n = np.cross(B - A, C - A)
    nn = np.einsum("nmk,nmk->nm", n, n)
    for i in range(0, len(P), 32):
        Q = P[i:i + 32, None, :]
        d = np.einsum("nmk,nmk->nm", Q - A, np.broadcast_to(n, (Q.shape[0],) + n.shape[1:])) / nn
        foot = Q - d[..., None] * n
        inside = np.ones(d.shape, bool)
        for X, Y in ((A, B), (B, C), (C, A)):
            inside &= np.einsum("nmk,nmk->nm", np.cross(X - foot, Y - foot),
                                np.broadcast_to(n, foot.shape)) >= 0
        plane = np.where(inside, np.abs(d) * np.sqrt(nn), np.inf)
        best = np.minimum(plane, np.minimum(seg_dist(Q, A, B),
                                            np.minimum(seg_dist(Q, B, C), seg_dist(Q, C, A))))
        out.append(best.min(axis=1))
    return np.concatenate(out)


# ---- the bodies ------------------------------------------------------------------

ARC = [(1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
WARC = [1.0, math.sqrt(0.5), 1.0]
R0, TH, H = 10.0, 4.0, 6.0  # inner radius, thickness (w), height (v)


def arc(u):
    b = [(1 - u) ** 2, 2 * u * (1 - u), u * u]
    s = sum(WARC[i] * b[i] for i in range(3))
    return [sum(WARC[i] * b[i] * ARC[i][k] for i in range(3)) / s for k in range(2)]


def bend(q):
    """The exact map of the ring body: ((R0 + TH w) c(u), H v)."""
    u, v, w = q
    c, r = arc(u), R0 + TH * w
    return [r * c[0], r * c[1], H * v]


def ring_model():
    def surf(pts, weights, deg):
        return {"type": "bspline-surface", "degree": deg, "points": pts, "weights": weights}

    def radial(K):  # w = K: (s,t) = (u,v)
        r = R0 + TH * K
        return surf([[[r * a[0], r * a[1], H * j] for j in (0, 1)] for a in ARC],
                    [[wt, wt] for wt in WARC], [2, 1])

    def height(J):  # v = J: (s,t) = (u,w)
        return surf([[[(R0 + TH * k) * a[0], (R0 + TH * k) * a[1], H * J] for k in (0, 1)]
                     for a in ARC], [[wt, wt] for wt in WARC], [2, 1])

    def end(I):  # u = I: (s,t) = (v,w)
        a = ARC[2 * I]
        return surf([[[(R0 + TH * k) * a[0], (R0 + TH * k) * a[1], H * j] for k in (0, 1)]
                     for j in (0, 1)], [[1, 1], [1, 1]], [1, 1])

    faces = {"u0": end(0), "u1": end(1), "v0": height(0), "v1": height(1),
             "w0": radial(0), "w1": radial(1)}
    return {"coons": 1, "units": "mm", "bodies": [{"type": "body2", "name": "ring",
                                                   "faces": faces}]}


O = np.array([1.0, -2.0, 0.5])
A = np.array([[4.0, 1.0, 0.6], [0.2, 6.0, -0.8], [0.4, 0.0, 3.0]])


def parallelepiped(mirror=False):
    M = np.diag([-1.0, 1.0, 1.0]) if mirror else np.eye(3)
    corners = [list(M @ (O + A @ np.array([n >> 2, (n >> 1) & 1, n & 1], float)))
               for n in range(8)]
    return {"coons": 1, "units": "mm",
            "bodies": [{"type": "body0", "name": "box", "corners": corners}]}


# ---- the tests ---------------------------------------------------------------------


class T:
    def __init__(self, r, tmp):
        self.r, self.tmp = r, tmp

    def path(self, name):
        return os.path.join(self.tmp, name)

    def model(self, name, m):
        p = self.path(name)
        with open(p, "w") as fh:
            json.dump(m, fh)
        return p


def test_affine(t):
    r = t.r
    V, F = icosphere(2, 2.0, (3.0, -1.0, 2.0))
    stl = t.path("sphere.stl")
    write_stl(stl, V, F)
    Tin = read_stl(stl)  # the float32 corners the file holds
    for mirror in (False, True):
        label = "mirrored parallelepiped" if mirror else "parallelepiped"
        model = t.model("pp%d.json" % mirror, parallelepiped(mirror))
        M = np.diag([-1.0, 1.0, 1.0]) if mirror else np.eye(3)
        for frame in (None, [1.0, -3.5, -0.5, 5.5, 1.5, 4.25]):
            out = t.path("pp.off")
            args = [model, "--deform", stl, "-o", out]
            if frame:
                args += ["--frame", ",".join("%.17g" % x for x in frame)]
            st, _, err = r.run(args)
            if not r.check(f"{label} {'--frame' if frame else 'bbox frame'}: exit 0",
                           st == 0, err):
                continue
            Vo, Fo = read_off(out)
            lo = np.array(frame[:3]) if frame else Tin.reshape(-1, 3).min(axis=0)
            hi = np.array(frame[3:]) if frame else Tin.reshape(-1, 3).max(axis=0)
            r.check(f"{label}: {len(F)} triangles in, as many out (no splitting)",
                    len(Fo) == len(F), f"{len(Fo)}")
            want = (M @ (O[:, None] + A @ ((Tin.reshape(-1, 3) - lo) / (hi - lo)).T)).T
            got = Vo[Fo[:, [0, 2, 1]] if mirror else Fo].reshape(-1, 3)
            if len(Fo) == len(F):
                err_ = np.abs(got - want).max()
                r.check(f"{label}: every corner at o + A (p - lo)/(hi - lo) (worst {err_:.2g})",
                        err_ <= 1e-13 * 10, "")
            ok, euler = topology(Vo, Fo)
            vol = volume(Vo[Fo])
            vin = volume(Tin)
            exact = vin * abs(np.linalg.det(A)) / np.prod(hi - lo)
            r.check(f"{label}: closed, oriented, Euler 2, outward volume {vol:.9g} = "
                    f"{exact:.9g}", ok and euler == 2 and abs(vol - exact) <= 1e-10 * exact,
                    f"{ok} {euler}")


def test_bent_bar(t):
    r = t.r
    model = t.model("ring.json", ring_model())
    lo_box, hi_box = [1.0, 0.5, 0.25], [9.0, 1.5, 0.75]
    V, F = box(lo_box, hi_box)
    stl = t.path("bar.stl")
    write_stl(stl, V, F)
    frame = [0.0, 0.0, 0.0, 10.0, 2.0, 1.0]
    tol = 0.01
    out = t.path("bar.off")
    args = [model, "--deform", stl, "--frame", "0,0,0,10,2,1", "-t", str(tol)]
    st, _, err = r.run(args + ["-o", out])
    if not r.check("bent bar: exit 0", st == 0, err):
        return
    Vo, Fo = read_off(out)
    ok, euler = topology(Vo, Fo)
    r.check(f"bent bar: split ({len(Fo)} triangles), closed, 2-manifold, oriented, Euler 2",
            len(Fo) > 100 and ok and euler == 2, f"{ok} {euler}")
    # dense points of the bar's faces, mapped exactly
    g = (np.arange(20) + 0.5) / 20
    pts = []
    for d in range(3):
        a, b = [k for k in range(3) if k != d]
        for side in (lo_box[d], hi_box[d]):
            for s in g:
                for tt in g:
                    p = [0.0] * 3
                    p[d] = side
                    p[a] = lo_box[a] + s * (hi_box[a] - lo_box[a])
                    p[b] = lo_box[b] + tt * (hi_box[b] - lo_box[b])
                    q = [(p[k] - frame[k]) / (frame[k + 3] - frame[k]) for k in range(3)]
                    pts.append(bend(q))
    dist = mesh_distance(np.array(pts), Vo[Fo])
    r.check(f"bent bar: {len(pts)} exact image points within the tolerance {tol} "
            f"(worst {dist.max():.3g})", dist.max() <= tol)
    # the volume: the integral of det J over the parameter box, closed form
    q0 = [(lo_box[k] - frame[k]) / (frame[k + 3] - frame[k]) for k in range(3)]
    q1 = [(hi_box[k] - frame[k]) / (frame[k + 3] - frame[k]) for k in range(3)]
    th = [math.atan2(*reversed(arc(u))) for u in (q0[0], q1[0])]
    r0, r1 = R0 + TH * q0[2], R0 + TH * q1[2]
    exact = H * (q1[1] - q0[1]) * (r1 * r1 - r0 * r0) / 2 * (th[1] - th[0])
    vol, ar = volume(Vo[Fo]), area(Vo[Fo])
    r.check(f"bent bar: volume {vol:.7g} = integral of det J {exact:.7g} within tol x area "
            f"({tol * ar:.3g})", abs(vol - exact) <= tol * ar)
    # ten times finer: the error shrinks with the tolerance (chords: about
    # tenfold), to the integral of det J
    fine = t.path("bar-fine.off")
    st, _, err = r.run([model, "--deform", stl, "--frame", "0,0,0,10,2,1", "-t", str(tol / 10),
                        "-o", fine])
    if r.check("bent bar at tol/10: exit 0", st == 0, err):
        Vf, Ff = read_off(fine)
        vf = volume(Vf[Ff])
        r.check(f"bent bar at tol/10: volume {vf:.8g}, error {abs(vf - exact):.3g} < 1/4 of "
                f"{abs(vol - exact):.3g} and within tol/10 x area",
                abs(vf - exact) < abs(vol - exact) / 4 and
                abs(vf - exact) <= tol / 10 * area(Vf[Ff]))
    # --info
    st, so, err = r.run(args + ["--info"])
    if r.check("bent bar --info: exit 0", st == 0, err):
        info = json.loads(so)["deform"]
        r.check("--info: frame, counts, closed input, deviation <= 0.9 tol",
                info["frame"]["min"] == frame[:3] and info["frame"]["max"] == frame[3:]
                and info["input_triangles"] == 12 and info["output_triangles"] == len(Fo)
                and info["input_closed"] is True and info["output_mesh"]["closed"] is True
                and 0 < info["deviation"] <= 0.9 * tol and info["tolerance"] == tol,
                json.dumps(info))
    # an open bar (one face left out): deformed as it is, reported
    open_stl = t.path("open.stl")
    write_stl(open_stl, V, F[:-2])
    st, so, err = r.run([model, "--deform", open_stl, "--frame", "0,0,0,10,2,1", "--info"])
    if r.check("open bar --info: exit 0", st == 0, err):
        info = json.loads(so)["deform"]
        r.check("open bar: input_closed false, output open too, a warning",
                info["input_closed"] is False and info["output_mesh"]["closed"] is False
                and info["output_mesh"]["boundary_edges"] > 0 and "not a closed" in err,
                json.dumps(info) + err)


def grid_box(lo, hi, n):
    """A box with n x n squares per face, two triangles each, outward, its
    vertices shared."""
    idx, V, F = {}, [], []

    def vid(k):
        if k not in idx:
            idx[k] = len(V)
            V.append([lo[d] + (hi[d] - lo[d]) * k[d] / n for d in range(3)])
        return idx[k]

    for d in range(3):
        a, b = (d + 1) % 3, (d + 2) % 3
        for side in (0, n):
            for i in range(n):
                for j in range(n):
                    c = []
                    for (s, t) in ((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)):
                        k = [0, 0, 0]
                        k[d], k[a], k[b] = side, s, t
                        c.append(vid(tuple(k)))
                    if side == 0:
                        c = [c[0], c[3], c[2], c[1]]
                    F += [(c[0], c[1], c[2]), (c[0], c[2], c[3])]
    return np.array(V, float), np.array(F)


def bend_np(Q):
    """bend() of the rows of Q."""
    u, v, w = Q[:, 0], Q[:, 1], Q[:, 2]
    b = [(1 - u) ** 2, 2 * u * (1 - u), u * u]
    s = sum(WARC[i] * b[i] for i in range(3))
    c = [sum(WARC[i] * b[i] * ARC[i][k] for i in range(3)) / s for k in range(2)]
    r = R0 + TH * w
    return np.stack([r * c[0], r * c[1], H * v], axis=1)


def unbend_np(X):
    """The parameters of image points of bend() (u by bisection on the
    angle, which grows with u)."""
    w = (np.hypot(X[:, 0], X[:, 1]) - R0) / TH
    th = np.arctan2(X[:, 1], X[:, 0])
    lo, hi = np.zeros(len(X)), np.ones(len(X))
    for _ in range(60):
        mid = (lo + hi) / 2
        c = bend_np(np.stack([mid, np.zeros(len(X)), np.zeros(len(X))], axis=1))
        below = np.arctan2(c[:, 1], c[:, 0]) < th
        lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
    return np.stack([(lo + hi) / 2, X[:, 2] / H, w], axis=1)


def tri_dist_paired(P, A, B, C):
    """|P_i - triangle A_i B_i C_i| for rows i."""
    n = np.cross(B - A, C - A)
    nn = np.einsum("ij,ij->i", n, n)
    d = np.einsum("ij,ij->i", P - A, n) / nn
    foot = P - d[:, None] * n
    inside = np.ones(len(P), bool)
    for X, Y in ((A, B), (B, C), (C, A)):
        inside &= np.einsum("ij,ij->i", np.cross(X - foot, Y - foot), n) >= 0

    def seg(X, Y):
        xy = Y - X
        t = np.clip(np.einsum("ij,ij->i", P - X, xy) / np.maximum(np.einsum("ij,ij->i", xy, xy),
                                                                   1e-300), 0, 1)
        return np.linalg.norm(X + t[:, None] * xy - P, axis=1)

    edge = np.minimum(seg(A, B), np.minimum(seg(B, C), seg(C, A)))
    return np.where(inside, np.abs(d) * np.sqrt(nn), edge)


def test_fine_bar(t):
    """A finely tessellated bar through the ring (enough triangles for the
    error estimate to run): the same bytes on 1 and 3 threads (-j), closed
    and oriented, and at 3 points of every output triangle the exact image of
    their parameter point (the output's vertices mapped back to parameters by
    the closed-form inverse, interpolated, mapped by F) within the tolerance
    of that triangle."""
    r = t.r
    model = t.model("ring.json", ring_model())
    V, F = grid_box([1.0, 0.5, 0.25], [9.0, 1.5, 0.75], 16)
    stl = t.path("fine-bar.stl")
    write_stl(stl, V, F)
    for tol in (0.05, 0.004):
        outs = []
        for j in (1, 3):  # the same file name (an OFF file names its mesh after it)
            os.makedirs(t.path(f"j{j}"), exist_ok=True)
            out = t.path(f"j{j}/fine-bar-{tol}.off")
            st, _, err = r.run([model, "--deform", stl, "--frame", "0,0,0,10,2,1", "-t", str(tol),
                                "-j", str(j), "-o", out])
            if not r.check(f"fine bar at {tol}, -j {j}: exit 0", st == 0, err):
                return
            with open(out, "rb") as fh:
                outs.append(fh.read())
        r.check(f"fine bar at {tol}: -j 1 and -j 3 write the same bytes", outs[0] == outs[1])
        Vo, Fo = read_off(t.path(f"j1/fine-bar-{tol}.off"))
        ok, euler = topology(Vo, Fo)
        r.check(f"fine bar at {tol}: {len(F)} -> {len(Fo)} triangles, closed, 2-manifold, "
                f"oriented, Euler 2", ok and euler == 2, f"{ok} {euler}")
        Qv = unbend_np(Vo)
        r.check(f"fine bar at {tol}: the output's vertices are exact images",
                np.abs(bend_np(Qv) - Vo).max() <= 1e-9)
        rng = np.random.default_rng(7)
        worst = 0.0
        for _ in range(3):
            lam = rng.dirichlet([1, 1, 1], len(Fo))
            Q = np.einsum("ik,ikd->id", lam, Qv[Fo])
            d = tri_dist_paired(bend_np(Q), Vo[Fo[:, 0]], Vo[Fo[:, 1]], Vo[Fo[:, 2]])
            worst = max(worst, float(d.max()))
        r.check(f"fine bar at {tol}: exact images of 3 parameter points of each of the "
                f"{len(Fo)} triangles within the tolerance (worst {worst:.3g})", worst <= tol)


def run_tool(argv, timeout=300):
    return subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=timeout)


def test_spool(t):
    r = t.r
    spool = os.path.join(r.src, "examples", "spool.json")
    V, F = icosphere(3, 5.0, (0.0, 0.0, 0.0))
    stl = t.path("ball.stl")
    write_stl(stl, V, F, ascii_=True)
    out = t.path("ball-spool.stl")
    st, _, err = r.run([spool, "--deform", stl, "--body", "spool", "-o", out])
    if not r.check("sphere through the spool: exit 0", st == 0, err):
        return
    Tout = read_stl(out)
    Vw, Fw = weld(Tout)
    ok, euler = topology(Vw, Fw)
    vol = volume(Tout)
    r.check(f"sphere through the spool: {len(Tout)} triangles, closed, oriented, Euler 2, "
            f"outward (volume {vol:.6g})", ok and euler == 2 and vol > 0, f"{ok} {euler}")
    # admesh
    if r.need("admesh"):
        p = run_tool(["admesh", out])
        rep = p.stdout
        bad = [ln for ln in rep.splitlines() if any(
            ln.startswith(k) for k in ("Degenerate facets", "Edges fixed", "Facets removed",
                                       "Facets added", "Facets reversed", "Backwards edges",
                                       "Normals fixed")) and not ln.rstrip().endswith(" 0")]
        r.check("admesh: exit 0, nothing repaired, %d facets" % len(Tout),
                p.returncode == 0 and not bad and
                ("Number of facets     :  %5d  %5d" % (len(Tout), len(Tout))) in rep
                or (p.returncode == 0 and not bad and "%d" % len(Tout) in rep), rep)
    # PrusaSlicer --info
    if r.need("prusa-slicer"):
        p = subprocess.run(["prusa-slicer", "--info", "--loglevel", "1", out],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                           timeout=600)
        kv = dict(ln.strip().split(" = ", 1) for ln in p.stdout.splitlines() if " = " in ln)
        repairs = [k for k in ("degenerate_facets", "edges_fixed", "facets_removed",
                               "facets_reversed", "backwards_edges", "open_edges") if k in kv]
        try:
            pv = float(kv.get("volume", "nan"))
        except ValueError:
            pv = float("nan")
        r.check(f"prusa-slicer --info: manifold, nothing repaired, {len(Tout)} facets, "
                f"volume {pv:.7g} = {vol:.7g}",
                p.returncode == 0 and kv.get("manifold") == "yes" and not repairs
                and kv.get("number_of_facets") == str(len(Tout)) and abs(pv - vol) <= 1e-4 * vol,
                p.stdout + p.stderr)
    # OpenSCAD: import() of the STL, and the .scad output, each rendered to STL
    if r.need("openscad"):
        scad_in = t.path("import.scad")
        with open(scad_in, "w") as fh:
            fh.write('import("ball-spool.stl");\n')
        scad_out = t.path("ball-spool.scad")
        st, _, err = r.run([spool, "--deform", stl, "--body", "spool", "-o", scad_out])
        r.check("sphere through the spool -o .scad: exit 0", st == 0, err)
        for label, src in (("import()", scad_in), (".scad output", scad_out)):
            rendered = t.path("rendered.stl")
            if os.path.exists(rendered):
                os.remove(rendered)
            p = subprocess.run(["openscad", "-o", rendered, src], cwd=t.tmp,
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                               timeout=600)
            if not r.check(f"openscad {label} renders to STL", p.returncode == 0 and
                           os.path.exists(rendered), p.stdout[-2000:]):
                continue
            with open(rendered, "rb") as fh:
                head = fh.read(5)
            if head == b"solid":
                tri = []
                with open(rendered) as fh:
                    cur = []
                    for ln in fh:
                        w = ln.split()
                        if w and w[0] == "vertex":
                            cur.append([float(x) for x in w[1:4]])
                            if len(cur) == 3:
                                tri.append(cur)
                                cur = []
                Tr = np.array(tri)
            else:
                Tr = read_stl(rendered)
            Vr, Fr = weld(Tr)
            okr, eulr = topology(Vr, Fr)
            vr = volume(Tr)
            r.check(f"openscad {label}: closed, oriented, Euler 2, volume {vr:.7g} = {vol:.7g}",
                    okr and eulr == 2 and abs(vr - vol) <= 1e-5 * vol, f"{okr} {eulr}")


def snapshot(d):
    return sorted(os.listdir(d))


def test_errors(t):
    r = t.r
    model = t.model("pp-err.json", parallelepiped())
    V, F = box([0, 0, 0], [1, 1, 1])
    good = t.path("good.stl")
    write_stl(good, V, F)
    with open(good, "rb") as fh:
        data = fh.read()
    out = t.path("kept.stl")
    old = b"an existing output\n"

    def refused(label, args, status, words, name=None):
        with open(out, "wb") as fh:
            fh.write(old)
        before = snapshot(t.tmp)
        st, so, err = r.run([model] + args + ["-o", out])
        with open(out, "rb") as fh:
            same = fh.read() == old
        r.check(f"{label}: exit {status}, says {words}, output unchanged, nothing created",
                st == status and all(w in err for w in words) and same
                and snapshot(t.tmp) == before, f"status {st}: {err}")

    cut = t.path("cut.stl")
    with open(cut, "wb") as fh:
        fh.write(data[:84 + 50 * 7 + 20])
    refused("truncated binary STL", ["--deform", cut], 1,
            [cut + ": byte 454: truncated", "inside triangle 7"])
    long_ = t.path("long.stl")
    with open(long_, "wb") as fh:
        fh.write(data + b"\0" * 10)
    refused("count disagreeing with the size", ["--deform", long_], 1,
            [long_ + ": byte 80: the triangle count 12 disagrees with the file size"])
    nan = t.path("nan.stl")
    with open(nan, "wb") as fh:
        # triangle 3, corner 2, z: 84 + 150 + 12 + 24 + 8 = 278
        fh.write(data[:278] + struct.pack("<f", float("nan")) + data[282:])
    refused("NaN in a binary STL", ["--deform", nan], 1,
            [nan + ": byte 278: triangle 3, corner 2: z = nan is not a finite number"])
    asc = t.path("nan-ascii.stl")
    write_stl(asc, V, F, ascii_=True)
    with open(asc) as fh:
        lines = fh.read().split("\n")
    lines[10] = "   vertex 1 nan 0"  # line 11, the y at column 13
    with open(asc, "w") as fh:
        fh.write("\n".join(lines))
    refused("NaN in an ASCII STL", ["--deform", asc], 1,
            [asc + ":11:13: y = nan is not a finite number"])
    off = t.path("bad.off")
    with open(off, "w") as fh:
        fh.write("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n")
    refused("OFF index out of range", ["--deform", off], 1,
            [off + ":6:7: face 0: vertex index 3 is out of range"])
    refused("too many triangles", ["--deform", good, "--max-triangles", "11"], 1,
            ["byte 80: 12 triangles, more than the limit of 11 triangles"])
    refused("points outside the frame", ["--deform", good, "--frame", "0,0,0,1,1,0.5"], 1,
            ["4 of the 8 points lie outside the frame"])
    refused("a flat --frame", ["--deform", good, "--frame", "0,0,0,1,1,0"], 2,
            ["--frame", "empty along z"])
    refused("a bad --frame", ["--deform", good, "--frame", "0,0,0,1,1"], 2,
            ["--frame needs six numbers"])
    refused("--frame without --deform", ["--frame", "0,0,0,1,1,1"], 2,
            ["--frame is for --deform"])
    refused("the output is the input", ["--deform", out], 2, ["refusing to overwrite"])
    st, _, err = r.run([model, "--deform", good, "-o", t.path("x.msh")])
    r.check("--deform to a volume format: exit 2", st == 2 and "surface" in err, err)
    st, _, err = r.run([model, "--deform", good, "-o", t.path("x.vtu")])
    with open(t.path("x.vtu"), "rb") as fh:
        vtu = fh.read()
    r.check("--deform to .vtu: a surface (12 triangles, VTK_TRIANGLE cells)",
            st == 0 and b"UnstructuredGrid" in vtu and b'NumberOfCells="12"' in vtu, err)
    two = parallelepiped()
    two["bodies"].append(dict(two["bodies"][0], name="second"))
    st, _, err = r.run([t.model("two.json", two), "--deform", good, "-o", t.path("two.stl")])
    r.check("two bodies, no --body: body 0, with a warning naming it",
            st == 0 and "deforming through body 0 ('box')" in err, err)
    st, _, err = r.run([model, "--deform", t.path("missing.stl"), "-o", t.path("y.stl")])
    r.check("a missing input: exit 1, names it", st == 1 and "missing.stl" in err and
            not os.path.exists(t.path("y.stl")), err)


def main():
    r = Runner(__doc__)
    tmp = tempfile.mkdtemp(prefix="coons-deform-")
    try:
        t = T(r, tmp)
        test_affine(t)
        test_bent_bar(t)
        test_fine_bar(t)
        test_errors(t)
        test_spool(t)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    r.finish()


if __name__ == "__main__":
    main()
