/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Tensor-product solids (seed 000 section 2, first equation):
 *   p(u,v,w) = sum_ijk b_ijk F_i(u) F_j(v) F_k(w),
 * with F the Bernstein basis (Bezier volume) or the B-spline basis over a
 * knot vector whose domain is mapped onto [0,1] (model format); NURBS
 * volumes divide sum w_ijk F F F b_ijk by sum w_ijk F F F (weights kept
 * separate from the Cartesian points, model format "Resolved details").
 * A Bezier volume is the B-spline volume with knots 0^(n) 1^(n).
 */
#include <string.h>

#include "body_impl.h"
#include "bspline.h"

static coons_status make_tensor(const coons__body_kind *kind, const int deg[3], const double *points,
                                const size_t n[3], const double *const knots[3],
                                const double *weights, const char *what, coons_body **out,
                                coons_error *err)
{
    *out = NULL;
    if (!points || !n || !deg)
        return coons__error_set(err, COONS_E_INVALID, "%s: points, counts or degrees are NULL",
                                what);
    size_t np = 1;
    for (int d = 0; d < 3; d++) {
        if (deg[d] < 1 || deg[d] > COONS_SPLINE_MAX_DEGREE)
            return coons__error_set(err, COONS_E_INVALID, "%s: degree %d along %c is outside 1..%d",
                                    what, deg[d], "uvw"[d], COONS_SPLINE_MAX_DEGREE);
        if (n[d] < (size_t)deg[d] + 1)
            return coons__error_set(err, COONS_E_INVALID,
                                    "%s: degree %d along %c needs at least %d points, got %zu",
                                    what, deg[d], "uvw"[d], deg[d] + 1, n[d]);
        if (n[d] > COONS_BODY_MAX_POINTS / np)
            return coons__error_set(err, COONS_E_LIMIT,
                                    "%s: more than %d control points", what,
                                    COONS_BODY_MAX_POINTS);
        np *= n[d];
    }
    for (size_t i = 0; i < np; i++)
        if (!v3_finite(points + 3 * i))
            return coons__error_set(err, COONS_E_INVALID, "%s: point [%zu][%zu][%zu] is not finite",
                                    what, i / (n[1] * n[2]), i / n[2] % n[1], i % n[2]);
    if (weights)
        for (size_t i = 0; i < np; i++)
            if (!(weights[i] > 0.0) || !isfinite(weights[i]))
                return coons__error_set(err, COONS_E_INVALID,
                                        "%s: weight [%zu][%zu][%zu] is %.17g, weights must be "
                                        "finite and > 0",
                                        what, i / (n[1] * n[2]), i / n[2] % n[1], i % n[2],
                                        weights[i]);
    coons_body *b;
    coons_status rc = coons__body_alloc(kind, COONS_BLEND_LINEAR, &b, err);
    if (rc) return rc;
    for (int d = 0; d < 3; d++) {
        b->deg[d] = deg[d];
        b->n[d] = n[d];
        if ((rc = coons__knots_make(deg[d], n[d], knots ? knots[d] : NULL, what, &b->knots[d],
                                    err))) {
            coons_body_free(b);
            return rc;
        }
    }
    if (weights && (rc = coons__weights_make(weights, np, what, &b->w, err))) {
        coons_body_free(b);
        return rc;
    }
    b->pts = coons__memdup(points, 3 * np, sizeof(double));
    if (!b->pts) {
        coons_body_free(b);
        return coons__error_nomem(err);
    }
    for (size_t i = 0; i < np; i++) bbox_add(b->lo, b->hi, points + 3 * i);
    *out = b;
    return COONS_OK;
}

coons_status coons_body_new_bezier(const double *points, const size_t n[3], coons_body **out,
                                   coons_error *err)
{
    *out = NULL;
    if (!n) return coons__error_set(err, COONS_E_INVALID, "bezier-volume: counts are NULL");
    int deg[3];
    double kn[3][2 * (COONS_SPLINE_MAX_DEGREE + 1)];
    const double *k[3];
    for (int d = 0; d < 3; d++) {
        if (n[d] < 2 || n[d] > COONS_SPLINE_MAX_DEGREE + 1)
            return coons__error_set(err, n[d] < 2 ? COONS_E_INVALID : COONS_E_LIMIT,
                                    "bezier-volume: %zu points along %c, need 2..%d", n[d],
                                    "uvw"[d], COONS_SPLINE_MAX_DEGREE + 1);
        deg[d] = (int)n[d] - 1;
        for (int i = 0; i <= deg[d]; i++) {
            kn[d][i] = 0.0;
            kn[d][deg[d] + 1 + i] = 1.0;
        }
        k[d] = kn[d];
    }
    return make_tensor(&coons__bezier_volume_kind, deg, points, n, k, NULL, "bezier-volume", out, err);
}

