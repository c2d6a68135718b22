/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Point evaluation of a Coons body 2 whose faces are tensor-product
 * surfaces (body2.c's fast path: bases computed once per point, the faces'
 * ends kept with the body):
 * - against a closed form: F = sum of terms in two of u, v, w each, of
 *   degree <= 2 in each, which body 2 reproduces with either blend (every
 *   term is linear-interpolated exactly along the third parameter), over
 *   biquadratic faces (Bezier, B-spline, rational with constant weights);
 *   points and Jacobians;
 * - bit for bit against the body's formula written out here from
 *   coons_patch_eval() (each edge the average of its two faces, corners of
 *   three, C2 = D - E + T grouped as body2.c groups it), on lattice faces
 *   of several spans, rational and not, both blends;
 * - values, Jacobians and determinants bit for bit against the same body
 *   of wrapped faces, which takes the general path (face by face);
 * - coons_body_eval_points() (values alone, with Jacobians, with
 *   determinants) bit for bit against coons_body_eval() and
 *   coons_body_eval_jacobian(), and a copy of the body against the body.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "body_fixtures.h"

/* ---- closed form ---- */

static void F(double u, double v, double w, double p[3], double J[3][3])
{
    p[0] = u + 0.2 * v * v * w + 0.1 * u * u * v * v;
    p[1] = v + 0.3 * u * w * w - 0.1 * u * u * w;
    p[2] = w + 0.25 * u * v + 0.15 * v * v * w * w;
    if (!J) return;
    /* J[r][c] = d p_r / d (u,v,w)_c */
    J[0][0] = 1.0 + 0.2 * u * v * v;
    J[0][1] = 0.4 * v * w + 0.2 * u * u * v;
    J[0][2] = 0.2 * v * v;
    J[1][0] = 0.3 * w * w - 0.2 * u * w;
    J[1][1] = 1.0;
    J[1][2] = 0.6 * u * w - 0.1 * u * u;
    J[2][0] = 0.25 * v;
    J[2][1] = 0.25 * u + 0.3 * v * w * w;
    J[2][2] = 1.0 + 0.3 * v * v * w;
}

/* The (u,v,w) of face f at (s,t): X_i (v,w), Y_j (u,w), Z_k (u,v). */
static void face_uvw(int f, double s, double t, double q[3])
{
    int dir = f / 2;
    double fixed = f & 1;
    if (dir == 0) q[0] = fixed, q[1] = s, q[2] = t;
    if (dir == 1) q[0] = s, q[1] = fixed, q[2] = t;
    if (dir == 2) q[0] = s, q[1] = t, q[2] = fixed;
}

/* Face f of F as a biquadratic: Bernstein coefficients from the values at
 * 0, 1/2, 1 (b0 = f0, b1 = 2 f_1/2 - (f0 + f1)/2, b2 = f1) along each
 * parameter. kind 0: bezier-surface, 1: bspline-surface, 2: rational
 * bspline-surface with weights 0.75 everywhere (the same surface). */
static coons_patch *closed_face(int f, int kind)
{
    static const double M[3][3] = {{1, 0, 0}, {-0.5, 2, -0.5}, {0, 0, 1}};
    double val[3][3][3], pts[27], wts[9];
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            double q[3];
            face_uvw(f, 0.5 * a, 0.5 * b, q);
            F(q[0], q[1], q[2], val[a][b], NULL);
        }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            for (int r = 0; r < 3; r++) {
                double s = 0;
                for (int a = 0; a < 3; a++)
                    for (int b = 0; b < 3; b++) s += M[i][a] * M[j][b] * val[a][b][r];
                pts[(i * 3 + j) * 3 + r] = s;
            }
            wts[i * 3 + j] = 0.75;
        }
    coons_patch *p = NULL;
    coons_error err;
    if (kind == 0)
        assert_coons_ok(coons_patch_new_bezier(pts, 3, 3, &p, &err), &err);
    else
        assert_coons_ok(coons_patch_new_bspline(2, 2, pts, 3, 3, NULL, NULL,
                                                kind == 2 ? wts : NULL, &p, &err),
                        &err);
    return p;
}

static void free_faces(coons_patch *f[6])
{
    for (int i = 0; i < 6; i++) coons_patch_free(f[i]);
}

