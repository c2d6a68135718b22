# SPDX-License-Identifier: GPL-3.0-or-later
"""Reference evaluator of the libcoons model format (version 1), in plain Python.

Written from the format contract (../shared/spec/model-format.md) and the seed
documents, independently of the C library, so that the examples and the CLI
tests can check libcoons against it. It evaluates the JSON objects themselves
(dicts as json.load returns them):

    curve_eval(c, t)        every curve type (line ... NURBS bspline)
    patch_eval(p, s, t)     every patch type
    body_eval(b, u, v, w)   body0, body1, body2, bezier-volume, bspline-volume

All arithmetic is written so that it also works on complex numbers: a
derivative is then the complex step Im f(x + ih) / h (exact to rounding, no
cancellation), used for the tangents of Hermite Coons patches and for det J.
Span look-ups compare real parts only. Standard library only.
"""

import json
import math

# ---------------------------------------------------------------- vectors


def vec(p):
    """A point or vector of the format: [x, y] means z = 0."""
    if len(p) == 2:
        return (p[0], p[1], 0.0)
    return (p[0], p[1], p[2])


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def mul(s, a):
    return (s * a[0], s * a[1], s * a[2])


def comb(coeffs, pts):
    """sum of coeffs[i] * pts[i]"""
    x = y = z = 0.0
    for c, p in zip(coeffs, pts):
        x += c * p[0]
        y += c * p[1]
        z += c * p[2]
    return (x, y, z)


def dist(a, b):
    d = sub(a, b)
    return math.sqrt(abs(d[0]) ** 2 + abs(d[1]) ** 2 + abs(d[2]) ** 2)


def re(x):
    return x.real if isinstance(x, complex) else x


# ---------------------------------------------------------------- bases


def bernstein(n, t):
    return [math.comb(n, i) * t ** i * (1 - t) ** (n - i) for i in range(n + 1)]


def hermite_basis(t):
    """H0 (value at 0), H1 (d/dt at 0), H2 (d/dt at 1), H3 (value at 1)."""
    return [1 - 3 * t * t + 2 * t ** 3, t - 2 * t * t + t ** 3, -t * t + t ** 3,
            3 * t * t - 2 * t ** 3]


def coons_basis(t):
    """Seed 002: the Coons polynomials C0..C3."""
    return [(1 - t) ** 3 / 6, (3 * t ** 3 - 6 * t * t + 4) / 6,
            (-3 * t ** 3 + 3 * t * t + 3 * t + 1) / 6, t ** 3 / 6]


def blend_pair(t, blend):
    """(L0, L1): (1-t, t), or (f, 1-f) with f = 1 - 3t^2 + 2t^3 for "cubic"."""
    if blend == "cubic":
        f = 1 - 3 * t * t + 2 * t ** 3
        return (f, 1 - f)
    return (1 - t, t)


def default_knots(p, count):
    """Clamped uniform knots for `count` control points of degree p."""
    n = count - 1
    inner = [i / (n - p + 1) for i in range(1, n - p + 1)]
    return [0.0] * (p + 1) + inner + [1.0] * (p + 1)


def bspline_basis(p, knots, count, t):
    """All `count` basis values N_{i,p} at t in [0,1] mapped onto [k_p, k_n+1].

    Plain Cox-de Boor recursion on the whole vector, with 0/0 = 0; the span is
    half-open and the right end belongs to the last non-empty span.
    """
    k = [float(x) for x in knots]
    n = count - 1
    assert len(k) == count + p + 1, "knot vector length"
    a, b = k[p], k[n + 1]
    x = a + t * (b - a)
    xr = re(x)
    span = None
    for i in range(p, n + 1):
        if k[i] <= xr < k[i + 1]:
            span = i
            break
    if span is None:
        if xr < a:
            span = p
            while k[span + 1] <= k[span]:
                span += 1
        else:
            span = n
            while k[span] >= k[span + 1]:
                span -= 1
    m = len(k) - 1
    N = [1.0 if i == span else 0.0 for i in range(m)]
    for q in range(1, p + 1):
        M = []
        for i in range(m - q):
            v = 0.0
            d1 = k[i + q] - k[i]
            if d1 > 0 and N[i] != 0:
                v += (x - k[i]) / d1 * N[i]
            d2 = k[i + q + 1] - k[i + 1]
            if d2 > 0 and N[i + 1] != 0:
                v += (k[i + q + 1] - x) / d2 * N[i + 1]
            M.append(v)
        N = M
    return N[:count]


