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

/* Small double[3] maths. */
static inline void v3_set(double o[3], double x, double y, double z) { o[0] = x; o[1] = y; o[2] = z; }
static inline void v3_copy(double o[3], const double a[3]) { o[0] = a[0]; o[1] = a[1]; o[2] = a[2]; }
static inline void v3_zero(double o[3]) { o[0] = o[1] = o[2] = 0.0; }
static inline void v3_add(double o[3], const double a[3], const double b[3]) { o[0] = a[0] + b[0]; o[1] = a[1] + b[1]; o[2] = a[2] + b[2]; }
static inline void v3_sub(double o[3], const double a[3], const double b[3]) { o[0] = a[0] - b[0]; o[1] = a[1] - b[1]; o[2] = a[2] - b[2]; }
static inline void v3_scale(double o[3], const double a[3], double s) { o[0] = a[0] * s; o[1] = a[1] * s; o[2] = a[2] * s; }
/* o += s * a */
static inline void v3_axpy(double o[3], double s, const double a[3]) { o[0] += s * a[0]; o[1] += s * a[1]; o[2] += s * a[2]; }
static inline double v3_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void v3_cross(double o[3], const double a[3], const double b[3])
{
    double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
    o[0] = x; o[1] = y; o[2] = z;
}
static inline double v3_norm(const double a[3]) { return sqrt(v3_dot(a, a)); }
static inline double v3_dist(const double a[3], const double b[3])
{
    double d[3];
    v3_sub(d, a, b);
    return v3_norm(d);
}
static inline void v3_lerp(double o[3], const double a[3], const double b[3], double t)
{
    o[0] = a[0] + t * (b[0] - a[0]); o[1] = a[1] + t * (b[1] - a[1]); o[2] = a[2] + t * (b[2] - a[2]);
}
static inline int v3_finite(const double a[3]) { return isfinite(a[0]) && isfinite(a[1]) && isfinite(a[2]); }

/* Bounding boxes: lo = +inf, hi = -inf, then extend. */
static inline void bbox_empty(double lo[3], double hi[3])
{
    lo[0] = lo[1] = lo[2] = INFINITY;
    hi[0] = hi[1] = hi[2] = -INFINITY;
}
static inline void bbox_add(double lo[3], double hi[3], const double p[3])
{
    for (int i = 0; i < 3; i++) {
        if (p[i] < lo[i]) lo[i] = p[i];
        if (p[i] > hi[i]) hi[i] = p[i];
    }
}
/* The box's diagonal, without overflow or underflow of the squares: a box
 * of size 1e200 or 1e-300 has a finite, non-zero diagonal. */
static inline double bbox_diag(const double lo[3], const double hi[3])
{
    if (!(lo[0] <= hi[0])) return 0.0;
    double m = 0, q = 0;
    for (int i = 0; i < 3; i++) m = fmax(m, hi[i] - lo[i]);
    if (!(m > 0) || !isfinite(m)) return m > 0 ? m : 0.0;
    for (int i = 0; i < 3; i++) q += ((hi[i] - lo[i]) / m) * ((hi[i] - lo[i]) / m);
    return m * sqrt(q);
}

/* NaN maps to 0: a parameter must never reach an integer conversion as NaN. */
static inline double clamp01(double x) { return x > 0.0 ? (x < 1.0 ? x : 1.0) : 0.0; }

/* All values of an array finite? */
int coons__all_finite(const double *a, size_t n);

/* Consistency tolerance: tol > 0 is absolute, otherwise 1e-9 * diag. */
static inline double coons__tolerance(double tol, double diag)
{
    if (tol > 0.0) return tol;
    return 1e-9 * (diag > 0.0 ? diag : 1.0);
}

#endif
