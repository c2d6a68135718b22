/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The mesh container: double vertices, uint32_t triangles, named parts
 * (contiguous triangle and vertex ranges). Plain C so the core needs no C++. */
#include <stdio.h>
#include <string.h>

#include "coons_internal.h"
#include "mesh_impl.h"

coons_status coons_mesh_new(coons_mesh **out, coons_error *err)
{
    *out = coons__calloc(1, sizeof **out);
    return *out ? COONS_OK : coons__error_nomem(err);
}

void coons_mesh_free(coons_mesh *m)
{
    if (!m) return;
    for (size_t i = 0; i < m->nparts; i++) coons__free(m->parts[i].name);
    coons__free(m->parts);
    coons__free(m->xyz);
    coons__free(m->tri);
    coons__free(m->uvw);
    coons__free(m);
}

static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap) return 1;
    size_t nc = *cap ? *cap : 16;
    while (nc < need) {
        if (nc > SIZE_MAX / 2 / elem) return 0;
        nc *= 2;
    }
    if (nc > SIZE_MAX / elem) return 0;
    void *q = coons__realloc(*p, nc * elem);
    if (!q) return 0;
    *p = q;
    *cap = nc;
    return 1;
}

coons_status coons_mesh_add_part(coons_mesh *m, const char *name, const double *xyz, size_t nv,
                                 const uint32_t *tri, size_t nt, coons_error *err)
{
    return coons__mesh_add_part_uvw(m, name, xyz, NULL, nv, tri, nt, err);
}

coons_status coons__mesh_add_part_uvw(coons_mesh *m, const char *name, const double *xyz,
                                      const double *uvw, size_t nv, const uint32_t *tri,
                                      size_t nt, coons_error *err)
{
    if (nv > (size_t)UINT32_MAX - m->nv)
        return coons__error_set(err, COONS_E_LIMIT,
                                "mesh would have more than %u vertices", (unsigned)UINT32_MAX);
    if (nt > SIZE_MAX / 3 - m->nt)
        return coons__error_set(err, COONS_E_LIMIT, "mesh has too many triangles");
    for (size_t i = 0; i < 3 * nt; i++)
        if (tri[i] >= nv)
            return coons__error_set(err, COONS_E_INVALID,
                                    "triangle %zu refers to vertex %u of %zu", i / 3,
                                    (unsigned)tri[i], nv);
    if (!coons__all_finite(xyz, 3 * nv))
        return coons__error_set(err, COONS_E_INVALID, "a mesh vertex is not finite");
    if (uvw)
        for (size_t i = 0; i < 3 * nv; i++)
            if (!(uvw[i] >= 0.0 && uvw[i] <= 1.0))
                return coons__error_set(err, COONS_E_DOMAIN,
                                        "vertex %zu has a parameter outside [0,1]", i / 3);
    char buf[32];
    if (!name) {
        snprintf(buf, sizeof buf, "part%zu", m->nparts);
        name = buf;
    }
    size_t len = strlen(name);
    char *nm = coons__malloc(len + 1);
    if (!nm) return coons__error_nomem(err);
    memcpy(nm, name, len + 1);
    if (!grow((void **)&m->xyz, &m->cap_v, 3 * (m->nv + nv), sizeof(double)) ||
        !grow((void **)&m->tri, &m->cap_t, 3 * (m->nt + nt), sizeof(uint32_t)) ||
        !grow((void **)&m->parts, &m->cap_p, m->nparts + 1, sizeof(coons__mesh_part))) {
        coons__free(nm);
        return coons__error_nomem(err);
    }
    /* The parameter array exists from the first part that has parameters
     * on; earlier and later vertices without them read NaN. */
    if (uvw || m->uvw) {
        int fresh = !m->uvw;
        if (!grow((void **)&m->uvw, &m->cap_uvw, 3 * (m->nv + nv), sizeof(double))) {
            coons__free(nm);
            return coons__error_nomem(err);
        }
        if (fresh)
            for (size_t i = 0; i < 3 * m->nv; i++) m->uvw[i] = NAN;
        for (size_t i = 0; i < 3 * nv; i++) m->uvw[3 * m->nv + i] = uvw ? uvw[i] : NAN;
    }
    if (nv) memcpy(m->xyz + 3 * m->nv, xyz, 3 * nv * sizeof(double));
    uint32_t base = (uint32_t)m->nv;
    for (size_t i = 0; i < 3 * nt; i++) m->tri[3 * m->nt + i] = tri[i] + base;
    coons__mesh_part *p = &m->parts[m->nparts++];
    p->name = nm;
    p->tri_first = m->nt;
    p->tri_count = nt;
    p->vert_first = m->nv;
    p->vert_count = nv;
    p->tolerance = -1.0;
    p->sampled = 0;
    p->deviation = -1.0;
    p->lattice[0] = p->lattice[1] = p->lattice[2] = 0;
    p->glued = 0;
    p->has_params = uvw != NULL;
    m->nv += nv;
    m->nt += nt;
    return COONS_OK;
}

