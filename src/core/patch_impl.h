/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The patch record, shared by patch.c, boolean_sum.c and the patch types'
 * files coons_patch.c, hermite_coons.c and tensor_surface.c. Internal.
 *
 * Bilinear, ruled, Coons and Hermite Coons patches are all Boolean sums of
 * two "line" families (seed 001 eq. 1.8 and 1.13-1.15):
 *
 *   x(s,t) = sum_m bs_m(s) Sv_m(t) + sum_m bt_m(t) [Tv_m(s) - r_m(s)],
 *   r_m(s) = sum_i bs_i(s) M[i][m],
 *
 * with n = 2 (blends, curves t0/t1 and s0/s1, M the corner matrix of
 * eq. 1.7) or n = 4 (Hermite H0..H3, curves and cross ribbons, M the
 * matrix of eq. 1.15). An s-line (fixed s) holds bs and W = Tv - r, a
 * t-line (fixed t) holds bt and Sv; both carry derivatives up to order 2.
 * Every derivative x_{s^a t^b} is the same sum with the a-th and b-th
 * derivatives, because each term is a product f(s) g(t).
 */
#ifndef COONS_PATCH_IMPL_H
#define COONS_PATCH_IMPL_H

#include "kinds.h"

struct coons__pline {
    int n;            /* 2 or 4 terms */
    int order;        /* derivatives filled: 0..2 */
    double b[3][4];   /* blend / basis values, b[d][m] = d^d/dx^d */
    double v[3][12];  /* v[d] + 3m: s-line W_m = Tv_m - r_m; t-line Sv_m */
};

struct coons_patch {
    const coons__patch_kind *kind; /* the type's row (kinds.h) */
    coons_blend blend;       /* COONS_PATCH_COONS */
    int n;                   /* terms of the Boolean sum (2 or 4) */
    coons_curve *curve[4];   /* boundary T0, T1, S0, S1; ruled: c0, c1 */
    coons_curve *cross[4];   /* Hermite: x_t(s,0), x_t(s,1), x_s(0,t), x_s(1,t), or NULL */
    double corner[4][3];     /* X00, X10, X01, X11 (index a + 2b), averaged */
    double M[4][4][3];       /* the corner matrix of eq. 1.7 (2x2) or eq. 1.15 (4x4) */
    coons_twist twist;       /* Hermite: how M's twists were found */

    /* Tensor-product surfaces (Bezier: degrees ns-1, nt-1, no knots). */
    int ps, pt;
    size_t ns, nt;           /* control net size */
    double *pts;             /* 3*ns*nt Cartesian points, i along s */
    double *w;               /* ns*nt weights or NULL */
    double *pw;              /* 4*ns*nt homogeneous (w x, w y, w z, w), or NULL */
    double *ks, *kt;         /* knot vectors, NULL for Bezier */

    /* Wrappers (patch_transformed.c, patch_reparam.c): the wrapped patch,
     * the map, the reparametrisation; lo/hi the control box. */
    coons_patch *inner;
    double xf[12];
    int swap, flip_s, flip_t;
    double lo[3], hi[3];

    /* Networks (network.c): ncs x nct cells, cell (i,j) at i*nct + j, each a
     * hermite-coons or coons patch over its own [0,1]^2; the node
     * parameters; the rows (nct+1) then the columns (ncs+1). */
    size_t ncs, nct;
    double *sn, *tn;
    coons_patch **cells;
    coons_curve **net;
};

/* A wrapper record of kind over a copy of p with control box [lo, hi]
 * (patch_transformed.c). */
coons_status coons__patch_wrap(const coons__patch_kind *kind, const coons_patch *p,
                               const double lo[3], const double hi[3], coons_patch **out,
                               coons_error *err);
/* control_bbox, copy and free of the wrapper rows. */
void coons__patch_wrap_bbox(const coons_patch *p, double lo[3], double hi[3]);
coons_status coons__patch_wrap_copy(const coons_patch *p, coons_patch *d, coons_error *err);
void coons__patch_wrap_free(coons_patch *p);

/* Vector m of derivative order d of a line. */
static inline double *coons__lv(coons__pline *L, int d, int m) { return L->v[d] + 3 * m; }

/* Allocates a zeroed record of the given kind (n = 2). */
coons_status coons__patch_alloc(const coons__patch_kind *kind, coons_patch **out,
                                coons_error *err);

/* Checks that the four boundary curves (none NULL) meet at the corners
 * within tol (> 0 absolute, else 1e-9 of the control box diagonal of the
 * curves), and stores the averaged corners in X[a + 2b]. *tol_used gets the
 * tolerance applied. ::COONS_E_INCOMPATIBLE names the corner. */
coons_status coons__patch_corners(const coons_curve *const b[4], double tol, double X[4][3],
                                  double *tol_used, coons_error *err);

/* The Boolean sum (boolean_sum.c): the eval and grid of the types whose
 * rows give an s-line and a t-line, and the parts of such a record that
 * are the same for all of them (its curves and cross curves). */
void coons__boolsum_eval(const coons_patch *p, double s, double t, int order, double out[][3]);
coons_status coons__boolsum_grid(const coons_patch *p, const double *s, size_t ns,
                                 const double *t, size_t nt, double *out, coons_error *err);
void coons__boolsum_control_bbox(const coons_patch *p, double lo[3], double hi[3]);
void coons__boolsum_breaks(const coons_patch *p, int dir, coons__breaks *B);
void coons__boolsum_space(const coons_patch *p, int dir, coons__space *S);
coons_status coons__boolsum_copy(const coons_patch *p, coons_patch *d, coons_error *err);
void coons__boolsum_free(coons_patch *p);

/* Clears L for n terms and derivatives up to order. */
void coons__pline_clear(coons__pline *L, int n, int order);
/* Curve value and derivatives up to order at x into vector m of L. */
void coons__pline_curve(coons__pline *L, int m, const coons_curve *c, double x, int order);

#endif
