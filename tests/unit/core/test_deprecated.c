/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The 0.1 names (include/coons/deprecated.h), kept for the 0.2 release: each
 * takes its 0.1 parameters (so the 0.1 casts are what a 0.1 caller wrote) and
 * builds the same object as its 0.2 replacement, compared point by point;
 * the 0.1 macro names equal the 0.2 ones.
 */
#include <string.h>

#include "test_util.h"

#if defined(__GNUC__) || defined(__clang__)
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
#endif

static const double pts[5][3] = {{0, 0, 0}, {1, 1, 0}, {2, 0, 1}, {3, 1, 0}, {4, 0, 0}};

static void same_curve(const coons_curve *a, const coons_curve *b)
{
    assert_int_equal(coons_curve_get_type(a), coons_curve_get_type(b));
    for (int i = 0; i <= 16; i++) {
        double x[3], y[3];
        coons_curve_eval(a, i / 16.0, x);
        coons_curve_eval(b, i / 16.0, y);
        assert_vec3_near(x, y, 0.0);
    }
}

static void same_patch(const coons_patch *a, const coons_patch *b)
{
    assert_int_equal(coons_patch_get_type(a), coons_patch_get_type(b));
    for (int i = 0; i <= 8; i++)
        for (int j = 0; j <= 8; j++) {
            double x[3], y[3];
            coons_patch_eval(a, i / 8.0, j / 8.0, x);
            coons_patch_eval(b, i / 8.0, j / 8.0, y);
            assert_vec3_near(x, y, 0.0);
        }
}

static void same_body(const coons_body *a, const coons_body *b)
{
    assert_int_equal(coons_body_get_type(a), coons_body_get_type(b));
    for (int n = 0; n < 125; n++) {
        double x[3], y[3];
        coons_body_eval(a, (n % 5) / 4.0, (n / 5 % 5) / 4.0, (n / 25) / 4.0, x);
        coons_body_eval(b, (n % 5) / 4.0, (n / 5 % 5) / 4.0, (n / 25) / 4.0, y);
        assert_vec3_near(x, y, 0.0);
    }
}

static void test_curves(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    coons_curve *a = NULL, *b = NULL;
    const double kn[9] = {0, 0, 0, 0, 0.5, 1, 1, 1, 1}, w[5] = {1, 2, 1, 2, 1};
    for (int k = 0; k < 7; k++) {
        switch (k) {
        case 0:
            assert_coons_ok(coons_curve_line(pts[0], pts[2], &a, &e), &e);
            assert_coons_ok(coons_curve_new_line(pts[0], pts[2], &b, &e), &e);
            break;
        case 1:
            assert_coons_ok(coons_curve_polyline(pts[0], 5, &a, &e), &e);
            assert_coons_ok(coons_curve_new_polyline(pts[0], 5, &b, &e), &e);
            break;
        case 2:
            assert_coons_ok(coons_curve_bezier(pts[0], 4, &a, &e), &e);
            assert_coons_ok(coons_curve_new_bezier(pts[0], 4, &b, &e), &e);
            break;
        case 3:
            assert_coons_ok(coons_curve_hermite(pts[0], pts[1], pts[2], pts[3], &a, &e), &e);
            assert_coons_ok(coons_curve_new_hermite(pts[0], pts[1], pts[2], pts[3], &b, &e), &e);
            break;
        case 4:
            assert_coons_ok(coons_curve_coons_cubic(pts[0], 5, 1, &a, &e), &e);
            assert_coons_ok(coons_curve_new_coons_cubic(pts[0], 5, 1, &b, &e), &e);
            break;
        case 5:
            assert_coons_ok(coons_curve_clamped_cubic(pts[0], 5, &a, &e), &e);
            assert_coons_ok(coons_curve_new_clamped_cubic(pts[0], 5, &b, &e), &e);
            break;
        default:
            assert_coons_ok(coons_curve_bspline(3, pts[0], 5, kn, w, &a, &e), &e);
            assert_coons_ok(coons_curve_new_bspline(3, pts[0], 5, kn, w, &b, &e), &e);
        }
        same_curve(a, b);
        coons_curve_free(a);
        coons_curve_free(b);
    }
    double c1[15], c2[15];
    assert_coons_ok(coons_cubic_open_to_clamped(pts[0], 5, c1, &e), &e);
    assert_coons_ok(coons_curve_convert_open_to_clamped(pts[0], 5, c2, &e), &e);
    assert_memory_equal(c1, c2, sizeof c1);
}

