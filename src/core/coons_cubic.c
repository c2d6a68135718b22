/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The Coons cubic B-spline of seed 002 ("Coons cubic B-spline"):
 * R_s(tau) = C0(tau) P_s + C1(tau) P_s+1 + C2(tau) P_s+2 + C3(tau) P_s+3,
 * tau in [0,1], s = 0..n-3 for an open curve of n+1 points (n-2 segments).
 * Over the whole curve, t in [0,1] is split into equal parts, one per
 * segment, so d/dt = nseg * d/dtau. A closed curve of m points is the open
 * curve of P0..P(m-1), P0, P1, P2 (m segments).
 * Also the clamped-to-open conversion formulas of seed 002 ("Clamped
 * curve") and the Bezier form of each Coons cubic segment.
 */
#include <string.h>

#include "basis.h"
#include "curve_impl.h"

/* Compared by value, not memcmp: -0 and 0 are the same coordinate (a model
 * file may well write "-0"), and the rule is about repeated points. */
static int repeats_first_three(const double *points, size_t count)
{
    const double *tail = points + 3 * (count - 3);
    for (int i = 0; i < 9; i++)
        if (!(points[i] == tail[i])) return 0;
    return 1;
}

coons_status coons_curve_new_coons_cubic(const double *points, size_t count, int closed,
                                         coons_curve **out, coons_error *err)
{
    *out = NULL;
    size_t min = closed ? 3 : 4;
    if (!points || count < min)
        return coons__error_set(err, COONS_E_INVALID,
                                "coons-cubic (%s) needs at least %zu points, got %zu",
                                closed ? "closed" : "open", min, count);
    if (count > COONS_CURVE_MAX_POINTS)
        return coons__error_set(err, COONS_E_LIMIT,
                                "coons-cubic has %zu points, more than the limit of %d", count,
                                COONS_CURVE_MAX_POINTS);
    if (!coons__all_finite(points, 3 * count))
        return coons__error_set(err, COONS_E_INVALID, "coons-cubic: a point is not finite");
    if (closed && count >= 6 && repeats_first_three(points, count))
        return coons__error_set(err, COONS_E_INVALID,
                                "closed coons-cubic: the last three points repeat the first "
                                "three; give the %zu distinct points only",
                                count - 3);
    coons_curve *c = NULL;
    coons_status rc = coons__curve_alloc(&coons__coons_cubic_kind, &c, err);
    if (rc) return rc;
    c->degree = 3;
    c->closed = closed ? 1 : 0;
    c->n = count + (closed ? 3 : 0);
    c->pts = coons__malloc_array(3 * c->n, sizeof(double));
    if (!c->pts) {
        coons__free(c);
        return coons__error_nomem(err);
    }
    memcpy(c->pts, points, 3 * count * sizeof(double));
    if (closed) memcpy(c->pts + 3 * count, points, 9 * sizeof(double));
    *out = c;
    return COONS_OK;
}

static void eval(const coons_curve *c, double t, int order, double out[][3])
{
    size_t nseg = c->n - 3;
    double x = t * (double)nseg;
    size_t s = (size_t)x;
    if (s >= nseg) s = nseg - 1;
    double tau = x - (double)s;
    double b[12];
    coons__coons_basis(tau, order, b);
    const double *P = c->pts + 3 * s;
    double f = 1.0;
    for (int d = 0; d <= order; d++) {
        v3_zero(out[d]);
        for (int j = 0; j < 4; j++) v3_axpy(out[d], b[4 * d + j] * f, P + 3 * j);
        f *= (double)nseg;
    }
}

static coons_status bezier_segments(const coons_curve *c, double *points, size_t capacity,
                                    size_t *segments, int *degree, coons_error *err)
{
    size_t nseg = c->n - 3;
    *segments = nseg;
    *degree = 3;
    if (!points) return COONS_OK;
    if (capacity < nseg * 12)
        return coons__error_set(err, COONS_E_INVALID,
                                "bezier segments need %zu doubles, capacity is %zu", nseg * 12,
                                capacity);
    for (size_t s = 0; s < nseg; s++) {
        const double *P = c->pts + 3 * s;
        double *B = points + 12 * s;
        /* B0 = (P0+4P1+P2)/6, B1 = (2P1+P2)/3, B2 = (P1+2P2)/3, B3 = (P1+4P2+P3)/6 */
        for (int k = 0; k < 3; k++) {
            B[k] = (P[k] + 4.0 * P[3 + k] + P[6 + k]) / 6.0;
            B[3 + k] = (2.0 * P[3 + k] + P[6 + k]) / 3.0;
            B[6 + k] = (P[3 + k] + 2.0 * P[6 + k]) / 3.0;
            B[9 + k] = (P[3 + k] + 4.0 * P[6 + k] + P[9 + k]) / 6.0;
        }
    }
    return COONS_OK;
}

/* The segment ends; closed curves carry P0, P1, P2 again. */
static void breaks(const coons_curve *c, coons__breaks *B) { coons__breaks_uniform(B, c->n - 3); }

static coons_status copy_data(const coons_curve *c, coons_curve *d, coons_error *err)
{
    d->pts = coons__memdup(c->pts, 3 * c->n, sizeof(double));
    return d->pts ? COONS_OK : coons__error_nomem(err);
}

static void free_data(coons_curve *c) { coons__free(c->pts); }

/* The uniform cubic B-spline over the segment ends (seed 002). */
static void space(const coons_curve *c, coons__space *S)
{
    *S = coons__space_poly(3);
    if (c->n > 4) S->cont = 2;
}

const coons__curve_kind coons__coons_cubic_kind = {
    .type = COONS_CURVE_COONS_CUBIC, .eval = eval, .bezier = bezier_segments, .breaks = breaks,
    .copy = copy_data, .free = free_data, .space = space};

coons_status coons_curve_convert_open_to_clamped(const double *open, size_t count, double *clamped,
                                                 coons_error *err)
{
    if (count < 4)
        return coons__error_set(err, COONS_E_INVALID,
                                "open-to-clamped conversion needs at least 4 points, got %zu",
                                count);
    size_t n = count - 1;
    const double *P = open;
    double tmp[5][3];
    for (int k = 0; k < 3; k++) {
        tmp[0][k] = P[k] / 6.0 + 2.0 * P[3 + k] / 3.0 + P[6 + k] / 6.0;
        tmp[1][k] = 2.0 * P[3 + k] / 3.0 + P[6 + k] / 3.0;
        tmp[3][k] = P[3 * (n - 2) + k] / 3.0 + 2.0 * P[3 * (n - 1) + k] / 3.0;
        tmp[4][k] = P[3 * (n - 2) + k] / 6.0 + 2.0 * P[3 * (n - 1) + k] / 3.0 + P[3 * n + k] / 6.0;
    }
    /* P_i = P~_i for 2 <= i <= n-2 (copied first: open and clamped may alias). */
    if (clamped != open)
        for (size_t i = 2; i + 2 <= n; i++) v3_copy(clamped + 3 * i, P + 3 * i);
    v3_copy(clamped, tmp[0]);
    v3_copy(clamped + 3, tmp[1]);
    v3_copy(clamped + 3 * (n - 1), tmp[3]);
    v3_copy(clamped + 3 * n, tmp[4]);
    return COONS_OK;
}
