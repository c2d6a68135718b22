/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * bench_points: times scattered-point evaluation, coons_body_eval_points(),
 * single thread, best of R runs, on P pseudo-random points of [0,1]^3
 * (fixed seed): values alone and with Jacobians and determinants, in
 * microseconds per point. Bodies: every body of each model file given
 * (e.g. examples/spool.json, the body 2 of rational biquadratic faces the
 * free-form deformation maps vertices through), or without files the
 * bicubic B-spline body 2 of bench_grid. The floor, measured in the same
 * run: a trilinear body 0 through the same call (the least work a point
 * can cost there), and ratios against it.
 *
 * To compare two libcoons builds in one run, run this binary twice with
 * LD_LIBRARY_PATH pointing at each build's library directory.
 *
 * Usage: bench_points [-p POINTS] [-r RUNS] [model.json ...]
 * Output: one JSON object on stdout.
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <coons.h>

#include "bench_body.h"

typedef struct timing {
    double values_us, jacobian_us;
} timing;

/* Best of `runs` over the n points: values alone, then values, Jacobians
 * and determinants. */
static int time_body(const coons_body *b, size_t n, const double *uvw, double *xyz,
                     double *jac, double *det, int runs, timing *t)
{
    coons_error err = COONS_ERROR_INIT;
    t->values_us = t->jacobian_us = INFINITY;
    for (int r = 0; r < runs; r++) {
        double t0 = now();
        if (coons_body_eval_points(b, n, uvw, xyz, NULL, NULL, &err)) goto fail;
        double t1 = now();
        if (coons_body_eval_points(b, n, uvw, xyz, jac, det, &err)) goto fail;
        double t2 = now();
        t->values_us = fmin(t->values_us, (t1 - t0) * 1e6 / (double)n);
        t->jacobian_us = fmin(t->jacobian_us, (t2 - t1) * 1e6 / (double)n);
    }
    return 0;
fail:
    fprintf(stderr, "bench_points: %s\n", err.message);
    return 1;
}

static void print_json_string(const char *s)
{
    putchar('"');
    for (; *s; s++) {
        if (*s == '"' || *s == '\\') putchar('\\');
        putchar(*s);
    }
    putchar('"');
}

int main(int argc, char **argv)
{
    size_t n = 200000;
    int runs = 5, first_file = argc;
    for (int a = 1; a < argc; a++) {
        if (!strcmp(argv[a], "-p") && a + 1 < argc)
            n = (size_t)strtoul(argv[++a], NULL, 10);
        else if (!strcmp(argv[a], "-r") && a + 1 < argc)
            runs = atoi(argv[++a]);
        else if (argv[a][0] != '-') {
            first_file = a;
            break;
        } else {
            fprintf(stderr, "usage: bench_points [-p POINTS] [-r RUNS] [model.json ...]\n");
            return 2;
        }
    }
    if (n < 1 || runs < 1) {
        fprintf(stderr, "bench_points: need points >= 1 and runs >= 1\n");
        return 2;
    }
    double *uvw = malloc(3 * n * sizeof *uvw), *xyz = malloc(3 * n * sizeof *xyz);
    double *jac = malloc(9 * n * sizeof *jac), *det = malloc(n * sizeof *det);
    if (!uvw || !xyz || !jac || !det) {
        fprintf(stderr, "bench_points: out of memory\n");
        return 1;
    }
    unsigned long long s = 88172645463325252ULL;
    for (size_t i = 0; i < 3 * n; i++) {
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;
        uvw[i] = (double)(s >> 11) / 9007199254740992.0;
    }
    coons_error err = COONS_ERROR_INIT;

    /* The floor: a trilinear body 0. */
    static const double hex[8][3] = {{0, 0, 0},        {0.1, -0.2, 1.1}, {0.2, 1.0, -0.1},
                                     {-0.1, 1.2, 0.9}, {1.0, 0.1, 0.2},  {1.3, 0.0, 1.2},
                                     {0.9, 0.8, 0.1},  {1.2, 1.1, 1.4}};
    coons_body *floor_body = NULL;
    if (coons_body_new_body0(&hex[0][0], COONS_BLEND_LINEAR, &floor_body, &err)) {
        fprintf(stderr, "bench_points: body0: %s\n", err.message);
        return 1;
    }
    timing fl;
    if (time_body(floor_body, n, uvw, xyz, jac, det, runs, &fl)) return 1;
    coons_body_free(floor_body);

    printf("{\n  \"points\": %zu, \"runs\": %d,\n", n, runs);
    printf("  \"floor_body0_values_us\": %.4f, \"floor_body0_jacobian_us\": %.4f,\n",
           fl.values_us, fl.jacobian_us);
    printf("  \"bodies\": [");
    int count = 0;
    if (first_file == argc) {
        coons_patch *faces[6] = {0};
        double pts[M * M * 3];
        for (int f = 0; f < 6; f++) {
            face_net(f, pts);
            if (coons_patch_new_bspline(3, 3, pts, M, M, NULL, NULL, NULL, &faces[f], &err)) {
                fprintf(stderr, "bench_points: face %d: %s\n", f, err.message);
                return 1;
            }
        }
        coons_body *b = NULL;
        if (coons_body_new_body2(faces, COONS_BLEND_LINEAR, COONS_TOL_DEFAULT, &b, &err)) {
            fprintf(stderr, "bench_points: body2: %s\n", err.message);
            return 1;
        }
        timing t;
        if (time_body(b, n, uvw, xyz, jac, det, runs, &t)) return 1;
        printf("\n    {\"body\": \"bench_grid bicubic body2\", \"values_us\": %.4f, "
               "\"jacobian_us\": %.4f, \"values_over_floor\": %.2f}",
               t.values_us, t.jacobian_us, t.values_us / fl.values_us);
        count++;
        coons_body_free(b);
        for (int f = 0; f < 6; f++) coons_patch_free(faces[f]);
    }
    for (int a = first_file; a < argc; a++) {
        coons_model *m = NULL;
        if (coons_model_load_file(argv[a], NULL, &m, &err)) {
            fprintf(stderr, "bench_points: %s: %s\n", argv[a], err.message);
            return 1;
        }
        for (size_t i = 0; i < coons_model_body_count(m); i++) {
            timing t;
            if (time_body(coons_model_body(m, i), n, uvw, xyz, jac, det, runs, &t)) return 1;
            const char *name = coons_model_body_name(m, i);
            printf("%s\n    {\"file\": ", count ? "," : "");
            print_json_string(argv[a]);
            printf(", \"body\": ");
            print_json_string(name ? name : "");
            printf(", \"values_us\": %.4f, \"jacobian_us\": %.4f, \"values_over_floor\": %.2f}",
                   t.values_us, t.jacobian_us, t.values_us / fl.values_us);
            count++;
        }
        coons_model_free(m);
    }
    printf("\n  ]\n}\n");
    free(uvw);
    free(xyz);
    free(jac);
    free(det);
    return 0;
}
