/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Flat faces sampled by their boundary (flat.c). Internal.
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

/* Triangulates the simple polygon xy[0 .. 2m-1] (m points, counter-
 * clockwise, no point repeated) with Steiner points inside it, so that the
 * angles are at least `min_angle` degrees where the polygon's own angles
 * and edge lengths allow (the polygon's edges are never split).
 * On success *ok = 1, *pts (ns x 2, coons__malloc'd, may be NULL when
 * ns = 0) holds the Steiner points, numbered m, m+1, ... in *tri
 * (3 *nt indices, counter-clockwise, coons__malloc'd). *ok = 0 (nothing
 * allocated) when the polygon is not simple, has a repeated point, or the
 * result fails its checks (every triangle counter-clockwise, every polygon
 * edge an edge of a triangle, areas summing to the polygon's).
 * Returns COONS_OK or COONS_E_NOMEM. */
coons_status coons__polygon_mesh(const double *xy, size_t m, double min_angle, double **pts,
                                 size_t *ns, uint32_t **tri, size_t *nt, int *ok,
                                 coons_error *err);

#endif
