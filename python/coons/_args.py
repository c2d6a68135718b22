# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks of the arguments the Python layer passes to libcoons: shapes,
dtypes, finiteness and ranges, so that no misuse reaches C."""
import numbers

import numpy as np

from .errors import DomainError, InvalidError, LimitError

#: Largest number of points one eval/grid call produces (3 doubles each: 3 GiB).
MAX_POINTS = 1 << 27


def float_array(x, what, shape_tail=None, ndim=None):
    try:
        a = np.array(x, dtype=np.float64, order="C", copy=True)
    except (TypeError, ValueError) as e:
        raise InvalidError("%s: not an array of numbers (%s)" % (what, e)) from None
    if ndim is not None and a.ndim != ndim:
        raise InvalidError("%s: expected %d dimensions, got shape %s" % (what, ndim, a.shape))
    if shape_tail is not None and a.shape[a.ndim - len(shape_tail):] != tuple(shape_tail):
        raise InvalidError("%s: expected shape (..., %s), got %s"
                           % (what, ", ".join(map(str, shape_tail)), a.shape))
    if not np.all(np.isfinite(a)):
        raise InvalidError("%s: contains NaN or infinity" % what)
    return a


def params(uvw):
    """(n, 3) or (3,) -> (C-contiguous (n, 3) clamped to [0, 1], was 1-D).
    Parameters within 1e-12 of [0, 1] are clamped, as coons2stl --eval does;
    others raise DomainError."""
    a = float_array(uvw, "uvw")
    single = a.ndim == 1
    if single:
        a = a.reshape(1, -1)
    if a.ndim != 2 or a.shape[1] != 3:
        raise InvalidError("uvw: expected shape (n, 3) or (3,), got %s" % (np.shape(uvw),))
    if a.shape[0] > MAX_POINTS:
        raise LimitError("uvw: %d points, more than %d in one call" % (a.shape[0], MAX_POINTS))
    unit(a, "uvw")
    return np.ascontiguousarray(np.clip(a, 0.0, 1.0)), single


def unit(a, what):
    bad = (a < -1e-12) | (a > 1 + 1e-12)
    if np.any(bad):
        raise DomainError("%s: %.17g is outside [0, 1]" % (what, a[bad].flat[0]))


def vector(x, what):
    a = float_array(x, what, ndim=1)
    unit(a, what)
    return np.ascontiguousarray(np.clip(a, 0.0, 1.0))


def time(t):
    if t is None:
        return None
    if not isinstance(t, numbers.Real) or not np.isfinite(t):
        raise InvalidError("time: expected a finite number, got %r" % (t,))
    if not 0.0 <= float(t) <= 1.0:
        raise DomainError("time: %r is outside [0, 1]" % (t,))
    return float(t)


def count(x, what, lo=0, hi=(1 << 32) - 1):
    if isinstance(x, bool) or not isinstance(x, numbers.Integral):
        raise InvalidError("%s: expected an integer, got %r" % (what, x))
    if not lo <= int(x) <= hi:
        raise (LimitError if int(x) > hi else InvalidError)(
            "%s: %d is outside [%d, %d]" % (what, int(x), lo, hi))
    return int(x)


def positive(x, what):
    if x is None:
        return 0.0
    if isinstance(x, bool) or not isinstance(x, numbers.Real) or not np.isfinite(x) or x <= 0:
        raise InvalidError("%s: expected a finite number > 0, got %r" % (what, x))
    return float(x)


def resolution3(r):
    if r is None:
        return (0, 0, 0)
    if isinstance(r, numbers.Integral) and not isinstance(r, bool):
        r = (r, r, r)
    try:
        r = tuple(r)
    except TypeError:
        raise InvalidError("resolution: expected an integer or three, got %r" % (r,)) from None
    if len(r) != 3:
        raise InvalidError("resolution: expected an integer or three, got %r" % (r,))
    return tuple(count(x, "resolution", 1, 1 << 20) for x in r)
