/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Sampling a body's boundary into a closed triangle mesh.
 *
 * A body F: [0,1]^3 -> R^3 (seed 000, section 2) is bounded by the six
 * surfaces F(0,v,w), F(1,v,w), F(u,0,w), F(u,1,w), F(u,v,0), F(u,v,1)
 * (seed 000 section 2.2, "Boundary surfaces"). They are sampled on one
 * parameter lattice per direction, shared by the four faces that run along
 * it, so a lattice point on an edge or corner is one vertex whichever face
 * reaches it: watertight by construction. Points are evaluated once, by the
 * first face that owns them (order u0 u1 v0 v1 w0 w1); the evaluations of
 * later faces are discarded rather than welded by distance.
 *
 * Collapsed edges and faces (cone apex, a face shrunk to a curve) produce
 * lattice neighbours at the same place. They are merged only along mesh
 * edges (lattice lines and the chosen diagonals), never across the surface,
 * so merging is an edge collapse of zero-length edges. "Same place" is
 * 1e-9 of the lattice's box diagonal (the model format's consistency
 * tolerance) plus 64 ulps of the largest coordinate: evaluating the same
 * point through different blend sums (e.g. (1-v)P + vP) differs from P by
 * a few ulps of the coordinates, while a real edge of an adaptive lattice
 * is at least COONS__SAMPLE_MIN_WIDTH times the parametric speed, many orders above.
 *
 * Density: the lattices start proportional to the body's extent along each
 * direction, plus the breakpoints of the body's data (knots, segment ends,
 * where the surface may have kinks), and are refined (intervals halved)
 * where exact points F(s,t) at sub-samples of a cell lie farther than the
 * tolerance from the cell's two triangles: points on the cell's sides along
 * a direction refine that direction, interior points the direction with
 * the longer side. The distance to those triangles is an upper bound of the
 * distance to the mesh; unlike the parametric error
 * |F(s,t) - L(s,t)| it ignores sliding within the surface (a cone's
 * straight generators need no refinement). The final pass (a 7 x 7 sampling of every cell, which holds
 * the edge midpoints and triangle centroids, against the final merged
 * vertices) measures the reported deviation and accepts it below
 * ACCEPT_FRACTION of the tolerance.
 *
 * Shape: the starting lattice gives every direction enough intervals that
 * its cells are at most max_aspect times longer than the shortest
 * direction's (by the longest lattice line along each direction), so flat
 * and long bodies start with well-shaped cells; each cell is then split
 * along its shorter diagonal. Refinement is not driven by shape: in a tensor
 * lattice, halving intervals to resolve a kink or a curved strip makes thin
 * cells across the whole lattice, and re-squaring them refines everything
 * (an aspect-driven loop gave 44 times the triangles on the polyline
 * example). Cells converging to an apex are thin however they are split.
 *
 * This file: the lattices, their mesh, the sampling loop and the part it
 * emits. The measurement and refinement are in sample_measure.c, the
 * options, budgets and refusals in sample_limits.c.
 */
#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "body_impl.h"
#include "coons_internal.h"
#include "sampling.h"
#include "mesh_impl.h"
#include "flat.h"
#include "morph_lattice.h"
#include "sampler.h"
#include "union_find.h"

enum {
    START_INTERVALS = 4, /* along the longest direction */
    MAX_ROUNDS = 200
};
#define LOOP_FRACTION 0.75          /* the coarse estimate aims below the tolerance */
/* The final measurement must stay below this share of the tolerance: the
 * true maximum lies between the samples and was seen 5% above them (a
 * bicubic face of examples/body-blend-cubic.json, 1 mm cells). */
#define ACCEPT_FRACTION 0.9
/* The measuring pass samples every cell at multiples of 1/6 of its sides:
 * edge midpoints and the centroids of both triangles are among them. */
#define MEASURE_STEPS 6
/* A fixed lattice whose cheap measurement finds more than this share of
 * the tolerance is measured again on the finer samples (measure_fixed):
 * the cheap figure was within this factor of the fine one on every example
 * (see measure_fixed). */
#define CHEAP_CONFIRM 0.5
const face_desc coons__faces[6] = {
    {0, 1, 2, 1, 0.0, "u0"}, {0, 1, 2, 0, 1.0, "u1"}, {1, 0, 2, 0, 0.0, "v0"},
    {1, 0, 2, 1, 1.0, "v1"}, {2, 0, 1, 1, 0.0, "w0"}, {2, 0, 1, 0, 1.0, "w1"}};

#define coons__faces coons__faces

