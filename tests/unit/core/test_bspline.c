/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * General B-spline and NURBS curves through the public API
 * (coons_curve_new_bspline), checking src/core/bspline.c: knot validation, span
 * search, Cox-de Boor basis with derivatives, the mapping of the domain
 * [k_p, k_{n+1}] onto t in [0,1] (model format, "Curves" and "Resolved
 * details").
 *
 * Expected values come from a naive recursive Cox-de Boor written here (the
 * textbook definition, not the library's triangular algorithm), from closed
 * forms (unit circle, interpolation at a knot of multiplicity p) and from
 * central finite differences.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"

/* ---- independent reference: the recursive definition ---------------------- */

/* N_{i,p}(x), half-open spans, 0/0 = 0. Valid for x inside the domain and not
 * at its right end. */
static double naive_N(const double *k, int i, int p, double x)
{
    if (p == 0) return (k[i] <= x && x < k[i + 1]) ? 1.0 : 0.0;
    double a = 0.0, b = 0.0;
    if (k[i + p] > k[i]) a = (x - k[i]) / (k[i + p] - k[i]) * naive_N(k, i, p - 1, x);
    if (k[i + p + 1] > k[i + 1])
        b = (k[i + p + 1] - x) / (k[i + p + 1] - k[i + 1]) * naive_N(k, i + 1, p - 1, x);
    return a + b;
}

/* sum w_i N_i P_i / sum w_i N_i (w NULL: all 1) */
static void naive_point(int p, const double *pts, int ncp, const double *k, const double *w,
                        double x, double out[3])
{
    double num[3] = {0, 0, 0}, den = 0.0;
    for (int i = 0; i < ncp; i++) {
        double b = naive_N(k, i, p, x) * (w ? w[i] : 1.0);
        den += b;
        for (int c = 0; c < 3; c++) num[c] += b * pts[3 * i + c];
    }
    for (int c = 0; c < 3; c++) out[c] = num[c] / den;
}

/* The curve at the t mapped from x, against the naive sum, at many x strictly
 * inside the domain (knots included: spans are half-open on both sides). */
static void check_against_naive(const coons_curve *c, int p, const double *pts, int ncp,
                                const double *k, const double *w, double eps)
{
    double lo = k[p], hi = k[ncp];
    for (int i = 0; i < 200; i++) {
        double t = i / 200.0, x = lo + t * (hi - lo), got[3], want[3];
        coons_curve_eval(c, t, got);
        naive_point(p, pts, ncp, k, w, x, want);
        assert_vec3_near(got, want, eps);
    }
}

static double dist3(const double *a, const double *b)
{
    double s = 0.0;
    for (int i = 0; i < 3; i++) s += (a[i] - b[i]) * (a[i] - b[i]);
    return sqrt(s);
}

static double norm3(const double *a)
{
    const double z[3] = {0, 0, 0};
    return dist3(a, z);
}

/* First and second derivatives against central differences, at t at least
 * 1e-3 away from every break (t of an interior knot). */
static void check_fd(const coons_curve *c, const double *breaks, int nbreaks, double rel1,
                     double rel2)
{
    const double h1 = 1e-6, h2 = 1e-4;
    int checked = 0;
    for (int i = 1; i < 100; i++) {
        double t = i / 100.0 + 0.0013;
        if (t > 1.0 - 1e-3) continue;
        int near = 0;
        for (int b = 0; b < nbreaks; b++)
            if (fabs(t - breaks[b]) < 1e-3) near = 1;
        if (near) continue;
        double d[3][3], pp[3], pm[3], qp[3], qm[3], fd1[3], fd2[3];
        coons_curve_eval_derivs(c, t, 2, d);
        coons_curve_eval(c, t + h1, pp);
        coons_curve_eval(c, t - h1, pm);
        coons_curve_eval(c, t + h2, qp);
        coons_curve_eval(c, t - h2, qm);
        for (int k = 0; k < 3; k++) {
            fd1[k] = (pp[k] - pm[k]) / (2 * h1);
            fd2[k] = (qp[k] - 2 * d[0][k] + qm[k]) / (h2 * h2);
        }
        assert_vec3_near(d[1], fd1, rel1 * (1.0 + norm3(d[1])));
        assert_vec3_near(d[2], fd2, rel2 * (1.0 + norm3(d[2])));
        checked++;
    }
    assert_true(checked > 50);
}

/* ---- polynomial B-splines ------------------------------------------------- */

/* Given a cubic with non-uniform knots, when evaluated, then it is the
 * Cox-de Boor sum, interpolates its end points (clamped) and its derivatives
 * are the difference quotients. */
static void test_nonuniform_cubic(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 2, 0, 3, 3, 1, 5, 1, 2, 6, -1, 0, 8, 0, -1, 9, 2, 0};
    const double k[] = {0, 0, 0, 0, 0.5, 1.5, 1.75, 4, 4, 4, 4};
    coons_curve *c = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_bspline(3, P, 7, k, NULL, &c, &e), &e);
    assert_int_equal(coons_curve_kind(c), COONS_CURVE_BSPLINE);
    check_against_naive(c, 3, P, 7, k, NULL, 1e-13);
    double a[3], b[3];
    coons_curve_eval(c, 0.0, a);
    coons_curve_eval(c, 1.0, b);
    assert_vec3_near(a, P, 0.0);
    assert_vec3_near(b, P + 18, 1e-15);
    /* End slopes of a clamped curve: p/(k_{p+1} - k_1) (P1 - P0) in x, times
     * the domain length 4 for d/dt. */
    double d[3][3], want[3];
    coons_curve_eval_derivs(c, 0.0, 2, d);
    for (int i = 0; i < 3; i++) want[i] = 4.0 * 3.0 / 0.5 * (P[3 + i] - P[i]);
    assert_vec3_near(d[1], want, 1e-12);
    coons_curve_eval_derivs(c, 1.0, 1, d);
    for (int i = 0; i < 3; i++) want[i] = 4.0 * 3.0 / (4 - 1.75) * (P[18 + i] - P[15 + i]);
    assert_vec3_near(d[1], want, 1e-12);
    const double br[] = {0.5 / 4, 1.5 / 4, 1.75 / 4};
    check_fd(c, br, 3, 1e-6, 1e-4);
    coons_curve_free(c);
}

