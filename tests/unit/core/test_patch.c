/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Bilinear, ruled, Coons (seed 001 eq. 1.2, 1.8/1.11) and Hermite Coons
 * patches (eq. 1.13-1.16): boundary interpolation, the equivalences the
 * seed implies, twists, cross-boundary tangents, derivatives against finite
 * differences, grids, copies and error reports. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "patch_fixture.h"

static const double par11[11] = {0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};

/* Hermite options with the given twist kind and no cross curves. */
static coons_hermite_options hopts(coons_twist tw)
{
    coons_hermite_options o = COONS_HERMITE_OPTIONS_INIT;
    o.twist = tw;
    if (tw == COONS_TWIST_EXPLICIT) {
        const double T[4][3] = {{0.3, -0.2, 0.1}, {-0.5, 0.4, 0.2}, {0.1, 0.1, -0.6}, {0.7, 0.0, 0.3}};
        memcpy(o.twists, T, sizeof T);
    }
    return o;
}

/* Cross curves compatible with the fixture's corner tangents and with the
 * explicit twists tw (cubic Hermite curves: value = corner tangent,
 * derivative = twist at each end). */
static void make_cross(const fx_boundary *b, double tw[4][3], coons_curve *cross[4])
{
    coons_error err = COONS_ERROR_INIT;
    double xs[4][3], xt[4][3], r[2][3];
    for (int k = 0; k < 4; k++) {
        int a = k & 1, bb = k >> 1;
        coons_curve_eval_derivs(b->c[bb ? COONS_SIDE_T1 : COONS_SIDE_T0], a, 1, r);
        memcpy(xs[k], r[1], sizeof r[1]);
        coons_curve_eval_derivs(b->c[a ? COONS_SIDE_S1 : COONS_SIDE_S0], bb, 1, r);
        memcpy(xt[k], r[1], sizeof r[1]);
    }
    /* x_t(s,b): from x_t(0,b) to x_t(1,b), d/ds = x_st(0,b), x_st(1,b) */
    assert_coons_ok(coons_curve_new_hermite(xt[0], tw[0], xt[1], tw[1], &cross[0], &err), &err);
    assert_coons_ok(coons_curve_new_hermite(xt[2], tw[2], xt[3], tw[3], &cross[1], &err), &err);
    /* x_s(a,t): from x_s(a,0) to x_s(a,1), d/dt = x_st(a,0), x_st(a,1) */
    assert_coons_ok(coons_curve_new_hermite(xs[0], tw[0], xs[2], tw[2], &cross[2], &err), &err);
    assert_coons_ok(coons_curve_new_hermite(xs[1], tw[1], xs[3], tw[3], &cross[3], &err), &err);
}

/* Every Boolean-sum patch of the fixture boundary (with cross curves for
 * the last one). */
#define NKINDS 7
static coons_patch *make_kind(const fx_boundary *b, int kind, coons_curve *cross[4])
{
    coons_error err = COONS_ERROR_INIT;
    coons_patch *p = NULL;
    if (kind == 0) {
        assert_coons_ok(coons_patch_new_coons(fx_curves(b), COONS_BLEND_LINEAR, 0.0, &p, &err), &err);
    } else if (kind == 1) {
        assert_coons_ok(coons_patch_new_coons(fx_curves(b), COONS_BLEND_CUBIC, 0.0, &p, &err), &err);
    } else if (kind <= 5) {
        coons_hermite_options o = hopts((coons_twist)(kind - 2));
        assert_coons_ok(coons_patch_new_hermite_coons(fx_curves(b), &o, &p, &err), &err);
    } else {
        coons_hermite_options o = hopts(COONS_TWIST_EXPLICIT);
        make_cross(b, o.twists, cross);
        for (int k = 0; k < 4; k++) o.cross[k] = cross[k];
        assert_coons_ok(coons_patch_new_hermite_coons(fx_curves(b), &o, &p, &err), &err);
    }
    return p;
}

static void free_cross(coons_curve *cross[4])
{
    for (int k = 0; k < 4; k++) {
        coons_curve_free(cross[k]);
        cross[k] = NULL;
    }
}

static void check_boundary(const coons_patch *p, coons_curve *const *c, double tol)
{
    for (int i = 0; i < 11; i++) {
        double u = par11[i], x[3], y[3];
        coons_patch_eval(p, u, 0.0, x);
        coons_curve_eval(c[COONS_SIDE_T0], u, y);
        assert_vec3_near(x, y, tol);
        coons_patch_eval(p, u, 1.0, x);
        coons_curve_eval(c[COONS_SIDE_T1], u, y);
        assert_vec3_near(x, y, tol);
        coons_patch_eval(p, 0.0, u, x);
        coons_curve_eval(c[COONS_SIDE_S0], u, y);
        assert_vec3_near(x, y, tol);
        coons_patch_eval(p, 1.0, u, x);
        coons_curve_eval(c[COONS_SIDE_S1], u, y);
        assert_vec3_near(x, y, tol);
    }
}

/* Boundary t0 = O (a point), t1 = E (a point), s0 = the line O-E, s1 =
 * the polyline O-Q-E: every term but the s-blend cancels, so
 * x(s,1/2) = g0(s) s0(1/2) + g1(s) s1(1/2) = (g1(s), 0, 1/2). */
