/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The affine image y(s,t) = M x(s,t) + t0 of a patch (coons-model(5),
 * "Definitions and references": "transform"): the point maps by M x + t0,
 * every partial (x_s, x_t, x_ss, x_st, x_tt) by M alone, which is exact for
 * every type; a grid is the inner grid with its points mapped. The control
 * box is the box of the mapped corners of the inner control box. Also the
 * wrapper lifecycle shared with patch_reparam.c.
 */
#include <string.h>

#include "affine.h"
#include "patch_impl.h"

static void eval(const coons_patch *p, double s, double t, int order, double out[][3])
{
    p->inner->kind->eval(p->inner, s, t, order, out);
    coons__affine_point(p->xf, out[0], out[0]);
    int n = order >= 2 ? 6 : order >= 1 ? 3 : 1;
    for (int k = 1; k < n; k++) coons__affine_vec(p->xf, out[k], out[k]);
}

static coons_status grid(const coons_patch *p, const double *s, size_t ns, const double *t,
                         size_t nt, double *out, coons_error *err)
{
    coons_status rc = p->inner->kind->grid(p->inner, s, ns, t, nt, out, err);
    if (rc) return rc;
    for (size_t i = 0; i < ns * nt; i++) coons__affine_point(p->xf, out + 3 * i, out + 3 * i);
    return COONS_OK;
}

static void breaks(const coons_patch *p, int dir, coons__breaks *B)
{
    coons__patch_breaks(p->inner, dir, B);
}

void coons__patch_wrap_bbox(const coons_patch *p, double lo[3], double hi[3])
{
    v3_copy(lo, p->lo);
    v3_copy(hi, p->hi);
}

coons_status coons__patch_wrap_copy(const coons_patch *p, coons_patch *d, coons_error *err)
{
    d->inner = NULL;
    return coons_patch_copy(p->inner, &d->inner, err);
}

void coons__patch_wrap_free(coons_patch *p) { coons_patch_free(p->inner); }

coons_status coons__patch_wrap(const coons__patch_kind *kind, const coons_patch *p,
                               const double lo[3], const double hi[3], coons_patch **out,
                               coons_error *err)
{
    coons_patch *w = NULL;
    coons_status rc = coons__patch_alloc(kind, &w, err);
    if (rc) return rc;
    if ((rc = coons_patch_copy(p, &w->inner, err))) {
        coons_patch_free(w);
        return rc;
    }
    v3_copy(w->lo, lo);
    v3_copy(w->hi, hi);
    *out = w;
    return COONS_OK;
}

static void space(const coons_patch *p, int dir, coons__space *S)
{
    *S = coons__patch_space(p->inner, dir);
}

const coons__patch_kind coons__patch_transformed_kind = {
    COONS_PATCH_BILINEAR, /* unused: coons_patch_kind() reports the inner type */
    eval, grid, NULL, NULL, coons__patch_wrap_bbox, breaks,
    coons__patch_wrap_copy, coons__patch_wrap_free, space,
};

coons_status coons_patch_new_transformed(const coons_patch *p, const double *m,
                                         coons_patch **out, coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "patch transform: out is NULL");
    *out = NULL;
    if (!p) return coons__error_set(err, COONS_E_INVALID, "patch transform: patch is NULL");
    coons_status rc = coons__affine_check(m, "patch", err);
    if (rc) return rc;
    double lo[3], hi[3], tlo[3], thi[3];
    coons_patch_control_bbox(p, lo, hi);
    coons__affine_bbox(m, lo, hi, tlo, thi);
    if ((rc = coons__patch_wrap(&coons__patch_transformed_kind, p, tlo, thi, out, err)))
        return rc;
    memcpy((*out)->xf, m, sizeof (*out)->xf);
    return COONS_OK;
}
