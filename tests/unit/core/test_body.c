/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Bodies of seed 000 section 2: body 0 (T), body 1 (C1), the tensor
 * volumes; body 2 lives in core/test_body2.c. Expected values are computed here
 * independently: affine maps and their exact volumes, trilinear and Coons
 * formulas written out, Cox-de Boor recursion, closed forms of a NURBS
 * cylinder, central finite differences for Jacobians.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "body_fixtures.h"

/* ---------- body 0 ---------- */

/* Affine map x = o + A q (q = (u,v,w)) and its 8 corners P_ijk. */
static const double AFF_O[3] = {1.0, -2.0, 0.5};
static const double AFF_A[3][3] = {{2.0, 0.5, 0.3}, {0.1, 3.0, -0.4}, {0.2, 0.0, 1.5}};

static void affine(const double o[3], const double A[3][3], const double q[3], double x[3])
{
    for (int r = 0; r < 3; r++) x[r] = o[r] + A[r][0] * q[0] + A[r][1] * q[1] + A[r][2] * q[2];
}

static void affine_corners(const double o[3], const double A[3][3], double c[8][3])
{
    for (int n = 0; n < 8; n++) {
        double q[3] = {n >> 2, (n >> 1) & 1, n & 1};
        affine(o, A, q, c[n]);
    }
}

static double det3(const double A[3][3])
{
    return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
           A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
           A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
}

static void test_body0_affine(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    double c[8][3];
    affine_corners(AFF_O, AFF_A, c);
    coons_body *b = NULL;
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err), &err);
    assert_int_equal(coons_body_kind(b), COONS_BODY_BODY0);
    tb_rng rng = {12345};
    for (int n = 0; n < 200; n++) {
        double q[3] = {tb_rand(&rng), tb_rand(&rng), tb_rand(&rng)}, x[3], y[3], jac[3][3];
        affine(AFF_O, AFF_A, q, x);
        coons_body_eval(b, q[0], q[1], q[2], y);
        assert_vec3_near(y, x, 1e-13);
        double det = coons_body_eval_jacobian(b, q[0], q[1], q[2], y, jac);
        assert_vec3_near(y, x, 1e-13);
        for (int r = 0; r < 3; r++)
            for (int s = 0; s < 3; s++) assert_near(jac[r][s], AFF_A[r][s], 1e-13);
        assert_near(det, det3(AFF_A), 1e-12);
    }
    /* Corners: T(P_ijk; i,j,k) = P_ijk at index 4i+2j+k. */
    for (int n = 0; n < 8; n++) {
        double y[3];
        coons_body_eval(b, n >> 2, (n >> 1) & 1, n & 1, y);
        assert_vec3_near(y, c[n], 0.0);
    }
    double vol = 0.0;
    assert_coons_ok(coons_body_volume(b, 1e-12, &vol, &err), &err);
    assert_near(vol, det3(AFF_A), 1e-12 * fabs(det3(AFF_A)));
    double lo[3], hi[3];
    coons_body_control_bbox(b, lo, hi);
    for (int n = 0; n < 8; n++)
        for (int r = 0; r < 3; r++) {
            assert_true(lo[r] <= c[n][r]);
            assert_true(hi[r] >= c[n][r]);
        }
    coons_body_free(b);
}

static void test_body0_box_volume(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    /* An axis box 2 x 3 x 5: volume 30. */
    const double o[3] = {-1, 4, 2}, A[3][3] = {{2, 0, 0}, {0, 3, 0}, {0, 0, 5}};
    double c[8][3];
    affine_corners(o, A, c);
    coons_body *b;
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err), &err);
    double vol;
    assert_coons_ok(coons_body_volume(b, 1e-10, &vol, &err), &err);
    assert_near(vol, 30.0, 1e-12);
    coons_body_free(b);
    /* A sheared parallelepiped: volume |det A| = 2*3*5 (shear keeps it). */
    const double S[3][3] = {{2, 1.5, -0.7}, {0, 3, 2.2}, {0, 0, 5}};
    affine_corners(o, S, c);
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err), &err);
    assert_coons_ok(coons_body_volume(b, 1e-10, &vol, &err), &err);
    assert_near(vol, 30.0, 1e-11);
    /* The cubic blend reparametrises each direction by 1-f(x) = 3x^2-2x^3,
     * a monotone map of [0,1] onto itself: same solid, same volume. */
    coons_body_free(b);
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_CUBIC, &b, &err), &err);
    assert_coons_ok(coons_body_volume(b, 1e-10, &vol, &err), &err);
    assert_near(vol, 30.0, 1e-9);
    coons_body_free(b);
}

/* Trilinear T written out with blend g (g0 = weight of the 0 side). */
static void blend_pair(coons_blend kind, double t, double g[2])
{
    if (kind == COONS_BLEND_CUBIC) {
        g[0] = 1.0 - 3.0 * t * t + 2.0 * t * t * t;
        g[1] = 1.0 - g[0];
    } else {
        g[0] = 1.0 - t;
        g[1] = t;
    }
}

static void trilinear_ref(const double c[8][3], coons_blend kind, double u, double v, double w,
                          double x[3])
{
    double a[2], b[2], e[2];
    blend_pair(kind, u, a);
    blend_pair(kind, v, b);
    blend_pair(kind, w, e);
    x[0] = x[1] = x[2] = 0.0;
    for (int n = 0; n < 8; n++)
        for (int r = 0; r < 3; r++) x[r] += a[n >> 2] * b[(n >> 1) & 1] * e[n & 1] * c[n][r];
}

