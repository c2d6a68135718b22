/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Fixed cubic bases and blending functions, with derivatives. Internal. */
#ifndef COONS_BASIS_H
#define COONS_BASIS_H

#include "coons_internal.h"

/* Coons polynomials C0..C3 of seed 002 (slide "Coons cubic curve"):
 * C0 = (1-t)^3/6, C1 = (3t^3-6t^2+4)/6, C2 = (-3t^3+3t^2+3t+1)/6, C3 = t^3/6.
 * b[d*4 + j] = d^d C_j / dt^d for d = 0..nd (nd <= 2). */
void coons__coons_basis(double t, int nd, double *b);

/* Cubic Hermite basis of seed 001 eq. 1.13: H0 value at 0, H1 derivative
 * at 0, H2 derivative at 1, H3 value at 1. b[d*4 + j], d = 0..nd <= 2. */
void coons__hermite_basis(double t, int nd, double *b);

/* Blending pair (seed 001 section 1.2): linear (1-t, t) or cubic
 * (f, 1-f) with f = 1 - 3t^2 + 2t^3. b[d*2 + 0] is the weight of the
 * t=0 side, b[d*2 + 1] of the t=1 side; d = 0..nd <= 2. */
void coons__blend(coons_blend kind, double t, int nd, double *b);

#endif
