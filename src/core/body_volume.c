/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Volume and fold detection of a body F: [0,1]^3 -> R^3 (seed 000 section
 * 2): the signed volume is the integral of det J = det dF/d(u,v,w) over the
 * unit cube (change of variables), computed by tensor 5-point
 * Gauss-Legendre quadrature. Base cells are bounded by the breakpoints of
 * the body's data (knots, segment ends), where the map may be only finitely
 * smooth; each is split into c_u x c_v x c_w sub-cells, the c of one
 * direction at a time doubling where the estimates show the error
 * (coons_body_volume_bounded), within a budget of evaluations, and the
 * achieved accuracy is returned with the volume. Within a base cell the
 * map is smooth (a polynomial for polynomial data) and the rule is exact
 * for degree 9 per variable: det J of a body of degree 3 per variable has
 * degree 8, so bicubic data converge at once and smooth data like h^10.
 * Where breakpoints are more than the list holds (a polyline of many
 * segments), det J jumps inside cells and converges only like h: the
 * budget ends the work, and the estimate says how far it got.
 * A negative det J somewhere means the body folds over itself.
 */
#include <stdlib.h>
#include <string.h>

#include "body_impl.h"
#include "bspline.h"

/* Gauss-Legendre points per direction and cell: exact for degree 9. */
#define NG 5

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Cell boundaries 0 = x_0 < ... < x_m = 1 of direction d into B (B->n = m+1). */
static void cell_bounds(const coons_body *b, int d, coons__breaks *B)
{
    /* Base cells start at the breakpoints of the body's data, so that
     * Gauss-Legendre integrates piecewise polynomials span by span. */
    if (b->kind->breaks) b->kind->breaks(b, d, B);
    if (B->n > COONS__MAX_BREAKS) B->n = 0;
    if (B->n) qsort(B->v, B->n, sizeof(double), cmp_double);
    size_t m = 0;
    for (size_t i = 0; i < B->n; i++)
        if (m == 0 || B->v[i] - B->v[m - 1] > 1e-12) B->v[m++] = B->v[i];
    B->n = m;
    /* add the ends: [0, breaks..., 1] */
    coons__breaks_add(B, 0.5); /* reserve room for two more values */
    coons__breaks_add(B, 0.5);
    if (B->nomem) return;
    memmove(B->v + 1, B->v, m * sizeof(double));
    B->v[0] = 0.0;
    B->v[m + 1] = 1.0;
    B->n = m + 2;
}

/* det J of a polynomial tensor volume (Bezier, non-rational B-spline) on
 * a grid, by successive contractions as its point grid (tensor_volume.c):
 * per u sample the values and u-derivatives of sum_a N_a(u) P_a.. over the
 * (v,w) net, per (u,v) three contractions along v, per point three along
 * w: a few hundred operations a point instead of the whole net's. */