static void test_body0_cubic(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_body *b;
    assert_coons_ok(coons_body_new_body0(tb_hex()[0], COONS_BLEND_CUBIC, &b, &err), &err);
    tb_rng rng = {7};
    for (int n = 0; n < 100; n++) {
        double u = tb_rand(&rng), v = tb_rand(&rng), w = tb_rand(&rng), x[3], y[3];
        trilinear_ref(tb_hex(), COONS_BLEND_CUBIC, u, v, w, x);
        coons_body_eval(b, u, v, w, y);
        assert_vec3_near(y, x, 1e-14);
    }
    /* Out-of-range parameters are clamped. */
    double y[3], z[3];
    coons_body_eval(b, -0.5, 2.0, 0.5, y);
    coons_body_eval(b, 0.0, 1.0, 0.5, z);
    assert_vec3_near(y, z, 0.0);
    coons_body_free(b);
}

static void test_body0_folded(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    double c[8][3];
    const double I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, o[3] = {0, 0, 0};
    affine_corners(o, I, c);
    coons_body *b;
    double m, where[3];
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err), &err);
    assert_coons_ok(coons_body_min_jacobian(b, 4, &m, where, &err), &err);
    assert_near(m, 1.0, 1e-14);
    coons_body_free(b);
    /* Push P111 through the face w = 0: at (1,1,1), d/dw = P111 - P110 points down. */
    c[7][2] = -0.5;
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err), &err);
    assert_coons_ok(coons_body_min_jacobian(b, 4, &m, where, &err), &err);
    assert_true(m < 0.0);
    /* det J at (1,1,1): d_u = (1,0,0), d_v = (0,1,0), d_w = (0,0,-0.5). */
    assert_near(m, -0.5, 1e-14);
    double y[3], jac[3][3];
    assert_near(coons_body_eval_jacobian(b, where[0], where[1], where[2], y, jac), m, 0.0);
    assert_near(where[0], 1.0, 0.0);
    assert_near(where[1], 1.0, 0.0);
    assert_int_equal(coons_body_min_jacobian(b, 0, &m, where, &err), COONS_E_INVALID);
    coons_body_free(b);
}

static void test_body0_invalid(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    double c[8][3];
    memcpy(c, tb_hex(), sizeof c);
    c[5][1] = NAN;
    coons_body *b = (coons_body *)&err;
    assert_int_equal(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err),
                     COONS_E_INVALID);
    assert_null(b);
    assert_non_null(strstr(err.message, "P101"));
    assert_int_equal(coons_body_new_body0(tb_hex()[0], (coons_blend)7, &b, &err), COONS_E_INVALID);
    coons_body_free(NULL);
}

/* ---------- body 1 ---------- */

/* Straight edges of a hexahedron, in body.h order. */
static void hex_edges(const double c[8][3], coons_curve *e[12])
{
    coons_error err = COONS_ERROR_INIT;
    for (int j = 0; j < 2; j++)
        for (int k = 0; k < 2; k++) {
            assert_coons_ok(coons_curve_new_line(c[2 * j + k], c[4 + 2 * j + k], &e[2 * j + k], &err),
                            &err);
        }
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 2; k++)
            assert_coons_ok(
                coons_curve_new_line(c[4 * i + k], c[4 * i + 2 + k], &e[4 + 2 * i + k], &err), &err);
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            assert_coons_ok(coons_curve_new_line(c[4 * i + 2 * j], c[4 * i + 2 * j + 1],
                                                 &e[8 + 2 * i + j], &err),
                            &err);
}

static void free_edges(coons_curve *e[12])
{
    for (int n = 0; n < 12; n++) coons_curve_free(e[n]);
}

