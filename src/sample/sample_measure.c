/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The sampler's measurement and refinement (sample.c): the distance of exact
 * boundary points F(s,t) at sub-samples of every lattice cell to the cell's
 * two triangles (an upper bound of their distance to the mesh), the
 * intervals it marks for halving and the shrink factors it predicts
 * (note_need), and the halving itself. See sample.c for the method. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "body_impl.h"
#include "coons_internal.h"
#include "sampler.h"
#include "union_find.h"

/* Distance from p to the cell's two triangles (diagonal dg): an upper bound
 * of the distance from p to the mesh. Both count: on a twisted cell the
 * tilted neighbour of the triangle that holds p's parameters is often the
 * nearer one (taking only that triangle gave the deformed cube example 4
 * times the lattice lines along w). */
static double cell_dist(const double p[3], const double *P00, const double *P10,
                        const double *P01, const double *P11, int dg)
{
    if (!dg)
        return sqrt(dmin(coons__tri_dist2(p, P00, P10, P11), coons__tri_dist2(p, P00, P11, P01)));
    return sqrt(dmin(coons__tri_dist2(p, P00, P10, P01), coons__tri_dist2(p, P10, P11, P01)));
}

static void mark(sampler *s, int d, size_t i)
{
    if (s->t[d][i + 1] - s->t[d][i] >= 2 * COONS__SAMPLE_MIN_WIDTH) s->mark[d][i] = 1;
}

/* Records that interval i of direction d showed the deviation `ratio`
 * times the threshold: the deviation of a smooth surface from its
 * triangles falls like h^2 with the cell's side h, so the interval must
 * shrink about sqrt(ratio) times (never below COONS__SAMPLE_MIN_WIDTH). A kink inside
 * a cell falls only like h: it needs more, so the prediction is low,
 * never high, there. */
static void note_need(sampler *s, int d, size_t i, double ratio)
{
    if (!(ratio > 1)) return;
    double k = sqrt(ratio); /* floored at COONS__SAMPLE_MIN_WIDTH by predict() */
    if (k > s->need[d][i]) s->need[d][i] = k;
}

/* Compares F with the mesh at the (r+1)^2 sub-samples of every cell, keeps
 * the largest distance in s->dev and, when thr > 0, marks the intervals to
 * halve. Rows of sub-samples are evaluated in blocks of cells along a, so
 * that the basis along b is computed once per block. */
