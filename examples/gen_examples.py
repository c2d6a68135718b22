#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Generates the example models in examples/ and verifies each one.

    python3 examples/gen_examples.py            write examples/*.json, verify, summarise
    python3 examples/gen_examples.py --check    verify that the files on disk are exactly
                                                what this script writes (nothing is written)

Every model is built from control data (a control net, or corner points plus
edge shapes) so that body 1 edges meet at the 8 corners and body 2 faces share
their 12 edges parametrically by construction (the faces of a body 2 are the
six boundary layers of one control volume, or Coons patches over one set of 12
edge curves). Each model is then checked numerically with the independent
evaluator in coons_ref.py, on the JSON text as written: corners, shared edges
at many parameters, boundary faces, closed forms where there are any, det J.
Output is deterministic (no time stamps, fixed key order, shortest round-trip
number formatting). Standard library only.
"""

import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import coons_ref as R  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
S2 = math.sqrt(0.5)  # weight of the middle point of a rational quarter circle

# ================================================================ helpers


def num(x):
    """Tidy a coordinate: integers stay integers, -0 becomes 0, and values that
    are a rounding away from a short decimal are snapped to it."""
    x = float(x)
    if x == 0:
        return 0
    r = round(x, 12)
    if abs(r - x) < 1e-13 * max(1.0, abs(x)):
        x = r
    if x == int(x) and abs(x) < 1e15:
        return int(x)
    return x


def P(*c):
    return [num(v) for v in c]


def lerp(a, b, t):
    return [a[d] + t * (b[d] - a[d]) for d in range(3)]


def model(bodies, operation=None, units="mm", tolerance=None):
    m = {"coons": 1, "units": units}
    if tolerance is not None:
        m["tolerance"] = tolerance
    if operation is not None:
        m["operation"] = operation
    m["bodies"] = bodies
    return m


def cube_corner(i, j, k, size=10.0, origin=(0.0, 0.0, 0.0)):
    return [origin[0] + size * i, origin[1] + size * j, origin[2] + size * k]


EDGE_KEYS = ["u00", "u01", "u10", "u11", "v00", "v01", "v10", "v11",
             "w00", "w01", "w10", "w11"]


def edge_ends(key):
    """Corner indices (i,j,k) at the start and the end of body 1 edge `key`."""
    ax, a, b = key[0], int(key[1]), int(key[2])
    if ax == "u":
        return (0, a, b), (1, a, b)
    if ax == "v":
        return (a, 0, b), (a, 1, b)
    return (a, b, 0), (a, b, 1)


def body1(corner, make_edge, name=None, blend=None):
    """Body 1 whose edge `key` is make_edge(key, start_corner, end_corner)."""
    edges = {}
    for key in EDGE_KEYS:
        s, e = edge_ends(key)
        edges[key] = make_edge(key, corner(*s), corner(*e))
    b = {"type": "body1"}
    if name:
        b["name"] = name
    if blend:
        b["blend"] = blend
    b["edges"] = edges
    return b


# Face uI of a body 2 is X_I(v,w), (s,t) = (v,w): its boundary t0 = C(I,v,0) =
# vI0, t1 = vI1, s0 = C(I,0,w) = wI0, s1 = wI1; face vJ = Y_J(u,w): t0 = uJ0,
# t1 = uJ1, s0 = w0J, s1 = w1J; face wK = Z_K(u,v): t0 = u0K, t1 = u1K,
# s0 = v0K, s1 = v1K.
FACE_BOUNDARY = {
    "u0": ("v00", "v01", "w00", "w01"), "u1": ("v10", "v11", "w10", "w11"),
    "v0": ("u00", "u01", "w00", "w10"), "v1": ("u10", "u11", "w01", "w11"),
    "w0": ("u00", "u10", "v00", "v10"), "w1": ("u01", "u11", "v01", "v11"),
}
FACE_KEYS = ["u0", "u1", "v0", "v1", "w0", "w1"]


def body2_coons_faces(edges, make_face):
    """Six faces over one set of 12 edge curves: make_face(key, boundary)."""
    faces = {}
    for fk in FACE_KEYS:
        t0, t1, s0, s1 = FACE_BOUNDARY[fk]
        faces[fk] = make_face(fk, {"t0": edges[t0], "t1": edges[t1],
                                   "s0": edges[s0], "s1": edges[s1]})
    return faces


def layer(net, axis, idx):
    """Boundary layer of a control volume net[i][j][k], as a patch net [s][t]."""
    ni, nj, nk = len(net), len(net[0]), len(net[0][0])
    if axis == "u":
        return [[net[idx][j][k] for k in range(nk)] for j in range(nj)]
    if axis == "v":
        return [[net[i][idx][k] for k in range(nk)] for i in range(ni)]
    return [[net[i][j][idx] for j in range(nj)] for i in range(ni)]


def body2_from_volume(net, degree=None, knots=None, weights=None, name=None, blend=None):
    """Body 2 whose six faces are the boundary layers of one control volume:
    Bezier surfaces when degree is None, else B-spline/NURBS surfaces. Faces
    that share an edge then share its control points, weights and knots, so
    they agree parametrically along it."""
    ni, nj, nk = len(net), len(net[0]), len(net[0][0])
    faces = {}
    pairs = {"u": (1, 2), "v": (0, 2), "w": (0, 1)}
    for fk in FACE_KEYS:
        ax, side = fk[0], int(fk[1])
        idx = side * ([ni, nj, nk]["uvw".index(ax)] - 1)
        pts = layer(net, ax, idx)
        if degree is None:
            faces[fk] = {"type": "bezier-surface", "points": pts}
            continue
        a, b = pairs[ax]
        f = {"type": "bspline-surface", "degree": [degree[a], degree[b]], "points": pts}
        if knots is not None:
            f["knots"] = [knots[a], knots[b]]
        if weights is not None:
            f["weights"] = tidy_net(layer(weights, ax, idx))
        faces[fk] = f
    b = {"type": "body2"}
    if name:
        b["name"] = name
    if blend:
        b["blend"] = blend
    b["faces"] = faces
    return b


def grid_net(n, lo, hi, greville=None):
    """A regular control net n[0] x n[1] x n[2] over the box lo..hi; with
    `greville` (three lists of abscissae in [0,1]) the points sit at those
    parameters, which gives a B-spline volume the identity-like
    parametrisation (linear precision)."""
    net = []
    for i in range(n[0]):
        row = []
        for j in range(n[1]):
            col = []
            for k in range(n[2]):
                q = [i / (n[0] - 1), j / (n[1] - 1), k / (n[2] - 1)]
                if greville:
                    q = [greville[0][i], greville[1][j], greville[2][k]]
                col.append([lo[d] + q[d] * (hi[d] - lo[d]) for d in range(3)])
            row.append(col)
        net.append(row)
    return net


def greville(p, knots):
    k = [float(x) for x in knots]
    a, b = k[p], k[len(k) - p - 1]
    n = len(k) - p - 1
    return [(sum(k[i + 1:i + p + 1]) / p - a) / (b - a) for i in range(n)]


def tidy_net(net):
    if isinstance(net[0], (int, float)):
        return [num(x) for x in net]
    return [tidy_net(x) for x in net]


# ---- round solids: the square (u,v) maps onto a disc with rational quadratics


def disc_net(r, z, cx=0.0, cy=0.0, zero=False):
    """3 x 3 control points of a rational biquadratic disc of radius r at
    height z: the four sides of the square are quarter circles (corners of
    the square at 270, 0, 90, 180 degrees, side middles at the intersection
    of the end tangents), the middle point is the centre."""
    if zero:
        r = 0.0
    pts = [[None] * 3 for _ in range(3)]
    # (i, j) -> offset in units of r
    off = {(0, 0): (0, -1), (1, 0): (1, -1), (2, 0): (1, 0),
           (0, 1): (-1, -1), (1, 1): (0, 0), (2, 1): (1, 1),
           (0, 2): (-1, 0), (1, 2): (-1, 1), (2, 2): (0, 1)}
    for (i, j), (dx, dy) in off.items():
        pts[i][j] = P(cx + r * dx, cy + r * dy, z)
    return pts


DISC_W = [[1.0, S2, 1.0], [S2, 0.5, S2], [1.0, S2, 1.0]]


def revolved(profile, degree_w, knots_w=None, cx=0.0, cy=0.0, name=None, u_factor=None,
             turn_h=None):
    """Body 2 (NURBS faces) of a round solid around the vertical axis through
    (cx, cy): profile = [(z, r), ...], one disc layer per profile point.
    u_factor c multiplies the weights of the net's layer i (along u) by c^i:
    the rational reparametrisation of a Bezier segment, which keeps every
    face's shape and changes how u runs across the section. turn_h = H turns
    the solid upside down by a half turn about the line y = cy, z = H/2
    (x, y, z) -> (x, 2 cy - y, H - z): a rotation, so the body stays
    right-handed (det J > 0), and the profile's z runs downwards from H."""
    net = [[[None] * len(profile) for _ in range(3)] for _ in range(3)]
    wts = [[[None] * len(profile) for _ in range(3)] for _ in range(3)]
    for k, (z, r) in enumerate(profile):
        d = disc_net(r, z, cx, cy)
        if turn_h is not None:
            d = [[P(q[0], 2 * cy - q[1], turn_h - q[2]) for q in row] for row in d]
        for i in range(3):
            for j in range(3):
                net[i][j][k] = d[i][j]
                wts[i][j][k] = DISC_W[i][j] * (u_factor ** i if u_factor else 1)
    knots = None
    if knots_w is not None:
        knots = [[0, 0, 0, 1, 1, 1], [0, 0, 0, 1, 1, 1], knots_w]
    return body2_from_volume(net, degree=[2, 2, degree_w], knots=knots, weights=wts,
                             name=name), net, wts


# ================================================================ models
# Each builder returns (file name, model, extra checks). An extra check is a
# function(model) -> (description, worst deviation, scale) run after the
# generic checks.


def m_deformed_cube():
    """Seed 000 Fig. 2: a cube whose four top corners are moved up and down;
    the six faces become hyperbolic paraboloids."""
    moves = {(0, 0, 1): 3, (1, 1, 1): 3, (0, 1, 1): -3, (1, 0, 1): -3}
    corners = []
    for i in range(2):
        for j in range(2):
            for k in range(2):
                c = cube_corner(i, j, k)
                c[2] += moves.get((i, j, k), 0)
                corners.append(P(*c))
    b = {"type": "body0", "name": "deformed-cube", "corners": corners}
    return "deformed-cube.json", model([b]), []


# Fig. 3 / Fig. 4. An extruded profile: the v and w edges (in the planes x = 0
# and x = 10) are B-splines with five de Boor points, some moved off the
# cube's edge; the u edges are straight. Because the u edges are straight and
# the edges at x = 10 are the x = 0 edges shifted, every face that contains a
# u edge is a translational surface, and re-spacing the de Boor points of the
# u edges along those edges changes the parametrisation (the interior
# "density") but not the outer shape (Fig. 4).
PROFILE_MOVES = {
    # key (without I): {point index: (dy, dz)}
    "v0": {2: (0, 2)},                # bottom edges (z = 0): arched up inside
    "v1": {1: (0, 2), 2: (0, 3.5), 3: (0, 2)},  # top edges: a roof
    "w0": {2: (-2.5, 0)},             # y = 0 side: bulges out
    "w1": {2: (2.5, 0), 3: (1, 0)},   # y = 10 side: bulges out, higher up
}
U_SPACING_UNIFORM = [0, 2.5, 5, 7.5, 10]
U_SPACING_DENSITY = {  # de Boor x positions of the u edges, moved along the edges
    "u00": [0, 0.5, 1.5, 4, 10], "u01": [0, 0.5, 1.5, 4, 10],
    "u10": [0, 1, 3, 6, 10], "u11": [0, 6, 8.5, 9.5, 10],
}


def fig3_edge(spacing):
    def make(key, a, b):
        pts = []
        if key[0] == "u":
            xs = spacing(key)
            pts = [P(x, a[1], a[2]) for x in xs]
        else:
            mv = PROFILE_MOVES[key[0] + key[2]]
            for n in range(5):
                q = lerp(a, b, n / 4)
                dy, dz = mv.get(n, (0, 0))
                pts.append(P(q[0], q[1] + dy, q[2] + dz))
        return {"type": "bspline", "degree": 3, "points": pts}
    return make


def m_body1_bspline_edges():
    b = body1(cube_corner, fig3_edge(lambda key: U_SPACING_UNIFORM), name="fig3")
    return "body1-bspline-edges.json", model([b]), []


def m_body1_density():
    b = body1(cube_corner, fig3_edge(lambda key: U_SPACING_DENSITY[key]), name="fig4")

    def same_shape(m):
        """The outer shape equals body1-bspline-edges: on faces u0/u1 the same
        point, on the other four faces the same (y, z) with x inside [0, 10];
        inside, (y, z) is unchanged and x = sum L_j(v) L_k(w) x_jk(u)."""
        ref = m_body1_bspline_edges()[1]["bodies"][0]
        bd = m["bodies"][0]
        E = bd["edges"]
        worst = 0.0
        g = [i / 8 for i in range(9)]
        for a in g:
            for c in g:
                for fixed in range(3):
                    for side in (0.0, 1.0):
                        q = [a, c]
                        q.insert(fixed, side)
                        p1 = R.body_eval(bd, *q)
                        p0 = R.body_eval(ref, *q)
                        if fixed == 0:
                            worst = max(worst, R.dist(p1, p0))
                        else:
                            worst = max(worst, abs(p1[1] - p0[1]), abs(p1[2] - p0[2]),
                                        max(0.0, -p1[0], p1[0] - 10))
                # interior closed form
                u, v, w = a, c, (a + c) / 2
                p1 = R.body_eval(bd, u, v, w)
                p0 = R.body_eval(ref, u, v, w)
                x = sum(Lv * Lw * R.curve_eval(E["u%d%d" % (j, k)], u)[0]
                        for j, Lv in enumerate((1 - v, v)) for k, Lw in enumerate((1 - w, w)))
                worst = max(worst, abs(p1[0] - x), abs(p1[1] - p0[1]), abs(p1[2] - p0[2]))
        return "same outer shape as body1-bspline-edges", worst, 10.0
    return "body1-density.json", model([b]), [same_shape]


def m_spool():
    """Seed 000 Fig. 7: a cube rounded at the bottom and at the top; the
    (u,v) squares become discs (rational quadratic NURBS), the profile along w
    is wide at both ends and narrow in the middle."""
    profile = [(0, 6), (1, 6), (1.5, 2.5), (8.5, 2.5), (9, 6), (10, 6)]
    b, net, _ = revolved(profile, 2, name="spool")
    return "spool.json", model([b]), [radius_check(0, profile, 2), stands_on(0, "w0")]


def radius_check(bi, profile, degree_w, cx=0.0, cy=0.0, knots_w=None, turn_h=None):
    """On the four side faces the distance from the axis equals the profile's
    radius r(w), the B-spline of the profile radii (the rational circle has
    the same denominator all round, so r and z are plain B-splines of w);
    the height is z(w), or H - z(w) for a solid turned upside down
    (revolved(turn_h=H))."""
    def check(m):
        bd = m["bodies"][bi]
        rs = [[0, 0, r] for _, r in profile]
        zs = [[0, 0, z] for z, _ in profile]
        curve_r = {"type": "bspline", "degree": degree_w, "points": rs}
        curve_z = {"type": "bspline", "degree": degree_w, "points": zs}
        if knots_w:
            curve_r["knots"] = curve_z["knots"] = knots_w
        worst = 0.0
        for n in range(41):
            w = n / 40
            r = R.curve_eval(curve_r, w)[2]
            z = R.curve_eval(curve_z, w)[2]
            if turn_h is not None:
                z = turn_h - z
            for t in [i / 10 for i in range(11)]:
                for q in ((0, t, w), (1, t, w), (t, 0, w), (t, 1, w)):
                    p = R.body_eval(bd, *q)
                    worst = max(worst, abs(math.hypot(p[0] - cx, p[1] - cy) - r),
                                abs(p[2] - z))
        return "side faces at radius r(w), height z(w)", worst, max(r for _, r in profile)
    return check


def stands_on(bi, fk):
    """Meant for printing: face fk of body bi is the model's base, flat in the
    lowest plane z = 0 of the whole boundary (a slicer's first layer needs an
    area on the bed, not a point): the worst of |z| on that face and of
    max(0, -z) on every face of every body, on a 21 x 21 grid."""
    def check(m):
        g = [i / 20 for i in range(21)]
        worst = 0.0
        for bj, b in enumerate(m["bodies"]):
            for fkey in FACE_KEYS:
                ax, side = "uvw".index(fkey[0]), float(fkey[1])
                for a in g:
                    for c in g:
                        q = [a, c]
                        q.insert(ax, side)
                        z = R.body_eval(b, *q)[2]
                        worst = max(worst, -z, abs(z) if (bj, fkey) == (bi, fk) else 0.0)
        return "stands on face %s of body %d, flat at z = 0, nothing below" % (fk, bi), worst, \
            R.control_diagonal(m, include_cross=False)
    return check


# The nail stands on its head, tip up (a slicer cannot start a print on the
# tip): its profile from the tip (z = 0) to the head (z = 12), turned over.
NAIL_PROFILE = [(0, 0), (2.5, 0.75), (10.5, 0.75), (11, 2.5), (12, 2.5)]
NAIL_H = 12


def m_nail():
    """Seed 000 Fig. 6: a round shaft, a flat round head and a pointed tip,
    standing on the head (face w1, flat at z = 0) with the tip up. The
    layer w = 0 is a single point, so face w0 collapses to the tip. Degree 1
    along w gives the sharp cone, shaft and head; the knots give the shaft
    most of the parameter range (the interior "density" along the nail).
    The head's inner side is a shallow cone: every layer is further from the
    tip than the one before, so det J > 0 inside (a flat annulus between two
    layers would squash a slab of the parameter cube flat, det J = 0)."""
    profile = NAIL_PROFILE
    kw = [0, 0, 1, 5, 6, 7, 7]
    b, net, _ = revolved(profile, 1, knots_w=kw, name="nail", turn_h=NAIL_H)
    return "nail.json", model([b]), [radius_check(0, profile, 1, knots_w=kw, turn_h=NAIL_H),
                                     stands_on(0, "w1")]


def m_nail_density():
    """The nail's outer shape with another interior parametrisation (the
    "density" of seed 000 Fig. 4, for Fig. 6): the knots along w give the
    tip most of the parameter range instead of the shaft, and the section's
    weights are scaled by 2.5^i along u (same quarter circles, u crowded
    towards one side). Every face is the nail's face reparametrised, so the
    boundary is the same surface; the isoparametric surfaces move."""
    profile = NAIL_PROFILE
    kw = [0, 0, 4, 5, 6, 7, 7]
    b, net, _ = revolved(profile, 1, knots_w=kw, name="nail", u_factor=2.5, turn_h=NAIL_H)
    return "nail-density.json", model([b]), [
        radius_check(0, profile, 1, knots_w=kw, turn_h=NAIL_H), stands_on(0, "w1")]


# ---- Fig. 8: union of three bodies 2


def slab_net(lo, hi, dome):
    net = grid_net((3, 3, 2), lo, hi)
    net[1][1][1][2] += dome
    return tidy_net(net)


def unit(a):
    n = math.sqrt(sum(x * x for x in a))
    return [x / n for x in a]


def cross3(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def bar(path, wdir, half_w, half_t, path_axis, name, degree=None, digits=3):
    """Body 2 of a bar of rectangular section 2 half_w x 2 half_t swept along
    the control polygon `path` (the centre line's Bezier/B-spline points).
    The width is along the unit vector wdir; the thickness direction at each
    control point is perpendicular to the polygon there (rounded to `digits`
    decimals: any net is valid, this only keeps the file short). path_axis 0
    puts the path along u (width v, thickness w), 1 along v (width u,
    thickness w). The thickness order is chosen so that the body is
    right-handed (det J > 0)."""
    n = len(path)
    thick = []
    for j in range(n):
        legs = []
        if j > 0:
            legs.append(unit([path[j][d] - path[j - 1][d] for d in range(3)]))
        if j < n - 1:
            legs.append(unit([path[j + 1][d] - path[j][d] for d in range(3)]))
        direc = [sum(l[d] for l in legs) for d in range(3)]
        thick.append(unit(cross3(direc, wdir)))

    def build(sign):
        grid = [[[P(*[round(path[j][d] + a * half_w * wdir[d] + sign * b * half_t * thick[j][d],
                            digits) for d in range(3)])
                  for b in (-1, 1)] for a in (-1, 1)] for j in range(n)]
        if path_axis == 1:  # [width][path][thick]
            grid = [[grid[j][a] for j in range(n)] for a in range(2)]
        return body2_from_volume(grid, degree=degree, name=name)
    b = build(1)
    if R.body_jacobian_det(json.loads(json.dumps(b)), 0.5, 0.5, 0.5) < 0:
        b = build(-1)
    return b


def m_union():
    """Seed 000 Fig. 8: three bodies 2 united: a slab with a domed top
    (B-spline faces), a round post through it (NURBS faces) and an arch whose
    feet stand in the slab (Bezier faces)."""
    slab = body2_from_volume(slab_net([0, 0, 0], [24, 12, 4], 2), degree=[2, 2, 1],
                             name="slab")
    post, _, _ = revolved([(-2, 3), (12, 3)], 1, cx=6, cy=6, name="post")
    arch = bar([[13, 6, 1], [13, 6, 14], [22, 6, 14], [22, 6, 1]], [0, 1, 0], 1.5, 1.5, 0,
               "arch")
    return "union-three-bodies.json", model([slab, post, arch], operation="union"), []


def m_chair():
    """Seed 000 Fig. 9: an ergonomic chair from five bodies 2 (seat, back,
    column, base, and a strut from the column to the back), united."""
    # seat: 42 x 42, 4 thick at z 44..48, dished top, front edge rolled down
    seat = grid_net((4, 4, 2), [-21, -21, 44], [21, 21, 48])
    for i in (1, 2):
        for j in (1, 2):
            seat[i][j][1][2] -= 1.5
    for i in range(4):
        for k in range(2):
            seat[i][0][k][2] -= 3  # waterfall front (v = 0 is the front)
    seat = tidy_net(seat)
    seat_b = body2_from_volume(seat, degree=[2, 2, 1], name="seat")
    # back: u along x, v through the thickness (y), w up; leans back, lumbar
    # bulge, sides wrapped forward; its foot is inside the seat
    back = []
    for i in range(4):
        x = -18 + 12 * i
        row = []
        for j in range(2):
            col = []
            for k in range(4):
                z = [45, 60, 76, 92][k]
                y = 15 + 4 * j + [0, -3, 2, 6][k] - (1.5 if i in (0, 3) and k > 0 else 0)
                col.append(P(x, y, z))
            row.append(col)
        back.append(row)
    back_b = body2_from_volume(back, degree=[2, 1, 2], name="back")
    column, _, _ = revolved([(8, 3), (45, 3)], 1, name="column")
    base, _, _ = revolved([(0, 24), (3, 20), (10, 4)], 1, name="base")
    strut = bar([[0, 0, 42], [0, 30, 38], [0, 16.5, 68]], [1, 0, 0], 2.5, 1.5, 1, "strut")
    return "chair.json", model([seat_b, back_b, column, base, strut], operation="union"), []


# ---- one model per curve type, as body 1 edges


def bulge(a, b, amount):
    """A vector perpendicular to edge a-b, pointing away from the cube centre
    (5,5,5) scaled to `amount` per axis (axis-aligned, so numbers stay short).

    At a corner the three edges leave along (a, -b, -b), (-b, a, -b),
    (-b, -b, a) (a along the edge, b the outward lean), whose determinant
    (a + b)^2 (a - 2b) is negative once b > a/2: the body then folds at the
    corner. Every use below keeps the lean under half the edge's own speed."""
    mid = lerp(a, b, 0.5)
    d = [0.0, 0.0, 0.0]
    axis = max(range(3), key=lambda i: abs(b[i] - a[i]))
    for i in range(3):
        if i != axis:
            d[i] = amount if mid[i] > 5 else -amount
    return d


def m_curve_line():
    def corner(i, j, k):
        return m_deformed_cube()[1]["bodies"][0]["corners"][4 * i + 2 * j + k]
    b = body1(corner, lambda key, a, c: {"type": "line", "points": [a, c]}, name="lines")
    return "curve-line.json", model([b]), [equals_body0(m_deformed_cube()[1]["bodies"][0])]


def equals_body0(ref):
    def check(m):
        bd = m["bodies"][0]
        worst = 0.0
        for q in sample3(5):
            worst = max(worst, R.dist(R.body_eval(bd, *q), R.body_eval(ref, *q)))
        return "equals body 0 of its corners (seed 000: straight edges)", worst, 10.0
    return check


def sample3(n):
    return [(i / n, j / n, k / n) for i in range(n + 1) for j in range(n + 1)
            for k in range(n + 1)]


def m_curve_polyline():
    def make(key, a, b):
        mid = lerp(a, b, 0.5)
        d = bulge(a, b, 1.5)
        if key[0] == "w":
            d = [-x for x in d]  # side edges pinched in: a waist
        return {"type": "polyline",
                "points": [P(*a), P(*lerp(a, b, 0.25)), P(*[mid[i] + d[i] for i in range(3)]),
                           P(*b)]}
    b = body1(cube_corner, make, name="polylines")
    return "curve-polyline.json", model([b]), []


def m_curve_bezier():
    def make(key, a, b):
        d = bulge(a, b, 1.5)
        return {"type": "bezier",
                "points": [P(*a), P(*[x + y for x, y in zip(lerp(a, b, 1 / 3), d)]),
                           P(*[x + y for x, y in zip(lerp(a, b, 2 / 3), d)]), P(*b)]}
    b = body1(lambda i, j, k: cube_corner(i, j, k, 12), make, name="beziers")
    return "curve-bezier.json", model([b]), []


def m_curve_hermite():
    def make(key, a, b):
        axis = max(range(3), key=lambda i: abs(b[i] - a[i]))
        d = bulge(a, b, 3)
        t0 = [b[i] - a[i] + d[i] for i in range(3)]
        t1 = [b[i] - a[i] - d[i] for i in range(3)]
        t0[axis] = t1[axis] = 10
        return {"type": "hermite", "points": [P(*a), P(*b)], "tangents": [P(*t0), P(*t1)]}
    b = body1(cube_corner, make, name="hermites")
    return "curve-hermite.json", model([b]), []


def m_curve_coons_cubic():
    """Open Coons cubic B-splines (seed 002) ending at the corners: with
    P1 = A and P0 = 2A - P2 the curve starts at (P0 + 4P1 + P2)/6 = A (the
    "ant centroid" property), likewise at the end."""
    def make(key, a, b):
        d = bulge(a, b, 1)
        m1 = [x + y for x, y in zip(lerp(a, b, 0.25), d)]
        m2 = [x + y for x, y in zip(lerp(a, b, 0.75), d)]
        p0 = [2 * a[i] - m1[i] for i in range(3)]
        p5 = [2 * b[i] - m2[i] for i in range(3)]
        return {"type": "coons-cubic", "points": [P(*p0), P(*a), P(*m1), P(*m2), P(*b), P(*p5)]}
    b = body1(cube_corner, make, name="coons-cubics")
    return "curve-coons-cubic.json", model([b]), []


def ring_loop(rad, diag, z):
    """8 points of a closed Coons cubic B-spline around the z axis, ordered so
    that the curve starts at ((2 diag + 4 rad)/6, 0, z) on the +x axis."""
    pts = [(diag, -diag), (rad, 0), (diag, diag), (0, rad), (-diag, diag), (-rad, 0),
           (-diag, -diag), (0, -rad)]
    return {"type": "coons-cubic", "closed": True, "points": [P(x, y, z) for x, y in pts]}


def m_curve_coons_cubic_closed():
    """Closed Coons cubic B-splines as the four u edges: each edge starts and
    ends at the same corner, so the faces u0 and u1 coincide and the body is a
    ring (a washer of rectangular section) whose u direction goes round."""
    # j = 0 is the outer loop, so that (u round, v inwards, w up) is right-handed
    loops = {(0, 0): ring_loop(6, 4.5, 0), (1, 0): ring_loop(3, 2.25, 0),
             (0, 1): ring_loop(6, 4.5, 3), (1, 1): ring_loop(3, 2.25, 3)}
    start = {jk: R.realv(R.curve_eval(c, 0.0)) for jk, c in loops.items()}

    def corner(i, j, k):
        return list(start[(j, k)])

    def make(key, a, b):
        if key[0] == "u":
            return loops[(int(key[1]), int(key[2]))]
        return {"type": "line", "points": [P(*a), P(*b)]}
    b = body1(corner, make, name="ring")

    def closed_form(m):
        # z(u,v,w) = 3 w exactly; the section (v, w) is the rectangle between
        # the loops: the point is (1-v) * inner(u) + v * outer(u) + z.
        bd = m["bodies"][0]
        worst = 0.0
        for (u, v, w) in sample3(6):
            p = R.body_eval(bd, u, v, w)
            outer = R.curve_eval(loops[(0, 0)], u)
            inner = R.curve_eval(loops[(1, 0)], u)
            q = [(1 - v) * outer[d] + v * inner[d] for d in range(2)] + [3 * w]
            worst = max(worst, R.dist(p, q))
        return "ring: section is the ruled band between the loops", worst, 6.0
    return "curve-coons-cubic-closed.json", model([b]), [closed_form]


def m_curve_clamped_cubic():
    def make(key, a, b):
        d = bulge(a, b, 1)
        pts = []
        for n in range(5):
            q = lerp(a, b, n / 4)
            f = [0, 1, 2, 1, 0][n]
            pts.append(P(*[q[i] + f * d[i] for i in range(3)]))
        return {"type": "clamped-cubic", "points": pts}
    b = body1(cube_corner, make, name="clamped-cubics")
    return "curve-clamped-cubic.json", model([b]), []


def m_curve_bspline():
    """Quadratic B-splines with a non-uniform knot vector (given explicitly)."""
    knots = [0, 0, 0, 1, 3, 4, 4, 4]

    def make(key, a, b):
        d = bulge(a, b, 0.8)
        pts = []
        for n, f in enumerate([0, 0.2, 0.5, 0.8, 1]):
            q = lerp(a, b, f)
            g = [0, 1, 0, -1, 0][n] if key[0] != "w" else [0, 1, 1, 1, 0][n]
            pts.append(P(*[q[i] + g * d[i] for i in range(3)]))
        return {"type": "bspline", "degree": 2, "knots": knots, "points": pts}
    b = body1(cube_corner, make, name="bsplines")
    return "curve-bspline.json", model([b]), []


def m_curve_nurbs():
    """NURBS quarter circles as u edges: a quarter of a thick tube (annular
    sector, radii 6..3, height 4; v runs inwards so that the body is
    right-handed). Body 1 of these edges is exactly r = 6 - 3v, z = 4w, with
    the angle of the rational arc at u."""
    arc = lambda r, z: {"type": "bspline", "degree": 2, "points": [P(r, 0, z), P(r, r, z), P(0, r, z)],
                        "weights": [1, S2, 1]}

    def corner(i, j, k):
        r, z = 6 - 3 * j, 4 * k
        return [r, 0, z] if i == 0 else [0, r, z]

    def make(key, a, b):
        if key[0] == "u":
            return arc(6 - 3 * int(key[1]), 4 * int(key[2]))
        return {"type": "line", "points": [P(*a), P(*b)]}
    b = body1(corner, make, name="quarter-tube")

    def closed_form(m):
        bd = m["bodies"][0]
        worst = 0.0
        for (u, v, w) in sample3(6):
            p = R.body_eval(bd, u, v, w)
            worst = max(worst, abs(math.hypot(p[0], p[1]) - (6 - 3 * v)), abs(p[2] - 4 * w))
        return "radius 6 - 3v and height 4w everywhere", worst, 6.0
    return "curve-nurbs.json", model([b]), [closed_form]


# ---- one model per patch type, as body 2 faces


def m_patch_bilinear():
    corners = m_deformed_cube()[1]["bodies"][0]["corners"]

    def C(i, j, k):
        return corners[4 * i + 2 * j + k]
    faces = {}
    for fk in FACE_KEYS:
        ax, I = fk[0], int(fk[1])
        q = []
        for (a, b) in ((0, 0), (1, 0), (0, 1), (1, 1)):  # X00, X10, X01, X11
            idx = {"u": (I, a, b), "v": (a, I, b), "w": (a, b, I)}[ax]
            q.append(C(*idx))
        faces[fk] = {"type": "bilinear", "corners": q}
    b = {"type": "body2", "name": "bilinear-faces", "faces": faces}
    return "patch-bilinear.json", model([b]), [equals_body0(m_deformed_cube()[1]["bodies"][0])]


def m_patch_ruled():
    """Ruled faces: a body 2 whose u edges are curved (cubic Bezier humps) and
    whose v and w edges are straight; every face is ruled between two of its
    edges, the straight ones being the rulings."""
    def edge(key, a, b):
        if key[0] == "u":
            h = 3 if key[2] == "1" else 1  # top humps higher than bottom
            return {"type": "bezier", "points": [P(*a), P(a[0] + 4, a[1], a[2] + h),
                                                  P(a[0] + 8, a[1], a[2] + h), P(*b)]}
        return {"type": "line", "points": [P(*a), P(*b)]}
    E = body1(lambda i, j, k: cube_corner(i, j, k, 12), edge)["edges"]
    faces = {}
    for fk in FACE_KEYS:
        t0, t1, s0, s1 = FACE_BOUNDARY[fk]
        # x(s,t) = (1-t) c0(s) + t c1(s): c0 = x(s,0) = t0, c1 = x(s,1) = t1;
        # the sides s0, s1 must then be straight (lines in every face here)
        faces[fk] = {"type": "ruled", "curves": [E[t0], E[t1]]}
    b = {"type": "body2", "name": "ruled-faces", "faces": faces}
    return "patch-ruled.json", model([b]), []


def pillow_edges():
    """The 12 edges of curve-bezier (a cube of 12 whose edges bulge out)."""
    return m_curve_bezier()[1]["bodies"][0]["edges"]


def m_patch_coons(blend):
    def face(fk, bd):
        f = {"type": "coons", "boundary": bd}
        if blend:
            f["blend"] = blend
        return f
    b = {"type": "body2", "name": "coons-faces" if not blend else "coons-cubic-faces",
         "faces": body2_coons_faces(pillow_edges(), face)}
    checks = []
    if not blend:
        ref = m_curve_bezier()[1]["bodies"][0]

        def eq(m):
            bd = m["bodies"][0]
            worst = max(R.dist(R.body_eval(bd, *q), R.body_eval(ref, *q)) for q in sample3(4))
            return "equals body 1 of the same edges (seed 000)", worst, 12.0
        checks.append(eq)
    return ("patch-coons.json" if not blend else "patch-coons-cubic.json"), model([b]), checks


def bezier_deriv_end(pts, end):
    """Exact end tangent of a Bezier curve: n (P1 - P0) or n (Pn - Pn-1)."""
    n = len(pts) - 1
    a, b = (pts[0], pts[1]) if end == 0 else (pts[-2], pts[-1])
    return [n * (b[i] - a[i]) for i in range(3)]


def m_patch_hermite(kind):
    """Hermite (bicubically blended) Coons faces over the pillow's edges:
    twist "zero", "adini", "bessel", explicit vectors, or with cross curves."""
    E = pillow_edges()

    def face(fk, bd):
        f = {"type": "hermite-coons", "boundary": bd}
        if kind in ("zero", "adini", "bessel"):
            if kind != "zero":
                f["twist"] = kind
            return f
        if kind == "twists":
            # explicit twists: a fraction of each corner's adini twist, rounded
            f["twist"] = [[-4, 2, 0], [2, -4, 0], [0, 0, 3], [0, 0, -3]]
            return f
        # cross curves: quadratic Bezier tangent fields between the required
        # corner tangents, with the middle pushed along the face's outward
        # side a little (the tangent leans out, so the face bulges).
        pts = {c: bd[c]["points"] for c in ("t0", "t1", "s0", "s1")}
        need = {
            "t0": (bezier_deriv_end(pts["s0"], 0), bezier_deriv_end(pts["s1"], 0)),
            "t1": (bezier_deriv_end(pts["s0"], 1), bezier_deriv_end(pts["s1"], 1)),
            "s0": (bezier_deriv_end(pts["t0"], 0), bezier_deriv_end(pts["t1"], 0)),
            "s1": (bezier_deriv_end(pts["t0"], 1), bezier_deriv_end(pts["t1"], 1)),
        }
        out = [0, 0, 0]
        out["uvw".index(fk[0])] = -3 if fk[1] == "0" else 3
        cross = {}
        for c, (a, b) in need.items():
            sgn = 1 if c in ("t0", "s0") else -1  # leaving the edge: out; arriving: in
            mid = [(a[i] + b[i]) / 2 + sgn * out[i] for i in range(3)]
            cross[c] = {"type": "bezier", "points": [P(*a), P(*mid), P(*b)]}
        f["cross"] = cross
        return f
    b = {"type": "body2", "name": "hermite-" + kind,
         "faces": body2_coons_faces(E, face)}
    return "patch-hermite-%s.json" % kind, model([b]), []


def m_patch_bezier():
    net = grid_net((3, 3, 3), [0, 0, 0], [10, 10, 10])
    net[1][1][2][2] += 4   # top centre up: a dome
    net[1][1][0][2] += 2   # bottom centre up: hollow underneath
    net[2][1][1][0] += 3   # +x side bulges
    net[1][0][1][1] -= 2   # -y side bulges
    net[0][2][2][1] += 2   # a pulled corner area
    b = body2_from_volume(tidy_net(net), name="bezier-faces")
    return "patch-bezier.json", model([b]), []


def m_patch_bspline():
    ku = [0, 0, 0, 0, 1, 2, 2, 2, 2]
    net = grid_net((5, 3, 2), [0, 0, 0], [16, 8, 6])
    for i in (1, 2, 3):
        net[i][1][1][2] += [2, -2, 2][i - 1]  # a wavy top along u
    net[2][0][0][1] -= 2                     # front foot
    net[2][2][0][1] += 2
    b = body2_from_volume(tidy_net(net), degree=[3, 2, 1], knots=[ku, [0, 0, 0, 1, 1, 1], [0, 0, 1, 1]],
                          name="bspline-faces")
    return "patch-bspline.json", model([b]), []


def m_patch_nurbs():
    b, _, _ = revolved([(0, 5), (8, 5)], 1, name="cylinder")
    return "patch-nurbs.json", model([b]), [radius_check(0, [(0, 5), (8, 5)], 1)]


def m_volume_bezier():
    """Bezier volume: a 3 x 3 x 2 grid (degree 2, 2, 1) with one point moved.
    Closed form: (10u, 10v, 10w) + B2,1(u) B2,1(v) B1,1(w) * (0, 0, 6)."""
    net = grid_net((3, 3, 2), [0, 0, 0], [10, 10, 10])
    net[1][1][1][2] += 6
    b = {"type": "bezier-volume", "name": "bezier-volume", "points": tidy_net(net)}

    def closed_form(m):
        bd = m["bodies"][0]
        worst = 0.0
        for (u, v, w) in sample3(6):
            p = R.body_eval(bd, u, v, w)
            q = [10 * u, 10 * v, 10 * w + 6 * (2 * u * (1 - u)) * (2 * v * (1 - v)) * w]
            worst = max(worst, R.dist(p, q))
        return "closed form (10u, 10v, 10w + 24 u(1-u) v(1-v) w)", worst, 10.0
    return "volume-bezier.json", model([b]), [closed_form]


def m_volume_bspline():
    """B-spline volume with explicit non-uniform knots, points at the Greville
    abscissae (so the map is (16u, 8v, 6w)) except three moved points."""
    ku, kv, kw = [0, 0, 0, 1, 3, 4, 4, 4], [0, 0, 0, 1, 1, 1], [0, 0, 1, 1]
    gr = [greville(2, ku), greville(2, kv), greville(1, kw)]
    net = grid_net((5, 3, 2), [0, 0, 0], [16, 8, 6], greville=gr)
    net[2][1][1][2] += 3
    net[0][0][0][0] -= 1
    net[4][2][1][1] += 1
    b = {"type": "bspline-volume", "name": "bspline-volume", "degree": [2, 2, 1],
         "knots": [ku, kv, kw], "points": tidy_net(net)}
    return "volume-bspline.json", model([b]), []


def m_volume_nurbs():
    """The NURBS cylinder as a single rational B-spline volume (weights)."""
    bd, net, wts = revolved([(0, 5), (8, 5)], 1)
    b = {"type": "bspline-volume", "name": "nurbs-cylinder", "degree": [2, 2, 1],
         "points": net, "weights": tidy_net(wts)}

    def closed_form(m):
        v = m["bodies"][0]
        worst = 0.0
        for (a, c, w) in sample3(6):
            for q in ((0, a, w), (1, a, w), (a, 0, w), (a, 1, w)):
                p = R.body_eval(v, *q)
                worst = max(worst, abs(math.hypot(p[0], p[1]) - 5), abs(p[2] - 8 * w))
        return "side faces at radius 5, z = 8w", worst, 5.0
    return "volume-nurbs.json", model([b]), [closed_form]


# Models for the CalculiX validation of the .inp volume meshes
# (tests/cli/test_volume_ccx_beams.py compares ccx with closed forms).
CANTILEVER = {"L": 100.0, "h": 10.0, "b": 10.0}
TUBE = {"a": 10.0, "b": 20.0, "H": 5.0}


def m_cantilever():
    """A cantilever box L x h x b (body 0): u along its length x, v along the
    height y (the direction of the tip load), w across z."""
    L, h, b = CANTILEVER["L"], CANTILEVER["h"], CANTILEVER["b"]
    corners = [P(L * i, h * j, b * k) for i in range(2) for j in range(2) for k in range(2)]
    body = {"type": "body0", "name": "beam", "corners": corners}
    return "cantilever.json", model([body]), []


def tube_net(radial_mid=None, c=1.0):
    """A quarter of a thick-walled tube, radii a..b, height H, as one NURBS
    volume: u radial (linear, or quadratic with its middle control points
    at radius radial_mid), v angular (rational quadratic quarter circle
    from the x axis to the y axis, weights 1, c sqrt(1/2), c^2: for any
    c > 0 the same circle, c != 1 spaces the parameter unevenly), w up."""
    a, b, H = TUBE["a"], TUBE["b"], TUBE["H"]
    radii = [a, b] if radial_mid is None else [a, radial_mid, b]
    arc = [(1, 0), (1, 1), (0, 1)]
    warc = [1.0, c * S2, c * c]
    net = [[[P(r * arc[j][0], r * arc[j][1], H * k) for k in range(2)] for j in range(3)]
           for r in radii]
    wts = [[[warc[j], warc[j]] for j in range(3)] for _ in radii]
    return net, wts


def tube_check(m):
    a, b, H = TUBE["a"], TUBE["b"], TUBE["H"]
    v = m["bodies"][0]
    worst = 0.0
    for (s, t, w) in sample3(6):
        for q, want in (((0, s, t), a), ((1, s, t), b)):
            p = R.body_eval(v, *q)
            worst = max(worst, abs(math.hypot(p[0], p[1]) - want))
        p = R.body_eval(v, s, 0, t)  # v0: the plane y = 0
        worst = max(worst, abs(p[1]))
        p = R.body_eval(v, s, 1, t)  # v1: the plane x = 0
        worst = max(worst, abs(p[0]))
        for k in (0, 1):
            p = R.body_eval(v, s, t, k)
            worst = max(worst, abs(p[2] - H * k))
        p = R.body_eval(v, s, t, w)
        r = math.hypot(p[0], p[1])
        worst = max(worst, max(0.0, a - r, r - b, -p[0], -p[1]))
    return "faces at r = a, r = b, y = 0, x = 0, z = 0, z = H; points inside", worst, b


def m_thick_cylinder():
    net, wts = tube_net()
    body = {"type": "bspline-volume", "name": "tube", "degree": [1, 2, 1],
            "points": net, "weights": tidy_net(wts)}
    return "thick-cylinder.json", model([body]), [tube_check]


def m_thick_cylinder_distorted():
    a, b = TUBE["a"], TUBE["b"]
    net, wts = tube_net(radial_mid=a + 0.2 * (b - a), c=1.6)
    body = {"type": "bspline-volume", "name": "tube", "degree": [2, 2, 1],
            "points": net, "weights": tidy_net(wts)}
    return "thick-cylinder-distorted.json", model([body]), [tube_check]


def m_blend_cubic():
    """blend "cubic" on a body 0, a body 1 and a body 2, side by side."""
    b0 = {"type": "body0", "name": "body0-cubic", "blend": "cubic",
          "corners": [P(*[c[0], c[1], c[2]]) for c in m_deformed_cube()[1]["bodies"][0]["corners"]]}
    b1 = m_curve_bezier()[1]["bodies"][0]
    b1 = {"type": "body1", "name": "body1-cubic", "blend": "cubic",
          "edges": shift_obj(b1["edges"], [16, 0, 0])}
    f = body2_coons_faces(shift_obj(pillow_edges(), [34, 0, 0]),
                          lambda fk, bd: {"type": "coons", "boundary": bd})
    b2 = {"type": "body2", "name": "body2-cubic", "blend": "cubic", "faces": f}

    return "body-blend-cubic.json", model([b0, b1, b2], operation="none"), []


def shift_obj(obj, d):
    """Copy of a curve/patch structure with every point shifted by d."""
    if isinstance(obj, dict):
        return {k: (shift_pts(v, d) if k in ("points", "corners") else shift_obj(v, d))
                for k, v in obj.items()}
    if isinstance(obj, list):
        return [shift_obj(v, d) for v in obj]
    return obj


def shift_pts(arr, d):
    if isinstance(arr[0], (int, float)):
        return P(*[arr[i] + d[i] for i in range(3)])
    return [shift_pts(a, d) for a in arr]


BUILDERS = [
    m_deformed_cube, m_body1_bspline_edges, m_body1_density, m_spool, m_nail,
    m_nail_density,
    m_union, m_chair,
    m_curve_line, m_curve_polyline, m_curve_bezier, m_curve_hermite, m_curve_coons_cubic,
    m_curve_coons_cubic_closed, m_curve_clamped_cubic, m_curve_bspline, m_curve_nurbs,
    m_patch_bilinear, m_patch_ruled, lambda: m_patch_coons(None),
    lambda: m_patch_coons("cubic"),
    lambda: m_patch_hermite("zero"), lambda: m_patch_hermite("adini"),
    lambda: m_patch_hermite("bessel"), lambda: m_patch_hermite("twists"),
    lambda: m_patch_hermite("cross"),
    m_patch_bezier, m_patch_bspline, m_patch_nurbs,
    m_volume_bezier, m_volume_bspline, m_volume_nurbs, m_blend_cubic,
    m_cantilever, m_thick_cylinder, m_thick_cylinder_distorted,
]

# ================================================================ JSON text


def fmt_num(x):
    if isinstance(x, bool):
        return "true" if x else "false"
    if isinstance(x, int):
        return str(x)
    return repr(float(x))


def is_numlist(x):
    return isinstance(x, list) and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                       for v in x)


def inline(x):
    if isinstance(x, dict):
        return "{" + ", ".join(json.dumps(k) + ": " + inline(v) for k, v in x.items()) + "}"
    if isinstance(x, list):
        return "[" + ", ".join(inline(v) for v in x) + "]"
    if isinstance(x, str):
        return json.dumps(x)
    return fmt_num(x)


def npoints(x):
    """How many point-like number lists x contains."""
    if is_numlist(x):
        return 1
    if isinstance(x, list):
        return sum(npoints(v) for v in x)
    if isinstance(x, dict):
        return sum(npoints(v) for v in x.values())
    return 0


def dump(x, ind=0):
    """Pretty JSON: number lists and small objects (at most two points, short)
    on one line, everything else one item per line."""
    s = inline(x)
    if not isinstance(x, (dict, list)) or is_numlist(x) or (len(s) + ind <= 96 and npoints(x) <= 2):
        return s
    pad = " " * (ind + 2)
    if isinstance(x, dict):
        items = [pad + json.dumps(k) + ": " + dump(v, ind + 2) for k, v in x.items()]
        return "{\n" + ",\n".join(items) + "\n" + " " * ind + "}"
    items = [pad + dump(v, ind + 2) for v in x]
    return "[\n" + ",\n".join(items) + "\n" + " " * ind + "]"


# ================================================================ checks


class Report:
    def __init__(self):
        self.lines = []
        self.failed = 0

    def check(self, name, what, worst, limit):
        ok = worst <= limit
        if not ok:
            self.failed += 1
        self.lines.append("  %-4s %-34s %-58s worst %.1e (limit %.1e)" %
                          ("ok" if ok else "FAIL", name, what, worst, limit))


def params(n):
    return [i / n for i in range(n + 1)]


def verify_body(b, tol, rep, label):
    ty = b["type"]
    worst = 0.0
    if ty == "body1":
        E = b["edges"]
        for i in range(2):
            for j in range(2):
                for k in range(2):
                    pts = [R.curve_eval(E["u%d%d" % (j, k)], float(i)),
                           R.curve_eval(E["v%d%d" % (i, k)], float(j)),
                           R.curve_eval(E["w%d%d" % (i, j)], float(k))]
                    for a in range(3):
                        for c in range(a):
                            worst = max(worst, R.dist(pts[a], pts[c]))
        rep.check(label, "body1: the three edges meet at each of the 8 corners", worst, tol)
    if ty == "body2":
        F = b["faces"]
        # corners of each Coons-type face's boundary curves
        wc = 0.0
        for f in F.values():
            if f["type"] in ("coons", "hermite-coons"):
                bd = f["boundary"]
                for (c1, e1, c2, e2) in (("t0", 0, "s0", 0), ("t0", 1, "s1", 0),
                                         ("t1", 0, "s0", 1), ("t1", 1, "s1", 1)):
                    wc = max(wc, R.dist(R.curve_eval(bd[c1], float(e1)),
                                        R.curve_eval(bd[c2], float(e2))))
                if "cross" in f:
                    X, xs, xt, T = R.hermite_corner_data(f)
                    cr = f["cross"]
                    for (c, e, want) in (("t0", 0, xt[0][0]), ("t0", 1, xt[1][0]),
                                         ("t1", 0, xt[0][1]), ("t1", 1, xt[1][1]),
                                         ("s0", 0, xs[0][0]), ("s0", 1, xs[0][1]),
                                         ("s1", 0, xs[1][0]), ("s1", 1, xs[1][1])):
                        wc = max(wc, R.dist(R.curve_eval(cr[c], float(e)), want))
        if wc:
            rep.check(label, "faces: boundary curves meet, cross curves fit", wc, tol)
        # the 12 shared edges, parametrically, at 201 parameters each
        for x in params(200):
            for a in range(2):
                for c in range(2):
                    worst = max(worst,
                                R.dist(R.patch_eval(F["v%d" % a], x, c), R.patch_eval(F["w%d" % c], x, a)),
                                R.dist(R.patch_eval(F["u%d" % a], x, c), R.patch_eval(F["w%d" % c], a, x)),
                                R.dist(R.patch_eval(F["u%d" % a], c, x), R.patch_eval(F["v%d" % c], a, x)))
        rep.check(label, "body2: faces agree on the 12 shared edges (201 params)", worst, tol)
    # the body's boundary is its faces / edges
    if ty in ("body1", "body2"):
        wb = 0.0
        g = params(6)
        for a in g:
            for c in g:
                for ax in range(3):
                    for side in (0, 1):
                        q = [a, c]
                        q.insert(ax, float(side))
                        p = R.body_eval(b, *q)
                        if ty == "body2":
                            f = b["faces"]["uvw"[ax] + str(side)]
                            want = R.patch_eval(f, a, c)
                        else:
                            want = face_of_body1(b, ax, side, a, c)
                        wb = max(wb, R.dist(p, want))
        rep.check(label, "boundary of the body = its faces", wb, tol)
    # det J on a 5 x 5 x 5 grid: > 0 at the interior points, >= 0 (to
    # rounding) on the boundary, where seams and collapsed faces give 0
    g = [i / 4 for i in range(5)]
    dets = {(u, v, w): R.body_jacobian_det(b, u, v, w) for u in g for v in g for w in g}
    inner = min(d for q, d in dets.items() if all(0 < x < 1 for x in q))
    outer = min(dets.values())
    return inner, outer


def face_of_body1(b, ax, side, a, c):
    """The Coons patch of body 1's four edges on a face (seed 000: boundary
    surfaces of body 1 are Coons patches)."""
    fk = "uvw"[ax] + str(side)
    t0, t1, s0, s1 = FACE_BOUNDARY[fk]
    E = b["edges"]
    p = {"type": "coons", "boundary": {"t0": E[t0], "t1": E[t1], "s0": E[s0], "s1": E[s1]}}
    if b.get("blend"):
        p["blend"] = b["blend"]
    return R.patch_eval(p, a, c)


def self_test(rep):
    """The reference evaluator against the seeds' own numbers."""
    # seed 002: open Coons cubic B-spline = clamped cubic with converted points
    Pt = [(0, -6, 0), (-6, 0, 0), (-6, 6, 0), (6, 6, 0), (6, 0, 0), (12, 0, 0)]
    n = len(Pt) - 1
    c = [None] * (n + 1)
    c[0] = [Pt[0][i] / 6 + 2 * Pt[1][i] / 3 + Pt[2][i] / 6 for i in range(3)]
    c[1] = [2 * Pt[1][i] / 3 + Pt[2][i] / 3 for i in range(3)]
    for i in range(2, n - 1):
        c[i] = list(Pt[i])
    c[n - 1] = [Pt[n - 2][i] / 3 + 2 * Pt[n - 1][i] / 3 for i in range(3)]
    c[n] = [Pt[n - 2][i] / 6 + 2 * Pt[n - 1][i] / 3 + Pt[n][i] / 6 for i in range(3)]
    co = {"type": "coons-cubic", "points": [list(p) for p in Pt]}
    cl = {"type": "clamped-cubic", "points": c}
    w = max(R.dist(R.curve_eval(co, t), R.curve_eval(cl, t)) for t in params(60))
    # seed 002: P'(0) = (P2 - P0)/2 per segment (times the segment count)
    d = R.curve_deriv(co, 0.0)
    w = max(w, R.dist(d, [3 * (Pt[2][i] - Pt[0][i]) / 2 for i in range(3)]))
    rep.check("self-test", "seed 002: Coons cubic = clamped cubic (conversion), P'(0)", w, 1e-12)
    # rational quarter circle: radius 1 everywhere
    arc = {"type": "bspline", "degree": 2, "points": [[1, 0], [1, 1], [0, 1]], "weights": [1, S2, 1]}
    w = max(abs(math.hypot(*R.curve_eval(arc, t)[:2]) - 1) for t in params(50))
    rep.check("self-test", "NURBS quarter circle has radius 1", w, 1e-14)
    # Hermite Coons patch reproduces its boundary and a bilinear patch
    bl = {"t0": {"type": "line", "points": [[0, 0, 0], [2, 0, 0]]},
          "t1": {"type": "line", "points": [[0, 3, 1], [2, 3, 0]]},
          "s0": {"type": "line", "points": [[0, 0, 0], [0, 3, 1]]},
          "s1": {"type": "line", "points": [[2, 0, 0], [2, 3, 0]]}}
    hp = {"type": "hermite-coons", "boundary": bl, "twist": "adini"}
    bil = {"type": "bilinear", "corners": [[0, 0, 0], [2, 0, 0], [0, 3, 1], [2, 3, 0]]}
    w = max(R.dist(R.patch_eval(hp, s, t), R.patch_eval(bil, s, t))
            for s in params(7) for t in params(7))
    rep.check("self-test", "Hermite Coons (adini) of straight edges = bilinear", w, 1e-12)


def verify(name, m, extra, rep):
    # the consistency tolerance: 1e-9 of the diagonal of the box of all control
    # points, leaving out the 'points' of cross curves (they are tangents)
    diag = R.control_diagonal(m, include_cross=False)
    tol = 1e-9 * diag
    mins = []
    for bi, b in enumerate(m["bodies"]):
        label = "%s[%d]" % (name, bi)
        inner, outer = verify_body(b, tol, rep, label)
        mins.append(outer)
        # every example is right-handed and does not fold: det J > 0 at the
        # 27 interior sample points, and >= 0 up to rounding on the boundary
        # of the parameter cube (seams and collapsed faces give 0 there)
        rep.check(label, "det J > 0 inside (min %.3g)" % inner, 0.0 if inner > 0 else 1.0, 0.0)
        rep.check(label, "det J >= 0 on the boundary (min %.3g)" % outer, max(0.0, -outer),
                  1e-9 * diag ** 3)
    for chk in extra:
        what, worst, scale = chk(m)
        rep.check(name, what, worst, 1e-9 * scale)
    return diag, mins


def main(argv):
    check_only = "--check" in argv
    rep = Report()
    self_test(rep)
    names = []
    summary = []
    stale = []
    for build in BUILDERS:
        name, m, extra = build()
        text = dump(m) + "\n"
        path = os.path.join(HERE, name)
        assert name not in names, name
        names.append(name)
        if check_only:
            try:
                with open(path, encoding="utf-8") as fh:
                    if fh.read() != text:
                        stale.append(name)
            except OSError:
                stale.append(name)
        else:
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(text)
        m = json.loads(text)  # verify what was written, not the Python objects
        diag, mins = verify(name, m, extra, rep)
        summary.append("%-32s %-40s diag %7.3f  min det J %s" % (
            name, ",".join(b["type"] for b in m["bodies"]), diag,
            " ".join("%.3g" % x for x in mins)))
    print("examples (%d files):" % len(names))
    for s in summary:
        print("  " + s)
    print("checks:")
    for line in rep.lines:
        print(line)
    for n in stale:
        print("STALE %s: differs from what gen_examples.py writes" % n)
    bad = rep.failed + len(stale)
    print("%d checks, %d failed%s" % (len(rep.lines), rep.failed,
                                      ", %d stale files" % len(stale) if stale else ""))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
