/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Reader of body0: the eight corners of a trilinear block, and a blend. */
#include "loader.h"

static const char *const KEYS[] = {"type", "name", "blend", "corners", NULL};

coons_status coons__ld_read_body0(coons__ld *L, coons__ld_obj *o, coons_body **out)
{
    size_t v[4], shape[3];
    coons_blend bl = COONS_BLEND_LINEAR;
    coons_status rc = coons__ld_body_keys(L, o, KEYS, v);
    if (!rc) rc = coons__ld_blend(L, v[2], &bl);
    if (!rc) rc = coons__ld_need(L, o->tok, v[3], "corners", o->need);
    if (rc) return rc;
    double *pts = NULL;
    coons__ld_netspec ns = {1, COONS__LD_POINT, NULL, 8, 1, 0, o->what, "corners"};
    rc = coons__ld_net_key(L, v[3], "corners", &ns, shape, &pts);
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        rc = coons__ld_built(L, o->tok, coons_body_new_body0(pts, bl, out, &e),
                             o->what, &e);
    }
    coons__free(pts);
    return rc;
}
