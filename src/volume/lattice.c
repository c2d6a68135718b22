/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Hexahedral meshes of bodies on their (u,v,w) lattice: the interior of
 * seed 000 (section 2: a Coons body F: [0,1]^3 -> R^3; sections 1, 2.2 and
 * 5: "hexahedral elements" of FEM), coons_body_volume_mesh() and
 * coons_model_volume_mesh() (coons/volume.h).
 *
 * The lattice along each direction is the boundary sampler's (the same
 * intervals coons_body_sample() settles on at the tolerance, so the volume
 * mesh's boundary is the boundary mesh's lattice) or uniform. Nodes live on
 * the node lattice: the lattice values, plus for hex20/hex27 the interval
 * midpoints in parameter space; each is evaluated on the exact map (one
 * coons_body_eval_grid() call per body), so the mesh is isoparametric to
 * the body: a cell's node k is F at the parameters of its reference
 * position (Gmsh order, coons/volume.h).
 *
 * Bodies that share a face (shared_faces.c) or a whole edge get one
 * lattice along the directions they connect (lattice_conform.c), so the
 * shared points are evaluated at the same parameters from both sides; the
 * same file refuses bodies that meet otherwise.
 *
 * Coincident nodes are one node: only boundary points of a body can
 * coincide with another point (the map of a valid body is injective inside),
 * so the boundary points of every body go into one hash grid of cell size
 * `merge_tol` and points within it are joined (union-find, lower raw id
 * stays the representative). That one rule makes collapsed edges and faces
 * (apex, tip), closed bodies (a tube whose faces u0 and u1 coincide) and
 * faces shared by two bodies conformal alike. The tolerance is the
 * consistency tolerance of the model format, 1e-9 of the box diagonal,
 * plus 64 ulps of the largest coordinate (as the sampler's).
 *
 * Orientation: a body whose det J is negative at most nodes is
 * left-handed; its cells take their nodes mirrored in r (node k at the
 * reference position (1 - r, s, t) of node k), which makes them positive.
 * The `det_j` field keeps the body's own sign.
 *
 * Each body's cells are added grouped by what the writers make of them
 * (cell_block(): hexahedra, wedges, pyramids), each group in lattice
 * order, so that readers that split a mesh into blocks of one cell type
 * (meshio, ParaView) see at most three per body. */
#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "body_impl.h"
#include "cell_shape.h"
#include "lattice_impl.h"
#include "parallel.h"
#include "sampling.h"

/* Doubled reference position of each Gmsh node of a hex27 (coons/volume.h);
 * hex8 and hex20 are its first 8 and 20 rows. */
static const unsigned char REF[27][3] = {
    {0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2}, {2, 2, 2},
    {0, 2, 2}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 1, 0}, {2, 0, 1}, {1, 2, 0},
    {2, 2, 1}, {0, 2, 1}, {1, 0, 2}, {0, 1, 2}, {2, 1, 2}, {1, 2, 2}, {1, 1, 0},
    {1, 0, 1}, {0, 1, 1}, {2, 1, 1}, {1, 2, 1}, {1, 1, 2}, {1, 1, 1}};

/* Corners of each local face (numbered as the body faces u0 .. w1). */
static const unsigned char FACE_CORNERS[6][4] = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4},
                                                 {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};

/* Runs of a parallel loop whose per-run results are kept on the stack. */
#define COONS__MAX_RUNS 64u

typedef coons__vbody vbody;
typedef coons__vbuild vbuild;

static void report(const vbuild *v, const char *stage, double fraction)
{
    if (v->progress) v->progress(v->userdata, stage, fraction);
}

static void vbuild_free(vbuild *v)
{
    for (size_t i = 0; i < v->nb; i++)
        for (int d = 0; d < 3; d++) {
            coons__free(v->vb[i].L[d]);
            coons__free(v->vb[i].t[d]);
        }
    coons__free(v->vb);
    coons__free(v->pos);
    coons__free(v->uf);
    coons__free(v->id);
}