static void test_body1_straight_is_body0(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_curve *e[12];
    hex_edges(tb_hex(), e);
    coons_body *b1, *b0, *b1c, *b0c;
    assert_coons_ok(coons_body_new_body1(e, COONS_BLEND_LINEAR,
                                         COONS_TOL_DEFAULT, &b1, &err),
                    &err);
    assert_coons_ok(coons_body_new_body0(tb_hex()[0], COONS_BLEND_LINEAR, &b0, &err), &err);
    assert_coons_ok(coons_body_new_body1(e, COONS_BLEND_CUBIC,
                                         COONS_TOL_DEFAULT, &b1c, &err),
                    &err);
    assert_coons_ok(coons_body_new_body0(tb_hex()[0], COONS_BLEND_CUBIC, &b0c, &err), &err);
    tb_rng rng = {99};
    double maxdiff = 0.0;
    for (int n = 0; n < 200; n++) {
        double u = tb_rand(&rng), v = tb_rand(&rng), w = tb_rand(&rng), x[3], y[3];
        coons_body_eval(b0, u, v, w, x);
        coons_body_eval(b1, u, v, w, y);
        assert_vec3_near(y, x, 1e-14);
        /* Seed 000 eq. of C1 written out with the cubic blend and straight
         * edges: the edges stay linear in their own parameter. */
        double a[2], bb[2], g[2], ref[3] = {0, 0, 0}, t[3];
        blend_pair(COONS_BLEND_CUBIC, u, a);
        blend_pair(COONS_BLEND_CUBIC, v, bb);
        blend_pair(COONS_BLEND_CUBIC, w, g);
        double lu[2] = {1 - u, u}, lv[2] = {1 - v, v}, lw[2] = {1 - w, w};
        for (int n8 = 0; n8 < 8; n8++) {
            int i = n8 >> 2, j = (n8 >> 1) & 1, k = n8 & 1;
            double f = a[i] * bb[j] * lw[k] + a[i] * lv[j] * g[k] + lu[i] * bb[j] * g[k];
            for (int r = 0; r < 3; r++) ref[r] += f * tb_hex()[n8][r];
        }
        trilinear_ref(tb_hex(), COONS_BLEND_CUBIC, u, v, w, t);
        for (int r = 0; r < 3; r++) ref[r] -= 2.0 * t[r];
        coons_body_eval(b1c, u, v, w, y);
        assert_vec3_near(y, ref, 1e-13);
        coons_body_eval(b0c, u, v, w, x);
        maxdiff = fmax(maxdiff, fmax(fabs(x[0] - y[0]), fmax(fabs(x[1] - y[1]), fabs(x[2] - y[2]))));
    }
    /* Seed 000's "body 1 with straight edges is body 0" needs the linear blend. */
    assert_true(maxdiff > 1e-3);
    coons_body_free(b0);
    coons_body_free(b1);
    coons_body_free(b0c);
    coons_body_free(b1c);
    free_edges(e);
}

/* Coons patch of seed 001 eq. 1.8 with blend `kind`, written out:
 * t0 = x(s,0), t1 = x(s,1), s0 = x(0,t), s1 = x(1,t). */
static void coons_patch_ref(const coons_curve *t0, const coons_curve *t1, const coons_curve *s0,
                            const coons_curve *s1, coons_blend kind, double s, double t,
                            double x[3])
{
    double a[2], b[2], c0[3], c1[3], d0[3], d1[3], p00[3], p10[3], p01[3], p11[3];
    blend_pair(kind, s, a);
    blend_pair(kind, t, b);
    coons_curve_eval(t0, s, c0);
    coons_curve_eval(t1, s, c1);
    coons_curve_eval(s0, t, d0);
    coons_curve_eval(s1, t, d1);
    coons_curve_eval(t0, 0, p00);
    coons_curve_eval(t0, 1, p10);
    coons_curve_eval(t1, 0, p01);
    coons_curve_eval(t1, 1, p11);
    for (int r = 0; r < 3; r++)
        x[r] = b[0] * c0[r] + b[1] * c1[r] + a[0] * d0[r] + a[1] * d1[r] -
               (a[0] * b[0] * p00[r] + a[1] * b[0] * p10[r] + a[0] * b[1] * p01[r] +
                a[1] * b[1] * p11[r]);
}

static void test_body1_boundary(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_curve *e[12];
    assert_coons_ok(tb_curved_edges(e, &err), &err);
    for (int kind = 0; kind < 2; kind++) {
        coons_body *b;
        assert_coons_ok(coons_body_new_body1(e, (coons_blend)kind,
                                             COONS_TOL_DEFAULT, &b, &err),
                        &err);
        assert_int_equal(coons_body_kind(b), COONS_BODY_BODY1);
        tb_rng rng = {5};
        for (int n = 0; n < 40; n++) {
            double p = tb_rand(&rng), q = tb_rand(&rng), x[3], y[3];
            /* Faces: u = I is the Coons patch of v-edges vI0 (w=0), vI1 and
             * w-edges wI0 (v=0), wI1; patch (s,t) = (v,w). */
            for (int I = 0; I < 2; I++) {
                coons_patch_ref(e[4 + 2 * I], e[4 + 2 * I + 1], e[8 + 2 * I], e[8 + 2 * I + 1],
                                (coons_blend)kind, p, q, x);
                coons_body_eval(b, I, p, q, y);
                assert_vec3_near(y, x, 1e-13);
                /* v = J: (s,t) = (u,w): t0 = u-edge uJ0, t1 = uJ1, s0 = w0J, s1 = w1J. */
                coons_patch_ref(e[2 * I], e[2 * I + 1], e[8 + I], e[10 + I], (coons_blend)kind,
                                p, q, x);
                coons_body_eval(b, p, I, q, y);
                assert_vec3_near(y, x, 1e-13);
                /* w = K: (s,t) = (u,v): t0 = u0K, t1 = u1K, s0 = v0K, s1 = v1K. */
                coons_patch_ref(e[I], e[2 + I], e[4 + I], e[6 + I], (coons_blend)kind, p, q, x);
                coons_body_eval(b, p, q, I, y);
                assert_vec3_near(y, x, 1e-13);
            }
            /* Edges. */
            for (int x1 = 0; x1 < 2; x1++)
                for (int x2 = 0; x2 < 2; x2++) {
                    coons_curve_eval(e[2 * x1 + x2], p, x);
                    coons_body_eval(b, p, x1, x2, y);
                    assert_vec3_near(y, x, 1e-14);
                    coons_curve_eval(e[4 + 2 * x1 + x2], p, x);
                    coons_body_eval(b, x1, p, x2, y);
                    assert_vec3_near(y, x, 1e-14);
                    coons_curve_eval(e[8 + 2 * x1 + x2], p, x);
                    coons_body_eval(b, x1, x2, p, y);
                    assert_vec3_near(y, x, 1e-14);
                }
        }
        coons_body_free(b);
    }
    free_edges(e);
}

