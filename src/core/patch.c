/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The patch record over (s,t) in [0,1]^2 (seed 001, section 1.2; model
 * format, "Patches"): lifecycle, control box, and evaluation through the
 * type's row (kinds.h). The types live in coons_patch.c (bilinear, ruled,
 * Coons), hermite_coons.c and tensor_surface.c; the first two families are
 * evaluated by the Boolean sum of boolean_sum.c.
 */
#include "patch_impl.h"

coons_status coons__patch_alloc(const coons__patch_kind *kind, coons_patch **out,
                                coons_error *err)
{
    coons_patch *p = coons__calloc(1, sizeof *p);
    if (!p) return coons__error_nomem(err);
    p->kind = kind;
    p->n = 2;
    *out = p;
    return COONS_OK;
}

void coons_patch_free(coons_patch *p)
{
    if (!p) return;
    p->kind->free(p);
    coons__free(p);
}

/* A wrapper reports the type of the patch it wraps (patch.h). */
coons_patch_type coons_patch_kind(const coons_patch *p)
{
    while (p->inner) p = p->inner;
    return p->kind->type;
}

coons_status coons_patch_copy(const coons_patch *p, coons_patch **out, coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "patch copy: out is NULL");
    *out = NULL;
    if (!p) return coons__error_set(err, COONS_E_INVALID, "patch copy: patch is NULL");
    coons_patch *d = coons__malloc(sizeof *d);
    if (!d) return coons__error_nomem(err);
    *d = *p;
    coons_status rc = p->kind->copy(p, d, err);
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
    p->kind->control_bbox(p, lo, hi);
}

void coons__patch_breaks(const coons_patch *p, int dir, coons__breaks *B)
{
    if (p->kind->breaks) p->kind->breaks(p, dir, B);
}

void coons_patch_eval_derivs(const coons_patch *p, double s, double t, int order,
                             double out[][3])
{
    if (order < 0) order = 0;
    if (order > 2) order = 2;
    p->kind->eval(p, clamp01(s), clamp01(t), order, out);
}

void coons_patch_eval(const coons_patch *p, double s, double t, double out[3])
{
    double r[1][3];
    coons_patch_eval_derivs(p, s, t, 0, r);
    v3_copy(out, r[0]);
}

coons_status coons_patch_eval_grid(const coons_patch *p, const double *s, size_t ns,
                                   const double *t, size_t nt, double *out, coons_error *err)
{
    if (!p) return coons__error_set(err, COONS_E_INVALID, "patch grid: patch is NULL");
    if (ns == 0 || nt == 0) return COONS_OK;
    if (!s || !t || !out)
        return coons__error_set(err, COONS_E_INVALID, "patch grid: NULL parameter or output array");
    return p->kind->grid(p, s, ns, t, nt, out, err);
}

coons__space coons__patch_space(const coons_patch *p, int dir)
{
    coons__space S = {3, COONS__SPACE_NONE, 0};
    if (p->kind->space) p->kind->space(p, dir, &S);
    return S;
}
