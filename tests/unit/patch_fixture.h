/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Test fixtures for the patch tests: a curved four-sided boundary made of
 * different curve kinds (Bezier, NURBS with an interior knot, open Coons
 * cubic B-spline, clamped cubic) meeting at four corners, and finite
 * difference checks. Static inline so each test uses what it needs. */
#ifndef COONS_PATCH_FIXTURE_H
#define COONS_PATCH_FIXTURE_H

#include <math.h>
#include <string.h>

#include "test_util.h"

/* Corners X00, X10, X01, X11 (index a + 2b). */
static const double fx_corner[4][3] = {
    {0.0, 0.0, 0.0}, {2.0, 0.0, 0.3}, {0.0, 2.0, -0.2}, {2.0, 2.0, 0.5}};

/* Interior sample parameters away from every knot of the fixture curves
 * (1/3, 1/2, 2/3) so central differences stay on one polynomial piece. */
static const double fx_par[5] = {0.13, 0.29, 0.41, 0.77, 0.92};

typedef struct fx_boundary {
    coons_curve *c[4]; /* T0, T1, S0, S1 */
} fx_boundary;

/* The boundary, translated by off (NULL: none). */
static inline void fx_boundary_make_off(fx_boundary *b, const double *off)
{
    coons_error err = COONS_ERROR_INIT;
    double X[4][3];
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < 3; i++) X[k][i] = fx_corner[k][i] + (off ? off[i] : 0.0);
    const double *X00 = X[0], *X10 = X[1], *X01 = X[2], *X11 = X[3];
    double o[3] = {off ? off[0] : 0.0, off ? off[1] : 0.0, off ? off[2] : 0.0};
    /* t0 = x(s,0): cubic Bezier X00 -> X10 */
    double t0[12] = {X00[0], X00[1], X00[2], 0.7 + o[0], -0.3 + o[1], 0.4 + o[2],
                     1.4 + o[0], 0.2 + o[1], -0.3 + o[2], X10[0], X10[1], X10[2]};
    assert_coons_ok(coons_curve_new_bezier(t0, 4, &b->c[COONS_SIDE_T0], &err), &err);
    /* t1 = x(s,1): quadratic NURBS X01 -> X11, interior knot at 1/2 */
    double t1[12] = {X01[0], X01[1], X01[2], 0.6 + o[0], 2.6 + o[1], 0.0 + o[2],
                     1.4 + o[0], 2.5 + o[1], 0.4 + o[2], X11[0], X11[1], X11[2]};
    double w1[4] = {1.0, 0.8, 1.3, 1.0};
    assert_coons_ok(coons_curve_new_bspline(2, t1, 4, NULL, w1, &b->c[COONS_SIDE_T1], &err), &err);
    /* s0 = x(0,t): open Coons cubic through X00 and X01: P1 = X00 with
     * P0 = 2 X00 - P2 gives (P0 + 4 P1 + P2)/6 = X00 (seed 002). */
    double a[3] = {-0.3 + o[0], 0.5 + o[1], 0.2 + o[2]}, c[3] = {0.4 + o[0], 1.3 + o[1], -0.4 + o[2]};
    double s0[18];
    for (int k = 0; k < 3; k++) {
        s0[k] = 2.0 * X00[k] - a[k];
        s0[3 + k] = X00[k];
        s0[6 + k] = a[k];
        s0[9 + k] = c[k];
        s0[12 + k] = X01[k];
        s0[15 + k] = 2.0 * X01[k] - c[k];
    }
    assert_coons_ok(coons_curve_new_coons_cubic(s0, 6, 0, &b->c[COONS_SIDE_S0], &err), &err);
    /* s1 = x(1,t): clamped cubic X10 -> X11 (interior knot at 1/2) */
    double s1[15] = {X10[0], X10[1], X10[2], 2.3 + o[0], 0.6 + o[1], 0.1 + o[2],
                     1.8 + o[0], 1.2 + o[1], 0.6 + o[2], 2.2 + o[0], 1.6 + o[1], 0.2 + o[2],
                     X11[0], X11[1], X11[2]};
    assert_coons_ok(coons_curve_new_clamped_cubic(s1, 5, &b->c[COONS_SIDE_S1], &err), &err);
}

