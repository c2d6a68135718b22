/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The curve record over t in [0,1] (model format, "Curves"): lifecycle,
 * control box, and evaluation through the type's row (kinds.h). The types
 * live in bspline_curve.c (line, polyline, Bezier, Hermite, clamped cubic,
 * B-spline/NURBS) and coons_cubic.c (seed 002's Coons cubic B-spline).
 */
#include "curve_impl.h"

coons_status coons__curve_alloc(const coons__curve_kind *kind, coons_curve **out,
                                coons_error *err)
{
    coons_curve *c = coons__calloc(1, sizeof *c);
    if (!c) return coons__error_nomem(err);
    c->kind = kind;
    *out = c;
    return COONS_OK;
}

void coons_curve_free(coons_curve *c)
{
    if (!c) return;
    c->kind->free(c);
    coons__free(c);
}

/* A wrapper reports the type of the curve it wraps (curve.h). */
coons_curve_type coons_curve_kind(const coons_curve *c)
{
    while (c->inner) c = c->inner;
    return c->kind->type;
}

coons_status coons_curve_copy(const coons_curve *c, coons_curve **out, coons_error *err)
{
    *out = NULL;
    coons_curve *d = coons__calloc(1, sizeof *d);
    if (!d) return coons__error_nomem(err);
    *d = *c;
    coons_status rc = c->kind->copy(c, d, err);
    if (rc) {
        coons_curve_free(d);
        return rc;
    }
    *out = d;
    return COONS_OK;
}

void coons_curve_eval_derivs(const coons_curve *c, double t, int order, double out[][3])
{
    if (order < 0) order = 0;
    if (order > 2) order = 2;
    c->kind->eval(c, clamp01(t), order, out);
}

void coons_curve_eval(const coons_curve *c, double t, double out[3])
{
    double r[1][3];
    coons_curve_eval_derivs(c, t, 0, r);
    v3_copy(out, r[0]);
}

void coons_curve_control_bbox(const coons_curve *c, double lo[3], double hi[3])
{
    bbox_empty(lo, hi);
    for (size_t i = 0; i < c->n; i++) bbox_add(lo, hi, c->pts + 3 * i);
}

coons_status coons_curve_bezier_segments(const coons_curve *c, double *points, size_t capacity,
                                         size_t *segments, int *degree, coons_error *err)
{
    return c->kind->bezier(c, points, capacity, segments, degree, err);
}

void coons__curve_breaks(const coons_curve *c, coons__breaks *B)
{
    if (c) c->kind->breaks(c, B);
}

coons__space coons__curve_space(const coons_curve *c)
{
    coons__space S = {1, COONS__SPACE_NONE, 0};
    if (!c) return coons__space_poly(1);
    if (c->kind->space) c->kind->space(c, &S);
    return S;
}