def rational(basis, pts, weights):
    if weights is None:
        return comb(basis, pts)
    wb = [b * w for b, w in zip(basis, weights)]
    s = sum(wb)
    return mul(1 / s, comb(wb, pts))


# ---------------------------------------------------------------- curves


def curve_eval(c, t):
    ty = c["type"]
    P = [vec(p) for p in c["points"]]
    if ty == "line":
        return add(mul(1 - t, P[0]), mul(t, P[1]))
    if ty == "polyline":
        n = len(P) - 1
        i = min(int(math.floor(re(t) * n)), n - 1)
        i = max(i, 0)
        loc = t * n - i
        return add(mul(1 - loc, P[i]), mul(loc, P[i + 1]))
    if ty == "bezier":
        return comb(bernstein(len(P) - 1, t), P)
    if ty == "hermite":
        T = [vec(x) for x in c["tangents"]]
        return comb(hermite_basis(t), [P[0], T[0], T[1], P[1]])
    if ty == "coons-cubic":
        if c.get("closed", False):
            m = len(P)
            x = t * m
            s = min(max(int(math.floor(re(x))), 0), m - 1)
            return comb(coons_basis(x - s), [P[(s + r) % m] for r in range(4)])
        nseg = len(P) - 3
        x = t * nseg
        s = min(max(int(math.floor(re(x))), 0), nseg - 1)
        return comb(coons_basis(x - s), P[s:s + 4])
    if ty == "clamped-cubic":
        return comb(bspline_basis(3, default_knots(3, len(P)), len(P), t), P)
    if ty == "bspline":
        p = c["degree"]
        k = c.get("knots") or default_knots(p, len(P))
        return rational(bspline_basis(p, k, len(P), t), P, c.get("weights"))
    raise ValueError("unknown curve type " + ty)


def deriv(f, x, h=1e-30):
    """Complex-step derivative of a vector function f at real x."""
    y = f(complex(x, h))
    return (y[0].imag / h, y[1].imag / h, y[2].imag / h)


def curve_deriv(c, t):
    return deriv(lambda z: curve_eval(c, z), t)


def realv(p):
    return (re(p[0]), re(p[1]), re(p[2]))


# ---------------------------------------------------------------- patches


_MEMO = {}


def memo(fn, obj):
    """fn(obj), computed once per object (corner data depends on the object
    only; the object itself is kept in the cache, so its id stays unique)."""
    key = (fn.__name__, id(obj))
    hit = _MEMO.get(key)
    if hit is not None and hit[0] is obj:
        return hit[1]
    val = fn(obj)
    _MEMO[key] = (obj, val)
    return val


def _corners4(b):
    return memo(_corners4_calc, b)


def _corners4_calc(b):
    """Corners X00, X10, X01, X11 of a Coons boundary, each the average of the
    two curves that meet there."""
    t0, t1, s0, s1 = b["t0"], b["t1"], b["s0"], b["s1"]

    def avg(a, c):
        return mul(0.5, add(a, c))
    return (avg(curve_eval(t0, 0.0), curve_eval(s0, 0.0)),
            avg(curve_eval(t0, 1.0), curve_eval(s1, 0.0)),
            avg(curve_eval(t1, 0.0), curve_eval(s0, 1.0)),
            avg(curve_eval(t1, 1.0), curve_eval(s1, 1.0)))