static coons_status opts_resolve(const coons_volume_options *in, coons_volume_options *out,
                                 coons_error *err)
{
    coons_volume_options def = COONS_VOLUME_OPTIONS_INIT;
    if (!in) in = &def;
    /* version 1 has no progress fields to read */
    if (coons__record_version_check("volume options", in->version, 1,
                                    COONS_VOLUME_OPTIONS_VERSION, "COONS_VOLUME_OPTIONS_INIT", err))
        return COONS_E_INVALID;
    if (in->version == 1) {
        *out = def;
        out->element = in->element;
        for (int d = 0; d < 3; d++) out->resolution[d] = in->resolution[d];
        out->tolerance = in->tolerance;
        out->max_cells = in->max_cells;
    } else if (in->version == 2) { /* no `threads` to read */
        *out = def;
        memcpy(out, in, offsetof(coons_volume_options, threads));
    } else {
        *out = *in;
    }
    out->threads = coons__record_threads(out->threads);
    if (out->element == 0) out->element = COONS_ELEMENT_HEX8;
    if (out->element != COONS_ELEMENT_HEX8 && out->element != COONS_ELEMENT_HEX20 &&
        out->element != COONS_ELEMENT_HEX27)
        return coons__error_set(err, COONS_E_INVALID,
                                "element kind %d: expected hex8 (8), hex20 (20) or hex27 (27)",
                                (int)out->element);
    int fixed = out->resolution[0] || out->resolution[1] || out->resolution[2];
    for (int d = 0; d < 3 && fixed; d++) {
        if (!out->resolution[d])
            return coons__error_set(err, COONS_E_INVALID,
                                    "resolution %u,%u,%u: every direction needs at least one "
                                    "interval (or all 0 for the sampled lattice)",
                                    out->resolution[0], out->resolution[1], out->resolution[2]);
        if (out->resolution[d] > (1u << 20))
            return coons__error_set(err, COONS_E_LIMIT, "resolution %u is above %u",
                                    out->resolution[d], 1u << 20);
    }
    if (isnan(out->tolerance) || isinf(out->tolerance))
        return coons__error_set(err, COONS_E_INVALID, "tolerance must be a finite number");
    if (!out->max_cells) out->max_cells = COONS_VOLUME_MAX_CELLS;
    return COONS_OK;
}

/* The cell lattice of a body: sampled or uniform. */
static coons_status body_lattice(vbuild *v, vbody *B, const coons_volume_options *o,
                                 double tolerance)
{
    double **t = B->t;
    coons_status st = COONS_OK;
    if (o->resolution[0]) {
        for (int d = 0; d < 3 && !st; d++) {
            B->n[d] = o->resolution[d];
            t[d] = coons__malloc_array(B->n[d] + 1, sizeof(double));
            if (!t[d]) {
                st = coons__error_nomem(v->err);
                break;
            }
            for (size_t i = 0; i <= B->n[d]; i++) t[d][i] = (double)i / (double)B->n[d];
        }
    } else {
        coons__sample_opts so;
        if ((st = coons__sample_opts_resolve(NULL, &so, v->err))) return st;
        so.tolerance = tolerance;
        so.max_cells = o->max_cells; /* a lattice far above it is refused at once */
        so.threads = v->threads;
        st = coons__body_sample_lattice(B->b, &so, B->name, t, B->n, NULL, v->err);
    }
    return st;
}

/* The node lattice: the cell lattice, with the interval midpoints for
 * hex20 and hex27. */
static coons_status node_lattice(vbuild *v, vbody *B)
{
    double **t = B->t;
    coons_status st = COONS_OK;
    for (int d = 0; d < 3 && !st; d++) {
        B->m[d] = (size_t)v->step * B->n[d] + 1;
        B->L[d] = coons__malloc_array(B->m[d], sizeof(double));
        if (!B->L[d]) {
            st = coons__error_nomem(v->err);
            break;
        }
        for (size_t i = 0; i < B->n[d]; i++) {
            B->L[d][(size_t)v->step * i] = t[d][i];
            if (v->step == 2) B->L[d][2 * i + 1] = 0.5 * (t[d][i] + t[d][i + 1]);
        }
        B->L[d][B->m[d] - 1] = 1.0;
    }
    return st;
}

/* One run of u planes [lo, hi) of a body's evaluated points: their box,
 * and the first point that is not finite (SIZE_MAX: none). */
typedef struct eval_run {
    const vbody *B;
    const double *pos;
    double lo[COONS__MAX_RUNS][3], hi[COONS__MAX_RUNS][3];
    size_t bad[COONS__MAX_RUNS];
} eval_run;

static void check_run(void *ctx, unsigned chunk, size_t a0, size_t a1)
{
    eval_run *e = ctx;
    const vbody *B = e->B;
    double *lo = e->lo[chunk], *hi = e->hi[chunk];
    bbox_empty(lo, hi);
    e->bad[chunk] = SIZE_MAX;
    size_t plane = B->m[1] * B->m[2];
    for (size_t r = a0 * plane; r < a1 * plane; r++) {
        const double *p = e->pos + 3 * (B->base + r);
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
            e->bad[chunk] = r;
            return;
        }
        bbox_add(lo, hi, p);
    }
}

static coons_status evaluate(vbuild *v)
{
    for (size_t i = 0; i < v->nb; i++) {
        vbody *B = &v->vb[i];
        report(v, "evaluate", (double)B->base / (double)v->nraw);
        coons_status st =
            coons_body_eval_grid_threads(B->b, B->L[0], B->m[0], B->L[1], B->m[1], B->L[2],
                                         B->m[2], v->pos + 3 * B->base, v->threads, v->err);
        if (st) return st;
        eval_run e;
        e.B = B;
        e.pos = v->pos;
        unsigned runs = v->threads < COONS__MAX_RUNS ? v->threads : COONS__MAX_RUNS;
        size_t k = runs < B->m[0] ? runs : B->m[0];
        coons__parallel_for(B->m[0], runs, check_run, &e);
        bbox_empty(B->lo, B->hi);
        for (size_t c = 0; c < k; c++) {
            if (e.bad[c] != SIZE_MAX) {
                size_t r = e.bad[c], plane = B->m[1] * B->m[2];
                return coons__error_set(v->err, COONS_E_INVALID,
                                        "body '%s' evaluates to a point that is not "
                                        "finite at (u,v,w) = (%g, %g, %g)",
                                        B->name, B->L[0][r / plane], B->L[1][r % plane / B->m[2]],
                                        B->L[2][r % B->m[2]]);
            }
            bbox_add(B->lo, B->hi, e.lo[c]);
            bbox_add(B->lo, B->hi, e.hi[c]);
        }
    }
    return COONS_OK;
}

