/* SPDX-License-Identifier: GPL-3.0-or-later */
#define _POSIX_C_SOURCE 200809L
/* coons_mesh_check() with OpenMesh, on good and deliberately broken meshes,
 * and coons__mesh_read() through OpenMesh's readers. The expected counts are
 * worked out by hand for each small mesh. The library must not print: stderr
 * is captured around the calls that make OpenMesh complain. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "coons_test_hooks.h"
#include "test_util.h"

static const double TET_V[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
/* counter-clockwise seen from outside */
static const uint32_t TET_T[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

static coons_mesh *make(const double *v, size_t nv, const uint32_t *t, size_t nt)
{
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    assert_coons_ok(coons_mesh_add_part(m, "t", v, nv, t, nt, &err), &err);
    return m;
}

static coons_mesh_report check(const coons_mesh *m)
{
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_check(m, &r, &err), &err);
    assert_int_equal(r.openmesh, 1);
    return r;
}

/* stderr redirected to a file while f runs; returns the bytes written. */
static long captured_stderr(void (*f)(void *), void *arg)
{
    char path[] = "/tmp/coons_om_stderrXXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    fflush(stderr);
    int saved = dup(2);
    dup2(fd, 2);
    f(arg);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    long size = (long)lseek(fd, 0, SEEK_END);
    close(fd);
    unlink(path);
    return size;
}

static void test_good_tetrahedron(void **state)
{
    (void)state;
    coons_mesh *m = make(&TET_V[0][0], 4, &TET_T[0][0], 4);
    coons_mesh_report r = check(m);
    assert_true(r.closed && r.manifold && r.oriented);
    assert_int_equal(r.vertices, 4);
    assert_int_equal(r.edges, 6);
    assert_int_equal(r.euler, 2);
    assert_int_equal(r.shells, 1);
    assert_int_equal(r.boundary_edges + r.nonmanifold_edges + r.misoriented_edges, 0);
    assert_int_equal(r.openmesh_rejected, 0);
    assert_int_equal(r.openmesh_boundary, 0);
    assert_near(r.volume, 1.0 / 6.0, 1e-15);
    assert_near(r.area, 1.5 + sqrt(3.0) / 2, 1e-14);
    coons_mesh_free(m);
}

static void test_sampled_box(void **state)
{
    (void)state;
    double c[8][3];
    for (int i = 0; i < 8; i++) {
        c[i][0] = (i >> 2) & 1;
        c[i][1] = (i >> 1) & 1;
        c[i][2] = i & 1;
    }
    coons_body *b = NULL;
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err), &err);
    assert_coons_ok(coons_body_sample(b, NULL, NULL, &m, &err), &err);
    coons_mesh_report r = check(m);
    assert_true(r.closed && r.manifold && r.oriented);
    assert_int_equal(r.euler, 2);
    assert_int_equal(r.openmesh_rejected, 0);
    assert_int_equal(r.openmesh_boundary, 0);
    assert_int_equal(r.triangles, coons_mesh_triangle_count(m));
    /* closed triangle mesh: 3F = 2E */
    assert_int_equal(3 * r.triangles, 2 * r.edges);
    coons_mesh_free(m);
    coons_body_free(b);
}

static void test_missing_triangle(void **state)
{
    (void)state;
    coons_mesh *m = make(&TET_V[0][0], 4, &TET_T[0][0], 3);
    coons_mesh_report r = check(m);
    assert_false(r.closed);
    assert_true(r.manifold); /* a disk: the links at the hole are paths */
    assert_true(r.oriented);
    assert_int_equal(r.boundary_edges, 3);
    assert_int_equal(r.openmesh_boundary, 3);
    assert_int_equal(r.euler, 1);
    coons_mesh_free(m);
}

typedef struct checked {
    const coons_mesh *m;
    coons_mesh_report r;
} checked;

static void run_check(void *arg)
{
    checked *c = arg;
    c->r = check(c->m);
}

