/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The affine image G = M F + t0 of a body (coons-model(5), "Definitions
 * and references": "transform"): points map by M x + t0, the partials
 * dF/du, dF/dv, dF/dw by M, so det J_G = det M det J_F: a negative det M
 * mirrors the body (left-handed, still written outward by the sampler).
 * The control box is the box of the mapped corners of the inner box.
 */
#include <string.h>

#include "affine.h"
#include "body_impl.h"

static void eval(const coons_body *b, double u, double v, double w, double out[3],
                 double d[3][3])
{
    b->inner->kind->eval(b->inner, u, v, w, out, d);
    coons__affine_point(b->xf, out, out);
    if (d)
        for (int q = 0; q < 3; q++) coons__affine_vec(b->xf, d[q], d[q]);
}

static coons_status grid(const coons_body *b, const double *u, size_t nu, const double *v,
                         size_t nv, const double *w, size_t nw, double *out, coons_error *err)
{
    coons_status rc = b->inner->kind->grid(b->inner, u, nu, v, nv, w, nw, out, err);
    if (rc) return rc;
    for (size_t i = 0; i < nu * nv * nw; i++)
        coons__affine_point(b->xf, out + 3 * i, out + 3 * i);
    return COONS_OK;
}

static coons_status det_grid(const coons_body *b, const double *u, size_t nu, const double *v,
                             size_t nv, const double *w, size_t nw, double *det, double *jac,
                             coons_error *err)
{
    size_t np = nu * nv * nw;
    if (det) {
        coons_status rc = coons__body_det_grid(b->inner, u, nu, v, nv, w, nw, det, err);
        if (rc) return rc;
        for (size_t i = 0; i < np; i++) det[i] *= b->xf_det;
    }
    if (jac) {
        coons_status rc = coons__body_jac_grid(b->inner, u, nu, v, nv, w, nw, jac, err);
        if (rc) return rc;
        for (size_t i = 0; i < 3 * np; i++) coons__affine_vec(b->xf, jac + 3 * i, jac + 3 * i);
    }
    return COONS_OK;
}

static void breaks(const coons_body *b, int d, coons__breaks *B)
{
    if (b->inner->kind->breaks) b->inner->kind->breaks(b->inner, d, B);
}

static coons_status copy(const coons_body *b, coons_body *d, coons_error *err)
{
    d->inner = NULL;
    return coons_body_copy(b->inner, &d->inner, err);
}

static void release(coons_body *b) { coons_body_free(b->inner); }

static void space(const coons_body *b, int d, coons__space *S)
{
    *S = coons__body_space(b->inner, d);
}

const coons__body_kind coons__body_transformed_kind = {
    COONS_BODY_BODY0, /* unused: coons_body_kind() reports the inner type */
    eval, grid, det_grid, breaks, copy, release, space, NULL,
};

coons_status coons_body_new_transformed(const coons_body *b, const double *m,
                                        coons_body **out, coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "body transform: out is NULL");
    *out = NULL;
    if (!b) return coons__error_set(err, COONS_E_INVALID, "body transform: body is NULL");
    coons_status rc = coons__affine_check(m, "body", err);
    if (rc) return rc;
    coons_body *g = NULL;
    if ((rc = coons__body_alloc(&coons__body_transformed_kind, b->blend, &g, err))) return rc;
    if ((rc = coons_body_copy(b, &g->inner, err))) {
        coons_body_free(g);
        return rc;
    }
    memcpy(g->xf, m, sizeof g->xf);
    g->xf_det = coons__affine_det(m);
    coons__affine_bbox(m, b->lo, b->hi, g->lo, g->hi);
    *out = g;
    return COONS_OK;
}
