/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Tensor-product Bezier and B-spline/NURBS surfaces: exact NURBS sphere
 * and cylinder, edges equal to the corresponding curves, Bezier = B-spline
 * with Bezier knots, derivatives against finite differences and the
 * sphere's identities, grids, copies and argument checks. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "patch_fixture.h"

static const double par11[11] = {0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};

/* The full unit circle as a quadratic NURBS: 9 points, knots
 * 0,0,0,1/4,1/4,1/2,1/2,3/4,3/4,1,1,1, weights 1, r, 1, r, ... (r = 1/sqrt 2). */
static const double circ_xy[9][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0},
                                     {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
static const double circ_knots[12] = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
static double circ_w(int j) { return (j & 1) ? sqrt(0.5) : 1.0; }

/* Unit sphere: half-circle profile (south pole to north pole through
 * (1,0,0)) along s, revolved by the full circle along t. */
static coons_patch *make_sphere(void)
{
    const double prof[5][2] = {{0, -1}, {1, -1}, {1, 0}, {1, 1}, {0, 1}}; /* (r, z) */
    const double pk[8] = {0, 0, 0, 0.5, 0.5, 1, 1, 1};
    double P[5][9][3], W[5][9];
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 9; j++) {
            P[i][j][0] = prof[i][0] * circ_xy[j][0];
            P[i][j][1] = prof[i][0] * circ_xy[j][1];
            P[i][j][2] = prof[i][1];
            W[i][j] = circ_w(i) * circ_w(j);
        }
    coons_error err = COONS_ERROR_INIT;
    coons_patch *p = NULL;
    assert_coons_ok(coons_patch_new_bspline(2, 2, &P[0][0][0], 5, 9, pk, circ_knots, &W[0][0], &p,
                                            &err),
                    &err);
    return p;
}

/* Cylinder of radius 2 and height 3: degree 1 along s (z), circle along t. */
static coons_patch *make_cylinder(void)
{
    double P[2][9][3], W[2][9];
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 9; j++) {
            P[i][j][0] = 2 * circ_xy[j][0];
            P[i][j][1] = 2 * circ_xy[j][1];
            P[i][j][2] = 3.0 * i;
            W[i][j] = circ_w(j);
        }
    coons_error err = COONS_ERROR_INIT;
    coons_patch *p = NULL;
    assert_coons_ok(coons_patch_new_bspline(1, 2, &P[0][0][0], 2, 9, NULL, circ_knots, &W[0][0], &p,
                                            &err),
                    &err);
    return p;
}

/* Given the NURBS sphere, then |x| = 1 to 1e-12 everywhere, and the
 * derivatives of |x|^2 = 1 vanish: x.x_s = x.x_t = 0 and
 * x.x_ss + x_s.x_s = 0, x.x_st + x_s.x_t = 0, x.x_tt + x_t.x_t = 0. */
static void test_nurbs_sphere(void **state)
{
    (void)state;
    coons_patch *p = make_sphere();
    assert_int_equal(coons_patch_kind(p), COONS_PATCH_BSPLINE);
    for (int i = 0; i <= 40; i++)
        for (int j = 0; j <= 40; j++) {
            double d[6][3];
            coons_patch_eval_derivs(p, i / 40.0 + 0.003 * (i % 3), j / 40.0, 2, d);
            double r = sqrt(d[0][0] * d[0][0] + d[0][1] * d[0][1] + d[0][2] * d[0][2]);
            assert_near(r, 1.0, 1e-12);
#define DOT(a, b) ((a)[0] * (b)[0] + (a)[1] * (b)[1] + (a)[2] * (b)[2])
            double sc = 1.0 + DOT(d[1], d[1]) + DOT(d[2], d[2]);
            assert_near(DOT(d[0], d[1]), 0.0, 1e-12 * sc);
            assert_near(DOT(d[0], d[2]), 0.0, 1e-12 * sc);
            double sc2 = sc + sqrt(DOT(d[3], d[3]) + DOT(d[4], d[4]) + DOT(d[5], d[5]));
            assert_near(DOT(d[0], d[3]) + DOT(d[1], d[1]), 0.0, 1e-11 * sc2);
            assert_near(DOT(d[0], d[4]) + DOT(d[1], d[2]), 0.0, 1e-11 * sc2);
            assert_near(DOT(d[0], d[5]) + DOT(d[2], d[2]), 0.0, 1e-11 * sc2);
        }
    /* poles and the seam */
    double x[3];
    coons_patch_eval(p, 0.0, 0.37, x);
    assert_vec3_near(x, ((double[3]){0, 0, -1}), 1e-15);
    coons_patch_eval(p, 0.5, 0.25, x);
    assert_vec3_near(x, ((double[3]){0, 1, 0}), 1e-15);
    coons_patch_free(p);
}

