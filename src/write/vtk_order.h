/* SPDX-License-Identifier: GPL-3.0-or-later */
/* VTK's cell types and node orders, shared by the legacy (vtk.c) and XML
 * (vtu.c) VTK writers. Sources: VTK's vtkCellType.h (type numbers) and the
 * class documentation of vtkHexahedron, vtkQuadraticHexahedron,
 * vtkTriQuadraticHexahedron, vtkWedge and vtkPyramid (node orders).
 *
 * Corners are numbered alike in Gmsh (the mesh's order, coons/volume.h)
 * and VTK. VTK's vtkQuadraticHexahedron edges are 0-1, 1-2, 3-2, 0-3, 4-5,
 * 5-6, 7-6, 4-7, 0-4, 1-5, 2-6, 3-7, and vtkTriQuadraticHexahedron's face
 * nodes lie on the faces x=0, x=1, y=0, y=1, z=0, z=1 of its parametric
 * coordinates (r=0, r=1, s=0, s=1, t=0, t=1), then the centre. */
#ifndef COONS_IO_VTK_ORDER_H
#define COONS_IO_VTK_ORDER_H

#include "writer.h"

enum {
    COONS__VTK_HEXAHEDRON = 12,
    COONS__VTK_WEDGE = 13,
    COONS__VTK_PYRAMID = 14,
    COONS__VTK_QUADRATIC_HEXAHEDRON = 25,
    COONS__VTK_TRIQUADRATIC_HEXAHEDRON = 29
};

/* VTK node k of a hexahedron is the mesh's (Gmsh) node
 * COONS__GMSH_OF_VTK[k]; the first 8, 20 or 27 entries serve the three
 * kinds. */
static const unsigned char COONS__GMSH_OF_VTK[27] = {0,  1,  2,  3,  4,  5,  6,  7,  8,
                                                     11, 13, 9,  16, 18, 19, 17, 10, 12,
                                                     14, 15, 22, 23, 21, 24, 20, 25, 26};

/* VTK node k of a wedge is node COONS__PRISM_OF_VTK_WEDGE[k] of the Gmsh
 * prism that coons__hex8_shape() gives. Gmsh's triangle (0,1,2) is
 * counter-clockwise seen from (3,4,5); VTK's (0,1,2) has its right-hand
 * normal pointing away from (3,4,5) (vtkWedge; vtkCellValidator calls the
 * Gmsh order's faces "oriented incorrectly"), so both triangles are
 * reversed. Pyramids need nothing: Gmsh and VTK both list the base
 * counter-clockwise seen from the apex, then the apex. */
static const unsigned char COONS__PRISM_OF_VTK_WEDGE[6] = {0, 2, 1, 3, 5, 4};

/* Cell i of a mesh of `npc` nodes per cell (Gmsh order) in VTK's terms:
 * its VTK nodes into out, its type into *type; returns the node count. A
 * hex8 cell with repeated corners is a wedge or pyramid where
 * coons__hex8_shape() finds one, else a degenerate hexahedron. */
static inline unsigned coons__vtk_cell(const uint32_t *h, size_t npc, uint32_t out[27],
                                       unsigned *type)
{
    if (npc != 8) {
        for (size_t k = 0; k < npc; k++) out[k] = h[COONS__GMSH_OF_VTK[k]];
        *type = npc == 20 ? COONS__VTK_QUADRATIC_HEXAHEDRON : COONS__VTK_TRIQUADRATIC_HEXAHEDRON;
        return (unsigned)npc;
    }
    uint32_t g[8];
    coons__cell_shape sh = coons__hex8_shape(h, g);
    if (sh == COONS__SHAPE_WEDGE) {
        for (int k = 0; k < 6; k++) out[k] = g[COONS__PRISM_OF_VTK_WEDGE[k]];
        *type = COONS__VTK_WEDGE;
        return 6;
    }
    memcpy(out, g, sizeof g);
    *type = sh == COONS__SHAPE_PYRAMID ? COONS__VTK_PYRAMID : COONS__VTK_HEXAHEDRON;
    return sh == COONS__SHAPE_PYRAMID ? 5u : 8u;
}

#endif
