/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The agreement checker (src/core/agree.c, compiled into this test: its
 * functions are internal): on a unit square and a unit cube it accepts
 * what agrees and, for one disagreement at a time, names the place, the
 * two sources, their parameters and values, and the distance; body 2
 * edges are sampled at 33 points.
 */
#include <math.h>
#include <string.h>

#include "agree.h"
#include "test_util.h"

static coons_curve *line(double x0, double y0, double z0, double x1, double y1, double z1)
{
    const double a[3] = {x0, y0, z0}, b[3] = {x1, y1, z1};
    coons_curve *c = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_line(a, b, &c, &err), &err);
    return c;
}

/* t0 t1 s0 s1 of the unit square, x(s,0) = t0, x(0,t) = s0. */
static void square(coons_curve *b[4])
{
    b[COONS_SIDE_T0] = line(0, 0, 0, 1, 0, 0);
    b[COONS_SIDE_T1] = line(0, 1, 0, 1, 1, 0);
    b[COONS_SIDE_S0] = line(0, 0, 0, 0, 1, 0);
    b[COONS_SIDE_S1] = line(1, 0, 0, 1, 1, 0);
}

static void free_curves(coons_curve **c, int n)
{
    for (int k = 0; k < n; k++) coons_curve_free(c[k]);
}

/* Given the unit square with t1 starting 0.25 above X01, then the corner
 * check stops at X01 (s=0, t=1): t1(0) against s0(1), 0.25 apart. */
static void test_patch_corners(void **state)
{
    (void)state;
    coons_curve *b[4];
    square(b);
    coons__agree r;
    memset(&r, 0, sizeof r);
    assert_int_equal(coons__agree_patch_corners((const coons_curve *const *)b, 1e-12, &r),
                     COONS_OK);
    coons_curve_free(b[COONS_SIDE_T1]);
    b[COONS_SIDE_T1] = line(0, 1, 0.25, 1, 1, 0);
    assert_int_equal(coons__agree_patch_corners((const coons_curve *const *)b, 1e-12, &r),
                     COONS_E_INCOMPATIBLE);
    assert_int_equal(r.at, 2);
    assert_int_equal(r.a, COONS_SIDE_T1);
    assert_int_equal(r.b, COONS_SIDE_S0);
    assert_near(r.ta, 0.0, 0.0);
    assert_near(r.tb, 1.0, 0.0);
    const double pa[3] = {0, 1, 0.25}, pb[3] = {0, 1, 0};
    assert_vec3_near(r.pa, pa, 1e-15);
    assert_vec3_near(r.pb, pb, 1e-15);
    assert_near(r.dist, 0.25, 1e-15);
    /* within a tolerance above the gap it agrees */
    assert_int_equal(coons__agree_patch_corners((const coons_curve *const *)b, 0.3, &r),
                     COONS_OK);
    free_curves(b, 4);
}

/* A quadratic Bezier from p to p through m: a curve with equal ends. */
static coons_curve *loop(const double p[3], const double m[3])
{
    double pts[9];
    memcpy(pts, p, 3 * sizeof(double));
    memcpy(pts + 3, m, 3 * sizeof(double));
    memcpy(pts + 6, p, 3 * sizeof(double));
    coons_curve *c = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_bezier(pts, 3, &c, &err), &err);
    return c;
}

/* Given cross curves equal to the square's tangents at their ends, then
 * they agree; with cross s1(1) off by 0.5 the check names cross s1 at 1
 * against t1'(1). */
static void test_cross(void **state)
{
    (void)state;
    coons_curve *b[4], *cr[4];
    square(b);
    const double xt[3] = {0, 1, 0}, xs[3] = {1, 0, 0}, mid[3] = {0.3, 0.2, 0.1};
    cr[0] = loop(xt, mid); /* x_t(s,0) = s0'(0) = s1'(0) */
    cr[1] = loop(xt, mid); /* x_t(s,1) */
    cr[2] = loop(xs, mid); /* x_s(0,t) = t0'(0) = t1'(0) */
    cr[3] = loop(xs, mid); /* x_s(1,t) */
    coons__agree r;
    const coons_curve *const *bb = (const coons_curve *const *)b;
    assert_int_equal(coons__agree_cross(bb, (const coons_curve *const *)cr, 1e-12, &r), COONS_OK);
    coons_curve_free(cr[3]);
    const double pts[9] = {1, 0, 0, 0.3, 0.2, 0.1, 1, 0, 0.5};
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_bezier(pts, 3, &cr[3], &err), &err);
    assert_int_equal(coons__agree_cross(bb, (const coons_curve *const *)cr, 1e-12, &r),
                     COONS_E_INCOMPATIBLE);
    assert_int_equal(r.at, 3);
    assert_near(r.ta, 1.0, 0.0);
    assert_int_equal(r.b, COONS_SIDE_T1);
    assert_near(r.tb, 1.0, 0.0);
    const double pa[3] = {1, 0, 0.5};
    assert_vec3_near(r.pa, pa, 1e-15);
    assert_vec3_near(r.pb, xs, 1e-15);
    assert_near(r.dist, 0.5, 1e-15);
    free_curves(cr, 4);
    free_curves(b, 4);
}

/* The 12 edges of the unit cube: u_jk = (x, j, k), v_ik = (i, x, k),
 * w_ij = (i, j, x); edge indices 2j+k, 4+2i+k, 8+2i+j. */
