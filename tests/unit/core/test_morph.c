/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The morph body (seed 000 section 4, Fig. 10; coons-model(5), "morph").
 * Expected values are independent of src/core/morph.c: the weights' sum and
 * their values at the keys; the path's tangents at the keys (the spec's
 * quotients) and its C1 continuity by finite differences; straight lines
 * of the linear path; the Jacobian by central differences; the B-spline
 * volume whose control points are blended (the seed's grid-point paths),
 * built independently; the sign of det J for keys of opposite handedness.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "body_fixtures.h"

enum { MAXK = 6 };

/* Random strictly increasing key times from 0 to 1. */
static void rand_times(tb_rng *r, size_t n, double *at)
{
    at[0] = 0.0;
    for (size_t k = 1; k < n; k++) at[k] = at[k - 1] + 0.2 + tb_rand(r);
    for (size_t k = 1; k + 1 < n; k++) at[k] /= at[n - 1];
    at[n - 1] = 1.0;
}

static double blend_scalar(size_t n, const double *at, coons_morph_path path, double t,
                           const double *y)
{
    double w[MAXK];
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_morph_weights(n, at, path, t, w, NULL, &err), &err);
    double s = 0;
    for (size_t k = 0; k < n; k++) s += w[k] * y[k];
    return s;
}

static void test_weights_partition(void **state)
{
    (void)state;
    tb_rng r = {7};
    coons_error err = COONS_ERROR_INIT;
    for (size_t n = 2; n <= MAXK; n++)
        for (int path = 0; path < 2; path++) {
            double at[MAXK], w[MAXK];
            rand_times(&r, n, at);
            for (int i = 0; i <= 200; i++) {
                double t = i / 200.0, s = 0;
                assert_coons_ok(coons_morph_weights(n, at, path, t, w, NULL, &err), &err);
                for (size_t k = 0; k < n; k++) s += w[k];
                assert_near(s, 1.0, 1e-14);
            }
            for (size_t k = 0; k < n; k++) {
                assert_coons_ok(coons_morph_weights(n, at, path, at[k], w, NULL, &err), &err);
                for (size_t j = 0; j < n; j++) assert_true(w[j] == (j == k ? 1.0 : 0.0));
            }
            /* NULL times: uniform k/(n-1) */
            for (size_t k = 0; k < n; k++) {
                double t = (double)k / (double)(n - 1);
                assert_coons_ok(coons_morph_weights(n, NULL, path, t, w, NULL, &err), &err);
                for (size_t j = 0; j < n; j++) assert_near(w[j], j == k ? 1.0 : 0.0, 1e-15);
            }
        }
}

/* The smooth path's velocity at a key is the spec's Catmull-Rom quotient,
 * the same from both sides (C1), and dw agrees with differences. */
static void test_smooth_tangents_c1(void **state)
{
    (void)state;
    tb_rng r = {11};
    coons_error err = COONS_ERROR_INIT;
    for (size_t n = 3; n <= MAXK; n++) {
        double at[MAXK], y[MAXK];
        rand_times(&r, n, at);
        for (size_t k = 0; k < n; k++) y[k] = 4.0 * tb_rand(&r) - 2.0;
        const double h = 1e-6;
        for (size_t k = 0; k < n; k++) {
            double want;
            if (k == 0)
                want = (y[1] - y[0]) / (at[1] - at[0]);
            else if (k == n - 1)
                want = (y[n - 1] - y[n - 2]) / (at[n - 1] - at[n - 2]);
            else
                want = (y[k + 1] - y[k - 1]) / (at[k + 1] - at[k - 1]);
            double f0 = blend_scalar(n, at, COONS_MORPH_SMOOTH, at[k], y);
            if (k + 1 < n) {
                double right = (blend_scalar(n, at, COONS_MORPH_SMOOTH, at[k] + h, y) - f0) / h;
                assert_near(right, want, 1e-4 * (1 + fabs(want)));
            }
            if (k > 0) {
                double left = (f0 - blend_scalar(n, at, COONS_MORPH_SMOOTH, at[k] - h, y)) / h;
                assert_near(left, want, 1e-4 * (1 + fabs(want)));
            }
        }
        /* dw against central differences inside the intervals */
        for (int i = 1; i < 100; i++) {
            double t = i / 100.0 + 0.003, w[MAXK], dw[MAXK], wp[MAXK], wm[MAXK];
            assert_coons_ok(coons_morph_weights(n, at, COONS_MORPH_SMOOTH, t, w, dw, &err), &err);
            assert_coons_ok(coons_morph_weights(n, at, COONS_MORPH_SMOOTH, t + h, wp, NULL, &err),
                            &err);
            assert_coons_ok(coons_morph_weights(n, at, COONS_MORPH_SMOOTH, t - h, wm, NULL, &err),
                            &err);
            int near_key = 0;
            for (size_t k = 0; k < n; k++) near_key |= fabs(t - at[k]) < 2 * h;
            if (near_key) continue;
            for (size_t k = 0; k < n; k++) assert_near(dw[k], (wp[k] - wm[k]) / (2 * h), 1e-5);
        }
    }
}

