/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The curve record, shared by curve.c and the curve types' files
 * (bspline_curve.c, coons_cubic.c). Internal. */
#ifndef COONS_CURVE_IMPL_H
#define COONS_CURVE_IMPL_H

#include "kinds.h"

struct coons_curve {
    const coons__curve_kind *kind; /* the type's row (kinds.h) */
    int degree;    /* B-spline degree (3 for the Coons cubic) */
    size_t n;      /* number of control points in pts */
    double *pts;   /* 3n; closed Coons cubic: the m given points plus P0, P1, P2 */
    double *knots; /* n + degree + 1 values; NULL for the Coons cubic */
    double *w;     /* n weights, or NULL */
    int closed;    /* Coons cubic only */
    /* Wrappers (curve_transformed.c, curve_reversed.c): the wrapped curve
     * and the map; pts then holds the inner control points as mapped. */
    coons_curve *inner;
    double xf[12];
};

/* A wrapper record of kind over a copy of c, with pts the inner control
 * points mapped by xf (NULL: unchanged) (curve_transformed.c). */
coons_status coons__curve_wrap(const coons__curve_kind *kind, const coons_curve *c,
                               const double *xf, coons_curve **out, coons_error *err);
/* copy and free of the wrapper rows. */
coons_status coons__curve_wrap_copy(const coons_curve *c, coons_curve *d, coons_error *err);
void coons__curve_wrap_free(coons_curve *c);

/* Allocates a zeroed record of the given kind. */
coons_status coons__curve_alloc(const coons__curve_kind *kind, coons_curve **out,
                                coons_error *err);

#endif
