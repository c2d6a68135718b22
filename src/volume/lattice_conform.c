/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Conformal volume meshes of a control lattice (seed 000 section 3: each
 * cell of the control lattice defines a Coons body; neighbouring cells
 * share faces, and in a lattice of more than one cell in two directions
 * also whole edges and corners), coons_model_volume_mesh().
 *
 * One lattice per tied class of directions (coons__vlattice_share()):
 * a face shared by two bodies (shared_faces.c) ties its two parameter
 * directions in one body to two in the other, and an edge shared by two
 * bodies (the same curve, in the same or the opposite sense, sampled at 5
 * parameters symmetric about 1/2 and compared within the consistency
 * tolerance) ties its direction in one body to its direction in the other;
 * lattice_share.c gives every class one lattice. So the points of a shared
 * face, edge or corner are evaluated at the same parameters from both
 * sides, coincide, and the mesher's merge makes them one node, also where
 * two cells meet only along an edge.
 *
 * Conformity (coons__vlattice_check()): two bodies whose boxes meet share
 * a set S of nodes. Each node of S must lie on a feature of each body (one
 * of its 6 faces, 12 edges or 8 corners in its node lattice) all of whose
 * nodes are in S: then the bodies meet along whole faces, whole edges or at
 * corners, and S is conformal, unless at a corner of both the two leave
 * along lattice edges in the same direction to different nodes (their
 * boundaries run together there: faces or edges that coincide but are
 * parametrised differently). A body pair sharing no node whose cells'
 * boxes meet within 1e-9 of the larger box diagonal touches or overlaps
 * without sharing: refused, naming both, as is a pair whose shared nodes
 * cover only part of a face or edge. */
#include <string.h>

#include "body_impl.h"
#include "lattice_impl.h"
#include "sampling.h"

/* ---- one lattice along directions that shared faces and edges tie ------ */

#define ES 5 /* samples per edge, symmetric about 1/2 */
static const double EDGE_T[ES] = {0.0, 0.2113248654051871, 0.5, 0.7886751345948129, 1.0};

/* Samples of the 12 edges of a body: edge 4 d + 2 p + q runs along axis d
 * with axis d + 1 at p and d + 2 at q (mod 3). */
static void edge_samples(const coons_body *b, double out[12][ES][3])
{
    for (int e = 0; e < 12; e++) {
        int d = e / 4;
        for (int k = 0; k < ES; k++) {
            double p[3];
            p[d] = EDGE_T[k];
            p[(d + 1) % 3] = (double)((e >> 1) & 1);
            p[(d + 2) % 3] = (double)(e & 1);
            coons_body_eval(b, p[0], p[1], p[2], out[e][k]);
        }
    }
}

static int close3(const double *a, const double *b, double tol)
{
    return fabs(a[0] - b[0]) <= tol && fabs(a[1] - b[1]) <= tol && fabs(a[2] - b[2]) <= tol;
}

/* Ties of the directions of edges that two bodies share (*out from
 * coons__malloc, *count of them). */
