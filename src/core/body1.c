/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Coons body 1 (seed 000 section 2.3) from the 12 edge curves C(u,j,k),
 * C(i,v,k), C(i,j,w):
 *   C1 = sum_ij a_i(u) a_j(v) C(i,j,w) + sum_ik a_i(u) a_k(w) C(i,v,k)
 *      + sum_jk a_j(v) a_k(w) C(u,j,k) - 2 T(C_ijk; u,v,w),
 * (a_0, a_1) the linear or cubic blend. The seed asks the three edges at a
 * corner to share the point C_ijk; within the tolerance we use their
 * average (model format, "Consistency").
 * Edge e: u-edges 0 + 2j + k, v-edges 4 + 2i + k, w-edges 8 + 2i + j.
 */
#include "agree.h"
#include "body_impl.h"

coons_status coons_body_new_body1(coons_curve *const *edges_in, coons_blend blend, double tol,
                                  coons_body **out, coons_error *err)
{
    /* The public idiom (coons/types.h, "Arrays") passes handles as X *const *;
     * the code here only reads them. */
    const coons_curve *const *edges = (const coons_curve *const *)edges_in;
    *out = NULL;
    if (!edges) return coons__error_set(err, COONS_E_INVALID, "body1: edges are NULL");
    if (blend != COONS_BLEND_LINEAR && blend != COONS_BLEND_CUBIC)
        return coons__error_set(err, COONS_E_INVALID, "body1: unknown blend %d", (int)blend);
    if (!(tol >= 0.0) || !isfinite(tol))
        return coons__error_set(err, COONS_E_INVALID, "body1: tolerance %g is not >= 0", tol);
    double lo[3], hi[3];
    bbox_empty(lo, hi);
    for (int e = 0; e < 12; e++) {
        if (!edges[e])
            return coons__error_set(err, COONS_E_INVALID, "body1: edge %s is NULL",
                                    coons__body_edge_name(e));
        double a[3], c[3];
        coons_curve_control_bbox(edges[e], a, c);
        bbox_add(lo, hi, a);
        bbox_add(lo, hi, c);
    }
    double eps = coons__tolerance(tol, bbox_diag(lo, hi));
    coons__agree ag;
    if (coons__agree_body1_corners(edges, eps, &ag)) {
        int i = ag.at >> 2, j = (ag.at >> 1) & 1, k = ag.at & 1;
        return coons__error_set(err, COONS_E_INCOMPATIBLE,
                                "body1: corner C%d%d%d (u=%d,v=%d,w=%d): edges %s and %s differ "
                                "by %.6g (tolerance %.3g)",
                                i, j, k, i, j, k, coons__body_edge_name(ag.a),
                                coons__body_edge_name(ag.b), ag.dist, eps);
    }
    /* Each corner is the average of its three edges. */
    double corner[8][3];
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) {
                int id[3] = {2 * j + k, 4 + 2 * i + k, 8 + 2 * i + j};
                double t[3] = {i, j, k}, p[3][3];
                for (int s = 0; s < 3; s++) coons_curve_eval(edges[id[s]], t[s], p[s]);
                double *c = corner[4 * i + 2 * j + k];
                for (int q = 0; q < 3; q++) c[q] = (p[0][q] + p[1][q] + p[2][q]) / 3.0;
            }
    coons_body *b;
    coons_status rc = coons__body_alloc(&coons__body1_kind, blend, &b, err);
    if (rc) return rc;
    for (int e = 0; e < 12; e++) {
        if ((rc = coons_curve_copy(edges[e], &b->edge[e], err))) {
            coons_body_free(b);
            return rc;
        }
    }
    for (int c = 0; c < 8; c++) v3_copy(b->corner[c], corner[c]);
    v3_copy(b->lo, lo);
    v3_copy(b->hi, hi);
    *out = b;
    return COONS_OK;
}

/* Edge value (and derivative if dv is not NULL). */
static void edge_at(const coons_body *b, int e, double t, double p[3], double *dv)
{
    double r[2][3];
    coons_curve_eval_derivs(b->edge[e], t, dv ? 1 : 0, r);
    v3_copy(p, r[0]);
    if (dv) v3_copy(dv, r[1]);
}

