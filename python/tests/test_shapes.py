# SPDX-License-Identifier: GPL-3.0-or-later
"""Curves, patches and the bodies made of them, built from numpy (one
builder per "type" of the model format): each curve and patch against its
closed form computed here (the seeds' formulas: Bernstein, Hermite, the
Coons cubic polynomials, Cox-de Boor, the Coons patch eq. 1.8), and every
body of every example rebuilt through the builders equal to the loaded
model bitwise, its Model.to_json() read back by coons2stl."""
import json
from math import comb

import numpy as np
import pytest

import coons
from conftest import EXAMPLE_FILES, example, ids, run_cli
from test_eval import cli_eval, points

RNG = np.random.default_rng(11)
T = np.r_[0.0, 1.0, 0.5, RNG.random(17)]


def close(a, b, tol=1e-13):
    a, b = np.asarray(a), np.asarray(b)
    return np.max(np.abs(a - b)) <= tol * max(1.0, np.max(np.abs(b)))


# ---- independent evaluations ------------------------------------------------

def bernstein(n, i, t):
    return comb(n, i) * t ** i * (1 - t) ** (n - i)


def bezier_ref(P, t):
    n = len(P) - 1
    return sum(np.outer(bernstein(n, i, t), P[i]) for i in range(n + 1))


def basis(knots, p, i, x):
    """Cox-de Boor N_i,p(x), right-continuous, the last span closed."""
    k = knots
    if p == 0:
        last = k[i + 1] == k[-1] and k[i] < k[i + 1]
        return np.where((k[i] <= x) & ((x < k[i + 1]) | (last & (x == k[i + 1]))), 1.0, 0.0)
    a = 0.0 if k[i + p] == k[i] else (x - k[i]) / (k[i + p] - k[i]) * basis(k, p - 1, i, x)
    b = 0.0 if k[i + p + 1] == k[i + 1] else \
        (k[i + p + 1] - x) / (k[i + p + 1] - k[i + 1]) * basis(k, p - 1, i + 1, x)
    return a + b


def nurbs_ref(P, p, knots, t, w=None):
    """A (rational) B-spline at normalised t: the domain [k_p, k_{n+1}]."""
    n = len(P)
    x = knots[p] + t * (knots[n] - knots[p])
    w = np.ones(n) if w is None else np.asarray(w, float)
    N = np.array([basis(knots, p, i, x) * w[i] for i in range(n)])  # (n, m)
    return (N.T @ P) / N.sum(axis=0)[:, None]


def clamped_uniform(n, p):
    inner = np.linspace(0, 1, n - p + 1)
    return np.r_[[0.0] * p, inner, [1.0] * p]


def coons_cubic_ref(P, t):
    """N. Pajerova, "Computer graphics, Lesson 3": segment s of the open
    Coons cubic B-spline uses P_s..P_s+3 with C0 = (1-x)^3/6,
    C1 = (3x^3 - 6x^2 + 4)/6, C2 = (-3x^3 + 3x^2 + 3x + 1)/6, C3 = x^3/6."""
    segs = len(P) - 3
    out = []
    for tt in t:
        s = min(int(tt * segs), segs - 1)
        x = tt * segs - s
        c = [(1 - x) ** 3 / 6, (3 * x ** 3 - 6 * x ** 2 + 4) / 6,
             (-3 * x ** 3 + 3 * x ** 2 + 3 * x + 1) / 6, x ** 3 / 6]
        out.append(sum(c[r] * P[s + r] for r in range(4)))
    return np.array(out)


# ---- curves -------------------------------------------------------------------

