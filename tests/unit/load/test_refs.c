/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * References of the model format (coons-model(5), "Definitions and
 * references"): the library's wrappers (coons_curve_new_transformed,
 * _reversed, coons_patch_new_transformed, _reparametrized,
 * coons_body_new_transformed) and the loader's "define"/"ref".
 *
 * - A transform equals the same object built from control points mapped by
 *   the test's own arithmetic (NURBS included, weights unchanged), points
 *   and every derivative, within 1e-12 relative; det J scales by det M.
 * - reverse, swap, flip_s, flip_t: the point identities exactly, the
 *   derivatives against central differences, grids against eval, the
 *   breakpoints remapped (white-box: linked against the static library).
 * - A model with references equals the model written inline: bitwise for
 *   identity transforms, 1e-12 for others; the control box is that of the
 *   control points as instanced; unused definitions are still checked.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"

#include "body_impl.h"
#include "curve_impl.h"
#include "patch_impl.h"

/* A regular map with det M < 0 (mirrors) and one with det M > 0. */
static const double MIRROR[12] = {-1.5, 0.25, 0.1, 3, 0.2, 2, -0.3, -1, 0.05, 0.4, 1.25, 7};
static const double ROT[12] = {0, -1, 0, 10, 1, 0, 0, -2, 0, 0, 2, 0.5};

static void map_point(const double m[12], const double *a, double *o)
{
    double x = a[0], y = a[1], z = a[2];
    for (int r = 0; r < 3; r++) o[r] = m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3];
}

static void map_vec(const double m[12], const double *a, double *o)
{
    double x = a[0], y = a[1], z = a[2];
    for (int r = 0; r < 3; r++) o[r] = m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z;
}

static double det3(const double m[12])
{
    return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
           m[2] * (m[4] * m[9] - m[5] * m[8]);
}

/* |a - b| <= 1e-12 max(1, |b|) per component. */
static void assert_rel(const double *a, const double *b)
{
    for (int k = 0; k < 3; k++) {
        double s = fabs(b[k]) > 1 ? fabs(b[k]) : 1;
        if (!(fabs(a[k] - b[k]) <= 1e-12 * s))
            fail_msg("component %d: %.17g vs %.17g", k, a[k], b[k]);
    }
}

static void assert_same(const double *a, const double *b)
{
    for (int k = 0; k < 3; k++)
        if (memcmp(&a[k], &b[k], sizeof(double)))
            fail_msg("component %d: %.17g vs %.17g (not bitwise)", k, a[k], b[k]);
}

/* ---- curves ------------------------------------------------------------ */

static const double CP[5][3] = {{0, 0, 0}, {1, 2, 0.5}, {3, 2.5, -1}, {4, 0, 2}, {6, 1, 1}};
static const double CW[5] = {1, 0.7, 1.3, 0.5, 1};
static const double CK[8] = {0, 0, 0, 0.3, 0.55, 1, 1, 1};

static coons_curve *nurbs(const double (*pts)[3])
{
    coons_curve *c = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_bspline(2, pts[0], 5, CK, CW, &c, &e), &e);
    return c;
}

static void test_curve_transform_nurbs(void **state)
{
    (void)state;
    const double *ms[2] = {MIRROR, ROT};
    for (int q = 0; q < 2; q++) {
        double tp[5][3];
        for (int i = 0; i < 5; i++) map_point(ms[q], CP[i], tp[i]);
        coons_curve *c = nurbs(CP), *inl = nurbs((const double (*)[3])tp), *x = NULL;
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(coons_curve_new_transformed(c, ms[q], &x, &e), &e);
        coons_curve_free(c); /* the wrapper holds its own copy */
        assert_int_equal(coons_curve_kind(x), COONS_CURVE_BSPLINE);
        for (int i = 0; i <= 20; i++) {
            double a[3][3], b[3][3];
            coons_curve_eval_derivs(x, i / 20.0, 2, a);
            coons_curve_eval_derivs(inl, i / 20.0, 2, b);
            for (int d = 0; d < 3; d++) assert_rel(a[d], b[d]);
        }
        double lo[3], hi[3], lo2[3], hi2[3];
        coons_curve_control_bbox(x, lo, hi);
        coons_curve_control_bbox(inl, lo2, hi2);
        assert_rel(lo, lo2);
        assert_rel(hi, hi2);
        /* breakpoints forwarded */
        coons__breaks B = {0}, B2 = {0};
        coons__curve_breaks(x, &B);
        coons__curve_breaks(inl, &B2);
        assert_int_equal(B.n, 2);
        assert_int_equal(B.n, B2.n);
        for (size_t i = 0; i < B.n; i++) assert_true(B.v[i] == B2.v[i]);
        coons__free(B.v);
        coons__free(B2.v);
        coons_curve_free(x);
        coons_curve_free(inl);
    }
}