/* Given the NURBS cylinder, then its distance to the axis is 2 to 1e-12
 * and z = 3 s. */
static void test_nurbs_cylinder(void **state)
{
    (void)state;
    coons_patch *p = make_cylinder();
    for (int i = 0; i <= 20; i++)
        for (int j = 0; j <= 80; j++) {
            double x[3], s = i / 20.0;
            coons_patch_eval(p, s, j / 80.0, x);
            assert_near(hypot(x[0], x[1]), 2.0, 1e-12);
            assert_near(x[2], 3.0 * s, 1e-14);
        }
    fx_check_derivs_fd(p, 1e-6);
    fx_check_grid(p);
    coons_patch_free(p);
}

/* Given the cylinder of radius 2e9 with every weight multiplied by 1e300
 * (w P alone would overflow) or by 1e-300, then it is still the cylinder; a weight ratio above the limit is COONS_E_LIMIT. */
static void test_nurbs_weight_scale(void **state)
{
    (void)state;
    const double scales[] = {1e300, 1e-300};
    double P[2][9][3], W[2][9];
    for (size_t k = 0; k <= sizeof scales / sizeof scales[0]; k++) {
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 9; j++) {
                P[i][j][0] = 2e9 * circ_xy[j][0];
                P[i][j][1] = 2e9 * circ_xy[j][1];
                P[i][j][2] = 3e9 * i;
                W[i][j] = k < 2 ? circ_w(j) * scales[k] : (i ? 2e100 : 1.0);
            }
        coons_error err = COONS_ERROR_INIT;
        coons_patch *p = NULL;
        coons_status rc = coons_patch_new_bspline(1, 2, &P[0][0][0], 2, 9, NULL, circ_knots,
                                                  &W[0][0], &p, &err);
        if (k == 2) {
            assert_int_equal(rc, COONS_E_LIMIT);
            assert_non_null(strstr(err.message, "ratio"));
            assert_null(p);
            break;
        }
        assert_coons_ok(rc, &err);
        for (int i = 0; i <= 10; i++)
            for (int j = 0; j <= 40; j++) {
                double x[3], s = i / 10.0;
                coons_patch_eval(p, s, j / 40.0, x);
                assert_near(hypot(x[0], x[1]) / 2e9, 1.0, 1e-14);
                assert_near(x[2] / 3e9, s, 1e-14);
            }
        coons_patch_free(p);
    }
}

/* A 4 x 5 net with some shape. */
static void net(double P[4][5][3])
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 5; j++) {
            P[i][j][0] = i + 0.1 * j;
            P[i][j][1] = j - 0.2 * i * i;
            P[i][j][2] = cos(0.9 * i + 1.7 * j);
        }
}

/* Given a Bezier net, then the Bezier surface equals the B-spline surface
 * of the same degrees with knots 0^(p+1) 1^(p+1), its edges are the Bezier
 * curves of the boundary rows, and its corners are the corner points. */
