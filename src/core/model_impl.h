/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The model record, filled by the loader (src/io/json/loader.h). Internal. */
#ifndef COONS_MODEL_IMPL_H
#define COONS_MODEL_IMPL_H

#include "coons_internal.h"

struct coons_model {
    size_t nbodies;
    coons_body **bodies; /* owned */
    char **names;        /* owned; the body's "name", or "body<i>" */
    unsigned char *named; /* 1 where the name was given in the file */
    char *units;         /* owned */
    double tolerance;    /* > 0 */
    coons_operation operation;
    double lo[3], hi[3]; /* box of all control points (points, not tangents) */
};

/* An empty model with room for n bodies (all NULL), units NULL. */
coons_status coons__model_alloc(size_t n, coons_model **out, coons_error *err);

#endif
