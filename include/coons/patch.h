/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/patch.h
 * @brief Patches over (s,t) in [0,1]^2: bilinear, ruled, Coons (linear and
 *        cubic blend), Hermite-blended Coons with tangent ribbons and twists
 *        (seed 001), Bezier and B-spline/NURBS surfaces, and networks of
 *        curves filled by Hermite Coons cells (seed 001 section 1.2.2).
 *
 * Constructors deep-copy their inputs (a patch holds copies of its curves);
 * the result belongs to the caller and is released with coons_patch_free().
 * Patches are immutable: concurrent evaluation is safe.
 *
 * Boundary curves are given in the order of the model format:
 * index ::COONS_SIDE_T0 = x(s,0), ::COONS_SIDE_T1 = x(s,1), ::COONS_SIDE_S0 = x(0,t),
 * ::COONS_SIDE_S1 = x(1,t). Where two curves give the same corner, the patch uses
 * their average (model format, "Consistency").
 */
#ifndef COONS_PATCH_H
#define COONS_PATCH_H

#include "coons/types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum coons_patch_type {
    COONS_PATCH_BILINEAR = 0,
    COONS_PATCH_RULED,
    COONS_PATCH_COONS,
    COONS_PATCH_HERMITE_COONS,
    COONS_PATCH_BEZIER,
    COONS_PATCH_BSPLINE,
    COONS_PATCH_NETWORK
} coons_patch_type;

/**
 * Sides of a Coons patch: indices of its four boundary curves, in the order of
 * the model format's keys (coons_patch_side_name()): `t0` = x(s,0),
 * `t1` = x(s,1), `s0` = x(0,t), `s1` = x(1,t).
 */
typedef enum coons_patch_side {
    COONS_SIDE_T0 = 0,
    COONS_SIDE_T1 = 1,
    COONS_SIDE_S0 = 2,
    COONS_SIDE_S1 = 3
} coons_patch_side;

/** Twist vectors of a Hermite Coons patch (seed 001 section 1.2.2). */
typedef enum coons_twist {
    COONS_TWIST_ZERO = 0,  /**< Ferguson: all four twists zero (default) */
    COONS_TWIST_ADINI,     /**< the twist of the bilinearly blended Coons patch */
    COONS_TWIST_BESSEL,    /**< single patch: the cell twist X00-X10-X01+X11 */
    COONS_TWIST_EXPLICIT   /**< the four given vectors */
} coons_twist;

/**
 * Consistency tolerance argument of constructors that check that curves
 * meet: a value > 0 is an absolute distance; 0 means 1e-9 times the
 * diagonal of the bounding box of the inputs' control points.
 */
#define COONS_TOL_DEFAULT 0.0

/** Largest control net (ns*nt points) a B-spline surface accepts (guards allocation). */
#define COONS_PATCH_MAX_POINTS 1000000

