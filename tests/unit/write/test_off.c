/* SPDX-License-Identifier: GPL-3.0-or-later */
/* OFF writer: read back with the test's own parser (strtod), every double
 * must come back bit for bit, faces in the mesh's (counter-clockwise)
 * order, comments carrying units and part ranges. */
#define _XOPEN_SOURCE 700
#include <float.h>

#include "io_test_util.h"

static char *write_off(const coons_mesh *m, const coons_write_options *o)
{
    char dir[64], path[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/m.off", dir);
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_write(m, path, COONS_FORMAT_AUTO, o, &e), &e);
    char *d = io_read_file(path, NULL);
    assert_non_null(d);
    io_rmdir(dir);
    return d;
}

static void assert_same_mesh(const coons_mesh *m, const io_off *o)
{
    assert_int_equal(o->nv, coons_mesh_vertex_count(m));
    assert_int_equal(o->nf, coons_mesh_triangle_count(m));
    const double *xyz = coons_mesh_vertices(m);
    for (size_t i = 0; i < 3 * o->nv; i++)
        if (memcmp(&o->v[i], &xyz[i], sizeof(double)) != 0)
            fail_msg("coordinate %zu: wrote %a, read %a", i, xyz[i], o->v[i]);
    assert_memory_equal(o->f, coons_mesh_triangles(m), 3 * o->nf * sizeof(uint32_t));
}

/* Given vertices with awkward values (0.1, 1e-300, -0, 2^53+1 and 2^53+2,
 * subnormals, DBL_MAX, 1/3) and 90000 random doubles, when written
 * as OFF and read back with strtod, then every coordinate has the same
 * bits. */
static void test_exact_round_trip(void **state)
{
    (void)state;
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    double v[] = {0.1,        1e-300,       -0.0,          9007199254740993.0,
                  9007199254740994.0, 4.9406564584124654e-324, 2.2250738585072009e-308,
                  -DBL_MAX,   DBL_MIN,      1.0 / 3.0,     -2.5e-320, 1e22, 1e23, 0.0,
                  123456789012345678.0, -7e-7, 0.30000000000000004, 5e-324 * 7};
    size_t nv = sizeof v / sizeof v[0] / 3;
    uint32_t t[] = {0, 1, 2, 3, 4, 5};
    assert_coons_ok(coons_mesh_add_part(m, "awkward", v, nv, t, 2, &e), &e);
    /* Random bit patterns, all finite. */
    enum { NR = 30000 };
    double *r = malloc(3 * NR * sizeof *r);
    uint64_t x = 0x9e3779b97f4a7c15ull;
    for (size_t i = 0; i < 3 * NR;) {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        double d;
        uint64_t u = (i % 4 == 0) ? x >> (x % 64) : x;
        memcpy(&d, &u, sizeof d);
        if (isfinite(d)) r[i++] = d;
    }
    uint32_t rt[3] = {0, 1, 2};
    assert_coons_ok(coons_mesh_add_part(m, "random", r, NR, rt, 1, &e), &e);
    free(r);
    char *text = write_off(m, NULL);
    io_off o;
    io_parse_off(text, &o);
    assert_same_mesh(m, &o);
    /* -0 keeps its sign. */
    assert_true(signbit(o.v[2]));
    io_off_free(&o);
    free(text);
    coons_mesh_free(m);
}

/* Given a two-part mesh with units, when written, then the file starts
 * with "OFF", faces keep the mesh's order, and comments give the units
 * and each part's name and ranges. */
static void test_layout_and_comments(void **state)
{
    (void)state;
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 2, 3};
    io_box(m, "left wing", lo, hi);
    const double sh[3] = {5, 0, 0};
    io_torus(m, "ring", 2, 0.5, 16, 8, sh);
    coons_write_options wo = COONS_WRITE_OPTIONS_INIT;
    wo.units = "mm";
    char *text = write_off(m, &wo);
    assert_int_equal(strncmp(text, "OFF\n", 4), 0);
    io_off o;
    io_parse_off(text, &o);
    assert_same_mesh(m, &o);
    assert_non_null(strstr(o.comments, "# units: mm\n"));
    assert_non_null(strstr(o.comments, "part 0: vertices 0+8, faces 0+12, name: left wing\n"));
    assert_non_null(strstr(o.comments, "part 1: vertices 8+128, faces 12+256, name: ring\n"));
    /* Closed and outward: volume of the read-back mesh = box + torus. */
    double vol = 0;
    for (size_t f = 0; f < o.nf; f++) {
        const double *a = o.v + 3 * o.f[3 * f], *b = o.v + 3 * o.f[3 * f + 1],
                     *c = o.v + 3 * o.f[3 * f + 2];
        vol += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
               a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    assert_near(vol / 6, coons_mesh_volume(m), 1e-9 * coons_mesh_volume(m));
    assert_true(vol > 6.0);
    io_off_free(&o);
    free(text);
    /* Without units, no units comment. */
    text = write_off(m, NULL);
    assert_null(strstr(text, "units"));
    free(text);
    coons_mesh_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exact_round_trip),
        cmocka_unit_test(test_layout_and_comments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
