/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Coons body 2 (seed 000 section 2.4). Expected values are computed here:
 * the seed's formula C2 = D - C1 - T written out from face evaluations,
 * boundary interpolation, the seed's equivalences (Coons faces give body 1,
 * flat faces give body 0, linear blend), exact volumes of a box and a
 * pyramid with a collapsed face. Jacobians, grids, copies and failing
 * allocations of body 2 run with the other types in core/test_body.c.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "body_fixtures.h"

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

/* Seed 000 section 2.4 from the faces, literally: edges C(u,j,k) etc. as
 * the average of the two faces carrying them, corners as the average of
 * three, then C2 = D - C1 - T. */
static void body2_ref(coons_patch *const f[6], coons_blend kind, double u, double v, double w,
                      double out[3])
{
    double a[2], b[2], c[2], X[2][3], Y[2][3], Z[2][3];
    blend_pair(kind, u, a);
    blend_pair(kind, v, b);
    blend_pair(kind, w, c);
    double D[3] = {0, 0, 0}, C1[3] = {0, 0, 0}, T[3] = {0, 0, 0};
    for (int x = 0; x < 2; x++) {
        coons_patch_eval(f[x], v, w, X[x]);
        coons_patch_eval(f[2 + x], u, w, Y[x]);
        coons_patch_eval(f[4 + x], u, v, Z[x]);
        for (int r = 0; r < 3; r++) D[r] += a[x] * X[x][r] + b[x] * Y[x][r] + c[x] * Z[x][r];
    }
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            double p[3], q[3];
            /* C(i,j,w) = X_i(j,w) ~ Y_j(i,w) */
            coons_patch_eval(f[i], j, w, p);
            coons_patch_eval(f[2 + j], i, w, q);
            for (int r = 0; r < 3; r++) C1[r] += a[i] * b[j] * 0.5 * (p[r] + q[r]);
            /* C(i,v,k) = X_i(v,k) ~ Z_k(i,v), k = j */
            coons_patch_eval(f[i], v, j, p);
            coons_patch_eval(f[4 + j], i, v, q);
            for (int r = 0; r < 3; r++) C1[r] += a[i] * c[j] * 0.5 * (p[r] + q[r]);
            /* C(u,j,k) = Y_j(u,k) ~ Z_k(u,j), here j -> i, k -> j */
            coons_patch_eval(f[2 + i], u, j, p);
            coons_patch_eval(f[4 + j], u, i, q);
            for (int r = 0; r < 3; r++) C1[r] += b[i] * c[j] * 0.5 * (p[r] + q[r]);
        }
    for (int n = 0; n < 8; n++) {
        int i = n >> 2, j = (n >> 1) & 1, k = n & 1;
        double p[3], q[3], s[3];
        coons_patch_eval(f[i], j, k, p);
        coons_patch_eval(f[2 + j], i, k, q);
        coons_patch_eval(f[4 + k], i, j, s);
        for (int r = 0; r < 3; r++) T[r] += a[i] * b[j] * c[k] * (p[r] + q[r] + s[r]) / 3.0;
    }
    for (int r = 0; r < 3; r++) {
        C1[r] -= 2.0 * T[r];
        out[r] = D[r] - C1[r] - T[r];
    }
}

static void free_faces(coons_patch *f[6])
{
    for (int n = 0; n < 6; n++) coons_patch_free(f[n]);
}

