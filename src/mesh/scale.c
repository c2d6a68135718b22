/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * coons_mesh_scale(): every vertex multiplied by one factor, a change of
 * units (coons2stl --scale-to: inches to millimetres is 25.4). The
 * parameters (u, v, w) of the vertices and the triangles stay; a factor
 * that would make a coordinate overflow is refused before anything
 * changes.
 */
#include <math.h>

#include "coons_internal.h"
#include "mesh_impl.h"

coons_status coons_mesh_scale(coons_mesh *m, double factor, coons_error *err)
{
    if (!m) return coons__error_set(err, COONS_E_INVALID, "scale: no mesh given");
    if (!isfinite(factor) || !(factor > 0))
        return coons__error_set(err, COONS_E_INVALID,
                                "scale: the factor %.17g is not a finite number > 0", factor);
    for (size_t i = 0; i < 3 * m->nv; i++)
        if (!isfinite(m->xyz[i] * factor))
            return coons__error_set(err, COONS_E_LIMIT,
                                    "scale: vertex %zu times %.17g is beyond the range of a "
                                    "double",
                                    i / 3, factor);
    for (size_t i = 0; i < 3 * m->nv; i++) m->xyz[i] *= factor;
    return COONS_OK;
}
