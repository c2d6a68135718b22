/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Fuzz target: the model loader from a memory buffer, then whatever loads
 * is evaluated. Any byte sequence must give a model or an error with a
 * message; nothing may crash, leak, read out of bounds, overflow a signed
 * integer or a float-to-integer conversion (the sanitizers report those),
 * or allocate without bound (libFuzzer's -malloc_limit_mb).
 *
 * Each input is loaded three times:
 *  1. normally, with limits small enough that one input stays cheap;
 *  2. on success, the bodies are evaluated (points, Jacobians, a small grid,
 *     the volume to a coarse tolerance, the minimum Jacobian), sampled into
 *     meshes (a fixed coarse lattice and adaptively to a coarse tolerance,
 *     under a small triangle limit), checked, and written in every format
 *     to a memory stream; sampling is repeated with an allocation failing;
 *  3. again with an allocator that fails the k-th allocation, k chosen from
 *     the input's hash among the allocations the first load made: the load
 *     must then report COONS_E_NOMEM (or the same error as before, if the
 *     failure comes after the point where it stopped) and free everything.
 *
 * Built two ways: with clang -fsanitize=fuzzer (tools/fuzz.sh, the
 * COONS_FUZZ CMake option) and, with replay_main.c, as an ordinary program
 * that runs the files named on its command line (the regression test).
 */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <coons.h>
#include <coons/io.h>
#include <coons/volume.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* A finding that is not a crash: print and abort so that libFuzzer keeps
 * the input. (This is a test program, not the library.) */
#define CHECK(cond, ...)                                                \
    do {                                                                \
        if (!(cond)) {                                                  \
            fprintf(stderr, "fuzz_model: check failed: %s: ", #cond);  \
            fprintf(stderr, __VA_ARGS__);                               \
            fputc('\n', stderr);                                        \
            abort();                                                    \
        }                                                               \
    } while (0)

#include "fuzz_alloc.h"

/* ---- evaluation of what loaded ------------------------------------------- */

static int finite3(const double p[3])
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

/* Largest absolute control coordinate: with moderate control data the
 * points of a body are finite (they are affine or convex combinations of
 * control data for all body types except the rational ones, whose weights
 * the loader keeps positive and finite). */
static double box_extent(const coons_body *b)
{
    double lo[3], hi[3], m = 0.0;
    coons_body_control_bbox(b, lo, hi);
    for (int i = 0; i < 3; i++) {
        if (!(fabs(lo[i]) <= m)) m = fabs(lo[i]);
        if (!(fabs(hi[i]) <= m)) m = fabs(hi[i]);
    }
    return m;
}

static void exercise_body(const coons_body *b)
{
    static const double P[][3] = {{0, 0, 0},       {1, 1, 1},         {0.5, 0.5, 0.5},
                                  {0.3, 0.7, 0.1}, {1e-300, 1, 0.999}, {-1, 2, 0.5}};
    int moderate = box_extent(b) < 1e100;
    for (size_t i = 0; i < sizeof P / sizeof P[0]; i++) {
        double x[3], y[3], jac[3][3];
        coons_body_eval(b, P[i][0], P[i][1], P[i][2], x);
        double det = coons_body_eval_jacobian(b, P[i][0], P[i][1], P[i][2], y, jac);
        (void)det;
        if (moderate) {
            CHECK(finite3(x), "non-finite point (%g %g %g) at (%g %g %g)", x[0], x[1], x[2],
                  P[i][0], P[i][1], P[i][2]);
            /* Same point from both entry points, to rounding. */
            for (int c = 0; c < 3; c++)
                CHECK(fabs(x[c] - y[c]) <= 1e-9 * (1.0 + fabs(x[c])),
                      "eval and eval_jacobian disagree: %.17g vs %.17g", x[c], y[c]);
        }
    }
    /* Out-of-domain and NaN parameters must not crash (clamped or NaN out). */
    double x[3], jac[3][3];
    coons_body_eval(b, NAN, 0.5, INFINITY, x);
    (void)coons_body_eval_jacobian(b, -INFINITY, NAN, 0.5, x, jac);

    /* A small grid and a boundary face grid. */
    double u[3] = {0.0, 0.5, 1.0}, v[3] = {1.0, 0.25, 0.0}, w[3] = {0.0, 0.75, 1.0};
    double grid[27 * 3], face[9 * 3];
    coons_error err = COONS_ERROR_INIT;
    coons_status rc = coons_body_eval_grid(b, u, 3, v, 3, w, 3, grid, &err);
    CHECK(rc == COONS_OK || rc == COONS_E_NOMEM, "eval_grid: %d %s", rc, err.message);
    if (rc == COONS_OK && moderate) {
        double p[3];
        coons_body_eval(b, u[2], v[1], w[0], p);
        const double *g = grid + ((2 * 3 + 1) * 3 + 0) * 3;
        for (int c = 0; c < 3; c++)
            CHECK(fabs(p[c] - g[c]) <= 1e-9 * (1.0 + fabs(p[c])),
                  "grid and eval disagree: %.17g vs %.17g", g[c], p[c]);
    }
    rc = coons_body_eval_grid(b, u, 3, v, 3, w + 2, 1, face, &err);
    CHECK(rc == COONS_OK || rc == COONS_E_NOMEM, "eval_grid face: %d %s", rc, err.message);

    double vol = 0.0, mind = 0.0, where[3];
    /* Coarse and bounded: a folded, piecewise or huge-tangent body may not
     * settle even to 100% (the library's default budget is 2^20 det J
     * evaluations, about 0.2 s in release and over libFuzzer's 10 s per
     * input when instrumented); the best estimate within 2^15 is returned. */
    size_t evals = 0;
    rc = coons_body_volume_bounded(b, 1.0, (size_t)1 << 15, &vol, NULL, &evals, &err);
    CHECK(rc != COONS_OK || evals <= (size_t)1 << 15, "volume: %zu evaluations", evals);
    CHECK(rc == COONS_OK, "volume: %d %s", rc, err.message);
    rc = coons_body_min_jacobian(b, 2, &mind, where, &err);
    CHECK(rc == COONS_OK, "min_jacobian: %d %s", rc, err.message);
    if (rc == COONS_OK && isfinite(mind))
        for (int c = 0; c < 3; c++) CHECK(where[c] >= 0.0 && where[c] <= 1.0, "where %g", where[c]);
}

/* Every writer on a memory stream. */
static void write_all(const coons_mesh *mesh)
{
    static const coons_format F[] = {COONS_FORMAT_STL_BINARY, COONS_FORMAT_STL_ASCII,
                                     COONS_FORMAT_OFF, COONS_FORMAT_SCAD};
    for (size_t i = 0; i < sizeof F / sizeof F[0]; i++) {
        char *text = NULL;
        size_t len = 0;
        FILE *fp = open_memstream(&text, &len);
        if (!fp) return;
        coons_error err = COONS_ERROR_INIT;
        coons_write_options wo = COONS_WRITE_OPTIONS_INIT;
        wo.units = "mm";
        coons_status rc = coons_mesh_write_stream(mesh, fp, F[i], &wo, &err);
        fclose(fp);
        int stl = F[i] == COONS_FORMAT_STL_BINARY || F[i] == COONS_FORMAT_STL_ASCII;
        CHECK(rc == COONS_OK || rc == COONS_E_NOMEM || (stl && rc == COONS_E_LIMIT),
              "writing %s: %d %s", coons_format_name(F[i]), rc, err.message);
        if (rc == COONS_OK) CHECK(len > 0, "empty %s output", coons_format_name(F[i]));
        free(text);
    }
}

/* A hex mesh of the body on a 2 x 2 x 2 lattice (hex8, and hex20 or
 * hex27 from the input's hash), through every volume writer. */
static void volume_all(const coons_body *b, uint64_t h)
{
    static const coons_element E[] = {COONS_ELEMENT_HEX8, COONS_ELEMENT_HEX20,
                                      COONS_ELEMENT_HEX27};
    static const coons_format F[] = {COONS_FORMAT_VTK, COONS_FORMAT_MSH2, COONS_FORMAT_MSH4,
                                     COONS_FORMAT_VTU, COONS_FORMAT_VTU_ASCII, COONS_FORMAT_INP};
    coons_volume_options vo = COONS_VOLUME_OPTIONS_INIT;
    vo.element = E[h % 3];
    vo.resolution[0] = vo.resolution[1] = vo.resolution[2] = 2;
    coons_volume_mesh *vm = NULL;
    coons_error err = COONS_ERROR_INIT;
    coons_status rc = coons_body_volume_mesh(b, &vo, "fuzz", &vm, &err);
    CHECK(rc == COONS_OK || rc == COONS_E_INVALID || rc == COONS_E_LIMIT,
          "volume mesh: %d %s", rc, err.message);
    if (rc) return;
    for (size_t i = 0; i < sizeof F / sizeof F[0]; i++) {
        char *text = NULL;
        size_t len = 0;
        FILE *fp = open_memstream(&text, &len);
        if (!fp) break;
        coons_write_options wo = COONS_WRITE_OPTIONS_INIT;
        rc = coons_volume_mesh_write_stream(vm, fp, F[i], &wo, &err);
        fclose(fp);
        /* hex27 has no CalculiX element: refused, as documented */
        CHECK(rc == COONS_OK || rc == COONS_E_UNSUPPORTED || rc == COONS_E_INVALID ||
                  rc == COONS_E_LIMIT,
              "writing %s: %d %s", coons_format_name(F[i]), rc, err.message);
        if (rc == COONS_OK) CHECK(len > 0, "empty %s output", coons_format_name(F[i]));
        free(text);
    }
    coons_volume_mesh_free(vm);
}

static void check_mesh(const coons_mesh *mesh)
{
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    coons_error err = COONS_ERROR_INIT;
    coons_status rc = coons_mesh_check(mesh, &r, &err);
    CHECK(rc == COONS_OK || rc == COONS_E_NOMEM, "mesh check: %d %s", rc, err.message);
    CHECK(r.triangles == coons_mesh_triangle_count(mesh), "report counts %zu triangles of %zu",
          r.triangles, coons_mesh_triangle_count(mesh));
}

/* Samples with opts, then again failing one allocation of the ones that
 * sampling made: the error must be COONS_E_NOMEM with nothing leaked. */
static void sample_body(const coons_body *b, const coons_sample_options *so, uint64_t h, int deep)
{
    coons_mesh *mesh = NULL;
    coons_error err = COONS_ERROR_INIT;
    long live0 = g_live;
    alloc_reset_keep(LONG_MAX);
    coons_status rc = coons_body_sample(b, so, "fuzz", &mesh, &err);
    long total = g_count;
    alloc_reset_keep(-1);
    if (getenv("FUZZ_MODEL_VERBOSE"))
        fprintf(stderr, "  sample res %u tol %g: %d %s (%zu triangles)\n", so->resolution,
                so->tolerance, rc, rc ? err.message : "", rc ? 0 : coons_mesh_triangle_count(mesh));
    CHECK(rc == COONS_OK || rc == COONS_E_LIMIT || rc == COONS_E_INVALID,
          "sampling: %d %s", rc, err.message);
    CHECK(rc == COONS_OK || err.message[0], "sampling error %d without a message", rc);
    if (rc == COONS_OK) {
        CHECK(mesh != NULL, "sampling OK without a mesh");
        if (deep) {
            check_mesh(mesh);
            write_all(mesh);
        }
        coons_mesh_free(mesh);
    }
    CHECK(g_live == live0, "sampling leaked %ld blocks", g_live - live0);
    if (total > 0 && rc == COONS_OK) {
        long k = (long)(h % (uint64_t)total);
        alloc_reset_keep(k);
        mesh = NULL;
        rc = coons_body_sample(b, so, "fuzz", &mesh, &err);
        alloc_reset_keep(-1);
        CHECK(rc == COONS_E_NOMEM, "allocation %ld of %ld failed, sampling returned %d: %s", k,
              total, rc, err.message);
        CHECK(mesh == NULL, "a mesh despite a failed allocation");
        CHECK(g_live == live0, "sampling leaked %ld blocks after allocation %ld failed",
              g_live - live0, k);
    }
}

static void exercise_model(const coons_model *m, uint64_t h)
{
    size_t n = coons_model_body_count(m);
    CHECK(n >= 1, "a model with no body");
    CHECK(coons_model_body(m, n) == NULL, "body past the end");
    (void)coons_model_tolerance(m);
    (void)coons_model_operation(m);
    CHECK(coons_model_units(m) != NULL, "no units");
    double lo[3], hi[3];
    coons_model_control_bbox(m, lo, hi);
    for (size_t i = 0; i < n; i++) {
        const coons_body *b = coons_model_body(m, i);
        const char *name = coons_model_body_name(m, i);
        CHECK(b && name, "body %zu missing", i);
        long k = coons_model_find_body(m, name);
        CHECK(k >= 0 && (size_t)k <= i, "body %zu (%s) found at %ld", i, name, k);
        exercise_body(b);
        volume_all(b, h);
        coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
        so.resolution = 2;
        so.max_triangles = 4000;
        sample_body(b, &so, h, 1);
        so.resolution = 0;
        double blo[3], bhi[3];
        coons_body_control_bbox(b, blo, bhi);
        double dx = bhi[0] - blo[0], dy = bhi[1] - blo[1], dz = bhi[2] - blo[2];
        so.tolerance = 0.02 * sqrt(dx * dx + dy * dy + dz * dz);
        /* sampled twice (once with a failed allocation), instrumented:
         * bounded well below the default 20 million triangles */
        so.max_triangles = 100000;
        sample_body(b, &so, h >> 17, 0);
    }
    /* The whole model: disjoint bodies are put together, others refused. */
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.resolution = 2;
    so.max_triangles = 4000 * n;
    coons_mesh *mesh = NULL;
    coons_error err = COONS_ERROR_INIT;
    coons_status rc = coons_model_sample(m, &so, &mesh, &err);
    CHECK(rc == COONS_OK || rc == COONS_E_LIMIT || rc == COONS_E_INVALID ||
              rc == COONS_E_UNSUPPORTED,
          "model mesh: %d %s", rc, err.message);
    /* A part per body, except that in a union bodies joined by shared faces
     * (a control lattice) are one part. */
    if (rc == COONS_OK) {
        size_t parts = coons_mesh_part_count(mesh);
        int none = coons_model_operation(m) == COONS_OP_NONE;
        CHECK(none ? parts == n : parts >= 1 && parts <= n, "%zu parts for %zu bodies (%s)",
              parts, n, none ? "none" : "union");
    }
    coons_mesh_free(mesh);
}

/* ---- structure-aware mutation ------------------------------------------- */

#ifdef COONS_FUZZ_LIBFUZZER
size_t LLVMFuzzerMutate(uint8_t *data, size_t size, size_t max_size);
size_t LLVMFuzzerCustomMutator(uint8_t *data, size_t size, size_t max_size, unsigned seed);

/* Replaces bytes [a, b) of data by the text r, if it fits. */
static size_t splice(uint8_t *data, size_t size, size_t max_size, size_t a, size_t b,
                     const char *r)
{
    size_t n = strlen(r);
    if (size - (b - a) + n > max_size) return 0;
    memmove(data + a + n, data + b, size - b);
    memcpy(data + a, r, n);
    return size - (b - a) + n;
}

/* Half of the mutations keep a model's JSON valid and move one of its
 * numbers across scales: to an extreme or special value (+-1e300,
 * denormals, -0, huge degrees and multiplicities within the limits), by a
 * power of ten, or to a neighbouring double. The rest are libFuzzer's own
 * byte-level mutations (with the dictionary). */
size_t LLVMFuzzerCustomMutator(uint8_t *data, size_t size, size_t max_size, unsigned seed)
{
    static const char *special[] = {
        "1e300", "-1e300", "1e-300", "5e-324", "-5e-324", "-0", "0", "1e150", "1e-150",
        "2.2250738585072014e-308", "1.7976931348623157e308", "1e16", "-1", "1", "2", "3",
        "4", "7", "31", "64", "1000", "65536", "4294967297", "0.9999999999999999",
        "1.0000000000000002", "0.5", "1e-9", "-1e-16"};
    uint64_t r = (uint64_t)seed * 6364136223846793005ull + 1442695040888963407ull;
    if ((r >> 33) & 1) return LLVMFuzzerMutate(data, size, max_size);
    /* the numbers outside strings */
    size_t count = 0;
    int in_str = 0;
    for (size_t i = 0; i < size; i++) {
        uint8_t c = data[i];
        if (in_str) {
            if (c == '\\') i++;
            else if (c == '"') in_str = 0;
        } else if (c == '"') {
            in_str = 1;
        } else if ((c == '-' || (c >= '0' && c <= '9')) &&
                   (i == 0 || !((data[i - 1] >= '0' && data[i - 1] <= '9') ||
                                data[i - 1] == '.' || data[i - 1] == 'e' ||
                                data[i - 1] == 'E' || data[i - 1] == '-' ||
                                data[i - 1] == '+'))) {
            count++;
        }
    }
    if (count == 0) return LLVMFuzzerMutate(data, size, max_size);
    size_t want = (size_t)((r >> 40) % count), k = 0, a = 0, b = 0;
    in_str = 0;
    for (size_t i = 0; i < size; i++) {
        uint8_t c = data[i];
        if (in_str) {
            if (c == '\\') i++;
            else if (c == '"') in_str = 0;
            continue;
        }
        if (c == '"') {
            in_str = 1;
            continue;
        }
        if ((c == '-' || (c >= '0' && c <= '9')) &&
            (i == 0 || !((data[i - 1] >= '0' && data[i - 1] <= '9') || data[i - 1] == '.' ||
                         data[i - 1] == 'e' || data[i - 1] == 'E' || data[i - 1] == '-' ||
                         data[i - 1] == '+'))) {
            if (k++ == want) {
                a = i;
                b = i + 1;
                while (b < size && strchr("0123456789.eE+-", data[b])) b++;
                break;
            }
        }
    }
    char old[64], text[64];
    size_t len = b - a < sizeof old - 1 ? b - a : sizeof old - 1;
    memcpy(old, data + a, len);
    old[len] = '\0';
    double x = strtod(old, NULL);
    switch ((r >> 20) % 4) {
    case 0:
    case 1:
        snprintf(text, sizeof text, "%s", special[(r >> 8) % (sizeof special / sizeof *special)]);
        break;
    case 2: /* a power of ten, -300..300 */
        snprintf(text, sizeof text, "%.17g", x * pow(10.0, (double)((int)((r >> 8) % 601) - 300)));
        break;
    default: /* the next double up or down */
        snprintf(text, sizeof text, "%.17g", nextafter(x, ((r >> 8) & 1) ? INFINITY : -INFINITY));
        break;
    }
    if (!strchr("-0123456789", text[0]) || strstr(text, "inf") || strstr(text, "nan"))
        snprintf(text, sizeof text, "1e308");
    size_t n = splice(data, size, max_size, a, b, text);
    return n ? n : LLVMFuzzerMutate(data, size, max_size);
}
#endif

/* ---- the target ------------------------------------------------------------ */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* Small limits: the defaults would let a short input describe a net of
     * 10^6 points whose evaluation alone takes seconds. The limits
     * themselves are exercised too (E_LIMIT is a valid outcome). */
    coons_model_load_options o = COONS_MODEL_LOAD_OPTIONS_INIT;
    o.max_bytes = 1 << 20;
    o.max_values = 1 << 16;
    o.max_points = 512;

    static int installed;
    if (!installed) {
        coons_set_allocator(f_malloc, f_realloc, f_free);
        installed = 1;
    }

    coons_model *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    alloc_reset(-1);
    coons_status rc = coons_model_load_memory((const char *)data, size, "fuzz", &o, &m, &err);
    if (getenv("FUZZ_MODEL_VERBOSE"))
        fprintf(stderr, "load: %d %s\n", rc, rc ? err.message : "");
    if (rc != COONS_OK) {
        CHECK(m == NULL, "error %d but a model", rc);
        CHECK(err.code == rc, "err.code %d, returned %d", err.code, rc);
        CHECK(err.message[0] != '\0', "error %d without a message", rc);
        CHECK(strncmp(err.message, "fuzz", 4) == 0 || rc == COONS_E_NOMEM,
              "message does not name the file: %s", err.message);
        CHECK(rc == COONS_E_PARSE || rc == COONS_E_INVALID || rc == COONS_E_LIMIT ||
                  rc == COONS_E_UNSUPPORTED || rc == COONS_E_INCOMPATIBLE,
              "unexpected status %d: %s", rc, err.message);
        CHECK(g_live == 0, "%ld blocks live after a failed load", g_live);
    } else {
        CHECK(m != NULL, "COONS_OK without a model");
        exercise_model(m, fnv1a(data, size) >> 7);
        coons_model_free(m);
        CHECK(g_live == 0, "%ld blocks live after coons_model_free", g_live);
    }

    /* Count the allocations of a load (fail_at beyond any count), then fail
     * one of them. */
    alloc_reset(LONG_MAX);
    m = NULL;
    coons_status rc2 = coons_model_load_memory((const char *)data, size, "fuzz", &o, &m, &err);
    CHECK(rc2 == rc, "second load gave %d, first %d", rc2, rc);
    coons_model_free(m);
    long total = g_count;
    /* FUZZ_MODEL_EVERY_ALLOCATION=1 fails each allocation of the load in
     * turn instead of one chosen by the input's hash (slow; for replaying). */
    int every = getenv("FUZZ_MODEL_EVERY_ALLOCATION") != NULL;
    for (long j = 0; total > 0 && j < (every ? total : 1); j++) {
        long k = every ? j : (long)(fnv1a(data, size) % (uint64_t)total);
        coons_error e3 = COONS_ERROR_INIT;
        alloc_reset(k);
        m = NULL;
        coons_status rc3 = coons_model_load_memory((const char *)data, size, "fuzz", &o, &m,
                                                   &e3);
        CHECK(rc3 == COONS_E_NOMEM, "allocation %ld of %ld failed, load returned %d: %s", k, total,
              rc3, e3.message);
        CHECK(m == NULL, "a model despite a failed allocation");
        CHECK(e3.message[0] != '\0', "out of memory without a message");
        CHECK(g_live == 0, "%ld blocks leaked after allocation %ld of %ld failed", g_live, k,
              total);
    }
    alloc_reset(-1);
    return 0;
}
