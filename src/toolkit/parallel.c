/* SPDX-License-Identifier: GPL-3.0-or-later */
#include "parallel.h"

#include <pthread.h>
#include <unistd.h>

#include "coons_internal.h"

unsigned coons__thread_count(unsigned threads)
{
    if (threads == 0) {
        long cores = sysconf(_SC_NPROCESSORS_ONLN);
        threads = cores > 0 ? (unsigned)cores : 1u;
    }
    return threads > COONS__MAX_THREADS ? COONS__MAX_THREADS : threads;
}

typedef struct chunk {
    coons__chunk_fn fn;
    void *ctx;
    unsigned index;
    size_t lo, hi;
} chunk;

static void *run(void *arg)
{
    chunk *c = arg;
    c->fn(c->ctx, c->index, c->lo, c->hi);
    return NULL;
}

void coons__parallel_for(size_t n, unsigned threads, coons__chunk_fn fn, void *ctx)
{
    if (n == 0) return;
    size_t k = coons__thread_count(threads);
    if (k > n) k = n;
    chunk *c = k > 1 ? coons__malloc_array(k, sizeof *c) : NULL;
    pthread_t *tid = c ? coons__malloc_array(k, sizeof *tid) : NULL;
    char *started = tid ? coons__calloc(k, 1) : NULL;
    if (!started) { /* one chunk, or no memory for the bookkeeping */
        coons__free(c);
        coons__free(tid);
        fn(ctx, 0, 0, n);
        return;
    }
    size_t q = n / k, r = n % k; /* the first r chunks take q + 1 */
    for (size_t i = 0; i < k; i++) {
        size_t lo = i * q + (i < r ? i : r);
        c[i] = (chunk){fn, ctx, (unsigned)i, lo, lo + q + (i < r)};
    }
    for (size_t i = 1; i < k; i++) started[i] = pthread_create(&tid[i], NULL, run, &c[i]) == 0;
    run(&c[0]);
    for (size_t i = 1; i < k; i++) {
        if (started[i])
            pthread_join(tid[i], NULL);
        else
            run(&c[i]);
    }
    coons__free(started);
    coons__free(tid);
    coons__free(c);
}
