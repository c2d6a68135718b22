/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Private helpers shared by the C sources: allocation through the user's
 * hooks, error recording, and small vector maths. Never installed. */
#ifndef COONS_INTERNAL_H
#define COONS_INTERNAL_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "coons.h"

#if defined(__GNUC__)
#define COONS__PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define COONS__PRINTF(a, b)
#endif

void *coons__malloc(size_t n);
void *coons__calloc(size_t count, size_t size); /* zeroed, overflow-checked */
void *coons__realloc(void *p, size_t n);
void coons__free(void *p);
/* Grows the array *p of *cap elements of `size` bytes (doubling from 16)
 * to hold at least `need`: 0, or -1 when out of memory (*p unchanged). */
int coons__grow(void **p, size_t *cap, size_t need, size_t size);
/* malloc of count*size with overflow check; NULL on overflow or failure. */
void *coons__malloc_array(size_t count, size_t size);
/* Duplicate count*size bytes (NULL input or count 0 gives NULL and ok). */
void *coons__memdup(const void *src, size_t count, size_t size);

/* Records code and a formatted message in err (if not NULL) and returns code.
 * Clears file/line/column/path. */
coons_status coons__error_set(coons_error *err, coons_status code, const char *fmt, ...)
    COONS__PRINTF(3, 4);
/* Shorthand for the common out-of-memory case. */
coons_status coons__error_nomem(coons_error *err);

/* COONS_E_INVALID, with the one wording of records.c, unless `version` (of
 * the record named `record`, e.g. "sample options") lies in [oldest,
 * current]; `init` names the record's INIT macro. COONS__RECORD_CHECK(err,
 * "sample options", o->version, COONS_SAMPLE_OPTIONS) is the usual call, for
 * a record that knows one version. */
coons_status coons__record_version_check(const char *record, unsigned version, unsigned oldest,
                                         unsigned current, const char *init, coons_error *err);
#define COONS__RECORD_CHECK(err, record, version, PREFIX)                                         \
    coons__record_version_check(record, version, PREFIX##_VERSION, PREFIX##_VERSION,               \
                                #PREFIX "_INIT", err)

/* The `threads` field of an options record (0 or 1: the calling thread)
 * as a count for coons__parallel_for(): at least 1, at most 1024. */
static inline unsigned coons__record_threads(unsigned threads)
{
    return threads < 1 ? 1u : threads > 1024u ? 1024u : threads;
}

#include "geom.h"

/* All values of an array finite? */
int coons__all_finite(const double *a, size_t n);

/* Consistency tolerance: tol > 0 is absolute, otherwise 1e-9 * diag. */
static inline double coons__tolerance(double tol, double diag)
{
    if (tol > 0.0) return tol;
    return COONS__REL_TOL * (diag > 0.0 ? diag : 1.0);
}

#endif
