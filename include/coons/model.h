/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/model.h
 * @brief Model files (format version 1, see coons-model(5)): loading and
 *        access to the bodies they describe.
 */
#ifndef COONS_MODEL_H
#define COONS_MODEL_H

#include "coons/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** What a model's bodies become on output. */
typedef enum coons_operation {
    COONS_OP_UNION = 0, /**< the boundary of the union of all bodies */
    COONS_OP_NONE = 1   /**< each body's own closed shell */
} coons_operation;

/** Default size limits of the loader (see ::coons_model_load_options). */
#define COONS_MODEL_MAX_BYTES ((size_t)256 << 20)
#define COONS_MODEL_MAX_VALUES ((size_t)1 << 23)
#define COONS_MODEL_MAX_DEPTH 64u
#define COONS_MODEL_MAX_POINTS ((size_t)1000000)
/**
 * The sizes of model (the diagonal of its control points' box) the library
 * supports: within them every tolerance is relative to the size and a model
 * meshes to the same triangles, up to scale, at every size; outside them
 * loading fails with ::COONS_E_LIMIT naming the size.
 */
#define COONS_MODEL_MIN_SIZE 1e-150
#define COONS_MODEL_MAX_SIZE 1e150

/**
 * Limits that guard the loader's allocations; exceeding one gives
 * ::COONS_E_LIMIT with a message that names the limit and how to raise it
 * (the field, and the coons2stl option). A field left 0 takes
 * the default. Initialise with ::COONS_MODEL_LOAD_OPTIONS_INIT.
 */
typedef struct coons_model_load_options {
    unsigned version;  /**< ::COONS_MODEL_LOAD_OPTIONS_VERSION */
    size_t max_bytes;  /**< size of the text; default ::COONS_MODEL_MAX_BYTES (256 MiB) */
    size_t max_values; /**< JSON values, keys included; default ::COONS_MODEL_MAX_VALUES */
    unsigned max_depth; /**< nesting of arrays and objects; default 64, at most 256 */
    size_t max_points; /**< points of one curve, surface or volume net; default 10^6 */
} coons_model_load_options;

#define COONS_MODEL_LOAD_OPTIONS_VERSION 1
#ifndef __cplusplus
#define COONS_MODEL_LOAD_OPTIONS_INIT {.version = COONS_MODEL_LOAD_OPTIONS_VERSION}
#else
#define COONS_MODEL_LOAD_OPTIONS_INIT COONS_RECORD_INIT_CXX_(coons_model_load_options, r_.version = COONS_MODEL_LOAD_OPTIONS_VERSION)
#endif

/**
 * Sets `*o` to ::COONS_MODEL_LOAD_OPTIONS_INIT (for language bindings that
 * cannot use the macro); NULL is a harmless no-op.
 */
COONS_EXPORT void coons_model_load_options_init(coons_model_load_options *o);

/**
 * Loads a model file. On error, err carries the file, line, column and JSON
 * path of the offending value and what was expected.
 *
 * The loader is strict (coons-model(5)): unknown or repeated keys, values
 * of the wrong type, non-finite numbers, invalid UTF-8 and text after the
 * top-level object are errors. Every error fills `err->file`, `err->line`
 * and `err->column` (1-based; the column counts UTF-8 code points) of the
 * start of the offending value, `err->path` (its JSON pointer, RFC 6901,
 * "" for the whole document) and `err->message`, which repeats them in the
 * form "FILE:LINE:COL: PATH: what was expected" so that it can be printed
 * alone. Errors about the file as a whole (it cannot be read, it is too
 * large) have line and column 0 and the message "FILE: ...".
 *
 * Agreement checks (patch corners, body 1 corners, body 2 shared edges,
 * Hermite cross tangents) use 1e-9 times the diagonal of the box of all
 * control points of the model (points, not tangents or twists); a
 * disagreement is reported at the first of the two values in the order of
 * the format's description, and the message names both and the distance.
 *
 * Numbers are read independently of the process locale.
 * @param[in] path a file name ("-" is not special here)
 * @param[in] opts the loader's limits; NULL means the defaults; a `version`
 *                 other than ::COONS_MODEL_LOAD_OPTIONS_VERSION is ::COONS_E_INVALID
 * @param[out] out the model, owned by the caller (coons_model_free())
 * @return ::COONS_OK, ::COONS_E_IO (with strerror's text), ::COONS_E_PARSE
 *         (malformed JSON), ::COONS_E_INVALID (a value the format does not
 *         allow), ::COONS_E_UNSUPPORTED ("coons" is not 1),
 *         ::COONS_E_INCOMPATIBLE (curves or faces that must meet do not),
 *         ::COONS_E_LIMIT (a limit of ::coons_model_load_options),
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_model_load_file(const char *path,
                                                const coons_model_load_options *opts,
                                                coons_model **out, coons_error *err);

/**
 * Loads a model from memory, like coons_model_load_file(). `name` is used as
 * the file name in messages (NULL: "<buffer>"). The buffer need not be
 * NUL-terminated and is not kept.
 * @return as coons_model_load_file() without ::COONS_E_IO: ::COONS_OK,
 *         ::COONS_E_PARSE, ::COONS_E_INVALID (also `data` NULL),
 *         ::COONS_E_UNSUPPORTED, ::COONS_E_INCOMPATIBLE, ::COONS_E_LIMIT,
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_model_load_memory(const char *data, size_t size,
                                                  const char *name,
                                                  const coons_model_load_options *opts,
                                                  coons_model **out, coons_error *err);

/** Releases a model and every body it owns; NULL is a harmless no-op. */
COONS_EXPORT void coons_model_free(coons_model *m);