coons_status coons__sampler_ensure(double **p, size_t *cap, size_t need, coons_error *err)
{
    if (need <= *cap) return COONS_OK;
    double *q = coons__malloc_array(need, sizeof(double));
    if (!q) return coons__error_nomem(err);
    coons__free(*p);
    *p = q;
    *cap = need;
    return COONS_OK;
}

/* Evaluates face f on av[0..na-1] x bv[0..nb-1] into out[(i*nb + j)*3]. */
coons_status coons__sampler_eval_face(sampler *s, int f, const double *av, size_t na, const double *bv,
                              size_t nb, double *out)
{
    const face_desc *F = &coons__faces[f];
    const double *q[3];
    size_t c[3];
    q[F->fixed] = &F->val;
    c[F->fixed] = 1;
    q[F->a] = av;
    c[F->a] = na;
    q[F->b] = bv;
    c[F->b] = nb;
    /* On the options' threads where the grid is worth starting them for
     * (the same points for any count). */
    unsigned threads = na * nb >= 4096 ? s->o->threads : 1;
    coons_status st = coons_body_eval_grid_threads(s->body, q[0], c[0], q[1], c[1], q[2], c[2], out,
                                                   threads, s->err);
    if (st) return st;
    if (s->scale != 1.0)
        for (size_t i = 0; i < 3 * na * nb; i++) out[i] *= s->scale;
    if (!coons__all_finite(out, 3 * na * nb))
        return coons__error_set(s->err, COONS_E_INVALID,
                                "body '%s' evaluates to a non-finite point on face %s", s->name,
                                F->name);
    return COONS_OK;
}

coons_status coons__sampler_alloc_lattices(sampler *s)
{
    for (int d = 0; d < 3; d++) {
        coons__free(s->mark[d]);
        coons__free(s->need[d]);
        s->mark[d] = coons__calloc(s->n[d], 1);
        s->need[d] = coons__calloc(s->n[d], sizeof(double));
        if (!s->mark[d] || !s->need[d]) return coons__error_nomem(s->err);
    }
    return COONS_OK;
}

static void free_lattices(sampler *s)
{
    for (int d = 0; d < 3; d++) {
        coons__free(s->t[d]);
        coons__free(s->mark[d]);
        coons__free(s->need[d]);
        s->t[d] = NULL;
        s->mark[d] = NULL;
        s->need[d] = NULL;
    }
}

/* Starting interval counts from the body's extent along each direction,
 * raised so that cells are at most max_aspect times longer than wide. */
static coons_status start_counts(sampler *s)
{
    /* Extent along each direction: the longest lattice line of a 9 x 9
     * sampling of the faces that run along it. */
    enum { K = 9 };
    double g[K], len[3] = {0, 0, 0};
    for (int i = 0; i < K; i++) g[i] = (double)i / (K - 1);
    coons_status st = coons__sampler_ensure(&s->buf, &s->buf_cap, 3 * K * K, s->err);
    if (st) return st;
    for (int f = 0; f < 6; f++) {
        if ((st = coons__sampler_eval_face(s, f, g, K, g, K, s->buf))) return st;
        for (int j = 0; j < K; j++) {
            double la = 0, lb = 0;
            for (int i = 0; i + 1 < K; i++) {
                la += v3_dist(s->buf + 3 * (i * K + j), s->buf + 3 * ((i + 1) * K + j));
                lb += v3_dist(s->buf + 3 * (j * K + i), s->buf + 3 * (j * K + i + 1));
            }
            if (la > len[coons__faces[f].a]) len[coons__faces[f].a] = la;
            if (lb > len[coons__faces[f].b]) len[coons__faces[f].b] = lb;
        }
    }
    /* A body whose boundary runs far outside its control box (a huge
     * tangent) can have lengths that overflow: taken as the largest double,
     * so the counts stay defined and the budget check refuses it later. */
    for (int d = 0; d < 3; d++)
        if (!(len[d] <= DBL_MAX)) len[d] = DBL_MAX;
    double lmax = fmax(len[0], fmax(len[1], len[2]));
    for (int d = 0; d < 3; d++) {
        double k = lmax > 0 ? ceil(START_INTERVALS * len[d] / lmax) : 1.0;
        s->n[d] = k < 1 ? 1 : (k > START_INTERVALS ? START_INTERVALS : (size_t)k);
    }
    /* Cell length along d is about len[d] / n[d]; the shortest of them
     * (ignoring collapsed directions) bounds the others. */
    double cmin = INFINITY;
    for (int d = 0; d < 3; d++)
        if (len[d] > 1e-9 * lmax) cmin = fmin(cmin, len[d] / (double)s->n[d]);
    if (isfinite(s->o->max_aspect) && isfinite(cmin))
        for (int d = 0; d < 3; d++) {
            double k = ceil(len[d] / (s->o->max_aspect * cmin) - 1e-9);
            /* capped so that a needle cannot exhaust the budget here */
            if (k > 4096) k = 4096;
            if (k > (double)s->n[d]) s->n[d] = (size_t)k;
        }
    return COONS_OK;
}

