/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The parts of the Gmsh MSH writers that versions 2.2 and 4.1 share (Gmsh
 * reference manual, section "MSH file format": "MSH file format version
 * 4.1" and "Legacy formats / MSH file format version 2"; element types and
 * node orders from "Node ordering").
 *
 * The mesh's cells are already in Gmsh's hexahedron order (coons/volume.h),
 * so hexahedra need no permutation. Hex8 cells at a collapsed edge or face
 * become prisms (type 6) and pyramids (type 7) through coons__hex8_shape();
 * hex20/hex27 cells with repeated nodes stay degenerate hexahedra, because
 * a 15- or 18-node prism would need nodes the lattice does not have.
 *
 * A face of a face set becomes a Gmsh quadrangle (quad4/quad8/quad9, nodes
 * counter-clockwise seen from outside the cell, then the edge nodes, then
 * the centre). Where one edge of the face collapsed it is a triangle
 * (tri3, or tri6 from the corners and the three remaining edge nodes; the
 * quad9's centre node is dropped, it lies inside the triangle); where it
 * collapsed to a line or a point it has no area and is not written. */
#include <stdlib.h>

#include "msh_common.h"

/* Local face f: corners counter-clockwise from outside (coons/volume.h),
 * the edge nodes between corners i and i+1, then the face node. */
static const unsigned char FACE[6][9] = {
    {0, 4, 7, 3, 10, 17, 15, 9, 22}, {1, 2, 6, 5, 11, 14, 18, 12, 23},
    {0, 1, 5, 4, 8, 12, 16, 10, 21}, {3, 7, 6, 2, 15, 19, 14, 13, 24},
    {0, 3, 2, 1, 9, 13, 11, 8, 20},  {4, 5, 6, 7, 16, 18, 19, 17, 25}};

static int hex_type(size_t npc)
{
    return npc == 8 ? COONS__MSH_HEX8 : npc == 20 ? COONS__MSH_HEX20 : COONS__MSH_HEX27;
}

size_t coons__msh_cell(const coons__msh_plan *p, size_t c, uint32_t out[27], int *type)
{
    const uint32_t *cell = coons_volume_mesh_cells(p->vm) + p->npc * c;
    *type = hex_type(p->npc);
    if (p->npc != 8) {
        memcpy(out, cell, p->npc * sizeof *cell);
        return p->npc;
    }
    switch (coons__hex8_shape(cell, out)) {
    case COONS__SHAPE_WEDGE: return *type = COONS__MSH_PRISM6, 6;
    case COONS__SHAPE_PYRAMID: return *type = COONS__MSH_PYRAMID5, 5;
    default: return 8;
    }
}

size_t coons__msh_face(const coons__msh_plan *p, uint32_t c, uint32_t lf, uint32_t out[9],
                       int *type)
{
    const uint32_t *cell = coons_volume_mesh_cells(p->vm) + p->npc * c;
    const unsigned char *f = FACE[lf];
    uint32_t q[4] = {cell[f[0]], cell[f[1]], cell[f[2]], cell[f[3]]};
    int distinct = 4, pair = -1;
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++)
            if (q[i] == q[j]) {
                distinct--;
                if (j == i + 1 || (i == 0 && j == 3)) pair = j == i + 1 ? i : 3;
            }
    if (distinct < 3) return 0;
    int quadratic = p->npc != 8;
    if (distinct == 4 || pair < 0) { /* a quadrangle, possibly degenerate */
        size_t n = p->npc == 8 ? 4 : p->npc == 20 ? 8 : 9;
        for (size_t i = 0; i < n; i++) out[i] = cell[f[i]];
        *type = n == 4 ? COONS__MSH_QUAD4 : n == 8 ? COONS__MSH_QUAD8 : COONS__MSH_QUAD9;
        return n;
    }
    /* Corners pair and pair+1 are one node: the triangle starts after it. */
    for (int i = 0; i < 3; i++) {
        int k = (pair + 1 + i) % 4;
        out[i] = q[k];
        if (quadratic) out[3 + i] = cell[f[4 + k]];
    }
    *type = quadratic ? COONS__MSH_TRI6 : COONS__MSH_TRI3;
    return quadratic ? 6 : 3;
}

/* ---- physical surfaces ---------------------------------------------------- */

/* A face as its sorted nodes (9 slots, unused ones UINT32_MAX). */
typedef struct face_key {
    uint32_t v[9];
} face_key;

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

