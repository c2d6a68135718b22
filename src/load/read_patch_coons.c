/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Reader of the coons patch: four boundary curves meeting at the corners,
 * and a blend (seed 001 eq. 1.5-1.8). */
#include "loader.h"

static const char *const KEYS[] = {"type", "boundary", "blend", NULL};

coons_status coons__ld_read_coons(coons__ld *L, coons__ld_obj *o, coons_patch **out)
{
    size_t v[3], btok[4] = {0};
    coons_curve *bd[4] = {0};
    coons_blend bl = COONS_BLEND_LINEAR;
    coons_status rc = coons__ld_keys(L, o, KEYS, v);
    if (!rc) rc = coons__ld_need(L, o->tok, v[1], "boundary", o->need);
    if (!rc) rc = coons__ld_four_curves(L, v[1], "boundary", "a boundary", bd, btok);
    if (!rc) rc = coons__ld_blend(L, v[2], &bl);
    if (!rc && L->build) rc = coons__ld_patch_corners(L, bd, btok);
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        rc = coons__ld_built(L, o->tok, coons_patch_new_coons(bd, bl, L->ctol, out, &e), o->what,
                             &e);
    }
    coons__ld_free_curves(bd, 4);
    return rc;
}
