/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Faces ruled between two straight lines, meshed as strips spanning their
 * rulings (coons__ruled_faces, ruled.h), for the flat-face pass of the
 * sampler (flat.c): a face that is not flat but straight along one
 * direction needs no lattice lines across its rulings where its measured
 * deviation stays within the tolerance. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "coons_internal.h"
#include "flat.h"
#include "ruled.h"
#include "union_find.h"

/* ---- Faces ruled between two straight lines ------------------------- */

/* The final measurement of a ruled face's strips must stay below this
 * share of the tolerance (ACCEPT_FRACTION of sample.c). */
#define RULED_ACCEPT 0.9
/* Sub-steps per lattice interval of the measurement (MEASURE_STEPS of
 * sample.c: 7 x 7 samples per cell). */
#define RULED_STEPS 6
/* Points per evaluation of the ruled-face measurement. */
#define RULED_BLOCK_POINTS ((size_t)1 << 15)

typedef struct ruled {
    sampler *s;
    int f, sdir;    /* sdir: the straight direction is the face's a (0) or b (1) */
    size_t no, ns;  /* intervals across and along the rulings */
    uint32_t *tri;  /* 3 nt */
    size_t nt, cap;
    int flip;       /* the face's triangles run clockwise in (a, b) */
    int bad;        /* a degenerate triangle */
} ruled;

static uint32_t ruled_id(const ruled *r, size_t io, size_t is)
{
    size_t ia = r->sdir ? io : is, ib = r->sdir ? is : io;
    return coons__uf_find(r->s->uf, coons__sampler_id(r->s, r->f, ia, ib));
}

static const double *ruled_pos(const ruled *r, size_t io, size_t is)
{
    return r->s->pos + 3 * (size_t)ruled_id(r, io, is);
}

/* Smallest angle of triangle pqr (radians); +INFINITY when two corners are
 * one vertex (the triangle drops: a collapsed edge). */
static double tri_angle(const ruled *r, size_t c[3][2])
{
    uint32_t v[3];
    const double *p[3];
    for (int k = 0; k < 3; k++) {
        v[k] = ruled_id(r, c[k][0], c[k][1]);
        p[k] = r->s->pos + 3 * (size_t)v[k];
    }
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) return INFINITY;
    double best = INFINITY;
    for (int k = 0; k < 3; k++) {
        double e1[3], e2[3], x[3];
        v3_sub(e1, p[(k + 1) % 3], p[k]);
        v3_sub(e2, p[(k + 2) % 3], p[k]);
        v3_cross(x, e1, e2);
        best = fmin(best, atan2(v3_norm(x), v3_dot(e1, e2)));
    }
    return best;
}

/* Appends triangle c (lattice points (io, is)) wound as the face's lattice
 * triangles; collapsed ones drop, degenerate ones mark the face bad. */
static int ruled_add(ruled *r, size_t c[3][2])
{
    double ang = tri_angle(r, c);
    if (ang == INFINITY) return 0;
    if (!(ang > 1e-6)) r->bad = 1;
    /* counter-clockwise in the (a, b) index plane, then the face's sense */
    double q[3][2];
    for (int k = 0; k < 3; k++) {
        q[k][0] = (double)(r->sdir ? c[k][0] : c[k][1]);
        q[k][1] = (double)(r->sdir ? c[k][1] : c[k][0]);
    }
    int swap = (coons__orient2(q[0], q[1], q[2]) < 0) != (r->flip != 0);
    if (coons__grow((void **)&r->tri, &r->cap, 3 * (r->nt + 1), sizeof(uint32_t))) return -1;
    uint32_t *t = r->tri + 3 * r->nt++;
    t[0] = ruled_id(r, c[0][0], c[0][1]);
    t[1] = ruled_id(r, c[swap ? 2 : 1][0], c[swap ? 2 : 1][1]);
    t[2] = ruled_id(r, c[swap ? 1 : 2][0], c[swap ? 1 : 2][1]);
    return 0;
}

