/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The one lattice and face list of a morph's whole path (morph_lattice.c;
 * seed 000 section 4, outputs.md "Metamorphosis"), which every output of
 * a morph uses: -o at the file's t, --time T, frame k of --frames, and the
 * OpenSCAD animation (src/io/write/scad_morph.c, which writes the keys'
 * vertex arrays of the tree below). Internal. */
#ifndef COONS_MORPH_LATTICE_H
#define COONS_MORPH_LATTICE_H

#include "sampling.h"

/* A node of a morph body's tree: what gives one vertex array on the
 * lattice. A constant node (no morph below it) holds its points; an
 * affine node applies its body's transform to the node `inner`; a morph
 * node blends the nodes `keys` (one per key, in key order). The last node
 * of a tree is its root. */
enum { COONS__MORPH_CONST, COONS__MORPH_AFFINE, COONS__MORPH_BLEND };
typedef struct coons__morph_node {
    int kind;
    const coons_body *b;
    double *pts;  /* CONST: 3 nv, the body grid evaluator at each vertex */
    size_t inner; /* AFFINE: the wrapped node */
    size_t *keys; /* BLEND: one node per key */
} coons__morph_node;

typedef struct coons__morph_lattice {
    unsigned n;        /* intervals along u, v and w (uniform) */
    size_t nv, nt;
    uint32_t *tri;     /* 3 nt, counter-clockwise seen from outside */
    double *uvw;       /* 3 nv: each vertex's (u, v, w) */
    int glued;         /* bit d: the body closes on itself along d */
    double deviation;  /* the worst measured over the path; NaN when the
                          lattice was given (resolution) */
    coons__morph_node *nodes; /* coons__morph_lattice_tree(); else NULL */
    size_t nn, cap;
} coons__morph_lattice;

/* 1 when b is a morph or wraps one (transforms), 0 otherwise. */
int coons__body_has_morph(const coons_body *b);

/* Plans the lattice of morph body b for its whole path, whatever b's own
 * time: uniform, n intervals along u, v and w; n = o->resolution when set,
 * else the smallest n, from the largest adaptive lattice count at the check
 * times up in steps of 1/4, whose mesh (the fixed face list with each
 * frame's vertices) is within o->tolerance at every check time (the key
 * times and 4 times inside each interval between keys, measured at 7
 * points of every triangle: edge midpoints, centroid, and halfway between
 * the centroid and the corners). The face list is the sampler's at time
 * 1/2; vertices merge only where they merge at every key time too.
 * @return COONS_OK, COONS_E_LIMIT (o->max_triangles), COONS_E_UNSUPPORTED
 *         (the lattice collapses differently at some key time: no one face
 *         list serves every frame), COONS_E_NOMEM, or a sampler error. */
coons_status coons__morph_lattice_plan(const coons_body *b, const coons__sample_opts *o,
                                       const char *name, coons__morph_lattice *L,
                                       coons_error *err);

/* The vertex arrays of b's tree on L (L->nodes, L->nn). */
coons_status coons__morph_lattice_tree(coons__morph_lattice *L, const coons_body *b,
                                       coons_error *err);

/* Releases what L holds and zeroes it; a zeroed L is a harmless no-op. */
void coons__morph_lattice_free(coons__morph_lattice *L);

/* Samples body b as one part of `mesh`: a body with a morph on the lattice
 * and faces of its whole path (coons__morph_lattice_plan()), its vertices
 * those of b at its own time (the body grid evaluator at each vertex:
 * bitwise the points of the uniform lattice n, hence what OpenSCAD's $t
 * gives of the animation to the printed digits); any other body, and a
 * morph whose plan is refused (COONS_E_UNSUPPORTED, or COONS_E_INVALID: a
 * frame of the plan has no boundary), by coons__body_sample_into().
 * *triangles gets the part's count. */
coons_status coons__body_sample_path(const coons_body *b, const coons__sample_opts *o,
                                     const char *name, coons_mesh *mesh, size_t *triangles,
                                     coons_error *err);

#endif
