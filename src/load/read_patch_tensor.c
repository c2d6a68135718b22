/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Readers of the tensor-product surfaces: bezier-surface (a net of points)
 * and bspline-surface (degrees, points, knots, weights). */
#include "loader.h"

coons_status coons__ld_read_bezier_surface(coons__ld *L, coons__ld_obj *o, coons_patch **out)
{
    static const char *const KEYS[] = {"type", "points", NULL};
    size_t v[2];
    coons_status rc = coons__ld_keys(L, o, KEYS, v);
    if (rc) return rc;
    const size_t val[4] = {v[1], 0, 0, 0};
    coons__ld_tensor t;
    rc = coons__ld_tensor_read(L, o, 2, 0, val, &t);
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        rc = coons__ld_built(L, o->tok, coons_patch_new_bezier(t.pts, t.n[0], t.n[1], out, &e),
                             o->what, &e);
    }
    coons__ld_tensor_free(&t);
    return rc;
}

coons_status coons__ld_read_bspline_surface(coons__ld *L, coons__ld_obj *o, coons_patch **out)
{
    static const char *const KEYS[] = {"type", "points", "degree", "knots", "weights", NULL};
    size_t v[5];
    coons_status rc = coons__ld_keys(L, o, KEYS, v);
    if (rc) return rc;
    const size_t val[4] = {v[1], v[2], v[3], v[4]};
    coons__ld_tensor t;
    rc = coons__ld_tensor_read(L, o, 2, 1, val, &t);
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        coons_status r = coons_patch_new_bspline(t.deg[0], t.deg[1], t.pts, t.n[0], t.n[1], t.kn[0],
                                                 t.kn[1], t.w, out, &e);
        rc = coons__ld_built(L, o->tok, r, o->what, &e);
    }
    coons__ld_tensor_free(&t);
    return rc;
}