/* ---- merging coincident boundary points -------------------------------- */

typedef struct hgrid {
    int64_t *key;  /* 3 per slot */
    uint32_t *head;/* first point of the slot's chain, UINT32_MAX: empty */
    uint32_t *next;/* per raw id */
    size_t cap;    /* power of two */
} hgrid;

static size_t hslot(const hgrid *h, const int64_t k[3])
{
    uint64_t x = (uint64_t)k[0] * 0x9E3779B97F4A7C15ull ^ (uint64_t)k[1] * 0xC2B2AE3D27D4EB4Full ^
                 (uint64_t)k[2] * 0x165667B19E3779F9ull;
    x ^= x >> 29;
    size_t s = (size_t)x & (h->cap - 1);
    while (h->head[s] != UINT32_MAX &&
           (h->key[3 * s] != k[0] || h->key[3 * s + 1] != k[1] || h->key[3 * s + 2] != k[2]))
        s = (s + 1) & (h->cap - 1);
    return s;
}

static int is_boundary(const vbody *B, size_t a, size_t b, size_t c)
{
    return a == 0 || b == 0 || c == 0 || a + 1 == B->m[0] || b + 1 == B->m[1] ||
           c + 1 == B->m[2];
}

static coons_status merge(vbuild *v)
{
    double lo[3], hi[3];
    bbox_empty(lo, hi);
    size_t nbnd = 0;
    for (size_t i = 0; i < v->nb; i++) {
        const vbody *B = &v->vb[i];
        bbox_add(lo, hi, B->lo);
        bbox_add(lo, hi, B->hi);
        size_t inner = 1;
        for (int d = 0; d < 3; d++) inner *= B->m[d] > 2 ? B->m[d] - 2 : 0;
        nbnd += B->m[0] * B->m[1] * B->m[2] - inner;
    }
    double tol = coons__same_place_tol(lo, hi);
    if (!(tol > 0)) tol = DBL_MIN;
    for (size_t r = 0; r < v->nraw; r++) v->uf[r] = (uint32_t)r;
    hgrid h = {NULL, NULL, NULL, 16};
    while (h.cap < 2 * nbnd) h.cap *= 2;
    h.key = coons__malloc_array(h.cap, 3 * sizeof(int64_t));
    h.head = coons__malloc_array(h.cap, sizeof(uint32_t));
    h.next = coons__malloc_array(v->nraw, sizeof(uint32_t));
    if (!h.key || !h.head || !h.next) {
        coons__free(h.key);
        coons__free(h.head);
        coons__free(h.next);
        return coons__error_nomem(v->err);
    }
    memset(h.head, 0xff, h.cap * sizeof(uint32_t));
    /* Cells of side 2 tol: two points within tol are in neighbouring cells. */
    double inv = 1.0 / (2 * tol);
    for (size_t i = 0; i < v->nb; i++) {
        const vbody *B = &v->vb[i];
        for (size_t a = 0; a < B->m[0]; a++)
            for (size_t b = 0; b < B->m[1]; b++)
                for (size_t c = 0; c < B->m[2]; c++) {
                    if (!is_boundary(B, a, b, c) || !coons__vneeded(v, a, b, c)) continue;
                    size_t r = coons__vraw(B, a, b, c);
                    const double *p = v->pos + 3 * r;
                    int64_t k[3];
                    for (int d = 0; d < 3; d++) k[d] = (int64_t)floor((p[d] - lo[d]) * inv);
                    for (int dx = -1; dx <= 1; dx++)
                        for (int dy = -1; dy <= 1; dy++)
                            for (int dz = -1; dz <= 1; dz++) {
                                int64_t q[3] = {k[0] + dx, k[1] + dy, k[2] + dz};
                                size_t s = hslot(&h, q);
                                for (uint32_t o = h.head[s]; o != UINT32_MAX; o = h.next[o]) {
                                    const double *w = v->pos + 3 * (size_t)o;
                                    if (fabs(w[0] - p[0]) <= tol && fabs(w[1] - p[1]) <= tol &&
                                        fabs(w[2] - p[2]) <= tol)
                                        coons__uf_union(v->uf, o, (uint32_t)r);
                                }
                            }
                    size_t s = hslot(&h, k);
                    if (h.head[s] == UINT32_MAX) memcpy(h.key + 3 * s, k, sizeof k);
                    h.next[r] = h.head[s];
                    h.head[s] = (uint32_t)r;
                }
    }
    coons__free(h.key);
    coons__free(h.head);
    coons__free(h.next);
    /* Flat: every entry its root (a root is the lowest id of its set, so
     * in increasing order each parent is already final), which makes
     * coons__vnode() a read that threads may share. */
    for (size_t r = 0; r < v->nraw; r++) v->uf[r] = v->uf[v->uf[r]];
    return COONS_OK;
}