static void blend_probe(coons_blend blend, double s, double *g1)
{
    coons_error err = COONS_ERROR_INIT;
    const double O[3] = {0, 0, 0}, E[3] = {0, 0, 1}, Q[3] = {1, 0, 0.5};
    const double poly[9] = {O[0], O[1], O[2], Q[0], Q[1], Q[2], E[0], E[1], E[2]};
    coons_curve *c[4];
    assert_coons_ok(coons_curve_new_line(O, O, &c[COONS_SIDE_T0], &err), &err);
    assert_coons_ok(coons_curve_new_line(E, E, &c[COONS_SIDE_T1], &err), &err);
    assert_coons_ok(coons_curve_new_line(O, E, &c[COONS_SIDE_S0], &err), &err);
    assert_coons_ok(coons_curve_new_polyline(poly, 3, &c[COONS_SIDE_S1], &err), &err);
    coons_patch *p = NULL;
    assert_coons_ok(coons_patch_new_coons(c, blend, 0.0, &p, &err), &err);
    double x[3];
    coons_patch_eval(p, s, 0.5, x);
    assert_near(x[1], 0.0, 1e-15);
    assert_near(x[2], 0.5, 1e-15);
    *g1 = x[0];
    coons_patch_free(p);
    for (int k = 0; k < 4; k++) coons_curve_free(c[k]);
}

/* Given the blend probe, then the blends are seed 001's: g1(s) = s for the
 * linear blend and 1 - f(s) = 3s^2 - 2s^3 for the cubic one. */
static void test_blend_values(void **state)
{
    (void)state;
    for (int i = 0; i <= 10; i++) {
        double s = i / 10.0, g;
        blend_probe(COONS_BLEND_LINEAR, s, &g);
        assert_near(g, s, 1e-15);
        blend_probe(COONS_BLEND_CUBIC, s, &g);
        assert_near(g, 3 * s * s - 2 * s * s * s, 1e-15);
    }
}

/* Given four boundary curves collapsed to one point c, then every patch is
 * c everywhere: with S = g0 + g1 the sum is c (2S - S^2), which is c only
 * if the blends sum to one. */
static void test_blends_sum_to_one(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    const double c0[3] = {0.3, -1.2, 2.5};
    coons_curve *c[4];
    for (int k = 0; k < 4; k++) assert_coons_ok(coons_curve_new_line(c0, c0, &c[k], &err), &err);
    for (int kind = 0; kind < 6; kind++) {
        coons_patch *p = NULL;
        if (kind < 2) {
            assert_coons_ok(coons_patch_new_coons(c, (coons_blend)kind,
                                                  0.0, &p, &err),
                            &err);
        } else {
            coons_hermite_options o = hopts((coons_twist)(kind - 2));
            memset(o.twists, 0, sizeof o.twists);
            assert_coons_ok(coons_patch_new_hermite_coons(c, &o, &p, &err),
                            &err);
        }
        for (int i = 0; i < 11; i++)
            for (int j = 0; j < 11; j++) {
                double x[3];
                coons_patch_eval(p, par11[i], par11[j], x);
                assert_vec3_near(x, c0, 1e-14);
            }
        coons_patch_free(p);
    }
    for (int k = 0; k < 4; k++) coons_curve_free(c[k]);
}

/* Given the boundary translated by v, then every patch is translated by v:
 * the blends reproduce constants (they sum to one). */
static void test_patches_translate_with_boundary(void **state)
{
    (void)state;
    const double v[3] = {1.5, -2.0, 0.75};
    fx_boundary b, bv;
    fx_boundary_make(&b);
    fx_boundary_make_off(&bv, v);
    for (int kind = 0; kind < NKINDS - 1; kind++) {
        coons_curve *cr[4] = {0};
        coons_patch *p = make_kind(&b, kind, cr), *q = make_kind(&bv, kind, cr);
        for (int i = 0; i < 5; i++)
            for (int j = 0; j < 5; j++) {
                double x[3], y[3];
                coons_patch_eval(p, fx_par[i], fx_par[j], x);
                coons_patch_eval(q, fx_par[i], fx_par[j], y);
                for (int k = 0; k < 3; k++) x[k] += v[k];
                assert_vec3_near(x, y, 1e-13);
            }
        coons_patch_free(p);
        coons_patch_free(q);
    }
    fx_boundary_free(&b);
    fx_boundary_free(&bv);
}

/* Given curved boundaries, when restricted to an edge, then every Coons
 * and Hermite Coons patch is that boundary curve (eq. 1.3, 1.4). */
static void test_boundary_interpolation_coons_hermite(void **state)
{
    (void)state;
    fx_boundary b;
    fx_boundary_make(&b);
    for (int kind = 0; kind < NKINDS; kind++) {
        coons_curve *cr[4] = {0};
        coons_patch *p = make_kind(&b, kind, cr);
        check_boundary(p, fx_curves(&b), 1e-13);
        coons_patch_free(p);
        free_cross(cr);
    }
    fx_boundary_free(&b);
}

/* Given two curves, then the ruled surface is c0 at t=0 and c1 at t=1
 * (eq. 1.1) and linear in t (eq. 1.2). */
