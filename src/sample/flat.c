/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Flat faces sampled by their boundary polygon (issue 14).
 *
 * Detection is measured, not read from the body's kind: a face is flat
 * when its lattice points and the points at thirds of every cell lie
 * within FLAT_EPS (relative to the body's extent) of the plane of its
 * vector area. On a cell where the face is polynomial of degree <= 3 in
 * each parameter (bilinear, bicubic Coons/B-spline faces; the lattice holds
 * the breakpoints), its distance to the plane is such a polynomial and
 * vanishes on the 4 x 4 samples, hence everywhere; for other faces the
 * adaptive sampler's own measurement already bounds the surface within the
 * tolerance of the cells, which lie in the plane. The face's image must
 * also be the region its boundary polygon bounds (the lattice does not fold
 * over itself): the polygon's area equals the lattice's vector area.
 *
 * Triangulation: Delaunay refinement (Ruppert, "A Delaunay refinement
 * algorithm for quality 2-dimensional mesh generation", J. Algorithms 18,
 * 1995; Shewchuk, "Delaunay refinement algorithms for triangular mesh
 * generation", CGTA 22, 2002) with one change: the polygon's edges are
 * lattice edges that the neighbouring faces share, so they are never split.
 * The boundary points are inserted first (Bowyer-Watson, in a super
 * triangle); every polygon edge must then be a Delaunay edge (else the face
 * keeps its lattice). Triangles with an angle below the bound get their
 * circumcentre inserted; a circumcentre that encroaches on a polygon edge
 * (lies in its diametral circle, or beyond it) is replaced by the apex of
 * the equilateral triangle on that edge, when that apex encroaches on no
 * edge and is not too close to a point. Steiner points never enter a
 * diametral circle, so the polygon's edges stay Delaunay, and the
 * Bowyer-Watson cavities never cross them. Sizes grade from the boundary
 * spacing inward, so a square face with m boundary points gets O(m)
 * triangles instead of O(m^2). Predicates are plain floating point; every
 * result is checked (orientation, polygon edges, total area) and a face
 * whose check fails keeps its lattice triangles. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "coons_internal.h"
#include "flat.h"
#include "union_find.h"

/* Planarity and area-equality tolerance, relative to the body's extent
 * (positions are scaled to about 1): far below any sampling tolerance,
 * far above rounding (a few ulps). */
#define FLAT_EPS 1e-12
#define NONE UINT32_MAX

typedef struct tri2 {
    uint32_t v[3];  /* counter-clockwise */
    uint32_t nb[3]; /* neighbour across the edge opposite v[k], NONE on the hull */
    uint32_t stamp;
    unsigned char alive, inside, done;
} tri2;

typedef struct dt {
    double *xy;
    size_t np, pcap, m; /* ring points 0..m-1, super triangle m..m+2 */
    tri2 *t;
    size_t nt, tcap;
    uint32_t stamp;
    uint32_t *stack, *cav, *be, *fresh;
    size_t scap, ccap, becap, fcap, slotcap, ncav, nbe, nfresh;
    uint32_t *slot; /* per point: the new triangle whose edge starts there */
    int constrained;
    uint32_t enc_a, enc_b; /* the encroached polygon edge */
    coons_error *err;
} dt;

enum { INS_OK = 0, INS_FAIL = 1, INS_ENCROACH = 2, INS_NOMEM = -1 };

static int grow(void **p, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap) return 0;
    size_t c = *cap ? *cap : 16;
    while (c < need) c *= 2;
    void *q = coons__realloc(*p, c * size);
    if (!q) return -1;
    *p = q;
    *cap = c;
    return 0;
}

static inline const double *P(const dt *d, uint32_t i) { return d->xy + 2 * (size_t)i; }

/* The predicates treat values within a relative DEGENERATE of their
 * terms' magnitude as zero (collinear, cocircular): the lattice's
 * boundary points are collinear along straight edges and cocircular on
 * grids, and the rounding of their coordinates (a model scaled by 10^k
 * rounds differently from the unscaled one) must not decide how they are
 * triangulated; only exact ties are broken, and always the same way. */
#define DEGENERATE 1e-10

static inline double orient(const double *a, const double *b, const double *c)
{
    double l = (b[0] - a[0]) * (c[1] - a[1]), r = (b[1] - a[1]) * (c[0] - a[0]);
    return fabs(l - r) <= DEGENERATE * (fabs(l) + fabs(r)) ? 0.0 : l - r;
}

/* > 0 when p is inside the circle through a, b, c (ccw). */
static double incircle(const double *a, const double *b, const double *c, const double *p)
{
    double ax = a[0] - p[0], ay = a[1] - p[1], bx = b[0] - p[0], by = b[1] - p[1];
    double cx = c[0] - p[0], cy = c[1] - p[1];
    double a2 = ax * ax + ay * ay, b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    double det = ax * (by * c2 - b2 * cy) - ay * (bx * c2 - b2 * cx) + a2 * (bx * cy - by * cx);
    double perm = (fabs(bx * cy) + fabs(by * cx)) * a2 + (fabs(cx * ay) + fabs(cy * ax)) * b2 +
                  (fabs(ax * by) + fabs(ay * bx)) * c2;
    return fabs(det) <= DEGENERATE * perm ? 0.0 : det;
}

/* Is ab an edge of the polygon (in either direction)? */
static inline int is_seg(const dt *d, uint32_t a, uint32_t b)
{
    size_t m = d->m;
    return a < m && b < m && ((size_t)b == (a + 1) % m || (size_t)a == (b + 1) % m);
}

static inline int seg_barrier(const dt *d, uint32_t a, uint32_t b)
{
    return d->constrained && is_seg(d, a, b);
}

/* Walks from triangle `start` to the one holding p. INS_ENCROACH when the
 * walk must cross a polygon edge (constrained phase), INS_FAIL when it
 * leaves the hull or does not end. */
static int locate(dt *d, const double *p, uint32_t start, uint32_t *out)
{
    uint32_t t = start;
    size_t limit = 4 * d->nt + 64;
    for (size_t step = 0; step < limit; step++) {
        const tri2 *T = &d->t[t];
        int moved = 0;
        for (int j = 0; j < 3; j++) {
            int k = (int)(((size_t)j + step) % 3); /* rotating start: no cycles on ties */
            uint32_t a = T->v[(k + 1) % 3], b = T->v[(k + 2) % 3];
            if (orient(P(d, a), P(d, b), p) < 0) {
                if (seg_barrier(d, a, b)) {
                    d->enc_a = a;
                    d->enc_b = b;
                    return INS_ENCROACH;
                }
                if (T->nb[k] == NONE) return INS_FAIL;
                t = T->nb[k];
                moved = 1;
                break;
            }
        }
        if (!moved) {
            *out = t;
            return INS_OK;
        }
    }
    return INS_FAIL;
}

static int new_tri(dt *d, uint32_t *id)
{
    if (d->ncav) { /* reuse a cavity's slot */
        *id = d->cav[--d->ncav];
        return 0;
    }
    if (grow((void **)&d->t, &d->tcap, d->nt + 1, sizeof(tri2))) return -1;
    *id = (uint32_t)d->nt++;
    return 0;
}

static int cmp_u32(const void *x, const void *y)
{
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return a < b ? -1 : a > b;
}

/* Bowyer-Watson insertion of p, starting the walk at `start`. Rejected
 * (nothing changed) when p is within mindist of a cavity vertex (its
 * nearest point is one), encroaches on a polygon edge (constrained phase),
 * or the cavity is not star-shaped from p (rounding). The new triangles
 * are left in d->fresh. */
static int insert(dt *d, double px, double py, uint32_t start, double mindist)
{
    double p[2] = {px, py};
    uint32_t t0;
    int r = locate(d, p, start, &t0);
    if (r != INS_OK) return r;
    if (++d->stamp == 0) {
        for (size_t i = 0; i < d->nt; i++) d->t[i].stamp = 0;
        d->stamp = 1;
    }
    d->ncav = 0;
    size_t sp = 0;
    if (grow((void **)&d->stack, &d->scap, 1, 4) || grow((void **)&d->cav, &d->ccap, 1, 4))
        return INS_NOMEM;
    d->stack[sp++] = t0;
    d->cav[d->ncav++] = t0;
    d->t[t0].stamp = d->stamp;
    while (sp) {
        uint32_t t = d->stack[--sp];
        for (int k = 0; k < 3; k++) {
            uint32_t n = d->t[t].nb[k];
            if (n == NONE || d->t[n].stamp == d->stamp) continue;
            if (seg_barrier(d, d->t[t].v[(k + 1) % 3], d->t[t].v[(k + 2) % 3])) continue;
            const tri2 *N = &d->t[n];
            if (!(incircle(P(d, N->v[0]), P(d, N->v[1]), P(d, N->v[2]), p) > 0)) continue;
            if (grow((void **)&d->stack, &d->scap, sp + 1, 4) ||
                grow((void **)&d->cav, &d->ccap, d->ncav + 1, 4))
                return INS_NOMEM;
            d->t[n].stamp = d->stamp;
            d->stack[sp++] = n;
            d->cav[d->ncav++] = n;
        }
    }
    /* The cavity in index order: the new triangles' slots and order then
     * depend on the cavity alone, not on the triangle the walk ended in
     * (of two, when p lies on their common edge). */
    if (d->ncav > 24) {
        /* (cavities along a straight run of boundary points reach hundreds
         * of triangles: an insertion sort was most of the triangulation) */
        qsort(d->cav, d->ncav, sizeof *d->cav, cmp_u32);
    } else {
        for (size_t i = 1; i < d->ncav; i++)
            for (size_t j = i; j > 0 && d->cav[j - 1] > d->cav[j]; j--) {
                uint32_t x = d->cav[j];
                d->cav[j] = d->cav[j - 1];
                d->cav[j - 1] = x;
            }
    }
    /* Cavity boundary: (a, b, outside neighbour, cavity triangle). */
    d->nbe = 0;
    for (size_t i = 0; i < d->ncav; i++) {
        const tri2 *T = &d->t[d->cav[i]];
        for (int k = 0; k < 3; k++) {
            uint32_t n = T->nb[k], a = T->v[(k + 1) % 3], b = T->v[(k + 2) % 3];
            if (n != NONE && d->t[n].stamp == d->stamp && !seg_barrier(d, a, b)) continue;
            const double *A = P(d, a), *B = P(d, b);
            double da = hypot(p[0] - A[0], p[1] - A[1]);
            /* Encroachment: p in the edge's diametral lens (it sees the
             * edge under more than 120 degrees; Shewchuk 2002, 3.1), also
             * on the edge itself (a circumcentre of a right triangle on
             * it): before the orientation test, which fails there. */
            double db = hypot(p[0] - B[0], p[1] - B[1]);
            if (d->constrained && is_seg(d, a, b) &&
                (p[0] - A[0]) * (p[0] - B[0]) + (p[1] - A[1]) * (p[1] - B[1]) < -0.5 * da * db) {
                d->enc_a = a;
                d->enc_b = b;
                return INS_ENCROACH;
            }
            if (!(orient(A, B, p) > 0)) return INS_FAIL;
            if (!(da > mindist)) return INS_FAIL;
            if (grow((void **)&d->be, &d->becap, 4 * (d->nbe + 1), 4)) return INS_NOMEM;
            uint32_t *e = d->be + 4 * d->nbe++;
            e[0] = a, e[1] = b, e[2] = n, e[3] = d->cav[i];
        }
    }
    /* Commit. */
    if (grow((void **)&d->xy, &d->pcap, 2 * (d->np + 1), sizeof(double)) ||
        grow((void **)&d->slot, &d->slotcap, d->np + 1, 4) ||
        grow((void **)&d->fresh, &d->fcap, d->nbe, 4))
        return INS_NOMEM;
    uint32_t pi = (uint32_t)d->np++;
    d->xy[2 * (size_t)pi] = px;
    d->xy[2 * (size_t)pi + 1] = py;
    for (size_t i = 0; i < d->ncav; i++) d->t[d->cav[i]].alive = 0;
    d->nfresh = 0;
    for (size_t i = 0; i < d->nbe; i++) {
        uint32_t *e = d->be + 4 * i, id;
        if (new_tri(d, &id)) return INS_NOMEM;
        tri2 *T = &d->t[id];
        T->v[0] = e[0], T->v[1] = e[1], T->v[2] = pi;
        T->nb[2] = e[2];
        T->alive = 1;
        T->inside = (unsigned char)d->constrained;
        T->done = 0;
        T->stamp = 0;
        if (e[2] != NONE) {
            tri2 *N = &d->t[e[2]];
            for (int k = 0; k < 3; k++)
                if (N->nb[k] == e[3] && N->v[(k + 1) % 3] == e[1] && N->v[(k + 2) % 3] == e[0])
                    N->nb[k] = id;
        }
        d->slot[e[0]] = id;
        d->fresh[d->nfresh++] = id;
    }
    for (size_t i = 0; i < d->nfresh; i++) {
        tri2 *T = &d->t[d->fresh[i]];
        T->nb[0] = d->slot[T->v[1]]; /* edge b -> p: the triangle starting at b */
    }
    for (size_t i = 0; i < d->nfresh; i++) {
        uint32_t id = d->fresh[i];
        d->t[d->t[id].nb[0]].nb[1] = id;
    }
    return INS_OK;
}

/* Shortest edge over circumradius is 2 sin(smallest angle). */
static int is_bad(const dt *d, const tri2 *T, double sin_min, double c[2])
{
    const double *a = P(d, T->v[0]), *b = P(d, T->v[1]), *q = P(d, T->v[2]);
    double bx = b[0] - a[0], by = b[1] - a[1], cx = q[0] - a[0], cy = q[1] - a[1];
    double den = 2 * (bx * cy - by * cx);
    if (!(den > 0)) return 0;
    double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    double ux = (cy * b2 - by * c2) / den, uy = (bx * c2 - cx * b2) / den;
    double r2 = ux * ux + uy * uy;
    double l2 = fmin(b2, fmin(c2, (q[0] - b[0]) * (q[0] - b[0]) + (q[1] - b[1]) * (q[1] - b[1])));
    c[0] = a[0] + ux;
    c[1] = a[1] + uy;
    return l2 < 4 * sin_min * sin_min * r2;
}

static void dt_free(dt *d)
{
    coons__free(d->xy);
    coons__free(d->t);
    coons__free(d->stack);
    coons__free(d->cav);
    coons__free(d->be);
    coons__free(d->fresh);
    coons__free(d->slot);
}

/* Refinement: a FIFO of bad triangles. */
static int refine_quality(dt *d, double min_angle, size_t max_steiner)
{
    double sin_min = sin(min_angle * 3.14159265358979323846 / 180.0);
    uint32_t *queue = NULL;
    size_t qcap = 0, qh = 0, qt = 0, steiner = 0;
    int r = INS_OK;
    for (size_t i = 0; i < d->nt; i++)
        if (d->t[i].alive && d->t[i].inside) {
            if (grow((void **)&queue, &qcap, qt + 1, 4)) {
                coons__free(queue);
                return INS_NOMEM;
            }
            queue[qt++] = (uint32_t)i;
        }
    while (qh < qt && steiner < max_steiner) {
        uint32_t t = queue[qh++];
        tri2 *T = &d->t[t];
        double c[2];
        if (!T->alive || T->done || !is_bad(d, T, sin_min, c)) continue;
        T->done = 1; /* tried once: what follows cannot fix it, or removes it */
        double lmin = INFINITY;
        for (int k = 0; k < 3; k++) {
            const double *a = P(d, T->v[k]), *b = P(d, T->v[(k + 1) % 3]);
            lmin = fmin(lmin, hypot(b[0] - a[0], b[1] - a[1]));
        }
        r = insert(d, c[0], c[1], t, 1e-3 * lmin);
        if (r == INS_ENCROACH) {
            uint32_t a = d->enc_a, b = d->enc_b;
            if ((size_t)a != (b + 1) % d->m) { /* a -> b in ring order: inside on the left */
                uint32_t x = a;
                a = b;
                b = x;
            }
            if ((size_t)b != (a + 1) % d->m) {
                uint32_t x = a;
                a = b;
                b = x;
            }
            /* Apexes of isosceles triangles on the edge, base angles 60,
             * 45 and 32 degrees (above 30: outside the edge's lens). */
            static const double height[3] = {0.8660254037844386, 0.5, 0.3124};
            const double *A = P(d, a), *B = P(d, b);
            double ex = B[0] - A[0], ey = B[1] - A[1], L = hypot(ex, ey);
            for (int h = 0; h < 3; h++) {
                double qx = 0.5 * (A[0] + B[0]) - height[h] * ey;
                double qy = 0.5 * (A[1] + B[1]) + height[h] * ex;
                r = insert(d, qx, qy, t, 0.9 * height[h] * L);
                if (r == INS_OK || r == INS_NOMEM) break;
            }
        }
        if (r == INS_NOMEM) break;
        if (r != INS_OK) {
            r = INS_OK;
            continue;
        }
        steiner++;
        if (grow((void **)&queue, &qcap, qt + d->nfresh, 4)) {
            r = INS_NOMEM;
            break;
        }
        if (qh > qcap / 2) { /* compact the consumed head */
            memmove(queue, queue + qh, (qt - qh) * sizeof *queue);
            qt -= qh;
            qh = 0;
        }
        for (size_t i = 0; i < d->nfresh; i++) queue[qt++] = d->fresh[i];
    }
    coons__free(queue);
    return r;
}

coons_status coons__polygon_mesh(const double *xy, size_t m, double min_angle, double **pts,
                                 size_t *ns, uint32_t **tri, size_t *nt, int *ok,
                                 coons_error *err)
{
    *pts = NULL;
    *tri = NULL;
    *ns = *nt = 0;
    *ok = 0;
    if (m < 3 || m > UINT32_MAX / 4) return COONS_OK;
    dt d;
    memset(&d, 0, sizeof d);
    d.m = m;
    d.err = err;
    int r = INS_OK, why = 0;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, area2 = 0;
    for (size_t i = 0; i < m; i++) {
        const double *a = xy + 2 * i, *b = xy + 2 * ((i + 1) % m);
        area2 += a[0] * b[1] - a[1] * b[0];
        for (int k = 0; k < 2; k++) lo[k] = fmin(lo[k], a[k]), hi[k] = fmax(hi[k], a[k]);
    }
    double D = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(area2 > 0) || !(D > 0) || !isfinite(D)) return COONS_OK;
    if (grow((void **)&d.xy, &d.pcap, 2 * (m + 3), sizeof(double)) ||
        grow((void **)&d.slot, &d.slotcap, m + 3, 4) ||
        grow((void **)&d.t, &d.tcap, 1, sizeof(tri2)))
        goto nomem;
    memcpy(d.xy, xy, 2 * m * sizeof(double));
    double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
    double sup[6] = {cx - 20 * D, cy - 10 * D, cx + 20 * D, cy - 10 * D, cx, cy + 20 * D};
    memcpy(d.xy + 2 * m, sup, sizeof sup);
    d.np = m + 3;
    tri2 *S = &d.t[0];
    memset(S, 0, sizeof *S);
    S->v[0] = (uint32_t)m, S->v[1] = (uint32_t)m + 1, S->v[2] = (uint32_t)m + 2;
    S->nb[0] = S->nb[1] = S->nb[2] = NONE;
    S->alive = 1;
    d.nt = 1;
    /* Boundary points in ring order (each near the last: short walks);
     * insert() numbers ring point i m+3+i, renumbered to i afterwards
     * (xy[0..m-1] already holds the same coordinates). */
    uint32_t last = 0;
    for (size_t i = 0; i < m; i++) {
        r = insert(&d, xy[2 * i], xy[2 * i + 1], last, 1e-12 * D);
        if (r == INS_NOMEM) goto nomem;
        if (r != INS_OK) { why = __LINE__; goto reject; }
        last = d.fresh[0];
    }
    for (size_t i = 0; i < d.nt; i++)
        for (int k = 0; k < 3; k++)
            if (d.t[i].v[k] >= m + 3) d.t[i].v[k] -= (uint32_t)(m + 3);
    d.np = m + 3;
    /* Every polygon edge a triangle edge, the interior flooded from them. */
    {
        uint32_t *seg = coons__malloc_array(m, sizeof(uint32_t));
        uint32_t *stack = coons__malloc_array(d.nt ? d.nt : 1, sizeof(uint32_t));
        if (!seg || !stack) {
            coons__free(seg);
            coons__free(stack);
            goto nomem;
        }
        for (size_t i = 0; i < m; i++) seg[i] = NONE;
        for (size_t i = 0; i < d.nt; i++) {
            if (!d.t[i].alive) continue;
            for (int k = 0; k < 3; k++) {
                uint32_t a = d.t[i].v[(k + 1) % 3], b = d.t[i].v[(k + 2) % 3];
                if (a < m && (size_t)b == (a + 1) % m) seg[a] = (uint32_t)i;
            }
        }
        size_t sp = 0;
        int bad = 0;
        for (size_t i = 0; i < m && !bad; i++) {
            if (seg[i] == NONE) bad = 1;
            else if (!d.t[seg[i]].inside) {
                d.t[seg[i]].inside = 1;
                stack[sp++] = seg[i];
            }
        }
        while (!bad && sp) {
            uint32_t t = stack[--sp];
            for (int k = 0; k < 3 && !bad; k++) {
                if (d.t[t].v[k] >= m) bad = 1; /* reached the super triangle */
                uint32_t n = d.t[t].nb[k];
                if (is_seg(&d, d.t[t].v[(k + 1) % 3], d.t[t].v[(k + 2) % 3])) continue;
                if (n == NONE) {
                    bad = 1;
                    break;
                }
                if (d.t[n].inside) continue;
                d.t[n].inside = 1;
                stack[sp++] = n;
            }
        }
        coons__free(seg);
        coons__free(stack);
        if (bad) { why = __LINE__; goto reject; }
    }
    d.constrained = 1;
    r = refine_quality(&d, min_angle, 8 * m + 32);
    if (r == INS_NOMEM) goto nomem;
    /* Output and its checks. */
    size_t ntri = 0;
    double sum2 = 0;
    for (size_t i = 0; i < d.nt; i++) {
        const tri2 *T = &d.t[i];
        if (!T->alive || !T->inside) continue;
        double o = orient(P(&d, T->v[0]), P(&d, T->v[1]), P(&d, T->v[2]));
        if (!(o > 0)) { why = __LINE__; goto reject; }
        for (int k = 0; k < 3; k++) {
            if (T->v[k] >= m && T->v[k] < m + 3) { why = __LINE__; goto reject; }
            uint32_t n = T->nb[k];
            if (!is_seg(&d, T->v[(k + 1) % 3], T->v[(k + 2) % 3]) &&
                (n == NONE || !d.t[n].alive || !d.t[n].inside))
                { why = __LINE__; goto reject; }
        }
        sum2 += o;
        ntri++;
    }
    if (!(fabs(sum2 - area2) <= FLAT_EPS * area2 * 1e3)) { why = __LINE__; goto reject; }
    size_t nsp = d.np - m - 3;
    *tri = coons__malloc_array(ntri, 3 * sizeof(uint32_t));
    *pts = nsp ? coons__malloc_array(nsp, 2 * sizeof(double)) : NULL;
    if (!*tri || (nsp && !*pts)) {
        coons__free(*tri);
        coons__free(*pts);
        *tri = NULL;
        *pts = NULL;
        goto nomem;
    }
    if (nsp) memcpy(*pts, d.xy + 2 * (m + 3), nsp * 2 * sizeof(double));
    size_t k3 = 0;
    size_t segs = 0;
    for (size_t i = 0; i < d.nt; i++) {
        const tri2 *T = &d.t[i];
        if (!T->alive || !T->inside) continue;
        for (int k = 0; k < 3; k++) {
            uint32_t v = T->v[k];
            (*tri)[k3++] = v < m ? v : v - 3;
            uint32_t a = T->v[(k + 1) % 3], b = T->v[(k + 2) % 3];
            if (a < m && (size_t)b == (a + 1) % m) segs++;
        }
    }
    if (segs != m) {
        coons__free(*tri);
        coons__free(*pts);
        *tri = NULL;
        *pts = NULL;
        { why = __LINE__; goto reject; }
    }
    *ns = nsp;
    *nt = ntri;
    *ok = 1;
    dt_free(&d);
    return COONS_OK;
reject:
    (void)why; /* the check that failed (kept for debugging) */
    dt_free(&d);
    return COONS_OK;
nomem:
    dt_free(&d);
    return coons__error_nomem(err);
}