/**
 * Bilinear patch from corners X00, X10, X01, X11 (Xab = x(s=a, t=b)).
 * @param[in] corners 12 doubles: X00, X10, X01, X11, each x y z (a
 *                    `double c[12]`, or `c[0]` of a `double c[4][3]`)
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL or non-finite), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_patch_new_bilinear(const double *corners, coons_patch **out,
                                                   coons_error *err);

/**
 * Ruled surface x(s,t) = (1-t) c0(s) + t c1(s) (seed 001 eq. 1.2).
 * @return ::COONS_OK, ::COONS_E_INVALID (a NULL curve), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_patch_new_ruled(const coons_curve *c0, const coons_curve *c1,
                                                coons_patch **out, coons_error *err);

/**
 * Coons patch of four boundary curves (seed 001 eq. 1.8/1.11), with
 * linear blending or the cubic blend f(t) = 1 - 3t^2 + 2t^3.
 * @param[in] boundary 4 curves indexed ::COONS_SIDE_T0 .. ::COONS_SIDE_S1 (an
 *                     array of handles: see "Arrays" in coons/types.h)
 * @param[in] tol      corner tolerance (see ::COONS_TOL_DEFAULT)
 * @return ::COONS_OK, ::COONS_E_INCOMPATIBLE (a corner where the two curves
 *         do not meet: the message names the corner and the distance),
 *         ::COONS_E_INVALID, ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_patch_new_coons(coons_curve *const *boundary, coons_blend blend,
                                                double tol, coons_patch **out,
                                                coons_error *err);

/** Options of coons_patch_new_hermite_coons(). Initialise with ::COONS_HERMITE_OPTIONS_INIT. */
typedef struct coons_hermite_options {
    unsigned version;                 /**< ::COONS_HERMITE_OPTIONS_VERSION */
    const coons_curve *cross[4];      /**< all NULL, or x_t(s,0), x_t(s,1), x_s(0,t), x_s(1,t) */
    coons_twist twist;                /**< how the corner twists are found */
    double twists[4][3];              /**< explicit x_st(0,0), x_st(1,0), x_st(0,1), x_st(1,1) */
    double tol;                       /**< consistency tolerance, see ::COONS_TOL_DEFAULT */
} coons_hermite_options;

#define COONS_HERMITE_OPTIONS_VERSION 1
#ifndef __cplusplus
#define COONS_HERMITE_OPTIONS_INIT {.version = COONS_HERMITE_OPTIONS_VERSION, .twist = COONS_TWIST_ZERO, .tol = COONS_TOL_DEFAULT}
#else
#define COONS_HERMITE_OPTIONS_INIT COONS_RECORD_INIT_CXX_(coons_hermite_options, r_.version = COONS_HERMITE_OPTIONS_VERSION, r_.twist = COONS_TWIST_ZERO, r_.tol = COONS_TOL_DEFAULT)
#endif

/**
 * Sets `*o` to ::COONS_HERMITE_OPTIONS_INIT (for language bindings that
 * cannot use the macro); NULL is a harmless no-op.
 */
COONS_EXPORT void coons_hermite_options_init(coons_hermite_options *o);

