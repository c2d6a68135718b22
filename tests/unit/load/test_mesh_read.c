/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The mesh reader (src/io/read/mesh_read.c). Every input is built here byte
 * by byte: a tetrahedron as binary STL (also with a header starting
 * "solid"), ASCII STL and OFF must give 4 welded vertices, 4 triangles, the
 * volume 1/6 and the input's winding; every error names the byte offset
 * (binary) or line:column (text) counted by hand below; limits are refused
 * before anything is allocated from a count; every allocation failing in
 * turn gives COONS_E_NOMEM with nothing leaked.
 */
#define _XOPEN_SOURCE 700
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test_util.h"

/* The tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1), outward. */
static const double TV[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
static const int TT[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

static void put32(unsigned char *p, uint32_t u)
{
    p[0] = (unsigned char)u, p[1] = (unsigned char)(u >> 8), p[2] = (unsigned char)(u >> 16),
    p[3] = (unsigned char)(u >> 24);
}

static void putf(unsigned char *p, float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    put32(p, u);
}

/* Binary STL of the tetrahedron: 84 + 4 * 50 = 284 bytes. */
static size_t binary_tet(unsigned char *b, const char *header)
{
    memset(b, 0, 284);
    memcpy(b, header, strlen(header));
    put32(b + 80, 4);
    for (int t = 0; t < 4; t++)
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++)
                putf(b + 84 + 50 * t + 12 + 12 * v + 4 * k, (float)TV[TT[t][v]][k]);
    return 284;
}

static void check_tet(const coons_mesh *m)
{
    assert_int_equal(coons_mesh_vertex_count(m), 4);
    assert_int_equal(coons_mesh_triangle_count(m), 4);
    assert_near(coons_mesh_volume(m), 1.0 / 6, 1e-15);
    /* each triangle's corners are the input's, in its order */
    const double *x = coons_mesh_vertices(m);
    const uint32_t *t = coons_mesh_triangles(m);
    for (int i = 0; i < 4; i++)
        for (int v = 0; v < 3; v++) assert_vec3_near(x + 3 * t[3 * i + v], TV[TT[i][v]], 0);
}

static coons_status read_mem(const void *d, size_t n, const char *name, size_t max_tri,
                             coons_mesh **m, coons_error *err)
{
    coons_mesh_read_options o = COONS_MESH_READ_OPTIONS_INIT;
    o.max_triangles = max_tri;
    return coons_mesh_read_memory(d, n, name, &o, m, err);
}

/* Reading fails with `code` and a message holding `want`. */
static void fails(const void *d, size_t n, const char *name, size_t max_tri, coons_status code,
                  const char *want)
{
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *m = (coons_mesh *)&err; /* must become NULL */
    coons_status rc = read_mem(d, n, name, max_tri, &m, &err);
    if (rc != code || !strstr(err.message, want))
        fail_msg("%s: status %d (expected %d), message '%s', expected '%s'", name, rc, code,
                 err.message, want);
    assert_null(m);
    assert_string_equal(err.file, name);
}

static void test_binary(void **state)
{
    (void)state;
    unsigned char b[400];
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *m = NULL;
    size_t n = binary_tet(b, "tetrahedron");
    assert_coons_ok(read_mem(b, n, "tet.stl", 0, &m, &err), &err);
    check_tet(m);
    assert_string_equal(coons_mesh_part_name(m, 0), "tet");
    coons_mesh_free(m);
    /* a header that starts like ASCII: the size decides */
    n = binary_tet(b, "solid tetrahedron");
    assert_coons_ok(read_mem(b, n, "tet.stl", 0, &m, &err), &err);
    check_tet(m);
    coons_mesh_free(m);
    /* -0 welds with 0, and a degenerate triangle is dropped */
    n = binary_tet(b, "x");
    putf(b + 84 + 12, -0.0f);
    assert_coons_ok(read_mem(b, n, "tet.stl", 0, &m, &err), &err);
    check_tet(m);
    coons_mesh_free(m);
    put32(b + 80, 5);
    memcpy(b + 284, b + 84, 50);
    for (int k = 0; k < 3; k++) putf(b + 284 + 24 + 4 * k, (float)TV[0][k]); /* corner 1 = 0 */
    assert_coons_ok(read_mem(b, 334, "tet.stl", 0, &m, &err), &err);
    check_tet(m);
    coons_mesh_free(m);
}

/* A binary STL of the n x n grid of unit squares in z = 0 (two triangles
 * each), written with -0 for the zeros of every other triangle; with
 * `soup`, every triangle moved by its index along z, so no corner is shared. */
static unsigned char *grid_stl(int n, int soup, size_t *size)
{
    size_t count = 2 * (size_t)n * (size_t)n;
    *size = 84 + 50 * count;
    unsigned char *b = calloc(1, *size);
    assert_non_null(b);
    put32(b + 80, (uint32_t)count);
    size_t t = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            for (int h = 0; h < 2; h++, t++) {
                const int c[2][3][2] = {{{0, 0}, {1, 0}, {1, 1}}, {{0, 0}, {1, 1}, {0, 1}}};
                for (int v = 0; v < 3; v++) {
                    float x = (float)(i + c[h][v][0]), y = (float)(j + c[h][v][1]);
                    float z = soup ? (float)t : 0.0f;
                    if (t % 2) { /* -0 for the zeros */
                        if (x == 0) x = -0.0f;
                        if (y == 0) y = -0.0f;
                        if (z == 0) z = -0.0f;
                    }
                    unsigned char *p = b + 84 + 50 * t + 12 + 12 * (size_t)v;
                    putf(p, x), putf(p + 4, y), putf(p + 8, z);
                }
            }
    return b;
}

/* Large binary files (the welding table is sized from the count, filled
 * past half and grown): (n + 1)^2 welded vertices for the grid, 3 per
 * triangle for the soup; every triangle's corners are the input's, and the
 * vertices are numbered in the order they first appear. */
static void test_binary_large(void **state)
{
    (void)state;
    for (int soup = 0; soup < 2; soup++) {
        int n = soup ? 25 : 40;
        size_t size, count = 2 * (size_t)n * (size_t)n;
        unsigned char *b = grid_stl(n, soup, &size);
        coons_error err = COONS_ERROR_INIT;
        coons_mesh *m = NULL;
        assert_coons_ok(read_mem(b, size, "grid.stl", 0, &m, &err), &err);
        assert_int_equal(coons_mesh_vertex_count(m),
                         soup ? 3 * count : (size_t)(n + 1) * (size_t)(n + 1));
        assert_int_equal(coons_mesh_triangle_count(m), count);
        const double *x = coons_mesh_vertices(m);
        const uint32_t *tri = coons_mesh_triangles(m);
        uint32_t next = 0;
        for (size_t t = 0; t < count; t++)
            for (int v = 0; v < 3; v++) {
                uint32_t id = tri[3 * t + v];
                assert_true(id <= next);
                if (id == next) next++;
                for (int k = 0; k < 3; k++) {
                    uint32_t u = (uint32_t)b[84 + 50 * t + 12 + 12 * v + 4 * k] |
                                 (uint32_t)b[85 + 50 * t + 12 + 12 * v + 4 * k] << 8 |
                                 (uint32_t)b[86 + 50 * t + 12 + 12 * v + 4 * k] << 16 |
                                 (uint32_t)b[87 + 50 * t + 12 + 12 * v + 4 * k] << 24;
                    float f;
                    memcpy(&f, &u, sizeof f);
                    assert_true(x[3 * id + k] == (double)f);
                }
            }
        coons_mesh_free(m);
        if (!soup) {
            /* triangle 1500, corner 2, z (past the first blocks):
             * 84 + 1500 * 50 + 12 + 24 + 8 = 75128 */
            putf(b + 75128, INFINITY);
            fails(b, size, "grid.stl", 0, COONS_E_PARSE,
                  "grid.stl: byte 75128: triangle 1500, corner 2: z = inf");
        }
        free(b);
    }
}

static void test_binary_errors(void **state)
{
    (void)state;
    unsigned char b[400];
    size_t n = binary_tet(b, "tet");
    /* the file ends inside triangle 3 (bytes 234..283) */
    fails(b, 274, "cut.stl", 0, COONS_E_PARSE, "cut.stl: byte 274: truncated");
    fails(b, 274, "cut.stl", 0, COONS_E_PARSE, "inside triangle 3");
    /* 7 bytes too many */
    fails(b, n + 7, "long.stl", 0, COONS_E_PARSE, "long.stl: byte 80: the triangle count 4 "
                                                    "disagrees with the file size");
    /* shorter than the header */
    fails(b, 40, "tiny.stl", 0, COONS_E_PARSE, "tiny.stl: byte 40: truncated");
    /* triangle 2, corner 1, y: 84 + 2 * 50 + 12 (normal) + 12 + 4 = 212 */
    putf(b + 212, NAN);
    fails(b, n, "nan.stl", 0, COONS_E_PARSE, "nan.stl: byte 212: triangle 2, corner 1: y = nan");
    putf(b + 212, -INFINITY);
    fails(b, n, "inf.stl", 0, COONS_E_PARSE, "inf.stl: byte 212: triangle 2, corner 1: y = -inf");
    /* limits: the count, then the bytes */
    n = binary_tet(b, "tet");
    fails(b, n, "big.stl", 3, COONS_E_LIMIT, "big.stl: byte 80: 4 triangles, more than the limit "
                                             "of 3 triangles");
    coons_mesh_read_options o = COONS_MESH_READ_OPTIONS_INIT;
    o.max_bytes = 200;
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *m = NULL;
    assert_int_equal(coons_mesh_read_memory(b, n, "x.stl", &o, &m, &err), COONS_E_LIMIT);
    assert_non_null(strstr(err.message, "284 bytes, above the limit of 200 bytes"));
    /* a huge count in a short file is a disagreement, nothing allocated */
    put32(b + 80, 0xffffffffu);
    coons_test_fail_after(0);
    fails(b, n, "huge.stl", 0, COONS_E_PARSE, "huge.stl: byte 284: truncated: the header (byte "
                                              "80) counts 4294967295 triangles");
    coons_test_fail_after(-1);
}

static const char ASCII_TET[] =
    "solid tet\n"                                      /* 1 */
    "  facet normal 0 0 -1\n"                          /* 2 */
    "    outer loop\n"                                 /* 3 */
    "      vertex 0 0 0\n"                             /* 4 */
    "      vertex 0 1 0\n"                             /* 5 */
    "      vertex 1 0 0\n"                             /* 6 */
    "    endloop\n"                                    /* 7 */
    "  endfacet\n"                                     /* 8 */
    "  FACET NORMAL 0 -1 0 OUTER LOOP\n"               /* 9: upper case, one line */
    "    VERTEX 0 0 0 VERTEX 1e0 0 0 VERTEX 0 0 1\n"   /* 10 */
    "  ENDLOOP ENDFACET\n"                             /* 11 */
    "endsolid tet\n"                                   /* 12 */
    "solid second\r\n"                                 /* 13: a second solid, CRLF */
    "facet normal -1 0 0\r\n outer loop\r\n"           /* 14, 15 */
    "vertex 0 0 0\r\nvertex 0 0 1\r\nvertex 0 1 0\r\n" /* 16-18 */
    "endloop\r\nendfacet\r\n"                          /* 19, 20 */
    "facet normal 1 1 1\n outer loop\n"                /* 21, 22 */
    "vertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\n"       /* 23-25 */
    "endloop\nendfacet\nendsolid\n";                   /* 26-28 */

static void test_ascii(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *m = NULL;
    assert_coons_ok(read_mem(ASCII_TET, strlen(ASCII_TET), "tet.stl", 0, &m, &err), &err);
    check_tet(m);
    coons_mesh_free(m);
    /* an empty solid is an empty mesh */
    const char *empty = "solid nothing\nendsolid nothing\n";
    assert_coons_ok(read_mem(empty, strlen(empty), "e.stl", 0, &m, &err), &err);
    assert_int_equal(coons_mesh_triangle_count(m), 0);
    coons_mesh_free(m);
}

/* ASCII_TET with `from` (first occurrence) replaced by `to`. */
static char *ascii_with(const char *from, const char *to)
{
    const char *at = strstr(ASCII_TET, from);
    assert_non_null(at);
    size_t pre = (size_t)(at - ASCII_TET), n = strlen(ASCII_TET) - strlen(from) + strlen(to);
    char *s = malloc(n + 1);
    memcpy(s, ASCII_TET, pre);
    strcpy(s + pre, to);
    strcat(s, at + strlen(from));
    return s;
}

static void ascii_fails(const char *from, const char *to, size_t max_tri, coons_status code,
                        const char *want, int line, int col)
{
    char *s = ascii_with(from, to);
    fails(s, strlen(s), "a.stl", max_tri, code, want);
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *m = NULL;
    read_mem(s, strlen(s), "a.stl", max_tri, &m, &err);
    assert_int_equal(err.line, line);
    assert_int_equal(err.column, col);
    free(s);
}

static void test_ascii_errors(void **state)
{
    (void)state;
    /* line 5 "      vertex 0 x 0": x at column 16 */
    ascii_fails("vertex 0 1 0\n", "vertex 0 x 0\n", 0, COONS_E_PARSE,
                "a.stl:5:16: expected a number (y), found 'x'", 5, 16);
    /* line 6 "      vertex 1 0 nan": nan at column 18 */
    ascii_fails("vertex 1 0 0\n", "vertex 1 0 nan\n", 0, COONS_E_PARSE,
                "a.stl:6:18: z = nan is not a finite number", 6, 18);
    ascii_fails("vertex 1 0 0\n", "vertex 1 0 -inf\n", 0, COONS_E_PARSE,
                "a.stl:6:18: z = -inf is not a finite number", 6, 18);
    /* line 7 "    endlop": column 5 */
    ascii_fails("    endloop\n", "    endlop\n", 0, COONS_E_PARSE,
                "a.stl:7:5: expected 'endloop', found 'endlop'", 7, 5);
    /* a fourth vertex: line 6 ends, "vertex" on line 7 at column 5 */
    ascii_fails("    endloop\n", "    vertex 1 1 1\n", 0, COONS_E_PARSE,
                "a.stl:7:5: expected 'endloop', found 'vertex'", 7, 5);
    /* cut after line 5: the end of the file at line 6, column 1 */
    char cut[200];
    const char *at = strstr(ASCII_TET, "      vertex 1 0 0");
    memcpy(cut, ASCII_TET, (size_t)(at - ASCII_TET));
    cut[at - ASCII_TET] = '\0';
    fails(cut, strlen(cut), "cut.stl", 0, COONS_E_PARSE,
          "cut.stl:6:1: expected 'vertex', found the end of the file");
    /* the third facet, the second solid's first (line 14, column 1), is one
     * too many */
    ascii_fails("endsolid tet", "endsolid tet", 2, COONS_E_LIMIT,
                "a.stl:14:1: more than the limit of 2 triangles", 14, 1);
}

static const char OFF_TET[] =
    "OFF\n"                    /* 1 */
    "# a tetrahedron\n"        /* 2 */
    "4 3 0\n"                  /* 3 */
    "0 0 0\n"                  /* 4 */
    "1 0 0\n"                  /* 5 */
    "0 1 0\n"                  /* 6 */
    "0 0 1   # the apex\n"     /* 7 */
    "3 0 2 1\n"                /* 8 */
    "4 0 1 3 3 255 0 0\n"      /* 9: 0 1 3 and the degenerate 0 3 3, then a colour */
    "\n"                       /* 10 */
    "5 0 3 2 2 2\n"            /* 11: 0 3 2, then 0 2 2 and 0 2 2 dropped */
    "# the writer's comments\n";

static void test_off(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *m = NULL;
    assert_coons_ok(read_mem(OFF_TET, strlen(OFF_TET), "tet.off", 0, &m, &err), &err);
    assert_int_equal(coons_mesh_vertex_count(m), 4);
    assert_int_equal(coons_mesh_triangle_count(m), 3); /* open: the face 1 2 3 is missing */
    coons_mesh_free(m);
    /* complete it: 4 faces, the tetrahedron */
    const char *full = "OFF 4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n"
                       "3 1 2 3\n";
    assert_coons_ok(read_mem(full, strlen(full), "full.off", 0, &m, &err), &err);
    check_tet(m);
    coons_mesh_free(m);
}

static void test_off_errors(void **state)
{
    (void)state;
    const char *s;
    /* face index 4 at line 8, column 7 */
    s = "OFF\n# c\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 4\n";
    fails(s, strlen(s), "i.off", 0, COONS_E_PARSE,
          "i.off:8:7: face 0: vertex index 4 is out of range (4 vertices, 0 to 3)");
    /* counts beyond the file: 1000 vertices cannot follow in the 15 bytes
     * after them (the counts line's newline, then 6 + 8) */
    s = "OFF\n1000 1 0\n0 0 0\n3 0 0 0\n";
    fails(s, strlen(s), "c.off", 0, COONS_E_PARSE,
          "c.off:2:1: truncated: 1000 vertices and 1 faces cannot fit in the 15 bytes");
    s = "OFF\n99999999999999999999 1 0\n";
    fails(s, strlen(s), "o.off", 0, COONS_E_PARSE, "o.off:2:1: expected the vertex count");
    /* a bad coordinate, line 4 column 3 */
    s = "OFF\n3 1 0\n0 0 0\n1 y 0\n0 1 0\n3 0 1 2\n";
    fails(s, strlen(s), "t.off", 0, COONS_E_PARSE, "t.off:4:3: expected a number (y), found 'y'");
    s = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 inf\n3 0 1 2\n";
    fails(s, strlen(s), "n.off", 0, COONS_E_PARSE, "n.off:5:5: z = inf is not a finite number");
    /* a face of 2 corners */
    s = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n";
    fails(s, strlen(s), "f.off", 0, COONS_E_PARSE, "f.off:6:1: a face of 2 corners");
    /* the file ends before face 2 */
    s = "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n# pad pad\n";
    fails(s, strlen(s), "e.off", 0, COONS_E_PARSE,
          "e.off:8:1: truncated: the file ends before face 2 of 2");
    /* text after the announced faces */
    s = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n";
    fails(s, strlen(s), "x.off", 0, COONS_E_PARSE,
          "x.off:7:1: unexpected '3' after the 1 faces the counts announce");
    /* more faces than the limit, refused at the counts */
    s = "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n";
    fails(s, strlen(s), "l.off", 1, COONS_E_LIMIT, "l.off:2:1: 2 faces, more than the limit of 1");
    /* a polygon fanning past the limit */
    s = "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n4 0 1 3 2\n";
    fails(s, strlen(s), "p.off", 1, COONS_E_LIMIT, "p.off:7:9: more than the limit of 1");
    /* neither format */
    s = "hello\n";
    fails(s, strlen(s), "h.txt", 0, COONS_E_PARSE, "h.txt:1:1: expected 'OFF', found 'hello'");
}

static void test_file(void **state)
{
    (void)state;
    char dir[] = "/tmp/coons_read_XXXXXX", path[64];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/part.stl", dir);
    unsigned char b[400];
    size_t n = binary_tet(b, "t");
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(b, 1, n - 1, f), n - 1); /* one byte short */
    fclose(f);
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *m = NULL;
    assert_int_equal(coons_mesh_read_file(path, NULL, &m, &err), COONS_E_PARSE);
    char want[128];
    snprintf(want, sizeof want, "%s: byte 283: truncated", path);
    assert_non_null(strstr(err.message, want));
    f = fopen(path, "wb");
    assert_int_equal(fwrite(b, 1, n, f), n);
    fclose(f);
    assert_coons_ok(coons_mesh_read_file(path, NULL, &m, &err), &err);
    check_tet(m);
    assert_string_equal(coons_mesh_part_name(m, 0), "part");
    coons_mesh_free(m);
    coons_mesh_read_options o = COONS_MESH_READ_OPTIONS_INIT;
    o.max_bytes = 100;
    assert_int_equal(coons_mesh_read_file(path, &o, &m, &err), COONS_E_LIMIT);
    assert_non_null(strstr(err.message, "284 bytes, above the limit of 100 bytes"));
    remove(path);
    assert_int_equal(coons_mesh_read_file(path, NULL, &m, &err), COONS_E_IO);
    assert_non_null(strstr(err.message, "cannot open"));
    o.version = 99;
    assert_int_equal(coons_mesh_read_memory(b, n, "v", &o, &m, &err), COONS_E_INVALID);
    rmdir(dir);
}

