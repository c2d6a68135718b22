/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Repair and union (CGAL layer): volumes by inclusion-exclusion and by
 * independent integration, closedness, manifoldness, self-intersection. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "coons_test_hooks.h"
#include "test_util.h"

/* The test's own lattice mesher (independent of the library's sampler):
 * the boundary of [0,1]^3 with n[0] x n[1] x n[2] cells, shared vertices,
 * triangles counter-clockwise seen from outside for a right-handed map. */
typedef struct lattice {
    double *xyz;
    uint32_t *tri;
    size_t nv, nt;
} lattice;

static long vid(int *idx, const int n[3], int i, int j, int k)
{
    return idx[((size_t)i * (n[1] + 1) + j) * (n[2] + 1) + k];
}

static void lattice_build(lattice *L, const coons_body *b, const int n[3], const double shift[3])
{
    size_t cnt = (size_t)(n[0] + 1) * (n[1] + 1) * (n[2] + 1);
    int *idx = malloc(cnt * sizeof *idx);
    L->xyz = malloc(cnt * 3 * sizeof(double));
    L->nv = 0;
    for (int i = 0; i <= n[0]; i++)
        for (int j = 0; j <= n[1]; j++)
            for (int k = 0; k <= n[2]; k++) {
                int on = i == 0 || i == n[0] || j == 0 || j == n[1] || k == 0 || k == n[2];
                size_t at = ((size_t)i * (n[1] + 1) + j) * (n[2] + 1) + k;
                idx[at] = -1;
                if (!on) continue;
                double p[3];
                coons_body_eval(b, (double)i / n[0], (double)j / n[1], (double)k / n[2], p);
                for (int c = 0; c < 3; c++) L->xyz[3 * L->nv + c] = p[c] + (shift ? shift[c] : 0);
                idx[at] = (int)L->nv++;
            }
    size_t maxt = 4 * ((size_t)n[0] * n[1] + (size_t)n[1] * n[2] + (size_t)n[0] * n[2]);
    L->tri = malloc(maxt * 3 * sizeof(uint32_t));
    L->nt = 0;
#define QUAD(a, b2, c, d)                                                                        \
    do {                                                                                         \
        uint32_t q_[4] = {(uint32_t)(a), (uint32_t)(b2), (uint32_t)(c), (uint32_t)(d)};          \
        uint32_t t_[6] = {q_[0], q_[1], q_[2], q_[0], q_[2], q_[3]};                             \
        memcpy(L->tri + 3 * L->nt, t_, sizeof t_);                                               \
        L->nt += 2;                                                                              \
    } while (0)
    for (int a = 0; a < n[1]; a++)
        for (int c = 0; c < n[2]; c++) {
            QUAD(vid(idx, n, 0, a, c), vid(idx, n, 0, a, c + 1), vid(idx, n, 0, a + 1, c + 1), vid(idx, n, 0, a + 1, c));
            QUAD(vid(idx, n, n[0], a, c), vid(idx, n, n[0], a + 1, c), vid(idx, n, n[0], a + 1, c + 1), vid(idx, n, n[0], a, c + 1));
        }
    for (int a = 0; a < n[0]; a++)
        for (int c = 0; c < n[2]; c++) {
            QUAD(vid(idx, n, a, 0, c), vid(idx, n, a + 1, 0, c), vid(idx, n, a + 1, 0, c + 1), vid(idx, n, a, 0, c + 1));
            QUAD(vid(idx, n, a, n[1], c), vid(idx, n, a, n[1], c + 1), vid(idx, n, a + 1, n[1], c + 1), vid(idx, n, a + 1, n[1], c));
        }
    for (int a = 0; a < n[0]; a++)
        for (int c = 0; c < n[1]; c++) {
            QUAD(vid(idx, n, a, c, 0), vid(idx, n, a, c + 1, 0), vid(idx, n, a + 1, c + 1, 0), vid(idx, n, a + 1, c, 0));
            QUAD(vid(idx, n, a, c, n[2]), vid(idx, n, a + 1, c, n[2]), vid(idx, n, a + 1, c + 1, n[2]), vid(idx, n, a, c + 1, n[2]));
        }
#undef QUAD
    free(idx);
}

