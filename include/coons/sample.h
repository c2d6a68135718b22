/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/sample.h
 * @brief Sampling bodies and models into closed boundary meshes.
 *
 * The options of a sampling (::coons_sample_options), the samplers
 * coons_body_sample() and coons_model_sample(), and what they record per
 * part (coons_mesh_part_sampling(), coons_mesh_deviation()).
 */
#ifndef COONS_SAMPLE_H
#define COONS_SAMPLE_H

#include "coons/types.h"
#include "coons/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Default largest side ratio of the cells of the starting lattice. */
#define COONS_SAMPLE_DEFAULT_MAX_ASPECT 4.0

/** Version of ::coons_sample_options this header describes. Version 2:
 *  `progress` and `userdata`; version 3: `threads`. Records of versions 1
 *  and 2 are still accepted (as one thread). */
#define COONS_SAMPLE_OPTIONS_VERSION 3

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
    /** (version 3) Threads that evaluate and measure a body: 0 or 1, the
     *  calling thread only (the default); N > 1, N threads (at most
     *  1024). The mesh does not depend on it, byte for byte. With more than
     *  one, progress is still reported from the calling thread, and an
     *  allocator set with coons_set_allocator() must be thread-safe. */
    unsigned int threads;
} coons_sample_options;

/**
 * Flag of ::coons_sample_options: with a fixed `resolution`, skip measuring
 * the deviation (it then reads NaN). The measurement of a fixed lattice is
 * cheap (about four evaluations per lattice point: see coons_body_sample()).
 * Adaptive sampling always measures.
 */
#define COONS_SAMPLE_UNMEASURED 1u

#ifndef __cplusplus
#define COONS_SAMPLE_OPTIONS_INIT {.version = COONS_SAMPLE_OPTIONS_VERSION}
#else
#define COONS_SAMPLE_OPTIONS_INIT COONS_RECORD_INIT_CXX_(coons_sample_options, r_.version = COONS_SAMPLE_OPTIONS_VERSION)
#endif

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
 * `resolution` it is measured, not enforced, and cheaply: on the 3 x 3
 * samples of every cell (edge midpoints and centre), and where those find
 * more than half the tolerance on the 7 x 7 samples above.
 *
 * A morph (coons_body_new_morph(), also transformed) is sampled at its
 * current time on the one lattice and face list of its whole path, as
 * coons_model_sample() describes: the same mesh at every time.
 *
 * @param[in]  b     the body (not modified)
 * @param[in]  opts  NULL or options (see ::coons_sample_options)
 * @param[in]  name  the part's name (copied), or NULL
 * @param[out] out   the new mesh, owned by the caller (coons_mesh_free())
 * @return ::COONS_OK; ::COONS_E_INVALID (bad options, a body that
 *         evaluates to a non-finite point, or whose boundary collapses
 *         entirely); ::COONS_E_LIMIT (more triangles than `max_triangles`
 *         would be needed; the message says the limit and how to raise
 *         it, and for a tolerance the predicted count and a tolerance to
 *         try that was sampled within the limit before it is named);
 *         ::COONS_E_NOMEM. Thread-safe for distinct outputs.
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
 *
 * A morph body (also a transformed one) is one mesh at every time: it is
 * sampled on one uniform lattice and face list for its whole path, those
 * of coons_model_write_scad_animation() with the same `opts`, at its
 * current time (coons_model_set_time()); its part's deviation is the
 * largest measured over the path's check times (with `resolution` set:
 * measured at this time, unless ::COONS_SAMPLE_UNMEASURED). A morph whose
 * lattice collapses differently at different times, or whose boundary
 * collapses entirely at a time the plan samples, has no such mesh and is
 * sampled at its time alone.
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

#ifdef __cplusplus
}
#endif
#endif