static void test_patches_and_bodies(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    double c[8][3];
    for (int n = 0; n < 8; n++) {
        c[n][0] = (n >> 2) + 0.1 * n;
        c[n][1] = ((n >> 1) & 1) - 0.05 * n;
        c[n][2] = (n & 1) + 0.02 * n * n;
    }
    /* Face u0 of the corners (X00, X10, X01, X11) and its four sides. */
    double q[4][3];
    for (int k = 0; k < 4; k++) memcpy(q[k], c[2 * (k & 1) + (k >> 1)], sizeof q[k]);
    coons_curve *side[4];
    assert_coons_ok(coons_curve_new_line(q[0], q[1], &side[COONS_T0], &e), &e);
    assert_coons_ok(coons_curve_new_line(q[2], q[3], &side[COONS_T1], &e), &e);
    assert_coons_ok(coons_curve_new_line(q[0], q[2], &side[COONS_S0], &e), &e);
    assert_coons_ok(coons_curve_new_line(q[1], q[3], &side[COONS_S1], &e), &e);
    assert_int_equal(COONS_T0, COONS_SIDE_T0);
    assert_int_equal(COONS_S1, COONS_SIDE_S1);
    coons_patch *a = NULL, *b = NULL;
    assert_coons_ok(coons_patch_bilinear((const double(*)[3])q, &a, &e), &e);
    assert_coons_ok(coons_patch_new_bilinear(q[0], &b, &e), &e);
    same_patch(a, b);
    coons_patch_free(a);
    coons_patch_free(b);
    assert_coons_ok(coons_patch_coons((const coons_curve *const *)side, COONS_BLEND_CUBIC, 0, &a,
                                      &e), &e);
    assert_coons_ok(coons_patch_new_coons(side, COONS_BLEND_CUBIC, 0, &b, &e), &e);
    same_patch(a, b);
    coons_patch_free(a);
    coons_patch_free(b);
    assert_coons_ok(coons_patch_hermite_coons((const coons_curve *const *)side, NULL, &a, &e), &e);
    assert_coons_ok(coons_patch_new_hermite_coons(side, NULL, &b, &e), &e);
    same_patch(a, b);
    coons_patch_free(a);
    coons_patch_free(b);
    assert_coons_ok(coons_patch_ruled(side[0], side[1], &a, &e), &e);
    assert_coons_ok(coons_patch_new_ruled(side[0], side[1], &b, &e), &e);
    same_patch(a, b);
    coons_patch_free(a);
    coons_patch_free(b);
    assert_coons_ok(coons_patch_bezier(q[0], 2, 2, &a, &e), &e);
    assert_coons_ok(coons_patch_new_bezier(q[0], 2, 2, &b, &e), &e);
    same_patch(a, b);
    coons_patch_free(a);
    coons_patch_free(b);
    assert_coons_ok(coons_patch_bspline(1, 1, q[0], 2, 2, NULL, NULL, NULL, &a, &e), &e);
    assert_coons_ok(coons_patch_new_bspline(1, 1, q[0], 2, 2, NULL, NULL, NULL, &b, &e), &e);
    same_patch(a, b);
    coons_patch_free(a);
    coons_patch_free(b);
    for (int k = 0; k < 4; k++) coons_curve_free(side[k]);

    coons_body *x = NULL, *y = NULL;
    assert_coons_ok(coons_body_body0((const double(*)[3])c, COONS_BLEND_CUBIC, &x, &e), &e);
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_CUBIC, &y, &e), &e);
    same_body(x, y);
    coons_body_free(x);
    coons_body_free(y);
    const size_t n[3] = {2, 2, 2};
    const int deg[3] = {1, 1, 1};
    const double k01[4] = {0, 0, 1, 1};
    const double *const kk[3] = {k01, NULL, k01};
    assert_coons_ok(coons_body_bezier(c[0], n, &x, &e), &e);
    assert_coons_ok(coons_body_new_bezier(c[0], n, &y, &e), &e);
    same_body(x, y);
    coons_body_free(x);
    coons_body_free(y);
    assert_coons_ok(coons_body_bspline(deg, c[0], n, kk, NULL, &x, &e), &e);
    assert_coons_ok(coons_body_new_bspline(deg, c[0], n, k01, NULL, k01, NULL, &y, &e), &e);
    same_body(x, y);
    coons_body_free(x);
    coons_body_free(y);
    assert_int_equal(COONS_MAX_CURVE_POINTS, COONS_CURVE_MAX_POINTS);
    assert_int_equal(COONS_MAX_DEGREE, COONS_SPLINE_MAX_DEGREE);
    assert_true(COONS_DEFAULT_MAX_TRIANGLES == COONS_MESH_MAX_TRIANGLES);
}

