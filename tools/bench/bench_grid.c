/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * bench_grid: times coons_body_eval_grid() of a Coons body 2 (seed 000
 * section 2.4) whose six faces are bicubic B-spline surfaces, on an N^3
 * grid (default 200^3), single thread, best of R runs; and the machine's
 * memory-write bound for the same output: the time to store 24 bytes per
 * point into a freshly allocated N^3 x 3 double array (memset and a plain
 * store loop, best of R runs each).
 *
 * Every output array is a fresh anonymous mapping advised for transparent
 * huge pages (what numpy does for large arrays, so splipy's result arrays
 * and ours pay the same page-fault cost); --small-pages skips the advice.
 *
 * With -t T (default: every online core) it also times
 * coons_body_eval_grid_threads() on T threads into fresh and reused arrays,
 * checks that its output equals the one-thread grid byte for byte, and
 * measures the all-core write bound (T threads each storing their slice).
 *
 * Usage: bench_grid [-n N] [-r RUNS] [-t THREADS] [--small-pages] [--net] [--probe i,j,k ...]
 *   --net    also print the faces' control net (JSON) for bench_grid.py
 *   --probe  print the grid point at index (i,j,k) (for cross-checking)
 * Output: one JSON object on stdout.
 */
#define _GNU_SOURCE /* MAP_ANONYMOUS, MADV_HUGEPAGE */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <pthread.h>
#include <time.h>
#include <unistd.h>

#include <coons.h>

#include "bench_body.h"

static int huge = 1;

/* A fresh, untouched array of `bytes` bytes. */
static double *fresh(size_t bytes)
{
    void *p = mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) {
        fprintf(stderr, "bench_grid: out of memory\n");
        exit(1);
    }
#ifdef MADV_HUGEPAGE
    if (huge) madvise(p, bytes, MADV_HUGEPAGE);
#endif
    return p;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

typedef struct slice {
    double *p;
    size_t lo, hi;
} slice;

static void *store_slice(void *arg)
{
    slice *s = arg;
    for (size_t m = s->lo; m < s->hi; m++) s->p[m] = (double)m;
    return NULL;
}

/* Stores m into p[m] for m < count on `threads` threads, one slice each. */
static void store_threads(double *p, size_t count, unsigned threads)
{
    pthread_t tid[256];
    slice sl[256];
    if (threads > 256) threads = 256;
    for (unsigned t = 0; t < threads; t++)
        sl[t] = (slice){p, count * t / threads, count * (t + 1) / threads};
    unsigned started = 0;
    for (unsigned t = 1; t < threads; t++, started++)
        if (pthread_create(&tid[t], NULL, store_slice, &sl[t])) break;
    store_slice(&sl[0]);
    for (unsigned t = started + 1; t < threads; t++) store_slice(&sl[t]);
    for (unsigned t = 1; t <= started; t++) pthread_join(tid[t], NULL);
}