static void test_ruled(void **state)
{
    (void)state;
    fx_boundary b;
    fx_boundary_make(&b);
    coons_error err = COONS_ERROR_INIT;
    coons_patch *p = NULL;
    assert_coons_ok(coons_patch_new_ruled(b.c[COONS_SIDE_T0], b.c[COONS_SIDE_T1], &p, &err), &err);
    assert_int_equal(coons_patch_kind(p), COONS_PATCH_RULED);
    for (int i = 0; i < 11; i++) {
        double u = par11[i], x[3], c0[3], c1[3];
        coons_curve_eval(b.c[COONS_SIDE_T0], u, c0);
        coons_curve_eval(b.c[COONS_SIDE_T1], u, c1);
        coons_patch_eval(p, u, 0.0, x);
        assert_vec3_near(x, c0, 1e-15);
        coons_patch_eval(p, u, 1.0, x);
        assert_vec3_near(x, c1, 1e-15);
        coons_patch_eval(p, u, 0.3, x);
        double want[3] = {0.7 * c0[0] + 0.3 * c1[0], 0.7 * c0[1] + 0.3 * c1[1],
                          0.7 * c0[2] + 0.3 * c1[2]};
        assert_vec3_near(x, want, 1e-14);
    }
    coons_patch_free(p);
    fx_boundary_free(&b);
}

/* Given four corners, then the bilinear patch has them as corners, its
 * edges are the straight lines between them, and it equals the linear
 * Coons patch of those four straight edges. */
static void test_bilinear_equals_coons_of_lines(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_patch *p = NULL, *q = NULL;
    assert_coons_ok(coons_patch_new_bilinear(fx_corner[0], &p, &err), &err);
    assert_int_equal(coons_patch_kind(p), COONS_PATCH_BILINEAR);
    coons_curve *c[4];
    assert_coons_ok(coons_curve_new_line(fx_corner[0], fx_corner[1], &c[COONS_SIDE_T0], &err), &err);
    assert_coons_ok(coons_curve_new_line(fx_corner[2], fx_corner[3], &c[COONS_SIDE_T1], &err), &err);
    assert_coons_ok(coons_curve_new_line(fx_corner[0], fx_corner[2], &c[COONS_SIDE_S0], &err), &err);
    assert_coons_ok(coons_curve_new_line(fx_corner[1], fx_corner[3], &c[COONS_SIDE_S1], &err), &err);
    assert_coons_ok(coons_patch_new_coons(c, COONS_BLEND_LINEAR, 0.0,
                                          &q, &err),
                    &err);
    check_boundary(p, c, 1e-15);
    for (int k = 0; k < 4; k++) {
        double x[3];
        coons_patch_eval(p, k & 1, k >> 1, x);
        assert_vec3_near(x, fx_corner[k], 0.0);
    }
    for (int i = 0; i < 11; i++)
        for (int j = 0; j < 11; j++) {
            double x[3], y[3], d[6][3], e[6][3];
            coons_patch_eval(p, par11[i], par11[j], x);
            coons_patch_eval(q, par11[i], par11[j], y);
            assert_vec3_near(x, y, 1e-14);
            coons_patch_eval_derivs(p, par11[i], par11[j], 2, d);
            coons_patch_eval_derivs(q, par11[i], par11[j], 2, e);
            for (int k = 0; k < 6; k++) assert_vec3_near(d[k], e[k], 1e-13);
        }
    coons_patch_free(p);
    coons_patch_free(q);
    for (int k = 0; k < 4; k++) coons_curve_free(c[k]);
}

/* Given two curves c0, c1 and the straight lines joining their ends as s0
 * and s1, then the linear Coons patch is the ruled surface (eq. 1.8 with
 * r_d = r_cd). */
static void test_ruled_equals_coons_with_straight_sides(void **state)
{
    (void)state;
    fx_boundary b;
    fx_boundary_make(&b);
    coons_error err = COONS_ERROR_INIT;
    coons_curve *c[4] = {b.c[COONS_SIDE_T0], b.c[COONS_SIDE_T1], NULL, NULL};
    double a0[3], a1[3], b0[3], b1[3];
    coons_curve_eval(b.c[COONS_SIDE_T0], 0.0, a0);
    coons_curve_eval(b.c[COONS_SIDE_T0], 1.0, a1);
    coons_curve_eval(b.c[COONS_SIDE_T1], 0.0, b0);
    coons_curve_eval(b.c[COONS_SIDE_T1], 1.0, b1);
    assert_coons_ok(coons_curve_new_line(a0, b0, &c[COONS_SIDE_S0], &err), &err);
    assert_coons_ok(coons_curve_new_line(a1, b1, &c[COONS_SIDE_S1], &err), &err);
    coons_patch *p = NULL, *q = NULL;
    assert_coons_ok(coons_patch_new_ruled(c[0], c[1], &p, &err), &err);
    assert_coons_ok(coons_patch_new_coons(c, COONS_BLEND_LINEAR, 0.0,
                                          &q, &err),
                    &err);
    for (int i = 0; i < 11; i++)
        for (int j = 0; j < 11; j++) {
            double d[6][3], e[6][3];
            coons_patch_eval_derivs(p, par11[i], par11[j], 2, d);
            coons_patch_eval_derivs(q, par11[i], par11[j], 2, e);
            for (int k = 0; k < 6; k++) assert_vec3_near(d[k], e[k], 1e-12 * fx_scale(d[k]));
        }
    coons_patch_free(p);
    coons_patch_free(q);
    coons_curve_free(c[2]);
    coons_curve_free(c[3]);
    fx_boundary_free(&b);
}