static void test_body2_formula_and_boundary(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_patch *f[6];
    assert_coons_ok(tb_bspline_faces(6, f, &err), &err);
    for (int kind = 0; kind < 2; kind++) {
        coons_body *b;
        assert_coons_ok(coons_body_new_body2(f, (coons_blend)kind,
                                             COONS_TOL_DEFAULT, &b, &err),
                        &err);
        assert_int_equal(coons_body_kind(b), COONS_BODY_BODY2);
        tb_rng rng = {11u + (unsigned)kind};
        for (int t = 0; t < 60; t++) {
            double u = tb_rand(&rng), v = tb_rand(&rng), w = tb_rand(&rng), x[3], y[3];
            body2_ref(f, (coons_blend)kind, u, v, w, x);
            coons_body_eval(b, u, v, w, y);
            assert_vec3_near(y, x, 1e-13);
            /* The six faces. */
            for (int I = 0; I < 2; I++) {
                coons_patch_eval(f[I], v, w, x);
                coons_body_eval(b, I, v, w, y);
                assert_vec3_near(y, x, 1e-13);
                coons_patch_eval(f[2 + I], u, w, x);
                coons_body_eval(b, u, I, w, y);
                assert_vec3_near(y, x, 1e-13);
                coons_patch_eval(f[4 + I], u, v, x);
                coons_body_eval(b, u, v, I, y);
                assert_vec3_near(y, x, 1e-13);
            }
            /* The twelve edges, each on the face of the first-named
             * direction: C(u,J,K) = Y_J(u,K), C(I,v,K) = X_I(v,K),
             * C(I,J,w) = X_I(J,w). */
            for (int J = 0; J < 2; J++)
                for (int K = 0; K < 2; K++) {
                    coons_patch_eval(f[2 + J], u, K, x);
                    coons_body_eval(b, u, J, K, y);
                    assert_vec3_near(y, x, 1e-13);
                    coons_patch_eval(f[J], v, K, x);
                    coons_body_eval(b, J, v, K, y);
                    assert_vec3_near(y, x, 1e-13);
                    coons_patch_eval(f[J], K, w, x);
                    coons_body_eval(b, J, K, w, y);
                    assert_vec3_near(y, x, 1e-13);
                }
        }
        /* Corners are the lattice corners. */
        for (int n = 0; n < 8; n++) {
            double x[3], y[3];
            tb_cube_net(6, (n >> 2) * 5, ((n >> 1) & 1) * 5, (n & 1) * 5, x);
            coons_body_eval(b, n >> 2, (n >> 1) & 1, n & 1, y);
            assert_vec3_near(y, x, 1e-14);
        }
        coons_body_free(b);
    }
    free_faces(f);
}

/* Coons patches of body-1 edges, each face with its own four edges:
 * face u_I: (s,t) = (v,w): t0 = v_I0 (w=0), t1 = v_I1, s0 = w_I0 (v=0), s1 = w_I1;
 * face v_J: (s,t) = (u,w): t0 = u_J0, t1 = u_J1, s0 = w_0J, s1 = w_1J;
 * face w_K: (s,t) = (u,v): t0 = u_0K, t1 = u_1K, s0 = v_0K, s1 = v_1K. */
static int coons_faces(coons_curve *const e[12], coons_blend kind, coons_patch *f[6],
                       coons_error *err)
{
    memset(f, 0, 6 * sizeof f[0]);
    for (int x = 0; x < 2; x++) {
        coons_curve *bu[4] = {e[4 + 2 * x], e[4 + 2 * x + 1], e[8 + 2 * x], e[8 + 2 * x + 1]};
        coons_curve *bv[4] = {e[2 * x], e[2 * x + 1], e[8 + x], e[10 + x]};
        coons_curve *bw[4] = {e[x], e[2 + x], e[4 + x], e[6 + x]};
        int rc = coons_patch_new_coons(bu, kind, COONS_TOL_DEFAULT, &f[x], err);
        if (!rc) rc = coons_patch_new_coons(bv, kind, COONS_TOL_DEFAULT, &f[2 + x], err);
        if (!rc) rc = coons_patch_new_coons(bw, kind, COONS_TOL_DEFAULT, &f[4 + x], err);
        if (rc) return rc;
    }
    return COONS_OK;
}

