/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Coons body 0 (seed 000 section 2.2): the trilinear interpolation
 *   T(P_ijk; u,v,w) = sum_ijk a_i(u) a_j(v) a_k(w) P_ijk,
 * (a_0, a_1) = (1-x, x), or (f, 1-f) with f = 1-3x^2+2x^3 for the cubic
 * blend (model format, "blend"). T is also the corner term of bodies 1, 2.
 */
#include "body_impl.h"

coons_status coons_body_new_body0(const double *flat, coons_blend blend, coons_body **out,
                                  coons_error *err)
{
    const double(*corners)[3] = (const double(*)[3])flat; /* 24 doubles, P_ijk at 4i+2j+k */
    *out = NULL;
    if (!corners) return coons__error_set(err, COONS_E_INVALID, "body0: corners are NULL");
    if (blend != COONS_BLEND_LINEAR && blend != COONS_BLEND_CUBIC)
        return coons__error_set(err, COONS_E_INVALID, "body0: unknown blend %d", (int)blend);
    for (int c = 0; c < 8; c++)
        if (!v3_finite(corners[c]))
            return coons__error_set(err, COONS_E_INVALID,
                                    "body0: corner P%d%d%d (index %d) is not finite", c >> 2,
                                    (c >> 1) & 1, c & 1, c);
    coons_body *b;
    coons_status rc = coons__body_alloc(&coons__body0_kind, blend, &b, err);
    if (rc) return rc;
    for (int c = 0; c < 8; c++) {
        v3_copy(b->corner[c], corners[c]);
        bbox_add(b->lo, b->hi, corners[c]);
    }
    *out = b;
    return COONS_OK;
}

void coons__trilinear(const double c[8][3], const double bu[4], const double bv[4],
                      const double bw[4], double out[3], double d[3][3])
{
    v3_zero(out);
    if (d) {
        v3_zero(d[0]);
        v3_zero(d[1]);
        v3_zero(d[2]);
    }
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) {
                const double *p = c[4 * i + 2 * j + k];
                v3_axpy(out, bu[i] * bv[j] * bw[k], p);
                if (d) {
                    v3_axpy(d[0], bu[2 + i] * bv[j] * bw[k], p);
                    v3_axpy(d[1], bu[i] * bv[2 + j] * bw[k], p);
                    v3_axpy(d[2], bu[i] * bv[j] * bw[2 + k], p);
                }
            }
}

/* The point grouped as the grid groups it (the same operations in the
 * same order, so a grid point equals the point evaluated alone bitwise):
 * u first, then v, then w. */
static void point(const double c[8][3], const double bu[2], const double bv[2],
                  const double bw[2], double out[3])
{
    for (int r = 0; r < 3; r++) {
        double A[4];
        for (int jk = 0; jk < 4; jk++) A[jk] = bu[0] * c[jk][r] + bu[1] * c[4 + jk][r];
        double q0 = bv[0] * A[0] + bv[1] * A[2], q1 = bv[0] * A[1] + bv[1] * A[3];
        out[r] = bw[0] * q0 + bw[1] * q1;
    }
}

static void eval(const coons_body *b, double u, double v, double w, double out[3],
                 double d[3][3])
{
    double bu[5], bv[5], bw[5], t[3];
    coons__blends_at(b->blend, u, v, w, bu, bv, bw);
    if (d) coons__trilinear(b->corner, bu, bv, bw, t, d);
    point(b->corner, bu, bv, bw, out);
}

/* Per (u,v) the body is the blend of two points Q_k along w; the w-line
 * then costs two scaled adds per point. */
static coons_status grid(const coons_body *b, const double *u, size_t nu, const double *v,
                         size_t nv, const double *w, size_t nw, double *out, coons_error *err)
{
    double *bw = coons__malloc_array(nw, 2 * sizeof(double));
    if (!bw) return coons__error_nomem(err);
    for (size_t k = 0; k < nw; k++) {
        double t[4];
        coons__blend(b->blend, clamp01(w[k]), 0, t);
        bw[2 * k] = t[0];
        bw[2 * k + 1] = t[1];
    }
    const double(*c)[3] = b->corner;
    for (size_t i = 0; i < nu; i++) {
        double bu[4];
        coons__blend(b->blend, clamp01(u[i]), 0, bu);
        double A[4][3]; /* A[2j+k] = sum_i a_i(u) P_ijk */
        for (int jk = 0; jk < 4; jk++)
            for (int r = 0; r < 3; r++) A[jk][r] = bu[0] * c[jk][r] + bu[1] * c[4 + jk][r];
        for (size_t j = 0; j < nv; j++) {
            double bv[4];
            coons__blend(b->blend, clamp01(v[j]), 0, bv);
            double q0[3], q1[3];
            for (int r = 0; r < 3; r++) {
                q0[r] = bv[0] * A[0][r] + bv[1] * A[2][r];
                q1[r] = bv[0] * A[1][r] + bv[1] * A[3][r];
            }
            double *o = out + (i * nv + j) * nw * 3;
            for (size_t k = 0; k < nw; k++) {
                double a0 = bw[2 * k], a1 = bw[2 * k + 1];
                o[3 * k] = a0 * q0[0] + a1 * q1[0];
                o[3 * k + 1] = a0 * q0[1] + a1 * q1[1];
                o[3 * k + 2] = a0 * q0[2] + a1 * q1[2];
            }
        }
    }
    coons__free(bw);
    return COONS_OK;
}

/* The eight corners are all its data: no breakpoints, nothing owned. */
/* The blends (seed 000 section 2.2). */
static void space(const coons_body *b, int d, coons__space *S)
{
    (void)d;
    *S = coons__space_poly(coons__blend_degree(b->blend));
}

const coons__body_kind coons__body0_kind = {
    .type = COONS_BODY_BODY0, .eval = eval, .grid = grid, .space = space};
