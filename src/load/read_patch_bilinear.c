/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Reader of the bilinear patch: its four corners X00, X10, X01, X11. */
#include "loader.h"

static const char *const KEYS[] = {"type", "corners", NULL};

coons_status coons__ld_read_bilinear(coons__ld *L, coons__ld_obj *o, coons_patch **out)
{
    size_t v[2], shape[3];
    coons_status rc = coons__ld_keys(L, o, KEYS, v);
    if (!rc) rc = coons__ld_need(L, o->tok, v[1], "corners", o->need);
    if (rc) return rc;
    double *pts = NULL;
    coons__ld_netspec ns = {1, COONS__LD_POINT, NULL, 4, 1, 0, o->what, "corners"};
    rc = coons__ld_net_key(L, v[1], "corners", &ns, shape, &pts);
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        rc = coons__ld_built(L, o->tok,
                             coons_patch_new_bilinear(pts, out, &e), o->what,
                             &e);
    }
    coons__free(pts);
    return rc;
}