def _coons(p, s, t):
    b = p["boundary"]
    X00, X10, X01, X11 = _corners4(b)
    F = blend_pair(s, p.get("blend", "linear"))
    G = blend_pair(t, p.get("blend", "linear"))
    rc = add(mul(G[0], curve_eval(b["t0"], s)), mul(G[1], curve_eval(b["t1"], s)))
    rd = add(mul(F[0], curve_eval(b["s0"], t)), mul(F[1], curve_eval(b["s1"], t)))
    rcd = comb([F[0] * G[0], F[1] * G[0], F[0] * G[1], F[1] * G[1]], [X00, X10, X01, X11])
    return sub(add(rc, rd), rcd)


def hermite_corner_data(p):
    """Corner points X[a][b], tangents xs[a][b] = x_s(a,b), xt[a][b] = x_t(a,b)
    and twists tw[a][b] = x_st(a,b) of a hermite-coons patch."""
    return memo(_hermite_corner_data, p)


def _hermite_corner_data(p):
    b = p["boundary"]
    X00, X10, X01, X11 = _corners4(b)
    X = [[X00, X01], [X10, X11]]
    xs = [[curve_deriv(b["t0"], 0.0), curve_deriv(b["t1"], 0.0)],
          [curve_deriv(b["t0"], 1.0), curve_deriv(b["t1"], 1.0)]]
    xt = [[curve_deriv(b["s0"], 0.0), curve_deriv(b["s0"], 1.0)],
          [curve_deriv(b["s1"], 0.0), curve_deriv(b["s1"], 1.0)]]
    tw = p.get("twist", "zero")
    cell = add(sub(sub(X00, X10), X01), X11)
    if tw == "zero":
        T = [[(0.0, 0.0, 0.0)] * 2 for _ in range(2)]
    elif tw == "bessel":
        T = [[cell, cell], [cell, cell]]
    elif tw == "adini":
        T = [[None, None], [None, None]]
        for a in range(2):
            for bb in range(2):
                d_s = sub(curve_deriv(b["s1"], float(bb)), curve_deriv(b["s0"], float(bb)))
                d_t = sub(curve_deriv(b["t1"], float(a)), curve_deriv(b["t0"], float(a)))
                T[a][bb] = sub(add(d_s, d_t), cell)
    else:
        v = [vec(x) for x in tw]  # x_st(0,0), x_st(1,0), x_st(0,1), x_st(1,1)
        T = [[v[0], v[2]], [v[1], v[3]]]
    return X, xs, xt, T


def _hermite_coons(p, s, t):
    b = p["boundary"]
    X, xs, xt, T = hermite_corner_data(p)
    Hs, Ht = hermite_basis(s), hermite_basis(t)
    cross = p.get("cross")
    if cross:
        xt0 = curve_eval(cross["t0"], s)
        xt1 = curve_eval(cross["t1"], s)
        xs0 = curve_eval(cross["s0"], t)
        xs1 = curve_eval(cross["s1"], t)
    else:  # tangent ribbons, seed 001 eq. 1.16
        xt0 = comb(Hs, [xt[0][0], T[0][0], T[1][0], xt[1][0]])
        xt1 = comb(Hs, [xt[0][1], T[0][1], T[1][1], xt[1][1]])
        xs0 = comb(Ht, [xs[0][0], T[0][0], T[0][1], xs[0][1]])
        xs1 = comb(Ht, [xs[1][0], T[1][0], T[1][1], xs[1][1]])
    hc = comb(Hs, [curve_eval(b["s0"], t), xs0, xs1, curve_eval(b["s1"], t)])
    hd = comb(Ht, [curve_eval(b["t0"], s), xt0, xt1, curve_eval(b["t1"], s)])
    M = [[X[0][0], xt[0][0], xt[0][1], X[0][1]],
         [xs[0][0], T[0][0], T[0][1], xs[0][1]],
         [xs[1][0], T[1][0], T[1][1], xs[1][1]],
         [X[1][0], xt[1][0], xt[1][1], X[1][1]]]
    hcd = (0.0, 0.0, 0.0)
    for a in range(4):
        hcd = add(hcd, mul(Hs[a], comb(Ht, M[a])))
    return sub(add(hc, hd), hcd)