static void test_curve_transform_hermite_and_bezier(void **state)
{
    (void)state;
    double p0[3] = {0, 0, 0}, t0[3] = {1, 3, 0}, p1[3] = {2, 1, 1}, t1[3] = {0, -2, 4};
    double q0[3], u0[3], q1[3], u1[3];
    map_point(MIRROR, p0, q0);
    map_point(MIRROR, p1, q1);
    map_vec(MIRROR, t0, u0); /* tangents transform by M alone */
    map_vec(MIRROR, t1, u1);
    coons_curve *c = NULL, *inl = NULL, *x = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_hermite(p0, t0, p1, t1, &c, &e), &e);
    assert_coons_ok(coons_curve_new_hermite(q0, u0, q1, u1, &inl, &e), &e);
    assert_coons_ok(coons_curve_new_transformed(c, MIRROR, &x, &e), &e);
    for (int i = 0; i <= 10; i++) {
        double a[3][3], b[3][3];
        coons_curve_eval_derivs(x, i / 10.0, 2, a);
        coons_curve_eval_derivs(inl, i / 10.0, 2, b);
        for (int d = 0; d < 3; d++) assert_rel(a[d], b[d]);
    }
    double sa[12], sb[12];
    size_t na, nb;
    int da, db;
    assert_coons_ok(coons_curve_bezier_segments(x, sa, 12, &na, &da, &e), &e);
    assert_coons_ok(coons_curve_bezier_segments(inl, sb, 12, &nb, &db, &e), &e);
    assert_int_equal(na, nb);
    assert_int_equal(da, db);
    for (int i = 0; i < 4; i++) assert_rel(sa + 3 * i, sb + 3 * i);
    coons_curve_free(c);
    coons_curve_free(inl);
    coons_curve_free(x);
}

static void test_curve_reverse(void **state)
{
    (void)state;
    coons_curve *c = nurbs(CP), *r = NULL, *rr = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_reversed(c, &r, &e), &e);
    assert_coons_ok(coons_curve_new_reversed(r, &rr, &e), &e);
    assert_int_equal(coons_curve_kind(rr), COONS_CURVE_BSPLINE);
    const double h = 1e-6;
    for (int i = 0; i <= 20; i++) {
        double t = i / 20.0, a[3][3], b[3][3], c2[3][3];
        coons_curve_eval_derivs(r, t, 2, a);
        coons_curve_eval_derivs(c, 1.0 - t, 2, b);
        coons_curve_eval_derivs(rr, 1.0 - t, 2, c2);
        assert_same(a[0], b[0]); /* y(t) = c(1 - t) */
        double nb1[3] = {-b[1][0], -b[1][1], -b[1][2]};
        assert_same(a[1], nb1); /* y' = -c'(1 - t) */
        assert_same(a[2], b[2]); /* y'' = c''(1 - t) */
        assert_same(c2[0], b[0]); /* reversed twice: c */
        if (t > 0.01 && t < 0.99 && fabs(t - 0.45) > 0.01 && fabs(t - 0.7) > 0.01) {
            double yp[3], ym[3];
            coons_curve_eval(r, t + h, yp);
            coons_curve_eval(r, t - h, ym);
            for (int k = 0; k < 3; k++) assert_near((yp[k] - ym[k]) / (2 * h), a[1][k], 1e-5);
        }
    }
    coons__breaks B = {0};
    coons__curve_breaks(r, &B);
    assert_int_equal(B.n, 2);
    assert_near(B.v[0], 0.7, 1e-15);
    assert_near(B.v[1], 0.45, 1e-15);
    coons__free(B.v);
    /* Bezier segments of a polynomial curve come reversed */
    coons_curve *p = NULL, *pr = NULL;
    assert_coons_ok(coons_curve_new_bspline(2, CP[0], 5, CK, NULL, &p, &e), &e);
    assert_coons_ok(coons_curve_new_reversed(p, &pr, &e), &e);
    double sa[27], sb[27];
    size_t na, nb;
    int da, db;
    assert_coons_ok(coons_curve_bezier_segments(p, sa, 27, &na, &da, &e), &e);
    assert_coons_ok(coons_curve_bezier_segments(pr, sb, 27, &nb, &db, &e), &e);
    assert_int_equal(na, 3);
    assert_int_equal(nb, 3);
    for (size_t i = 0; i < 9; i++) assert_same(sb + 3 * i, sa + 3 * (8 - i));
    coons_curve_free(p);
    coons_curve_free(pr);
    coons_curve_free(c);
    coons_curve_free(r);
    coons_curve_free(rr);
}

