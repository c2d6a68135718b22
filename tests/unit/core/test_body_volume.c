/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * coons_body_volume_bounded() (src/core/body_volume.c): bounded work and
 * an error estimate that bounds the true error. Expected volumes are
 * closed forms computed here: affine maps (det A), a Bezier volume
 * x = 10u, y = 10v, z = 10 w h(u,v) with h a Bernstein polynomial
 * (det J = 1000 h, and a Bernstein basis function of degree n integrates
 * to 1/(n+1), so the volume is 1000 times the mean of h's coefficients),
 * and a body 1 whose u edges are one polyline translated: F = P(u) +
 * (0, v Ly, w Lz), det J = x'(u) Ly Lz, a step function with a jump at
 * each of its many vertices, whose integral is (x(1) - x(0)) Ly Lz.
 * The tensor volumes' det J grid is checked against det J point by point.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "body_fixtures.h"

static void check_bounded(const coons_body *b, double truth, double rel_tol, size_t budget,
                          double want_rel, size_t *evals_out)
{
    coons_error err = COONS_ERROR_INIT;
    double vol = NAN, e = NAN;
    size_t evals = 0;
    assert_coons_ok(coons_body_volume_bounded(b, rel_tol, budget, &vol, &e, &evals, &err), &err);
    size_t cap = budget ? budget : COONS_BODY_VOLUME_MAX_EVALS;
    printf("# volume %.17g truth %.17g |error| %.3g estimate %.3g evaluations %zu (budget %zu)\n",
           vol, truth, fabs(vol - truth), e, evals, cap);
    assert_true(evals > 0 && evals <= cap);
    /* the estimate bounds the true error (plus rounding of det J) */
    assert_true(isfinite(e) && e >= 0);
    assert_true(fabs(vol - truth) <= e + 1e-14 * fabs(truth));
    if (want_rel > 0) assert_true(fabs(vol - truth) <= want_rel * fabs(truth));
    if (evals_out) *evals_out = evals;
    /* coons_body_volume() is the same computation with the defaults */
    if (!budget) {
        double v2 = NAN;
        assert_coons_ok(coons_body_volume(b, rel_tol, &v2, &err), &err);
        assert_true(v2 == vol);
    }
}

/* x = o + A q: box, parallelepiped (exact at once, to rounding). */
static void test_affine(void **state)
{
    (void)state;
    static const double A[2][3][3] = {{{2, 0, 0}, {0, 3, 0}, {0, 0, 0.5}},
                                      {{2.0, 0.5, 0.3}, {0.1, 3.0, -0.4}, {0.2, 0.0, 1.5}}};
    static const double o[3] = {1.0, -2.0, 0.5};
    for (int k = 0; k < 2; k++) {
        double c[8][3];
        for (int n = 0; n < 8; n++) {
            double q[3] = {n >> 2, (n >> 1) & 1, n & 1};
            for (int r = 0; r < 3; r++)
                c[n][r] = o[r] + A[k][r][0] * q[0] + A[k][r][1] * q[1] + A[k][r][2] * q[2];
        }
        coons_error err = COONS_ERROR_INIT;
        coons_body *b = NULL;
        assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err), &err);
        const double(*M)[3] = A[k];
        double det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                     M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                     M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
        size_t evals;
        check_bounded(b, det, 1e-12, 0, 1e-12, &evals);
        /* one round: the level and its three tests (125 * (1 + 3 * 2)) */
        assert_int_equal(evals, 875);
        coons_body_free(b);
    }
}

