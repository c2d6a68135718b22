/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Sampling on threads (coons_sample_options.threads): the mesh of 2 and 5
 * threads is the mesh of one, byte for byte (vertices, triangles, the
 * lattice and the measured deviation), for every fixture body on a fixed
 * lattice large enough to be split (faces of 4096 points and more), and
 * for a few adaptively (the measuring passes evaluate rows of samples on
 * the threads) and measured on the fixed lattice. */
#include <string.h>

#include "body_fixtures.h"
#include "test_util.h"

static coons_mesh *sample(const coons_body *b, coons_sample_options o, unsigned threads)
{
    coons_error e = COONS_ERROR_INIT;
    coons_mesh *m = NULL;
    o.threads = threads;
    assert_coons_ok(coons_body_sample(b, &o, "b", &m, &e), &e);
    return m;
}

static void same_mesh(const coons_mesh *a, const coons_mesh *b)
{
    size_t nv = coons_mesh_vertex_count(a), nt = coons_mesh_triangle_count(a);
    assert_int_equal(coons_mesh_vertex_count(b), nv);
    assert_int_equal(coons_mesh_triangle_count(b), nt);
    if (memcmp(coons_mesh_vertices(a), coons_mesh_vertices(b), 3 * nv * sizeof(double)))
        fail_msg("vertices differ between thread counts");
    if (memcmp(coons_mesh_triangles(a), coons_mesh_triangles(b), 3 * nt * sizeof(uint32_t)))
        fail_msg("triangles differ between thread counts");
    double ta, tb, da, db;
    size_t la[3], lb[3];
    coons_mesh_part_sampling(a, 0, &ta, &da, la);
    coons_mesh_part_sampling(b, 0, &tb, &db, lb);
    assert_memory_equal(la, lb, sizeof la);
    assert_memory_equal(&da, &db, sizeof da); /* NaN too, when not measured */
}

static void check(const coons_body *b, coons_sample_options o)
{
    coons_mesh *one = sample(b, o, 1);
    static const unsigned threads[2] = {2, 5};
    for (int t = 0; t < 2; t++) {
        coons_mesh *m = sample(b, o, threads[t]);
        same_mesh(one, m);
        coons_mesh_free(m);
    }
    coons_mesh_free(one);
}

static void test_bodies(void **state)
{
    (void)state;
    for (int k = 0; k < TB_MAX_BODIES; k++) {
        coons_error e = COONS_ERROR_INIT;
        coons_body *b = NULL;
        if (tb_make_body(k, &b, &e) == TB_NO_BODY) continue;
        coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
        double lo[3], hi[3];
        coons_body_control_bbox(b, lo, hi);
        o.tolerance = 5e-3 * (hi[0] - lo[0] + hi[1] - lo[1] + hi[2] - lo[2]);
        /* Adaptive and measured runs are costly under valgrind: a few
         * bodies of different types. */
        if (k % 3 == 0) check(b, o);
        o.resolution = 64; /* faces of 65 x 65 points: split over the threads */
        o.flags |= COONS_SAMPLE_UNMEASURED;
        check(b, o);
        if (k == 0 || k == 9) {
            o.flags = 0;
            check(b, o);
        }
        coons_body_free(b);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bodies),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