/* Given cross curves compatible with the corner tangents and twists, then
 * the Hermite Coons patch takes them as its cross-boundary derivatives:
 * x_t(s,0) = cross.t0(s), x_t(s,1) = cross.t1(s), x_s(0,t) = cross.s0(t),
 * x_s(1,t) = cross.s1(t) (eq. 1.12). */
static void test_hermite_takes_cross_tangents(void **state)
{
    (void)state;
    fx_boundary b;
    fx_boundary_make(&b);
    coons_curve *cr[4] = {0};
    coons_patch *p = make_kind(&b, 6, cr);
    for (int i = 0; i < 11; i++) {
        double u = par11[i], d[3][3], y[3];
        coons_patch_eval_derivs(p, u, 0.0, 1, d);
        coons_curve_eval(cr[0], u, y);
        assert_vec3_near(d[2], y, 1e-12);
        coons_patch_eval_derivs(p, u, 1.0, 1, d);
        coons_curve_eval(cr[1], u, y);
        assert_vec3_near(d[2], y, 1e-12);
        coons_patch_eval_derivs(p, 0.0, u, 1, d);
        coons_curve_eval(cr[2], u, y);
        assert_vec3_near(d[1], y, 1e-12);
        coons_patch_eval_derivs(p, 1.0, u, 1, d);
        coons_curve_eval(cr[3], u, y);
        assert_vec3_near(d[1], y, 1e-12);
    }
    /* The same cross tangents seen by central differences across t = 0.5
     * of a second patch would need neighbours; here check one-sided second
     * order differences at the edge t = 0 instead. */
    const double h = 1e-4;
    for (int i = 1; i < 10; i++) {
        double u = par11[i], x0[3], x1[3], x2[3], y[3], fd[3];
        coons_patch_eval(p, u, 0.0, x0);
        coons_patch_eval(p, u, h, x1);
        coons_patch_eval(p, u, 2 * h, x2);
        for (int k = 0; k < 3; k++) fd[k] = (-3 * x0[k] + 4 * x1[k] - x2[k]) / (2 * h);
        coons_curve_eval(cr[0], u, y);
        assert_vec3_near(fd, y, 1e-6);
    }
    coons_patch_free(p);
    free_cross(cr);
    fx_boundary_free(&b);
}

/* Given a bicubic Bezier surface and its exact boundary, cross-boundary
 * derivatives (hodographs) and twists, then the bicubically blended Coons
 * patch reproduces it (h_c, h_d and h_cd all reproduce bicubics). */
static void test_hermite_reproduces_bicubic(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    double P[4][4][3];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            P[i][j][0] = i + 0.2 * j * j - 0.1 * i * j;
            P[i][j][1] = j + 0.15 * i * i;
            P[i][j][2] = sin(1.0 + i * 1.3 + j * 0.7);
        }
    coons_patch *bez = NULL, *h = NULL;
    assert_coons_ok(coons_patch_new_bezier(&P[0][0][0], 4, 4, &bez, &err), &err);
    double e[4][4][3], xd[4][4][3];
    for (int m = 0; m < 4; m++)
        for (int k = 0; k < 3; k++) {
            e[COONS_SIDE_T0][m][k] = P[m][0][k];
            e[COONS_SIDE_T1][m][k] = P[m][3][k];
            e[COONS_SIDE_S0][m][k] = P[0][m][k];
            e[COONS_SIDE_S1][m][k] = P[3][m][k];
            xd[0][m][k] = 3 * (P[m][1][k] - P[m][0][k]);
            xd[1][m][k] = 3 * (P[m][3][k] - P[m][2][k]);
            xd[2][m][k] = 3 * (P[1][m][k] - P[0][m][k]);
            xd[3][m][k] = 3 * (P[3][m][k] - P[2][m][k]);
        }
    coons_curve *c[4], *cr[4];
    for (int k = 0; k < 4; k++) {
        assert_coons_ok(coons_curve_new_bezier(&e[k][0][0], 4, &c[k], &err), &err);
        assert_coons_ok(coons_curve_new_bezier(&xd[k][0][0], 4, &cr[k], &err), &err);
    }
    coons_hermite_options o = COONS_HERMITE_OPTIONS_INIT;
    o.twist = COONS_TWIST_EXPLICIT;
    for (int k = 0; k < 4; k++) {
        int i = (k & 1) ? 2 : 0, j = (k >> 1) ? 2 : 0;
        for (int q = 0; q < 3; q++)
            o.twists[k][q] = 9 * (P[i + 1][j + 1][q] - P[i + 1][j][q] - P[i][j + 1][q] + P[i][j][q]);
        o.cross[k] = cr[k];
    }
    assert_coons_ok(coons_patch_new_hermite_coons(c, &o, &h, &err), &err);
    for (int i = 0; i < 11; i++)
        for (int j = 0; j < 11; j++) {
            double d1[6][3], d2[6][3];
            coons_patch_eval_derivs(bez, par11[i], par11[j], 2, d1);
            coons_patch_eval_derivs(h, par11[i], par11[j], 2, d2);
            for (int k = 0; k < 6; k++) assert_vec3_near(d1[k], d2[k], 1e-12 * fx_scale(d1[k]));
        }
    coons_patch_free(bez);
    coons_patch_free(h);
    for (int k = 0; k < 4; k++) {
        coons_curve_free(c[k]);
        coons_curve_free(cr[k]);
    }
}