/* Default knots (NULL) are clamped uniform: 0,0,0,1,2,3,3,3 for degree 2 and
 * five points. */
static void test_default_knots(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 3, 0, 4, 4, 1, 6, 0, 1, 7, 2, 2};
    const double k[] = {0, 0, 0, 1, 2, 3, 3, 3};
    coons_curve *c = NULL;
    assert_int_equal(coons_curve_new_bspline(2, P, 5, NULL, NULL, &c, NULL), COONS_OK);
    check_against_naive(c, 2, P, 5, k, NULL, 1e-13);
    coons_curve_free(c);
}

/* Given interior multiplicity p (= 3) at x = 2 of the domain [0,4], the curve
 * passes through P3 at t = 1/2 and is only C0 there: the returned derivative
 * is the right-hand one, 4 * 3/(4-2) (P4 - P3), and just left of the knot the
 * slope tends to 4 * 3/(2-0) (P3 - P2). */
static void test_interior_multiplicity_p(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 2, 0, 2, 2, 0, 3, 0, 0, 5, 1, 0, 6, 3, 0, 7, 0, 0};
    const double k[] = {0, 0, 0, 0, 2, 2, 2, 4, 4, 4, 4};
    coons_curve *c = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_bspline(3, P, 7, k, NULL, &c, &e), &e);
    check_against_naive(c, 3, P, 7, k, NULL, 1e-13);
    double d[3][3], want[3], left[3][3];
    coons_curve_eval_derivs(c, 0.5, 1, d);
    assert_vec3_near(d[0], P + 9, 1e-15);
    for (int i = 0; i < 3; i++) want[i] = 4.0 * 1.5 * (P[12 + i] - P[9 + i]);
    assert_vec3_near(d[1], want, 1e-12);
    coons_curve_eval_derivs(c, 0.5 - 1e-9, 1, left);
    for (int i = 0; i < 3; i++) want[i] = 4.0 * 1.5 * (P[9 + i] - P[6 + i]);
    assert_vec3_near(left[1], want, 1e-6);
    const double br[] = {0.5};
    check_fd(c, br, 1, 1e-6, 1e-4);
    coons_curve_free(c);
}

/* Given multiplicity p+1 inside (two Bezier pieces that do not meet), then
 * t = 1/2 belongs to the right span (value P4), the left limit is P3. */
