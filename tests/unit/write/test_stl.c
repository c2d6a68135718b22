/* SPDX-License-Identifier: GPL-3.0-or-later */
/* STL writers, read back by the independent readers of io_test_util.h:
 * binary records are decoded byte by byte here (little-endian), ASCII is
 * tokenised and read with strtof. */
#define _XOPEN_SOURCE 700
#include "io_test_util.h"

#include "mesh_impl.h"

static coons_mesh *sample_mesh(void)
{
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    const double lo[3] = {-1.5, 0.1, 1e-3}, hi[3] = {2.25, 0.7, 1.0 / 3.0};
    io_box(m, "box", lo, hi);
    const double sh[3] = {10, -3, 0.5};
    io_torus(m, "ring", 3.0, 0.75, 24, 12, sh);
    io_tetra(m, "tet", 0.1, 1e-7, 12345.678);
    return m;
}

static unsigned char *write_bin(const coons_mesh *m, const coons_write_options *o, size_t *len)
{
    char dir[64], path[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/m.stl", dir);
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_write(m, path, COONS_FORMAT_AUTO, o, &e), &e);
    unsigned char *d = (unsigned char *)io_read_file(path, len);
    assert_non_null(d);
    io_rmdir(dir);
    return d;
}

static char *write_text(const coons_mesh *m, coons_format f, const coons_write_options *o)
{
    char dir[64], path[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/m.txt", dir);
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_write(m, path, f, o, &e), &e);
    char *d = io_read_file(path, NULL);
    assert_non_null(d);
    io_rmdir(dir);
    return d;
}

static int header_starts_with_solid(const unsigned char *h)
{
    size_t i = 0;
    while (i < 80 && (h[i] == ' ' || h[i] == '\t' || h[i] == '\n' || h[i] == '\r')) i++;
    const char *w = "solid";
    for (size_t k = 0; k < 5; k++)
        if (i + k >= 80 || (h[i + k] | 0x20) != w[k]) return 0;
    return 1;
}

/* Given a three-part mesh, when written as binary STL, then the file has
 * 84 + 50 n bytes, the triangles in the mesh's order with vertices equal to
 * the float32 roundings of the doubles, unit normals along (b-a)x(c-a),
 * and a header carrying the units. */
static void test_binary_matches_mesh(void **state)
{
    (void)state;
    coons_mesh *m = sample_mesh();
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.units = "mm";
    size_t len;
    unsigned char *d = write_bin(m, &o, &len);
    float *t = NULL;
    long n = io_parse_stl_binary(d, len, &t);
    assert_int_equal(n, (long)coons_mesh_triangle_count(m));
    assert_false(header_starts_with_solid(d));
    char header[81];
    memcpy(header, d, 80);
    header[80] = '\0';
    assert_non_null(strstr(header, "libcoons"));
    assert_non_null(strstr(header, "units=mm"));
    const double *xyz = coons_mesh_vertices(m);
    const uint32_t *tri = coons_mesh_triangles(m);
    for (long i = 0; i < n; i++) {
        const double *p[3];
        for (int k = 0; k < 3; k++) {
            p[k] = xyz + 3 * tri[3 * i + k];
            for (int c = 0; c < 3; c++) {
                float want = (float)p[k][c];
                assert_memory_equal(&t[12 * i + 3 + 3 * k + c], &want, sizeof want);
            }
        }
        double e1[3], e2[3], nrm[3];
        for (int c = 0; c < 3; c++) {
            e1[c] = p[1][c] - p[0][c];
            e2[c] = p[2][c] - p[0][c];
        }
        nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
        nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
        nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double len_n = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        const float *f = t + 12 * i;
        assert_near(sqrt((double)f[0] * f[0] + (double)f[1] * f[1] + (double)f[2] * f[2]), 1.0,
                    1e-6);
        assert_near((f[0] * nrm[0] + f[1] * nrm[1] + f[2] * nrm[2]) / len_n, 1.0, 1e-6);
    }
    /* Outward: the soup encloses the mesh's positive volume. */
    assert_near(io_soup_volume(t, n), coons_mesh_volume(m), 1e-4 * coons_mesh_volume(m));
    free(t);
    free(d);
    coons_mesh_free(m);
}