static coons_status edge_ties(coons__vbuild *v, double tol, coons__lattice_tie **out,
                              size_t *count)
{
    *out = NULL;
    *count = 0;
    double (*s)[12][ES][3] = coons__malloc_array(v->nb, sizeof *s);
    double (*box)[6] = coons__malloc_array(v->nb, sizeof *box);
    unsigned short *live = coons__malloc_array(v->nb, sizeof *live); /* non-degenerate edges */
    if (!s || !box || !live) {
        coons__free(s);
        coons__free(box);
        coons__free(live);
        return coons__error_nomem(v->err);
    }
    for (size_t i = 0; i < v->nb; i++) {
        edge_samples(v->vb[i].b, s[i]);
        coons_body_control_bbox(v->vb[i].b, box[i], box[i] + 3);
        live[i] = 0;
        for (int e = 0; e < 12; e++) {
            int deg = 1;
            for (int k = 1; k < ES; k++) deg &= close3(s[i][e][k], s[i][e][0], tol);
            if (!deg) live[i] |= (unsigned short)(1u << e);
        }
    }
    coons__lattice_tie *t = NULL;
    size_t n = 0, cap = 0;
    coons_status st = COONS_OK;
    for (size_t i = 0; i < v->nb && !st; i++)
        for (size_t j = i + 1; j < v->nb && !st; j++) {
            int apart = 0;
            for (int d = 0; d < 3; d++)
                apart |= box[i][d] > box[j][3 + d] + tol || box[j][d] > box[i][3 + d] + tol;
            if (apart) continue;
            for (int ea = 0; ea < 12 && !st; ea++)
                for (int eb = 0; eb < 12 && !st; eb++) {
                    if (!(live[i] >> ea & 1) || !(live[j] >> eb & 1)) continue;
                    int same = 1, flip = 1;
                    for (int k = 0; k < ES; k++) {
                        same &= close3(s[i][ea][k], s[j][eb][k], tol);
                        flip &= close3(s[i][ea][k], s[j][eb][ES - 1 - k], tol);
                    }
                    if (!same && !flip) continue;
                    if (n == cap) {
                        size_t nc = cap ? 2 * cap : 64;
                        coons__lattice_tie *g = coons__realloc(t, nc * sizeof *t);
                        if (!g) {
                            st = coons__error_nomem(v->err);
                            break;
                        }
                        t = g;
                        cap = nc;
                    }
                    t[n].x = 3 * i + (size_t)(ea / 4);
                    t[n].y = 3 * j + (size_t)(eb / 4);
                    t[n].flip = !same;
                    n++;
                }
        }
    coons__free(s);
    coons__free(box);
    coons__free(live);
    if (st) {
        coons__free(t);
        return st;
    }
    *out = t;
    *count = n;
    return COONS_OK;
}

/* Gives every set of directions that shared faces and edges connect (in
 * either sense) one lattice (lattice_share.c), so each body's lattice is
 * refined, never coarsened (each still meets its tolerance). */
coons_status coons__vlattice_share(coons__vbuild *v)
{
    if (v->nb < 2) return COONS_OK;
    double lo[3], hi[3];
    bbox_empty(lo, hi);
    const coons_body **bodies = coons__malloc_array(v->nb, sizeof *bodies);
    if (!bodies) return coons__error_nomem(v->err);
    for (size_t i = 0; i < v->nb; i++) {
        double a[3], b[3];
        coons_body_control_bbox(v->vb[i].b, a, b);
        bbox_add(lo, hi, a);
        bbox_add(lo, hi, b);
        bodies[i] = v->vb[i].b;
    }
    double tol = 1e-9 * bbox_diag(lo, hi);
    coons__shared_face *sf = NULL;
    coons__lattice_tie *ties = NULL;
    size_t nsf = 0, nties = 0;
    coons_status st = coons__find_shared_faces(bodies, v->nb, tol, &sf, &nsf, v->err);
    coons__free(bodies);
    if (!st) st = edge_ties(v, tol, &ties, &nties);
    if (st || (!nsf && !nties)) {
        coons__free(sf);
        coons__free(ties);
        return st;
    }
    double **t = coons__malloc_array(3 * v->nb, sizeof *t);
    size_t *n = coons__malloc_array(3 * v->nb, sizeof *n);
    if (!t || !n) {
        st = coons__error_nomem(v->err);
    } else {
        for (size_t x = 0; x < 3 * v->nb; x++) t[x] = v->vb[x / 3].t[x % 3], n[x] = v->vb[x / 3].n[x % 3];
        st = coons__share_lattices_tied(v->nb, t, n, sf, nsf, ties, nties, NULL, v->err);
        /* The arrays were replaced in t (also on failure, up to it). */
        for (size_t x = 0; x < 3 * v->nb; x++) v->vb[x / 3].t[x % 3] = t[x], v->vb[x / 3].n[x % 3] = n[x];
    }
    coons__free(t);
    coons__free(n);
    coons__free(sf);
    coons__free(ties);
    return st;
}