static void test_interior_multiplicity_p_plus_1(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 1, 0, 2, 1, 0, 3, 0, 0, 10, 0, 0, 11, 1, 0, 12, 1, 0,
                        13, 0, 0};
    const double k[] = {0, 0, 0, 0, 2, 2, 2, 2, 4, 4, 4, 4};
    coons_curve *c = NULL;
    assert_int_equal(coons_curve_new_bspline(3, P, 8, k, NULL, &c, NULL), COONS_OK);
    double v[3];
    coons_curve_eval(c, 0.5, v);
    assert_vec3_near(v, P + 12, 1e-15);
    coons_curve_eval(c, 0.5 - 1e-12, v);
    assert_vec3_near(v, P + 9, 1e-9);
    coons_curve_eval(c, 1.0, v);
    assert_vec3_near(v, P + 21, 1e-15);
    check_against_naive(c, 3, P, 8, k, NULL, 1e-13);
    size_t nseg = 0;
    int deg = 0;
    assert_int_equal(coons_curve_bezier_segments(c, NULL, 0, &nseg, &deg, NULL), COONS_OK);
    assert_int_equal(nseg, 2);
    assert_int_equal(deg, 3);
    double B[24];
    assert_int_equal(coons_curve_bezier_segments(c, B, 24, &nseg, &deg, NULL), COONS_OK);
    for (int i = 0; i < 24; i++) assert_near(B[i], P[i], 1e-14);
    coons_curve_free(c);
}

/* Domain mapping: knots on [10, 20] are evaluated over t in [0,1] (x = 10 +
 * 10t); the same curve with knots scaled to [0,1] is identical, and d/dt is
 * 10 d/dx (checked with differences in t). */
static void test_domain_mapping(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 2, 4, 1, 5, 5, 0, 7, 1, -1, 9, 3, 0};
    const double k[] = {10, 10, 10, 13, 17, 20, 20, 20};
    const double u[] = {0, 0, 0, 0.3, 0.7, 1, 1, 1};
    coons_curve *c = NULL, *cu = NULL;
    assert_int_equal(coons_curve_new_bspline(2, P, 5, k, NULL, &c, NULL), COONS_OK);
    assert_int_equal(coons_curve_new_bspline(2, P, 5, u, NULL, &cu, NULL), COONS_OK);
    check_against_naive(c, 2, P, 5, k, NULL, 1e-13);
    for (int i = 0; i <= 50; i++) {
        double t = i / 50.0, a[3][3], b[3][3];
        coons_curve_eval_derivs(c, t, 2, a);
        coons_curve_eval_derivs(cu, t, 2, b);
        for (int d = 0; d < 3; d++) assert_vec3_near(a[d], b[d], 1e-11 * (1 + norm3(b[d])));
    }
    double v[3];
    coons_curve_eval(c, 0.0, v);
    assert_vec3_near(v, P, 0.0);
    coons_curve_eval(c, 1.0, v);
    assert_vec3_near(v, P + 12, 1e-15);
    /* first span derivative: d/dt = 10 * 2/(13-10) (P1 - P0) at t = 0 */
    double d[2][3], want[3];
    coons_curve_eval_derivs(c, 0.0, 1, d);
    for (int i = 0; i < 3; i++) want[i] = 10.0 * 2.0 / 3.0 * (P[3 + i] - P[i]);
    assert_vec3_near(d[1], want, 1e-12);
    const double br[] = {0.3, 0.7};
    check_fd(c, br, 2, 1e-6, 1e-4);
    coons_curve_free(c);
    coons_curve_free(cu);
}

/* Unclamped uniform quadratic, knots 0..6, domain [k2, k4] = [2, 4]: the curve
 * starts at (P0+P1)/2, passes (P1+P2)/2 at t = 1/2 and ends at (P2+P3)/2;
 * the slope at t = 0 is 2 (P1 - P0) (1 per unit x, domain length 2). */
static void test_unclamped_uniform(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 2, 2, 0, 4, 0, 2, 6, 2, 2};
    const double k[] = {0, 1, 2, 3, 4, 5, 6};
    coons_curve *c = NULL;
    assert_int_equal(coons_curve_new_bspline(2, P, 4, k, NULL, &c, NULL), COONS_OK);
    double v[3], want[3], d[2][3];
    coons_curve_eval(c, 0.0, v);
    for (int i = 0; i < 3; i++) want[i] = (P[i] + P[3 + i]) / 2;
    assert_vec3_near(v, want, 1e-15);
    coons_curve_eval(c, 0.5, v);
    for (int i = 0; i < 3; i++) want[i] = (P[3 + i] + P[6 + i]) / 2;
    assert_vec3_near(v, want, 1e-15);
    coons_curve_eval(c, 1.0, v);
    for (int i = 0; i < 3; i++) want[i] = (P[6 + i] + P[9 + i]) / 2;
    assert_vec3_near(v, want, 1e-15);
    coons_curve_eval_derivs(c, 0.0, 1, d);
    for (int i = 0; i < 3; i++) want[i] = 2.0 * (P[3 + i] - P[i]);
    assert_vec3_near(d[1], want, 1e-14);
    check_against_naive(c, 2, P, 4, k, NULL, 1e-14);
    coons_curve_free(c);
}