/* ---- Faces of a sampled body ---------------------------------------- */

/* Is face f flat? n gets the unit normal of its (outward) triangles, o a
 * point of it. *flat = 0 on any doubt. */
static coons_status face_plane(sampler *s, int f, double n[3], double o[3], double *area2,
                               int *flat)
{
    const face_desc *F = &coons__faces[f];
    size_t na = s->n[F->a], nb = s->n[F->b];
    double N[3] = {0, 0, 0};
    *flat = 0;
    size_t t0 = s->face_tri[f], t1 = s->face_tri[f + 1];
    if (t0 == t1) return COONS_OK;
    v3_copy(o, s->pos + 3 * (size_t)s->tri[3 * t0]);
    for (size_t t = t0; t < t1; t++) {
        double a[3], b[3], c[3];
        v3_sub(a, s->pos + 3 * (size_t)s->tri[3 * t + 1], s->pos + 3 * (size_t)s->tri[3 * t]);
        v3_sub(b, s->pos + 3 * (size_t)s->tri[3 * t + 2], s->pos + 3 * (size_t)s->tri[3 * t]);
        v3_cross(c, a, b);
        v3_add(N, N, c);
    }
    double len = v3_norm(N);
    if (!(len > 1e-6)) return COONS_OK; /* a sliver or a face shrunk to a curve */
    *area2 = len;
    v3_scale(n, N, 1.0 / len);
    for (size_t ia = 0; ia <= na; ia++)
        for (size_t ib = 0; ib <= nb; ib++) {
            double q[3];
            v3_sub(q, s->pos + 3 * (size_t)coons__uf_find(s->uf, coons__sampler_id(s, f, ia, ib)), o);
            if (!(fabs(v3_dot(q, n)) <= FLAT_EPS)) return COONS_OK;
        }
    /* Thirds of every cell, a row of samples at a time. */
    size_t nbs = 3 * nb + 1;
    double *bv = coons__malloc_array(nbs, sizeof(double));
    double *row = coons__malloc_array(nbs, 3 * sizeof(double));
    if (!bv || !row) {
        coons__free(bv);
        coons__free(row);
        return coons__error_nomem(s->err);
    }
    const double *ta = s->t[F->a], *tb = s->t[F->b];
    for (size_t q = 0; q < nb; q++)
        for (int j = 0; j < 3; j++) bv[3 * q + (size_t)j] = tb[q] + (tb[q + 1] - tb[q]) * j / 3.0;
    bv[3 * nb] = tb[nb];
    coons_status st = COONS_OK;
    int ok = 1;
    for (size_t i = 0; i <= 3 * na && ok && !st; i++) {
        size_t p = i / 3;
        double av = p < na ? ta[p] + (ta[p + 1] - ta[p]) * (double)(i % 3) / 3.0 : ta[na];
        const double *qv[3];
        size_t c[3];
        qv[F->fixed] = &F->val;
        c[F->fixed] = 1;
        qv[F->a] = &av;
        c[F->a] = 1;
        qv[F->b] = bv;
        c[F->b] = nbs;
        st = coons_body_eval_grid(s->body, qv[0], c[0], qv[1], c[1], qv[2], c[2], row, s->err);
        for (size_t j = 0; j < nbs && !st && ok; j++) {
            double x[3];
            v3_scale(x, row + 3 * j, s->scale);
            v3_sub(x, x, o);
            if (!(fabs(v3_dot(x, n)) <= FLAT_EPS)) ok = 0;
        }
    }
    coons__free(bv);
    coons__free(row);
    *flat = ok && !st;
    return st;
}