/* ---- conformity between bodies ----------------------------------------- */

/* A feature of a body's node lattice: fix[d] is -1 (free along d), 0 or 1
 * (the low or high end). Its points are the box lo[d] .. hi[d]. */
static void feature_range(const coons__vbody *B, const int fix[3], size_t lo[3], size_t hi[3])
{
    for (int d = 0; d < 3; d++) {
        lo[d] = fix[d] == 1 ? B->m[d] - 1 : 0;
        hi[d] = fix[d] == 0 ? 0 : B->m[d] - 1;
    }
}

/* The stamps `stamp[n] = tag` of every node on the feature (mode 0), or
 * whether every node on it has stamp[n] == tag (mode 1). */
static int feature_visit(const coons__vbuild *v, const coons__vbody *B, const int fix[3],
                         uint32_t *stamp, uint32_t tag, int mode)
{
    size_t lo[3], hi[3];
    feature_range(B, fix, lo, hi);
    for (size_t a = lo[0]; a <= hi[0]; a++)
        for (size_t b = lo[1]; b <= hi[1]; b++)
            for (size_t c = lo[2]; c <= hi[2]; c++) {
                if (!coons__vneeded(v, a, b, c)) continue;
                uint32_t n = coons__vnode(v, B, a, b, c);
                if (n == UINT32_MAX) continue;
                if (mode == 0)
                    stamp[n] = tag;
                else if (stamp[n] != tag)
                    return 0;
            }
    return 1;
}

/* The 26 features: index f in 1..26 (0: all free), a digit base 3 per
 * axis, fix[d] = digit - 1. */
static void feature_fix(int f, int fix[3])
{
    for (int d = 0; d < 3; d++, f /= 3) fix[d] = f % 3 - 1;
}

/* Marks in cov with `tag` the nodes of every feature of B wholly in S
 * (inS[n] == tag). */
static void cover(const coons__vbuild *v, const coons__vbody *B, uint32_t *inS, uint32_t *cov,
                  uint32_t tag)
{
    for (int f = 1; f < 27; f++) {
        int fix[3];
        feature_fix(f, fix);
        if (feature_visit(v, B, fix, inS, tag, 1)) feature_visit(v, B, fix, cov, tag, 0);
    }
}

/* Whether every node of S (on B's faces) is covered from both sides. */
static int covered(const coons__vbuild *v, const coons__vbody *B, const uint32_t *inS,
                   const uint32_t *covA, const uint32_t *covB, uint32_t tag)
{
    for (int f = 0; f < 6; f++) {
        int fix[3] = {-1, -1, -1};
        fix[f / 2] = f % 2;
        size_t lo[3], hi[3];
        feature_range(B, fix, lo, hi);
        for (size_t a = lo[0]; a <= hi[0]; a++)
            for (size_t b = lo[1]; b <= hi[1]; b++)
                for (size_t c = lo[2]; c <= hi[2]; c++) {
                    if (!coons__vneeded(v, a, b, c)) continue;
                    uint32_t n = coons__vnode(v, B, a, b, c);
                    if (n != UINT32_MAX && inS[n] == tag && (covA[n] != tag || covB[n] != tag))
                        return 0;
                }
    }
    return 1;
}

/* The first lattice segment from corner k (bits: u, v, w at their high
 * end) of B along axis d: *next gets the node at its other end, dir its
 * direction (not normalised). */
static void corner_segment(const coons__vbuild *v, const coons__vbody *B, int k, int d,
                           uint32_t *next, double dir[3])
{
    size_t p[3], q[3];
    for (int e = 0; e < 3; e++) p[e] = q[e] = (k >> e & 1) ? B->m[e] - 1 : 0;
    q[d] = (k >> d & 1) ? p[d] - 1 : p[d] + 1;
    *next = coons__vnode(v, B, q[0], q[1], q[2]);
    const double *a = v->pos + 3 * coons__vraw(B, p[0], p[1], p[2]);
    const double *b = v->pos + 3 * coons__vraw(B, q[0], q[1], q[2]);
    for (int e = 0; e < 3; e++) dir[e] = b[e] - a[e];
}

