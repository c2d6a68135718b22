/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The B-spline curve types (model format, "Curves"). Line, polyline,
 * Bezier, cubic Hermite, clamped cubic and general B-spline/NURBS are all
 * B-splines over a knot vector whose domain [k_p, k_{n+1}] maps onto [0,1]:
 * - line and polyline: degree 1, clamped uniform knots (segment i spans
 *   [i/n, (i+1)/n]);
 * - Bezier: degree n, knots 0^(n+1) 1^(n+1) (the Bernstein basis);
 * - Hermite: the cubic Bezier P0, P0 + T0/3, P1 - T1/3, P1 (the same cubic);
 * - clamped cubic: degree 3, clamped uniform knots (seed 002);
 * - rational curves: C = sum w N P / sum w N (The NURBS Book, eq. 4.8).
 * One file for the six types: they share the record, the evaluator and the
 * Bezier extraction, and differ only in their constructors (and rows).
 */
#include "bspline.h"
#include "curve_impl.h"

static coons_status check_points(const double *pts, size_t count, size_t min, const char *what,
                                 coons_error *err)
{
    if (!pts && count)
        return coons__error_set(err, COONS_E_INVALID, "%s: points are NULL", what);
    if (count < min)
        return coons__error_set(err, COONS_E_INVALID, "%s needs at least %zu points, got %zu",
                                what, min, count);
    if (count > COONS_CURVE_MAX_POINTS)
        return coons__error_set(err, COONS_E_LIMIT,
                                "%s has %zu points, more than the limit of %d", what, count,
                                COONS_CURVE_MAX_POINTS);
    for (size_t i = 0; i < count; i++)
        if (!v3_finite(pts + 3 * i))
            return coons__error_set(err, COONS_E_INVALID, "%s: point %zu is not finite", what,
                                    i);
    return COONS_OK;
}

/* Builds a B-spline-backed curve; takes the given arrays by copy. */
static coons_status make_bspline(const coons__curve_kind *kind, int p, const double *pts, size_t n,
                                 const double *knots, const double *w, const char *what,
                                 coons_curve **out, coons_error *err)
{
    *out = NULL;
    coons_status rc = check_points(pts, n, (size_t)(p < 1 ? 1 : p) + 1, what, err);
    if (rc) return rc;
    if (w) {
        for (size_t i = 0; i < n; i++)
            if (!(w[i] > 0.0) || !isfinite(w[i]))
                return coons__error_set(err, COONS_E_INVALID,
                                        "%s: weight %zu is %.17g, weights must be finite and > 0",
                                        what, i, w[i]);
    }
    coons_curve *c = NULL;
    if ((rc = coons__curve_alloc(kind, &c, err))) return rc;
    c->degree = p;
    c->n = n;
    if ((rc = coons__knots_make(p, n, knots, what, &c->knots, err))) {
        coons_curve_free(c);
        return rc;
    }
    if (w && (rc = coons__weights_make(w, n, what, &c->w, err))) {
        coons_curve_free(c);
        return rc;
    }
    c->pts = coons__memdup(pts, 3 * n, sizeof(double));
    if (!c->pts) {
        coons_curve_free(c);
        return coons__error_nomem(err);
    }
    *out = c;
    return COONS_OK;
}

coons_status coons_curve_new_line(const double p0[3], const double p1[3], coons_curve **out,
                                  coons_error *err)
{
    double pts[6];
    v3_copy(pts, p0);
    v3_copy(pts + 3, p1);
    return make_bspline(&coons__line_kind, 1, pts, 2, NULL, NULL, "line", out, err);
}

coons_status coons_curve_new_polyline(const double *points, size_t count, coons_curve **out,
                                      coons_error *err)
{
    return make_bspline(&coons__polyline_kind, 1, points, count, NULL, NULL, "polyline", out,
                        err);
}