static const char MODEL[] =
    "{\"coons\": 1, \"operation\": \"none\", \"bodies\": [{\"type\": \"body0\", \"corners\": "
    "[[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]}";

static void test_models_and_meshes(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    coons_model *a = NULL, *b = NULL;
    coons_model_load_options o = COONS_MODEL_LOAD_OPTIONS_INIT;
    assert_coons_ok(coons_model_load_buffer(MODEL, sizeof MODEL - 1, "m", &a, &e), &e);
    coons_model_free(a);
    assert_coons_ok(coons_model_load_buffer_opts(MODEL, sizeof MODEL - 1, "m", &o, &a, &e), &e);
    assert_int_equal(coons_model_load("/nonexistent/m.json", &b, &e), COONS_E_IO);
    assert_int_equal(coons_model_load_opts("/nonexistent/m.json", &o, &b, &e), COONS_E_IO);
    assert_non_null(strstr(e.message, "/nonexistent/m.json: cannot open"));
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.resolution = 2;
    coons_mesh *m1 = NULL, *m2 = NULL;
    assert_coons_ok(coons_model_mesh(a, &so, &m1, &e), &e);
    assert_coons_ok(coons_model_sample(a, &so, &m2, &e), &e);
    assert_int_equal(coons_mesh_triangle_count(m1), coons_mesh_triangle_count(m2));
    assert_memory_equal(coons_mesh_vertices(m1), coons_mesh_vertices(m2),
                        3 * sizeof(double) * coons_mesh_vertex_count(m1));
    coons_mesh_free(m1);
    m1 = NULL;
    coons_csg_report rep; /* 0.1 code: no version to set */
    memset(&rep, 0xa5, sizeof rep);
    coons_status s1 = coons_model_solid(a, &so, NULL, &m1, &rep, &e);
    assert_int_equal(s1, COONS_OK);
    assert_int_equal(rep.version, COONS_CSG_REPORT_VERSION);
    assert_int_equal(coons_mesh_triangle_count(m1), coons_mesh_triangle_count(m2));
    assert_int_equal(coons_csg_available(), coons_csg_is_available());
    size_t p1 = 7, p2 = 9;
    coons_status r1 = coons_mesh_self_intersections(m1, &p1, &e);
    coons_status r2 = coons_mesh_count_self_intersections(m1, &p2, &e);
    assert_int_equal(r1, r2);
    if (r1 == COONS_OK) assert_int_equal(p1, p2);
    r1 = coons_mesh_self_intersections_float(m1, &p1, &e);
    r2 = coons_mesh_count_self_intersections_float(m1, &p2, &e);
    assert_int_equal(r1, r2);
    coons_mesh_free(m1);
    coons_mesh_free(m2);
    coons_model_free(a);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_curves),
        cmocka_unit_test(test_patches_and_bodies),
        cmocka_unit_test(test_models_and_meshes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
