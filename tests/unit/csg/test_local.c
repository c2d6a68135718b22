/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Unions by structure (issue 14), through coons_model_solidify():
 *  - the final check of a union is local (only triangles not taken
 *    unchanged from an input shell are tested); here the FULL exact check,
 *    coons_mesh_count_self_intersections(), runs on every result and must
 *    agree with the local one's verdict (clean, since the call succeeded);
 *  - the result is the same, byte for byte, on 1 and on 3 threads, and the
 *    report too;
 *  - bodies whose boxes overlap but whose shells are apart need no Boolean
 *    (two groups, both passed through); a body inside another is not
 *    passed through (one group, the inner shell is gone);
 *  - a version-2 options record (no `threads`) is still accepted. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "test_util.h"

/* A body0 box [lo, hi] as JSON, its top face moved by `shear` along x. */
static int box(char *out, size_t cap, const char *name, const double lo[3], const double hi[3],
               double shear)
{
    int n = snprintf(out, cap, "{\"type\": \"body0\", \"name\": \"%s\", \"corners\": [", name);
    for (int c = 0; c < 8; c++) {
        int i = c >> 2, j = (c >> 1) & 1, k = c & 1;
        n += snprintf(out + n, cap - (size_t)n, "%s[%.17g, %.17g, %.17g]", c ? ", " : "",
                      (i ? hi : lo)[0] + k * shear, (j ? hi : lo)[1], (k ? hi : lo)[2]);
    }
    n += snprintf(out + n, cap - (size_t)n, "]}");
    return n;
}

static coons_model *boxes(const double (*lo)[3], const double (*hi)[3], const double *shear,
                          size_t n)
{
    char json[8192];
    int len = snprintf(json, sizeof json, "{\"coons\": 1, \"operation\": \"union\", \"bodies\": [");
    for (size_t i = 0; i < n; i++) {
        char name[16];
        snprintf(name, sizeof name, "b%zu", i);
        if (i) len += snprintf(json + len, sizeof json - (size_t)len, ", ");
        len += box(json + len, sizeof json - (size_t)len, name, lo[i], hi[i],
                   shear ? shear[i] : 0.0);
    }
    len += snprintf(json + len, sizeof json - (size_t)len, "]}");
    coons_model *m = NULL;
    coons_error err;
    assert_coons_ok(coons_model_load_memory(json, (size_t)len, "boxes", NULL, &m, &err), &err);
    return m;
}

static coons_mesh *solid(const coons_model *m, unsigned threads, unsigned res,
                         coons_csg_report *rep)
{
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.resolution = res;
    coons_csg_options co = COONS_CSG_OPTIONS_INIT;
    co.threads = threads;
    coons_csg_report_init(rep);
    coons_mesh *out = NULL;
    coons_error err;
    assert_coons_ok(coons_model_solidify(m, &so, &co, &out, rep, &err), &err);
    return out;
}

/* The full exact check on the result of the local one, and the same bytes
 * on 1 and 3 threads. */
static void check_model(const coons_model *m, unsigned res, coons_csg_report *rep)
{
    coons_csg_report r3;
    coons_mesh *a = solid(m, 1, res, rep), *b = solid(m, 3, res, &r3);
    coons_error err;
    size_t pairs = 99;
    assert_coons_ok(coons_mesh_count_self_intersections(a, &pairs, &err), &err);
    assert_int_equal(pairs, 0);
    coons_mesh_report mr = COONS_MESH_REPORT_INIT;
    assert_coons_ok(coons_mesh_check(a, &mr, &err), &err);
    assert_true(mr.closed && mr.manifold && mr.oriented);
    assert_int_equal(coons_mesh_vertex_count(a), coons_mesh_vertex_count(b));
    assert_int_equal(coons_mesh_triangle_count(a), coons_mesh_triangle_count(b));
    assert_int_equal(coons_mesh_part_count(a), coons_mesh_part_count(b));
    assert_memory_equal(coons_mesh_vertices(a), coons_mesh_vertices(b),
                        3 * sizeof(double) * coons_mesh_vertex_count(a));
    assert_memory_equal(coons_mesh_triangles(a), coons_mesh_triangles(b),
                        3 * sizeof(uint32_t) * coons_mesh_triangle_count(a));
    assert_int_equal(rep->groups, r3.groups);
    assert_int_equal(rep->passed_through, r3.passed_through);
    assert_int_equal(rep->fast_unions, r3.fast_unions);
    assert_int_equal(rep->triangles_out, r3.triangles_out);
    coons_mesh_free(a);
    coons_mesh_free(b);
}

static void test_three_examples(void **state)
{
    (void)state;
    coons_model *m = test_source_model("tests/data/ok/three-examples-union.json");
    coons_csg_report rep;
    check_model(m, 12, &rep);
    assert_int_equal(rep.groups, 1);
    coons_model_free(m);
}

/* Overlapping boxes (a real union) next to boxes apart and a box whose
 * box overlaps another's without the shells meeting (an L around it). */