static void test_flipped_triangle(void **state)
{
    (void)state;
    uint32_t t[4][3];
    memcpy(t, TET_T, sizeof t);
    t[3][0] = TET_T[3][1];
    t[3][1] = TET_T[3][0];
    coons_mesh *m = make(&TET_V[0][0], 4, &t[0][0], 4);
    checked c = {m, COONS_MESH_REPORT_INIT};
    /* OpenMesh refuses the flipped face (it would print "complex edge"). */
    assert_int_equal(captured_stderr(run_check, &c), 0);
    coons_mesh_report r = c.r;
    assert_false(r.oriented);
    assert_true(r.closed);
    assert_int_equal(r.misoriented_edges, 3);
    assert_int_equal(r.openmesh_rejected, 1);
    assert_near(r.volume, 1.0 / 6.0 - 2 * (1.0 / 6.0), 1e-15);
    coons_mesh_free(m);
}

static void test_tetrahedra_sharing_vertex(void **state)
{
    (void)state;
    double v[7][3];
    uint32_t t[8][3];
    memcpy(v, TET_V, sizeof TET_V);
    for (int i = 1; i < 4; i++)
        for (int k = 0; k < 3; k++) v[3 + i][k] = -TET_V[i][k]; /* mirrored through vertex 0 */
    memcpy(t, TET_T, sizeof TET_T);
    /* the point reflection has det -1: reverse the triangles to stay outward */
    for (int f = 0; f < 4; f++)
        for (int k = 0; k < 3; k++) {
            uint32_t x = TET_T[f][2 - k];
            t[4 + f][k] = x ? x + 3 : 0;
        }
    coons_mesh *m = make(&v[0][0], 7, &t[0][0], 8);
    checked c = {m, COONS_MESH_REPORT_INIT};
    assert_int_equal(captured_stderr(run_check, &c), 0);
    coons_mesh_report r = c.r;
    assert_true(r.closed);
    assert_true(r.oriented);
    assert_false(r.manifold);
    assert_int_equal(r.nonmanifold_vertices, 1);
    assert_int_equal(r.nonmanifold_edges, 0);
    assert_int_equal(r.shells, 1);
    assert_int_equal(r.euler, 3); /* 7 - 12 + 8: not two spheres */
    assert_true(r.openmesh_rejected > 0);
    assert_near(r.volume, 2.0 / 6.0, 1e-15);
    coons_mesh_free(m);
}

static void test_fin_and_degenerate(void **state)
{
    (void)state;
    /* three triangles on edge 0-1 */
    double v[5][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1, 0}};
    uint32_t t[4][3] = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {2, 2, 3}};
    coons_mesh *m = make(&v[0][0], 5, &t[0][0], 3);
    coons_mesh_report r = check(m);
    assert_int_equal(r.nonmanifold_edges, 1);
    assert_false(r.manifold);
    assert_false(r.closed);
    coons_mesh_free(m);
    m = make(&v[0][0], 5, &t[0][0], 4);
    r = check(m);
    assert_int_equal(r.degenerate_triangles, 1);
    assert_int_equal(r.unused_vertices, 0);
    coons_mesh_free(m);
    /* an unused vertex */
    m = make(&v[0][0], 5, &t[0][0], 1);
    r = check(m);
    assert_int_equal(r.unused_vertices, 2);
    assert_int_equal(r.vertices, 3);
    coons_mesh_free(m);
}

static void test_report_version(void **state)
{
    (void)state;
    coons_mesh *m = make(&TET_V[0][0], 4, &TET_T[0][0], 4);
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    r.version = 7;
    coons_error err = COONS_ERROR_INIT;
    assert_int_equal(coons_mesh_check(m, &r, &err), COONS_E_INVALID);
    coons_mesh_free(m);
}

static void write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    fclose(f);
}