static coons_status tensor_det_grid(const coons_body *b, const double *u, size_t nu,
                                    const double *v, size_t nv, const double *w, size_t nw,
                                    double *det, double *jac, coons_error *err)
{
    int p = b->deg[0], q = b->deg[1], r = b->deg[2];
    size_t n1 = b->n[1], n2 = b->n[2], slab = 3 * n1 * n2, row = 3 * n2;
    /* basis values and first derivatives: 2 (deg + 1) per sample */
    size_t need = 2 * slab + 3 * row + 2 * (nu * (size_t)(p + 1) + nv * (size_t)(q + 1) +
                                            nw * (size_t)(r + 1));
    double *s = coons__malloc_array(need, sizeof(double));
    size_t *fi = coons__malloc_array(nu + nv + nw, sizeof(size_t));
    if (!s || !fi) {
        coons__free(s);
        coons__free(fi);
        return coons__error_nomem(err);
    }
    double *A0 = s, *A1 = A0 + slab, *B00 = A1 + slab, *B01 = B00 + row, *B10 = B01 + row;
    double *BU = B10 + row, *BV = BU + 2 * nu * (size_t)(p + 1);
    double *BW = BV + 2 * nv * (size_t)(q + 1);
    size_t *fu = fi, *fv = fu + nu, *fw = fv + nv;
    for (size_t i = 0; i < nu; i++)
        fu[i] = coons__bspline_basis01(b->knots[0], b->n[0], p, clamp01(u[i]), 1,
                                       BU + 2 * i * (size_t)(p + 1));
    for (size_t j = 0; j < nv; j++)
        fv[j] = coons__bspline_basis01(b->knots[1], b->n[1], q, clamp01(v[j]), 1,
                                       BV + 2 * j * (size_t)(q + 1));
    for (size_t k = 0; k < nw; k++)
        fw[k] = coons__bspline_basis01(b->knots[2], b->n[2], r, clamp01(w[k]), 1,
                                       BW + 2 * k * (size_t)(r + 1));
    for (size_t i = 0; i < nu; i++) {
        const double *N = BU + 2 * i * (size_t)(p + 1), *dN = N + p + 1;
        memset(A0, 0, 2 * slab * sizeof(double));
        for (int a = 0; a <= p; a++) {
            const double *P = b->pts + (fu[i] + (size_t)a) * slab;
            for (size_t m = 0; m < slab; m++) {
                A0[m] += N[a] * P[m];
                A1[m] += dN[a] * P[m];
            }
        }
        for (size_t j = 0; j < nv; j++) {
            const double *M = BV + 2 * j * (size_t)(q + 1), *dM = M + q + 1;
            memset(B00, 0, 3 * row * sizeof(double));
            for (int c = 0; c <= q; c++) {
                size_t off = (fv[j] + (size_t)c) * row;
                const double *a0 = A0 + off, *a1 = A1 + off;
                for (size_t m = 0; m < row; m++) {
                    B00[m] += M[c] * a0[m];
                    B01[m] += dM[c] * a0[m];
                    B10[m] += M[c] * a1[m];
                }
            }
            size_t o = (i * nv + j) * nw;
            for (size_t k = 0; k < nw; k++) {
                const double *L = BW + 2 * k * (size_t)(r + 1), *dL = L + r + 1;
                double du[3] = {0, 0, 0}, dv[3] = {0, 0, 0}, dw[3] = {0, 0, 0}, x[3];
                for (int e = 0; e <= r; e++) {
                    size_t off = 3 * (fw[k] + (size_t)e);
                    v3_axpy(du, L[e], B10 + off);
                    v3_axpy(dv, L[e], B01 + off);
                    v3_axpy(dw, dL[e], B00 + off);
                }
                if (jac) {
                    v3_copy(jac + 9 * (o + k), du);
                    v3_copy(jac + 9 * (o + k) + 3, dv);
                    v3_copy(jac + 9 * (o + k) + 6, dw);
                }
                if (det) {
                    v3_cross(x, dv, dw);
                    det[o + k] = v3_dot(du, x);
                }
            }
        }
    }
    coons__free(s);
    coons__free(fi);
    return COONS_OK;
}

/* det J (det not NULL) and the partials (jac not NULL) over a tensor grid
 * (body_impl.h): the type's grid path, else point by point through eval
 * with det J as coons_body_eval_jacobian() takes it. */
static coons_status jacobian_grid(const coons_body *b, const double *u, size_t nu,
                                  const double *v, size_t nv, const double *w, size_t nw,
                                  double *det, double *jac, coons_error *err)
{
    if (b->kind->det_grid) return b->kind->det_grid(b, u, nu, v, nv, w, nw, det, jac, err);
    if ((b->kind == &coons__bezier_volume_kind || b->kind == &coons__bspline_volume_kind) && !b->w)
        return tensor_det_grid(b, u, nu, v, nv, w, nw, det, jac, err);
    for (size_t i = 0; i < nu; i++)
        for (size_t j = 0; j < nv; j++)
            for (size_t k = 0; k < nw; k++) {
                size_t n = (i * nv + j) * nw + k;
                double p[3], d[3][3], x[3];
                b->kind->eval(b, clamp01(u[i]), clamp01(v[j]), clamp01(w[k]), p, d);
                if (jac) memcpy(jac + 9 * n, d, sizeof d);
                if (det) {
                    v3_cross(x, d[1], d[2]);
                    det[n] = v3_dot(d[0], x);
                }
            }
    return COONS_OK;
}

