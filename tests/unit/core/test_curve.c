/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Curves of coons/curve.h: line, polyline, Bezier, Hermite, the Coons cubic
 * B-spline (open and closed) and the clamped cubic curve of seed 002, with
 * the seed's worked Example 2.13 and Exercises 2.19 and 2.26; errors,
 * copies and allocation failures of every constructor.
 *
 * Expected values are computed here from the seeds' formulas (Coons
 * polynomials, "ant centroid" knots, tangent halves, the clamped curve's
 * leg construction), by de Casteljau, or by central differences; the
 * hand-worked numbers of the seed examples are written as literals.
 * Derivatives returned by coons_curve_eval_derivs are d/dt over the whole
 * curve: for a Coons cubic of nseg segments, d/dt = nseg d/dtau.
 */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"

/* ---- small helpers -------------------------------------------------------- */

static double norm3(const double *a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

/* o = sum c[j] P[j], j < n */
static void comb(double o[3], int n, const double *c, const double *const *P)
{
    o[0] = o[1] = o[2] = 0.0;
    for (int j = 0; j < n; j++)
        for (int k = 0; k < 3; k++) o[k] += c[j] * P[j][k];
}

static void lerp3(double o[3], const double *a, const double *b, double u)
{
    for (int k = 0; k < 3; k++) o[k] = a[k] + u * (b[k] - a[k]);
}

/* Planar points (x, y) of the seed to packed 3D (z = 0). */
static void xy_to_3d(const double *xy, size_t n, double *out)
{
    for (size_t i = 0; i < n; i++) {
        out[3 * i] = xy[2 * i];
        out[3 * i + 1] = xy[2 * i + 1];
        out[3 * i + 2] = 0.0;
    }
}

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

/* Seed 002 Coons polynomials, written out again. */
static void seed_C(double t, double C[4])
{
    C[0] = (1 - t) * (1 - t) * (1 - t) / 6;
    C[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
    C[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;
    C[3] = t * t * t / 6;
}

/* The Coons cubic B-spline of seed 002 evaluated straight from its
 * definition: segment s = floor(t nseg) uses P_s..P_s+3 (indices taken
 * modulo m for a closed curve of m points). */
static void seed_coons_eval(const double *P, size_t count, int closed, double t, double o[3])
{
    size_t nseg = closed ? count : count - 3;
    double x = t * (double)nseg;
    size_t s = (size_t)floor(x);
    if (s >= nseg) s = nseg - 1;
    double C[4];
    seed_C(x - (double)s, C);
    const double *Q[4];
    for (size_t j = 0; j < 4; j++) Q[j] = P + 3 * (closed ? (s + j) % count : s + j);
    comb(o, 4, C, Q);
}

/* First and second derivatives against central differences, at t at least
 * 1e-3 away from every break. */
static void check_fd(const coons_curve *c, const double *breaks, int nbreaks)
{
    const double h1 = 1e-6, h2 = 1e-4;
    int checked = 0;
    for (int i = 1; i < 100; i++) {
        double t = i / 100.0 + 0.0017;
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
        assert_vec3_near(d[1], fd1, 1e-6 * (1.0 + norm3(d[1])));
        assert_vec3_near(d[2], fd2, 1e-4 * (1.0 + norm3(d[2])));
        checked++;
    }
    assert_true(checked > 50);
}

/* Two curves trace the same points and derivatives at many t. */
static void assert_same_curve(const coons_curve *a, const coons_curve *b, int nt, double eps)
{
    for (int i = 0; i <= nt; i++) {
        double t = (double)i / nt, da[3][3], db[3][3];
        coons_curve_eval_derivs(a, t, 2, da);
        coons_curve_eval_derivs(b, t, 2, db);
        for (int d = 0; d < 3; d++) assert_vec3_near(da[d], db[d], eps * (1.0 + norm3(db[d])));
    }
}

/* cp, not *cp: the out pointer is read after the call has returned. */
static void expect_error(coons_status rc, coons_status want, const coons_error *e,
                         const char *word, coons_curve *const *cp)
{
    assert_int_equal(rc, want);
    assert_int_equal(e->code, want);
    if (!strstr(e->message, word)) fail_msg("message '%s' lacks '%s'", e->message, word);
    assert_null(*cp);
}

/* ---- line, polyline, Bezier, Hermite -------------------------------------- */

static void test_line(void **state)
{
    (void)state;
    const double a[3] = {1, 2, 3}, b[3] = {-3, 4, 11};
    coons_curve *c = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_line(a, b, &c, &e), &e);
    assert_int_equal(coons_curve_kind(c), COONS_CURVE_LINE);
    for (int i = 0; i <= 16; i++) {
        double t = i / 16.0, d[3][3], want[3];
        coons_curve_eval_derivs(c, t, 2, d);
        lerp3(want, a, b, t);
        assert_vec3_near(d[0], want, 1e-15);
        for (int k = 0; k < 3; k++) want[k] = b[k] - a[k];
        assert_vec3_near(d[1], want, 1e-14);
        const double z[3] = {0, 0, 0};
        assert_vec3_near(d[2], z, 0.0);
    }
    check_fd(c, NULL, 0);
    /* t outside [0,1] is clamped */
    double v[3];
    coons_curve_eval(c, -5.0, v);
    assert_vec3_near(v, a, 0.0);
    coons_curve_eval(c, 7.0, v);
    assert_vec3_near(v, b, 0.0);
    coons_curve_free(c);
}

/* Segment i of a polyline spans t in [i/n, (i+1)/n]: the vertices are hit at
 * i/n, the midpoints at (i+1/2)/n, the slope is n (P_i+1 - P_i), right-hand at
 * an inner vertex and left-hand at t = 1. */
static void test_polyline(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 0, 0, 1, 3, 0, 2, 3, 4, 2, 3, 6};
    const int n = 4;
    coons_curve *c = NULL;
    assert_int_equal(coons_curve_new_polyline(P, 5, &c, NULL), COONS_OK);
    assert_int_equal(coons_curve_kind(c), COONS_CURVE_POLYLINE);
    for (int i = 0; i <= n; i++) {
        double d[2][3], want[3];
        coons_curve_eval_derivs(c, (double)i / n, 1, d);
        assert_vec3_near(d[0], P + 3 * i, 1e-15);
        int seg = i < n ? i : n - 1;
        for (int k = 0; k < 3; k++) want[k] = n * (P[3 * (seg + 1) + k] - P[3 * seg + k]);
        assert_vec3_near(d[1], want, 1e-14);
        if (i < n) {
            double m[3];
            coons_curve_eval(c, (i + 0.5) / n, m);
            lerp3(want, P + 3 * i, P + 3 * (i + 1), 0.5);
            assert_vec3_near(m, want, 1e-15);
        }
    }
    const double br[] = {0.25, 0.5, 0.75};
    check_fd(c, br, 3);
    /* two points: the line */
    coons_curve *l = NULL;
    const double a[3] = {0, 0, 0}, b[3] = {2, 2, 2};
    double ab[6] = {0, 0, 0, 2, 2, 2};
    assert_int_equal(coons_curve_new_polyline(ab, 2, &l, NULL), COONS_OK);
    coons_curve *ln = NULL;
    assert_int_equal(coons_curve_new_line(a, b, &ln, NULL), COONS_OK);
    assert_same_curve(l, ln, 20, 1e-15);
    coons_curve_free(l);
    coons_curve_free(ln);
    coons_curve_free(c);
}

/* A quintic Bezier in space against de Casteljau; end derivatives
 * n (P1 - P0), n (Pn - Pn-1), n(n-1)(P2 - 2P1 + P0); difference quotients. */
static void test_bezier(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 3, 0, 3, 4, 2, 5, 1, 3, 6, -2, 1, 8, 0, 0};
    coons_curve *c = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_bezier(P, 6, &c, &e), &e);
    assert_int_equal(coons_curve_kind(c), COONS_CURVE_BEZIER);
    for (int i = 0; i <= 50; i++) {
        double t = i / 50.0, got[3], want[3];
        coons_curve_eval(c, t, got);
        decasteljau(P, 5, t, want);
        assert_vec3_near(got, want, 1e-13);
    }
    double d[3][3], want[3];
    coons_curve_eval_derivs(c, 0.0, 2, d);
    for (int k = 0; k < 3; k++) want[k] = 5 * (P[3 + k] - P[k]);
    assert_vec3_near(d[1], want, 1e-13);
    for (int k = 0; k < 3; k++) want[k] = 20 * (P[6 + k] - 2 * P[3 + k] + P[k]);
    assert_vec3_near(d[2], want, 1e-12);
    coons_curve_eval_derivs(c, 1.0, 2, d);
    for (int k = 0; k < 3; k++) want[k] = 5 * (P[15 + k] - P[12 + k]);
    assert_vec3_near(d[1], want, 1e-13);
    for (int k = 0; k < 3; k++) want[k] = 20 * (P[15 + k] - 2 * P[12 + k] + P[9 + k]);
    assert_vec3_near(d[2], want, 1e-12);
    check_fd(c, NULL, 0);
    /* its one Bezier segment is itself */
    size_t nseg;
    int deg;
    double B[18];
    assert_int_equal(coons_curve_bezier_segments(c, B, 18, &nseg, &deg, NULL), COONS_OK);
    assert_int_equal(nseg, 1);
    assert_int_equal(deg, 5);
    for (int i = 0; i < 18; i++) assert_near(B[i], P[i], 1e-14);
    coons_curve_free(c);
    /* degree 1 Bezier = line */
    assert_int_equal(coons_curve_new_bezier(P, 2, &c, NULL), COONS_OK);
    double m[3];
    coons_curve_eval(c, 0.25, m);
    lerp3(want, P, P + 3, 0.25);
    assert_vec3_near(m, want, 1e-15);
    coons_curve_free(c);
}