static void test_transform_refused(void **state)
{
    (void)state;
    coons_curve *c = nurbs(CP), *x = (coons_curve *)&x;
    coons_error e = COONS_ERROR_INIT;
    double sing[12] = {1, 0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 5}; /* rows 1 and 3 span a plane */
    assert_int_equal(coons_curve_new_transformed(c, sing, &x, &e), COONS_E_INVALID);
    assert_null(x);
    assert_non_null(strstr(e.message, "determinant"));
    /* nearly singular relative to the scale: refused whatever the units */
    double tiny[12] = {1e-9, 0, 0, 0, 0, 1e-9, 0, 0, 0, 0, 1e-9, 0};
    assert_int_equal(coons_curve_new_transformed(c, tiny, &x, &e), COONS_OK);
    coons_curve_free(x);
    double flat[12] = {1, 0, 0, 0, 0, 1, 0, 0, 1, 1, 1e-13, 0}; /* rows nearly dependent */
    assert_int_equal(coons_curve_new_transformed(c, flat, &x, &e), COONS_E_INVALID);
    double nan[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, NAN};
    assert_int_equal(coons_curve_new_transformed(c, nan, &x, &e), COONS_E_INVALID);
    assert_non_null(strstr(e.message, "finite"));
    assert_int_equal(coons_curve_new_transformed(NULL, ROT, &x, &e), COONS_E_INVALID);
    assert_int_equal(coons_curve_new_transformed(c, NULL, &x, &e), COONS_E_INVALID);
    assert_int_equal(coons_curve_new_reversed(NULL, &x, &e), COONS_E_INVALID);
    coons_patch *p = NULL;
    coons_body *b = NULL;
    double k[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1}};
    assert_coons_ok(coons_patch_new_bilinear(k[0], &p, &e), &e);
    coons_patch *px = NULL;
    assert_int_equal(coons_patch_new_transformed(p, sing, &px, &e), COONS_E_INVALID);
    assert_non_null(strstr(e.message, "determinant"));
    double c8[8][3];
    for (int i = 0; i < 8; i++) v3_set(c8[i], i >> 2 & 1, i >> 1 & 1, i & 1);
    assert_coons_ok(coons_body_new_body0(c8[0], COONS_BLEND_LINEAR, &b, &e), &e);
    coons_body *bx = NULL;
    assert_int_equal(coons_body_new_transformed(b, sing, &bx, &e), COONS_E_INVALID);
    assert_non_null(strstr(e.message, "determinant"));
    assert_null(bx);
    coons_patch_free(p);
    coons_body_free(b);
    coons_curve_free(c);
}

/* ---- patches ----------------------------------------------------------- */

enum { NS = 4, NT = 5 };
static double SP[NS][NT][3], SW[NS][NT];
static const double SKS[7] = {0, 0, 0, 0.4, 1, 1, 1}, SKT[9] = {0, 0, 0, 0, 0.6, 1, 1, 1, 1};

static void surface_data(void)
{
    for (int i = 0; i < NS; i++)
        for (int j = 0; j < NT; j++) {
            v3_set(SP[i][j], i + 0.1 * j * j, j - 0.2 * i, sin(i + 2.0 * j));
            SW[i][j] = 1 + 0.3 * ((i + j) % 3);
        }
}

static coons_patch *surface(const double (*pts)[NT][3])
{
    coons_patch *p = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_patch_new_bspline(2, 3, pts[0][0], NS, NT, SKS, SKT, SW[0], &p, &e), &e);
    return p;
}

static void test_patch_transform_nurbs(void **state)
{
    (void)state;
    surface_data();
    double tp[NS][NT][3];
    for (int i = 0; i < NS; i++)
        for (int j = 0; j < NT; j++) map_point(MIRROR, SP[i][j], tp[i][j]);
    coons_patch *p = surface((const double (*)[NT][3])SP), *inl = surface((const double (*)[NT][3])tp);
    coons_patch *x = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_patch_new_transformed(p, MIRROR, &x, &e), &e);
    assert_int_equal(coons_patch_kind(x), COONS_PATCH_BSPLINE);
    double s[7], t[6], ga[7 * 6 * 3], gb[7 * 6 * 3];
    for (int i = 0; i < 7; i++) s[i] = i / 6.0;
    for (int j = 0; j < 6; j++) t[j] = j / 5.0;
    for (int i = 0; i < 7; i++)
        for (int j = 0; j < 6; j++) {
            double a[6][3], b[6][3];
            coons_patch_eval_derivs(x, s[i], t[j], 2, a);
            coons_patch_eval_derivs(inl, s[i], t[j], 2, b);
            for (int d = 0; d < 6; d++) assert_rel(a[d], b[d]);
        }
    assert_coons_ok(coons_patch_eval_grid(x, s, 7, t, 6, ga, &e), &e);
    assert_coons_ok(coons_patch_eval_grid(inl, s, 7, t, 6, gb, &e), &e);
    for (int i = 0; i < 42; i++) assert_rel(ga + 3 * i, gb + 3 * i);
    /* the control box contains the inline one (corners of the mapped box) */
    double lo[3], hi[3], lo2[3], hi2[3];
    coons_patch_control_bbox(x, lo, hi);
    coons_patch_control_bbox(inl, lo2, hi2);
    for (int k = 0; k < 3; k++) assert_true(lo[k] <= lo2[k] + 1e-12 && hi[k] >= hi2[k] - 1e-12);
    coons_patch *cx = NULL;
    assert_coons_ok(coons_patch_copy(x, &cx, &e), &e);
    double a[3], b[3];
    coons_patch_free(x);
    coons_patch_eval(cx, 0.3, 0.7, a);
    coons_patch_eval(inl, 0.3, 0.7, b);
    assert_rel(a, b);
    coons_patch_free(cx);
    coons_patch_free(p);
    coons_patch_free(inl);
}