static void test_body1_incompatible(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_curve *e[12];
    hex_edges(tb_hex(), e);
    /* Move the far end of v10 = C(1,v,0), which should be C110. */
    double p0[3], p1[3];
    coons_curve_eval(e[6], 0, p0);
    coons_curve_eval(e[6], 1, p1);
    p1[2] += 0.3;
    coons_curve_free(e[6]);
    assert_coons_ok(coons_curve_new_line(p0, p1, &e[6], &err), &err);
    coons_body *b = (coons_body *)&err;
    assert_int_equal(coons_body_new_body1(e, COONS_BLEND_LINEAR,
                                          COONS_TOL_DEFAULT, &b, &err),
                     COONS_E_INCOMPATIBLE);
    assert_null(b);
    assert_int_equal(err.code, COONS_E_INCOMPATIBLE);
    assert_non_null(strstr(err.message, "C110"));
    assert_non_null(strstr(err.message, "v10"));
    assert_non_null(strstr(err.message, "0.3"));
    /* A tolerance above the gap accepts it; the corner is the average. */
    assert_coons_ok(coons_body_new_body1(e, COONS_BLEND_LINEAR, 0.5, &b,
                                         &err),
                    &err);
    double y[3];
    coons_body_eval(b, 1, 1, 0, y);
    assert_near(y[2], tb_hex()[6][2] + 0.1, 1e-14);
    coons_body_free(b);
    coons_curve_free(e[3]);
    e[3] = NULL;
    assert_int_equal(coons_body_new_body1(e, COONS_BLEND_LINEAR,
                                          COONS_TOL_DEFAULT, &b, &err),
                     COONS_E_INVALID);
    assert_non_null(strstr(err.message, "u11"));
    free_edges(e);
}

/* ---------- tensor volumes ---------- */

static double binom(int n, int k)
{
    double r = 1.0;
    for (int i = 1; i <= k; i++) r = r * (n - k + i) / i;
    return r;
}

static double bern(int n, int i, double t) { return binom(n, i) * pow(t, i) * pow(1 - t, n - i); }

static void test_bezier_volume(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    size_t n[3] = {3, 4, 2};
    double P[3 * 4 * 2 * 3];
    tb_rng rng = {31};
    for (size_t m = 0; m < sizeof P / sizeof P[0]; m++) P[m] = tb_rand(&rng) * 4.0 - 2.0;
    coons_body *b;
    assert_coons_ok(coons_body_new_bezier(P, n, &b, &err), &err);
    assert_int_equal(coons_body_kind(b), COONS_BODY_BEZIER);
    for (int t = 0; t < 50; t++) {
        double u = tb_rand(&rng), v = tb_rand(&rng), w = tb_rand(&rng), x[3] = {0, 0, 0}, y[3];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 4; j++)
                for (int k = 0; k < 2; k++) {
                    double f = bern(2, i, u) * bern(3, j, v) * bern(1, k, w);
                    for (int r = 0; r < 3; r++) x[r] += f * P[((i * 4 + j) * 2 + k) * 3 + r];
                }
        coons_body_eval(b, u, v, w, y);
        assert_vec3_near(y, x, 1e-13);
    }
    coons_body_free(b);
    /* Degree (1,1,1) is body 0 on the same corners. */
    size_t n2[3] = {2, 2, 2};
    coons_body *b0;
    assert_coons_ok(coons_body_new_bezier(&tb_hex()[0][0], n2, &b, &err), &err);
    assert_coons_ok(coons_body_new_body0(tb_hex()[0], COONS_BLEND_LINEAR, &b0, &err), &err);
    for (int t = 0; t < 20; t++) {
        double u = tb_rand(&rng), v = tb_rand(&rng), w = tb_rand(&rng), x[3], y[3];
        coons_body_eval(b0, u, v, w, x);
        coons_body_eval(b, u, v, w, y);
        assert_vec3_near(y, x, 1e-14);
    }
    coons_body_free(b);
    coons_body_free(b0);
    size_t bad[3] = {1, 2, 2};
    assert_int_equal(coons_body_new_bezier(P, bad, &b, &err), COONS_E_INVALID);
}

/* Cox-de Boor recursion, straight from the definition (0/0 = 0). */
static double cox(const double *k, int i, int p, double x)
{
    if (p == 0) return (k[i] <= x && x < k[i + 1]) ? 1.0 : 0.0;
    double a = 0.0, b = 0.0;
    if (k[i + p] > k[i]) a = (x - k[i]) / (k[i + p] - k[i]) * cox(k, i, p - 1, x);
    if (k[i + p + 1] > k[i + 1]) b = (k[i + p + 1] - x) / (k[i + p + 1] - k[i + 1]) * cox(k, i + 1, p - 1, x);
    return a + b;
}

