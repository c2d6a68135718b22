/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Reader of the hermite curve: two points and their two tangents. */
#include "loader.h"

static const char *const KEYS[] = {"type", "points", "tangents", NULL};

coons_status coons__ld_read_hermite(coons__ld *L, coons__ld_obj *o, coons_curve **out)
{
    size_t v[3], shape[3];
    coons_status rc = coons__ld_keys(L, o, KEYS, v);
    if (!rc) rc = coons__ld_need(L, o->tok, v[1], "points", o->need);
    if (rc) return rc;
    double *pts = NULL, *tan = NULL;
    coons__ld_netspec ns = {1, COONS__LD_POINT, NULL, 2, 1, 0, o->what, "points"};
    rc = coons__ld_net_key(L, v[1], "points", &ns, shape, &pts);
    if (!rc) rc = coons__ld_need(L, o->tok, v[2], "tangents", o->need);
    if (!rc) {
        coons__ld_netspec ts = {1, COONS__LD_VECTOR, NULL, 2, 1, 0, o->what, "tangents"};
        rc = coons__ld_net_key(L, v[2], "tangents", &ts, shape, &tan);
    }
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        rc = coons__ld_built(L, o->tok, coons_curve_new_hermite(pts, tan, pts + 3, tan + 3, out, &e),
                             o->what, &e);
    }
    coons__free(pts);
    coons__free(tan);
    return rc;
}
