/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The tables of the core: one row per curve, patch and body type, holding
 * the type's operations. Internal.
 *
 * A record (coons_curve, coons_patch, coons_body) points at its row; the
 * dispatch files curve.c, patch.c and body.c keep only the record's
 * lifecycle and call through the row, so they know no type. Each type's
 * file (named after the type, citing the seed equation it implements)
 * defines its row. kinds.c collects the rows into one table per kind,
 * indexed by the public type enum, with the model-format name of each.
 *
 * Adding a type: its enum value in the public header, one new file that
 * defines the row (declared below), and one line in the table of kinds.c.
 * Its space operation (below) tells the exact spline form of nurbs.c what
 * space holds it; without one the type is fitted.
 *
 * Conventions of every row:
 * - eval gets parameters already clamped to [0,1] (clamp01), grid gets them
 *   as given and clamps each itself; grid sizes are non-zero;
 * - copy gets d as a bitwise copy of the source record and replaces every
 *   pointer the type owns with a deep copy; it sets the pointers it has not
 *   copied yet to NULL first, so that on failure free(d) is safe;
 * - free releases what the type owns (not the record);
 * - an operation that a type does not need is NULL where so stated.
 */
#ifndef COONS_KINDS_H
#define COONS_KINDS_H

#include "breaks.h"
#include "coons_internal.h"

typedef struct coons__pline coons__pline; /* patch_impl.h */

/* The spline space of an object along one direction (the space operation
 * of the rows; nurbs.c): between its breakpoints the object is a
 * polynomial of at most `degree` in that parameter (POLY), the quotient of
 * such polynomials over its own weights, a tensor-product NURBS whose
 * control net is the type's data (NURBS), or neither (NONE: an offset, a
 * Boolean sum of rational curves). A Boolean sum, blend or morph joins its
 * parts with coons__space_join(); a wrapper forwards its inner object's. */
typedef enum coons__space_kind {
    COONS__SPACE_POLY = 0,
    COONS__SPACE_NURBS = 1,
    COONS__SPACE_NONE = 2
} coons__space_kind;

typedef struct coons__space {
    int degree;             /* >= 1 */
    coons__space_kind kind;
    /* Continuity at every breakpoint: C^cont at least (0: C0 only;
     * COONS__SMOOTH (breaks.h) where the object has no breakpoints of its own). */
    int cont;
} coons__space;


/* S becomes the space of a sum of S's and T's objects (products with
 * polynomials included): the larger degree, the lesser continuity (each
 * term is smooth away from its own breakpoints); POLY if both are, else
 * NONE (two rational parts have different denominators). */
static inline void coons__space_join(coons__space *S, coons__space T)
{
    if (T.degree > S->degree) S->degree = T.degree;
    if (T.cont < S->cont) S->cont = T.cont;
    S->kind = S->kind == COONS__SPACE_POLY && T.kind == COONS__SPACE_POLY ? COONS__SPACE_POLY
                                                                          : COONS__SPACE_NONE;
}

/* The polynomial space of degree p (a blend, a fixed basis). */
static inline coons__space coons__space_poly(int p)
{
    coons__space S = {p < 1 ? 1 : p, COONS__SPACE_POLY, COONS__SMOOTH};
    return S;
}

/* NURBS for weights w[0..n-1], POLY for none or all equal (the quotient
 * is then the polynomial itself). */
static inline coons__space_kind coons__weights_space(const double *w, size_t n)
{
    for (size_t i = 1; w && i < n; i++)
        if (w[i] != w[0]) return COONS__SPACE_NURBS;
    return COONS__SPACE_POLY;
}

/* The degree of a blend pair (basis.h): 1 linear, 3 cubic. */
static inline int coons__blend_degree(coons_blend blend)
{
    return blend == COONS_BLEND_CUBIC ? 3 : 1;
}

typedef struct coons__curve_kind {
    coons_curve_type type;
    /* Point (out[0]) and derivatives up to order (<= 2) at t. */
    void (*eval)(const coons_curve *c, double t, int order, double out[][3]);
    /* coons_curve_bezier_segments. */
    coons_status (*bezier)(const coons_curve *c, double *points, size_t capacity,
                           size_t *segments, int *degree, coons_error *err);
    /* Breakpoints of the curve's data in (0,1) into B. */
    void (*breaks)(const coons_curve *c, coons__breaks *B);
    coons_status (*copy)(const coons_curve *c, coons_curve *d, coons_error *err);
    void (*free)(coons_curve *c);
    /* The spline space (coons__space); NULL: NONE. */
    void (*space)(const coons_curve *c, coons__space *S);
} coons__curve_kind;

