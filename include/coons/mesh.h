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

/* ------------------------------------------------------------------------ */
/* Sampling bodies into closed boundary meshes (src/mesh/sample.c)          */
/* ------------------------------------------------------------------------ */

/** Default largest side ratio of the cells of the starting lattice. */
#define COONS_SAMPLE_DEFAULT_MAX_ASPECT 4.0

/** Version of ::coons_sample_options this header describes. Version 2:
 *  `progress` and `userdata`; records of version 1 are still accepted. */
#define COONS_SAMPLE_OPTIONS_VERSION 2

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
    /** (version 2) Progress of each body's sampling, from the calling
     *  thread: the stage "measure" with the share of the body's face rows
     *  measured in the current pass (adaptive sampling makes several
     *  passes, each from 0 to 1). Bodies that coons_model_solidify()
     *  samples on other threads report nothing here (see its progress).
     *  NULL: no reports. */
    coons_progress_fn progress;
    /** (version 2) Passed to `progress`. */
    void *userdata;
} coons_sample_options;

/**
 * Flag of ::coons_sample_options: with a fixed `resolution`, skip measuring
 * the deviation (it then reads NaN); the measurement evaluates each cell at
 * 36 more points and is most of the work of a fixed lattice. Adaptive
 * sampling always measures.
 */
#define COONS_SAMPLE_UNMEASURED 1u

#define COONS_SAMPLE_OPTIONS_INIT \
    {COONS_SAMPLE_OPTIONS_VERSION, 0.0, 0u, 0u, 0.0, 0u, NULL, NULL}

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
 * "union", bodies joined by shared faces (a control lattice: coons-model(5)
 * "Bodies that share faces") are one part named "A+B+..." (first and last
 * as "A+...+Z" when long): sampled on shared lattices, the shared faces
 * left out, joined by index into one closed shell with no Boolean
 * operation. Parts whose sampled bounding boxes (grown by the tolerance)
 * are disjoint are simply put together; other overlapping or touching
 * bodies need the Boolean union, which this function does not perform: it
 * returns ::COONS_E_UNSUPPORTED naming the two bodies.
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
/* Isoparametric surfaces (src/mesh/iso.c)                                  */
/* ------------------------------------------------------------------------ */

/**
 * The body parameters of every vertex, 3 doubles (u, v, w) per vertex in
 * vertex order (borrowed view, valid until the mesh is modified or freed),
 * or NULL when the mesh has no part or a part without them. Parts made by
 * coons_body_iso_surface() and coons_model_iso_surfaces() carry them
 * (boundary parts included); parts added with coons_mesh_add_part() or
 * sampled by coons_body_sample() / coons_model_sample() do not.
 */
COONS_EXPORT const double *coons_mesh_vertex_parameters(const coons_mesh *m);

/** 1 if part i carries vertex parameters (see coons_mesh_vertex_parameters()). */
COONS_EXPORT int coons_mesh_part_has_parameters(const coons_mesh *m, size_t i);

/** How a writer shows a part. */
typedef enum coons_part_display {
    COONS_PART_NORMAL = 0,    /**< an ordinary part (every part starts so) */
    /**
     * Context, not geometry: the OpenSCAD writer calls its module with the
     * background modifier `%` (drawn transparent in the preview, left out
     * of renders and exports). Other formats write it as an ordinary part.
     */
    COONS_PART_BACKGROUND = 1
} coons_part_display;

/**
 * Sets how part i is shown (see ::coons_part_display).
 * @return ::COONS_OK; ::COONS_E_INVALID (no part i, unknown value; the
 *         mesh is then unchanged).
 */
COONS_EXPORT coons_status coons_mesh_set_part_display(coons_mesh *m, size_t i,
                                                      coons_part_display display,
                                                      coons_error *err);

/** How part i is shown; ::COONS_PART_NORMAL for parts out of range. */
COONS_EXPORT coons_part_display coons_mesh_part_display(const coons_mesh *m, size_t i);

/** One isoparametric surface: direction 0 (u), 1 (v) or 2 (w) = value. */
typedef struct coons_iso_request {
    int direction;
    double value;
} coons_iso_request;

/** Flag of coons_model_iso_surfaces(): also each body's boundary. */
#define COONS_ISO_WITH_BOUNDARY 1u

/** Longest part name coons_iso_surface_name() writes, NUL included. */
#define COONS_ISO_NAME_MAX 320

/**
 * The name of an isoparametric surface part: `BODY.u=VALUE` (or `.v=`,
 * `.w=`), VALUE the shortest decimal text that reads back to the value
 * ("0.25", "0.1", "1", "0.3333333333333333"), whatever the locale; just
 * `u=VALUE` when `body` is NULL. The OpenSCAD writer makes module names of
 * such names by turning `.` and `=` into `_` (`BODY_u_0_25`). Written into
 * out[cap] (truncated to fit; cap >= 1).
 */
COONS_EXPORT void coons_iso_surface_name(const char *body, int direction, double value,
                                         char *out, size_t cap);

