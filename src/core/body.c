/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The body record of seed 000 section 2 (F: [0,1]^3 -> R^3): lifetime,
 * copies, control box, and point, Jacobian and grid evaluation through
 * the type's row (kinds.h). The types live in body0.c (T), body1.c (C1),
 * body2.c (C2) and tensor_volume.c (the tensor-product solid of section 2).
 */
#include <string.h>

#include "body_impl.h"
#include "parallel.h"

coons_status coons__body_alloc(const coons__body_kind *kind, coons_blend blend,
                               coons_body **out, coons_error *err)
{
    *out = NULL;
    coons_body *b = coons__calloc(1, sizeof *b);
    if (!b) return coons__error_nomem(err);
    b->kind = kind;
    b->blend = blend;
    bbox_empty(b->lo, b->hi);
    *out = b;
    return COONS_OK;
}

void coons_body_free(coons_body *b)
{
    if (!b) return;
    if (b->kind->free) b->kind->free(b);
    coons__free(b);
}

/* A wrapper reports the type of the body it wraps (body.h). */
coons_body_type coons_body_kind(const coons_body *b)
{
    while (b->inner) b = b->inner;
    return b->kind->type;
}

coons_status coons_body_copy(const coons_body *b, coons_body **out, coons_error *err)
{
    *out = NULL;
    coons_body *d = coons__calloc(1, sizeof *d);
    if (!d) return coons__error_nomem(err);
    *d = *b;
    coons_status rc = b->kind->copy ? b->kind->copy(b, d, err) : COONS_OK;
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

void coons_body_eval(const coons_body *b, double u, double v, double w, double out[3])
{
    b->kind->eval(b, clamp01(u), clamp01(v), clamp01(w), out, NULL);
}

double coons_body_eval_jacobian(const coons_body *b, double u, double v, double w,
                                double out[3], double jac[3][3])
{
    double d[3][3]; /* d[q] = dF/dq: the columns of the Jacobian */
    b->kind->eval(b, clamp01(u), clamp01(v), clamp01(w), out, d);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) jac[r][c] = d[c][r];
    /* det = d_u . (d_v x d_w) */
    double x[3];
    v3_cross(x, d[1], d[2]);
    return v3_dot(d[0], x);
}

coons_status coons_body_eval_points(const coons_body *b, size_t n, const double *uvw,
                                    double *xyz, double *jac, double *det, coons_error *err)
{
    if (!b) return coons__error_set(err, COONS_E_INVALID, "body points: NULL body");
    if (n && (!uvw || !xyz))
        return coons__error_set(err, COONS_E_INVALID, "body points: NULL parameters or output");
    if (b->kind->points) {
        b->kind->points(b, n, uvw, xyz, jac, det);
        return COONS_OK;
    }
    if (!jac && !det) {
        for (size_t i = 0; i < n; i++) {
            const double *q = uvw + 3 * i;
            b->kind->eval(b, clamp01(q[0]), clamp01(q[1]), clamp01(q[2]), xyz + 3 * i, NULL);
        }
        return COONS_OK;
    }
    for (size_t i = 0; i < n; i++) {
        const double *q = uvw + 3 * i;
        double J[3][3];
        double d = coons_body_eval_jacobian(b, q[0], q[1], q[2], xyz + 3 * i, J);
        if (jac) memcpy(jac + 9 * i, J, sizeof J);
        if (det) det[i] = d;
    }
    return COONS_OK;
}

/* The arguments of a non-empty grid: arrays present, and nu*nv*nw points
 * of 3 doubles whose every product fits in a size_t counted in bytes. */
static coons_status grid_args(const double *u, size_t nu, const double *v, size_t nv,
                              const double *w, size_t nw, const double *out, coons_error *err)
{
    if (!u || !v || !w || !out)
        return coons__error_set(err, COONS_E_INVALID, "body grid: NULL parameter or output");
    size_t lim = SIZE_MAX / (3 * sizeof(double));
    if (nv > lim / nu || nw > lim / (nu * nv))
        return coons__error_set(err, COONS_E_LIMIT,
                                "body grid of %zu x %zu x %zu points is too large", nu, nv, nw);
    return COONS_OK;
}

coons_status coons_body_eval_grid(const coons_body *b, const double *u, size_t nu,
                                  const double *v, size_t nv, const double *w, size_t nw,
                                  double *out, coons_error *err)
{
    if (nu == 0 || nv == 0 || nw == 0) return COONS_OK;
    coons_status rc = grid_args(u, nu, v, nv, w, nw, out, err);
    return rc ? rc : b->kind->grid(b, u, nu, v, nv, w, nw, out, err);
}

typedef struct grid_run {
    const coons_body *b;
    const double *u, *v, *w;
    size_t nv, nw;
    double *out;
    coons_status *st;
    coons_error *err; /* one per run */
} grid_run;

static void grid_chunk(void *ctx, unsigned c, size_t lo, size_t hi)
{
    grid_run *g = ctx;
    g->st[c] = g->b->kind->grid(g->b, g->u + lo, hi - lo, g->v, g->nv, g->w, g->nw,
                                g->out + lo * g->nv * g->nw * 3, &g->err[c]);
}

coons_status coons_body_eval_grid_threads(const coons_body *b, const double *u, size_t nu,
                                          const double *v, size_t nv, const double *w,
                                          size_t nw, double *out, unsigned threads,
                                          coons_error *err)
{
    unsigned k = coons__thread_count(threads);
    if (k <= 1 || nu <= 1 || nv == 0 || nw == 0)
        return coons_body_eval_grid(b, u, nu, v, nv, w, nw, out, err);
    coons_status rc = grid_args(u, nu, v, nv, w, nw, out, err);
    if (rc) return rc;
    if (k > nu) k = (unsigned)nu;
    coons_status *st = coons__calloc(k, sizeof *st);
    coons_error *errs = coons__calloc(k, sizeof *errs);
    if (!st || !errs) {
        coons__free(st);
        coons__free(errs);
        return coons__error_nomem(err);
    }
    grid_run g = {b, u, v, w, nv, nw, out, st, errs};
    coons__parallel_for(nu, k, grid_chunk, &g);
    for (unsigned c = 0; c < k && !rc; c++)
        if ((rc = st[c]) && err) *err = errs[c];
    coons__free(st);
    coons__free(errs);
    return rc;
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

coons__space coons__body_space(const coons_body *b, int d)
{
    coons__space S = {3, COONS__SPACE_NONE, 0};
    if (b->kind->space) b->kind->space(b, d, &S);
    return S;
}