/* The starting lattice values of direction d: n[d] uniform intervals
 * merged with the breakpoints of the body's data. */
static coons_status start_values(sampler *s, int d)
{
    /* Adaptive lattices start at the breakpoints of the body's data
     * (knots, segment ends): a kink inside a cell converges only
     * linearly, and its peak error falls between the measured samples.
     * Uniform values closer than a quarter step to a breakpoint yield. */
    double *br = NULL;
    size_t nbr = 0, n = s->n[d], k = 0;
    if (!s->o->resolution) {
        coons_status st = coons__body_breaks(s->body, d, &br, &nbr, s->err);
        if (st) return st;
    }
    s->t[d] = coons__malloc_array(n + nbr + 1, sizeof(double));
    if (!s->t[d]) {
        coons__free(br);
        return coons__error_nomem(s->err);
    }
    for (size_t i = 0, j = 0; i <= n || j < nbr;) {
        double x = i <= n ? (double)i / (double)n : 2.0, y = j < nbr ? br[j] : 2.0;
        if (y <= x) {
            if (!k || y > s->t[d][k - 1]) s->t[d][k++] = y;
            j++;
            if (fabs(x - y) < 0.25 / (double)n) i++;
        } else {
            int near = (j < nbr && br[j] - x < 0.25 / (double)n) ||
                       (j > 0 && x - br[j - 1] < 0.25 / (double)n);
            if (!near && (!k || x > s->t[d][k - 1])) s->t[d][k++] = x;
            i++;
        }
    }
    coons__free(br);
    s->t[d][0] = 0.0;
    s->t[d][k - 1] = 1.0;
    s->n[d] = k - 1;
    return COONS_OK;
}

static coons_status init_lattices(sampler *s)
{
    coons_status st = COONS_OK;
    if (s->start_t[0]) { /* a control lattice's shared values (sample_lattice.c) */
        for (int d = 0; d < 3; d++) {
            s->n[d] = s->start_n[d];
            s->t[d] = coons__malloc_array(s->n[d] + 1, sizeof(double));
            if (!s->t[d]) return coons__error_nomem(s->err);
            memcpy(s->t[d], s->start_t[d], (s->n[d] + 1) * sizeof(double));
        }
        return coons__sampler_alloc_lattices(s);
    }
    if (s->skip == 63 && !s->o->resolution) {
        /* Every face shared (a cell inside a lattice): no boundary of its
         * own; its lattice comes from its neighbours', its points only
         * join theirs (sample_lattice.c). */
        for (int d = 0; d < 3; d++) {
            s->n[d] = 1;
            s->t[d] = coons__malloc_array(2, sizeof(double));
            if (!s->t[d]) return coons__error_nomem(s->err);
            s->t[d][0] = 0.0;
            s->t[d][1] = 1.0;
        }
        return coons__sampler_alloc_lattices(s);
    }
    if (s->o->resolution) {
        for (int d = 0; d < 3; d++) s->n[d] = s->o->resolution;
    } else if ((st = start_counts(s))) {
        return st;
    }
    for (int d = 0; d < 3 && !st; d++) st = start_values(s, d);
    return st ? st : coons__sampler_alloc_lattices(s);
}

/* First face (in coons__faces order) holding lattice point ijk, of those not in
 * the mask `skip`: that face owns it. -1 when no such face holds it. */
static int owner(const sampler *s, const size_t ijk[3], unsigned skip)
{
    for (int f = 0; f < 6; f++) {
        if (skip & 1u << f) continue;
        size_t want = coons__faces[f].val == 0.0 ? 0 : s->n[coons__faces[f].fixed];
        if (ijk[coons__faces[f].fixed] == want) return f;
    }
    return -1;
}

/* Whether points p and q are surely farther apart than tol along one
 * coordinate: then v3_dist(p, q) > tol too (sqrt of a sum with d^2 in it
 * is at least |d| in floating point, where d^2 neither underflows nor
 * overflows; overflow gives infinity), without the square root. */