static void test_body2_coons_faces_is_body1(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_curve *e[12];
    assert_coons_ok(tb_curved_edges(e, &err), &err);
    /* Seed 000: with Coons patches of the edges as faces, body 2 is body 1
     * (linear blend everywhere). The Boolean-sum algebra behind it holds
     * for any blend pair with f(0)=1, f(1)=0 as long as the faces use the
     * same blend as the body, which the cubic case checks too. */
    for (int kind = 0; kind < 2; kind++) {
        coons_patch *f[6];
        assert_coons_ok(coons_faces(e, (coons_blend)kind, f, &err), &err);
        coons_body *b1, *b2;
        assert_coons_ok(coons_body_new_body1(e, (coons_blend)kind,
                                             COONS_TOL_DEFAULT, &b1, &err),
                        &err);
        assert_coons_ok(coons_body_new_body2(f, (coons_blend)kind,
                                             COONS_TOL_DEFAULT, &b2, &err),
                        &err);
        tb_rng rng = {21};
        for (int t = 0; t < 100; t++) {
            double u = tb_rand(&rng), v = tb_rand(&rng), w = tb_rand(&rng), x[3], y[3];
            coons_body_eval(b1, u, v, w, x);
            coons_body_eval(b2, u, v, w, y);
            assert_vec3_near(y, x, 1e-13);
        }
        coons_body_free(b1);
        coons_body_free(b2);
        free_faces(f);
    }
    /* Linear faces under a cubic body blend: no longer body 1 (model
     * format: the equivalences are for the linear blend). */
    coons_patch *f[6];
    assert_coons_ok(coons_faces(e, COONS_BLEND_LINEAR, f, &err), &err);
    coons_body *b1, *b2;
    assert_coons_ok(coons_body_new_body1(e, COONS_BLEND_CUBIC,
                                         COONS_TOL_DEFAULT, &b1, &err),
                    &err);
    assert_coons_ok(coons_body_new_body2(f, COONS_BLEND_CUBIC,
                                         COONS_TOL_DEFAULT, &b2, &err),
                    &err);
    double x[3], y[3];
    coons_body_eval(b1, 0.3, 0.6, 0.45, x);
    coons_body_eval(b2, 0.3, 0.6, 0.45, y);
    assert_true(fabs(x[0] - y[0]) + fabs(x[1] - y[1]) + fabs(x[2] - y[2]) > 1e-4);
    coons_body_free(b1);
    coons_body_free(b2);
    free_faces(f);
    for (int n = 0; n < 12; n++) coons_curve_free(e[n]);
}

/* Bilinear faces of a hexahedron with corners c (P_ijk at 4i+2j+k). */
static void flat_faces(const double *c, coons_patch *f[6])
{
    coons_error err = COONS_ERROR_INIT;
    for (int x = 0; x < 2; x++) {
        /* corners X00, X10, X01, X11 with Xab = x(s=a, t=b) */
        double qu[4][3], qv[4][3], qw[4][3];
        for (int a = 0; a < 2; a++)
            for (int bb = 0; bb < 2; bb++) {
                memcpy(qu[a + 2 * bb], c + 3 * (4 * x + 2 * a + bb), sizeof qu[0]); /* (v,w) */
                memcpy(qv[a + 2 * bb], c + 3 * (4 * a + 2 * x + bb), sizeof qv[0]); /* (u,w) */
                memcpy(qw[a + 2 * bb], c + 3 * (4 * a + 2 * bb + x), sizeof qw[0]); /* (u,v) */
            }
        assert_coons_ok(coons_patch_new_bilinear(qu[0], &f[x], &err), &err);
        assert_coons_ok(coons_patch_new_bilinear(qv[0], &f[2 + x], &err), &err);
        assert_coons_ok(coons_patch_new_bilinear(qw[0], &f[4 + x], &err), &err);
    }
}