def patch_eval(p, s, t):
    ty = p["type"]
    if ty == "bilinear":
        X00, X10, X01, X11 = [vec(x) for x in p["corners"]]
        return comb([(1 - s) * (1 - t), s * (1 - t), (1 - s) * t, s * t], [X00, X10, X01, X11])
    if ty == "ruled":
        c0, c1 = p["curves"]
        return add(mul(1 - t, curve_eval(c0, s)), mul(t, curve_eval(c1, s)))
    if ty == "coons":
        return _coons(p, s, t)
    if ty == "hermite-coons":
        return _hermite_coons(p, s, t)
    if ty == "bezier-surface":
        net = p["points"]
        bs = bernstein(len(net) - 1, s)
        rows = [comb(bernstein(len(r) - 1, t), [vec(x) for x in r]) for r in net]
        return comb(bs, rows)
    if ty == "bspline-surface":
        net = p["points"]
        ps, pt = p["degree"]
        ns, nt = len(net), len(net[0])
        ks, kt = p.get("knots") or (None, None)
        Ns = bspline_basis(ps, ks or default_knots(ps, ns), ns, s)
        Nt = bspline_basis(pt, kt or default_knots(pt, nt), nt, t)
        W = p.get("weights")
        num = (0.0, 0.0, 0.0)
        den = 0.0
        for i in range(ns):
            if Ns[i] == 0:
                continue
            for j in range(nt):
                if Nt[j] == 0:
                    continue
                w = Ns[i] * Nt[j] * (W[i][j] if W else 1.0)
                num = add(num, mul(w, vec(net[i][j])))
                den += w
        return mul(1 / den, num)
    if ty == "network":
        return _network(p, s, t)
    raise ValueError("unknown patch type " + ty)


# ---------------------------------------------------------------- bodies


def trilinear(C, u, v, w, blend="linear"):
    """T(C_ijk; u,v,w); C[i][j][k]."""
    L = [blend_pair(u, blend), blend_pair(v, blend), blend_pair(w, blend)]
    r = (0.0, 0.0, 0.0)
    for i in range(2):
        for j in range(2):
            for k in range(2):
                r = add(r, mul(L[0][i] * L[1][j] * L[2][k], C[i][j][k]))
    return r


def _c1(eu, ev, ew, C, u, v, w, blend):
    """Coons body 1 from edge functions eu(j,k,u) = C(u,j,k), ev(i,k,v) =
    C(i,v,k), ew(i,j,w) = C(i,j,w) and corners C[i][j][k] (seed 000, 2.3)."""
    Lu, Lv, Lw = blend_pair(u, blend), blend_pair(v, blend), blend_pair(w, blend)
    r = mul(-2.0, trilinear(C, u, v, w, blend))
    for a in range(2):
        for b in range(2):
            r = add(r, mul(Lu[a] * Lv[b], ew(a, b, w)))
            r = add(r, mul(Lu[a] * Lw[b], ev(a, b, v)))
            r = add(r, mul(Lv[a] * Lw[b], eu(a, b, u)))
    return r


def body1_corners(b):
    return memo(_body1_corners, b)


def _body1_corners(b):
    E = b["edges"]
    C = [[[None] * 2 for _ in range(2)] for _ in range(2)]
    for i in range(2):
        for j in range(2):
            for k in range(2):
                pts = [curve_eval(E["u%d%d" % (j, k)], float(i)),
                       curve_eval(E["v%d%d" % (i, k)], float(j)),
                       curve_eval(E["w%d%d" % (i, j)], float(k))]
                C[i][j][k] = mul(1 / 3, add(add(pts[0], pts[1]), pts[2]))
    return C


def body2_edge(F, axis, a, b, x):
    """Shared edge of body2 faces F as the average of its two faces:
    axis 'u': C(x,a,b) from Y_a(x,b) and Z_b(x,a); 'v': C(a,x,b) from X_a(x,b)
    and Z_b(a,x); 'w': C(a,b,x) from X_a(b,x) and Y_b(a,x)."""
    if axis == "u":
        p, q = patch_eval(F["v%d" % a], x, b), patch_eval(F["w%d" % b], x, a)
    elif axis == "v":
        p, q = patch_eval(F["u%d" % a], x, b), patch_eval(F["w%d" % b], a, x)
    else:
        p, q = patch_eval(F["u%d" % a], b, x), patch_eval(F["v%d" % b], a, x)
    return mul(0.5, add(p, q))