static inline int far_apart(const double *p, const double *q, double tol)
{
    for (int d = 0; d < 3; d++) {
        double x = fabs(p[d] - q[d]);
        if (x > tol && x > 1e-150) return 1;
    }
    return 0;
}

static void merge_close(sampler *s, uint32_t a, uint32_t b)
{
    uint32_t ra = coons__uf_find(s->uf, a), rb = coons__uf_find(s->uf, b);
    if (ra == rb) return;
    const double *p = s->pos + 3 * (size_t)ra, *q = s->pos + 3 * (size_t)rb;
    if (far_apart(p, q, s->merge_tol) || v3_dist(p, q) > s->merge_tol) return;
    /* The lower id, evaluated first, stays the representative. */
    coons__uf_link(s->uf, ra, rb);
}

static void free_mesh(sampler *s)
{
    coons__free(s->pos);
    coons__free(s->uf);
    coons__free(s->tri);
    coons__free(s->evaluated);
    coons__free(s->flat_uvw);
    s->flat_uvw = NULL;
    s->pos = NULL;
    s->uf = NULL;
    s->tri = NULL;
    s->evaluated = NULL;
    s->nt = 0;
    for (int f = 0; f < 6; f++) {
        coons__free(s->ids[f]);
        coons__free(s->diag[f]);
        s->ids[f] = NULL;
        s->diag[f] = NULL;
    }
}

/* Raw vertex of lattice point (ia, ib) of face f. */
static inline uint32_t lattice_id(const sampler *s, int f, size_t ia, size_t ib)
{
    return s->ids[f][ia * (s->n[coons__faces[f].b] + 1) + ib];
}

/* The arrays of one build: raw vertices (the lattice points on the
 * boundary), their union-find, per face its lattice ids and diagonals, and
 * room for two triangles per cell. */
static coons_status alloc_mesh(sampler *s)
{
    const size_t *n = s->n;
    size_t total = (n[0] + 1) * (n[1] + 1) * (n[2] + 1);
    size_t inner = (n[0] - 1) * (n[1] - 1) * (n[2] - 1);
    s->nv = total - inner;
    if (s->nv > UINT32_MAX)
        return coons__error_set(s->err, COONS_E_LIMIT, "body '%s': more than %u vertices",
                                s->name, (unsigned)UINT32_MAX);
    s->pos = coons__malloc_array(s->nv, 3 * sizeof(double));
    s->uf = coons__malloc_array(s->nv, sizeof(uint32_t));
    s->evaluated = coons__calloc(s->nv, 1);
    if (!s->pos || !s->uf || !s->evaluated) return coons__error_nomem(s->err);
    size_t cells = 0;
    for (int f = 0; f < 6; f++) {
        size_t na = n[coons__faces[f].a], nb = n[coons__faces[f].b];
        s->ids[f] = coons__malloc_array((na + 1) * (nb + 1), sizeof(uint32_t));
        s->diag[f] = coons__malloc_array(na * nb, 1);
        if (!s->ids[f] || !s->diag[f]) return coons__error_nomem(s->err);
        cells += na * nb;
    }
    s->tri = coons__malloc_array(cells, 6 * sizeof(uint32_t));
    if (!s->tri) return coons__error_nomem(s->err);
    return COONS_OK;
}

/* Evaluates every face on its lattice; a point is stored by the face that
 * owns it (owner()) and shared by id with the later faces, so seams are
 * one vertex by construction. Extends lo/hi by the stored points. Faces
 * in s->skip are not evaluated: their points get ids (in the same order),
 * and positions only from the other faces that hold them. */
