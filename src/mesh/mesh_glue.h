/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Internal declarations shared by the C sources of src/mesh and the C++
 * OpenMesh glue (openmesh.cpp). Plain C: no OpenMesh or C++ types here. */
#ifndef COONS_MESH_GLUE_H
#define COONS_MESH_GLUE_H

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
} coons__sample_opts;

/* Internal flag of coons__sample_opts: coons__body_sample_into() stores
 * each vertex's (u, v, w) with the part (coons_mesh_vertex_parameters()). */
#define COONS__SAMPLE_PARAMS (1u << 31)

/* Checks a public options struct (NULL: defaults) and resolves it;
 * tolerance stays <= 0 when the caller must supply the default. */
coons_status coons__sample_opts_resolve(const coons_sample_options *in, coons__sample_opts *out,
                                        coons_error *err);

/* Samples body b (sample.c) and appends it to `mesh` as one part.
 * *triangles receives the part's triangle count. */
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

/* The lattice the boundary sampler settles on for body b with options o
 * (adaptive or fixed, as coons__body_sample_into() would use): t[d] gets
 * n[d] + 1 increasing values from 0 to 1 per direction d = u, v, w,
 * allocated with coons__malloc (the caller frees them). `deviation` (may
 * be NULL) gets the measured deviation of the boundary mesh on it (NaN if
 * unmeasured). The budget check is the triangle budget of o. */
coons_status coons__body_sample_lattice(const coons_body *b, const coons__sample_opts *o,
                                        const char *name, double *t[3], size_t n[3],
                                        double *deviation, coons_error *err);
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

/* The index-array checks of coons_mesh_check() (check.c): everything but
 * the OpenMesh fields, which are left 0. */
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

coons_status coons__mesh_check_c(const coons_mesh *m, coons_mesh_report *r, coons_error *err);

#ifdef __cplusplus
}
#endif
#endif