/* The linear path is a straight line between neighbouring keys. */
static void test_linear_piecewise(void **state)
{
    (void)state;
    tb_rng r = {5};
    double at[4], y[4] = {1.0, -2.0, 3.5, 0.25};
    rand_times(&r, 4, at);
    for (int k = 0; k < 3; k++)
        for (int i = 0; i <= 10; i++) {
            double s = i / 10.0, t = at[k] + s * (at[k + 1] - at[k]);
            double want = (1 - s) * y[k] + s * y[k + 1];
            assert_near(blend_scalar(4, at, COONS_MORPH_LINEAR, t, y), want, 1e-13);
        }
    /* with two keys the smooth path is the linear one */
    double y2[2] = {3.0, -1.0};
    for (int i = 0; i <= 10; i++)
        assert_near(blend_scalar(2, NULL, COONS_MORPH_SMOOTH, i / 10.0, y2), 3.0 - 4.0 * i / 10.0,
                    1e-14);
}

/* Keys: a skew hex (body 0), the deformed cube as a bicubic B-spline
 * volume, and a NURBS cylinder. */
static void make_keys(coons_body *k[3])
{
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_body0(tb_hex()[0], COONS_BLEND_LINEAR, &k[0], &err), &err);
    enum { M = 5 };
    double p[M * M * M * 3];
    for (int i = 0; i < M; i++)
        for (int j = 0; j < M; j++)
            for (int l = 0; l < M; l++) tb_cube_net(M, i, j, l, p + 3 * ((i * M + j) * M + l));
    const int deg[3] = {3, 3, 3};
    const size_t n[3] = {M, M, M};
    assert_coons_ok(coons_body_new_bspline(deg, p, n, NULL, NULL, NULL, NULL, &k[1], &err), &err);
    tb_nurbs_cylinder(1.0, 2.0, &k[2]);
}

static void test_eval_is_blend_and_jacobian_fd(void **state)
{
    (void)state;
    coons_body *k[3];
    make_keys(k);
    coons_error err = COONS_ERROR_INIT;
    const double at[3] = {0.0, 0.35, 1.0};
    tb_rng r = {3};
    for (int path = 0; path < 2; path++)
        for (int trial = 0; trial < 6; trial++) {
            double t = tb_rand(&r), w[3];
            coons_body *m = NULL;
            assert_coons_ok(coons_body_new_morph(k, 3, at, path, t, &m,
                                                 &err),
                            &err);
            assert_int_equal(coons_body_kind(m), COONS_BODY_MORPH);
            assert_coons_ok(coons_morph_weights(3, at, path, t, w, NULL, &err), &err);
            for (int q = 0; q < 10; q++) {
                double u = tb_rand(&r), v = tb_rand(&r), x = tb_rand(&r), p[3], want[3] = {0};
                for (int j = 0; j < 3; j++) {
                    double pk[3];
                    coons_body_eval(k[j], u, v, x, pk);
                    for (int c = 0; c < 3; c++) want[c] += w[j] * pk[c];
                }
                coons_body_eval(m, u, v, x, p);
                assert_vec3_near(p, want, 1e-12);
                /* Jacobian against central differences, away from the faces */
                u = 0.05 + 0.9 * u, v = 0.05 + 0.9 * v, x = 0.05 + 0.9 * x;
                double J[3][3], o[3];
                double det = coons_body_eval_jacobian(m, u, v, x, o, J);
                const double h = 1e-6;
                double fd[3][3];
                for (int c = 0; c < 3; c++) {
                    double qp[3] = {u, v, x}, qm[3] = {u, v, x}, a[3], b[3];
                    qp[c] += h;
                    qm[c] -= h;
                    coons_body_eval(m, qp[0], qp[1], qp[2], a);
                    coons_body_eval(m, qm[0], qm[1], qm[2], b);
                    for (int rr = 0; rr < 3; rr++) fd[rr][c] = (a[rr] - b[rr]) / (2 * h);
                }
                for (int rr = 0; rr < 3; rr++)
                    for (int c = 0; c < 3; c++) assert_near(J[rr][c], fd[rr][c], 1e-6);
                double d = fd[0][0] * (fd[1][1] * fd[2][2] - fd[1][2] * fd[2][1]) -
                           fd[0][1] * (fd[1][0] * fd[2][2] - fd[1][2] * fd[2][0]) +
                           fd[0][2] * (fd[1][0] * fd[2][1] - fd[1][1] * fd[2][0]);
                assert_near(det, d, 1e-5 * (1 + fabs(d)));
            }
            /* the grid agrees with the points */
            double g[3] = {0.0, 0.3, 1.0}, out[27 * 3];
            assert_coons_ok(coons_body_eval_grid(m, g, 3, g, 3, g, 3, out, &err), &err);
            for (int i = 0; i < 27; i++) {
                double p[3];
                coons_body_eval(m, g[i / 9], g[(i / 3) % 3], g[i % 3], p);
                assert_vec3_near(out + 3 * i, p, 1e-12);
            }
            coons_body_free(m);
        }
    for (int j = 0; j < 3; j++) coons_body_free(k[j]);
}