static coons_status eval_lattice(sampler *s, double lo[3], double hi[3])
{
    const size_t *n = s->n;
    uint32_t next = 0;
    for (int f = 0; f < 6; f++) {
        const face_desc *F = &coons__faces[f];
        size_t na = n[F->a], nb = n[F->b];
        int sampled = !(s->skip & 1u << f);
        coons_status st = COONS_OK;
        if (sampled) {
            st = coons__sampler_ensure(&s->buf, &s->buf_cap, 3 * (na + 1) * (nb + 1), s->err);
            if (!st) st = coons__sampler_eval_face(s, f, s->t[F->a], na + 1, s->t[F->b], nb + 1, s->buf);
            if (st) return st;
        }
        for (size_t ia = 0; ia <= na; ia++)
            for (size_t ib = 0; ib <= nb; ib++) {
                size_t ijk[3];
                ijk[F->fixed] = F->val == 0.0 ? 0 : n[F->fixed];
                ijk[F->a] = ia;
                ijk[F->b] = ib;
                int g = owner(s, ijk, 0);
                uint32_t id;
                if (g == f) {
                    id = next++;
                    v3_set(s->pos + 3 * (size_t)id, 0, 0, 0);
                } else {
                    id = lattice_id(s, g, ijk[coons__faces[g].a], ijk[coons__faces[g].b]);
                }
                s->ids[f][ia * (nb + 1) + ib] = id;
                if (sampled && owner(s, ijk, s->skip) == f) {
                    v3_copy(s->pos + 3 * (size_t)id, s->buf + 3 * (ia * (nb + 1) + ib));
                    s->evaluated[id] = 1;
                    bbox_add(lo, hi, s->pos + 3 * (size_t)id);
                }
            }
    }
    if (next != s->nv)
        return coons__error_set(s->err, COONS_E_INTERNAL, "lattice vertex count %u != %zu",
                                (unsigned)next, s->nv);
    return COONS_OK;
}

/* Opposite faces that coincide point for point (a body closed on itself
 * along u, v or w: a ring made with closed edge curves) are glued and
 * left out: they are inside the solid, and what remains is its boundary
 * (a torus for one such pair). */
static void glue_opposite_faces(sampler *s)
{
    s->glued = 0;
    for (int d = 0; d < 3; d++) {
        if (s->skip & 3u << 2 * d) continue;
        const uint32_t *i0 = s->ids[2 * d], *i1 = s->ids[2 * d + 1];
        size_t np = (s->n[coons__faces[2 * d].a] + 1) * (s->n[coons__faces[2 * d].b] + 1), k;
        for (k = 0; k < np; k++)
            if (v3_dist(s->pos + 3 * (size_t)i0[k], s->pos + 3 * (size_t)i1[k]) > s->merge_tol)
                break;
        if (k < np) continue;
        s->glued |= 1 << d;
        for (k = 0; k < np; k++) coons__uf_union(s->uf, i0[k], i1[k]);
    }
}

/* Collapses the zero-length lattice lines (cone apex, shrunk faces). */
static void merge_lattice_lines(sampler *s)
{
    for (int f = 0; f < 6; f++) {
        if (s->skip & 1u << f) continue;
        size_t na = s->n[coons__faces[f].a], nb = s->n[coons__faces[f].b];
        for (size_t ia = 0; ia <= na; ia++)
            for (size_t ib = 0; ib <= nb; ib++) {
                if (ia < na) merge_close(s, lattice_id(s, f, ia, ib), lattice_id(s, f, ia + 1, ib));
                if (ib < nb) merge_close(s, lattice_id(s, f, ia, ib), lattice_id(s, f, ia, ib + 1));
            }
    }
}

/* Splits each cell along its shorter diagonal, and collapses that
 * diagonal where it has zero length. */
static void choose_diagonals(sampler *s)
{
    for (int f = 0; f < 6; f++) {
        if (s->skip & 1u << f) continue;
        size_t na = s->n[coons__faces[f].a], nb = s->n[coons__faces[f].b];
        for (size_t p = 0; p < na; p++)
            for (size_t q = 0; q < nb; q++) {
                uint32_t i00 = lattice_id(s, f, p, q), i10 = lattice_id(s, f, p + 1, q);
                uint32_t i01 = lattice_id(s, f, p, q + 1), i11 = lattice_id(s, f, p + 1, q + 1);
                double d1 = v3_dist(coons__sampler_rep(s, i00), coons__sampler_rep(s, i11));
                double d2 = v3_dist(coons__sampler_rep(s, i10), coons__sampler_rep(s, i01));
                unsigned char dg = d2 < d1;
                s->diag[f][p * nb + q] = dg;
                /* merge_close() of the diagonal measures this distance
                 * between the same representatives again. */
                if ((dg ? d2 : d1) > s->merge_tol) continue;
                if (dg)
                    merge_close(s, i10, i01);
                else
                    merge_close(s, i00, i11);
            }
    }
}

/* The two triangles of every cell of the faces not glued, between the
 * representatives, wound by the face's orientation; collapsed ones drop. */