static void test_read_stl_off(void **state)
{
    (void)state;
    char path[512];
    /* ASCII STL of the tetrahedron: 12 corners, welded by OpenMesh to 4. */
    char stl[4096];
    size_t len = (size_t)snprintf(stl, sizeof stl, "solid tet\n");
    for (int f = 0; f < 4; f++) {
        len += (size_t)snprintf(stl + len, sizeof stl - len,
                                "facet normal 0 0 0\nouter loop\n");
        for (int k = 0; k < 3; k++) {
            const double *p = TET_V[TET_T[f][k]];
            len += (size_t)snprintf(stl + len, sizeof stl - len, "vertex %g %g %g\n", p[0], p[1],
                                    p[2]);
        }
        len += (size_t)snprintf(stl + len, sizeof stl - len, "endloop\nendfacet\n");
    }
    len += (size_t)snprintf(stl + len, sizeof stl - len, "endsolid tet\n");
    snprintf(path, sizeof path, "%s/test_om_mesh_tet.stl", COONS_BINARY_DIR);
    write_file(path, stl, len);
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons__mesh_read(path, &m, &err), &err);
    assert_int_equal(coons_mesh_vertex_count(m), 4);
    assert_int_equal(coons_mesh_triangle_count(m), 4);
    assert_string_equal(coons_mesh_part_name(m, 0), "test_om_mesh_tet.stl");
    coons_mesh_report r = check(m);
    assert_true(r.closed && r.manifold && r.oriented);
    assert_near(r.volume, 1.0 / 6.0, 1e-7);
    coons_mesh_free(m);
    unlink(path);

    /* OFF with a quad (triangulated by OpenMesh's TriMesh): a unit square
     * pyramid, 5 vertices, 4 side triangles + 2 for the base. */
    const char *off = "OFF\n5 5 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n"
                      "4 0 3 2 1\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n";
    snprintf(path, sizeof path, "%s/test_om_mesh_pyr.off", COONS_BINARY_DIR);
    write_file(path, off, strlen(off));
    assert_coons_ok(coons__mesh_read(path, &m, &err), &err);
    assert_int_equal(coons_mesh_vertex_count(m), 5);
    assert_int_equal(coons_mesh_triangle_count(m), 6);
    r = check(m);
    assert_true(r.closed && r.manifold && r.oriented);
    assert_near(r.volume, 1.0 / 3.0, 1e-7);
    coons_mesh_free(m);
    unlink(path);
}

static void read_bad(void *arg)
{
    const char **paths = arg;
    coons_error err = COONS_ERROR_INIT;
    for (int i = 0; paths[i]; i++) {
        coons_mesh *m = (coons_mesh *)arg;
        assert_int_equal(coons__mesh_read(paths[i], &m, &err), COONS_E_IO);
        assert_null(m);
    }
}

static void test_read_errors_silent(void **state)
{
    (void)state;
    char missing[512], unknown[512], broken[512];
    snprintf(missing, sizeof missing, "%s/no_such_file.stl", COONS_BINARY_DIR);
    snprintf(unknown, sizeof unknown, "%s/test_om_mesh.xyz", COONS_BINARY_DIR);
    snprintf(broken, sizeof broken, "%s/test_om_mesh_broken.off", COONS_BINARY_DIR);
    write_file(unknown, "hello\n", 6);
    /* (a truncated OFF file would do too, but OpenMesh 9.0's reader then
     * uses uninitialised face indices: valgrind flags it inside OpenMesh) */
    write_file(broken, "OFF\n0 0 0\n", 10);
    const char *paths[] = {missing, unknown, broken, NULL};
    assert_int_equal(captured_stderr(read_bad, paths), 0);
    unlink(unknown);
    unlink(broken);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_good_tetrahedron),
        cmocka_unit_test(test_sampled_box),
        cmocka_unit_test(test_missing_triangle),
        cmocka_unit_test(test_flipped_triangle),
        cmocka_unit_test(test_tetrahedra_sharing_vertex),
        cmocka_unit_test(test_fin_and_degenerate),
        cmocka_unit_test(test_report_version),
        cmocka_unit_test(test_read_stl_off),
        cmocka_unit_test(test_read_errors_silent),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