static void test_body2_flat_is_body0(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_patch *f[6];
    flat_faces(tb_hex()[0], f);
    coons_body *b0, *b2;
    assert_coons_ok(coons_body_new_body0(tb_hex()[0], COONS_BLEND_LINEAR, &b0, &err), &err);
    assert_coons_ok(coons_body_new_body2(f, COONS_BLEND_LINEAR,
                                         COONS_TOL_DEFAULT, &b2, &err),
                    &err);
    tb_rng rng = {8};
    for (int t = 0; t < 100; t++) {
        double u = tb_rand(&rng), v = tb_rand(&rng), w = tb_rand(&rng), x[3], y[3], jx[3][3],
               jy[3][3];
        double dx = coons_body_eval_jacobian(b0, u, v, w, x, jx);
        double dy = coons_body_eval_jacobian(b2, u, v, w, y, jy);
        assert_vec3_near(y, x, 1e-14);
        for (int r = 0; r < 3; r++) assert_vec3_near(jy[r], jx[r], 1e-13);
        assert_near(dy, dx, 1e-13);
    }
    double v0, v2;
    assert_coons_ok(coons_body_volume(b0, 1e-12, &v0, &err), &err);
    assert_coons_ok(coons_body_volume(b2, 1e-12, &v2, &err), &err);
    assert_near(v2, v0, 1e-13);
    coons_body_free(b0);
    coons_body_free(b2);
    free_faces(f);
}

/* Degenerate geometry (model format: allowed): a square pyramid, base
 * a x a at z = 0, apex at height h, as body 2 whose top face w1 has
 * collapsed to the apex. Volume a^2 h / 3. */
static void test_body2_pyramid(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    const double a = 2.0, h = 3.0;
    double c[8][3];
    for (int n = 0; n < 8; n++) {
        int i = n >> 2, j = (n >> 1) & 1, k = n & 1;
        c[n][0] = k ? 0.5 * a : a * i;
        c[n][1] = k ? 0.5 * a : a * j;
        c[n][2] = k ? h : 0.0;
    }
    coons_patch *f[6];
    flat_faces(c[0], f);
    coons_body *b;
    assert_coons_ok(coons_body_new_body2(f, COONS_BLEND_LINEAR,
                                         COONS_TOL_DEFAULT, &b, &err),
                    &err);
    double vol, m, where[3];
    assert_coons_ok(coons_body_volume(b, 1e-12, &vol, &err), &err);
    assert_near(vol, a * a * h / 3.0, 1e-12);
    assert_coons_ok(coons_body_min_jacobian(b, 6, &m, where, &err), &err);
    assert_near(m, 0.0, 1e-12); /* zero on the collapsed face, positive inside */
    assert_near(where[2], 1.0, 0.0);
    double y[3];
    coons_body_eval(b, 0.3, 0.9, 1.0, y);
    assert_vec3_near(y, ((double[3]){0.5 * a, 0.5 * a, h}), 1e-14);
    coons_body_free(b);
    free_faces(f);
}

