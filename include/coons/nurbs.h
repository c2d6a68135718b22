/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/nurbs.h
 * @brief The B-spline / NURBS form of every curve, patch, body face and
 *        body: degrees, knots, control points and weights, exact where the
 *        construction lies in a spline space, fitted within a tolerance
 *        where it does not.
 *
 * Which constructions are exact. Between the breakpoints of its data (knots,
 * segment ends, network nodes) every construction of libcoons except the
 * shell is a polynomial in each parameter, or a NURBS over its own weights:
 * - polynomial: Coons cubic curves; bilinear, ruled, Coons (linear and cubic
 *   blend) and Hermite Coons patches and networks of polynomial curves;
 *   bodies 0, 1 and 2 of polynomial data, morphs of polynomial keys, and the
 *   affine images and reparametrisations of all of these. Seed 000 §2.4
 *   (Ďurikovič & Czanner, "Modelling with three types of Coons bodies"):
 *   the Coons body 2 defined by B-spline boundary surfaces is a B-spline
 *   body; the same holds for the other constructions, whose blends are
 *   polynomials. Their form uses in each direction the highest degree p of
 *   the data and blends there, a knot of multiplicity p - c at every
 *   breakpoint, c the continuity all the parts keep there (C2 for a Coons
 *   cubic or a cubic B-spline with simple knots, C0 in general: such a
 *   space contains every part, hence their sum), and clamped ends; the
 *   control points are found by interpolation at the tensor-product Greville
 *   points, one banded collocation system per direction (de Boor, "A
 *   Practical Guide to Splines", ch. XIII and XVII: the collocation matrix
 *   at the Greville points is totally positive, so elimination needs no
 *   pivoting). ::coons_nurbs.exact is 1.
 * - control nets: B-spline-backed curves (line, polyline, Bezier, Hermite,
 *   clamped cubic, B-spline), Bezier and B-spline surfaces and volumes,
 *   with or without weights (NURBS: weights not all equal), their affine
 *   images, reversals and reparametrisations, are copied rather than
 *   interpolated (knots mapped to [0,1]; the copy keeps the digits of high
 *   degrees that interpolation at equally spaced points would lose); a face
 *   of a volume is its homogeneous section; a face of a body 2 with
 *   rational faces is that face patch's form (Coons interpolation: the
 *   body there is the patch). exact is 1.
 * - none: shells (the offset along the unit normal), Boolean sums and bodies
 *   that mix rational curves or faces, morphs with such keys. These are
 *   fitted: cubic in every direction that has no exact space (a knot of
 *   multiplicity 3 at each breakpoint and uniform simple knots between,
 *   doubled until the deviation is within the tolerance), the exact space in
 *   the others (a shell is linear through its thickness). exact is 0.
 *
 * An exact form is claimed (exact 1) only when its measured deviation is
 * also at most 1e-10 of its size (the larger of the object's and the
 * form's control boxes and of their coordinates); one that is not (data that
 * failed to report a breakpoint) is refitted within `tol` when `tol` > 0, or
 * returned as it is, with exact 0 either way.
 *
 * The deviation is always measured: the largest distance between the form
 * and the construction (coons_curve_eval(), coons_patch_eval_grid(),
 * coons_body_eval_grid()) over a fixed grid of three points inside every knot
 * span in every direction and the domain's ends; for exact forms it is
 * rounding (about 1e-15 of the size), for fitted ones at most `tol` there.
 * A fit is judged on these points only: between them the error may be
 * somewhat larger.
 *
 * The result ::coons_nurbs is a plain value owned by the caller: its arrays
 * are allocated through the library's allocator and released with
 * coons_nurbs_free(). The functions only read their object; any number of
 * threads may call them at once on the same object with different outputs.
 */
#ifndef COONS_NURBS_H
#define COONS_NURBS_H

#include "coons/types.h"
#include "coons/curve.h"
#include "coons/patch.h"
#include "coons/body.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest number of control points of a form, exact or fitted; one that
 * would need more is ::COONS_E_LIMIT. */
#define COONS_NURBS_MAX_POINTS 2097152

