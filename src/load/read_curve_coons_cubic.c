/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Reader of the coons-cubic curve: 4 or more points, or 3 or more when
 * "closed" (and then not repeating the first three at the end).
 */
#include <stdio.h>
#include <string.h>

#include "loader.h"

static const char *const KEYS[] = {"type", "points", "closed", NULL};

static coons_status closed_flag(coons__ld *L, size_t tok, int *closed)
{
    *closed = 0;
    if (!tok) return COONS_OK;
    size_t old = coons__ld_push_key(L, "closed");
    coons_status rc = COONS_OK;
    coons__json_type t = coons__json_type_of(L->j, tok);
    if (t == COONS__JSON_TRUE)
        *closed = 1;
    else if (t != COONS__JSON_FALSE)
        rc = coons__ld_fail(L, tok, COONS_E_INVALID, "expected true or false, found %s",
                            coons__ld_kind(L, tok));
    coons__ld_pop(L, old);
    return rc;
}

/* The points, and for a closed curve no repeat of the first three. */
static coons_status points(coons__ld *L, coons__ld_obj *o, size_t tok, int closed, double **pts,
                           size_t *n)
{
    coons__ld_netspec ns = {1, COONS__LD_POINT, NULL, closed ? 3 : 4, 0, 0, o->what, "points"};
    size_t shape[3], old = coons__ld_push_key(L, "points");
    coons_status rc = coons__ld_net(L, tok, &ns, shape, pts);
    *n = shape[0];
    if (!rc && closed && *n >= 6 && memcmp(*pts, *pts + 3 * (*n - 3), 9 * sizeof(double)) == 0) {
        size_t o2 = coons__ld_push_index(L, *n - 3);
        rc = coons__ld_fail(L, coons__json_nth(L->j, tok, *n - 3), COONS_E_INVALID,
                            "a closed coons-cubic curve must not repeat its first three points "
                            "at the end: give the %zu distinct points only (or set \"closed\": "
                            "false)",
                            *n - 3);
        coons__ld_pop(L, o2);
    }
    coons__ld_pop(L, old);
    return rc;
}

coons_status coons__ld_read_coons_cubic(coons__ld *L, coons__ld_obj *o, coons_curve **out)
{
    size_t v[3], n = 0;
    int closed = 0;
    coons_status rc = coons__ld_keys(L, o, KEYS, v);
    if (!rc) rc = closed_flag(L, v[2], &closed);
    if (!rc) rc = coons__ld_need(L, o->tok, v[1], "points", o->need);
    if (rc) return rc;
    snprintf(o->what, sizeof o->what, "%s coons-cubic curve", closed ? "a closed" : "an open");
    double *pts = NULL;
    rc = points(L, o, v[1], closed, &pts, &n);
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        rc = coons__ld_built(L, o->tok, coons_curve_new_coons_cubic(pts, n, closed, out, &e),
                             o->what, &e);
    }
    coons__free(pts);
    return rc;
}