/* The right end of the domain belongs to the last non-empty span: with
 * knots 0,0,0,1,2,2,3,4 (p = 2) the domain is [k2, k5] = [0, 2] and k4 = k5,
 * so t = 1 is evaluated in [1, 2), where the double knot makes the curve pass
 * through P3 (C0 there); the slope is the left-hand one, 2 * 2/(2-1) (P3 - P2).
 */
static void test_right_end_in_multiple_knot(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 2, 0, 3, 3, 1, 5, 1, 2, 6, -1, 0};
    const double k[] = {0, 0, 0, 1, 2, 2, 3, 4};
    coons_curve *c = NULL;
    assert_int_equal(coons_curve_new_bspline(2, P, 5, k, NULL, &c, NULL), COONS_OK);
    double d[2][3], want[3];
    coons_curve_eval_derivs(c, 1.0, 1, d);
    assert_vec3_near(d[0], P + 9, 1e-15);
    for (int i = 0; i < 3; i++) want[i] = 2.0 * 2.0 * (P[9 + i] - P[6 + i]);
    assert_vec3_near(d[1], want, 1e-13);
    check_against_naive(c, 2, P, 5, k, NULL, 1e-14);
    const double br[] = {0.5};
    check_fd(c, br, 1, 1e-6, 1e-4);
    coons_curve_free(c);
}

/* Degree 1 is the polyline through the points, knots included. */
static void test_degree1_is_polyline(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 0, 0, 1, 2, 0, 4, 2, 1};
    const double k[] = {0, 0, 1, 3, 4, 4};
    coons_curve *c = NULL;
    assert_int_equal(coons_curve_new_bspline(1, P, 4, k, NULL, &c, NULL), COONS_OK);
    double v[3], want[3];
    coons_curve_eval(c, 0.25, v);
    assert_vec3_near(v, P + 3, 1e-15);
    coons_curve_eval(c, 0.75, v);
    assert_vec3_near(v, P + 6, 1e-15);
    coons_curve_eval(c, 0.5, v); /* x = 2: halfway on leg P1P2 */
    for (int i = 0; i < 3; i++) want[i] = (P[3 + i] + P[6 + i]) / 2;
    assert_vec3_near(v, want, 1e-15);
    double d[3][3];
    coons_curve_eval_derivs(c, 0.5, 2, d);
    for (int i = 0; i < 3; i++) want[i] = 4.0 * (P[6 + i] - P[3 + i]) / 2.0;
    assert_vec3_near(d[1], want, 1e-14);
    const double zero[3] = {0, 0, 0};
    assert_vec3_near(d[2], zero, 0.0);
    coons_curve_free(c);
}

/* Bezier extraction of a general B-spline: one segment per non-empty span
 * (the double knot makes no empty segment), each segment evaluated with de
 * Casteljau at u equals the curve at the t of that span, and neighbours
 * share their end point. */
static void decasteljau(const double *B, int deg, double u, double out[3])
{
    double w[65][3];
    for (int i = 0; i <= deg; i++)
        for (int c = 0; c < 3; c++) w[i][c] = B[3 * i + c];
    for (int r = 1; r <= deg; r++)
        for (int i = 0; i <= deg - r; i++)
            for (int c = 0; c < 3; c++) w[i][c] = (1 - u) * w[i][c] + u * w[i + 1][c];
    for (int c = 0; c < 3; c++) out[c] = w[0][c];
}