/* Hermite: C(0) = p0, C(1) = p1, C'(0) = t0, C'(1) = t1, and at every t the
 * Ferguson form H0 p0 + H1 t0 + H2 t1 + H3 p1 (seed 001 eq. 1.13); its Bezier
 * points are p0, p0 + t0/3, p1 - t1/3, p1. */
static void test_hermite(void **state)
{
    (void)state;
    const double p0[3] = {0, 0, 0}, t0[3] = {3, 6, 0}, p1[3] = {4, 1, 2}, t1[3] = {0, -6, 3};
    coons_curve *c = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_hermite(p0, t0, p1, t1, &c, &e), &e);
    assert_int_equal(coons_curve_kind(c), COONS_CURVE_HERMITE);
    const double *V[4] = {p0, t0, t1, p1};
    for (int i = 0; i <= 40; i++) {
        double t = i / 40.0, s = 1 - t, H[4], want[3], got[3];
        H[0] = (1 + 2 * t) * s * s;
        H[1] = t * s * s;
        H[2] = -t * t * s;
        H[3] = t * t * (3 - 2 * t);
        comb(want, 4, H, V);
        coons_curve_eval(c, t, got);
        assert_vec3_near(got, want, 1e-14);
    }
    double d[3][3];
    coons_curve_eval_derivs(c, 0.0, 1, d);
    assert_vec3_near(d[0], p0, 1e-15);
    assert_vec3_near(d[1], t0, 1e-14);
    coons_curve_eval_derivs(c, 1.0, 1, d);
    assert_vec3_near(d[0], p1, 1e-15);
    assert_vec3_near(d[1], t1, 1e-14);
    check_fd(c, NULL, 0);
    double B[12];
    size_t nseg;
    int deg;
    assert_int_equal(coons_curve_bezier_segments(c, B, 12, &nseg, &deg, NULL), COONS_OK);
    assert_int_equal(nseg, 1);
    assert_int_equal(deg, 3);
    const double b1[3] = {1, 2, 0}, b2[3] = {4, 3, 1};
    assert_vec3_near(B, p0, 1e-15);
    assert_vec3_near(B + 3, b1, 1e-15);
    assert_vec3_near(B + 6, b2, 1e-15);
    assert_vec3_near(B + 9, p1, 1e-15);
    /* the control box holds the curve */
    double lo[3], hi[3];
    coons_curve_control_bbox(c, lo, hi);
    for (int i = 0; i <= 40; i++) {
        double v[3];
        coons_curve_eval(c, i / 40.0, v);
        for (int k = 0; k < 3; k++) {
            assert_true(v[k] >= lo[k] - 1e-15);
            assert_true(v[k] <= hi[k] + 1e-15);
        }
    }
    coons_curve_free(c);
}

/* ---- Coons cubic B-spline (seed 002) -------------------------------------- */

/* One Coons cubic curve P0..P3 in space: P(0) is the "ant centroid"
 * (P0 + 4P1 + P2)/6, P(1) = (P1 + 4P2 + P3)/6, P'(0) = (P2 - P0)/2, P'(1) =
 * (P3 - P1)/2 (one segment: d/dt = d/dtau), P''(0) = P0 - 2P1 + P2, P''(1) =
 * P1 - 2P2 + P3; the curve is the seed's polynomial sum at every t. */
static void test_coons_single_segment(void **state)
{
    (void)state;
    const double P[] = {1, 1, 0, 2, 5, 1, 6, 6, -1, 8, 0, 2};
    const double *Q[4] = {P, P + 3, P + 6, P + 9};
    coons_curve *c = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_coons_cubic(P, 4, 0, &c, &e), &e);
    assert_int_equal(coons_curve_kind(c), COONS_CURVE_COONS_CUBIC);
    double d[3][3], want[3];
    coons_curve_eval_derivs(c, 0.0, 2, d);
    comb(want, 3, (const double[]){1.0 / 6, 4.0 / 6, 1.0 / 6}, Q);
    assert_vec3_near(d[0], want, 1e-15);
    comb(want, 3, (const double[]){-0.5, 0, 0.5}, Q);
    assert_vec3_near(d[1], want, 1e-15);
    comb(want, 3, (const double[]){1, -2, 1}, Q);
    assert_vec3_near(d[2], want, 1e-14);
    coons_curve_eval_derivs(c, 1.0, 2, d);
    comb(want, 3, (const double[]){1.0 / 6, 4.0 / 6, 1.0 / 6}, Q + 1);
    assert_vec3_near(d[0], want, 1e-15);
    comb(want, 3, (const double[]){-0.5, 0, 0.5}, Q + 1);
    assert_vec3_near(d[1], want, 1e-15);
    comb(want, 3, (const double[]){1, -2, 1}, Q + 1);
    assert_vec3_near(d[2], want, 1e-14);
    for (int i = 0; i <= 30; i++) {
        double t = i / 30.0, got[3];
        coons_curve_eval(c, t, got);
        seed_coons_eval(P, 4, 0, t, want);
        assert_vec3_near(got, want, 1e-14);
    }
    check_fd(c, NULL, 0);
    coons_curve_free(c);
}