typedef struct coons__patch_kind {
    coons_patch_type type;
    /* Point and partials out[0..5] = x, x_s, x_t, x_ss, x_st, x_tt up to
     * order (<= 2). */
    void (*eval)(const coons_patch *p, double s, double t, int order, double out[][3]);
    /* coons_patch_eval_grid, arguments checked. */
    coons_status (*grid)(const coons_patch *p, const double *s, size_t ns, const double *t,
                         size_t nt, double *out, coons_error *err);
    /* Boolean-sum types only (boolean_sum.c), else NULL: the s-line and
     * t-line of patch_impl.h. */
    void (*sline)(const coons_patch *p, double s, int order, coons__pline *L);
    void (*tline)(const coons_patch *p, double t, int order, coons__pline *L);
    void (*control_bbox)(const coons_patch *p, double lo[3], double hi[3]);
    /* Breakpoints along s (dir 0) or t (dir 1) into B; NULL: polynomial. */
    void (*breaks)(const coons_patch *p, int dir, coons__breaks *B);
    coons_status (*copy)(const coons_patch *p, coons_patch *d, coons_error *err);
    void (*free)(coons_patch *p);
    /* The spline space along s (dir 0) or t (dir 1); NULL: NONE. */
    void (*space)(const coons_patch *p, int dir, coons__space *S);
} coons__patch_kind;

typedef struct coons__body_kind {
    coons_body_type type;
    /* Point (+ partials d[q] = dF/dq if d is not NULL). */
    void (*eval)(const coons_body *b, double u, double v, double w, double out[3],
                 double d[3][3]);
    /* coons_body_eval_grid; nu*nv*nw*3 does not overflow. */
    coons_status (*grid)(const coons_body *b, const double *u, size_t nu, const double *v,
                         size_t nv, const double *w, size_t nw, double *out, coons_error *err);
    /* On a grid, point n = (i*nv + j)*nw + k: det J into det[n] where det
     * is not NULL, the partials dF/du, dF/dv, dF/dw into jac[9n ..] where
     * jac is not NULL; NULL member: point by point through eval
     * (body_volume.c). */
    coons_status (*det_grid)(const coons_body *b, const double *u, size_t nu, const double *v,
                             size_t nv, const double *w, size_t nw, double *det, double *jac,
                             coons_error *err);
    /* Breakpoints along direction d (0: u, 1: v, 2: w) into B; NULL: none. */
    void (*breaks)(const coons_body *b, int d, coons__breaks *B);
    /* NULL: the type owns no memory beyond the record. */
    coons_status (*copy)(const coons_body *b, coons_body *d, coons_error *err);
    void (*free)(coons_body *b);
    /* The spline space along direction d; NULL: NONE. */
    void (*space)(const coons_body *b, int d, coons__space *S);
    /* coons_body_eval_points: n points (clamped here) bitwise as eval
     * gives them, with jac or det not NULL the Jacobians and determinants
     * as coons_body_eval_jacobian() gives them; NULL: point by point. */
    void (*points)(const coons_body *b, size_t n, const double *uvw, double *xyz, double *jac,
                   double *det);
} coons__body_kind;

/* Breakpoints of c in (0,1) into B through its row (nothing if c is NULL;
 * curve.c). */
void coons__curve_breaks(const coons_curve *c, coons__breaks *B);
/* Breakpoints of p along s (dir 0) or t (dir 1) through its row (patch.c). */
void coons__patch_breaks(const coons_patch *p, int dir, coons__breaks *B);