static void test_bezier_extraction(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 2, 0, 3, 3, 1, 5, 1, 2, 6, -1, 0, 8, 0, -1, 9, 2, 0};
    const double k[] = {0, 0, 0, 0, 1, 1, 2.5, 4, 4, 4, 4};
    const double xs[] = {0, 1, 2.5, 4};
    coons_curve *c = NULL;
    assert_int_equal(coons_curve_new_bspline(3, P, 7, k, NULL, &c, NULL), COONS_OK);
    size_t nseg = 0;
    int deg = 0;
    double B[3 * 12];
    assert_int_equal(coons_curve_bezier_segments(c, B, 36, &nseg, &deg, NULL), COONS_OK);
    assert_int_equal(nseg, 3);
    assert_int_equal(deg, 3);
    for (size_t s = 0; s < nseg; s++) {
        for (int i = 0; i <= 20; i++) {
            double u = i / 20.0, x = xs[s] + u * (xs[s + 1] - xs[s]), got[3], want[3];
            decasteljau(B + 12 * s, 3, u, got);
            coons_curve_eval(c, x / 4.0, want);
            assert_vec3_near(got, want, 1e-13);
        }
        if (s + 1 < nseg) assert_vec3_near(B + 12 * s + 9, B + 12 * (s + 1), 1e-14);
    }
    assert_vec3_near(B, P, 1e-15);
    assert_vec3_near(B + 33, P + 18, 1e-15);
    /* too small a buffer: refused, count still reported */
    coons_error e = COONS_ERROR_INIT;
    assert_int_equal(coons_curve_bezier_segments(c, B, 35, &nseg, &deg, &e), COONS_E_INVALID);
    assert_int_equal(e.code, COONS_E_INVALID);
    assert_true(strlen(e.message) > 0);
    assert_int_equal(coons_curve_bezier_segments(c, B, 35, &nseg, &deg, NULL), COONS_E_INVALID);
    coons_curve_free(c);
}

/* ---- NURBS ---------------------------------------------------------------- */

/* Given the quarter circle (1,0), (1,1), (0,1) with weights 1, sqrt(2)/2, 1,
 * then every point is at distance 1 from the origin, the tangent is
 * perpendicular to the radius, C(1/2) = (sqrt2/2, sqrt2/2) by symmetry, and
 * the rational derivatives are the difference quotients. */
static void test_nurbs_quarter_circle(void **state)
{
    (void)state;
    const double s = sqrt(2.0) / 2.0;
    const double P[] = {1, 0, 0, 1, 1, 0, 0, 1, 0};
    const double w[] = {1, s, 1};
    const double k[] = {0, 0, 0, 1, 1, 1};
    coons_curve *c = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_bspline(2, P, 3, NULL, w, &c, &e), &e);
    for (int i = 0; i <= 1000; i++) {
        double t = i / 1000.0, d[2][3];
        coons_curve_eval_derivs(c, t, 1, d);
        assert_near(norm3(d[0]), 1.0, 1e-12);
        assert_near(d[0][0] * d[1][0] + d[0][1] * d[1][1] + d[0][2] * d[1][2], 0.0, 1e-12);
    }
    double v[3];
    coons_curve_eval(c, 0.5, v);
    const double mid[3] = {s, s, 0};
    assert_vec3_near(v, mid, 1e-15);
    check_against_naive(c, 2, P, 3, k, w, 1e-14);
    check_fd(c, NULL, 0, 1e-6, 1e-4);
    /* end tangent of a rational Bezier: p w1/w0 (P1 - P0) = 2 s (0,1,0) */
    double d[2][3];
    coons_curve_eval_derivs(c, 0.0, 1, d);
    const double t0[3] = {0, 2 * s, 0};
    assert_vec3_near(d[1], t0, 1e-14);
    /* rational: no polynomial Bezier segments */
    size_t nseg;
    int deg;
    assert_int_equal(coons_curve_bezier_segments(c, NULL, 0, &nseg, &deg, &e),
                     COONS_E_UNSUPPORTED);
    assert_int_equal(e.code, COONS_E_UNSUPPORTED);
    coons_curve_free(c);
}

/* The full circle from 9 points with knots 0,0,0,1,1,2,2,3,3,4,4,4 (here
 * scaled by 2.5), centre (1,-2,3), radius 2, in a plane tilted about the x
 * axis: every point at radius 2 (to 1e-12) and in the plane, the quarter
 * points at t = 0, 1/4, 1/2, 3/4 are the axis points, C(0) = C(1). */