static void emit_cells(sampler *s)
{
    size_t nt = 0;
    s->flat_faces = 0;
    for (int f = 0; f < 6; f++) {
        s->face_tri[f] = nt;
        if (s->glued & 1 << coons__faces[f].fixed || s->skip & 1u << f) continue;
        size_t na = s->n[coons__faces[f].a], nb = s->n[coons__faces[f].b];
        for (size_t p = 0; p < na; p++)
            for (size_t q = 0; q < nb; q++) {
                uint32_t A = coons__uf_find(s->uf, lattice_id(s, f, p, q));
                uint32_t B = coons__uf_find(s->uf, lattice_id(s, f, p + 1, q));
                uint32_t C = coons__uf_find(s->uf, lattice_id(s, f, p + 1, q + 1));
                uint32_t D = coons__uf_find(s->uf, lattice_id(s, f, p, q + 1));
                uint32_t t[2][3];
                if (!s->diag[f][p * nb + q]) {
                    t[0][0] = A, t[0][1] = B, t[0][2] = C;
                    t[1][0] = A, t[1][1] = C, t[1][2] = D;
                } else {
                    t[0][0] = A, t[0][1] = B, t[0][2] = D;
                    t[1][0] = B, t[1][1] = C, t[1][2] = D;
                }
                for (int k = 0; k < 2; k++) {
                    uint32_t x = t[k][0], y = t[k][1], z = t[k][2];
                    if (x == y || y == z || z == x) continue; /* collapsed */
                    if (coons__faces[f].flip) {
                        uint32_t tmp = y;
                        y = z;
                        z = tmp;
                    }
                    s->tri[3 * nt] = x;
                    s->tri[3 * nt + 1] = y;
                    s->tri[3 * nt + 2] = z;
                    nt++;
                }
            }
    }
    s->face_tri[6] = nt;
    s->nt = nt;
}

/* Outward whatever the handedness: a left-handed body (det J < 0) maps
 * the outward lattice orientation inward, which makes the volume
 * negative. Shifting by one vertex reduces cancellation. */
static void orient_outward(sampler *s)
{
    size_t nt = s->nt;
    double vol = 0;
    if (s->skip) { /* an open shell: the sign found from the whole body */
        if (s->sign < 0)
            for (size_t t = 0; t < nt; t++) {
                uint32_t tmp = s->tri[3 * t + 1];
                s->tri[3 * t + 1] = s->tri[3 * t + 2];
                s->tri[3 * t + 2] = tmp;
            }
        return;
    }
    const double *o = nt ? s->pos + 3 * (size_t)s->tri[0] : NULL;
    for (size_t t = 0; t < nt; t++) {
        double a[3], b[3], c[3], bc[3];
        v3_sub(a, s->pos + 3 * (size_t)s->tri[3 * t], o);
        v3_sub(b, s->pos + 3 * (size_t)s->tri[3 * t + 1], o);
        v3_sub(c, s->pos + 3 * (size_t)s->tri[3 * t + 2], o);
        v3_cross(bc, b, c);
        vol += v3_dot(a, bc);
    }
    if (vol < 0)
        for (size_t t = 0; t < nt; t++) {
            uint32_t tmp = s->tri[3 * t + 1];
            s->tri[3 * t + 1] = s->tri[3 * t + 2];
            s->tri[3 * t + 2] = tmp;
        }
}

/* Evaluates the lattice, shares seam vertices, merges collapsed edges,
 * splits cells along the shorter diagonal and orients the triangles. */
static coons_status build(sampler *s)
{
    free_mesh(s);
    double lo[3], hi[3];
    bbox_empty(lo, hi);
    coons_status st = alloc_mesh(s);
    if (!st) st = eval_lattice(s, lo, hi);
    if (st) return st;
    s->merge_tol = coons__same_place_tol(lo, hi);
    for (uint32_t i = 0; i < (uint32_t)s->nv; i++) s->uf[i] = i;
    glue_opposite_faces(s);
    merge_lattice_lines(s);
    choose_diagonals(s);
    emit_cells(s);
    orient_outward(s);
    return COONS_OK;
}

/* The body's orientation, for a sampler that leaves faces out (its own
 * shell is then open): the sign of the volume enclosed by all six faces
 * sampled on a K x K grid each, wound as emit_cells() winds them. */