/* ---- nodes, cells, fields and sets ------------------------------------- */

/* The nodes of cell (i, j, k) of body B in Gmsh order (mirrored in r for a
 * left-handed body). */
static void cell_nodes(const vbuild *v, const vbody *B, size_t i, size_t j, size_t k,
                       uint32_t *out)
{
    size_t s = (size_t)v->step;
    for (size_t q = 0; q < v->npc; q++) {
        size_t r = REF[q][0], t1 = REF[q][1], t2 = REF[q][2];
        if (B->left) r = 2 - r;
        out[q] = coons__vnode(v, B, s * i + r * s / 2, s * j + t1 * s / 2, s * k + t2 * s / 2);
    }
}

static size_t distinct_corners(const uint32_t *c)
{
    size_t n = 0;
    for (int i = 0; i < 8; i++) {
        int dup = 0;
        for (int j = 0; j < i; j++) dup |= c[j] == c[i];
        n += !dup;
    }
    return n;
}

/* The nodes of u planes [a0, a1) of one body: coordinates, parameters
 * and det J (evaluated in slabs of u, one grid call each: the types' grid
 * paths are many times faster than point by point); each run counts the
 * signs of det J and keeps its own error. */
typedef struct node_run {
    const vbuild *v;
    const vbody *B;
    double *xyz, *par[3], *det; /* the mesh's nodes and node fields u, v, w, det_j */
    long sign[COONS__MAX_RUNS];
    coons_status st[COONS__MAX_RUNS];
    coons_error err[COONS__MAX_RUNS];
} node_run;

static void node_rows(void *ctx, unsigned chunk, size_t a0, size_t a1)
{
    node_run *nr = ctx;
    const vbuild *v = nr->v;
    const vbody *B = nr->B;
    long sign = 0;
    coons_status st = COONS_OK;
    size_t plane = B->m[1] * B->m[2], slab = plane ? ((size_t)1 << 18) / plane : 1;
    if (slab < 1) slab = 1;
    if (slab > a1 - a0) slab = a1 - a0;
    double *dg = coons__malloc_array(slab * plane, sizeof(double));
    if (!dg) st = coons__error_nomem(&nr->err[chunk]);
    for (size_t s0 = a0; s0 < a1 && !st; s0 += slab) {
        size_t na = a1 - s0 < slab ? a1 - s0 : slab;
        st = coons__body_det_grid(B->b, B->L[0] + s0, na, B->L[1], B->m[1], B->L[2], B->m[2], dg,
                                  &nr->err[chunk]);
        for (size_t a = s0; a < s0 + na && !st; a++)
            for (size_t b = 0; b < B->m[1]; b++)
                for (size_t c = 0; c < B->m[2]; c++) {
                    size_t r = coons__vraw(B, a, b, c);
                    if (!coons__vneeded(v, a, b, c) || v->uf[r] != r) continue;
                    uint32_t n = v->id[r];
                    double d = dg[((a - s0) * B->m[1] + b) * B->m[2] + c];
                    v3_copy(nr->xyz + 3 * (size_t)n, v->pos + 3 * r);
                    nr->par[0][n] = B->L[0][a];
                    nr->par[1][n] = B->L[1][b];
                    nr->par[2][n] = B->L[2][c];
                    nr->det[n] = isfinite(d) ? d : 0.0;
                    sign += d > 0 ? 1 : d < 0 ? -1 : 0;
                }
    }
    coons__free(dg);
    nr->sign[chunk] = sign;
    nr->st[chunk] = st;
}

/* Numbers the nodes (representatives used by some kept cell, in raw
 * order) and adds them with their fields u, v, w (parameters) and det_j,
 * decides each body's handedness from det J at its nodes. */