/**
 * Bicubically blended (Hermite) Coons patch, seed 001 eq. 1.13-1.15:
 * x = h_c + h_d - h_cd with the cubic Hermite basis H0..H3.
 *
 * Corner points and corner tangents come from the boundary curves; twists
 * from `opts->twist`. Without cross curves each cross-boundary tangent is
 * the ribbon of seed 001 eq. 1.16 built from the corner tangents and twists.
 * Given cross curves must agree with the corner tangents within `tol`
 * (cross.t0(0) = s0'(0), cross.t0(1) = s1'(0), cross.s0(0) = t0'(0),
 * cross.s0(1) = t1'(0), and likewise at the far corners).
 *
 * Twists: ZERO, ADINI (x_st(a,b) = [s1'(b) - s0'(b)] + [t1'(a) - t0'(a)]
 * - (X00 - X10 - X01 + X11)), BESSEL (the cell twist X00 - X10 - X01 + X11
 * at all four corners of a single patch) or EXPLICIT. The patch takes the
 * given cross tangents exactly (x_t(s,0) = cross.t0(s), ...) when the
 * twists are compatible with them (x_st(0,0) = cross.t0'(0) = cross.s0'(0),
 * and so on); otherwise x_t(s,0) differs from cross.t0(s) by
 * H1(s) [cross.s0'(0) - x_st(0,0)] + H2(s) [cross.s1'(0) - x_st(1,0)].
 * @param[in] opts NULL for the defaults (no cross curves, zero twists);
 *                 `version` must be ::COONS_HERMITE_OPTIONS_VERSION; cross
 *                 curves are all four or none.
 * @return ::COONS_OK, ::COONS_E_INCOMPATIBLE (a corner point, or a cross
 *         curve against a corner tangent: the message names the corner),
 *         ::COONS_E_INVALID, ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_patch_new_hermite_coons(coons_curve *const *boundary,
                                                        const coons_hermite_options *opts,
                                                        coons_patch **out, coons_error *err);

/**
 * Tensor-product Bezier surface; points[(i*nt + j)*3], i along s (ns >= 2
 * points), j along t (nt >= 2).
 * @return ::COONS_OK, ::COONS_E_INVALID, ::COONS_E_LIMIT (a degree above
 *         ::COONS_SPLINE_MAX_DEGREE), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_patch_new_bezier(const double *points, size_t ns, size_t nt,
                                                 coons_patch **out, coons_error *err);

/**
 * Tensor-product B-spline or NURBS surface of degrees (ps, pt).
 * @param[in] knots_s,knots_t NULL for clamped uniform knots (each may be
 *            NULL independently), else ns+ps+1 and nt+pt+1 values
 * @param[in] weights NULL, or ns*nt values > 0 indexed like the points
 *            (points stay Cartesian, never pre-multiplied)
 * @return ::COONS_OK, ::COONS_E_INVALID (degrees outside 1..::COONS_SPLINE_MAX_DEGREE,
 *         too few points, bad knots or weights, non-finite values),
 *         ::COONS_E_LIMIT (more than ::COONS_PATCH_MAX_POINTS points),
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_patch_new_bspline(int ps, int pt, const double *points, size_t ns,
                                                  size_t nt, const double *knots_s,
                                                  const double *knots_t, const double *weights,
                                                  coons_patch **out, coons_error *err);

/**
 * The affine image y(s,t) = M x(s,t) + t of a patch (coons-model(5),
 * "Definitions and references", "transform"): points map by M x + t, every
 * partial by M alone, exact for every type. The control box is the box of
 * the 8 mapped corners of p's control box. coons_patch_kind() of the
 * result is p's type. Copies p: the caller keeps p and frees the result
 * with coons_patch_free().
 * @param[in]  p   the patch
 * @param[in]  m   12 doubles, the row-major 3 x 4 matrix [[a,b,c,tx],[d,e,f,ty],
 *                 [g,h,i,tz]] (a `double m[12]`, or `m[0]` of a `double m[3][4]`)
 *                 of y = M x + t: 12 finite numbers with M regular
 *                 (|det M| > 1e-12 x the product of M's row norms).
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL argument, an entry not
 *         finite, or M singular: the message gives the determinant),
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_patch_new_transformed(const coons_patch *p, const double *m,
                                                      coons_patch **out, coons_error *err);

/**
 * The patch y(s,t) = x(a,b) with (a,b) = swap ? (t,s) : (s,t), then
 * a -> 1 - a if flip_s, b -> 1 - b if flip_t ("swap", "flip_s", "flip_t");
 * partials follow by the chain rule, breakpoints are remapped. Any non-zero
 * int is true. Copies p; the result's type is p's; its control box is p's.
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL argument), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_patch_new_reparametrized(const coons_patch *p, int swap,
                                                         int flip_s, int flip_t,
                                                         coons_patch **out, coons_error *err);

/** Options of coons_patch_new_network(). Initialise with ::COONS_NETWORK_OPTIONS_INIT. */
typedef struct coons_network_options {
    unsigned version;      /**< ::COONS_NETWORK_OPTIONS_VERSION */
    const double *s_nodes; /**< ncolumns node parameters s_i, or NULL: uniform i/m */
    const double *t_nodes; /**< nrows node parameters t_j, or NULL: uniform j/n */
    coons_twist twist;     /**< ZERO, ADINI or BESSEL (default): the node twist rule */
    coons_blend blend;     /**< CUBIC (default): Hermite cells; LINEAR: Coons cells */
    double tol;            /**< consistency tolerance, see ::COONS_TOL_DEFAULT */
} coons_network_options;

