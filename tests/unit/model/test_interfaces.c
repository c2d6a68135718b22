/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Faces shared by two bodies, found by geometry, and the continuity across
 * them (coons_model_interfaces(); coons-model(5) "Bodies that share faces",
 * outputs.md --info "interfaces"), against closed forms: two unit boxes
 * join C1 and G1; a box twice as long has twice the cross derivative
 * (c1_defect 1/2, g1_angle 0); a sheared neighbour whose cross derivative
 * leans by 45 degrees (c1_defect 1/sqrt 2, g1_angle 45); all 8 orientations
 * of the second box's parameters are found, and the reported orientation
 * maps face points onto face points; a face 1e-6 away, and the same square
 * with another parametrisation, are not shared. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test_util.h"

static coons_model *load(const char *json)
{
    coons_model *m = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_model_load_memory(json, strlen(json), "t.json", NULL, &m, &e), &e);
    return m;
}

/* body0 corners P_ijk at 4i+2j+k of the map (u,v,w) -> x. */
static void corners(char *out, size_t cap, void (*map)(const double p[3], double x[3]))
{
    size_t n = (size_t)snprintf(out, cap, "[");
    for (int i = 0; i < 8; i++) {
        double p[3] = {i >> 2 & 1, i >> 1 & 1, i & 1}, x[3];
        map(p, x);
        n += (size_t)snprintf(out + n, cap - n, "%s[%.17g,%.17g,%.17g]", i ? "," : "", x[0], x[1],
                              x[2]);
    }
    snprintf(out + n, cap - n, "]");
}

static void unit(const double p[3], double x[3]) { memcpy(x, p, 3 * sizeof *x); }
static void right(const double p[3], double x[3]) { x[0] = 1 + p[0], x[1] = p[1], x[2] = p[2]; }
static void right2(const double p[3], double x[3]) { x[0] = 1 + 2 * p[0], x[1] = p[1], x[2] = p[2]; }
static void sheared(const double p[3], double x[3])
{
    x[0] = 1 + p[0], x[1] = p[1], x[2] = p[2] + p[0];
}

static coons_model *pair(void (*second)(const double p[3], double x[3]))
{
    char a[512], b[512], json[1200];
    corners(a, sizeof a, unit);
    corners(b, sizeof b, second);
    snprintf(json, sizeof json,
             "{\"coons\": 1, \"operation\": \"none\", \"bodies\": [{\"type\": \"body0\", \"name\": "
             "\"a\", \"corners\": %s}, {\"type\": \"body0\", \"name\": \"b\", \"corners\": %s}]}",
             a, b);
    return load(json);
}

static void one(coons_model *m, coons_interface *out)
{
    coons_interface *list = NULL;
    size_t n = 99;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_model_interfaces(m, &list, &n, &e), &e);
    assert_int_equal(n, 1);
    *out = list[0];
    coons_interfaces_free(list);
}

static void test_closed_forms(void **state)
{
    (void)state;
    coons_interface I;
    coons_model *m = pair(right);
    one(m, &I);
    assert_int_equal(I.body[0], 0);
    assert_int_equal(I.body[1], 1);
    assert_int_equal(I.face[0], 1); /* a.u1 */
    assert_int_equal(I.face[1], 0); /* b.u0 */
    assert_int_equal(I.orientation, 0);
    assert_true(I.c1_defect < 1e-14 && I.g1_angle < 1e-6);
    coons_model_free(m);

    m = pair(right2);
    one(m, &I);
    assert_near(I.c1_defect, 0.5, 1e-14);
    assert_true(I.g1_angle < 1e-6);
    coons_model_free(m);

    m = pair(sheared);
    one(m, &I);
    assert_near(I.c1_defect, 1 / sqrt(2.0), 1e-14);
    assert_near(I.g1_angle, 45.0, 1e-9);
    coons_model_free(m);
}

/* The second box's parameters in every orientation of its face u0 on a's
 * face u1: b(u, v, w) = (1 + u, V, W) with (V, W) one of the 8 symmetries
 * of (v, w). */
static int g_sym;
static void turned(const double p[3], double x[3])
{
    double a = p[1], b = p[2];
    double s = (g_sym & 1) ? b : a, t = (g_sym & 1) ? a : b;
    if (g_sym & 2) s = 1 - s;
    if (g_sym & 4) t = 1 - t;
    x[0] = 1 + p[0], x[1] = s, x[2] = t;
}

static void test_orientations(void **state)
{
    (void)state;
    int seen = 0;
    for (g_sym = 0; g_sym < 8; g_sym++) {
        coons_model *m = pair(turned);
        coons_interface I;
        one(m, &I);
        assert_int_equal(I.face[0], 1);
        assert_int_equal(I.face[1], 0);
        assert_true(I.c1_defect < 1e-14);
        seen |= 1 << I.orientation;
        /* The orientation maps a's face point (a, b) to b's. */
        const double a = 0.3, b = 0.8;
        double a2 = (I.orientation & 1) ? b : a, b2 = (I.orientation & 1) ? a : b;
        if (I.orientation & 2) a2 = 1 - a2;
        if (I.orientation & 4) b2 = 1 - b2;
        double pa[3], pb[3];
        coons_body_eval(coons_model_body(m, 0), 1, a, b, pa);
        coons_body_eval(coons_model_body(m, 1), 0, a2, b2, pb);
        assert_vec3_near(pa, pb, 1e-14);
        coons_model_free(m);
    }
    assert_int_equal(seen, 0xff);
}

static void test_not_shared(void **state)
{
    (void)state;
    /* 1e-6 apart: far beyond the consistency tolerance (1e-9 of ~3). */
    const char *gap = "{\"coons\": 1, \"bodies\": ["
                      "{\"type\": \"body0\", \"corners\": [[0,0,0],[0,0,1],[0,1,0],[0,1,1],"
                      "[1,0,0],[1,0,1],[1,1,0],[1,1,1]]},"
                      "{\"type\": \"body0\", \"corners\": [[1.000001,0,0],[1.000001,0,1],"
                      "[1.000001,1,0],[1.000001,1,1],[2,0,0],[2,0,1],[2,1,0],[2,1,1]]}]}";
    coons_model *m = load(gap);
    coons_interface *list = NULL;
    size_t n = 9;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_model_interfaces(m, &list, &n, &e), &e);
    assert_int_equal(n, 0);
    assert_null(list);
    coons_model_free(m);
    /* The same square x = 1, but the second body's v runs non-uniformly
     * (a quadratic Bezier in v whose middle control points sit at y =
     * 0.25): equal as point sets, not as maps. */
    const char *reparam =
        "{\"coons\": 1, \"bodies\": ["
        "{\"type\": \"body0\", \"corners\": [[0,0,0],[0,0,1],[0,1,0],[0,1,1],"
        "[1,0,0],[1,0,1],[1,1,0],[1,1,1]]},"
        "{\"type\": \"bezier-volume\", \"points\": ["
        "[[[1,0,0],[1,0,1]],[[1,0.25,0],[1,0.25,1]],[[1,1,0],[1,1,1]]],"
        "[[[2,0,0],[2,0,1]],[[2,0.25,0],[2,0.25,1]],[[2,1,0],[2,1,1]]]]}]}";
    m = load(reparam);
    assert_coons_ok(coons_model_interfaces(m, &list, &n, &e), &e);
    assert_int_equal(n, 0);
    coons_model_free(m);
    assert_int_equal(coons_model_interfaces(NULL, &list, &n, &e), COONS_E_INVALID);
    coons_interfaces_free(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_forms),
        cmocka_unit_test(test_orientations),
        cmocka_unit_test(test_not_shared),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
