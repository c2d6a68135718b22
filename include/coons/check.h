/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/check.h
 * @brief Topological checks of triangle meshes.
 *
 * coons_mesh_check() counts what keeps a mesh from being closed,
 * 2-manifold and consistently oriented (::coons_mesh_report).
 */
#ifndef COONS_CHECK_H
#define COONS_CHECK_H

#include "coons/types.h"
#include "coons/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Version of ::coons_mesh_report this header describes. */
#define COONS_MESH_REPORT_VERSION 1

/**
 * Topological facts about a mesh, filled by coons_mesh_check(). The caller
 * sets `version` (use ::COONS_MESH_REPORT_INIT); the rest is output.
 * Edges are undirected vertex-index pairs; nothing is welded by position.
 */
typedef struct coons_mesh_report {
    unsigned int version;        /**< in: ::COONS_MESH_REPORT_VERSION */
    size_t vertices;             /**< vertices used by at least one triangle */
    size_t unused_vertices;      /**< vertices no triangle uses */
    size_t triangles;            /**< all triangles, degenerate ones included */
    size_t degenerate_triangles; /**< triangles that repeat a vertex index */
    size_t edges;                /**< distinct edges of the non-degenerate triangles */
    size_t boundary_edges;       /**< edges with exactly one triangle */
    size_t nonmanifold_edges;    /**< edges with three or more triangles */
    size_t misoriented_edges;    /**< edges whose two triangles run them the same way */
    size_t nonmanifold_vertices; /**< vertices whose triangles do not form one fan */
    size_t shells;               /**< connected components (sharing vertices) */
    long euler;                  /**< V - E + F (2 per sphere-like shell) */
    /**
     * What `euler` should be: per sampled part 2, or 0 when the body closes
     * on itself (a ring: its glued faces leave a torus); 2 per shell for
     * other parts.
     */
    long expected_euler;
    int closed;   /**< every edge has exactly two triangles */
    int manifold; /**< no non-manifold edge or vertex, no degenerate triangle */
    int oriented; /**< every two-triangle edge is run in opposite directions */
    int openmesh; /**< 1 if the mesh was also built and checked as an OpenMesh mesh */
    size_t openmesh_rejected; /**< faces OpenMesh's add_face() refused (invalid handle) */
    size_t openmesh_boundary; /**< boundary halfedges of the resulting OpenMesh mesh */
    double volume; /**< signed enclosed volume, as coons_mesh_volume() */
    double area;   /**< total area, as coons_mesh_area() */
} coons_mesh_report;

#ifndef __cplusplus
#define COONS_MESH_REPORT_INIT {.version = COONS_MESH_REPORT_VERSION}
#else
#define COONS_MESH_REPORT_INIT COONS_RECORD_INIT_CXX_(coons_mesh_report, r_.version = COONS_MESH_REPORT_VERSION)
#endif

/** Sets `*r` to ::COONS_MESH_REPORT_INIT; NULL is a harmless no-op. */
COONS_EXPORT void coons_mesh_report_init(coons_mesh_report *r);

/**
 * Checks that a mesh is closed, 2-manifold and consistently oriented and
 * counts what is not. The verdicts and counts come from the index arrays
 * (the same in every build). With OpenMesh built in, the mesh is also
 * loaded into an OpenMesh halfedge mesh (double coordinates, faces added
 * in order); a closed, manifold, oriented mesh loads with no refused face
 * and no boundary halfedge, anything else shows in `openmesh_rejected` and
 * `openmesh_boundary`. A closed, manifold, oriented mesh of s sphere-like
 * shells has `euler == 2 * s`; `expected_euler` says what the parts should
 * give. The library never prints: OpenMesh's log
 * streams (omlog, omout, omerr) are disabled, process-wide, by any call
 * into the OpenMesh layer.
 * @param[in]     m       the mesh
 * @param[in,out] report  version set by the caller, facts filled in
 * @return ::COONS_OK (whatever the verdict), ::COONS_E_INVALID (report
 *         version), ::COONS_E_NOMEM, ::COONS_E_INTERNAL.
 */
COONS_EXPORT coons_status coons_mesh_check(const coons_mesh *m, coons_mesh_report *report,
                                           coons_error *err);

#ifdef __cplusplus
}
#endif
#endif
