/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The boundary of a control lattice (seed 000 §3: "each cell of the control
 * lattice is defined by six faces ... Each cell defines a Coons body", and
 * neighbouring cells share faces), without a Boolean operation.
 *
 * Bodies joined by shared faces (shared_faces.c) are sampled together:
 *  1. every body runs the adaptive sampler (sample.c) with its shared faces
 *     left out (they lie inside the solid: only their borders, which other
 *     faces hold, are evaluated);
 *  2. the lattices of the directions the shared faces tie together are made
 *     one (lattice_share.c), and every body samples again from that lattice,
 *     refining where its own boundary needs it, until no lattice changes: the
 *     final lattice satisfies every body's tolerance, and a shared face has
 *     the same lattice points from both sides;
 *  3. the lattice points of each shared face are joined by index with the
 *     other body's (in the face pair's orientation), through one union-find
 *     over all bodies' lattice points, so vertices on the border of a shared
 *     face are one vertex, also where three or more bodies meet along an edge
 *     and a point is reached only through a third body's lattice;
 *  4. the bodies' triangles, on those joined vertices, are one part: a closed
 *     shell when the bodies only touch along shared faces, exactly, with no
 *     vertex moved and no CGAL call. Each joined vertex is at the position
 *     the lowest-numbered body evaluated (the two sides agree within the
 *     consistency tolerance by the definition of a shared face).
 * Bodies that also overlap elsewhere make a shell that crosses itself; the
 * repair layer unites it as it unites any folded body, and the shared faces
 * never reach it. */
#include <string.h>

#include "coons_internal.h"
#include "sampling.h"
#include "mesh_impl.h"
#include "sampler.h"
#include "union_find.h"

/* Rounds of "sample, share" before giving up: each round only adds lattice
 * values, so the loop ends; 2 rounds settle every example. */
enum { MAX_SHARE_ROUNDS = 32 };

typedef struct lattice_job {
    size_t nb;
    sampler *s;
    uint32_t *base; /* first global id of each body's raw vertices */
    double **t;     /* 3 nb lattices being shared */
    size_t *n;
    coons_error *err;
} lattice_job;

static void job_free(lattice_job *j)
{
    for (size_t i = 0; j->s && i < j->nb; i++) coons__sampler_free(&j->s[i]);
    for (size_t x = 0; j->t && x < 3 * j->nb; x++) coons__free(j->t[x]);
    coons__free(j->s);
    coons__free(j->base);
    coons__free(j->t);
    coons__free(j->n);
}

/* Copies each sampler's final lattice into j->t (for sharing). */
static coons_status take_lattices(lattice_job *j)
{
    for (size_t i = 0; i < j->nb; i++)
        for (int d = 0; d < 3; d++) {
            size_t x = 3 * i + (size_t)d, n = j->s[i].n[d];
            double *v = coons__malloc_array(n + 1, sizeof(double));
            if (!v) return coons__error_nomem(j->err);
            memcpy(v, j->s[i].t[d], (n + 1) * sizeof(double));
            coons__free(j->t[x]);
            j->t[x] = v;
            j->n[x] = n;
        }
    return COONS_OK;
}

/* Lattice point (ia, ib) of face f0 of body A seen on face f1 of body B:
 * the indices on B's face for the pair's symmetry (mesh_glue.h). */
static void map_point(const coons__shared_face *p, size_t ia, size_t ib, size_t na1, size_t nb1,
                      size_t *ja, size_t *jb)
{
    size_t a = ia, b = ib;
    if (p->sym & COONS__SYM_SWAP) {
        a = ib;
        b = ia;
    }
    if (p->sym & COONS__SYM_FLIP_A) a = na1 - a;
    if (p->sym & COONS__SYM_FLIP_B) b = nb1 - b;
    *ja = a;
    *jb = b;
}

/* Joins the lattice points of every shared face pair in the global
 * union-find; the lattices were shared, so the point counts agree. */
