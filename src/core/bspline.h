/* SPDX-License-Identifier: GPL-3.0-or-later */
/* B-spline knot vectors and basis functions (Cox-de Boor), shared by curves,
 * surfaces and volumes. Internal. */
#ifndef COONS_BSPLINE_H
#define COONS_BSPLINE_H

#include "coons_internal.h"

/*
 * Validates or builds a knot vector of degree p for ncp control points
 * (ncp + p + 1 values). given == NULL builds clamped uniform knots
 * (p+1 zeros, 1..ncp-p-1, p+1 times ncp-p). Given knots must be finite,
 * non-decreasing, no value more than p+1 times, and [k_p, k_ncp] non-empty.
 * `what` names the object in messages. *out is allocated with coons__malloc.
 */
coons_status coons__knots_make(int p, size_t ncp, const double *given, const char *what,
                               double **out, coons_error *err);

/*
 * Rational weights (model format "Resolved details": the point is
 * sum w N P / sum w N), each already checked finite and > 0 by the caller.
 * Refuses (COONS_E_LIMIT) a largest weight more than
 * COONS_SPLINE_MAX_WEIGHT_RATIO times the smallest, and returns in *out
 * (coons__malloc) a copy scaled by one power of two so that the largest lies
 * in [0.5, 1). The map is unchanged and so is every rounded evaluation that
 * neither overflowed nor underflowed before (a power-of-two scale is exact);
 * with the ratio bounded, w N P cannot overflow for finite control points
 * that N P does not overflow, and the denominator sum w N stays at least
 * 0.5 / COONS_SPLINE_MAX_WEIGHT_RATIO. `what` names the object in messages.
 */
coons_status coons__weights_make(const double *w, size_t n, const char *what, double **out,
                                 coons_error *err);

/* Index i of the span k[i] <= x < k[i+1] with p <= i <= ncp-1; x outside the
 * domain is clamped; the right end belongs to the last non-empty span. */
size_t coons__bspline_span(const double *k, size_t ncp, int p, double x);

/*
 * Non-zero basis functions N_{span-p+j,p}(x), j = 0..p, and their
 * derivatives up to order nd (<= 2) with respect to x (Piegl & Tiller,
 * The NURBS Book, A2.3): ders[d*(p+1) + j].
 */
void coons__bspline_basis(const double *k, size_t span, int p, double x, int nd, double *ders);

/* Bernstein polynomials B_{j,n}(t), j = 0..n, and their derivatives up to
 * order nd (<= 2): ders[d*(n+1) + j]. */
void coons__bernstein(int n, double t, int nd, double *ders);

/* The same basis (B-spline over a knot vector) sampled at a parameter in
 * [0,1] that is mapped to [k_p, k_ncp]; derivatives are scaled to d/dt.
 * Returns the first control index (span - p). */
size_t coons__bspline_basis01(const double *k, size_t ncp, int p, double t, int nd,
                              double *ders);

#endif