/* The end cell, between lattice points j0 and j1 along the rulings, of
 * the strip between the full ruling io_full (all its lattice points, which
 * the neighbouring face holds) and the ruling io_short (only j0 and j1): a
 * fan of the full side's segments to the short side's two points, split
 * where the smallest angle is largest. */
static int ruled_fan(ruled *r, size_t io_full, size_t io_short, size_t j0, size_t j1)
{
    size_t best_k = j0;
    double best = -1;
    for (size_t k = j0; k <= j1; k++) {
        double m = INFINITY;
        for (size_t j = j0; j < j1; j++) {
            size_t c[3][2] = {{io_full, j}, {io_full, j + 1}, {io_short, j < k ? j0 : j1}};
            m = fmin(m, tri_angle(r, c));
        }
        size_t c[3][2] = {{io_full, k}, {io_short, j0}, {io_short, j1}};
        m = fmin(m, tri_angle(r, c));
        if (m > best) best = m, best_k = k;
    }
    for (size_t j = j0; j < j1; j++) {
        size_t c[3][2] = {{io_full, j}, {io_full, j + 1}, {io_short, j < best_k ? j0 : j1}};
        if (ruled_add(r, c)) return -1;
    }
    size_t c[3][2] = {{io_full, best_k}, {io_short, j0}, {io_short, j1}};
    return ruled_add(r, c);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The lattice lines across the rulings that a ruled face keeps: q[0] = 0
 * < q[1] < ... < q[*m] = ns, *m >= segs_min segments of the rulings (as
 * far as the lattice has lines) at most max_aspect times longer than the
 * strips' median width (with max_aspect INFINITY and segs_min 1: all of
 * them dropped, *m = 1). q holds ns + 1. */
static coons_status ruled_lines(ruled *r, size_t segs_min, size_t *q, size_t *m)
{
    size_t no = r->no, ns = r->ns;
    const double *ts = r->s->t[r->sdir ? coons__faces[r->f].b : coons__faces[r->f].a];
    double *w = coons__malloc_array(no, sizeof(double)), len = 0;
    if (!w) return coons__error_nomem(r->s->err);
    for (size_t p = 0; p <= no; p++) {
        len = fmax(len, v3_dist(ruled_pos(r, p, 0), ruled_pos(r, p, ns)));
        if (p < no)
            w[p] = 0.5 * (v3_dist(ruled_pos(r, p, 0), ruled_pos(r, p + 1, 0)) +
                          v3_dist(ruled_pos(r, p, ns), ruled_pos(r, p + 1, ns)));
    }
    qsort(w, no, sizeof(double), cmp_double);
    double wm = w[no / 2], k = ceil(len / (r->s->o->max_aspect * wm) - 1e-9);
    coons__free(w);
    size_t segs = !(wm > 0) || !(k < (double)ns) ? ns : k < 1 ? 1 : (size_t)k;
    if (segs < segs_min) segs = segs_min < ns ? segs_min : ns;
    /* the lattice value nearest each k / segs (rulings are parametrized
     * about proportionally to length: they are straight) */
    size_t n = 0, j = 0;
    q[n++] = 0;
    for (size_t i = 1; i < segs; i++) {
        double target = (double)i / (double)segs;
        while (j + 1 < ns && fabs(ts[j + 1] - target) <= fabs(ts[j] - target)) j++;
        if (j > q[n - 1] && j < ns) q[n++] = j;
    }
    q[n++] = ns;
    *m = n - 1;
    return COONS_OK;
}

/* Distance from p to triangle abc (the toolkit's, geom.h). */
static double tri_dist(const double p[3], const double *a, const double *b, const double *c)
{
    return sqrt(coons__tri_dist2(p, a, b, c));
}

/* Evaluates face f at (a, b) for a in av[0..na-1], b in bv[0..nb-1]:
 * out[(i nb + j) 3], scaled. */