static void test_bezier_surface(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    double P[4][5][3];
    net(P);
    coons_patch *b = NULL, *s = NULL;
    assert_coons_ok(coons_patch_new_bezier(&P[0][0][0], 4, 5, &b, &err), &err);
    assert_int_equal(coons_patch_kind(b), COONS_PATCH_BEZIER);
    const double ks[8] = {0, 0, 0, 0, 1, 1, 1, 1}, kt[10] = {0, 0, 0, 0, 0, 1, 1, 1, 1, 1};
    assert_coons_ok(coons_patch_new_bspline(3, 4, &P[0][0][0], 4, 5, ks, kt, NULL, &s, &err), &err);
    for (int i = 0; i < 11; i++)
        for (int j = 0; j < 11; j++) {
            double d1[6][3], d2[6][3];
            coons_patch_eval_derivs(b, par11[i], par11[j], 2, d1);
            coons_patch_eval_derivs(s, par11[i], par11[j], 2, d2);
            for (int k = 0; k < 6; k++) assert_vec3_near(d1[k], d2[k], 1e-12 * fx_scale(d1[k]));
        }
    /* edges */
    double e[4][5][3];
    for (int m = 0; m < 4; m++) memcpy(e[0][m], P[m][0], sizeof e[0][m]);
    for (int m = 0; m < 4; m++) memcpy(e[1][m], P[m][4], sizeof e[1][m]);
    for (int m = 0; m < 5; m++) memcpy(e[2][m], P[0][m], sizeof e[2][m]);
    for (int m = 0; m < 5; m++) memcpy(e[3][m], P[3][m], sizeof e[3][m]);
    coons_curve *c[4];
    for (int k = 0; k < 4; k++)
        assert_coons_ok(coons_curve_new_bezier(&e[k][0][0], k < 2 ? 4 : 5, &c[k], &err), &err);
    for (int i = 0; i < 11; i++) {
        double u = par11[i], x[3], y[3];
        coons_patch_eval(b, u, 0.0, x);
        coons_curve_eval(c[0], u, y);
        assert_vec3_near(x, y, 1e-14);
        coons_patch_eval(b, u, 1.0, x);
        coons_curve_eval(c[1], u, y);
        assert_vec3_near(x, y, 1e-14);
        coons_patch_eval(b, 0.0, u, x);
        coons_curve_eval(c[2], u, y);
        assert_vec3_near(x, y, 1e-14);
        coons_patch_eval(b, 1.0, u, x);
        coons_curve_eval(c[3], u, y);
        assert_vec3_near(x, y, 1e-14);
    }
    double x[3];
    coons_patch_eval(b, 1.0, 1.0, x);
    assert_vec3_near(x, P[3][4], 0.0);
    fx_check_derivs_fd(b, 1e-6);
    fx_check_grid(b);
    coons_patch_free(b);
    coons_patch_free(s);
    for (int k = 0; k < 4; k++) coons_curve_free(c[k]);
}

/* Given a rational B-spline surface with non-uniform knots, then its edges
 * are the NURBS curves of the boundary rows with the same knots and
 * weights, derivatives match finite differences, and grid = pointwise. */