static void test_groups(void **state)
{
    (void)state;
    const double lo[5][3] = {{0, 0, 0}, {0.5, 0.5, 0.5}, {5, 0, 0}, {5, 2, 0}, {10, 0, 0}};
    const double hi[5][3] = {{1, 1, 1}, {1.5, 1.5, 1.5}, {9, 1, 1}, {6, 3, 1}, {11, 1, 1}};
    coons_model *m = boxes(lo, hi, NULL, 5);
    coons_csg_report rep;
    check_model(m, 4, &rep);
    /* {b0, b1} meet; b2, b3 and b4 are apart from everything */
    assert_int_equal(rep.groups, 4);
    assert_int_equal(rep.passed_through, 3);
    assert_int_equal(rep.fast_unions, 1);
    coons_model_free(m);

    /* b0 leans (its top moved by 3 along x): b1 lies in b0's box, in the
     * empty corner under its overhang, apart from its shell (triangle boxes
     * apart, winding number 0): two groups, no Boolean. */
    const double lo2[2][3] = {{0, 0, 0}, {3, 0, 0}};
    const double hi2[2][3] = {{1, 1, 1}, {3.5, 1, 0.2}};
    const double shear[2] = {3, 0};
    m = boxes(lo2, hi2, shear, 2);
    check_model(m, 4, &rep);
    assert_int_equal(rep.groups, 2);
    assert_int_equal(rep.passed_through, 2);
    coons_model_free(m);
}

/* A box strictly inside another: not apart (winding number 1), one group;
 * the union is the outer box alone. */
static void test_nested(void **state)
{
    (void)state;
    const double lo[2][3] = {{0, 0, 0}, {0.25, 0.25, 0.25}};
    const double hi[2][3] = {{1, 1, 1}, {0.75, 0.75, 0.75}};
    coons_model *m = boxes(lo, hi, NULL, 2);
    coons_csg_report rep;
    coons_mesh *u = solid(m, 2, 3, &rep);
    assert_int_equal(rep.groups, 1);
    assert_int_equal(rep.passed_through, 0);
    assert_near(coons_mesh_volume(u), 1.0, 1e-12);
    coons_mesh_report mr = COONS_MESH_REPORT_INIT;
    coons_error err;
    assert_coons_ok(coons_mesh_check(u, &mr, &err), &err);
    assert_int_equal(mr.shells, 1);
    coons_mesh_free(u);
    coons_model_free(m);
}

/* A caller built against version 2 of the options (no `threads`). */
typedef struct {
    unsigned version;
    int unite, repair;
    const char *name;
    coons_progress_fn progress;
    void *userdata;
} options_v2;

static void test_options_v2(void **state)
{
    (void)state;
    const double lo[2][3] = {{0, 0, 0}, {0.5, 0.5, 0.5}};
    const double hi[2][3] = {{1, 1, 1}, {1.5, 1.5, 1.5}};
    coons_model *m = boxes(lo, hi, NULL, 2);
    options_v2 o2 = {2, 1, 1, NULL, NULL, NULL};
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    coons_mesh *out = NULL;
    coons_error err;
    assert_coons_ok(coons_model_solidify(m, NULL, (const coons_csg_options *)(const void *)&o2,
                                         &out, &rep, &err),
                    &err);
    assert_near(coons_mesh_volume(out), 2.0 - 0.125, 1e-12);
    coons_mesh_free(out);
    coons_model_free(m);
}

/* A caller built against version 1 of the report (no pinch fields),
 * followed by memory the library must not touch. */
typedef struct {
    unsigned version;
    size_t triangles_in, degenerate_dropped, intersecting_pairs, parts_in, groups,
        passed_through, patches, patches_kept, fast_unions, fallbacks, triangles_out,
        rounding_merged, close_merged, slivers_fixed;
    int closed;
    size_t nonmanifold_edges;
} report_v1;

static void test_report_v1(void **state)
{
    (void)state;
    assert_int_equal(sizeof(report_v1), offsetof(coons_csg_report, pinch_edges_split));
    const double lo[2][3] = {{0, 0, 0}, {0.5, 0.5, 0.5}};
    const double hi[2][3] = {{1, 1, 1}, {1.5, 1.5, 1.5}};
    coons_model *m = boxes(lo, hi, NULL, 2);
    for (int entry = 0; entry < 3; entry++) {
        struct {
            report_v1 r;
            unsigned char canary[64];
        } buf;
        memset(&buf, 0xA5, sizeof buf);
        buf.r.version = 1;
        coons_mesh *out = NULL, *in = NULL;
        coons_error err;
        coons_csg_report *r = (coons_csg_report *)(void *)&buf.r;
        if (entry == 0) {
            assert_coons_ok(coons_model_solidify(m, NULL, NULL, &out, r, &err), &err);
        } else if (entry == 1) {
            assert_coons_ok(coons_model_solidify_body(m, 1, NULL, NULL, &out, r, &err), &err);
        } else {
            assert_coons_ok(coons_body_sample(coons_model_body(m, 0), NULL, "b0", &in, &err),
                            &err);
            assert_coons_ok(coons_mesh_solidify(in, NULL, &out, r, &err), &err);
        }
        assert_int_equal(buf.r.version, 1);
        assert_int_equal(buf.r.triangles_out, coons_mesh_triangle_count(out));
        assert_int_equal(buf.r.parts_in, entry == 0 ? 2 : 1);
        assert_int_equal(buf.r.closed, 1);
        assert_int_equal(buf.r.nonmanifold_edges, 0);
        for (size_t i = 0; i < sizeof buf.canary; i++) assert_int_equal(buf.canary[i], 0xA5);
        coons_mesh_free(in);
        coons_mesh_free(out);
    }
    coons_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_three_examples),
        cmocka_unit_test(test_groups),
        cmocka_unit_test(test_nested),
        cmocka_unit_test(test_options_v2),
        cmocka_unit_test(test_report_v1),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