/* A morph of two B-spline volumes of one structure is the B-spline volume
 * whose control points (and, here, weights 1) are blended (seed 000 §4:
 * moving each grid point along its path). */
static void test_bspline_grid_points(void **state)
{
    (void)state;
    enum { A = 4, B = 3, C = 5, N = A * B * C };
    const size_t n[3] = {A, B, C};
    const int deg[3] = {2, 2, 3};
    const double ku[] = {0, 0, 0, 0.4, 1, 1, 1}, kv[] = {0, 0, 0, 1, 1, 1},
                 kw[] = {0, 0, 0, 0, 0.7, 1, 1, 1, 1};
    double p0[N * 3], p1[N * 3], p2[N * 3];
    tb_rng r = {19};
    for (int i = 0; i < N * 3; i++) {
        p0[i] = (double)(i % 7) + 0.3 * tb_rand(&r);
        p1[i] = (double)(i % 5) * 1.5 - 0.4 * tb_rand(&r);
        p2[i] = 2.0 * tb_rand(&r);
    }
    coons_error err = COONS_ERROR_INIT;
    coons_body *k[3], *m = NULL, *direct = NULL;
    assert_coons_ok(coons_body_new_bspline(deg, p0, n, ku, kv, kw, NULL, &k[0], &err), &err);
    assert_coons_ok(coons_body_new_bspline(deg, p1, n, ku, kv, kw, NULL, &k[1], &err), &err);
    assert_coons_ok(coons_body_new_bspline(deg, p2, n, ku, kv, kw, NULL, &k[2], &err), &err);
    for (int trial = 0; trial < 8; trial++) {
        double t = tb_rand(&r);
        /* two keys, linear: weights 1 - t and t written out */
        double pb[N * 3];
        for (int i = 0; i < N * 3; i++) pb[i] = (1 - t) * p0[i] + t * p1[i];
        assert_coons_ok(coons_body_new_morph(k, 2, NULL,
                                             COONS_MORPH_LINEAR, t, &m, &err),
                        &err);
        assert_coons_ok(coons_body_new_bspline(deg, pb, n, ku, kv, kw, NULL, &direct, &err), &err);
        for (int q = 0; q < 20; q++) {
            double u = tb_rand(&r), v = tb_rand(&r), w = tb_rand(&r), a[3], b[3];
            coons_body_eval(m, u, v, w, a);
            coons_body_eval(direct, u, v, w, b);
            assert_vec3_near(a, b, 1e-12);
        }
        coons_body_free(m);
        coons_body_free(direct);
        /* three keys on the smooth path, with the path's weights */
        double at[3] = {0, 0.6, 1}, W[3];
        assert_coons_ok(coons_morph_weights(3, at, COONS_MORPH_SMOOTH, t, W, NULL, &err), &err);
        for (int i = 0; i < N * 3; i++) pb[i] = W[0] * p0[i] + W[1] * p1[i] + W[2] * p2[i];
        assert_coons_ok(coons_body_new_morph(k, 3, at,
                                             COONS_MORPH_SMOOTH, t, &m, &err),
                        &err);
        assert_coons_ok(coons_body_new_bspline(deg, pb, n, ku, kv, kw, NULL, &direct, &err), &err);
        for (int q = 0; q < 20; q++) {
            double u = tb_rand(&r), v = tb_rand(&r), w = tb_rand(&r), a[3], b[3];
            coons_body_eval(m, u, v, w, a);
            coons_body_eval(direct, u, v, w, b);
            assert_vec3_near(a, b, 1e-11);
        }
        coons_body_free(m);
        coons_body_free(direct);
    }
    for (int j = 0; j < 3; j++) coons_body_free(k[j]);
}