static void test_bspline_surface(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    enum { NS = 6, NT = 5 };
    double P[NS][NT][3], W[NS][NT];
    for (int i = 0; i < NS; i++)
        for (int j = 0; j < NT; j++) {
            P[i][j][0] = i + 0.1 * sin(j);
            P[i][j][1] = j + 0.3 * cos(i);
            P[i][j][2] = 0.5 * sin(0.8 * i + 1.1 * j);
            W[i][j] = 1.0 + 0.5 * sin(i + 2.0 * j) * sin(i + 2.0 * j);
        }
    /* s: cubic with non-uniform interior knots, not normalised; t: quadratic,
     * default clamped knots. */
    const double ks[10] = {-1, -1, -1, -1, 0.7, 2.4, 3, 3, 3, 3};
    coons_patch *p = NULL;
    assert_coons_ok(coons_patch_new_bspline(3, 2, &P[0][0][0], NS, NT, ks, NULL, &W[0][0], &p, &err),
                    &err);
    double row[NS][3], rw[NS], col[NT][3], cw[NT];
    for (int i = 0; i < NS; i++) {
        memcpy(row[i], P[i][NT - 1], sizeof row[i]);
        rw[i] = W[i][NT - 1];
    }
    for (int j = 0; j < NT; j++) {
        memcpy(col[j], P[0][j], sizeof col[j]);
        cw[j] = W[0][j];
    }
    coons_curve *t1 = NULL, *s0 = NULL;
    assert_coons_ok(coons_curve_new_bspline(3, &row[0][0], NS, ks, rw, &t1, &err), &err);
    assert_coons_ok(coons_curve_new_bspline(2, &col[0][0], NT, NULL, cw, &s0, &err), &err);
    for (int i = 0; i < 11; i++) {
        double u = par11[i], x[3], y[3], d[6][3], cd[3][3];
        coons_patch_eval(p, u, 1.0, x);
        coons_curve_eval(t1, u, y);
        assert_vec3_near(x, y, 1e-13);
        coons_patch_eval(p, 0.0, u, x);
        coons_curve_eval(s0, u, y);
        assert_vec3_near(x, y, 1e-13);
        /* along the edge, the patch's tangent is the curve's */
        coons_patch_eval_derivs(p, u, 1.0, 2, d);
        coons_curve_eval_derivs(t1, u, 2, cd);
        assert_vec3_near(d[1], cd[1], 1e-12 * fx_scale(cd[1]));
    }
    fx_check_derivs_fd(p, 1e-6);
    fx_check_grid(p);
    /* copy */
    coons_patch *q = NULL;
    assert_coons_ok(coons_patch_copy(p, &q, &err), &err);
    for (int i = 0; i < 11; i++)
        for (int j = 0; j < 11; j++) {
            double a[6][3], b[6][3];
            coons_patch_eval_derivs(p, par11[i], par11[j], 2, a);
            coons_patch_eval_derivs(q, par11[i], par11[j], 2, b);
            assert_memory_equal(a, b, sizeof a);
        }
    double lo[3], hi[3];
    coons_patch_control_bbox(q, lo, hi);
    for (int i = 0; i < NS; i++)
        for (int j = 0; j < NT; j++)
            for (int k = 0; k < 3; k++) {
                assert_true(lo[k] <= P[i][j][k]);
                assert_true(hi[k] >= P[i][j][k]);
            }
    coons_patch_free(p);
    coons_patch_free(q);
    coons_curve_free(t1);
    coons_curve_free(s0);
}

/* Given a degree (1,1) B-spline surface of 2 x 2 points, then it is the
 * bilinear patch of its corners. */
static void test_bspline_bilinear(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_patch *a = NULL, *b = NULL;
    assert_coons_ok(coons_patch_new_bilinear(fx_corner[0], &a, &err), &err);
    /* points[(i*nt + j)]: i along s: X00, X01, X10, X11 */
    double P[4][3];
    memcpy(P[0], fx_corner[0], sizeof P[0]);
    memcpy(P[1], fx_corner[2], sizeof P[1]);
    memcpy(P[2], fx_corner[1], sizeof P[2]);
    memcpy(P[3], fx_corner[3], sizeof P[3]);
    assert_coons_ok(coons_patch_new_bspline(1, 1, &P[0][0], 2, 2, NULL, NULL, NULL, &b, &err), &err);
    for (int i = 0; i < 11; i++)
        for (int j = 0; j < 11; j++) {
            double x[3], y[3];
            coons_patch_eval(a, par11[i], par11[j], x);
            coons_patch_eval(b, par11[i], par11[j], y);
            assert_vec3_near(x, y, 1e-15);
        }
    coons_patch_free(a);
    coons_patch_free(b);
}

/* Given invalid nets, degrees, knots or weights, or sizes above the
 * limits, then the constructors refuse them (limits before allocating). */