static void test_bspline_volume(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    int deg[3] = {2, 3, 1};
    size_t n[3] = {5, 6, 3};
    double ku[8] = {0, 0, 0, 0.5, 1.5, 2, 2, 2};              /* domain [0,2] */
    double kv[10] = {-1, -1, -1, -1, 0, 0.25, 1, 1, 1, 1};    /* domain [-1,1] */
    double kw[5] = {0, 0, 0.3, 1, 1};
    const double *kn[3] = {ku, kv, kw};
    size_t np = 5 * 6 * 3;
    double *P = malloc(np * 3 * sizeof *P), *W = malloc(np * sizeof *W);
    tb_rng rng = {77};
    for (size_t m = 0; m < np * 3; m++) P[m] = tb_rand(&rng) * 2.0 - 1.0;
    for (size_t m = 0; m < np; m++) W[m] = 0.5 + tb_rand(&rng);
    for (int rational = 0; rational < 2; rational++) {
        coons_body *b;
        assert_coons_ok(coons_body_new_bspline(deg, P, n, kn[0], kn[1], kn[2], rational ? W : NULL, &b, &err), &err);
        assert_int_equal(coons_body_kind(b), COONS_BODY_BSPLINE);
        for (int t = 0; t < 60; t++) {
            double u = tb_rand(&rng), v = tb_rand(&rng), w = tb_rand(&rng);
            double x = 2.0 * u, yv = -1.0 + 2.0 * v, z = w, ref[3] = {0, 0, 0}, den = 0.0, y[3];
            for (int i = 0; i < 5; i++)
                for (int j = 0; j < 6; j++)
                    for (int k = 0; k < 3; k++) {
                        size_t idx = ((size_t)i * 6 + j) * 3 + k;
                        double f = cox(ku, i, 2, x) * cox(kv, j, 3, yv) * cox(kw, k, 1, z) *
                                   (rational ? W[idx] : 1.0);
                        den += f;
                        for (int r = 0; r < 3; r++) ref[r] += f * P[3 * idx + r];
                    }
            for (int r = 0; r < 3; r++) ref[r] /= den;
            coons_body_eval(b, u, v, w, y);
            assert_vec3_near(y, ref, 1e-13);
        }
        coons_body_free(b);
    }
    /* Clamped default knots with every degree one less than the count: a Bezier volume. */
    int dz[3] = {2, 3, 1};
    size_t nz[3] = {3, 4, 2};
    coons_body *bs, *bz;
    assert_coons_ok(coons_body_new_bspline(dz, P, nz, NULL, NULL, NULL, NULL, &bs, &err), &err);
    assert_coons_ok(coons_body_new_bezier(P, nz, &bz, &err), &err);
    for (int t = 0; t < 20; t++) {
        double u = tb_rand(&rng), v = tb_rand(&rng), w = tb_rand(&rng), x[3], y[3];
        coons_body_eval(bs, u, v, w, x);
        coons_body_eval(bz, u, v, w, y);
        assert_vec3_near(y, x, 1e-14);
    }
    coons_body_free(bs);
    coons_body_free(bz);
    /* Invalid input. */
    coons_body *b;
    W[7] = 0.0;
    assert_int_equal(coons_body_new_bspline(deg, P, n, kn[0], kn[1], kn[2], W, &b, &err), COONS_E_INVALID);
    assert_null(b);
    assert_non_null(strstr(err.message, "weight"));
    W[7] = 1e300; /* the others are near 1 */
    assert_int_equal(coons_body_new_bspline(deg, P, n, kn[0], kn[1], kn[2], W, &b, &err), COONS_E_LIMIT);
    assert_null(b);
    assert_non_null(strstr(err.message, "ratio"));
    ku[4] = 0.1; /* decreasing */
    assert_int_equal(coons_body_new_bspline(deg, P, n, kn[0], kn[1], kn[2], NULL, &b, &err), COONS_E_INVALID);
    int d0[3] = {0, 1, 1};
    assert_int_equal(coons_body_new_bspline(d0, P, n, NULL, NULL, NULL, NULL, &b, &err), COONS_E_INVALID);
    size_t huge[3] = {1u << 12, 1u << 12, 1u << 12};
    assert_int_equal(coons_body_new_bspline(deg, P, huge, NULL, NULL, NULL, NULL, &b, &err), COONS_E_LIMIT);
    P[4] = INFINITY;
    assert_int_equal(coons_body_new_bspline(deg, P, n, NULL, NULL, NULL, NULL, &b, &err), COONS_E_INVALID);
    free(P);
    free(W);
}

static void test_nurbs_cylinder(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    const double r = 1.5, h = 2.5;
    coons_body *b;
    tb_nurbs_cylinder(r, h, &b);
    tb_rng rng = {3};
    for (int t = 0; t < 50; t++) {
        double u = tb_rand(&rng), w = tb_rand(&rng), y[3];
        coons_body_eval(b, u, 1.0, w, y);
        assert_near(hypot(y[0], y[1]), r, 1e-14);
        assert_near(y[2], h * w, 1e-14);
        coons_body_eval(b, u, 0.0, w, y);
        assert_near(hypot(y[0], y[1]), 0.0, 1e-15);
    }
    double vol;
    assert_coons_ok(coons_body_volume(b, 1e-10, &vol, &err), &err);
    double exact = M_PI * r * r * h;
    assert_true(fabs(fabs(vol) - exact) <= 1e-6 * exact);
    coons_body_free(b);
}