static coons_status face_grid(sampler *s, int f, const double *av, size_t na, const double *bv,
                              size_t nb, double *out)
{
    const face_desc *F = &coons__faces[f];
    const double *qv[3];
    size_t c[3];
    qv[F->fixed] = &F->val;
    c[F->fixed] = 1;
    qv[F->a] = av;
    c[F->a] = na;
    qv[F->b] = bv;
    c[F->b] = nb;
    coons_status st = coons_body_eval_grid(s->body, qv[0], c[0], qv[1], c[1], qv[2], c[2], out,
                                           s->err);
    for (size_t i = 0; !st && i < 3 * na * nb; i++) out[i] *= s->scale;
    return st;
}

/* Face f ruled along its direction sdir (0: a, 1: b): every line across
 * the other direction (at the lattice values and the thirds of its
 * intervals) straight, within COONS__FLAT_EPS, at the thirds and the midpoint?
 * Then its mesh is a strip: the lattice lines across the rulings are
 * dropped, each interval across is one quad (two triangles) spanning the
 * rulings, and the two end intervals are fans to the straight edges'
 * lattice points, which the neighbouring faces hold. With a finite
 * max_aspect (the sample option; 4 by default) some lines across stay so
 * that the strips' cells are at most that many times longer than their
 * median width (ruled_lines()): a strip of m segments. Kept (*ok = 1, *tri, *nt)
 * when no triangle is degenerate, it has fewer triangles than the
 * lattice, and the strips' distance to the face, measured as the sampler
 * measures its cells (7 x 7 samples per lattice cell, each to its strip's
 * triangles), stays below RULED_ACCEPT of the tolerance (*dev). A ruled
 * face whose rulings are not parallel (a twisted, doubly curved strip)
 * fails that measurement and keeps its lattice. */