static void test_patch_reparam(void **state)
{
    (void)state;
    surface_data();
    coons_patch *p = surface((const double (*)[NT][3])SP);
    coons_error e = COONS_ERROR_INIT;
    const double h = 1e-5;
    for (int f = 0; f < 8; f++) {
        int sw = f & 1, fs = f >> 1 & 1, ft = f >> 2 & 1;
        coons_patch *y = NULL;
        assert_coons_ok(coons_patch_new_reparametrized(p, sw, fs, ft, &y, &e), &e);
        assert_int_equal(coons_patch_kind(y), COONS_PATCH_BSPLINE);
        double s[5] = {0, 0.2, 0.5, 0.77, 1}, t[4] = {0, 0.35, 0.61, 1}, g[20 * 3];
        assert_coons_ok(coons_patch_eval_grid(y, s, 5, t, 4, g, &e), &e);
        for (int i = 0; i < 5; i++)
            for (int j = 0; j < 4; j++) {
                double a = sw ? t[j] : s[i], b = sw ? s[i] : t[j];
                if (fs) a = 1 - a;
                if (ft) b = 1 - b;
                double yv[6][3], xv[6][3];
                coons_patch_eval_derivs(y, s[i], t[j], 2, yv);
                coons_patch_eval_derivs(p, a, b, 2, xv);
                assert_same(yv[0], xv[0]); /* y(s,t) = x(a,b) */
                assert_rel(g + 3 * (i * 4 + j), yv[0]);
                if (s[i] == 0 || s[i] == 1 || t[j] == 0 || t[j] == 1) continue;
                /* partials against central differences of y itself */
                double pp[3], pm[3], mp[3], mm[3], fd[3];
                coons_patch_eval(y, s[i] + h, t[j], pp);
                coons_patch_eval(y, s[i] - h, t[j], pm);
                for (int k = 0; k < 3; k++) fd[k] = (pp[k] - pm[k]) / (2 * h);
                assert_vec3_near(fd, yv[1], 1e-5);
                coons_patch_eval(y, s[i], t[j] + h, pp);
                coons_patch_eval(y, s[i], t[j] - h, pm);
                for (int k = 0; k < 3; k++) fd[k] = (pp[k] - pm[k]) / (2 * h);
                assert_vec3_near(fd, yv[2], 1e-5);
                const double H = 1e-4;
                coons_patch_eval(y, s[i] + H, t[j] + H, pp);
                coons_patch_eval(y, s[i] + H, t[j] - H, pm);
                coons_patch_eval(y, s[i] - H, t[j] + H, mp);
                coons_patch_eval(y, s[i] - H, t[j] - H, mm);
                for (int k = 0; k < 3; k++) fd[k] = (pp[k] - pm[k] - mp[k] + mm[k]) / (4 * H * H);
                assert_vec3_near(fd, yv[4], 1e-4);
                double c0[3];
                coons_patch_eval(y, s[i], t[j], c0);
                coons_patch_eval(y, s[i] + H, t[j], pp);
                coons_patch_eval(y, s[i] - H, t[j], pm);
                for (int k = 0; k < 3; k++) fd[k] = (pp[k] - 2 * c0[k] + pm[k]) / (H * H);
                assert_vec3_near(fd, yv[3], 1e-3);
                coons_patch_eval(y, s[i], t[j] + H, pp);
                coons_patch_eval(y, s[i], t[j] - H, pm);
                for (int k = 0; k < 3; k++) fd[k] = (pp[k] - 2 * c0[k] + pm[k]) / (H * H);
                assert_vec3_near(fd, yv[5], 1e-3);
            }
        /* breakpoints: inner s knot 0.4, t knot 0.6, moved with the parameters */
        for (int dir = 0; dir < 2; dir++) {
            coons__breaks B = {0};
            coons__patch_breaks(y, dir, &B);
            int from = sw ? 1 - dir : dir;
            double k = from == 0 ? 0.4 : 0.6;
            if (from == 0 ? fs : ft) k = 1 - k;
            assert_int_equal(B.n, 1);
            assert_near(B.v[0], k, 1e-15);
            coons__free(B.v);
        }
        coons_patch_free(y);
    }
    coons_patch_free(p);
}

/* ---- bodies ------------------------------------------------------------ */

enum { NU = 3, NV = 4, NW = 3 };
static double VP[NU][NV][NW][3], VW[NU][NV][NW];

static coons_body *volume(const double (*pts)[NV][NW][3])
{
    coons_body *b = NULL;
    coons_error e = COONS_ERROR_INIT;
    int deg[3] = {2, 2, 2};
    size_t n[3] = {NU, NV, NW};
    double kv[7] = {0, 0, 0, 0.5, 1, 1, 1};
    assert_coons_ok(coons_body_new_bspline(deg, pts[0][0][0], n, NULL, kv, NULL, VW[0][0], &b, &e), &e);
    return b;
}