def test_curves_against_their_closed_forms():
    P = RNG.random((6, 3)) * 10
    assert close(coons.line(P[:2]).eval(T), np.outer(1 - T, P[0]) + np.outer(T, P[1]))
    # polyline: segment i over [i/n, (i+1)/n]
    n = len(P) - 1
    i = np.minimum((T * n).astype(int), n - 1)
    x = (T * n - i)[:, None]
    assert close(coons.polyline(P).eval(T), (1 - x) * P[i] + x * P[i + 1])
    assert close(coons.bezier(P).eval(T), bezier_ref(P, T))
    # cubic Hermite: H0 = 2t^3 - 3t^2 + 1, H1 = t^3 - 2t^2 + t, H2 = t^3 - t^2, H3 = -2t^3 + 3t^2
    tg = RNG.random((2, 3)) * 5
    H = [2 * T ** 3 - 3 * T ** 2 + 1, T ** 3 - 2 * T ** 2 + T, T ** 3 - T ** 2,
         -2 * T ** 3 + 3 * T ** 2]
    ref = np.outer(H[0], P[0]) + np.outer(H[1], tg[0]) + np.outer(H[2], tg[1]) + \
        np.outer(H[3], P[1])
    h = coons.hermite(P[:2], tg)
    assert close(h.eval(T), ref)
    assert close(h.derivatives([0.0, 1.0])[:, 1], tg)
    assert close(coons.coons_cubic(P).eval(T), coons_cubic_ref(P, T))
    # closed: the m points cyclic, as if P0, P1, P2 were appended
    Q = np.vstack([P[:4], P[:3]])
    assert close(coons.coons_cubic(P[:4], closed=True).eval(T), coons_cubic_ref(Q, T))
    # clamped cubic: knots 0,0,0,0,1,...,n-3,n-2 x4, normalised
    knots = np.r_[[0.0] * 4, np.arange(1, n - 2), [n - 2.0] * 4] / (n - 2)
    assert close(coons.clamped_cubic(P).eval(T), nurbs_ref(P, 3, knots, T))
    # B-spline and NURBS, default (clamped uniform) and explicit knots
    assert close(coons.bspline(P, 2).eval(T), nurbs_ref(P, 2, clamped_uniform(6, 2), T))
    k = np.sort(np.r_[0, 0, 0.1, 0.25, 0.25, 0.6, 0.9, 2, 2.5])
    w = 0.5 + RNG.random(6)
    assert close(coons.bspline(P, 2, knots=k, weights=w).eval(T), nurbs_ref(P, 2, k, T, w))
    # 2-D points are z = 0
    assert np.all(coons.bezier(P[:, :2]).eval(T)[:, 2] == 0)
    assert coons.coons_cubic(P).type == "coons-cubic"


def test_curve_derivatives():
    P = RNG.random((5, 3))
    c = coons.bezier(P)
    h = 1e-6
    d = c.derivatives(T[3:], order=2)
    fd = (c.eval(T[3:] + h) - c.eval(T[3:] - h)) / (2 * h)
    assert d.shape == (17, 3, 3) and close(d[:, 1], fd, 1e-7)


# ---- patches ------------------------------------------------------------------

ST = np.c_[RNG.random(25), RNG.random(25)]
ST = np.vstack([ST, [[0, 0], [1, 0], [0, 1], [1, 1], [0.5, 0.5]]])


def square_boundary(rng, wobble=0.3):
    """Four curves that meet at the corners of a wobbly unit square."""
    X = {(a, b): np.array([a, b, 0.0]) + wobble * rng.random(3) for a in (0, 1) for b in (0, 1)}

    def cub(p, q):
        mid = rng.random((2, 3)) * wobble
        return coons.bezier([p, p + (q - p) / 3 + mid[0], p + 2 * (q - p) / 3 + mid[1], q])
    return X, {"t0": cub(X[0, 0], X[1, 0]), "t1": cub(X[0, 1], X[1, 1]),
               "s0": cub(X[0, 0], X[0, 1]), "s1": cub(X[1, 0], X[1, 1])}


def test_patches_against_their_closed_forms():
    rng = np.random.default_rng(5)
    C = rng.random((4, 3))
    s, t = ST[:, :1], ST[:, 1:]
    ref = (1 - s) * (1 - t) * C[0] + s * (1 - t) * C[1] + (1 - s) * t * C[2] + s * t * C[3]
    assert close(coons.bilinear(C).eval(ST), ref)
    c0, c1 = coons.bezier(rng.random((3, 3))), coons.polyline(rng.random((4, 3)))
    assert close(coons.ruled([c0, c1]).eval(ST),
                 (1 - t) * c0.eval(ST[:, 0]) + t * c1.eval(ST[:, 0]))
    # the bilinearly blended Coons patch (P. Bonomi, eq. 1.8): ruled + ruled - bilinear
    X, bd = square_boundary(rng)
    for blend in ("linear", "cubic"):
        f = (lambda x: x) if blend == "linear" else (lambda x: 3 * x ** 2 - 2 * x ** 3)
        fs, ft = f(s), f(t)
        ref = (1 - ft) * bd["t0"].eval(ST[:, 0]) + ft * bd["t1"].eval(ST[:, 0]) + \
            (1 - fs) * bd["s0"].eval(ST[:, 1]) + fs * bd["s1"].eval(ST[:, 1]) - \
            ((1 - fs) * (1 - ft) * X[0, 0] + fs * (1 - ft) * X[1, 0] +
             (1 - fs) * ft * X[0, 1] + fs * ft * X[1, 1])
        p = coons.coons(bd, blend=blend)
        assert close(p.eval(ST), ref), blend
        assert p.type == "coons"
    # tensor Bezier and NURBS surfaces
    P = rng.random((4, 3, 3))
    ref = sum(np.outer(bernstein(3, i, ST[:, 0]) * bernstein(2, j, ST[:, 1]), P[i, j])
              for i in range(4) for j in range(3))
    assert close(coons.bezier_surface(P).eval(ST), ref)
    P = rng.random((5, 4, 3))
    W = 0.5 + rng.random((5, 4))
    ks, kt = clamped_uniform(5, 2), np.r_[0, 0, 0, 0.3, 1, 1, 1]
    Ns = np.array([basis(ks, 2, i, ST[:, 0]) for i in range(5)])
    Nt = np.array([basis(kt, 2, j, ST[:, 1]) for j in range(4)])
    num = np.einsum("im,jm,ij,ijr->mr", Ns, Nt, W, P)
    den = np.einsum("im,jm,ij->m", Ns, Nt, W)[:, None]
    assert close(coons.bspline_surface(P, (2, 2), knots=[ks, kt], weights=W).eval(ST),
                 num / den)