static coons_body *make_body(coons_patch *f[6], coons_blend blend)
{
    coons_body *b = NULL;
    coons_error err;
    assert_coons_ok(coons_body_new_body2(f, blend, COONS_TOL_DEFAULT, &b, &err), &err);
    return b;
}

static void random_points(tb_rng *rng, size_t n, double *uvw)
{
    for (size_t i = 0; i < 3 * n; i++) {
        double r = tb_rand(rng);
        /* some on the faces, edges and corners, a few outside (clamped) */
        uvw[i] = i % 7 == 0 ? 0.0 : i % 11 == 0 ? 1.0 : i % 13 == 0 ? 1.25 : r;
    }
}

static void test_closed_form(void **state)
{
    (void)state;
    for (int kinds = 0; kinds < 3; kinds++)
        for (int blend = 0; blend < 2; blend++) {
            coons_patch *f[6];
            /* kinds 0..2: all faces of one kind; mixed in the last round */
            for (int i = 0; i < 6; i++) f[i] = closed_face(i, blend ? (i + kinds) % 3 : kinds);
            coons_body *b = make_body(f, blend ? COONS_BLEND_CUBIC : COONS_BLEND_LINEAR);
            enum { N = 300 };
            double uvw[3 * N], xyz[3 * N], jac[9 * N], det[N];
            tb_rng rng = {(unsigned long long)(11 + kinds + 5 * blend)};
            random_points(&rng, N, uvw);
            coons_error err;
            assert_coons_ok(coons_body_eval_points(b, N, uvw, xyz, jac, det, &err), &err);
            for (size_t n = 0; n < N; n++) {
                double q[3], p[3], J[3][3];
                for (int r = 0; r < 3; r++) q[r] = fmin(fmax(uvw[3 * n + (size_t)r], 0.0), 1.0);
                F(q[0], q[1], q[2], p, J);
                for (int r = 0; r < 3; r++) {
                    assert_true(fabs(xyz[3 * n + (size_t)r] - p[r]) < 1e-13);
                    for (int c = 0; c < 3; c++)
                        assert_true(fabs(jac[9 * n + (size_t)(3 * r + c)] - J[r][c]) < 1e-12);
                }
                double x[3];
                x[0] = J[1][1] * J[2][2] - J[1][2] * J[2][1];
                x[1] = J[1][2] * J[2][0] - J[1][0] * J[2][2];
                x[2] = J[1][0] * J[2][1] - J[1][1] * J[2][0];
                assert_true(fabs(det[n] - (J[0][0] * x[0] + J[0][1] * x[1] + J[0][2] * x[2])) <
                            1e-11);
            }
            coons_body_free(b);
            free_faces(f);
        }
}

/* ---- the formula, bit for bit ---- */

/* The blend pair of body2.c (basis.c), the same operations. */
static void blend_pair(coons_blend kind, double t, double g[2])
{
    if (kind == COONS_BLEND_CUBIC) {
        double f = 1.0 - 3.0 * t * t + 2.0 * t * t * t;
        g[0] = f;
        g[1] = 1.0 - f;
    } else {
        g[0] = 1.0 - t;
        g[1] = t;
    }
}

static void avg(const double a[3], const double b[3], double out[3])
{
    for (int r = 0; r < 3; r++) out[r] = 0.5 * (a[r] + b[r]);
}