static coons_status number_nodes(vbuild *v, coons_volume_mesh *vm)
{
    memset(v->id, 0xff, v->nraw * sizeof(uint32_t));
    /* Mark every representative some needed point maps to. */
    for (size_t i = 0; i < v->nb; i++) {
        const vbody *B = &v->vb[i];
        for (size_t a = 0; a < B->m[0]; a++)
            for (size_t b = 0; b < B->m[1]; b++)
                for (size_t c = 0; c < B->m[2]; c++)
                    if (coons__vneeded(v, a, b, c)) v->id[v->uf[coons__vraw(B, a, b, c)]] = 0;
    }
    size_t nn = 0;
    for (size_t r = 0; r < v->nraw; r++)
        if (v->id[r] == 0) v->id[r] = (uint32_t)nn++;
    double *xyz = coons__volume_mesh_reserve_nodes(vm, nn, v->err);
    if (!xyz) return COONS_E_NOMEM;
    v->nn = nn;
    static const char *names[4] = {"u", "v", "w", "det_j"};
    double *f[4];
    for (int d = 0; d < 4; d++)
        if (!(f[d] = coons__volume_mesh_reserve_field(vm, COONS_FIELD_NODE, names[d],
                                                      COONS_FIELD_FLOAT64, v->err)))
            return COONS_E_NOMEM;
    coons_status st = COONS_OK;
    for (size_t i = 0; i < v->nb && !st; i++) {
        vbody *B = &v->vb[i];
        node_run nr;
        nr.v = v;
        nr.B = B;
        nr.xyz = xyz;
        for (int d = 0; d < 3; d++) nr.par[d] = f[d];
        nr.det = f[3];
        unsigned runs = v->threads < COONS__MAX_RUNS ? v->threads : COONS__MAX_RUNS;
        size_t k = runs < B->m[0] ? runs : B->m[0];
        const coons_error none = COONS_ERROR_INIT;
        for (size_t c = 0; c < k; c++) nr.err[c] = none;
        coons__parallel_for(B->m[0], runs, node_rows, &nr);
        long sign = 0;
        for (size_t c = 0; c < k && !st; c++) {
            sign += nr.sign[c];
            if ((st = nr.st[c]) && v->err) *v->err = nr.err[c];
        }
        B->left = sign < 0;
    }
    return st;
}

/* The block a cell goes to within its body: 0 hexahedra (with or without
 * repeated nodes), 1 wedges, 2 pyramids, by the one classification the
 * writers and coons_volume_mesh_cell_shape() use (cell_shape.c), so each
 * body's cells of one written type are consecutive. */
static int cell_block(const vbuild *v, const uint32_t *h)
{
    uint32_t out[27];
    coons__cell_shape sh = coons__cell_shape_of(h, v->npc, out);
    return sh == COONS__SHAPE_WEDGE ? 1 : sh == COONS__SHAPE_PYRAMID ? 2 : 0;
}

/* Cells of u layers [a0, a1) of one body, in two passes: the first puts
 * each lattice cell's block (3: dropped) into `no` and counts the blocks
 * per run, the second writes each kept cell's nodes at its place (`at`:
 * the run's next place in each block) and its number into `no`. Placing
 * by the counts of the runs before makes the order the same for any
 * number of runs: by block, and in lattice order within a block. */
typedef struct cell_run {
    const vbuild *v;
    const vbody *B;
    uint32_t *no;  /* the body's lattice cells */
    uint32_t *dst; /* the body's first cell row in the mesh */
    size_t cell0;  /* its number */
    size_t count[COONS__MAX_RUNS][4];
    size_t at[COONS__MAX_RUNS][3];
} cell_run;

static void cell_blocks(void *ctx, unsigned chunk, size_t a0, size_t a1)
{
    cell_run *cr = ctx;
    const vbuild *v = cr->v;
    const vbody *B = cr->B;
    size_t *count = cr->count[chunk];
    count[0] = count[1] = count[2] = count[3] = 0;
    uint32_t row[27];
    for (size_t a = a0; a < a1; a++)
        for (size_t b = 0; b < B->n[1]; b++)
            for (size_t c = 0; c < B->n[2]; c++) {
                /* A cell with no point on the body's boundary is a
                 * hexahedron: only boundary points are ever merged. */
                if (a && b && c && a + 1 < B->n[0] && b + 1 < B->n[1] && c + 1 < B->n[2]) {
                    cr->no[(a * B->n[1] + b) * B->n[2] + c] = 0;
                    count[0]++;
                    continue;
                }
                cell_nodes(v, B, a, b, c, row);
                /* Fewer than 4 distinct corners: no volume at all. */
                int k = distinct_corners(row) >= 4 ? cell_block(v, row) : 3;
                cr->no[(a * B->n[1] + b) * B->n[2] + c] = (uint32_t)k;
                count[k]++;
            }
}

static void cell_place(void *ctx, unsigned chunk, size_t a0, size_t a1)
{
    cell_run *cr = ctx;
    const vbuild *v = cr->v;
    const vbody *B = cr->B;
    size_t *at = cr->at[chunk];
    for (size_t a = a0; a < a1; a++)
        for (size_t b = 0; b < B->n[1]; b++)
            for (size_t c = 0; c < B->n[2]; c++) {
                uint32_t *no = cr->no + (a * B->n[1] + b) * B->n[2] + c;
                if (*no == 3) {
                    *no = UINT32_MAX;
                    continue;
                }
                size_t pos = at[*no]++;
                cell_nodes(v, B, a, b, c, cr->dst + v->npc * pos);
                *no = (uint32_t)(cr->cell0 + pos);
            }
}

/* Adds each body's cells as one part, grouped by block (cell_block()) and
 * in lattice order within a block. cellno[] (lattice order over all
 * bodies) receives each lattice cell's number in the mesh, UINT32_MAX for
 * a cell with fewer than 4 distinct corners (no volume at all: dropped). */