static void lattice_free(lattice *L)
{
    free(L->xyz);
    free(L->tri);
}

static coons_body *box(double x0, double y0, double z0, double dx, double dy, double dz)
{
    double c[8][3];
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) {
                c[4 * i + 2 * j + k][0] = x0 + i * dx;
                c[4 * i + 2 * j + k][1] = y0 + j * dy;
                c[4 * i + 2 * j + k][2] = z0 + k * dz;
            }
    coons_body *b = NULL;
    coons_error err;
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err), &err);
    return b;
}

static void add_body(coons_mesh *m, const coons_body *b, const int n[3], const char *name)
{
    lattice L;
    coons_error err;
    lattice_build(&L, b, n, NULL);
    assert_coons_ok(coons_mesh_add_part(m, name, L.xyz, L.nv, L.tri, L.nt, &err), &err);
    lattice_free(&L);
}

static void assert_valid_solid(const coons_mesh *m, const coons_csg_report *rep)
{
    coons_error err;
    size_t pairs = 99;
    assert_coons_ok(coons_mesh_count_self_intersections(m, &pairs, &err), &err);
    assert_int_equal(pairs, 0);
    assert_true(rep->closed);
    assert_int_equal(rep->nonmanifold_edges, 0);
    /* Independent check of closed + oriented: every directed edge has its
     * reverse exactly once. */
    size_t nt = coons_mesh_triangle_count(m);
    const uint32_t *t = coons_mesh_triangles(m);
    for (size_t i = 0; i < nt; i++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = t[3 * i + k], b = t[3 * i + (k + 1) % 3];
            int rev = 0;
            for (size_t j = 0; j < nt; j++)
                for (int l = 0; l < 3; l++)
                    if (t[3 * j + l] == b && t[3 * j + (l + 1) % 3] == a) rev++;
            assert_int_equal(rev, 1);
        }
}

static void test_overlapping_boxes(void **state)
{
    (void)state;
    coons_body *a = box(0, 0, 0, 1, 1, 1), *b = box(0.5, 0.25, 0.125, 1, 1, 1);
    coons_mesh *m = NULL, *u = NULL;
    coons_error err;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    int n[3] = {4, 4, 4};
    add_body(m, a, n, "a");
    add_body(m, b, n, "b");
    coons_csg_options o = COONS_CSG_OPTIONS_INIT;
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    assert_coons_ok(coons_mesh_solidify(m, &o, &u, &rep, &err), &err);
    assert_int_equal(coons_mesh_part_count(u), 1);
    /* inclusion-exclusion: 1 + 1 - 0.5*0.75*0.875 */
    double expect = 2.0 - 0.5 * 0.75 * 0.875;
    assert_near(coons_mesh_volume(u), expect, 1e-12);
    assert_int_equal(rep.groups, 1);
    assert_valid_solid(u, &rep);
    coons_mesh_free(u);
    coons_mesh_free(m);
    coons_body_free(a);
    coons_body_free(b);
}

static void test_boxes_sharing_a_face(void **state)
{
    (void)state;
    coons_body *a = box(0, 0, 0, 1, 1, 1), *b = box(1, 0, 0, 1, 1, 1), *ab = box(0, 0, 0, 2, 1, 1);
    coons_mesh *m = NULL, *u = NULL;
    coons_error err;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    int n[3] = {3, 3, 3}, n2[3] = {6, 3, 3};
    add_body(m, a, n, "a");
    add_body(m, b, n, "b");
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    assert_coons_ok(coons_mesh_solidify(m, NULL, &u, &rep, &err), &err);
    lattice single;
    lattice_build(&single, ab, n2, NULL);
    assert_int_equal(coons_mesh_triangle_count(u), single.nt);
    assert_near(coons_mesh_volume(u), 2.0, 1e-12);
    assert_valid_solid(u, &rep);
    lattice_free(&single);
    coons_mesh_free(u);
    coons_mesh_free(m);
    coons_body_free(a);
    coons_body_free(b);
    coons_body_free(ab);
}

