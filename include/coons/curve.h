/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/curve.h
 * @brief Curves over t in [0,1]: line, polyline, Bezier, cubic Hermite,
 *        Coons cubic B-spline (seed 002), clamped cubic, B-spline and NURBS.
 *
 * Points are `double[3]`; arrays of points are packed `x0 y0 z0 x1 y1 z1 ...`.
 * Constructors deep-copy their inputs; the returned curve belongs to the
 * caller and is released with coons_curve_free(). A curve never changes after
 * construction, so any number of threads may evaluate it at once.
 *
 * Every curve type is stored exactly as its definition: the Coons cubic
 * B-spline is evaluated with the Coons polynomials C0..C3 of seed 002, the
 * others with de Boor's algorithm over their knot vector, whose domain
 * [k_p, k_{n+1}] is mapped linearly onto [0,1].
 */
#ifndef COONS_CURVE_H
#define COONS_CURVE_H

#include "coons/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Curve types, in the order of the model format. */
typedef enum coons_curve_type {
    COONS_CURVE_LINE = 0,
    COONS_CURVE_POLYLINE,
    COONS_CURVE_BEZIER,
    COONS_CURVE_HERMITE,
    COONS_CURVE_COONS_CUBIC,
    COONS_CURVE_CLAMPED_CUBIC,
    COONS_CURVE_BSPLINE
} coons_curve_type;

/** Largest number of control points a curve accepts (guards allocation). */
#define COONS_CURVE_MAX_POINTS 1000000
/** Largest B-spline or Bezier degree accepted. */
#define COONS_SPLINE_MAX_DEGREE 64
/**
 * Largest ratio of the largest to the smallest weight of a rational curve,
 * surface or volume: beyond it sum w N P overflows or loses every digit
 * (weights 1e300 and 1, or all of them subnormal), so it is refused.
 */
#define COONS_SPLINE_MAX_WEIGHT_RATIO 1e100

/**
 * Straight segment (1-t) P0 + t P1.
 * @param[in]  p0,p1 end points
 * @param[out] out   the new curve
 * @return ::COONS_OK, ::COONS_E_INVALID (non-finite input), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_curve_new_line(const double p0[3], const double p1[3],
                                               coons_curve **out, coons_error *err);

/**
 * Polyline through `count` >= 2 points; segment i spans t in [i/n, (i+1)/n]
 * with n = count-1.
 * @return ::COONS_OK, ::COONS_E_INVALID, ::COONS_E_LIMIT, ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_curve_new_polyline(const double *points, size_t count,
                                                   coons_curve **out, coons_error *err);

/**
 * Bezier curve of degree count-1 (count >= 2), Bernstein basis.
 * @return ::COONS_OK, ::COONS_E_INVALID (fewer than 2 points, non-finite
 *         points), ::COONS_E_LIMIT (a degree above ::COONS_SPLINE_MAX_DEGREE),
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_curve_new_bezier(const double *points, size_t count,
                                                 coons_curve **out, coons_error *err);

/**
 * Cubic Hermite curve: value p0 and derivative d/dt t0 at t=0, value p1 and
 * derivative t1 at t=1.
 * @return ::COONS_OK, ::COONS_E_INVALID (non-finite input), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_curve_new_hermite(const double p0[3], const double t0[3],
                                                  const double p1[3], const double t1[3],
                                                  coons_curve **out, coons_error *err);

/**
 * Coons cubic B-spline of seed 002.
 *
 * Open (`closed` = 0): count = n+1 >= 4 points, n-2 uniform segments; segment
 * s covers t in [s/(n-2), (s+1)/(n-2)] and is C0 P_s + C1 P_s+1 + C2 P_s+2 +
 * C3 P_s+3 in its local parameter. Closed: the count >= 3 points are cyclic
 * (as if P0, P1, P2 were appended), count segments; a list whose last three
 * points repeat its first three is rejected with ::COONS_E_INVALID.
 * @return ::COONS_OK, ::COONS_E_INVALID (too few points, non-finite
 *         points, a repeated closing run), ::COONS_E_LIMIT (more than
 *         ::COONS_CURVE_MAX_POINTS), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_curve_new_coons_cubic(const double *points, size_t count,
                                                      int closed, coons_curve **out,
                                                      coons_error *err);

/**
 * Uniform clamped cubic B-spline of seed 002 (knots 0,0,0,0,1,...,n-2 x4,
 * normalised); count = n+1 >= 4. Passes through the first and last point.
 * @return ::COONS_OK, ::COONS_E_INVALID (fewer than 4 points, non-finite
 *         points), ::COONS_E_LIMIT (more than ::COONS_CURVE_MAX_POINTS),
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_curve_new_clamped_cubic(const double *points, size_t count,
                                                        coons_curve **out, coons_error *err);

/**
 * General B-spline or NURBS curve of degree p >= 1 with count = n+1 >= p+1
 * control points.
 * @param[in] knots   NULL for clamped uniform knots, else n+p+2 non-decreasing
 *                    values, no value repeated more than p+1 times, with a
 *                    non-empty domain [knots[p], knots[n+1]].
 * @param[in] weights NULL for a polynomial B-spline, else count values > 0
 *                    (points stay Cartesian, never pre-multiplied).
 * @return ::COONS_OK, ::COONS_E_INVALID (a degree outside
 *         1..::COONS_SPLINE_MAX_DEGREE, too few points, bad knots or
 *         weights, non-finite points), ::COONS_E_LIMIT (more than
 *         ::COONS_CURVE_MAX_POINTS), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_curve_new_bspline(int degree, const double *points, size_t count,
                                                  const double *knots, const double *weights,
                                                  coons_curve **out, coons_error *err);

/** Deep copy. @return ::COONS_OK or ::COONS_E_NOMEM. */
COONS_EXPORT coons_status coons_curve_copy(const coons_curve *c, coons_curve **out,
                                           coons_error *err);

