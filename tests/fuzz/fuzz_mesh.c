/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Fuzz target: the mesh reader of --deform (binary and ASCII STL, OFF) from
 * a memory buffer, then what it read deformed through a fixed curved body.
 *
 * What must hold, whatever the bytes:
 *  - a mesh or an error with a message that names the input ("fuzz: byte
 *    N" or "fuzz:LINE:COL"); nothing crashes, leaks or allocates without
 *    bound;
 *  - a mesh read has finite coordinates, indices below its vertex count
 *    and no triangle with two equal corners (the reader welds and drops
 *    them);
 *  - its deformation succeeds or hits the triangle limit, and a closed
 *    input stays closed, unless two of its triangles have the same three
 *    corners (a doubled sheet: splitting an edge of one makes the new
 *    inner edge a fourth-face edge; tests/fuzz/mesh/doubled-triangle.off);
 *  - with the k-th allocation of the read failed (k from the input's hash)
 *    the read reports COONS_E_NOMEM and frees everything.
 *
 * Built with libFuzzer by `tools/fuzz.sh mesh` and, with replay_main.c, as
 * the regression test over tests/fuzz/mesh/.
 */
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <coons.h>

#include "fuzz_alloc.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define CHECK(cond, ...)                                               \
    do {                                                               \
        if (!(cond)) {                                                 \
            fprintf(stderr, "fuzz_mesh: check failed: %s: ", #cond);   \
            fprintf(stderr, __VA_ARGS__);                              \
            fputc('\n', stderr);                                       \
            abort();                                                   \
        }                                                              \
    } while (0)

/* A body 0 whose blends are cubic and whose corners are not an affine
 * image of the cube: the deformation must split triangles. */
static coons_body *curved_body(void)
{
    static const double c[24] = {0, 0, 0,   0, 0, 1,   0, 1.3, 0,   0.2, 1, 1.4,
                                 1, 0, 0.3, 1.5, 0, 1, 1, 1, 0,     1.2, 1.1, 1};
    coons_body *b = NULL;
    coons_error err = COONS_ERROR_INIT;
    CHECK(coons_body_new_body0(c, COONS_BLEND_CUBIC, &b, &err) == COONS_OK, "body: %s",
          err.message);
    return b;
}

static int cmp3(const void *x, const void *y)
{
    const uint32_t *a = x, *b = y;
    for (int k = 0; k < 3; k++)
        if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
    return 0;
}

/* Do two triangles have the same three corners (in any order)? */
static int doubled(const coons_mesh *m)
{
    size_t nt = coons_mesh_triangle_count(m);
    const uint32_t *t = coons_mesh_triangles(m);
    uint32_t *s = malloc((nt ? nt : 1) * 3 * sizeof *s);
    CHECK(s != NULL, "out of memory");
    for (size_t i = 0; i < nt; i++) {
        uint32_t a = t[3 * i], b = t[3 * i + 1], c = t[3 * i + 2], x;
        if (a > b) x = a, a = b, b = x;
        if (b > c) x = b, b = c, c = x;
        if (a > b) x = a, a = b, b = x;
        s[3 * i] = a, s[3 * i + 1] = b, s[3 * i + 2] = c;
    }
    qsort(s, nt, 3 * sizeof *s, cmp3);
    int dup = 0;
    for (size_t i = 1; i < nt && !dup; i++) dup = cmp3(s + 3 * (i - 1), s + 3 * i) == 0;
    free(s);
    return dup;
}

static void check_mesh(const coons_mesh *m)
{
    size_t nv = coons_mesh_vertex_count(m), nt = coons_mesh_triangle_count(m);
    const double *v = coons_mesh_vertices(m);
    const uint32_t *t = coons_mesh_triangles(m);
    for (size_t i = 0; i < 3 * nv; i++) CHECK(isfinite(v[i]), "vertex coordinate %zu: %g", i, v[i]);
    for (size_t i = 0; i < nt; i++) {
        const uint32_t *f = t + 3 * i;
        CHECK(f[0] < nv && f[1] < nv && f[2] < nv, "triangle %zu: index beyond %zu", i, nv);
        CHECK(f[0] != f[1] && f[1] != f[2] && f[0] != f[2], "triangle %zu repeats a corner", i);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int installed;
    if (!installed) {
        coons_set_allocator(f_malloc, f_realloc, f_free);
        installed = 1;
    }
    coons_mesh_read_options o = COONS_MESH_READ_OPTIONS_INIT;
    o.max_bytes = 1 << 20;
    o.max_triangles = 1 << 14;

    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    alloc_reset(-1);
    coons_status rc = coons_mesh_read_memory(data, size, "fuzz", &o, &m, &err);
    if (rc != COONS_OK) {
        CHECK(m == NULL, "error %d but a mesh", rc);
        CHECK(err.message[0] != '\0', "error %d without a message", rc);
        CHECK(strncmp(err.message, "fuzz", 4) == 0 || rc == COONS_E_NOMEM,
              "message does not name the input: %s", err.message);
        CHECK(rc == COONS_E_PARSE || rc == COONS_E_INVALID || rc == COONS_E_LIMIT ||
                  rc == COONS_E_UNSUPPORTED,
              "unexpected status %d: %s", rc, err.message);
    } else {
        CHECK(m != NULL, "COONS_OK without a mesh");
        check_mesh(m);
        coons_mesh_report rep = COONS_MESH_REPORT_INIT;
        coons_error e2 = COONS_ERROR_INIT;
        CHECK(coons_mesh_check(m, &rep, &e2) == COONS_OK, "mesh check: %s", e2.message);
        if (coons_mesh_triangle_count(m) > 0) {
            coons_body *b = curved_body();
            coons_mesh *d = NULL;
            double lo[3], hi[3];
            const double *v = coons_mesh_vertices(m);
            size_t nv = coons_mesh_vertex_count(m);
            for (int k = 0; k < 3; k++) lo[k] = hi[k] = v[k];
            for (size_t i = 1; i < nv; i++)
                for (int k = 0; k < 3; k++) {
                    if (v[3 * i + k] < lo[k]) lo[k] = v[3 * i + k];
                    if (v[3 * i + k] > hi[k]) hi[k] = v[3 * i + k];
                }
            int flat = 0;
            for (int k = 0; k < 3; k++) flat |= !(hi[k] - lo[k] > 1e-300 * (1 + fabs(hi[k])));
            coons_status rd = coons_body_deform_mesh(b, m, NULL, NULL, 0.05, 1 << 15, &d, &e2);
            CHECK(rd == COONS_OK || rd == COONS_E_LIMIT || (flat && rd == COONS_E_INVALID),
                  "deform: %d %s", rd, e2.message);
            if (rd == COONS_OK) {
                check_mesh(d);
                coons_mesh_report r2 = COONS_MESH_REPORT_INIT;
                CHECK(coons_mesh_check(d, &r2, &e2) == COONS_OK, "check: %s", e2.message);
                CHECK(!rep.closed || doubled(m) || r2.closed,
                      "a closed input deformed into an open mesh");
            } else {
                CHECK(d == NULL, "deform error %d but a mesh", rd);
            }
            coons_mesh_free(d);
            coons_body_free(b);
        }
        coons_mesh_free(m);
    }
    CHECK(g_live == 0, "%ld blocks live after the read", g_live);

    /* Count the read's allocations, then fail one of them. */
    alloc_reset(LONG_MAX);
    m = NULL;
    coons_status rc2 = coons_mesh_read_memory(data, size, "fuzz", &o, &m, &err);
    CHECK(rc2 == rc, "second read gave %d, first %d", rc2, rc);
    coons_mesh_free(m);
    long total = g_count;
    if (total > 0) {
        long k = (long)(fnv1a(data, size) % (uint64_t)total);
        coons_error e3 = COONS_ERROR_INIT;
        alloc_reset(k);
        m = NULL;
        coons_status rc3 = coons_mesh_read_memory(data, size, "fuzz", &o, &m, &e3);
        CHECK(rc3 == COONS_E_NOMEM, "allocation %ld of %ld failed, read returned %d: %s", k,
              total, rc3, e3.message);
        CHECK(m == NULL, "a mesh despite a failed allocation");
        CHECK(g_live == 0, "%ld blocks leaked after allocation %ld failed", g_live, k);
    }
    alloc_reset(-1);
    return 0;
}
