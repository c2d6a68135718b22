/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A body-free 2-D quality mesher of simple polygons (coons__polygon_mesh,
 * delaunay.h), used for flat faces (flat.c).
 *
 * Delaunay refinement (Ruppert, "A Delaunay refinement
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
#include "delaunay.h"

#define NONE UINT32_MAX
/* The final check's area tolerance, relative to the area and times 1e3:
 * the planarity tolerance of flat faces (COONS__FLAT_EPS, flat.h). */
#define AREA_EPS 1e-12

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
    if (coons__grow((void **)&d->t, &d->tcap, d->nt + 1, sizeof(tri2))) return -1;
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
    if (coons__grow((void **)&d->stack, &d->scap, 1, 4) || coons__grow((void **)&d->cav, &d->ccap, 1, 4))
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
            if (coons__grow((void **)&d->stack, &d->scap, sp + 1, 4) ||
                coons__grow((void **)&d->cav, &d->ccap, d->ncav + 1, 4))
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
            if (coons__grow((void **)&d->be, &d->becap, 4 * (d->nbe + 1), 4)) return INS_NOMEM;
            uint32_t *e = d->be + 4 * d->nbe++;
            e[0] = a, e[1] = b, e[2] = n, e[3] = d->cav[i];
        }
    }
    /* Commit. */
    if (coons__grow((void **)&d->xy, &d->pcap, 2 * (d->np + 1), sizeof(double)) ||
        coons__grow((void **)&d->slot, &d->slotcap, d->np + 1, 4) ||
        coons__grow((void **)&d->fresh, &d->fcap, d->nbe, 4))
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
            if (coons__grow((void **)&queue, &qcap, qt + 1, 4)) {
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
        if (coons__grow((void **)&queue, &qcap, qt + d->nfresh, 4)) {
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
    if (coons__grow((void **)&d.xy, &d.pcap, 2 * (m + 3), sizeof(double)) ||
        coons__grow((void **)&d.slot, &d.slotcap, m + 3, 4) ||
        coons__grow((void **)&d.t, &d.tcap, 1, sizeof(tri2)))
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
    if (!(fabs(sum2 - area2) <= AREA_EPS * area2 * 1e3)) { why = __LINE__; goto reject; }
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