#define COONS_NETWORK_OPTIONS_VERSION 1
#ifndef __cplusplus
#define COONS_NETWORK_OPTIONS_INIT {.version = COONS_NETWORK_OPTIONS_VERSION, .twist = COONS_TWIST_BESSEL, .blend = COONS_BLEND_CUBIC, .tol = COONS_TOL_DEFAULT}
#else
#define COONS_NETWORK_OPTIONS_INIT COONS_RECORD_INIT_CXX_(coons_network_options, r_.version = COONS_NETWORK_OPTIONS_VERSION, r_.twist = COONS_TWIST_BESSEL, r_.blend = COONS_BLEND_CUBIC, r_.tol = COONS_TOL_DEFAULT)
#endif

/**
 * Sets `*o` to ::COONS_NETWORK_OPTIONS_INIT; NULL is a harmless no-op.
 */
COONS_EXPORT void coons_network_options_init(coons_network_options *o);

/**
 * The patch that fills a network of curves (seed 001 section 1.2.2,
 * coons-model(5) "Networks of curves"): row j is x(s, t_j) (parameter s),
 * column i is x(s_i, t) (parameter t). Cell (i, j) over [s_i, s_i+1] x
 * [t_j, t_j+1] is, with blend CUBIC, the Hermite Coons patch (eq.
 * 1.13-1.15) of its four curve pieces with the ribbons of eq. 1.16 from
 * node data: x_s from the rows, x_t from the columns (one-sided where a
 * curve has a kink at a node) and one twist per node, the average of the
 * twists its cells propose (ZERO: 0; ADINI: the cell's Adini twist;
 * BESSEL: the cell's difference quotient (X(i+1,j+1) - X(i+1,j) -
 * X(i,j+1) + X(i,j)) / (ds dt)), weighted as Bessel weights the two sides
 * of a node (left cell (s_i+1 - s_i) / (s_i+1 - s_i-1), right cell
 * (s_i - s_i-1) / (s_i+1 - s_i-1), products in s and t). The result is C1
 * across inner rows and columns where the curves are C1. With blend LINEAR
 * each cell is the bilinearly blended Coons patch (C0 only, Fig. 1.3).
 * Node points are the average of the row's and the column's point. A
 * network of one cell equals coons_patch_new_hermite_coons() of its four
 * curves with the same twist. Copies the curves.
 * @param[in] rows     nrows >= 2 curves (row 0 is t0, the last t1)
 * @param[in] columns  ncolumns >= 2 curves (column 0 is s0, the last s1)
 * @param[in] opts     NULL for the defaults; node parameters strictly
 *                     increasing from exactly 0 to exactly 1
 * @return ::COONS_OK, ::COONS_E_INCOMPATIBLE (a node where row and column
 *         do not meet: the message names node (i, j) and the distance),
 *         ::COONS_E_INVALID (NULL, counts, nodes, twist, blend),
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_patch_new_network(coons_curve *const *rows, size_t nrows,
                                                  coons_curve *const *columns, size_t ncolumns,
                                                  const coons_network_options *opts,
                                                  coons_patch **out, coons_error *err);

/** The smoothness of a network across one inner row or column. */
typedef struct coons_network_seam {
    int dir;          /**< 0: the inner column s = s_i; 1: the inner row t = t_j */
    size_t index;     /**< i (column) or j (row), in the network's own numbering */
    double param;     /**< s_i or t_j */
    double c1_defect; /**< largest |B - A| of the cross derivative over the seam, relative
                           to the larger of |A|, |B| (A, B: the two sides' one-sided values) */
    double g1_angle;  /**< largest angle in degrees between the two sides' tangent planes */
    int face;         /**< coons_body_network_seams(): the body 2 face (::COONS_FACE_U0 ..)
                           that is the network, or -1 (a shell's surface); else -1 */
} coons_network_seam;

