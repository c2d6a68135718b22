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

/**
 * Loads a model file. On error, err carries the file, line, column and JSON
 * path of the offending value and what was expected.
 * @param[in] path a file name ("-" is not special here)
 * @return ::COONS_OK, ::COONS_E_IO, ::COONS_E_PARSE, ::COONS_E_INVALID,
 *         ::COONS_E_INCOMPATIBLE, ::COONS_E_LIMIT, ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_model_load(const char *path, coons_model **out,
                                           coons_error *err);

/**
 * Loads a model from memory. `name` is used as the file name in messages
 * (NULL: "<buffer>"). The buffer need not be NUL-terminated.
 */
COONS_EXPORT coons_status coons_model_load_buffer(const char *data, size_t size,
                                                  const char *name, coons_model **out,
                                                  coons_error *err);

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

#ifdef __cplusplus
}
#endif
#endif