/** Number of bodies (>= 1). */
COONS_EXPORT size_t coons_model_body_count(const coons_model *m);

/** Borrowed body i, valid until the model is freed; NULL if out of range. */
COONS_EXPORT const coons_body *coons_model_body(const coons_model *m, size_t i);

/** Name of body i: its "name", or "body<i>" when it has none. */
COONS_EXPORT const char *coons_model_body_name(const coons_model *m, size_t i);

/** Index of the body with that name, or -1. */
COONS_EXPORT long coons_model_find_body(const coons_model *m, const char *name);

/** The tolerance: the model's "tolerance", or 1/1000 of the control box diagonal. */
COONS_EXPORT double coons_model_tolerance(const coons_model *m);

/** The "units" string ("mm" by default). */
COONS_EXPORT const char *coons_model_units(const coons_model *m);

COONS_EXPORT coons_operation coons_model_operation(const coons_model *m);

/** Box of all control points of the model. */
COONS_EXPORT void coons_model_control_bbox(const coons_model *m, double lo[3], double hi[3]);

/**
 * A face shared by two bodies (coons-model(5), "Bodies that share faces":
 * the same map up to one of the 8 symmetries of the unit square, within
 * 1e-9 of the model's control box diagonal, found by geometry), with the
 * continuity across it.
 */
typedef struct coons_interface {
    size_t body[2];  /**< body indices, body[0] < body[1] */
    int face[2];     /**< their faces, 0..5 = u0 u1 v0 v1 w0 w1 */
    /** How face[1]'s parameters (a', b') follow face[0]'s (a, b) (each face's
     *  two other parameters in increasing order): swapped if bit 1, then
     *  a' -> 1 - a' if bit 2, b' -> 1 - b' if bit 4. */
    int orientation;
    /** Largest |dB/dn - dA/dn| over a 9 x 9 grid of the face, relative to
     *  the larger of the two; dA/dn, dB/dn are the two bodies' derivatives
     *  along their parameter across the face, both pointing from body[0]
     *  into body[1]. 0: the bodies join C1 in their parameters. */
    double c1_defect;
    /** Largest angle, in degrees, over the same points and both face
     *  parameter lines, between the two bodies' tangent planes along the
     *  line: the plane of the line's tangent and dA/dn against the plane of
     *  the tangent and dB/dn. 0: the bodies join G1. */
    double g1_angle;
} coons_interface;

/**
 * The faces shared by the model's bodies, in the order found. `*out` is
 * freed with coons_interfaces_free(); NULL with `*count` 0 when there are
 * none.
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL arguments), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_model_interfaces(const coons_model *m, coons_interface **out,
                                                 size_t *count, coons_error *err);

/** Frees a list from coons_model_interfaces(); NULL is a harmless no-op. */
COONS_EXPORT void coons_interfaces_free(coons_interface *list);

/**
 * Takes every morph body of the model (coons_body_new_morph()) at time t
 * instead of its own "t": also morphs that are keys of other morphs and
 * morphs reached through references or transforms (coons2stl --time T).
 * Changes the model in place: not while another thread uses it. Nothing
 * else depends on the time (the control box and the tolerance are those
 * of all keys), so a model can be set to one time after another.
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL model, t not in [0,1]; the
 *         model is then unchanged).
 */
COONS_EXPORT coons_status coons_model_set_time(coons_model *m, double t, coons_error *err);

/** The number of the model's bodies that are morphs (also transformed
 * morphs); morphs that are only keys of others do not count. */
COONS_EXPORT size_t coons_model_morph_count(const coons_model *m);

#ifdef __cplusplus
}
#endif
#endif
