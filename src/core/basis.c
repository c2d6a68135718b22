/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The fixed cubic bases of the seeds:
 * - Coons polynomials C0..C3 (seed 002, "Coons cubic curve"), the uniform
 *   cubic B-spline basis on one segment;
 * - cubic Hermite H0..H3 (seed 001, eq. 1.13-1.15);
 * - blending pairs: linear 1-t, t (eq. 1.8) and cubic f = 1-3t^2+2t^3, 1-f
 *   (section 1.2.1: any pair summing to 1 with f(0)=1, f(1)=0).
 */
#include "basis.h"

void coons__coons_basis(double t, int nd, double *b)
{
    double t2 = t * t, t3 = t2 * t, s = 1.0 - t;
    b[0] = s * s * s / 6.0;
    b[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
    b[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
    b[3] = t3 / 6.0;
    if (nd >= 1) {
        b[4] = -0.5 * s * s;
        b[5] = (9.0 * t2 - 12.0 * t) / 6.0;
        b[6] = (-9.0 * t2 + 6.0 * t + 3.0) / 6.0;
        b[7] = 0.5 * t2;
    }
    if (nd >= 2) {
        b[8] = s;
        b[9] = 3.0 * t - 2.0;
        b[10] = -3.0 * t + 1.0;
        b[11] = t;
    }
}

void coons__hermite_basis(double t, int nd, double *b)
{
    double t2 = t * t, t3 = t2 * t;
    b[0] = 1.0 - 3.0 * t2 + 2.0 * t3;
    b[1] = t - 2.0 * t2 + t3;
    b[2] = -t2 + t3;
    b[3] = 3.0 * t2 - 2.0 * t3;
    if (nd >= 1) {
        b[4] = -6.0 * t + 6.0 * t2;
        b[5] = 1.0 - 4.0 * t + 3.0 * t2;
        b[6] = -2.0 * t + 3.0 * t2;
        b[7] = 6.0 * t - 6.0 * t2;
    }
    if (nd >= 2) {
        b[8] = -6.0 + 12.0 * t;
        b[9] = -4.0 + 6.0 * t;
        b[10] = -2.0 + 6.0 * t;
        b[11] = 6.0 - 12.0 * t;
    }
}

void coons__blend(coons_blend kind, double t, int nd, double *b)
{
    if (kind == COONS_BLEND_CUBIC) {
        double f = 1.0 - 3.0 * t * t + 2.0 * t * t * t;
        b[0] = f;
        b[1] = 1.0 - f;
        if (nd >= 1) {
            b[2] = -6.0 * t + 6.0 * t * t;
            b[3] = -b[2];
        }
        if (nd >= 2) {
            b[4] = -6.0 + 12.0 * t;
            b[5] = -b[4];
        }
        return;
    }
    b[0] = 1.0 - t;
    b[1] = t;
    if (nd >= 1) {
        b[2] = -1.0;
        b[3] = 1.0;
    }
    if (nd >= 2) {
        b[4] = 0.0;
        b[5] = 0.0;
    }
}
