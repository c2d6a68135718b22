/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The body record of seed 000 section 2 (F: [0,1]^3 -> R^3): lifetime,
 * copies, control box, and the dispatch of point, Jacobian and grid
 * evaluation to the five types (body0.c T, body1.c C1, body2.c C2,
 * tensor_volume.c the tensor-product solid of section 2).
 */
#include <string.h>

#include "body_impl.h"

/* In body2.c: the faces are the only patch-owning part of the record. */
void coons__body2_free_faces(coons_body *b);
coons_status coons__body2_copy_faces(const coons_body *b, coons_body *d, coons_error *err);

coons_status coons__body_alloc(coons_body_type type, coons_blend blend, coons_body **out,
                               coons_error *err)
{
    *out = NULL;
    coons_body *b = coons__calloc(1, sizeof *b);
    if (!b) return coons__error_nomem(err);
    b->type = type;
    b->blend = blend;
    bbox_empty(b->lo, b->hi);
    *out = b;
    return COONS_OK;
}

void coons_body_free(coons_body *b)
{
    if (!b) return;
    for (int e = 0; e < 12; e++) coons_curve_free(b->edge[e]);
    coons__body2_free_faces(b);
    coons__free(b->pts);
    for (int d = 0; d < 3; d++) coons__free(b->knots[d]);
    coons__free(b->w);
    coons__free(b);
}

coons_body_type coons_body_get_type(const coons_body *b) { return b->type; }

coons_status coons_body_copy(const coons_body *b, coons_body **out, coons_error *err)
{
    *out = NULL;
    coons_body *d = coons__calloc(1, sizeof *d);
    if (!d) return coons__error_nomem(err);
    *d = *b;
    /* Detach every owned pointer first so that a partial copy frees cleanly. */
    memset(d->edge, 0, sizeof d->edge);
    memset(d->face, 0, sizeof d->face);
    d->pts = NULL;
    d->w = NULL;
    for (int k = 0; k < 3; k++) d->knots[k] = NULL;
    coons_status rc = COONS_OK;
    for (int e = 0; e < 12 && !rc; e++)
        if (b->edge[e]) rc = coons_curve_copy(b->edge[e], &d->edge[e], err);
    if (!rc) rc = coons__body2_copy_faces(b, d, err);
    if (!rc && b->pts) {
        size_t np = b->n[0] * b->n[1] * b->n[2];
        d->pts = coons__memdup(b->pts, 3 * np, sizeof(double));
        if (b->w) d->w = coons__memdup(b->w, np, sizeof(double));
        for (int k = 0; k < 3; k++)
            d->knots[k] = coons__memdup(b->knots[k], b->n[k] + (size_t)b->deg[k] + 1,
                                        sizeof(double));
        if (!d->pts || (b->w && !d->w) || !d->knots[0] || !d->knots[1] || !d->knots[2])
            rc = coons__error_nomem(err);
    }
    if (rc) {
        coons_body_free(d);
        return rc;
    }
    *out = d;
    return COONS_OK;
}

void coons_body_control_bbox(const coons_body *b, double lo[3], double hi[3])
{
    v3_copy(lo, b->lo);
    v3_copy(hi, b->hi);
}

static void eval_any(const coons_body *b, double u, double v, double w, double out[3],
                     double d[3][3])
{
    u = clamp01(u);
    v = clamp01(v);
    w = clamp01(w);
    switch (b->type) {
    case COONS_BODY_BODY0: coons__body0_eval(b, u, v, w, out, d); break;
    case COONS_BODY_BODY1: coons__body1_eval(b, u, v, w, out, d); break;
    case COONS_BODY_BODY2: coons__body2_eval(b, u, v, w, out, d); break;
    default: coons__tensor_eval(b, u, v, w, out, d); break;
    }
}

void coons_body_eval(const coons_body *b, double u, double v, double w, double out[3])
{
    eval_any(b, u, v, w, out, NULL);
}

double coons_body_eval_jacobian(const coons_body *b, double u, double v, double w,
                                double out[3], double jac[3][3])
{
    double d[3][3]; /* d[q] = dF/dq: the columns of the Jacobian */
    eval_any(b, u, v, w, out, d);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) jac[r][c] = d[c][r];
    /* det = d_u . (d_v x d_w) */
    double x[3];
    v3_cross(x, d[1], d[2]);
    return v3_dot(d[0], x);
}

coons_status coons_body_eval_grid(const coons_body *b, const double *u, size_t nu,
                                  const double *v, size_t nv, const double *w, size_t nw,
                                  double *out, coons_error *err)
{
    if (nu == 0 || nv == 0 || nw == 0) return COONS_OK;
    if (!u || !v || !w || !out)
        return coons__error_set(err, COONS_E_INVALID, "body grid: NULL parameter or output");
    /* The output holds nu*nv*nw points of 3 doubles: every product must fit
     * in a size_t counted in bytes. */
    size_t lim = SIZE_MAX / (3 * sizeof(double));
    if (nv > lim / nu || nw > lim / (nu * nv))
        return coons__error_set(err, COONS_E_LIMIT,
                                "body grid of %zu x %zu x %zu points is too large", nu, nv, nw);
    switch (b->type) {
    case COONS_BODY_BODY0: return coons__body0_grid(b, u, nu, v, nv, w, nw, out, err);
    case COONS_BODY_BODY1: return coons__body1_grid(b, u, nu, v, nv, w, nw, out, err);
    case COONS_BODY_BODY2: return coons__body2_grid(b, u, nu, v, nv, w, nw, out, err);
    default: return coons__tensor_grid(b, u, nu, v, nv, w, nw, out, err);
    }
}

const char *coons__body_edge_name(int e)
{
    const char *n = coons_body_edge_name(e);
    return n ? n : "?";
}

const char *coons__body_face_name(int f)
{
    const char *n = coons_body_face_name(f);
    return n ? n : "?";
}
