/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * A parallel loop over [0, n) in contiguous chunks, one per thread.
 * Internal. With k chunks, q = n / k and r = n % k, chunk c covers q + 1
 * indices if c < r, else q, in order, whatever runs it, so work whose result depends only on the indices it covers gives
 * the same bytes for every thread count. Chunk 0 runs on the calling
 * thread; a thread that cannot be started (no pthreads, as in a
 * WebAssembly build without them, or out of resources) leaves its chunk to
 * the calling thread too. Returns when every chunk is done.
 */
#ifndef COONS_PARALLEL_H
#define COONS_PARALLEL_H

#include <stddef.h>

/* fn(ctx, chunk, lo, hi) for each chunk. */
typedef void (*coons__chunk_fn)(void *ctx, unsigned chunk, size_t lo, size_t hi);

/* The thread count `threads` stands for: 0 is every online core; at most
 * COONS__MAX_THREADS. */
#define COONS__MAX_THREADS 1024u
unsigned coons__thread_count(unsigned threads);

/* Runs fn over [0, n) in min(threads, n) chunks (at least 1 when n > 0);
 * `threads` as coons__thread_count() reads it. */
void coons__parallel_for(size_t n, unsigned threads, coons__chunk_fn fn, void *ctx);

#endif