def body2_corners(F):
    return memo(_body2_corners, F)


def _body2_corners(F):
    C = [[[None] * 2 for _ in range(2)] for _ in range(2)]
    for i in range(2):
        for j in range(2):
            for k in range(2):
                pts = [patch_eval(F["u%d" % i], j, k), patch_eval(F["v%d" % j], i, k),
                       patch_eval(F["w%d" % k], i, j)]
                C[i][j][k] = mul(1 / 3, add(add(pts[0], pts[1]), pts[2]))
    return C


def volume_eval(b, u, v, w):
    net = b["points"]
    n = (len(net), len(net[0]), len(net[0][0]))
    if b["type"] == "bezier-volume":
        N = [bernstein(n[0] - 1, u), bernstein(n[1] - 1, v), bernstein(n[2] - 1, w)]
        W = None
    else:
        deg = b["degree"]
        ks = b.get("knots") or (None, None, None)
        N = [bspline_basis(deg[d], ks[d] or default_knots(deg[d], n[d]), n[d], x)
             for d, x in enumerate((u, v, w))]
        W = b.get("weights")
    num = (0.0, 0.0, 0.0)
    den = 0.0
    for i in range(n[0]):
        if N[0][i] == 0:
            continue
        for j in range(n[1]):
            if N[1][j] == 0:
                continue
            for k in range(n[2]):
                if N[2][k] == 0:
                    continue
                c = N[0][i] * N[1][j] * N[2][k] * (W[i][j][k] if W else 1.0)
                num = add(num, mul(c, vec(net[i][j][k])))
                den += c
    return mul(1 / den, num)


def body_eval(b, u, v, w):
    ty = b["type"]
    blend = b.get("blend", "linear")
    if ty == "body0":
        P = [vec(x) for x in b["corners"]]
        C = [[[P[4 * i + 2 * j + k] for k in range(2)] for j in range(2)] for i in range(2)]
        return trilinear(C, u, v, w, blend)
    if ty == "body1":
        E = b["edges"]
        C = body1_corners(b)
        return _c1(lambda j, k, x: curve_eval(E["u%d%d" % (j, k)], x),
                   lambda i, k, x: curve_eval(E["v%d%d" % (i, k)], x),
                   lambda i, j, x: curve_eval(E["w%d%d" % (i, j)], x),
                   C, u, v, w, blend)
    if ty == "body2":
        F = b["faces"]
        C = body2_corners(F)
        c1 = _c1(lambda j, k, x: body2_edge(F, "u", j, k, x),
                 lambda i, k, x: body2_edge(F, "v", i, k, x),
                 lambda i, j, x: body2_edge(F, "w", i, j, x),
                 C, u, v, w, blend)
        Lu, Lv, Lw = blend_pair(u, blend), blend_pair(v, blend), blend_pair(w, blend)
        D = (0.0, 0.0, 0.0)
        for a in range(2):
            D = add(D, mul(Lu[a], patch_eval(F["u%d" % a], v, w)))
            D = add(D, mul(Lv[a], patch_eval(F["v%d" % a], u, w)))
            D = add(D, mul(Lw[a], patch_eval(F["w%d" % a], u, v)))
        return sub(sub(D, c1), trilinear(C, u, v, w, blend))
    if ty in ("bezier-volume", "bspline-volume"):
        return volume_eval(b, u, v, w)
    if ty == "shell":
        return _shell(b, u, v, w)
    if ty == "morph":
        return morph_eval(b, u, v, w)
    raise ValueError("unknown body type " + ty)