static coons_status add_cells(vbuild *v, coons_volume_mesh *vm, uint32_t **cellno)
{
    size_t total = 0;
    for (size_t i = 0; i < v->nb; i++) total += v->vb[i].n[0] * v->vb[i].n[1] * v->vb[i].n[2];
    uint32_t *no = coons__malloc_array(total ? total : 1, sizeof *no);
    if (!no) return coons__error_nomem(v->err);
    size_t base = 0, cell0 = 0;
    coons_status st = COONS_OK;
    unsigned runs = v->threads < COONS__MAX_RUNS ? v->threads : COONS__MAX_RUNS;
    for (size_t i = 0; i < v->nb && !st; i++) {
        const vbody *B = &v->vb[i];
        size_t nc = B->n[0] * B->n[1] * B->n[2];
        report(v, "cells", (double)base / (double)(total ? total : 1));
        cell_run cr;
        cr.v = v;
        cr.B = B;
        cr.no = no + base;
        size_t k = runs < B->n[0] ? runs : B->n[0];
        coons__parallel_for(B->n[0], runs, cell_blocks, &cr);
        size_t start[3] = {0, 0, 0};
        for (int blk = 0; blk < 3; blk++) {
            if (blk) start[blk] = start[blk - 1];
            for (size_t c = 0; c < k; c++) {
                cr.at[c][blk] = start[blk];
                start[blk] += cr.count[c][blk];
            }
        }
        size_t nk = start[2]; /* the end of block 2 */
        if ((st = coons_volume_mesh_add_part(vm, B->name, NULL, v->err))) break;
        cr.dst = coons__volume_mesh_reserve_cells(vm, nk, i, v->err);
        if (!cr.dst) {
            st = COONS_E_NOMEM;
            break;
        }
        cr.cell0 = cell0;
        coons__parallel_for(B->n[0], runs, cell_place, &cr);
        base += nc;
        cell0 += nk;
    }
    if (st) {
        coons__free(no);
        return st;
    }
    *cellno = no;
    return COONS_OK;
}

/* Scaled Jacobians of cells [lo, hi). */
typedef struct sj_run {
    const coons_volume_mesh *vm;
    double *sj;
} sj_run;

static void sj_cells(void *ctx, unsigned chunk, size_t lo, size_t hi)
{
    (void)chunk;
    sj_run *r = ctx;
    coons__volume_mesh_scaled_jacobians(r->vm, lo, hi, r->sj + lo);
}

/* The cell fields: body (part) and scaled_jacobian. */
static coons_status add_fields(vbuild *v, coons_volume_mesh *vm)
{
    size_t nc = coons_volume_mesh_cell_count(vm);
    int32_t *body = coons__volume_mesh_reserve_field(vm, COONS_FIELD_CELL, "body",
                                                     COONS_FIELD_INT32, v->err);
    if (!body) return COONS_E_NOMEM;
    const uint32_t *part = coons_volume_mesh_cell_parts(vm);
    for (size_t c = 0; c < nc; c++) body[c] = (int32_t)part[c];
    sj_run r = {vm, coons__volume_mesh_reserve_field(vm, COONS_FIELD_CELL, "scaled_jacobian",
                                                     COONS_FIELD_FLOAT64, v->err)};
    if (!r.sj) return COONS_E_NOMEM;
    coons__parallel_for(nc, v->threads, sj_cells, &r);
    return COONS_OK;
}

/* Cell set per body; node and face set per body face. `cellno` is each
 * lattice cell's number in the mesh (add_cells()). */