/* A unit cube and its mirror image: det J = 1 - 2t (linear path), so the
 * morph is right-handed before t = 1/2 and folds (det J < 0) after. */
static void test_handedness_fold(void **state)
{
    (void)state;
    double c[8][3];
    for (int n = 0; n < 8; n++) c[n][0] = n >> 2, c[n][1] = (n >> 1) & 1, c[n][2] = n & 1;
    coons_error err = COONS_ERROR_INIT;
    coons_body *k[2], *m = NULL, *m2 = NULL;
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &k[0], &err), &err);
    const double mirror[12] = {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    assert_coons_ok(coons_body_new_transformed(k[0], mirror, &k[1], &err), &err);
    assert_coons_ok(coons_body_new_morph(k, 2, NULL,
                                         COONS_MORPH_LINEAR, 0.25, &m, &err),
                    &err);
    double md, where[3], o[3], J[3][3];
    assert_coons_ok(coons_body_min_jacobian(m, 4, &md, where, &err), &err);
    assert_near(md, 0.5, 1e-12);
    assert_coons_ok(coons_body_at_time(m, 0.75, &m2, &err), &err);
    assert_coons_ok(coons_body_min_jacobian(m2, 4, &md, where, &err), &err);
    assert_near(md, -0.5, 1e-12);
    assert_near(coons_body_eval_jacobian(m2, 0.3, 0.3, 0.3, o, J), -0.5, 1e-12);
    /* the original keeps its own time */
    assert_near(coons_body_eval_jacobian(m, 0.3, 0.3, 0.3, o, J), 0.5, 1e-12);
    coons_morph_path path;
    double t;
    assert_coons_ok(coons_body_morph_info(m2, &path, &t, &err), &err);
    assert_int_equal(path, COONS_MORPH_LINEAR);
    assert_near(t, 0.75, 0);
    coons_body_free(m2);
    coons_body_free(m);
    coons_body_free(k[0]);
    coons_body_free(k[1]);
}

/* A morph as a key of a morph, inside a transform: coons_body_at_time()
 * reaches both; accessors see through the transform. */
static void test_nested_time(void **state)
{
    (void)state;
    double c0[8][3], c1[8][3], c2[8][3];
    for (int n = 0; n < 8; n++)
        for (int d = 0; d < 3; d++) {
            double q = d == 0 ? n >> 2 : d == 1 ? (n >> 1) & 1 : n & 1;
            c0[n][d] = q;
            c1[n][d] = 2 * q + 1;
            c2[n][d] = -q + 3;
        }
    coons_error err = COONS_ERROR_INIT;
    coons_body *a, *b, *c, *inner, *outer, *xf, *at;
    assert_coons_ok(coons_body_new_body0(c0[0], COONS_BLEND_LINEAR, &a, &err), &err);
    assert_coons_ok(coons_body_new_body0(c1[0], COONS_BLEND_LINEAR, &b, &err), &err);
    assert_coons_ok(coons_body_new_body0(c2[0], COONS_BLEND_LINEAR, &c, &err), &err);
    coons_body *ab[2] = {a, b};
    assert_coons_ok(coons_body_new_morph(ab, 2, NULL, COONS_MORPH_LINEAR, 0.0, &inner, &err),
                    &err);
    coons_body *ic[2] = {inner, c};
    assert_coons_ok(coons_body_new_morph(ic, 2, NULL, COONS_MORPH_LINEAR, 0.0, &outer, &err),
                    &err);
    const double shift[12] = {1, 0, 0, 10, 0, 1, 0, 0, 0, 0, 1, 0};
    assert_coons_ok(coons_body_new_transformed(outer, shift, &xf, &err), &err);
    assert_int_equal(coons_body_morph_keys(xf), 2);
    assert_int_equal(coons_body_morph_keys(a), 0);
    double kt = -1;
    assert_non_null(coons_body_morph_key(xf, 1, &kt));
    assert_near(kt, 1.0, 0);
    assert_null(coons_body_morph_key(xf, 2, NULL));
    double t = 0.3;
    assert_coons_ok(coons_body_at_time(xf, t, &at, &err), &err);
    /* point (u,v,w) = q: inner = (1-t) q + t (2q+1), outer = (1-t) inner + t (3 - q) */
    double q[3] = {0.2, 0.7, 0.4}, p[3], want[3];
    for (int d = 0; d < 3; d++)
        want[d] = (1 - t) * ((1 - t) * q[d] + t * (2 * q[d] + 1)) + t * (3 - q[d]) +
                  (d == 0 ? 10 : 0);
    coons_body_eval(at, q[0], q[1], q[2], p);
    assert_vec3_near(p, want, 1e-13);
    coons_body *cp;
    assert_coons_ok(coons_body_copy(at, &cp, &err), &err);
    double p2[3];
    coons_body_eval(cp, q[0], q[1], q[2], p2);
    assert_vec3_near(p2, want, 1e-13);
    coons_body_free(cp);
    coons_body_free(at);
    coons_body_free(xf);
    coons_body_free(outer);
    coons_body_free(inner);
    coons_body_free(a);
    coons_body_free(b);
    coons_body_free(c);
}

