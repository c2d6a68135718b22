/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Free-form deformation of a triangle mesh by a body (seed 000 sections 1
 * and 5: Coons bodies "can be easily utilized in FFD applications", after
 * Sederberg and Parry): a point p goes to B((p - lo) / (hi - lo)).
 *
 * Refinement by edge bisection with conforming templates: an edge is
 * marked when the image of its parametric midpoint lies farther than the
 * tolerance from the chord of its end images, and a triangle marks its
 * three edges when the image of its parametric centroid (or of the points
 * halfway between the centroid and its corners) lies farther than the
 * tolerance from the triangle of its corner images. "Farther than the
 * tolerance" is judged against 0.9 times it, as the sampler does: the margin
 * covers maxima between the samples. Before measuring, a triangle whose
 * error estimate (below, "deciding without evaluating") is at most half
 * that is left whole unmeasured, and its edges are left to its neighbours:
 * the estimate only accepts what measuring would accept where it holds, so
 * the mesh is the same. A triangle measured (or estimated) within it and
 * left whole is not measured again; the largest distance or estimate over
 * the triangles of the result is the deviation (coons_deform_report).
 *
 * Evaluation is batched and threaded (coons_deform_options.threads): the
 * input's vertices, the estimate's lattice, each round's inner points and
 * edge midpoints and the new vertices go through coons_body_eval_points()
 * in contiguous shares of coons__parallel_for(), each result in a slot of
 * its own; the edge table, the marking and the splitting walk the
 * triangles in order on the calling thread, creating the midpoints in the
 * order the serial method did, so the bytes are the same for every thread
 * count (and as before the batching).
 *
 * Every marked edge gets one midpoint, shared by both its triangles, and
 * each triangle is split
 * by the template of its marked edges (1: two triangles, 2: three, 3:
 * four), keeping its winding; this repeats until nothing is marked. The
 * split depends on the edge alone, so a closed 2-manifold input stays
 * closed and 2-manifold, and with unchanged winding outward; through a
 * left-handed body (det J < 0) the winding is reversed at the end.
 *
 * Progress (coons_deform_options.progress, stage "deform"): round r (from
 * 0, at most 64) spans the fractions 1 - 2^-r to 1 - 2^-(r+1), its first
 * half the triangles measured, its second half the triangles split, so the
 * fraction never goes back; 1 at the end.
 */
#include <stdlib.h>
#include <string.h>

#include "body_impl.h"
#include "mesh_impl.h"
#include "coons_test_hooks.h"
#include "parallel.h"

/* Per triangle, how this round's measurement decided it. */
enum { T_WHOLE = 0, T_FAIL = 1, T_PASS = 2, T_EST = 3 };

/* The estimate of the interpolation error (see "Deciding without
 * evaluating" above): a lattice of cells over the unit cube, m[d] cells
 * along d between the nodes node[d][0] = 0 < ... < node[d][m[d]] = 1 (the
 * body's breakpoints among them); c0[d][i] set where node i is a
 * breakpoint at which the map may be only C0 (a triangle across it is not
 * estimated); per cell and direction a, k[3 c + a] = R_a / 2 (with the
 * safety factor), the triangle's estimate its squared circumradius (or a
 * quarter of its longest side squared) with lengths scaled by sqrt(k). */
typedef struct estimate {
    int on;
    size_t m[3];
    double *node[3];
    unsigned char *c0[3];
    double *k;
} estimate;

typedef struct work {
    double *q, *x; /* parameters and images, 3 per vertex */
    size_t nv, cap_v;
    uint32_t *tri;
    size_t nt, cap_t;
    /* per triangle: its measured deviation, or -1 when not yet measured */
    float *dev;
    /* this round, per triangle: T_* and the largest squared distance of
     * its inner points (T_PASS) */
    unsigned char *state;
    double *fdev;
    /* edge -> midpoint vertex (open addressing; key 0 is empty) */
    uint64_t *key;
    uint32_t *mid;  /* UINT32_MAX: not split */
    uint32_t *eix;  /* index into the measured edges, or UINT32_MAX */
    size_t cap_e;
    /* this round's measured edges: ends, image of the midpoint, squared
     * distance to the chord */
    uint32_t *ends;
    double *ex, *ed2;
    size_t ne, cap_me;
    /* vertices created without an image, evaluated in one batch */
    uint32_t *pend;
    size_t npend, cap_p;
    const coons_body *b;
    estimate est;
    size_t estimated; /* triangles decided by the estimate */
    unsigned threads;
    double tol, limit; /* limit = 0.9 * tol */
    coons_error *err;
    /* the progress report: round r spans [base, base + span) */
    coons_progress_fn progress;
    void *userdata;
    double base, span, shown;
} work;

/* Points evaluated per call of coons_body_eval_points() on one thread. */
#define BATCH 256
/* Triangles measured between two progress reports (each block on every
 * thread). */
#define BLOCK 65536

/* Reports the share `done` of the current round (0 to 1); never
 * backwards. */
static void report_round(work *w, double done)
{
    if (!w->progress) return;
    double f = w->base + w->span * done;
    if (f < w->shown) return;
    w->shown = f;
    w->progress(w->userdata, "deform", f);
}

static uint64_t edge_key(uint32_t a, uint32_t b)
{
    uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
    return ((uint64_t)lo << 32 | hi) + 1;
}

static size_t slot(const work *w, uint64_t k)
{
    uint64_t h = k * 0x9e3779b97f4a7c15ull;
    size_t i = (size_t)(h >> 20) & (w->cap_e - 1);
    while (w->key[i] && w->key[i] != k) i = (i + 1) & (w->cap_e - 1);
    return i;
}

static coons_status reset_edges(work *w, size_t n)
{
    size_t cap = 16;
    while (cap < 4 * n) cap *= 2;
    if (cap != w->cap_e) {
        coons__free(w->key);
        coons__free(w->mid);
        coons__free(w->eix);
        w->key = coons__malloc_array(cap, sizeof *w->key);
        w->mid = coons__malloc_array(cap, sizeof *w->mid);
        w->eix = coons__malloc_array(cap, sizeof *w->eix);
        w->cap_e = cap;
        if (!w->key || !w->mid || !w->eix) {
            w->cap_e = 0;
            return coons__error_nomem(w->err);
        }
    }
    memset(w->key, 0, cap * sizeof *w->key);
    w->ne = 0;
    w->npend = 0;
    return COONS_OK;
}