static void test_nurbs_full_circle(void **state)
{
    (void)state;
    const double s = sqrt(2.0) / 2.0, R = 2.0;
    const double ctr[3] = {1, -2, 3};
    const double ca = cos(0.3), sa = sin(0.3);
    /* plane axes: e1 = x, e2 = (0, cos a, sin a) */
    const double uv[9][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0},
                             {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
    double P[27], w[9];
    for (int i = 0; i < 9; i++) {
        P[3 * i + 0] = ctr[0] + R * uv[i][0];
        P[3 * i + 1] = ctr[1] + R * uv[i][1] * ca;
        P[3 * i + 2] = ctr[2] + R * uv[i][1] * sa;
        w[i] = (i % 2) ? s : 1.0;
    }
    double k[] = {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
    for (int i = 0; i < 12; i++) k[i] *= 2.5;
    coons_curve *c = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_bspline(2, P, 9, k, w, &c, &e), &e);
    const double nrm[3] = {0, -sa, ca};
    for (int i = 0; i <= 4000; i++) {
        double t = i / 4000.0, v[3];
        coons_curve_eval(c, t, v);
        assert_near(dist3(v, ctr), R, 1e-12);
        double off = (v[0] - ctr[0]) * nrm[0] + (v[1] - ctr[1]) * nrm[1] + (v[2] - ctr[2]) * nrm[2];
        assert_near(off, 0.0, 1e-12);
    }
    for (int q = 0; q <= 4; q++) {
        double v[3];
        coons_curve_eval(c, q / 4.0, v);
        assert_vec3_near(v, P + 6 * q, 1e-14);
    }
    const double br[] = {0.25, 0.5, 0.75};
    check_fd(c, br, 3, 1e-6, 1e-4);
    check_against_naive(c, 2, P, 9, k, w, 1e-13);
    coons_curve_free(c);
}

/* Equal weights cancel: a NURBS with every weight 3 is the B-spline. */
static void test_equal_weights_polynomial(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 2, 0, 3, 3, 1, 5, 1, 2, 6, -1, 0};
    const double w[] = {3, 3, 3, 3, 3};
    coons_curve *a = NULL, *b = NULL;
    assert_int_equal(coons_curve_new_bspline(3, P, 5, NULL, w, &a, NULL), COONS_OK);
    assert_int_equal(coons_curve_new_bspline(3, P, 5, NULL, NULL, &b, NULL), COONS_OK);
    for (int i = 0; i <= 64; i++) {
        double da[3][3], db[3][3];
        coons_curve_eval_derivs(a, i / 64.0, 2, da);
        coons_curve_eval_derivs(b, i / 64.0, 2, db);
        for (int d = 0; d < 3; d++) assert_vec3_near(da[d], db[d], 1e-12 * (1 + norm3(db[d])));
    }
    coons_curve_free(a);
    coons_curve_free(b);
}

/* ---- errors --------------------------------------------------------------- */

/* cp, not *cp: the out pointer is read after the call has returned. */
static void expect_error(coons_status rc, coons_status want, const coons_error *e,
                         const char *word, coons_curve *const *cp)
{
    assert_int_equal(rc, want);
    assert_int_equal(e->code, want);
    if (!strstr(e->message, word)) fail_msg("message '%s' lacks '%s'", e->message, word);
    assert_null(*cp);
}

/* Each invalid knot vector is refused with COONS_E_INVALID and a message that
 * names the knots and the fault; err may be NULL. */
static void test_knot_errors(void **state)
{
    (void)state;
    static const double P[] = {0, 0, 0, 1, 0, 0, 2, 1, 0, 3, 0, 0, 4, 1, 0, 5, 0, 0};
    static const double decreasing[] = {0, 0, 0, 2, 1, 3, 3};
    static const double mult_end[] = {0, 0, 0, 0, 1, 1, 1};           /* 0 four times, p = 2 */
    static const double mult_inner[] = {0, 0, 0, 1, 1, 1, 1, 2, 2};   /* 1 four times, p = 2 */
    static const double mult_inner1[] = {0, 0, 1, 1, 1, 2};           /* 1 three times, p = 1 */
    static const double empty[] = {0, 0, 1, 1, 1, 2, 2};              /* k[2] = k[4] = 1 */
    static const double empty_unclamped[] = {0, 1, 2, 2, 2, 3, 4};    /* k[2] = k[4] = 2 */
    static const double nan_knot[] = {0, 0, 0, NAN, 1, 1, 1};
    static const double inf_knot[] = {0, 0, 0, 0.5, 1, 1, INFINITY};
    static const struct {
        int p;
        size_t n;
        const double *k;
        const char *word;
    } cases[] = {
        {2, 4, decreasing, "non-decreasing"}, {2, 4, mult_end, "repeated"},
        {2, 6, mult_inner, "repeated"},       {1, 4, mult_inner1, "repeated"},
        {2, 4, empty, "empty"},               {2, 4, empty_unclamped, "empty"},
        {2, 4, nan_knot, "finite"},           {2, 4, inf_knot, "finite"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        coons_curve *c = (coons_curve *)&c;
        coons_error e = COONS_ERROR_INIT;
        expect_error(coons_curve_new_bspline(cases[i].p, P, cases[i].n, cases[i].k, NULL, &c, &e),
                     COONS_E_INVALID, &e, cases[i].word, &c);
        assert_non_null(strstr(e.message, "knot"));
        c = (coons_curve *)&c;
        assert_int_equal(coons_curve_new_bspline(cases[i].p, P, cases[i].n, cases[i].k, NULL, &c,
                                                 NULL),
                         COONS_E_INVALID);
        assert_null(c);
    }
    /* multiplicity exactly p+1, inside and at the ends, is accepted */
    static const double ok[] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    coons_curve *c = NULL;
    assert_int_equal(coons_curve_new_bspline(2, P, 6, ok, NULL, &c, NULL), COONS_OK);
    coons_curve_free(c);
}

/* Weights must be finite and > 0. */
static void test_weight_errors(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 0, 0, 2, 1, 0};
    const double bad[][3] = {{1, 0, 1}, {1, -0.5, 1}, {1, NAN, 1}, {1, INFINITY, 1}, {-0.0, 1, 1}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        coons_curve *c = (coons_curve *)&c;
        coons_error e = COONS_ERROR_INIT;
        expect_error(coons_curve_new_bspline(2, P, 3, NULL, bad[i], &c, &e), COONS_E_INVALID, &e,
                     "weight", &c);
        assert_int_equal(coons_curve_new_bspline(2, P, 3, NULL, bad[i], &c, NULL), COONS_E_INVALID);
    }
}