/* Given header texts that start with "solid" in any case or after blanks,
 * when written, then the header does not start with "solid" and still
 * ends with the units, and a long text is cut to leave them whole. */
static void test_header_never_solid(void **state)
{
    (void)state;
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    io_tetra(m, "t", 1, 2, 3);
    char longtext[300];
    memset(longtext, 'x', sizeof longtext - 1);
    longtext[sizeof longtext - 1] = '\0';
    const char *texts[] = {"solid", "SOLID part", "  solid x", "\tSoLiD\n", "solidarity", "",
                           "no solid here", longtext};
    for (size_t i = 0; i < sizeof texts / sizeof texts[0]; i++) {
        coons_write_options o = COONS_WRITE_OPTIONS_INIT;
        o.header = texts[i];
        o.units = "inch";
        size_t len;
        unsigned char *d = write_bin(m, &o, &len);
        assert_int_equal(len, 84 + 4 * 50);
        if (header_starts_with_solid(d)) fail_msg("header for '%s' starts with solid", texts[i]);
        char header[81];
        memcpy(header, d, 80);
        header[80] = '\0';
        assert_non_null(strstr(header, "units=inch"));
        for (size_t k = 0; k < 80 && header[k]; k++) assert_true(header[k] >= 0x20);
        free(d);
    }
    coons_mesh_free(m);
}

/* Given a mesh, when written as ASCII STL and as binary STL, then the
 * ASCII text parses (strtof) to exactly the binary file's floats, with
 * the sanitised solid name on both the solid and endsolid lines. */
static void test_ascii_matches_binary(void **state)
{
    (void)state;
    coons_mesh *m = sample_mesh();
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.name = "my part\n2";
    size_t len;
    unsigned char *d = write_bin(m, &o, &len);
    float *tb = NULL, *ta = NULL;
    long nb = io_parse_stl_binary(d, len, &tb);
    char *text = write_text(m, COONS_FORMAT_STL_ASCII, &o), *name;
    long na = io_parse_stl_ascii(text, &ta, &name);
    assert_int_equal(na, nb);
    assert_string_equal(name, "my_part_2");
    assert_memory_equal(ta, tb, (size_t)na * 12 * sizeof(float));
    free(name);
    free(ta);
    free(text);
    o.name = NULL;
    text = write_text(m, COONS_FORMAT_STL_ASCII, &o);
    na = io_parse_stl_ascii(text, &ta, &name);
    assert_string_equal(name, "coons_model");
    assert_memory_equal(ta, tb, (size_t)na * 12 * sizeof(float));
    assert_int_equal(strncmp(text, "solid coons_model\n", 18), 0);
    free(name);
    free(ta);
    free(text);
    free(tb);
    free(d);
    coons_mesh_free(m);
}

/* An empty mesh gives an 84-byte binary file and an empty solid. */
static void test_empty(void **state)
{
    (void)state;
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    size_t len;
    unsigned char *d = write_bin(m, NULL, &len);
    assert_int_equal(len, 84);
    assert_int_equal(d[80] | d[81] | d[82] | d[83], 0);
    free(d);
    char *text = write_text(m, COONS_FORMAT_STL_ASCII, NULL);
    assert_string_equal(text, "solid coons_model\nendsolid coons_model\n");
    free(text);
    coons_mesh_free(m);
}

/* Given a mesh record claiming 2^32 triangles, when written as binary STL,
 * then COONS_E_LIMIT comes back before anything is read or created. Only
 * where size_t can hold 2^32 (elsewhere the limit cannot be reached). */
