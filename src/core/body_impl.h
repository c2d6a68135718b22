/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The body record (seed 000 section 2), shared by body.c, the body types'
 * files (body0.c, body1.c, body2.c, tensor_volume.c), body_volume.c and
 * the boundary sampler. Internal. */
#ifndef COONS_BODY_IMPL_H
#define COONS_BODY_IMPL_H

#include "basis.h"
#include "kinds.h"

/* Marks a hot loop to be compiled also for AVX2 and picked at load time
 * (GCC function multiversioning, needs ifunc: x86-64 ELF). */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__ELF__) && \
    !defined(COONS_NO_CLONES)
#define COONS__SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define COONS__SIMD_CLONES
#endif

struct coons_body {
    const coons__body_kind *kind; /* the type's row (kinds.h) */
    coons_blend blend;
    /* Corners C_ijk of T, index 4i+2j+k: body 0 the given points, body 1
     * and body 2 the average of the sources that meet there. */
    double corner[8][3];
    coons_curve *edge[12]; /* body 1, in the order of body.h */
    coons_patch *face[6];  /* body 2, in the order of body.h */
    /* Body 2 of tensor-product faces: what its point evaluation keeps from
     * one point to the next (body2.c), built with the body, read only after. */
    struct coons__body2_fast *fast;
    /* Tensor volumes (Bezier = B-spline with knots 0^(n) 1^(n)). */
    int deg[3];
    size_t n[3];
    double *pts;      /* n0*n1*n2 Cartesian points, i along u */
    double *knots[3]; /* n[d] + deg[d] + 1 values each */
    double *w;        /* weights or NULL */
    double lo[3], hi[3]; /* control box */
    /* The affine wrapper (body_transformed.c): the wrapped body, the map
     * and its determinant. */
    coons_body *inner;
    double xf[12];
    double xf_det;
    /* Shells (shell.c): the surface is face[0]; thickness h, offset c. */
    double shell_h, shell_c;
    /* The morph (morph.c): nkeys keys, their times at[], the path
     * (coons_morph_path) and the time t. */
    coons_body **keys;
    size_t nkeys;
    double *at;
    int path;
    double t;
};

/* Allocates a zeroed record of the given kind, with an empty control box. */
coons_status coons__body_alloc(const coons__body_kind *kind, coons_blend blend,
                               coons_body **out, coons_error *err);

/* T(c; u,v,w) from blend pairs bu, bv, bw (coons__blend(kind, t, 1, b)
 * layout: b[0], b[1] the weights of the 0 and 1 sides, b[2], b[3] their
 * derivatives) and,
 * if d is not NULL, its three partials d[0] = d/du, d[1] = d/dv, d[2] = d/dw. */
void coons__trilinear(const double c[8][3], const double bu[4], const double bv[4],
                      const double bw[4], double out[3], double d[3][3]);

/* The blend pairs of u, v and w with their first derivatives (the
 * coons__trilinear layout), each followed by the parameter at index 4. */
static inline void coons__blends_at(coons_blend blend, double u, double v, double w,
                                    double bu[5], double bv[5], double bw[5])
{
    coons__blend(blend, u, 1, bu);
    coons__blend(blend, v, 1, bv);
    coons__blend(blend, w, 1, bw);
    bu[4] = u;
    bv[4] = v;
    bw[4] = w;
}

/* *acc += n*k unless that overflows (then returns 0 and leaves *acc). */
static inline int coons__size_addmul(size_t *acc, size_t n, size_t k)
{
    if (k && n > (SIZE_MAX - *acc) / k) return 0;
    *acc += n * k;
    return 1;
}

/* Cell boundaries 0 = x_0 < ... < x_m = 1 along direction d (0: u, 1: v,
 * 2: w): the breakpoints of the body's data where the map may lose
 * smoothness (knots, Coons cubic segment ends; only 0 and 1 beyond 64
 * breakpoints). *out (m + 1 values in *n) is freed with coons__free().
 * Used by the volume quadrature and the boundary sampler (src/mesh). */
coons_status coons__body_breaks(const coons_body *b, int d, double **out, size_t *n,
                                coons_error *err);

/* Name of an edge ("u00" .. "w11") or a face ("u0" .. "w1"). */
const char *coons__body_edge_name(int e);
const char *coons__body_face_name(int f);

/* Value (and derivative along its parameter if dp is not NULL) of edge e
 * (body.h order) at parameter x. */
typedef void (*coons__edge_fn)(const coons_body *b, int e, double x, double p[3], double *dp);

/* Adds sign * E to out (and to d[q] = dE/dq if d is not NULL), with
 * E = sum_ij a_i(u) a_j(v) C(i,j,w) + sum_ik a_i(u) a_k(w) C(i,v,k)
 *   + sum_jk a_j(v) a_k(w) C(u,j,k), the edge part of seed 000's C1.
 * bu, bv, bw: blend pairs (coons__trilinear layout) followed by the
 * parameter itself at index 4. */
void coons__edge_sum(const coons_body *b, coons__edge_fn edge, double sign, const double bu[5],
                     const double bv[5], const double bw[5], double out[3], double d[3][3]);
/* The same sum from the edges' values E[e] and derivatives dE[e] (read
 * only if d is not NULL), e in body.h order. */
void coons__edge_sum_tab(double E[12][3], double dE[12][3], double sign,
                         const double bu[5], const double bv[5], const double bw[5],
                         double out[3], double d[3][3]);

/* det J of b over the tensor grid u x v x w into det[(i*nv + j)*nw + k]:
 * the type's grid path where it has one, else point by point
 * (body_volume.c). */
coons_status coons__body_det_grid(const coons_body *b, const double *u, size_t nu,
                                  const double *v, size_t nv, const double *w, size_t nw,
                                  double *det, coons_error *err);

/* The partials dF/du, dF/dv, dF/dw of b over the same grid into
 * jac[9 ((i*nv + j)*nw + k) ..], by the same path: det J of a point is
 * det of its partials, as coons_body_eval_jacobian() takes it. */
coons_status coons__body_jac_grid(const coons_body *b, const double *u, size_t nu,
                                  const double *v, size_t nv, const double *w, size_t nw,
                                  double *jac, coons_error *err);

#endif
