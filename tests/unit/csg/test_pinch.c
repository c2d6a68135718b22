/* SPDX-License-Identifier: GPL-3.0-or-later */
/* coons__mesh_split_pinches() (src/mesh/pinch.c) on meshes made by hand
 * whose expected result is known: a cube (a 2-manifold: left unchanged,
 * byte for byte), two cubes sharing an edge (the edge of four triangles
 * becomes two edges, its two vertices two each), two cubes sharing a
 * vertex (the vertex becomes two), three wedges around one axis (an edge
 * of six triangles becomes three), a pinched part followed by others (the
 * vertex ranges move); every result checked by coons_mesh_check() (closed,
 * 2-manifold, oriented, shells, Euler characteristic 2 per shell), by its
 * volume (each copy moved into its own solid: slightly less, by at most
 * what the moves allow), by the corners of every triangle (where they
 * were, or moved by at most 1e-3 of the shortest edge, 1e-3 here) and by
 * the copies' separation (welding by position merges nothing); and each
 * allocation failed in turn (the mesh is left as it was). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pinch.h"
#include "test_util.h"

static const double PI = 3.14159265358979323846;

/* Vertex i of the unit cube at bits (x, y, z) = (i & 1, i >> 1 & 1, i >> 2 & 1). */
static const int QUADS[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}}; /* outward */

typedef struct soup {
    double v[64][3];
    uint32_t t[128][3];
    size_t nv, nt;
} soup;

/* The index of point p in s, added if new (welded by coordinates). */
static uint32_t vertex(soup *s, const double p[3])
{
    for (size_t i = 0; i < s->nv; i++)
        if (s->v[i][0] == p[0] && s->v[i][1] == p[1] && s->v[i][2] == p[2]) return (uint32_t)i;
    memcpy(s->v[s->nv], p, sizeof s->v[0]);
    return (uint32_t)s->nv++;
}

static void tri(soup *s, const double *a, const double *b, const double *c)
{
    s->t[s->nt][0] = vertex(s, a);
    s->t[s->nt][1] = vertex(s, b);
    s->t[s->nt][2] = vertex(s, c);
    s->nt++;
}

static void add_cube(soup *s, double ox, double oy, double oz)
{
    double c[8][3];
    for (int i = 0; i < 8; i++) {
        c[i][0] = ox + (i & 1);
        c[i][1] = oy + (i >> 1 & 1);
        c[i][2] = oz + (i >> 2 & 1);
    }
    for (int f = 0; f < 6; f++) {
        tri(s, c[QUADS[f][0]], c[QUADS[f][1]], c[QUADS[f][2]]);
        tri(s, c[QUADS[f][0]], c[QUADS[f][2]], c[QUADS[f][3]]);
    }
}

/* A prism over the 60-degree wedge of the unit disc from angle a0,
 * 0 <= z <= 1: two of its faces contain the z axis. */
static void add_wedge(soup *s, double a0)
{
    double a1 = a0 + PI / 3;
    double A0[3] = {0, 0, 0}, A1[3] = {0, 0, 1};
    double P0[3] = {cos(a0), sin(a0), 0}, P1[3] = {cos(a1), sin(a1), 0};
    double Q0[3] = {P0[0], P0[1], 1}, Q1[3] = {P1[0], P1[1], 1};
    tri(s, A0, P1, P0); /* bottom */
    tri(s, A1, Q0, Q1); /* top */
    tri(s, A0, P0, Q0); /* side at a0 */
    tri(s, A0, Q0, A1);
    tri(s, A0, A1, Q1); /* side at a1 */
    tri(s, A0, Q1, P1);
    tri(s, P0, P1, Q1); /* outside */
    tri(s, P0, Q1, Q0);
}

static coons_mesh *mesh_of(const soup *const *parts, size_t n)
{
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    for (size_t i = 0; i < n; i++)
        assert_coons_ok(coons_mesh_add_part(m, NULL, &parts[i]->v[0][0], parts[i]->nv,
                                            &parts[i]->t[0][0], parts[i]->nt, &err),
                        &err);
    return m;
}

static coons_mesh_report check(const coons_mesh *m)
{
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_check(m, &r, &err), &err);
    return r;
}

/* The corners of every triangle of a and b (same triangles in the same
 * order, whatever their indices) within `moved` of each other; returns the
 * number of corners that moved at all. */
static size_t assert_same_geometry(const coons_mesh *a, const coons_mesh *b, double moved)
{
    assert_int_equal(coons_mesh_triangle_count(a), coons_mesh_triangle_count(b));
    const double *va = coons_mesh_vertices(a), *vb = coons_mesh_vertices(b);
    const uint32_t *ta = coons_mesh_triangles(a), *tb = coons_mesh_triangles(b);
    size_t n = 0;
    for (size_t k = 0; k < 3 * coons_mesh_triangle_count(a); k++) {
        const double *p = va + 3 * (size_t)ta[k], *q = vb + 3 * (size_t)tb[k];
        double d = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                        (p[2] - q[2]) * (p[2] - q[2]));
        assert_true(d <= moved);
        n += d > 0;
    }
    return n;
}