static coons_status ruled_face(sampler *s, int f, int sdir, int flip, uint32_t **tri, size_t *nt,
                               double *dev, int *ok)
{
    const face_desc *F = &coons__faces[f];
    int dir_o = sdir ? F->a : F->b, dir_s = sdir ? F->b : F->a;
    ruled r = {.s = s, .f = f, .sdir = sdir, .no = s->n[dir_o], .ns = s->n[dir_s], .flip = flip};
    size_t no = r.no, ns = r.ns;
    *ok = 0;
    *tri = NULL;
    *nt = 0;
    *dev = 0;
    if (no < 2 || ns < 2) return COONS_OK;
    const double *to = s->t[dir_o], *ts = s->t[dir_s];
    /* Straight rulings. */
    size_t nov = 3 * no + 1, nsv = RULED_STEPS * ns + 1;
    /* the measurement evaluates `block` strips at a time (7 rows each),
     * about RULED_BLOCK_POINTS points: the basis along the rulings is then
     * computed once per block, not once per strip */
    size_t block = RULED_BLOCK_POINTS / ((RULED_STEPS + 1) * nsv);
    if (block < 1) block = 1;
    if (block > no) block = no;
    size_t nrows = block * (RULED_STEPS + 1);
    double *ov = coons__malloc_array(nov > nrows ? nov : nrows, sizeof(double));
    double *sv = coons__malloc_array(nsv > 5 ? nsv : 5, sizeof(double));
    double *pts = coons__malloc_array(nrows * (nsv > 5 ? nsv : 5), 3 * sizeof(double));
    coons_status st = COONS_OK;
    if (!ov || !sv || !pts) {
        st = coons__error_nomem(s->err);
        goto done;
    }
    for (size_t p = 0; p < no; p++)
        for (int j = 0; j < 3; j++) ov[3 * p + (size_t)j] = to[p] + (to[p + 1] - to[p]) * j / 3.0;
    ov[3 * no] = to[no];
    static const double thirds[5] = {0, 1.0 / 3, 0.5, 2.0 / 3, 1};
    for (size_t i = 0; i < nov; i++) {
        st = sdir ? face_grid(s, f, ov + i, 1, thirds, 5, pts)
                  : face_grid(s, f, thirds, 5, ov + i, 1, pts);
        if (st) goto done;
        for (int k = 1; k < 4; k++)
            if (!(tri_dist(pts + 3 * k, pts, pts + 12, pts + 12) <= COONS__FLAT_EPS)) goto done;
    }
    /* The strips: segs_min segments at least, doubled while the
     * measurement fails (a twisted face: shorter segments deviate less). */
    /* cs[p (ns + 1) + k]: strip p's first triangle of segment k (k = m: the
     * strip's end); kq[i]: the segment that holds sample sv[i]. */
    size_t *cs = coons__malloc_array(no * (ns + 1) + 1, sizeof(size_t));
    size_t *ql = coons__malloc_array(ns + 1, sizeof(size_t));
    size_t *kq = coons__malloc_array(nsv, sizeof(size_t));
    if (!cs || !ql || !kq) {
        coons__free(cs);
        coons__free(ql);
        coons__free(kq);
        st = coons__error_nomem(s->err);
        goto done;
    }
    for (size_t q = 0; q < ns; q++)
        for (int j = 0; j < RULED_STEPS; j++)
            sv[RULED_STEPS * q + (size_t)j] = ts[q] + (ts[q + 1] - ts[q]) * j / RULED_STEPS;
    sv[RULED_STEPS * ns] = ts[ns];
    for (size_t segs_min = 1, m = 0; !st && segs_min <= ns;
         segs_min = 2 * (m > segs_min ? m : segs_min)) {
        r.nt = 0;
        r.bad = 0;
        if ((st = ruled_lines(&r, segs_min, ql, &m))) break;
        int fail = 0;
        for (size_t p = 0; p < no && !fail; p++) {
            for (size_t k = 0; k < m && !fail; k++) {
                size_t j0 = ql[k], j1 = ql[k + 1];
                cs[p * (ns + 1) + k] = r.nt;
                if (p == 0) fail = ruled_fan(&r, 0, 1, j0, j1);
                else if (p == no - 1) fail = ruled_fan(&r, no, no - 1, j0, j1);
                else {
                    const double *A = ruled_pos(&r, p, j0), *B = ruled_pos(&r, p + 1, j0),
                                 *C = ruled_pos(&r, p + 1, j1), *D = ruled_pos(&r, p, j1);
                    size_t c1[3][2] = {{p, j0}, {p + 1, j0}, {p + 1, j1}};
                    size_t c2[3][2] = {{p, j0}, {p + 1, j1}, {p, j1}};
                    size_t d1[3][2] = {{p, j0}, {p + 1, j0}, {p, j1}};
                    size_t d2[3][2] = {{p + 1, j0}, {p + 1, j1}, {p, j1}};
                    int dg = v3_dist(B, D) < v3_dist(A, C);
                    fail = ruled_add(&r, dg ? d1 : c1) || ruled_add(&r, dg ? d2 : c2);
                }
            }
            cs[p * (ns + 1) + m] = r.nt;
        }
        for (size_t k = 0; k < m; k++)
            for (size_t i = RULED_STEPS * ql[k]; i <= RULED_STEPS * ql[k + 1]; i++) kq[i] = k;
        if (fail) st = coons__error_nomem(s->err);
        if (st || r.bad || r.nt >= s->face_tri[f + 1] - s->face_tri[f]) break;
        /* The measurement: every sample of a strip's cells against the
         * triangles of its segment and the two next to it (nearer ones do
         * not exist on a face that does not fold back onto itself within a
         * few cells, and farther ones would only lower the measure). */
        /* A sample's distance to its own segment's triangles first: when
         * that is not above the worst so far, the nearer neighbours cannot
         * raise it (the same result, with a third of the distances). */
        double worst = 0;
        for (size_t p0 = 0; p0 < no && !st && worst <= RULED_ACCEPT * s->tol; p0 += block) {
            size_t nb = no - p0 < block ? no - p0 : block, rows = nb * (RULED_STEPS + 1);
            for (size_t p = p0; p < p0 + nb; p++) {
                double *o = ov + (p - p0) * (RULED_STEPS + 1);
                for (int j = 0; j <= RULED_STEPS; j++)
                    o[j] = to[p] + (to[p + 1] - to[p]) * j / RULED_STEPS;
                o[RULED_STEPS] = to[p + 1];
            }
            st = sdir ? face_grid(s, f, ov, rows, sv, nsv, pts)
                      : face_grid(s, f, sv, nsv, ov, rows, pts);
            for (size_t i = 0; !st && i < rows * nsv; i++) {
                size_t row = sdir ? i / nsv : i % rows, q = sdir ? i % nsv : i / rows;
                size_t p = p0 + row / (RULED_STEPS + 1), k = kq[q];
                const size_t *c = cs + p * (ns + 1);
                const double *x = pts + 3 * i;
                double d = INFINITY;
                for (size_t t = c[k]; t < c[k + 1]; t++)
                    d = fmin(d, tri_dist(x, s->pos + 3 * (size_t)r.tri[3 * t],
                                         s->pos + 3 * (size_t)r.tri[3 * t + 1],
                                         s->pos + 3 * (size_t)r.tri[3 * t + 2]));
                if (!(d <= worst)) {
                    size_t k0 = k ? k - 1 : 0, k1 = k + 2 < m ? k + 2 : m;
                    for (size_t t = c[k0]; t < c[k1]; t++)
                        if (t < c[k] || t >= c[k + 1])
                            d = fmin(d, tri_dist(x, s->pos + 3 * (size_t)r.tri[3 * t],
                                                 s->pos + 3 * (size_t)r.tri[3 * t + 1],
                                                 s->pos + 3 * (size_t)r.tri[3 * t + 2]));
                    if (d < INFINITY) worst = fmax(worst, d);
                }
            }
        }
        if (!st && worst <= RULED_ACCEPT * s->tol) {
            *ok = 1;
            *tri = r.tri;
            *nt = r.nt;
            *dev = worst;
            r.tri = NULL;
            break;
        }
    }
    coons__free(cs);
    coons__free(ql);
    coons__free(kq);
done:
    coons__free(r.tri);
    coons__free(ov);
    coons__free(sv);
    coons__free(pts);
    return st;
}

