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
    int has_params; /* m->uvw holds this part's vertex parameters */
} coons__mesh_part;

struct coons_mesh {
    double *xyz;   /* 3 * nv */
    uint32_t *tri; /* 3 * nt, global vertex indices */
    size_t nv, nt, cap_v, cap_t;
    coons__mesh_part *parts;
    size_t nparts, cap_p;
    /* 3 * nv body parameters (u, v, w) per vertex once a part with them was
     * added (NaN for the vertices of parts without), else NULL. */
    double *uvw;
    size_t cap_uvw;
};

/* coons_mesh_add_part() with the (u, v, w) of each vertex (uvw: 3 * nv
 * doubles, or NULL for none). Leaves the mesh unchanged on failure. */
coons_status coons__mesh_add_part_uvw(coons_mesh *m, const char *name, const double *xyz,
                                      const double *uvw, size_t nv, const uint32_t *tri,
                                      size_t nt, coons_error *err);

#endif