void coons__edge_sum_tab(double E[12][3], double dE[12][3], double sign,
                         const double bu[5], const double bv[5], const double bw[5],
                         double out[3], double d[3][3])
{
    for (int x = 0; x < 2; x++)
        for (int y = 0; y < 2; y++) {
            const double *p, *dp;
            double f;
            /* w-edge C(x,y,w): blends a_x(u) a_y(v) */
            p = E[8 + 2 * x + y], dp = dE[8 + 2 * x + y];
            v3_axpy(out, sign * bu[x] * bv[y], p);
            if (d) {
                v3_axpy(d[0], sign * bu[2 + x] * bv[y], p);
                v3_axpy(d[1], sign * bu[x] * bv[2 + y], p);
                v3_axpy(d[2], sign * bu[x] * bv[y], dp);
            }
            /* v-edge C(x,v,y): blends a_x(u) a_y(w) */
            p = E[4 + 2 * x + y], dp = dE[4 + 2 * x + y];
            f = sign * bu[x] * bw[y];
            v3_axpy(out, f, p);
            if (d) {
                v3_axpy(d[0], sign * bu[2 + x] * bw[y], p);
                v3_axpy(d[1], f, dp);
                v3_axpy(d[2], sign * bu[x] * bw[2 + y], p);
            }
            /* u-edge C(u,x,y): blends a_x(v) a_y(w) */
            p = E[2 * x + y], dp = dE[2 * x + y];
            f = sign * bv[x] * bw[y];
            v3_axpy(out, f, p);
            if (d) {
                v3_axpy(d[0], f, dp);
                v3_axpy(d[1], sign * bv[2 + x] * bw[y], p);
                v3_axpy(d[2], sign * bv[x] * bw[2 + y], p);
            }
        }
}

void coons__edge_sum(const coons_body *b, coons__edge_fn edge, double sign, const double bu[5],
                     const double bv[5], const double bw[5], double out[3], double d[3][3])
{
    double E[12][3], dE[12][3];
    for (int e = 0; e < 12; e++) {
        const double *q = e < 4 ? bu : e < 8 ? bv : bw;
        edge(b, e, q[4], E[e], d ? dE[e] : NULL);
    }
    coons__edge_sum_tab(E, dE, sign, bu, bv, bw, out, d);
}

/* The point grouped as the grid below groups it (the same operations in
 * the same order, so a grid point equals the point evaluated alone
 * bitwise; summed term by term it was up to 7 ulp of the body's size off). */
static void point(const coons_body *b, const double bu[5], const double bv[5],
                  const double bw[5], double E[12][3], double out[3])
{
    const double a0 = bu[0], a1 = bu[1], b0 = bv[0], b1 = bv[1];
    const double(*c)[3] = b->corner;
    double(*Cu)[3] = E, (*Cv)[3] = E + 4, (*Cw)[3] = E + 8;
    for (int r = 0; r < 3; r++) {
        double h0 = a0 * Cw[0][r] + a1 * Cw[2][r], h1 = a0 * Cw[1][r] + a1 * Cw[3][r], P[2];
        for (int k = 0; k < 2; k++) {
            double tk = a0 * c[k][r] + a1 * c[4 + k][r];
            double t2k = a0 * c[2 + k][r] + a1 * c[6 + k][r];
            P[k] = a0 * Cv[k][r] + a1 * Cv[2 + k][r] + b0 * (Cu[k][r] - 2.0 * tk) +
                   b1 * (Cu[2 + k][r] - 2.0 * t2k);
        }
        out[r] = b0 * h0 + b1 * h1 + bw[0] * P[0] + bw[1] * P[1];
    }
}

static void eval(const coons_body *b, double u, double v, double w, double out[3],
                 double d[3][3])
{
    double bu[5], bv[5], bw[5], E[12][3], dE[12][3];
    coons__blends_at(b->blend, u, v, w, bu, bv, bw);
    /* each edge once, with its derivative on the Jacobian path */
    for (int e = 0; e < 12; e++) {
        const double *q = e < 4 ? bu : e < 8 ? bv : bw;
        edge_at(b, e, q[4], E[e], d ? dE[e] : NULL);
    }
    if (d) {
        /* the partials term by term: d(E - 2T) */
        double t[3], dt[3][3];
        coons__trilinear(b->corner, bu, bv, bw, t, dt);
        v3_scale(t, t, -2.0);
        for (int q = 0; q < 3; q++) v3_scale(d[q], dt[q], -2.0);
        coons__edge_sum_tab(E, dE, 1.0, bu, bv, bw, t, d);
    }
    point(b, bu, bv, bw, E, out);
}

/*
 * Grid. With H_j(w) = sum_i a_i(u) C(i,j,w) (per u, along w) and
 * P_k = sum_i a_i(u) C(i,v,k) + sum_j a_j(v) (C(u,j,k) - 2 sum_i a_i(u) C_ijk)
 * (per (u,v)), every point of a w-line is
 *   C1 = a_0(v) H_0(w) + a_1(v) H_1(w) + a_0(w) P_0 + a_1(w) P_1.
 */
