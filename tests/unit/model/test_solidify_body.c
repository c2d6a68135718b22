/* SPDX-License-Identifier: GPL-3.0-or-later */
/* coons_model_solidify_body(): one body of a model alone (coons2stl --body),
 * in the C-only build and with CGAL. The body of a "union" model comes out
 * as its own part, named after it, not united with the others; sampled as
 * coons_body_sample() samples it at the model's tolerance (bit for bit
 * without CGAL; with CGAL a closed 2-manifold whose volume is the body's
 * det J integral within the tolerance); progress hears "sample" i / n,
 * then 1. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test_util.h"

#define UNION_MODEL "tests/data/ok/three-examples-union.json"

static coons_model *load(const char *rel)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", COONS_SOURCE_DIR, rel);
    coons_model *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_model_load_file(path, NULL, &m, &err), &err);
    return m;
}

typedef struct calls {
    int sample, other;
    double fractions[4];
    int after_solidify_sample; /* a "sample" after another stage */
} calls;

static void record(void *ud, const char *stage, double f)
{
    calls *c = ud;
    assert_true(f >= 0.0 && f <= 1.0);
    if (strcmp(stage, "sample") == 0) {
        if (c->other) c->after_solidify_sample = 1;
        if (c->sample < 4) c->fractions[c->sample] = f;
        c->sample++;
    } else {
        c->other++;
    }
}

static int same_mesh(const coons_mesh *a, const coons_mesh *b)
{
    size_t nv = coons_mesh_vertex_count(a), nt = coons_mesh_triangle_count(a);
    return nv == coons_mesh_vertex_count(b) && nt == coons_mesh_triangle_count(b) &&
           memcmp(coons_mesh_vertices(a), coons_mesh_vertices(b), 3 * nv * sizeof(double)) == 0 &&
           memcmp(coons_mesh_triangles(a), coons_mesh_triangles(b), 3 * nt * sizeof(uint32_t)) ==
               0;
}

static void check_body(const coons_model *m, size_t i, double tol)
{
    coons_error err = COONS_ERROR_INIT;
    size_t n = coons_model_body_count(m);
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.tolerance = tol;
    coons_csg_options co = COONS_CSG_OPTIONS_INIT;
    calls c;
    memset(&c, 0, sizeof c);
    co.progress = record;
    co.userdata = &c;
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    coons_mesh *solid = NULL;
    assert_coons_ok(coons_model_solidify_body(m, i, &so, &co, &solid, &rep, &err), &err);

    /* One part, the body's, whatever the model's operation. */
    assert_int_equal(coons_model_operation(m), COONS_OP_UNION);
    assert_int_equal(coons_mesh_part_count(solid), 1);
    assert_string_equal(coons_mesh_part_name(solid, 0), coons_model_body_name(m, i));
    /* "sample" once with the body's share, then 1, before the CGAL stages. */
    assert_int_equal(c.sample, 2);
    assert_true(c.fractions[0] == (double)i / (double)n);
    assert_true(c.fractions[1] == 1.0);
    assert_false(c.after_solidify_sample);

    coons_mesh *shell = NULL;
    assert_coons_ok(coons_body_sample(coons_model_body(m, i), &so, coons_model_body_name(m, i),
                                      &shell, &err),
                    &err);
    if (!coons_csg_is_available()) {
        assert_true(same_mesh(solid, shell));
        assert_int_equal(rep.triangles_in, 0);
        assert_int_equal(c.other, 0);
    } else {
        coons_mesh_report r = COONS_MESH_REPORT_INIT;
        assert_coons_ok(coons_mesh_check(solid, &r, &err), &err);
        assert_true(r.closed && r.manifold && r.oriented);
        assert_int_equal(rep.parts_in, 1);
        assert_int_equal(rep.triangles_in, coons_mesh_triangle_count(shell));
        assert_int_equal(rep.triangles_out, coons_mesh_triangle_count(solid));
        double v = 0.0;
        assert_coons_ok(coons_body_volume(coons_model_body(m, i), 1e-9, &v, &err), &err);
        assert_near(coons_mesh_volume(solid), fabs(v), coons_mesh_area(solid) * tol);
    }
    coons_mesh_free(shell);
    coons_mesh_free(solid);
}

static void test_each_body_alone(void **state)
{
    (void)state;
    coons_model *m = load(UNION_MODEL);
    assert_true(coons_model_body_count(m) >= 3);
    for (size_t i = 0; i < coons_model_body_count(m); i++) check_body(m, i, 0.05);
    coons_model_free(m);
}

/* NULL options: defaults, at the model's tolerance (not the body's own
 * default, 1/1000 of its control box). */
static void test_defaults_use_model_tolerance(void **state)
{
    (void)state;
    coons_model *m = load(UNION_MODEL);
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *a = NULL, *b = NULL;
    assert_coons_ok(coons_model_solidify_body(m, 1, NULL, NULL, &a, NULL, &err), &err);
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.tolerance = coons_model_tolerance(m);
    assert_coons_ok(coons_model_solidify_body(m, 1, &so, NULL, &b, NULL, &err), &err);
    assert_true(same_mesh(a, b));
    coons_mesh_free(b);
    so.tolerance = coons_model_tolerance(m) * 8;
    assert_coons_ok(coons_model_solidify_body(m, 1, &so, NULL, &b, NULL, &err), &err);
    assert_true(coons_mesh_triangle_count(b) < coons_mesh_triangle_count(a));
    coons_mesh_free(a);
    coons_mesh_free(b);
    coons_model_free(m);
}

static void test_index_out_of_range(void **state)
{
    (void)state;
    coons_model *m = load(UNION_MODEL);
    size_t n = coons_model_body_count(m);
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *dummy = NULL, *out;
    assert_coons_ok(coons_mesh_new(&dummy, &err), &err);
    out = dummy; /* must be reset */
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    memset(&rep, 0xff, sizeof rep);
    rep.version = COONS_CSG_REPORT_VERSION; /* a valid record with garbage outputs */
    assert_int_equal(coons_model_solidify_body(m, n, NULL, NULL, &out, &rep, &err), COONS_E_INVALID);
    assert_null(out);
    coons_mesh_free(dummy);
    assert_int_equal(rep.triangles_in, 0);
    assert_int_equal(rep.parts_in, 0);
    assert_non_null(strstr(err.message, "out of range"));
    assert_int_equal(coons_model_solidify_body(m, (size_t)-1, NULL, NULL, &out, NULL, NULL),
                     COONS_E_INVALID);
    coons_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_each_body_alone),
        cmocka_unit_test(test_defaults_use_model_tolerance),
        cmocka_unit_test(test_index_out_of_range),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