static void test_body_transform_nurbs(void **state)
{
    (void)state;
    double tp[NU][NV][NW][3];
    for (int i = 0; i < NU; i++)
        for (int j = 0; j < NV; j++)
            for (int k = 0; k < NW; k++) {
                v3_set(VP[i][j][k], i + 0.1 * j * k, j + 0.05 * i * i, k + 0.1 * sin(i + j));
                VW[i][j][k] = 1 + 0.25 * ((i + 2 * j + k) % 3);
                map_point(MIRROR, VP[i][j][k], tp[i][j][k]);
            }
    coons_body *b = volume((const double (*)[NV][NW][3])VP);
    coons_body *inl = volume((const double (*)[NV][NW][3])tp), *x = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_transformed(b, MIRROR, &x, &e), &e);
    assert_int_equal(coons_body_kind(x), COONS_BODY_BSPLINE);
    double dm = det3(MIRROR);
    assert_true(dm < 0);
    for (int i = 0; i <= 4; i++)
        for (int j = 0; j <= 4; j++)
            for (int k = 0; k <= 4; k++) {
                double u = i / 4.0, v = j / 4.0, w = k / 4.0, pa[3], pb[3], ja[3][3], jb[3][3],
                       j0[3][3], p0[3];
                double da = coons_body_eval_jacobian(x, u, v, w, pa, ja);
                double db = coons_body_eval_jacobian(inl, u, v, w, pb, jb);
                double d0 = coons_body_eval_jacobian(b, u, v, w, p0, j0);
                assert_rel(pa, pb);
                for (int r = 0; r < 3; r++) assert_rel(ja[r], jb[r]);
                assert_near(da, db, 1e-12 * fabs(db));
                assert_near(da, dm * d0, 1e-12 * fabs(da)); /* det J scales by det M */
            }
    double ua[3] = {0, 0.3, 1}, va[2] = {0.2, 0.9}, wa[2] = {0, 0.5}, ga[12 * 3], gb[12 * 3];
    assert_coons_ok(coons_body_eval_grid(x, ua, 3, va, 2, wa, 2, ga, &e), &e);
    assert_coons_ok(coons_body_eval_grid(inl, ua, 3, va, 2, wa, 2, gb, &e), &e);
    for (int i = 0; i < 12; i++) assert_rel(ga + 3 * i, gb + 3 * i);
    double va0, vx;
    /* 1e-9: a wrongly forwarded Jacobian is off by O(1); a tighter request
     * only multiplies the rational volume's evaluations (under valgrind
     * 1e-12 took two minutes). */
    assert_coons_ok(coons_body_volume(b, 1e-9, &va0, &e), &e);
    assert_coons_ok(coons_body_volume(x, 1e-9, &vx, &e), &e);
    assert_true(vx < 0); /* mirrored: left-handed */
    assert_near(vx, dm * va0, 4e-9 * fabs(vx));
    /* det grid (used by the volume mesh) and breakpoints forwarded */
    double det[12], det0[12];
    assert_coons_ok(coons__body_det_grid(x, ua, 3, va, 2, wa, 2, det, &e), &e);
    assert_coons_ok(coons__body_det_grid(b, ua, 3, va, 2, wa, 2, det0, &e), &e);
    for (int i = 0; i < 12; i++) assert_near(det[i], dm * det0[i], 1e-12 * fabs(det[i]));
    double *bk = NULL;
    size_t nbk = 0;
    assert_coons_ok(coons__body_breaks(x, 1, &bk, &nbk, &e), &e);
    assert_int_equal(nbk, 3);
    assert_near(bk[1], 0.5, 0);
    coons__free(bk);
    /* the control box holds the mapped control points */
    double lo[3], hi[3];
    coons_body_control_bbox(x, lo, hi);
    for (int i = 0; i < NU; i++)
        for (int j = 0; j < NV; j++)
            for (int k = 0; k < NW; k++)
                for (int c = 0; c < 3; c++)
                    assert_true(tp[i][j][k][c] >= lo[c] - 1e-12 && tp[i][j][k][c] <= hi[c] + 1e-12);
    coons_body *cx = NULL, *xx = NULL;
    assert_coons_ok(coons_body_copy(x, &cx, &e), &e);
    assert_coons_ok(coons_body_new_transformed(cx, ROT, &xx, &e), &e);
    assert_int_equal(coons_body_kind(xx), COONS_BODY_BSPLINE);
    double p1[3], p2[3], p3[3];
    coons_body_eval(xx, 0.2, 0.4, 0.6, p1);
    coons_body_eval(b, 0.2, 0.4, 0.6, p2);
    map_point(MIRROR, p2, p3);
    map_point(ROT, p3, p2);
    assert_rel(p1, p2);
    coons_body_free(xx);
    coons_body_free(cx);
    coons_body_free(x);
    coons_body_free(b);
    coons_body_free(inl);
}

/* ---- the loader -------------------------------------------------------- */

static coons_model *load(const char *json, coons_status want, coons_error *e)
{
    coons_model *m = NULL;
    coons_status rc = coons_model_load_memory(json, strlen(json), "t.json", NULL, &m, e);
    if (rc != want) fail_msg("load -> %d, want %d: %s", rc, want, e->message);
    return m;
}