coons_status coons_curve_new_bezier(const double *points, size_t count, coons_curve **out,
                                    coons_error *err)
{
    *out = NULL;
    if (count < 2)
        return coons__error_set(err, COONS_E_INVALID, "bezier needs at least 2 points, got %zu",
                                count);
    if (count > COONS_SPLINE_MAX_DEGREE + 1)
        return coons__error_set(err, COONS_E_LIMIT,
                                "bezier has %zu points; degree %zu is above the limit %d", count,
                                count - 1, COONS_SPLINE_MAX_DEGREE);
    int p = (int)count - 1;
    double knots[2 * (COONS_SPLINE_MAX_DEGREE + 1)];
    for (int i = 0; i <= p; i++) {
        knots[i] = 0.0;
        knots[p + 1 + i] = 1.0;
    }
    return make_bspline(&coons__bezier_kind, p, points, count, knots, NULL, "bezier", out, err);
}

coons_status coons_curve_new_hermite(const double p0[3], const double t0[3], const double p1[3],
                                     const double t1[3], coons_curve **out, coons_error *err)
{
    *out = NULL;
    if (!v3_finite(t0) || !v3_finite(t1))
        return coons__error_set(err, COONS_E_INVALID, "hermite: tangent is not finite");
    /* Same cubic: Bezier points P0, P0 + T0/3, P1 - T1/3, P1. */
    double b[12], knots[8] = {0, 0, 0, 0, 1, 1, 1, 1};
    v3_copy(b, p0);
    v3_copy(b + 3, p0);
    v3_axpy(b + 3, 1.0 / 3.0, t0);
    v3_copy(b + 6, p1);
    v3_axpy(b + 6, -1.0 / 3.0, t1);
    v3_copy(b + 9, p1);
    return make_bspline(&coons__hermite_kind, 3, b, 4, knots, NULL, "hermite", out, err);
}

coons_status coons_curve_new_clamped_cubic(const double *points, size_t count, coons_curve **out,
                                           coons_error *err)
{
    return make_bspline(&coons__clamped_cubic_kind, 3, points, count, NULL, NULL,
                        "clamped-cubic", out, err);
}

coons_status coons_curve_new_bspline(int degree, const double *points, size_t count,
                                     const double *knots, const double *weights, coons_curve **out,
                                     coons_error *err)
{
    *out = NULL;
    if (degree < 1 || degree > COONS_SPLINE_MAX_DEGREE)
        return coons__error_set(err, COONS_E_INVALID, "bspline: degree %d is outside 1..%d",
                                degree, COONS_SPLINE_MAX_DEGREE);
    return make_bspline(&coons__bspline_kind, degree, points, count, knots, weights, "bspline",
                        out, err);
}

static void eval(const coons_curve *c, double t, int order, double out[][3])
{
    int p = c->degree;
    double N[3 * (COONS_SPLINE_MAX_DEGREE + 1)];
    size_t first = coons__bspline_basis01(c->knots, c->n, p, t, order, N);
    if (!c->w) {
        for (int d = 0; d <= order; d++) {
            v3_zero(out[d]);
            for (int j = 0; j <= p; j++) v3_axpy(out[d], N[d * (p + 1) + j], c->pts + 3 * (first + (size_t)j));
        }
        return;
    }
    /* Rational: A = sum w N P, W = sum w N; C = A/W and the quotient rule
     * (The NURBS Book, eq. 4.8). */
    double A[3][3] = {{0}}, W[3] = {0};
    for (int d = 0; d <= order; d++) {
        for (int j = 0; j <= p; j++) {
            size_t i = first + (size_t)j;
            double wn = c->w[i] * N[d * (p + 1) + j];
            W[d] += wn;
            v3_axpy(A[d], wn, c->pts + 3 * i);
        }
    }
    v3_scale(out[0], A[0], 1.0 / W[0]);
    if (order >= 1) {
        for (int k = 0; k < 3; k++) out[1][k] = (A[1][k] - W[1] * out[0][k]) / W[0];
    }
    if (order >= 2) {
        for (int k = 0; k < 3; k++)
            out[2][k] = (A[2][k] - 2.0 * W[1] * out[1][k] - W[2] * out[0][k]) / W[0];
    }
}

/* Blossom of the span ending in `span` at the p arguments x[0..p-1]
 * (de Boor's algorithm with one argument per level). */