/* Does face f's first lattice triangle run clockwise in (a, b)? (as
 * emit_cells() made it, then orient_outward()). -1: not found. */
static int face_flip(sampler *s, int f)
{
    const face_desc *F = &coons__faces[f];
    size_t na = s->n[F->a], nb = s->n[F->b];
    if (s->face_tri[f] == s->face_tri[f + 1]) return -1;
    const uint32_t *t0 = s->tri + 3 * s->face_tri[f];
    for (size_t p = 0; p < na; p++)
        for (size_t q = 0; q < nb; q++)
            for (int k = 0; k < 2; k++) {
                size_t ia[3], ib[3];
                coons__cell_tri(p, q, s->diag[f][p * nb + q], k, ia, ib);
                uint32_t v[3];
                for (int j = 0; j < 3; j++)
                    v[j] = coons__uf_find(s->uf, coons__sampler_id(s, f, ia[j], ib[j]));
                if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
                if (t0[0] != v[0]) return -1;
                if (t0[1] == v[1] && t0[2] == v[2]) return 0;
                if (t0[1] == v[2] && t0[2] == v[1]) return 1;
                return -1;
            }
    return -1;
}

coons_status coons__ruled_faces(sampler *s, int flat[6], uint32_t *ftri[6], size_t fnt[6],
                                unsigned *bits, double *dev_out)
{
    coons_status st = COONS_OK;
    unsigned ruled_bits = 0;
    double ruled_dev = 0;
    for (int f = 0; f < 6 && !st; f++) {
        if (flat[f] || s->glued & 1 << coons__faces[f].fixed || s->skip & 1u << f) continue;
        int flip = face_flip(s, f);
        if (flip < 0) continue;
        for (int sdir = 1; sdir >= 0 && !st && !flat[f]; sdir--) {
            double dev;
            int ok;
            st = ruled_face(s, f, sdir, flip, &ftri[f], &fnt[f], &dev, &ok);
            if (!st && ok) {
                flat[f] = 1;
                ruled_bits |= 1u << f;
                ruled_dev = fmax(ruled_dev, dev);
            }
        }
    }
    *bits = ruled_bits;
    *dev_out = ruled_dev;
    return st;
}