coons_status coons__sampler_scan(sampler *s, int r, double thr)
{
    enum { BLOCK_POINTS = 1 << 15 };
    s->dev = 0;
    if (thr > 0)
        for (int d = 0; d < 3; d++) memset(s->need[d], 0, s->n[d] * sizeof(double));
    for (int f = 0; f < 6; f++) {
        const face_desc *F = &coons__faces[f];
        if (s->glued & 1 << F->fixed || s->skip & 1u << f) continue;
        size_t na = s->n[F->a], nb = s->n[F->b], nbs = (size_t)r * nb + 1;
        size_t block = BLOCK_POINTS / ((size_t)r * nbs);
        if (block < 1) block = 1;
        if (block > na) block = na;
        const double *ta = s->t[F->a], *tb = s->t[F->b];
        coons_status st = coons__sampler_ensure(&s->bs, &s->bs_cap, nbs + (size_t)r * block + 1, s->err);
        if (!st) st = coons__sampler_ensure(&s->buf, &s->buf_cap, 3 * ((size_t)r * block + 1) * nbs, s->err);
        if (st) return st;
        double *as = s->bs + nbs;
        for (size_t q = 0; q < nb; q++)
            for (int j = 0; j < r; j++) s->bs[q * r + j] = tb[q] + (tb[q + 1] - tb[q]) * j / r;
        s->bs[nb * r] = tb[nb];
        for (size_t p0 = 0; p0 < na; p0 += block) {
            size_t p1 = p0 + block < na ? p0 + block : na, rows = (p1 - p0) * (size_t)r + 1;
            for (size_t p = p0; p < p1; p++)
                for (int i = 0; i < r; i++)
                    as[(p - p0) * r + i] = ta[p] + (ta[p + 1] - ta[p]) * i / r;
            as[rows - 1] = ta[p1];
            if ((st = coons__sampler_eval_face(s, f, as, rows, s->bs, nbs, s->buf))) return st;
            if (s->o->progress) /* the pass's share: faces, then rows */
                s->o->progress(s->o->userdata, "measure", ((double)f + (double)p1 / na) / 6);
            for (size_t p = p0; p < p1; p++)
                for (size_t q = 0; q < nb; q++) {
                    const uint32_t *id = s->ids[f];
                    const double *P00 = coons__sampler_rep(s, id[p * (nb + 1) + q]);
                    const double *P10 = coons__sampler_rep(s, id[(p + 1) * (nb + 1) + q]);
                    const double *P01 = coons__sampler_rep(s, id[p * (nb + 1) + q + 1]);
                    const double *P11 = coons__sampler_rep(s, id[(p + 1) * (nb + 1) + q + 1]);
                    int dg = s->diag[f][p * nb + q];
                    double ea = 0, eb = 0, ec = 0;
                    for (int i = 0; i <= r; i++)
                        for (int j = 0; j <= r; j++) {
                            int ei = i == 0 || i == r, ej = j == 0 || j == r;
                            if (ei && ej) continue; /* lattice point */
                            size_t row = (p - p0) * (size_t)r + (size_t)i;
                            const double *X = s->buf + 3 * (row * nbs + q * r + j);
                            double e = cell_dist(X, P00, P10, P01, P11, dg);
                            if (ej)
                                ea = dmax(ea, e);
                            else if (ei)
                                eb = dmax(eb, e);
                            else
                                ec = dmax(ec, e);
                        }
                    double e = dmax(ea, dmax(eb, ec));
                    if (e > s->dev) s->dev = e;
                    if (!(thr > 0)) continue;
                    double la = dmax(v3_dist(P00, P10), v3_dist(P01, P11));
                    double lb = dmax(v3_dist(P00, P01), v3_dist(P10, P11));
                    int ma = ea > thr, mb = eb > thr;
                    /* Only the interior is off: halve the longer side, both
                     * when the sides are equal. Sides equal by symmetry come
                     * out a few ulps apart, which way depending on the
                     * rounding of the coordinates (a model scaled by 1e100
                     * halved one side of the Bezier volume's symmetric cells
                     * where the unscaled one halved both): within
                     * COONS__REL_TOL of each other they are equal. */
                    if (ec > thr && !ma && !mb) {
                        ma = la >= lb * (1 - COONS__REL_TOL);
                        mb = lb >= la * (1 - COONS__REL_TOL);
                    }
                    if (ma) mark(s, F->a, p);
                    if (mb) mark(s, F->b, q);
                    note_need(s, F->a, p, (ma && !(ea > thr) ? ec : ea) / thr);
                    note_need(s, F->b, q, (mb && !(eb > thr) ? ec : eb) / thr);
                }
        }
    }
    return COONS_OK;
}

/* Halves the marked intervals; returns how many were split. */
coons_status coons__sampler_refine(sampler *s, size_t *split)
{
    *split = 0;
    for (int d = 0; d < 3; d++) {
        size_t m = 0;
        for (size_t i = 0; i < s->n[d]; i++) m += s->mark[d][i];
        if (!m) continue;
        double *t = coons__malloc_array(s->n[d] + m + 1, sizeof(double));
        if (!t) return coons__error_nomem(s->err);
        size_t k = 0;
        for (size_t i = 0; i < s->n[d]; i++) {
            t[k++] = s->t[d][i];
            if (s->mark[d][i]) t[k++] = 0.5 * (s->t[d][i] + s->t[d][i + 1]);
        }
        t[k] = 1.0;
        coons__free(s->t[d]);
        s->t[d] = t;
        s->n[d] += m;
        *split += m;
    }
    return coons__sampler_alloc_lattices(s);
}