static inline void fx_boundary_make(fx_boundary *b) { fx_boundary_make_off(b, NULL); }

static inline void fx_boundary_free(fx_boundary *b)
{
    for (int k = 0; k < 4; k++) coons_curve_free(b->c[k]);
}

static inline coons_curve *const *fx_curves(const fx_boundary *b)
{
    return b->c;
}

static inline double fx_scale(const double *v) { return 1.0 + fabs(v[0]) + fabs(v[1]) + fabs(v[2]); }

/* Checks all first and second partials of p at interior points against
 * central differences: first partials from coons_patch_eval, second
 * partials from differences of the first partials. */
static inline void fx_check_derivs_fd(const coons_patch *p, double tol)
{
    const double h = 1e-5;
    for (int i = 0; i < 5; i++) {
        for (int j = 0; j < 5; j++) {
            double s = fx_par[i], t = fx_par[j];
            double d[6][3], a[3], b[3], fd[3];
            coons_patch_eval_derivs(p, s, t, 2, d);
            double x[3];
            coons_patch_eval(p, s, t, x);
            assert_vec3_near(d[0], x, 0.0);
            /* x_s, x_t */
            coons_patch_eval(p, s + h, t, a);
            coons_patch_eval(p, s - h, t, b);
            for (int k = 0; k < 3; k++) fd[k] = (a[k] - b[k]) / (2 * h);
            assert_vec3_near(d[1], fd, tol * fx_scale(d[1]));
            coons_patch_eval(p, s, t + h, a);
            coons_patch_eval(p, s, t - h, b);
            for (int k = 0; k < 3; k++) fd[k] = (a[k] - b[k]) / (2 * h);
            assert_vec3_near(d[2], fd, tol * fx_scale(d[2]));
            /* x_ss, x_st (both ways), x_tt */
            double dp[3][3], dm[3][3];
            coons_patch_eval_derivs(p, s + h, t, 1, dp);
            coons_patch_eval_derivs(p, s - h, t, 1, dm);
            for (int k = 0; k < 3; k++) fd[k] = (dp[1][k] - dm[1][k]) / (2 * h);
            assert_vec3_near(d[3], fd, tol * fx_scale(d[3]));
            for (int k = 0; k < 3; k++) fd[k] = (dp[2][k] - dm[2][k]) / (2 * h);
            assert_vec3_near(d[4], fd, tol * fx_scale(d[4]));
            coons_patch_eval_derivs(p, s, t + h, 1, dp);
            coons_patch_eval_derivs(p, s, t - h, 1, dm);
            for (int k = 0; k < 3; k++) fd[k] = (dp[1][k] - dm[1][k]) / (2 * h);
            assert_vec3_near(d[4], fd, tol * fx_scale(d[4]));
            for (int k = 0; k < 3; k++) fd[k] = (dp[2][k] - dm[2][k]) / (2 * h);
            assert_vec3_near(d[5], fd, tol * fx_scale(d[5]));
            /* order 1 agrees with order 2 */
            double d1[3][3];
            coons_patch_eval_derivs(p, s, t, 1, d1);
            for (int k = 0; k < 3; k++) assert_vec3_near(d1[k], d[k], 0.0);
        }
    }
}

/* Grid over parameters including both ends equals pointwise evaluation
 * bit for bit. */
static inline void fx_check_grid(const coons_patch *p)
{
    coons_error err = COONS_ERROR_INIT;
    const double s[7] = {0.0, 0.05, 0.3333333333333333, 0.5, 0.61, 0.999, 1.0};
    const double t[6] = {1.0, 0.0, 0.25, 0.5, 0.6666666666666666, 0.87};
    double g[7 * 6 * 3];
    assert_coons_ok(coons_patch_eval_grid(p, s, 7, t, 6, g, &err), &err);
    for (int i = 0; i < 7; i++)
        for (int j = 0; j < 6; j++) {
            double x[3];
            coons_patch_eval(p, s[i], t[j], x);
            const double *y = g + (i * 6 + j) * 3;
            assert_vec3_near(y, x, 1e-12 * fx_scale(x));
            assert_memory_equal(y, x, sizeof x);
        }
}

#endif