int main(int argc, char **argv)
{
    size_t n = 200;
    int runs = 5, print_net = 0;
    unsigned threads = 0;
    size_t probes[64][3];
    int nprobe = 0;
    for (int a = 1; a < argc; a++) {
        if (!strcmp(argv[a], "-n") && a + 1 < argc)
            n = (size_t)strtoul(argv[++a], NULL, 10);
        else if (!strcmp(argv[a], "-r") && a + 1 < argc)
            runs = atoi(argv[++a]);
        else if (!strcmp(argv[a], "-t") && a + 1 < argc)
            threads = (unsigned)strtoul(argv[++a], NULL, 10);
        else if (!strcmp(argv[a], "--small-pages"))
            huge = 0;
        else if (!strcmp(argv[a], "--net"))
            print_net = 1;
        else if (!strcmp(argv[a], "--probe") && a + 1 < argc && nprobe < 64) {
            unsigned long x, y, z;
            if (sscanf(argv[++a], "%lu,%lu,%lu", &x, &y, &z) != 3) {
                fprintf(stderr, "bench_grid: bad --probe %s\n", argv[a]);
                return 2;
            }
            probes[nprobe][0] = x;
            probes[nprobe][1] = y;
            probes[nprobe][2] = z;
            nprobe++;
        } else {
            fprintf(stderr, "usage: bench_grid [-n N] [-r RUNS] [-t THREADS] [--small-pages] [--net] [--probe i,j,k]\n");
            return 2;
        }
    }
    if (n < 2 || runs < 1) {
        fprintf(stderr, "bench_grid: need n >= 2 and runs >= 1\n");
        return 2;
    }
    coons_error err = COONS_ERROR_INIT;
    coons_patch *faces[6] = {0};
    double pts[M * M * 3];
    for (int f = 0; f < 6; f++) {
        face_net(f, pts);
        if (coons_patch_new_bspline(3, 3, pts, M, M, NULL, NULL, NULL, &faces[f], &err)) {
            fprintf(stderr, "bench_grid: face %d: %s\n", f, err.message);
            return 1;
        }
    }
    coons_body *body;
    if (coons_body_new_body2(faces, COONS_BLEND_LINEAR, COONS_TOL_DEFAULT, &body, &err)) {
        fprintf(stderr, "bench_grid: body2: %s\n", err.message);
        return 1;
    }
    double *par = malloc(n * sizeof *par);
    for (size_t i = 0; i < n; i++) par[i] = (double)i / (double)(n - 1);
    size_t npts = n * n * n, bytes = npts * 3 * sizeof(double);

    /* Grid evaluation into a fresh array each run (page faults included,
     * as for the write bound), then into a reused, already-touched array. */
    double *t_fresh = malloc((size_t)runs * sizeof(double));
    double *t_warm = malloc((size_t)runs * sizeof(double));
    double *keep = NULL;
    for (int r = 0; r < runs; r++) {
        double *out = fresh(bytes);
        double t0 = now();
        if (coons_body_eval_grid(body, par, n, par, n, par, n, out, &err)) {
            fprintf(stderr, "bench_grid: grid: %s\n", err.message);
            return 1;
        }
        t_fresh[r] = now() - t0;
        if (r == runs - 1)
            keep = out;
        else
            munmap(out, bytes);
    }
    for (int r = 0; r < runs; r++) {
        double t0 = now();
        coons_body_eval_grid(body, par, n, par, n, par, n, keep, &err);
        t_warm[r] = now() - t0;
    }
    double probeval[64][3];
    for (int p = 0; p < nprobe; p++) {
        size_t i = probes[p][0], j = probes[p][1], k = probes[p][2];
        if (i >= n || j >= n || k >= n) {
            fprintf(stderr, "bench_grid: probe out of range\n");
            return 2;
        }
        memcpy(probeval[p], keep + ((i * n + j) * n + k) * 3, sizeof probeval[p]);
    }
    /* The same grid on `threads` threads: fresh and reused output, equal
     * to the one-thread grid byte for byte. */
    if (threads == 0) {
        long c = sysconf(_SC_NPROCESSORS_ONLN);
        threads = c > 0 ? (unsigned)c : 1u;
    }
    double *t_fresh_mt = malloc((size_t)runs * sizeof(double));
    double *t_warm_mt = malloc((size_t)runs * sizeof(double));
    int threads_equal = 1;
    for (int r = 0; r < runs; r++) {
        double *out = fresh(bytes);
        double t0 = now();
        if (coons_body_eval_grid_threads(body, par, n, par, n, par, n, out, threads, &err)) {
            fprintf(stderr, "bench_grid: grid on %u threads: %s\n", threads, err.message);
            return 1;
        }
        t_fresh_mt[r] = now() - t0;
        if (memcmp(out, keep, bytes)) threads_equal = 0;
        munmap(out, bytes);
    }
    double *warm_mt = fresh(bytes);
    memcpy(warm_mt, keep, bytes);
    for (int r = 0; r < runs; r++) {
        double t0 = now();
        coons_body_eval_grid_threads(body, par, n, par, n, par, n, warm_mt, threads, &err);
        t_warm_mt[r] = now() - t0;
    }
    if (memcmp(warm_mt, keep, bytes)) threads_equal = 0;
    munmap(warm_mt, bytes);
    /* The all-core write bound: `threads` threads each storing their slice
     * of a fresh array. */
    double *t_store_mt = malloc((size_t)runs * sizeof(double));
    for (int r = 0; r < runs; r++) {
        double *out = fresh(bytes);
        double t0 = now();
        store_threads(out, 3 * npts, threads);
        t_store_mt[r] = now() - t0;
        munmap(out, bytes);
    }
    qsort(t_fresh_mt, (size_t)runs, sizeof(double), cmp_double);
    qsort(t_warm_mt, (size_t)runs, sizeof(double), cmp_double);
    qsort(t_store_mt, (size_t)runs, sizeof(double), cmp_double);

    /* Memory-write bound: the same number of bytes into a fresh array. */
    double *t_memset = malloc((size_t)runs * sizeof(double));
    double *t_store = malloc((size_t)runs * sizeof(double));
    volatile double sink = 0.0;
    for (int r = 0; r < runs; r++) {
        double *out = fresh(bytes);
        double t0 = now();
        memset(out, 0x3f, bytes); /* not 0: malloc+memset(0) may become calloc */
        t_memset[r] = now() - t0;
        sink += out[npts / 2];
        munmap(out, bytes);
        out = fresh(bytes);
        t0 = now();
        for (size_t m = 0; m < 3 * npts; m++) out[m] = (double)m;
        t_store[r] = now() - t0;
        sink += out[npts / 3];
        munmap(out, bytes);
    }
    /* The same stores into the already-touched array of the warm runs. */
    double *t_warm_store = malloc((size_t)runs * sizeof(double));
    for (int r = 0; r < runs; r++) {
        double t0 = now();
        for (size_t m = 0; m < 3 * npts; m++) keep[m] = (double)m;
        t_warm_store[r] = now() - t0;
        sink += keep[npts / 5];
    }
    (void)sink;
    qsort(t_warm_store, (size_t)runs, sizeof(double), cmp_double);
    qsort(t_fresh, (size_t)runs, sizeof(double), cmp_double);
    qsort(t_warm, (size_t)runs, sizeof(double), cmp_double);
    qsort(t_memset, (size_t)runs, sizeof(double), cmp_double);
    qsort(t_store, (size_t)runs, sizeof(double), cmp_double);
    double bound = t_memset[0] < t_store[0] ? t_memset[0] : t_store[0];

    printf("{\n  \"n\": %zu, \"points\": %zu, \"runs\": %d, \"net\": %d,\n", n, npts, runs, M);
    printf("  \"grid_fresh_s\": %.6f, \"grid_warm_s\": %.6f,\n", t_fresh[0], t_warm[0]);
    printf("  \"grid_fresh_pts_per_s\": %.6e, \"grid_warm_pts_per_s\": %.6e,\n",
           (double)npts / t_fresh[0], (double)npts / t_warm[0]);
    printf("  \"memset_s\": %.6f, \"store_loop_s\": %.6f, \"write_bound_s\": %.6f,\n",
           t_memset[0], t_store[0], bound);
    printf("  \"warm_store_loop_s\": %.6f, \"warm_grid_over_warm_store\": %.3f,\n",
           t_warm_store[0], t_warm[0] / t_warm_store[0]);
    printf("  \"write_bound_pts_per_s\": %.6e, \"grid_over_bound\": %.3f,\n", (double)npts / bound,
           t_fresh[0] / bound);
    printf("  \"threads\": %u, \"threads_equal\": %s, \"grid_fresh_threads_s\": %.6f,\n",
           threads, threads_equal ? "true" : "false", t_fresh_mt[0]);
    printf("  \"grid_warm_threads_s\": %.6f, \"store_loop_threads_s\": %.6f,\n", t_warm_mt[0],
           t_store_mt[0]);
    printf("  \"speedup_fresh\": %.3f, \"speedup_warm\": %.3f, \"threads_over_bound\": %.3f",
           t_fresh[0] / t_fresh_mt[0], t_warm[0] / t_warm_mt[0], t_fresh_mt[0] / t_store_mt[0]);
    if (nprobe) {
        printf(",\n  \"probes\": [");
        for (int p = 0; p < nprobe; p++)
            printf("%s[%zu, %zu, %zu, %.17g, %.17g, %.17g]", p ? ", " : "", probes[p][0],
                   probes[p][1], probes[p][2], probeval[p][0], probeval[p][1], probeval[p][2]);
        printf("]");
    }
    if (print_net) {
        printf(",\n  \"faces\": [");
        for (int f = 0; f < 6; f++) {
            face_net(f, pts);
            printf("%s[", f ? ", " : "");
            for (int m = 0; m < M * M; m++)
                printf("%s[%.17g, %.17g, %.17g]", m ? ", " : "", pts[3 * m], pts[3 * m + 1],
                       pts[3 * m + 2]);
            printf("]");
        }
        printf("]");
    }
    printf("\n}\n");
    munmap(keep, bytes);
    free(par);
    free(t_fresh);
    free(t_warm);
    free(t_memset);
    free(t_store);
    free(t_warm_store);
    coons_body_free(body);
    for (int f = 0; f < 6; f++) coons_patch_free(faces[f]);
    return 0;
}