/* Second-order one-sided difference of f along a direction, at 0 or 1. */
static void corner_mixed_fd(const coons_patch *p, int a, int b, double out[3])
{
    const double h = 1e-4, w[3] = {-3.0, 4.0, -1.0};
    double ss = a ? -1.0 : 1.0, st = b ? -1.0 : 1.0;
    for (int k = 0; k < 3; k++) out[k] = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double x[3];
            coons_patch_eval(p, a + ss * i * h, b + st * j * h, x);
            for (int k = 0; k < 3; k++) out[k] += w[i] * w[j] * x[k];
        }
    for (int k = 0; k < 3; k++) out[k] *= ss * st / (4 * h * h);
}

/* Given the Adini twist option, then the twists are the mixed partials
 * x_st of the bilinearly blended Coons patch of the same boundary at the
 * corners (measured by finite differences on the linear Coons patch), and
 * the Hermite patch's own x_st at the corners equals its twists. */
static void test_adini_twist(void **state)
{
    (void)state;
    fx_boundary b;
    fx_boundary_make(&b);
    coons_curve *cr[4] = {0};
    coons_patch *lin = make_kind(&b, 0, cr), *ad = make_kind(&b, 2 + COONS_TWIST_ADINI, cr);
    for (int k = 0; k < 4; k++) {
        int a = k & 1, bb = k >> 1;
        double fd[3], d[6][3], dl[6][3];
        corner_mixed_fd(lin, a, bb, fd);
        coons_patch_eval_derivs(ad, a, bb, 2, d);
        assert_vec3_near(d[4], fd, 1e-6 * fx_scale(fd));
        coons_patch_eval_derivs(lin, a, bb, 2, dl);
        assert_vec3_near(d[4], dl[4], 1e-12);
    }
    coons_patch_free(lin);
    coons_patch_free(ad);
    fx_boundary_free(&b);
}

/* Given zero, Bessel or explicit twists, then x_st at each corner is that
 * twist: 0, the cell twist X00 - X10 - X01 + X11, or the given vector. */
static void test_zero_bessel_explicit_twists(void **state)
{
    (void)state;
    fx_boundary b;
    fx_boundary_make(&b);
    double cell[3];
    for (int k = 0; k < 3; k++)
        cell[k] = fx_corner[0][k] - fx_corner[1][k] - fx_corner[2][k] + fx_corner[3][k];
    const double zero[3] = {0, 0, 0};
    coons_hermite_options ex = hopts(COONS_TWIST_EXPLICIT);
    for (int tw = COONS_TWIST_ZERO; tw <= COONS_TWIST_EXPLICIT; tw++) {
        if (tw == COONS_TWIST_ADINI) continue;
        coons_curve *cr[4] = {0};
        coons_patch *p = make_kind(&b, 2 + tw, cr);
        for (int k = 0; k < 4; k++) {
            double d[6][3];
            coons_patch_eval_derivs(p, k & 1, k >> 1, 2, d);
            const double *want = tw == COONS_TWIST_ZERO ? zero
                                 : tw == COONS_TWIST_BESSEL ? cell
                                                            : ex.twists[k];
            assert_vec3_near(d[4], want, 1e-12);
        }
        coons_patch_free(p);
    }
    fx_boundary_free(&b);
}

/* Given no cross curves and zero twists, then the Hermite Coons patch is
 * the Coons patch with the cubic blend f = 1 - 3t^2 + 2t^3 = H0 (the
 * ribbons of eq. 1.16 cancel against h_cd). */
static void test_hermite_zero_equals_cubic_coons(void **state)
{
    (void)state;
    fx_boundary b;
    fx_boundary_make(&b);
    coons_error err = COONS_ERROR_INIT;
    coons_patch *h = NULL, *c = NULL;
    assert_coons_ok(coons_patch_new_hermite_coons(fx_curves(&b), NULL, &h, &err), &err);
    assert_coons_ok(coons_patch_new_coons(fx_curves(&b), COONS_BLEND_CUBIC, 0.0, &c, &err), &err);
    for (int i = 0; i < 11; i++)
        for (int j = 0; j < 11; j++) {
            double d1[6][3], d2[6][3];
            coons_patch_eval_derivs(h, par11[i], par11[j], 2, d1);
            coons_patch_eval_derivs(c, par11[i], par11[j], 2, d2);
            for (int k = 0; k < 6; k++) assert_vec3_near(d1[k], d2[k], 1e-12 * fx_scale(d1[k]));
        }
    coons_patch_free(h);
    coons_patch_free(c);
    fx_boundary_free(&b);
}

/* Given every kind of patch on curved boundaries, then the first and second
 * partials agree with central differences. */
static void test_derivs_fd(void **state)
{
    (void)state;
    fx_boundary b;
    fx_boundary_make(&b);
    coons_error err = COONS_ERROR_INIT;
    for (int kind = 0; kind < NKINDS; kind++) {
        coons_curve *cr[4] = {0};
        coons_patch *p = make_kind(&b, kind, cr);
        fx_check_derivs_fd(p, 1e-6);
        coons_patch_free(p);
        free_cross(cr);
    }
    coons_patch *p = NULL;
    assert_coons_ok(coons_patch_new_ruled(b.c[COONS_SIDE_S0], b.c[COONS_SIDE_T1], &p, &err), &err);
    fx_check_derivs_fd(p, 1e-6);
    coons_patch_free(p);
    assert_coons_ok(coons_patch_new_bilinear(fx_corner[0], &p, &err), &err);
    fx_check_derivs_fd(p, 1e-6);
    coons_patch_free(p);
    fx_boundary_free(&b);
}

