/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Reader of the bspline curve: a degree, at least degree + 1 points, and
 * optionally knots (default: clamped uniform) and weights (NURBS).
 */
#include "loader.h"

static const char *const KEYS[] = {"type", "points", "degree", "knots", "weights", NULL};

coons_status coons__ld_read_bspline(coons__ld *L, coons__ld_obj *o, coons_curve **out)
{
    size_t v[5], shape[3], n = 0;
    int p = 3;
    coons_status rc = coons__ld_keys(L, o, KEYS, v);
    if (!rc) rc = coons__ld_need(L, o->tok, v[2], "degree", o->need);
    if (!rc) {
        size_t old = coons__ld_push_key(L, "degree");
        rc = coons__ld_degree(L, v[2], &p);
        coons__ld_pop(L, old);
    }
    if (!rc) rc = coons__ld_need(L, o->tok, v[1], "points", o->need);
    if (rc) return rc;
    double *pts = NULL, *kn = NULL, *w = NULL;
    coons__ld_netspec ns = {1, COONS__LD_POINT, NULL, (size_t)p + 1, 0, 0, o->what, "points"};
    rc = coons__ld_net_key(L, v[1], "points", &ns, shape, &pts);
    n = shape[0];
    if (!rc && v[3]) {
        size_t old = coons__ld_push_key(L, "knots");
        rc = coons__ld_knots(L, v[3], p, n, &kn);
        coons__ld_pop(L, old);
    }
    if (!rc && v[4]) {
        size_t fixed[3] = {n, 1, 1};
        coons__ld_netspec ws = {1, COONS__LD_WEIGHT, fixed, 0, 0, 0, o->what, "weights"};
        rc = coons__ld_net_key(L, v[4], "weights", &ws, shape, &w);
    }
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        rc = coons__ld_built(L, o->tok, coons_curve_new_bspline(p, pts, n, kn, w, out, &e), o->what,
                             &e);
    }
    coons__free(pts);
    coons__free(kn);
    coons__free(w);
    return rc;
}
