/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * B-spline basis functions by the Cox-de Boor recurrence, with derivatives
 * (Piegl & Tiller, The NURBS Book, 2nd ed., algorithms A2.1 and A2.3), and
 * the knot-vector rules of the model format ("Resolved details": knots
 * non-decreasing, multiplicity <= p+1, half-open spans, the right end in the
 * last non-empty span, domain [k_p, k_{n+1}] mapped linearly onto [0,1]).
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "bspline.h"

coons_status coons__knots_make(int p, size_t ncp, const double *given, const char *what,
                               double **out, coons_error *err)
{
    *out = NULL;
    if (p < 1 || p > COONS_SPLINE_MAX_DEGREE)
        return coons__error_set(err, COONS_E_INVALID, "%s: degree %d is outside 1..%d", what, p,
                                COONS_SPLINE_MAX_DEGREE);
    if (ncp < (size_t)p + 1)
        return coons__error_set(err, COONS_E_INVALID,
                                "%s: degree %d needs at least %d control points, got %zu", what,
                                p, p + 1, ncp);
    size_t nk = ncp + (size_t)p + 1;
    double *k = coons__malloc_array(nk, sizeof *k);
    if (!k) return coons__error_nomem(err);
    if (!given) {
        size_t interior = ncp - (size_t)p - 1;
        for (size_t i = 0; i < nk; i++) {
            if (i <= (size_t)p)
                k[i] = 0.0;
            else if (i < ncp)
                k[i] = (double)(i - (size_t)p);
            else
                k[i] = (double)(interior + 1);
        }
        *out = k;
        return COONS_OK;
    }
    for (size_t i = 0; i < nk; i++) {
        if (!isfinite(given[i])) {
            coons__free(k);
            return coons__error_set(err, COONS_E_INVALID, "%s: knot %zu is not a finite number",
                                    what, i);
        }
        if (i > 0 && given[i] < given[i - 1]) {
            coons__free(k);
            return coons__error_set(err, COONS_E_INVALID,
                                    "%s: knots must be non-decreasing, but knot %zu (%.17g) < "
                                    "knot %zu (%.17g)",
                                    what, i, given[i], i - 1, given[i - 1]);
        }
        /* A non-empty span narrower than the smallest normal double (or
         * wider than the largest) leaves the basis recurrence dividing by a
         * denormal: 1/5e-324 overflows and the basis comes out NaN. */
        double gap = i > 0 ? given[i] - given[i - 1] : 0.0;
        if (gap != 0.0 && !(gap >= DBL_MIN && gap <= DBL_MAX)) {
            coons__free(k);
            return coons__error_set(err, COONS_E_INVALID,
                                    "%s: knots %zu and %zu (%.17g, %.17g) are %s: a non-empty "
                                    "knot span must lie between the smallest normal double "
                                    "(%.3g) and the largest; scale the knot vector",
                                    what, i - 1, i, given[i - 1], given[i],
                                    gap >= DBL_MIN ? "too far apart" : "too close together",
                                    DBL_MIN);
        }
        k[i] = given[i];
    }
    /* Messages quote given[], never k[]: k is freed before the message is made. */
    size_t run = 1;
    for (size_t i = 1; i < nk; i++) {
        run = (k[i] == k[i - 1]) ? run + 1 : 1;
        if (run > (size_t)p + 1) {
            coons__free(k);
            return coons__error_set(err, COONS_E_INVALID,
                                    "%s: knot value %.17g is repeated more than degree+1 = %d "
                                    "times",
                                    what, given[i], p + 1);
        }
    }
    if (!(k[p] < k[ncp])) {
        coons__free(k);
        return coons__error_set(err, COONS_E_INVALID,
                                "%s: empty domain: knots[%d] = knots[%zu] = %.17g", what, p, ncp,
                                given[p]);
    }
    *out = k;
    return COONS_OK;
}

size_t coons__bspline_span(const double *k, size_t ncp, int p, double x)
{
    return coons__bspline_span_inl(k, ncp, p, x);
}