def test_hermite_coons_and_network_pass_through_their_curves():
    """Eq. 1.13-1.15 and the network of 1.2.2 interpolate their curves."""
    rng = np.random.default_rng(9)
    X, bd = square_boundary(rng)
    u = T[3:]
    z, o = np.zeros_like(u), np.ones_like(u)
    for tw in ("zero", "adini", "bessel"):
        p = coons.hermite_coons(bd, twist=tw)
        assert p.type == "hermite-coons"
        assert close(p.eval(np.c_[u, z]), bd["t0"].eval(u), 1e-12), tw
        assert close(p.eval(np.c_[u, o]), bd["t1"].eval(u), 1e-12), tw
        assert close(p.eval(np.c_[z, u]), bd["s0"].eval(u), 1e-12), tw
        assert close(p.eval(np.c_[o, u]), bd["s1"].eval(u), 1e-12), tw
    # a 3 x 3 node grid on z = f(x, y); rows and columns are degree-1
    # B-splines with their middle knot at the node parameter
    f = lambda x, y: 0.2 * np.sin(3 * x) * np.cos(2 * y)  # noqa: E731
    sn, tn = np.array([0, 0.4, 1.0]), np.array([0, 0.5, 1.0])
    nodes = np.array([[[x, y, f(x, y)] for y in tn] for x in sn])  # [i][j]
    rows = [coons.bspline(nodes[:, j], 1, knots=[0, 0, sn[1], 1, 1]) for j in range(3)]
    cols = [coons.bspline(nodes[i, :], 1, knots=[0, 0, tn[1], 1, 1]) for i in range(3)]
    x = np.linspace(0, 1, 11)
    for blend in ("cubic", "linear"):
        p = coons.network(rows, cols, s_nodes=sn, t_nodes=tn, blend=blend)
        assert p.type == "network"
        for j, tj in enumerate(tn):
            assert close(p.eval(np.c_[x, np.full(11, tj)]), rows[j].eval(x), 1e-12)
        for i, si in enumerate(sn):
            assert close(p.eval(np.c_[np.full(11, si), x]), cols[i].eval(x), 1e-12)


def test_patch_grid_equals_eval():
    rng = np.random.default_rng(2)
    p = coons.coons(square_boundary(rng)[1], blend="cubic")
    s, t = np.sort(rng.random(7)), np.sort(rng.random(5))
    g = p.grid(s, t)
    S, Tt = np.meshgrid(s, t, indexing="ij")
    e = p.eval(np.c_[S.ravel(), Tt.ravel()]).reshape(g.shape)
    assert np.all(np.abs(g - e) <= 4 * np.spacing(np.abs(e).max()))


# ---- every example body rebuilt through the builders --------------------------

