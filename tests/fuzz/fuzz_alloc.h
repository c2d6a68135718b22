/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The fuzz targets' counting, failing allocator (installed with
 * coons_set_allocator) and the input hash that picks which allocation
 * fails. Static: each target is one translation unit. */
#ifndef COONS_FUZZ_ALLOC_H
#define COONS_FUZZ_ALLOC_H

#include <stdint.h>
#include <stdlib.h>

/* ---- counting, failing allocator ------------------------------------------ */

static long g_fail_at = -1; /* fail the allocation with this index; -1: never */
static long g_count, g_live;

static inline void *f_malloc(size_t n)
{
    if (g_fail_at >= 0 && g_count++ == g_fail_at) return NULL;
    void *p = malloc(n);
    if (p) g_live++;
    return p;
}

static inline void *f_realloc(void *p, size_t n)
{
    if (g_fail_at >= 0 && g_count++ == g_fail_at) return NULL;
    void *q = realloc(p, n);
    if (q && !p) g_live++;
    return q;
}

static inline void f_free(void *p)
{
    if (p) g_live--;
    free(p);
}

/* Counts from zero with a new failure point, keeping the live count. */
static inline void alloc_reset_keep(long fail_at)
{
    g_fail_at = fail_at;
    g_count = 0;
}

static inline void alloc_reset(long fail_at)
{
    g_fail_at = fail_at;
    g_count = 0;
    g_live = 0;
}

static inline uint64_t fnv1a(const uint8_t *d, size_t n)
{
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < n; i++) h = (h ^ d[i]) * 1099511628211ull;
    return h;
}

#endif