/* The face's boundary ring of representative vertices, without repeats
 * of collapsed edges; *m = 0 when a vertex comes back (a pinched face). */
static coons_status face_ring(sampler *s, int f, unsigned char *seen, uint32_t **ring, size_t *m)
{
    const face_desc *F = &coons__faces[f];
    size_t na = s->n[F->a], nb = s->n[F->b], k = 0;
    *m = 0;
    uint32_t *r = coons__malloc_array(2 * (na + nb), sizeof(uint32_t));
    if (!r) return coons__error_nomem(s->err);
    for (size_t i = 0; i < 2 * (na + nb); i++) {
        size_t ia, ib;
        if (i < na) ia = i, ib = 0;
        else if (i < na + nb) ia = na, ib = i - na;
        else if (i < 2 * na + nb) ia = 2 * na + nb - i, ib = nb;
        else ia = 0, ib = 2 * (na + nb) - i;
        uint32_t v = coons__uf_find(s->uf, coons__sampler_id(s, f, ia, ib));
        if (k && r[k - 1] == v) continue;
        r[k++] = v;
    }
    while (k > 1 && r[k - 1] == r[0]) k--;
    int pinched = 0;
    for (size_t i = 0; i < k; i++) {
        if (seen[r[i]]) pinched = 1;
        seen[r[i]] = 1;
    }
    for (size_t i = 0; i < k; i++) seen[r[i]] = 0;
    *ring = r;
    *m = pinched || k < 3 ? 0 : k;
    return COONS_OK;
}