/* Given the NURBS cylinder of radius 1.5e9 with every weight multiplied by
 * 1e300 (w P alone would overflow) or 1e-300, then it is
 * still the cylinder, and its Jacobian agrees with the unscaled one. */
static void test_nurbs_weight_scale(void **state)
{
    (void)state;
    const double r = 1.5e9, h = 2.5e9, scales[] = {1e300, 1e-300};
    coons_body *ref;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(tb_nurbs_cylinder_scaled_rc(r, h, 1.0, &ref, &err), &err);
    for (size_t k = 0; k < sizeof scales / sizeof scales[0]; k++) {
        coons_body *b;
        assert_coons_ok(tb_nurbs_cylinder_scaled_rc(r, h, scales[k], &b, &err), &err);
        tb_rng rng = {5};
        for (int t = 0; t < 50; t++) {
            double u = tb_rand(&rng), v = tb_rand(&rng), w = tb_rand(&rng), y[3], y0[3];
            double J[3][3], J0[3][3];
            double det = coons_body_eval_jacobian(b, u, v, w, y, J);
            double det0 = coons_body_eval_jacobian(ref, u, v, w, y0, J0);
            assert_near(hypot(y[0], y[1]) / r, v, 1e-14);
            assert_near(y[2] / h, w, 1e-14);
            assert_near(det / det0, 1.0, 1e-12);
        }
        coons_body_free(b);
    }
    coons_body_free(ref);
}

/* F = (X(u), Y(v), Z(w) + H(u,v)) has det J = X' Y' Z', so its volume is
 * (X(1)-X(0)) (Y(1)-Y(0)) (Z(1)-Z(0)) whatever H. Built as a B-spline
 * volume with uneven knots: x, y on Greville abscissae (linear X, Y), z
 * any increasing sequence plus a shear h_ij. Z' jumps at the w knots (degree
 * 2), so only knot-aligned cells integrate it exactly. */
static void test_bspline_volume_exact(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    int deg[3] = {3, 2, 2};
    size_t n[3] = {6, 5, 5};
    double ku[10] = {0, 0, 0, 0, 0.3, 0.37, 1, 1, 1, 1};
    double kv[8] = {0, 0, 0, 0.21, 0.8, 1, 1, 1};
    double kw[8] = {0, 0, 0, 0.13, 0.55, 1, 1, 1};
    const double *kn[3] = {ku, kv, kw};
    const double zeta[5] = {0.0, 0.1, 0.9, 1.0, 2.5};
    double P[6 * 5 * 5 * 3];
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 5; j++)
            for (int k = 0; k < 5; k++) {
                double *p = P + ((i * 5 + j) * 5 + k) * 3;
                p[0] = 2.0 * (ku[i + 1] + ku[i + 2] + ku[i + 3]) / 3.0;
                p[1] = 3.0 * (kv[j + 1] + kv[j + 2]) / 2.0;
                p[2] = zeta[k] + 0.3 * sin(1.0 + i * j);
            }
    coons_body *b;
    assert_coons_ok(coons_body_new_bspline(deg, P, n, kn[0], kn[1], kn[2], NULL, &b, &err), &err);
    /* X, Y linear: x = 2u, y = 3v. */
    double y[3];
    coons_body_eval(b, 0.4, 0.7, 0.5, y);
    assert_near(y[0], 0.8, 1e-14);
    assert_near(y[1], 2.1, 1e-14);
    double vol;
    assert_coons_ok(coons_body_volume(b, 1e-13, &vol, &err), &err);
    assert_near(vol, 2.0 * 3.0 * 2.5, 1e-12);
    coons_body_free(b);
}

/* ---------- shared properties over every type ---------- */

static void test_jacobian_fd(void **state)
{
    (void)state;
    coons_body *bodies[TB_MAX_BODIES];
    int nb = tb_all_bodies(bodies);
    for (int m = 0; m < nb; m++) {
        tb_rng rng = {1000u + (unsigned)m};
        for (int t = 0; t < 20; t++) {
            /* Stay away from the knots of the B-spline samples (kinks in
             * derivatives of lower continuity would spoil the difference). */
            double q[3] = {0.05 + 0.9 * tb_rand(&rng), 0.05 + 0.9 * tb_rand(&rng),
                           0.05 + 0.9 * tb_rand(&rng)};
            double x[3], jac[3][3], hstep = 1e-6;
            double det = coons_body_eval_jacobian(bodies[m], q[0], q[1], q[2], x, jac);
            double y[3];
            coons_body_eval(bodies[m], q[0], q[1], q[2], y);
            assert_vec3_near(x, y, 1e-14);
            double fd[3][3];
            for (int c = 0; c < 3; c++) {
                double qa[3] = {q[0], q[1], q[2]}, qb[3] = {q[0], q[1], q[2]}, pa[3], pb[3];
                qa[c] += hstep;
                qb[c] -= hstep;
                coons_body_eval(bodies[m], qa[0], qa[1], qa[2], pa);
                coons_body_eval(bodies[m], qb[0], qb[1], qb[2], pb);
                for (int r = 0; r < 3; r++) fd[r][c] = (pa[r] - pb[r]) / (2 * hstep);
            }
            for (int r = 0; r < 3; r++)
                for (int c = 0; c < 3; c++)
                    if (fabs(fd[r][c] - jac[r][c]) > 1e-6 * (1.0 + fabs(fd[r][c])))
                        fail_msg("body %d (%s) at (%g,%g,%g): jac[%d][%d] = %.12g, FD %.12g", m,
                                 tb_body_label(m), q[0], q[1], q[2], r, c, jac[r][c], fd[r][c]);
            double dd = fd[0][0] * (fd[1][1] * fd[2][2] - fd[1][2] * fd[2][1]) -
                        fd[0][1] * (fd[1][0] * fd[2][2] - fd[1][2] * fd[2][0]) +
                        fd[0][2] * (fd[1][0] * fd[2][1] - fd[1][1] * fd[2][0]);
            assert_near(det, dd, 1e-5 * (1.0 + fabs(dd)));
        }
        coons_body_free(bodies[m]);
    }
}

