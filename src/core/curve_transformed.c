/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The affine image y(t) = M c(t) + t0 of a curve (coons-model(5),
 * "Definitions and references": "transform"). Exact for every type: each
 * basis here is a partition of unity (rational ones too), so the image is
 * the same curve over the mapped control points; it is evaluated by
 * mapping the inner curve's point by M x + t0 and its derivatives by M.
 * Also the wrapper lifecycle shared with curve_reversed.c.
 */
#include <string.h>

#include "affine.h"
#include "curve_impl.h"

static void eval(const coons_curve *c, double t, int order, double out[][3])
{
    c->inner->kind->eval(c->inner, t, order, out);
    coons__affine_point(c->xf, out[0], out[0]);
    for (int k = 1; k <= order; k++) coons__affine_vec(c->xf, out[k], out[k]);
}

/* Bezier control points map like the curve (affine invariance). */
static coons_status bezier(const coons_curve *c, double *points, size_t capacity,
                           size_t *segments, int *degree, coons_error *err)
{
    coons_status rc = coons_curve_bezier_segments(c->inner, points, capacity, segments, degree,
                                                  err);
    if (rc || !points) return rc;
    size_t n = *segments * (size_t)(*degree + 1);
    for (size_t i = 0; i < n; i++) coons__affine_point(c->xf, points + 3 * i, points + 3 * i);
    return COONS_OK;
}

static void breaks(const coons_curve *c, coons__breaks *B) { coons__curve_breaks(c->inner, B); }

coons_status coons__curve_wrap_copy(const coons_curve *c, coons_curve *d, coons_error *err)
{
    d->inner = NULL;
    d->pts = NULL;
    coons_status rc = coons_curve_copy(c->inner, &d->inner, err);
    if (rc) return rc;
    if (c->n && !(d->pts = coons__memdup(c->pts, c->n, 3 * sizeof(double))))
        return coons__error_nomem(err);
    return COONS_OK;
}

void coons__curve_wrap_free(coons_curve *c)
{
    coons_curve_free(c->inner);
    coons__free(c->pts);
}

coons_status coons__curve_wrap(const coons__curve_kind *kind, const coons_curve *c,
                               const double *xf, coons_curve **out, coons_error *err)
{
    coons_curve *w = NULL;
    coons_status rc = coons__curve_alloc(kind, &w, err);
    if (rc) return rc;
    if ((rc = coons_curve_copy(c, &w->inner, err))) goto fail;
    w->degree = c->degree;
    w->n = c->n;
    if (c->n && !(w->pts = coons__memdup(c->pts, c->n, 3 * sizeof(double)))) {
        rc = coons__error_nomem(err);
        goto fail;
    }
    if (xf) {
        memcpy(w->xf, xf, sizeof w->xf);
        for (size_t i = 0; i < w->n; i++) coons__affine_point(xf, w->pts + 3 * i, w->pts + 3 * i);
    }
    *out = w;
    return COONS_OK;
fail:
    coons_curve_free(w);
    return rc;
}

static void space(const coons_curve *c, coons__space *S) { *S = coons__curve_space(c->inner); }

const coons__curve_kind coons__curve_transformed_kind = {
    COONS_CURVE_LINE, /* unused: coons_curve_kind() reports the inner type */
    eval, bezier, breaks, coons__curve_wrap_copy, coons__curve_wrap_free, space,
};

coons_status coons_curve_new_transformed(const coons_curve *c, const double *m,
                                         coons_curve **out, coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "curve transform: out is NULL");
    *out = NULL;
    if (!c) return coons__error_set(err, COONS_E_INVALID, "curve transform: curve is NULL");
    coons_status rc = coons__affine_check(m, "curve", err);
    if (rc) return rc;
    return coons__curve_wrap(&coons__curve_transformed_kind, c, m, out, err);
}