coons_status coons_body_new_bspline(const int degree[3], const double *points, const size_t n[3],
                                    const double *knots_u, const double *knots_v,
                                    const double *knots_w, const double *weights,
                                    coons_body **out, coons_error *err)
{
    const double *const knots[3] = {knots_u, knots_v, knots_w};
    return make_tensor(&coons__bspline_volume_kind, degree, points, n, knots, weights, "bspline-volume",
                       out, err);
}

static void eval(const coons_body *b, double u, double v, double w, double out[3],
                 double d[3][3])
{
    int p = b->deg[0], q = b->deg[1], r = b->deg[2], nd = d ? 1 : 0;
    double Nu[2 * (COONS_SPLINE_MAX_DEGREE + 1)], Nv[2 * (COONS_SPLINE_MAX_DEGREE + 1)],
        Nw[2 * (COONS_SPLINE_MAX_DEGREE + 1)];
    size_t fu = coons__bspline_basis01(b->knots[0], b->n[0], p, u, nd, Nu);
    size_t fv = coons__bspline_basis01(b->knots[1], b->n[1], q, v, nd, Nv);
    size_t fw = coons__bspline_basis01(b->knots[2], b->n[2], r, w, nd, Nw);
    /* S[0] value, S[1..3] partials of sum (w) N N N P; W likewise. */
    double S[4][3] = {{0}}, W[4] = {0};
    size_t n1 = b->n[1], n2 = b->n[2];
    for (int a = 0; a <= p; a++)
        for (int c = 0; c <= q; c++)
            for (int e = 0; e <= r; e++) {
                size_t idx = ((fu + (size_t)a) * n1 + fv + (size_t)c) * n2 + fw + (size_t)e;
                const double *P = b->pts + 3 * idx;
                double wt = b->w ? b->w[idx] : 1.0;
                double f[4];
                f[0] = Nu[a] * Nv[c] * Nw[e];
                if (d) {
                    f[1] = Nu[p + 1 + a] * Nv[c] * Nw[e];
                    f[2] = Nu[a] * Nv[q + 1 + c] * Nw[e];
                    f[3] = Nu[a] * Nv[c] * Nw[r + 1 + e];
                }
                for (int m = 0; m <= 3 * nd; m++) {
                    v3_axpy(S[m], wt * f[m], P);
                    W[m] += wt * f[m];
                }
            }
    v3_scale(out, S[0], 1.0 / W[0]);
    if (!d) return;
    for (int m = 0; m < 3; m++)
        for (int k = 0; k < 3; k++) d[m][k] = (S[1 + m][k] - W[1 + m] * out[k]) / W[0];
}

/* Basis values of one direction at every sample: first control index and
 * the deg+1 non-zero values. */
static void line_basis(const double *knots, size_t ncp, int deg, const double *t, size_t nt,
                       size_t *first, double *N)
{
    for (size_t i = 0; i < nt; i++)
        first[i] = coons__bspline_basis01(knots, ncp, deg, clamp01(t[i]), 0,
                                          N + i * (size_t)(deg + 1));
}

/*
 * Grid by successive contractions: per u sample A = sum_a N_a(u) b_a.. over
 * the whole (v,w) net, per (u,v) B = sum_c N_c(v) A_c. over the w net, per
 * point sum_e N_e(w) B_e. Rational volumes carry the weight as a fourth
 * homogeneous coordinate and divide at the end.
 */