static void cube_edges(coons_curve *e[12])
{
    for (int x = 0; x < 2; x++)
        for (int y = 0; y < 2; y++) {
            e[2 * x + y] = line(0, x, y, 1, x, y);
            e[4 + 2 * x + y] = line(x, 0, y, x, 1, y);
            e[8 + 2 * x + y] = line(x, y, 0, x, y, 1);
        }
}

/* Given the cube's edges, then they meet; with v10's end 0.3 off, corner
 * C110 fails first between u10 and v10; with w00's start off, corner C000
 * fails between u00 and w00 (pairs u-v, u-w, v-w in turn). */
static void test_body1_corners(void **state)
{
    (void)state;
    coons_curve *e[12];
    cube_edges(e);
    coons__agree r;
    const coons_curve *const *ee = (const coons_curve *const *)e;
    assert_int_equal(coons__agree_body1_corners(ee, 1e-12, &r), COONS_OK);
    coons_curve_free(e[6]);
    e[6] = line(1, 0, 0, 1, 1, 0.3);
    assert_int_equal(coons__agree_body1_corners(ee, 1e-12, &r), COONS_E_INCOMPATIBLE);
    assert_int_equal(r.at, 6); /* C110 = 4i + 2j + k */
    assert_int_equal(r.a, 2);  /* u10 */
    assert_int_equal(r.b, 6);  /* v10 */
    assert_near(r.ta, 1.0, 0.0);
    assert_near(r.tb, 1.0, 0.0);
    assert_near(r.dist, 0.3, 1e-15);
    coons_curve_free(e[6]);
    e[6] = line(1, 0, 0, 1, 1, 0);
    coons_curve_free(e[8]);
    e[8] = line(0, 0, 0.1, 0, 0, 1);
    assert_int_equal(coons__agree_body1_corners(ee, 1e-12, &r), COONS_E_INCOMPATIBLE);
    assert_int_equal(r.at, 0);
    assert_int_equal(r.a, 0); /* u00 */
    assert_int_equal(r.b, 8); /* w00 */
    assert_near(r.ta, 0.0, 0.0);
    assert_near(r.tb, 0.0, 0.0);
    assert_near(r.dist, 0.1, 1e-15);
    free_curves(e, 12);
}

/* Point (s,t) of face f of the unit cube: X_i(v,w) = (i, s, t),
 * Y_j(u,w) = (s, j, t), Z_k(u,v) = (s, t, k). */
static void face_point(int f, double s, double t, double p[3])
{
    int x = f & 1;
    if (f < 2) v3_set(p, x, s, t);
    else if (f < 4) v3_set(p, s, x, t);
    else v3_set(p, s, t, x);
}

/* Face f as a cubic Bezier surface; h lifts control point [1][0] along z. */
static coons_patch *face(int f, double h)
{
    double pts[16 * 3];
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) face_point(f, a / 3.0, b / 3.0, pts + (a * 4 + b) * 3);
    pts[(1 * 4 + 0) * 3 + 2] += h;
    coons_patch *p = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_patch_new_bezier(pts, 4, 4, &p, &err), &err);
    return p;
}

/* Given the cube's faces, then they agree; with w0's edge v = 0 lifted by
 * 3x(1-x)^2 h, edge u00 fails between v0 and w0 at the sample nearest the
 * maximum x = 1/3 among 33 (x = 11/32; 19 samples would find 6/18). The
 * constructor reports the same place. */
static void test_body2_edges(void **state)
{
    (void)state;
    coons_patch *f[6];
    for (int k = 0; k < 6; k++) f[k] = face(k, 0.0);
    coons__agree r;
    const coons_patch *const *ff = (const coons_patch *const *)f;
    assert_int_equal(coons__agree_body2_edges(ff, 1e-12, &r), COONS_OK);
    const double h = 0.4;
    coons_patch_free(f[4]);
    f[4] = face(4, h);
    assert_int_equal(coons__agree_body2_edges(ff, 1e-12, &r), COONS_E_INCOMPATIBLE);
    assert_int_equal(r.at, 0); /* u00 */
    assert_int_equal(r.a, 2);  /* v0 */
    assert_int_equal(r.b, 4);  /* w0 */
    double x = 11.0 / 32.0;
    assert_near(r.ta, x, 0.0);
    assert_near(r.tb, x, 0.0);
    double z = 3 * x * (1 - x) * (1 - x) * h;
    const double pa[3] = {x, 0, 0}, pb[3] = {x, 0, z};
    assert_vec3_near(r.pa, pa, 1e-15);
    assert_vec3_near(r.pb, pb, 1e-15);
    assert_near(r.dist, z, 1e-15);
    assert_int_equal(COONS__AGREE_EDGE_SAMPLES, 33);
    coons_body *b = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_int_equal(coons_body_new_body2(f, COONS_BLEND_LINEAR, 1e-12, &b, &err),
                     COONS_E_INCOMPATIBLE);
    if (!strstr(err.message, "edge u00 (v=0,w=0): faces v0 and w0") ||
        !strstr(err.message, "at u=0.34375"))
        fail_msg("message '%s'", err.message);
    for (int k = 0; k < 6; k++) coons_patch_free(f[k]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_patch_corners),
        cmocka_unit_test(test_cross),
        cmocka_unit_test(test_body1_corners),
        cmocka_unit_test(test_body2_edges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
