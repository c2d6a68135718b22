/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The benchmarks' body (bench_grid, bench_points): a body 2 of bicubic
 * B-spline faces whose nets are the boundary slices of one M^3 lattice of a
 * deformed unit cube, so the faces agree along shared edges; and a
 * monotonic clock. Needs <math.h> and <time.h> (CLOCK_MONOTONIC).
 */
#ifndef COONS_BENCH_BODY_H
#define COONS_BENCH_BODY_H

/* Control net of the faces: an M^3 lattice of a deformed unit cube; the
 * six faces are its boundary slices, so they agree along shared edges. */
#define M 8

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void net_point(int i, int j, int k, double p[3])
{
    double x = (double)i / (M - 1), y = (double)j / (M - 1), z = (double)k / (M - 1);
    p[0] = x + 0.08 * sin(3.0 * y + 1.0) * sin(2.0 * z);
    p[1] = y + 0.06 * cos(2.0 * x + 0.5) * sin(3.0 * z + 0.3);
    p[2] = z + 0.1 * sin(2.5 * x) * cos(1.5 * y) + 0.05 * x * y;
}

/* Face f of body.h order as an M x M net (points[(a*M + b)*3], a along s). */
static void face_net(int f, double *pts)
{
    int fixed = (f & 1) ? M - 1 : 0;
    for (int a = 0; a < M; a++)
        for (int b = 0; b < M; b++) {
            int i, j, k;
            if (f < 2) { /* X_I(v,w): s = v, t = w */
                i = fixed; j = a; k = b;
            } else if (f < 4) { /* Y_J(u,w) */
                i = a; j = fixed; k = b;
            } else { /* Z_K(u,v) */
                i = a; j = b; k = fixed;
            }
            net_point(i, j, k, pts + (a * M + b) * 3);
        }
}

#endif
