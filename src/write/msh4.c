/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Gmsh MSH 4.1 ASCII writer (Gmsh reference manual, "MSH file format",
 * "MSH file format version 4.1"): $MeshFormat 4.1 0 8, $PhysicalNames,
 * $Entities, $Nodes and $Elements in entity blocks, then $NodeData /
 * $ElementData per field (the same sections as in version 2.2).
 *
 * Entities: one volume per part (tag i + 1, physical volume i + 1), one
 * surface per physical surface k (tag k + 1, physical np + 1 + k), no
 * points or curves (a discrete model: bounding boxes only, no boundary
 * lists). Each node is listed once, in the block of the volume of the
 * first cell that uses it (nodes of no cell: the first volume); surface
 * elements refer to the volumes' nodes, which Gmsh accepts. Element tags
 * are those of the 2.2 writer (cell c is c + 1, the surface elements
 * follow in face-set order), so fields and tags agree between versions;
 * a block holds one part's cells of one type (hexahedra, prisms,
 * pyramids) or one surface's quadrangles or triangles. The data sections
 * list nodes and elements in this file order, not by tag. */
#include "msh_common.h"

/* Index of a cell type within a part's blocks. */
static int cell_slot(int type)
{
    return type == COONS__MSH_PRISM6 ? 1 : type == COONS__MSH_PYRAMID5 ? 2 : 0;
}

typedef struct msh4 {
    coons__msh_plan p;
    size_t nve;       /* volume entities: np, or 1 for nodes without parts */
    uint32_t *norder; /* nodes grouped by entity */
    size_t *nstart;   /* [nve + 1] */
    uint32_t *corder; /* cells grouped by part and slot */
    size_t *cstart;   /* [3 np + 1] */
    double (*vbox)[6], (*sbox)[6];
} msh4;

static void box_add(double b[6], const double *x)
{
    for (int k = 0; k < 3; k++) {
        if (x[k] < b[k]) b[k] = x[k];
        if (x[k] > b[3 + k]) b[3 + k] = x[k];
    }
}

static void box_empty(double (*b)[6], size_t n)
{
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) b[i][k] = INFINITY, b[i][3 + k] = -INFINITY;
}

/* Counting sort of n items by key[i] < nkeys: start[nkeys + 1], order[n]. */
static void group(const uint32_t *key, size_t n, size_t nkeys, size_t *start, uint32_t *order)
{
    memset(start, 0, (nkeys + 1) * sizeof *start);
    for (size_t i = 0; i < n; i++) start[key[i] + 1]++;
    for (size_t k = 0; k < nkeys; k++) start[k + 1] += start[k];
    for (size_t i = 0; i < n; i++) order[start[key[i]]++] = (uint32_t)i;
    for (size_t k = nkeys; k > 0; k--) start[k] = start[k - 1];
    start[0] = 0;
}

static coons_status prepare(msh4 *m, coons__sink *s)
{
    coons__msh_plan *p = &m->p;
    m->nve = p->np ? p->np : p->nn ? 1 : 0;
    uint32_t *key = coons__malloc_array((p->nn > p->nc ? p->nn : p->nc) + 1, sizeof *key);
    m->norder = coons__malloc_array(p->nn + 1, sizeof *m->norder);
    m->nstart = coons__malloc_array(m->nve + 1, sizeof *m->nstart);
    m->corder = coons__malloc_array(p->nc + 1, sizeof *m->corder);
    m->cstart = coons__malloc_array(3 * p->np + 1, sizeof *m->cstart);
    m->vbox = coons__malloc_array(m->nve + 1, sizeof *m->vbox);
    m->sbox = coons__malloc_array(p->nsurf + 1, sizeof *m->sbox);
    if (!key || !m->norder || !m->nstart || !m->corder || !m->cstart || !m->vbox || !m->sbox) {
        coons__free(key);
        return s->status = coons__error_nomem(s->err);
    }
    const uint32_t *part = coons_volume_mesh_cell_parts(p->vm);
    const uint32_t *cells = coons_volume_mesh_cells(p->vm);
    const double *xyz = coons_volume_mesh_nodes(p->vm);
    box_empty(m->vbox, m->nve);
    box_empty(m->sbox, p->nsurf);
    /* Cells by part and type, and the volumes' boxes. */
    for (size_t c = 0; c < p->nc; c++) {
        uint32_t nodes[27];
        int type;
        coons__msh_cell(p, c, nodes, &type);
        key[c] = 3 * part[c] + (uint32_t)cell_slot(type);
        for (size_t k = 0; k < p->npc; k++)
            box_add(m->vbox[part[c]], xyz + 3 * cells[p->npc * c + k]);
    }
    group(key, p->nc, 3 * p->np, m->cstart, m->corder);
    /* Nodes by the part of the first cell using them. */
    for (size_t v = 0; v < p->nn; v++) key[v] = UINT32_MAX;
    for (size_t c = 0; c < p->nc; c++)
        for (size_t k = 0; k < p->npc; k++) {
            uint32_t v = cells[p->npc * c + k];
            if (key[v] == UINT32_MAX) key[v] = part[c];
        }
    for (size_t v = 0; v < p->nn; v++)
        if (key[v] == UINT32_MAX) {
            key[v] = 0;
            box_add(m->vbox[0], xyz + 3 * v);
        }
    group(key, p->nn, m->nve, m->nstart, m->norder);
    coons__free(key);
    for (size_t k = 0; k < p->nsurf; k++) {
        const uint32_t *pairs;
        size_t nf;
        coons_volume_mesh_face_set(p->vm, p->first[k], &pairs, &nf);
        for (size_t j = 0; j < nf; j++) {
            uint32_t nodes[9];
            int type;
            size_t n = coons__msh_face(p, pairs[2 * j], pairs[2 * j + 1], nodes, &type);
            for (size_t i = 0; i < n; i++) box_add(m->sbox[k], xyz + 3 * nodes[i]);
        }
    }
    return COONS_OK;
}