/* C2 = D - E + T as body2.c's point() groups it, from coons_patch_eval. */
static void formula(coons_patch *const f[6], coons_blend kind, double u, double v, double w,
                    double out[3])
{
    double a[2], bb[2], c[2], X[2][3], Y[2][3], Z[2][3], Cu[4][3], Cv[4][3], Cw[4][3];
    double cn[8][3];
    blend_pair(kind, u, a);
    blend_pair(kind, v, bb);
    blend_pair(kind, w, c);
    for (int x = 0; x < 2; x++) {
        coons_patch_eval(f[x], v, w, X[x]);
        coons_patch_eval(f[2 + x], u, w, Y[x]);
        coons_patch_eval(f[4 + x], u, v, Z[x]);
    }
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            double p[3], q[3];
            /* u-edge 2J+K: Y_J(u, K), Z_K(u, J) */
            coons_patch_eval(f[2 + i], u, j, p);
            coons_patch_eval(f[4 + j], u, i, q);
            avg(p, q, Cu[2 * i + j]);
            /* v-edge 2I+K: X_I(v, K), Z_K(I, v) */
            coons_patch_eval(f[i], v, j, p);
            coons_patch_eval(f[4 + j], i, v, q);
            avg(p, q, Cv[2 * i + j]);
            /* w-edge 2I+J: X_I(J, w), Y_J(I, w) */
            coons_patch_eval(f[i], j, w, p);
            coons_patch_eval(f[2 + j], i, w, q);
            avg(p, q, Cw[2 * i + j]);
        }
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) {
                double x[3], y[3], z[3];
                coons_patch_eval(f[i], j, k, x);
                coons_patch_eval(f[2 + j], i, k, y);
                coons_patch_eval(f[4 + k], i, j, z);
                for (int r = 0; r < 3; r++) cn[4 * i + 2 * j + k][r] = (x[r] + y[r] + z[r]) / 3.0;
            }
    for (int r = 0; r < 3; r++) {
        double G[2], P[2];
        for (int j = 0; j < 2; j++) G[j] = Y[j][r] - (a[0] * Cw[j][r] + a[1] * Cw[2 + j][r]);
        for (int k = 0; k < 2; k++) {
            double tk = a[0] * cn[k][r] + a[1] * cn[4 + k][r];
            double t2k = a[0] * cn[2 + k][r] + a[1] * cn[6 + k][r];
            P[k] = Z[k][r] - (a[0] * Cv[k][r] + a[1] * Cv[2 + k][r] + bb[0] * (Cu[k][r] - tk) +
                              bb[1] * (Cu[2 + k][r] - t2k));
        }
        out[r] = (X[0][r] + a[1] * (X[1][r] - X[0][r])) + (G[0] + bb[1] * (G[1] - G[0])) +
                 (P[0] + c[1] * (P[1] - P[0]));
    }
}

/* An L^3 lattice of a twisted box with weights; faces are its boundary
 * slices (so they agree along the edges), degree 2 (several spans) or 3
 * (Bezier-like with L = 4 given as bezier-surface). */
#define L 6
static void lattice(int i, int j, int k, double p[3], double *wt)
{
    double x = (double)i / (L - 1), y = (double)j / (L - 1), z = (double)k / (L - 1);
    p[0] = 2.0 * x + 0.3 * sin(3.0 * y + 1.0) * sin(2.0 * z) - 0.4;
    p[1] = -y + 0.2 * cos(2.0 * x + 0.5) * sin(3.0 * z + 0.3);
    p[2] = 3.0 * z + 0.5 * sin(2.5 * x) * cos(1.5 * y) + 0.25 * x * y;
    *wt = 1.0 + 0.3 * sin(1.0 + i + 2.0 * j + 3.0 * k) * sin(1.0 + i + 2.0 * j + 3.0 * k);
}

/* kind 0: bspline degree 2, 1: rational bspline degree 2, 2: bezier
 * (degree L-1), 3: rational bspline degree 3 with repeated interior knots,
 * 4: as 0 with the knots scaled by 0.3 (another basis object, the same
 * surface up to rounding); on the lattice's rows 0, 2, 3, 5 (L = 6):
 * 5: bezier degree 3; on rows 0, 2, 5: 6: bezier degree 2, 7: rational
 * bspline degree 2 (Bezier-like knots); 8: bspline degree 3 on all rows,
 * not rational; 9: as 0 but rational with all weights 0.75 (the same
 * surface to rounding; beside faces of kind 0, faces of two kinds of sums:
 * the batch path does not apply); 10: bspline of degree 3 along u
 * (knots k3 below) and 2 along v and w, rational; 11: as 10, not rational
 * (faces of several degrees: the batch path's degrees at run time);
 * 12: as 1 with every point scaled by 2.5e299 (the net at most 1e300 in
 * size, so the ends keep their columns, but the s-derivative sums of the
 * Jacobian path are not bounded: its columns are not used there). */