static void test_tensor_invalid(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_patch *p = NULL;
    double P[4][5][3], W[4][5];
    net(P);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 5; j++) W[i][j] = 1.0;
    assert_int_equal(coons_patch_new_bezier(&P[0][0][0], 1, 5, &p, &err), COONS_E_INVALID);
    assert_int_equal(coons_patch_new_bezier(NULL, 4, 5, &p, &err), COONS_E_INVALID);
    assert_int_equal(coons_patch_new_bezier(&P[0][0][0], 4, 5, NULL, &err), COONS_E_INVALID);
    assert_int_equal(coons_patch_new_bezier(&P[0][0][0], COONS_SPLINE_MAX_DEGREE + 2, 2, &p, &err),
                     COONS_E_LIMIT);
    assert_int_equal(coons_patch_new_bspline(2, 2, &P[0][0][0], 1000001, 1000001, NULL, NULL, NULL,
                                             &p, &err),
                     COONS_E_LIMIT);
    assert_int_equal(coons_patch_new_bspline(2, 2, &P[0][0][0], 2000, 501, NULL, NULL, NULL, &p, &err),
                     COONS_E_LIMIT);
    assert_int_equal(coons_patch_new_bspline(2, 2, &P[0][0][0], (size_t)-1 / 2, 4, NULL, NULL, NULL,
                                             &p, &err),
                     COONS_E_LIMIT);
    assert_int_equal(coons_patch_new_bspline(0, 2, &P[0][0][0], 4, 5, NULL, NULL, NULL, &p, &err),
                     COONS_E_INVALID);
    assert_int_equal(coons_patch_new_bspline(4, 2, &P[0][0][0], 4, 5, NULL, NULL, NULL, &p, &err),
                     COONS_E_INVALID);
    assert_int_equal(coons_patch_new_bspline(2, COONS_SPLINE_MAX_DEGREE + 1, &P[0][0][0], 4, 5, NULL, NULL,
                                             NULL, &p, &err),
                     COONS_E_INVALID);
    P[2][3][1] = NAN;
    assert_int_equal(coons_patch_new_bspline(2, 2, &P[0][0][0], 4, 5, NULL, NULL, NULL, &p, &err),
                     COONS_E_INVALID);
    assert_non_null(strstr(err.message, "[2][3]"));
    assert_int_equal(coons_patch_new_bezier(&P[0][0][0], 4, 5, &p, &err), COONS_E_INVALID);
    net(P);
    W[1][4] = 0.0;
    assert_int_equal(coons_patch_new_bspline(2, 2, &P[0][0][0], 4, 5, NULL, NULL, &W[0][0], &p, &err),
                     COONS_E_INVALID);
    assert_non_null(strstr(err.message, "[1][4]"));
    W[1][4] = -2.0;
    assert_int_equal(coons_patch_new_bspline(2, 2, &P[0][0][0], 4, 5, NULL, NULL, &W[0][0], &p, &err),
                     COONS_E_INVALID);
    W[1][4] = NAN;
    assert_int_equal(coons_patch_new_bspline(2, 2, &P[0][0][0], 4, 5, NULL, NULL, &W[0][0], &p, &err),
                     COONS_E_INVALID);
    W[1][4] = INFINITY;
    assert_int_equal(coons_patch_new_bspline(2, 2, &P[0][0][0], 4, 5, NULL, NULL, &W[0][0], &p, &err),
                     COONS_E_INVALID);
    const double dec[7] = {0, 0, 0, 2, 1, 3, 3};
    assert_int_equal(coons_patch_new_bspline(2, 2, &P[0][0][0], 4, 5, dec, NULL, NULL, &p, &err),
                     COONS_E_INVALID);
    const double empty[8] = {0, 0, 0, 0, 0, 1, 1, 1};
    assert_int_equal(coons_patch_new_bspline(2, 2, &P[0][0][0], 4, 5, NULL, empty, NULL, &p, &err),
                     COONS_E_INVALID);
    assert_null(p);
}

/* Given the sphere, then grid = pointwise, also with parameters outside
 * [0,1] (clamped). */
static void test_tensor_grid(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_patch *p = make_sphere();
    fx_check_grid(p);
    const double s[3] = {-1.0, 0.5, 7.0}, t[2] = {0.3, 1.5};
    double g[18];
    assert_coons_ok(coons_patch_eval_grid(p, s, 3, t, 2, g, &err), &err);
    double x[3];
    coons_patch_eval(p, 0.0, 0.3, x);
    assert_memory_equal(g, x, sizeof x);
    coons_patch_eval(p, 1.0, 1.0, x);
    assert_memory_equal(g + 15, x, sizeof x);
    coons_patch_free(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nurbs_sphere),
        cmocka_unit_test(test_nurbs_cylinder),
        cmocka_unit_test(test_nurbs_weight_scale),
        cmocka_unit_test(test_bezier_surface),
        cmocka_unit_test(test_bspline_surface),
        cmocka_unit_test(test_bspline_bilinear),
        cmocka_unit_test(test_tensor_invalid),
        cmocka_unit_test(test_tensor_grid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
