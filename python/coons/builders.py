# SPDX-License-Identifier: GPL-3.0-or-later
"""Curves, patches and bodies built from numpy arrays (the constructors of
coons/curve.h, coons/patch.h and coons/body.h), one function per "type" of
the model format under the same name (``-`` becomes ``_``: "coons-cubic"
is :func:`coons_cubic`, "bezier-volume" :func:`bezier_volume`). Each
object carries its model-format description, so that :class:`coons.Model`
and Model.to_json() give a file coons2stl reads as the same model.

Index conventions are the model format's (coons-model(5)): ``P[i][j][k]``
has i along u, j along v, k along w; ``points[i][j]`` of a surface has i
along s. A point may have 2 coordinates (z = 0)."""
import contextlib
import json
import numbers

import numpy as np

from . import _args, _lib
from ._handle import Handle
from .errors import InvalidError
from .model import Body, loads
from .shapes import Curve, Patch


def _blend(blend):
    if blend not in ("linear", "cubic"):
        raise InvalidError("blend: expected 'linear' or 'cubic', got %r" % (blend,))
    return blend == "cubic"


def _name(spec, name):
    if name is not None:
        if not isinstance(name, str):
            raise InvalidError("name: expected a string, got %r" % (name,))
        spec["name"] = name
    return name


def _own(ptr, spec, name, default):
    return Body(Handle(ptr, _lib.body_free, "body"), None, name or default, spec)


def body0(corners, blend="linear", name=None):
    """Coons body 0, the trilinear interpolation of 8 corners: corners
    (2, 2, 2, 3), [i][j][k] = P_ijk (i along u, j along v, k along w)."""
    c = _args.float_array(corners, "corners")
    if c.shape != (2, 2, 2, 3):
        raise InvalidError("corners: expected shape (2, 2, 2, 3), got %s" % (c.shape,))
    cubic = _blend(blend)
    spec = {"type": "body0", "corners": c.reshape(8, 3).tolist()}
    if cubic:
        spec["blend"] = "cubic"
    _name(spec, name)
    return _own(_lib.body_new_body0(c, cubic), spec, name, "body0")


def _net(points, what):
    p = _args.float_array(points, what)
    if p.ndim != 4 or p.shape[3] != 3 or min(p.shape[:3]) < 2:
        raise InvalidError("%s: expected shape (nu, nv, nw, 3), each n >= 2, got %s"
                           % (what, p.shape))
    if p.shape[0] * p.shape[1] * p.shape[2] > _lib.lib.COONS_BODY_MAX_POINTS:
        raise _args.LimitError("%s: %d points, more than %d" % (
            what, p.shape[0] * p.shape[1] * p.shape[2], _lib.lib.COONS_BODY_MAX_POINTS))
    return p


def bezier_volume(points, name=None):
    """Tensor-product Bezier volume: points (l+1, m+1, n+1, 3)."""
    p = _net(points, "points")
    spec = {"type": "bezier-volume", "points": p.tolist()}
    _name(spec, name)
    return _own(_lib.body_new_bezier(p), spec, name, "bezier-volume")


def bspline_volume(points, knots_u, knots_v, knots_w, weights=None, name=None):
    """Tensor-product B-spline (NURBS with weights) volume: points
    (nu, nv, nw, 3); knots_d (n_d + p_d + 1,) non-decreasing, which gives the
    degrees p_d; weights None or (nu, nv, nw), > 0."""
    p = _net(points, "points")
    knots, degree = [], []
    for d, k in enumerate((knots_u, knots_v, knots_w)):
        k = _args.float_array(k, "knots_" + "uvw"[d], ndim=1)
        deg = len(k) - p.shape[d] - 1
        if deg < 1:
            raise InvalidError("knots_%s: %d values for %d points give degree %d (< 1)"
                               % ("uvw"[d], len(k), p.shape[d], deg))
        knots.append(np.ascontiguousarray(k))
        degree.append(deg)
    w = None
    spec = {"type": "bspline-volume", "degree": degree, "points": p.tolist(),
            "knots": [k.tolist() for k in knots]}
    if weights is not None:
        w = _args.float_array(weights, "weights")
        if w.shape != p.shape[:3]:
            raise InvalidError("weights: expected shape %s, got %s" % (p.shape[:3], w.shape))
        spec["weights"] = w.tolist()
    _name(spec, name)
    return _own(_lib.body_new_bspline(degree, p, knots[0], knots[1], knots[2], w), spec, name,
                "bspline-volume")


