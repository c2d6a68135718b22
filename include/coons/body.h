/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/body.h
 * @brief Trivariate bodies over (u,v,w) in [0,1]^3 (seed 000): Coons body 0
 *        (8 points), body 1 (12 edge curves), body 2 (6 boundary patches),
 *        Bezier and B-spline/NURBS volumes, and shells (a patch made solid).
 *
 * Constructors deep-copy their inputs; the body belongs to the caller and is
 * released with coons_body_free(). Bodies are immutable: any number of
 * threads may evaluate one body at once.
 *
 * Index conventions (model format): corner P_ijk of body 0 is corners[4i+2j+k].
 * Body 1 edges are ordered u00 u01 u10 u11 (uJK = C(u,J,K)), v00 v01 v10 v11
 * (vIK = C(I,v,K)), w00 w01 w10 w11 (wIJ = C(I,J,w)). Body 2 faces are
 * ordered u0 u1 (X_I(v,w) = C(I,v,w), patch (s,t) = (v,w)), v0 v1
 * (Y_J(u,w), (s,t) = (u,w)), w0 w1 (Z_K(u,v), (s,t) = (u,v)).
 * Volume points are points[((i*nv + j)*nw + k)*3], i along u.
 */
#ifndef COONS_BODY_H
#define COONS_BODY_H

#include "coons/types.h"
#include "coons/patch.h" /* coons_network_seam */

