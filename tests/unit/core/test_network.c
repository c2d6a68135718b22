/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The network patch (seed 001 section 1.2.2; coons-model(5) "Networks of
 * curves"):
 * - one cell equals the hermite-coons patch of its four curves with the
 *   same twist rule (zero, adini, bessel), point and all partials;
 * - rows and columns cut exactly from x(s,t) = f(s) + g(t) + c s t (f, g
 *   cubic) reproduce it to 1e-12 with bessel and adini twists (whose node
 *   twist is then c), on uniform and non-uniform nodes; zero twists do
 *   not;
 * - across inner rows and columns the cross derivative, measured by
 *   one-sided finite differences from both sides, is continuous with the
 *   cubic blend and jumps with the linear one; coons_patch_network_seams
 *   reports the same jumps;
 * - straight lines on a regular grid give the plane;
 * - first and second partials against finite differences, grid = eval;
 * - the loader: the node error names the node, both curves' JSON paths and
 *   the distance; a network as a referenced, transformed definition.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "patch_fixture.h"
#include "test_util.h"

static const double C_TW[3] = {0.7, -0.4, 1.1};

/* f(s) and g(t): cubic polynomials, coefficients [degree][xyz]. */
static const double F[4][3] = {{0.0, 0.0, 0.0}, {3.0, 0.2, -0.5}, {-0.4, 1.0, 0.8}, {0.6, -0.3, 0.9}};
static const double G[4][3] = {{0.1, 0.0, 0.3}, {0.3, 2.5, 0.4}, {0.5, -0.6, -1.2}, {-0.2, 0.4, 0.7}};

static void poly(const double a[4][3], double x, double o[3])
{
    for (int k = 0; k < 3; k++) o[k] = a[0][k] + x * (a[1][k] + x * (a[2][k] + x * a[3][k]));
}

/* The exact surface and its partials. */
static void exact(double s, double t, double d[6][3])
{
    double f[3], g[3];
    poly(F, s, f);
    poly(G, t, g);
    for (int k = 0; k < 3; k++) {
        d[0][k] = f[k] + g[k] + C_TW[k] * s * t;
        d[1][k] = F[1][k] + 2 * F[2][k] * s + 3 * F[3][k] * s * s + C_TW[k] * t;
        d[2][k] = G[1][k] + 2 * G[2][k] * t + 3 * G[3][k] * t * t + C_TW[k] * s;
        d[3][k] = 2 * F[2][k] + 6 * F[3][k] * s;
        d[4][k] = C_TW[k];
        d[5][k] = 2 * G[2][k] + 6 * G[3][k] * t;
    }
}

/* The cubic a0 + a1 x + a2 x^2 + a3 x^3 as a Bezier curve. */
static coons_curve *bezier_of(double a[4][3])
{
    double p[12];
    for (int k = 0; k < 3; k++) {
        p[k] = a[0][k];
        p[3 + k] = a[0][k] + a[1][k] / 3;
        p[6 + k] = a[0][k] + 2 * a[1][k] / 3 + a[2][k] / 3;
        p[9 + k] = a[0][k] + a[1][k] + a[2][k] + a[3][k];
    }
    coons_curve *c = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_bezier(p, 4, &c, &err), &err);
    return c;
}

/* Row x(s, t0) and column x(s0, t) of the exact surface. */
static coons_curve *exact_row(double t0)
{
    double a[4][3], g[3];
    poly(G, t0, g);
    for (int k = 0; k < 3; k++) {
        a[0][k] = F[0][k] + g[k];
        a[1][k] = F[1][k] + C_TW[k] * t0;
        a[2][k] = F[2][k];
        a[3][k] = F[3][k];
    }
    return bezier_of(a);
}

static coons_curve *exact_col(double s0)
{
    double a[4][3], f[3];
    poly(F, s0, f);
    for (int k = 0; k < 3; k++) {
        a[0][k] = G[0][k] + f[k];
        a[1][k] = G[1][k] + C_TW[k] * s0;
        a[2][k] = G[2][k];
        a[3][k] = G[3][k];
    }
    return bezier_of(a);
}

static void free_curves(coons_curve **c, size_t n)
{
    for (size_t k = 0; k < n; k++) coons_curve_free(c[k]);
}

