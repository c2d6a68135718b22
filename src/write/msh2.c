/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Gmsh MSH 2.2 ASCII writer (Gmsh reference manual, "MSH file format",
 * "Legacy formats / MSH file format version 2"): $MeshFormat 2.2 0 8,
 * $PhysicalNames, $Nodes (number x y z), $Elements (number type 2
 * physical elementary nodes...), then a $NodeData per node field; cell
 * fields are left out (below).
 *
 * Node n is number n + 1, cell c element c + 1 (the tag the fields and
 * MSH 4.1 use too), the surface elements follow. Each element carries two
 * tags, its physical group and its elementary entity: a cell of part i has
 * both i + 1, an element of physical surface k has np + 1 + k and k + 1
 * (msh_common.h). What the cells and faces become is msh_common.c's. */
#include "msh_common.h"

static int put_nodes(const coons__msh_plan *p, coons__sink *s)
{
    const double *xyz = coons_volume_mesh_nodes(p->vm);
    if (!coons__msh_put_u(s, "$Nodes\n", p->nn, "\n")) return 0;
    for (size_t v = 0; v < p->nn; v++) {
        char *q = coons__sink_room(s, 4 * COONS__FMT_MAX + 1), *q0 = q;
        if (!q) return 0;
        q += coons__fmt_u64(q, v + 1);
        for (int k = 0; k < 3; k++) {
            *q++ = ' ';
            q += coons__fmt_double(q, xyz[3 * v + (size_t)k]);
        }
        *q++ = '\n';
        s->len += (size_t)(q - q0);
    }
    return coons__sink_puts(s, "$EndNodes\n");
}

/* One element line: number, type, the two tags, 1-based nodes. */
static int put_element(coons__sink *s, uint64_t tag, int type, uint64_t phys, uint64_t ent,
                       const uint32_t *nodes, size_t n)
{
    uint64_t v[32] = {tag, (uint64_t)type, 2, phys, ent};
    for (size_t i = 0; i < n; i++) v[5 + i] = (uint64_t)nodes[i] + 1;
    return coons__msh_put_ints(s, v, 5 + n);
}

static int put_elements(const coons__msh_plan *p, coons__sink *s)
{
    const uint32_t *part = coons_volume_mesh_cell_parts(p->vm);
    if (!coons__msh_put_u(s, "$Elements\n", p->nc + p->nsurfel, "\n")) return 0;
    uint32_t nodes[27];
    int type;
    for (size_t c = 0; c < p->nc; c++) {
        size_t n = coons__msh_cell(p, c, nodes, &type);
        if (!put_element(s, c + 1, type, part[c] + 1u, part[c] + 1u, nodes, n)) return 0;
    }
    uint64_t tag = p->nc;
    for (size_t k = 0; k < p->nsurf; k++) {
        const uint32_t *pairs;
        size_t nf;
        coons_volume_mesh_face_set(p->vm, p->first[k], &pairs, &nf);
        for (size_t j = 0; j < nf; j++) {
            size_t n = coons__msh_face(p, pairs[2 * j], pairs[2 * j + 1], nodes, &type);
            if (n && !put_element(s, ++tag, type, p->np + 1 + k, k + 1, nodes, n)) return 0;
        }
    }
    return coons__sink_puts(s, "$EndElements\n");
}

coons_status coons__write_msh2(const coons_volume_mesh *vm, const coons__wopts *o, coons__sink *s)
{
    (void)o; /* MSH 2.2 has no place for a title or units */
    coons__msh_plan p;
    /* Node fields only: meshio 5.0 (Debian 12) cannot read an MSH 2.2 file
     * with any $ElementData (it splits the values by the length of its
     * (type, cells) tuples, 2); 4.1 carries the cell fields. */
    const coons__msh_order order = {NULL, 0, NULL, NULL};
    if (coons__msh_plan_build(&p, vm, s) == COONS_OK && coons__msh_put_format(s, "2.2") &&
        coons__msh_put_physical_names(&p, s) && put_nodes(&p, s) && put_elements(&p, s))
        coons__msh_put_fields(&p, &order, s);
    coons__msh_plan_free(&p);
    return s->status;
}
