/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * One lattice and one face list for a morph's whole path (seed 000
 * section 4, Fig. 10; outputs.md "Metamorphosis"): what every output of a
 * morph uses, so that -o at the file's t, --time T, frame k of --frames and
 * OpenSCAD's $t of the animation (src/io/write/scad_morph.c) are one mesh.
 *
 * The lattice: uniform, n intervals along u, v and w (the sampler's fixed
 * lattice, which does not depend on the time): with a resolution that
 * one; else the smallest n, from the largest adaptive lattice count at the
 * check times up in steps of 1/4, whose mesh (the fixed face list with each
 * frame's vertices) is within the tolerance at every check time: the key
 * times, and 4 times inside each interval between keys, measured at 7
 * points of every triangle (edge midpoints, centroid, and the points
 * halfway between the centroid and the corners) against that triangle. The
 * face list: the sampler's at the middle time 1/2; vertices merge only
 * where they merge at every key time and at 1/2 (the vertex counts agree),
 * else no one face list serves every frame and the plan is refused.
 *
 * A frame's vertex is the body at that time at the vertex's parameters, by
 * the body grid evaluator at each vertex alone: bitwise what any grid
 * through that point gives (body.h), so what the sampler's uniform lattice
 * gives at that time, and what the animation's blend of the keys' arrays
 * (the tree below, evaluated the same way) gives in OpenSCAD.
 */
#include "morph_lattice.h"

#include "body_impl.h"
#include "mesh_impl.h"

#include <math.h>
#include <string.h>

#define REF_TIME 0.5
#define CHECKS_PER_INTERVAL 4

int coons__body_has_morph(const coons_body *b)
{
    for (; b; b = b->inner)
        if (b->kind == &coons__morph_kind) return 1;
    return 0;
}

void coons__morph_lattice_free(coons__morph_lattice *L)
{
    coons__free(L->tri);
    coons__free(L->uvw);
    for (size_t i = 0; i < L->nn; i++) {
        coons__free(L->nodes[i].pts);
        coons__free(L->nodes[i].keys);
    }
    coons__free(L->nodes);
    memset(L, 0, sizeof *L);
}

/* ---- the lattice and the face list ------------------------------------- */

/* Samples b on the uniform lattice of n intervals: one part with vertex
 * parameters into a new mesh. */
static coons_status sample_fixed(const coons_body *b, const coons__sample_opts *o, unsigned n,
                                 const char *name, coons_mesh **out, coons_error *err)
{
    coons__sample_opts f = *o;
    f.resolution = n;
    f.flags |= COONS_SAMPLE_UNMEASURED | COONS__SAMPLE_PARAMS;
    coons_status st = coons_mesh_new(out, err);
    if (st) return st;
    size_t used = 0;
    st = coons__body_sample_into(b, &f, name, *out, &used, err);
    if (st) {
        coons_mesh_free(*out);
        *out = NULL;
    }
    return st;
}

static coons_status sample_at(const coons_body *b, double t, const coons__sample_opts *o,
                              unsigned n, const char *name, coons_mesh **out, coons_error *err)
{
    coons_body *c = NULL;
    coons_status st = coons_body_at_time(b, t, &c, err);
    if (!st) st = sample_fixed(c, o, n, name, out, err);
    coons_body_free(c);
    return st;
}

/* The check times: keys, and CHECKS_PER_INTERVAL inside each interval. */
static size_t check_times(const coons_body *m, double *t, size_t cap)
{
    size_t n = 0, nk = m->nkeys;
    for (size_t k = 0; k < nk && n < cap; k++) {
        double a = 0, b = 0;
        coons_body_morph_key(m, k, &a);
        t[n++] = a;
        if (k + 1 == nk) break;
        coons_body_morph_key(m, k + 1, &b);
        for (int j = 1; j <= CHECKS_PER_INTERVAL && n < cap; j++)
            t[n++] = a + (b - a) * j / (CHECKS_PER_INTERVAL + 1);
    }
    return n;
}

/* The 7 points of a triangle at which it is measured, as barycentric
 * weights in sixths: edge midpoints, centroid, halfway from the centroid
 * to each corner. */
static const int SIXTHS[7][3] = {{3, 3, 0}, {0, 3, 3}, {3, 0, 3}, {2, 2, 2},
                                 {4, 1, 1}, {1, 4, 1}, {1, 1, 4}};

/* Largest squared distance of the points x[7] from triangle P. */
static double tri_worst(double P[3][3], double x[7][3])
{
    double worst = 0;
    for (int s = 0; s < 7; s++) worst = fmax(worst, coons__tri_dist2(x[s], P[0], P[1], P[2]));
    return worst;
}

/* The face (u0 u1 v0 v1 w0 w1: 0 .. 5) of the lattice that holds the
 * corners v of a triangle, with their integer lattice coordinates k; -1
 * when they are not lattice points of one face. */
static int lattice_face(const coons__morph_lattice *p, const uint32_t *v, long k[3][3])
{
    for (int c = 0; c < 3; c++)
        for (int d = 0; d < 3; d++) {
            double x = p->uvw[3 * (size_t)v[c] + (size_t)d] * p->n, r = nearbyint(x);
            if (!(fabs(x - r) <= 1e-6)) return -1;
            k[c][d] = (long)r;
        }
    for (int d = 0; d < 3; d++)
        for (int side = 0; side < 2; side++) {
            long at = side ? (long)p->n : 0;
            if (k[0][d] == at && k[1][d] == at && k[2][d] == at) return 2 * d + side;
        }
    return -1;
}

/* Grid points per face beyond which the face grids are not used. */
#define FACE_GRID_MAX ((size_t)1 << 22)

/* *out: the largest distance of the exact boundary of b from the fixed face
 * list with b's vertices, at 7 points per triangle. The points of a
 * triangle on a face of the uniform lattice n lie on the face's grid of 6n
 * intervals, evaluated at once by the body grid evaluator (a face at a
 * time); other triangles (vertices merged across faces) point by point. */
static coons_status deviation(const coons_body *b, const coons__morph_lattice *p, double *out,
                              coons_error *err)
{
    size_t G = 6 * (size_t)p->n, ng = G + 1;
    int grids = ng * ng <= FACE_GRID_MAX;
    double *par = grids ? coons__malloc_array(ng, sizeof *par) : NULL;
    double *pts = grids ? coons__malloc_array(ng * ng, 3 * sizeof *pts) : NULL;
    if (grids && (!par || !pts)) {
        coons__free(par);
        coons__free(pts);
        return coons__error_nomem(err);
    }
    for (size_t i = 0; grids && i < ng; i++) par[i] = (double)i / (double)G;
    /* Measured at a power of two near 1 / the body's size (exact: the same
     * figure at every scale), as the sampler does: the distance's products
     * of four coordinates overflowed at 1e100 (and underflowed at 1e-100),
     * so a scaled morph refined without end. */
    double lo[3], hi[3], ext = 0;
    coons_body_control_bbox(b, lo, hi);
    for (int d = 0; d < 3; d++) ext = fmax(ext, hi[d] - lo[d]);
    const double scale = ext > 0 && isfinite(ext) ? ldexp(1.0, -ilogb(ext)) : 1.0;
    double worst = 0;
    coons_status st = COONS_OK;
    for (int f = grids ? 0 : 6; f <= 6 && !st; f++) {
        int fixed = f / 2, a = fixed ? 0 : 1, bb = fixed == 2 ? 1 : 2;
        const double side = f % 2 ? 1.0 : 0.0;
        if (f < 6) {
            const double *axis[3] = {par, par, par};
            size_t cnt[3] = {ng, ng, ng};
            axis[fixed] = &side;
            cnt[fixed] = 1;
            st = coons_body_eval_grid(b, axis[0], cnt[0], axis[1], cnt[1], axis[2], cnt[2], pts,
                                      err);
        }
        for (size_t t = 0; t < p->nt && !st; t++) {
            const uint32_t *v = p->tri + 3 * t;
            long k[3][3];
            int on = grids ? lattice_face(p, v, k) : -1;
            if (on != (f < 6 ? f : -1)) continue;
            double P[3][3], x[7][3];
            if (f < 6) {
                for (int c = 0; c < 3; c++)
                    v3_copy(P[c], pts + 3 * ((size_t)(6 * k[c][a]) * ng + (size_t)(6 * k[c][bb])));
                for (int s = 0; s < 7; s++) {
                    long ia = 0, ib = 0;
                    for (int c = 0; c < 3; c++) {
                        ia += SIXTHS[s][c] * k[c][a];
                        ib += SIXTHS[s][c] * k[c][bb];
                    }
                    v3_copy(x[s], pts + 3 * ((size_t)ia * ng + (size_t)ib));
                }
            } else {
                for (int c = 0; c < 3; c++) {
                    const double *q = p->uvw + 3 * (size_t)v[c];
                    coons_body_eval(b, q[0], q[1], q[2], P[c]);
                }
                for (int s = 0; s < 7; s++) {
                    double q[3];
                    for (int d = 0; d < 3; d++) {
                        q[d] = 0;
                        for (int c = 0; c < 3; c++)
                            q[d] += SIXTHS[s][c] / 6.0 * p->uvw[3 * (size_t)v[c] + (size_t)d];
                    }
                    coons_body_eval(b, q[0], q[1], q[2], x[s]);
                }
            }
            for (int c = 0; c < 3; c++) v3_scale(P[c], P[c], scale);
            for (int q = 0; q < 7; q++) v3_scale(x[q], x[q], scale);
            worst = fmax(worst, tri_worst(P, x));
        }
    }
    coons__free(par);
    coons__free(pts);
    *out = sqrt(worst) / scale;
    return st;
}

/* Takes the face list and vertex parameters of mesh part 0. */
static coons_status take_faces(coons__morph_lattice *p, const coons_mesh *mesh, coons_error *err)
{
    coons__free(p->tri);
    coons__free(p->uvw);
    p->nv = coons_mesh_vertex_count(mesh);
    p->nt = coons_mesh_triangle_count(mesh);
    p->tri = coons__malloc_array(p->nt, 3 * sizeof *p->tri);
    p->uvw = coons__malloc_array(p->nv, 3 * sizeof *p->uvw);
    if (!p->tri || !p->uvw) return coons__error_nomem(err);
    memcpy(p->tri, coons_mesh_triangles(mesh), p->nt * 3 * sizeof *p->tri);
    memcpy(p->uvw, coons_mesh_vertex_parameters(mesh), p->nv * 3 * sizeof *p->uvw);
    p->glued = mesh->nparts ? mesh->parts[0].glued : 0;
    return COONS_OK;
}

static coons_status faces_on_lattice(const coons_body *b, const coons_body *m,
                                     const coons__sample_opts *o, const char *name,
                                     const double *times, size_t nt, coons__morph_lattice *p,
                                     coons_error *err)
{
    coons_status st = COONS_OK;
    unsigned n = o->resolution;
    if (!n) { /* the largest adaptive lattice count at the check times */
        coons__sample_opts a = *o;
        a.resolution = 0;
        for (size_t i = 0; i < nt && !st; i++) {
            coons_body *c = NULL;
            double *t3[3] = {NULL, NULL, NULL};
            size_t n3[3];
            st = coons_body_at_time(b, times[i], &c, err);
            if (!st) st = coons__body_sample_lattice(c, &a, name, t3, n3, NULL, err);
            for (int d = 0; d < 3; d++) {
                if (!st && n3[d] > n) n = (unsigned)n3[d];
                coons__free(t3[d]);
            }
            coons_body_free(c);
        }
        if (st) return st;
    }
    for (;;) {
        coons_mesh *ref = NULL;
        st = sample_at(b, REF_TIME, o, n, name, &ref, err);
        if (!st) st = take_faces(p, ref, err);
        coons_mesh_free(ref);
        if (st) return st;
        p->n = n;
        if (p->nt > o->max_triangles)
            return coons__error_set(err, COONS_E_LIMIT,
                                    "body '%s': the lattice of %u intervals of the morph's "
                                    "whole path needs more than %zu triangles (the limit)",
                                    name, n, o->max_triangles);
        /* vertices merge the same way at every key time */
        for (size_t k = 0; k < m->nkeys && !st; k++) {
            double at = 0;
            coons_body_morph_key(m, k, &at);
            coons_mesh *km = NULL;
            st = sample_at(b, at, o, n, name, &km, err);
            if (!st && coons_mesh_vertex_count(km) != p->nv)
                st = coons__error_set(err, COONS_E_UNSUPPORTED,
                                      "body '%s': its lattice collapses differently at key time "
                                      "%g (%zu vertices, %zu at time %g), so no one face list "
                                      "serves every frame; write frames with --frames instead",
                                      name, at, coons_mesh_vertex_count(km), p->nv, REF_TIME);
            coons_mesh_free(km);
        }
        if (st) return st;
        if (o->resolution) return COONS_OK;
        double worst = 0;
        for (size_t i = 0; i < nt && !st; i++) {
            coons_body *c = NULL;
            st = coons_body_at_time(b, times[i], &c, err);
            double dev = 0;
            if (!st) st = deviation(c, p, &dev, err);
            worst = fmax(worst, dev);
            coons_body_free(c);
        }
        if (st) return st;
        p->deviation = worst;
        if (worst <= o->tolerance) return COONS_OK;
        n += n / 4 > 0 ? n / 4 : 1;
    }
}

coons_status coons__morph_lattice_plan(const coons_body *b, const coons__sample_opts *o,
                                       const char *name, coons__morph_lattice *p,
                                       coons_error *err)
{
    memset(p, 0, sizeof *p);
    p->deviation = NAN;
    const coons_body *m = b;
    while (m->kind != &coons__morph_kind) m = m->inner;
    size_t cap = m->nkeys * (CHECKS_PER_INTERVAL + 1);
    double *times = coons__malloc_array(cap, sizeof *times);
    if (!times) return coons__error_nomem(err);
    size_t nt = check_times(m, times, cap);
    coons_status st = faces_on_lattice(b, m, o, name, times, nt, p, err);
    coons__free(times);
    if (st) coons__morph_lattice_free(p);
    return st;
}

/* ---- the vertex arrays of the tree ------------------------------------ */

static coons_status add_node(coons__morph_lattice *p, coons__morph_node nd, size_t *index,
                             coons_error *err)
{
    if (p->nn == p->cap) {
        size_t cap = p->cap ? 2 * p->cap : 8;
        coons__morph_node *q = coons__realloc(p->nodes, cap * sizeof *q);
        if (!q) {
            coons__free(nd.pts);
            coons__free(nd.keys);
            return coons__error_nomem(err);
        }
        p->nodes = q;
        p->cap = cap;
    }
    p->nodes[p->nn] = nd;
    *index = p->nn++;
    return COONS_OK;
}

/* The node of b (and its subtree); *index receives it. */
static coons_status build_node(coons__morph_lattice *p, const coons_body *b, size_t *index,
                               coons_error *err)
{
    coons__morph_node nd = {COONS__MORPH_CONST, b, NULL, 0, NULL};
    coons_status st = COONS_OK;
    if (!coons__body_has_morph(b)) {
        if (!(nd.pts = coons__malloc_array(p->nv, 3 * sizeof *nd.pts)))
            return coons__error_nomem(err);
        for (size_t v = 0; v < p->nv && !st; v++) {
            const double *q = p->uvw + 3 * v;
            st = coons_body_eval_grid(b, q, 1, q + 1, 1, q + 2, 1, nd.pts + 3 * v, err);
        }
        if (st) {
            coons__free(nd.pts);
            return st;
        }
        return add_node(p, nd, index, err);
    }
    if (b->kind != &coons__morph_kind) { /* an affine wrapper */
        nd.kind = COONS__MORPH_AFFINE;
        if ((st = build_node(p, b->inner, &nd.inner, err))) return st;
        return add_node(p, nd, index, err);
    }
    nd.kind = COONS__MORPH_BLEND;
    size_t *keys = coons__malloc_array(b->nkeys, sizeof *keys);
    if (!keys) return coons__error_nomem(err);
    for (size_t k = 0; k < b->nkeys && !st; k++) st = build_node(p, b->keys[k], &keys[k], err);
    if (st) {
        coons__free(keys);
        return st;
    }
    nd.keys = keys;
    return add_node(p, nd, index, err);
}

coons_status coons__morph_lattice_tree(coons__morph_lattice *L, const coons_body *b,
                                       coons_error *err)
{
    size_t root = 0;
    return build_node(L, b, &root, err);
}

/* ---- a frame ------------------------------------------------------------- */

coons_status coons__body_sample_path(const coons_body *b, const coons__sample_opts *o,
                                     const char *name, coons_mesh *mesh, size_t *triangles,
                                     coons_error *err)
{
    if (!coons__body_has_morph(b)) return coons__body_sample_into(b, o, name, mesh, triangles, err);
    coons__morph_lattice L;
    coons_status st = coons__morph_lattice_plan(b, o, name, &L, err);
    /* a morph whose lattice collapses differently at different times, or
     * whose boundary collapses entirely at a time the plan samples (keys of
     * opposite handedness at t = 1/2), has no one mesh: each frame is
     * sampled on its own */
    if (st == COONS_E_UNSUPPORTED || st == COONS_E_INVALID)
        return coons__body_sample_into(b, o, name, mesh, triangles, err);
    if (st) return st;
    double *xyz = coons__malloc_array(L.nv ? L.nv : 1, 3 * sizeof *xyz);
    if (!xyz) st = coons__error_nomem(err);
    for (size_t v = 0; v < L.nv && !st; v++) {
        const double *q = L.uvw + 3 * v;
        st = coons_body_eval_grid(b, q, 1, q + 1, 1, q + 2, 1, xyz + 3 * v, err);
    }
    size_t part = mesh->nparts;
    if (!st)
        st = coons__mesh_add_part_uvw(mesh, name ? name : "body", xyz,
                                      o->flags & COONS__SAMPLE_PARAMS ? L.uvw : NULL, L.nv, L.tri,
                                      L.nt, err);
    if (!st) {
        coons__mesh_part *P = &mesh->parts[part];
        P->tolerance = o->tolerance;
        P->sampled = 1;
        /* the worst over the path's check times; a given lattice is
         * measured at this frame unless the caller asked not to */
        P->deviation = L.deviation;
        if (o->resolution && !(o->flags & COONS_SAMPLE_UNMEASURED))
            st = deviation(b, &L, &P->deviation, err);
        for (int d = 0; d < 3; d++) P->lattice[d] = L.n;
        P->glued = L.glued;
        if (triangles) *triangles = L.nt;
    }
    coons__free(xyz);
    coons__morph_lattice_free(&L);
    return st;
}
