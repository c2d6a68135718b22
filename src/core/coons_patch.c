/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Bilinear, ruled and bilinearly blended Coons patches (seed 001):
 * - ruled surface x(s,t) = (1-t) c0(s) + t c1(s), eq. 1.2;
 * - Coons patch x = r_c + r_d - r_cd, eq. 1.5-1.8 (written out in eq. 1.11),
 *   with the blends 1-x, x or, for COONS_BLEND_CUBIC, f = 1 - 3x^2 + 2x^3
 *   and 1-f (section 1.2: any pair summing to 1 with f(0)=1, f(1)=0);
 * - bilinear patch, the ruled surface between the lines X00-X10 and
 *   X01-X11 (= r_cd of eq. 1.7).
 * Seed 001's (u,v) are our (s,t); x(s,0) = t0, x(s,1) = t1, x(0,t) = s0,
 * x(1,t) = s1 (model format). Corners shared by two curves are averaged.
 */
#include <string.h>

#include "agree.h"
#include "basis.h"
#include "patch_impl.h"

static const char *const curve_name[4] = {"t0", "t1", "s0", "s1"};

coons_status coons__patch_corners(const coons_curve *const b[4], double tol, double X[4][3],
                                  double *tol_used, coons_error *err)
{
    if (!b) return coons__error_set(err, COONS_E_INVALID, "boundary curve array is NULL");
    for (int k = 0; k < 4; k++)
        if (!b[k])
            return coons__error_set(err, COONS_E_INVALID, "boundary curve %s is NULL",
                                    curve_name[k]);
    if (!(tol >= 0.0) || !isfinite(tol))
        return coons__error_set(err, COONS_E_INVALID,
                                "tolerance %g is not a finite number >= 0", tol);
    double lo[3], hi[3];
    bbox_empty(lo, hi);
    for (int k = 0; k < 4; k++) {
        double a[3], c[3];
        coons_curve_control_bbox(b[k], a, c);
        bbox_add(lo, hi, a);
        bbox_add(lo, hi, c);
    }
    double tv = coons__tolerance(tol, bbox_diag(lo, hi));
    coons__agree r;
    if (coons__agree_patch_corners(b, tv, &r))
        return coons__error_set(err, COONS_E_INCOMPATIBLE,
                                "corner (s=%d,t=%d): %s(%d) and %s(%d) are %g apart "
                                "(tolerance %g)",
                                r.at & 1, r.at >> 1, curve_name[r.a], (int)r.ta, curve_name[r.b],
                                (int)r.tb, r.dist, tv);
    /* Corner X(s,t), index s + 2t, the average of the t-curve and the
     * s-curve that meet there. */
    for (int k = 0; k < 4; k++) {
        int s = k & 1, t = k >> 1;
        double a[3], c[3];
        coons_curve_eval(b[t ? COONS_SIDE_T1 : COONS_SIDE_T0], s, a);
        coons_curve_eval(b[s ? COONS_SIDE_S1 : COONS_SIDE_S0], t, c);
        for (int i = 0; i < 3; i++) X[k][i] = 0.5 * (a[i] + c[i]);
    }
    if (tol_used) *tol_used = tv;
    return COONS_OK;
}

static coons_status check_out(coons_patch **out, const char *what, coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "%s: out is NULL", what);
    *out = NULL;
    return COONS_OK;
}

coons_status coons_patch_new_bilinear(const double *flat, coons_patch **out, coons_error *err)
{
    const double(*corners)[3] = (const double(*)[3])flat; /* X00, X10, X01, X11 */
    coons_status rc = check_out(out, "bilinear patch", err);
    if (rc) return rc;
    if (!corners) return coons__error_set(err, COONS_E_INVALID, "bilinear patch: corners are NULL");
    for (int k = 0; k < 4; k++)
        if (!v3_finite(corners[k]))
            return coons__error_set(err, COONS_E_INVALID,
                                    "bilinear patch: corner X%d%d is not finite", k & 1, k >> 1);
    coons_patch *p = NULL;
    if ((rc = coons__patch_alloc(&coons__bilinear_kind, &p, err))) return rc;
    memcpy(p->corner, corners, sizeof p->corner);
    *out = p;
    return COONS_OK;
}

coons_status coons_patch_new_ruled(const coons_curve *c0, const coons_curve *c1, coons_patch **out,
                                   coons_error *err)
{
    coons_status rc = check_out(out, "ruled patch", err);
    if (rc) return rc;
    if (!c0 || !c1)
        return coons__error_set(err, COONS_E_INVALID, "ruled patch: curve c%d is NULL",
                                c0 ? 1 : 0);
    coons_patch *p = NULL;
    if ((rc = coons__patch_alloc(&coons__ruled_kind, &p, err))) return rc;
    if ((rc = coons_curve_copy(c0, &p->curve[0], err)) ||
        (rc = coons_curve_copy(c1, &p->curve[1], err))) {
        coons_patch_free(p);
        return rc;
    }
    coons_curve_eval(c0, 0.0, p->corner[0]);
    coons_curve_eval(c0, 1.0, p->corner[1]);
    coons_curve_eval(c1, 0.0, p->corner[2]);
    coons_curve_eval(c1, 1.0, p->corner[3]);
    *out = p;
    return COONS_OK;
}

