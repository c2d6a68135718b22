/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A model's solid through sampling + the CGAL layer: overlapping examples
 * united into one closed, 2-manifold solid without self-intersection, whose
 * volume lies between the largest body's and the sum (body volumes from
 * the det J integral, independent of the meshes). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test_util.h"

/* Every report is in [0, 1]; the input checks ("check") report one figure
 * per body checked, never going back, so the stage moves. */
typedef struct heard {
    int calls, checks;
    double check_lo, check_hi;
} heard;

static void progress(void *ud, const char *stage, double f)
{
    heard *h = ud;
    assert_true(f >= 0.0 && f <= 1.0);
    if (strcmp(stage, "check") == 0) {
        if (!h->checks++) h->check_lo = f;
        assert_true(f >= h->check_hi);
        h->check_hi = f;
    }
    h->calls++;
}

static void check_union(const char *rel, double tol)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", COONS_SOURCE_DIR, rel);
    coons_model *m = NULL;
    coons_error err;
    assert_coons_ok(coons_model_load_file(path, NULL, &m, &err), &err);
    assert_int_equal(coons_model_operation(m), COONS_OP_UNION);
    double vmax = 0.0, vsum = 0.0;
    for (size_t i = 0; i < coons_model_body_count(m); i++) {
        double v = 0.0;
        assert_coons_ok(coons_body_volume(coons_model_body(m, i), 1e-9, &v, &err), &err);
        v = fabs(v);
        vsum += v;
        if (v > vmax) vmax = v;
    }
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.tolerance = tol;
    coons_csg_options co = COONS_CSG_OPTIONS_INIT;
    heard h = {0, 0, 0.0, 0.0};
    co.progress = progress;
    co.userdata = &h;
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    coons_mesh *solid = NULL;
    assert_coons_ok(coons_model_solidify(m, &so, &co, &solid, &rep, &err), &err);
    assert_true(h.calls > 0);
    /* one body after another (co.threads is 1): the check stage moves */
    assert_true(h.checks >= (int)coons_model_body_count(m));
    assert_true(h.check_hi > h.check_lo);
    assert_int_equal(coons_mesh_part_count(solid), 1);
    coons_mesh_report mr = COONS_MESH_REPORT_INIT;
    assert_coons_ok(coons_mesh_check(solid, &mr, &err), &err);
    size_t pairs = 99;
    assert_coons_ok(coons_mesh_count_self_intersections(solid, &pairs, &err), &err);
    double vol = coons_mesh_volume(solid);
    printf("%s: %zu bodies, %zu -> %zu triangles, %zu patches (%zu kept), volume %.6f in "
           "[%.6f, %.6f], closed %d manifold %d oriented %d shells %zu euler %ld, pairs %zu\n",
           rel, coons_model_body_count(m), rep.triangles_in, rep.triangles_out, rep.patches,
           rep.patches_kept, vol, vmax, vsum, mr.closed, mr.manifold, mr.oriented, mr.shells,
           mr.euler, pairs);
    assert_int_equal(pairs, 0);
    assert_true(mr.closed);
    assert_true(mr.manifold);
    assert_true(mr.oriented);
    /* The sampled surfaces lie within tol of the exact ones: allow the
     * volume that a tol-thick skin can hold. */
    double slack = mr.area * tol;
    assert_true(vol > vmax - slack);
    assert_true(vol < vsum + slack);
    assert_true(vol < vsum - 1e-3 * vsum); /* they do overlap */
    coons_mesh_free(solid);
    coons_model_free(m);
}

static void test_three_examples(void **state)
{
    (void)state;
    check_union("tests/data/ok/three-examples-union.json", 0.05);
}

/* Finer: the chained in-place corefinement leaves removed vertices behind,
 * whose indices once overflowed the output's vertex map (heap overflow,
 * "double free or corruption" at tolerances <= 0.015). */
static void test_three_examples_fine(void **state)
{
    (void)state;
    check_union("tests/data/ok/three-examples-union.json", 0.01);
}

static void test_union_example(void **state)
{
    (void)state;
    check_union("examples/union-three-bodies.json", 0.05);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_three_examples),
        cmocka_unit_test(test_three_examples_fine),
        cmocka_unit_test(test_union_example),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