/* Seed 002 properties 5-6 and the "construction of endpoints": the tangent
 * line at P(0) meets leg P0P1 and leg P1P2 one third from P1, at
 * P(0) -+ P'(0)/3; P(0) is the centre of the segment joining those points
 * (divide the legs in thirds). Likewise at P(1) with P2. */
static void test_coons_construction(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 3, 6, 0, 9, 6, 0, 12, 0, 0};
    coons_curve *c = NULL;
    assert_int_equal(coons_curve_new_coons_cubic(P, 4, 0, &c, NULL), COONS_OK);
    double d[2][3], on01[3], on12[3], on23[3], mid[3], x[3];
    coons_curve_eval_derivs(c, 0.0, 1, d);
    lerp3(on01, P, P + 3, 2.0 / 3); /* point "0": one third from P1 */
    lerp3(on12, P + 3, P + 6, 1.0 / 3); /* point "0*" */
    lerp3(mid, on01, on12, 0.5);
    assert_vec3_near(d[0], mid, 1e-15);
    for (int k = 0; k < 3; k++) x[k] = d[0][k] + d[1][k] / 3;
    assert_vec3_near(x, on12, 1e-15);
    for (int k = 0; k < 3; k++) x[k] = d[0][k] - d[1][k] / 3;
    assert_vec3_near(x, on01, 1e-15);
    coons_curve_eval_derivs(c, 1.0, 1, d);
    lerp3(on12, P + 3, P + 6, 2.0 / 3); /* point "1" */
    lerp3(on23, P + 6, P + 9, 1.0 / 3); /* point "1*" */
    lerp3(mid, on12, on23, 0.5);
    assert_vec3_near(d[0], mid, 1e-14);
    for (int k = 0; k < 3; k++) x[k] = d[0][k] + d[1][k] / 3;
    assert_vec3_near(x, on23, 1e-14);
    coons_curve_free(c);
}

/* Exercise 2.19: six points, so n - 2 = 3 segments; knots (hand-computed
 * ant centroids) (-5,0), (-4,5), (4,5), (7,1); tangents in the segment
 * parameter (P_i+2 - P_i)/2 = (-3,6), (6,3), (6,-3), (3,-3), so d/dt is three
 * times that; C2 at the inner knots. */
static void test_exercise_2_19(void **state)
{
    (void)state;
    const double xy[] = {0, -6, -6, 0, -6, 6, 6, 6, 6, 0, 12, 0};
    const double knots[4][3] = {{-5, 0, 0}, {-4, 5, 0}, {4, 5, 0}, {7, 1, 0}};
    const double tang[4][3] = {{-3, 6, 0}, {6, 3, 0}, {6, -3, 0}, {3, -3, 0}};
    double P[18];
    xy_to_3d(xy, 6, P);
    coons_curve *c = NULL;
    assert_int_equal(coons_curve_new_coons_cubic(P, 6, 0, &c, NULL), COONS_OK);
    size_t nseg;
    int deg;
    assert_int_equal(coons_curve_bezier_segments(c, NULL, 0, &nseg, &deg, NULL), COONS_OK);
    assert_int_equal(nseg, 3);
    for (int j = 0; j <= 3; j++) {
        double d[3][3], want[3];
        coons_curve_eval_derivs(c, j / 3.0, 2, d);
        assert_vec3_near(d[0], knots[j], 1e-14);
        for (int k = 0; k < 3; k++) want[k] = 3 * tang[j][k];
        assert_vec3_near(d[1], want, 1e-13);
    }
    /* C2: one-sided limits at the inner knots agree */
    for (int j = 1; j < 3; j++) {
        double l[3][3], r[3][3];
        coons_curve_eval_derivs(c, j / 3.0 - 1e-10, 2, l);
        coons_curve_eval_derivs(c, j / 3.0 + 1e-10, 2, r);
        for (int dd = 0; dd < 3; dd++) assert_vec3_near(l[dd], r[dd], 1e-6);
    }
    coons_curve_free(c);
}

/* A longer open curve in space: at the knot t_s = s/nseg the point is
 * (P_s + 4P_s+1 + P_s+2)/6, C' = nseg (P_s+2 - P_s)/2, C'' = nseg^2 (P_s -
 * 2P_s+1 + P_s+2). C2 at the knots: the left-hand limits, from the end of
 * segment s-1 (points P_s-1..P_s+2) by the seed formulas and by one-sided
 * differences of the curve, equal the right-hand ones. */
static void test_coons_open_knots_c2(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 3, 1, 4, 4, -1, 6, 1, 0, 7, -2, 2, 10, 0, 1, 11, 4, 0, 13, 5, 3};
    const size_t cnt = 8, nseg = cnt - 3;
    const double ns = (double)nseg;
    coons_curve *c = NULL;
    assert_int_equal(coons_curve_new_coons_cubic(P, cnt, 0, &c, NULL), COONS_OK);
    double br[8];
    for (size_t s = 0; s <= nseg; s++) {
        const double *Q[4] = {P + 3 * s, P + 3 * (s + 1), P + 3 * (s + 2), NULL};
        double t = (double)s / ns, d[3][3], want[3];
        coons_curve_eval_derivs(c, t, 2, d);
        comb(want, 3, (const double[]){1.0 / 6, 4.0 / 6, 1.0 / 6}, Q);
        assert_vec3_near(d[0], want, 1e-14);
        comb(want, 3, (const double[]){-0.5 * ns, 0, 0.5 * ns}, Q);
        assert_vec3_near(d[1], want, 1e-13);
        comb(want, 3, (const double[]){ns * ns, -2 * ns * ns, ns * ns}, Q);
        assert_vec3_near(d[2], want, 1e-11);
        if (s == 0 || s == nseg) continue;
        br[s - 1] = t;
        /* left: segment s-1 at tau = 1 */
        const double *L[4] = {P + 3 * (s - 1), P + 3 * s, P + 3 * (s + 1), P + 3 * (s + 2)};
        double lv[3], l1[3], l2[3];
        comb(lv, 4, (const double[]){0, 1.0 / 6, 4.0 / 6, 1.0 / 6}, L);
        comb(l1, 4, (const double[]){0, -0.5 * ns, 0, 0.5 * ns}, L);
        comb(l2, 4, (const double[]){0, ns * ns, -2 * ns * ns, ns * ns}, L);
        assert_vec3_near(lv, d[0], 1e-14);
        assert_vec3_near(l1, d[1], 1e-13);
        assert_vec3_near(l2, d[2], 1e-11);
        /* left by backward differences of the curve itself (second order) */
        const double h = 1e-4;
        double a0[3], a1[3], a2[3], a3[3], b1[3], b2[3];
        coons_curve_eval(c, t, a0);
        coons_curve_eval(c, t - h, a1);
        coons_curve_eval(c, t - 2 * h, a2);
        coons_curve_eval(c, t - 3 * h, a3);
        for (int k = 0; k < 3; k++) {
            b1[k] = (3 * a0[k] - 4 * a1[k] + a2[k]) / (2 * h);
            b2[k] = (2 * a0[k] - 5 * a1[k] + 4 * a2[k] - a3[k]) / (h * h);
        }
        assert_vec3_near(b1, d[1], 1e-5 * (1 + norm3(d[1])));
        assert_vec3_near(b2, d[2], 1e-3 * (1 + norm3(d[2])));
    }
    for (int i = 0; i <= 200; i++) {
        double t = i / 200.0, got[3], want[3];
        coons_curve_eval(c, t, got);
        seed_coons_eval(P, cnt, 0, t, want);
        assert_vec3_near(got, want, 1e-13);
    }
    check_fd(c, br, (int)nseg - 1);
    coons_curve_free(c);
}

