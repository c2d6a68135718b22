/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Combinatorial checks of a triangle mesh from its index arrays: edge use
 * (boundary, non-manifold, misoriented), vertex links (one fan each), shells
 * and the Euler characteristic. Nothing is welded by position: a mesh is
 * closed here only if its triangles share vertex indices, which is what the
 * sampler guarantees by construction. Plain C so that the core can check
 * meshes without OpenMesh; openmesh.cpp adds the halfedge-mesh view. */
#include <stdlib.h>
#include <string.h>

#include "coons_internal.h"
#include "mesh_glue.h"
#include "mesh_impl.h"
#include "union_find.h"

typedef struct edge_rec {
    uint32_t lo, hi; /* undirected key */
    uint32_t fwd;    /* 1 when the triangle runs lo -> hi */
} edge_rec;

static int cmp_edge(const void *x, const void *y)
{
    const edge_rec *a = x, *b = y;
    if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    return 0;
}

static int cmp_u32(const void *x, const void *y)
{
    uint32_t a = *(const uint32_t *)x, b = *(const uint32_t *)y;
    return a < b ? -1 : (a > b);
}

static int degenerate(const uint32_t *t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

/* Is the link of a vertex (the opposite edges of its triangles) one path or
 * one cycle? link holds 2k endpoints; scratch holds 4k + 1 uint32_t. */
static int link_is_fan(const uint32_t *link, size_t k, uint32_t *scratch)
{
    uint32_t *nodes = scratch, *uf = scratch + 2 * k;
    memcpy(nodes, link, 2 * k * sizeof *nodes);
    qsort(nodes, 2 * k, sizeof *nodes, cmp_u32);
    size_t nn = 0, ends = 0;
    for (size_t i = 0; i < 2 * k;) {
        size_t j = i;
        while (j < 2 * k && nodes[j] == nodes[i]) j++;
        size_t deg = j - i;
        if (deg > 2) return 0;
        ends += deg == 1;
        nodes[nn++] = nodes[i];
        i = j;
    }
    if (ends != 0 && ends != 2) return 0;
    for (uint32_t i = 0; i < nn; i++) uf[i] = i;
    for (size_t e = 0; e < k; e++) {
        uint32_t *a = bsearch(&link[2 * e], nodes, nn, sizeof *nodes, cmp_u32);
        uint32_t *b = bsearch(&link[2 * e + 1], nodes, nn, sizeof *nodes, cmp_u32);
        coons__uf_union(uf, (uint32_t)(a - nodes), (uint32_t)(b - nodes));
    }
    for (uint32_t i = 1; i < nn; i++)
        if (coons__uf_find(uf, i) != coons__uf_find(uf, 0)) return 0;
    return 1;
}

/* Edges of the non-degenerate triangles into e (3 per triangle), sorted
 * by undirected key, counted by use; degenerate triangles are counted and
 * skipped. Returns the number of non-degenerate triangles. */
static size_t count_edges(const coons_mesh *m, edge_rec *e, coons_mesh_report *r)
{
    size_t ne = 0, nf = 0;
    for (size_t t = 0; t < m->nt; t++) {
        const uint32_t *v = m->tri + 3 * t;
        if (degenerate(v)) {
            r->degenerate_triangles++;
            continue;
        }
        nf++;
        for (int k = 0; k < 3; k++) {
            uint32_t a = v[k], b = v[(k + 1) % 3];
            e[ne].lo = a < b ? a : b;
            e[ne].hi = a < b ? b : a;
            e[ne].fwd = a < b;
            ne++;
        }
    }
    qsort(e, ne, sizeof *e, cmp_edge);
    for (size_t i = 0; i < ne;) {
        size_t j = i, fwd = 0;
        while (j < ne && !cmp_edge(&e[j], &e[i])) fwd += e[j++].fwd;
        size_t c = j - i;
        r->edges++;
        if (c == 1)
            r->boundary_edges++;
        else if (c > 2)
            r->nonmanifold_edges++;
        else if (fwd != 1)
            r->misoriented_edges++;
        i = j;
    }
    return nf;
}

/* Incidence lists (CSR): the triangles of vertex i are inc[first[i] ..
 * first[i+1]-1]. first holds nv + 1 zeros on entry. *maxdeg gets the
 * largest count. */
static coons_status incidence(const coons_mesh *m, size_t *first, uint32_t *inc,
                              size_t *maxdeg, coons_error *err)
{
    size_t nv = m->nv, nt = m->nt;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) first[m->tri[3 * t + k] + 1]++;
    *maxdeg = 0;
    for (size_t i = 0; i < nv; i++) {
        if (first[i + 1] > *maxdeg) *maxdeg = first[i + 1];
        first[i + 1] += first[i];
    }
    size_t *fill = coons__malloc_array(nv ? nv : 1, sizeof *fill);
    if (!fill) return coons__error_nomem(err);
    memcpy(fill, first, nv * sizeof *fill);
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) inc[fill[m->tri[3 * t + k]]++] = (uint32_t)t;
    coons__free(fill);
    return COONS_OK;
}