size_t coons_mesh_vertex_count(const coons_mesh *m) { return m->nv; }
size_t coons_mesh_triangle_count(const coons_mesh *m) { return m->nt; }
const double *coons_mesh_vertices(const coons_mesh *m) { return m->xyz; }
const uint32_t *coons_mesh_triangles(const coons_mesh *m) { return m->tri; }
size_t coons_mesh_part_count(const coons_mesh *m) { return m->nparts; }
const char *coons_mesh_part_name(const coons_mesh *m, size_t i)
{
    return i < m->nparts ? m->parts[i].name : NULL;
}

void coons_mesh_part_range(const coons_mesh *m, size_t i, size_t *tri_first, size_t *tri_count,
                           size_t *vert_first, size_t *vert_count)
{
    const coons__mesh_part *p = i < m->nparts ? &m->parts[i] : NULL;
    if (tri_first) *tri_first = p ? p->tri_first : 0;
    if (tri_count) *tri_count = p ? p->tri_count : 0;
    if (vert_first) *vert_first = p ? p->vert_first : 0;
    if (vert_count) *vert_count = p ? p->vert_count : 0;
}

int coons_mesh_part_sampling(const coons_mesh *m, size_t i, double *tolerance,
                             double *deviation, size_t lattice[3])
{
    const coons__mesh_part *p = i < m->nparts ? &m->parts[i] : NULL;
    int sampled = p && p->sampled;
    if (tolerance) *tolerance = sampled ? p->tolerance : -1.0;
    if (deviation) *deviation = sampled ? p->deviation : -1.0;
    if (lattice)
        for (int d = 0; d < 3; d++) lattice[d] = sampled ? p->lattice[d] : 0;
    return sampled;
}

const double *coons_mesh_vertex_parameters(const coons_mesh *m)
{
    if (!m->nparts || !m->uvw) return NULL;
    for (size_t i = 0; i < m->nparts; i++)
        if (!m->parts[i].has_params) return NULL;
    return m->uvw;
}

int coons_mesh_part_has_parameters(const coons_mesh *m, size_t i)
{
    return i < m->nparts && m->parts[i].has_params;
}

double coons_mesh_deviation(const coons_mesh *m)
{
    double dev = -1.0;
    for (size_t i = 0; i < m->nparts; i++) {
        if (!m->parts[i].sampled) continue;
        if (isnan(m->parts[i].deviation)) return NAN;
        if (m->parts[i].deviation > dev) dev = m->parts[i].deviation;
    }
    return dev;
}

double coons_mesh_volume(const coons_mesh *m)
{
    return coons__signed_volume6(m->xyz, m->tri, m->nt) / 6.0;
}

double coons_mesh_area(const coons_mesh *m)
{
    double area = 0.0;
    for (size_t t = 0; t < m->nt; t++) {
        double e1[3], e2[3], n[3];
        const double *a = m->xyz + 3 * m->tri[3 * t];
        v3_sub(e1, m->xyz + 3 * m->tri[3 * t + 1], a);
        v3_sub(e2, m->xyz + 3 * m->tri[3 * t + 2], a);
        v3_cross(n, e1, e2);
        area += 0.5 * v3_norm(n);
    }
    return area;
}
