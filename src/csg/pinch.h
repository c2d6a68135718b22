/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Splitting the pinches of a closed mesh (pinch.c): internal to the library
 * (coons_model_solidify() calls it on every solid it makes); reachable from
 * the tests through coons_static. Plain C. */
#ifndef COONS_PINCH_H
#define COONS_PINCH_H

#include "coons.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Makes every part of `m` a 2-manifold where its boundary touches itself,
 * in place:
 *  - an edge of 2k > 2 triangles, k of them running it one way and k the
 *    other, is split into k edges: the triangles are sorted by angle
 *    around the edge and each is paired with its neighbour on the side of
 *    the solid (the side its normal points away from), so that each pair
 *    bounds one wedge of solid;
 *  - then a vertex whose triangles form more than one fan (across the
 *    edges as paired) is written once per fan (same parameters); the
 *    triangles of each fan use their own copy, and every copy is moved
 *    into its fan's solid (against the sum of the fan's unit normals) by
 *    1e-3 of the fan's shortest edge, at least 16 float32 units of its
 *    largest coordinate and 2^-19 model units (OpenSCAD's grid is 2^-20),
 *    at most 1/10 of that edge: readers that weld
 *    vertices by position (STL, OpenSCAD's Booleans) see a 2-manifold.
 *    The move could in principle make triangles cross: the caller checks.
 * An edge whose triangles cannot be paired so (an odd number, unequal
 * directions, an order that does not alternate) is left as it is.
 * Counts are added to *edges_split (edges of more than two triangles
 * before, two after) and *vertices_split (vertices written more than once);
 * *nonmanifold_left (may be NULL) is set to the edges of more than two
 * triangles left in the result. Parts are independent (a vertex is never
 * shared between parts). On failure (COONS_E_NOMEM, COONS_E_LIMIT) `m` is
 * unchanged.
 */
coons_status coons__mesh_split_pinches(coons_mesh *m, size_t *edges_split, size_t *vertices_split,
                                       size_t *nonmanifold_left, coons_error *err);

/*
 * A copy of `m` with the vertices of each part that have the same
 * coordinates merged into one (for the tests: after a split, nothing
 * merges). Part names are kept, nothing else.
 */
coons_status coons__mesh_welded(const coons_mesh *m, coons_mesh **out, coons_error *err);

/* A deep copy of `m` (parts and their records, parameters). */
coons_status coons__mesh_clone(const coons_mesh *m, coons_mesh **out, coons_error *err);

#ifdef __cplusplus
}
#endif
#endif