static int cmp_key(const void *a, const void *b)
{
    const face_key *x = a, *y = b;
    for (int i = 0; i < 9; i++)
        if (x->v[i] != y->v[i]) return x->v[i] < y->v[i] ? -1 : 1;
    return 0;
}

/* keys gets each face set's faces as sorted node lists, each set's sorted;
 * at[i] is where set i starts (at[nsets] the end). */
static coons_status face_keys(const coons__msh_plan *p, face_key **keys, size_t **at,
                              coons__sink *s)
{
    size_t total = 0, nfn = p->npc == 8 ? 4 : p->npc == 20 ? 8 : 9;
    *at = coons__malloc_array(p->nsets + 1, sizeof **at);
    if (!*at) return s->status = coons__error_nomem(s->err);
    for (size_t i = 0; i < p->nsets; i++) {
        size_t n;
        coons_volume_mesh_face_set(p->vm, i, NULL, &n);
        (*at)[i] = total;
        total += n;
    }
    (*at)[p->nsets] = total;
    *keys = coons__malloc_array(total ? total : 1, sizeof **keys);
    if (!*keys) return s->status = coons__error_nomem(s->err);
    const uint32_t *cells = coons_volume_mesh_cells(p->vm);
    for (size_t i = 0; i < p->nsets; i++) {
        const uint32_t *pairs;
        size_t n;
        coons_volume_mesh_face_set(p->vm, i, &pairs, &n);
        face_key *k = *keys + (*at)[i];
        for (size_t j = 0; j < n; j++) {
            const uint32_t *cell = cells + p->npc * pairs[2 * j];
            for (size_t m = 0; m < 9; m++)
                k[j].v[m] = m < nfn ? cell[FACE[pairs[2 * j + 1]][m]] : UINT32_MAX;
            qsort(k[j].v, nfn, sizeof k[j].v[0], cmp_u32);
        }
        qsort(k, n, sizeof *k, cmp_key);
    }
    return COONS_OK;
}

/* Counts the elements of each surface's faces. */
static void count_surface(coons__msh_plan *p, size_t k)
{
    const uint32_t *pairs;
    size_t n;
    coons_volume_mesh_face_set(p->vm, p->first[k], &pairs, &n);
    p->surf_count[k][0] = p->surf_count[k][1] = 0;
    for (size_t j = 0; j < n; j++) {
        uint32_t nodes[9];
        int type;
        if (coons__msh_face(p, pairs[2 * j], pairs[2 * j + 1], nodes, &type))
            p->surf_count[k][coons__msh_face_slot(type)]++;
    }
}

static coons_status group_sets(coons__msh_plan *p, coons__sink *s)
{
    face_key *keys = NULL;
    size_t *at = NULL;
    if (face_keys(p, &keys, &at, s) != COONS_OK) {
        coons__free(keys);
        coons__free(at);
        return s->status;
    }
    /* Quadratic in the number of sets (six per body), linear in faces. */
    for (size_t i = 0; i < p->nsets; i++) {
        size_t n = at[i + 1] - at[i];
        if (p->surface_of[i] != COONS__MSH_NONE || n == 0) continue;
        size_t k = p->nsurf;
        p->first[k] = i;
        p->surface_of[i] = k;
        count_surface(p, k);
        if (p->surf_count[k][0] + p->surf_count[k][1] == 0) {
            p->surface_of[i] = COONS__MSH_NONE; /* every face collapsed */
            continue;
        }
        p->nsurf++;
        p->nsurfel += p->surf_count[k][0] + p->surf_count[k][1];
        size_t last = i;
        for (size_t j = i + 1; j < p->nsets; j++)
            if (p->surface_of[j] == COONS__MSH_NONE && at[j + 1] - at[j] == n &&
                memcmp(keys + at[i], keys + at[j], n * sizeof *keys) == 0) {
                p->surface_of[j] = k;
                p->next[last] = j;
                last = j;
            }
    }
    coons__free(keys);
    coons__free(at);
    return COONS_OK;
}

/* Gmsh 4.8 reads the rest of a $PhysicalNames line (blank, quoted name,
 * newline) with fgets() into 256 bytes (GModelIO_MSH2.cpp, _MSH4.cpp): a
 * longer name loses its closing quote and the file does not load. */
#define NAME_MAX_GMSH 252

