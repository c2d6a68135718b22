/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The one allocator of the C core. Replaceable once, before any other call
 * (libuv's uv_replace_allocator); tests use it to fail the Nth allocation. */
#include <stdlib.h>
#include <string.h>

#include "coons_internal.h"

static void *(*g_malloc)(size_t) = malloc;
static void *(*g_realloc)(void *, size_t) = realloc;
static void (*g_free)(void *) = free;

void coons_set_allocator(void *(*malloc_fn)(size_t), void *(*realloc_fn)(void *, size_t),
                         void (*free_fn)(void *))
{
    if (!malloc_fn || !realloc_fn || !free_fn) {
        g_malloc = malloc;
        g_realloc = realloc;
        g_free = free;
        return;
    }
    g_malloc = malloc_fn;
    g_realloc = realloc_fn;
    g_free = free_fn;
}

void *coons__malloc(size_t n) { return g_malloc(n ? n : 1); }
void *coons__realloc(void *p, size_t n) { return g_realloc(p, n ? n : 1); }
void coons__free(void *p)
{
    if (p) g_free(p);
}

void *coons__malloc_array(size_t count, size_t size)
{
    if (size && count > SIZE_MAX / size) return NULL;
    return coons__malloc(count * size);
}

void *coons__calloc(size_t count, size_t size)
{
    void *p = coons__malloc_array(count, size);
    if (p && count && size) memset(p, 0, count * size);
    return p;
}

void *coons__memdup(const void *src, size_t count, size_t size)
{
    if (!src || count == 0) return NULL;
    void *p = coons__malloc_array(count, size);
    if (p) memcpy(p, src, count * size);
    return p;
}

int coons__all_finite(const double *a, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(a[i])) return 0;
    return 1;
}

int coons__grow(void **p, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap) return 0;
    size_t c = *cap ? *cap : 16;
    while (c < need) c *= 2;
    void *q = coons__realloc(*p, c * size);
    if (!q) return -1;
    *p = q;
    *cap = c;
    return 0;
}
