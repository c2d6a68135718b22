/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The self-intersection count of the repair and union checks (hierarchical
 * grids of triangle boxes, with exact tests in an axis projection before the
 * 3-D ones) against the earlier method (CGAL's box_intersection_d and the
 * 3-D tests alone): the same count on soups built to be degenerate (lattice
 * points: exact coplanar and collinear contacts, shared vertices and edges,
 * boxes of every size), on the crossing shells of sampled examples, and in
 * the local form (pairs of two flagged triangles skipped), on 1 and 3
 * threads; and the count itself on configurations counted by hand. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "coons_test_hooks.h"
#include "test_util.h"


static size_t count(const coons_mesh *m, const unsigned char *old, int reference,
                    unsigned threads)
{
    size_t pairs = 0, degenerate = 0;
    coons_error err;
    assert_coons_ok(coons__csg_count_pairs(m, old, reference, threads, &pairs, &degenerate, &err),
                    &err);
    return pairs;
}

/* Every way of counting agrees; returns the count. */
static size_t agree(const coons_mesh *m, const unsigned char *old)
{
    size_t ref = count(m, old, 1, 1);
    assert_int_equal(count(m, old, 0, 1), ref);
    assert_int_equal(count(m, old, 0, 3), ref);
    assert_int_equal(count(m, old, 1, 3), ref);
    return ref;
}

static uint64_t rng = 0x9e3779b97f4a7c15ull;
static uint32_t next(uint32_t n)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (uint32_t)(rng % n);
}

static coons_mesh *soup(const double *xyz, size_t nv, const uint32_t *tri, size_t nt)
{
    coons_mesh *m = NULL;
    coons_error err;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    assert_coons_ok(coons_mesh_add_part(m, "soup", xyz, nv, tri, nt, &err), &err);
    return m;
}

/* Triangles on the points of a 5 x 5 x 5 lattice, some small (vertices one
 * step apart), some spanning it: exact coplanarity and shared indices
 * everywhere. A third of the draws also use a jittered copy of the
 * lattice, whose near-degenerate contacts the filters cannot settle. */
static void test_lattice_soups(void **state)
{
    (void)state;
    enum { K = 5, NV = 2 * K * K * K, NT = 800 };
    double xyz[3 * NV];
    for (int i = 0; i < K; i++)
        for (int j = 0; j < K; j++)
            for (int k = 0; k < K; k++) {
                double *p = xyz + 3 * ((i * K + j) * K + k), *q = p + 3 * K * K * K;
                p[0] = i, p[1] = j, p[2] = k;
                q[0] = i + 1e-13 * (double)next(7), q[1] = j - 1e-13 * (double)next(5),
                q[2] = k + 1e-13 * (double)next(3);
            }
    size_t total = 0;
    for (int round = 0; round < 6; round++) {
        uint32_t tri[3 * NT];
        unsigned char old[NT];
        size_t nt = 0;
        for (size_t t = 0; t < NT; t++) {
            uint32_t base = next(3) == 0 ? (uint32_t)(K * K * K) : 0, v[3];
            if (next(4) == 0) { /* anywhere */
                for (int c = 0; c < 3; c++) v[c] = base + next(K * K * K);
            } else { /* a corner and two neighbours one step away */
                int i = (int)next(K - 1), j = (int)next(K - 1), k = (int)next(K - 1);
                for (int c = 0; c < 3; c++) {
                    int di = (int)next(2), dj = (int)next(2), dk = (int)next(2);
                    v[c] = base + (uint32_t)(((i + di) * K + (j + dj)) * K + (k + dk));
                }
            }
            /* no collinear triple (on the lattice, so also not jittered):
             * the check's input triangles have area (the shells are checked
             * for flat triangles first), and CGAL's triangle tests require it */
            long c[3][3];
            for (int a = 0; a < 3; a++) {
                uint32_t w = v[a] % (uint32_t)(K * K * K);
                c[a][0] = w / (K * K), c[a][1] = w / K % K, c[a][2] = w % K;
            }
            long e1[3], e2[3];
            for (int d = 0; d < 3; d++) e1[d] = c[1][d] - c[0][d], e2[d] = c[2][d] - c[0][d];
            if (e1[1] * e2[2] - e1[2] * e2[1] == 0 && e1[2] * e2[0] - e1[0] * e2[2] == 0 &&
                e1[0] * e2[1] - e1[1] * e2[0] == 0)
                continue;
            memcpy(tri + 3 * nt, v, sizeof v);
            old[nt] = next(2) == 0;
            nt++;
        }
        coons_mesh *m = soup(xyz, NV, tri, nt);
        size_t n = agree(m, NULL);
        total += n;
        agree(m, old);
        coons_mesh_free(m);
    }
    /* the soups are meant to cross a lot */
    assert_true(total > 1000);
}