#ifdef __cplusplus
extern "C" {
#endif

typedef enum coons_body_type {
    COONS_BODY_BODY0 = 0,
    COONS_BODY_BODY1,
    COONS_BODY_BODY2,
    COONS_BODY_BEZIER,
    COONS_BODY_BSPLINE,
    COONS_BODY_SHELL,
    COONS_BODY_MORPH
} coons_body_type;

/** Largest number of control points (product of the three counts) of a tensor volume. */
#define COONS_BODY_MAX_POINTS 16777216

/** Edges: body 1 edge indices (coons_body_edge_name(): "u00" is C(u,0,0), ...). */
typedef enum coons_body_edge {
    COONS_EDGE_U00 = 0, COONS_EDGE_U01, COONS_EDGE_U10, COONS_EDGE_U11,
    COONS_EDGE_V00, COONS_EDGE_V01, COONS_EDGE_V10, COONS_EDGE_V11,
    COONS_EDGE_W00, COONS_EDGE_W01, COONS_EDGE_W10, COONS_EDGE_W11
} coons_body_edge;

/** Faces: body 2 face indices, also the faces of any body's boundary
 * (coons_body_face_name(): "u0" is u = 0, ...). */
typedef enum coons_body_face {
    COONS_FACE_U0 = 0, COONS_FACE_U1, COONS_FACE_V0, COONS_FACE_V1,
    COONS_FACE_W0, COONS_FACE_W1
} coons_body_face;

/**
 * Coons body 0: trilinear interpolation T(P_ijk; u,v,w) of 8 points
 * (seed 000 section 2.2); with ::COONS_BLEND_CUBIC the blends 1-x, x are
 * replaced by f(x), 1-f(x).
 * @param[in] corners 24 doubles: P_ijk (x y z) at index 4i + 2j + k (a
 *                    `double c[24]`, or `c[0]` of a `double c[8][3]`)
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL or non-finite corners, an
 *         unknown blend), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_new_body0(const double *corners, coons_blend blend,
                                               coons_body **out, coons_error *err);

/**
 * Coons body 1 from 12 edge curves (seed 000 section 2.3):
 * C1 = sum of the three bilinear blends of edge curves - 2 T(C_ijk).
 * The three edges meeting at each corner must meet within `tol`
 * (::COONS_TOL_DEFAULT: 1e-9 of the control box diagonal); the corner used
 * is their average.
 * @param[in] edges 12 curves indexed ::COONS_EDGE_U00 .. ::COONS_EDGE_W11 (an
 *                  array of handles: see "Arrays" in coons/types.h)
 * @return ::COONS_OK, ::COONS_E_INCOMPATIBLE (names the corner and the
 *         distance), ::COONS_E_INVALID, ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_new_body1(coons_curve *const *edges, coons_blend blend,
                                               double tol, coons_body **out, coons_error *err);

/**
 * Coons body 2 from 6 boundary patches (seed 000 section 2.4):
 * C2 = D - C1 - T, with C1 and T built from the faces' shared boundary
 * curves (each edge point the average of the two faces that carry it).
 * Faces must agree parametrically along their 12 shared edges within
 * `tol`, checked at sample points along each edge.
 * @param[in] faces 6 patches indexed ::COONS_FACE_U0 .. ::COONS_FACE_W1 (an
 *                  array of handles: see "Arrays" in coons/types.h)
 * @return ::COONS_OK, ::COONS_E_INCOMPATIBLE (names the edge, the parameter
 *         and the distance), ::COONS_E_INVALID, ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_new_body2(coons_patch *const *faces, coons_blend blend,
                                               double tol, coons_body **out, coons_error *err);

/**
 * Tensor-product Bezier volume; n[0..2] >= 2 points along u, v, w.
 * @return ::COONS_OK, ::COONS_E_INVALID (fewer than 2 points along a
 *         direction, non-finite points), ::COONS_E_LIMIT (more than
 *         ::COONS_BODY_MAX_POINTS, or a degree above
 *         ::COONS_SPLINE_MAX_DEGREE), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_new_bezier(const double *points, const size_t n[3],
                                                coons_body **out, coons_error *err);

/**
 * Tensor-product B-spline / NURBS volume of degrees degree[0..2].
 * @param[in] knots_u,knots_v,knots_w each NULL (clamped uniform) or
 *                    n[d]+degree[d]+1 values
 * @param[in] weights NULL or n[0]*n[1]*n[2] values > 0, indexed like the points
 * @return ::COONS_OK, ::COONS_E_INVALID (a degree outside
 *         1..::COONS_SPLINE_MAX_DEGREE, too few points, bad knots or
 *         weights, non-finite points), ::COONS_E_LIMIT (more than
 *         ::COONS_BODY_MAX_POINTS), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_new_bspline(const int degree[3], const double *points,
                                                 const size_t n[3], const double *knots_u,
                                                 const double *knots_v, const double *knots_w,
                                                 const double *weights, coons_body **out,
                                                 coons_error *err);

/** Where a shell's solid lies relative to its surface (coons_body_new_shell()). */
typedef enum coons_shell_side {
    COONS_SHELL_BOTH = 0, /**< the surface is the mid-surface (c = 1/2) */
    COONS_SHELL_FRONT,    /**< on the normal's side: the surface is the w0 face (c = 0) */
    COONS_SHELL_BACK      /**< against the normal: the surface is the w1 face (c = 1) */
} coons_shell_side;

/**
 * A surface made solid (coons-model(5), "Shells"):
 * S(u,v,w) = x(u,v) + (w - c) h n(u,v), with x the patch, n = x_s x x_t /
 * |x_s x x_t| its unit normal, h the thickness and c from `side`. The
 * Jacobian is exact: dS/du = x_s + (w - c) h n_s with n_s from the
 * patch's second derivatives (likewise v), dS/dw = h n, so det J = h |N|
 * at the surface (a shell is right-handed) and becomes <= 0 where the
 * offset (w - c) h passes a centre of curvature: a shell thicker than the
 * surface's radius of curvature folds (coons_body_min_jacobian() finds it).
 * The normal must be defined: it is checked on a 65 x 65 grid of (s,t)
 * (|x_s x x_t| <= 1e-12 |x_s| |x_t|, or 0, is undefined). Copies the patch.
 * The control box is the patch's, grown by h on every side.
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL, thickness not finite and
 *         > 0, unknown side, an undefined normal: the message gives (s,t)),
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_new_shell(const coons_patch *surface, double thickness,
                                               coons_shell_side side, coons_body **out,
                                               coons_error *err);

/**
 * The seams of every network patch of a body (coons_patch_network_seams()):
 * the faces of a body 2 in face order, the surface of a shell, as the body
 * is instanced (through transforms, which change lengths and angles), each
 * entry's `face` saying which. Bodies of other types have none.
 * @param[out] seams NULL (count only) or room for cap entries
 * @param[out] n     the number of seams
 * @return ::COONS_OK (at most cap written), ::COONS_E_INVALID (NULL b or n),
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_network_seams(const coons_body *b,
                                                   coons_network_seam *seams, size_t cap,
                                                   size_t *n, coons_error *err);

/**
 * The affine image G = M F + t of a body (coons-model(5), "Definitions and
 * references", "transform"): points map by M x + t, the Jacobian by M
 * (J_G = M J_F, det J_G = det M det J_F), exact for every type. With
 * det M < 0 the body is mirrored: left-handed, and still meshed outward.
 * The control box is the box of the 8 mapped corners of b's. The result's
 * type (coons_body_kind()) is b's. Copies b: the caller keeps b and
 * frees the result with coons_body_free().
 * @param[in]  b   the body
 * @param[in]  m   12 doubles, the row-major 3 x 4 matrix [[a,b,c,tx],[d,e,f,ty],
 *                 [g,h,i,tz]] (a `double m[12]`, or `m[0]` of a `double m[3][4]`)
 *                 of y = M x + t: 12 finite numbers with M regular
 *                 (|det M| > 1e-12 x the product of M's row norms).
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL argument, an entry not
 *         finite, or M singular: the message gives the determinant),
 *         ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_new_transformed(const coons_body *b, const double *m,
                                                     coons_body **out, coons_error *err);

/** Deep copy. @return ::COONS_OK or ::COONS_E_NOMEM. */
COONS_EXPORT coons_status coons_body_copy(const coons_body *b, coons_body **out,
                                          coons_error *err);

/** Releases a body; NULL is a harmless no-op. */
COONS_EXPORT void coons_body_free(coons_body *b);

/** The type the body was built as (of a transformed body: the type of the
 * body it was made from). */
COONS_EXPORT coons_body_type coons_body_kind(const coons_body *b);

/** Point F(u,v,w), parameters clamped to [0,1]. */
COONS_EXPORT void coons_body_eval(const coons_body *b, double u, double v, double w,
                                  double out[3]);

/**
 * Point and Jacobian: jac[r][c] = d x_r / d q_c with q = (u, v, w), so
 * the columns are d/du, d/dv, d/dw. Returns det(jac).
 */
COONS_EXPORT double coons_body_eval_jacobian(const coons_body *b, double u, double v, double w,
                                             double out[3], double jac[3][3]);

/**
 * Evaluates the body on the grid u[0..nu-1] x v[0..nv-1] x w[0..nw-1] into
 * out[((i*nv + j)*nw + k)*3]. Basis, blend and boundary values are computed
 * once per parameter line; no allocation per point. A grid with one of
 * nu, nv, nw equal to 1 samples a boundary face. Parameters need not be
 * sorted and are clamped to [0,1]. Each point is computed from its own
 * (u,v,w) only, by the same operations whatever the rest of the grid, so
 * two grids that share a parameter triple give bitwise-equal points there
 * (seams of face grids weld exactly). Agrees with coons_body_eval() to
 * rounding, not bitwise.
 * @return ::COONS_OK, ::COONS_E_NOMEM (scratch), ::COONS_E_LIMIT (sizes overflow),
 *         ::COONS_E_INVALID (NULL arrays with non-zero sizes).
 */
COONS_EXPORT coons_status coons_body_eval_grid(const coons_body *b, const double *u, size_t nu,
                                               const double *v, size_t nv, const double *w,
                                               size_t nw, double *out, coons_error *err);

/**
 * coons_body_eval_grid() on `threads` threads (0: every online core; at most
 * 1024): the grid is cut along u into one run of u values per thread, each
 * evaluated by coons_body_eval_grid(), so the output is the same, byte for
 * byte, for every thread count (each point depends on its own (u,v,w)
 * only). Where threads cannot be started, the calling thread does their
 * share. The per-line tabulations along v and w are repeated per thread.
 * @return as coons_body_eval_grid(): ::COONS_OK, ::COONS_E_NOMEM,
 *         ::COONS_E_LIMIT, ::COONS_E_INVALID; with several runs failing,
 *         the error of the first along u.
 */
COONS_EXPORT coons_status coons_body_eval_grid_threads(const coons_body *b, const double *u,
                                                       size_t nu, const double *v, size_t nv,
                                                       const double *w, size_t nw, double *out,
                                                       unsigned threads, coons_error *err);

/**
 * Points at n scattered parameter triples uvw[3i], uvw[3i+1], uvw[3i+2]
 * (clamped to [0,1]) in one call: xyz[3i..3i+2] is what coons_body_eval()
 * gives there, bitwise. With `jac` or `det` not NULL, the Jacobians too:
 * jac[9i + 3r + c] = d x_r / d q_c and det[i] = det J, and then xyz is
 * what coons_body_eval_jacobian() gives (the same point to rounding).
 * No allocation; no per-point call overhead for bindings (Python, the
 * browser) that evaluate arrays. A body 2 whose faces are all
 * bezier-surface or bspline-surface patches keeps from its construction
 * (read-only after it) what every point shares: each face's bases at its
 * ends and its net combined there; a point then computes each face's two
 * bases once for the face and the edges it carries (tools/bench/bench_points
 * times it), with the same floating-point operations, so the same bits.
 * Without Jacobians, where its faces are all polynomial or all rational,
 * such a body evaluates the whole batch in one loop with no call per point
 * (coons_body_eval() takes that loop for one point: the same bits).
 * @param[in]  uvw  3 n parameters
 * @param[out] xyz  3 n coordinates
 * @param[out] jac  NULL or 9 n partials (row-major 3 x 3 per point)
 * @param[out] det  NULL or n determinants
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL body; NULL uvw or xyz with
 *         n > 0).
 */
COONS_EXPORT coons_status coons_body_eval_points(const coons_body *b, size_t n,
                                                 const double *uvw, double *xyz, double *jac,
                                                 double *det, coons_error *err);

/** Box of the body's control data (corners, curve or patch control points, net). */
COONS_EXPORT void coons_body_control_bbox(const coons_body *b, double lo[3], double hi[3]);

/**
 * Volume of the body, the integral of det J over the unit cube, by
 * tensor Gauss-Legendre quadrature (5 points per direction and cell) on
 * cells bounded by the breakpoints of the body's data (knots of B-spline
 * curves, surfaces and volumes, Coons cubic segment ends), refined along
 * each direction where needed until the error estimate is below `rel_tol`
 * (relative; <= 0 means 1e-9), within ::COONS_BODY_VOLUME_MAX_EVALS
 * Jacobian evaluations (coons_body_volume_bounded() with its defaults; it
 * also reports the achieved accuracy). The volume is signed: negative for a
 * left-handed body (det J < 0), and folded regions count with their sign.
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL arguments), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_volume(const coons_body *b, double rel_tol,
                                            double *volume, coons_error *err);

/** Default evaluation budget of coons_body_volume_bounded(). */
#define COONS_BODY_VOLUME_MAX_EVALS ((size_t)1 << 20)

/**
 * The signed volume (as coons_body_volume()) with bounded work and its
 * achieved accuracy. Gauss-Legendre (5 points) on the cells bounded by
 * the breakpoints of the body's data; each direction's sub-cells are
 * doubled where the estimates show the error, until the error estimate
 * is below `rel_tol` relative (<= 0 means 1e-9), or until the next step
 * would take the Jacobian evaluations past `max_evals` (0 means
 * ::COONS_BODY_VOLUME_MAX_EVALS): the best estimate so far is then
 * returned, with its estimate. `error` (may be NULL) receives the error
 * estimate (absolute; infinite if the budget allowed none), `evaluations`
 * (may be NULL) the number of det J evaluations made.
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL arguments), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_volume_bounded(const coons_body *b, double rel_tol,
                                                    size_t max_evals, double *volume,
                                                    double *error, size_t *evaluations,
                                                    coons_error *err);

/**
 * Smallest det J over an (n+1)^3 sampling of the unit cube (n >= 1), and
 * where it was found (`where` may be NULL; the first lattice point in
 * (u,v,w) lexicographic order on ties). A negative value means the body
 * folds over itself (or is left-handed everywhere: compare with the sign of
 * coons_body_volume()).
 * @return ::COONS_OK, ::COONS_E_INVALID (n = 0), ::COONS_E_LIMIT (n > 2^20).
 */
COONS_EXPORT coons_status coons_body_min_jacobian(const coons_body *b, unsigned n,
                                                  double *min_det, double where[3],
                                                  coons_error *err);

/**
 * The model format's name of a body type ("body0", "bezier-volume", ...),
 * or NULL for a value that is not a body type. Static storage.
 */
COONS_EXPORT const char *coons_body_type_name(coons_body_type type);

/**
 * The body type of a model-format name (exact, case-sensitive).
 * @return ::COONS_OK, or ::COONS_E_INVALID for an unknown name (or NULL).
 */
COONS_EXPORT coons_status coons_body_type_from_name(const char *name, coons_body_type *out,
                                                    coons_error *err);

/**
 * The model format's key of a body 1 edge ("u00" .. "w11", in the order of
 * ::COONS_EDGE_U00 ..), or NULL for any other value.
 */
COONS_EXPORT const char *coons_body_edge_name(int edge);

/**
 * The model format's key of a face ("u0", "u1", "v0", "v1", "w0", "w1", in
 * the order of ::COONS_FACE_U0 ..), or NULL for any other value.
 */
COONS_EXPORT const char *coons_body_face_name(int face);

/** The path of a morph in time (coons-model(5), "morph"). */
typedef enum coons_morph_path {
    /** Piecewise linear between neighbouring keys. */
    COONS_MORPH_LINEAR = 0,
    /** The C1 non-uniform Catmull-Rom spline through the keys: per unit
     * time, the tangent at an inner key k is (K_k+1 - K_k-1) / (at_k+1 -
     * at_k-1), at the ends the one-sided quotients; each interval is the
     * cubic Hermite between its keys. With two keys, the same as linear. */
    COONS_MORPH_SMOOTH = 1
} coons_morph_path;

/** Largest number of keys of a morph. */
#define COONS_MORPH_MAX_KEYS 4096

/**
 * The weights W_k(t) of a morph's path at time t (clamped to [0,1]):
 * M(t) = sum_k W_k(t) K_k. They sum to 1; at t = at[k], W_k = 1 and the
 * others are 0. With `dw` not NULL, dw[k] = dW_k/dt as well (the
 * one-sided derivative of the interval that holds t; at an inner key the
 * interval that starts there).
 * @param[in]  nkeys 2 .. ::COONS_MORPH_MAX_KEYS
 * @param[in]  at    NULL (uniform, k/(nkeys-1)) or nkeys times strictly
 *                   increasing from exactly 0 to exactly 1
 * @param[out] w     nkeys weights
 * @param[out] dw    NULL or nkeys derivatives
 * @return ::COONS_OK, ::COONS_E_INVALID (bad count, times or path; NULL w).
 */
COONS_EXPORT coons_status coons_morph_weights(size_t nkeys, const double *at,
                                              coons_morph_path path, double t, double *w,
                                              double *dw, coons_error *err);

/**
 * A metamorphosis (seed 000 section 4, Fig. 10; coons-model(5), "morph"):
 * the pointwise blend M(u,v,w) = sum_k W_k(t) K_k(u,v,w) of 2 or more key
 * bodies of any types with the weights of coons_morph_weights(), and its
 * Jacobian sum_k W_k(t) J_k, exact. A morph may be a key of another. The
 * control box is the box of all keys' boxes (whatever t). Keys that differ
 * in handedness make det J change sign at some time: that is a fold, found
 * by coons_body_min_jacobian() like any other. Copies the keys: the caller
 * keeps them. The type is ::COONS_BODY_MORPH.
 * @param[in] keys  nkeys bodies (an array of handles, see "Arrays" in
 *                  coons/types.h)
 * @param[in] at    NULL (uniform) or nkeys key times, strictly increasing
 *                  from exactly 0 to exactly 1
 * @param[in] t     the time, in [0,1]
 * @return ::COONS_OK, ::COONS_E_INVALID (NULL argument, fewer than 2 or
 *         more than ::COONS_MORPH_MAX_KEYS keys, bad times or path, t outside
 *         [0,1]: the message says which), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_new_morph(coons_body *const *keys, size_t nkeys,
                                               const double *at, coons_morph_path path,
                                               double t, coons_body **out, coons_error *err);

/**
 * The number of keys of a morph body (seen through transforms: a
 * transformed morph reports its morph's keys), or 0 for any other body.
 */
COONS_EXPORT size_t coons_body_morph_keys(const coons_body *b);

/**
 * Key k of a morph body (through transforms, the key as the morph holds it,
 * not transformed), its time in *at (may be NULL), or NULL when b is no
 * morph or k is out of range. Borrowed: valid while b lives.
 */
COONS_EXPORT const coons_body *coons_body_morph_key(const coons_body *b, size_t k, double *at);

/**
 * The path and current time of a morph body (through transforms).
 * @return ::COONS_OK, or ::COONS_E_INVALID when b is no morph.
 */
COONS_EXPORT coons_status coons_body_morph_info(const coons_body *b, coons_morph_path *path,
                                                double *t, coons_error *err);

/**
 * A copy of b in which every morph, also morphs that are keys of morphs
 * and morphs inside transformed bodies, is taken at time t instead of its
 * own. A body without morphs is copied unchanged.
 * @return ::COONS_OK, ::COONS_E_INVALID (t outside [0,1], NULL), ::COONS_E_NOMEM.
 */
COONS_EXPORT coons_status coons_body_at_time(const coons_body *b, double t, coons_body **out,
                                             coons_error *err);

#ifdef __cplusplus
}
#endif
#endif