static size_t surface_name_length(const coons__msh_plan *p, size_t k)
{
    size_t n = 0;
    for (size_t set = p->first[k]; set != COONS__MSH_NONE; set = p->next[set])
        n += (n ? 1 : 0) + strlen(coons_volume_mesh_face_set(p->vm, set, NULL, NULL));
    return n;
}

static coons_status check_names(const coons__msh_plan *p, coons__sink *s)
{
    for (size_t i = 0; i < p->np + p->nsurf; i++) {
        const char *name = i < p->np ? coons_volume_mesh_part_name(p->vm, i)
                                     : coons_volume_mesh_face_set(p->vm, p->first[i - p->np],
                                                                  NULL, NULL);
        size_t n = i < p->np ? strlen(name) : surface_name_length(p, i - p->np);
        if (n > NAME_MAX_GMSH)
            return s->status = coons__error_set(
                       s->err, COONS_E_LIMIT,
                       "the Gmsh physical name of %s '%.40s...' would have %zu bytes: Gmsh "
                       "reads at most %d",
                       i < p->np ? "the part" : "the face set", name, n, NAME_MAX_GMSH);
    }
    return COONS_OK;
}

coons_status coons__msh_plan_build(coons__msh_plan *p, const coons_volume_mesh *vm,
                                   coons__sink *s)
{
    memset(p, 0, sizeof *p);
    p->vm = vm;
    p->npc = coons_volume_mesh_nodes_per_cell(vm);
    p->nn = coons_volume_mesh_node_count(vm);
    p->nc = coons_volume_mesh_cell_count(vm);
    p->np = coons_volume_mesh_part_count(vm);
    p->nsets = coons_volume_mesh_face_set_count(vm);
    size_t ns = p->nsets ? p->nsets : 1;
    p->first = coons__malloc_array(ns, sizeof *p->first);
    p->next = coons__malloc_array(ns, sizeof *p->next);
    p->surface_of = coons__malloc_array(ns, sizeof *p->surface_of);
    p->surf_count = coons__malloc_array(ns, sizeof *p->surf_count);
    if (!p->first || !p->next || !p->surface_of || !p->surf_count)
        return s->status = coons__error_nomem(s->err);
    for (size_t i = 0; i < p->nsets; i++) p->next[i] = p->surface_of[i] = COONS__MSH_NONE;
    if (group_sets(p, s) != COONS_OK) return s->status;
    return check_names(p, s);
}

void coons__msh_plan_free(coons__msh_plan *p)
{
    coons__free(p->first);
    coons__free(p->next);
    coons__free(p->surface_of);
    coons__free(p->surf_count);
    memset(p, 0, sizeof *p);
}

/* ---- text ------------------------------------------------------------------ */

int coons__msh_put_u(coons__sink *s, const char *prefix, uint64_t n, const char *suffix)
{
    char num[COONS__FMT_MAX];
    num[coons__fmt_u64(num, n)] = '\0';
    return coons__sink_puts(s, prefix) && coons__sink_puts(s, num) && coons__sink_puts(s, suffix);
}

int coons__msh_put_ints(coons__sink *s, const uint64_t *v, size_t n)
{
    /* At most 32 numbers of 20 digits: within one reservation. */
    char *p = coons__sink_room(s, COONS__SINK_MAXREC), *p0 = p;
    if (!p) return 0;
    for (size_t i = 0; i < n; i++) {
        if (i) *p++ = ' ';
        p += coons__fmt_u64(p, v[i]);
    }
    *p++ = '\n';
    s->len += (size_t)(p - p0);
    return 1;
}

int coons__msh_put_format(coons__sink *s, const char *version)
{
    /* file-type 0 (ASCII), data-size 8 (sizeof(double)). */
    return coons__sink_puts(s, "$MeshFormat\n") && coons__sink_puts(s, version) &&
           coons__sink_puts(s, " 0 8\n$EndMeshFormat\n");
}

/* A name inside double quotes: Gmsh's reader ends it at the next double
 * quote, so any inside it becomes a single quote. */
static int put_name(coons__sink *s, const char *name)
{
    char buf[64];
    size_t n = 0;
    for (; *name; name++) {
        buf[n++] = *name == '"' ? '\'' : *name;
        if (n == sizeof buf && !coons__sink_put(s, buf, n)) return 0;
        if (n == sizeof buf) n = 0;
    }
    return coons__sink_put(s, buf, n);
}