void coons__bspline_basis(const double *k, size_t span, int p, double x, int nd, double *ders)
{
    if (nd <= 0) { /* the values alone: A2.2, the same operations (bspline.h) */
        coons__bspline_vals(k, span, p, x, ders);
        return;
    }
    if (nd == 1 && p >= 1) { /* with first derivatives: the same operations (bspline.h) */
        coons__bspline_vals1(k, span, p, x, ders);
        return;
    }
    /* A2.3 with fixed-size scratch: p <= COONS_SPLINE_MAX_DEGREE. */
    double ndu[COONS_SPLINE_MAX_DEGREE + 1][COONS_SPLINE_MAX_DEGREE + 1];
    double left[COONS_SPLINE_MAX_DEGREE + 1], right[COONS_SPLINE_MAX_DEGREE + 1];
    double a[2][COONS_SPLINE_MAX_DEGREE + 1];
    ndu[0][0] = 1.0;
    for (int j = 1; j <= p; j++) {
        left[j] = x - k[span + 1 - (size_t)j];
        right[j] = k[span + (size_t)j] - x;
        double saved = 0.0;
        for (int r = 0; r < j; r++) {
            ndu[j][r] = right[r + 1] + left[j - r];
            double temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for (int j = 0; j <= p; j++) ders[j] = ndu[j][p];
    if (nd > p) {
        for (int d = p + 1; d <= nd; d++)
            for (int j = 0; j <= p; j++) ders[d * (p + 1) + j] = 0.0;
        nd = p;
    }
    for (int r = 0; r <= p; r++) {
        int s1 = 0, s2 = 1;
        a[0][0] = 1.0;
        for (int d = 1; d <= nd; d++) {
            double dv = 0.0;
            int rk = r - d, pk = p - d;
            if (r >= d) {
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
                dv = a[s2][0] * ndu[rk][pk];
            }
            int j1 = rk >= -1 ? 1 : -rk;
            int j2 = (r - 1 <= pk) ? d - 1 : p - r;
            for (int j = j1; j <= j2; j++) {
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
                dv += a[s2][j] * ndu[rk + j][pk];
            }
            if (r <= pk) {
                a[s2][d] = -a[s1][d - 1] / ndu[pk + 1][r];
                dv += a[s2][d] * ndu[r][pk];
            }
            ders[d * (p + 1) + r] = dv;
            int tmp = s1;
            s1 = s2;
            s2 = tmp;
        }
    }
    double f = (double)p;
    for (int d = 1; d <= nd; d++) {
        for (int j = 0; j <= p; j++) ders[d * (p + 1) + j] *= f;
        f *= (double)(p - d);
    }
}

void coons__bernstein(int n, double t, int nd, double *ders)
{
    /* B_{j,n} by de Casteljau-style recurrence; derivatives from the
     * degree-reduced polynomials: B'_{j,n} = n (B_{j-1,n-1} - B_{j,n-1}). */
    double b[COONS_SPLINE_MAX_DEGREE + 1][COONS_SPLINE_MAX_DEGREE + 1]; /* b[m][j] = B_{j,m} */
    double s = 1.0 - t;
    b[0][0] = 1.0;
    for (int m = 1; m <= n; m++) {
        b[m][0] = s * b[m - 1][0];
        for (int j = 1; j < m; j++) b[m][j] = s * b[m - 1][j] + t * b[m - 1][j - 1];
        b[m][m] = t * b[m - 1][m - 1];
    }
    for (int j = 0; j <= n; j++) ders[j] = b[n][j];
    if (nd >= 1) {
        for (int j = 0; j <= n; j++) {
            double lo = (j >= 1 && n >= 1) ? b[n - 1][j - 1] : 0.0;
            double hi = (j <= n - 1 && n >= 1) ? b[n - 1][j] : 0.0;
            ders[(n + 1) + j] = n >= 1 ? n * (lo - hi) : 0.0;
        }
    }
    if (nd >= 2) {
        for (int j = 0; j <= n; j++) {
            double v = 0.0;
            if (n >= 2) {
                /* B'' = n(n-1) (B_{j-2,n-2} - 2 B_{j-1,n-2} + B_{j,n-2}) */
                double a0 = (j - 2 >= 0 && j - 2 <= n - 2) ? b[n - 2][j - 2] : 0.0;
                double a1 = (j - 1 >= 0 && j - 1 <= n - 2) ? b[n - 2][j - 1] : 0.0;
                double a2 = (j <= n - 2) ? b[n - 2][j] : 0.0;
                v = (double)n * (n - 1) * (a0 - 2.0 * a1 + a2);
            }
            ders[2 * (n + 1) + j] = v;
        }
    }
}

size_t coons__bspline_basis01(const double *k, size_t ncp, int p, double t, int nd,
                              double *ders)
{
    double lo = k[p], hi = k[ncp], len = hi - lo;
    t = clamp01(t);
    double x = lo + t * len;
    if (t >= 1.0) x = hi;
    size_t span = coons__bspline_span(k, ncp, p, x);
    coons__bspline_basis(k, span, p, x, nd, ders);
    double f = len;
    for (int d = 1; d <= nd; d++) {
        for (int j = 0; j <= p; j++) ders[d * (p + 1) + j] *= f;
        f *= len;
    }
    return span - (size_t)p;
}

coons_status coons__weights_make(const double *w, size_t n, const char *what, double **out,
                                 coons_error *err)
{
    *out = NULL;
    size_t lo = 0, hi = 0;
    for (size_t i = 1; i < n; i++) {
        if (w[i] < w[lo]) lo = i;
        if (w[i] > w[hi]) hi = i;
    }
    if (n && !(w[hi] <= COONS_SPLINE_MAX_WEIGHT_RATIO * w[lo]))
        return coons__error_set(err, COONS_E_LIMIT,
                                "%s: weight %zu is %.17g and weight %zu is %.17g, a ratio of "
                                "%.3g: more than the limit of %g (the rational sums would "
                                "overflow or lose every digit)",
                                what, hi, w[hi], lo, w[lo], w[hi] / w[lo],
                                COONS_SPLINE_MAX_WEIGHT_RATIO);
    double *c = coons__malloc_array(n ? n : 1, sizeof(double));
    if (!c) return coons__error_nomem(err);
    int e = 0;
    if (n) (void)frexp(w[hi], &e); /* w[hi] = f 2^e, 0.5 <= f < 1 */
    for (size_t i = 0; i < n; i++) c[i] = ldexp(w[i], -e);
    *out = c;
    return COONS_OK;
}