static void test_grid_matches_points(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_body *bodies[TB_MAX_BODIES];
    int nb = tb_all_bodies(bodies);
    /* Unsorted, repeated, exact ends and out-of-range values (clamped). */
    double u[7] = {0.0, 0.31, 1.0, -0.2, 0.5, 0.5, 0.97};
    double v[5] = {1.0, 0.0, 0.123, 0.77, 1.3};
    double w[6] = {0.0, 0.25, 0.5, 0.6, 0.999, 1.0};
    double out[7 * 5 * 6 * 3];
    for (int m = 0; m < nb; m++) {
        assert_coons_ok(coons_body_eval_grid(bodies[m], u, 7, v, 5, w, 6, out, &err), &err);
        for (size_t i = 0; i < 7; i++)
            for (size_t j = 0; j < 5; j++)
                for (size_t k = 0; k < 6; k++) {
                    double y[3];
                    coons_body_eval(bodies[m], u[i], v[j], w[k], y);
                    const double *g = out + ((i * 5 + j) * 6 + k) * 3;
                    if (fabs(g[0] - y[0]) > 1e-12 || fabs(g[1] - y[1]) > 1e-12 ||
                        fabs(g[2] - y[2]) > 1e-12)
                        fail_msg("body %d (%s) grid (%zu,%zu,%zu): (%.17g %.17g %.17g) vs "
                                 "(%.17g %.17g %.17g)",
                                 m, tb_body_label(m), i, j, k, g[0], g[1], g[2], y[0], y[1], y[2]);
                }
        /* A grid with one u value samples a face. */
        double face[5 * 6 * 3];
        assert_coons_ok(coons_body_eval_grid(bodies[m], u + 2, 1, v, 5, w, 6, face, &err), &err);
        for (size_t n = 0; n < 5 * 6 * 3; n++) assert_near(face[n], out[2 * 5 * 6 * 3 + n], 1e-13);
        /* Empty grids are fine; overflowing ones are refused. */
        assert_coons_ok(coons_body_eval_grid(bodies[m], u, 0, v, 5, w, 6, out, &err), &err);
        size_t big = (size_t)1 << (sizeof(size_t) * 4);
        assert_int_equal(coons_body_eval_grid(bodies[m], u, big, v, big, w, 6, out, &err),
                         COONS_E_LIMIT);
        coons_body_free(bodies[m]);
    }
}

/* coons_body_eval_points: bitwise coons_body_eval() point by point, and
 * coons_body_eval_jacobian() with the Jacobians; bad arguments refused. */
static void test_eval_points(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_body *bodies[TB_MAX_BODIES];
    int nb = tb_all_bodies(bodies);
    enum { N = 40 };
    double uvw[3 * N], xyz[3 * N], xj[3 * N], jac[9 * N], det[N];
    for (int m = 0; m < nb; m++) {
        tb_rng rng = {77u + (unsigned)m};
        for (int i = 0; i < 3 * N; i++) uvw[i] = 1.2 * tb_rand(&rng) - 0.1; /* some clamped */
        assert_coons_ok(coons_body_eval_points(bodies[m], N, uvw, xyz, NULL, NULL, &err), &err);
        assert_coons_ok(coons_body_eval_points(bodies[m], N, uvw, xj, jac, det, &err), &err);
        for (int i = 0; i < N; i++) {
            double y[3], x[3], J[3][3];
            const double *q = uvw + 3 * i;
            coons_body_eval(bodies[m], q[0], q[1], q[2], y);
            if (memcmp(y, xyz + 3 * i, sizeof y))
                fail_msg("body %d (%s) point %d differs from coons_body_eval", m,
                         tb_body_label(m), i);
            double d = coons_body_eval_jacobian(bodies[m], q[0], q[1], q[2], x, J);
            if (memcmp(x, xj + 3 * i, sizeof x) || memcmp(J, jac + 9 * i, sizeof J) ||
                memcmp(&d, det + i, sizeof d))
                fail_msg("body %d (%s) point %d differs from coons_body_eval_jacobian", m,
                         tb_body_label(m), i);
        }
        /* det alone, no Jacobian array: the same determinants */
        double det2[N];
        assert_coons_ok(coons_body_eval_points(bodies[m], N, uvw, xj, NULL, det2, &err), &err);
        assert_memory_equal(det2, det, sizeof det);
        assert_int_equal(coons_body_eval_points(bodies[m], N, NULL, xyz, NULL, NULL, &err),
                         COONS_E_INVALID);
        assert_int_equal(coons_body_eval_points(bodies[m], N, uvw, NULL, jac, NULL, &err),
                         COONS_E_INVALID);
        assert_coons_ok(coons_body_eval_points(bodies[m], 0, NULL, NULL, NULL, NULL, &err), &err);
        coons_body_free(bodies[m]);
    }
    assert_int_equal(coons_body_eval_points(NULL, 1, uvw, xyz, NULL, NULL, &err),
                     COONS_E_INVALID);
}