#define LATTICE_KINDS 13
static coons_patch *lattice_face(int f, int kind)
{
    double pts[L * L * 3], wts[L * L];
    int fixed = (f & 1) ? L - 1 : 0;
    static const int rows4[4] = {0, 2, 3, 5}, rows3[3] = {0, 2, 5};
    if (kind >= 5 && kind <= 7) {
        const int n = kind == 5 ? 4 : 3;
        const int *rows = kind == 5 ? rows4 : rows3;
        for (int a = 0; a < n; a++)
            for (int b = 0; b < n; b++) {
                int ijk[3];
                if (f < 2)
                    ijk[0] = fixed, ijk[1] = rows[a], ijk[2] = rows[b];
                else if (f < 4)
                    ijk[0] = rows[a], ijk[1] = fixed, ijk[2] = rows[b];
                else
                    ijk[0] = rows[a], ijk[1] = rows[b], ijk[2] = fixed;
                lattice(ijk[0], ijk[1], ijk[2], pts + (a * n + b) * 3, wts + a * n + b);
            }
        coons_patch *p = NULL;
        coons_error err;
        if (kind == 7)
            assert_coons_ok(coons_patch_new_bspline(2, 2, pts, 3, 3, NULL, NULL, wts, &p, &err),
                            &err);
        else
            assert_coons_ok(coons_patch_new_bezier(pts, (size_t)n, (size_t)n, &p, &err), &err);
        return p;
    }
    for (int a = 0; a < L; a++)
        for (int b = 0; b < L; b++) {
            int ijk[3];
            if (f < 2)
                ijk[0] = fixed, ijk[1] = a, ijk[2] = b;
            else if (f < 4)
                ijk[0] = a, ijk[1] = fixed, ijk[2] = b;
            else
                ijk[0] = a, ijk[1] = b, ijk[2] = fixed;
            lattice(ijk[0], ijk[1], ijk[2], pts + (a * L + b) * 3, wts + a * L + b);
        }
    coons_patch *p = NULL;
    coons_error err;
    static const double k3[L + 4] = {0, 0, 0, 0, 0.5, 0.5, 2, 2, 2, 2};
    static const double k2[L + 3] = {0, 0, 0, 0.3, 0.6, 0.9, 1.2, 1.2, 1.2};
    if (kind == 2)
        assert_coons_ok(coons_patch_new_bezier(pts, L, L, &p, &err), &err);
    else if (kind == 8)
        assert_coons_ok(coons_patch_new_bspline(3, 3, pts, L, L, k3, k3, NULL, &p, &err), &err);
    else if (kind == 10 || kind == 11) {
        /* face f's (s,t): X (v,w), Y (u,w), Z (u,v); u of degree 3 */
        const int su = f >= 2;
        assert_coons_ok(coons_patch_new_bspline(su ? 3 : 2, 2, pts, L, L, su ? k3 : NULL, NULL,
                                                kind == 10 ? wts : NULL, &p, &err),
                        &err);
    } else if (kind == 12) {
        for (int i = 0; i < 3 * L * L; i++) pts[i] *= 2.5e299;
        assert_coons_ok(coons_patch_new_bspline(2, 2, pts, L, L, NULL, NULL, wts, &p, &err),
                        &err);
    } else if (kind == 9) {
        for (int i = 0; i < L * L; i++) wts[i] = 0.75;
        assert_coons_ok(coons_patch_new_bspline(2, 2, pts, L, L, NULL, NULL, wts, &p, &err),
                        &err);
    }
    else if (kind == 4)
        assert_coons_ok(coons_patch_new_bspline(2, 2, pts, L, L, k2, k2, NULL, &p, &err), &err);
    else if (kind == 3)
        assert_coons_ok(coons_patch_new_bspline(3, 3, pts, L, L, k3, k3, wts, &p, &err), &err);
    else
        assert_coons_ok(
            coons_patch_new_bspline(2, 2, pts, L, L, NULL, NULL, kind ? wts : NULL, &p, &err),
            &err);
    return p;
}

static int same_bits(const double *a, const double *b, size_t n)
{
    return memcmp(a, b, n * sizeof(double)) == 0;
}