static coons_status join_faces(lattice_job *j, uint32_t *uf, const coons__shared_face *sf,
                               size_t nsf)
{
    for (size_t k = 0; k < nsf; k++) {
        const coons__shared_face *p = &sf[k];
        const sampler *A = &j->s[p->body[0]], *B = &j->s[p->body[1]];
        const face_desc *FA = &coons__faces[p->face[0]], *FB = &coons__faces[p->face[1]];
        size_t na0 = A->n[FA->a], nb0 = A->n[FA->b], na1 = B->n[FB->a], nb1 = B->n[FB->b];
        int swap = (p->sym & COONS__SYM_SWAP) != 0;
        if ((swap ? nb0 : na0) != na1 || (swap ? na0 : nb0) != nb1)
            return coons__error_set(j->err, COONS_E_INTERNAL,
                                    "shared face %s/%s: lattices %zux%zu and %zux%zu differ",
                                    FA->name, FB->name, na0, nb0, na1, nb1);
        for (size_t ia = 0; ia <= na0; ia++)
            for (size_t ib = 0; ib <= nb0; ib++) {
                size_t ja, jb;
                map_point(p, ia, ib, na1, nb1, &ja, &jb);
                uint32_t ga = j->base[p->body[0]] + coons__sampler_id(A, p->face[0], ia, ib);
                uint32_t gb = j->base[p->body[1]] + coons__sampler_id(B, p->face[1], ja, jb);
                coons__uf_union(uf, ga, gb);
            }
    }
    return COONS_OK;
}

/* The joined shell as one part of `mesh`. */
static coons_status emit_joined(lattice_job *j, const coons__shared_face *sf, size_t nsf,
                                const char *name, double tolerance, coons_mesh *mesh,
                                size_t *triangles)
{
    size_t total = 0, nt = 0;
    for (size_t i = 0; i < j->nb; i++) {
        if (total + j->s[i].nv > UINT32_MAX)
            return coons__error_set(j->err, COONS_E_LIMIT,
                                    "the bodies joined with '%s' have more than %u vertices",
                                    j->s[0].name, (unsigned)UINT32_MAX);
        j->base[i] = (uint32_t)total;
        total += j->s[i].nv;
        nt += j->s[i].nt;
    }
    uint32_t *uf = coons__malloc_array(total ? total : 1, sizeof(uint32_t));
    uint32_t *rep = coons__malloc_array(total ? total : 1, sizeof(uint32_t));
    uint32_t *repb = coons__malloc_array(total ? total : 1, sizeof(uint32_t));
    uint32_t *map = coons__malloc_array(total ? total : 1, sizeof(uint32_t));
    uint32_t *tri = coons__malloc_array(nt ? nt : 1, 3 * sizeof(uint32_t));
    double *xyz = coons__malloc_array(total ? total : 1, 3 * sizeof(double));
    coons_status st = COONS_OK;
    if (!uf || !rep || !repb || !map || !tri || !xyz) {
        st = coons__error_nomem(j->err);
        goto done;
    }
    /* Each body's own merges (collapsed edges, closed directions). */
    for (size_t i = 0; i < j->nb; i++) {
        sampler *S = &j->s[i];
        for (uint32_t r = 0; r < (uint32_t)S->nv; r++)
            uf[j->base[i] + r] = j->base[i] + coons__uf_find(S->uf, r);
    }
    if ((st = join_faces(j, uf, sf, nsf))) goto done;
    /* The position of a class: its lowest evaluated member's. */
    memset(rep, 0xff, total * sizeof(uint32_t));
    for (size_t i = 0; i < j->nb; i++) {
        const sampler *S = &j->s[i];
        for (uint32_t r = 0; r < (uint32_t)S->nv; r++) {
            uint32_t g = j->base[i] + r, root = coons__uf_find(uf, g);
            if (rep[root] == UINT32_MAX && S->evaluated[r]) {
                rep[root] = r;
                repb[root] = (uint32_t)i;
            }
        }
    }
    memset(map, 0xff, total * sizeof(uint32_t));
    uint32_t nv = 0;
    size_t kept = 0;
    for (size_t i = 0; i < j->nb; i++) {
        const sampler *S = &j->s[i];
        for (size_t t = 0; t < S->nt; t++) {
            uint32_t v[3];
            for (int c = 0; c < 3; c++) {
                uint32_t root = coons__uf_find(uf, j->base[i] + S->tri[3 * t + (size_t)c]);
                if (map[root] == UINT32_MAX) {
                    uint32_t r = rep[root];
                    if (r == UINT32_MAX) {
                        st = coons__error_set(j->err, COONS_E_INTERNAL,
                                              "body '%s': a vertex of the joined shell was "
                                              "never evaluated",
                                              S->name);
                        goto done;
                    }
                    coons__sampler_unscaled(&j->s[repb[root]], r, xyz + 3 * (size_t)nv);
                    map[root] = nv++;
                }
                v[c] = map[root];
            }
            if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue; /* collapsed */
            memcpy(tri + 3 * kept, v, sizeof v);
            kept++;
        }
    }
    if (!kept) {
        st = coons__error_set(j->err, COONS_E_INVALID,
                              "the bodies joined with '%s' by shared faces have no boundary: "
                              "every face is shared",
                              j->s[0].name);
        goto done;
    }
    size_t part = mesh->nparts;
    st = coons__mesh_add_part_uvw(mesh, name, xyz, NULL, nv, tri, kept, j->err);
    if (!st) {
        coons__mesh_part *P = &mesh->parts[part];
        P->tolerance = tolerance;
        P->sampled = 1;
        double dev = 0;
        int measured = 1;
        for (size_t i = 0; i < j->nb; i++) {
            if (!j->s[i].measured) measured = 0;
            if (j->s[i].dev / j->s[i].scale > dev) dev = j->s[i].dev / j->s[i].scale;
        }
        P->deviation = measured ? dev : NAN;
        /* The lattice of the first body (a part made of several bodies has
         * no single lattice; --info reports each body's). */
        for (int d = 0; d < 3; d++) P->lattice[d] = j->s[0].n[d];
        P->glued = 0;
        if (triangles) *triangles = kept;
    }
done:
    coons__free(uf);
    coons__free(rep);
    coons__free(repb);
    coons__free(map);
    coons__free(tri);
    coons__free(xyz);
    return st;
}

