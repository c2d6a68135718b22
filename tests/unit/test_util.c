/* SPDX-License-Identifier: GPL-3.0-or-later */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "test_util.h"

void assert_near_impl(double a, double b, double eps, const char *ea, const char *eb,
                      const char *file, int line)
{
    if (!(fabs(a - b) <= eps)) {
        print_error("%s:%d: %s = %.17g, %s = %.17g, |diff| = %.3g > %.3g\n", file, line, ea,
                       a, eb, b, fabs(a - b), eps);
        _fail(file, line);
    }
}

void assert_vec3_near_impl(const double *a, const double *b, double eps, const char *ea,
                           const char *eb, const char *file, int line)
{
    for (int i = 0; i < 3; i++) {
        if (!(fabs(a[i] - b[i]) <= eps)) {
            print_error("%s:%d: %s = (%.17g, %.17g, %.17g) vs %s = (%.17g, %.17g, %.17g), "
                           "component %d differs by %.3g > %.3g\n",
                           file, line, ea, a[0], a[1], a[2], eb, b[0], b[1], b[2], i,
                           fabs(a[i] - b[i]), eps);
            _fail(file, line);
        }
    }
}

static long g_fail_after = -1;
static long g_count = 0;
static long g_live = 0;

static void *t_malloc(size_t n)
{
    if (g_fail_after >= 0 && g_count++ >= g_fail_after) return NULL;
    void *p = malloc(n);
    if (p) g_live++;
    return p;
}
static void *t_realloc(void *p, size_t n)
{
    if (g_fail_after >= 0 && g_count++ >= g_fail_after) return NULL;
    void *q = realloc(p, n);
    if (q && !p) g_live++;
    return q;
}
static void t_free(void *p)
{
    if (p) g_live--;
    free(p);
}

void coons_test_fail_after(long n)
{
    g_fail_after = n;
    g_count = 0;
    g_live = 0;
    if (n < 0)
        coons_set_allocator(NULL, NULL, NULL);
    else
        coons_set_allocator(t_malloc, t_realloc, t_free);
}

long coons_test_alloc_count(void) { return g_count; }
long coons_test_live_allocs(void) { return g_live; }

coons_model *test_source_model(const char *rel)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", COONS_SOURCE_DIR, rel);
    coons_model *m = NULL;
    coons_error err;
    assert_coons_ok(coons_model_load_file(path, NULL, &m, &err), &err);
    return m;
}