/* Grows an array of `cap` elements of `size` bytes to hold n. */
static int grow(void **p, size_t *cap, size_t n, size_t size)
{
    if (n <= *cap) return 1;
    size_t c = *cap ? *cap : 64;
    while (c < n) c *= 2;
    void *q = coons__realloc(*p, c * size);
    if (!q) return 0;
    *p = q;
    *cap = c;
    return 1;
}

/* A new vertex at parameters q; x: its image if known, else NULL (the
 * vertex waits in `pend` for eval_pending()). */
static coons_status add_vertex(work *w, const double q[3], const double *x, uint32_t *id)
{
    if (w->nv == UINT32_MAX) return coons__error_set(w->err, COONS_E_LIMIT, "deform: too many vertices");
    if (w->nv == w->cap_v) {
        size_t cap = w->cap_v ? 2 * w->cap_v : 64;
        double *q2 = coons__realloc(w->q, cap * 3 * sizeof *q2);
        if (!q2) return coons__error_nomem(w->err);
        w->q = q2;
        double *x2 = coons__realloc(w->x, cap * 3 * sizeof *x2);
        if (!x2) return coons__error_nomem(w->err);
        w->x = x2;
        w->cap_v = cap;
    }
    memcpy(w->q + 3 * w->nv, q, 3 * sizeof *q);
    if (x) {
        memcpy(w->x + 3 * w->nv, x, 3 * sizeof *x);
    } else {
        size_t cap = w->cap_p;
        void *p = w->pend;
        if (!grow(&p, &cap, w->npend + 1, sizeof *w->pend)) return coons__error_nomem(w->err);
        w->pend = p;
        w->cap_p = cap;
        w->pend[w->npend++] = (uint32_t)w->nv;
    }
    *id = (uint32_t)w->nv++;
    return COONS_OK;
}

/* --- threaded evaluation; every result goes to a slot of its own, so the
 * bytes do not depend on the thread count --- */

/* Images of the vertices pend[lo..hi) (or lo..hi themselves when pend is
 * NULL). */
typedef struct vjob {
    const work *w;
    const uint32_t *ids;
} vjob;

static void eval_vertices_chunk(void *ctx, unsigned chunk, size_t lo, size_t hi)
{
    (void)chunk;
    const vjob *j = ctx;
    const work *w = j->w;
    double q[3 * BATCH], x[3 * BATCH];
    for (size_t s = lo; s < hi; s += BATCH) {
        size_t n = hi - s < BATCH ? hi - s : BATCH;
        if (!j->ids) {
            coons_body_eval_points(w->b, n, w->q + 3 * s, w->x + 3 * s, NULL, NULL, NULL);
            continue;
        }
        for (size_t i = 0; i < n; i++) memcpy(q + 3 * i, w->q + 3 * (size_t)j->ids[s + i], sizeof(double[3]));
        coons_body_eval_points(w->b, n, q, x, NULL, NULL, NULL);
        for (size_t i = 0; i < n; i++) memcpy(w->x + 3 * (size_t)j->ids[s + i], x + 3 * i, sizeof(double[3]));
    }
}

static void eval_pending(work *w)
{
    vjob j = {w, w->pend};
    coons__parallel_for(w->npend, w->threads, eval_vertices_chunk, &j);
    w->npend = 0;
}

/* The 4 inner points of a triangle, in barycentric coordinates. */
static const double BARY[4][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3},
                                  {2.0 / 3, 1.0 / 6, 1.0 / 6},
                                  {1.0 / 6, 2.0 / 3, 1.0 / 6},
                                  {1.0 / 6, 1.0 / 6, 2.0 / 3}};

/* --- deciding without evaluating ---
 *
 * For a map F that is C1 with bounded second derivatives on a triangle of
 * parameter points x_i, and its linear interpolant I on the triangle of
 * images, Taylor's theorem at x gives
 *   |F(x) - I(x)| <= rho/2 sum_i l_i |x_i - x|^2 = rho/2 sum_{i<j} l_i l_j |x_i - x_j|^2
 * (l: barycentric coordinates of x), rho a bound of |d^2/dt^2 F(x + t e)|
 * over unit directions e. Sharper, with M_ab bounds of |d^2 F / dx_a dx_b|
 * and R_a = sum_b M_ab (as |y|^T M |y| <= sum_a R_a y_a^2): the error is at
 * most 1/2 sum_{i<j} l_i l_j |S (x_i - x_j)|^2, S = diag(sqrt(R_a)), whose
 * largest value over the triangle is the squared circumradius of the
 * triangle scaled by S if it is acute, else a quarter of its longest side
 * squared. The distance from F(x) to the triangle of images is at most
 * that. rho is estimated, not proved: per cell of a lattice (ESTIMATE_CELLS
 * along each direction, the body's breakpoints added; the body evaluated
 * once at each node), second differences of the nodes' images (averages
 * of the second partials near the cell, estimate_build()) give M_ab, and
 * R_a; each is taken over the cell and its neighbours, plus the spread
 * between them, times ESTIMATE_SAFETY. Next to a C0
 * breakpoint the differences are large (no estimate), and a triangle
 * across one is not estimated. A triangle whose
 * estimate is at most half the limit (0.45 times the tolerance, where
 * measuring accepts 0.9) is left whole unmeasured; any other is measured
 * as before. */
#define ESTIMATE_CELLS 16
#define ESTIMATE_SAFETY 2.0
/* At most this many nodes, and then only for inputs of at least half as
 * many triangles (else measuring them is cheaper). */
#define ESTIMATE_MAX_NODES 20000
/* Nodes closer than this are one. */
#define ESTIMATE_GAP 1e-7

/* Test hook (coons_test_hooks.h): 0, estimates on, nothing counted; 1,
 * on, and the triangles they decided counted; 2, off (every triangle
 * measured), counted as 0. */
