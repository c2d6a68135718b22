/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/types.h
 * @brief Status codes, the error record and the shared enums of libcoons.
 *
 * Every fallible function returns a ::coons_status and takes a caller-owned
 * ::coons_error pointer as its last parameter; that pointer may be NULL.
 * The library never prints, never exits and never aborts: the status and the
 * message in the error record are the whole report.
 *
 * Names (the rule in full: coons.h): constructors are
 * `coons_<object>_new_<type>` (coons_curve_new_line(), coons_body_new_body2(),
 * coons_mesh_new()), each object is released by its own `coons_<object>_free()`,
 * accessors are `coons_<object>_<attribute>` with no `get_` (coons_body_kind()),
 * every other function `coons_<object>_<verb>`.
 *
 * Arrays: every public function is called from C (C11 and later) with
 * ordinary arrays and no cast.
 * - Points: a point is `double[3]`; a fixed number of points (patch corners,
 *   body 0 corners) is one flat `const double *` of x y z triples, so that a
 *   `double c[12]` passes as it is and a `double c[4][3]` as `c[0]`.
 * - Handles: an array of objects (a patch's boundary curves, a body's edges or
 *   faces) is `coons_X *const *`: pass an ordinary array `coons_X *a[N]` of the
 *   handles the constructors returned. The function only reads the objects
 *   (constructors deep-copy them) and never changes or frees them.
 * - Outputs (`double out[3]`, `double jac[3][3]`) are caller arrays of that shape.
 */
#ifndef COONS_TYPES_H
#define COONS_TYPES_H

#include <stddef.h>
#include <stdint.h>

#include "coons/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Stable status codes. ::COONS_OK is zero, every error is negative. */
typedef enum coons_status {
    COONS_OK = 0,
    COONS_E_NOMEM = -1,       /**< an allocation failed */
    COONS_E_INVALID = -2,     /**< an argument or model value is invalid */
    COONS_E_DOMAIN = -3,      /**< a parameter lies outside its domain */
    COONS_E_IO = -4,          /**< reading or writing a file failed */
    COONS_E_PARSE = -5,       /**< the JSON text is malformed */
    COONS_E_CSG = -6,         /**< a repair or Boolean operation failed */
    COONS_E_INTERNAL = -7,    /**< a bug or an unexpected exception */
    COONS_E_LIMIT = -8,       /**< a size limit was exceeded */
    COONS_E_UNSUPPORTED = -9, /**< the feature is not built in or not available */
    COONS_E_INCOMPATIBLE = -10 /**< curves or patches that must meet do not */
} coons_status;

/** Sizes of the text fields of ::coons_error. */
#define COONS_ERROR_MESSAGE_MAX 512
#define COONS_ERROR_FILE_MAX 256
#define COONS_ERROR_PATH_MAX 256

/**
 * Caller-owned error record, filled by a failing call.
 *
 * `line` and `column` (1-based) and `path` (a JSON pointer such as
 * `/bodies/2/faces/u0`) are set by the model loader; elsewhere they are 0 and
 * empty. Initialise with ::COONS_ERROR_INIT or leave it to the first call.
 */
typedef struct coons_error {
    int code;                               /**< the ::coons_status returned */
    char message[COONS_ERROR_MESSAGE_MAX];  /**< human-readable, one line */
    char file[COONS_ERROR_FILE_MAX];        /**< model file name, or "" */
    int line;                               /**< 1-based line, or 0 */
    int column;                             /**< 1-based column, or 0 */
    char path[COONS_ERROR_PATH_MAX];        /**< JSON pointer, or "" */
} coons_error;

/*
 * The *_INIT macros of the records name the fields they set: in C a
 * designated initialiser (every other field zero); C++17 has none, so there
 * the record is value-initialised (all zero) and the same fields are set.
 */
#ifdef __cplusplus
#define COONS_RECORD_INIT_CXX_(type, ...) ([] { type r_{}; __VA_ARGS__; return r_; }())
#endif

#ifndef __cplusplus
#define COONS_ERROR_INIT {.code = COONS_OK}
#else
#define COONS_ERROR_INIT COONS_RECORD_INIT_CXX_(coons_error, r_.code = COONS_OK)
#endif

/** Blending functions of Coons patches and bodies (seed 001 section 1.2). */
typedef enum coons_blend {
    COONS_BLEND_LINEAR = 0, /**< 1-t and t */
    COONS_BLEND_CUBIC = 1   /**< f(t) = 1 - 3t^2 + 2t^3 and 1 - f(t) */
} coons_blend;

/** Opaque handles. Each is freed with its own coons_X_free(), which accepts NULL. */
typedef struct coons_curve coons_curve;
typedef struct coons_patch coons_patch;
typedef struct coons_body coons_body;
typedef struct coons_model coons_model;
typedef struct coons_mesh coons_mesh;

/**
 * Progress callback of the options records that take one (repair and union,
 * coons/csg.h; volume meshes, coons/volume.h): `stage` names the step
 * ("sample", "autorefine", "check", "evaluate", ...), `fraction` in [0,1]
 * is the share of that step's work done. Called from the calling thread;
 * keep it cheap; it must not call back into the library.
 */
typedef void (*coons_progress_fn)(void *userdata, const char *stage, double fraction);

/**
 * Returns a static, never-NULL English description of a status code.
 */
COONS_EXPORT const char *coons_strerror(int code);

/**
 * Replaces the allocator used by all C code of the library.
 *
 * Call it once, before any other call; it is not thread-safe. Passing NULL
 * for all three restores malloc/realloc/free. Allocations made inside the
 * C++ layers (OpenMesh, CGAL) do not go through these hooks.
 */
COONS_EXPORT void coons_set_allocator(void *(*malloc_fn)(size_t),
                                      void *(*realloc_fn)(void *, size_t),
                                      void (*free_fn)(void *));

/** Runtime version number (major*10000 + minor*100 + patch). */
COONS_EXPORT int coons_version(void);
/** Runtime version string, e.g. "0.3.0". */
COONS_EXPORT const char *coons_version_string(void);

#ifdef __cplusplus
}
#endif
#endif