/* Example 2.13: P0 = (0,0), (-6,6), (-6,0), (0,-6), (6,0), (6,6), P6 = P0.
 * Open: n = 6, so n - 2 = 4 Coons cubic curves with control polygons
 * P0P1P2P3, P1P2P3P4, P2P3P4P5, P3P4P5P6; their knots (hand-computed) are
 * (-5,4), (-5,0), (0,-4), (5,0), (5,4). Closing it: append P7 = P1, P8 = P2
 * (P_n = P2, P_n-1 = P1, P_n-2 = P0): 6 segments, the same curve as the closed
 * curve of the 6 distinct points P0..P5, which is periodic. */
static void test_example_2_13(void **state)
{
    (void)state;
    const double xy[] = {0, 0, -6, 6, -6, 0, 0, -6, 6, 0, 6, 6, 0, 0, -6, 6, -6, 0};
    double P[27];
    xy_to_3d(xy, 9, P);
    coons_curve *open = NULL, *reopen = NULL, *closed = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_coons_cubic(P, 7, 0, &open, &e), &e);
    size_t nseg;
    int deg;
    double B[4 * 12];
    assert_int_equal(coons_curve_bezier_segments(open, B, 48, &nseg, &deg, NULL), COONS_OK);
    assert_int_equal(nseg, 4);
    assert_int_equal(deg, 3);
    const double knots[5][3] = {{-5, 4, 0}, {-5, 0, 0}, {0, -4, 0}, {5, 0, 0}, {5, 4, 0}};
    for (int s = 0; s < 4; s++) {
        /* segment s is the Coons cubic curve of the polygon P_s..P_s+3 */
        coons_curve *seg = NULL;
        assert_int_equal(coons_curve_new_coons_cubic(P + 3 * s, 4, 0, &seg, NULL), COONS_OK);
        for (int i = 0; i <= 10; i++) {
            double u = i / 10.0, a[3], b[3];
            coons_curve_eval(open, (s + u) / 4.0, a);
            coons_curve_eval(seg, u, b);
            assert_vec3_near(a, b, 1e-13);
        }
        coons_curve_free(seg);
        double v[3];
        coons_curve_eval(open, s / 4.0, v);
        assert_vec3_near(v, knots[s], 1e-14);
        assert_vec3_near(B + 12 * s, knots[s], 1e-14);
        assert_vec3_near(B + 12 * s + 9, knots[s + 1], 1e-14);
    }
    double v[3];
    coons_curve_eval(open, 1.0, v);
    assert_vec3_near(v, knots[4], 1e-14);
    /* the open curve does not close: it ends at (5,4), not at (-5,4) */
    coons_curve_eval(open, 0.0, v);
    assert_true(fabs(v[0] - knots[4][0]) > 1.0);

    /* closing: 9 points open (last three repeat the first three) = closed of 6 */
    assert_coons_ok(coons_curve_new_coons_cubic(P, 9, 0, &reopen, &e), &e);
    assert_coons_ok(coons_curve_new_coons_cubic(P, 6, 1, &closed, &e), &e);
    assert_int_equal(coons_curve_bezier_segments(closed, NULL, 0, &nseg, &deg, NULL), COONS_OK);
    assert_int_equal(nseg, 6);
    assert_same_curve(reopen, closed, 240, 1e-13);
    double d0[3][3], d1[3][3];
    coons_curve_eval_derivs(closed, 0.0, 2, d0);
    coons_curve_eval_derivs(closed, 1.0, 2, d1);
    assert_vec3_near(d0[0], knots[0], 1e-14);
    for (int d = 0; d < 3; d++) assert_vec3_near(d0[d], d1[d], 1e-12);
    /* the same list given as closed is the mistake the model format rejects */
    coons_curve *bad = (coons_curve *)&bad;
    expect_error(coons_curve_new_coons_cubic(P, 9, 1, &bad, &e), COONS_E_INVALID, &e, "repeat", &bad);
    assert_int_equal(coons_curve_new_coons_cubic(P, 9, 1, &bad, NULL), COONS_E_INVALID);
    /* the example's own list (P6 = P0 only) is a legitimate closed curve of 7 */
    coons_curve *seven = NULL;
    assert_int_equal(coons_curve_new_coons_cubic(P, 7, 1, &seven, NULL), COONS_OK);
    assert_int_equal(coons_curve_bezier_segments(seven, NULL, 0, &nseg, &deg, NULL), COONS_OK);
    assert_int_equal(nseg, 7);
    coons_curve_free(seven);
    coons_curve_free(open);
    coons_curve_free(reopen);
    coons_curve_free(closed);
}

/* A closed curve in space is periodic with C2 across t = 0 = 1; every knot
 * s/m is the ant centroid of P_s, P_s+1, P_s+2 (indices mod m), and the curve
 * is the seed's cyclic sum. The smallest closed curve has 3 points. */
static void test_coons_closed(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 4, 1, 1, 5, 5, -1, 1, 6, 2, -2, 3, 0};
    for (size_t m = 3; m <= 5; m++) {
        coons_curve *c = NULL;
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(coons_curve_new_coons_cubic(P, m, 1, &c, &e), &e);
        double d0[3][3], d1[3][3], l[3][3];
        coons_curve_eval_derivs(c, 0.0, 2, d0);
        coons_curve_eval_derivs(c, 1.0, 2, d1);
        coons_curve_eval_derivs(c, 1.0 - 1e-10, 2, l);
        for (int d = 0; d < 3; d++) {
            assert_vec3_near(d0[d], d1[d], 1e-12 * (1 + norm3(d0[d])));
            assert_vec3_near(d0[d], l[d], 1e-6 * (1 + norm3(d0[d])));
        }
        for (size_t s = 0; s < m; s++) {
            const double *Q[3] = {P + 3 * s, P + 3 * ((s + 1) % m), P + 3 * ((s + 2) % m)};
            double v[2][3], want[3];
            coons_curve_eval_derivs(c, (double)s / (double)m, 1, v);
            comb(want, 3, (const double[]){1.0 / 6, 4.0 / 6, 1.0 / 6}, Q);
            assert_vec3_near(v[0], want, 1e-14);
            comb(want, 3, (const double[]){-0.5 * (double)m, 0, 0.5 * (double)m}, Q);
            assert_vec3_near(v[1], want, 1e-13);
        }
        for (int i = 0; i <= 120; i++) {
            double t = i / 120.0, got[3], want[3];
            coons_curve_eval(c, t, got);
            seed_coons_eval(P, m, 1, t, want);
            assert_vec3_near(got, want, 1e-13);
        }
        double br[5];
        for (size_t s = 1; s < m; s++) br[s - 1] = (double)s / (double)m;
        check_fd(c, br, (int)m - 1);
        coons_curve_free(c);
    }
}

/* The repeated-three rule compares values: -0 and 0 are the same coordinate,
 * so the repeat is found whatever the sign of a zero. */
