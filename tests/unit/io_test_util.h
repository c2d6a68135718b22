/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Helpers of the writer tests: hand-built closed meshes and readers of the
 * written formats that share no code with the library's writers. */
#ifndef COONS_IO_TEST_UTIL_H
#define COONS_IO_TEST_UTIL_H

/* Needs POSIX: define _XOPEN_SOURCE 700 before including anything. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test_util.h"

/* ---- meshes ------------------------------------------------------------ */

/* Axis-aligned box [lo, hi], 8 vertices, 12 triangles counter-clockwise
 * seen from outside. */
static inline void io_box(coons_mesh *m, const char *name, const double lo[3], const double hi[3])
{
    double v[8][3];
    for (int i = 0; i < 8; i++) {
        v[i][0] = (i & 1) ? hi[0] : lo[0];
        v[i][1] = (i & 2) ? hi[1] : lo[1];
        v[i][2] = (i & 4) ? hi[2] : lo[2];
    }
    static const uint32_t t[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},
                                      {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},
                                      {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_add_part(m, name, &v[0][0], 8, &t[0][0], 12, &e), &e);
}

/* Tetrahedron (0,0,0), (a,0,0), (0,b,0), (0,0,c): volume abc/6. */
static inline void io_tetra(coons_mesh *m, const char *name, double a, double b, double c)
{
    double v[4][3] = {{0, 0, 0}, {a, 0, 0}, {0, b, 0}, {0, 0, c}};
    static const uint32_t t[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_add_part(m, name, &v[0][0], 4, &t[0][0], 4, &e), &e);
}

/* Torus around the z axis (radii R > r), n x k vertices, 2nk triangles,
 * outward. */
static inline void io_torus(coons_mesh *m, const char *name, double R, double r, size_t n,
                            size_t k, const double shift[3])
{
    double *v = malloc(3 * n * k * sizeof *v);
    uint32_t *t = malloc(6 * n * k * sizeof *t);
    assert_non_null(v);
    assert_non_null(t);
    const double pi = 3.14159265358979323846;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < k; j++) {
            double u = 2 * pi * (double)i / (double)n, w = 2 * pi * (double)j / (double)k;
            double *p = v + 3 * (i * k + j);
            p[0] = (R + r * cos(w)) * cos(u) + shift[0];
            p[1] = (R + r * cos(w)) * sin(u) + shift[1];
            p[2] = r * sin(w) + shift[2];
        }
    size_t q = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < k; j++) {
            uint32_t a = (uint32_t)(i * k + j), b = (uint32_t)(((i + 1) % n) * k + j),
                     c = (uint32_t)(((i + 1) % n) * k + (j + 1) % k),
                     d = (uint32_t)(i * k + (j + 1) % k);
            /* d/du x d/dw points outward for this parametrisation. */
            uint32_t tri[6] = {a, b, c, a, c, d};
            memcpy(t + 6 * q++, tri, sizeof tri);
        }
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_add_part(m, name, v, n * k, t, 2 * n * k, &e), &e);
    free(v);
    free(t);
}

/* ---- files ------------------------------------------------------------- */

static inline char *io_read_file(const char *path, size_t *len)
{
    if (len) *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap + 1);
    for (;;) {
        size_t r = fread(buf + n, 1, cap - n, f);
        n += r;
        if (n < cap) break;
        cap *= 2;
        buf = realloc(buf, cap + 1);
    }
    fclose(f);
    buf[n] = '\0';
    if (len) *len = n;
    return buf;
}

static inline void io_write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

/* A fresh directory under /tmp, and its removal with its (flat) contents. */
static inline void io_tmpdir(char *buf, size_t cap)
{
    snprintf(buf, cap, "/tmp/coons-test-XXXXXX");
    assert_non_null(mkdtemp(buf));
}

/* Number of entries of a directory (without . and ..). */
static inline int io_dir_count(const char *dir)
{
    DIR *d = opendir(dir);
    assert_non_null(d);
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
    closedir(d);
    return n;
}

static inline void io_rmdir(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *e;
    char p[4096];
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        unlink(p);
    }
    closedir(d);
    rmdir(dir);
}

/* ---- independent readers ------------------------------------------------ */

/* Binary STL: header, count, records. tri gets 12 floats per triangle
 * (normal, a, b, c). Returns the count or -1 if the size is wrong. */
static inline long io_parse_stl_binary(const unsigned char *d, size_t len, float **tri)
{
    *tri = NULL;
    if (len < 84) return -1;
    unsigned long n = (unsigned long)d[80] | (unsigned long)d[81] << 8 |
                      (unsigned long)d[82] << 16 | (unsigned long)d[83] << 24;
    if (len != 84 + 50 * (size_t)n) return -1;
    *tri = malloc((n ? n : 1) * 12 * sizeof(float));
    for (unsigned long t = 0; t < n; t++) {
        const unsigned char *r = d + 84 + 50 * t;
        for (int i = 0; i < 12; i++) {
            uint32_t u = (uint32_t)r[4 * i] | (uint32_t)r[4 * i + 1] << 8 |
                         (uint32_t)r[4 * i + 2] << 16 | (uint32_t)r[4 * i + 3] << 24;
            memcpy(&(*tri)[12 * t + (unsigned long)i], &u, 4);
        }
        if (r[48] || r[49]) return -1;
    }
    return (long)n;
}