static void test_body2_incompatible(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    /* Face w0 = Z_0(u,v) with one boundary control point moved: its edge
     * v = 0 (C(u,0,0), edge u00, shared with face v0) no longer agrees. */
    const int m = 6;
    coons_patch *f[6];
    assert_coons_ok(tb_bspline_faces(m, f, &err), &err);
    double pts[6 * 6 * 3];
    for (int a = 0; a < m; a++)
        for (int b = 0; b < m; b++) tb_cube_net(m, a, b, 0, pts + (a * m + b) * 3);
    pts[(2 * m + 0) * 3 + 2] += 0.3; /* point [2][0]: on the v = 0 boundary, inside */
    coons_patch_free(f[4]);
    assert_coons_ok(coons_patch_new_bspline(3, 3, pts, m, m, NULL, NULL, NULL, &f[4], &err), &err);
    coons_body *b = (coons_body *)&err;
    assert_int_equal(coons_body_new_body2(f, COONS_BLEND_LINEAR,
                                          COONS_TOL_DEFAULT, &b, &err),
                     COONS_E_INCOMPATIBLE);
    assert_null(b);
    assert_int_equal(err.code, COONS_E_INCOMPATIBLE);
    assert_non_null(strstr(err.message, "edge u00 (v=0,w=0)"));
    assert_non_null(strstr(err.message, "faces v0 and w0"));
    assert_non_null(strstr(err.message, "at u="));
    /* A tolerance above the gap accepts the faces; the edge is then the
     * average of the two faces (model format, "Consistency"), pointwise
     * and in grids. */
    assert_coons_ok(coons_body_new_body2(f, COONS_BLEND_LINEAR, 0.5, &b,
                                         &err),
                    &err);
    double us[4] = {0.1, 0.35, 0.5, 0.8}, zero = 0.0, g[4 * 3];
    assert_coons_ok(coons_body_eval_grid(b, us, 4, &zero, 1, &zero, 1, g, &err), &err);
    for (int n = 0; n < 4; n++) {
        double y0[3], z0[3], avg[3], y[3];
        coons_patch_eval(f[2], us[n], 0, y0);
        coons_patch_eval(f[4], us[n], 0, z0);
        for (int r = 0; r < 3; r++) avg[r] = 0.5 * (y0[r] + z0[r]);
        assert_true(fabs(y0[2] - z0[2]) > 1e-3);
        coons_body_eval(b, us[n], 0, 0, y);
        assert_vec3_near(y, avg, 1e-14);
        assert_vec3_near(g + 3 * n, avg, 1e-14);
    }
    coons_body_free(b);
    /* A moved corner: C000 is the average of the three faces there. */
    double c0[3];
    tb_cube_net(m, 0, 0, 0, c0);
    pts[(2 * m + 0) * 3 + 2] -= 0.3;
    pts[2] += 0.3; /* point [0][0] of w0 */
    coons_patch_free(f[4]);
    assert_coons_ok(coons_patch_new_bspline(3, 3, pts, m, m, NULL, NULL, NULL, &f[4], &err), &err);
    assert_int_equal(coons_body_new_body2(f, COONS_BLEND_LINEAR,
                                          COONS_TOL_DEFAULT, &b, &err),
                     COONS_E_INCOMPATIBLE);
    assert_coons_ok(coons_body_new_body2(f, COONS_BLEND_LINEAR, 0.5, &b,
                                         &err),
                    &err);
    double y[3], one[1] = {0.0};
    c0[2] += 0.1;
    coons_body_eval(b, 0, 0, 0, y);
    assert_vec3_near(y, c0, 1e-14);
    assert_coons_ok(coons_body_eval_grid(b, one, 1, one, 1, one, 1, y, &err), &err);
    assert_vec3_near(y, c0, 1e-14);
    coons_body_free(b);
    /* Same check for a w-edge: move X_1's boundary v = 1 (edge w11, shared with Y_1). */
    for (int a = 0; a < m; a++)
        for (int bb = 0; bb < m; bb++) tb_cube_net(m, m - 1, a, bb, pts + (a * m + bb) * 3);
    pts[((m - 1) * m + 3) * 3 + 0] -= 0.05; /* [v = last][w = 3] */
    coons_patch_free(f[4]);
    coons_patch_free(f[1]);
    f[4] = NULL;
    assert_coons_ok(coons_patch_new_bspline(3, 3, pts, m, m, NULL, NULL, NULL, &f[1], &err), &err);
    assert_int_equal(coons_body_new_body2(f, COONS_BLEND_LINEAR,
                                          COONS_TOL_DEFAULT, &b, &err),
                     COONS_E_INVALID); /* f[4] is NULL */
    assert_non_null(strstr(err.message, "w0"));
    for (int a = 0; a < m; a++)
        for (int bb = 0; bb < m; bb++) tb_cube_net(m, a, bb, 0, pts + (a * m + bb) * 3);
    assert_coons_ok(coons_patch_new_bspline(3, 3, pts, m, m, NULL, NULL, NULL, &f[4], &err), &err);
    assert_int_equal(coons_body_new_body2(f, COONS_BLEND_LINEAR,
                                          COONS_TOL_DEFAULT, &b, &err),
                     COONS_E_INCOMPATIBLE);
    assert_non_null(strstr(err.message, "edge w11 (u=1,v=1)"));
    assert_non_null(strstr(err.message, "faces u1 and v1"));
    assert_non_null(strstr(err.message, "at w="));
    free_faces(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_body2_formula_and_boundary),
        cmocka_unit_test(test_body2_coons_faces_is_body1),
        cmocka_unit_test(test_body2_flat_is_body0),
        cmocka_unit_test(test_body2_pyramid),
        cmocka_unit_test(test_body2_incompatible),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