static void check_batch(const coons_body *b, size_t n, const double *uvw)
{
    double *xyz = malloc(3 * n * sizeof(double)), *xyz2 = malloc(3 * n * sizeof(double));
    double *jac = malloc(9 * n * sizeof(double)), *det = malloc(n * sizeof(double));
    double *xyz3 = malloc(3 * n * sizeof(double)), *det2 = malloc(n * sizeof(double));
    assert_non_null(xyz && xyz2 && jac && det && xyz3 && det2);
    coons_error err;
    assert_coons_ok(coons_body_eval_points(b, n, uvw, xyz, NULL, NULL, &err), &err);
    assert_coons_ok(coons_body_eval_points(b, n, uvw, xyz2, jac, det, &err), &err);
    assert_coons_ok(coons_body_eval_points(b, n, uvw, xyz3, NULL, det2, &err), &err);
    assert_true(same_bits(xyz, xyz2, 3 * n));
    assert_true(same_bits(xyz, xyz3, 3 * n));
    assert_true(same_bits(det, det2, n));
    for (size_t i = 0; i < n; i++) {
        const double *q = uvw + 3 * i;
        double p[3], pj[3], J[3][3];
        coons_body_eval(b, q[0], q[1], q[2], p);
        double d = coons_body_eval_jacobian(b, q[0], q[1], q[2], pj, J);
        assert_true(same_bits(p, xyz + 3 * i, 3));
        assert_true(same_bits(pj, xyz + 3 * i, 3));
        assert_true(same_bits(&J[0][0], jac + 9 * i, 9));
        assert_true(same_bits(&d, det + i, 1));
    }
    free(xyz);
    free(xyz2);
    free(xyz3);
    free(jac);
    free(det);
    free(det2);
}

static void test_formula_bitwise(void **state)
{
    (void)state;
    for (int kind = 0; kind < 5; kind++)
        for (int blend = 0; blend < 2; blend++) {
            coons_patch *f[6];
            /* kind 4: faces X_i with scaled knots, the others as kind 0 */
            for (int i = 0; i < 6; i++) f[i] = lattice_face(i, kind < 4 ? kind : i < 2 ? 4 : 0);
            coons_blend bl = blend ? COONS_BLEND_CUBIC : COONS_BLEND_LINEAR;
            coons_body *b = make_body(f, bl);
            enum { N = 400 };
            double uvw[3 * N];
            tb_rng rng = {(unsigned long long)(101 + kind + 7 * blend)};
            random_points(&rng, N, uvw);
            for (size_t n = 0; n < N; n++) {
                double q[3], want[3], got[3];
                for (int r = 0; r < 3; r++) q[r] = fmin(fmax(uvw[3 * n + (size_t)r], 0.0), 1.0);
                formula(f, bl, q[0], q[1], q[2], want);
                coons_body_eval(b, uvw[3 * n], uvw[3 * n + 1], uvw[3 * n + 2], got);
                if (!same_bits(want, got, 3))
                    fail_msg("kind %d blend %d point %zu (%.17g %.17g %.17g): "
                             "%.17g %.17g %.17g, formula %.17g %.17g %.17g",
                             kind, blend, n, q[0], q[1], q[2], got[0], got[1], got[2], want[0],
                             want[1], want[2]);
            }
            check_batch(b, N, uvw);
            /* a copy evaluates as the body */
            coons_body *c = NULL;
            coons_error err;
            assert_coons_ok(coons_body_copy(b, &c, &err), &err);
            double x1[3 * N], x2[3 * N], j1[9 * N], j2[9 * N];
            assert_coons_ok(coons_body_eval_points(b, N, uvw, x1, j1, NULL, &err), &err);
            assert_coons_ok(coons_body_eval_points(c, N, uvw, x2, j2, NULL, &err), &err);
            assert_true(same_bits(x1, x2, 3 * N));
            assert_true(same_bits(j1, j2, 9 * N));
            coons_body_free(c);
            coons_body_free(b);
            free_faces(f);
        }
}

/* The same body through the general path (each face a wrapper, the
 * reparametrisation without swap or flips, whose points and partials are
 * its face's bit for bit) gives the same bits, Jacobians included. */