/* ---- Parameters of the Steiner points -------------------------------- */

/* Twice the signed area of abc in the plane. */
static inline double orient2(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* The corners (ia, ib) of triangle k (0, 1) of cell (p, q) split by
 * diagonal dg (as emit_cells() in sample.c splits it). */
static void cell_tri(size_t p, size_t q, unsigned char dg, int k, size_t ia[3], size_t ib[3])
{
    /* A = (p,q), B = (p+1,q), C = (p+1,q+1), D = (p,q+1) */
    static const int ca[2][2][3] = {{{0, 1, 1}, {0, 1, 0}}, {{0, 1, 0}, {1, 1, 0}}};
    static const int cb[2][2][3] = {{{0, 0, 1}, {0, 1, 1}}, {{0, 0, 1}, {0, 1, 1}}};
    for (int j = 0; j < 3; j++) {
        ia[j] = p + (size_t)ca[dg][k][j];
        ib[j] = q + (size_t)cb[dg][k][j];
    }
}

/* The face's parameters (a, b) of the point p of its plane: the lattice
 * triangle of face f (in the plane, 2-D points xy of its lattice points)
 * holding p, found by a walk over the lattice cells from `*cell`, gives
 * them by barycentric interpolation, exact where the face is affine;
 * Newton's method on the body's map (its Jacobian) then solves
 * F(a, b) = p to rounding. *found = 0 when it does not converge. */
static void locate_params(sampler *s, int f, const double *xy, double sigma, const double p[2],
                          const double o[3], const double e1[3], const double e2[3],
                          const double n[3], size_t *cell, double ab[2], int *found)
{
    const face_desc *F = &coons__faces[f];
    size_t na = s->n[F->a], nb = s->n[F->b], cp = *cell / nb, cq = *cell % nb;
    const double *ta = s->t[F->a], *tb = s->t[F->b];
    double best = -INFINITY;
    *found = 0;
    ab[0] = ab[1] = 0.5;
    for (size_t step = 0, limit = 2 * (na + nb) + 8; step < limit; step++) {
        /* The cell's two triangles: barycentric coordinates of p. */
        for (int k = 0; k < 2; k++) {
            size_t ia[3], ib[3];
            cell_tri(cp, cq, s->diag[f][cp * nb + cq], k, ia, ib);
            const double *c[3];
            for (int j = 0; j < 3; j++) c[j] = xy + 2 * (ia[j] * (nb + 1) + ib[j]);
            double ar = orient2(c[0], c[1], c[2]);
            if (!(fabs(ar) > 0)) continue; /* collapsed */
            double l[3] = {orient2(c[1], c[2], p) / ar, orient2(c[2], c[0], p) / ar,
                           orient2(c[0], c[1], p) / ar};
            double mn = fmin(l[0], fmin(l[1], l[2]));
            if (mn > best) {
                best = mn;
                ab[0] = ab[1] = 0;
                for (int j = 0; j < 3; j++) {
                    ab[0] += l[j] * ta[ia[j]];
                    ab[1] += l[j] * tb[ib[j]];
                }
                *cell = cp * nb + cq;
            }
        }
        if (best >= -1e-9) break;
        /* Out of the cell: across an edge that p lies beyond (the cell
         * runs A B C D counter-clockwise when sigma > 0). */
        const double *A = xy + 2 * (cp * (nb + 1) + cq), *B = xy + 2 * ((cp + 1) * (nb + 1) + cq);
        const double *C = B + 2, *D = A + 2;
        const double *ed[4][2] = {{A, B}, {B, C}, {C, D}, {D, A}};
        int ok[4] = {cq > 0, cp + 1 < na, cq + 1 < nb, cp > 0}, moved = 0;
        for (int j = 0; j < 4 && !moved; j++) {
            int k = (int)((step + (size_t)j) % 4);
            if (!ok[k] || !(sigma * orient2(ed[k][0], ed[k][1], p) < 0)) continue;
            if (k == 0) cq--;
            else if (k == 1) cp++;
            else if (k == 2) cq++;
            else cp--;
            moved = 1;
        }
        if (!moved) break;
    }
    double P3[3];
    v3_copy(P3, o);
    v3_axpy(P3, p[0], e1);
    v3_axpy(P3, p[1], e2);
    double a = fmin(1, fmax(0, ab[0])), b = fmin(1, fmax(0, ab[1]));
    for (int it = 0; it < 40; it++) {
        double q[3], x[3], jac[3][3], d[3], xa[3], xb[3];
        q[F->fixed] = F->val;
        q[F->a] = a;
        q[F->b] = b;
        coons_body_eval_jacobian(s->body, q[0], q[1], q[2], x, jac);
        v3_scale(x, x, s->scale);
        v3_sub(d, x, P3);
        double r1 = v3_dot(d, e1), r2 = v3_dot(d, e2);
        if (hypot(r1, r2) <= 4e-14 && fabs(v3_dot(d, n)) <= FLAT_EPS) {
            ab[0] = a;
            ab[1] = b;
            *found = 1;
            return;
        }
        for (int r = 0; r < 3; r++) {
            xa[r] = jac[r][F->a] * s->scale;
            xb[r] = jac[r][F->b] * s->scale;
        }
        double j11 = v3_dot(e1, xa), j12 = v3_dot(e1, xb), j21 = v3_dot(e2, xa),
               j22 = v3_dot(e2, xb), det = j11 * j22 - j12 * j21;
        if (!(fabs(det) > 0) || !isfinite(det)) return;
        a = fmin(1, fmax(0, a - (j22 * r1 - j12 * r2) / det));
        b = fmin(1, fmax(0, b - (j11 * r2 - j21 * r1) / det));
    }
}

/* Parameters (u, v, w) of the np points pts (2-D, in the frame o, e1, e2
 * of flat face f) into uvw (3 each). *ok = 0 when the face's lattice folds
 * over itself in the plane (its triangles' areas do not all have one
 * sign) or a point's parameters are not found: the face keeps its
 * lattice. Locating a point is a walk from the cell whose centre lies in
 * its bucket of a uniform grid over the face (O(1) cells for a lattice of
 * cells of similar sizes; from the last point's cell otherwise). */
static coons_status steiner_params(sampler *s, int f, const double o[3], const double e1[3],
                                   const double e2[3], const double n[3], const double *pts,
                                   size_t np, double *uvw, int *ok)
{
    const face_desc *F = &coons__faces[f];
    size_t na = s->n[F->a], nb = s->n[F->b], nq = (na + 1) * (nb + 1), nc = na * nb;
    *ok = 0;
    size_t K = (size_t)ceil(sqrt((double)nc));
    double *xy = coons__malloc_array(nq, 2 * sizeof(double));
    uint32_t *bucket = coons__malloc_array(K * K, sizeof(uint32_t));
    if (!xy || !bucket) {
        coons__free(xy);
        coons__free(bucket);
        return coons__error_nomem(s->err);
    }
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t ia = 0; ia <= na; ia++)
        for (size_t ib = 0; ib <= nb; ib++) {
            double q[3], *c = xy + 2 * (ia * (nb + 1) + ib);
            v3_sub(q, s->pos + 3 * (size_t)coons__uf_find(s->uf, coons__sampler_id(s, f, ia, ib)),
                   o);
            c[0] = v3_dot(q, e1);
            c[1] = v3_dot(q, e2);
            for (int d = 0; d < 2; d++) lo[d] = fmin(lo[d], c[d]), hi[d] = fmax(hi[d], c[d]);
        }
    /* No fold: the areas of the lattice triangles all of one sign. */
    double sum = 0, sabs = 0;
    for (size_t p = 0; p < na; p++)
        for (size_t q = 0; q < nb; q++)
            for (int k = 0; k < 2; k++) {
                size_t ia[3], ib[3];
                cell_tri(p, q, s->diag[f][p * nb + q], k, ia, ib);
                double ar = orient2(xy + 2 * (ia[0] * (nb + 1) + ib[0]),
                                    xy + 2 * (ia[1] * (nb + 1) + ib[1]),
                                    xy + 2 * (ia[2] * (nb + 1) + ib[2]));
                sum += ar;
                sabs += fabs(ar);
            }
    int good = fabs(sum) > 0 && sabs <= fabs(sum) * (1 + 1e-9);
    double sigma = sum > 0 ? 1 : -1;
    double w0 = (hi[0] - lo[0]) / (double)K, w1 = (hi[1] - lo[1]) / (double)K;
    size_t K1 = K - 1;
#define BUCKET(x, y)                                                                          \
    (fmin((double)K1, fmax(0, floor(((x) - lo[0]) / w0))) +                                   \
     (double)K * fmin((double)K1, fmax(0, floor(((y) - lo[1]) / w1))))
    for (size_t i = 0; i < K * K; i++) bucket[i] = NONE;
    if (good && w0 > 0 && w1 > 0)
        for (size_t p = 0; p < na; p++)
            for (size_t q = 0; q < nb; q++) {
                const double *A = xy + 2 * (p * (nb + 1) + q), *C = xy + 2 * ((p + 1) * (nb + 1) + q + 1);
                bucket[(size_t)BUCKET(0.5 * (A[0] + C[0]), 0.5 * (A[1] + C[1]))] =
                    (uint32_t)(p * nb + q);
            }
    size_t cell = 0;
    for (size_t i = 0; i < np && good; i++) {
        const double *p = pts + 2 * i;
        if (w0 > 0 && w1 > 0) {
            uint32_t c = bucket[(size_t)BUCKET(p[0], p[1])];
            if (c != NONE) cell = c;
        }
        double ab[2];
        int found;
        locate_params(s, f, xy, sigma, p, o, e1, e2, n, &cell, ab, &found);
        if (!found) good = 0;
        double *q = uvw + 3 * i;
        q[F->fixed] = F->val;
        q[F->a] = ab[0];
        q[F->b] = ab[1];
    }
#undef BUCKET
    coons__free(xy);
    coons__free(bucket);
    *ok = good;
    return COONS_OK;
}

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
    int swap = (orient2(q[0], q[1], q[2]) < 0) != (r->flip != 0);
    if (grow((void **)&r->tri, &r->cap, 3 * (r->nt + 1), sizeof(uint32_t))) return -1;
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

