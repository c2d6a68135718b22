/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The table of curve readers: one row per curve type of the model format,
 * named by coons_curve_type_name(). A new type is a read_curve_<type>.c
 * and a row here.
 */
#include <stdio.h>

#include "loader.h"

static const coons__ld_curve_row CURVES[] = {
    {COONS_CURVE_LINE, coons__ld_read_line},
    {COONS_CURVE_POLYLINE, coons__ld_read_polyline},
    {COONS_CURVE_BEZIER, coons__ld_read_bezier},
    {COONS_CURVE_HERMITE, coons__ld_read_hermite},
    {COONS_CURVE_COONS_CUBIC, coons__ld_read_coons_cubic},
    {COONS_CURVE_CLAMPED_CUBIC, coons__ld_read_clamped_cubic},
    {COONS_CURVE_BSPLINE, coons__ld_read_bspline},
};
enum { NCURVES = sizeof CURVES / sizeof CURVES[0] };

coons_status coons__ld_curve(coons__ld *L, size_t obj, coons_curve **out)
{
    if (coons__ld_is_ref(L, obj)) {
        void *r = NULL;
        coons_status st = coons__ld_ref(L, obj, COONS__LD_KIND_CURVE, (size_t)-1, out ? &r : NULL);
        if (out) *out = r;
        return st;
    }
    const char *names[NCURVES + 1];
    for (int i = 0; i < NCURVES; i++) names[i] = coons_curve_type_name(CURVES[i].type);
    names[NCURVES] = NULL;
    int type = 0;
    coons__ld_obj o;
    coons_status rc = coons__ld_typed(L, obj, "a curve", names, " curve", &type, &o);
    if (rc) return rc;
    snprintf(o.hint, sizeof o.hint, "%s",
             "a blend belongs to coons patches and to body0, body1 and body2, not to curves");
    return CURVES[type].read(L, &o, out);
}