/* Whether A and B, at a corner node of both, leave it along lattice edges
 * in the same direction (within 1/100 radian) without sharing the edge's
 * next node: their boundaries then run together beyond the corner (faces
 * or edges that coincide but are parametrised differently), which the
 * shared nodes alone do not show. */
static int corner_overlap(const coons__vbuild *v, const coons__vbody *A, const coons__vbody *B,
                          const uint32_t *inS, uint32_t tag)
{
    for (int ka = 0; ka < 8; ka++) {
        size_t pa[3];
        for (int e = 0; e < 3; e++) pa[e] = (ka >> e & 1) ? A->m[e] - 1 : 0;
        uint32_t n = coons__vnode(v, A, pa[0], pa[1], pa[2]);
        if (n == UINT32_MAX || inS[n] != tag) continue;
        for (int kb = 0; kb < 8; kb++) {
            size_t pb[3];
            for (int e = 0; e < 3; e++) pb[e] = (kb >> e & 1) ? B->m[e] - 1 : 0;
            if (coons__vnode(v, B, pb[0], pb[1], pb[2]) != n) continue;
            for (int da = 0; da < 3; da++)
                for (int db = 0; db < 3; db++) {
                    uint32_t na, nb;
                    double x[3], y[3];
                    corner_segment(v, A, ka, da, &na, x);
                    corner_segment(v, B, kb, db, &nb, y);
                    double lx = v3_norm(x), ly = v3_norm(y);
                    if (na == nb || na == n || nb == n || !(lx > 0) || !(ly > 0)) continue;
                    if (v3_dot(x, y) > (1 - 5e-5) * lx * ly) return 1;
                }
        }
    }
    return 0;
}

/* First and one-past-last cell of each part (cells are added part by
 * part). */
static void part_ranges(const coons_volume_mesh *vm, size_t np, size_t *first)
{
    size_t nc = coons_volume_mesh_cell_count(vm);
    const uint32_t *part = coons_volume_mesh_cell_parts(vm);
    for (size_t i = 0; i <= np; i++) first[i] = nc;
    for (size_t c = nc; c-- > 0;) first[part[c]] = c;
    for (size_t i = np; i-- > 0;)
        if (first[i] > first[i + 1]) first[i] = first[i + 1];
}

static void cell_box(const coons_volume_mesh *vm, size_t npc, size_t c, double lo[3],
                     double hi[3])
{
    const uint32_t *row = coons_volume_mesh_cells(vm) + npc * c;
    const double *xyz = coons_volume_mesh_nodes(vm);
    bbox_empty(lo, hi);
    for (size_t k = 0; k < npc; k++) bbox_add(lo, hi, xyz + 3 * (size_t)row[k]);
}

static int boxes_meet(const double *alo, const double *ahi, const double *blo,
                      const double *bhi, double g)
{
    for (int d = 0; d < 3; d++)
        if (alo[d] > bhi[d] + g || blo[d] > ahi[d] + g) return 0;
    return 1;
}

/* Whether a cell of part i and a cell of part j have boxes that meet. */
static int cells_meet(const coons__vbuild *v, const coons_volume_mesh *vm, const size_t *first,
                      size_t i, size_t j, double g)
{
    const coons__vbody *B = &v->vb[j];
    for (size_t c = first[i]; c < first[i + 1]; c++) {
        double lo[3], hi[3];
        cell_box(vm, v->npc, c, lo, hi);
        if (!boxes_meet(lo, hi, B->lo, B->hi, g)) continue;
        for (size_t e = first[j]; e < first[j + 1]; e++) {
            double lo2[3], hi2[3];
            cell_box(vm, v->npc, e, lo2, hi2);
            if (boxes_meet(lo, hi, lo2, hi2, g)) return 1;
        }
    }
    return 0;
}

