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

/* The same, inline (body2.c's batch of points; bspline.c's definition). */
static inline size_t coons__bspline_span_inl(const double *k, size_t ncp, int p, double x)
{
    size_t lo = (size_t)p, hi = ncp; /* domain [k[lo], k[hi]] */
    if (x >= k[hi]) {
        /* right end: the last non-empty span */
        size_t i = hi - 1;
        while (i > lo && k[i] == k[hi]) i--;
        return i;
    }
    if (x <= k[lo]) {
        size_t i = lo;
        while (i + 1 < hi && k[i + 1] == k[lo]) i++;
        return i;
    }
    /* binary search for k[i] <= x < k[i+1] */
    size_t a = lo, b = hi;
    while (b - a > 1) {
        size_t m = (a + b) / 2;
        if (x < k[m])
            b = m;
        else
            a = m;
    }
    return a;
}

/* The values N_{span-p+j,p}(x), j = 0..p, alone (The NURBS Book, A2.2):
 * the same operations in the same order as the values of
 * coons__bspline_basis() (A2.3 keeps the triangle; A2.2 overwrites it in
 * place), so bitwise the same; inline so that a constant p unrolls. */
static inline void coons__bspline_vals(const double *k, size_t span, int p, double x, double *N)
{
    double left[COONS_SPLINE_MAX_DEGREE + 1], right[COONS_SPLINE_MAX_DEGREE + 1];
    N[0] = 1.0;
    for (int j = 1; j <= p; j++) {
        left[j] = x - k[span + 1 - (size_t)j];
        right[j] = k[span + (size_t)j] - x;
        double saved = 0.0;
        for (int r = 0; r < j; r++) {
            double temp = N[r] / (right[r + 1] + left[j - r]);
            N[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        N[j] = saved;
    }
}

/* The values and first derivatives, ders[j] and ders[p+1+j] (p >= 1):
 * A2.2 for the levels below p, then the last level with A2.3's
 * derivative terms for nd = 1 written out (a_0 = 1/ndu[p][r-1] times
 * ndu[r-1][p-1], plus -1/ndu[p][r] times ndu[r][p-1], then times p), so
 * bitwise coons__bspline_basis(..., 1, ders); inline for a constant p. */
static inline void coons__bspline_vals1(const double *k, size_t span, int p, double x,
                                        double *ders)
{
    double left[COONS_SPLINE_MAX_DEGREE + 1], right[COONS_SPLINE_MAX_DEGREE + 1];
    double N[COONS_SPLINE_MAX_DEGREE + 1], den[COONS_SPLINE_MAX_DEGREE + 1];
    N[0] = 1.0;
    for (int j = 1; j <= p; j++) {
        left[j] = x - k[span + 1 - (size_t)j];
        right[j] = k[span + (size_t)j] - x;
        if (j == p) break;
        double saved = 0.0;
        for (int r = 0; r < j; r++) {
            double temp = N[r] / (right[r + 1] + left[j - r]);
            N[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        N[j] = saved;
    }
    /* level p: N holds level p-1 (A2.3's ndu[r][p-1]) */
    double saved = 0.0;
    for (int r = 0; r < p; r++) {
        den[r] = right[r + 1] + left[p - r];
        double temp = N[r] / den[r];
        ders[r] = saved + right[r + 1] * temp;
        saved = left[p - r] * temp;
    }
    ders[p] = saved;
    const double f = (double)p;
    for (int r = 0; r <= p; r++) {
        double dv = 0.0;
        if (r >= 1) dv = (1.0 / den[r - 1]) * N[r - 1];
        if (r <= p - 1) dv += (-1.0 / den[r]) * N[r];
        ders[p + 1 + r] = dv * f;
    }
}

/* Bernstein values B_{j,n}(t) alone, in place with coons__bernstein()'s
 * operations (b[m][j] = s b[m-1][j] + t b[m-1][j-1]), so bitwise the same. */
static inline void coons__bernstein_vals(int n, double t, double *N)
{
    double s = 1.0 - t;
    N[0] = 1.0;
    for (int m = 1; m <= n; m++) {
        N[m] = t * N[m - 1];
        for (int j = m - 1; j >= 1; j--) N[j] = s * N[j] + t * N[j - 1];
        N[0] = s * N[0];
    }
}

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