static void release(msh4 *m)
{
    coons__msh_plan_free(&m->p);
    coons__free(m->norder);
    coons__free(m->nstart);
    coons__free(m->corder);
    coons__free(m->cstart);
    coons__free(m->vbox);
    coons__free(m->sbox);
}

/* "tag minX minY minZ maxX maxY maxZ numPhysicalTags [tag] 0" (no
 * bounding entities); an empty box is written as zeros. */
static int put_entity(coons__sink *s, size_t tag, const double b[6], size_t phys)
{
    char *q = coons__sink_room(s, 9 * COONS__FMT_MAX), *q0 = q;
    if (!q) return 0;
    q += coons__fmt_u64(q, tag);
    for (int k = 0; k < 6; k++) {
        *q++ = ' ';
        q += coons__fmt_double(q, b[0] <= b[3] ? b[k] : 0.0);
    }
    *q++ = ' ';
    if (phys) {
        *q++ = '1';
        *q++ = ' ';
        q += coons__fmt_u64(q, phys);
    } else {
        *q++ = '0';
    }
    memcpy(q, " 0\n", 3);
    s->len += (size_t)(q + 3 - q0);
    return 1;
}

static int put_entities(const msh4 *m, coons__sink *s)
{
    const coons__msh_plan *p = &m->p;
    if (!coons__msh_put_u(s, "$Entities\n0 0 ", p->nsurf, "") ||
        !coons__msh_put_u(s, " ", m->nve, "\n"))
        return 0;
    for (size_t k = 0; k < p->nsurf; k++)
        if (!put_entity(s, k + 1, m->sbox[k], p->np + 1 + k)) return 0;
    for (size_t i = 0; i < m->nve; i++)
        if (!put_entity(s, i + 1, m->vbox[i], p->np ? i + 1 : 0)) return 0;
    return coons__sink_puts(s, "$EndEntities\n");
}

static int put_nodes(const msh4 *m, coons__sink *s)
{
    const coons__msh_plan *p = &m->p;
    const double *xyz = coons_volume_mesh_nodes(p->vm);
    size_t blocks = 0;
    for (size_t i = 0; i < m->nve; i++) blocks += m->nstart[i + 1] > m->nstart[i];
    uint64_t head[4] = {blocks, p->nn, p->nn ? 1 : 0, p->nn};
    if (!coons__sink_puts(s, "$Nodes\n") || !coons__msh_put_ints(s, head, 4)) return 0;
    for (size_t i = 0; i < m->nve; i++) {
        size_t a = m->nstart[i], b = m->nstart[i + 1];
        uint64_t bh[4] = {3, i + 1, 0, b - a};
        if (a == b) continue;
        if (!coons__msh_put_ints(s, bh, 4)) return 0;
        for (size_t j = a; j < b; j++) {
            uint64_t t = (uint64_t)m->norder[j] + 1;
            if (!coons__msh_put_ints(s, &t, 1)) return 0;
        }
        for (size_t j = a; j < b; j++) {
            char *q = coons__sink_room(s, 3 * COONS__FMT_MAX + 1), *q0 = q;
            if (!q) return 0;
            for (int k = 0; k < 3; k++) {
                q += coons__fmt_double(q, xyz[3 * (size_t)m->norder[j] + (size_t)k]);
                *q++ = k < 2 ? ' ' : '\n';
            }
            s->len += (size_t)(q - q0);
        }
    }
    return coons__sink_puts(s, "$EndNodes\n");
}

static int put_row(coons__sink *s, uint64_t tag, const uint32_t *nodes, size_t n)
{
    uint64_t v[28] = {tag};
    for (size_t i = 0; i < n; i++) v[1 + i] = (uint64_t)nodes[i] + 1;
    return coons__msh_put_ints(s, v, 1 + n);
}

static int surface_type(size_t npc, int slot)
{
    if (slot) return npc == 8 ? COONS__MSH_TRI3 : COONS__MSH_TRI6;
    return npc == 8 ? COONS__MSH_QUAD4 : npc == 20 ? COONS__MSH_QUAD8 : COONS__MSH_QUAD9;
}

/* The blocks of surface k: its quadrangles, then its triangles, each
 * element with the tag it has in face order (base + 1 ...). */