/* Every allocation failing in turn: COONS_E_NOMEM, nothing leaked. */
static void test_alloc_failures(void **state)
{
    (void)state;
    unsigned char b[400];
    size_t n = binary_tet(b, "t"), gn;
    /* a soup of 800 triangles: the arrays sized from the count, the
     * welding table grown */
    unsigned char *g = grid_stl(20, 1, &gn);
    const struct {
        const void *d;
        size_t n;
        const char *name;
    } in[] = {{b, n, "b.stl"}, {ASCII_TET, sizeof ASCII_TET - 1, "a.stl"},
              {OFF_TET, sizeof OFF_TET - 1, "o.off"}, {g, gn, "g.stl"}};
    for (size_t i = 0; i < 4; i++) {
        int done = 0;
        for (long k = 0; !done && k < 1000; k++) {
            coons_error err = COONS_ERROR_INIT;
            coons_mesh *m = NULL;
            coons_test_fail_after(k);
            coons_status rc = read_mem(in[i].d, in[i].n, in[i].name, 0, &m, &err);
            coons_mesh_free(m);
            assert_int_equal(coons_test_live_allocs(), 0);
            coons_test_fail_after(-1);
            if (rc == COONS_OK)
                done = 1;
            else
                assert_int_equal(rc, COONS_E_NOMEM);
        }
        assert_true(done);
    }
    free(g);
}