/* The shells of sampled examples put together, crossing each other: the
 * three bodies of the union benchmark and two copies of the spool, one
 * moved by less than a lattice step. */
static void test_sampled_shells(void **state)
{
    (void)state;
    coons_model *m = test_source_model("tests/data/ok/three-examples-union.json");
    coons_error err;
    coons_mesh *all = NULL;
    assert_coons_ok(coons_mesh_new(&all, &err), &err);
    for (size_t b = 0; b < coons_model_body_count(m); b++) {
        coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
        so.resolution = 16;
        coons_mesh *one = NULL;
        assert_coons_ok(coons_body_sample(coons_model_body(m, b), &so, "b", &one, &err), &err);
        /* each shell alone is clean */
        assert_int_equal(agree(one, NULL), 0);
        for (int copy = 0; copy < (b == 0 ? 2 : 1); copy++) {
            size_t nv = coons_mesh_vertex_count(one);
            double *xyz = malloc(3 * nv * sizeof(double));
            assert_non_null(xyz);
            memcpy(xyz, coons_mesh_vertices(one), 3 * nv * sizeof(double));
            for (size_t v = 0; copy && v < nv; v++) xyz[3 * v] += 0.037;
            assert_coons_ok(coons_mesh_add_part(all, copy ? "moved" : "b", xyz, nv,
                                                coons_mesh_triangles(one),
                                                coons_mesh_triangle_count(one), &err),
                            &err);
            free(xyz);
        }
        coons_mesh_free(one);
    }
    size_t crossings = agree(all, NULL);
    assert_true(crossings > 100);
    /* local: the first shell's triangles flagged as taken from the input */
    size_t nt = coons_mesh_triangle_count(all);
    unsigned char *old = calloc(nt, 1);
    assert_non_null(old);
    for (size_t t = 0; t < nt / 3; t++) old[t] = 1;
    size_t local = agree(all, old);
    assert_true(local <= crossings);
    free(old);
    coons_mesh_free(all);
    coons_model_free(m);
}