static coons_patch *exact_network(const double *sn, size_t nc, const double *tn, size_t nr,
                                  coons_twist tw, coons_blend bl)
{
    coons_curve *rows[8], *cols[8];
    for (size_t j = 0; j < nr; j++) rows[j] = exact_row(tn[j]);
    for (size_t i = 0; i < nc; i++) cols[i] = exact_col(sn[i]);
    coons_network_options o = COONS_NETWORK_OPTIONS_INIT;
    o.s_nodes = sn;
    o.t_nodes = tn;
    o.twist = tw;
    o.blend = bl;
    coons_patch *p = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_patch_new_network(rows, nr, cols, nc, &o, &p, &err), &err);
    free_curves(rows, nr);
    free_curves(cols, nc);
    return p;
}

/* Largest |x - exact| over a 41 x 41 grid (points and, if derivs, all
 * partials), relative to 1 + |exact|. */
static double exact_error(const coons_patch *p, int derivs)
{
    double worst = 0.0;
    for (int i = 0; i <= 40; i++)
        for (int j = 0; j <= 40; j++) {
            double s = i / 40.0, t = j / 40.0, d[6][3], e[6][3];
            coons_patch_eval_derivs(p, s, t, 2, d);
            exact(s, t, e);
            for (int q = 0; q < (derivs ? 6 : 1); q++)
                for (int k = 0; k < 3; k++) {
                    double r = fabs(d[q][k] - e[q][k]) / (1.0 + fabs(e[q][k]));
                    if (r > worst) worst = r;
                }
        }
    return worst;
}

/* Given rows and columns of f(s) + g(t) + c s t, then bessel and adini
 * networks reproduce it (and its partials) to 1e-12 on uniform and
 * non-uniform nodes, and zero twists do not. */
static void test_exact_surface(void **state)
{
    (void)state;
    const double su[4] = {0, 1.0 / 3, 2.0 / 3, 1}, tu[3] = {0, 0.5, 1};
    const double sv[4] = {0, 0.17, 0.6, 1}, tv[3] = {0, 0.72, 1};
    const double *S[2] = {su, sv}, *T[2] = {tu, tv};
    for (int g = 0; g < 2; g++) {
        for (int tw = COONS_TWIST_ADINI; tw <= COONS_TWIST_BESSEL; tw++) {
            coons_patch *p = exact_network(S[g], 4, T[g], 3, (coons_twist)tw, COONS_BLEND_CUBIC);
            double e = exact_error(p, 1);
            if (!(e <= 1e-12)) fail_msg("grid %d twist %d: error %g", g, tw, e);
            coons_patch_free(p);
        }
        coons_patch *z = exact_network(S[g], 4, T[g], 3, COONS_TWIST_ZERO, COONS_BLEND_CUBIC);
        assert_true(exact_error(z, 0) > 1e-3);
        coons_patch_free(z);
    }
}

/* Given one cell, then the network equals hermite-coons of its four curves
 * for each twist rule, point and partials, to 1e-12. */
static void test_one_cell(void **state)
{
    (void)state;
    fx_boundary b;
    fx_boundary_make(&b);
    coons_error err = COONS_ERROR_INIT;
    coons_curve *rows[2] = {b.c[COONS_SIDE_T0], b.c[COONS_SIDE_T1]};
    coons_curve *cols[2] = {b.c[COONS_SIDE_S0], b.c[COONS_SIDE_S1]};
    const coons_twist tws[3] = {COONS_TWIST_ZERO, COONS_TWIST_ADINI, COONS_TWIST_BESSEL};
    for (int k = 0; k < 3; k++) {
        coons_network_options o = COONS_NETWORK_OPTIONS_INIT;
        o.twist = tws[k];
        coons_hermite_options ho = COONS_HERMITE_OPTIONS_INIT;
        ho.twist = tws[k];
        coons_patch *n = NULL, *h = NULL;
        assert_coons_ok(coons_patch_new_network(rows, 2, cols, 2, &o, &n, &err), &err);
        assert_coons_ok(coons_patch_new_hermite_coons(fx_curves(&b), &ho, &h, &err), &err);
        assert_int_equal(coons_patch_kind(n), COONS_PATCH_NETWORK);
        for (int i = 0; i <= 20; i++)
            for (int j = 0; j <= 20; j++) {
                double d1[6][3], d2[6][3];
                coons_patch_eval_derivs(n, i / 20.0, j / 20.0, 2, d1);
                coons_patch_eval_derivs(h, i / 20.0, j / 20.0, 2, d2);
                for (int q = 0; q < 6; q++) assert_vec3_near(d1[q], d2[q], 1e-12 * fx_scale(d2[q]));
            }
        coons_patch_free(n);
        coons_patch_free(h);
    }
    fx_boundary_free(&b);
}