static void blossom(const coons_curve *c, size_t span, const double *x, double out[3])
{
    int p = c->degree;
    const double *k = c->knots;
    double d[COONS_SPLINE_MAX_DEGREE + 1][3];
    for (int r = 0; r <= p; r++) v3_copy(d[r], c->pts + 3 * (span - (size_t)p + (size_t)r));
    for (int l = 1; l <= p; l++) {
        for (int r = p; r >= l; r--) {
            size_t i = span - (size_t)p + (size_t)r;
            double den = k[i + (size_t)p + 1 - (size_t)l] - k[i];
            double a = den > 0.0 ? (x[l - 1] - k[i]) / den : 0.0;
            v3_lerp(d[r], d[r - 1], d[r], a);
        }
    }
    v3_copy(out, d[p]);
}

static coons_status bezier_segments(const coons_curve *c, double *points, size_t capacity,
                                    size_t *segments, int *degree, coons_error *err)
{
    if (c->w)
        return coons__error_set(err, COONS_E_UNSUPPORTED,
                                "a rational curve has rational Bezier segments");
    int p = c->degree;
    size_t nseg = 0;
    for (size_t i = (size_t)p; i < c->n; i++)
        if (c->knots[i] < c->knots[i + 1]) nseg++;
    *segments = nseg;
    *degree = p;
    if (!points) return COONS_OK;
    size_t need = nseg * (size_t)(p + 1) * 3;
    if (capacity < need)
        return coons__error_set(err, COONS_E_INVALID,
                                "bezier segments need %zu doubles, capacity is %zu", need,
                                capacity);
    double x[COONS_SPLINE_MAX_DEGREE];
    size_t s = 0;
    for (size_t i = (size_t)p; i < c->n; i++) {
        double a = c->knots[i], b = c->knots[i + 1];
        if (!(a < b)) continue;
        /* Bezier point j is the blossom at (a^(p-j), b^j). */
        for (int j = 0; j <= p; j++) {
            for (int m = 0; m < p; m++) x[m] = m < p - j ? a : b;
            blossom(c, i, x, points + (s * (size_t)(p + 1) + (size_t)j) * 3);
        }
        s++;
    }
    return COONS_OK;
}

static void free_data(coons_curve *c)
{
    coons__free(c->pts);
    coons__free(c->knots);
    coons__free(c->w);
}

static coons_status copy_data(const coons_curve *c, coons_curve *d, coons_error *err)
{
    d->pts = coons__memdup(c->pts, 3 * c->n, sizeof(double));
    d->knots = c->knots ? coons__memdup(c->knots, c->n + (size_t)c->degree + 1, sizeof(double))
                        : NULL;
    d->w = c->w ? coons__memdup(c->w, c->n, sizeof(double)) : NULL;
    if (!d->pts || (c->knots && !d->knots) || (c->w && !d->w)) return coons__error_nomem(err);
    return COONS_OK;
}

static void breaks(const coons_curve *c, coons__breaks *B)
{
    coons__breaks_knots(B, c->knots, c->n, c->degree);
}

/* Degree p over the knots; rational with weights that differ (The NURBS
 * Book, eq. 4.8). */
static void space(const coons_curve *c, coons__space *S)
{
    S->degree = c->degree;
    S->kind = coons__weights_space(c->w, c->n);
    S->cont = coons__knots_continuity(c->knots, c->n, c->degree);
}

#define BSPLINE_ROW(t)                                                                 \
    {.type = t, .eval = eval, .bezier = bezier_segments, .breaks = breaks,              \
     .copy = copy_data, .free = free_data, .space = space}
const coons__curve_kind coons__line_kind = BSPLINE_ROW(COONS_CURVE_LINE);
const coons__curve_kind coons__polyline_kind = BSPLINE_ROW(COONS_CURVE_POLYLINE);
const coons__curve_kind coons__bezier_kind = BSPLINE_ROW(COONS_CURVE_BEZIER);
const coons__curve_kind coons__hermite_kind = BSPLINE_ROW(COONS_CURVE_HERMITE);
const coons__curve_kind coons__clamped_cubic_kind = BSPLINE_ROW(COONS_CURVE_CLAMPED_CUBIC);
const coons__curve_kind coons__bspline_kind = BSPLINE_ROW(COONS_CURVE_BSPLINE);