/* Given every kind of patch, then a grid equals pointwise evaluation. */
static void test_grid_equals_pointwise(void **state)
{
    (void)state;
    fx_boundary b;
    fx_boundary_make(&b);
    coons_error err = COONS_ERROR_INIT;
    for (int kind = 0; kind < NKINDS; kind++) {
        coons_curve *cr[4] = {0};
        coons_patch *p = make_kind(&b, kind, cr);
        fx_check_grid(p);
        coons_patch_free(p);
        free_cross(cr);
    }
    coons_patch *p = NULL;
    assert_coons_ok(coons_patch_new_ruled(b.c[COONS_SIDE_S0], b.c[COONS_SIDE_T1], &p, &err), &err);
    fx_check_grid(p);
    /* empty grids are fine, NULL arrays are not */
    assert_int_equal(coons_patch_eval_grid(p, NULL, 0, NULL, 0, NULL, &err), COONS_OK);
    double t = 0.5, out[3];
    assert_int_equal(coons_patch_eval_grid(p, NULL, 1, &t, 1, out, &err), COONS_E_INVALID);
    coons_patch_free(p);
    assert_coons_ok(coons_patch_new_bilinear(fx_corner[0], &p, &err), &err);
    fx_check_grid(p);
    coons_patch_free(p);
    fx_boundary_free(&b);
}

/* Given a copy, then it evaluates like the original, also after the
 * original and the input curves are freed (deep copy). */
static void test_copy(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    for (int kind = 0; kind < NKINDS; kind++) {
        fx_boundary b;
        fx_boundary_make(&b);
        coons_curve *cr[4] = {0};
        coons_patch *p = make_kind(&b, kind, cr), *q = NULL;
        double want[5][5][6][3];
        for (int i = 0; i < 5; i++)
            for (int j = 0; j < 5; j++) coons_patch_eval_derivs(p, fx_par[i], fx_par[j], 2, want[i][j]);
        assert_coons_ok(coons_patch_copy(p, &q, &err), &err);
        assert_int_equal(coons_patch_kind(q), coons_patch_kind(p));
        double lo1[3], hi1[3], lo2[3], hi2[3];
        coons_patch_control_bbox(p, lo1, hi1);
        coons_patch_control_bbox(q, lo2, hi2);
        assert_memory_equal(lo1, lo2, sizeof lo1);
        assert_memory_equal(hi1, hi2, sizeof hi1);
        coons_patch_free(p);
        free_cross(cr);
        fx_boundary_free(&b);
        for (int i = 0; i < 5; i++)
            for (int j = 0; j < 5; j++) {
                double d[6][3];
                coons_patch_eval_derivs(q, fx_par[i], fx_par[j], 2, d);
                assert_memory_equal(d, want[i][j], sizeof d);
            }
        coons_patch_free(q);
    }
}

/* Given the fixture, then the control box holds all boundary control
 * points and the corners. */
static void test_control_bbox(void **state)
{
    (void)state;
    fx_boundary b;
    fx_boundary_make(&b);
    coons_curve *cr[4] = {0};
    coons_patch *p = make_kind(&b, 0, cr);
    double lo[3], hi[3];
    coons_patch_control_bbox(p, lo, hi);
    /* s0's outer Coons points 2 X00 - a and 2 X01 - c stick out most. */
    assert_near(lo[0], -0.4, 1e-15);
    assert_near(hi[0], 2.3, 1e-15);
    assert_near(lo[1], -0.5, 1e-15);
    assert_near(hi[1], 2.7, 1e-15);
    assert_near(lo[2], -0.4, 1e-15);
    assert_near(hi[2], 0.6, 1e-15);
    coons_patch_free(p);
    fx_boundary_free(&b);
}

/* Straight boundary whose corner k is moved by 0.25 on the t-curve. */
static void lines_with_gap(int k, coons_curve *c[4])
{
    coons_error err = COONS_ERROR_INIT;
    double X[4][3];
    memcpy(X, fx_corner, sizeof X);
    double T0a[3], T0b[3], T1a[3], T1b[3];
    memcpy(T0a, X[0], sizeof T0a);
    memcpy(T0b, X[1], sizeof T0b);
    memcpy(T1a, X[2], sizeof T1a);
    memcpy(T1b, X[3], sizeof T1b);
    double *moved = k == 0 ? T0a : k == 1 ? T0b : k == 2 ? T1a : T1b;
    moved[2] += 0.25;
    assert_coons_ok(coons_curve_new_line(T0a, T0b, &c[COONS_SIDE_T0], &err), &err);
    assert_coons_ok(coons_curve_new_line(T1a, T1b, &c[COONS_SIDE_T1], &err), &err);
    assert_coons_ok(coons_curve_new_line(X[0], X[2], &c[COONS_SIDE_S0], &err), &err);
    assert_coons_ok(coons_curve_new_line(X[1], X[3], &c[COONS_SIDE_S1], &err), &err);
}

/* Given boundary curves that miss one corner by 0.25, then construction
 * fails with COONS_E_INCOMPATIBLE and the message names the corner, the two
 * curve ends and the distance. */