/* Tensor-product surfaces (tensor_surface.c) evaluated from bases computed
 * once and reused (body2.c), with the IEEE operations of their eval row, so
 * bitwise equal to coons_patch_eval_derivs():
 * - coons__patch_is_tensor: p is a bezier-surface or bspline-surface
 *   (not a wrapper);
 * - coons__tensor_basis: the basis along s (dir 0) or t (dir 1) at x in
 *   [0,1] with derivatives up to nd (<= 2), N[d*(deg+1) + k]; returns the
 *   first control index;
 * - coons__tensor_eval_basis: the point and derivatives up to order (<= 2,
 *   the bases computed to at least that order) from the two bases;
 * - coons__tensor_srow: the net combined along s with the value basis Ns
 *   (first index fs): R[4l + c], l < p->nt, c < 3 or 4 (homogeneous);
 * - coons__tensor_eval_srow: from such a row, the point at the t-basis Nt
 *   (ft) and, if order >= 1, its derivative along t into dt. */
int coons__patch_is_tensor(const coons_patch *p);
size_t coons__tensor_basis(const coons_patch *p, int dir, double x, int nd, double *N);
void coons__tensor_eval_basis(const coons_patch *p, size_t fs, const double *Ns, size_t ft,
                              const double *Nt, int order, double out[][3]);
void coons__tensor_srow(const coons_patch *p, size_t fs, const double *Ns, double *R);
/* - coons__tensor_tcol: column j of the net (t index j), T[4k + c];
 * - coons__tensor_eval_tcol: the point and, if order is 1, its derivative
 *   along s into ds, at the s-basis Ns (fs) where the t-basis is 1.0 at
 *   column j and 0 elsewhere, from that column: bitwise eval's provided
 *   eval's other terms are finite (the caller bounds the net's and the
 *   basis's sizes). */
void coons__tensor_tcol(const coons_patch *p, size_t j, double *T);
void coons__tensor_eval_tcol(const coons_patch *p, const double *T, size_t fs,
                             const double *Ns, int order, double out[3], double *ds);
void coons__tensor_eval_srow(const coons_patch *p, const double *R, size_t ft,
                             const double *Nt, int order, double out[3], double *dt);

/* The spline space of a curve, of a patch along dir, of a body along d
 * through the row (NONE where the row has no space operation; curve.c,
 * patch.c, body.c). A NULL curve (an absent cross curve) is degree 1 POLY. */
coons__space coons__curve_space(const coons_curve *c);
coons__space coons__patch_space(const coons_patch *p, int dir);
coons__space coons__body_space(const coons_body *b, int d);

/* The row of a type for a value outside the enum. */
const coons__curve_kind *coons__curve_kind_of(coons_curve_type type);
const coons__patch_kind *coons__patch_kind_of(coons_patch_type type);
const coons__body_kind *coons__body_kind_of(coons_body_type type);

/* The rows, each defined in its type's file. */
extern const coons__curve_kind coons__line_kind, coons__polyline_kind, coons__bezier_kind,
    coons__hermite_kind, coons__clamped_cubic_kind, coons__bspline_kind; /* bspline_curve.c */
extern const coons__curve_kind coons__coons_cubic_kind;                 /* coons_cubic.c */
extern const coons__patch_kind coons__bilinear_kind, coons__ruled_kind,
    coons__coons_patch_kind;                                     /* coons_patch.c */
extern const coons__patch_kind coons__hermite_coons_kind;        /* hermite_coons.c */
extern const coons__patch_kind coons__bezier_surface_kind,
    coons__bspline_surface_kind;                                 /* tensor_surface.c */
extern const coons__patch_kind coons__network_kind;              /* network.c */
extern const coons__body_kind coons__body0_kind;                 /* body0.c */
extern const coons__body_kind coons__body1_kind;                 /* body1.c */
extern const coons__body_kind coons__body2_kind;                 /* body2.c */
extern const coons__body_kind coons__bezier_volume_kind,
    coons__bspline_volume_kind;                                  /* tensor_volume.c */
extern const coons__body_kind coons__shell_kind;                 /* shell.c */
extern const coons__body_kind coons__morph_kind;                 /* morph.c */

/* Wrappers of another object (coons-model(5), "Definitions and
 * references"); not in the tables: they report the wrapped type. */
extern const coons__curve_kind coons__curve_transformed_kind; /* curve_transformed.c */
extern const coons__curve_kind coons__curve_reversed_kind;    /* curve_reversed.c */
extern const coons__patch_kind coons__patch_transformed_kind; /* patch_transformed.c */
extern const coons__patch_kind coons__patch_reparam_kind;     /* patch_reparam.c */
extern const coons__body_kind coons__body_transformed_kind;   /* body_transformed.c */

#endif