def morph_eval(b, u, v, w, t=None):
    """The morph (coons-model(5) "morph", seed 000 section 4) at its "t" (or
    t): on the interval of t between neighbouring key times, the straight
    blend of its two keys (linear path, or two keys), or the cubic Hermite
    through them with the non-uniform Catmull-Rom tangents of the spec
    (central difference quotients of the neighbouring keys, one-sided at
    the ends)."""
    keys = b["keys"]
    n = len(keys)
    at = b.get("at") or [k / (n - 1) for k in range(n)]
    t = b.get("t", 0) if t is None else t
    t = min(max(t, 0.0), 1.0)
    i = 0
    while i + 2 < n and t >= at[i + 1]:
        i += 1
    h = at[i + 1] - at[i]
    s = min((t - at[i]) / h, 1.0)
    P = {}

    def key(k):
        if k not in P:
            P[k] = body_eval(keys[k], u, v, w)
        return P[k]

    if b.get("path", "linear") == "linear" or n == 2:
        return add(mul(1 - s, key(i)), mul(s, key(i + 1)))

    def tangent(k):
        lo, hi = max(k - 1, 0), min(k + 1, n - 1)
        return mul(1.0 / (at[hi] - at[lo]), sub(key(hi), key(lo)))

    h00, h10, h11, h01 = hermite_basis(s)  # value 0, slope 0, slope 1, value 1
    return add(add(mul(h00, key(i)), mul(h * h10, tangent(i))),
               add(mul(h01, key(i + 1)), mul(h * h11, tangent(i + 1))))


def body_corner(b, i, j, k):
    return realv(body_eval(b, float(i), float(j), float(k)))


def body_jacobian_det(b, u, v, w):
    """det J at (u,v,w) by complex-step partial derivatives."""
    cols = [deriv(lambda z: body_eval(b, z, v, w), u),
            deriv(lambda z: body_eval(b, u, z, w), v),
            deriv(lambda z: body_eval(b, u, v, z), w)]
    a, bb, c = cols
    return (a[0] * (bb[1] * c[2] - bb[2] * c[1]) - a[1] * (bb[0] * c[2] - bb[2] * c[0])
            + a[2] * (bb[0] * c[1] - bb[1] * c[0]))


# ---------------------------------------------------------------- models


def _walk_points(obj, out, key=None):
    """Collect every control point of a model: 'points', 'corners' arrays
    (not tangents, twists or weights), per the format's tolerance rule."""
    if isinstance(obj, dict):
        for k, v in obj.items():
            if k in ("points", "corners"):
                _collect(v, out)
            elif k in ("tangents", "twist", "weights", "knots", "degree"):
                continue
            else:
                _walk_points(v, out, k)
    elif isinstance(obj, list):
        for v in obj:
            _walk_points(v, out, key)


def _collect(arr, out):
    if arr and isinstance(arr[0], (int, float)):
        out.append(vec(arr))
    else:
        for a in arr:
            _collect(a, out)


def control_points(model, include_cross=True):
    """All control points of the model. include_cross=False leaves out the
    'points' of Hermite cross curves (they are tangent vectors)."""
    out = []
    for b in model["bodies"]:
        if include_cross:
            _walk_points(b, out)
        else:
            _walk_points(_strip_cross(b), out)
    return out


def _strip_cross(obj):
    if isinstance(obj, dict):
        return {k: _strip_cross(v) for k, v in obj.items() if k != "cross"}
    if isinstance(obj, list):
        return [_strip_cross(v) for v in obj]
    return obj


def control_diagonal(model, include_cross=True):
    pts = control_points(model, include_cross)
    lo = [min(p[d] for p in pts) for d in range(3)]
    hi = [max(p[d] for p in pts) for d in range(3)]
    return math.sqrt(sum((hi[d] - lo[d]) ** 2 for d in range(3)))


# ---- references (coons-model(5) "Definitions and references")

def _affine(T, p):
    return [sum(T[r][c] * p[c] for c in range(3)) + T[r][3] for r in range(3)]


def _transformed(obj, T, key=None):
    """Control data mapped by y = M x + t. Exact for every type here: affine
    maps commute with the Bernstein, B-spline and rational sums (weights
    stay). Tangent-like data (cross curves, Hermite tangents) would map by
    M alone; they are refused rather than guessed."""
    if isinstance(obj, dict):
        if obj.get("type") == "hermite" or "cross" in obj:
            raise NotImplementedError("transformed tangents")
        return {k: _transformed(v, T, k) for k, v in obj.items()}
    if isinstance(obj, list):
        if key in ("points", "corners") and len(obj) == 3 and all(
                isinstance(c, (int, float)) for c in obj):
            return _affine(T, obj)
        return [_transformed(v, T, key) for v in obj]
    return obj


