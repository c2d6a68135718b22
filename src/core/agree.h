/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The agreement checker (model format, "Consistency"): where two
 * descriptions of the same point or curve meet, they must agree within the
 * consistency tolerance. One check per kind of meeting, used by the loader
 * (which words the error with the file position and JSON path) and by the
 * constructors (which word it without them). Internal.
 *
 * Each check looks at the places in a fixed order and stops at the first
 * one that disagrees: it then returns COONS_E_INCOMPATIBLE and fills *r
 * with which place it is, the two sources, their parameters and values,
 * and the distance. It sets no coons_error: the caller writes the message.
 */
#ifndef COONS_AGREE_H
#define COONS_AGREE_H

#include "coons_internal.h"

/* Samples along each shared body 2 edge, both ends included. */
#define COONS__AGREE_EDGE_SAMPLES 33

typedef struct coons__agree {
    int at;              /* the place: see each check */
    int a, b;            /* the two sources that disagree (indices, see each check) */
    double ta, tb;       /* their parameters */
    double pa[3], pb[3]; /* their values */
    double dist;         /* how far apart (> tol, or NaN) */
} coons__agree;

/*
 * Corners of a patch's boundary (t0 t1 s0 s1 = COONS_SIDE_T0..COONS_SIDE_S1):
 * X00 = t0(0) = s0(0), X10 = t0(1) = s1(0), X01 = t1(0) = s0(1),
 * X11 = t1(1) = s1(1), checked in that order. at: the corner, s + 2t;
 * a: the t-curve, b: the s-curve; ta, tb: 0 or 1.
 */
coons_status coons__agree_patch_corners(const coons_curve *const b[4], double tol,
                                        coons__agree *r);

/*
 * Hermite cross curves against the boundary tangents: cross.t0(e) =
 * s_e'(0), cross.t1(e) = s_e'(1), cross.s0(e) = t_e'(0), cross.s1(e) =
 * t_e'(1) (s_0 = s0, s_1 = s1, t_0 = t0, t_1 = t1), cross curves in order,
 * e = 0 before e = 1. at: the cross curve, ta: e, pa: its value; b: the
 * boundary curve, tb: where its tangent pb is taken.
 */
coons_status coons__agree_cross(const coons_curve *const b[4], const coons_curve *const cross[4],
                                double tol, coons__agree *r);

/*
 * Body 1 corners P_ijk = u_jk(i) = v_ik(j) = w_ij(k), corners in the order
 * (i, j, k) = 000, 001, ..., 111, and at each the pairs (u, v), (u, w),
 * (v, w). at: 4i + 2j + k; a, b: the edges (0 + 2j + k, 4 + 2i + k,
 * 8 + 2i + j), ta, tb: their parameters.
 */
coons_status coons__agree_body1_corners(const coons_curve *const e[12], double tol,
                                        coons__agree *r);

/*
 * Body 2 shared edges, parametrically, at COONS__AGREE_EDGE_SAMPLES points
 * x = m / (samples - 1) each (the ends cover the corners: any two of the
 * three faces at a corner share an edge through it). Edge e (u-edges
 * 0 + 2J + K, v-edges 4 + 2I + K, w-edges 8 + 2I + J) lies on
 *   uJK: Y_J(x, K) and Z_K(x, J)
 *   vIK: X_I(x, K) and Z_K(I, x)
 *   wIJ: X_I(J, x) and Y_J(I, x)
 * (faces u0 u1 v0 v1 w0 w1 = X_0 X_1 Y_0 Y_1 Z_0 Z_1). at: the first edge
 * that disagrees; a, b: its two faces in the order above; ta = tb: the x
 * of its largest disagreement (the first, if several are equal); dist: that
 * distance, INFINITY where it is NaN.
 */
coons_status coons__agree_body2_edges(const coons_patch *const f[6], double tol,
                                      coons__agree *r);

/* Face m (0, 1) of body 2 edge e, the patch parameter that runs along the
 * edge (0 = s, 1 = t) and the value of the other one. */
void coons__agree_edge_source(int e, int m, int *face, int *run, int *fixed);

/* Network nodes rows[j](sn[i]) = cols[i](tn[j]), j outer, i inner: the
 * first node (*i, *j) further apart than tol, with the distance
 * (network.c). */
coons_status coons__network_nodes_agree(const coons_curve *const *rows, size_t nr,
                                        const coons_curve *const *cols, size_t nc,
                                        const double *sn, const double *tn, double tol,
                                        size_t *i, size_t *j, double *dist);

#endif