static coons_status coarse_sign(sampler *s)
{
    enum { K = 9 };
    double g[K], vol = 0, o[3] = {0, 0, 0};
    for (int i = 0; i < K; i++) g[i] = (double)i / (K - 1);
    coons_status st = coons__sampler_ensure(&s->buf, &s->buf_cap, 3 * K * K, s->err);
    for (int f = 0; f < 6 && !st; f++) {
        if ((st = coons__sampler_eval_face(s, f, g, K, g, K, s->buf))) break;
        if (f == 0) v3_copy(o, s->buf); /* a point of the shell: less cancellation */
        for (int p = 0; p + 1 < K; p++)
            for (int q = 0; q + 1 < K; q++) {
                const double *A = s->buf + 3 * (p * K + q), *B = s->buf + 3 * ((p + 1) * K + q);
                const double *C = s->buf + 3 * ((p + 1) * K + q + 1);
                const double *D = s->buf + 3 * (p * K + q + 1);
                const double *tri[2][3] = {{A, B, C}, {A, C, D}};
                for (int k = 0; k < 2; k++) {
                    double a[3], b[3], c[3], bc[3];
                    v3_sub(a, tri[k][0], o);
                    v3_sub(b, tri[k][coons__faces[f].flip ? 2 : 1], o);
                    v3_sub(c, tri[k][coons__faces[f].flip ? 1 : 2], o);
                    v3_cross(bc, b, c);
                    vol += v3_dot(a, bc);
                }
            }
    }
    s->sign = vol < 0 ? -1 : 1;
    return st;
}

/* A fixed lattice's deviation, cheaply: the 3 x 3 samples of every cell
 * (edge midpoints and centre, as each round of adaptive refinement scans
 * them: about 4 evaluations per lattice point); where that finds more than
 * CHEAP_CONFIRM of the tolerance, the 7 x 7 samples of the adaptive
 * acceptance (MEASURE_STEPS) give the figure reported. */
static coons_status measure_fixed(sampler *s)
{
    s->measured = 1;
    coons_status st = coons__sampler_scan(s, 2, 0.0);
    if (st || !(s->dev > CHEAP_CONFIRM * s->tol)) return st;
    return coons__sampler_scan(s, MEASURE_STEPS, 0.0);
}

static coons_status run_once(sampler *s)
{
    coons_status st = init_lattices(s);
    if (st) return st;
    if (s->skip && s->skip != 63 && (st = coarse_sign(s))) return st;
    if (s->o->resolution) {
        if ((st = coons__sampler_check_budget(s)) || (st = build(s))) return st;
        if (s->o->flags & COONS_SAMPLE_UNMEASURED) return COONS_OK;
        return measure_fixed(s);
    }
    for (int round = 0; round < MAX_ROUNDS; round++) {
        if ((st = coons__sampler_check_budget(s)) || (st = build(s))) return st;
        if ((st = coons__sampler_scan(s, 2, LOOP_FRACTION * s->tol)) || (st = coons__sampler_predict_budget(s))) return st;
        size_t split;
        if ((st = coons__sampler_refine(s, &split))) return st;
        if (split) continue;
        /* The coarse estimate is satisfied: measure on the finer samples. */
        if ((st = coons__sampler_scan(s, MEASURE_STEPS, ACCEPT_FRACTION * s->tol))) return st;
        s->measured = 1;
        if (s->dev <= ACCEPT_FRACTION * s->tol) return COONS_OK;
        if ((st = coons__sampler_refine(s, &split))) return st;
        if (!split) break;
    }
    return coons__error_set(s->err, COONS_E_LIMIT,
                            "body '%s': cannot reach tolerance %g (deviation %g remains where "
                            "the parameter step is already %g)",
                            s->name, s->o->tolerance, s->dev / s->scale, COONS__SAMPLE_MIN_WIDTH);
}

coons_status coons__sampler_adapt(sampler *s)
{
    s->refused = 0;
    coons_status st = run_once(s);
    return st == COONS_E_LIMIT && s->refused ? coons__sampler_refusal(s) : st;
}