static void test_invalid(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_body *k[2], *m = NULL;
    assert_coons_ok(coons_body_new_body0(tb_hex()[0], COONS_BLEND_LINEAR, &k[0], &err), &err);
    assert_coons_ok(coons_body_new_body0(tb_hex()[0], COONS_BLEND_CUBIC, &k[1], &err), &err);
    coons_body *const *kk = k;
    assert_int_equal(coons_body_new_morph(kk, 1, NULL, COONS_MORPH_LINEAR, 0, &m, &err),
                     COONS_E_INVALID);
    const double bad1[2] = {0.0, 0.9}, bad2[2] = {0.1, 1.0}, ok[2] = {0.0, 1.0};
    assert_int_equal(coons_body_new_morph(kk, 2, bad1, COONS_MORPH_LINEAR, 0, &m, &err),
                     COONS_E_INVALID);
    assert_non_null(strstr(err.message, "exactly 0"));
    assert_int_equal(coons_body_new_morph(kk, 2, bad2, COONS_MORPH_LINEAR, 0, &m, &err),
                     COONS_E_INVALID);
    assert_int_equal(coons_body_new_morph(kk, 2, ok, COONS_MORPH_LINEAR, 1.5, &m, &err),
                     COONS_E_INVALID);
    assert_int_equal(coons_body_new_morph(kk, 2, ok, (coons_morph_path)7, 0.5, &m, &err),
                     COONS_E_INVALID);
    assert_null(m);
    double w[3];
    const double dec[3] = {0.0, 1.0, 1.0};
    assert_int_equal(coons_morph_weights(3, dec, COONS_MORPH_SMOOTH, 0.2, w, NULL, &err),
                     COONS_E_INVALID);
    assert_non_null(strstr(err.message, "increase strictly"));
    coons_body *c = NULL;
    assert_int_equal(coons_body_at_time(k[0], -0.1, &c, &err), COONS_E_INVALID);
    assert_int_equal(coons_model_set_time(NULL, 0.5, &err), COONS_E_INVALID);
    coons_body_free(k[0]);
    coons_body_free(k[1]);
}

/* The model format: keys of any types, a reference, a nested morph;
 * coons_model_set_time() reaches them all; errors name the JSON path. */
