/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The Boolean sum x = r_c + r_d - r_cd of seed 001 eq. 1.8 (and its
 * Hermite form h_c + h_d - h_cd of eq. 1.13-1.15), evaluated from an
 * s-line and a t-line (see patch_impl.h) that the type's row gives: the
 * evaluator of the bilinear, ruled, Coons and Hermite Coons patches, and
 * the parts of their records they share (boundary and cross curves).
 *
 * eval and grid share one combining routine so that the grid is bitwise
 * equal to pointwise evaluation: samplers rely on it where neighbouring
 * grids meet.
 */
#include <string.h>

#include "patch_impl.h"

void coons__pline_clear(coons__pline *L, int n, int order)
{
    memset(L, 0, sizeof *L);
    L->n = n;
    L->order = order;
}

void coons__pline_curve(coons__pline *L, int m, const coons_curve *c, double x, int order)
{
    double r[3][3];
    coons_curve_eval_derivs(c, x, order, r);
    for (int d = 0; d <= order; d++) v3_copy(coons__lv(L, d, m), r[d]);
}

/* x = sum_m sb[m] tv[m] + tb[m] sv[m] (see patch_impl.h); n is a constant
 * at every call site so the loop unrolls. */
static inline void combine(int n, const double *sb, const double *sv, const double *tb,
                           const double *tv, double out[3])
{
    double x = 0.0, y = 0.0, z = 0.0;
    for (int m = 0; m < n; m++) {
        x += sb[m] * tv[3 * m] + tb[m] * sv[3 * m];
        y += sb[m] * tv[3 * m + 1] + tb[m] * sv[3 * m + 1];
        z += sb[m] * tv[3 * m + 2] + tb[m] * sv[3 * m + 2];
    }
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

static void combine_lines(const coons__pline *S, const coons__pline *T, int a, int b,
                          double out[3])
{
    if (S->n == 2)
        combine(2, S->b[a], S->v[a], T->b[b], T->v[b], out);
    else
        combine(4, S->b[a], S->v[a], T->b[b], T->v[b], out);
}

void coons__boolsum_eval(const coons_patch *p, double s, double t, int order, double out[][3])
{
    coons__pline S, T;
    p->kind->sline(p, s, order, &S);
    p->kind->tline(p, t, order, &T);
    combine_lines(&S, &T, 0, 0, out[0]);
    if (order >= 1) {
        combine_lines(&S, &T, 1, 0, out[1]);
        combine_lines(&S, &T, 0, 1, out[2]);
    }
    if (order >= 2) {
        combine_lines(&S, &T, 2, 0, out[3]);
        combine_lines(&S, &T, 1, 1, out[4]);
        combine_lines(&S, &T, 0, 2, out[5]);
    }
}

/* One cached t-line: 4 blend values and 4 vectors. */
#define TLINE_DOUBLES 16

static inline void grid_lines(int n, const coons_patch *p, const double *s, size_t ns, size_t nt,
                              const double *cache, double *out)
{
    coons__pline S;
    for (size_t i = 0; i < ns; i++) {
        p->kind->sline(p, clamp01(s[i]), 0, &S);
        double *o = out + i * nt * 3;
        for (size_t j = 0; j < nt; j++) {
            const double *c = cache + j * TLINE_DOUBLES;
            combine(n, S.b[0], S.v[0], c, c + 4, o + 3 * j);
        }
    }
}

coons_status coons__boolsum_grid(const coons_patch *p, const double *s, size_t ns,
                                 const double *t, size_t nt, double *out, coons_error *err)
{
    double *cache = coons__malloc_array(nt, TLINE_DOUBLES * sizeof(double));
    if (!cache) return coons__error_nomem(err);
    coons__pline T;
    for (size_t j = 0; j < nt; j++) {
        p->kind->tline(p, clamp01(t[j]), 0, &T);
        double *c = cache + j * TLINE_DOUBLES;
        memcpy(c, T.b[0], 4 * sizeof(double));
        memcpy(c + 4, T.v[0], 12 * sizeof(double));
    }
    if (p->n == 2)
        grid_lines(2, p, s, ns, nt, cache, out);
    else
        grid_lines(4, p, s, ns, nt, cache, out);
    coons__free(cache);
    return COONS_OK;
}

/* Boundary curves only: cross curves carry tangents, not positions
 * (model format, "Consistency": points only). */
void coons__boolsum_control_bbox(const coons_patch *p, double lo[3], double hi[3])
{
    for (int k = 0; k < 4; k++) {
        if (!p->curve[k]) continue;
        double a[3], b[3];
        coons_curve_control_bbox(p->curve[k], a, b);
        bbox_add(lo, hi, a);
        bbox_add(lo, hi, b);
    }
}

/* T0, T1 and the cross curves x_t(s,0), x_t(s,1) run along s; S0, S1 and
 * x_s(0,t), x_s(1,t) along t (a ruled patch has only T0 = c0, T1 = c1). */
/* The blends (Hermite: cubic) times polynomials of the other parameter,
 * plus the curves (and cross curves) running along dir: their spaces
 * joined (a rational curve makes the sum NONE: the terms' denominators
 * differ). Bilinear and ruled patches have linear blends. */
void coons__boolsum_space(const coons_patch *p, int dir, coons__space *S)
{
    *S = coons__space_poly(p->n == 4 ? 3 : coons__blend_degree(p->blend));
    int a = dir == 0 ? COONS_SIDE_T0 : COONS_SIDE_S0, b = dir == 0 ? COONS_SIDE_T1 : COONS_SIDE_S1;
    coons__space_join(S, coons__curve_space(p->curve[a]));
    coons__space_join(S, coons__curve_space(p->curve[b]));
    coons__space_join(S, coons__curve_space(p->cross[dir == 0 ? 0 : 2]));
    coons__space_join(S, coons__curve_space(p->cross[dir == 0 ? 1 : 3]));
}

void coons__boolsum_breaks(const coons_patch *p, int dir, coons__breaks *B)
{
    coons__curve_breaks(p->curve[dir == 0 ? COONS_SIDE_T0 : COONS_SIDE_S0], B);
    coons__curve_breaks(p->curve[dir == 0 ? COONS_SIDE_T1 : COONS_SIDE_S1], B);
    coons__curve_breaks(p->cross[dir == 0 ? 0 : 2], B);
    coons__curve_breaks(p->cross[dir == 0 ? 1 : 3], B);
}

coons_status coons__boolsum_copy(const coons_patch *p, coons_patch *d, coons_error *err)
{
    for (int k = 0; k < 4; k++) d->curve[k] = d->cross[k] = NULL;
    coons_status rc = COONS_OK;
    for (int k = 0; k < 4 && !rc; k++) {
        if (p->curve[k]) rc = coons_curve_copy(p->curve[k], &d->curve[k], err);
        if (!rc && p->cross[k]) rc = coons_curve_copy(p->cross[k], &d->cross[k], err);
    }
    return rc;
}

void coons__boolsum_free(coons_patch *p)
{
    for (int k = 0; k < 4; k++) {
        coons_curve_free(p->curve[k]);
        coons_curve_free(p->cross[k]);
    }
}
