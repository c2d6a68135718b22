/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The near chain of the fast union (issue 14): only the triangles near the
 * other shell are corefined, and the library classifies the patches itself
 * (rays with exact predicates, coplanar patches by their cover). Checked
 * against independent answers:
 *  - unions of axis-aligned boxes (body0) whose exact volume comes from
 *    inclusion-exclusion (the intersection of boxes is a box): crossing
 *    transversally, standing on one plane (coplanar faces facing the same
 *    way), stacked with partly overlapping contact faces (facing opposite
 *    ways), pierced, sharing three side planes, and chains of three;
 *  - the union of the three example bodies (curved shells) against the
 *    same union by CGAL's Boolean of the whole shells (the test hook
 *    coons__csg_whole_corefinement), which does not use this code;
 *  - every result is closed, 2-manifold, oriented, one shell, and clean
 *    under the FULL exact self-intersection check;
 *  - rep.patches > 0 shows that the near chain made the result (the whole
 *    corefinement reports no patches), so a near chain that failed its own
 *    checks and fell back could not pass here. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "coons_test_hooks.h"
#include "test_util.h"

/* The volume of the union of n boxes by inclusion-exclusion. */
static double union_volume(const double (*lo)[3], const double (*hi)[3], size_t n)
{
    double v = 0;
    for (unsigned s = 1; s < (1u << n); s++) {
        double a[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, b[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
        int bits = 0;
        for (size_t i = 0; i < n; i++)
            if (s >> i & 1) {
                bits++;
                for (int c = 0; c < 3; c++) {
                    a[c] = fmax(a[c], lo[i][c]);
                    b[c] = fmin(b[c], hi[i][c]);
                }
            }
        double w = 1;
        for (int c = 0; c < 3; c++) w *= b[c] > a[c] ? b[c] - a[c] : 0;
        v += (bits & 1) ? w : -w;
    }
    return v;
}

/* A union model of n body0 bodies, body i with the corners corners[i]
 * (in body0's order: corner c at (c >> 2, (c >> 1) & 1, c & 1)). */
static coons_model *body0_union(double (*corners)[8][3], size_t n)
{
    char json[8192];
    int len = snprintf(json, sizeof json, "{\"coons\": 1, \"operation\": \"union\", \"bodies\": [");
    for (size_t i = 0; i < n; i++) {
        len += snprintf(json + len, sizeof json - (size_t)len,
                        "%s{\"type\": \"body0\", \"name\": \"b%zu\", \"corners\": [", i ? ", " : "",
                        i);
        for (int c = 0; c < 8; c++)
            len += snprintf(json + len, sizeof json - (size_t)len, "%s[%.17g, %.17g, %.17g]",
                            c ? ", " : "", corners[i][c][0], corners[i][c][1], corners[i][c][2]);
        len += snprintf(json + len, sizeof json - (size_t)len, "]}");
    }
    len += snprintf(json + len, sizeof json - (size_t)len, "]}");
    coons_model *m = NULL;
    coons_error err;
    assert_coons_ok(coons_model_load_memory(json, (size_t)len, "bodies", NULL, &m, &err), &err);
    return m;
}

/* Axis-aligned boxes [lo[i], hi[i]]. */
static coons_model *boxes(const double (*lo)[3], const double (*hi)[3], size_t n)
{
    double corners[3][8][3];
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 8; c++) {
            int x = c >> 2, y = (c >> 1) & 1, z = c & 1;
            corners[i][c][0] = (x ? hi : lo)[i][0];
            corners[i][c][1] = (y ? hi : lo)[i][1];
            corners[i][c][2] = (z ? hi : lo)[i][2];
        }
    return body0_union(corners, n);
}

/* The union of m at resolution res by the near chain (whole = 0) or by
 * CGAL's Boolean of whole shells (whole = 1); the result checked fully. */
static coons_mesh *unite(const coons_model *m, unsigned res, int whole, coons_csg_report *rep)
{
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.resolution = res;
    coons_csg_options co = COONS_CSG_OPTIONS_INIT;
    co.threads = 2;
    coons_csg_report_init(rep);
    coons_mesh *out = NULL;
    coons_error err;
    coons__csg_whole_corefinement(whole);
    coons_status rc = coons_model_solidify(m, &so, &co, &out, rep, &err);
    coons__csg_whole_corefinement(0);
    assert_coons_ok(rc, &err);
    size_t pairs = 99;
    assert_coons_ok(coons_mesh_count_self_intersections(out, &pairs, &err), &err);
    assert_int_equal(pairs, 0);
    coons_mesh_report mr = COONS_MESH_REPORT_INIT;
    assert_coons_ok(coons_mesh_check(out, &mr, &err), &err);
    assert_true(mr.closed && mr.manifold && mr.oriented);
    assert_int_equal(mr.shells, 1);
    assert_int_equal(rep->groups, 1);
    assert_int_equal(rep->fast_unions, 1);
    assert_int_equal(rep->fallbacks, 0);
    return out;
}

static void check_boxes(const double (*lo)[3], const double (*hi)[3], size_t n, unsigned res)
{
    coons_model *m = boxes(lo, hi, n);
    double exact = union_volume(lo, hi, n);
    coons_csg_report rn, rw;
    coons_mesh *near = unite(m, res, 0, &rn), *whole = unite(m, res, 1, &rw);
    printf("  %zu boxes, res %u: volume %.15g (exact %.15g), %zu triangles (whole shells: "
           "%zu), %zu patches, %zu kept\n",
           n, res, coons_mesh_volume(near), exact, coons_mesh_triangle_count(near),
           coons_mesh_triangle_count(whole), rn.patches, rn.patches_kept);
    assert_true(rn.patches > 0);
    assert_true(rn.patches_kept > 0 && rn.patches_kept < rn.patches);
    assert_int_equal(rw.patches, 0);
    /* the sampled lattice points carry the rounding of the corners (0.3,
     * 1.4, ...): volumes to 1e-11 */
    assert_near(coons_mesh_volume(near), exact, 1e-11 * exact);
    assert_near(coons_mesh_volume(whole), exact, 1e-11 * exact);
    coons_mesh_free(near);
    coons_mesh_free(whole);
    coons_model_free(m);
}

static void test_crossing(void **state)
{
    (void)state;
    const double lo[2][3] = {{0, 0, 0}, {0.5, 0.4, 0.3}};
    const double hi[2][3] = {{1, 1, 1}, {1.5, 1.4, 1.3}};
    check_boxes(lo, hi, 2, 4);
    check_boxes(lo, hi, 2, 9);
}

/* Both on z = 0: their bottoms overlap on a square, facing the same way
 * (one copy stays); the top of the lower meets the sides of the other. */
static void test_coplanar_same(void **state)
{
    (void)state;
    const double lo[2][3] = {{0, 0, 0}, {0.5, 0.5, 0}};
    const double hi[2][3] = {{1, 1, 1}, {1.5, 1.5, 0.6}};
    check_boxes(lo, hi, 2, 5);
    check_boxes(lo, hi, 2, 8);
}

/* One on top of the other, the contact faces overlapping on a square and
 * facing opposite ways (both go: the union is one solid). */
static void test_coplanar_opposite(void **state)
{
    (void)state;
    const double lo[2][3] = {{0, 0, 0}, {0.5, 0.5, 1}};
    const double hi[2][3] = {{1, 1, 1}, {1.5, 1.5, 2}};
    check_boxes(lo, hi, 2, 4);
    check_boxes(lo, hi, 2, 7);
}

/* A pin through a box (two crossing curves, four patches), and a box
 * sharing the planes x = 0, x = 1, z = 0 and z = 1 with the other. */
static void test_pierced_and_flush(void **state)
{
    (void)state;
    const double lo[2][3] = {{0, 0, 0}, {0.25, 0.3, -0.5}};
    const double hi[2][3] = {{1, 1, 1}, {0.75, 0.7, 1.5}};
    check_boxes(lo, hi, 2, 6);
    const double lo2[2][3] = {{0, 0, 0}, {0, 0.5, 0}};
    const double hi2[2][3] = {{1, 1, 1}, {1, 1.5, 1}};
    check_boxes(lo2, hi2, 2, 6);
}

/* Chains: the second step unites the first result (no longer a sampled
 * shell) with the third box. */
static void test_chains(void **state)
{
    (void)state;
    const double lo[3][3] = {{0, 0, 0}, {0.6, 0.2, 0.1}, {0.3, 0.7, -0.2}};
    const double hi[3][3] = {{1, 1, 1}, {1.4, 0.9, 0.8}, {0.9, 1.6, 0.5}};
    check_boxes(lo, hi, 3, 5);
    const double lo2[3][3] = {{0, 0, 0}, {0.5, 0, 0}, {0.25, 0.25, 1}};
    const double hi2[3][3] = {{1, 1, 1}, {1.5, 1, 0.5}, {1.25, 0.75, 1.5}};
    check_boxes(lo2, hi2, 3, 6);
}

/* Curved shells (the three example bodies): the same solid as CGAL's
 * Boolean of the whole shells makes, to rounding. */
static void test_three_examples(void **state)
{
    (void)state;
    coons_model *m = test_source_model("tests/data/ok/three-examples-union.json");
    coons_csg_report rn, rw;
    coons_mesh *near = unite(m, 20, 0, &rn), *whole = unite(m, 20, 1, &rw);
    double vn = coons_mesh_volume(near), vw = coons_mesh_volume(whole);
    printf("  three bodies: volume %.15g (whole shells: %.15g), %zu triangles (%zu), %zu "
           "patches\n",
           vn, vw, coons_mesh_triangle_count(near), coons_mesh_triangle_count(whole),
           rn.patches);
    assert_true(rn.patches > 0);
    assert_int_equal(rw.patches, 0);
    assert_near(vn, vw, 1e-9 * vw);
    /* the same surface: equal areas, and equal boxes */
    coons_mesh_report a = COONS_MESH_REPORT_INIT, b = COONS_MESH_REPORT_INIT;
    coons_error err;
    assert_coons_ok(coons_mesh_check(near, &a, &err), &err);
    assert_coons_ok(coons_mesh_check(whole, &b, &err), &err);
    assert_near(a.area, b.area, 1e-9 * b.area);
    coons_mesh_free(near);
    coons_mesh_free(whole);
    coons_model_free(m);
}

/* Parallelepipeds in general position (sheared, turned, corners from a
 * fixed pseudo-random sequence), two and three at a time: the near chain
 * makes every union (no fallback to whole shells), with the volume and
 * area of CGAL's Boolean of the whole shells. */
static double rnd(unsigned *seed)
{
    *seed = *seed * 1103515245u + 12345u;
    return ((*seed >> 8) & 0xffff) / 65535.0;
}

static void test_general_position(void **state)
{
    (void)state;
    unsigned seed = 2026;
    for (int trial = 0; trial < 12; trial++) {
        size_t n = 2 + (size_t)(trial % 2);
        double corners[3][8][3];
        for (size_t i = 0; i < n; i++) {
            double o[3], e[3][3];
            for (int c = 0; c < 3; c++) o[c] = 0.6 * rnd(&seed);
            for (int k = 0; k < 3; k++)
                for (int c = 0; c < 3; c++) e[k][c] = (k == c ? 0.8 : 0.0) + 0.5 * (rnd(&seed) - 0.5);
            for (int c = 0; c < 8; c++)
                for (int d = 0; d < 3; d++)
                    corners[i][c][d] =
                        o[d] + (c >> 2 & 1) * e[0][d] + (c >> 1 & 1) * e[1][d] + (c & 1) * e[2][d];
        }
        coons_model *m = body0_union(corners, n);
        coons_error err;
        coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
        so.resolution = 3 + (unsigned)(trial % 4);
        coons_csg_options co = COONS_CSG_OPTIONS_INIT;
        coons_csg_report rn, rw;
        coons_mesh *near = NULL, *whole = NULL;
        coons_csg_report_init(&rn);
        coons_csg_report_init(&rw);
        assert_coons_ok(coons_model_solidify(m, &so, &co, &near, &rn, &err), &err);
        coons__csg_whole_corefinement(1);
        coons_status rc = coons_model_solidify(m, &so, &co, &whole, &rw, &err);
        coons__csg_whole_corefinement(0);
        assert_coons_ok(rc, &err);
        size_t pairs = 99;
        assert_coons_ok(coons_mesh_count_self_intersections(near, &pairs, &err), &err);
        assert_int_equal(pairs, 0);
        coons_mesh_report a = COONS_MESH_REPORT_INIT, b = COONS_MESH_REPORT_INIT;
        assert_coons_ok(coons_mesh_check(near, &a, &err), &err);
        assert_coons_ok(coons_mesh_check(whole, &b, &err), &err);
        printf("  trial %d: %zu bodies, %zu groups, volume %.15g (whole %.15g), patches %zu, "
               "fast %zu / %zu\n",
               trial, n, rn.groups, a.volume, b.volume, rn.patches, rn.fast_unions,
               rw.fast_unions);
        assert_true(a.closed && a.manifold && a.oriented);
        assert_near(a.volume, b.volume, 1e-9 * b.volume);
        assert_near(a.area, b.area, 1e-9 * b.area);
        if (rn.groups < n) { /* some bodies met: a union was made */
            assert_true(rn.patches > 0);
            assert_int_equal(rn.fallbacks, 0);
        }
        coons_mesh_free(near);
        coons_mesh_free(whole);
        coons_model_free(m);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crossing),          cmocka_unit_test(test_coplanar_same),
        cmocka_unit_test(test_coplanar_opposite), cmocka_unit_test(test_pierced_and_flush),
        cmocka_unit_test(test_chains),            cmocka_unit_test(test_three_examples),
        cmocka_unit_test(test_general_position),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
