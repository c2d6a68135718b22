/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The state of one lattice volume mesh (lattice.c), shared with the part
 * that makes bodies of a control lattice meet conformally
 * (lattice_conform.c): the bodies' lattices, their raw node lattice points
 * and the union-find that joins coincident ones. */
#ifndef COONS_LATTICE_IMPL_H
#define COONS_LATTICE_IMPL_H

#include "coons_internal.h"
#include "union_find.h"
#include "volume_impl.h"

typedef struct coons__vbody {
    const coons_body *b;
    const char *name;
    double *t[3];  /* cell lattice values, n[d] + 1 of them */
    double *L[3];  /* node lattice values, m[d] of them */
    size_t n[3];   /* cell intervals */
    size_t m[3];   /* node lattice points: step * n + 1 */
    size_t base;   /* first raw id */
    int left;      /* left-handed: cells mirrored in r */
    double lo[3], hi[3]; /* box of its points */
} coons__vbody;

typedef struct coons__vbuild {
    coons_element el;
    int step;        /* 1 (hex8) or 2: node lattice index per cell interval */
    size_t npc;
    coons__vbody *vb;
    size_t nb;
    size_t nraw;
    double *pos;     /* 3 * nraw */
    uint32_t *uf;    /* nraw */
    uint32_t *id;    /* nraw: final node of a representative, UINT32_MAX if unused */
    size_t nn;       /* final nodes */
    coons_error *err;
    coons_progress_fn progress; /* the options' (version 2), or NULL */
    void *userdata;
    unsigned threads; /* the options' (version 3), at least 1 */
} coons__vbuild;

/* Raw id of node lattice point (a, b, c) of body B (coons_body_eval_grid's
 * order: u slowest). */
static inline size_t coons__vraw(const coons__vbody *B, size_t a, size_t b, size_t c)
{
    return B->base + (a * B->m[1] + b) * B->m[2] + c;
}

/* Whether a node lattice point is a node of some cell: hex20 uses corners
 * and edge midpoints (at most one odd index), the others every point. */
static inline int coons__vneeded(const coons__vbuild *v, size_t a, size_t b, size_t c)
{
    return v->el != COONS_ELEMENT_HEX20 || (a & 1) + (b & 1) + (c & 1) <= 1;
}

/* Node of lattice point (a, b, c): its representative's final id. The
 * union-find is flat once the points are merged (every entry its root,
 * lattice.c), so this only reads, and threads may call it at once. */
static inline uint32_t coons__vnode(const coons__vbuild *v, const coons__vbody *B, size_t a,
                                    size_t b, size_t c)
{
    return v->id[v->uf[coons__vraw(B, a, b, c)]];
}

/* Gives the directions that shared faces and shared edges tie one lattice
 * (lattice_conform.c), before the node lattices are made. */
coons_status coons__vlattice_share(coons__vbuild *v);

/* Refuses bodies that touch or overlap other than along whole shared
 * faces, whole shared edges or at corners (lattice_conform.c), once the
 * mesh's nodes, cells and sets are made. */
coons_status coons__vlattice_check(coons__vbuild *v, const coons_volume_mesh *vm);

#endif