static coons_status grid(const coons_body *b, const double *u, size_t nu, const double *v,
                         size_t nv, const double *w, size_t nw, double *out, coons_error *err)
{
    int p = b->deg[0], q = b->deg[1], r = b->deg[2];
    size_t n1 = b->n[1], n2 = b->n[2], dim = b->w ? 4 : 3;
    size_t nd = 0, ni = 0;
    if (!coons__size_addmul(&nd, nu, (size_t)p + 1) || !coons__size_addmul(&nd, nv, (size_t)q + 1) ||
        !coons__size_addmul(&nd, nw, (size_t)r + 1) || !coons__size_addmul(&nd, n1 * n2, dim) ||
        !coons__size_addmul(&nd, n2, dim) || !coons__size_addmul(&ni, nu, 1) ||
        !coons__size_addmul(&ni, nv, 1) || !coons__size_addmul(&ni, nw, 1))
        return coons__error_set(err, COONS_E_LIMIT, "volume grid: scratch size overflows");
    double *s = coons__malloc_array(nd, sizeof(double));
    size_t *fi = coons__malloc_array(ni, sizeof(size_t));
    if (!s || !fi) {
        coons__free(s);
        coons__free(fi);
        return coons__error_nomem(err);
    }
    double *BU = s, *BV = BU + nu * (size_t)(p + 1), *BW = BV + nv * (size_t)(q + 1),
           *A = BW + nw * (size_t)(r + 1), *B = A + n1 * n2 * dim;
    size_t *fu = fi, *fv = fu + nu, *fw = fv + nv;
    line_basis(b->knots[0], b->n[0], p, u, nu, fu, BU);
    line_basis(b->knots[1], b->n[1], q, v, nv, fv, BV);
    line_basis(b->knots[2], b->n[2], r, w, nw, fw, BW);
    size_t slab = n1 * n2;
    for (size_t i = 0; i < nu; i++) {
        const double *N = BU + i * (size_t)(p + 1);
        memset(A, 0, slab * dim * sizeof(double));
        for (int a = 0; a <= p; a++) {
            size_t base = (fu[i] + (size_t)a) * slab;
            const double *P = b->pts + 3 * base;
            double f = N[a];
            if (!b->w) {
                for (size_t m = 0; m < 3 * slab; m++) A[m] += f * P[m];
            } else {
                const double *wt = b->w + base;
                for (size_t m = 0; m < slab; m++) {
                    double fw_ = f * wt[m];
                    A[4 * m] += fw_ * P[3 * m];
                    A[4 * m + 1] += fw_ * P[3 * m + 1];
                    A[4 * m + 2] += fw_ * P[3 * m + 2];
                    A[4 * m + 3] += fw_;
                }
            }
        }
        for (size_t j = 0; j < nv; j++) {
            const double *M = BV + j * (size_t)(q + 1);
            size_t row = n2 * dim;
            const double *Ar = A + fv[j] * row;
            for (size_t m = 0; m < row; m++) B[m] = M[0] * Ar[m];
            for (int c = 1; c <= q; c++) {
                const double *Ac = Ar + (size_t)c * row;
                for (size_t m = 0; m < row; m++) B[m] += M[c] * Ac[m];
            }
            double *o = out + (i * nv + j) * nw * 3;
            for (size_t k = 0; k < nw; k++) {
                const double *L = BW + k * (size_t)(r + 1), *Bk = B + fw[k] * dim;
                double x = 0.0, y = 0.0, z = 0.0, h = 0.0;
                for (int e = 0; e <= r; e++) {
                    const double *Be = Bk + (size_t)e * dim;
                    x += L[e] * Be[0];
                    y += L[e] * Be[1];
                    z += L[e] * Be[2];
                    if (dim == 4) h += L[e] * Be[3];
                }
                if (dim == 4) {
                    x /= h;
                    y /= h;
                    z /= h;
                }
                o[3 * k] = x;
                o[3 * k + 1] = y;
                o[3 * k + 2] = z;
            }
        }
    }
    coons__free(s);
    coons__free(fi);
    return COONS_OK;
}

static void breaks(const coons_body *b, int d, coons__breaks *B)
{
    coons__breaks_knots(B, b->knots[d], b->n[d], b->deg[d]);
}

static coons_status copy_data(const coons_body *b, coons_body *d, coons_error *err)
{
    size_t np = b->n[0] * b->n[1] * b->n[2];
    d->pts = coons__memdup(b->pts, 3 * np, sizeof(double));
    d->w = b->w ? coons__memdup(b->w, np, sizeof(double)) : NULL;
    for (int k = 0; k < 3; k++)
        d->knots[k] =
            coons__memdup(b->knots[k], b->n[k] + (size_t)b->deg[k] + 1, sizeof(double));
    if (!d->pts || (b->w && !d->w) || !d->knots[0] || !d->knots[1] || !d->knots[2])
        return coons__error_nomem(err);
    return COONS_OK;
}

static void free_data(coons_body *b)
{
    coons__free(b->pts);
    for (int d = 0; d < 3; d++) coons__free(b->knots[d]);
    coons__free(b->w);
}

/* Degrees deg[d]; rational with weights that differ. */
static void space(const coons_body *b, int d, coons__space *S)
{
    S->degree = b->deg[d];
    S->kind = coons__weights_space(b->w, b->n[0] * b->n[1] * b->n[2]);
    S->cont = coons__knots_continuity(b->knots[d], b->n[d], b->deg[d]);
}

#define TENSOR_ROW(t)                                                                  \
    {.type = t, .eval = eval, .grid = grid, .breaks = breaks, .copy = copy_data,          \
     .free = free_data, .space = space}
const coons__body_kind coons__bezier_volume_kind = TENSOR_ROW(COONS_BODY_BEZIER);
const coons__body_kind coons__bspline_volume_kind = TENSOR_ROW(COONS_BODY_BSPLINE);