coons_status coons__lattice_sample_into(const coons_body *const *bodies,
                                        const char *const *names, size_t nb,
                                        const coons__shared_face *sf, size_t nsf,
                                        const coons__sample_opts *o, const char *name,
                                        coons_mesh *mesh, size_t *triangles,
                                        coons_error *err)
{
    lattice_job j;
    memset(&j, 0, sizeof j);
    j.nb = nb;
    j.err = err;
    j.s = coons__calloc(nb, sizeof *j.s);
    j.base = coons__calloc(nb, sizeof *j.base);
    j.t = coons__calloc(3 * nb, sizeof *j.t);
    j.n = coons__calloc(3 * nb, sizeof *j.n);
    coons_status st = COONS_OK;
    if (!j.s || !j.base || !j.t || !j.n) {
        job_free(&j);
        return coons__error_nomem(err);
    }
    for (size_t i = 0; i < nb; i++) coons__sampler_init(&j.s[i], bodies[i], o, names[i], err);
    for (size_t k = 0; k < nsf; k++)
        for (int e = 0; e < 2; e++) j.s[sf[k].body[e]].skip |= 1u << sf[k].face[e];
    int settled = 0;
    for (int round = 0; round < MAX_SHARE_ROUNDS && !st && !settled; round++) {
        size_t used = 0;
        for (size_t i = 0; i < nb && !st; i++) {
            if (round > 0)
                for (int d = 0; d < 3; d++) {
                    j.s[i].start_t[d] = j.t[3 * i + (size_t)d];
                    j.s[i].start_n[d] = j.n[3 * i + (size_t)d];
                }
            st = coons__sampler_run(&j.s[i]);
            if (!st) used += j.s[i].nt;
        }
        if (!st && used > o->max_triangles)
            st = coons__error_set(err, COONS_E_LIMIT,
                                  "the %zu bodies joined with '%s' by shared faces need %zu "
                                  "triangles, more than the limit of %zu; raise max_triangles "
                                  "(coons2stl --max-triangles N) or loosen the tolerance",
                                  nb, j.s[0].name, used, o->max_triangles);
        if (st) break;
        int changed = 0;
        if ((st = take_lattices(&j))) break;
        if ((st = coons__share_lattices(nb, j.t, j.n, sf, nsf, &changed, err))) break;
        settled = !changed;
    }
    if (!st && !settled)
        st = coons__error_set(err, COONS_E_LIMIT,
                              "the bodies joined with '%s' by shared faces: their lattices did "
                              "not settle in %d rounds",
                              j.s[0].name, MAX_SHARE_ROUNDS);
    if (!st) st = emit_joined(&j, sf, nsf, name, o->tolerance, mesh, triangles);
    job_free(&j);
    return st;
}
