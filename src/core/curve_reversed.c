/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The reversed curve y(t) = c(1 - t) (coons-model(5), "Definitions and
 * references": "reverse"): y' = -c'(1 - t), y'' = c''(1 - t); breakpoints
 * x become 1 - x, Bezier segments come in the opposite order, each with
 * its points reversed.
 */
#include "curve_impl.h"

static void eval(const coons_curve *c, double t, int order, double out[][3])
{
    c->inner->kind->eval(c->inner, 1.0 - t, order, out);
    if (order >= 1) v3_scale(out[1], out[1], -1.0);
}

static coons_status bezier(const coons_curve *c, double *points, size_t capacity,
                           size_t *segments, int *degree, coons_error *err)
{
    coons_status rc = coons_curve_bezier_segments(c->inner, points, capacity, segments, degree,
                                                  err);
    if (rc || !points) return rc;
    /* Reversing all points reverses the segments and each segment. */
    size_t n = *segments * (size_t)(*degree + 1);
    for (size_t i = 0, j = n ? n - 1 : 0; i < j; i++, j--)
        for (int k = 0; k < 3; k++) {
            double x = points[3 * i + k];
            points[3 * i + k] = points[3 * j + k];
            points[3 * j + k] = x;
        }
    return COONS_OK;
}

static void breaks(const coons_curve *c, coons__breaks *B)
{
    if (B->probe) {
        coons__breaks in = {.probe = 1, .at = 1.0 - B->at, .tol = B->tol};
        coons__curve_breaks(c->inner, &in);
        B->hit |= in.hit;
        return;
    }
    size_t n0 = B->n;
    coons__curve_breaks(c->inner, B);
    for (size_t i = n0; i < B->n; i++) B->v[i] = 1.0 - B->v[i];
}

static void space(const coons_curve *c, coons__space *S) { *S = coons__curve_space(c->inner); }

const coons__curve_kind coons__curve_reversed_kind = {
    COONS_CURVE_LINE, /* unused: coons_curve_kind() reports the inner type */
    eval, bezier, breaks, coons__curve_wrap_copy, coons__curve_wrap_free, space,
};

coons_status coons_curve_new_reversed(const coons_curve *c, coons_curve **out, coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "curve reverse: out is NULL");
    *out = NULL;
    if (!c) return coons__error_set(err, COONS_E_INVALID, "curve reverse: curve is NULL");
    return coons__curve_wrap(&coons__curve_reversed_kind, c, NULL, out, err);
}
