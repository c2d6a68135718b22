/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/deform.h
 * @brief Free-form deformation of triangle meshes through a body.
 *
 * coons_body_deform_mesh() maps a mesh through a Coons body as a
 * free-form deformation, refining it to a tolerance
 * (::coons_deform_report says what it did); coons_body_deform() does the
 * same from a ::coons_deform_options record, with a progress report.
 */
#ifndef COONS_DEFORM_H
#define COONS_DEFORM_H

#include "coons/types.h"
#include "coons/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Free-form deformation (seed 000: Coons bodies as FFDs, after Sederberg
 * and Parry): a new mesh holding `in` mapped through body b, a point p
 * going to B((p - lo) / (hi - lo)). Triangles are split by edge bisection
 * until each triangle is accepted: measured, when the image of every edge's
 * parametric midpoint lies within 0.9 times `tolerance` of the chord of its
 * end images and the images of 4 inner points of the triangle lie within
 * 0.9 times `tolerance` of it (the margin covers maxima between the
 * samples); or estimated, without evaluating it, when an estimate of its
 * interpolation error is at most 0.45 times `tolerance`. The estimate is
 * second partials of the body per cell of a lattice (16 cells along each
 * direction, the body's breakpoints added: second differences of the
 * body's points at the nodes, the largest over the cell and its neighbours
 * plus their spread, times 2) in Taylor's bound for linear interpolation; it is
 * measured, not proved, so a body with features smaller than a cell can
 * defeat it. It is made only for inputs of at least half as many triangles
 * as lattice points, for bodies that are C1 or whose C0 breakpoints are
 * known (no estimate across those), and only accepts: a triangle it
 * accepts has an estimate half the measured test's limit, so the mesh is
 * the one measuring alone gives wherever the estimate holds. An edge is
 * split the same way in both its triangles, so a closed 2-manifold input stays
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
     * Largest over the output triangles of: the distance measured from
     * exact image points (its edges' parametric midpoints and 4 inner
     * points) to the triangle, for a triangle that was measured; its error
     * estimate, for a triangle the estimate accepted (see
     * coons_body_deform_mesh()). Refinement keeps it within 0.9 times the
     * tolerance (estimates within 0.45 times), the margin covering maxima
     * between the samples.
     */
    double deviation;
    size_t triangles_in, triangles_out, vertices_in, vertices_out;
    /** Rounds of edge bisection that split something. */
    unsigned int rounds;
    /** 1 when the body is left-handed and the winding was reversed. */
    int reversed;
} coons_deform_report;

#ifndef __cplusplus
#define COONS_DEFORM_REPORT_INIT {.version = COONS_DEFORM_REPORT_VERSION}
#else
#define COONS_DEFORM_REPORT_INIT COONS_RECORD_INIT_CXX_(coons_deform_report, r_.version = COONS_DEFORM_REPORT_VERSION)
#endif

/**
 * coons_body_deform_mesh() that also fills `report` (NULL: none; its
 * version must be ::COONS_DEFORM_REPORT_VERSION, else ::COONS_E_INVALID).
 * @return as coons_body_deform_mesh(): ::COONS_OK, ::COONS_E_INVALID (also
 *         a report of another version), ::COONS_E_DOMAIN, ::COONS_E_LIMIT,
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_deform_mesh_report(const coons_body *b, const coons_mesh *in,
                                                        const double *lo, const double *hi,
                                                        double tolerance, size_t max_triangles,
                                                        coons_mesh **out,
                                                        coons_deform_report *report,
                                                        coons_error *err);

/** Version of ::coons_deform_options this header describes. Version 2:
 *  `threads`; version 3: `relative_tolerance`. Records of versions 1 and 2
 *  are still accepted (version 1 as one thread). */
#define COONS_DEFORM_OPTIONS_VERSION 3

/** How coons_body_deform() deforms a mesh. */
typedef struct coons_deform_options {
    /** ::COONS_DEFORM_OPTIONS_VERSION, set by the caller (use
     *  ::COONS_DEFORM_OPTIONS_INIT or coons_deform_options_init()). */
    unsigned int version;
    /** Largest distance of the result from the exact image; must be > 0
     *  unless `relative_tolerance` is (the initialiser leaves it 0: the
     *  caller chooses). */
    double tolerance;
    /** The budget of output triangles; 0: ::COONS_MESH_MAX_TRIANGLES. */
    size_t max_triangles;
    /** The frame's corners (3 doubles each); unless both are given, the
     *  bounding box of the input's vertices. */
    const double *lo, *hi;
    /**
     * Called (when not NULL) on the calling thread with the stage
     * "deform" and the fraction done: 0 at the start, then as the
     * triangles of each refinement round are measured and split (round r,
     * from 0, covers the fractions 1 - 2^-r to 1 - 2^-(r+1) in proportion
     * to its triangles done), never decreasing within one call, and 1 at
     * the end when the call succeeds.
     */
    coons_progress_fn progress;
    /** Passed to `progress`. */
    void *userdata;
    /** (version 2) Threads that map and measure: 0 or 1, the calling
     *  thread only (the default); N > 1, N threads (at most 1024): the
     *  input's vertices, the estimate's lattice and each round's measured
     *  points are evaluated in batches (coons_body_eval_points()), each
     *  thread on its own contiguous share, every result in a slot of its
     *  own; marking and splitting walk the triangles in order on the
     *  calling thread. The mesh does not depend on it, byte for byte.
     *  Progress is reported from the calling thread; an allocator set with
     *  coons_set_allocator() must be thread-safe. */
    unsigned int threads;
    /** (version 3) With `tolerance` 0 and this > 0: the tolerance is this
     *  times the diagonal of the bounding box of the images of the input's
     *  vertices (which the call maps anyway: vertices 0 to vertices_in - 1
     *  of the result are those images, in order), or this itself when that
     *  diagonal is 0 or not finite. coons2stl's default is 1e-3. */
    double relative_tolerance;
} coons_deform_options;

#ifndef __cplusplus
#define COONS_DEFORM_OPTIONS_INIT {.version = COONS_DEFORM_OPTIONS_VERSION}
#else
#define COONS_DEFORM_OPTIONS_INIT COONS_RECORD_INIT_CXX_(coons_deform_options, r_.version = COONS_DEFORM_OPTIONS_VERSION)
#endif

/** Sets `*o` to ::COONS_DEFORM_OPTIONS_INIT (o NULL: nothing). */
COONS_EXPORT void coons_deform_options_init(coons_deform_options *o);

/**
 * coons_body_deform_mesh_report() with an options record, which adds a
 * progress report: the same mesh, triangle for triangle, for the same
 * body, input, frame, tolerance and budget.
 * @param[in] opts   version ::COONS_DEFORM_OPTIONS_VERSION (else
 *                   ::COONS_E_INVALID); not NULL
 * @param[out] report NULL: none; its version must be
 *                   ::COONS_DEFORM_REPORT_VERSION
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL body, mesh, options or out;
 *         an options record or report of another version; tolerance not
 *         > 0 and no relative tolerance > 0; a flat frame),
 *         ::COONS_E_DOMAIN (vertices outside the frame), ::COONS_E_LIMIT
 *         (more than max_triangles needed), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_deform(const coons_body *b, const coons_mesh *in,
                                            const coons_deform_options *opts, coons_mesh **out,
                                            coons_deform_report *report, coons_error *err);

#ifdef __cplusplus
}
#endif
#endif