static void test_disjoint_bodies_pass_through(void **state)
{
    (void)state;
    coons_body *a = box(0, 0, 0, 1, 1, 1), *b = box(3, 0, 0, 1, 1, 1);
    coons_mesh *m = NULL, *u = NULL;
    coons_error err;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    int n[3] = {2, 2, 2};
    add_body(m, a, n, "a");
    add_body(m, b, n, "b");
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    assert_coons_ok(coons_mesh_solidify(m, NULL, &u, &rep, &err), &err);
    assert_int_equal(rep.groups, 2);
    assert_int_equal(rep.passed_through, 2);
    assert_int_equal(coons_mesh_triangle_count(u), coons_mesh_triangle_count(m));
    assert_near(coons_mesh_volume(u), 2.0, 1e-12);
    coons_mesh_free(u);
    coons_mesh_free(m);
    coons_body_free(a);
    coons_body_free(b);
}

/* A body whose top face is pushed through the bottom face in its middle:
 * a Bezier volume of degrees (2,2,1) with x = u, y = v, z = w t(u,v), where
 * t = 1 - K B1(u) B1(v) (B1 = 2s(1-s)) dips below the bottom z = 0. The
 * region it covers is {z between 0 and t(x,y)}, of volume integral |t|. */
static double fold_t(double x, double y) { return 1.0 - 6.0 * 4.0 * x * (1 - x) * y * (1 - y); }

static void test_fold_is_repaired(void **state)
{
    (void)state;
    double P[3][3][2][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 2; k++) {
                P[i][j][k][0] = i / 2.0;
                P[i][j][k][1] = j / 2.0;
                P[i][j][k][2] = k ? ((i == 1 && j == 1) ? 1.0 - 6.0 : 1.0) : 0.0;
            }
    size_t dims[3] = {3, 3, 2};
    coons_body *b = NULL;
    coons_error err;
    assert_coons_ok(coons_body_new_bezier(&P[0][0][0][0], dims, &b, &err), &err);
    double p[3];
    coons_body_eval(b, 0.3, 0.6, 1.0, p);
    assert_near(p[2], fold_t(0.3, 0.6), 1e-12); /* the test's t is the body's top */
    coons_mesh *m = NULL, *r = NULL;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    int n[3] = {40, 40, 2};
    add_body(m, b, n, "fold");
    size_t pairs = 0;
    assert_coons_ok(coons_mesh_count_self_intersections(m, &pairs, &err), &err);
    assert_true(pairs > 0); /* the sampled boundary crosses itself */
    coons_csg_options o = COONS_CSG_OPTIONS_INIT;
    o.unite = 0;
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    assert_coons_ok(coons_mesh_solidify(m, &o, &r, &rep, &err), &err);
    assert_true(rep.intersecting_pairs > 0);
    double vol = 0.0;
    int N = 4000;
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++)
            vol += fabs(fold_t((i + 0.5) / N, (j + 0.5) / N)) / ((double)N * N);
    printf("fold: covered volume %.9f, input signed %.9f, repaired %.9f, triangles %zu, "
           "nonmanifold edges %zu\n",
           vol, coons_mesh_volume(m), coons_mesh_volume(r), coons_mesh_triangle_count(r),
           rep.nonmanifold_edges);
    assert_near(coons_mesh_volume(r), vol, 3e-3 * vol);
    size_t after = 99;
    assert_coons_ok(coons_mesh_count_self_intersections(r, &after, &err), &err);
    assert_int_equal(after, 0);
    assert_true(rep.closed);
    coons_mesh_free(r);
    coons_mesh_free(m);
    coons_body_free(b);
}