coons_status coons__body_det_grid(const coons_body *b, const double *u, size_t nu,
                                  const double *v, size_t nv, const double *w, size_t nw,
                                  double *det, coons_error *err)
{
    return jacobian_grid(b, u, nu, v, nv, w, nw, det, NULL, err);
}

coons_status coons__body_jac_grid(const coons_body *b, const double *u, size_t nu,
                                  const double *v, size_t nv, const double *w, size_t nw,
                                  double *jac, coons_error *err)
{
    return jacobian_grid(b, u, nu, v, nv, w, nw, NULL, jac, err);
}

/* Grids are processed in slabs of u of at most this many points. */
#define SLAB_POINTS ((size_t)1 << 18)

/* Estimate with every base cell of direction d split into c[d] sub-cells,
 * NG nodes each: the nodes form a tensor grid, with weights
 * wt_u(i) wt_v(j) wt_w(k). */
static coons_status volume_level(const coons_body *b, const coons__breaks X[3], const size_t c[3],
                                 double *sum, coons_error *err)
{
    static const double x[NG] = {-0.90617984593866399280, -0.53846931010568309104, 0.0,
                                 0.53846931010568309104, 0.90617984593866399280};
    static const double wt[NG] = {0.23692688505618908751, 0.47862867049936646804,
                                  0.56888888888888888889, 0.47862867049936646804,
                                  0.23692688505618908751};
    size_t n[3], total = 0;
    for (int d = 0; d < 3; d++) {
        n[d] = (X[d].n - 1) * c[d] * NG;
        total += 2 * n[d];
    }
    size_t slab = SLAB_POINTS / (n[1] * n[2]);
    if (slab < 1) slab = 1;
    if (slab > n[0]) slab = n[0];
    double *t = coons__malloc_array(total + slab * n[1] * n[2], sizeof(double));
    if (!t) return coons__error_nomem(err);
    double *node[3], *wgt[3], *det = t + total;
    double *q = t;
    for (int d = 0; d < 3; d++) {
        node[d] = q;
        wgt[d] = q + n[d];
        q += 2 * n[d];
        size_t m = 0;
        for (size_t e = 0; e + 1 < X[d].n; e++) {
            double h = (X[d].v[e + 1] - X[d].v[e]) / (double)c[d];
            for (size_t sub = 0; sub < c[d]; sub++)
                for (int g = 0; g < NG; g++, m++) {
                    node[d][m] = X[d].v[e] + ((double)sub + 0.5 * (1.0 + x[g])) * h;
                    wgt[d][m] = 0.5 * h * wt[g];
                }
        }
    }
    double acc = 0.0;
    for (size_t i0 = 0; i0 < n[0]; i0 += slab) {
        size_t ni = n[0] - i0 < slab ? n[0] - i0 : slab;
        coons_status rc =
            coons__body_det_grid(b, node[0] + i0, ni, node[1], n[1], node[2], n[2], det, err);
        if (rc) {
            coons__free(t);
            return rc;
        }
        for (size_t i = 0; i < ni; i++) {
            double si = 0.0;
            for (size_t j = 0; j < n[1]; j++) {
                double sj = 0.0;
                const double *dk = det + (i * n[1] + j) * n[2];
                for (size_t k = 0; k < n[2]; k++) sj += wgt[2][k] * dk[k];
                si += wgt[1][j] * sj;
            }
            acc += wgt[0][i0 + i] * si;
        }
    }
    coons__free(t);
    *sum = acc;
    return COONS_OK;
}