static void test_coons_closed_repeat_signed_zero(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 2, 0,
                        -0.0, 0, 0, 1, -0.0, 0, 1, 1, -0.0};
    coons_curve *c = (coons_curve *)&c;
    coons_error e = COONS_ERROR_INIT;
    expect_error(coons_curve_new_coons_cubic(P, 7, 1, &c, &e), COONS_E_INVALID, &e, "repeat", &c);
}

/* Coons cubic Bezier form: each segment's Bezier points are the knot
 * (P_s + 4P_s+1 + P_s+2)/6, then one third of the tangent further, i.e. on
 * leg P_s+1P_s+2 at one third and two thirds (seed property 5), then the next
 * knot; the Bezier segment traces the curve. */
static void test_coons_bezier_segments(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 3, 1, 4, 4, -1, 6, 1, 0, 7, -2, 2, 10, 0, 1};
    coons_curve *c = NULL;
    assert_int_equal(coons_curve_new_coons_cubic(P, 6, 0, &c, NULL), COONS_OK);
    double B[3 * 12];
    size_t nseg;
    int deg;
    coons_error e = COONS_ERROR_INIT;
    assert_int_equal(coons_curve_bezier_segments(c, B, 35, &nseg, &deg, &e), COONS_E_INVALID);
    assert_true(strlen(e.message) > 0);
    assert_int_equal(coons_curve_bezier_segments(c, B, 36, &nseg, &deg, NULL), COONS_OK);
    assert_int_equal(nseg, 3);
    for (size_t s = 0; s < 3; s++) {
        const double *Q[4] = {P + 3 * s, P + 3 * (s + 1), P + 3 * (s + 2), P + 3 * (s + 3)};
        double want[3];
        comb(want, 3, (const double[]){1.0 / 6, 4.0 / 6, 1.0 / 6}, Q);
        assert_vec3_near(B + 12 * s, want, 1e-14);
        lerp3(want, Q[1], Q[2], 1.0 / 3);
        assert_vec3_near(B + 12 * s + 3, want, 1e-14);
        lerp3(want, Q[1], Q[2], 2.0 / 3);
        assert_vec3_near(B + 12 * s + 6, want, 1e-14);
        comb(want, 3, (const double[]){1.0 / 6, 4.0 / 6, 1.0 / 6}, Q + 1);
        assert_vec3_near(B + 12 * s + 9, want, 1e-14);
        for (int i = 0; i <= 10; i++) {
            double u = i / 10.0, a[3], b[3];
            decasteljau(B + 12 * s, 3, u, a);
            coons_curve_eval(c, ((double)s + u) / 3.0, b);
            assert_vec3_near(a, b, 1e-13);
        }
    }
    coons_curve_free(c);
}

/* ---- clamped cubic --------------------------------------------------------- */

/* Passes through P0 and Pn with end slopes 3 (P1 - P0) and 3 (Pn - Pn-1) per
 * unit of the knot domain, which has length n - 2 (so d/dt is n - 2 times
 * that); n = 3 is the cubic Bezier curve. */
static void test_clamped_ends(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 3, 1, 4, 4, -1, 6, 1, 0, 7, -2, 2, 10, 0, 1, 11, 4, 0};
    for (size_t cnt = 4; cnt <= 7; cnt++) {
        size_t n = cnt - 1;
        double m = (double)(n - 2);
        coons_curve *c = NULL;
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(coons_curve_new_clamped_cubic(P, cnt, &c, &e), &e);
        assert_int_equal(coons_curve_kind(c), COONS_CURVE_CLAMPED_CUBIC);
        double d[2][3], want[3];
        coons_curve_eval_derivs(c, 0.0, 1, d);
        assert_vec3_near(d[0], P, 1e-15);
        for (int k = 0; k < 3; k++) want[k] = 3 * m * (P[3 + k] - P[k]);
        assert_vec3_near(d[1], want, 1e-13);
        coons_curve_eval_derivs(c, 1.0, 1, d);
        assert_vec3_near(d[0], P + 3 * n, 1e-14);
        for (int k = 0; k < 3; k++) want[k] = 3 * m * (P[3 * n + k] - P[3 * (n - 1) + k]);
        assert_vec3_near(d[1], want, 1e-13);
        double br[8];
        for (size_t j = 1; j < n - 2; j++) br[j - 1] = (double)j / m;
        check_fd(c, br, (int)n - 3);
        if (cnt == 4) {
            for (int i = 0; i <= 20; i++) {
                double a[3], b[3];
                coons_curve_eval(c, i / 20.0, a);
                decasteljau(P, 3, i / 20.0, b);
                assert_vec3_near(a, b, 1e-14);
            }
        }
        coons_curve_free(c);
    }
}

/* Seed 002's conversion formulas, written out here, against the library;
 * then the clamped cubic of the converted points traces the open Coons cubic
 * B-spline of the original points at every t (same parametrisation: both
 * have n - 2 uniform segments). Converting in place gives the same points. */
static void test_open_to_clamped(void **state)
{
    (void)state;
    const double T[] = {0, 0, 0, 1, 3, 1, 4, 4, -1, 6, 1, 0, 7, -2, 2,
                        10, 0, 1, 11, 4, 0, 13, 5, 3, 12, 8, 1, 9, 9, 0};
    for (size_t cnt = 4; cnt <= 10; cnt++) {
        size_t n = cnt - 1;
        double want[30], got[30], inplace[30];
        memcpy(want, T, sizeof want);
        for (int k = 0; k < 3; k++) {
            want[k] = T[k] / 6 + 2 * T[3 + k] / 3 + T[6 + k] / 6;
            want[3 + k] = 2 * T[3 + k] / 3 + T[6 + k] / 3;
            want[3 * (n - 1) + k] = T[3 * (n - 2) + k] / 3 + 2 * T[3 * (n - 1) + k] / 3;
            want[3 * n + k] = T[3 * (n - 2) + k] / 6 + 2 * T[3 * (n - 1) + k] / 3 + T[3 * n + k] / 6;
        }
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(coons_curve_convert_open_to_clamped(T, cnt, got, &e), &e);
        for (size_t i = 0; i < 3 * cnt; i++) assert_near(got[i], want[i], 1e-14);
        memcpy(inplace, T, 3 * cnt * sizeof(double));
        assert_coons_ok(coons_curve_convert_open_to_clamped(inplace, cnt, inplace, &e), &e);
        for (size_t i = 0; i < 3 * cnt; i++) assert_near(inplace[i], want[i], 1e-14);

        coons_curve *open = NULL, *clamped = NULL;
        assert_coons_ok(coons_curve_new_coons_cubic(T, cnt, 0, &open, &e), &e);
        assert_coons_ok(coons_curve_new_clamped_cubic(got, cnt, &clamped, &e), &e);
        assert_same_curve(open, clamped, 300, 1e-12);
        coons_curve_free(open);
        coons_curve_free(clamped);
    }
    double out[9];
    coons_error e = COONS_ERROR_INIT;
    assert_int_equal(coons_curve_convert_open_to_clamped(T, 3, out, &e), COONS_E_INVALID);
    assert_int_equal(e.code, COONS_E_INVALID);
    assert_true(strlen(e.message) > 0);
    assert_int_equal(coons_curve_convert_open_to_clamped(T, 3, out, NULL), COONS_E_INVALID);
}