/* Every body of a and b agrees at a lattice of points (bitwise: exact). */
static void same_models(const coons_model *a, const coons_model *b, int exact)
{
    assert_int_equal(coons_model_body_count(a), coons_model_body_count(b));
    for (size_t i = 0; i < coons_model_body_count(a); i++) {
        const coons_body *x = coons_model_body(a, i), *y = coons_model_body(b, i);
        assert_string_equal(coons_model_body_name(a, i), coons_model_body_name(b, i));
        assert_int_equal(coons_body_kind(x), coons_body_kind(y));
        for (int q = 0; q < 125; q++) {
            double u = (q / 25) / 4.0, v = (q / 5 % 5) / 4.0, w = (q % 5) / 4.0;
            double p[3], r[3], jp[3][3], jr[3][3];
            coons_body_eval_jacobian(x, u, v, w, p, jp);
            coons_body_eval_jacobian(y, u, v, w, r, jr);
            if (exact) {
                assert_same(p, r);
                for (int k = 0; k < 3; k++) assert_same(jp[k], jr[k]);
            } else {
                assert_rel(p, r);
                for (int k = 0; k < 3; k++) assert_rel(jp[k], jr[k]);
            }
        }
    }
    double lo[3], hi[3], lo2[3], hi2[3];
    coons_model_control_bbox(a, lo, hi);
    coons_model_control_bbox(b, lo2, hi2);
    assert_rel(lo, lo2);
    assert_rel(hi, hi2);
    assert_true(coons_model_tolerance(a) == coons_model_tolerance(b) || !exact);
}

#define ID "[[1,0,0,0],[0,1,0,0],[0,0,1,0]]"
#define LINE(a, b) "{\"type\":\"line\",\"points\":[" a "," b "]}"
#define ARC(z) "{\"type\":\"bspline\",\"degree\":2,\"points\":[[2,0," z "],[2,2," z "],[0,2," z "]],\"weights\":[1,0.7071067811865476,1]}"
#define HALF(z) "{\"type\":\"bspline\",\"degree\":2,\"points\":[[1,0," z "],[1,1," z "],[0,1," z "]],\"weights\":[1,0.7071067811865476,1]}"
#define ARCR(z) "{\"type\":\"bspline\",\"degree\":2,\"points\":[[0,2," z "],[2,2," z "],[2,0," z "]],\"weights\":[1,0.7071067811865476,1]}"

/* body1 with NURBS edges: u00 and u01 through references (one reversed
 * twice), the inline model writes them out. */
static const char *B1_INLINE =
    "{\"coons\":1,\"bodies\":[{\"type\":\"body1\",\"name\":\"q\",\"edges\":{"
    "\"u00\":" ARC("0") ",\"u01\":" ARC("1") ",\"u10\":" HALF("0") ",\"u11\":" HALF("1") ","
    "\"v00\":" LINE("[2,0,0]", "[1,0,0]") ",\"v01\":" LINE("[2,0,1]", "[1,0,1]") ","
    "\"v10\":" LINE("[0,2,0]", "[0,1,0]") ",\"v11\":" LINE("[0,2,1]", "[0,1,1]") ","
    "\"w00\":" LINE("[2,0,0]", "[2,0,1]") ",\"w01\":" LINE("[1,0,0]", "[1,0,1]") ","
    "\"w10\":" LINE("[0,2,0]", "[0,2,1]") ",\"w11\":" LINE("[0,1,0]", "[0,1,1]") "}}]}";

static void test_load_identity_refs(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    const char *half0 = HALF("0"), *half1 = HALF("1");
    char ref[4096];
    snprintf(ref, sizeof ref,
             "{\"coons\":1,\"define\":{\"arc\":" ARC("0") ",\"arc1\":{\"ref\":\"arc\",\"transform\":[[1,0,0,0],[0,1,0,0],[0,0,1,1]]},"
             "\"unused\":" LINE("[0,0]", "[9,9]") ","
             "\"half\":%s,\"cube\":{\"type\":\"body1\",\"name\":\"ignored\",\"edges\":{"
             "\"u00\":{\"ref\":\"arc\",\"transform\":" ID "},\"u01\":{\"ref\":\"arc1\"},"
             "\"u10\":{\"ref\":\"half\",\"reverse\":false},\"u11\":%s,"
             "\"v00\":" LINE("[2,0,0]", "[1,0,0]") ",\"v01\":" LINE("[2,0,1]", "[1,0,1]") ","
             "\"v10\":" LINE("[0,2,0]", "[0,1,0]") ",\"v11\":" LINE("[0,2,1]", "[0,1,1]") ","
             "\"w00\":" LINE("[2,0,0]", "[2,0,1]") ",\"w01\":" LINE("[1,0,0]", "[1,0,1]") ","
             "\"w10\":" LINE("[0,2,0]", "[0,2,1]") ",\"w11\":" LINE("[0,1,0]", "[0,1,1]") "}}},"
             "\"bodies\":[{\"ref\":\"cube\",\"name\":\"q\",\"transform\":" ID "}]}",
             half0, half1);
    coons_model *a = load(B1_INLINE, COONS_OK, &e), *b = load(ref, COONS_OK, &e);
    /* arc1's transform only translates: z + 1 is exact, so bitwise */
    same_models(a, b, 1);
    coons_model_free(a);
    coons_model_free(b);
}