/* A rational map is unchanged when every weight is multiplied by one
 * factor: the quarter circle of radius 1e9 with weights 1e300 (w P alone
 * would overflow) is the circle of radius 1e9; weights 3, 2, 3 times 2^-1070
 * (subnormal: w N alone would underflow) give the very points of weights
 * 3, 2, 3; and weights whose ratio passes COONS_SPLINE_MAX_WEIGHT_RATIO are
 * refused with COONS_E_LIMIT. */
static void test_weight_scale(void **state)
{
    (void)state;
    const double s = sqrt(2.0) / 2.0, R = 1e9;
    const double P[] = {R, 0, 0, R, R, 0, 0, R, 0};
    {
        const double w[] = {1e300, s * 1e300, 1e300};
        coons_curve *c = NULL;
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(coons_curve_new_bspline(2, P, 3, NULL, w, &c, &e), &e);
        for (int i = 0; i <= 100; i++) {
            double d[2][3];
            coons_curve_eval_derivs(c, i / 100.0, 1, d);
            assert_near(norm3(d[0]) / R, 1.0, 1e-14);
            assert_near((d[0][0] * d[1][0] + d[0][1] * d[1][1]) / (R * norm3(d[1])), 0.0, 1e-12);
        }
        coons_curve_free(c);
    }
    {
        const double P5[] = {0, 0, 0, 1, 2, 0, 3, 3, 1, 5, 1, 2, 6, -1, 0};
        const double w[] = {3, 2, 3, 1, 5}, ws[] = {0x3p-1070, 0x2p-1070, 0x3p-1070, 0x1p-1070, 0x5p-1070};
        coons_curve *a = NULL, *b = NULL;
        assert_int_equal(coons_curve_new_bspline(3, P5, 5, NULL, w, &a, NULL), COONS_OK);
        assert_int_equal(coons_curve_new_bspline(3, P5, 5, NULL, ws, &b, NULL), COONS_OK);
        for (int i = 0; i <= 64; i++) {
            double da[3][3], db[3][3];
            coons_curve_eval_derivs(a, i / 64.0, 2, da);
            coons_curve_eval_derivs(b, i / 64.0, 2, db);
            assert_memory_equal(da, db, sizeof da);
        }
        coons_curve_free(a);
        coons_curve_free(b);
    }
    const double w[] = {1.0, 1.0, 1.01 * COONS_SPLINE_MAX_WEIGHT_RATIO};
    coons_curve *c = (coons_curve *)&c;
    coons_error e = COONS_ERROR_INIT;
    expect_error(coons_curve_new_bspline(2, P, 3, NULL, w, &c, &e), COONS_E_LIMIT, &e, "ratio",
                 &c);
    const double wok[] = {1.0, 1.0, COONS_SPLINE_MAX_WEIGHT_RATIO};
    assert_int_equal(coons_curve_new_bspline(2, P, 3, NULL, wok, &c, NULL), COONS_OK);
    coons_curve_free(c);
}