/**
 * Parses an isoparametric surface option, `u=0.25,0.5` (direction u, v or
 * w, then one or more comma-separated numbers in [0,1], read in the C
 * locale), appending one request per value at out[*count]; *count grows.
 * @return ::COONS_OK; ::COONS_E_INVALID (not of that form; the message
 *         quotes it); ::COONS_E_DOMAIN (a value outside [0,1]);
 *         ::COONS_E_LIMIT (more than `cap` requests in all). On error
 *         *count and the requests before it are unchanged.
 */
COONS_EXPORT coons_status coons_iso_parse(const char *spec, coons_iso_request *out, size_t cap,
                                          size_t *count, coons_error *err);

/**
 * Appends to `into` one part: the isoparametric surface of body b where
 * parameter `direction` (0 u, 1 v, 2 w) equals `value` (seed 000 section
 * 2.1, Fig. 2-6), e.g. F(0.25, v, w) over (v, w) in [0,1]^2.
 *
 * The surface is sampled on the lattice of the other two directions that
 * coons_body_sample() settles on for b with `opts` (so the surface at 0 or
 * 1 is that boundary face, point for point); each lattice cell gives two
 * triangles split along its shorter diagonal, and every vertex is the
 * body's point at its own parameters, stored with it
 * (coons_mesh_vertex_parameters()). As in coons_body_sample(), lattice
 * neighbours at the same place (collapsed edges, an apex) are merged, the
 * triangles that become degenerate are dropped, and a surface that closes
 * on itself (a seam along which its two opposite sides coincide) is glued
 * there. A surface that collapses entirely (to a curve or a point) gives a
 * part with no triangles. Triangles are wound so that their normal is
 * F_a x F_b with (a, b) = (v, w), (w, u), (u, v) for u, v, w = const: it
 * points towards increasing `direction` when the body is right-handed
 * (det J > 0), away from it when left-handed.
 *
 * @param[in]     b          the body (not modified)
 * @param[in]     direction  0, 1 or 2
 * @param[in]     value      in [0,1]
 * @param[in]     opts       NULL or sampling options (the tolerance
 *                           defaults to 1/1000 of the body's control box
 *                           diagonal, as in coons_body_sample())
 * @param[in]     name       the part's name (copied); NULL: as
 *                           coons_iso_surface_name() with no body
 * @param[in,out] into       the mesh to append to
 * @return ::COONS_OK; ::COONS_E_DOMAIN (value outside [0,1] or NaN; the
 *         message names it); ::COONS_E_INVALID (direction not 0, 1 or 2,
 *         bad options, a body that evaluates to a non-finite point);
 *         ::COONS_E_LIMIT (the boundary sampling or the surface needs more
 *         than `max_triangles`); ::COONS_E_NOMEM. On error `into` is
 *         unchanged. Thread-safe for distinct meshes.
 */
COONS_EXPORT coons_status coons_body_iso_surface(const coons_body *b, int direction, double value,
                                                 const coons_sample_options *opts,
                                                 const char *name, coons_mesh *into,
                                                 coons_error *err);

/**
 * The isoparametric surfaces `req[0..n)` of every body of a model, as a new
 * mesh: per body (in model order), with ::COONS_ISO_WITH_BOUNDARY in
 * `flags` first its boundary (a part named after the body, sampled as
 * coons_model_sample() does, with vertex parameters, and shown as
 * ::COONS_PART_BACKGROUND), then one part per request in request order,
 * named by coons_iso_surface_name() (`BODY.u=0.25`). The lattice is
 * computed once per body. The model's operation is ignored: each body's
 * surfaces and own boundary are written as they are. The tolerance
 * defaults to the model's; `max_triangles` bounds the whole mesh.
 * @param[out] out  the new mesh (coons_mesh_free()); NULL on error
 * @return as coons_body_iso_surface(); ::COONS_E_INVALID also for
 *         unknown flags or `req` NULL with n > 0.
 */
COONS_EXPORT coons_status coons_model_iso_surfaces(const coons_model *m,
                                                   const coons_iso_request *req, size_t n,
                                                   const coons_sample_options *opts,
                                                   unsigned int flags, coons_mesh **out,
                                                   coons_error *err);

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

/**
 * Free-form deformation (seed 000: Coons bodies as FFDs, after Sederberg
 * and Parry): a new mesh holding `in` mapped through body b, a point p
 * going to B((p - lo) / (hi - lo)). Triangles are split by edge bisection
 * until the image of every edge's parametric midpoint lies within 0.9 times
 * `tolerance` of the chord of its end images and the images of 4 inner
 * points of every triangle lie within 0.9 times `tolerance` of it (the
 * margin covers maxima between the samples); an edge is split
 * the same way in both its triangles, so a closed 2-manifold input stays
 * closed and 2-manifold, with its winding (reversed when b is left-handed,
 * so that an outward input stays outward). An affine body splits nothing
 * and maps every vertex exactly. One part, named "deformed".
 * @param[in] lo,hi the frame's corners, or both NULL for the bounding box
 *                  of `in`'s vertices
 * @param[in] max_triangles the budget; 0: ::COONS_MESH_MAX_TRIANGLES
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL, tolerance not > 0, a flat
 *         frame), ::COONS_E_DOMAIN (vertices outside the frame: the message
 *         counts them and gives the first), ::COONS_E_LIMIT, ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_deform_mesh(const coons_body *b, const coons_mesh *in,
                                                 const double *lo, const double *hi,
                                                 double tolerance, size_t max_triangles,
                                                 coons_mesh **out, coons_error *err);

/** Version of ::coons_deform_report this header describes. */
#define COONS_DEFORM_REPORT_VERSION 1

