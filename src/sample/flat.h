/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Flat faces sampled by their boundary (flat.c), and what flat.c shares
 * with the ruled faces (ruled.c). Internal.
 *
 * A face of a body whose points all lie in one plane needs no interior
 * lattice points: its mesh is a quality triangulation of its boundary
 * polygon (the lattice points on its four edges, which the neighbouring
 * faces hold too, so the shell stays joined by index). */
#ifndef COONS_FLAT_H
#define COONS_FLAT_H

#include "sampler.h"

/* Smallest angle, in degrees, the polygon mesher aims at (Delaunay
 * refinement; angles of the polygon itself below it stay). */
#define COONS__FLAT_MIN_ANGLE 20.0

/* Planarity and area-equality tolerance, relative to the body's extent
 * (positions are scaled to about 1): far below any sampling tolerance,
 * far above rounding (a few ulps). */
#define COONS__FLAT_EPS 1e-12

/* Twice the signed area of abc in the plane. */
static inline double coons__orient2(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* The corners (ia, ib) of triangle k (0, 1) of cell (p, q) split by
 * diagonal dg (as emit_cells() in sample.c splits it). */
static inline void coons__cell_tri(size_t p, size_t q, unsigned char dg, int k, size_t ia[3],
                                   size_t ib[3])
{
    /* A = (p,q), B = (p+1,q), C = (p+1,q+1), D = (p,q+1) */
    static const int ca[2][2][3] = {{{0, 1, 1}, {0, 1, 0}}, {{0, 1, 0}, {1, 1, 0}}};
    static const int cb[2][2][3] = {{{0, 0, 1}, {0, 1, 1}}, {{0, 0, 1}, {0, 1, 1}}};
    for (int j = 0; j < 3; j++) {
        ia[j] = p + (size_t)ca[dg][k][j];
        ib[j] = q + (size_t)cb[dg][k][j];
    }
}

/* Replaces the lattice triangles of every flat face of s's final mesh
 * (not shared, not glued; planar within FLAT_EPS of the body's extent at
 * the lattice points and at 3 x 3 sub-samples of every cell) by a
 * triangulation of its boundary polygon, with Steiner points appended to
 * s's raw vertices (evaluated, their own union-find roots) with their
 * parameters in s->flat_uvw. A face whose polygon the mesher cannot
 * triangulate exactly, or whose Steiner points' parameters are not found,
 * keeps its lattice triangles. A face that is not flat but straight along
 * one direction (ruled between two straight lines) is meshed as strips
 * spanning its rulings where their measured deviation stays within the
 * tolerance (s->ruled_faces; s->dev takes their deviation). Nothing
 * happens with COONS__SAMPLE_LATTICE_FACES or for morph bodies.
 * Returns COONS_OK, COONS_E_NOMEM, or an evaluation error of the body. */
coons_status coons__flat_faces(sampler *s);

#endif