/* A generic smooth network: the iso-curves of a bicubic Bezier surface
 * (rows and columns are Bezier curves), on non-uniform nodes, which no
 * twist rule reproduces exactly. */
static const double NET[4][4][3] = {
    {{0, 0, 0}, {0, 1, 0.5}, {0, 2, -0.3}, {0, 3, 0.2}},
    {{1, 0, 0.4}, {1.2, 1, 1.5}, {0.8, 2, 0.9}, {1, 3, -0.4}},
    {{2, 0, -0.6}, {2.1, 1, 0.2}, {1.9, 2, 1.6}, {2, 3, 0.5}},
    {{3, 0, 0.1}, {3, 1, -0.7}, {3, 2, 0.4}, {3, 3, 1.0}}};

static double bern(int i, double x)
{
    static const double C[4] = {1, 3, 3, 1};
    return C[i] * pow(x, i) * pow(1 - x, 3 - i);
}

static coons_curve *iso(int dir, double x)
{
    double p[12] = {0};
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++)
            for (int k = 0; k < 3; k++) {
                /* dir 0: row t = x, control point a along s */
                double w = bern(b, x);
                p[3 * a + k] += w * (dir == 0 ? NET[a][b][k] : NET[b][a][k]);
            }
    coons_curve *c = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_bezier(p, 4, &c, &err), &err);
    return c;
}

static const double GS[4] = {0, 0.3, 0.55, 1}, GT[3] = {0, 0.4, 1};

static coons_patch *generic(coons_twist tw, coons_blend bl)
{
    coons_curve *rows[3], *cols[4];
    for (int j = 0; j < 3; j++) rows[j] = iso(0, GT[j]);
    for (int i = 0; i < 4; i++) cols[i] = iso(1, GS[i]);
    coons_network_options o = COONS_NETWORK_OPTIONS_INIT;
    o.s_nodes = GS;
    o.t_nodes = GT;
    o.twist = tw;
    o.blend = bl;
    coons_patch *p = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_patch_new_network(rows, 3, cols, 4, &o, &p, &err), &err);
    free_curves(rows, 3);
    free_curves(cols, 4);
    return p;
}

/* Second-order one-sided difference of x along s (dir 0) or t at (s,t),
 * from below (side -1) or above (+1). */
static void one_sided(const coons_patch *p, int dir, double s, double t, int side, double out[3])
{
    const double h = 1e-5 * side;
    double x0[3], x1[3], x2[3];
    coons_patch_eval(p, s, t, x0);
    coons_patch_eval(p, s + (dir == 0 ? h : 0), t + (dir == 1 ? h : 0), x1);
    coons_patch_eval(p, s + (dir == 0 ? 2 * h : 0), t + (dir == 1 ? 2 * h : 0), x2);
    for (int k = 0; k < 3; k++) out[k] = (-3 * x0[k] + 4 * x1[k] - x2[k]) / (2 * h);
}

/* Largest relative jump of the cross derivative across the inner seams,
 * measured by finite differences from both sides. */
static double fd_defect(const coons_patch *p, int dir, double x)
{
    double worst = 0.0;
    for (int m = 1; m < 32; m++) {
        double y = m / 32.0, a[3], b[3];
        double s = dir == 0 ? x : y, t = dir == 0 ? y : x;
        one_sided(p, dir, s, t, -1, a);
        one_sided(p, dir, s, t, +1, b);
        double big = fmax(sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]),
                          sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]));
        double d = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                        (a[2] - b[2]) * (a[2] - b[2])) /
                   big;
        if (d > worst) worst = d;
    }
    return worst;
}

/* Given a generic network, then with the cubic blend the cross
 * derivative is continuous across every inner column and row (finite
 * differences from both sides agree to 1e-7), and with the linear blend
 * it jumps (> 1e-2 somewhere); the seams report says the same. */
