/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Bicubically blended (Hermite) Coons patch, seed 001 section 1.2.1:
 * x = h_c + h_d - h_cd (eq. 1.13, 1.14, 1.15) with the cubic Hermite basis
 * H0..H3. Seed 001's (u,v) are our (s,t).
 *
 * Corner points are the averaged boundary corners; corner tangents come
 * from the boundary curves (x_s(0,0) = t0'(0), x_t(0,0) = s0'(0), ...),
 * twists from the option (section 1.2.2: Ferguson/zero, Adini, Bessel,
 * explicit). Missing cross-boundary tangents are the ribbons of eq. 1.16,
 * e.g. x_t(s,0) = x_t(0,0) H0(s) + x_st(0,0) H1(s) + x_st(1,0) H2(s) +
 * x_t(1,0) H3(s), which is row/column of the eq. 1.15 matrix blended by H:
 * such a ribbon cancels against h_cd exactly (see hermite_sline).
 */
#include <string.h>

#include "agree.h"
#include "basis.h"
#include "patch_impl.h"

static const char *const cross_name[4] = {"t0", "t1", "s0", "s1"};

/* The options are usable: version, twist, explicit twists finite, all four
 * cross curves or none (*ncross gets how many). */
static coons_status check_options(const coons_hermite_options *opts, int *ncross,
                                  coons_error *err)
{
    if (COONS__RECORD_CHECK(err, "hermite-coons options", opts->version, COONS_HERMITE_OPTIONS))
        return COONS_E_INVALID;
    if ((int)opts->twist < (int)COONS_TWIST_ZERO || (int)opts->twist > (int)COONS_TWIST_EXPLICIT)
        return coons__error_set(err, COONS_E_INVALID, "hermite-coons patch: unknown twist %d",
                                (int)opts->twist);
    if (opts->twist == COONS_TWIST_EXPLICIT)
        for (int k = 0; k < 4; k++)
            if (!v3_finite(opts->twists[k]))
                return coons__error_set(err, COONS_E_INVALID,
                                        "hermite-coons patch: twist x_st(%d,%d) is not finite",
                                        k & 1, k >> 1);
    *ncross = 0;
    for (int k = 0; k < 4; k++) *ncross += opts->cross[k] != NULL;
    if (*ncross != 0 && *ncross != 4)
        return coons__error_set(err, COONS_E_INVALID,
                                "hermite-coons patch: give all four cross curves or none "
                                "(%d given)",
                                *ncross);
    return COONS_OK;
}

/* Corner tangents x_s, x_t from the boundary curves, index a + 2b like
 * the corners. */
static void corner_tangents(const coons_curve *const boundary[4], double xs[4][3],
                            double xt[4][3])
{
    double r[2][3];
    for (int k = 0; k < 4; k++) {
        int a = k & 1, b = k >> 1;
        coons_curve_eval_derivs(boundary[b ? COONS_SIDE_T1 : COONS_SIDE_T0], (double)a, 1, r);
        v3_copy(xs[k], r[1]);
        coons_curve_eval_derivs(boundary[a ? COONS_SIDE_S1 : COONS_SIDE_S0], (double)b, 1, r);
        v3_copy(xt[k], r[1]);
    }
}

/* The twists x_st at the corners (section 1.2.2): zero (Ferguson), Adini,
 * Bessel or explicit. */
static void corner_twists(const coons_hermite_options *opts, double X[4][3], double xs[4][3],
                          double xt[4][3], double tw[4][3])
{
    memset(tw, 0, 4 * sizeof tw[0]);
    double cell[3];
    v3_sub(cell, X[0], X[1]);
    v3_sub(cell, cell, X[2]);
    v3_add(cell, cell, X[3]);
    for (int k = 0; k < 4; k++) {
        int a = k & 1, b = k >> 1;
        switch (opts->twist) {
        case COONS_TWIST_ADINI: {
            /* [s1'(b) - s0'(b)] + [t1'(a) - t0'(a)] - cell: the x_st of eq. 1.11 */
            double ds[3], dt[3];
            v3_sub(ds, xt[1 + 2 * b], xt[2 * b]);
            v3_sub(dt, xs[2 + a], xs[a]);
            v3_add(tw[k], ds, dt);
            v3_sub(tw[k], tw[k], cell);
            break;
        }
        case COONS_TWIST_BESSEL: v3_copy(tw[k], cell); break;
        case COONS_TWIST_EXPLICIT: v3_copy(tw[k], opts->twists[k]); break;
        default: break;
        }
    }
}

/* The averaged corners and the matrix M of eq. 1.15. */
static void fill_record(coons_patch *p, double X[4][3], double xs[4][3], double xt[4][3],
                        double tw[4][3])
{
    memcpy(p->corner, X, sizeof p->corner);
    /* eq. 1.15: rows x(0,.), x_s(0,.), x_s(1,.), x(1,.); columns
     * .(.,0), ._t(.,0), ._t(.,1), .(.,1). */
    const double *rows[4][4] = {
        {X[0], xt[0], xt[2], X[2]},
        {xs[0], tw[0], tw[2], xs[2]},
        {xs[1], tw[1], tw[3], xs[3]},
        {X[1], xt[1], xt[3], X[3]},
    };
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) v3_copy(p->M[i][j], rows[i][j]);
}