/* Jacobian evaluations of a level (as a double: no overflow). */
static double level_cost(const coons__breaks X[3], const size_t c[3])
{
    double k = 1.0;
    for (int d = 0; d < 3; d++) k *= (double)(X[d].n - 1) * (double)c[d] * NG;
    return k;
}

/* Keeps every other interior breakpoint of direction d (the base cells
 * then hold a kink each, which the refinement resolves like any other). */
static void thin_breaks(coons__breaks *B)
{
    size_t m = 1;
    for (size_t i = 2; i + 1 < B->n; i += 2) B->v[m++] = B->v[i];
    B->v[m++] = 1.0;
    B->n = m;
}

/*
 * Adaptive in each direction, bounded in work. A round compares the
 * current estimate Q (sub-cells c) with Q_d, the estimate with the
 * sub-cells of direction d doubled, for each direction d whose difference
 * was not already negligible: e_d = |Q_d - Q| estimates the error the rule
 * makes along d (the error of a tensor rule is the sum of its 1-D rules'
 * errors, to first order). The result is Q + sum (Q_d - Q), with the
 * error estimate 2 sum e_d: the doubled rules reduce the error 2^10 times
 * on smooth data, 4 times at a kink and 2 times at a jump of det J inside
 * a cell (the worst case, where Q_d's error is e_d), so it bounds the
 * result's error with a factor 2 to spare. Until that is below the target, the
 * direction with the largest e_d is doubled. No level is started that
 * would take the evaluations past `max_evals`: the last complete round's
 * result and estimate are returned.
 */
coons_status coons_body_volume_bounded(const coons_body *b, double rel_tol, size_t max_evals,
                                       double *volume, double *error, size_t *evaluations,
                                       coons_error *err)
{
    if (!b || !volume) return coons__error_set(err, COONS_E_INVALID, "body volume: NULL argument");
    if (!(rel_tol > 0.0)) rel_tol = 1e-9;
    if (!max_evals) max_evals = COONS_BODY_VOLUME_MAX_EVALS;
    coons__breaks X[3] = {{0}};
    coons_status rc = COONS_OK;
    for (int d = 0; d < 3 && !rc; d++) {
        cell_bounds(b, d, &X[d]);
        if (X[d].nomem) rc = coons__error_nomem(err);
    }
    double budget = (double)max_evals, used = 0.0, result = 0.0, est = INFINITY;
    size_t c[3] = {1, 1, 1};
    if (!rc) {
        /* The first round (a level and its three tests, 7 levels' worth)
         * must fit: fewer base cells where the breakpoints are many. */
        while (7.0 * level_cost(X, c) > budget) {
            int dm = 0;
            for (int d = 1; d < 3; d++)
                if (X[d].n > X[dm].n) dm = d;
            if (X[dm].n <= 2) break;
            thin_breaks(&X[dm]);
        }
        /* An absolute floor for bodies of (near) zero volume, where a relative
         * test cannot be met: rounding of det J is about 1e-16 diag^3. */
        double diag = bbox_diag(b->lo, b->hi);
        double floor_ = 1e-14 * diag * diag * diag, q0 = 0.0, e[3] = {0, 0, 0},
               prev[3] = {0, 0, 0};
        int settled[3] = {0, 0, 0};
        if (level_cost(X, c) <= budget) {
            rc = volume_level(b, X, c, &q0, err);
            used += level_cost(X, c);
            result = q0;
        }
        while (!rc && used > 0) {
            double qd[3] = {0, 0, 0}, sum = q0, e_sum = 0.0;
            int tested = 0, out_of_budget = 0;
            for (int d = 0; d < 3 && !rc; d++) {
                if (settled[d]) continue;
                size_t c2[3] = {c[0], c[1], c[2]};
                c2[d] *= 2;
                double k = level_cost(X, c2);
                if (used + k > budget || c2[d] > ((size_t)1 << 24)) {
                    out_of_budget = 1;
                    break;
                }
                rc = volume_level(b, X, c2, &qd[d], err);
                if (rc) break; /* qd[d] was not set */
                used += k;
                /* at least half the previous difference along d: where the
                 * rule converges only linearly (det J jumps inside cells),
                 * successive errors may nearly cancel by chance */
                e[d] = fmax(fabs(qd[d] - q0), 0.5 * prev[d]);
                tested |= 1 << d;
            }
            if (rc || out_of_budget) break;
            for (int d = 0; d < 3; d++) {
                if (tested & 1 << d) sum += qd[d] - q0;
                e_sum += e[d];
            }
            result = sum;
            est = 2.0 * e_sum;
            double target = fmax(rel_tol * fabs(sum), floor_);
            if (!(est > target)) break;
            int dm = -1;
            for (int d = 0; d < 3; d++)
                if ((tested & 1 << d) && (dm < 0 || e[d] > e[dm])) dm = d;
            for (int d = 0; d < 3; d++)
                if ((tested & 1 << d) && d != dm && !(e[d] > 1e-3 * target)) settled[d] = 1;
            prev[dm] = fabs(qd[dm] - q0);
            c[dm] *= 2;
            q0 = qd[dm];
        }
    }
    for (int e = 0; e < 3; e++) coons__free(X[e].v);
    if (rc) return rc;
    *volume = result;
    if (error) *error = est;
    if (evaluations) *evaluations = (size_t)used;
    return COONS_OK;
}

