/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Every allocation failure is handled, across the whole pipeline of the
 * C library on real models: for every example and every valid test model,
 * loading, sampling each body on a coarse lattice (one body at a time),
 * meshing the model and writing the mesh in every format are each repeated
 * with the k-th allocation failing, for every k up to the number that the
 * operation makes (the first and last 80, and about 150 evenly spaced
 * between them in longer runs). Each must then return COONS_E_NOMEM with a
 * message, produce no object, and leave no block allocated (the test
 * allocator counts them). ALLOC_VERBOSE=1 prints each operation's count
 * and time.
 *
 * Under a sanitizer (COONS_TEST_REPRESENTATIVE=1, tools/test.sh's asan
 * stage) the examples are the representative subset of
 * tests/data/representative-examples.txt (every kind of curve, patch and
 * body of the examples); the release and core stages take every example.
 */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <coons/io.h>

#include "test_util.h"

static char *read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    while (buf) {
        n += fread(buf + n, 1, cap - n, f);
        if (n < cap) break;
        char *nb = realloc(buf, cap *= 2);
        if (!nb) free(buf);
        buf = nb;
    }
    fclose(f);
    *len = n;
    return buf;
}

/* Whether a file name is listed in tests/data/representative-examples.txt. */
static int representative(const char *name)
{
    FILE *f = fopen(COONS_SOURCE_DIR "/tests/data/representative-examples.txt", "r");
    if (!f) fail_msg("cannot read tests/data/representative-examples.txt");
    char line[256];
    int found = 0;
    while (!found && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = '\0';
        found = line[0] != '#' && line[0] != '\0' && strcmp(line, name) == 0;
    }
    fclose(f);
    return found;
}

/* Model files of a directory, sorted; returns the count. With subset set
 * and COONS_TEST_REPRESENTATIVE in the environment, only the
 * representative ones. */
static size_t list_models(const char *dir, char names[][256], size_t max, int subset)
{
    subset = subset && getenv("COONS_TEST_REPRESENTATIVE") && *getenv("COONS_TEST_REPRESENTATIVE");
    DIR *d = opendir(dir);
    if (!d) return 0;
    size_t n = 0;
    struct dirent *e;
    while ((e = readdir(d)) && n < max) {
        size_t l = strlen(e->d_name);
        if (l > 5 && l < 200 && strcmp(e->d_name + l - 5, ".json") == 0 &&
            (!subset || representative(e->d_name))) {
            int w = snprintf(names[n], 256, "%s/%s", dir, e->d_name);
            if (w > 0 && w < 256) n++;
        }
    }
    closedir(d);
    qsort(names, n, sizeof names[0], (int (*)(const void *, const void *))strcmp);
    return n;
}

/* One operation on a model, under the failing allocator. */
typedef coons_status (*op_fn)(const char *text, size_t len, const coons_model *m,
                              coons_error *err);

static coons_status op_load(const char *text, size_t len, const coons_model *m, coons_error *err)
{
    (void)m;
    coons_model *out = (coons_model *)1;
    coons_status rc = coons_model_load_memory(text, len, "model", NULL, &out, err);
    if (rc == COONS_OK) coons_model_free(out);
    else if (out != NULL) fail_msg("load failed with %d but returned a model", rc);
    return rc;
}

/* The body that op_sample samples: one body per run, so that a run costs
 * one body's sampling, not the whole model's (a lattice has 64 bodies). */
static size_t g_body;

/* Failure points checked at each end of a run, and about how many between. */
enum { EDGE = 80, MIDDLE = 150 };

static coons_status op_sample(const char *text, size_t len, const coons_model *m,
                              coons_error *err)
{
    (void)text;
    (void)len;
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.resolution = 3;
    coons_mesh *mesh = (coons_mesh *)1;
    coons_status rc = coons_body_sample(coons_model_body(m, g_body), &so, "b", &mesh, err);
    if (rc != COONS_OK) {
        if (mesh != NULL) fail_msg("sampling failed with %d but returned a mesh", rc);
        return rc;
    }
    coons_mesh_free(mesh);
    return COONS_OK;
}

