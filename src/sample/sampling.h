/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The sampling stage's internal interface for the stages after it (volume,
 * write, model): resolved sampling options, faces shared by bodies, the
 * lattice a body is sampled on, and sampling into a mesh (sample.c,
 * shared_faces.c, lattice_share.c, sample_lattice.c). Plain C. */
#ifndef COONS_SAMPLING_H
#define COONS_SAMPLING_H

#include "coons_internal.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Resolved sampling options: tolerance > 0, max_triangles > 0,
 * max_aspect >= 1 (INFINITY: no aspect refinement). */
typedef struct coons__sample_opts {
    double tolerance;
    unsigned resolution;
    size_t max_triangles;
    double max_aspect;
    unsigned flags;
    /* A volume mesh's cell budget (volume/lattice.c): 0 for none; else the
     * sampler refuses at once a lattice predicted far above it. */
    size_t max_cells;
    /* coons_sample_options.progress (version 2), or NULL: "measure" */
    void (*progress)(void *, const char *, double);
    void *userdata;
    /* coons_sample_options.threads (version 3), at least 1 */
    unsigned threads;
} coons__sample_opts;

/* Internal flag of coons__sample_opts: coons__body_sample_into() stores
 * each vertex's (u, v, w) with the part (coons_mesh_vertex_parameters()). */
#define COONS__SAMPLE_PARAMS (1u << 31)

/* Checks a public options struct (NULL: defaults) and resolves it;
 * tolerance stays <= 0 when the caller must supply the default. */
coons_status coons__sample_opts_resolve(const coons_sample_options *in, coons__sample_opts *out,
                                        coons_error *err);

/* A face shared by two bodies (shared_faces.c): face[0] of body[0] and
 * face[1] of body[1] (faces numbered u0 u1 v0 v1 w0 w1) are the same map:
 * F1(a', b') = F0(a, b), where (a', b') is (a, b), swapped when sym has
 * COONS__SYM_SWAP, then a' -> 1 - a' with COONS__SYM_FLIP_A and
 * b' -> 1 - b' with COONS__SYM_FLIP_B. A face's (a, b) are its body's two
 * other parameters in increasing order (coons__face_axes()). */
enum { COONS__SYM_SWAP = 1, COONS__SYM_FLIP_A = 2, COONS__SYM_FLIP_B = 4 };
typedef struct coons__shared_face {
    size_t body[2];
    int face[2];
    int sym;
} coons__shared_face;

/* The fixed axis and the two parameter axes (a < b) of face f. */
void coons__face_axes(int f, int *fixed, int *a, int *b);

/* Every pair of faces of different bodies that are the same map within
 * `tol` (coordinates, each), each face in one pair at most; *out is
 * allocated with coons__malloc (NULL when *count is 0 may also be). */
coons_status coons__find_shared_faces(const coons_body *const *bodies, size_t nb, double tol,
                                      coons__shared_face **out, size_t *count,
                                      coons_error *err);

/* Gives every class of directions that the shared faces sf[0..nsf-1]
 * tie together one lattice (lattice_share.c): the union of the members'
 * values, each in its own sense. t[3 i + d] (n[3 i + d] + 1 values, from
 * coons__malloc) is body i's lattice along d; replaced arrays are freed.
 * *changed (may be NULL) is set when some lattice gained values. */
coons_status coons__share_lattices(size_t nb, double **t, size_t *n,
                                   const coons__shared_face *sf, size_t nsf, int *changed,
                                   coons_error *err);

/* A tie of two lattice directions x = 3 i + d (body i, axis d) and y: the
 * same lattice, y's running in the opposite sense (t <-> 1 - t) when flip. */
typedef struct coons__lattice_tie {
    size_t x, y;
    int flip;
} coons__lattice_tie;

/* coons__share_lattices() with further ties of single directions. */
coons_status coons__share_lattices_tied(size_t nb, double **t, size_t *n,
                                        const coons__shared_face *sf, size_t nsf,
                                        const coons__lattice_tie *ties, size_t nties,
                                        int *changed, coons_error *err);

/* The lattice the boundary sampler settles on for body b with options o
 * (adaptive or fixed, as coons__body_sample_into() would use): t[d] gets
 * n[d] + 1 increasing values from 0 to 1 per direction d = u, v, w,
 * allocated with coons__malloc (the caller frees them). `deviation` (may
 * be NULL) gets the measured deviation of the boundary mesh on it (NaN if
 * unmeasured). The budget check is the triangle budget of o. */
coons_status coons__body_sample_lattice(const coons_body *b, const coons__sample_opts *o,
                                        const char *name, double *t[3], size_t n[3],
                                        double *deviation, coons_error *err);
/* Samples body b (sample.c) and appends it to `mesh` as one part.
 * *triangles receives the part's triangle count. */
coons_status coons__body_sample_into(const coons_body *b, const coons__sample_opts *o,
                                     const char *name, coons_mesh *mesh, size_t *triangles,
                                     coons_error *err);

/* Samples the bodies[0..nb-1] (a control lattice: joined by the shared
 * faces sf, whose body indices are into `bodies`) into one part `name` of
 * mesh, joined by index along the shared faces, which are left out
 * (sample_lattice.c). *triangles (may be NULL) gets the part's count. */
coons_status coons__lattice_sample_into(const coons_body *const *bodies,
                                        const char *const *names, size_t nb,
                                        const coons__shared_face *sf, size_t nsf,
                                        const coons__sample_opts *o, const char *name,
                                        coons_mesh *mesh, size_t *triangles,
                                        coons_error *err);

#ifdef __cplusplus
}
#endif
#endif