/* A body that crosses itself united with a box: the fold is repaired on
 * its own first (soup pass), then united with the box on the exact path
 * (the fast path needs bodies that do not cross themselves). */
static void test_fold_united_with_box(void **state)
{
    (void)state;
    /* u folds back: x = 4u - 3u^2 (0 -> 4/3 -> 1), the cross-section grows
     * and sinks with u, so the folded layers cross transversally. */
    double X[3] = {0, 2, 1}, h[3] = {0.3, 0.4, 0.8}, c[3] = {0, -0.1, -0.3}, g[3] = {1, 1.2, 1.6};
    double P[3][2][2][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) {
                P[i][j][k][0] = X[i];
                P[i][j][k][1] = (2 * j - 1) * h[i];
                P[i][j][k][2] = c[i] + k * g[i];
            }
    size_t dims[3] = {3, 2, 2};
    coons_body *f = NULL, *b = box(-0.5, -0.2, 0.3, 1.0, 0.4, 0.4);
    coons_error err;
    assert_coons_ok(coons_body_new_bezier(&P[0][0][0][0], dims, &f, &err), &err);
    coons_mesh *m = NULL, *u = NULL, *alone = NULL;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    int nf[3] = {24, 6, 6}, nb[3] = {4, 4, 4};
    add_body(m, f, nf, "fold");
    coons_csg_options o = COONS_CSG_OPTIONS_INIT;
    o.unite = 0;
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    assert_coons_ok(coons_mesh_solidify(m, &o, &alone, &rep, &err), &err);
    assert_true(rep.intersecting_pairs > 0);
    add_body(m, b, nb, "box");
    o.unite = 1;
    assert_coons_ok(coons_mesh_solidify(m, &o, &u, &rep, &err), &err);
    assert_int_equal(rep.fast_unions, 0);
    size_t pairs = 99;
    assert_coons_ok(coons_mesh_count_self_intersections(u, &pairs, &err), &err);
    assert_int_equal(pairs, 0);
    assert_true(rep.closed);
    double vf = coons_mesh_volume(alone), vb = 0.4 * 0.4 * 1.0, vu = coons_mesh_volume(u);
    printf("fold %.6f box %.6f union %.6f\n", vf, vb, vu);
    assert_true(vu > vf + 1e-3 && vu < vf + vb - 1e-3); /* the box sticks out of the fold */
    coons_mesh_free(u);
    coons_mesh_free(alone);
    coons_mesh_free(m);
    coons_body_free(f);
    coons_body_free(b);
}

static void test_injected_failure(void **state)
{
    (void)state;
    coons_body *a = box(0, 0, 0, 1, 1, 1);
    coons_mesh *m = NULL, *u = (coons_mesh *)1;
    coons_error err;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    int n[3] = {2, 2, 2};
    add_body(m, a, n, "lonely");
    coons_csg_options o = COONS_CSG_OPTIONS_INIT;
    coons__csg_inject_failure(1);
    assert_int_equal(coons_mesh_solidify(m, &o, &u, NULL, &err), COONS_E_CSG);
    assert_null(u);
    /* names the bodies and CGAL's explanation, as a real CGAL failure does */
    assert_string_equal(err.message, "CGAL could not complete the operation on bodies 'lonely': "
                                     "injected failure (testing)");
    coons__csg_inject_failure(0);
    u = NULL;
    assert_coons_ok(coons_mesh_solidify(m, &o, &u, NULL, &err), &err);
    coons_mesh_free(u);
    coons_mesh_free(m);
    coons_body_free(a);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_overlapping_boxes),
        cmocka_unit_test(test_boxes_sharing_a_face),
        cmocka_unit_test(test_disjoint_bodies_pass_through),
        cmocka_unit_test(test_fold_is_repaired),
        cmocka_unit_test(test_fold_united_with_box),
        cmocka_unit_test(test_injected_failure),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