def build(spec):
    """A curve, patch or body of the model format through coons.<type>()."""
    t = spec["type"]
    kw = {k: v for k, v in spec.items() if k != "type"}
    if t in ("coons", "hermite-coons"):
        kw["boundary"] = {k: build(c) for k, c in kw["boundary"].items()}
        if "cross" in kw:
            kw["cross"] = {k: build(c) for k, c in kw["cross"].items()}
        if t == "hermite-coons" and not isinstance(kw.get("twist", "zero"), str):
            kw["twist"] = np.array(kw["twist"], float)
    elif t == "ruled":
        kw["curves"] = [build(c) for c in kw["curves"]]
    elif t == "network":
        kw["rows"] = [build(c) for c in kw["rows"]]
        kw["columns"] = [build(c) for c in kw["columns"]]
    elif t == "body0":
        kw["corners"] = np.array(kw["corners"], float).reshape(2, 2, 2, 3)
    elif t == "body1":
        kw["edges"] = {k: build(c) for k, c in kw["edges"].items()}
    elif t == "body2":
        kw["faces"] = {k: build(c) for k, c in kw["faces"].items()}
    elif t == "shell":
        kw["surface"] = build(kw["surface"])
    elif t == "morph":
        kw["keys"] = [build(k) for k in kw["keys"]]
    elif t == "bspline-volume":
        pts = np.array(kw["points"], float)
        deg = kw.pop("degree")
        ku, kv, kw_ = kw.pop("knots", None) or [clamped_uniform(n, p)
                                                for n, p in zip(pts.shape[:3], deg)]
        kw.update(knots_u=ku, knots_v=kv, knots_w=kw_)
    return getattr(coons, t.replace("-", "_"))(**kw)


def has_ref(x):
    if isinstance(x, dict):
        return "ref" in x or "transform" in x or any(has_ref(v) for v in x.values())
    if isinstance(x, list):
        return any(has_ref(v) for v in x)
    return False


PLAIN = [f for f in EXAMPLE_FILES if not has_ref(json.load(open(f)))]


@pytest.mark.parametrize("path", PLAIN, ids=ids(PLAIN))
def test_every_example_body_rebuilt_equals_the_model(path):
    doc = json.load(open(path))
    m = coons.load(path)
    q = points(1, 20)
    for i, spec in enumerate(doc["bodies"]):
        b = build(spec)
        assert b.type == m.bodies[i].type
        assert np.array_equal(b.eval(q), m.bodies[i].eval(q)), (path, i)
        # its own description is a model that loads as the same body
        again = coons.loads(json.dumps({"coons": 1, "bodies": [b.to_dict()]})).bodies[0]
        assert np.array_equal(again.eval(q), m.bodies[i].eval(q)), (path, i)


def test_every_type_has_its_builder():
    """Every curve, patch and body type the examples use has coons.<type>."""
    seen = set()

    def walk(x):
        if isinstance(x, dict):
            if "type" in x:
                seen.add(x["type"])
            for v in x.values():
                walk(v)
        elif isinstance(x, list):
            for v in x:
                walk(v)
    for f in EXAMPLE_FILES:
        walk(json.load(open(f)))
    assert {"bspline", "coons", "hermite-coons", "network", "body2", "shell", "morph"} <= seen
    for t in seen:
        assert callable(getattr(coons, t.replace("-", "_"))), t


def test_built_body2_model_read_by_coons2stl(tmp_path):
    """A body 2 of Coons patches of Bezier curves, built here, written by
    Model.to_json() and evaluated by coons2stl: the same doubles."""
    rng = np.random.default_rng(4)
    corners = np.array([[[[i, j, k] for k in (0, 1)] for j in (0, 1)] for i in (0, 1)], float)
    corners = corners * [4, 3, 2] + 0.3 * rng.random((2, 2, 2, 3))

    def edge(a, b):
        return coons.bezier([a, a + (b - a) / 3 + 0.2 * rng.random(3),
                             a + 2 * (b - a) / 3 + 0.2 * rng.random(3), b])
    P = lambda i, j, k: corners[i, j, k]  # noqa: E731
    E = {}
    for j in (0, 1):
        for k in (0, 1):
            E["u%d%d" % (j, k)] = edge(P(0, j, k), P(1, j, k))
    for i in (0, 1):
        for k in (0, 1):
            E["v%d%d" % (i, k)] = edge(P(i, 0, k), P(i, 1, k))
    for i in (0, 1):
        for j in (0, 1):
            E["w%d%d" % (i, j)] = edge(P(i, j, 0), P(i, j, 1))
    faces = {}
    for I in (0, 1):  # X_I(v, w): s = v, t = w
        faces["u%d" % I] = coons.coons({"t0": E["v%d0" % I], "t1": E["v%d1" % I],
                                        "s0": E["w%d0" % I], "s1": E["w%d1" % I]})
    for J in (0, 1):  # Y_J(u, w)
        faces["v%d" % J] = coons.coons({"t0": E["u%d0" % J], "t1": E["u%d1" % J],
                                        "s0": E["w0%d" % J], "s1": E["w1%d" % J]})
    for K in (0, 1):  # Z_K(u, v)
        faces["w%d" % K] = coons.coons({"t0": E["u0%d" % K], "t1": E["u1%d" % K],
                                        "s0": E["v0%d" % K], "s1": E["v1%d" % K]})
    b2 = coons.body2(faces, name="built")
    b1 = coons.body1(E, name="frame")
    q = points(6, 15)
    # a body 2 whose faces are the Coons patches of body 1's edges is body 1
    assert close(b2.eval(q), b1.eval(q), 1e-12)
    path = tmp_path / "built.json"
    path.write_text(coons.Model([b2, b1], operation="none").to_json())
    assert np.array_equal(cli_eval(str(path), "built", q), b2.eval(q))
    assert np.array_equal(cli_eval(str(path), "frame", q), b1.eval(q))