static coons_status add_sets(vbuild *v, coons_volume_mesh *vm, const uint32_t *cellno)
{
    size_t maxc = 0, maxf = 0;
    for (size_t i = 0; i < v->nb; i++) {
        const vbody *B = &v->vb[i];
        maxc = B->n[0] * B->n[1] * B->n[2] > maxc ? B->n[0] * B->n[1] * B->n[2] : maxc;
        size_t f = B->m[0] * B->m[1] + B->m[1] * B->m[2] + B->m[0] * B->m[2];
        maxf = f > maxf ? f : maxf;
    }
    uint32_t *items = coons__malloc_array(2 * maxc + 2 * maxf + 2, sizeof(uint32_t));
    uint32_t *stamp = coons__malloc_array(v->nn ? v->nn : 1, sizeof(uint32_t));
    if (!items || !stamp) {
        coons__free(items);
        coons__free(stamp);
        return coons__error_nomem(v->err);
    }
    memset(stamp, 0xff, (v->nn ? v->nn : 1) * sizeof(uint32_t));
    uint32_t tag = 0;
    coons_status st = COONS_OK;
    size_t base = 0, cell0 = 0;
    for (size_t i = 0; i < v->nb && !st; i++) {
        const vbody *B = &v->vb[i];
        size_t nc = B->n[0] * B->n[1] * B->n[2];
        /* Kept cell number of each lattice cell of this body. */
        size_t kept = 0;
        for (size_t q = 0; q < nc; q++) kept += cellno[base + q] != UINT32_MAX;
        for (size_t q = 0; q < kept; q++) items[q] = (uint32_t)(cell0 + q);
        st = coons_volume_mesh_add_cell_set(vm, B->name, items, kept, v->err);
        /* A closed body's two faces along a direction that coincide point
         * for point (a tube's seam) are inside it: their sets stay empty. */
        int glued[3];
        for (int ax = 0; ax < 3; ax++) {
            glued[ax] = 1;
            size_t m0 = B->m[(ax + 1) % 3], m1 = B->m[(ax + 2) % 3];
            for (size_t x = 0; x < m0 && glued[ax]; x++)
                for (size_t y = 0; y < m1 && glued[ax]; y++) {
                    size_t p[3], q[3];
                    p[ax] = 0;
                    q[ax] = B->m[ax] - 1;
                    p[(ax + 1) % 3] = q[(ax + 1) % 3] = x;
                    p[(ax + 2) % 3] = q[(ax + 2) % 3] = y;
                    if (!coons__vneeded(v, p[0], p[1], p[2])) continue;
                    glued[ax] = coons__vnode(v, B, p[0], p[1], p[2]) == coons__vnode(v, B, q[0], q[1], q[2]);
                }
        }
        for (int f = 0; f < 6 && !st; f++) {
            int ax = f / 2, hi = f % 2;
            int lf = (B->left && ax == 0) ? 1 - hi : f; /* local face of the cell */
            char name[COONS_VOLUME_NAME_MAX + 1];
            snprintf(name, sizeof name, "%s.%s", B->name, coons_body_face_name(f));
            /* Face set: cells on the face whose local face keeps 3 corners;
             * the quadrangles first, then the triangles (a local face with
             * two neighbouring corners merged), so that a writer's elements
             * of one type are consecutive. */
            size_t np = 0;
            uint32_t row[27];
            /* The layer of cells on the face, in lattice order. */
            size_t lo[3] = {0, 0, 0}, up[3] = {B->n[0], B->n[1], B->n[2]};
            lo[ax] = hi ? B->n[ax] - 1 : 0;
            up[ax] = glued[ax] ? lo[ax] : lo[ax] + 1;
            for (int tri = 0; tri < 2; tri++) {
                for (size_t a = lo[0]; a < up[0]; a++)
                    for (size_t b = lo[1]; b < up[1]; b++)
                        for (size_t c = lo[2]; c < up[2]; c++) {
                            size_t q = (a * B->n[1] + b) * B->n[2] + c;
                            uint32_t cell = cellno[base + q];
                            if (cell == UINT32_MAX) continue;
                            cell_nodes(v, B, a, b, c, row);
                            uint32_t fc[4];
                            for (int z = 0; z < 4; z++) fc[z] = row[FACE_CORNERS[lf][z]];
                            size_t nd = 0;
                            int next = 0; /* neighbouring corners merged */
                            for (int z = 0; z < 4; z++) {
                                int dup = 0;
                                for (int y = 0; y < z; y++) dup |= fc[y] == fc[z];
                                nd += !dup;
                                next |= fc[z] == fc[(z + 1) % 4];
                            }
                            if (nd < 3 || (nd == 3 && next) != tri) continue;
                            items[2 * np] = cell;
                            items[2 * np + 1] = (uint32_t)lf;
                            np++;
                        }
            }
            st = coons_volume_mesh_add_face_set(vm, name, items, np, v->err);
            if (st) break;
            /* Node set: every node on the face, once. */
            tag++;
            size_t nn = 0;
            size_t m0 = B->m[(ax + 1) % 3], m1 = B->m[(ax + 2) % 3];
            for (size_t x = 0; x < m0 && !glued[ax]; x++)
                for (size_t y = 0; y < m1; y++) {
                    size_t p[3];
                    p[ax] = hi ? B->m[ax] - 1 : 0;
                    p[(ax + 1) % 3] = x;
                    p[(ax + 2) % 3] = y;
                    if (!coons__vneeded(v, p[0], p[1], p[2])) continue;
                    uint32_t n = coons__vnode(v, B, p[0], p[1], p[2]);
                    if (n == UINT32_MAX || stamp[n] == tag) continue;
                    stamp[n] = tag;
                    items[nn++] = n;
                }
            st = coons_volume_mesh_add_node_set(vm, name, items, nn, v->err);
        }
        base += nc;
        cell0 += kept;
    }
    coons__free(items);
    coons__free(stamp);
    return st;
}

/* ---- entry points -------------------------------------------------------- */