static coons_status op_mesh_write(const char *text, size_t len, const coons_model *m,
                                  coons_error *err)
{
    (void)text;
    (void)len;
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.resolution = 2;
    coons_mesh *mesh = NULL;
    coons_status rc = coons_model_sample(m, &so, &mesh, err);
    if (rc == COONS_E_UNSUPPORTED) return COONS_OK; /* overlapping bodies need CGAL */
    if (rc != COONS_OK) return rc;
    static const coons_format F[] = {COONS_FORMAT_STL_BINARY, COONS_FORMAT_STL_ASCII,
                                     COONS_FORMAT_OFF, COONS_FORMAT_SCAD};
    for (size_t f = 0; f < 4 && rc == COONS_OK; f++) {
        char *buf = NULL;
        size_t n = 0;
        FILE *fp = open_memstream(&buf, &n);
        assert_non_null(fp);
        rc = coons_mesh_write_stream(mesh, fp, F[f], NULL, err);
        fclose(fp);
        free(buf);
    }
    coons_mesh_free(mesh);
    return rc;
}

static long g_points; /* failure points checked */

/* Runs op with every allocation index failing in turn. */
static void every_failure(const char *name, const char *what, op_fn op, const char *text,
                          size_t len, const coons_model *m)
{
    coons_error err = COONS_ERROR_INIT;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    long points0 = g_points;
    coons_test_fail_after(1L << 40); /* count only */
    coons_status rc = op(text, len, m, &err);
    long total = coons_test_alloc_count();
    coons_test_fail_after(-1);
    if (rc != COONS_OK) fail_msg("%s: %s failed without a failing allocation: %s", name, what,
                                 err.message);
    for (long k = 0; k < total; k++) {
        /* The first and last EDGE failure points, and every step-th
         * between (7, or more so that at most about MIDDLE fall there):
         * the middle of a long run repeats the same few sites (one per
         * curve, patch or body), and each run costs in proportion to k, so
         * that the whole test stays well inside the ASan stage's timeout. */
        long step = total / MIDDLE > 7 ? total / MIDDLE : 7;
        if (k >= EDGE && k < total - EDGE && k % step != 0) continue;
        g_points++;
        coons_error e = COONS_ERROR_INIT;
        coons_test_fail_after(k);
        rc = op(text, len, m, &e);
        long live = coons_test_live_allocs();
        coons_test_fail_after(-1);
        if (rc == COONS_OK) continue; /* a fallback that needs no memory, e.g. a cache */
        if (rc != COONS_E_NOMEM || e.message[0] == '\0' || e.code != rc)
            fail_msg("%s: %s with allocation %ld of %ld failing: status %d, message '%s'", name,
                     what, k, total, rc, e.message);
        if (live != 0)
            fail_msg("%s: %s with allocation %ld of %ld failing: %ld blocks leaked", name, what,
                     k, total, live);
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (getenv("ALLOC_VERBOSE")) /* to find what dominates the test's time */
        print_message("%s %s: %ld allocations, %ld points, %.3f s\n", name, what, total,
                      g_points - points0,
                      (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec));
}

static void run_dir(const char *dir, size_t min_count, int subset)
{
    static char names[128][256];
    size_t n = list_models(dir, names, 128, subset);
    assert_true(n >= min_count);
    g_points = 0;
    for (size_t i = 0; i < n; i++) {
        size_t len = 0;
        char *text = read_file(names[i], &len);
        assert_non_null(text);
        every_failure(names[i], "loading", op_load, text, len, NULL);
        coons_model *m = NULL;
        coons_error err = COONS_ERROR_INIT;
        assert_coons_ok(coons_model_load_memory(text, len, names[i], NULL, &m, &err), &err);
        for (g_body = 0; g_body < coons_model_body_count(m); g_body++) {
            char what[64];
            snprintf(what, sizeof what, "sampling body %zu", g_body);
            every_failure(names[i], what, op_sample, text, len, m);
        }
        every_failure(names[i], "meshing and writing", op_mesh_write, text, len, m);
        coons_model_free(m);
        free(text);
    }
    print_message("%s: %zu models, %ld allocation failures checked\n", dir, n, g_points);
}

/* Given every example, when each allocation fails in turn, then every
 * stage reports COONS_E_NOMEM and frees everything. */
static void test_examples(void **state)
{
    (void)state;
    run_dir(COONS_SOURCE_DIR "/examples", getenv("COONS_TEST_REPRESENTATIVE") ? 10 : 20, 1);
}

/* The same for the valid models of the test data. */
static void test_data_ok(void **state)
{
    (void)state;
    run_dir(COONS_SOURCE_DIR "/tests/data/ok", 1, 0);
}

/* The same for models with references (coons-model(5), "Definitions and
 * references"): definitions built once, copied and wrapped per reference. */
static void test_data_refs(void **state)
{
    (void)state;
    run_dir(COONS_SOURCE_DIR "/tests/data/refs", 1, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_examples),
        cmocka_unit_test(test_data_ok),
        cmocka_unit_test(test_data_refs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