coons_status coons_patch_new_coons(coons_curve *const *boundary_in, coons_blend blend,
                                   double tol, coons_patch **out, coons_error *err)
{
    /* The public idiom (coons/types.h, "Arrays") passes handles as X *const *;
     * the code here only reads them. */
    const coons_curve *const *boundary = (const coons_curve *const *)boundary_in;
    coons_status rc = check_out(out, "coons patch", err);
    if (rc) return rc;
    if (blend != COONS_BLEND_LINEAR && blend != COONS_BLEND_CUBIC)
        return coons__error_set(err, COONS_E_INVALID, "coons patch: unknown blend %d",
                                (int)blend);
    double X[4][3];
    if ((rc = coons__patch_corners(boundary, tol, X, NULL, err))) return rc;
    coons_patch *p = NULL;
    if ((rc = coons__patch_alloc(&coons__coons_patch_kind, &p, err))) return rc;
    p->blend = blend;
    for (int k = 0; k < 4; k++) {
        if ((rc = coons_curve_copy(boundary[k], &p->curve[k], err))) {
            coons_patch_free(p);
            return rc;
        }
    }
    memcpy(p->corner, X, sizeof X);
    /* eq. 1.7: rows along s (x(0,.), x(1,.)), columns along t. */
    v3_copy(p->M[0][0], X[0]);
    v3_copy(p->M[0][1], X[2]);
    v3_copy(p->M[1][0], X[1]);
    v3_copy(p->M[1][1], X[3]);
    *out = p;
    return COONS_OK;
}

/* Bilinear: Tv = the lines X00-X10 and X01-X11; bs unused (no S terms). */
static void bilinear_sline(const coons_patch *p, double s, int order, coons__pline *L)
{
    coons__pline_clear(L, 2, order);
    /* (1-s) a + s b rather than a + s (b - a): exact at both ends */
    for (int m = 0; m < 2; m++)
        for (int k = 0; k < 3; k++)
            coons__lv(L, 0, m)[k] = (1.0 - s) * p->corner[2 * m][k] + s * p->corner[2 * m + 1][k];
    if (order >= 1) {
        v3_sub(coons__lv(L, 1, 0), p->corner[1], p->corner[0]);
        v3_sub(coons__lv(L, 1, 1), p->corner[3], p->corner[2]);
    }
}

/* Ruled: Tv = c0(s), c1(s); no S terms. */
static void ruled_sline(const coons_patch *p, double s, int order, coons__pline *L)
{
    coons__pline_clear(L, 2, order);
    coons__pline_curve(L, 0, p->curve[0], s, order);
    coons__pline_curve(L, 1, p->curve[1], s, order);
}

static void coons_sline(const coons_patch *p, double s, int order, coons__pline *L)
{
    coons__pline_clear(L, 2, order);
    double b[6];
    coons__blend(p->blend, s, order, b);
    coons__pline_curve(L, 0, p->curve[COONS_SIDE_T0], s, order);
    coons__pline_curve(L, 1, p->curve[COONS_SIDE_T1], s, order);
    for (int d = 0; d <= order; d++) {
        L->b[d][0] = b[2 * d];
        L->b[d][1] = b[2 * d + 1];
        /* W_m = Tv_m - sum_i bs_i M[i][m] */
        for (int m = 0; m < 2; m++)
            for (int i = 0; i < 2; i++) v3_axpy(coons__lv(L, d, m), -b[2 * d + i], p->M[i][m]);
    }
}

/* The blends along t, and no curves: the t-line of bilinear and ruled. */
static void blend_tline(coons_blend blend, double t, int order, coons__pline *L)
{
    coons__pline_clear(L, 2, order);
    double b[6];
    coons__blend(blend, t, order, b);
    for (int d = 0; d <= order; d++) {
        L->b[d][0] = b[2 * d];
        L->b[d][1] = b[2 * d + 1];
    }
}

static void linear_tline(const coons_patch *p, double t, int order, coons__pline *L)
{
    (void)p;
    blend_tline(COONS_BLEND_LINEAR, t, order, L);
}

static void coons_tline(const coons_patch *p, double t, int order, coons__pline *L)
{
    blend_tline(p->blend, t, order, L);
    coons__pline_curve(L, 0, p->curve[COONS_SIDE_S0], t, order);
    coons__pline_curve(L, 1, p->curve[COONS_SIDE_S1], t, order);
}

static void bilinear_bbox(const coons_patch *p, double lo[3], double hi[3])
{
    for (int k = 0; k < 4; k++) bbox_add(lo, hi, p->corner[k]);
}

/* The Boolean-sum rows: eval, grid and the record parts of boolean_sum.c
 * with this file's lines. */
#define BOOLSUM_ROW(type_, sline_, tline_, bbox_, breaks_)                               \
    {.type = type_, .eval = coons__boolsum_eval, .grid = coons__boolsum_grid,             \
     .sline = sline_, .tline = tline_, .control_bbox = bbox_, .breaks = breaks_,          \
     .copy = coons__boolsum_copy, .free = coons__boolsum_free, .space = coons__boolsum_space}
const coons__patch_kind coons__bilinear_kind =
    BOOLSUM_ROW(COONS_PATCH_BILINEAR, bilinear_sline, linear_tline, bilinear_bbox, NULL);
const coons__patch_kind coons__ruled_kind =
    BOOLSUM_ROW(COONS_PATCH_RULED, ruled_sline, linear_tline, coons__boolsum_control_bbox,
                coons__boolsum_breaks);
const coons__patch_kind coons__coons_patch_kind =
    BOOLSUM_ROW(COONS_PATCH_COONS, coons_sline, coons_tline, coons__boolsum_control_bbox,
                coons__boolsum_breaks);
