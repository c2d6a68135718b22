/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The model stage's internal interface (model_mesh.c), shared by
 * model_mesh.c and model_solid.c. Plain C. */
#ifndef COONS_MODEL_GLUE_H
#define COONS_MODEL_GLUE_H

#include "sampling.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Samples every body of a model into one mesh, a part per body, within one
 * triangle budget; *tolerance receives the tolerance used. `progress`
 * (may be NULL) hears the stage "sample" before each body with the share
 * of bodies done (i / count), and 1 at the end. */
coons_status coons__model_sample(const coons_model *model, const coons_sample_options *opts,
                                 void (*progress)(void *, const char *, double),
                                 void *userdata, coons_mesh **out, double *tolerance,
                                 coons_error *err);
/* coons__model_sample() on up to `threads` threads (0, 1: this one), one
 * body (or group of bodies joined by shared faces) per thread at a time;
 * the same mesh, byte for byte, whatever the number. */
coons_status coons__model_sample_threads(const coons_model *model,
                                         const coons_sample_options *opts,
                                         void (*progress)(void *, const char *, double),
                                         void *userdata, unsigned threads, coons_mesh **out,
                                         double *tolerance, coons_error *err);
/* 1 and the first pair (i < j) of parts whose sampled boxes, grown by 2 tol,
 * meet; 0 when all are apart. */
int coons__parts_meet(const coons_mesh *m, double tol, size_t *i, size_t *j);
/* The error for a union that needs CGAL in a build without it. */
coons_status coons__union_unavailable(const coons_mesh *m, size_t i, size_t j, coons_error *err);

#ifdef __cplusplus
}
#endif
#endif