static coons_status emit(sampler *s, coons_mesh *mesh, size_t *triangles)
{
    coons_status fst = coons__flat_faces(s);
    if (fst) return fst;
    if (!s->nt)
        return coons__error_set(s->err, COONS_E_INVALID,
                                "body '%s' has no boundary surface: it collapses to a curve or "
                                "a point",
                                s->name);
    uint32_t *map = coons__malloc_array(s->nv, sizeof(uint32_t));
    uint32_t *tri = coons__malloc_array(s->nt, 3 * sizeof(uint32_t));
    double *xyz = coons__malloc_array(s->nv, 3 * sizeof(double));
    /* Parameters on request (isoparametric output with the boundary). */
    int params = (s->o->flags & COONS__SAMPLE_PARAMS) != 0;
    double *uvw = params ? coons__malloc_array(s->nv, 6 * sizeof(double)) : NULL;
    coons_status st = COONS_OK;
    if (!map || !tri || !xyz || (params && !uvw)) {
        st = coons__error_nomem(s->err);
        goto done;
    }
    if (params) { /* raw vertex parameters in uvw[3 nv ..], then compacted */
        for (int f = 0; f < 6; f++) {
            const face_desc *F = &coons__faces[f];
            for (size_t ia = 0; ia <= s->n[F->a]; ia++)
                for (size_t ib = 0; ib <= s->n[F->b]; ib++) {
                    double *q = uvw + 3 * (s->nv + (size_t)lattice_id(s, f, ia, ib));
                    q[F->fixed] = F->val;
                    q[F->a] = s->t[F->a][ia];
                    q[F->b] = s->t[F->b][ib];
                }
        }
        /* and the Steiner points of flat faces (flat.c) */
        for (size_t v = s->flat_v0; s->flat_uvw && v < s->nv; v++)
            v3_copy(uvw + 3 * (s->nv + v), s->flat_uvw + 3 * (v - s->flat_v0));
    }
    memset(map, 0xff, s->nv * sizeof(uint32_t));
    uint32_t nv = 0;
    for (size_t i = 0; i < 3 * s->nt; i++) {
        uint32_t v = s->tri[i];
        if (map[v] == UINT32_MAX) {
            coons__sampler_unscaled(s, v, xyz + 3 * (size_t)nv);
            if (params) v3_copy(uvw + 3 * (size_t)nv, uvw + 3 * (s->nv + (size_t)v));
            map[v] = nv++;
        }
        tri[i] = map[v];
    }
    size_t part = mesh->nparts;
    st = coons__mesh_add_part_uvw(mesh, s->name, xyz, uvw, nv, tri, s->nt, s->err);
    if (!st) {
        coons__mesh_part *P = &mesh->parts[part];
        P->tolerance = s->o->tolerance;
        P->sampled = 1;
        P->deviation = s->measured ? s->dev / s->scale : NAN;
        for (int d = 0; d < 3; d++) P->lattice[d] = s->n[d];
        P->glued = s->glued;
        if (triangles) *triangles = s->nt;
    }
done:
    coons__free(map);
    coons__free(tri);
    coons__free(xyz);
    coons__free(uvw);
    return st;
}

void coons__sampler_init(sampler *s, const coons_body *b, const coons__sample_opts *o,
                         const char *name, coons_error *err)
{
    memset(s, 0, sizeof *s);
    s->body = b;
    s->o = o;
    s->name = name ? name : "body";
    s->err = err;
    s->sign = 1;
    /* A power of two near 1 / the body's extent (control box). */
    double lo[3], hi[3], ext = 0;
    coons_body_control_bbox(b, lo, hi);
    for (int d = 0; d < 3; d++) ext = fmax(ext, hi[d] - lo[d]);
    s->scale = ext > 0 && isfinite(ext) ? ldexp(1.0, -ilogb(ext)) : 1.0;
    s->tol = o->tolerance * s->scale;
}

coons_status coons__sampler_run(sampler *s)
{
    /* A sampler may run again (from a new starting lattice). */
    free_mesh(s);
    free_lattices(s);
    s->measured = 0;
    s->dev = 0;
    coons_status st = coons__sampler_adapt(s);
    return st ? st : coons__flat_faces(s);
}

void coons__sampler_free(sampler *s)
{
    free_mesh(s);
    free_lattices(s);
    coons__free(s->buf);
    coons__free(s->bs);
    s->buf = s->bs = NULL;
    s->buf_cap = s->bs_cap = 0;
}

coons_status coons__body_sample_into(const coons_body *b, const coons__sample_opts *o,
                                     const char *name, coons_mesh *mesh, size_t *triangles,
                                     coons_error *err)
{
    sampler s;
    coons__sampler_init(&s, b, o, name, err);
    coons_status st = coons__sampler_adapt(&s);
    if (!st) st = emit(&s, mesh, triangles);
    coons__sampler_free(&s);
    return st;
}

coons_status coons__body_sample_lattice(const coons_body *b, const coons__sample_opts *o,
                                        const char *name, double *t[3], size_t n[3],
                                        double *deviation, coons_error *err)
{
    sampler s;
    coons__sampler_init(&s, b, o, name, err);
    coons_status st = coons__sampler_adapt(&s);
    for (int d = 0; d < 3; d++) {
        if (st == COONS_OK) {
            t[d] = s.t[d];
            n[d] = s.n[d];
            s.t[d] = NULL;
        } else {
            t[d] = NULL;
            n[d] = 0;
        }
    }
    if (deviation) *deviation = st == COONS_OK && s.measured ? s.dev / s.scale : NAN;
    coons__sampler_free(&s);
    return st;
}