static void test_load_reverse_swap_flip(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    /* body1 whose u00 is given reversed from the reversed arc */
    char ref[4096], inl[4096];
    snprintf(inl, sizeof inl, "%s", B1_INLINE);
    snprintf(ref, sizeof ref, "%s", B1_INLINE);
    char *p = strstr(ref, "\"u00\":");
    char tail[4096];
    snprintf(tail, sizeof tail, "%s", strstr(p, ",\"u01\""));
    snprintf(p, sizeof ref - (size_t)(p - ref), "\"u00\":{\"ref\":\"r\",\"reverse\":true}%s", tail);
    char full[4400];
    snprintf(full, sizeof full, "{\"coons\":1,\"define\":{\"r\":" ARCR("0") "},%s", ref + strlen("{\"coons\":1,"));
    coons_model *a = load(inl, COONS_OK, &e), *b = load(full, COONS_OK, &e);
    same_models(a, b, 0); /* 1 - (1 - t) is t only to rounding */
    coons_model_free(a);
    coons_model_free(b);

    /* body2 of bilinear faces: face w0 given swapped and flipped */
    static const char *C8 = "[[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1.5,1.2,1]]";
    (void)C8;
#define BL(a, b, c, d) "{\"type\":\"bilinear\",\"corners\":[" a "," b "," c "," d "]}"
#define P000 "[0,0,0]"
#define P001 "[0,0,1]"
#define P010 "[0,1,0]"
#define P011 "[0,1,1]"
#define P100 "[1,0,0]"
#define P101 "[1,0,1]"
#define P110 "[1,1,0]"
#define P111 "[1.5,1.2,1]"
    /* X_ab = x(s=a, t=b); u faces (s,t) = (v,w), v faces (u,w), w faces (u,v) */
    const char *faces_tail =
        "\"u0\":" BL(P000, P010, P001, P011) ",\"u1\":" BL(P100, P110, P101, P111) ","
        "\"v0\":" BL(P000, P100, P001, P101) ",\"v1\":" BL(P010, P110, P011, P111) ","
        "\"w1\":" BL(P001, P101, P011, P111);
    char b2i[4096], b2r[4096];
    snprintf(b2i, sizeof b2i,
             "{\"coons\":1,\"bodies\":[{\"type\":\"body2\",\"name\":\"f\",\"faces\":{%s,\"w0\":" BL(P000, P100, P010, P110) "}}]}",
             faces_tail);
    /* w0 = x(u,v); the definition g(s,t) with y = g(1-t, 1-s) after swap
     * then both flips: g(a,b) = w0(1-b, 1-a), i.e. g's corners G_ab = w0(1-b,1-a) */
    snprintf(b2r, sizeof b2r,
             "{\"coons\":1,\"define\":{\"g\":" BL(P110, P100, P010, P000) "},"
             "\"bodies\":[{\"type\":\"body2\",\"name\":\"f\",\"faces\":{%s,\"w0\":{\"ref\":\"g\",\"swap\":true,\"flip_s\":true,\"flip_t\":true}}}]}",
             faces_tail);
    a = load(b2i, COONS_OK, &e);
    b = load(b2r, COONS_OK, &e);
    same_models(a, b, 0);
    coons_model_free(a);
    coons_model_free(b);
}

/* A transformed NURBS volume reference against the inline volume with the
 * control points mapped here; the model's box is that of the mapped points. */
static void test_load_transform_nurbs(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    const double M[12] = {0, -2, 0, 10, 1, 0, 0.5, -2, 0, 0, 1, 3};
    double P[2][2][3][3];
    double W[2][2][3] = {{{1, 0.5, 1}, {1, 2, 1}}, {{1, 0.75, 1}, {1, 1, 3}}};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 3; k++) v3_set(P[i][j][k], i + 0.25 * k, j * 1.5, k + 0.3 * i * j);
    char pts[2][1024], wts[256];
    for (int q = 0; q < 2; q++) {
        size_t o = 0;
        o += (size_t)snprintf(pts[q] + o, 1024 - o, "[");
        for (int i = 0; i < 2; i++) {
            o += (size_t)snprintf(pts[q] + o, 1024 - o, "%s[", i ? "," : "");
            for (int j = 0; j < 2; j++) {
                o += (size_t)snprintf(pts[q] + o, 1024 - o, "%s[", j ? "," : "");
                for (int k = 0; k < 3; k++) {
                    double x[3];
                    if (q) map_point(M, P[i][j][k], x);
                    else v3_copy(x, P[i][j][k]);
                    o += (size_t)snprintf(pts[q] + o, 1024 - o, "%s[%.17g,%.17g,%.17g]", k ? "," : "", x[0], x[1], x[2]);
                }
                o += (size_t)snprintf(pts[q] + o, 1024 - o, "]");
            }
            o += (size_t)snprintf(pts[q] + o, 1024 - o, "]");
        }
        snprintf(pts[q] + o, 1024 - o, "]");
    }
    snprintf(wts, sizeof wts, "[[[1,0.5,1],[1,2,1]],[[1,0.75,1],[1,1,3]]]");
    (void)W;
    char inl[4096], ref[4096];
    snprintf(inl, sizeof inl,
             "{\"coons\":1,\"tolerance\":0.01,\"bodies\":[{\"type\":\"bspline-volume\",\"name\":\"v\",\"degree\":[1,1,2],\"points\":%s,\"weights\":%s}]}",
             pts[1], wts);
    snprintf(ref, sizeof ref,
             "{\"coons\":1,\"tolerance\":0.01,\"define\":{\"v\":{\"type\":\"bspline-volume\",\"degree\":[1,1,2],\"points\":%s,\"weights\":%s}},"
             "\"bodies\":[{\"ref\":\"v\",\"transform\":[[0,-2,0,10],[1,0,0.5,-2],[0,0,1,3]]}]}",
             pts[0], wts);
    coons_model *a = load(inl, COONS_OK, &e), *b = load(ref, COONS_OK, &e);
    same_models(a, b, 0);
    coons_model_free(a);
    coons_model_free(b);
}