typedef struct split {
    size_t edges, vertices, left;
} split;

static split run(coons_mesh *m)
{
    split s = {0, 0, 99};
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons__mesh_split_pinches(m, &s.edges, &s.vertices, &s.left, &err), &err);
    return s;
}

/* The split result of the soups: closed, 2-manifold, oriented, `shells`
 * shells, volume `vol`, `nv` vertices, the same triangles as before. */
static coons_mesh *assert_split(const soup *const *parts, size_t n, split want, size_t nv,
                                size_t shells, double vol)
{
    coons_mesh *before = mesh_of(parts, n), *m = mesh_of(parts, n);
    coons_mesh_report r0 = check(before);
    assert_int_equal(r0.nonmanifold_edges, want.edges);
    split s = run(m);
    assert_int_equal(s.edges, want.edges);
    assert_int_equal(s.vertices, want.vertices);
    assert_int_equal(s.left, 0);
    coons_mesh_report r = check(m);
    assert_true(r.closed);
    assert_true(r.manifold);
    assert_true(r.oriented);
    assert_int_equal(r.nonmanifold_edges, 0);
    assert_int_equal(r.nonmanifold_vertices, 0);
    assert_int_equal(r.shells, shells);
    assert_int_equal(r.euler, 2 * (long)shells); /* each shell a sphere */
    assert_int_equal(coons_mesh_vertex_count(m), nv);
    /* each copy moved by <= 1e-3 (edges of 1 or more) into its own solid */
    double v0 = coons_mesh_volume(before), v1 = coons_mesh_volume(m);
    assert_near(v0, vol, 1e-14 * fmax(1, vol));
    assert_true(v1 < v0 && v1 > v0 - 2e-3 * (double)want.vertices);
    size_t moved = assert_same_geometry(before, m, 1.0001e-3);
    assert_true(moved > 0);
    /* a second pass finds nothing */
    split again = run(m);
    assert_int_equal(again.edges + again.vertices + again.left, 0);
    /* the copies are apart: welding by position merges nothing */
    coons_mesh *w = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons__mesh_welded(m, &w, &err), &err);
    assert_int_equal(coons_mesh_vertex_count(w), coons_mesh_vertex_count(m));
    coons_mesh_free(w);
    coons_mesh_free(before);
    return m;
}

static void test_cube_unchanged(void **state)
{
    (void)state;
    soup a = {0};
    add_cube(&a, 0, 0, 0);
    const soup *parts[] = {&a};
    coons_mesh *m = mesh_of(parts, 1);
    split s = run(m);
    assert_int_equal(s.edges, 0);
    assert_int_equal(s.vertices, 0);
    assert_int_equal(s.left, 0);
    assert_int_equal(coons_mesh_vertex_count(m), 8);
    assert_memory_equal(coons_mesh_vertices(m), &a.v[0][0], 8 * 3 * sizeof(double));
    assert_memory_equal(coons_mesh_triangles(m), &a.t[0][0], 12 * 3 * sizeof(uint32_t));
    coons_mesh_free(m);
}

static void test_cubes_sharing_edge(void **state)
{
    (void)state;
    soup a = {0};
    add_cube(&a, 0, 0, 0);
    add_cube(&a, 1, 1, 0); /* the edge x = y = 1 */
    assert_int_equal(a.nv, 14);
    const soup *parts[] = {&a};
    split want = {1, 2, 0};
    coons_mesh *m = assert_split(parts, 1, want, 16, 2, 2.0);
    coons_mesh_free(m);
}

static void test_cubes_sharing_vertex(void **state)
{
    (void)state;
    soup a = {0};
    add_cube(&a, 0, 0, 0);
    add_cube(&a, 1, 1, 1); /* the vertex (1, 1, 1) */
    assert_int_equal(a.nv, 15);
    const soup *parts[] = {&a};
    split want = {0, 1, 0};
    coons_mesh *m = assert_split(parts, 1, want, 16, 2, 2.0);
    coons_mesh_free(m);
}

static void test_three_wedges_around_an_axis(void **state)
{
    (void)state;
    soup a = {0};
    for (int k = 0; k < 3; k++) add_wedge(&a, k * 2 * PI / 3);
    assert_int_equal(a.nv, 14);
    const soup *parts[] = {&a};
    split want = {1, 2, 0};
    /* each axis end: one vertex made three */
    coons_mesh *m = assert_split(parts, 1, want, 18, 3, 3 * sqrt(3.0) / 4);
    coons_mesh_free(m);
}

