/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The mesh record, shared by the C sources of src/mesh and src/io. */
#ifndef COONS_MESH_IMPL_H
#define COONS_MESH_IMPL_H

#include "coons_internal.h"

typedef struct coons__mesh_part {
    char *name;
    size_t tri_first, tri_count;
    size_t vert_first, vert_count;
    /* Set by the sampler (sample.c); sampled = 0 for other parts. deviation
     * is NaN when it was not measured (COONS_SAMPLE_UNMEASURED). */
    int sampled;
    double tolerance, deviation;
    size_t lattice[3];
    int glued; /* bit d: the body closes on itself along direction d */
} coons__mesh_part;

struct coons_mesh {
    double *xyz;   /* 3 * nv */
    uint32_t *tri; /* 3 * nt, global vertex indices */
    size_t nv, nt, cap_v, cap_t;
    coons__mesh_part *parts;
    size_t nparts, cap_p;
};

#endif