static coons_status build(vbuild *v, const coons_volume_options *o, double tolerance,
                          coons_volume_mesh **out)
{
    coons_status st = COONS_OK;
    size_t cells = 0;
    for (size_t i = 0; i < v->nb && !st; i++) {
        report(v, "lattice", (double)i / (double)v->nb);
        st = body_lattice(v, &v->vb[i], o, tolerance);
    }
    if (!st) report(v, "lattice", 1.0);
    if (!st) st = coons__vlattice_share(v);
    for (size_t i = 0; i < v->nb && !st; i++) {
        vbody *B = &v->vb[i];
        if ((st = node_lattice(v, B))) break;
        size_t c = B->n[0] * B->n[1] * B->n[2];
        cells += c;
        if (cells > o->max_cells)
            return coons__error_set(v->err, COONS_E_LIMIT,
                                    "the volume mesh would have %zu cells or more (body '%s': "
                                    "%zu x %zu x %zu), above the limit of %zu",
                                    cells, B->name, B->n[0], B->n[1], B->n[2], o->max_cells);
        B->base = v->nraw;
        size_t raw = B->m[0] * B->m[1] * B->m[2];
        if (raw > (size_t)UINT32_MAX - 1 - v->nraw)
            return coons__error_set(v->err, COONS_E_LIMIT,
                                    "the volume mesh would have more than %lu nodes",
                                    (unsigned long)UINT32_MAX - 1);
        v->nraw += raw;
    }
    if (st) return st;
    v->pos = coons__malloc_array(v->nraw, 3 * sizeof(double));
    v->uf = coons__malloc_array(v->nraw, sizeof(uint32_t));
    v->id = coons__malloc_array(v->nraw, sizeof(uint32_t));
    if (!v->pos || !v->uf || !v->id) return coons__error_nomem(v->err);
    if ((st = evaluate(v)) || (st = merge(v))) return st;
    report(v, "evaluate", 1.0);
    coons_volume_mesh *vm;
    if ((st = coons_volume_mesh_new(v->el, &vm, v->err))) return st;
    uint32_t *cellno = NULL;
    st = number_nodes(v, vm);
    report(v, "cells", 0.0);
    if (!st) st = add_cells(v, vm, &cellno);
    if (!st) report(v, "cells", 1.0);
    if (!st) st = add_fields(v, vm);
    if (!st) st = add_sets(v, vm, cellno);
    if (!st) st = coons__vlattice_check(v, vm);
    coons__free(cellno);
    if (st) {
        coons_volume_mesh_free(vm);
        return st;
    }
    *out = vm;
    return COONS_OK;
}

static coons_status run(const coons_body *const *bodies, const char *const *names, size_t nb,
                        const coons_volume_options *opts, double tolerance,
                        coons_volume_mesh **out, coons_error *err)
{
    coons_volume_options o;
    coons_status st = opts_resolve(opts, &o, err);
    if (st) return st;
    if (o.tolerance > 0) tolerance = o.tolerance;
    vbuild v;
    memset(&v, 0, sizeof v);
    v.el = o.element;
    v.npc = (size_t)o.element;
    v.step = o.element == COONS_ELEMENT_HEX8 ? 1 : 2;
    v.err = err;
    v.progress = o.progress;
    v.userdata = o.userdata;
    v.threads = o.threads ? o.threads : 1;
    v.vb = coons__calloc(nb ? nb : 1, sizeof(vbody));
    if (!v.vb) return coons__error_nomem(err);
    v.nb = nb;
    for (size_t i = 0; i < nb; i++) {
        v.vb[i].b = bodies[i];
        v.vb[i].name = names[i];
    }
    st = build(&v, &o, tolerance, out);
    vbuild_free(&v);
    return st;
}

void coons_volume_options_init(coons_volume_options *o)
{
    const coons_volume_options d = COONS_VOLUME_OPTIONS_INIT;
    if (o) *o = d;
}

coons_status coons_body_volume_mesh(const coons_body *b, const coons_volume_options *opts,
                                    const char *name, coons_volume_mesh **out,
                                    coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "no output pointer given");
    *out = NULL;
    if (!b) return coons__error_set(err, COONS_E_INVALID, "no body given");
    double lo[3], hi[3];
    coons_body_control_bbox(b, lo, hi);
    double d = bbox_diag(lo, hi);
    const char *nm = name ? name : "body0";
    return run(&b, &nm, 1, opts, d > 0 ? 1e-3 * d : 1e-3, out, err);
}

coons_status coons_model_volume_mesh(const coons_model *m, const coons_volume_options *opts,
                                     coons_volume_mesh **out, coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "no output pointer given");
    *out = NULL;
    if (!m) return coons__error_set(err, COONS_E_INVALID, "no model given");
    size_t nb = coons_model_body_count(m);
    const coons_body **bodies = coons__malloc_array(nb ? nb : 1, sizeof *bodies);
    const char **names = coons__malloc_array(nb ? nb : 1, sizeof *names);
    coons_status st;
    if (!bodies || !names) {
        st = coons__error_nomem(err);
    } else {
        for (size_t i = 0; i < nb; i++) {
            bodies[i] = coons_model_body(m, i);
            names[i] = coons_model_body_name(m, i);
        }
        st = run(bodies, names, nb, opts, coons_model_tolerance(m), out, err);
    }
    coons__free(bodies);
    coons__free(names);
    return st;
}