coons_status coons_body_volume(const coons_body *b, double rel_tol, double *volume,
                               coons_error *err)
{
    return coons_body_volume_bounded(b, rel_tol, 0, volume, NULL, NULL, err);
}

coons_status coons_body_min_jacobian(const coons_body *b, unsigned n, double *min_det,
                                     double where[3], coons_error *err)
{
    if (!b || !min_det)
        return coons__error_set(err, COONS_E_INVALID, "body min Jacobian: NULL argument");
    if (n < 1)
        return coons__error_set(err, COONS_E_INVALID, "body min Jacobian: n = %u, need n >= 1",
                                n);
    if (n > 1u << 20)
        return coons__error_set(err, COONS_E_LIMIT, "body min Jacobian: n = %u is too large", n);
    size_t m = (size_t)n + 1;
    size_t slab = SLAB_POINTS / (m * m);
    if (slab < 1) slab = 1;
    if (slab > m) slab = m;
    double *t = coons__malloc_array(m + slab * m * m, sizeof(double));
    if (!t) return coons__error_nomem(err);
    double *par = t, *det = t + m;
    for (size_t i = 0; i < m; i++) par[i] = (double)i / n;
    double best = INFINITY, at[3] = {0, 0, 0};
    for (size_t i0 = 0; i0 < m; i0 += slab) {
        size_t ni = m - i0 < slab ? m - i0 : slab;
        coons_status rc = coons__body_det_grid(b, par + i0, ni, par, m, par, m, det, err);
        if (rc) {
            coons__free(t);
            return rc;
        }
        for (size_t i = 0; i < ni; i++)
            for (size_t j = 0; j < m; j++)
                for (size_t k = 0; k < m; k++) {
                    double dj = det[(i * m + j) * m + k];
                    if (dj < best) {
                        best = dj;
                        v3_set(at, par[i0 + i], par[j], par[k]);
                    }
                }
    }
    coons__free(t);
    *min_det = best;
    if (where) v3_copy(where, at);
    return COONS_OK;
}

coons_status coons__body_breaks(const coons_body *b, int d, double **out, size_t *n,
                                coons_error *err)
{
    coons__breaks B = {0};
    cell_bounds(b, d, &B);
    if (B.nomem) {
        coons__free(B.v);
        *out = NULL;
        *n = 0;
        return coons__error_nomem(err);
    }
    *out = B.v;
    *n = B.n;
    return COONS_OK;
}