/*
 * The Bezier points of a clamped cubic by seed 002's construction (slide
 * "construction of knots of clamped curve"), for any n >= 4: the first and
 * last legs are not divided, the second and next-to-last legs are halved,
 * the inner legs are divided in thirds; walking along the polygon these
 * division points (with P1 and P(n-1)) are the inner Bezier points, two per
 * segment; the knots Q0 = P0, Qm = Pn and Qj at the centre of the segment
 * joining the division points on either side of it.
 */
static size_t clamped_bezier_by_construction(const double *P, size_t count, double *B)
{
    size_t n = count - 1, m = n - 2, q = 0;
    double L[64][3], K[33][3];
    for (int k = 0; k < 3; k++) L[q][k] = P[3 + k];
    q++;
    lerp3(L[q++], P + 3, P + 6, 0.5);
    for (size_t i = 2; i <= n - 3; i++) {
        lerp3(L[q++], P + 3 * i, P + 3 * (i + 1), 1.0 / 3);
        lerp3(L[q++], P + 3 * i, P + 3 * (i + 1), 2.0 / 3);
    }
    lerp3(L[q++], P + 3 * (n - 2), P + 3 * (n - 1), 0.5);
    for (int k = 0; k < 3; k++) L[q][k] = P[3 * (n - 1) + k];
    q++;
    assert_int_equal(q, 2 * m);
    for (int k = 0; k < 3; k++) {
        K[0][k] = P[k];
        K[m][k] = P[3 * n + k];
    }
    for (size_t j = 1; j < m; j++) lerp3(K[j], L[2 * j - 1], L[2 * j], 0.5);
    for (size_t j = 0; j < m; j++)
        for (int k = 0; k < 3; k++) {
            B[12 * j + k] = K[j][k];
            B[12 * j + 3 + k] = L[2 * j][k];
            B[12 * j + 6 + k] = L[2 * j + 1][k];
            B[12 * j + 9 + k] = K[j + 1][k];
        }
    return m;
}

/* Exercise 2.26 a-d: the Bezier cubic curves of each clamped curve, from the
 * construction above (a and b also as hand-computed literals); the library's
 * Bezier segments equal them, the curve is their union (segment j covers t in
 * [j/m, (j+1)/m]), and the joins are C2: c0 = b3, c1 - c0 = b3 - b2,
 * c2 - 2c1 + c0 = b3 - 2b2 + b1 (equal parameter lengths). */
static void test_exercise_2_26(void **state)
{
    (void)state;
    static const double a[] = {1, 1, 3, 1, 5, 7, 7, 1, 9, 4};
    static const double b[] = {4, 1, 1, 3, 1, 7, 7, 7, 7, 3, 10, 1};
    static const double c_[] = {3, 1, 1, 3, 3, 7, 6, 1, 9, 7, 7, 7, 6, 5};
    static const double d_[] = {4, 5, 3, 7, 1, 7, 4, 1, 7, 7, 10, 1, 8, 1, 7, 3};
    static const struct {
        const double *xy;
        size_t count;
    } ex[] = {{a, 5}, {b, 6}, {c_, 7}, {d_, 8}};
    /* hand-computed: a) M(P1P2) = (4,4), M(P2P3) = (6,4), knot (5,4) */
    static const double a_hand[] = {1, 1, 3, 1, 4, 4, 5, 4, 5, 4, 6, 4, 7, 1, 9, 4};
    /* b) (1,5), thirds (3,7) (5,7), (7,5); knots (2,6), (6,6) */
    static const double b_hand[] = {4, 1, 1, 3, 1, 5, 2, 6, 2, 6, 3, 7, 5, 7, 6, 6,
                                    6, 6, 7, 5, 7, 3, 10, 1};
    static const double *hand[] = {a_hand, b_hand};
    for (size_t x = 0; x < 4; x++) {
        double P[24], want[6 * 12], got[6 * 12];
        size_t cnt = ex[x].count;
        xy_to_3d(ex[x].xy, cnt, P);
        size_t m = clamped_bezier_by_construction(P, cnt, want);
        assert_int_equal(m, cnt - 3);
        if (x < 2) {
            double hb[6 * 12];
            xy_to_3d(hand[x], 4 * m, hb);
            for (size_t i = 0; i < 12 * m; i++) assert_near(want[i], hb[i], 1e-14);
        }
        coons_curve *c = NULL;
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(coons_curve_new_clamped_cubic(P, cnt, &c, &e), &e);
        size_t nseg = 0;
        int deg = 0;
        assert_coons_ok(coons_curve_bezier_segments(c, NULL, 0, &nseg, &deg, &e), &e);
        assert_int_equal(nseg, m);
        assert_int_equal(deg, 3);
        assert_coons_ok(coons_curve_bezier_segments(c, got, sizeof got / sizeof got[0], &nseg,
                                                    &deg, &e),
                        &e);
        for (size_t i = 0; i < 12 * m; i++) assert_near(got[i], want[i], 1e-13);
        for (size_t j = 0; j < m; j++) {
            for (int i = 0; i <= 12; i++) {
                double u = i / 12.0, p[3], q[3];
                decasteljau(want + 12 * j, 3, u, p);
                coons_curve_eval(c, ((double)j + u) / (double)m, q);
                assert_vec3_near(p, q, 1e-13);
            }
            if (j + 1 == m) continue;
            const double *L = got + 12 * j, *R = got + 12 * (j + 1);
            for (int k = 0; k < 3; k++) {
                assert_near(R[k], L[9 + k], 1e-13);
                assert_near(R[3 + k] - R[k], L[9 + k] - L[6 + k], 1e-13);
                assert_near(R[6 + k] - 2 * R[3 + k] + R[k], L[9 + k] - 2 * L[6 + k] + L[3 + k],
                            1e-13);
            }
        }
        coons_curve_free(c);
    }
}

/* ---- errors ---------------------------------------------------------------- */

/* Too few points for each type, with and without an error record. */
static void test_too_few_points(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 0, 0, 2, 1, 0, 3, 0, 0, 4, 4, 4};
    coons_curve *c = (coons_curve *)&c;
    coons_error e = COONS_ERROR_INIT;
    expect_error(coons_curve_new_polyline(P, 1, &c, &e), COONS_E_INVALID, &e, "at least", &c);
    expect_error(coons_curve_new_polyline(P, 0, &c, &e), COONS_E_INVALID, &e, "at least", &c);
    expect_error(coons_curve_new_bezier(P, 1, &c, &e), COONS_E_INVALID, &e, "at least", &c);
    expect_error(coons_curve_new_coons_cubic(P, 3, 0, &c, &e), COONS_E_INVALID, &e, "at least", &c);
    expect_error(coons_curve_new_coons_cubic(P, 2, 1, &c, &e), COONS_E_INVALID, &e, "at least", &c);
    expect_error(coons_curve_new_clamped_cubic(P, 3, &c, &e), COONS_E_INVALID, &e, "at least", &c);
    expect_error(coons_curve_new_bspline(2, P, 2, NULL, NULL, &c, &e), COONS_E_INVALID, &e, "at least",
                 &c);
    assert_int_equal(coons_curve_new_polyline(P, 1, &c, NULL), COONS_E_INVALID);
    assert_int_equal(coons_curve_new_bezier(P, 1, &c, NULL), COONS_E_INVALID);
    assert_int_equal(coons_curve_new_coons_cubic(P, 3, 0, &c, NULL), COONS_E_INVALID);
    assert_int_equal(coons_curve_new_coons_cubic(P, 2, 1, &c, NULL), COONS_E_INVALID);
    assert_int_equal(coons_curve_new_clamped_cubic(P, 3, &c, NULL), COONS_E_INVALID);
    /* NULL point arrays */
    expect_error(coons_curve_new_polyline(NULL, 3, &c, &e), COONS_E_INVALID, &e, "NULL", &c);
    expect_error(coons_curve_new_bezier(NULL, 3, &c, &e), COONS_E_INVALID, &e, "NULL", &c);
    assert_int_equal(coons_curve_new_coons_cubic(NULL, 5, 0, &c, &e), COONS_E_INVALID);
    assert_int_equal(coons_curve_new_clamped_cubic(NULL, 5, &c, &e), COONS_E_INVALID);
}