/**
 * The affine image y(t) = M c(t) + t of a curve (coons-model(5),
 * "Definitions and references", "transform"). Exact for every type, NURBS
 * included (affine maps commute with rational evaluation): points map by
 * M x + t, derivatives by M alone. The control box is that of c's control
 * points mapped. coons_curve_kind() of the result is c's type.
 *
 * Copies c (coons_curve_copy()): the caller keeps c and frees the result
 * with coons_curve_free().
 * @param[in]  c   the curve
 * @param[in]  m   12 doubles, the row-major 3 x 4 matrix [[a,b,c,tx],[d,e,f,ty],
 *                 [g,h,i,tz]] (a `double m[12]`, or `m[0]` of a `double m[3][4]`)
 *                 of y = M x + t: 12 finite numbers with M regular
 *                 (|det M| > 1e-12 x the product of M's row norms).
 * @param[out] out the new curve
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL argument, an entry not
 *         finite, or M singular: the message gives the determinant),
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_curve_new_transformed(const coons_curve *c, const double *m,
                                                      coons_curve **out, coons_error *err);

/**
 * The reversed curve y(t) = c(1 - t), y'(t) = -c'(1 - t) ("reverse"); its
 * Bezier segments are c's in the opposite order. Copies c; the result's
 * type is c's. @return ::COONS_OK, ::COONS_E_INVALID (NULL argument),
 * ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_curve_new_reversed(const coons_curve *c, coons_curve **out,
                                                   coons_error *err);

/** Releases a curve; NULL is a harmless no-op. */
COONS_EXPORT void coons_curve_free(coons_curve *c);

/** The type the curve was built as (of a transformed or reversed curve: the
 * type of the curve it was made from). */
COONS_EXPORT coons_curve_type coons_curve_kind(const coons_curve *c);

/** Point at t (t is clamped to [0,1]; a NaN t counts as 0). */
COONS_EXPORT void coons_curve_eval(const coons_curve *c, double t, double out[3]);

/**
 * Point and derivatives at t: out[0] = C(t), out[1] = C'(t) (if order >= 1),
 * out[2] = C''(t) (if order >= 2). order is 0, 1 or 2. Derivatives are with
 * respect to the normalised parameter t in [0,1]; at a knot the right-hand
 * derivative is returned, except at t = 1. t is clamped to [0,1] (NaN
 * counts as 0), so no t makes it fail.
 */
COONS_EXPORT void coons_curve_eval_derivs(const coons_curve *c, double t, int order,
                                          double out[][3]);

/**
 * Axis-aligned box of the control points (a box that contains the curve
 * for every type: all bases here are non-negative partitions of unity, and
 * Hermite tangents are converted to Bezier points).
 */
COONS_EXPORT void coons_curve_control_bbox(const coons_curve *c, double lo[3], double hi[3]);

/**
 * Bezier segments of a polynomial curve (every type but a rational NURBS).
 *
 * Writes each non-empty span as a Bezier curve of the curve's degree d:
 * segment s occupies points[s*(d+1)*3 ...]. With points NULL, only
 * *segments and *degree are set, so a caller can size the array.
 * Segment s covers the parameter interval of the s-th non-empty knot span.
 * @param[in]  capacity number of doubles points can hold
 * @return ::COONS_OK, ::COONS_E_UNSUPPORTED (rational curve),
 *         ::COONS_E_INVALID (capacity too small), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_curve_bezier_segments(const coons_curve *c, double *points,
                                                      size_t capacity, size_t *segments,
                                                      int *degree, coons_error *err);

/**
 * Seed 002's conversion from the control points of an open Coons cubic
 * B-spline (P~0..P~n, n >= 3) to those of the clamped cubic curve
 * that traces the same curve:
 * P0 = P~0/6 + 2P~1/3 + P~2/6, P1 = 2P~1/3 + P~2/3, Pi = P~i (2 <= i <= n-2),
 * P(n-1) = P~(n-2)/3 + 2P~(n-1)/3, Pn = P~(n-2)/6 + 2P~(n-1)/3 + P~n/6.
 * @param[in]  open    count points
 * @param[out] clamped count points
 * @return ::COONS_OK or ::COONS_E_INVALID (count < 4).
 */
COONS_EXPORT coons_status coons_curve_convert_open_to_clamped(const double *open, size_t count,
                                                              double *clamped, coons_error *err);

/**
 * The model format's name of a curve type ("line", "coons-cubic", ...), or
 * NULL for a value that is not a curve type (so a caller can list every type
 * by counting up from 0 until NULL). Static storage, never freed.
 */
COONS_EXPORT const char *coons_curve_type_name(coons_curve_type type);

/**
 * The curve type of a model-format name (exact, case-sensitive).
 * @return ::COONS_OK, or ::COONS_E_INVALID for an unknown name (or NULL).
 */
COONS_EXPORT coons_status coons_curve_type_from_name(const char *name, coons_curve_type *out,
                                                     coons_error *err);

#ifdef __cplusplus
}
#endif
#endif