/* Counted by hand. */
static void test_known_counts(void **state)
{
    (void)state;
    /* 0-2: a triangle in z = 0; 3-5: one piercing it; 6-8: one beside
     * both; 9-11: in z = 0 sharing vertex 0, overlapping the first. */
    const double xyz[] = {0, 0, 0, 4, 0, 0, 0, 4, 0,    1, 1, -1, 1, 1, 1, 3, 3, 1,
                          9, 9, 9, 10, 9, 9, 9, 10, 9,  3, 1, 0, 1, 3, 0, 8, 8, 0};
    const uint32_t cross[] = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    coons_mesh *m = soup(xyz, 12, cross, 3);
    assert_int_equal(agree(m, NULL), 1);
    coons_mesh_free(m);
    /* coplanar, sharing vertex 0, overlapping: 1 */
    const uint32_t cop[] = {0, 1, 2, 0, 9, 10};
    m = soup(xyz, 12, cop, 2);
    assert_int_equal(agree(m, NULL), 1);
    coons_mesh_free(m);
    /* a flat fan of six around the origin, and the same fan with one
     * triangle folded over its neighbour (same side of the shared edge) */
    double fan[3 * 7] = {0, 0, 0};
    const double ring[6][2] = {{2, 0}, {1, 2}, {-1, 2}, {-2, 0}, {-1, -2}, {1, -2}};
    for (int i = 0; i < 6; i++) fan[3 * (i + 1)] = ring[i][0], fan[3 * (i + 1) + 1] = ring[i][1];
    uint32_t ft[18];
    for (uint32_t i = 0; i < 6; i++) ft[3 * i] = 0, ft[3 * i + 1] = 1 + i, ft[3 * i + 2] = 1 + (i + 1) % 6;
    m = soup(fan, 7, ft, 6);
    assert_int_equal(agree(m, NULL), 0);
    coons_mesh_free(m);
    /* two coplanar triangles on the same side of their shared edge, one
     * inside the other: 1; on opposite sides: 0 */
    const double fold[] = {0, 0, 0, 2, 0, 0, 1, 2, 0, 1, 1, 0, 1, -1, 0};
    const uint32_t same[] = {0, 1, 2, 1, 0, 3}, opposite[] = {0, 1, 2, 1, 0, 4};
    m = soup(fold, 5, same, 2);
    assert_int_equal(agree(m, NULL), 1);
    coons_mesh_free(m);
    m = soup(fold, 5, opposite, 2);
    assert_int_equal(agree(m, NULL), 0);
    coons_mesh_free(m);
    /* extents beyond doubles (1e308 - -1e308): counted, at once (the grids
     * would need cells of infinite size; the reference counts these) */
    const double huge[] = {-1e308, 0, 0, 1e308, 0, 0, 0, 1e308, 0, 0, 0, 1e308,
                           -1e308, 1, 1, 1, -1e308, 1};
    const uint32_t ht[] = {0, 1, 2, 0, 1, 3, 3, 4, 5, 0, 2, 3};
    m = soup(huge, 6, ht, 4);
    size_t pairs = 0;
    coons_error err;
    assert_coons_ok(coons_mesh_count_self_intersections(m, &pairs, &err), &err);
    assert_int_equal(pairs, agree(m, NULL));
    coons_mesh_free(m);
}

/* The public threaded count (coons_mesh_count_self_intersections_threads)
 * against the two one-thread counts: two triangles one float32 step apart
 * cross only when rounded; a soup of 6000 lattice triangles (past the
 * 4096 boxes from which threads are used) counts the same on 1, 2 and 3
 * threads; a bad `rounded` is refused. */
static void test_threads_api(void **state)
{
    (void)state;
    coons_error err;
    size_t a = 0, b = 0;
    /* z = 1 and z = 1 + 1e-9 (1.0f when rounded): parallel, then coplanar
     * and overlapping */
    const double two[] = {0, 0, 1, 2, 0, 1, 0, 2, 1, 0.5, 0.5, 1 + 1e-9, 3, 0.5, 1 + 1e-9,
                          0.5, 3, 1 + 1e-9};
    const uint32_t tt[] = {0, 1, 2, 3, 4, 5};
    coons_mesh *m = soup(two, 6, tt, 2);
    for (unsigned t = 1; t <= 3; t++) {
        assert_coons_ok(coons_mesh_count_self_intersections_threads(m, 0, t, &a, &err), &err);
        assert_coons_ok(coons_mesh_count_self_intersections_threads(m, 1, t, &b, &err), &err);
        assert_int_equal(a, 0);
        assert_int_equal(b, 1);
    }
    assert_int_equal(coons_mesh_count_self_intersections_threads(m, 2, 1, &a, &err),
                     COONS_E_INVALID);
    coons_mesh_free(m);
    enum { N = 5, NT = 6000 };
    double xyz[3 * N * N * N];
    for (int i = 0; i < N * N * N; i++) {
        xyz[3 * i] = i % N + 1e-3 * (i % 7);
        xyz[3 * i + 1] = (i / N) % N;
        xyz[3 * i + 2] = i / (N * N) + 0.1;
    }
    uint32_t *tri = malloc(3 * NT * sizeof *tri);
    assert_non_null(tri);
    for (size_t t = 0; t < NT; t++) {
        /* small triangles: corners one lattice step apart */
        uint32_t c = next(N * N * N);
        uint32_t x = c % N, y = (c / N) % N, z = c / (N * N);
        uint32_t c1 = (x + 1 < N ? c + 1 : c - 1), c2 = (y + 1 < N ? c + N : c - N);
        if (next(2)) c2 = (z + 1 < N ? c + N * N : c - N * N);
        tri[3 * t] = c, tri[3 * t + 1] = c1, tri[3 * t + 2] = c2;
    }
    m = soup(xyz, N * N * N, tri, NT);
    size_t ref = 0, ref32 = 0;
    assert_coons_ok(coons_mesh_count_self_intersections(m, &ref, &err), &err);
    assert_coons_ok(coons_mesh_count_self_intersections_float(m, &ref32, &err), &err);
    assert_true(ref > 0);
    for (unsigned t = 1; t <= 3; t++) {
        assert_coons_ok(coons_mesh_count_self_intersections_threads(m, 0, t, &a, &err), &err);
        assert_coons_ok(coons_mesh_count_self_intersections_threads(m, 1, t, &b, &err), &err);
        assert_int_equal(a, ref);
        assert_int_equal(b, ref32);
    }
    coons_mesh_free(m);
    free(tri);
}