/** What a deformation did (coons_body_deform_mesh_report()). */
typedef struct coons_deform_report {
    /** ::COONS_DEFORM_REPORT_VERSION, set by the caller. */
    unsigned int version;
    /** The frame used (given, or the input's bounding box). */
    double lo[3], hi[3];
    /**
     * Largest distance measured from exact image points (every edge's
     * parametric midpoint and 4 inner points of every output triangle) to
     * the output triangle they belong to; refinement keeps it within 0.9
     * times the tolerance, the margin covering maxima between the samples.
     */
    double deviation;
    size_t triangles_in, triangles_out, vertices_in, vertices_out;
    /** Rounds of edge bisection that split something. */
    unsigned int rounds;
    /** 1 when the body is left-handed and the winding was reversed. */
    int reversed;
} coons_deform_report;

#define COONS_DEFORM_REPORT_INIT \
    {COONS_DEFORM_REPORT_VERSION, {0, 0, 0}, {0, 0, 0}, 0.0, 0u, 0u, 0u, 0u, 0u, 0}

/**
 * coons_body_deform_mesh() that also fills `report` (NULL: none; its
 * version must be ::COONS_DEFORM_REPORT_VERSION, else ::COONS_E_INVALID).
 */
COONS_EXPORT coons_status coons_body_deform_mesh_report(const coons_body *b, const coons_mesh *in,
                                                        const double *lo, const double *hi,
                                                        double tolerance, size_t max_triangles,
                                                        coons_mesh **out,
                                                        coons_deform_report *report,
                                                        coons_error *err);

/* ------------------------------------------------------------------------ */
/* Reading triangle meshes: STL and OFF (src/io/read/mesh_read.c)           */
/* ------------------------------------------------------------------------ */

/** Default largest mesh file coons_mesh_read_file() reads (1 GiB). */
#define COONS_MESH_READ_MAX_BYTES ((size_t)1 << 30)

/** Version of ::coons_mesh_read_options this header describes. */
#define COONS_MESH_READ_OPTIONS_VERSION 1

/** Limits of the mesh reader; NULL instead of options means the defaults. */
typedef struct coons_mesh_read_options {
    /** ::COONS_MESH_READ_OPTIONS_VERSION. */
    unsigned int version;
    /** Largest file, in bytes; 0: ::COONS_MESH_READ_MAX_BYTES. */
    size_t max_bytes;
    /** Largest number of triangles; 0: ::COONS_MESH_MAX_TRIANGLES. */
    size_t max_triangles;
} coons_mesh_read_options;

#define COONS_MESH_READ_OPTIONS_INIT {COONS_MESH_READ_OPTIONS_VERSION, 0u, 0u}

/**
 * Reads a triangle mesh: binary STL (exactly 84 + 50 * count bytes), ASCII
 * STL (`solid` ... `endsolid`, several solids allowed) or OFF (`OFF`, the
 * counts, vertices, polygons fanned into triangles; `#` comments), told
 * apart by their content. STL vertices are welded by exact coordinate
 * equality (so a closed STL gives a closed indexed mesh); triangles whose
 * corners coincide are dropped. One part, named after the file (without
 * directory and extension).
 *
 * Errors name the file and, for binary STL, the byte offset
 * (`FILE: byte N: ...`), for text the line and column (`FILE:LINE:COL:
 * ...`; also in err->file, err->line, err->column): a truncated file, a
 * triangle count that disagrees with the file size, a non-finite
 * coordinate, a token that is not what the format needs there, a face
 * index out of range. Limits are checked before anything is allocated
 * from a count (every count is first checked against the file size).
 * @return ::COONS_OK; ::COONS_E_IO (cannot open or read); ::COONS_E_PARSE
 *         (malformed); ::COONS_E_LIMIT (more than `max_bytes` or
 *         `max_triangles`; the message says which); ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_mesh_read_file(const char *path,
                                               const coons_mesh_read_options *opts,
                                               coons_mesh **out, coons_error *err);

/**
 * coons_mesh_read_file() of `size` bytes at `data`; `name` (NULL:
 * "<memory>") names the input in messages and the part.
 */
COONS_EXPORT coons_status coons_mesh_read_memory(const void *data, size_t size, const char *name,
                                                 const coons_mesh_read_options *opts,
                                                 coons_mesh **out, coons_error *err);

#ifdef __cplusplus
}
#endif
#endif