static void test_c1_across(void **state)
{
    (void)state;
    const coons_twist tws[3] = {COONS_TWIST_ZERO, COONS_TWIST_ADINI, COONS_TWIST_BESSEL};
    for (int k = 0; k < 3; k++) {
        coons_patch *p = generic(tws[k], COONS_BLEND_CUBIC);
        for (int i = 1; i < 3; i++) assert_true(fd_defect(p, 0, GS[i]) < 1e-7);
        assert_true(fd_defect(p, 1, GT[1]) < 1e-7);
        coons_network_seam seams[8];
        size_t n = 0;
        coons_error err = COONS_ERROR_INIT;
        assert_coons_ok(coons_patch_network_seams(p, seams, 8, &n, &err), &err);
        assert_int_equal(n, 3);
        for (size_t q = 0; q < n; q++) {
            assert_true(seams[q].c1_defect < 1e-12);
            assert_true(seams[q].g1_angle < 1e-6);
        }
        coons_patch_free(p);
    }
    coons_patch *l = generic(COONS_TWIST_BESSEL, COONS_BLEND_LINEAR);
    coons_network_seam seams[8];
    size_t n = 0;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_patch_network_seams(l, seams, 8, &n, &err), &err);
    assert_int_equal(n, 3);
    double fd[3] = {fd_defect(l, 0, GS[1]), fd_defect(l, 0, GS[2]), fd_defect(l, 1, GT[1])};
    const double where[3] = {GS[1], GS[2], GT[1]};
    for (int q = 0; q < 3; q++) {
        assert_true(fd[q] > 1e-2);
        assert_int_equal(seams[q].dir, q < 2 ? 0 : 1);
        assert_near(seams[q].param, where[q], 0.0);
        /* the exact measure at 65 points is at least the 31-point FD one */
        assert_true(seams[q].c1_defect >= fd[q] * (1 - 1e-4));
        assert_true(seams[q].c1_defect < 10 * fd[q]);
        assert_true(seams[q].g1_angle > 0.1);
    }
    coons_patch_free(l);
}

/* Given straight lines on a regular grid, then every twist and blend gives
 * the plane x = (s W, t H, 0). */
static void test_plane(void **state)
{
    (void)state;
    const double W = 4.0, H = 2.5;
    coons_curve *rows[4], *cols[5];
    coons_error err = COONS_ERROR_INIT;
    for (int j = 0; j < 4; j++) {
        double a[3] = {0, H * j / 3.0, 0}, b[3] = {W, H * j / 3.0, 0};
        assert_coons_ok(coons_curve_new_line(a, b, &rows[j], &err), &err);
    }
    for (int i = 0; i < 5; i++) {
        double a[3] = {W * i / 4.0, 0, 0}, b[3] = {W * i / 4.0, H, 0};
        assert_coons_ok(coons_curve_new_line(a, b, &cols[i], &err), &err);
    }
    for (int tw = COONS_TWIST_ZERO; tw <= COONS_TWIST_BESSEL; tw++)
        for (int bl = 0; bl < 2; bl++) {
            coons_network_options o = COONS_NETWORK_OPTIONS_INIT;
            o.twist = (coons_twist)tw;
            o.blend = bl ? COONS_BLEND_LINEAR : COONS_BLEND_CUBIC;
            coons_patch *p = NULL;
            assert_coons_ok(coons_patch_new_network(rows, 4, cols, 5, &o, &p, &err), &err);
            for (int i = 0; i <= 30; i++)
                for (int j = 0; j <= 30; j++) {
                    double x[3], want[3] = {W * i / 30.0, H * j / 30.0, 0};
                    coons_patch_eval(p, i / 30.0, j / 30.0, x);
                    assert_vec3_near(x, want, 1e-12 * W);
                }
            coons_patch_free(p);
        }
    free_curves(rows, 4);
    free_curves(cols, 5);
}

/* Given networks of mixed curve kinds and a generic one, then partials
 * agree with finite differences and grids with eval. */
