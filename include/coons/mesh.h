/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/mesh.h
 * @brief Triangle meshes of body boundaries: the mesh container, sampling
 *        of bodies into closed meshes, checks, and writers (STL, OFF, SCAD).
 *
 * A ::coons_mesh holds double-precision vertices and uint32_t triangles
 * (counter-clockwise seen from outside), grouped into named parts: a part is
 * a contiguous range of triangles, e.g. one body's closed shell. Meshes
 * returned by the library belong to the caller (coons_mesh_free()).
 * Vertex and triangle arrays returned by accessors are borrowed views, valid
 * until the mesh is modified or freed.
 */
#ifndef COONS_MESH_H
#define COONS_MESH_H

#include <stdio.h>

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

/* ------------------------------------------------------------------------ */
/* Sampling bodies into closed boundary meshes (src/mesh/sample.c)          */
/* ------------------------------------------------------------------------ */

/** Default largest side ratio of the cells of the starting lattice. */
#define COONS_SAMPLE_DEFAULT_MAX_ASPECT 4.0

/** Version of ::coons_sample_options this header describes. */
#define COONS_SAMPLE_OPTIONS_VERSION 1

/**
 * How a body's boundary is sampled. Initialise with
 * ::COONS_SAMPLE_OPTIONS_INIT and change the fields you need; passing NULL
 * instead of options means all defaults.
 */
typedef struct coons_sample_options {
    /** ::COONS_SAMPLE_OPTIONS_VERSION. */
    unsigned int version;
    /**
     * Largest allowed distance between the mesh and the exact boundary, in
     * model units. <= 0: the default, which is the model's tolerance for
     * coons_model_sample() and 1/1000 of the body's control box diagonal for
     * coons_body_sample().
     */
    double tolerance;
    /**
     * 0: adaptive sampling to the tolerance. N > 0: a fixed uniform lattice
     * of N intervals along each of u, v, w (the deviation is still measured).
     */
    unsigned int resolution;
    /** Largest number of triangles; 0: ::COONS_MESH_MAX_TRIANGLES. */
    size_t max_triangles;
    /**
     * Adaptive sampling starts from a lattice whose cells are at most this
     * many times longer in one direction than in another (judged by the
     * body's extent along u, v, w; refinement for the tolerance may then
     * make cells thinner where it concentrates, e.g. along a kink).
     * 0: ::COONS_SAMPLE_DEFAULT_MAX_ASPECT; values below 1 other than 0 are
     * invalid; INFINITY disables it.
     */
    double max_aspect;
    /** Zero or more ::COONS_SAMPLE_UNMEASURED. */
    unsigned int flags;
} coons_sample_options;

/**
 * Flag of ::coons_sample_options: with a fixed `resolution`, skip measuring
 * the deviation (it then reads NaN); the measurement evaluates each cell at
 * 36 more points and is most of the work of a fixed lattice. Adaptive
 * sampling always measures.
 */
#define COONS_SAMPLE_UNMEASURED 1u

#define COONS_SAMPLE_OPTIONS_INIT {COONS_SAMPLE_OPTIONS_VERSION, 0.0, 0u, 0u, 0.0, 0u}

/**
 * Sets `*o` to ::COONS_SAMPLE_OPTIONS_INIT (for language bindings that
 * cannot use the macro); NULL is a harmless no-op.
 */
COONS_EXPORT void coons_sample_options_init(coons_sample_options *o);

/**
 * Samples the boundary of a body into a closed, outward-oriented triangle
 * mesh with one part named `name` (NULL: "body").
 *
 * One parameter lattice per direction u, v, w (possibly non-uniform) is
 * shared by the six boundary faces, so neighbouring faces use the very same
 * vertices along their 12 common edges and 8 corners: the mesh is watertight
 * by construction, not by welding. Lattice neighbours that evaluate to the
 * same point (collapsed edges and faces: a cone apex, a face shrunk to a
 * curve) are merged (within 1e-9 of the lattice's bounding box diagonal
 * plus a few units of rounding of the coordinates) and the triangles that
 * become degenerate are dropped. Each lattice cell is split along its
 * shorter diagonal. The mesh is oriented so that its enclosed volume is
 * positive, whatever the body's handedness.
 *
 * Adaptive sampling starts from lattices that contain the breakpoints of
 * the body's data (knots, segment ends) and halves intervals until exact
 * boundary points on a 7 x 7 sampling of every cell (steps of 1/6: edge
 * midpoints and triangle centroids included) lie within 0.9 times the tolerance of the cell's two triangles (the
 * margin covers maxima between the samples). That measured deviation (an
 * upper bound of the distance from those exact points to the mesh) is
 * stored with the part: coons_mesh_part_sampling(). With a fixed
 * `resolution` it is measured the same way but not enforced.
 *
 * @param[in]  b     the body (not modified)
 * @param[in]  opts  NULL or options (see ::coons_sample_options)
 * @param[in]  name  the part's name (copied), or NULL
 * @param[out] out   the new mesh, owned by the caller (coons_mesh_free())
 * @return ::COONS_OK; ::COONS_E_INVALID (bad options, a body that
 *         evaluates to a non-finite point, or whose boundary collapses
 *         entirely); ::COONS_E_LIMIT (more triangles than `max_triangles`
 *         would be needed; the message says the limit and how to raise
 *         it); ::COONS_E_NOMEM. Thread-safe for distinct outputs.
 */
COONS_EXPORT coons_status coons_body_sample(const coons_body *b,
                                            const coons_sample_options *opts, const char *name,
                                            coons_mesh **out, coons_error *err);

/**
 * Samples every body of a model (each a part named after the body, see
 * coons_model_body_name()) with the model's tolerance unless `opts` sets
 * one. `max_triangles` bounds the whole model.
 *
 * For operation "none" the parts are the bodies' own closed shells. For
 * "union", bodies whose sampled bounding boxes (grown by the tolerance) are
 * disjoint are simply put together; overlapping or touching bodies need the
 * Boolean union, which this function does not perform: it returns
 * ::COONS_E_UNSUPPORTED naming the two bodies.
 * @return as coons_body_sample(), plus ::COONS_E_UNSUPPORTED.
 */
COONS_EXPORT coons_status coons_model_sample(const coons_model *m,
                                             const coons_sample_options *opts, coons_mesh **out,
                                             coons_error *err);

/**
 * What sampling recorded for part i: the tolerance it aimed at, the
 * measured deviation (see coons_body_sample(); NaN if not measured, see
 * ::COONS_SAMPLE_UNMEASURED) and the number of lattice intervals along
 * u, v, w. Any output pointer may be NULL.
 * @return 1 if the part came from sampling, 0 otherwise (hand-built or
 *         read parts; outputs are then -1 and 0).
 */
COONS_EXPORT int coons_mesh_part_sampling(const coons_mesh *m, size_t i, double *tolerance,
                                          double *deviation, size_t lattice[3]);

/**
 * Largest measured deviation over all sampled parts: -1 if none was
 * sampled, NaN if one was not measured.
 */
COONS_EXPORT double coons_mesh_deviation(const coons_mesh *m);

/* ------------------------------------------------------------------------ */
/* Checks (src/mesh/check.c, src/mesh/openmesh.cpp)                         */
/* ------------------------------------------------------------------------ */

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

#define COONS_MESH_REPORT_INIT {COONS_MESH_REPORT_VERSION, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, \
                                0, 0, 0, 0, 0, 0, 0, 0.0, 0.0}

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