/* A Bezier volume of degree (n-1, n-1, 1): z = 10 w h(u, v). */
static coons_body *bezier_height(size_t n, double *truth)
{
    size_t dims[3] = {n, n, 2};
    double *p = malloc(n * n * 2 * 3 * sizeof(double));
    assert_non_null(p);
    tb_rng rng = {2026};
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++) {
            double c = 1.0 + tb_rand(&rng);
            sum += c;
            for (int k = 0; k < 2; k++) {
                double *q = p + 3 * ((i * n + j) * 2 + (size_t)k);
                q[0] = 10.0 * (double)i / (double)(n - 1);
                q[1] = 10.0 * (double)j / (double)(n - 1);
                q[2] = 10.0 * k * c;
            }
        }
    *truth = 1000.0 * sum / (double)(n * n);
    coons_error err = COONS_ERROR_INIT;
    coons_body *b = NULL;
    assert_coons_ok(coons_body_new_bezier(p, dims, &b, &err), &err);
    free(p);
    return b;
}

static void test_bezier_cubic_exact(void **state)
{
    (void)state;
    double truth;
    coons_body *b = bezier_height(4, &truth); /* det J of degree 3: exact */
    check_bounded(b, truth, 1e-12, 0, 1e-12, NULL);
    coons_body_free(b);
}

/* Degree 32 x 32 x 1 (det J of degree 32 in u and v): converges within a
 * small budget, and the estimate holds at a budget too small to converge. */
static void test_bezier_large(void **state)
{
    (void)state;
    double truth;
    coons_body *b = bezier_height(33, &truth);
    size_t evals;
    check_bounded(b, truth, 1e-10, (size_t)1 << 16, 1e-10, &evals);
    check_bounded(b, truth, 1e-12, 4000, 0, NULL);
    coons_body_free(b);
}

/* Body 1 over a polyline of 150 segments (more vertices than the breakpoint
 * list holds, so the base cells do not follow them): det J jumps inside the
 * cells, the estimate never reaches 1e-9, and the work stays in the budget
 * with an estimate that bounds the error. */
static void test_polyline_body(void **state)
{
    (void)state;
    enum { NP = 151 };
    const double Ly = 3.0, Lz = 2.0;
    double *pts = malloc(NP * 3 * sizeof(double));
    assert_non_null(pts);
    tb_rng rng = {77};
    double x = 0;
    for (int k = 0; k < NP; k++) {
        pts[3 * k] = x;
        pts[3 * k + 1] = 0.3 * sin(0.7 * k);
        pts[3 * k + 2] = 0;
        x += 0.02 + 0.06 * tb_rand(&rng); /* uneven steps: x' jumps at every vertex */
    }
    double Lx = pts[3 * (NP - 1)] - pts[0];
    coons_error err = COONS_ERROR_INIT;
    coons_curve *e[12] = {0};
    double *q = malloc(NP * 3 * sizeof(double));
    assert_non_null(q);
    for (int n = 0; n < 4; n++) { /* uJK = P(u) + (0, J Ly, K Lz) */
        for (int k = 0; k < NP; k++) {
            q[3 * k] = pts[3 * k];
            q[3 * k + 1] = pts[3 * k + 1] + ((n >> 1) & 1) * Ly;
            q[3 * k + 2] = (n & 1) * Lz;
        }
        assert_coons_ok(coons_curve_new_polyline(q, NP, &e[n], &err), &err);
    }
    for (int n = 0; n < 4; n++) { /* vIK: straight, from P(I) + (0, 0, K Lz) */
        int I = (n >> 1) & 1, K = n & 1;
        const double *P = pts + 3 * (I ? NP - 1 : 0);
        double l[6] = {P[0], P[1], K * Lz, P[0], P[1] + Ly, K * Lz};
        assert_coons_ok(coons_curve_new_line(l, l + 3, &e[4 + n], &err), &err);
    }
    for (int n = 0; n < 4; n++) { /* wIJ: straight, from P(I) + (0, J Ly, 0) */
        int I = (n >> 1) & 1, J = n & 1;
        const double *P = pts + 3 * (I ? NP - 1 : 0);
        double l[6] = {P[0], P[1] + J * Ly, 0, P[0], P[1] + J * Ly, Lz};
        assert_coons_ok(coons_curve_new_line(l, l + 3, &e[8 + n], &err), &err);
    }
    coons_body *b = NULL;
    assert_coons_ok(coons_body_new_body1(e, COONS_BLEND_LINEAR, COONS_TOL_DEFAULT, &b, &err),
                    &err);
    /* the body is the translated polyline (checked at a few points) */
    tb_rng r2 = {5};
    for (int i = 0; i < 20; i++) {
        double u = tb_rand(&r2), v = tb_rand(&r2), w = tb_rand(&r2), y[3], c[3];
        coons_body_eval(b, u, v, w, y);
        coons_curve_eval(e[0], u, c);
        assert_near(y[0], c[0], 1e-12);
        assert_near(y[1], c[1] + v * Ly, 1e-12);
        assert_near(y[2], w * Lz, 1e-12);
    }
    double truth = Lx * Ly * Lz;
    size_t evals;
    for (size_t budget = 1000; budget <= (size_t)1 << 16; budget *= 2)
        check_bounded(b, truth, 1e-9, budget, 0, &evals);
    coons_body_free(b);
    for (int n = 0; n < 12; n++) coons_curve_free(e[n]);
    free(pts);
    free(q);
}