def expand(model):
    """The model with every body reference {"ref": NAME, ...} replaced by its
    definition, a "transform" applied to its control data, "name" kept
    (default: the definition's name). References inside definitions and
    reverse/swap/flip are not handled here (NotImplementedError)."""
    defs = model.get("define", {})

    def resolve(b):
        if "ref" not in b:
            return b
        mods = set(b) - {"ref", "name", "transform"}
        if mods:
            raise NotImplementedError("reference modifiers %s" % sorted(mods))
        d = json.loads(json.dumps(defs[b["ref"]]))
        if "transform" in b:
            d = _transformed(d, b["transform"])
        d["name"] = b.get("name", b["ref"])
        return d
    out = dict(model)
    out.pop("define", None)
    out["bodies"] = [resolve(b) for b in model["bodies"]]
    return out


def det3(T):
    """Determinant of the 3 x 3 part of a 3 x 4 transform."""
    return (T[0][0] * (T[1][1] * T[2][2] - T[1][2] * T[2][1])
            - T[0][1] * (T[1][0] * T[2][2] - T[1][2] * T[2][0])
            + T[0][2] * (T[1][0] * T[2][1] - T[1][1] * T[2][0]))


# ---------------------------------------------------------------- networks, shells
# coons-model(5) "Networks of curves" and "Shells", written from the format's
# text (seed 001 eq. 1.13-1.16 per cell), not from libcoons.


def _nodes(given, count):
    return [float(x) for x in given] if given else [k / (count - 1) for k in range(count)]


def _cell_of(x, nodes):
    i = 0
    while i + 2 < len(nodes) and re(x) >= nodes[i + 1]:
        i += 1
    return i


def network_node_data(p):
    return memo(_network_node_data, p)


def _network_node_data(p):
    rows, cols = p["rows"], p["columns"]
    sn, tn = _nodes(p.get("s_nodes"), len(cols)), _nodes(p.get("t_nodes"), len(rows))
    m, n = len(cols) - 1, len(rows) - 1
    X = [[mul(0.5, add(curve_eval(rows[j], sn[i]), curve_eval(cols[i], tn[j])))
          for j in range(n + 1)] for i in range(m + 1)]
    xs = [[curve_deriv(rows[j], sn[i]) for j in range(n + 1)] for i in range(m + 1)]
    xt = [[curve_deriv(cols[i], tn[j]) for j in range(n + 1)] for i in range(m + 1)]
    rule = p.get("twist", "bessel")

    def proposal(i, j, a, b):
        """The twist cell (i, j) proposes at its corner (a, b), in (s, t)."""
        ds, dt = sn[i + 1] - sn[i], tn[j + 1] - tn[j]
        cell = add(sub(sub(X[i][j], X[i + 1][j]), X[i][j + 1]), X[i + 1][j + 1])
        if rule == "zero":
            return (0.0, 0.0, 0.0)
        if rule == "bessel":
            return mul(1 / (ds * dt), cell)
        # adini in the cell's own parameters: x_a = ds x_s, x_b = dt x_t
        d_s = mul(dt, sub(xt[i + 1][j + b], xt[i][j + b]))
        d_t = mul(ds, sub(xs[i + a][j + 1], xs[i + a][j]))
        return mul(1 / (ds * dt), sub(add(d_s, d_t), cell))

    def weights(x, k):
        if k == 0:
            return {0: 1.0}  # only the cell after the node
        if k == len(x) - 1:
            return {-1: 1.0}
        span = x[k + 1] - x[k - 1]
        return {-1: (x[k + 1] - x[k]) / span, 0: (x[k] - x[k - 1]) / span}

    T = [[None] * (n + 1) for _ in range(m + 1)]
    for i in range(m + 1):
        for j in range(n + 1):
            acc = (0.0, 0.0, 0.0)
            for di, wi in weights(sn, i).items():
                for dj, wj in weights(tn, j).items():
                    ci, cj = i + di, j + dj
                    acc = add(acc, mul(wi * wj, proposal(ci, cj, i - ci, j - cj)))
            T[i][j] = acc
    return sn, tn, X, xs, xt, T