/* Degree outside 1..COONS_SPLINE_MAX_DEGREE, and too few points for the degree. */
static void test_degree_errors(void **state)
{
    (void)state;
    static double P[3 * (COONS_SPLINE_MAX_DEGREE + 2)];
    for (int i = 0; i < COONS_SPLINE_MAX_DEGREE + 2; i++) P[3 * i] = i;
    const int bad[] = {0, -1, COONS_SPLINE_MAX_DEGREE + 1, 1000};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        coons_curve *c = (coons_curve *)&c;
        coons_error e = COONS_ERROR_INIT;
        expect_error(coons_curve_new_bspline(bad[i], P, COONS_SPLINE_MAX_DEGREE + 2, NULL, NULL, &c, &e),
                     COONS_E_INVALID, &e, "degree", &c);
        assert_int_equal(coons_curve_new_bspline(bad[i], P, 4, NULL, NULL, &c, NULL),
                         COONS_E_INVALID);
    }
    /* the largest degree works and is the Bezier curve of the same points */
    coons_curve *c = NULL, *bz = NULL;
    assert_int_equal(coons_curve_new_bspline(COONS_SPLINE_MAX_DEGREE, P, COONS_SPLINE_MAX_DEGREE + 1, NULL, NULL,
                                             &c, NULL),
                     COONS_OK);
    assert_int_equal(coons_curve_new_bezier(P, COONS_SPLINE_MAX_DEGREE + 1, &bz, NULL), COONS_OK);
    double a[3], b[3];
    coons_curve_eval(c, 0.37, a);
    coons_curve_eval(bz, 0.37, b);
    assert_vec3_near(a, b, 1e-12);
    /* x coordinates i: linear precision, x(t) = 64 t */
    assert_near(a[0], 64 * 0.37, 1e-11);
    coons_curve_free(c);
    coons_curve_free(bz);
    /* p + 1 points needed */
    coons_error e = COONS_ERROR_INIT;
    c = (coons_curve *)&c;
    expect_error(coons_curve_new_bspline(3, P, 3, NULL, NULL, &c, &e), COONS_E_INVALID, &e, "at least",
                 &c);
}

/* Coordinates must be finite; points may not be NULL. */
static void test_point_errors(void **state)
{
    (void)state;
    double P[] = {0, 0, 0, 1, 0, 0, 2, 1, 0, 3, 0, 0};
    const double vals[] = {NAN, INFINITY, -INFINITY};
    for (int v = 0; v < 3; v++) {
        for (int slot = 0; slot < 12; slot += 5) {
            double Q[12];
            memcpy(Q, P, sizeof Q);
            Q[slot] = vals[v];
            coons_curve *c = (coons_curve *)&c;
            coons_error e = COONS_ERROR_INIT;
            expect_error(coons_curve_new_bspline(2, Q, 4, NULL, NULL, &c, &e), COONS_E_INVALID, &e,
                         "finite", &c);
            assert_int_equal(coons_curve_new_bspline(2, Q, 4, NULL, NULL, &c, NULL), COONS_E_INVALID);
        }
    }
    coons_curve *c = (coons_curve *)&c;
    coons_error e = COONS_ERROR_INIT;
    expect_error(coons_curve_new_bspline(2, NULL, 4, NULL, NULL, &c, &e), COONS_E_INVALID, &e, "NULL",
                 &c);
}

/* More than COONS_CURVE_MAX_POINTS points: COONS_E_LIMIT. */
static void test_size_limit(void **state)
{
    (void)state;
    size_t n = (size_t)COONS_CURVE_MAX_POINTS + 1;
    double *P = calloc(3 * n, sizeof *P);
    assert_non_null(P);
    coons_curve *c = (coons_curve *)&c;
    coons_error e = COONS_ERROR_INIT;
    expect_error(coons_curve_new_bspline(3, P, n, NULL, NULL, &c, &e), COONS_E_LIMIT, &e, "limit", &c);
    assert_int_equal(coons_curve_new_bspline(3, P, n, NULL, NULL, &c, NULL), COONS_E_LIMIT);
    free(P);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nonuniform_cubic),
        cmocka_unit_test(test_default_knots),
        cmocka_unit_test(test_interior_multiplicity_p),
        cmocka_unit_test(test_interior_multiplicity_p_plus_1),
        cmocka_unit_test(test_domain_mapping),
        cmocka_unit_test(test_unclamped_uniform),
        cmocka_unit_test(test_right_end_in_multiple_knot),
        cmocka_unit_test(test_degree1_is_polyline),
        cmocka_unit_test(test_bezier_extraction),
        cmocka_unit_test(test_nurbs_quarter_circle),
        cmocka_unit_test(test_nurbs_full_circle),
        cmocka_unit_test(test_equal_weights_polynomial),
        cmocka_unit_test(test_weight_scale),
        cmocka_unit_test(test_knot_errors),
        cmocka_unit_test(test_weight_errors),
        cmocka_unit_test(test_degree_errors),
        cmocka_unit_test(test_point_errors),
        cmocka_unit_test(test_size_limit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