static void test_load(void **state)
{
    (void)state;
    const char *doc =
        "{\"coons\": 1, \"define\": {\"box\": {\"type\": \"body0\", \"corners\": "
        "[[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}},"
        " \"bodies\": [{\"type\": \"morph\", \"name\": \"m\", \"path\": \"smooth\", "
        "\"at\": [0, 0.25, 1], \"t\": 0.5, \"keys\": ["
        "{\"ref\": \"box\"},"
        "{\"ref\": \"box\", \"transform\": [[2,0,0,0],[0,2,0,0],[0,0,2,0]]},"
        "{\"type\": \"morph\", \"keys\": [{\"ref\": \"box\", \"transform\": [[1,0,0,1],[0,1,0,0],[0,0,1,0]]},"
        " {\"ref\": \"box\", \"transform\": [[3,0,0,0],[0,3,0,0],[0,0,3,0]]}]}]}]}";
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    assert_coons_ok(coons_model_load_memory(doc, strlen(doc), "m.json", NULL, &m, &err), &err);
    assert_int_equal(coons_model_morph_count(m), 1);
    const coons_body *b = coons_model_body(m, 0);
    assert_int_equal(coons_body_kind(b), COONS_BODY_MORPH);
    assert_int_equal(coons_body_morph_keys(b), 3);
    double at1 = 0;
    assert_int_equal(coons_body_kind(coons_body_morph_key(b, 2, &at1)), COONS_BODY_MORPH);
    assert_near(at1, 1.0, 0);
    /* at t = 0.25 the morph is key 1 (the box scaled by 2) */
    assert_coons_ok(coons_model_set_time(m, 0.25, &err), &err);
    double p[3], want[3] = {1.2, 0.8, 2.0};
    coons_body_eval(b, 0.6, 0.4, 1.0, p);
    assert_vec3_near(p, want, 1e-14);
    /* at t = 1 the outer morph is its last key, the inner morph at t = 1:
     * the box scaled by 3 */
    assert_coons_ok(coons_model_set_time(m, 1.0, &err), &err);
    coons_body_eval(b, 0.6, 0.4, 1.0, p);
    double want3[3] = {1.8, 1.2, 3.0};
    assert_vec3_near(p, want3, 1e-14);
    assert_int_equal(coons_model_set_time(m, 1.5, &err), COONS_E_INVALID);
    coons_model_free(m);

    const char *bad = "{\"coons\": 1, \"bodies\": [{\"type\": \"morph\", \"at\": [0, 0, 1], "
                      "\"keys\": [{\"type\": \"body0\", \"corners\": "
                      "[[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]},"
                      "{\"type\": \"body0\", \"corners\": "
                      "[[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]},"
                      "{\"type\": \"body0\", \"corners\": "
                      "[[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[2,2,2]]}]}]}";
    assert_int_equal(coons_model_load_memory(bad, strlen(bad), "bad.json", NULL, &m, &err),
                     COONS_E_INVALID);
    assert_string_equal(err.path, "/bodies/0/at/1");
    const char *one = "{\"coons\": 1, \"bodies\": [{\"type\": \"morph\", \"keys\": ["
                      "{\"type\": \"body0\", \"corners\": "
                      "[[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]}]}";
    assert_int_equal(coons_model_load_memory(one, strlen(one), "one.json", NULL, &m, &err),
                     COONS_E_INVALID);
    assert_non_null(strstr(err.message, "2 to"));
    const char *blend = "{\"coons\": 1, \"bodies\": [{\"type\": \"morph\", \"blend\": \"cubic\","
                        " \"keys\": []}]}";
    assert_int_equal(coons_model_load_memory(blend, strlen(blend), "b.json", NULL, &m, &err),
                     COONS_E_INVALID);
}

static void test_alloc_failures(void **state)
{
    (void)state;
    coons_body *k[3];
    make_keys(k);
    int done = 0;
    for (long n = 0; !done && n < 10000; n++) {
        coons_test_fail_after(n);
        coons_error err = COONS_ERROR_INIT;
        coons_body *m = NULL, *c = NULL;
        int rc = coons_body_new_morph(k, 3, NULL, COONS_MORPH_SMOOTH,
                                      0.4, &m, &err);
        if (!rc) rc = coons_body_at_time(m, 0.7, &c, &err);
        double g[2] = {0, 1}, out[8 * 3];
        if (!rc) rc = coons_body_eval_grid(c, g, 2, g, 2, g, 2, out, &err);
        coons_body_free(m);
        coons_body_free(c);
        assert_int_equal(coons_test_live_allocs(), 0);
        coons_test_fail_after(-1);
        if (rc == COONS_OK)
            done = 1;
        else
            assert_int_equal(rc, COONS_E_NOMEM);
    }
    assert_true(done);
    for (int j = 0; j < 3; j++) coons_body_free(k[j]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_weights_partition),
        cmocka_unit_test(test_smooth_tangents_c1),
        cmocka_unit_test(test_linear_piecewise),
        cmocka_unit_test(test_eval_is_blend_and_jacobian_fd),
        cmocka_unit_test(test_bspline_grid_points),
        cmocka_unit_test(test_handedness_fold),
        cmocka_unit_test(test_nested_time),
        cmocka_unit_test(test_invalid),
        cmocka_unit_test(test_load),
        cmocka_unit_test(test_alloc_failures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
