/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/csg.h
 * @brief Repair and union of body shells into valid solids (CGAL layer).
 *
 * A body's solid is the set of points around which its boundary surface has
 * a non-zero winding number (model format, "Solids and outputs"). A sampled
 * shell of a folded body crosses itself; these functions return the
 * boundary of the solid it bounds, and of the union of several solids.
 *
 * Method: a body that meets nothing and does not cross itself passes
 * through. Bodies that do not cross themselves are united by chained
 * corefinement (first with inexact constructions, kept only when the exact
 * check of the result is clean; else on CGAL's exact-constructions kernel).
 * A body that crosses itself is repaired first by an exact soup pass: the
 * shell is autorefined (every intersection becomes a mesh edge), cut into
 * patches along the intersection curves, and each patch is classified by
 * exact ray casting: it is kept when the winding numbers on its two sides
 * make exactly one side belong to a solid, oriented towards the other side.
 * The same pass unites bodies that corefinement refuses. Coincident faces
 * (bodies sharing a face) vanish. Exact results are rounded to doubles once
 * and checked again for self-intersections with exact predicates; a
 * rounding that leaves an intersection is an error, never a silent result.
 *
 * Available only when libcoons is built with CGAL (GPL-3.0-or-later);
 * otherwise every function returns ::COONS_E_UNSUPPORTED.
 * Memory of the C++ layer is not allocated through coons_set_allocator().
 */
#ifndef COONS_CSG_H
#define COONS_CSG_H

#include "coons/types.h"
#include "coons/mesh.h"
#include "coons/sample.h"
#include "coons/model.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Options of coons_mesh_solidify(). Initialise with ::COONS_CSG_OPTIONS_INIT. */
typedef struct coons_csg_options {
    unsigned version;           /**< ::COONS_CSG_OPTIONS_VERSION */
    int unite;                  /**< nonzero: unite all parts into one solid */
    int repair;                 /**< nonzero: resolve a part's self-intersections (default);
                                     0: a part that meets no other passes unchecked */
    const char *name;           /**< name of the united part (NULL: "union") */
    coons_progress_fn progress; /**< NULL: no progress reports */
    void *userdata;             /**< passed to progress */
    unsigned threads;           /**< (version 3) threads for sampling the bodies
                                     (coons_model_solidify()), the checks and the
                                     unions of groups of bodies that do not meet;
                                     0 or 1: the calling thread only (default). The
                                     result does not depend on it, byte for byte.
                                     With more, progress is still reported from the
                                     calling thread, and an allocator set with
                                     coons_set_allocator() must be thread-safe */
} coons_csg_options;

/** Version 2: the testing field `inject_failure` of version 1 is gone.
 *  Version 3: `threads`; records of version 2 are still accepted (as one thread). */
#define COONS_CSG_OPTIONS_VERSION 3
#ifndef __cplusplus
#define COONS_CSG_OPTIONS_INIT {.version = COONS_CSG_OPTIONS_VERSION, .unite = 1, .repair = 1, .threads = 1}
#else
#define COONS_CSG_OPTIONS_INIT COONS_RECORD_INIT_CXX_(coons_csg_options, r_.version = COONS_CSG_OPTIONS_VERSION, r_.unite = 1, r_.repair = 1, r_.threads = 1)
#endif

/**
 * Sets `*o` to ::COONS_CSG_OPTIONS_INIT (for language bindings that cannot
 * use the macro); NULL is a harmless no-op.
 */
COONS_EXPORT void coons_csg_options_init(coons_csg_options *o);

/** Version 3: adds `tolerance` and `deviation` (model solids); version 2
 *  added `pinch_edges_split` and `pinch_vertices_split`. Records of
 *  versions 1 and 2 (without them) are still accepted and filled. */
#define COONS_CSG_REPORT_VERSION 3

/**
 * What coons_mesh_solidify() found and did. The caller sets `version` (use
 * ::COONS_CSG_REPORT_INIT or coons_csg_report_init()); the rest is output.
 */
typedef struct coons_csg_report {
    unsigned version;           /**< in: ::COONS_CSG_REPORT_VERSION */
    size_t triangles_in;        /**< triangles of the input */
    size_t degenerate_dropped;  /**< zero-area triangles dropped */
    size_t intersecting_pairs;  /**< self-intersecting triangle pairs found in the input */
    size_t parts_in;            /**< input parts (bodies) */
    size_t groups;              /**< groups of parts whose bounding boxes overlap */
    size_t passed_through;      /**< parts that needed no Boolean work */
    size_t patches;             /**< patches classified by ray casting */
    size_t patches_kept;        /**< of which kept */
    size_t fast_unions;         /**< groups united on the inexact-constructions kernel, result verified */
    size_t fallbacks;           /**< groups the corefinement refused, done by the soup pass */
    size_t triangles_out;       /**< triangles of the result */
    size_t rounding_merged;     /**< vertices merged by rounding to double */
    size_t close_merged;        /**< vertices within 1e-11 of the size of another, merged */
    size_t slivers_fixed;       /**< triangles flattened by rounding, removed by an edge split */
    int closed;                 /**< the result has no border edge */
    size_t nonmanifold_edges;   /**< edges with more than two faces in the result */
    size_t pinch_edges_split;   /**< edges of 2k > 2 faces (solids touching along a curve)
                                     split into k edges of two faces each (model solids) */
    size_t pinch_vertices_split; /**< vertices whose triangles formed more than one fan,
                                      written once per fan (copies moved apart slightly) */
    /** Model solids (coons_model_solidify(), coons_model_solidify_body()):
     *  the tolerance the bodies were sampled to; 0 otherwise. */
    double tolerance;
    /** Model solids: the largest deviation measured on the sampled bodies
     *  (coons_mesh_deviation() of the sampled shells: NaN when not measured,
     *  see ::COONS_SAMPLE_UNMEASURED); above `tolerance` only with a fixed
     *  `resolution`. 0 otherwise. */
    double deviation;
} coons_csg_report;

#ifndef __cplusplus
#define COONS_CSG_REPORT_INIT {.version = COONS_CSG_REPORT_VERSION}
#else
#define COONS_CSG_REPORT_INIT COONS_RECORD_INIT_CXX_(coons_csg_report, r_.version = COONS_CSG_REPORT_VERSION)
#endif

/**
 * Sets `*r` to ::COONS_CSG_REPORT_INIT; NULL is a harmless no-op.
 */
COONS_EXPORT void coons_csg_report_init(coons_csg_report *r);

/**
 * Turns the parts of `in` (closed shells, one per body, possibly crossing
 * themselves or each other) into valid solids: each part repaired on its
 * own (`opts->unite` = 0), or all united into one part. Parts whose
 * bounding boxes meet nothing else and that do not cross themselves pass
 * through unchanged.
 * @param[in]  opts   NULL for ::COONS_CSG_OPTIONS_INIT
 * @param[out] out    the new mesh (caller frees)
 * @param[in,out] report may be NULL; else its `version` must be
 *                ::COONS_CSG_REPORT_VERSION
 * @return ::COONS_OK; ::COONS_E_INVALID when `opts` or `report` has another
 *         version; ::COONS_E_CSG when CGAL cannot complete (the message
 *         names the parts and the reason); ::COONS_E_UNSUPPORTED without
 *         CGAL; ::COONS_E_NOMEM; ::COONS_E_INTERNAL.
 */
COONS_EXPORT coons_status coons_mesh_solidify(const coons_mesh *in, const coons_csg_options *opts,
                                              coons_mesh **out, coons_csg_report *report,
                                              coons_error *err);

/**
 * Counts pairs of triangles of `m` that intersect other than along shared
 * edges or at shared vertices (CGAL's does_self_intersect, exact
 * predicates on the double coordinates).
 * @return ::COONS_OK, ::COONS_E_UNSUPPORTED without CGAL, ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_mesh_count_self_intersections(const coons_mesh *m, size_t *pairs,
                                                              coons_error *err);

/**
 * As coons_mesh_count_self_intersections(), after rounding every coordinate to
 * float32 as binary STL stores it.
 * @return ::COONS_OK, ::COONS_E_UNSUPPORTED without CGAL, ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_mesh_count_self_intersections_float(const coons_mesh *m, size_t *pairs,
                                                                    coons_error *err);

/**
 * coons_mesh_count_self_intersections() (`rounded` 0) or
 * coons_mesh_count_self_intersections_float() (`rounded` 1) on `threads`
 * threads (0 or 1: the calling thread only); the count does not depend on
 * them. An allocator set with coons_set_allocator() must be thread-safe.
 * @return as those: ::COONS_OK, ::COONS_E_UNSUPPORTED without CGAL,
 *         ::COONS_E_LIMIT (rounded: a coordinate beyond float32),
 *         ::COONS_E_NOMEM; ::COONS_E_INVALID for `rounded` other than 0 or 1.
 */
COONS_EXPORT coons_status coons_mesh_count_self_intersections_threads(const coons_mesh *m,
                                                                      int rounded,
                                                                      unsigned threads,
                                                                      size_t *pairs,
                                                                      coons_error *err);

/**
 * Samples every body of a model (see coons_model_sample()) and makes the
 * model's solid: with operation "union" the boundary of the union of all
 * bodies' solids as one part named after `copts->name` (default "union"),
 * with "none" each body's solid as its own part. Bodies that meet nothing
 * else and do not cross themselves are written as sampled.
 * With CGAL, every part of the result is a 2-manifold: where the solid
 * touches itself along a curve or at a point (a repaired fold whose
 * sheets touch, bodies meeting along an edge), each edge of 2k > 2
 * triangles is split into k edges, pairing the triangles around it that
 * bound the same wedge of solid, and each vertex whose triangles form
 * several fans is written once per fan, the copies moved apart into their
 * own fans' solids by 1e-3 of the shortest edge there, so that readers
 * that weld by position see a 2-manifold too; kept only when the exact
 * count then finds no crossing (report: `pinch_edges_split`,
 * `pinch_vertices_split`; `nonmanifold_edges` is what is left).
 * coons_mesh_solidify() itself leaves pinches as they are.
 * @param[in] sopts  sampling options (NULL: defaults, model tolerance)
 * @param[in] copts  repair/union options (NULL: defaults); its `unite`
 *                   field is ignored: the model's operation decides. Its
 *                   `progress` also hears the stage "sample" before each
 *                   body, with the share of bodies sampled (i / count, then
 *                   1), before the stages of coons_mesh_solidify(), whose
 *                   fraction starts again from 0; with `threads` > 1 the
 *                   bodies are sampled at once and the calling thread
 *                   reports "sample" i / count each time body i becomes
 *                   the first one (in body order) still being sampled
 * @param[in,out] report may be NULL; else its `version` must be
 *                ::COONS_CSG_REPORT_VERSION; its output fields are zeroed
 *                when no CGAL work was needed
 * @return as coons_model_sample() and coons_mesh_solidify() (::COONS_E_INVALID
 *         for a wrong `copts` or `report` version); without CGAL,
 *         ::COONS_E_UNSUPPORTED when bodies overlap or touch under "union" or
 *         repair is asked for a body that crosses itself cannot be checked
 *         (without CGAL no check is made: shells are written as sampled).
 */
COONS_EXPORT coons_status coons_model_solidify(const coons_model *model,
                                               const coons_sample_options *sopts,
                                               const coons_csg_options *copts, coons_mesh **out,
                                               coons_csg_report *report, coons_error *err);

/**
 * The solid of one body of a model, alone: body `index` sampled as
 * coons_model_solidify() samples it (the model's tolerance unless `sopts`
 * sets one) and repaired on its own; the model's operation is not applied
 * (one body needs no union). Without CGAL the shell is returned as sampled.
 * Pinches are split as coons_model_solidify() splits them.
 * This is what coons2stl --body writes.
 * @param[in] index  0-based body index, below coons_model_body_count()
 * @param[in] sopts  sampling options (NULL: defaults, model tolerance)
 * @param[in] copts  repair options (NULL: defaults); `unite` is ignored.
 *                   Its `progress` hears the stage "sample" once before the
 *                   body, with the fraction index / count, then 1, before
 *                   the stages of coons_mesh_solidify()
 * @param[out] out    the new mesh, one part named after the body (caller frees)
 * @param[out] report may be NULL; zeroed when no CGAL work was done
 * @return ::COONS_OK; ::COONS_E_INVALID for an index out of range; else as
 *         coons_body_sample() and coons_mesh_solidify().
 */
COONS_EXPORT coons_status coons_model_solidify_body(const coons_model *model, size_t index,
                                                 const coons_sample_options *sopts,
                                                 const coons_csg_options *copts,
                                                 coons_mesh **out, coons_csg_report *report,
                                                 coons_error *err);

/** 1 when the library was built with CGAL (repair and union available). */
COONS_EXPORT int coons_csg_is_available(void);

#ifdef __cplusplus
}
#endif
#endif