/* Next whitespace-separated token of *s into tok; 0 at the end. */
static inline int io_token(const char **s, char *tok, size_t cap)
{
    const char *p = *s;
    while (*p == ' ' || *p == '\n' || *p == '\t' || *p == '\r') p++;
    if (!*p) return 0;
    size_t n = 0;
    while (*p && *p != ' ' && *p != '\n' && *p != '\t' && *p != '\r') {
        if (n + 1 < cap) tok[n++] = *p;
        p++;
    }
    tok[n] = '\0';
    *s = p;
    return 1;
}

/* Reads a number token that must be consumed completely. */
static inline double io_num(const char **s)
{
    char tok[64], *end;
    assert_true(io_token(s, tok, sizeof tok));
    double v = strtod(tok, &end);
    if (*end) fail_msg("not a number: '%s'", tok);
    return v;
}
static inline float io_numf(const char **s)
{
    char tok[64], *end;
    assert_true(io_token(s, tok, sizeof tok));
    float v = strtof(tok, &end);
    if (*end) fail_msg("not a number: '%s'", tok);
    return v;
}
static inline void io_expect(const char **s, const char *word)
{
    char tok[64];
    assert_true(io_token(s, tok, sizeof tok));
    assert_string_equal(tok, word);
}

/* ASCII STL: returns the facet count, 12 floats per facet; *name gets the
 * solid name (malloc'd). */
static inline long io_parse_stl_ascii(const char *text, float **tri, char **name)
{
    const char *s = text;
    char tok[256];
    io_expect(&s, "solid");
    const char *eol = strchr(s, '\n');
    assert_non_null(eol);
    *name = malloc((size_t)(eol - s) + 1);
    const char *b = s;
    while (*b == ' ') b++;
    memcpy(*name, b, (size_t)(eol - b));
    (*name)[eol - b] = '\0';
    s = eol;
    long n = 0, cap = 64;
    *tri = malloc((size_t)cap * 12 * sizeof(float));
    for (;;) {
        assert_true(io_token(&s, tok, sizeof tok));
        if (strcmp(tok, "endsolid") == 0) break;
        assert_string_equal(tok, "facet");
        io_expect(&s, "normal");
        if (n == cap) {
            cap *= 2;
            *tri = realloc(*tri, (size_t)cap * 12 * sizeof(float));
        }
        float *f = *tri + 12 * n;
        for (int i = 0; i < 3; i++) f[i] = io_numf(&s);
        io_expect(&s, "outer");
        io_expect(&s, "loop");
        for (int k = 1; k <= 3; k++) {
            io_expect(&s, "vertex");
            for (int i = 0; i < 3; i++) f[3 * k + i] = io_numf(&s);
        }
        io_expect(&s, "endloop");
        io_expect(&s, "endfacet");
        n++;
    }
    assert_true(io_token(&s, tok, sizeof tok));
    assert_string_equal(tok, *name);
    assert_false(io_token(&s, tok, sizeof tok));
    return n;
}

/* OFF with '#' comment lines anywhere. Returns 0 on success. */
typedef struct io_off {
    size_t nv, nf;
    double *v;
    uint32_t *f;
    char comments[4096];
} io_off;

static inline void io_parse_off(const char *text, io_off *o)
{
    /* Strip comments into o->comments, keep the rest. */
    size_t len = strlen(text);
    char *body = malloc(len + 1), *q = body;
    o->comments[0] = '\0';
    for (const char *p = text; *p;) {
        const char *eol = strchr(p, '\n');
        size_t l = eol ? (size_t)(eol - p) + 1 : strlen(p);
        if (*p == '#') {
            size_t have = strlen(o->comments);
            if (have + l + 1 < sizeof o->comments) {
                memcpy(o->comments + have, p, l);
                o->comments[have + l] = '\0';
            }
        } else {
            memcpy(q, p, l);
            q += l;
        }
        p += l;
    }
    *q = '\0';
    const char *s = body;
    io_expect(&s, "OFF");
    o->nv = (size_t)io_num(&s);
    o->nf = (size_t)io_num(&s);
    assert_true(io_num(&s) == 0.0);
    o->v = malloc((o->nv ? o->nv : 1) * 3 * sizeof(double));
    o->f = malloc((o->nf ? o->nf : 1) * 3 * sizeof(uint32_t));
    for (size_t i = 0; i < 3 * o->nv; i++) o->v[i] = io_num(&s);
    for (size_t i = 0; i < o->nf; i++) {
        assert_true(io_num(&s) == 3.0);
        for (int k = 0; k < 3; k++) o->f[3 * i + (size_t)k] = (uint32_t)io_num(&s);
    }
    char tok[8];
    assert_false(io_token(&s, tok, sizeof tok));
    free(body);
}

static inline void io_off_free(io_off *o)
{
    free(o->v);
    free(o->f);
}

/* Signed volume of a float triangle soup (12 floats per triangle), in
 * double, about the first vertex. */
static inline double io_soup_volume(const float *tri, long n)
{
    double v = 0, o[3] = {0, 0, 0};
    if (n > 0)
        for (int i = 0; i < 3; i++) o[i] = tri[3 + i];
    for (long t = 0; t < n; t++) {
        double a[3], b[3], c[3];
        for (int i = 0; i < 3; i++) {
            a[i] = tri[12 * t + 3 + i] - o[i];
            b[i] = tri[12 * t + 6 + i] - o[i];
            c[i] = tri[12 * t + 9 + i] - o[i];
        }
        v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return v / 6.0;
}

#endif