static coons_status grid(const coons_body *b, const double *u, size_t nu, const double *v,
                         size_t nv, const double *w, size_t nw, double *out, coons_error *err)
{
    size_t total = 0;
    /* bw (2), Cw (12), H (6) per w; Cv (12) per v; Cu (12) and bu (2) per u */
    if (!coons__size_addmul(&total, nw, 20) || !coons__size_addmul(&total, nv, 12) ||
        !coons__size_addmul(&total, nu, 14))
        return coons__error_set(err, COONS_E_LIMIT, "body1 grid: scratch size overflows");
    double *s = coons__malloc_array(total, sizeof(double));
    if (!s) return coons__error_nomem(err);
    double *bw = s, *Cw = bw + 2 * nw, *H = Cw + 12 * nw, *Cv = H + 6 * nw, *Cu = Cv + 12 * nv,
           *bu = Cu + 12 * nu;
    /* Cw[(2i+j)*3nw + 3k]: C(i,j,w_k); Cv[(2i+k)*3nv + 3j]: C(i,v_j,k);
     * Cu[(2j+k)*3nu + 3i]: C(u_i,j,k). */
    for (size_t k = 0; k < nw; k++) {
        double t[4], x = clamp01(w[k]);
        coons__blend(b->blend, x, 0, t);
        bw[2 * k] = t[0];
        bw[2 * k + 1] = t[1];
        for (int e = 0; e < 4; e++) coons_curve_eval(b->edge[8 + e], x, Cw + e * 3 * nw + 3 * k);
    }
    for (size_t j = 0; j < nv; j++) {
        double x = clamp01(v[j]);
        for (int e = 0; e < 4; e++) coons_curve_eval(b->edge[4 + e], x, Cv + e * 3 * nv + 3 * j);
    }
    for (size_t i = 0; i < nu; i++) {
        double t[4], x = clamp01(u[i]);
        coons__blend(b->blend, x, 0, t);
        bu[2 * i] = t[0];
        bu[2 * i + 1] = t[1];
        for (int e = 0; e < 4; e++) coons_curve_eval(b->edge[e], x, Cu + e * 3 * nu + 3 * i);
    }
    const double(*c)[3] = b->corner;
    for (size_t i = 0; i < nu; i++) {
        double a0 = bu[2 * i], a1 = bu[2 * i + 1];
        for (int j = 0; j < 2; j++) {
            const double *c0 = Cw + (size_t)j * 3 * nw, *c1 = Cw + (size_t)(2 + j) * 3 * nw;
            double *h = H + (size_t)j * 3 * nw;
            for (size_t m = 0; m < 3 * nw; m++) h[m] = a0 * c0[m] + a1 * c1[m];
        }
        double tu[4][3]; /* sum_i a_i(u) C_ijk at 2j+k */
        double cu[4][3]; /* C(u_i,j,k) at 2j+k */
        for (int jk = 0; jk < 4; jk++)
            for (int r = 0; r < 3; r++) {
                tu[jk][r] = a0 * c[jk][r] + a1 * c[4 + jk][r];
                cu[jk][r] = Cu[jk * 3 * nu + 3 * i + r];
            }
        for (size_t j = 0; j < nv; j++) {
            double t[4];
            coons__blend(b->blend, clamp01(v[j]), 0, t);
            double b0 = t[0], b1 = t[1], P[2][3];
            for (int k = 0; k < 2; k++)
                for (int r = 0; r < 3; r++)
                    P[k][r] = a0 * Cv[k * 3 * nv + 3 * j + r] +
                              a1 * Cv[(2 + k) * 3 * nv + 3 * j + r] +
                              b0 * (cu[k][r] - 2.0 * tu[k][r]) +
                              b1 * (cu[2 + k][r] - 2.0 * tu[2 + k][r]);
            const double *h0 = H, *h1 = H + 3 * nw;
            double *o = out + (i * nv + j) * nw * 3;
            for (size_t k = 0; k < nw; k++) {
                double w0 = bw[2 * k], w1 = bw[2 * k + 1];
                for (int r = 0; r < 3; r++)
                    o[3 * k + r] = b0 * h0[3 * k + r] + b1 * h1[3 * k + r] + w0 * P[0][r] +
                                   w1 * P[1][r];
            }
        }
    }
    coons__free(s);
    return COONS_OK;
}

/* The four edges along direction d. */
static void breaks(const coons_body *b, int d, coons__breaks *B)
{
    for (int e = 0; e < 4; e++) coons__curve_breaks(b->edge[4 * d + e], B);
}

static coons_status copy_data(const coons_body *b, coons_body *d, coons_error *err)
{
    for (int e = 0; e < 12; e++) d->edge[e] = NULL;
    coons_status rc = COONS_OK;
    for (int e = 0; e < 12 && !rc; e++)
        if (b->edge[e]) rc = coons_curve_copy(b->edge[e], &d->edge[e], err);
    return rc;
}

static void free_data(coons_body *b)
{
    for (int e = 0; e < 12; e++) coons_curve_free(b->edge[e]);
}

/* The blends and the four edges along d (the others enter through the
 * blends of d). */
static void space(const coons_body *b, int d, coons__space *S)
{
    *S = coons__space_poly(coons__blend_degree(b->blend));
    for (int e = 0; e < 4; e++) coons__space_join(S, coons__curve_space(b->edge[4 * d + e]));
}

const coons__body_kind coons__body1_kind = {
    .type = COONS_BODY_BODY1, .eval = eval, .grid = grid, .breaks = breaks,
    .copy = copy_data, .free = free_data, .space = space};
