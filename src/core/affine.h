/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Affine maps y = M x + t of the model format's "Definitions and
 * references" (coons-model(5)): m[12] is the row-major 3 x 4 matrix
 * [[a,b,c,tx],[d,e,f,ty],[g,h,i,tz]]. Points map by M x + t, derivatives by
 * M alone. Internal.
 */
#ifndef COONS_AFFINE_H
#define COONS_AFFINE_H

#include "coons_internal.h"

/* out = M a (a vector); out may be a. */
static inline void coons__affine_vec(const double *m, const double a[3], double out[3])
{
    double x = a[0], y = a[1], z = a[2];
    for (int r = 0; r < 3; r++) out[r] = m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z;
}

/* out = M a + t (a point); out may be a. */
static inline void coons__affine_point(const double *m, const double a[3], double out[3])
{
    coons__affine_vec(m, a, out);
    for (int r = 0; r < 3; r++) out[r] += m[4 * r + 3];
}

static inline double coons__affine_det(const double *m)
{
    return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
           m[2] * (m[4] * m[9] - m[5] * m[8]);
}

/* The box of the 8 corners of [lo, hi] mapped by m (nothing if empty). */
void coons__affine_bbox(const double *m, const double lo[3], const double hi[3],
                        double olo[3], double ohi[3]);

/* m is finite and regular: |det M| > 1e-12 x the product of M's row norms
 * (coons-model(5), "Resolved details of the additions"); else
 * ::COONS_E_INVALID naming the determinant. what: "curve", ... */
coons_status coons__affine_check(const double *m, const char *what, coons_error *err);

/* out = a o b (apply b first). */
void coons__affine_compose(const double a[12], const double b[12], double out[12]);

#endif