/* NaN and infinite coordinates are refused by every constructor. */
static void test_non_finite(void **state)
{
    (void)state;
    const double bad[] = {NAN, INFINITY, -INFINITY};
    for (int v = 0; v < 3; v++) {
        double P[15] = {0, 0, 0, 1, 0, 0, 2, 1, 0, 3, 0, 0, 4, 4, 4};
        P[7] = bad[v];
        double good[3] = {0, 0, 0}, badp[3] = {0, bad[v], 0};
        coons_curve *c = (coons_curve *)&c;
        coons_error e = COONS_ERROR_INIT;
        expect_error(coons_curve_new_line(good, badp, &c, &e), COONS_E_INVALID, &e, "finite", &c);
        expect_error(coons_curve_new_line(badp, good, &c, &e), COONS_E_INVALID, &e, "finite", &c);
        expect_error(coons_curve_new_polyline(P, 5, &c, &e), COONS_E_INVALID, &e, "finite", &c);
        expect_error(coons_curve_new_bezier(P, 5, &c, &e), COONS_E_INVALID, &e, "finite", &c);
        expect_error(coons_curve_new_coons_cubic(P, 5, 0, &c, &e), COONS_E_INVALID, &e, "finite", &c);
        expect_error(coons_curve_new_coons_cubic(P, 5, 1, &c, &e), COONS_E_INVALID, &e, "finite", &c);
        expect_error(coons_curve_new_clamped_cubic(P, 5, &c, &e), COONS_E_INVALID, &e, "finite", &c);
        expect_error(coons_curve_new_hermite(badp, good, good, good, &c, &e), COONS_E_INVALID, &e,
                     "finite", &c);
        expect_error(coons_curve_new_hermite(good, badp, good, good, &c, &e), COONS_E_INVALID, &e,
                     "finite", &c);
        expect_error(coons_curve_new_hermite(good, good, badp, good, &c, &e), COONS_E_INVALID, &e,
                     "finite", &c);
        expect_error(coons_curve_new_hermite(good, good, good, badp, &c, &e), COONS_E_INVALID, &e,
                     "finite", &c);
        assert_int_equal(coons_curve_new_line(good, badp, &c, NULL), COONS_E_INVALID);
        assert_int_equal(coons_curve_new_coons_cubic(P, 5, 1, &c, NULL), COONS_E_INVALID);
        assert_int_equal(coons_curve_new_hermite(good, badp, good, good, &c, NULL), COONS_E_INVALID);
    }
}

/* Size limits: more than COONS_CURVE_MAX_POINTS points, or a Bezier degree
 * above COONS_SPLINE_MAX_DEGREE, is COONS_E_LIMIT; the largest Bezier degree works. */
static void test_limits(void **state)
{
    (void)state;
    size_t n = (size_t)COONS_CURVE_MAX_POINTS + 1;
    double *P = calloc(3 * n, sizeof *P);
    assert_non_null(P);
    coons_curve *c = (coons_curve *)&c;
    coons_error e = COONS_ERROR_INIT;
    expect_error(coons_curve_new_polyline(P, n, &c, &e), COONS_E_LIMIT, &e, "limit", &c);
    expect_error(coons_curve_new_coons_cubic(P, n, 0, &c, &e), COONS_E_LIMIT, &e, "limit", &c);
    expect_error(coons_curve_new_coons_cubic(P, n, 1, &c, &e), COONS_E_LIMIT, &e, "limit", &c);
    expect_error(coons_curve_new_clamped_cubic(P, n, &c, &e), COONS_E_LIMIT, &e, "limit", &c);
    expect_error(coons_curve_new_bezier(P, COONS_SPLINE_MAX_DEGREE + 2, &c, &e), COONS_E_LIMIT, &e, "limit",
                 &c);
    assert_int_equal(coons_curve_new_polyline(P, n, &c, NULL), COONS_E_LIMIT);
    assert_int_equal(coons_curve_new_bezier(P, COONS_SPLINE_MAX_DEGREE + 2, &c, NULL), COONS_E_LIMIT);
    /* exactly the limit is accepted */
    for (size_t i = 0; i < n; i++) P[3 * i] = (double)i;
    assert_int_equal(coons_curve_new_polyline(P, n - 1, &c, NULL), COONS_OK);
    double v[3];
    coons_curve_eval(c, 0.5, v);
    assert_near(v[0], (double)(n - 2) / 2, 1e-9);
    coons_curve_free(c);
    assert_int_equal(coons_curve_new_bezier(P, COONS_SPLINE_MAX_DEGREE + 1, &c, NULL), COONS_OK);
    coons_curve_eval(c, 0.25, v); /* linear precision: x = 64 t */
    assert_near(v[0], COONS_SPLINE_MAX_DEGREE * 0.25, 1e-11);
    coons_curve_free(c);
    free(P);
}

/* t is clamped to [0,1]; NaN gives the start point, never a crash. */
static void test_eval_outside(void **state)
{
    (void)state;
    const double P[] = {0, 0, 0, 1, 3, 1, 4, 4, -1, 6, 1, 0, 7, -2, 2};
    coons_curve *cc = NULL, *bs = NULL;
    assert_int_equal(coons_curve_new_coons_cubic(P, 5, 0, &cc, NULL), COONS_OK);
    assert_int_equal(coons_curve_new_clamped_cubic(P, 5, &bs, NULL), COONS_OK);
    coons_curve *cs[2] = {cc, bs};
    for (int i = 0; i < 2; i++) {
        double a[3][3], b[3][3];
        coons_curve_eval_derivs(cs[i], 0.0, 2, a);
        coons_curve_eval_derivs(cs[i], -1.0, 2, b);
        for (int d = 0; d < 3; d++) assert_vec3_near(a[d], b[d], 0.0);
        coons_curve_eval_derivs(cs[i], NAN, 2, b);
        for (int d = 0; d < 3; d++) assert_vec3_near(a[d], b[d], 0.0);
        coons_curve_eval_derivs(cs[i], -INFINITY, 2, b);
        for (int d = 0; d < 3; d++) assert_vec3_near(a[d], b[d], 0.0);
        coons_curve_eval_derivs(cs[i], 1.0, 2, a);
        coons_curve_eval_derivs(cs[i], 3.5, 2, b);
        for (int d = 0; d < 3; d++) assert_vec3_near(a[d], b[d], 0.0);
        coons_curve_eval_derivs(cs[i], INFINITY, 2, b);
        for (int d = 0; d < 3; d++) assert_vec3_near(a[d], b[d], 0.0);
        /* order 0 writes only out[0] */
        double o[3][3] = {{7, 7, 7}, {7, 7, 7}, {7, 7, 7}};
        coons_curve_eval_derivs(cs[i], 0.5, 0, o);
        const double sev[3] = {7, 7, 7};
        assert_vec3_near(o[1], sev, 0.0);
        assert_vec3_near(o[2], sev, 0.0);
    }
    coons_curve_free(cc);
    coons_curve_free(bs);
}

