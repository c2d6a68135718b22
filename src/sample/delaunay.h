/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A body-free 2-D quality mesher of simple polygons (delaunay.c): Delaunay
 * refinement that never splits the polygon's edges. Internal. */
#ifndef COONS_DELAUNAY_H
#define COONS_DELAUNAY_H

#include <stddef.h>
#include <stdint.h>

#include "coons_internal.h"

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