static void test_general_path_bitwise(void **state)
{
    (void)state;
    for (int kind = 0; kind < 5; kind++)
        for (int blend = 0; blend < 2; blend++) {
            coons_patch *f[6], *g[6];
            coons_error err;
            for (int i = 0; i < 6; i++) {
                f[i] = lattice_face(i, kind < 4 ? kind : i < 2 ? 4 : 0);
                assert_coons_ok(coons_patch_new_reparametrized(f[i], 0, 0, 0, &g[i], &err),
                                &err);
            }
            coons_blend bl = blend ? COONS_BLEND_CUBIC : COONS_BLEND_LINEAR;
            coons_body *b = make_body(f, bl), *c = make_body(g, bl);
            enum { N = 400 };
            double uvw[3 * N], x1[3 * N], x2[3 * N], j1[9 * N], j2[9 * N], d1[N], d2[N];
            tb_rng rng = {(unsigned long long)(1001 + kind + 7 * blend)};
            random_points(&rng, N, uvw);
            assert_coons_ok(coons_body_eval_points(b, N, uvw, x1, NULL, NULL, &err), &err);
            assert_coons_ok(coons_body_eval_points(c, N, uvw, x2, NULL, NULL, &err), &err);
            assert_true(same_bits(x1, x2, 3 * N));
            assert_coons_ok(coons_body_eval_points(b, N, uvw, x1, j1, d1, &err), &err);
            assert_coons_ok(coons_body_eval_points(c, N, uvw, x2, j2, d2, &err), &err);
            assert_true(same_bits(x1, x2, 3 * N));
            assert_true(same_bits(j1, j2, 9 * N));
            assert_true(same_bits(d1, d2, N));
            coons_body_free(b);
            coons_body_free(c);
            free_faces(f);
            free_faces(g);
        }
}

/*
 * The batch of points (coons_body_eval_points; body2.c's spec_points and
 * spec_points_jac where the faces are of one dim, each edge from a kept
 * row or column; lattice kinds 0-8 and 10-12) bit for bit against the general path (the
 * same faces wrapped), point by point: batches of 1..9 points at the first
 * 25 offsets of a mixed array (inside, on the faces, edges and corners,
 * outside, NaN and infinities, which are clamped), values alone and with
 * Jacobians and determinants, and single points through coons_body_eval()
 * (which takes the batch path for one point).
 */