/* coons_body_min_jacobian (tabulated det J, a separate path for body 2)
 * against det J point by point on the same lattice. */
static void test_min_jacobian_matches_points(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_body *bodies[TB_MAX_BODIES];
    int nb = tb_all_bodies(bodies);
    const unsigned n = 6;
    for (int m = 0; m < nb; m++) {
        double best = INFINITY;
        for (unsigned i = 0; i <= n; i++)
            for (unsigned j = 0; j <= n; j++)
                for (unsigned k = 0; k <= n; k++) {
                    double p[3], jac[3][3];
                    double d = coons_body_eval_jacobian(bodies[m], (double)i / n, (double)j / n,
                                                        (double)k / n, p, jac);
                    if (d < best) best = d;
                }
        double mj, where[3];
        assert_coons_ok(coons_body_min_jacobian(bodies[m], n, &mj, where, &err), &err);
        if (fabs(mj - best) > 1e-11 * (1.0 + fabs(best)))
            fail_msg("body %d (%s): min det %.17g, pointwise %.17g", m, tb_body_label(m), mj,
                     best);
        double p[3], jac[3][3];
        assert_near(coons_body_eval_jacobian(bodies[m], where[0], where[1], where[2], p, jac), mj,
                    1e-11 * (1.0 + fabs(mj)));
        coons_body_free(bodies[m]);
    }
}

static void test_copy(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_body *bodies[TB_MAX_BODIES];
    int nb = tb_all_bodies(bodies);
    for (int m = 0; m < nb; m++) {
        coons_body *c;
        assert_coons_ok(coons_body_copy(bodies[m], &c, &err), &err);
        assert_int_equal(coons_body_kind(c), coons_body_kind(bodies[m]));
        double lo[3], hi[3], lo2[3], hi2[3];
        coons_body_control_bbox(bodies[m], lo, hi);
        coons_body_control_bbox(c, lo2, hi2);
        assert_vec3_near(lo, lo2, 0.0);
        assert_vec3_near(hi, hi2, 0.0);
        coons_body_free(bodies[m]);
        tb_rng rng = {4};
        for (int t = 0; t < 10; t++) {
            double q[3] = {tb_rand(&rng), tb_rand(&rng), tb_rand(&rng)}, y[3];
            coons_body_eval(c, q[0], q[1], q[2], y);
            assert_true(isfinite(y[0]) && isfinite(y[1]) && isfinite(y[2]));
        }
        coons_body_free(c);
    }
}

/* Every allocation of every constructor, copy and grid fails in turn:
 * COONS_E_NOMEM each time, nothing leaks (run under valgrind). */
static void test_alloc_failures(void **state)
{
    (void)state;
    for (int m = 0; m < TB_MAX_BODIES; m++) {
        int done = 0;
        for (long n = 0; !done && n < 10000; n++) {
            coons_test_fail_after(n);
            coons_error err = COONS_ERROR_INIT;
            coons_body *b = NULL, *c = NULL;
            int rc = tb_make_body(m, &b, &err);
            if (rc == TB_NO_BODY) {
                coons_test_fail_after(-1);
                done = 1;
                break;
            }
            if (rc == COONS_OK) rc = coons_body_copy(b, &c, &err);
            double u[3] = {0, 0.4, 1}, out[3 * 3 * 3 * 3];
            if (rc == COONS_OK) rc = coons_body_eval_grid(c, u, 3, u, 3, u, 3, out, &err);
            double vol;
            if (rc == COONS_OK) rc = coons_body_volume(b, 1e-3, &vol, &err);
            coons_test_fail_after(-1);
            coons_body_free(b);
            coons_body_free(c);
            if (rc == COONS_OK)
                done = 1;
            else if (rc != COONS_E_NOMEM)
                fail_msg("body %d, allocation %ld: status %d (%s)", m, n, rc, err.message);
            else
                assert_int_equal(err.code, COONS_E_NOMEM);
        }
        assert_true(done);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_body0_affine),
        cmocka_unit_test(test_body0_box_volume),
        cmocka_unit_test(test_body0_cubic),
        cmocka_unit_test(test_body0_folded),
        cmocka_unit_test(test_body0_invalid),
        cmocka_unit_test(test_body1_straight_is_body0),
        cmocka_unit_test(test_body1_boundary),
        cmocka_unit_test(test_body1_incompatible),
        cmocka_unit_test(test_bezier_volume),
        cmocka_unit_test(test_bspline_volume),
        cmocka_unit_test(test_nurbs_cylinder),
        cmocka_unit_test(test_nurbs_weight_scale),
        cmocka_unit_test(test_bspline_volume_exact),
        cmocka_unit_test(test_jacobian_fd),
        cmocka_unit_test(test_grid_matches_points),
        cmocka_unit_test(test_eval_points),
        cmocka_unit_test(test_min_jacobian_matches_points),
        cmocka_unit_test(test_copy),
        cmocka_unit_test(test_alloc_failures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