static void test_corner_mismatch_names_corner(void **state)
{
    (void)state;
    static const char *const want[4] = {
        "corner (s=0,t=0): t0(0) and s0(0) are 0.25 apart",
        "corner (s=1,t=0): t0(1) and s1(0) are 0.25 apart",
        "corner (s=0,t=1): t1(0) and s0(1) are 0.25 apart",
        "corner (s=1,t=1): t1(1) and s1(1) are 0.25 apart",
    };
    for (int k = 0; k < 4; k++) {
        coons_curve *c[4];
        lines_with_gap(k, c);
        coons_error err = COONS_ERROR_INIT;
        coons_patch *p = (coons_patch *)&err; /* must be reset to NULL */
        assert_int_equal(coons_patch_new_coons(c, COONS_BLEND_LINEAR,
                                               0.0, &p, &err),
                         COONS_E_INCOMPATIBLE);
        assert_null(p);
        assert_int_equal(err.code, COONS_E_INCOMPATIBLE);
        if (!strstr(err.message, want[k])) fail_msg("message '%s' lacks '%s'", err.message, want[k]);
        assert_int_equal(coons_patch_new_hermite_coons(c, NULL, &p, &err),
                         COONS_E_INCOMPATIBLE);
        if (!strstr(err.message, want[k])) fail_msg("message '%s' lacks '%s'", err.message, want[k]);
        /* an absolute tolerance above the gap accepts it and averages the corner */
        assert_coons_ok(coons_patch_new_coons(c, COONS_BLEND_LINEAR, 0.3,
                                              &p, &err),
                        &err);
        double x[3], m[3];
        memcpy(m, fx_corner[k], sizeof m);
        m[2] += 0.125;
        coons_patch_eval(p, k & 1, k >> 1, x);
        assert_vec3_near(x, m, 1e-15);
        coons_patch_free(p);
        for (int q = 0; q < 4; q++) coons_curve_free(c[q]);
    }
}

/* Given a gap of 1e-6 on a patch of size ~3, then the default tolerance
 * (1e-9 of the control box diagonal) rejects it and 1e-5 accepts it. */
static void test_default_tolerance(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    double X[4][3];
    memcpy(X, fx_corner, sizeof X);
    double moved[3] = {X[1][0], X[1][1], X[1][2] + 1e-6};
    coons_curve *c[4];
    assert_coons_ok(coons_curve_new_line(X[0], moved, &c[COONS_SIDE_T0], &err), &err);
    assert_coons_ok(coons_curve_new_line(X[2], X[3], &c[COONS_SIDE_T1], &err), &err);
    assert_coons_ok(coons_curve_new_line(X[0], X[2], &c[COONS_SIDE_S0], &err), &err);
    assert_coons_ok(coons_curve_new_line(X[1], X[3], &c[COONS_SIDE_S1], &err), &err);
    coons_patch *p = NULL;
    assert_int_equal(coons_patch_new_coons(c, COONS_BLEND_CUBIC,
                                           COONS_TOL_DEFAULT, &p, &err),
                     COONS_E_INCOMPATIBLE);
    assert_non_null(strstr(err.message, "corner (s=1,t=0)"));
    assert_coons_ok(coons_patch_new_coons(c, COONS_BLEND_CUBIC, 1e-5, &p,
                                          &err),
                    &err);
    coons_patch_free(p);
    for (int q = 0; q < 4; q++) coons_curve_free(c[q]);
}

/* Given cross curves that disagree with a corner tangent, then the Hermite
 * patch is refused and the message names the corner and the curves. */
static void test_cross_mismatch(void **state)
{
    (void)state;
    fx_boundary b;
    fx_boundary_make(&b);
    coons_error err = COONS_ERROR_INIT;
    coons_hermite_options o = hopts(COONS_TWIST_EXPLICIT);
    coons_curve *cr[4] = {0};
    make_cross(&b, o.twists, cr);
    /* replace cross s1 = x_s(1,t) by one whose start is off by 0.5 */
    double xs[2][3], xe[2][3];
    coons_curve_eval_derivs(b.c[COONS_SIDE_T0], 1.0, 1, xs);
    coons_curve_eval_derivs(b.c[COONS_SIDE_T1], 1.0, 1, xe);
    xs[1][0] += 0.5;
    coons_curve_free(cr[3]);
    assert_coons_ok(coons_curve_new_hermite(xs[1], o.twists[1], xe[1], o.twists[3], &cr[3], &err), &err);
    for (int k = 0; k < 4; k++) o.cross[k] = cr[k];
    coons_patch *p = NULL;
    assert_int_equal(coons_patch_new_hermite_coons(fx_curves(&b), &o, &p, &err), COONS_E_INCOMPATIBLE);
    assert_null(p);
    const char *want = "corner (s=1,t=0): cross s1(0) and the boundary tangent t0'(1) are 0.5 apart";
    if (!strstr(err.message, want)) fail_msg("message '%s' lacks '%s'", err.message, want);
    /* three cross curves are not allowed */
    o.cross[3] = NULL;
    assert_int_equal(coons_patch_new_hermite_coons(fx_curves(&b), &o, &p, &err), COONS_E_INVALID);
    free_cross(cr);
    fx_boundary_free(&b);
}