/**
 * A tensor-product B-spline or NURBS of dimension 1 (curve), 2 (surface) or
 * 3 (volume) in 3-space. Direction d has degree[d] and count[d] control
 * points over knots[d] (count[d] + degree[d] + 1 values, the domain
 * [knots[d][degree[d]], knots[d][count[d]]] is [0,1]); unused directions
 * have degree 0, count 1 and knots NULL. Control point (i,j,k) is points[3
 * ((i*count[1] + j)*count[2] + k)], with i along the first direction. The
 * point at a parameter is sum w N P / sum w N (The NURBS Book, eq. 4.8),
 * or sum N P when weights is NULL.
 */
typedef struct coons_nurbs {
    int dim;          /**< 1 curve, 2 surface, 3 volume; 0 when empty */
    int degree[3];    /**< per direction, unused = 0 */
    size_t count[3];  /**< control points per direction, unused = 1 */
    double *knots[3]; /**< count[d] + degree[d] + 1 values each, domain [0,1] */
    double *points;   /**< 3 * count[0]*count[1]*count[2] doubles */
    double *weights;  /**< NULL when polynomial, else one per point */
    int exact;        /**< 1: the construction lies in this spline space exactly */
    double deviation; /**< measured largest distance to the construction */
} coons_nurbs;

/**
 * The B-spline or NURBS form of a curve over its parameter t in [0,1].
 * @param[in]  c   the curve
 * @param[in]  tol the largest deviation a fit may have (> 0, finite); read
 *                 only when no exact form exists (never for curves today:
 *                 every curve type is exact)
 * @param[out] out filled on success (previous contents are overwritten, not
 *                 freed); zeroed on failure
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL argument; tol not > 0 when a
 *         fit is needed), ::COONS_E_LIMIT (more breakpoints or control
 *         points than ::COONS_NURBS_MAX_POINTS), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_curve_to_nurbs(const coons_curve *c, double tol,
                                               coons_nurbs *out, coons_error *err);

/**
 * The form of a patch over (s,t) in [0,1]^2 (dim 2, direction 0 = s).
 * Same parameters as coons_curve_to_nurbs().
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL argument; tol not finite and
 *         > 0 when a fit is needed), ::COONS_E_LIMIT (too many control
 *         points; a fit that does not reach `tol` within
 *         ::COONS_NURBS_MAX_POINTS, with the deviation reached in the
 *         message), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_patch_to_nurbs(const coons_patch *p, double tol,
                                               coons_nurbs *out, coons_error *err);

/**
 * The form of one boundary face of a body (dim 2), over the face parameters
 * of the model format: u0, u1 over (v,w), v0, v1 over (u,w), w0, w1 over
 * (u,v) (::COONS_FACE_U0 .. ::COONS_FACE_W1, coons_body_face_name()). The
 * deviation is measured against coons_body_eval_grid() on the face. A
 * collapsed face (an apex) is a form whose control points coincide.
 * @param[in] face 0..5
 * @return as coons_patch_to_nurbs(); ::COONS_E_INVALID for a face outside
 *         0..5.
 */
COONS_EXPORT coons_status coons_body_face_to_nurbs(const coons_body *b, int face, double tol,
                                                   coons_nurbs *out, coons_error *err);

/**
 * The whole body as a trivariate tensor-product form over (u,v,w) (dim 3):
 * exact for the polynomial bodies and rational volumes listed above
 * (seed 000 §2.4), fitted otherwise (a shell is fitted in u and v and
 * linear in w).
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL argument; no usable tol for a
 *         fit), ::COONS_E_LIMIT (as coons_patch_to_nurbs()),
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_to_nurbs(const coons_body *b, double tol, coons_nurbs *out,
                                              coons_error *err);

/**
 * The point of a form at param[0 .. dim-1] (each clamped to [0,1]) into
 * out. An empty or NULL form gives NaN. Pure and thread-safe.
 */
COONS_EXPORT void coons_nurbs_eval(const coons_nurbs *n, const double *param, double out[3]);

/** Releases the arrays of a form and zeroes it; NULL-safe. */
COONS_EXPORT void coons_nurbs_free(coons_nurbs *n);

#ifdef __cplusplus
}
#endif

#endif