def test_shell_and_morph_builders():
    rng = np.random.default_rng(8)
    surf = coons.bezier_surface(np.array([[[i, j, 0.3 * rng.random()] for j in range(3)]
                                          for i in range(3)], float))
    sh = coons.shell(surf, 0.5, side="front")
    uv = ST[:20]
    # S(u, v, w) = x(u, v) + w h n(u, v) for side "front"
    d = surf.derivatives(uv)
    n = np.cross(d[:, 1], d[:, 2])
    n /= np.linalg.norm(n, axis=1)[:, None]
    q = np.c_[uv, np.full(len(uv), 0.6)]
    assert close(sh.eval(q), d[:, 0] + 0.6 * 0.5 * n, 1e-12)
    a, b = coons.body0(rng.random((2, 2, 2, 3))), coons.body0(rng.random((2, 2, 2, 3)) + 1)
    m = coons.morph([a, b], t=0.25)
    qq = points(2, 10)
    assert close(m.eval(qq), 0.75 * a.eval(qq) + 0.25 * b.eval(qq), 1e-14)
    assert m.type == "morph" and sh.type == "shell"
    again = coons.loads(coons.Model([m]).to_json()).bodies[0]
    assert np.array_equal(again.eval(qq), m.eval(qq))


# ---- misuse raises ---------------------------------------------------------------

def test_builders_raise_on_bad_input():
    P = RNG.random((4, 3))
    with pytest.raises(coons.InvalidError):
        coons.line(P)                       # 4 points for a line
    with pytest.raises(coons.InvalidError):
        coons.bezier(P[:, :1])              # 1 coordinate
    with pytest.raises(coons.InvalidError):
        coons.bezier([[0, 0, np.nan], [1, 1, 1]])
    with pytest.raises(coons.InvalidError):
        coons.bspline(P, 0)                 # degree 0
    with pytest.raises(coons.InvalidError):
        coons.bspline(P, 2, knots=[0, 1])   # wrong knot count
    with pytest.raises(coons.Error):
        coons.bspline(P, 2, knots=[0, 0, 0, 0.5, 0.2, 1, 1])  # decreasing
    with pytest.raises(coons.InvalidError):
        coons.coons({"t0": coons.line(P[:2])})  # missing sides
    with pytest.raises(coons.InvalidError):
        coons.ruled([coons.line(P[:2]), "not a curve"])
    with pytest.raises(coons.InvalidError):
        coons.shell(coons.bilinear(P), -1)
    with pytest.raises(coons.InvalidError):
        coons.bilinear(P).eval([[0.5, 0.5, 0.5]])  # (n, 3) for a patch
    with pytest.raises(coons.DomainError):
        coons.line(P[:2]).eval(1.5)
    # four curves that do not meet at a corner: the library names it
    X, bd = square_boundary(np.random.default_rng(1))
    bd["s1"] = coons.line([[5, 5, 5], [6, 6, 6]])
    with pytest.raises(coons.GeometryError) as e:
        coons.coons(bd)
    assert "corner" in str(e.value)


def test_parts_outlive_what_they_were_made_of():
    """Constructors copy: a patch works after its curves are closed; a
    closed curve raises instead of reaching freed memory."""
    X, bd = square_boundary(np.random.default_rng(12))
    p = coons.coons(bd)
    before = p.eval(ST)
    for c in bd.values():
        c.close()
    assert np.array_equal(p.eval(ST), before)
    with pytest.raises(coons.ClosedError):
        bd["t0"].eval(0.5)
    with pytest.raises(coons.ClosedError):
        coons.coons(bd)