/* ---- lifecycle ----------------------------------------------------------- */

typedef coons_status (*ctor_fn)(coons_curve **out, coons_error *err);

static const double G[] = {0, 0, 0, 1, 3, 1, 4, 4, -1, 6, 1, 0, 7, -2, 2, 10, 0, 1};
static coons_status mk_line(coons_curve **o, coons_error *e) { return coons_curve_new_line(G, G + 3, o, e); }
static coons_status mk_polyline(coons_curve **o, coons_error *e) { return coons_curve_new_polyline(G, 6, o, e); }
static coons_status mk_bezier(coons_curve **o, coons_error *e) { return coons_curve_new_bezier(G, 5, o, e); }
static coons_status mk_hermite(coons_curve **o, coons_error *e)
{
    return coons_curve_new_hermite(G, G + 3, G + 6, G + 9, o, e);
}
static coons_status mk_open(coons_curve **o, coons_error *e) { return coons_curve_new_coons_cubic(G, 6, 0, o, e); }
static coons_status mk_closed(coons_curve **o, coons_error *e) { return coons_curve_new_coons_cubic(G, 5, 1, o, e); }
static coons_status mk_clamped(coons_curve **o, coons_error *e) { return coons_curve_new_clamped_cubic(G, 6, o, e); }
static coons_status mk_bspline(coons_curve **o, coons_error *e)
{
    static const double k[] = {0, 0, 0, 1, 1, 3, 4, 4, 4};
    return coons_curve_new_bspline(2, G, 6, k, NULL, o, e);
}
static coons_status mk_nurbs(coons_curve **o, coons_error *e)
{
    static const double w[] = {1, 0.5, 2, 1, 0.7, 1};
    return coons_curve_new_bspline(3, G, 6, NULL, w, o, e);
}
static const ctor_fn ctors[] = {mk_line, mk_polyline, mk_bezier, mk_hermite, mk_open,
                                mk_closed, mk_clamped, mk_bspline, mk_nurbs};
#define NCTORS (sizeof ctors / sizeof ctors[0])

/* A copy has the same type, points, derivatives and Bezier segments, and
 * outlives its original. */
static void test_copy(void **state)
{
    (void)state;
    for (size_t i = 0; i < NCTORS; i++) {
        coons_curve *c = NULL, *d = NULL;
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(ctors[i](&c, &e), &e);
        assert_coons_ok(coons_curve_copy(c, &d, &e), &e);
        assert_ptr_not_equal(c, d);
        assert_int_equal(coons_curve_kind(c), coons_curve_kind(d));
        double lo1[3], hi1[3], lo2[3], hi2[3];
        coons_curve_control_bbox(c, lo1, hi1);
        coons_curve_control_bbox(d, lo2, hi2);
        assert_vec3_near(lo1, lo2, 0.0);
        assert_vec3_near(hi1, hi2, 0.0);
        double ref[101][3];
        for (int j = 0; j <= 100; j++) coons_curve_eval(c, j / 100.0, ref[j]);
        assert_same_curve(c, d, 100, 0.0);
        size_t n1 = 0, n2 = 0;
        int g1 = 0, g2 = 0;
        coons_status r1 = coons_curve_bezier_segments(c, NULL, 0, &n1, &g1, NULL);
        coons_status r2 = coons_curve_bezier_segments(d, NULL, 0, &n2, &g2, NULL);
        assert_int_equal(r1, r2);
        if (r1 == COONS_OK) {
            assert_int_equal(n1, n2);
            assert_int_equal(g1, g2);
        }
        coons_curve_free(c);
        for (int j = 0; j <= 100; j++) {
            double v[3];
            coons_curve_eval(d, j / 100.0, v);
            assert_vec3_near(v, ref[j], 0.0);
        }
        coons_curve_free(d);
    }
    coons_curve_free(NULL);
}

/* Every allocation of every constructor (and of the copy) fails in turn:
 * each time the call returns COONS_E_NOMEM with the out pointer NULL and a
 * message, and nothing leaks (valgrind); after the last allocation point the
 * call succeeds. */
static void test_alloc_failures(void **state)
{
    (void)state;
    for (size_t i = 0; i < NCTORS; i++) {
        coons_curve *c = NULL;
        coons_test_fail_after(LONG_MAX);
        assert_int_equal(ctors[i](&c, NULL), COONS_OK);
        long allocs = coons_test_alloc_count();
        coons_test_fail_after(-1);
        coons_curve_free(c);
        assert_true(allocs >= 2);
        for (long n = 0; n <= allocs; n++) {
            coons_error e = COONS_ERROR_INIT;
            c = (coons_curve *)&c;
            coons_test_fail_after(n);
            coons_status rc = ctors[i](&c, &e);
            coons_test_fail_after(-1);
            if (n < allocs) {
                expect_error(rc, COONS_E_NOMEM, &e, "memory", &c);
                c = (coons_curve *)&c;
                coons_test_fail_after(n);
                rc = ctors[i](&c, NULL);
                coons_test_fail_after(-1);
                assert_int_equal(rc, COONS_E_NOMEM);
                assert_null(c);
            } else {
                assert_int_equal(rc, COONS_OK);
                coons_curve_free(c);
            }
        }
        /* the copy */
        coons_curve *orig = NULL;
        assert_int_equal(ctors[i](&orig, NULL), COONS_OK);
        coons_test_fail_after(LONG_MAX);
        assert_int_equal(coons_curve_copy(orig, &c, NULL), COONS_OK);
        allocs = coons_test_alloc_count();
        coons_test_fail_after(-1);
        coons_curve_free(c);
        for (long n = 0; n <= allocs; n++) {
            coons_error e = COONS_ERROR_INIT;
            c = (coons_curve *)&c;
            coons_test_fail_after(n);
            coons_status rc = coons_curve_copy(orig, &c, &e);
            coons_test_fail_after(-1);
            if (n < allocs) {
                expect_error(rc, COONS_E_NOMEM, &e, "memory", &c);
            } else {
                assert_int_equal(rc, COONS_OK);
                assert_same_curve(orig, c, 20, 0.0);
                coons_curve_free(c);
            }
        }
        coons_curve_free(orig);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_line),
        cmocka_unit_test(test_polyline),
        cmocka_unit_test(test_bezier),
        cmocka_unit_test(test_hermite),
        cmocka_unit_test(test_coons_single_segment),
        cmocka_unit_test(test_coons_construction),
        cmocka_unit_test(test_exercise_2_19),
        cmocka_unit_test(test_coons_open_knots_c2),
        cmocka_unit_test(test_example_2_13),
        cmocka_unit_test(test_coons_closed),
        cmocka_unit_test(test_coons_closed_repeat_signed_zero),
        cmocka_unit_test(test_coons_bezier_segments),
        cmocka_unit_test(test_clamped_ends),
        cmocka_unit_test(test_open_to_clamped),
        cmocka_unit_test(test_exercise_2_26),
        cmocka_unit_test(test_too_few_points),
        cmocka_unit_test(test_non_finite),
        cmocka_unit_test(test_limits),
        cmocka_unit_test(test_eval_outside),
        cmocka_unit_test(test_copy),
        cmocka_unit_test(test_alloc_failures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