static void test_load_errors(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    /* an unused definition is still checked, also its agreement checks */
    load("{\"coons\":1,\"define\":{\"p\":{\"type\":\"coons\",\"boundary\":{"
         "\"t0\":" LINE("[0,0]", "[1,0]") ",\"t1\":" LINE("[0,1]", "[1,1]") ","
         "\"s0\":" LINE("[0,0]", "[0,1]") ",\"s1\":" LINE("[1,0]", "[1,2]") "}}},"
         "\"bodies\":[{\"type\":\"body0\",\"corners\":[[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]}",
         COONS_E_INCOMPATIBLE, &e);
    assert_non_null(strstr(e.path, "/define/p/boundary"));
    /* and its values, as when used */
    load("{\"coons\":1,\"define\":{\"x\":{\"type\":\"line\",\"points\":[[0,0]]}},"
         "\"bodies\":[{\"type\":\"body0\",\"corners\":[[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]}",
         COONS_E_INVALID, &e);
    assert_string_equal(e.path, "/define/x/points");
    assert_null(strstr(e.message, "referenced at"));
    /* an error inside a definition: its path, and the references' in the message */
    load("{\"coons\":1,\"define\":{\"c\":{\"type\":\"body0\",\"corners\":[[0,0,0]]},"
         "\"b\":{\"ref\":\"c\",\"transform\":[[2,0,0,0],[0,1,0,0],[0,0,1,0]]}},"
         "\"bodies\":[{\"ref\":\"b\"}]}",
         COONS_E_INVALID, &e);
    assert_string_equal(e.path, "/define/c/corners");
    assert_non_null(strstr(e.message, "in definition \"c\" referenced at /define/b"));
    assert_non_null(strstr(e.message, "in \"b\" referenced at /bodies/0"));
    assert_int_equal(e.line, 1);
    /* a patch where a curve stands, in an unused definition */
    load("{\"coons\":1,\"define\":{\"q\":{\"type\":\"bilinear\",\"corners\":[[0,0],[1,0],[0,1],[1,1]]},"
         "\"p\":{\"type\":\"ruled\",\"curves\":[{\"ref\":\"q\"}," LINE("[0,1]", "[1,1]") "]}},"
         "\"bodies\":[{\"type\":\"body0\",\"corners\":[[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]}",
         COONS_E_INVALID, &e);
    assert_string_equal(e.path, "/define/p/curves/0/ref");
    assert_non_null(strstr(e.message, "\"q\" is a patch"));
    assert_non_null(strstr(e.message, "a curve stands here"));
    /* the control box is that of the points as instanced, unused definitions aside */
    coons_model *m = load("{\"coons\":1,\"define\":{\"c\":{\"type\":\"body0\",\"corners\":[[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]},"
                          "\"far\":" LINE("[-100,0]", "[100,0]") "},"
                          "\"bodies\":[{\"ref\":\"c\",\"transform\":[[0,-3,0,10],[1,0,0,0],[0,0,1,0]]}]}",
                          COONS_OK, &e);
    double lo[3], hi[3], wl[3] = {7, 0, 0}, wh[3] = {10, 1, 1};
    coons_model_control_bbox(m, lo, hi);
    assert_same(lo, wl);
    assert_same(hi, wh);
    assert_string_equal(coons_model_body_name(m, 0), "c");
    coons_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_curve_transform_nurbs),
        cmocka_unit_test(test_curve_transform_hermite_and_bezier),
        cmocka_unit_test(test_curve_reverse),
        cmocka_unit_test(test_transform_refused),
        cmocka_unit_test(test_patch_transform_nurbs),
        cmocka_unit_test(test_patch_reparam),
        cmocka_unit_test(test_body_transform_nurbs),
        cmocka_unit_test(test_load_identity_refs),
        cmocka_unit_test(test_load_reverse_swap_flip),
        cmocka_unit_test(test_load_transform_nurbs),
        cmocka_unit_test(test_load_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
