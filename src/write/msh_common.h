/* SPDX-License-Identifier: GPL-3.0-or-later */
/* What the two Gmsh writers (msh2.c: MSH 2.2, msh4.c: MSH 4.1) share: the
 * element types, the cells as Gmsh elements (hex8 cells at collapsed edges
 * and faces as prisms and pyramids), the quadrangles of the face sets, the
 * physical groups and the text of the sections the two versions write
 * alike ($MeshFormat, $PhysicalNames, $NodeData, $ElementData). */
#ifndef COONS_IO_MSH_COMMON_H
#define COONS_IO_MSH_COMMON_H

#include "writer.h"

/* Gmsh element types (reference manual, "MSH file format", elm-type). */
enum {
    COONS__MSH_TRI3 = 2,
    COONS__MSH_QUAD4 = 3,
    COONS__MSH_HEX8 = 5,
    COONS__MSH_PRISM6 = 6,
    COONS__MSH_PYRAMID5 = 7,
    COONS__MSH_TRI6 = 9,
    COONS__MSH_QUAD9 = 10,
    COONS__MSH_HEX27 = 12,
    COONS__MSH_QUAD8 = 16,
    COONS__MSH_HEX20 = 17
};

#define COONS__MSH_NONE SIZE_MAX

/* The physical groups of a mesh and the counts both writers need.
 *
 * Physical volume i (i < np) is part i, tag i + 1. Physical surface k
 * (k < nsurf) has tag np + 1 + k, so that tags are unique across
 * dimensions (tools that key groups by tag alone, such as meshio's
 * converters, keep them apart); its elementary surface is k + 1. Surface k
 * is one face set, or several that hold the same faces node for node (a
 * face shared by two bodies): first[k] is the first of them in set order,
 * whose faces (outward from its cells) are written, next[set] the next one
 * of the same surface (COONS__MSH_NONE at the end). Face sets without an
 * element (empty, or all faces collapsed to lines or points) are no
 * surface: surface_of[set] is COONS__MSH_NONE. */
typedef struct coons__msh_plan {
    const coons_volume_mesh *vm;
    size_t npc, nn, nc, np, nsets;
    size_t nsurf;
    size_t *first;           /* [nsurf] */
    size_t *next;            /* [nsets] */
    size_t *surface_of;      /* [nsets] */
    size_t (*surf_count)[2]; /* [nsurf]: quadrangles, triangles */
    size_t nsurfel;          /* all surface elements */
} coons__msh_plan;

/* Builds the plan; on error records it in s and returns s->status:
 * COONS_E_NOMEM, or COONS_E_LIMIT for a physical name longer than the
 * 252 bytes Gmsh reads. */
coons_status coons__msh_plan_build(coons__msh_plan *p, const coons_volume_mesh *vm,
                                   coons__sink *s);
void coons__msh_plan_free(coons__msh_plan *p);

/* Cell c as a Gmsh element: writes its nodes (mesh indices, Gmsh order)
 * to out, its type to *type and returns the node count. */
size_t coons__msh_cell(const coons__msh_plan *p, size_t c, uint32_t out[27], int *type);
/* Local face lf (0..5) of cell c as a Gmsh element: a quadrangle (4, 8
 * or 9 nodes) counter-clockwise seen from outside the cell, or a triangle
 * (3 or 6 nodes) where one of its edges collapsed; returns 0 where it
 * collapsed further (a line or a point: no element). */
size_t coons__msh_face(const coons__msh_plan *p, uint32_t c, uint32_t lf, uint32_t out[9],
                       int *type);
/* Index of a surface element type in surf_count (0 quadrangle, 1 triangle). */
static inline int coons__msh_face_slot(int type)
{
    return type == COONS__MSH_TRI3 || type == COONS__MSH_TRI6;
}

/* Writes prefix, then n, then suffix. Returns 0 after an error. */
int coons__msh_put_u(coons__sink *s, const char *prefix, uint64_t n, const char *suffix);
/* Writes the integers v[0..n) separated by blanks and a newline. */
int coons__msh_put_ints(coons__sink *s, const uint64_t *v, size_t n);
/* "$MeshFormat" with the given version text ("2.2", "4.1"). */
int coons__msh_put_format(coons__sink *s, const char *version);
/* "$PhysicalNames" (nothing when there are no groups). */
int coons__msh_put_physical_names(const coons__msh_plan *p, coons__sink *s);
/* The order of the file's nodes and elements, for the data sections:
 * node[i] is the i-th node listed (NULL: node i), and the i-th of the ne
 * elements listed carries the values of cell cell[i] and has tag tag[i]
 * (NULL: i + 1). A surface element carries the values of the cell whose
 * face it is. */
typedef struct coons__msh_order {
    const uint32_t *node;
    size_t ne;
    uint32_t *cell;
    uint64_t *tag;
} coons__msh_order;
/* The cell of each surface element, in the order of the surfaces and of
 * their faces (p->nsurfel values). */
void coons__msh_surface_cells(const coons__msh_plan *p, uint32_t *out);
/* One $NodeData per node field and, when order->ne > 0, one $ElementData
 * per cell field, each listing its values in the order the file lists the
 * nodes and elements (meshio's reader ignores the tags there and takes
 * them in file order). */
int coons__msh_put_fields(const coons__msh_plan *p, const coons__msh_order *order,
                          coons__sink *s);

#endif