static void test_derivs(void **state)
{
    (void)state;
    coons_patch *p = generic(COONS_TWIST_ADINI, COONS_BLEND_CUBIC);
    fx_check_derivs_fd(p, 1e-6);
    fx_check_grid(p);
    coons_patch *q = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_patch_copy(p, &q, &err), &err);
    fx_check_grid(q);
    coons_patch_free(p);
    coons_patch_free(q);
    p = generic(COONS_TWIST_ZERO, COONS_BLEND_LINEAR);
    fx_check_derivs_fd(p, 1e-6);
    /* the wrappers of references: transform and reparametrisation, whose
     * second partials follow by M and the chain rule */
    const double M[12] = {0, -1, 0.3, 10, 1, 0, 0, -2, 0, 0.5, 2, 0.5};
    coons_patch *tp = NULL, *rp = NULL;
    assert_coons_ok(coons_patch_new_transformed(p, M, &tp, &err), &err);
    assert_coons_ok(coons_patch_new_reparametrized(tp, 1, 1, 0, &rp, &err), &err);
    fx_check_derivs_fd(tp, 1e-6);
    fx_check_derivs_fd(rp, 1e-6);
    assert_int_equal(coons_patch_kind(rp), COONS_PATCH_NETWORK);
    /* the seams seen through them: the same defects; a swap makes columns rows */
    coons_network_seam a[3], sb[3];
    size_t na = 0, nb = 0;
    assert_coons_ok(coons_patch_network_seams(p, a, 3, &na, &err), &err);
    assert_coons_ok(coons_patch_network_seams(rp, sb, 3, &nb, &err), &err);
    assert_int_equal(na, 3);
    assert_int_equal(nb, 3);
    for (int k = 0; k < 3; k++) {
        assert_int_equal(sb[k].dir, 1 - a[k].dir);
        assert_true(a[k].c1_defect > 1e-3 && sb[k].c1_defect > 1e-3);
        /* flip_s (the network's s after the swap) mirrors the columns */
        assert_near(sb[k].param, a[k].dir == 0 ? 1 - a[k].param : a[k].param, 1e-15);
    }
    coons_patch_free(tp);
    coons_patch_free(rp);
    coons_patch_free(p);
    fx_boundary b;
    fx_boundary_make(&b);
    coons_curve *rows[2] = {b.c[COONS_SIDE_T0], b.c[COONS_SIDE_T1]};
    coons_curve *cols[2] = {b.c[COONS_SIDE_S0], b.c[COONS_SIDE_S1]};
    assert_coons_ok(coons_patch_new_network(rows, 2, cols, 2, NULL, &p, &err), &err);
    fx_check_derivs_fd(p, 1e-6);
    coons_patch_free(p);
    fx_boundary_free(&b);
}

/* Given bad arguments, then the constructor refuses and says why. */
static void test_invalid(void **state)
{
    (void)state;
    coons_curve *rows[3], *cols[4];
    for (int j = 0; j < 3; j++) rows[j] = iso(0, GT[j]);
    for (int i = 0; i < 4; i++) cols[i] = iso(1, GS[i]);
    coons_network_options o = COONS_NETWORK_OPTIONS_INIT;
    coons_patch *p = NULL;
    coons_error err = COONS_ERROR_INIT;
    /* uniform nodes do not match curves cut at GS, GT */
    assert_int_equal(coons_patch_new_network(rows, 3, cols, 4, &o, &p, &err),
                     COONS_E_INCOMPATIBLE);
    assert_non_null(strstr(err.message, "node (1, 0)"));
    assert_null(p);
    const double bad[4] = {0, 0.55, 0.3, 1};
    o.s_nodes = bad;
    o.t_nodes = GT;
    assert_int_equal(coons_patch_new_network(rows, 3, cols, 4, &o, &p, &err), COONS_E_INVALID);
    assert_non_null(strstr(err.message, "s_nodes"));
    o.s_nodes = GS;
    o.twist = COONS_TWIST_EXPLICIT;
    assert_int_equal(coons_patch_new_network(rows, 3, cols, 4, &o, &p, &err), COONS_E_INVALID);
    o.twist = COONS_TWIST_BESSEL;
    assert_int_equal(coons_patch_new_network(rows, 1, cols, 4, &o, &p, &err), COONS_E_INVALID);
    assert_coons_ok(coons_patch_new_network(rows, 3, cols, 4, &o, &p, &err), &err);
    coons_network_seam sm[1];
    size_t n = 0;
    assert_coons_ok(coons_patch_network_seams(p, sm, 1, &n, &err), &err);
    assert_int_equal(n, 3); /* the count, though only one was written */
    coons_patch_free(p);
    coons_patch *bl = NULL;
    assert_coons_ok(coons_patch_new_bilinear(fx_corner[0], &bl, &err), &err);
    assert_int_equal(coons_patch_network_seams(bl, NULL, 0, &n, &err), COONS_E_INVALID);
    coons_patch_free(bl);
    free_curves(rows, 3);
    free_curves(cols, 4);
}