coons_status coons__vlattice_check(coons__vbuild *v, const coons_volume_mesh *vm)
{
    if (v->nb < 2) return COONS_OK;
    size_t nn = v->nn ? v->nn : 1;
    uint32_t *onA = coons__malloc_array(nn, sizeof(uint32_t));
    uint32_t *inS = coons__malloc_array(nn, sizeof(uint32_t));
    uint32_t *covA = coons__malloc_array(nn, sizeof(uint32_t));
    uint32_t *covB = coons__malloc_array(nn, sizeof(uint32_t));
    size_t *first = coons__malloc_array(v->nb + 1, sizeof(size_t));
    coons_status st = COONS_OK;
    if (!onA || !inS || !covA || !covB || !first) {
        st = coons__error_nomem(v->err);
        goto done;
    }
    memset(onA, 0, nn * sizeof(uint32_t));
    memset(inS, 0, nn * sizeof(uint32_t));
    memset(covA, 0, nn * sizeof(uint32_t));
    memset(covB, 0, nn * sizeof(uint32_t));
    part_ranges(vm, v->nb, first);
    uint32_t tag = 0;
    for (size_t i = 0; i < v->nb && !st; i++)
        for (size_t j = i + 1; j < v->nb && !st; j++) {
            const coons__vbody *A = &v->vb[i], *B = &v->vb[j];
            double g = 1e-9 * fmax(bbox_diag(A->lo, A->hi), bbox_diag(B->lo, B->hi));
            if (!boxes_meet(A->lo, A->hi, B->lo, B->hi, g)) continue;
            if (++tag == 0) { /* wrapped: start the stamps afresh */
                memset(onA, 0, nn * sizeof(uint32_t));
                memset(inS, 0, nn * sizeof(uint32_t));
                memset(covA, 0, nn * sizeof(uint32_t));
                memset(covB, 0, nn * sizeof(uint32_t));
                tag = 1;
            }
            /* S: the boundary nodes of B that are boundary nodes of A. */
            size_t shared = 0;
            for (int f = 0; f < 6; f++) {
                int fix[3] = {-1, -1, -1};
                fix[f / 2] = f % 2;
                feature_visit(v, A, fix, onA, tag, 0);
            }
            for (int f = 0; f < 6; f++) {
                int fix[3] = {-1, -1, -1};
                fix[f / 2] = f % 2;
                size_t lo[3], hi[3];
                feature_range(B, fix, lo, hi);
                for (size_t a = lo[0]; a <= hi[0]; a++)
                    for (size_t b = lo[1]; b <= hi[1]; b++)
                        for (size_t c = lo[2]; c <= hi[2]; c++) {
                            if (!coons__vneeded(v, a, b, c)) continue;
                            uint32_t n = coons__vnode(v, B, a, b, c);
                            if (n == UINT32_MAX || onA[n] != tag || inS[n] == tag) continue;
                            inS[n] = tag;
                            shared++;
                        }
            }
            int ok;
            if (!shared) {
                ok = !cells_meet(v, vm, first, i, j, g);
            } else {
                cover(v, A, inS, covA, tag);
                cover(v, B, inS, covB, tag);
                ok = covered(v, B, inS, covA, covB, tag) && !corner_overlap(v, A, B, inS, tag);
            }
            if (!ok)
                st = coons__error_set(v->err, COONS_E_UNSUPPORTED,
                                      "bodies '%s' and '%s' overlap or touch without sharing "
                                      "a whole face, a whole edge or a corner: a conformal "
                                      "volume mesh needs bodies that meet only so",
                                      A->name, B->name);
        }
done:
    coons__free(onA);
    coons__free(inS);
    coons__free(covA);
    coons__free(covB);
    coons__free(first);
    return st;
}