/* A file that is not a regular one cannot be measured first: reading stops
 * one byte past the limit (the model loader shares this reader). */
static void test_stream_limit(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *m = NULL;
    coons_mesh_read_options o = COONS_MESH_READ_OPTIONS_INIT;
    o.max_bytes = 100;
    assert_int_equal(coons_mesh_read_file("/dev/zero", &o, &m, &err), COONS_E_LIMIT);
    assert_string_equal(err.message,
                        "/dev/zero: the mesh is more than 100 bytes, the limit (max_bytes)");
    assert_string_equal(err.file, "/dev/zero");
    assert_null(m);
    coons_model_load_options lo = COONS_MODEL_LOAD_OPTIONS_INIT;
    lo.max_bytes = 100;
    coons_model *model = NULL;
    assert_int_equal(coons_model_load_file("/dev/zero", &lo, &model, &err), COONS_E_LIMIT);
    assert_string_equal(err.message, "/dev/zero: the model is more than 100 bytes, the limit "
                                     "(raise max_bytes; coons2stl --max-bytes N)");
    assert_null(model);
    assert_int_equal(coons_mesh_read_file("no-such-dir/none.stl", NULL, &m, &err), COONS_E_IO);
    assert_string_equal(err.message,
                        "no-such-dir/none.stl: cannot open the mesh: No such file or directory");
    assert_string_equal(err.file, "no-such-dir/none.stl");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_binary),     cmocka_unit_test(test_binary_large),
        cmocka_unit_test(test_binary_errors),
        cmocka_unit_test(test_ascii),      cmocka_unit_test(test_ascii_errors),
        cmocka_unit_test(test_off),        cmocka_unit_test(test_off_errors),
        cmocka_unit_test(test_file),       cmocka_unit_test(test_alloc_failures),
        cmocka_unit_test(test_stream_limit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