static void test_batch_against_general(void **state)
{
    (void)state;
    enum { N = 61 };
    double uvw[3 * N];
    tb_rng rng = {4242};
    random_points(&rng, N, uvw);
    uvw[3 * 5] = NAN, uvw[3 * 9 + 1] = INFINITY, uvw[3 * 17 + 2] = -INFINITY;
    uvw[3 * 23] = -0.0, uvw[3 * 23 + 1] = 0.5, uvw[3 * 23 + 2] = 1.0;
    for (int kind = 0; kind < LATTICE_KINDS; kind++)
        for (int blend = 0; blend < 2; blend++) {
            coons_patch *f[6], *g[6];
            coons_error err;
            for (int i = 0; i < 6; i++) {
                /* kinds 4 and 9: faces X_i of that kind, the others of kind 0 */
                f[i] = lattice_face(i, kind == 4 || kind == 9 ? (i < 2 ? kind : 0) : kind);
                assert_coons_ok(coons_patch_new_reparametrized(f[i], 0, 0, 0, &g[i], &err),
                                &err);
            }
            coons_blend bl = blend ? COONS_BLEND_CUBIC : COONS_BLEND_LINEAR;
            coons_body *b = make_body(f, bl), *c = make_body(g, bl);
            double want[3 * N], wantj[3 * N], wantJ[9 * N], wantd[N];
            for (size_t i = 0; i < N; i++) {
                const double *q = uvw + 3 * i;
                coons_body_eval(c, q[0], q[1], q[2], want + 3 * i);
                wantd[i] = coons_body_eval_jacobian(c, q[0], q[1], q[2], wantj + 3 * i,
                                                    (double(*)[3])(wantJ + 9 * i));
            }
            for (size_t i = 0; i < N; i++) {
                double got[3];
                coons_body_eval(b, uvw[3 * i], uvw[3 * i + 1], uvw[3 * i + 2], got);
                if (!same_bits(got, want + 3 * i, 3))
                    fail_msg("kind %d blend %d single point %zu: %.17g %.17g %.17g, general "
                             "path %.17g %.17g %.17g",
                             kind, blend, i, got[0], got[1], got[2], want[3 * i],
                             want[3 * i + 1], want[3 * i + 2]);
            }
            for (size_t n = 1; n <= 9; n++)
                for (size_t off = 0; off + n <= N && off <= 24; off++) {
                    /* guards after the batch: nothing written past it */
                    double got[3 * 9 + 3];
                    for (size_t k = 0; k < 3 * 9 + 3; k++) got[k] = 12345.0;
                    assert_coons_ok(
                        coons_body_eval_points(b, n, uvw + 3 * off, got, NULL, NULL, &err),
                        &err);
                    if (!same_bits(got, want + 3 * off, 3 * n))
                        fail_msg("kind %d blend %d batch of %zu at %zu differs from the "
                                 "general path",
                                 kind, blend, n, off);
                    for (size_t k = 3 * n; k < 3 * 9 + 3; k++) assert_true(got[k] == 12345.0);
                    /* with Jacobians, determinants, or both */
                    double gj[9 * 9 + 9], gd[9 + 1];
                    for (size_t k = 0; k < 9 * 9 + 9; k++) gj[k] = 12345.0;
                    for (size_t k = 0; k < 9 + 1; k++) gd[k] = 12345.0;
                    for (int mode = 0; mode < 3; mode++) {
                        assert_coons_ok(coons_body_eval_points(b, n, uvw + 3 * off, got,
                                                               mode != 1 ? gj : NULL,
                                                               mode != 0 ? gd : NULL, &err),
                                        &err);
                        if (!same_bits(got, wantj + 3 * off, 3 * n) ||
                            (mode != 1 && !same_bits(gj, wantJ + 9 * off, 9 * n)) ||
                            (mode != 0 && !same_bits(gd, wantd + off, n)))
                            fail_msg("kind %d blend %d batch of %zu at %zu (mode %d) with "
                                     "Jacobians differs from the general path",
                                     kind, blend, n, off, mode);
                    }
                    for (size_t k = 9 * n; k < 9 * 9 + 9; k++) assert_true(gj[k] == 12345.0);
                    for (size_t k = n; k < 9 + 1; k++) assert_true(gd[k] == 12345.0);
                }
            /* the whole array at once, and through the general path's batch */
            double x1[3 * N], x2[3 * N];
            assert_coons_ok(coons_body_eval_points(b, N, uvw, x1, NULL, NULL, &err), &err);
            assert_coons_ok(coons_body_eval_points(c, N, uvw, x2, NULL, NULL, &err), &err);
            assert_true(same_bits(x1, want, 3 * N));
            assert_true(same_bits(x2, want, 3 * N));
            coons_body_free(b);
            coons_body_free(c);
            free_faces(f);
            free_faces(g);
        }
}

/* The Jacobian of the lattice bodies against central differences. */
static void test_jacobian_differences(void **state)
{
    (void)state;
    for (int kind = 0; kind < 4; kind++) {
        coons_patch *f[6];
        for (int i = 0; i < 6; i++) f[i] = lattice_face(i, kind);
        coons_body *b = make_body(f, COONS_BLEND_CUBIC);
        tb_rng rng = {(unsigned long long)(7 + kind)};
        for (int n = 0; n < 100; n++) {
            double q[3], p[3], J[3][3], h = 1e-6;
            /* inside, away from the knots 0.5 of kind 3 by more than h */
            for (int r = 0; r < 3; r++) q[r] = 0.01 + 0.98 * tb_rand(&rng);
            coons_body_eval_jacobian(b, q[0], q[1], q[2], p, J);
            for (int c = 0; c < 3; c++) {
                double qa[3] = {q[0], q[1], q[2]}, qb[3] = {q[0], q[1], q[2]}, pa[3], pb[3];
                qa[c] += h;
                qb[c] -= h;
                coons_body_eval(b, qa[0], qa[1], qa[2], pa);
                coons_body_eval(b, qb[0], qb[1], qb[2], pb);
                for (int r = 0; r < 3; r++)
                    assert_true(fabs((pa[r] - pb[r]) / (2 * h) - J[r][c]) <
                                1e-5 * (1.0 + fabs(J[r][c])));
            }
        }
        coons_body_free(b);
        free_faces(f);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_form),
        cmocka_unit_test(test_formula_bitwise),
        cmocka_unit_test(test_general_path_bitwise),
        cmocka_unit_test(test_batch_against_general),
        cmocka_unit_test(test_jacobian_differences),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