int coons__msh_put_physical_names(const coons__msh_plan *p, coons__sink *s)
{
    if (p->np + p->nsurf == 0) return 1;
    if (!coons__msh_put_u(s, "$PhysicalNames\n", p->np + p->nsurf, "\n")) return 0;
    for (size_t i = 0; i < p->np; i++)
        if (!coons__msh_put_u(s, "3 ", i + 1, " \"") ||
            !put_name(s, coons_volume_mesh_part_name(p->vm, i)) || !coons__sink_puts(s, "\"\n"))
            return 0;
    for (size_t k = 0; k < p->nsurf; k++) {
        if (!coons__msh_put_u(s, "2 ", p->np + 1 + k, " \"")) return 0;
        for (size_t set = p->first[k]; set != COONS__MSH_NONE; set = p->next[set])
            if ((set != p->first[k] && !coons__sink_puts(s, "+")) ||
                !put_name(s, coons_volume_mesh_face_set(p->vm, set, NULL, NULL)))
                return 0;
        if (!coons__sink_puts(s, "\"\n")) return 0;
    }
    return coons__sink_puts(s, "$EndPhysicalNames\n");
}

void coons__msh_surface_cells(const coons__msh_plan *p, uint32_t *out)
{
    size_t i = 0;
    for (size_t k = 0; k < p->nsurf; k++) {
        const uint32_t *pairs;
        size_t nf;
        coons_volume_mesh_face_set(p->vm, p->first[k], &pairs, &nf);
        for (size_t j = 0; j < nf; j++) {
            uint32_t nodes[9];
            int type;
            if (coons__msh_face(p, pairs[2 * j], pairs[2 * j + 1], nodes, &type))
                out[i++] = pairs[2 * j];
        }
    }
}

/* One $NodeData or $ElementData: n values, the i-th the value of item[i]
 * (NULL: i) for the entity tagged tag[i] (NULL: i + 1, or item[i] + 1 for
 * nodes, whose tags are their indices + 1). */
static int put_field(coons__sink *s, const char *section, const char *name, coons_field_type type,
                     const void *values, size_t n, const uint32_t *item, const uint64_t *tag,
                     int nodes)
{
    /* One string tag (the view's name), one real tag (the time), three
     * integer tags (time step, components, number of values). */
    if (!coons__sink_puts(s, "$") || !coons__sink_puts(s, section) ||
        !coons__sink_puts(s, "\n1\n\"") || !put_name(s, name) ||
        !coons__msh_put_u(s, "\"\n1\n0\n3\n0\n1\n", n, "\n"))
        return 0;
    for (size_t i = 0; i < n; i++) {
        char *p = coons__sink_room(s, 2 * COONS__FMT_MAX + 2), *p0 = p;
        if (!p) return 0;
        size_t at = item ? item[i] : i;
        p += coons__fmt_u64(p, tag ? tag[i] : (nodes ? at : i) + 1);
        *p++ = ' ';
        if (type == COONS_FIELD_FLOAT64) {
            p += coons__fmt_double(p, ((const double *)values)[at]);
        } else {
            int32_t v = ((const int32_t *)values)[at];
            if (v < 0) *p++ = '-';
            p += coons__fmt_u64(p, v < 0 ? (uint64_t)(-(int64_t)v) : (uint64_t)v);
        }
        *p++ = '\n';
        s->len += (size_t)(p - p0);
    }
    return coons__sink_puts(s, "$End") && coons__sink_puts(s, section) &&
           coons__sink_puts(s, "\n");
}

int coons__msh_put_fields(const coons__msh_plan *p, const coons__msh_order *order,
                          coons__sink *s)
{
    for (int loc = 0; loc < 2; loc++) {
        coons_field_location l = loc ? COONS_FIELD_CELL : COONS_FIELD_NODE;
        size_t n = loc ? order->ne : p->nn; /* ne 0: no cell fields written */
        if (n == 0) continue;
        for (size_t f = 0; f < coons_volume_mesh_field_count(p->vm, l); f++) {
            coons_field_type type;
            const void *values;
            const char *name = coons_volume_mesh_field(p->vm, l, f, &type, &values);
            int ok = loc ? put_field(s, "ElementData", name, type, values, n, order->cell,
                                     order->tag, 0)
                         : put_field(s, "NodeData", name, type, values, n, order->node, NULL, 1);
            if (!ok) return 0;
        }
    }
    return 1;
}
