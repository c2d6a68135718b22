/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Readers of the tensor-product volumes: bezier-volume (a net of points)
 * and bspline-volume (degrees, points, knots, weights). */
#include "loader.h"

coons_status coons__ld_read_bezier_volume(coons__ld *L, coons__ld_obj *o, coons_body **out)
{
    static const char *const KEYS[] = {"type", "name", "points", NULL};
    size_t v[3];
    coons_status rc = coons__ld_body_keys(L, o, KEYS, v);
    if (rc) return rc;
    const size_t val[4] = {v[2], 0, 0, 0};
    coons__ld_tensor t;
    rc = coons__ld_tensor_read(L, o, 3, 0, val, &t);
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        rc = coons__ld_built(L, o->tok, coons_body_new_bezier(t.pts, t.n, out, &e), o->what, &e);
    }
    coons__ld_tensor_free(&t);
    return rc;
}

coons_status coons__ld_read_bspline_volume(coons__ld *L, coons__ld_obj *o, coons_body **out)
{
    static const char *const KEYS[] = {"type",  "name",    "points", "degree",
                                       "knots", "weights", NULL};
    size_t v[6];
    coons_status rc = coons__ld_body_keys(L, o, KEYS, v);
    if (rc) return rc;
    const size_t val[4] = {v[2], v[3], v[4], v[5]};
    coons__ld_tensor t;
    rc = coons__ld_tensor_read(L, o, 3, 1, val, &t);
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        rc = coons__ld_built(L, o->tok, coons_body_new_bspline(t.deg, t.pts, t.n, t.kn[0], t.kn[1],
                                                            t.kn[2], t.w, out, &e),
                             o->what, &e);
    }
    coons__ld_tensor_free(&t);
    return rc;
}
