# SPDX-License-Identifier: GPL-3.0-or-later
"""Model.info(): the main fields of coons2stl --info (tools/coons2stl/info.c,
which assembles them in the command), computed with the same library calls
and the same constants: the sampled box over 65 x 65 points per face, the
volume to the relative accuracy tied to the tolerance, the smallest det J
on a 16^3 grid."""
import math

import numpy as np

from . import _lib

INFO_GRID = 65
INFO_JAC = 16


def _box(lo, hi):
    return {"min": [float(x) for x in lo], "max": [float(x) for x in hi]}


def _sampled_box(b):
    g = np.array([i / (INFO_GRID - 1) for i in range(INFO_GRID)])
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    for face in range(6):
        e = np.array([float(face % 2)])
        axes = [g, g, g]
        axes[face // 2] = e
        pts = _lib.body_eval_grid(b, *axes).reshape(-1, 3)
        lo, hi = np.minimum(lo, pts.min(0)), np.maximum(hi, pts.max(0))
    return lo, hi


def model_info(m):
    clo, chi = _lib.model_control_bbox(m)
    diag = math.sqrt(sum((h - l) * (h - l) for l, h in zip(clo, chi)))  # as info.c
    tol = _lib.model_tolerance(m)
    rel = tol / diag if diag > 0 else 1e-6
    rel = min(max(rel, 1e-12), 1e-6)
    bodies, total = [], 0.0
    for i in range(_lib.model_body_count(m)):
        b = _lib.model_body(m, i)
        lo, hi = _sampled_box(b)
        vol, verr = _lib.body_volume_bounded(b, rel)
        mindet, where = _lib.body_min_jacobian(b, INFO_JAC)
        blo, bhi = _lib.body_control_bbox(b)
        bodies.append({"index": i, "name": _lib.model_body_name(m, i), "type": _lib.body_type(b),
                       "bbox": _box(lo, hi), "control_bbox": _box(blo, bhi), "volume": vol,
                       "volume_error": verr, "min_det_jacobian": mindet,
                       "min_det_jacobian_at": where})
        total += abs(vol)
    names = [_lib.model_body_name(m, i) for i in range(_lib.model_body_count(m))]
    interfaces = []
    for it in _lib.model_interfaces(m):
        it = dict(it)
        interfaces.append(dict({"bodies": [names[j] for j in it["body_indices"]]}, **it))
    return {"units": _lib.model_units(m), "tolerance": tol,
            "operation": _lib.model_operation(m), "control_bbox": _box(clo, chi),
            "bodies": bodies, "body_count": len(bodies), "total_volume": total,
            "interfaces": interfaces}
