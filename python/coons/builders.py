# SPDX-License-Identifier: GPL-3.0-or-later
"""Bodies built from numpy arrays (coons/body.h constructors), each
carrying its model-format description so that :class:`coons.Model` and
Model.to_json() give a file coons2stl reads as the same body.

Index conventions are the model format's (coons-model(5)): ``P[i][j][k]``
has i along u, j along v, k along w."""
import json

import numpy as np

from . import _args, _lib
from ._handle import Handle
from .errors import InvalidError
from .model import Body, loads


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