/* A bezier curve's JSON with points P0..P3 of a cubic. */
static void json_cubic(char *out, size_t cap, double a[4][3])
{
    double p[12];
    for (int k = 0; k < 3; k++) {
        p[k] = a[0][k];
        p[3 + k] = a[0][k] + a[1][k] / 3;
        p[6 + k] = a[0][k] + 2 * a[1][k] / 3 + a[2][k] / 3;
        p[9 + k] = a[0][k] + a[1][k] + a[2][k] + a[3][k];
    }
    snprintf(out, cap,
             "{\"type\": \"bezier\", \"points\": [[%.17g,%.17g,%.17g],[%.17g,%.17g,%.17g],"
             "[%.17g,%.17g,%.17g],[%.17g,%.17g,%.17g]]}",
             p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], p[9], p[10], p[11]);
}

/* The exact-surface network as JSON (2 x 3 cells; column 1 moved by dz). */
static char *network_json(double dz, const char *extra)
{
    const double sn[3] = {0, 0.4, 1}, tn[4] = {0, 0.25, 0.6, 1};
    size_t cap = 16384, len = 0;
    char *buf = malloc(cap), cur[1024];
    len += (size_t)snprintf(buf + len, cap - len,
                            "{\"type\": \"network\", \"s_nodes\": [0, 0.4, 1], "
                            "\"t_nodes\": [0, 0.25, 0.6, 1]%s,\n \"rows\": [",
                            extra);
    for (int j = 0; j < 4; j++) {
        double a[4][3], g[3];
        poly(G, tn[j], g);
        for (int k = 0; k < 3; k++) {
            a[0][k] = F[0][k] + g[k];
            a[1][k] = F[1][k] + C_TW[k] * tn[j];
            a[2][k] = F[2][k];
            a[3][k] = F[3][k];
        }
        json_cubic(cur, sizeof cur, a);
        len += (size_t)snprintf(buf + len, cap - len, "%s%s", j ? ",\n  " : "", cur);
    }
    len += (size_t)snprintf(buf + len, cap - len, "],\n \"columns\": [");
    for (int i = 0; i < 3; i++) {
        double a[4][3], f[3];
        poly(F, sn[i], f);
        for (int k = 0; k < 3; k++) {
            a[0][k] = G[0][k] + f[k] + (i == 1 && k == 2 ? dz : 0);
            a[1][k] = G[1][k] + C_TW[k] * sn[i];
            a[2][k] = G[2][k];
            a[3][k] = G[3][k];
        }
        json_cubic(cur, sizeof cur, a);
        len += (size_t)snprintf(buf + len, cap - len, "%s%s", i ? ",\n  " : "", cur);
    }
    snprintf(buf + len, cap - len, "]}");
    return buf;
}

static coons_status load(const char *json, coons_model **m, coons_error *e)
{
    return coons_model_load_memory(json, strlen(json), "net.json", NULL, m, e);
}

/* Given a model with a network defined once and referenced through a
 * transform as a shell's surface, then the shell's mid-surface is the
 * transformed exact surface; a moved column is an error naming node
 * (1, 0), both curves' paths and the distance. */
