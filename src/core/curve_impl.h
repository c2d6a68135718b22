/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The curve record, shared by curve.c and coons_cubic.c only. */
#ifndef COONS_CURVE_IMPL_H
#define COONS_CURVE_IMPL_H

#include "coons_internal.h"

struct coons_curve {
    coons_curve_type type;
    int degree;    /* B-spline degree (3 for the Coons cubic) */
    size_t n;      /* number of control points in pts */
    double *pts;   /* 3n; closed Coons cubic: the m given points plus P0, P1, P2 */
    double *knots; /* n + degree + 1 values; NULL for the Coons cubic */
    double *w;     /* n weights, or NULL */
    int closed;    /* Coons cubic only */
};

void coons__coons_cubic_eval(const coons_curve *c, double t, int order, double out[][3]);
coons_status coons__coons_cubic_bezier(const coons_curve *c, double *points, size_t capacity,
                                       size_t *segments, int *degree, coons_error *err);

#endif
