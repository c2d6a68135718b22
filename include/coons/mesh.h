/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/mesh.h
 * @brief Triangle meshes: the container (parts, vertices, triangles).
 *
 * A ::coons_mesh holds double-precision vertices and uint32_t triangles
 * (counter-clockwise seen from outside), grouped into named parts: a part is
 * a contiguous range of triangles, e.g. one body's closed shell. Meshes
 * returned by the library belong to the caller (coons_mesh_free()).
 * Vertex and triangle arrays returned by accessors are borrowed views, valid
 * until the mesh is modified or freed. Meshes are made by sampling
 * (coons/sample.h), isoparametric surfaces (coons/iso.h), deformation
 * (coons/deform.h) and reading (coons/mesh_read.h), checked by
 * coons/check.h and written by coons/io.h.
 */
#ifndef COONS_MESH_H
#define COONS_MESH_H

#include "coons/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Default largest number of triangles a sampling may produce. */
#define COONS_MESH_MAX_TRIANGLES ((size_t)20000000)

/**
 * Creates an empty mesh.
 * @return ::COONS_OK or ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_mesh_new(coons_mesh **out, coons_error *err);

/**
 * Appends a part: `nv` vertices (xyz packed) and `nt` triangles whose
 * indices refer to those vertices (0-based, local to the part). The part's
 * name is copied (NULL: "part<i>").
 * @return ::COONS_OK, ::COONS_E_INVALID (index out of range, non-finite
 *         vertex), ::COONS_E_LIMIT (more than 2^32-1 vertices), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_mesh_add_part(coons_mesh *m, const char *name, const double *xyz,
                                              size_t nv, const uint32_t *tri, size_t nt,
                                              coons_error *err);

/** Releases a mesh; NULL is a harmless no-op. */
COONS_EXPORT void coons_mesh_free(coons_mesh *m);

COONS_EXPORT size_t coons_mesh_vertex_count(const coons_mesh *m);
COONS_EXPORT size_t coons_mesh_triangle_count(const coons_mesh *m);
/** Borrowed view: 3 doubles per vertex. */
COONS_EXPORT const double *coons_mesh_vertices(const coons_mesh *m);

/**
 * Multiplies every vertex by `factor` (a change of units: 25.4 turns
 * inches into millimetres); triangles, parts and vertex parameters stay.
 * @return ::COONS_OK; ::COONS_E_INVALID (no mesh, or `factor` not a finite
 *         number > 0); ::COONS_E_LIMIT when a coordinate would overflow
 *         (the mesh is then unchanged).
 */
COONS_EXPORT coons_status coons_mesh_scale(coons_mesh *m, double factor, coons_error *err);
/** Borrowed view: 3 indices per triangle (into the whole mesh's vertices). */
COONS_EXPORT const uint32_t *coons_mesh_triangles(const coons_mesh *m);

COONS_EXPORT size_t coons_mesh_part_count(const coons_mesh *m);
/** Name of part i (borrowed). */
COONS_EXPORT const char *coons_mesh_part_name(const coons_mesh *m, size_t i);
/** Triangle range [*first, *first + *count) and vertex range of part i. */
COONS_EXPORT void coons_mesh_part_range(const coons_mesh *m, size_t i, size_t *tri_first,
                                        size_t *tri_count, size_t *vert_first,
                                        size_t *vert_count);

/** Signed enclosed volume (divergence theorem; positive when outward). */
COONS_EXPORT double coons_mesh_volume(const coons_mesh *m);
/** Total triangle area. */
COONS_EXPORT double coons_mesh_area(const coons_mesh *m);

#ifdef __cplusplus
}
#endif
#endif