/* Given invalid arguments, then constructors refuse them and leave *out NULL. */
static void test_invalid_arguments(void **state)
{
    (void)state;
    fx_boundary b;
    fx_boundary_make(&b);
    coons_error err = COONS_ERROR_INIT;
    coons_patch *p = NULL;
    double bad[4][3];
    memcpy(bad, fx_corner, sizeof bad);
    bad[3][1] = NAN;
    assert_int_equal(coons_patch_new_bilinear(bad[0], &p, &err), COONS_E_INVALID);
    assert_null(p);
    bad[3][1] = INFINITY;
    assert_int_equal(coons_patch_new_bilinear(bad[0], &p, &err), COONS_E_INVALID);
    assert_int_equal(coons_patch_new_bilinear(NULL, &p, &err), COONS_E_INVALID);
    assert_int_equal(coons_patch_new_bilinear(fx_corner[0], NULL, &err), COONS_E_INVALID);
    assert_int_equal(coons_patch_new_ruled(b.c[0], NULL, &p, &err), COONS_E_INVALID);
    assert_int_equal(coons_patch_new_ruled(NULL, b.c[0], &p, &err), COONS_E_INVALID);
    coons_curve *missing[4] = {b.c[0], b.c[1], NULL, b.c[3]};
    assert_int_equal(coons_patch_new_coons(missing, COONS_BLEND_LINEAR, 0.0, &p, &err), COONS_E_INVALID);
    assert_non_null(strstr(err.message, "s0"));
    assert_int_equal(coons_patch_new_coons(NULL, COONS_BLEND_LINEAR, 0.0, &p, &err), COONS_E_INVALID);
    assert_int_equal(coons_patch_new_hermite_coons(missing, NULL, &p, &err), COONS_E_INVALID);
    assert_int_equal(coons_patch_new_coons(fx_curves(&b), (coons_blend)7, 0.0, &p, &err),
                     COONS_E_INVALID);
    assert_int_equal(coons_patch_new_coons(fx_curves(&b), COONS_BLEND_LINEAR, -1.0, &p, &err),
                     COONS_E_INVALID);
    assert_int_equal(coons_patch_new_coons(fx_curves(&b), COONS_BLEND_LINEAR, NAN, &p, &err),
                     COONS_E_INVALID);
    coons_hermite_options o = COONS_HERMITE_OPTIONS_INIT;
    o.version = 99;
    assert_int_equal(coons_patch_new_hermite_coons(fx_curves(&b), &o, &p, &err), COONS_E_INVALID);
    o = hopts(COONS_TWIST_EXPLICIT);
    o.twists[2][0] = NAN;
    assert_int_equal(coons_patch_new_hermite_coons(fx_curves(&b), &o, &p, &err), COONS_E_INVALID);
    o = hopts(COONS_TWIST_ZERO);
    o.twist = (coons_twist)9;
    assert_int_equal(coons_patch_new_hermite_coons(fx_curves(&b), &o, &p, &err), COONS_E_INVALID);
    o.twist = COONS_TWIST_ZERO;
    o.tol = -1.0;
    assert_int_equal(coons_patch_new_hermite_coons(fx_curves(&b), &o, &p, &err), COONS_E_INVALID);
    assert_null(p);
    assert_int_equal(coons_patch_copy(NULL, &p, &err), COONS_E_INVALID);
    /* NULL error record is allowed */
    assert_int_equal(coons_patch_new_bilinear(NULL, &p, NULL), COONS_E_INVALID);
    coons_patch_free(NULL);
    fx_boundary_free(&b);
}

/* Given parameters outside [0,1] (or NaN), then evaluation clamps them. */
static void test_parameters_clamped(void **state)
{
    (void)state;
    fx_boundary b;
    fx_boundary_make(&b);
    coons_curve *cr[4] = {0};
    coons_patch *p = make_kind(&b, 3, cr);
    double x[3], y[3];
    coons_patch_eval(p, -0.5, 2.0, x);
    coons_patch_eval(p, 0.0, 1.0, y);
    assert_memory_equal(x, y, sizeof x);
    coons_patch_eval(p, NAN, 0.3, x);
    coons_patch_eval(p, 0.0, 0.3, y);
    assert_memory_equal(x, y, sizeof x);
    coons_patch_free(p);
    fx_boundary_free(&b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_blend_values),
        cmocka_unit_test(test_blends_sum_to_one),
        cmocka_unit_test(test_patches_translate_with_boundary),
        cmocka_unit_test(test_boundary_interpolation_coons_hermite),
        cmocka_unit_test(test_ruled),
        cmocka_unit_test(test_bilinear_equals_coons_of_lines),
        cmocka_unit_test(test_ruled_equals_coons_with_straight_sides),
        cmocka_unit_test(test_hermite_takes_cross_tangents),
        cmocka_unit_test(test_hermite_reproduces_bicubic),
        cmocka_unit_test(test_adini_twist),
        cmocka_unit_test(test_zero_bessel_explicit_twists),
        cmocka_unit_test(test_hermite_zero_equals_cubic_coons),
        cmocka_unit_test(test_derivs_fd),
        cmocka_unit_test(test_grid_equals_pointwise),
        cmocka_unit_test(test_copy),
        cmocka_unit_test(test_control_bbox),
        cmocka_unit_test(test_corner_mismatch_names_corner),
        cmocka_unit_test(test_default_tolerance),
        cmocka_unit_test(test_cross_mismatch),
        cmocka_unit_test(test_invalid_arguments),
        cmocka_unit_test(test_parameters_clamped),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