/* Distance from p to triangle abc. */
static double tri_dist(const double p[3], const double *a, const double *b, const double *c)
{
    double ab[3], ac[3], ap[3], n[3];
    v3_sub(ab, b, a);
    v3_sub(ac, c, a);
    v3_sub(ap, p, a);
    v3_cross(n, ab, ac);
    double nn = v3_dot(n, n);
    if (nn > 0) { /* the foot of the perpendicular, when inside */
        double x[3], y[3];
        v3_cross(x, ap, ac);
        v3_cross(y, ab, ap);
        double l1 = v3_dot(x, n) / nn, l2 = v3_dot(y, n) / nn;
        if (l1 >= 0 && l2 >= 0 && l1 + l2 <= 1) return fabs(v3_dot(ap, n)) / sqrt(nn);
    }
    const double *e[3][2] = {{a, b}, {b, c}, {c, a}};
    double best = INFINITY;
    for (int k = 0; k < 3; k++) {
        double d[3], q[3];
        v3_sub(d, e[k][1], e[k][0]);
        v3_sub(q, p, e[k][0]);
        double l2 = v3_dot(d, d), t = l2 > 0 ? fmin(1, fmax(0, v3_dot(q, d) / l2)) : 0;
        v3_axpy(q, -t, d);
        best = fmin(best, v3_norm(q));
    }
    return best;
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
 * intervals) straight, within FLAT_EPS, at the thirds and the midpoint?
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
            if (!(tri_dist(pts + 3 * k, pts, pts + 12, pts + 12) <= FLAT_EPS)) goto done;
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
                cell_tri(p, q, s->diag[f][p * nb + q], k, ia, ib);
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