/* Per used vertex: its link is one fan? Joins each vertex with its
 * neighbours in uf (shells). link and scratch hold 2 maxdeg and
 * 4 maxdeg + 1 values. */
static void check_links(const coons_mesh *m, const size_t *first, const uint32_t *inc,
                        uint32_t *uf, uint32_t *link, uint32_t *scratch, coons_mesh_report *r)
{
    for (size_t vi = 0; vi < m->nv; vi++) {
        size_t k = 0;
        for (size_t p = first[vi]; p < first[vi + 1]; p++) {
            const uint32_t *v = m->tri + 3 * (size_t)inc[p];
            if (degenerate(v)) continue;
            int at = v[0] == vi ? 0 : (v[1] == vi ? 1 : 2);
            link[2 * k] = v[(at + 1) % 3];
            link[2 * k + 1] = v[(at + 2) % 3];
            coons__uf_union(uf, (uint32_t)vi, v[(at + 1) % 3]);
            coons__uf_union(uf, (uint32_t)vi, v[(at + 2) % 3]);
            k++;
        }
        if (first[vi + 1] == first[vi]) {
            r->unused_vertices++;
            continue;
        }
        r->vertices++;
        if (k && !link_is_fan(link, k, scratch)) r->nonmanifold_vertices++;
    }
}

/* Is used vertex vi the root of its shell? */
static int shell_root(const size_t *first, uint32_t *uf, size_t vi)
{
    return first[vi + 1] > first[vi] && coons__uf_find(uf, (uint32_t)vi) == vi;
}

/* Shells, and the expected Euler characteristic, part by part: a sampled
 * body's boundary is a sphere, or tori once opposite faces were glued;
 * anything else is assumed to be spheres, one per shell. */
static void count_shells(const coons_mesh *m, const size_t *first, uint32_t *uf,
                         coons_mesh_report *r)
{
    for (size_t vi = 0; vi < m->nv; vi++)
        if (shell_root(first, uf, vi)) r->shells++;
    for (size_t p = 0; p < m->nparts; p++) {
        const coons__mesh_part *P = &m->parts[p];
        if (P->sampled) {
            r->expected_euler += P->glued ? 0 : 2;
            continue;
        }
        for (size_t vi = P->vert_first; vi < P->vert_first + P->vert_count; vi++)
            if (shell_root(first, uf, vi)) r->expected_euler += 2;
    }
}

coons_status coons__mesh_check_c(const coons_mesh *m, coons_mesh_report *r, coons_error *err)
{
    if (COONS__RECORD_CHECK(err, "mesh report", r->version, COONS_MESH_REPORT)) return COONS_E_INVALID;
    coons_mesh_report z = COONS_MESH_REPORT_INIT;
    *r = z;
    size_t nv = m->nv, nt = m->nt;
    r->triangles = nt;
    r->volume = coons_mesh_volume(m);
    r->area = coons_mesh_area(m);

    edge_rec *e = coons__malloc_array(nt, 3 * sizeof *e);
    uint32_t *uf = coons__malloc_array(nv ? nv : 1, sizeof *uf);
    size_t *first = coons__calloc(nv + 1, sizeof *first);
    uint32_t *inc = coons__malloc_array(nt ? nt : 1, 3 * sizeof *inc);
    uint32_t *link = NULL, *scratch = NULL;
    size_t nf = 0, maxdeg = 0;
    coons_status st = COONS_OK;
    if (!e || !uf || !first || !inc) {
        st = coons__error_nomem(err);
        goto done;
    }
    nf = count_edges(m, e, r);
    for (uint32_t i = 0; i < nv; i++) uf[i] = i;
    if ((st = incidence(m, first, inc, &maxdeg, err))) goto done;
    link = coons__malloc_array(maxdeg ? maxdeg : 1, 2 * sizeof *link);
    scratch = coons__malloc_array(4 * maxdeg + 1, sizeof *scratch);
    if (!link || !scratch) {
        st = coons__error_nomem(err);
        goto done;
    }
    check_links(m, first, inc, uf, link, scratch, r);
    count_shells(m, first, uf, r);

    r->euler = (long)r->vertices - (long)r->edges + (long)nf;
    r->closed = nt > 0 && r->boundary_edges == 0 && r->nonmanifold_edges == 0;
    r->manifold = r->nonmanifold_edges == 0 && r->nonmanifold_vertices == 0 &&
                  r->degenerate_triangles == 0;
    r->oriented = r->misoriented_edges == 0;
done:
    coons__free(e);
    coons__free(uf);
    coons__free(first);
    coons__free(inc);
    coons__free(link);
    coons__free(scratch);
    return st;
}

void coons_mesh_report_init(coons_mesh_report *r)
{
    const coons_mesh_report d = COONS_MESH_REPORT_INIT;
    if (r) *r = d;
}