static void test_parts_move(void **state)
{
    (void)state;
    soup a = {0}, b = {0}, c = {0};
    add_cube(&a, 0, 0, 0);
    add_cube(&b, 0, 0, 0);
    add_cube(&b, 1, 1, 0);
    add_cube(&c, 5, 0, 0);
    add_cube(&c, 6, 0, 1); /* shares the edge x = 6, z = 1 */
    const soup *parts[] = {&a, &b, &c};
    split want = {2, 4, 0};
    coons_mesh *m = assert_split(parts, 3, want, 8 + 16 + 16, 5, 5.0);
    size_t tf, tc, vf, vc;
    coons_mesh_part_range(m, 0, &tf, &tc, &vf, &vc);
    assert_true(vf == 0 && vc == 8 && tf == 0 && tc == 12);
    coons_mesh_part_range(m, 1, &tf, &tc, &vf, &vc);
    assert_true(vf == 8 && vc == 16 && tf == 12 && tc == 24);
    coons_mesh_part_range(m, 2, &tf, &tc, &vf, &vc);
    assert_true(vf == 24 && vc == 16 && tf == 36 && tc == 24);
    const uint32_t *t = coons_mesh_triangles(m);
    for (size_t k = 0; k < 3 * coons_mesh_triangle_count(m); k++) {
        size_t part = k / 3 < 12 ? 0 : k / 3 < 36 ? 1 : 2;
        size_t lo = part == 0 ? 0 : part == 1 ? 8 : 24, hi = part == 0 ? 8 : part == 1 ? 24 : 40;
        assert_true(t[k] >= lo && t[k] < hi); /* each part uses its own vertices */
    }
    coons_mesh_free(m);
}

/* Each allocation of the pass failed in turn: COONS_E_NOMEM, nothing
 * leaked, the mesh exactly as it was. */
static void test_allocation_failures(void **state)
{
    (void)state;
    soup a = {0};
    add_cube(&a, 0, 0, 0);
    add_cube(&a, 1, 1, 0);
    const soup *parts[] = {&a};
    coons_mesh *ref = mesh_of(parts, 1);
    int done = 0;
    for (long k = 0; k < 100 && !done; k++) {
        coons_mesh *m = mesh_of(parts, 1);
        size_t e = 0, v = 0, left = 0;
        coons_error err = COONS_ERROR_INIT;
        coons_test_fail_after(k);
        coons_status st = coons__mesh_split_pinches(m, &e, &v, &left, &err);
        long live = coons_test_live_allocs();
        coons_test_fail_after(-1);
        if (st == COONS_OK) {
            done = 1;
            assert_int_equal(v, 2);
            assert_int_equal(live, 0); /* the old arrays freed, the new ones kept */
        } else {
            assert_int_equal(st, COONS_E_NOMEM);
            assert_int_equal(live, 0);
            assert_int_equal(e + v, 0);
            assert_int_equal(coons_mesh_vertex_count(m), coons_mesh_vertex_count(ref));
            assert_memory_equal(coons_mesh_vertices(m), coons_mesh_vertices(ref),
                                3 * coons_mesh_vertex_count(ref) * sizeof(double));
            assert_memory_equal(coons_mesh_triangles(m), coons_mesh_triangles(ref),
                                3 * coons_mesh_triangle_count(ref) * sizeof(uint32_t));
        }
        coons_mesh_free(m);
    }
    assert_true(done);
    coons_mesh_free(ref);
}

/* coons__mesh_clone(): the same arrays and part records; each allocation
 * failed in turn gives COONS_E_NOMEM and leaks nothing. */
static void test_clone(void **state)
{
    (void)state;
    soup a = {0}, b = {0};
    add_cube(&a, 0, 0, 0);
    add_cube(&b, 3, 0, 0);
    const soup *parts[] = {&a, &b};
    coons_mesh *m = mesh_of(parts, 2);
    int done = 0;
    for (long k = 0; k < 100 && !done; k++) {
        coons_mesh *c = NULL;
        coons_error err = COONS_ERROR_INIT;
        coons_test_fail_after(k);
        coons_status st = coons__mesh_clone(m, &c, &err);
        coons_test_fail_after(-1);
        if (st == COONS_OK) {
            done = 1;
            assert_int_equal(coons_mesh_vertex_count(c), 16);
            assert_int_equal(coons_mesh_part_count(c), 2);
            assert_memory_equal(coons_mesh_vertices(c), coons_mesh_vertices(m), 48 * sizeof(double));
            assert_memory_equal(coons_mesh_triangles(c), coons_mesh_triangles(m),
                                72 * sizeof(uint32_t));
            assert_string_equal(coons_mesh_part_name(c, 1), coons_mesh_part_name(m, 1));
            size_t r[4], q[4];
            coons_mesh_part_range(c, 1, &r[0], &r[1], &r[2], &r[3]);
            coons_mesh_part_range(m, 1, &q[0], &q[1], &q[2], &q[3]);
            assert_memory_equal(r, q, sizeof r);
            coons_mesh_free(c);
        } else {
            assert_int_equal(st, COONS_E_NOMEM);
            assert_null(c);
        }
    }
    assert_true(done);
    coons_mesh_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cube_unchanged),
        cmocka_unit_test(test_cubes_sharing_edge),
        cmocka_unit_test(test_cubes_sharing_vertex),
        cmocka_unit_test(test_three_wedges_around_an_axis),
        cmocka_unit_test(test_parts_move),
        cmocka_unit_test(test_allocation_failures),
        cmocka_unit_test(test_clone),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