static int estimate_mode;
static size_t estimate_count;
void coons__deform_estimates(int mode) { estimate_mode = mode; }
size_t coons__deform_estimated(void) { return estimate_count; }

static void estimate_free(estimate *E)
{
    for (int d = 0; d < 3; d++) {
        coons__free(E->node[d]);
        coons__free(E->c0[d]);
        E->node[d] = NULL;
        E->c0[d] = NULL;
    }
    coons__free(E->k);
    E->k = NULL;
    E->on = 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The nodes along d: 0, 1, ESTIMATE_CELLS equal cells and the breakpoints
 * (flagged in c0 when the map may be only C0 there). 0: no estimate along
 * d (C0 breakpoints that are not known), else 1 (COONS_E_NOMEM: -1). */
static int estimate_nodes(const coons_body *b, int d, estimate *E, coons_error *err)
{
    coons__space S = coons__body_space(b, d);
    double *br = NULL;
    size_t nb = 0;
    if (coons__body_breaks(b, d, &br, &nb, err)) return -1;
    /* no inner breakpoints listed while the map has some (beyond
     * COONS__MAX_BREAKS, or a type that does not list them) */
    int known = nb > 2 || S.cont >= COONS__SMOOTH;
    if (!known && S.cont < 1) {
        coons__free(br);
        return 0;
    }
    size_t cap = ESTIMATE_CELLS + 1 + nb;
    double *x = coons__malloc_array(cap, sizeof *x);
    unsigned char *c0 = coons__calloc(cap, 1);
    if (!x || !c0) {
        coons__free(br);
        coons__free(x);
        coons__free(c0);
        return -1;
    }
    size_t n = 0;
    for (size_t i = 0; i <= ESTIMATE_CELLS; i++) x[n++] = (double)i / ESTIMATE_CELLS;
    for (size_t i = 0; i < nb; i++)
        if (br[i] > 0 && br[i] < 1) x[n++] = br[i];
    qsort(x, n, sizeof *x, cmp_double);
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (m == 0 || x[i] - x[m - 1] > ESTIMATE_GAP) x[m++] = x[i];
    x[m - 1] = 1.0;
    /* the breakpoints among the nodes: where the map may be only C0 */
    if (S.cont < 1)
        for (size_t i = 1; i + 1 < m; i++)
            for (size_t j = 0; j < nb; j++)
                if (fabs(br[j] - x[i]) <= ESTIMATE_GAP) c0[i] = 1;
    coons__free(br);
    E->node[d] = x;
    E->c0[d] = c0;
    E->m[d] = m - 1;
    return 1;
}

typedef struct ejob {
    const coons_body *b;
    const double *uvw;
    double *xyz;
} ejob;

static void estimate_eval_chunk(void *ctx, unsigned chunk, size_t lo, size_t hi)
{
    (void)chunk;
    const ejob *j = ctx;
    for (size_t s = lo; s < hi; s += BATCH) {
        size_t n = hi - s < BATCH ? hi - s : BATCH;
        coons_body_eval_points(j->b, n, j->uvw + 3 * s, j->xyz + 3 * s, NULL, NULL, NULL);
    }
}

/* |second divided difference| of the lattice points along d through nodes
 * c - 1, c, c + 1 (c moved inside at the ends), the others at g. */
static double second_diff(const estimate *E, const double *xyz, const size_t g[3], int d,
                          size_t c)
{
    size_t m = E->m[d];
    if (c < 1) c = 1;
    if (c > m - 1) c = m - 1;
    const double *x = E->node[d];
    double h0 = x[c] - x[c - 1], h1 = x[c + 1] - x[c], s2 = 0;
    size_t i[3] = {g[0], g[1], g[2]}, id[3];
    const double *p[3];
    for (int k = 0; k < 3; k++) {
        i[d] = c - 1 + (size_t)k;
        id[k] = (i[0] * (E->m[1] + 1) + i[1]) * (E->m[2] + 1) + i[2];
        p[k] = xyz + 3 * id[k];
    }
    for (int r = 0; r < 3; r++) {
        double v = 2 * ((p[2][r] - p[1][r]) / h1 - (p[1][r] - p[0][r]) / h0) / (h0 + h1);
        s2 += v * v;
    }
    return sqrt(s2);
}

/* Builds the estimate's lattice (E->on stays 0 when the body or the input
 * does not suit it). Only COONS_E_NOMEM fails. The second partials of a
 * cell: along d, the second divided differences along its 4 edges in d
 * centred at both their ends (inside the unit cube); mixed, the twist
 * (F11 - F10 - F01 + F00) / (h_a h_b) of its 2 faces spanning a and b:
 * averages of the partial near the cell. */
static coons_status estimate_build(work *w, size_t nt)
{
    estimate *E = &w->est;
    memset(E, 0, sizeof *E);
    if (estimate_mode == 2) return COONS_OK;
    for (int d = 0; d < 3; d++) {
        int r = estimate_nodes(w->b, d, E, w->err);
        if (r < 0) {
            estimate_free(E);
            return coons__error_nomem(w->err);
        }
        if (r == 0 || E->m[d] < 2) {
            estimate_free(E);
            return COONS_OK;
        }
    }
    size_t n0 = E->m[0] + 1, n1 = E->m[1] + 1, n2 = E->m[2] + 1, total = n0 * n1 * n2;
    if (total > ESTIMATE_MAX_NODES || 2 * nt < total) {
        estimate_free(E);
        return COONS_OK;
    }
    coons_status st = COONS_OK;
    double *uvw = coons__malloc_array(total, 3 * sizeof *uvw);
    double *xyz = coons__malloc_array(total, 3 * sizeof *xyz);
    size_t m0 = E->m[0], m1 = E->m[1], m2 = E->m[2], nc = m0 * m1 * m2;
    double *rho = coons__malloc_array(nc, 3 * sizeof *rho);
    E->k = coons__malloc_array(nc, 3 * sizeof *E->k);
    if (!uvw || !xyz || !rho || !E->k) {
        st = coons__error_nomem(w->err);
        goto done;
    }
    for (size_t i = 0, p = 0; i < n0; i++)
        for (size_t j = 0; j < n1; j++)
            for (size_t k = 0; k < n2; k++, p++) {
                uvw[3 * p] = E->node[0][i];
                uvw[3 * p + 1] = E->node[1][j];
                uvw[3 * p + 2] = E->node[2][k];
            }
    ejob job = {w->b, uvw, xyz};
    coons__parallel_for(total, w->threads, estimate_eval_chunk, &job);
    for (size_t p = 0; p < 3 * total; p++)
        if (!isfinite(xyz[p])) goto done;
    for (size_t i = 0; i < m0; i++)
        for (size_t j = 0; j < m1; j++)
            for (size_t k = 0; k < m2; k++) {
                size_t cell[3] = {i, j, k};
                double M[3][3] = {{0}};
                /* pure: the 4 edges along d, at both ends */
                for (int d = 0; d < 3; d++)
                    for (int e = 0; e < 4; e++) {
                        size_t g[3];
                        int o1 = (d + 1) % 3, o2 = (d + 2) % 3;
                        g[o1] = cell[o1] + (size_t)(e & 1);
                        g[o2] = cell[o2] + (size_t)(e >> 1);
                        g[d] = 0;
                        for (size_t c = cell[d]; c <= cell[d] + 1; c++)
                            M[d][d] = fmax(M[d][d], second_diff(E, xyz, g, d, c));
                    }
                /* mixed: the 2 faces spanning a and b */
                for (int a = 0; a < 3; a++)
                    for (int bb = a + 1; bb < 3; bb++) {
                        int c = 3 - a - bb;
                        double ha = E->node[a][cell[a] + 1] - E->node[a][cell[a]];
                        double hb = E->node[bb][cell[bb] + 1] - E->node[bb][cell[bb]];
                        for (size_t lc = cell[c]; lc <= cell[c] + 1; lc++) {
                            const double *p[4];
                            for (int q = 0; q < 4; q++) {
                                size_t g[3];
                                g[a] = cell[a] + (size_t)(q & 1);
                                g[bb] = cell[bb] + (size_t)(q >> 1);
                                g[c] = lc;
                                p[q] = xyz + 3 * ((g[0] * n1 + g[1]) * n2 + g[2]);
                            }
                            double s2 = 0;
                            for (int r = 0; r < 3; r++) {
                                double v = (p[3][r] - p[1][r] - p[2][r] + p[0][r]) / (ha * hb);
                                s2 += v * v;
                            }
                            double v = sqrt(s2);
                            M[a][bb] = fmax(M[a][bb], v);
                            M[bb][a] = fmax(M[bb][a], v);
                        }
                    }
                for (int a = 0; a < 3; a++)
                    rho[3 * ((i * m1 + j) * m2 + k) + a] = M[a][0] + M[a][1] + M[a][2];
            }
    /* over the neighbours, plus their spread, times the safety factor, and
     * the 1/2 of the remainder */
    for (size_t i = 0; i < m0; i++)
        for (size_t j = 0; j < m1; j++)
            for (size_t k = 0; k < m2; k++)
                for (int d = 0; d < 3; d++) {
                    double hi_ = 0, lo_ = INFINITY;
                    for (size_t a = i ? i - 1 : 0; a <= i + 1 && a < m0; a++)
                        for (size_t b = j ? j - 1 : 0; b <= j + 1 && b < m1; b++)
                            for (size_t c = k ? k - 1 : 0; c <= k + 1 && c < m2; c++) {
                                double r = rho[3 * ((a * m1 + b) * m2 + c) + d];
                                hi_ = fmax(hi_, r);
                                lo_ = fmin(lo_, r);
                            }
                    E->k[3 * ((i * m1 + j) * m2 + k) + d] =
                        0.5 * ESTIMATE_SAFETY * (2 * hi_ - lo_);
                }
    E->on = 1;
done:
    coons__free(uvw);
    coons__free(xyz);
    coons__free(rho);
    if (!E->on) estimate_free(E);
    return st;
}

/* The cells along d that [a, b] meets: *i0..*i1; 0 when it crosses a
 * node where the map may be only C0. */
static int cell_range(const estimate *E, int d, double a, double b, size_t *i0, size_t *i1)
{
    const double *x = E->node[d];
    size_t m = E->m[d], l = 0, h = m; /* the cell of a: x[l] <= a < x[l+1] */
    while (h - l > 1) {
        size_t c = (l + h) / 2;
        if (x[c] <= a) l = c; else h = c;
    }
    size_t e = l;
    while (e + 1 < m && x[e + 1] < b) e++;
    for (size_t i = l + 1; i <= e; i++)
        if (E->c0[d][i]) return 0;
    *i0 = l;
    *i1 = e;
    return 1;
}

/* The error estimate of a triangle (parameters of its corners p[3]), or
 * -1 when the estimate cannot be made (across a C0 breakpoint, or over
 * more than 8 cells). */
static double estimate_triangle(const estimate *E, const double *p0, const double *p1,
                                const double *p2)
{
    size_t i0[3], i1[3], cells = 1;
    for (int d = 0; d < 3; d++) {
        double a = fmin(p0[d], fmin(p1[d], p2[d])), b = fmax(p0[d], fmax(p1[d], p2[d]));
        if (!cell_range(E, d, a, b, &i0[d], &i1[d])) return -1;
        cells *= i1[d] - i0[d] + 1;
    }
    if (cells > 8) return -1;
    double k[3] = {0, 0, 0};
    for (size_t i = i0[0]; i <= i1[0]; i++)
        for (size_t j = i0[1]; j <= i1[1]; j++)
            for (size_t l = i0[2]; l <= i1[2]; l++)
                for (int d = 0; d < 3; d++)
                    k[d] = fmax(k[d], E->k[3 * ((i * E->m[1] + j) * E->m[2] + l) + d]);
    /* the largest sum_{i<j} l_i l_j |x_i - x_j|^2 over the triangle, lengths
     * scaled by k */
    double s[3] = {0, 0, 0};
    for (int d = 0; d < 3; d++) {
        s[0] += k[d] * (p1[d] - p0[d]) * (p1[d] - p0[d]);
        s[1] += k[d] * (p2[d] - p1[d]) * (p2[d] - p1[d]);
        s[2] += k[d] * (p0[d] - p2[d]) * (p0[d] - p2[d]);
    }
    double c2 = fmax(s[0], fmax(s[1], s[2])), f = c2 / 4;
    if (s[0] + s[1] + s[2] > 2 * c2) { /* acute: the circumradius squared */
        double den = 2 * (s[0] * s[1] + s[1] * s[2] + s[2] * s[0]) -
                     (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        double r2 = den > 0 ? s[0] * s[1] * s[2] / den : c2 / 3;
        f = fmax(f, fmin(r2, c2 / 3));
    }
    return f;
}

/* Triangles [lo, hi) of the block starting at t0 that are not yet measured:
 * state and largest squared distance of the images of their inner points
 * to the triangle of their corner images. */
typedef struct tjob {
    work *w;
    size_t t0;
} tjob;

static void inner_point(const work *w, const uint32_t v[3], int s, double q[3])
{
    for (int d = 0; d < 3; d++)
        q[d] = BARY[s][0] * w->q[3 * v[0] + d] + BARY[s][1] * w->q[3 * v[1] + d] +
               BARY[s][2] * w->q[3 * v[2] + d];
}

/* The centroids of a batch first, then the 3 other inner points of the
 * triangles whose centroid is within the limit: a triangle fails at its
 * first point beyond it, as measured one by one. */
static void measure_faces_chunk(void *ctx, unsigned chunk, size_t lo, size_t hi)
{
    (void)chunk;
    const tjob *j = ctx;
    work *w = j->w;
    double lim2 = w->limit * w->limit;
    enum { PER = BATCH / 4 };
    double q[3 * BATCH], x[3 * BATCH];
    size_t id[PER], pass[PER];
    for (size_t t = j->t0 + lo, end = j->t0 + hi; t < end;) {
        size_t n = 0, np = 0;
        for (; t < end && n < PER; t++) {
            if (w->dev[t] >= 0) {
                w->state[t] = T_WHOLE;
                continue;
            }
            const uint32_t *v = w->tri + 3 * t;
            if (w->est.on) {
                double e = estimate_triangle(&w->est, w->q + 3 * v[0], w->q + 3 * v[1],
                                             w->q + 3 * v[2]);
                if (e >= 0 && e <= 0.5 * w->limit) {
                    w->state[t] = T_EST;
                    w->fdev[t] = e;
                    continue;
                }
            }
            inner_point(w, v, 0, q + 3 * n);
            id[n++] = t;
        }
        if (!n) continue;
        coons_body_eval_points(w->b, n, q, x, NULL, NULL, NULL);
        for (size_t i = 0; i < n; i++) {
            const uint32_t *v = w->tri + 3 * id[i];
            double d2 = fmax(0.0, coons__tri_dist2(x + 3 * i, w->x + 3 * v[0], w->x + 3 * v[1],
                                                   w->x + 3 * v[2]));
            w->fdev[id[i]] = d2;
            if (d2 > lim2)
                w->state[id[i]] = T_FAIL;
            else
                pass[np++] = id[i];
        }
        for (size_t i = 0; i < np; i++)
            for (int s = 1; s < 4; s++) inner_point(w, w->tri + 3 * pass[i], s, q + 3 * (3 * i + s - 1));
        if (np) coons_body_eval_points(w->b, 3 * np, q, x, NULL, NULL, NULL);
        for (size_t i = 0; i < np; i++) {
            const uint32_t *v = w->tri + 3 * pass[i];
            double worst = w->fdev[pass[i]];
            for (int s = 0; s < 3; s++)
                worst = fmax(worst, coons__tri_dist2(x + 3 * (3 * i + s), w->x + 3 * v[0],
                                                     w->x + 3 * v[1], w->x + 3 * v[2]));
            w->state[pass[i]] = worst > lim2 ? T_FAIL : T_PASS;
            w->fdev[pass[i]] = worst;
        }
    }
}

/* The measured edges [lo, hi): image of the parametric midpoint and its
 * squared distance to the chord of the end images. */
static void measure_edges_chunk(void *ctx, unsigned chunk, size_t lo, size_t hi)
{
    (void)chunk;
    work *w = ctx;
    double q[3 * BATCH];
    for (size_t s = lo; s < hi; s += BATCH) {
        size_t n = hi - s < BATCH ? hi - s : BATCH;
        for (size_t i = 0; i < n; i++) {
            uint32_t a = w->ends[2 * (s + i)], b = w->ends[2 * (s + i) + 1];
            for (int d = 0; d < 3; d++) q[3 * i + d] = 0.5 * (w->q[3 * a + d] + w->q[3 * b + d]);
        }
        coons_body_eval_points(w->b, n, q, w->ex + 3 * s, NULL, NULL, NULL);
        for (size_t i = 0; i < n; i++) {
            uint32_t a = w->ends[2 * (s + i)], b = w->ends[2 * (s + i) + 1];
            w->ed2[s + i] = coons__seg_dist2(w->ex + 3 * (s + i), w->x + 3 * a, w->x + 3 * b);
        }
    }
}

/* The edge's hash slot, inserting it (not split, not measured) when new. */
static size_t edge_slot(work *w, uint32_t a, uint32_t b)
{
    uint64_t k = edge_key(a, b);
    size_t i = slot(w, k);
    if (!w->key[i]) {
        w->key[i] = k;
        w->mid[i] = UINT32_MAX;
        w->eix[i] = UINT32_MAX;
    }
    return i;
}

/* Splits the edge in slot i (ends a, b) once: its midpoint becomes a
 * vertex, with the measured image when there is one. */
static coons_status split_edge(work *w, size_t i, uint32_t a, uint32_t b)
{
    if (w->mid[i] != UINT32_MAX) return COONS_OK;
    double q[3];
    for (int d = 0; d < 3; d++) q[d] = 0.5 * (w->q[3 * a + d] + w->q[3 * b + d]);
    const double *x = w->eix[i] != UINT32_MAX ? w->ex + 3 * (size_t)w->eix[i] : NULL;
    return add_vertex(w, q, x, &w->mid[i]);
}

static uint32_t midpoint(const work *w, uint32_t a, uint32_t b)
{
    size_t i = slot(w, edge_key(a, b));
    return w->key[i] ? w->mid[i] : UINT32_MAX;
}

static void put(uint32_t *t, size_t *n, uint32_t a, uint32_t b, uint32_t c)
{
    t[3 * *n] = a, t[3 * *n + 1] = b, t[3 * *n + 2] = c;
    ++*n;
}

static coons_status limit_error(work *w, size_t max_triangles)
{
    return coons__error_set(w->err, COONS_E_LIMIT,
                            "deform: reaching the tolerance %g needs more than %zu triangles "
                            "(the limit)",
                            w->tol, max_triangles);
}

/* One round: measure, mark, then split. *changed: whether anything was
 * split. Measuring runs on w->threads threads, each point's result in a
 * slot of its own; marking and splitting walk the triangles in order, so
 * the vertices and triangles come out in the same order for every thread
 * count. */
static coons_status round_once(work *w, size_t max_triangles, int *changed)
{
    coons_status st = COONS_OK;
    double lim2 = w->limit * w->limit;
    /* measuring is the first half of the round's share, splitting the second */
    double per = w->nt ? 0.5 / (double)w->nt : 0;
    size_t cap = w->nt ? w->nt : 1;
    unsigned char *state = coons__malloc_array(cap, sizeof *state);
    double *fdev = coons__malloc_array(cap, sizeof *fdev);
    if (!state || !fdev) {
        coons__free(state);
        coons__free(fdev);
        return coons__error_nomem(w->err);
    }
    w->state = state;
    w->fdev = fdev;
    size_t nv0 = w->nv;
    /* 1. the inner points of every triangle not yet measured (a quarter) */
    for (size_t t0 = 0; t0 < w->nt; t0 += BLOCK) {
        report_round(w, 0.5 * per * (double)t0);
        tjob j = {w, t0};
        size_t n = w->nt - t0 < BLOCK ? w->nt - t0 : BLOCK;
        coons__parallel_for(n, w->threads, measure_faces_chunk, &j);
    }
    /* 2. the edges of the triangles whose inner points passed, each once
     * (the table sized for the triangles measured this round) */
    size_t measured = 0;
    for (size_t t = 0; t < w->nt; t++) measured += state[t] == T_PASS || state[t] == T_FAIL;
    st = reset_edges(w, 3 * measured + 16);
    for (size_t t = 0; t < w->nt && !st; t++) {
        if (state[t] != T_PASS) continue;
        const uint32_t *v = w->tri + 3 * t;
        for (int e = 0; e < 3; e++) {
            uint32_t a = v[e], b = v[(e + 1) % 3];
            size_t i = edge_slot(w, a, b);
            if (w->eix[i] != UINT32_MAX) continue;
            size_t capm = w->cap_me;
            void *p = w->ends;
            if (!grow(&p, &capm, w->ne + 1, 2 * sizeof *w->ends)) {
                st = coons__error_nomem(w->err);
                break;
            }
            w->ends = p;
            if (capm != w->cap_me) {
                double *ex = coons__realloc(w->ex, capm * 3 * sizeof *ex);
                if (ex) w->ex = ex;
                double *ed2 = ex ? coons__realloc(w->ed2, capm * sizeof *ed2) : NULL;
                if (ed2) w->ed2 = ed2;
                if (!ex || !ed2) {
                    st = coons__error_nomem(w->err);
                    break;
                }
                w->cap_me = capm;
            }
            w->ends[2 * w->ne] = a;
            w->ends[2 * w->ne + 1] = b;
            w->eix[i] = (uint32_t)w->ne++;
        }
    }
    if (!st) {
        report_round(w, 0.25);
        coons__parallel_for(w->ne, w->threads, measure_edges_chunk, w);
        report_round(w, 0.375);
    }
    /* 3. in triangle order: an edge is split at the first triangle that
     * fails or that measured it beyond the limit; a triangle left whole
     * keeps its largest measured distance */
    for (size_t t = 0; t < w->nt && !st; t++) {
        if (state[t] == T_WHOLE) continue;
        if (state[t] == T_EST) { /* its estimate for its deviation */
            w->dev[t] = (float)fdev[t];
            w->estimated++;
            continue;
        }
        const uint32_t *v = w->tri + 3 * t;
        double worst = fdev[t];
        for (int e = 0; e < 3 && !st; e++) {
            uint32_t a = v[e], b = v[(e + 1) % 3];
            size_t i = edge_slot(w, a, b);
            if (state[t] == T_FAIL) {
                st = split_edge(w, i, a, b);
                continue;
            }
            double d2 = w->ed2[w->eix[i]];
            if (d2 > lim2) st = split_edge(w, i, a, b);
            worst = fmax(worst, d2);
        }
        /* a triangle that needs splitting is measured again as its parts */
        w->dev[t] = state[t] == T_FAIL || worst > lim2 ? -1.0f : (float)sqrt(worst);
    }
    w->state = NULL;
    w->fdev = NULL;
    coons__free(state);
    coons__free(fdev);
    if (st) return st;
    report_round(w, 0.45);
    eval_pending(w);
    report_round(w, 0.5);
    *changed = 0;
    if (w->nv == nv0) /* nothing split */
        return w->nt > max_triangles ? limit_error(w, max_triangles) : COONS_OK;
    cap = 4 * w->nt;
    size_t n = 0;
    uint32_t *out = coons__malloc_array(cap ? cap : 1, 3 * sizeof *out);
    float *dev = coons__malloc_array(cap ? cap : 1, sizeof *dev);
    if (!out || !dev) {
        coons__free(out);
        coons__free(dev);
        return coons__error_nomem(w->err);
    }
    *changed = 0;
    for (size_t t = 0; t < w->nt; t++) {
        if (t % BLOCK == 0) report_round(w, 0.5 + per * (double)t);
        const uint32_t *v = w->tri + 3 * t;
        uint32_t m[3];
        int k = 0, first = -1;
        for (int e = 0; e < 3; e++) {
            m[e] = midpoint(w, v[e], v[(e + 1) % 3]); /* m[e] on edge v[e] v[e+1] */
            if (m[e] != UINT32_MAX) k++;
        }
        size_t n0 = n;
        if (k == 0) {
            dev[n] = w->dev[t];
            put(out, &n, v[0], v[1], v[2]);
            continue;
        }
        *changed = 1;
        if (k == 3) {
            put(out, &n, v[0], m[0], m[2]);
            put(out, &n, m[0], v[1], m[1]);
            put(out, &n, m[2], m[1], v[2]);
            put(out, &n, m[0], m[1], m[2]);
            for (size_t i = n0; i < n; i++) dev[i] = -1.0f;
            continue;
        }
        /* rotate so that edge 0 (a b) is split and, with two, edge 1 too */
        for (int r = 0; r < 3; r++)
            if (m[r] != UINT32_MAX && (k == 1 || m[(r + 1) % 3] != UINT32_MAX)) first = r;
        uint32_t a = v[first], b = v[(first + 1) % 3], c = v[(first + 2) % 3];
        uint32_t mab = m[first], mbc = m[(first + 1) % 3];
        if (k == 1) {
            put(out, &n, a, mab, c);
            put(out, &n, mab, b, c);
        } else {
            put(out, &n, mab, b, mbc);
            put(out, &n, a, mab, mbc);
            put(out, &n, a, mbc, c);
        }
        for (size_t i = n0; i < n; i++) dev[i] = -1.0f;
    }
    coons__free(w->tri);
    coons__free(w->dev);
    w->tri = out;
    w->dev = dev;
    w->nt = n;
    w->cap_t = cap;
    return n > max_triangles ? limit_error(w, max_triangles) : COONS_OK;
}

/* Largest squared distance of a triangle's measured points (4 inner points,
 * 3 edge midpoints): for the parts left after the last round. */
static double tri_dev2(const work *w, const uint32_t v[3])
{
    double q[3 * 7], x[3 * 7], worst = 0;
    for (int s = 0; s < 4; s++)
        for (int d = 0; d < 3; d++)
            q[3 * s + d] = BARY[s][0] * w->q[3 * v[0] + d] + BARY[s][1] * w->q[3 * v[1] + d] +
                           BARY[s][2] * w->q[3 * v[2] + d];
    for (int e = 0; e < 3; e++)
        for (int d = 0; d < 3; d++)
            q[3 * (4 + e) + d] = 0.5 * (w->q[3 * v[e] + d] + w->q[3 * v[(e + 1) % 3] + d]);
    coons_body_eval_points(w->b, 7, q, x, NULL, NULL, NULL);
    for (int s = 0; s < 4; s++)
        worst = fmax(worst, coons__tri_dist2(x + 3 * s, w->x + 3 * v[0], w->x + 3 * v[1],
                                             w->x + 3 * v[2]));
    for (int e = 0; e < 3; e++)
        worst = fmax(worst, coons__seg_dist2(x + 3 * (4 + e), w->x + 3 * v[e],
                                             w->x + 3 * v[(e + 1) % 3]));
    return worst;
}

coons_status coons_body_deform_mesh(const coons_body *b, const coons_mesh *in, const double *lo,
                                    const double *hi, double tolerance, size_t max_triangles,
                                    coons_mesh **out, coons_error *err)
{
    return coons_body_deform_mesh_report(b, in, lo, hi, tolerance, max_triangles, out, NULL, err);
}

void coons_deform_options_init(coons_deform_options *o)
{
    const coons_deform_options d = COONS_DEFORM_OPTIONS_INIT;
    if (o) *o = d;
}

coons_status coons_body_deform_mesh_report(const coons_body *b, const coons_mesh *in,
                                           const double *lo, const double *hi, double tolerance,
                                           size_t max_triangles, coons_mesh **out,
                                           coons_deform_report *report, coons_error *err)
{
    coons_deform_options o = COONS_DEFORM_OPTIONS_INIT;
    o.tolerance = tolerance;
    o.max_triangles = max_triangles;
    o.lo = lo;
    o.hi = hi;
    return coons_body_deform(b, in, &o, out, report, err);
}

coons_status coons_body_deform(const coons_body *b, const coons_mesh *in,
                               const coons_deform_options *opts, coons_mesh **out,
                               coons_deform_report *report, coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "deform: out is NULL");
    *out = NULL;
    if (report && COONS__RECORD_CHECK(err, "deform report", report->version, COONS_DEFORM_REPORT))
        return COONS_E_INVALID;
    if (!opts) return coons__error_set(err, COONS_E_INVALID, "deform: options is NULL");
    /* version 1 has no `threads`, version 2 no `relative_tolerance` */
    if (coons__record_version_check("deform options", opts->version, 1,
                                    COONS_DEFORM_OPTIONS_VERSION, "COONS_DEFORM_OPTIONS_INIT", err))
        return COONS_E_INVALID;
    unsigned threads = coons__record_threads(opts->version >= 2 ? opts->threads : 1);
    if (!b || !in) return coons__error_set(err, COONS_E_INVALID, "deform: NULL body or mesh");
    const double *lo = opts->lo, *hi = opts->hi;
    double tolerance = opts->tolerance;
    double relative = opts->version >= 3 && tolerance == 0 ? opts->relative_tolerance : 0;
    size_t max_triangles = opts->max_triangles;
    if (relative != 0 ? !(relative > 0) || !isfinite(relative)
                      : !(tolerance > 0) || !isfinite(tolerance))
        return coons__error_set(err, COONS_E_INVALID, "deform: the tolerance must be > 0");
    if (!max_triangles) max_triangles = COONS_MESH_MAX_TRIANGLES;
    size_t nv = coons_mesh_vertex_count(in), nt = coons_mesh_triangle_count(in);
    const double *xyz = coons_mesh_vertices(in);
    double L[3], H[3];
    if (lo && hi) {
        v3_copy(L, lo);
        v3_copy(H, hi);
    } else {
        bbox_empty(L, H);
        for (size_t i = 0; i < nv; i++) bbox_add(L, H, xyz + 3 * i);
    }
    for (int d = 0; d < 3; d++)
        if (!(H[d] > L[d]) || !isfinite(H[d] - L[d]))
            return coons__error_set(err, COONS_E_INVALID,
                                    "deform: the frame is flat or not finite along %c "
                                    "(%.17g to %.17g)",
                                    "xyz"[d], L[d], H[d]);
    /* a point may lie outside by rounding of the frame: 1e-12 of the extent */
    size_t outside = 0, first = 0;
    for (size_t i = 0; i < nv; i++)
        for (int d = 0; d < 3; d++) {
            double s = (xyz[3 * i + d] - L[d]) / (H[d] - L[d]);
            if (s < -1e-12 || s > 1 + 1e-12 || !isfinite(s)) {
                if (!outside++) first = i;
                break;
            }
        }
    if (outside)
        return coons__error_set(err, COONS_E_DOMAIN,
                                "deform: %zu of the %zu points lie outside the frame (%.9g, %.9g, "
                                "%.9g) - (%.9g, %.9g, %.9g), the first is point %zu at (%.9g, %.9g, "
                                "%.9g)",
                                outside, nv, L[0], L[1], L[2], H[0], H[1], H[2], first,
                                xyz[3 * first], xyz[3 * first + 1], xyz[3 * first + 2]);
    work w;
    memset(&w, 0, sizeof w);
    w.b = b;
    w.threads = threads;
    w.tol = tolerance;
    w.limit = 0.9 * tolerance;
    w.err = err;
    w.progress = opts->progress;
    w.userdata = opts->userdata;
    w.span = 0.5;
    report_round(&w, 0);
    coons_status st = COONS_OK;
    /* the input's vertices, mapped in one threaded batch */
    if (nv > UINT32_MAX - 1)
        st = coons__error_set(err, COONS_E_LIMIT, "deform: too many vertices");
    else if (nv && (!(w.q = coons__malloc_array(nv, 3 * sizeof *w.q)) ||
                    !(w.x = coons__malloc_array(nv, 3 * sizeof *w.x))))
        st = coons__error_nomem(err);
    if (!st) {
        w.nv = w.cap_v = nv;
        for (size_t i = 0; i < nv; i++)
            for (int d = 0; d < 3; d++)
                w.q[3 * i + d] = clamp01((xyz[3 * i + d] - L[d]) / (H[d] - L[d]));
        vjob j = {&w, NULL};
        coons__parallel_for(nv, threads, eval_vertices_chunk, &j);
        if (relative != 0) { /* the box of the vertices' images */
            double blo[3] = {INFINITY, INFINITY, INFINITY};
            double bhi[3] = {-INFINITY, -INFINITY, -INFINITY}, diag = 0;
            for (size_t i = 0; i < nv; i++)
                for (int d = 0; d < 3; d++) {
                    blo[d] = fmin(blo[d], w.x[3 * i + d]);
                    bhi[d] = fmax(bhi[d], w.x[3 * i + d]);
                }
            for (int d = 0; d < 3 && nv; d++) diag += (bhi[d] - blo[d]) * (bhi[d] - blo[d]);
            diag = sqrt(diag);
            w.tol = diag > 0 && isfinite(diag) ? relative * diag : relative;
            w.limit = 0.9 * w.tol;
        }
    }
    if (!st && (!(w.tri = coons__malloc_array(nt ? nt : 1, 3 * sizeof *w.tri)) ||
                !(w.dev = coons__malloc_array(nt ? nt : 1, sizeof *w.dev))))
        st = coons__error_nomem(err);
    if (!st) {
        memcpy(w.tri, coons_mesh_triangles(in), nt * 3 * sizeof *w.tri);
        for (size_t t = 0; t < nt; t++) w.dev[t] = -1.0f;
        w.nt = nt;
    }
    if (!st) st = estimate_build(&w, nt);
    unsigned rounds = 0;
    for (int changed = 1; !st && changed && rounds < 64;) {
        st = round_once(&w, max_triangles, &changed);
        rounds += !st && changed;
        /* round r (from 0) spans [1 - 2^-r, 1 - 2^-(r+1)) */
        w.base += w.span;
        w.span *= 0.5;
    }
    /* after 64 rounds that all split something, the last parts are measured */
    for (size_t t = 0; t < w.nt && !st; t++)
        if (w.dev[t] < 0) {
            w.dev[t] = (float)sqrt(tri_dev2(&w, w.tri + 3 * t));
        }
    double o[3], J[3][3];
    int reversed = !st && coons_body_eval_jacobian(b, 0.5, 0.5, 0.5, o, J) < 0;
    if (!st) {
        /* a left-handed body turns the winding inside out */
        if (reversed)
            for (size_t t = 0; t < w.nt; t++) {
                uint32_t x = w.tri[3 * t + 1];
                w.tri[3 * t + 1] = w.tri[3 * t + 2];
                w.tri[3 * t + 2] = x;
            }
        st = coons_mesh_new(out, err);
        if (!st) st = coons_mesh_add_part(*out, "deformed", w.x, w.nv, w.tri, w.nt, err);
        if (st) {
            coons_mesh_free(*out);
            *out = NULL;
        }
    }
    if (!st && w.progress) w.progress(w.userdata, "deform", 1.0);
    if (!st && report) {
        v3_copy(report->lo, L);
        v3_copy(report->hi, H);
        double worst = 0;
        for (size_t t = 0; t < w.nt; t++) worst = fmax(worst, (double)w.dev[t]);
        /* the float rounding of the stored distances, upwards */
        report->deviation = worst * (1 + 1e-7);
        report->triangles_in = nt;
        report->triangles_out = w.nt;
        report->vertices_in = nv;
        report->vertices_out = w.nv;
        report->rounds = rounds;
        report->reversed = reversed;
    }
    coons__free(w.dev);
    coons__free(w.q);
    coons__free(w.x);
    coons__free(w.tri);
    coons__free(w.key);
    coons__free(w.mid);
    coons__free(w.eix);
    coons__free(w.ends);
    coons__free(w.ex);
    coons__free(w.ed2);
    coons__free(w.pend);
    estimate_free(&w.est);
    if (estimate_mode) estimate_count = w.estimated;
    return st;
}