/**
 * Measures a network patch (also one transformed or reparametrised, as
 * coons_patch_kind() sees it) across each inner column and row, from
 * the one-sided derivatives of the cells on both sides, at 65 points along
 * the seam. Columns come first, in order, then rows; the seams are given
 * in the patch's own (s,t) after any reparametrisation.
 * @param[out] seams  NULL (count only) or room for cap entries
 * @param[out] n      the number of inner rows plus inner columns
 * @return ::COONS_OK (at most cap entries written, *n the full count),
 *         ::COONS_E_INVALID (not a network, NULL p or n).
 */
COONS_EXPORT coons_status coons_patch_network_seams(const coons_patch *p,
                                                    coons_network_seam *seams, size_t cap,
                                                    size_t *n, coons_error *err);

/** Deep copy. @return ::COONS_OK, ::COONS_E_INVALID (NULL), ::COONS_E_NOMEM. */
COONS_EXPORT coons_status coons_patch_copy(const coons_patch *p, coons_patch **out,
                                           coons_error *err);

/** Releases a patch; NULL is a harmless no-op. */
COONS_EXPORT void coons_patch_free(coons_patch *p);

/** The type the patch was built as (of a transformed or reparametrised
 * patch: the type of the patch it was made from). */
COONS_EXPORT coons_patch_type coons_patch_kind(const coons_patch *p);

/** Point at (s,t), parameters clamped to [0,1] (NaN counts as 0). */
COONS_EXPORT void coons_patch_eval(const coons_patch *p, double s, double t, double out[3]);

/**
 * Point and partial derivatives. order 0: out[0] = x. order 1 adds
 * out[1] = x_s, out[2] = x_t. order 2 adds out[3] = x_ss, out[4] = x_st,
 * out[5] = x_tt. out must hold 1, 3 or 6 vectors. Exact for every type
 * (NURBS by the quotient rule); at an interior knot the right-hand
 * derivative is returned, as for curves.
 */
COONS_EXPORT void coons_patch_eval_derivs(const coons_patch *p, double s, double t, int order,
                                          double out[][3]);

/**
 * Evaluates the patch on the tensor grid s[0..ns-1] x t[0..nt-1] into
 * out[(i*nt + j)*3] (out holds 3*ns*nt doubles); parameters are clamped as
 * in coons_patch_eval(). Basis and blending values are computed once per
 * parameter line (O(ns + nt) curve evaluations), so a grid costs little
 * more than its ns*nt sums; the values are bitwise those of
 * coons_patch_eval(). One scratch allocation per call.
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL arrays with ns, nt > 0),
 *         ::COONS_E_NOMEM (scratch memory).
 */
COONS_EXPORT coons_status coons_patch_eval_grid(const coons_patch *p, const double *s,
                                                size_t ns, const double *t, size_t nt,
                                                double *out, coons_error *err);

/**
 * Box of the patch's control data, used to scale tolerances: the corners
 * (bilinear), the control points of the boundary curves (ruled, Coons,
 * Hermite Coons; not the cross curves, which carry tangents), of the rows
 * and columns (network) or the net.
 */
COONS_EXPORT void coons_patch_control_bbox(const coons_patch *p, double lo[3], double hi[3]);

/**
 * The model format's name of a patch type ("bilinear", "hermite-coons",
 * ...), or NULL for a value that is not a patch type. Static storage.
 */
COONS_EXPORT const char *coons_patch_type_name(coons_patch_type type);

/**
 * The patch type of a model-format name (exact, case-sensitive).
 * @return ::COONS_OK, or ::COONS_E_INVALID for an unknown name (or NULL).
 */
COONS_EXPORT coons_status coons_patch_type_from_name(const char *name, coons_patch_type *out,
                                                     coons_error *err);

/**
 * The model format's key of a side of a Coons patch's boundary: "t0", "t1",
 * "s0", "s1" for ::COONS_SIDE_T0 .. ::COONS_SIDE_S1; NULL for any other value.
 */
COONS_EXPORT const char *coons_patch_side_name(int side);

#ifdef __cplusplus
}
#endif
#endif
