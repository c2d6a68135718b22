/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The patch record and its evaluation (seed 001, section 1.2): lifecycle,
 * bounding box, and the Boolean sum x = r_c + r_d - r_cd of eq. 1.8 (and its
 * Hermite form h_c + h_d - h_cd of eq. 1.13-1.15) evaluated from an s-line
 * and a t-line (see patch_impl.h). Tensor-product surfaces are dispatched to
 * tensor_surface.c.
 *
 * eval, eval_derivs and eval_grid share one combining routine so that the
 * grid is bitwise equal to pointwise evaluation: samplers rely on it where
 * neighbouring grids meet.
 */
#include <string.h>

#include "patch_impl.h"

coons_status coons__patch_alloc(coons_patch_type type, coons_patch **out, coons_error *err)
{
    coons_patch *p = coons__calloc(1, sizeof *p);
    if (!p) return coons__error_nomem(err);
    p->type = type;
    p->n = 2;
    *out = p;
    return COONS_OK;
}

void coons_patch_free(coons_patch *p)
{
    if (!p) return;
    for (int k = 0; k < 4; k++) {
        coons_curve_free(p->curve[k]);
        coons_curve_free(p->cross[k]);
    }
    coons__free(p->pts);
    coons__free(p->w);
    coons__free(p->pw);
    coons__free(p->ks);
    coons__free(p->kt);
    coons__free(p);
}

coons_patch_type coons_patch_get_type(const coons_patch *p) { return p->type; }

coons_status coons_patch_copy(const coons_patch *p, coons_patch **out, coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "patch copy: out is NULL");
    *out = NULL;
    if (!p) return coons__error_set(err, COONS_E_INVALID, "patch copy: patch is NULL");
    coons_patch *d = coons__malloc(sizeof *d);
    if (!d) return coons__error_nomem(err);
    *d = *p;
    /* Detach every owned pointer first so a partial copy frees cleanly. */
    for (int k = 0; k < 4; k++) d->curve[k] = d->cross[k] = NULL;
    d->pts = d->w = d->pw = d->ks = d->kt = NULL;
    coons_status rc = COONS_OK;
    for (int k = 0; k < 4 && !rc; k++) {
        if (p->curve[k]) rc = coons_curve_copy(p->curve[k], &d->curve[k], err);
        if (!rc && p->cross[k]) rc = coons_curve_copy(p->cross[k], &d->cross[k], err);
    }
    if (!rc && p->pts) rc = coons__surface_copy(p, d, err);
    if (rc) {
        coons_patch_free(d);
        return rc;
    }
    *out = d;
    return COONS_OK;
}

void coons_patch_control_bbox(const coons_patch *p, double lo[3], double hi[3])
{
    bbox_empty(lo, hi);
    if (p->type == COONS_PATCH_BILINEAR) {
        for (int k = 0; k < 4; k++) bbox_add(lo, hi, p->corner[k]);
        return;
    }
    if (p->pts) {
        for (size_t i = 0; i < p->ns * p->nt; i++) bbox_add(lo, hi, p->pts + 3 * i);
        return;
    }
    /* Boundary curves only: cross curves carry tangents, not positions
     * (model format, "Consistency": points only). */
    for (int k = 0; k < 4; k++) {
        if (!p->curve[k]) continue;
        double a[3], b[3];
        coons_curve_control_bbox(p->curve[k], a, b);
        bbox_add(lo, hi, a);
        bbox_add(lo, hi, b);
    }
}

void coons__patch_sline(const coons_patch *p, double s, int order, coons__pline *L)
{
    if (p->type == COONS_PATCH_HERMITE_COONS)
        coons__hermite_sline(p, s, order, L);
    else
        coons__coons_sline(p, s, order, L);
}

void coons__patch_tline(const coons_patch *p, double t, int order, coons__pline *L)
{
    if (p->type == COONS_PATCH_HERMITE_COONS)
        coons__hermite_tline(p, t, order, L);
    else
        coons__coons_tline(p, t, order, L);
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

void coons_patch_eval_derivs(const coons_patch *p, double s, double t, int order,
                             double out[][3])
{
    if (order < 0) order = 0;
    if (order > 2) order = 2;
    s = coons__param01(s);
    t = coons__param01(t);
    if (p->pts) {
        coons__surface_eval(p, s, t, order, out);
        return;
    }
    coons__pline S, T;
    coons__patch_sline(p, s, order, &S);
    coons__patch_tline(p, t, order, &T);
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

void coons_patch_eval(const coons_patch *p, double s, double t, double out[3])
{
    double r[1][3];
    coons_patch_eval_derivs(p, s, t, 0, r);
    v3_copy(out, r[0]);
}

/* One cached t-line: 4 blend values and 4 vectors. */
#define TLINE_DOUBLES 16

static inline void grid_lines(int n, const coons_patch *p, const double *s, size_t ns, size_t nt,
                       const double *cache, double *out)
{
    coons__pline S;
    for (size_t i = 0; i < ns; i++) {
        coons__patch_sline(p, coons__param01(s[i]), 0, &S);
        double *o = out + i * nt * 3;
        for (size_t j = 0; j < nt; j++) {
            const double *c = cache + j * TLINE_DOUBLES;
            combine(n, S.b[0], S.v[0], c, c + 4, o + 3 * j);
        }
    }
}

coons_status coons_patch_eval_grid(const coons_patch *p, const double *s, size_t ns,
                                   const double *t, size_t nt, double *out, coons_error *err)
{
    if (!p) return coons__error_set(err, COONS_E_INVALID, "patch grid: patch is NULL");
    if (ns == 0 || nt == 0) return COONS_OK;
    if (!s || !t || !out)
        return coons__error_set(err, COONS_E_INVALID, "patch grid: NULL parameter or output array");
    if (p->pts) return coons__surface_grid(p, s, ns, t, nt, out, err);

    double *cache = coons__malloc_array(nt, TLINE_DOUBLES * sizeof(double));
    if (!cache) return coons__error_nomem(err);
    coons__pline T;
    for (size_t j = 0; j < nt; j++) {
        coons__patch_tline(p, coons__param01(t[j]), 0, &T);
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
