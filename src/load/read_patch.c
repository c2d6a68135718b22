/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The table of patch readers: one row per patch type of the model format,
 * named by coons_patch_type_name(). A new type is a read_patch_<type>.c
 * and a row here.
 */
#include <stdio.h>

#include "loader.h"

static const coons__ld_patch_row PATCHES[] = {
    {COONS_PATCH_BILINEAR, coons__ld_read_bilinear},
    {COONS_PATCH_RULED, coons__ld_read_ruled},
    {COONS_PATCH_COONS, coons__ld_read_coons},
    {COONS_PATCH_HERMITE_COONS, coons__ld_read_hermite_coons},
    {COONS_PATCH_BEZIER, coons__ld_read_bezier_surface},
    {COONS_PATCH_BSPLINE, coons__ld_read_bspline_surface},
    {COONS_PATCH_NETWORK, coons__ld_read_network},
};
enum { NPATCHES = sizeof PATCHES / sizeof PATCHES[0] };

coons_status coons__ld_patch(coons__ld *L, size_t obj, coons_patch **out)
{
    if (coons__ld_is_ref(L, obj)) {
        void *r = NULL;
        coons_status st = coons__ld_ref(L, obj, COONS__LD_KIND_PATCH, (size_t)-1, out ? &r : NULL);
        if (out) *out = r;
        return st;
    }
    const char *names[NPATCHES + 1];
    for (int i = 0; i < NPATCHES; i++) names[i] = coons_patch_type_name(PATCHES[i].type);
    names[NPATCHES] = NULL;
    int type = 0;
    coons__ld_obj o;
    coons_status rc = coons__ld_typed(L, obj, "a patch", names, " patch", &type, &o);
    if (rc) return rc;
    snprintf(o.hint, sizeof o.hint, "%s",
             "only a coons or network patch (and body0, body1, body2) has a blend");
    return PATCHES[type].read(L, &o, out);
}