/* Past the sizes from which the grid is built on the threads (chunks of
 * 65536 triangles, parallel radix sort from 65536 entries): 70000 small
 * triangles on a jittered 30 x 30 x 30 lattice, about seventy of them
 * collinear, counted alike by the reference and the grids on 1 and 3
 * threads (pairs and zero-area triangles), with and without kept ones. */
static void test_large_soup(void **state)
{
    (void)state;
    enum { N = 30, NT = 70000 };
    size_t nv = (size_t)N * N * N;
    double *xyz = malloc(3 * nv * sizeof *xyz);
    uint32_t *tri = malloc(3 * (size_t)NT * sizeof *tri);
    unsigned char *old = malloc(NT);
    assert_non_null(xyz);
    assert_non_null(tri);
    assert_non_null(old);
    for (size_t i = 0; i < nv; i++) {
        xyz[3 * i] = (double)(i % N) + 0.25 * (double)next(3);
        xyz[3 * i + 1] = (double)((i / N) % N);
        xyz[3 * i + 2] = (double)(i / (N * N));
    }
    for (size_t t = 0; t < NT; t++) {
        uint32_t x = next(N - 2), y = next(N - 2), z = next(N - 2);
        uint32_t c = (z * N + y) * N + x;
        uint32_t c1 = c + 1 + (next(2) ? N : 0), c2 = c + N * N + (next(2) ? 1 : 0);
        tri[3 * t] = c, tri[3 * t + 1] = c1, tri[3 * t + 2] = c2;
        old[t] = next(3) == 0;
    }
    /* collinear: three of a row (the jitter is along x only); never kept
     * (kept triangles come from checked inputs: not tested for area) */
    for (size_t t = 0; t < NT; t += 997) {
        tri[3 * t + 1] = tri[3 * t] + 1, tri[3 * t + 2] = tri[3 * t] + 2;
        old[t] = 0;
    }
    coons_mesh *m = soup(xyz, nv, tri, NT);
    size_t n = agree(m, NULL);
    assert_true(n > 1000);
    agree(m, old);
    size_t d1 = 0, d3 = 0, p1 = 0, p3 = 0;
    coons_error err;
    assert_coons_ok(coons__csg_count_pairs(m, NULL, 1, 1, &p1, &d1, &err), &err);
    assert_coons_ok(coons__csg_count_pairs(m, NULL, 0, 3, &p3, &d3, &err), &err);
    assert_true(d1 > 50);
    assert_int_equal(d3, d1);
    coons_mesh_free(m);
    free(xyz);
    free(tri);
    free(old);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lattice_soups),
        cmocka_unit_test(test_sampled_shells),
        cmocka_unit_test(test_known_counts),
        cmocka_unit_test(test_threads_api),
        cmocka_unit_test(test_large_soup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