#if SIZE_MAX > UINT32_MAX
static void test_triangle_limit(void **state)
{
    (void)state;
    struct coons_mesh fake;
    memset(&fake, 0, sizeof fake);
    fake.nt = (size_t)UINT32_MAX + 1;
    char dir[64], path[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/big.stl", dir);
    coons_error e = COONS_ERROR_INIT;
    assert_int_equal(coons_mesh_write(&fake, path, COONS_FORMAT_AUTO, NULL, &e), COONS_E_LIMIT);
    assert_int_equal(e.code, COONS_E_LIMIT);
    assert_int_equal(coons_mesh_write_stream(&fake, stdout, COONS_FORMAT_STL_BINARY, NULL, &e),
                     COONS_E_LIMIT);
    assert_int_equal(io_dir_count(dir), 0);
    io_rmdir(dir);
}

#endif

/* The same mesh always gives the same bytes. */
static void test_deterministic(void **state)
{
    (void)state;
    coons_mesh *m = sample_mesh();
    size_t l1, l2;
    unsigned char *a = write_bin(m, NULL, &l1), *b = write_bin(m, NULL, &l2);
    assert_int_equal(l1, l2);
    assert_memory_equal(a, b, l1);
    free(a);
    free(b);
    char *x = write_text(m, COONS_FORMAT_STL_ASCII, NULL),
         *y = write_text(m, COONS_FORMAT_STL_ASCII, NULL);
    assert_string_equal(x, y);
    free(x);
    free(y);
    coons_mesh_free(m);
}

/* The facet normal is the one of the stored float32 vertices: a thin
 * triangle near x = 1000, where float32's step is 6.1e-5, whose vertex
 * x = 1000.00003 rounds to 1000, turns by about 17 degrees. Binary and
 * ASCII alike (the writers share the normal). */
static void test_normal_of_float_vertices(void **state)
{
    (void)state;
    const double xyz[9] = {1000, 0, 0, 1000.00003, 1e-4, 0, 1000, 0, 1e-4};
    const uint32_t tri[3] = {0, 1, 2};
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    assert_coons_ok(coons_mesh_add_part(m, "thin", xyz, 3, tri, 1, &e), &e);
    size_t len;
    unsigned char *d = write_bin(m, NULL, &len);
    float *t = NULL, *ta = NULL;
    assert_int_equal(io_parse_stl_binary(d, len, &t), 1);
    char *text = write_text(m, COONS_FORMAT_STL_ASCII, NULL), *name;
    assert_int_equal(io_parse_stl_ascii(text, &ta, &name), 1);
    for (int pass = 0; pass < 2; pass++) {
        const float *f = pass ? ta : t;
        /* the normal of the stored vertices, in double */
        double e1[3], e2[3], n[3], nd[3];
        for (int c = 0; c < 3; c++) {
            e1[c] = (double)f[6 + c] - f[3 + c];
            e2[c] = (double)f[9 + c] - f[3 + c];
        }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double ln = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int c = 0; c < 3; c++) assert_near(f[c], n[c] / ln, 1e-6);
        /* ... which is not the double vertices' (so this test can fail) */
        for (int c = 0; c < 3; c++) {
            e1[c] = xyz[3 + c] - xyz[c];
            e2[c] = xyz[6 + c] - xyz[c];
        }
        nd[0] = e1[1] * e2[2] - e1[2] * e2[1];
        nd[1] = e1[2] * e2[0] - e1[0] * e2[2];
        nd[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double lnd = sqrt(nd[0] * nd[0] + nd[1] * nd[1] + nd[2] * nd[2]);
        double cosang = (f[0] * nd[0] + f[1] * nd[1] + f[2] * nd[2]) / lnd;
        assert_true(cosang < cos(10 * 3.14159265358979 / 180));
    }
    free(t);
    free(ta);
    free(name);
    free(text);
    free(d);
    coons_mesh_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_binary_matches_mesh), cmocka_unit_test(test_header_never_solid),
        cmocka_unit_test(test_ascii_matches_binary), cmocka_unit_test(test_empty),
#if SIZE_MAX > UINT32_MAX
        cmocka_unit_test(test_triangle_limit),
#endif
        cmocka_unit_test(test_deterministic),
        cmocka_unit_test(test_normal_of_float_vertices),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