static void test_loader(void **state)
{
    (void)state;
    const double M[12] = {0, -1, 0, 10, 1, 0, 0, -2, 0, 0, 2, 0.5};
    char *net = network_json(0.0, ", \"twist\": \"adini\"");
    size_t cap = 65536;
    char *doc = malloc(cap);
    snprintf(doc, cap,
             "{\"coons\": 1, \"define\": {\"net\": %s},\n"
             " \"bodies\": [{\"type\": \"shell\", \"thickness\": 0.01, \"surface\": "
             "{\"ref\": \"net\", \"transform\": [[0,-1,0,10],[1,0,0,-2],[0,0,2,0.5]]}}]}",
             net);
    coons_model *m = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(load(doc, &m, &e), &e);
    const coons_body *b = coons_model_body(m, 0);
    for (int i = 0; i <= 10; i++)
        for (int j = 0; j <= 10; j++) {
            double x[3], d[6][3], want[3];
            coons_body_eval(b, i / 10.0, j / 10.0, 0.5, x);
            exact(i / 10.0, j / 10.0, d);
            for (int r = 0; r < 3; r++)
                want[r] = M[4 * r] * d[0][0] + M[4 * r + 1] * d[0][1] + M[4 * r + 2] * d[0][2] +
                          M[4 * r + 3];
            assert_vec3_near(x, want, 1e-11);
        }
    coons_model_free(m);
    free(doc);
    free(net);

    char *badnet = network_json(0.01, "");
    char *bad = malloc(cap);
    snprintf(bad, cap,
             "{\"coons\": 1, \"bodies\": [{\"type\": \"shell\", \"thickness\": 1, \"surface\": "
             "%s}]}",
             badnet);
    m = NULL;
    assert_int_equal(load(bad, &m, &e), COONS_E_INCOMPATIBLE);
    assert_null(m);
    assert_non_null(strstr(e.message, "node (1, 0)"));
    assert_non_null(strstr(e.message, "/bodies/0/surface/rows/0"));
    assert_non_null(strstr(e.message, "/bodies/0/surface/columns/1"));
    assert_non_null(strstr(e.message, "0.01 apart"));
    assert_string_equal(e.path, "/bodies/0/surface/rows/0");
    free(bad);
    free(badnet);
}

/* Given rows with a kink at the inner node (a roof: polylines up to the
 * ridge and down), then each cell takes its own one-sided tangents: the
 * network is the two planes exactly, and the seam report sees the kink. */
static void test_kink(void **state)
{
    (void)state;
    coons_curve *rows[2], *cols[3];
    coons_error err = COONS_ERROR_INIT;
    for (int j = 0; j < 2; j++) {
        double p[9] = {0, j, 0, 1, j, 1, 2, j, 0};
        assert_coons_ok(coons_curve_new_polyline(p, 3, &rows[j], &err), &err);
    }
    for (int i = 0; i < 3; i++) {
        double a[3] = {i, 0, i == 1}, b[3] = {i, 1, i == 1};
        assert_coons_ok(coons_curve_new_line(a, b, &cols[i], &err), &err);
    }
    coons_patch *p = NULL;
    assert_coons_ok(coons_patch_new_network(rows, 2, cols, 3, NULL, &p, &err), &err);
    for (int i = 0; i <= 20; i++)
        for (int j = 0; j <= 10; j++) {
            double s = i / 20.0, t = j / 10.0, d[3][3];
            double want[3] = {2 * s, t, s <= 0.5 ? 2 * s : 2 - 2 * s};
            double ws[3] = {2, 0, s < 0.5 ? 2 : -2}, wt[3] = {0, 1, 0};
            coons_patch_eval_derivs(p, s, t, 1, d);
            assert_vec3_near(d[0], want, 1e-12);
            assert_vec3_near(d[1], ws, 1e-6);
            assert_vec3_near(d[2], wt, 1e-6);
        }
    /* across the ridge x_s jumps from (2, 0, 2) to (2, 0, -2): relative
     * defect |(0, 0, 4)| / |(2, 0, 2)| = sqrt 2, planes z = x and z = -x at
     * 90 degrees */
    coons_network_seam sm[1];
    size_t n = 0;
    assert_coons_ok(coons_patch_network_seams(p, sm, 1, &n, &err), &err);
    assert_int_equal(n, 1);
    assert_near(sm[0].c1_defect, sqrt(2.0), 1e-6);
    assert_near(sm[0].g1_angle, 90.0, 1e-4);
    coons_patch_free(p);
    free_curves(rows, 2);
    free_curves(cols, 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_cell),      cmocka_unit_test(test_exact_surface),
        cmocka_unit_test(test_c1_across),     cmocka_unit_test(test_plane),
        cmocka_unit_test(test_derivs),        cmocka_unit_test(test_invalid),
        cmocka_unit_test(test_loader),        cmocka_unit_test(test_kink),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
