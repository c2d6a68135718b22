/* SPDX-License-Identifier: GPL-3.0-or-later */
/* What a cell of a volume mesh is where its body collapses (cell_shape.c):
 * the one rule that the volume mesher (lattice.c: grouping each body's
 * cells by type), the public accessor coons_volume_mesh_cell_shape() and
 * the writers (Gmsh, VTK, CalculiX) share. */
#ifndef COONS_VOLUME_CELL_SHAPE_H
#define COONS_VOLUME_CELL_SHAPE_H

#include <stddef.h>
#include <stdint.h>

/* What a cell with repeated corner nodes is. */
typedef enum coons__cell_shape {
    COONS__SHAPE_HEX = 8,     /* 8 distinct corners: out = the cell */
    COONS__SHAPE_WEDGE = 6,   /* two parallel edges of one face collapsed: out[0..5] in
                               * Gmsh's prism order, triangle (0,1,2) counter-clockwise
                               * seen from its partner (3,4,5), node i+3 across from i */
    COONS__SHAPE_PYRAMID = 5, /* one face collapsed to a node: out[0..3] the base,
                               * counter-clockwise seen from the apex out[4] (Gmsh's and
                               * VTK's pyramid order) */
    COONS__SHAPE_DEGENERATE = 0 /* any other repetition: out = the cell as given */
} coons__cell_shape;

/* Classifies a hex8 cell (Gmsh corner order, right-handed reference frame)
 * by which corner nodes coincide and writes the nodes of its shape. */
coons__cell_shape coons__hex8_shape(const uint32_t h[8], uint32_t out[8]);

/* The same per element kind: a cell of `npc` nodes (8, 20 or 27, Gmsh
 * order). Hex8 cells as coons__hex8_shape(); hex20 and hex27 cells stay
 * hexahedra (no quadratic wedge or pyramid is made): COONS__SHAPE_HEX
 * with 8 distinct corners, else COONS__SHAPE_DEGENERATE, and out = the
 * cell's npc nodes either way. */
coons__cell_shape coons__cell_shape_of(const uint32_t *h, size_t npc, uint32_t out[27]);

#endif