def body(type, name=None, **fields):
    """Any body of the model format from its JSON fields, e.g.
    ``coons.body("body1", edges={...})`` or ``coons.body("shell", ...)``:
    the fields are the format's (numpy arrays allowed), checked by the
    library's loader."""
    spec = {"type": type}
    for k, v in fields.items():
        spec[k] = v.tolist() if isinstance(v, np.ndarray) else v
    _name(spec, name)
    text = json.dumps({"coons": 1, "bodies": [spec]}, default=_json_default)
    m = loads(text, name="<%s>" % type)
    b = m.bodies[0]
    b._spec = json.loads(text)["bodies"][0]
    return b


def _json_default(x):
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, np.generic):
        return x.item()
    raise TypeError("not JSON: %r" % (x,))


# ---- curves (t in [0, 1]) -------------------------------------------------

def _pad(x):
    """Nested lists of points, each [x, y] or [x, y, z] (mixed as the model
    format allows): every point with 3 coordinates."""
    if isinstance(x, (list, tuple)):
        if x and all(isinstance(c, numbers.Real) for c in x):
            return list(x) + [0.0] if len(x) == 2 else x
        return [_pad(c) for c in x]
    return x


def _points(x, what, ndim=2):
    """float64 points with 2 or 3 coordinates (z = 0) -> C-contiguous (..., 3)."""
    a = _args.float_array(_pad(x), what)
    if a.ndim != ndim or a.shape[-1] not in (2, 3):
        raise InvalidError("%s: expected shape %s with 2 or 3 coordinates, got %s"
                           % (what, "(n, 3)" if ndim == 2 else "(ns, nt, 3)", a.shape))
    if a.shape[-1] == 2:
        a = np.concatenate([a, np.zeros(a.shape[:-1] + (1,))], axis=-1)
    if a.size // 3 > _lib.lib.COONS_BODY_MAX_POINTS:
        raise _args.LimitError("%s: %d points, more than %d"
                               % (what, a.size // 3, _lib.lib.COONS_BODY_MAX_POINTS))
    return np.ascontiguousarray(a)


def _curve(ptr, spec):
    return Curve(Handle(ptr, _lib.curve_free, "curve"), spec)


def _count(p, what, n):
    if p.shape[0] != n:
        raise InvalidError("%s: expected %d points, got %d" % (what, n, p.shape[0]))


def line(points):
    """The segment (1-t) P0 + t P1: points (2, 3)."""
    p = _points(points, "points")
    _count(p, "points", 2)
    return _curve(_lib.curve_new("line", p), {"type": "line", "points": p.tolist()})


def polyline(points):
    """n segments through n+1 >= 2 points, segment i over [i/n, (i+1)/n]."""
    p = _points(points, "points")
    return _curve(_lib.curve_new("polyline", p), {"type": "polyline", "points": p.tolist()})


def bezier(points):
    """The Bezier curve of degree n of n+1 >= 2 control points (Bernstein basis)."""
    p = _points(points, "points")
    return _curve(_lib.curve_new("bezier", p), {"type": "bezier", "points": p.tolist()})


def hermite(points, tangents):
    """The cubic Hermite curve: points (2, 3) at t = 0 and 1, tangents (2, 3)
    d/dt there."""
    p, t = _points(points, "points"), _points(tangents, "tangents")
    _count(p, "points", 2)
    _count(t, "tangents", 2)
    return _curve(_lib.curve_new_hermite(p, t),
                  {"type": "hermite", "points": p.tolist(), "tangents": t.tolist()})


def coons_cubic(points, closed=False):
    """The Coons cubic B-spline of N. Pajerova's "Computer graphics, Lesson 3":
    open, n+1 >= 4 points and n-2 uniform segments; closed, m >= 3 cyclic points."""
    p = _points(points, "points")
    if not isinstance(closed, bool):
        raise InvalidError("closed: expected True or False, got %r" % (closed,))
    spec = {"type": "coons-cubic", "points": p.tolist()}
    if closed:
        spec["closed"] = True
    return _curve(_lib.curve_new("coons-cubic", p, closed=closed), spec)


def clamped_cubic(points):
    """The uniform clamped cubic B-spline of n+1 >= 4 points (through P0 and Pn)."""
    p = _points(points, "points")
    return _curve(_lib.curve_new("clamped-cubic", p), {"type": "clamped-cubic",
                                                        "points": p.tolist()})


def _degree(x, what):
    return _args.count(x, what, 1, 1 << 16)


def _knots(k, what, n):
    k = np.ascontiguousarray(_args.float_array(k, what, ndim=1))
    if len(k) != n:
        raise InvalidError("%s: expected %d values, got %d" % (what, n, len(k)))
    return k


def _weights(w, what, shape):
    w = np.ascontiguousarray(_args.float_array(w, what))
    if w.shape != shape:
        raise InvalidError("%s: expected shape %s, got %s" % (what, shape, w.shape))
    return w


def bspline(points, degree, knots=None, weights=None):
    """B-spline (NURBS with weights) curve of degree p >= 1 over n+1 points;
    knots (n + p + 2,) non-decreasing (default clamped uniform), the domain
    [knots[p], knots[n+1]] mapped onto [0, 1]; weights (n+1,) > 0."""
    p = _points(points, "points")
    deg = _degree(degree, "degree")
    spec = {"type": "bspline", "degree": deg, "points": p.tolist()}
    k = w = None
    if knots is not None:
        k = _knots(knots, "knots", len(p) + deg + 1)
        spec["knots"] = k.tolist()
    if weights is not None:
        w = _weights(weights, "weights", (len(p),))
        spec["weights"] = w.tolist()
    return _curve(_lib.curve_new("bspline", p, degree=deg, knots=k, weights=w), spec)


# ---- patches ((s, t) in [0, 1]^2) -----------------------------------------

_SIDES = ("t0", "t1", "s0", "s1")


def _patch(ptr, spec):
    return Patch(Handle(ptr, _lib.patch_free, "patch"), spec)


def _parts(objs, cls, what):
    for o in objs:
        if not isinstance(o, cls):
            raise InvalidError("%s: expected a coons.%s, got %r" % (what, cls.__name__, o))
    return objs


@contextlib.contextmanager
def _pointers(objs):
    """C pointers of Curves, Patches or Bodies, each in use for the block."""
    with contextlib.ExitStack() as stack:
        out = []
        for o in objs:
            if isinstance(o, Body):
                out.append(stack.enter_context(o._ptr()))
            else:
                out.append(stack.enter_context(o._h.use()))
        yield out


def _keyed(d, keys, cls, what):
    if not isinstance(d, dict) or set(d) != set(keys):
        got = sorted(d) if isinstance(d, dict) else type(d).__name__
        raise InvalidError("%s: expected a dict with keys %s, got %s"
                           % (what, " ".join(keys), got))
    return _parts([d[k] for k in keys], cls, what)


def bilinear(corners):
    """The bilinear patch of corners (4, 3) = [X00, X10, X01, X11], Xab = x(s=a, t=b)."""
    c = _points(corners, "corners")
    _count(c, "corners", 4)
    return _patch(_lib.patch_new_bilinear(c), {"type": "bilinear", "corners": c.tolist()})


def ruled(curves):
    """x(s, t) = (1-t) c0(s) + t c1(s) for curves = [c0, c1] (coons.Curve)."""
    cs = _parts(list(curves), Curve, "curves")
    if len(cs) != 2:
        raise InvalidError("curves: expected 2 curves, got %d" % len(cs))
    with _pointers(cs) as p:
        ptr = _lib.patch_new_ruled(p[0], p[1])
    return _patch(ptr, {"type": "ruled", "curves": [c.to_dict() for c in cs]})


def coons(boundary, blend="linear"):
    """The Coons patch of four boundary curves, boundary = {"t0": x(s,0),
    "t1": x(s,1), "s0": x(0,t), "s1": x(1,t)} (coons.Curve), bilinearly
    (``"linear"``) or cubically blended (P. Bonomi's "Superfici di Coons",
    eq. 1.8/1.11)."""
    cs = _keyed(boundary, _SIDES, Curve, "boundary")
    cubic = _blend(blend)
    with _pointers(cs) as p:
        ptr = _lib.patch_new_coons(p, cubic)
    spec = {"type": "coons", "boundary": {k: c.to_dict() for k, c in zip(_SIDES, cs)}}
    if cubic:
        spec["blend"] = "cubic"
    return _patch(ptr, spec)


coons_patch = coons


def hermite_coons(boundary, cross=None, twist="zero"):
    """The bicubically blended (Hermite) Coons patch (eq. 1.13-1.15):
    boundary as for :func:`coons`; cross None (tangent ribbons, eq. 1.16) or
    the four cross-boundary derivative curves {"t0": x_t(s,0), "t1": x_t(s,1),
    "s0": x_s(0,t), "s1": x_s(1,t)}; twist "zero", "adini", "bessel" or (4, 3)
    = [x_st(0,0), x_st(1,0), x_st(0,1), x_st(1,1)]."""
    cs = _keyed(boundary, _SIDES, Curve, "boundary")
    xs = None if cross is None else _keyed(cross, _SIDES, Curve, "cross")
    spec = {"type": "hermite-coons", "boundary": {k: c.to_dict() for k, c in zip(_SIDES, cs)}}
    twists = None
    if isinstance(twist, str):
        if twist not in ("zero", "adini", "bessel"):
            raise InvalidError("twist: expected 'zero', 'adini', 'bessel' or 4 vectors, got %r"
                               % (twist,))
        if twist != "zero":
            spec["twist"] = twist
    else:
        twists = _points(twist, "twist")
        _count(twists, "twist", 4)
        spec["twist"] = twists.tolist()
    if xs is not None:
        spec["cross"] = {k: c.to_dict() for k, c in zip(_SIDES, xs)}
    with _pointers(cs + (xs or [])) as p:
        ptr = _lib.patch_new_hermite_coons(p[:4], p[4:] or None, twist, twists)
    return _patch(ptr, spec)


def bezier_surface(points):
    """Tensor-product Bezier surface: points (ns, nt, 3), each n >= 2, i along s."""
    p = _points(points, "points", ndim=3)
    return _patch(_lib.patch_new_bezier(p), {"type": "bezier-surface", "points": p.tolist()})


def bspline_surface(points, degree, knots=None, weights=None):
    """Tensor-product B-spline (NURBS with weights) surface: points (ns, nt, 3),
    degree (p, q), knots None (clamped uniform) or [ks, kt], weights (ns, nt)."""
    p = _points(points, "points", ndim=3)
    try:
        deg = [_degree(d, "degree") for d in degree]
    except TypeError:
        raise InvalidError("degree: expected two integers, got %r" % (degree,)) from None
    if len(deg) != 2:
        raise InvalidError("degree: expected two integers, got %r" % (degree,))
    spec = {"type": "bspline-surface", "degree": deg, "points": p.tolist()}
    ks = kt = w = None
    if knots is not None:
        if len(knots) != 2:
            raise InvalidError("knots: expected [ks, kt], got %d arrays" % len(knots))
        ks = _knots(knots[0], "knots[0]", p.shape[0] + deg[0] + 1)
        kt = _knots(knots[1], "knots[1]", p.shape[1] + deg[1] + 1)
        spec["knots"] = [ks.tolist(), kt.tolist()]
    if weights is not None:
        w = _weights(weights, "weights", p.shape[:2])
        spec["weights"] = w.tolist()
    return _patch(_lib.patch_new_bspline(deg, p, ks, kt, w), spec)


def _nodes(x, what, n):
    if x is None:
        return None
    a = _knots(x, what, n)
    return a


def network(rows, columns, s_nodes=None, t_nodes=None, twist="bessel", blend="cubic"):
    """A network of curves filled C1 (P. Bonomi's "Superfici di Coons", 1.2.2):
    rows (n+1 >= 2 coons.Curve, row j = x(s, t_j)), columns (m+1 >= 2, column
    i = x(s_i, t)), node parameters (default uniform), twist "zero", "adini"
    or "bessel", blend "cubic" (Hermite cells) or "linear" (Coons cells)."""
    rs = _parts(list(rows), Curve, "rows")
    cs = _parts(list(columns), Curve, "columns")
    if twist not in ("zero", "adini", "bessel"):
        raise InvalidError("twist: expected 'zero', 'adini' or 'bessel', got %r" % (twist,))
    cubic = _blend(blend)
    sn, tn = _nodes(s_nodes, "s_nodes", len(cs)), _nodes(t_nodes, "t_nodes", len(rs))
    spec = {"type": "network", "rows": [c.to_dict() for c in rs],
            "columns": [c.to_dict() for c in cs], "twist": twist,
            "blend": "cubic" if cubic else "linear"}
    if sn is not None:
        spec["s_nodes"] = sn.tolist()
    if tn is not None:
        spec["t_nodes"] = tn.tolist()
    with _pointers(rs + cs) as p:
        ptr = _lib.patch_new_network(p[:len(rs)], p[len(rs):], sn, tn, twist, cubic)
    return _patch(ptr, spec)


# ---- the other bodies -----------------------------------------------------

_EDGES = ("u00", "u01", "u10", "u11", "v00", "v01", "v10", "v11", "w00", "w01", "w10", "w11")


def body1(edges, blend="linear", name=None):
    """Coons body 1 of 12 edge curves (coons.Curve) keyed u00 .. w11 (uJK =
    C(u,J,K), vIK = C(I,v,K), wIJ = C(I,J,w))."""
    cs = _keyed(edges, _EDGES, Curve, "edges")
    cubic = _blend(blend)
    spec = {"type": "body1", "edges": {k: c.to_dict() for k, c in zip(_EDGES, cs)}}
    if cubic:
        spec["blend"] = "cubic"
    _name(spec, name)
    with _pointers(cs) as p:
        ptr = _lib.body_new_body1(p, cubic)
    return _own(ptr, spec, name, "body1")


def body2(faces, blend="linear", name=None):
    """Coons body 2 of 6 face patches (coons.Patch) keyed u0 u1 (X_I(v,w)), v0
    v1 (Y_J(u,w)), w0 w1 (Z_K(u,v)); C2 = D - C1 - T (seed 000, 2.4)."""
    ps = _keyed(faces, _lib.FACE_NAMES, Patch, "faces")
    cubic = _blend(blend)
    spec = {"type": "body2", "faces": {k: f.to_dict() for k, f in zip(_lib.FACE_NAMES, ps)}}
    if cubic:
        spec["blend"] = "cubic"
    _name(spec, name)
    with _pointers(ps) as p:
        ptr = _lib.body_new_body2(p, cubic)
    return _own(ptr, spec, name, "body2")


def shell(surface, thickness, side="both", name=None):
    """A surface made solid: S(u,v,w) = x(u,v) + (w - c) h n(u,v), surface a
    coons.Patch, h = thickness > 0, side "both" (c = 1/2), "front" (0) or
    "back" (1)."""
    (s,) = _parts([surface], Patch, "surface")
    h = _args.positive(thickness, "thickness")
    if side not in ("both", "front", "back"):
        raise InvalidError("side: expected 'both', 'front' or 'back', got %r" % (side,))
    spec = {"type": "shell", "surface": s.to_dict(), "thickness": h}
    if side != "both":
        spec["side"] = side
    _name(spec, name)
    with _pointers([s]) as p:
        ptr = _lib.body_new_shell(p[0], h, side)
    return _own(ptr, spec, name, "shell")


def morph(keys, at=None, path="linear", t=0.0, name=None):
    """The metamorphosis M = sum_k W_k(t) K_k of 2 or more key bodies
    (coons.Body), at = key times (default uniform), path "linear" or
    "smooth" (C1 Catmull-Rom), taken at time t."""
    ks = _parts(list(keys), Body, "keys")
    if path not in ("linear", "smooth"):
        raise InvalidError("path: expected 'linear' or 'smooth', got %r" % (path,))
    tt = _args.time(t)
    if tt is None:
        raise InvalidError("t: expected a number in [0, 1], got None")
    a = None if at is None else _knots(at, "at", len(ks))
    specs = []
    for k in ks:
        if k._spec is None:  # a body of a loaded model: no description of its own
            specs = None
            break
        d = k.to_dict()
        d.pop("name", None)
        specs.append(d)
    spec = {"type": "morph", "keys": specs}
    if a is not None:
        spec["at"] = a.tolist()
    if path != "linear":
        spec["path"] = path
    if tt:
        spec["t"] = tt
    _name(spec, name)
    with _pointers(ks) as p:
        ptr = _lib.body_new_morph(p, a, path == "smooth", tt)
    return _own(ptr, spec if specs is not None else None, name, "morph")
