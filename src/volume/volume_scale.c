/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * coons_volume_mesh_scale(): every node multiplied by one factor, a change
 * of units (coons2stl --scale-to). Cells, parts, sets and fields stay as
 * they are (a field keeps the units it was computed in); a factor that
 * would make a coordinate overflow is refused before anything changes.
 */
#include <math.h>

#include "volume_impl.h"

coons_status coons_volume_mesh_scale(coons_volume_mesh *vm, double factor, coons_error *err)
{
    if (!vm) return coons__error_set(err, COONS_E_INVALID, "scale: no volume mesh given");
    if (!isfinite(factor) || !(factor > 0))
        return coons__error_set(err, COONS_E_INVALID,
                                "scale: the factor %.17g is not a finite number > 0", factor);
    for (size_t i = 0; i < 3 * vm->nn; i++)
        if (!isfinite(vm->xyz[i] * factor))
            return coons__error_set(err, COONS_E_LIMIT,
                                    "scale: node %zu times %.17g is beyond the range of a double",
                                    i / 3, factor);
    for (size_t i = 0; i < 3 * vm->nn; i++) vm->xyz[i] *= factor;
    return COONS_OK;
}