/* The polynomial tensor volumes' det J grid (contractions) agrees with
 * det J point by point (coons_body_eval_jacobian): the smallest over a
 * lattice, and where, as coons_body_min_jacobian() finds it. */
static void check_min_jacobian(const coons_body *b, unsigned n)
{
    coons_error err = COONS_ERROR_INIT;
    double mind = NAN, where[3];
    assert_coons_ok(coons_body_min_jacobian(b, n, &mind, where, &err), &err);
    double best = INFINITY, at[3] = {0, 0, 0}, scale = 0;
    for (unsigned i = 0; i <= n; i++)
        for (unsigned j = 0; j <= n; j++)
            for (unsigned k = 0; k <= n; k++) {
                double p[3], jac[3][3];
                double d = coons_body_eval_jacobian(b, (double)i / n, (double)j / n,
                                                    (double)k / n, p, jac);
                scale = fmax(scale, fabs(d));
                if (d < best) {
                    best = d;
                    at[0] = (double)i / n, at[1] = (double)j / n, at[2] = (double)k / n;
                }
            }
    assert_near(mind, best, 1e-12 * scale);
    for (int d = 0; d < 3; d++) assert_near(where[d], at[d], 1e-15);
}

static void test_tensor_det_grid(void **state)
{
    (void)state;
    double truth;
    coons_body *b = bezier_height(33, &truth);
    check_min_jacobian(b, 12);
    coons_body_free(b);
    /* a B-spline volume of degrees 3, 2, 1 over a perturbed grid */
    enum { NU = 6, NV = 5, NW = 3 };
    double pts[NU * NV * NW * 3];
    tb_rng rng = {99};
    for (int i = 0; i < NU; i++)
        for (int j = 0; j < NV; j++)
            for (int k = 0; k < NW; k++) {
                double *q = pts + 3 * ((i * NV + j) * NW + k);
                q[0] = i + 0.3 * tb_rand(&rng);
                q[1] = j + 0.3 * tb_rand(&rng) + 0.1 * i;
                q[2] = k + 0.3 * tb_rand(&rng);
            }
    const int deg[3] = {3, 2, 1};
    const size_t n[3] = {NU, NV, NW};
    const double ku[] = {0, 0, 0, 0, 0.2, 0.7, 1, 1, 1, 1};
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_bspline(deg, pts, n, ku, NULL, NULL, NULL, &b, &err), &err);
    check_min_jacobian(b, 16);
    coons_body_free(b);
}

static void test_null(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    double v;
    assert_int_equal(coons_body_volume_bounded(NULL, 0, 0, &v, NULL, NULL, &err),
                     COONS_E_INVALID);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_affine),
        cmocka_unit_test(test_bezier_cubic_exact),
        cmocka_unit_test(test_bezier_large),
        cmocka_unit_test(test_polyline_body),
        cmocka_unit_test(test_tensor_det_grid),
        cmocka_unit_test(test_null),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