coons_status coons__flat_faces(sampler *s)
{
    /* Morph bodies keep the lattice: all their frames share one mesh
     * topology (the OpenSCAD animation, scad_morph.c). */
    coons__free(s->flat_uvw);
    s->flat_uvw = NULL;
    s->flat_v0 = s->nv;
    s->flat_faces = s->ruled_faces = 0;
    if (s->o->flags & COONS__SAMPLE_LATTICE_FACES || !s->nt ||
        coons_body_kind(s->body) == COONS_BODY_MORPH)
        return COONS_OK;
    uint32_t *ftri[6] = {NULL};
    size_t fnt[6] = {0}, ns = 0, scap = 0;
    int flat[6] = {0};
    double *spos = NULL, *suvw = NULL;
    coons_status st = COONS_OK;
    unsigned char *seen = coons__calloc(s->nv, 1);
    if (!seen) return coons__error_nomem(s->err);
    for (int f = 0; f < 6 && !st; f++) {
        if (s->glued & 1 << coons__faces[f].fixed || s->skip & 1u << f) continue;
        double n[3], o[3], area2 = 0;
        int is_flat;
        if ((st = face_plane(s, f, n, o, &area2, &is_flat)) || !is_flat) continue;
        uint32_t *ring = NULL;
        size_t m;
        if ((st = face_ring(s, f, seen, &ring, &m)) || !m) {
            coons__free(ring);
            continue;
        }
        /* A frame (e1, e2, n), e1 from the axis least along n (exact for
         * faces normal to an axis). */
        int ax = 0;
        for (int d = 1; d < 3; d++)
            if (fabs(n[d]) < fabs(n[ax])) ax = d;
        double u[3] = {0, 0, 0}, e1[3], e2[3];
        u[ax] = 1;
        v3_cross(e1, n, u);
        v3_scale(e1, e1, 1.0 / v3_norm(e1));
        v3_cross(e2, n, e1);
        double *xy = coons__malloc_array(m, 2 * sizeof(double));
        if (!xy) {
            coons__free(ring);
            st = coons__error_nomem(s->err);
            break;
        }
        double a2 = 0;
        for (size_t i = 0; i < m; i++) {
            double q[3];
            v3_sub(q, s->pos + 3 * (size_t)ring[i], o);
            xy[2 * i] = v3_dot(q, e1);
            xy[2 * i + 1] = v3_dot(q, e2);
        }
        for (size_t i = 0; i < m; i++) {
            const double *a = xy + 2 * i, *b = xy + 2 * ((i + 1) % m);
            a2 += a[0] * b[1] - a[1] * b[0];
        }
        if (a2 < 0) { /* the ring runs clockwise seen from outside */
            for (size_t i = 0, j = m - 1; i < j; i++, j--) {
                uint32_t x = ring[i];
                ring[i] = ring[j];
                ring[j] = x;
                for (size_t c = 0; c < 2; c++) {
                    double y = xy[2 * i + c];
                    xy[2 * i + c] = xy[2 * j + c];
                    xy[2 * j + c] = y;
                }
            }
        }
        /* The lattice covers the polygon once (no fold): equal areas. */
        double *pts = NULL;
        uint32_t *tri = NULL;
        size_t np = 0, nt = 0;
        int ok = 0;
        if (fabs(fabs(a2) - area2) <= 1e3 * FLAT_EPS * area2)
            st = coons__polygon_mesh(xy, m, COONS__FLAT_MIN_ANGLE, &pts, &np, &tri, &nt, &ok,
                                     s->err);
        coons__free(xy);
        if (!st && ok && ns + np + s->nv > UINT32_MAX) ok = 0;
        /* Only where it saves triangles: a coarse face whose lattice cells
         * are long keeps them rather than gain Steiner points. */
        if (!st && ok && nt >= s->face_tri[f + 1] - s->face_tri[f]) ok = 0;
        if (!st && ok && np) {
            size_t need = 3 * (ns + np);
            if (need > scap) {
                size_t c = scap ? scap : 48;
                while (c < need) c *= 2;
                double *q = coons__realloc(spos, c * sizeof(double));
                if (q) spos = q;
                double *r = q ? coons__realloc(suvw, c * sizeof(double)) : NULL;
                if (r) suvw = r;
                if (!q || !r) st = coons__error_nomem(s->err);
                else scap = c;
            }
        }
        /* The Steiner points' parameters: with them, the isoparametric
         * output (which keeps every vertex's (u,v,w)) meshes flat faces
         * as the boundary does; a face whose points have none keeps its
         * lattice, whether parameters are asked for or not. */
        if (!st && ok && np)
            st = steiner_params(s, f, o, e1, e2, n, pts, np, suvw + 3 * ns, &ok);
        if (!st && ok) {
            for (size_t i = 0; i < np; i++) {
                double *q = spos + 3 * (ns + i);
                v3_copy(q, o);
                v3_axpy(q, pts[2 * i], e1);
                v3_axpy(q, pts[2 * i + 1], e2);
            }
            for (size_t i = 0; i < 3 * nt; i++)
                tri[i] = tri[i] < m ? ring[tri[i]] : (uint32_t)(s->nv + ns + (tri[i] - m));
            ns += np;
            ftri[f] = tri;
            fnt[f] = nt;
            flat[f] = 1;
            tri = NULL;
        }
        coons__free(pts);
        coons__free(tri);
        coons__free(ring);
    }
    coons__free(seen);
    /* Faces ruled between two straight lines (not flat): strips. */
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
    /* The new mesh: lattice triangles of the other faces, in face order. */
    size_t total = 0;
    int any = 0;
    for (int f = 0; f < 6; f++) {
        total += flat[f] ? fnt[f] : s->face_tri[f + 1] - s->face_tri[f];
        any |= flat[f];
    }
    uint32_t *tri = NULL;
    if (!st && any) {
        tri = coons__malloc_array(total, 3 * sizeof(uint32_t));
        double *pos = coons__realloc(s->pos, (s->nv + ns) * 3 * sizeof(double));
        if (pos) s->pos = pos;
        uint32_t *uf = coons__realloc(s->uf, (s->nv + ns) * sizeof(uint32_t));
        if (uf) s->uf = uf;
        unsigned char *ev = coons__realloc(s->evaluated, s->nv + ns);
        if (ev) s->evaluated = ev;
        if (!tri || !pos || !uf || !ev) st = coons__error_nomem(s->err);
    }
    if (!st && any) {
        size_t k = 0, face_tri[7];
        for (int f = 0; f < 6; f++) {
            face_tri[f] = k;
            if (flat[f]) {
                if (fnt[f]) memcpy(tri + 3 * k, ftri[f], 3 * fnt[f] * sizeof(uint32_t));
                k += fnt[f];
            } else {
                size_t c = s->face_tri[f + 1] - s->face_tri[f];
                if (c) memcpy(tri + 3 * k, s->tri + 3 * s->face_tri[f], 3 * c * sizeof(uint32_t));
                k += c;
            }
        }
        face_tri[6] = k;
        memcpy(s->face_tri, face_tri, sizeof face_tri);
        if (ns) memcpy(s->pos + 3 * s->nv, spos, 3 * ns * sizeof(double));
        s->flat_uvw = suvw; /* 3 ns: raw vertices s->nv .. s->nv + ns - 1 */
        suvw = NULL;
        for (size_t i = 0; i < ns; i++) {
            s->uf[s->nv + i] = (uint32_t)(s->nv + i);
            s->evaluated[s->nv + i] = 1;
        }
        s->nv += ns;
        coons__free(s->tri);
        s->tri = tri;
        s->nt = k;
        s->flat_faces = 0;
        for (int f = 0; f < 6; f++) s->flat_faces |= (unsigned)flat[f] << f;
        s->flat_faces &= ~ruled_bits;
        s->ruled_faces = ruled_bits;
        if (s->measured) s->dev = fmax(s->dev, ruled_dev);
        tri = NULL;
    }
    coons__free(tri);
    coons__free(spos);
    coons__free(suvw);
    for (int f = 0; f < 6; f++) coons__free(ftri[f]);
    return st;
}
