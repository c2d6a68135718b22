/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * A patch reparametrised by a symmetry of the square (coons-model(5),
 * "Definitions and references": "swap", "flip_s", "flip_t"):
 * y(s,t) = x(a,b), (a,b) = swap ? (t,s) : (s,t), then a -> 1-a if flip_s,
 * b -> 1-b if flip_t. With sa, sb = -1 where flipped (else 1), the chain
 * rule gives, without swap, y_s = sa x_a, y_t = sb x_b, y_ss = x_aa,
 * y_st = sa sb x_ab, y_tt = x_bb, and with swap y_s = sb x_b,
 * y_t = sa x_a, y_ss = x_bb, y_st = sa sb x_ab, y_tt = x_aa.
 */
#include <string.h>

#include "patch_impl.h"

/* (a, b) of (s, t). */
static void map(const coons_patch *p, double s, double t, double *a, double *b)
{
    *a = p->swap ? t : s;
    *b = p->swap ? s : t;
    if (p->flip_s) *a = 1.0 - *a;
    if (p->flip_t) *b = 1.0 - *b;
}

static void eval(const coons_patch *p, double s, double t, int order, double out[][3])
{
    double a, b, x[6][3];
    map(p, s, t, &a, &b);
    p->inner->kind->eval(p->inner, a, b, order, x);
    v3_copy(out[0], x[0]);
    double sa = p->flip_s ? -1.0 : 1.0, sb = p->flip_t ? -1.0 : 1.0;
    if (order >= 1) {
        v3_scale(out[p->swap ? 2 : 1], x[1], sa);
        v3_scale(out[p->swap ? 1 : 2], x[2], sb);
    }
    if (order >= 2) {
        v3_copy(out[p->swap ? 5 : 3], x[3]);
        v3_scale(out[4], x[4], sa * sb);
        v3_copy(out[p->swap ? 3 : 5], x[5]);
    }
}

/* The parameters u (n of them, clamped) as the inner patch sees them. */
static double *mapped(const double *u, size_t n, int flip)
{
    double *r = coons__malloc_array(n, sizeof *r);
    if (r)
        for (size_t i = 0; i < n; i++) r[i] = flip ? 1.0 - clamp01(u[i]) : clamp01(u[i]);
    return r;
}

static coons_status grid(const coons_patch *p, const double *s, size_t ns, const double *t,
                         size_t nt, double *out, coons_error *err)
{
    /* Inner grid over a (na values) x b (nb values). */
    const double *ua = p->swap ? t : s, *ub = p->swap ? s : t;
    size_t na = p->swap ? nt : ns, nb = p->swap ? ns : nt;
    double *a = mapped(ua, na, p->flip_s), *b = mapped(ub, nb, p->flip_t);
    double *tmp = p->swap ? coons__malloc_array(ns * nt, 3 * sizeof(double)) : out;
    coons_status rc = COONS_OK;
    if (!a || !b || !tmp)
        rc = coons__error_nomem(err);
    else
        rc = p->inner->kind->grid(p->inner, a, na, b, nb, tmp, err);
    if (!rc && p->swap)
        for (size_t i = 0; i < ns; i++)
            for (size_t j = 0; j < nt; j++) v3_copy(out + 3 * (i * nt + j), tmp + 3 * (j * ns + i));
    if (p->swap) coons__free(tmp);
    coons__free(a);
    coons__free(b);
    return rc;
}

/* y along s is the inner patch along a (no swap) or b (swap). */
static void breaks(const coons_patch *p, int dir, coons__breaks *B)
{
    int idir = p->swap ? 1 - dir : dir;
    int flip = idir == 0 ? p->flip_s : p->flip_t;
    size_t n0 = B->n;
    coons__patch_breaks(p->inner, idir, B);
    if (flip)
        for (size_t i = n0; i < B->n; i++) B->v[i] = 1.0 - B->v[i];
}

/* Flips keep the space, the swap exchanges the directions. */
static void space(const coons_patch *p, int dir, coons__space *S)
{
    *S = coons__patch_space(p->inner, p->swap ? 1 - dir : dir);
}

const coons__patch_kind coons__patch_reparam_kind = {
    COONS_PATCH_BILINEAR, /* unused: coons_patch_kind() reports the inner type */
    eval, grid, NULL, NULL, coons__patch_wrap_bbox, breaks,
    coons__patch_wrap_copy, coons__patch_wrap_free, space,
};

coons_status coons_patch_new_reparametrized(const coons_patch *p, int swap, int flip_s,
                                            int flip_t, coons_patch **out, coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "patch reparametrisation: out is NULL");
    *out = NULL;
    if (!p)
        return coons__error_set(err, COONS_E_INVALID, "patch reparametrisation: patch is NULL");
    double lo[3], hi[3];
    coons_patch_control_bbox(p, lo, hi);
    coons_status rc = coons__patch_wrap(&coons__patch_reparam_kind, p, lo, hi, out, err);
    if (rc) return rc;
    (*out)->swap = !!swap;
    (*out)->flip_s = !!flip_s;
    (*out)->flip_t = !!flip_t;
    return COONS_OK;
}