def _network(p, s, t):
    rows, cols = p["rows"], p["columns"]
    sn, tn, X, xs, xt, T = network_node_data(p)
    i, j = _cell_of(s, sn), _cell_of(t, tn)
    ds, dt = sn[i + 1] - sn[i], tn[j + 1] - tn[j]
    a, b = (s - sn[i]) / ds, (t - tn[j]) / dt

    def row(k, x):
        return curve_eval(rows[k], sn[i] + x * ds)

    def col(k, y):
        return curve_eval(cols[k], tn[j] + y * dt)
    Xc = [[X[i][j], X[i][j + 1]], [X[i + 1][j], X[i + 1][j + 1]]]
    if p.get("blend", "cubic") == "linear":  # eq. 1.8 on the cell
        rc = add(mul(1 - b, row(j, a)), mul(b, row(j + 1, a)))
        rd = add(mul(1 - a, col(i, b)), mul(a, col(i + 1, b)))
        rcd = comb([(1 - a) * (1 - b), a * (1 - b), (1 - a) * b, a * b],
                   [Xc[0][0], Xc[1][0], Xc[0][1], Xc[1][1]])
        return sub(add(rc, rd), rcd)
    # local corner data: x_a = ds x_s, x_b = dt x_t, x_ab = ds dt x_st
    Ls = [[mul(ds, xs[i + A][j + B]) for B in range(2)] for A in range(2)]
    Lt = [[mul(dt, xt[i + A][j + B]) for B in range(2)] for A in range(2)]
    Lw = [[mul(ds * dt, T[i + A][j + B]) for B in range(2)] for A in range(2)]
    Ha, Hb = hermite_basis(a), hermite_basis(b)
    # ribbons, eq. 1.16
    xt0 = comb(Ha, [Lt[0][0], Lw[0][0], Lw[1][0], Lt[1][0]])
    xt1 = comb(Ha, [Lt[0][1], Lw[0][1], Lw[1][1], Lt[1][1]])
    xs0 = comb(Hb, [Ls[0][0], Lw[0][0], Lw[0][1], Ls[0][1]])
    xs1 = comb(Hb, [Ls[1][0], Lw[1][0], Lw[1][1], Ls[1][1]])
    hc = comb(Ha, [col(i, b), xs0, xs1, col(i + 1, b)])   # eq. 1.13
    hd = comb(Hb, [row(j, a), xt0, xt1, row(j + 1, a)])   # eq. 1.14
    M = [[Xc[0][0], Lt[0][0], Lt[0][1], Xc[0][1]],        # eq. 1.15
         [Ls[0][0], Lw[0][0], Lw[0][1], Ls[0][1]],
         [Ls[1][0], Lw[1][0], Lw[1][1], Ls[1][1]],
         [Xc[1][0], Lt[1][0], Lt[1][1], Xc[1][1]]]
    hcd = (0.0, 0.0, 0.0)
    for k in range(4):
        hcd = add(hcd, mul(Ha[k], comb(Hb, M[k])))
    return sub(add(hc, hd), hcd)


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _shell(b, u, v, w):
    """S = x + (w - c) h n, n = x_s x x_t / |x_s x x_t| (real u, v, w: the
    partials of the patch by complex step)."""
    p = b["surface"]
    x = realv(patch_eval(p, u, v))
    xs = deriv(lambda z: patch_eval(p, z, v), u)
    xt = deriv(lambda z: patch_eval(p, u, z), v)
    N = _cross(xs, xt)
    n = mul(1 / math.sqrt(N[0] ** 2 + N[1] ** 2 + N[2] ** 2), N)
    c = {"both": 0.5, "front": 0.0, "back": 1.0}[b.get("side", "both")]
    return add(x, mul((w - c) * float(b["thickness"]), n))