coons_status coons_patch_new_hermite_coons(coons_curve *const *boundary_in,
                                           const coons_hermite_options *opts, coons_patch **out,
                                           coons_error *err)
{
    /* The public idiom (coons/types.h, "Arrays") passes handles as X *const *;
     * the code here only reads them. */
    const coons_curve *const *boundary = (const coons_curve *const *)boundary_in;
    if (!out) return coons__error_set(err, COONS_E_INVALID, "hermite-coons patch: out is NULL");
    *out = NULL;
    const coons_hermite_options defaults = COONS_HERMITE_OPTIONS_INIT;
    if (!opts) opts = &defaults;
    int ncross = 0;
    coons_status rc = check_options(opts, &ncross, err);
    if (rc) return rc;

    double X[4][3], tol;
    rc = coons__patch_corners(boundary, opts->tol, X, &tol, err);
    if (rc) return rc;

    double xs[4][3], xt[4][3];
    corner_tangents(boundary, xs, xt);

    coons__agree ag;
    if (ncross && coons__agree_cross(boundary, opts->cross, tol, &ag)) {
        /* cross t0/t1 = x_t(s,b) at s = 0,1; cross s0/s1 = x_s(a,t) at t = 0,1. */
        int c = ag.at, e = (int)ag.ta, k = c < 2 ? e + 2 * c : (c - 2) + 2 * e;
        return coons__error_set(err, COONS_E_INCOMPATIBLE,
                                "corner (s=%d,t=%d): cross %s(%d) and the boundary tangent "
                                "%s'(%d) are %g apart (tolerance %g)",
                                k & 1, k >> 1, cross_name[c], e, cross_name[ag.b], (int)ag.tb,
                                ag.dist, tol);
    }

    double tw[4][3];
    corner_twists(opts, X, xs, xt, tw);

    coons_patch *p = NULL;
    if ((rc = coons__patch_alloc(&coons__hermite_coons_kind, &p, err))) return rc;
    p->n = 4;
    p->twist = opts->twist;
    for (int k = 0; k < 4 && !rc; k++) {
        rc = coons_curve_copy(boundary[k], &p->curve[k], err);
        if (!rc && ncross) rc = coons_curve_copy(opts->cross[k], &p->cross[k], err);
    }
    if (rc) {
        coons_patch_free(p);
        return rc;
    }
    fill_record(p, X, xs, xt, tw);
    *out = p;
    return COONS_OK;
}

/* A line of four Hermite terms at x: basis H into L->b and H, the
 * boundary curves c0, c3 into vectors 0 and 3, and the cross curves c1, c2
 * (if given) into 1 and 2. */
static void hermite_line(double x, int order, const coons_curve *c0, const coons_curve *c1,
                         const coons_curve *c2, const coons_curve *c3, double H[12],
                         coons__pline *L)
{
    coons__pline_clear(L, 4, order);
    coons__hermite_basis(x, order, H);
    coons__pline_curve(L, 0, c0, x, order);
    coons__pline_curve(L, 3, c3, x, order);
    if (c1) {
        coons__pline_curve(L, 1, c1, x, order);
        coons__pline_curve(L, 2, c2, x, order);
    }
    for (int d = 0; d <= order; d++)
        for (int i = 0; i < 4; i++) L->b[d][i] = H[4 * d + i];
}

/* Tv = t0(s), x_t(s,0), x_t(s,1), t1(s); W = Tv - H(s) M. Without cross
 * curves the middle two Tv are the ribbons H(s) M[.][1..2] of eq. 1.16 and
 * W is zero there. */
static void sline(const coons_patch *p, double s, int order, coons__pline *L)
{
    double H[12];
    hermite_line(s, order, p->curve[COONS_SIDE_T0], p->cross[0], p->cross[1], p->curve[COONS_SIDE_T1], H,
                 L);
    for (int d = 0; d <= order; d++)
        for (int m = 0; m < 4; m++) {
            if (!p->cross[0] && (m == 1 || m == 2)) continue;
            for (int i = 0; i < 4; i++) v3_axpy(coons__lv(L, d, m), -H[4 * d + i], p->M[i][m]);
        }
}

/* Sv = s0(t), x_s(0,t), x_s(1,t), s1(t); ribbons x_s(a,t) = M[1 or 2][.] H(t). */
static void tline(const coons_patch *p, double t, int order, coons__pline *L)
{
    double H[12];
    hermite_line(t, order, p->curve[COONS_SIDE_S0], p->cross[2], p->cross[3], p->curve[COONS_SIDE_S1], H,
                 L);
    if (p->cross[2]) return;
    for (int d = 0; d <= order; d++)
        for (int j = 0; j < 4; j++) {
            v3_axpy(coons__lv(L, d, 1), H[4 * d + j], p->M[1][j]);
            v3_axpy(coons__lv(L, d, 2), H[4 * d + j], p->M[2][j]);
        }
}

const coons__patch_kind coons__hermite_coons_kind = {
    .type = COONS_PATCH_HERMITE_COONS, .eval = coons__boolsum_eval,
    .grid = coons__boolsum_grid, .sline = sline, .tline = tline,
    .control_bbox = coons__boolsum_control_bbox, .breaks = coons__boolsum_breaks,
    .copy = coons__boolsum_copy, .free = coons__boolsum_free, .space = coons__boolsum_space};

void coons_hermite_options_init(coons_hermite_options *o)
{
    const coons_hermite_options d = COONS_HERMITE_OPTIONS_INIT;
    if (o) *o = d;
}
