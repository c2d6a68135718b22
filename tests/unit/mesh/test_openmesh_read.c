/* SPDX-License-Identifier: GPL-3.0-or-later */
/* What the writers produce reads back through OpenMesh's readers
 * (coons__mesh_read) and through the test's own readers with the same
 * vertex and face counts; OpenMesh's coordinates are the float32 roundings
 * of ours (it reads single precision), and OFF keeps the faces verbatim. */
#define _XOPEN_SOURCE 700
#include "coons_test_hooks.h"
#include "io_test_util.h"

static coons_mesh *hand_mesh(void)
{
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    const double lo[3] = {-1, 0.1, 2}, hi[3] = {1.5, 0.7, 3.25}, sh[3] = {10, 0, 0};
    io_box(m, "box", lo, hi);
    io_torus(m, "ring", 3, 1, 20, 10, sh);
    io_tetra(m, "tet", 0.5, 0.25, 2);
    return m;
}

static coons_mesh *sampled_mesh(void)
{
    /* A 3x3x2 Bezier volume with a raised top centre (examples/volume-bezier). */
    double P[3][3][2][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 2; k++) {
                P[i][j][k][0] = 5.0 * i;
                P[i][j][k][1] = 5.0 * j;
                P[i][j][k][2] = (i == 1 && j == 1 && k == 1) ? 16.0 : 10.0 * k;
            }
    const size_t n[3] = {3, 3, 2};
    coons_body *b;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_bezier(&P[0][0][0][0], n, &b, &e), &e);
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.resolution = 9;
    coons_mesh *m;
    assert_coons_ok(coons_body_sample(b, &o, "bezier", &m, &e), &e);
    coons_body_free(b);
    return m;
}

static int cmp_f3(const void *a, const void *b) { return memcmp(a, b, 3 * sizeof(float)); }

/* Distinct float32 positions among 3*n floats (sorted in place). */
static size_t distinct_f3(float *p, size_t n)
{
    if (!n) return 0;
    qsort(p, n, 3 * sizeof(float), cmp_f3);
    size_t d = 1;
    for (size_t i = 1; i < n; i++) d += memcmp(p + 3 * i, p + 3 * (i - 1), 3 * sizeof(float)) != 0;
    return d;
}

static void check_mesh(coons_mesh *m)
{
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    size_t nv = coons_mesh_vertex_count(m), nt = coons_mesh_triangle_count(m);
    const double *xyz = coons_mesh_vertices(m);
    static const struct {
        const char *file;
        coons_format format;
    } outs[] = {{"m.stl", COONS_FORMAT_STL_BINARY},
                {"a.stl", COONS_FORMAT_STL_ASCII},
                {"m.off", COONS_FORMAT_OFF}};
    for (int i = 0; i < 3; i++) {
        snprintf(p, sizeof p, "%s/%s", dir, outs[i].file);
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(coons_mesh_write(m, p, outs[i].format, NULL, &e), &e);
        /* OpenMesh. */
        coons_mesh *r;
        assert_coons_ok(coons__mesh_read(p, &r, &e), &e);
        assert_int_equal(coons_mesh_triangle_count(r), nt);
        assert_int_equal(coons_mesh_vertex_count(r), nv);
        const double *rx = coons_mesh_vertices(r);
        if (outs[i].format == COONS_FORMAT_OFF) {
            for (size_t k = 0; k < 3 * nv; k++) assert_true(rx[k] == (double)(float)xyz[k]);
            assert_memory_equal(coons_mesh_triangles(r), coons_mesh_triangles(m),
                                3 * nt * sizeof(uint32_t));
        } else {
            /* Same set of float positions, whatever order OpenMesh welds in. */
            float *a = malloc(3 * nv * sizeof *a), *b = malloc(3 * nv * sizeof *b);
            for (size_t k = 0; k < 3 * nv; k++) {
                a[k] = (float)xyz[k];
                b[k] = (float)rx[k];
            }
            assert_int_equal(distinct_f3(a, nv), nv);
            assert_int_equal(distinct_f3(b, nv), nv);
            assert_memory_equal(a, b, 3 * nv * sizeof(float));
            free(a);
            free(b);
        }
        assert_near(coons_mesh_volume(r), coons_mesh_volume(m), 1e-5 * coons_mesh_volume(m));
        coons_mesh_free(r);
        /* The test's own readers. */
        size_t len;
        char *d = io_read_file(p, &len);
        if (outs[i].format == COONS_FORMAT_OFF) {
            io_off o;
            io_parse_off(d, &o);
            assert_int_equal(o.nv, nv);
            assert_int_equal(o.nf, nt);
            io_off_free(&o);
        } else {
            float *t = NULL;
            long n;
            if (outs[i].format == COONS_FORMAT_STL_BINARY) {
                n = io_parse_stl_binary((const unsigned char *)d, len, &t);
            } else {
                char *name = NULL;
                n = io_parse_stl_ascii(d, &t, &name);
                free(name);
            }
            assert_int_equal(n, (long)nt);
            float *v = malloc(9 * nt * sizeof *v + 1);
            for (long f = 0; f < n; f++) memcpy(v + 9 * f, t + 12 * f + 3, 9 * sizeof(float));
            assert_int_equal(distinct_f3(v, 3 * (size_t)n), nv);
            free(v);
            free(t);
        }
        free(d);
    }
    io_rmdir(dir);
}

static void test_hand_built(void **state)
{
    (void)state;
    coons_mesh *m = hand_mesh();
    check_mesh(m);
    coons_mesh_free(m);
}

static void test_sampled_body(void **state)
{
    (void)state;
    coons_mesh *m = sampled_mesh();
    coons_mesh_report rep = COONS_MESH_REPORT_INIT;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_check(m, &rep, &e), &e);
    assert_true(rep.closed && rep.manifold && rep.oriented);
    check_mesh(m);
    coons_mesh_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hand_built),
        cmocka_unit_test(test_sampled_body),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
