# SPDX-License-Identifier: GPL-3.0-or-later
"""Curve and Patch: the curves (t in [0, 1]) and patches ((s, t) in
[0, 1]^2) of the model format (coons-model(5)), built from numpy arrays by
the functions of :mod:`coons.builders` and evaluated exactly
(coons/curve.h, coons/patch.h). They are the parts bodies 1 and 2, shells
and patches are made of; each carries its JSON description, so a body
built from them writes a model file coons2stl reads as the same body."""
import json

import numpy as np

from . import _args, _lib
from .errors import InvalidError


class _Part:
    def __init__(self, handle, spec):
        self._h = handle
        self._spec = spec

    @property
    def type(self):
        """The model format's "type" ("bspline", "coons", ...)."""
        with self._h.use() as p:
            return self._type_of(p)

    @property
    def closed(self):
        return self._h.closed

    def to_dict(self):
        """The JSON description (model format)."""
        return json.loads(json.dumps(self._spec))

    def close(self):
        """Frees the C object now (bodies and patches made from it keep
        their own copies)."""
        self._h.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self):
        state = "closed" if self._h.closed else self._spec.get("type")
        return "<coons.%s %s>" % (type(self).__name__, state)


class Curve(_Part):
    """A curve of the model format over t in [0, 1] (coons/curve.h)."""

    @staticmethod
    def _type_of(p):
        return _lib.curve_type(p)

    def eval(self, t):
        """Points: t scalar or (n,) in [0, 1] -> (3,) or (n, 3)."""
        q, single = _params1(t)
        with self._h.use() as p:
            x = _lib.curve_eval(p, q, 0)[:, 0]
        return x[0] if single else x

    def derivatives(self, t, order=1):
        """The point and its derivatives d/dt up to order (1 or 2):
        t scalar or (n,) -> (order + 1, 3) or (n, order + 1, 3). At an
        inner knot the right-hand derivative (coons_curve_eval_derivs)."""
        order = _args.count(order, "order", 1, 2)
        q, single = _params1(t)
        with self._h.use() as p:
            x = _lib.curve_eval(p, q, order)
        return x[0] if single else x


class Patch(_Part):
    """A patch of the model format over (s, t) in [0, 1]^2 (coons/patch.h)."""

    @staticmethod
    def _type_of(p):
        return _lib.patch_type(p)

    def eval(self, st):
        """Points: st (2,) or (n, 2) in [0, 1] -> (3,) or (n, 3)."""
        q, single = _params2(st)
        with self._h.use() as p:
            x = _lib.patch_eval(p, q, 0)[:, 0]
        return x[0] if single else x

    def derivatives(self, st, order=1):
        """The point and its partials: order 1 -> [x, x_s, x_t], order 2
        adds [x_ss, x_st, x_tt]; st (2,) or (n, 2) -> (k, 3) or (n, k, 3)."""
        order = _args.count(order, "order", 1, 2)
        q, single = _params2(st)
        with self._h.use() as p:
            x = _lib.patch_eval(p, q, order)
        return x[0] if single else x

    def grid(self, s, t):
        """Points on the tensor grid of 1-D arrays: -> (len(s), len(t), 3)."""
        s, t = _args.vector(s, "s"), _args.vector(t, "t")
        if len(s) * len(t) > _args.MAX_POINTS:
            raise _args.LimitError("grid: %d points, more than %d in one call"
                                   % (len(s) * len(t), _args.MAX_POINTS))
        with self._h.use() as p:
            return _lib.patch_eval_grid(p, s, t)


def _params1(t):
    a = _args.float_array(t, "t")
    single = a.ndim == 0
    a = a.reshape(-1) if single else a
    if a.ndim != 1:
        raise InvalidError("t: expected a number or shape (n,), got %s" % (np.shape(t),))
    if a.shape[0] > _args.MAX_POINTS:
        raise _args.LimitError("t: %d points, more than %d in one call"
                               % (a.shape[0], _args.MAX_POINTS))
    _args.unit(a, "t")
    return np.ascontiguousarray(np.clip(a, 0.0, 1.0)), single


def _params2(st):
    a = _args.float_array(st, "st")
    single = a.ndim == 1
    a = a.reshape(1, -1) if single else a
    if a.ndim != 2 or a.shape[1] != 2:
        raise InvalidError("st: expected shape (n, 2) or (2,), got %s" % (np.shape(st),))
    if a.shape[0] > _args.MAX_POINTS:
        raise _args.LimitError("st: %d points, more than %d in one call"
                               % (a.shape[0], _args.MAX_POINTS))
    _args.unit(a, "st")
    return np.ascontiguousarray(np.clip(a, 0.0, 1.0)), single