static int put_surface(const coons__msh_plan *p, size_t k, uint64_t base, coons__sink *s)
{
    const uint32_t *pairs;
    size_t nf;
    coons_volume_mesh_face_set(p->vm, p->first[k], &pairs, &nf);
    for (int slot = 0; slot < 2; slot++) {
        if (!p->surf_count[k][slot]) continue;
        uint64_t bh[4] = {2, k + 1, (uint64_t)surface_type(p->npc, slot), p->surf_count[k][slot]};
        if (!coons__msh_put_ints(s, bh, 4)) return 0;
        uint64_t tag = base;
        for (size_t j = 0; j < nf; j++) {
            uint32_t nodes[9];
            int type;
            size_t n = coons__msh_face(p, pairs[2 * j], pairs[2 * j + 1], nodes, &type);
            if (!n) continue;
            tag++;
            if (coons__msh_face_slot(type) == slot && !put_row(s, tag, nodes, n)) return 0;
        }
    }
    return 1;
}

static int put_elements(const msh4 *m, coons__sink *s)
{
    const coons__msh_plan *p = &m->p;
    size_t blocks = 0, total = p->nc + p->nsurfel;
    for (size_t i = 0; i < 3 * p->np; i++) blocks += m->cstart[i + 1] > m->cstart[i];
    for (size_t k = 0; k < p->nsurf; k++)
        blocks += (p->surf_count[k][0] > 0) + (p->surf_count[k][1] > 0);
    uint64_t head[4] = {blocks, total, total ? 1 : 0, total};
    if (!coons__sink_puts(s, "$Elements\n") || !coons__msh_put_ints(s, head, 4)) return 0;
    for (size_t i = 0; i < 3 * p->np; i++) {
        size_t a = m->cstart[i], b = m->cstart[i + 1];
        if (a == b) continue;
        uint32_t nodes[27];
        int type;
        coons__msh_cell(p, m->corder[a], nodes, &type);
        uint64_t bh[4] = {3, i / 3 + 1, (uint64_t)type, b - a};
        if (!coons__msh_put_ints(s, bh, 4)) return 0;
        for (size_t j = a; j < b; j++) {
            size_t n = coons__msh_cell(p, m->corder[j], nodes, &type);
            if (!put_row(s, (uint64_t)m->corder[j] + 1, nodes, n)) return 0;
        }
    }
    uint64_t base = p->nc;
    for (size_t k = 0; k < p->nsurf; k++) {
        if (!put_surface(p, k, base, s)) return 0;
        base += p->surf_count[k][0] + p->surf_count[k][1];
    }
    return coons__sink_puts(s, "$EndElements\n");
}

/* The file's element order (put_elements): the cells block by block, then
 * each surface's quadrangles and its triangles; only for cell fields. */
static int element_order(const msh4 *m, coons__msh_order *order, coons__sink *s)
{
    const coons__msh_plan *p = &m->p;
    order->node = m->norder;
    if (coons_volume_mesh_field_count(p->vm, COONS_FIELD_CELL) == 0) return 1;
    order->ne = p->nc + p->nsurfel;
    order->cell = coons__malloc_array(order->ne + 1, sizeof *order->cell);
    order->tag = coons__malloc_array(order->ne + 1, sizeof *order->tag);
    if (!order->cell || !order->tag) return s->status = coons__error_nomem(s->err), 0;
    for (size_t i = 0; i < p->nc; i++) {
        order->cell[i] = m->corder[i];
        order->tag[i] = (uint64_t)m->corder[i] + 1;
    }
    size_t i = p->nc;
    uint64_t base = p->nc;
    for (size_t k = 0; k < p->nsurf; k++) {
        const uint32_t *pairs;
        size_t nf;
        coons_volume_mesh_face_set(p->vm, p->first[k], &pairs, &nf);
        for (int slot = 0; slot < 2; slot++) {
            uint64_t tag = base;
            for (size_t j = 0; j < nf; j++) {
                uint32_t nodes[9];
                int type;
                if (!coons__msh_face(p, pairs[2 * j], pairs[2 * j + 1], nodes, &type)) continue;
                tag++;
                if (coons__msh_face_slot(type) != slot) continue;
                order->cell[i] = pairs[2 * j];
                order->tag[i++] = tag;
            }
        }
        base += p->surf_count[k][0] + p->surf_count[k][1];
    }
    return 1;
}

coons_status coons__write_msh4(const coons_volume_mesh *vm, const coons__wopts *o, coons__sink *s)
{
    (void)o; /* MSH 4.1 has no place for a title or units */
    msh4 m;
    memset(&m, 0, sizeof m);
    coons__msh_order order = {NULL, 0, NULL, NULL};
    if (coons__msh_plan_build(&m.p, vm, s) == COONS_OK && prepare(&m, s) == COONS_OK &&
        element_order(&m, &order, s) && coons__msh_put_format(s, "4.1") &&
        coons__msh_put_physical_names(&m.p, s) && put_entities(&m, s) && put_nodes(&m, s) &&
        put_elements(&m, s))
        coons__msh_put_fields(&m.p, &order, s);
    coons__free(order.cell);
    coons__free(order.tag);
    release(&m);
    return s->status;
}
