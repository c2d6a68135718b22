/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Tensor-product surfaces (model format, "Patches": bezier-surface and
 * bspline-surface; the surface analogue of seed 000's tensor-product solid):
 *   x(s,t) = sum_i sum_j B_i(s) B_j(t) P_ij            (Bernstein, degrees ns-1, nt-1)
 *   x(s,t) = sum w_ij N_i(s) N_j(t) P_ij / sum w_ij N_i(s) N_j(t)   (B-spline / NURBS)
 * Knot domains [k_p, k_n+1] map linearly onto [0,1] (coons__bspline_basis01).
 * Weights are separate from the Cartesian points (model format, "Resolved
 * details"); internally the net is also kept homogeneous (w P, w) so that
 * derivatives follow from the quotient rule (The NURBS Book, eq. 4.20).
 *
 * Pointwise evaluation and the grid sum in the same order (first over i for
 * each column j, then over j), so the grid is bitwise equal to eval.
 */
#include <string.h>

#include "bspline.h"
#include "patch_impl.h"

#define MAXB (COONS_SPLINE_MAX_DEGREE + 1)

/* Basis functions along s (dir 0) or t (dir 1): N[d*(deg+1) + k] for the
 * control indices first..first+deg; returns first. */
static size_t basis(const coons_patch *p, int dir, double x, int nd, double *N)
{
    int deg = dir ? p->pt : p->ps;
    if (!p->ks) { /* Bezier: no knots */
        coons__bernstein(deg, x, nd, N);
        return 0;
    }
    return coons__bspline_basis01(dir ? p->kt : p->ks, dir ? p->nt : p->ns, deg, x, nd, N);
}

/* R[c] = sum_k N[k] P[k*stride + c], k = 0..deg */
static inline void sum_rows(int dim, int deg, const double *N, const double *P, size_t stride,
                            double *R)
{
    double acc[4] = {0.0, 0.0, 0.0, 0.0};
    for (int k = 0; k <= deg; k++) {
        const double *q = P + (size_t)k * stride;
        for (int c = 0; c < dim; c++) acc[c] += N[k] * q[c];
    }
    for (int c = 0; c < dim; c++) R[c] = acc[c];
}

/* The point and its derivatives up to order from the bases along s (first
 * index fs, Ns[d*(ps+1) + k]) and t (ft, Nt): the sums of eval. */
#if defined(__GNUC__)
#define COONS__ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define COONS__ALWAYS_INLINE inline
#endif

static COONS__ALWAYS_INLINE void eval_basis_dim(int dim, int ps, int pt, const coons_patch *p, size_t fs,
                                  const double *Ns, size_t ft, const double *Nt, int order,
                                  double out[][3])
{
    const double *P = dim == 4 ? p->pw : p->pts;
    /* R[a][l] = sum_k d^a N_k(s) P[fs+k][ft+l]; A[a][b] = sum_l d^b N_l(t) R[a][l] */
    double R[3][MAXB][4];
    double A[3][3][4] = {{{0}}};
    size_t stride = p->nt * (size_t)dim;
    for (int a = 0; a <= order; a++)
        for (int l = 0; l <= pt; l++)
            sum_rows(dim, ps, Ns + a * (ps + 1), P + (fs * p->nt + ft + (size_t)l) * (size_t)dim,
                     stride, R[a][l]);
    for (int a = 0; a <= order; a++)
        for (int b = 0; a + b <= order; b++)
            sum_rows(dim, pt, Nt + b * (pt + 1), R[a][0], 4, A[a][b]);
    if (dim == 3) {
        v3_copy(out[0], A[0][0]);
        if (order >= 1) {
            v3_copy(out[1], A[1][0]);
            v3_copy(out[2], A[0][1]);
        }
        if (order >= 2) {
            v3_copy(out[3], A[2][0]);
            v3_copy(out[4], A[1][1]);
            v3_copy(out[5], A[0][2]);
        }
        return;
    }
    /* Quotient rule: S = A/W, differentiated with A = W S. */
    double W = A[0][0][3];
    double S00[3], S10[3], S01[3];
    for (int c = 0; c < 3; c++) S00[c] = A[0][0][c] / W;
    v3_copy(out[0], S00);
    if (order < 1) return;
    for (int c = 0; c < 3; c++) {
        S10[c] = (A[1][0][c] - A[1][0][3] * S00[c]) / W;
        S01[c] = (A[0][1][c] - A[0][1][3] * S00[c]) / W;
    }
    v3_copy(out[1], S10);
    v3_copy(out[2], S01);
    if (order < 2) return;
    for (int c = 0; c < 3; c++) {
        out[3][c] = (A[2][0][c] - 2.0 * A[1][0][3] * S10[c] - A[2][0][3] * S00[c]) / W;
        out[4][c] = (A[1][1][c] - A[1][0][3] * S01[c] - A[0][1][3] * S10[c] -
                     A[1][1][3] * S00[c]) / W;
        out[5][c] = (A[0][2][c] - 2.0 * A[0][1][3] * S01[c] - A[0][2][3] * S00[c]) / W;
    }
}

/* The sums for a constant dim (3: polynomial, 4: homogeneous), so that
 * sum_rows unrolls. */
static void eval_basis(const coons_patch *p, size_t fs, const double *Ns, size_t ft,
                       const double *Nt, int order, double out[][3])
{
    /* and for the common low degrees constant ones too (the same sums) */
#define EVAL(D, PS, PT)                                                                    \
    do {                                                                                   \
        if (order == 0)                                                                    \
            eval_basis_dim(D, PS, PT, p, fs, Ns, ft, Nt, 0, out);                          \
        else                                                                               \
            eval_basis_dim(D, PS, PT, p, fs, Ns, ft, Nt, order, out);                      \
    } while (0)
    const int ps = p->ps, pt = p->pt;
    if (p->pw) {
        if (ps == 2 && pt == 2)
            EVAL(4, 2, 2);
        else if (ps == 3 && pt == 3)
            EVAL(4, 3, 3);
        else
            EVAL(4, ps, pt);
    } else {
        if (ps == 2 && pt == 2)
            EVAL(3, 2, 2);
        else if (ps == 3 && pt == 3)
            EVAL(3, 3, 3);
        else
            EVAL(3, ps, pt);
    }
#undef EVAL
}

static void eval(const coons_patch *p, double s, double t, int order, double out[][3])
{
    double Ns[3 * MAXB], Nt[3 * MAXB];
    size_t fs = basis(p, 0, s, order, Ns), ft = basis(p, 1, t, order, Nt);
    eval_basis(p, fs, Ns, ft, Nt, order, out);
}

int coons__patch_is_tensor(const coons_patch *p)
{
    return p->kind == &coons__bezier_surface_kind || p->kind == &coons__bspline_surface_kind;
}

size_t coons__tensor_basis(const coons_patch *p, int dir, double x, int nd, double *N)
{
    return basis(p, dir, x, nd, N);
}

void coons__tensor_eval_basis(const coons_patch *p, size_t fs, const double *Ns, size_t ft,
                              const double *Nt, int order, double out[][3])
{
    eval_basis(p, fs, Ns, ft, Nt, order, out);
}

void coons__tensor_srow(const coons_patch *p, size_t fs, const double *Ns, double *R)
{
    const int dim = p->pw ? 4 : 3;
    const double *P = p->pw ? p->pw : p->pts;
    const size_t stride = p->nt * (size_t)dim;
    for (size_t l = 0; l < p->nt; l++)
        sum_rows(dim, p->ps, Ns, P + (fs * p->nt + l) * (size_t)dim, stride, R + 4 * l);
}

void coons__tensor_tcol(const coons_patch *p, size_t j, double *T)
{
    const int dim = p->pw ? 4 : 3;
    const double *P = p->pw ? p->pw : p->pts;
    for (size_t k = 0; k < p->ns; k++)
        for (int c = 0; c < dim; c++) T[4 * k + (size_t)c] = P[(k * p->nt + j) * (size_t)dim + (size_t)c];
}

static COONS__ALWAYS_INLINE void eval_tcol_dim(int dim, int ps, const double *T,
                                               size_t fs, const double *Ns, int order,
                                               double out[3], double *ds)
{
    double A0[4], A1[4];
    /* eval's sum over the t-basis: +0 before the 1, then R, then +-0 */
    sum_rows(dim, ps, Ns, T + 4 * fs, 4, A0);
    for (int c = 0; c < dim; c++) A0[c] = 0.0 + A0[c];
    if (order >= 1) {
        sum_rows(dim, ps, Ns + (ps + 1), T + 4 * fs, 4, A1);
        for (int c = 0; c < dim; c++) A1[c] = 0.0 + A1[c];
    }
    if (dim == 3) {
        v3_copy(out, A0);
        if (order >= 1) v3_copy(ds, A1);
        return;
    }
    double W = A0[3], S00[3];
    for (int c = 0; c < 3; c++) S00[c] = A0[c] / W;
    v3_copy(out, S00);
    if (order < 1) return;
    for (int c = 0; c < 3; c++) ds[c] = (A1[c] - A1[3] * S00[c]) / W;
}

void coons__tensor_eval_tcol(const coons_patch *p, const double *T, size_t fs,
                             const double *Ns, int order, double out[3], double *ds)
{
#define TCOL(D, PS)                                                                        \
    do {                                                                                   \
        if (order == 0)                                                                    \
            eval_tcol_dim(D, PS, T, fs, Ns, 0, out, ds);                                   \
        else                                                                               \
            eval_tcol_dim(D, PS, T, fs, Ns, 1, out, ds);                                   \
    } while (0)
    const int ps = p->ps;
    if (p->pw) {
        if (ps == 2)
            TCOL(4, 2);
        else if (ps == 3)
            TCOL(4, 3);
        else
            TCOL(4, ps);
    } else {
        if (ps == 2)
            TCOL(3, 2);
        else if (ps == 3)
            TCOL(3, 3);
        else
            TCOL(3, ps);
    }
#undef TCOL
}

static COONS__ALWAYS_INLINE void eval_srow_dim(int dim, int pt, const double *R, size_t ft,
                                               const double *Nt, int order, double out[3],
                                               double *dt)
{
    double A00[4], A01[4];
    sum_rows(dim, pt, Nt, R + 4 * ft, 4, A00);
    if (order >= 1) sum_rows(dim, pt, Nt + (pt + 1), R + 4 * ft, 4, A01);
    if (dim == 3) {
        v3_copy(out, A00);
        if (order >= 1) v3_copy(dt, A01);
        return;
    }
    double W = A00[3], S00[3];
    for (int c = 0; c < 3; c++) S00[c] = A00[c] / W;
    v3_copy(out, S00);
    if (order < 1) return;
    for (int c = 0; c < 3; c++) dt[c] = (A01[c] - A01[3] * S00[c]) / W;
}

void coons__tensor_eval_srow(const coons_patch *p, const double *R, size_t ft,
                             const double *Nt, int order, double out[3], double *dt)
{
    const int pt = p->pt;
    if (p->pw) {
        if (pt == 2)
            eval_srow_dim(4, 2, R, ft, Nt, order, out, dt);
        else if (pt == 3)
            eval_srow_dim(4, 3, R, ft, Nt, order, out, dt);
        else
            eval_srow_dim(4, pt, R, ft, Nt, order, out, dt);
    } else {
        if (pt == 2)
            eval_srow_dim(3, 2, R, ft, Nt, order, out, dt);
        else if (pt == 3)
            eval_srow_dim(3, 3, R, ft, Nt, order, out, dt);
        else
            eval_srow_dim(3, pt, R, ft, Nt, order, out, dt);
    }
}

_Static_assert(_Alignof(size_t) <= _Alignof(double), "size_t packed after doubles");

/* The grid for a constant dim (3: polynomial, 4: homogeneous), so that
 * sum_rows unrolls; same sums in the same order as eval. */
static inline void grid_lines(int dim, const coons_patch *p, const double *P, const double *s,
                              size_t ns, size_t nt, const double *Nt, const size_t *ft,
                              double *R, double *out)
{
    const int ps = p->ps, pt = p->pt;
    const size_t q1 = (size_t)pt + 1, nct = p->nt, stride = nct * (size_t)dim;
    double Ns[MAXB];
    for (size_t i = 0; i < ns; i++) {
        size_t fs = basis(p, 0, clamp01(s[i]), 0, Ns);
        const double *row = P + fs * stride;
        for (size_t jj = 0; jj < nct; jj++)
            sum_rows(dim, ps, Ns, row + jj * (size_t)dim, stride, R + jj * (size_t)dim);
        double *o = out + i * nt * 3;
        for (size_t j = 0; j < nt; j++) {
            double A[4];
            sum_rows(dim, pt, Nt + j * q1, R + ft[j] * (size_t)dim, (size_t)dim, A);
            if (dim == 4) {
                for (int c = 0; c < 3; c++) o[3 * j + (size_t)c] = A[c] / A[3];
            } else {
                o[3 * j] = A[0];
                o[3 * j + 1] = A[1];
                o[3 * j + 2] = A[2];
            }
        }
    }
}


static coons_status grid(const coons_patch *p, const double *s, size_t ns, const double *t,
                         size_t nt, double *out, coons_error *err)
{
    const int pt = p->pt, dim = p->pw ? 4 : 3;
    const double *P = p->pw ? p->pw : p->pts;
    const size_t q1 = (size_t)pt + 1, nct = p->nt;
    /* Scratch: t-basis per grid column, one s-combined net column per
     * control column, and the first t-index per grid column. */
    /* nct * 4 doubles is small (the net passed COONS_PATCH_MAX_POINTS);
     * only nt can overflow the byte count. */
    const size_t per_col = q1 * sizeof(double) + sizeof(size_t);
    const size_t fixed = nct * 4 * sizeof(double);
    if (nt > (SIZE_MAX - fixed) / per_col) return coons__error_nomem(err);
    const size_t nd = nt * q1 + nct * (size_t)dim, bytes_d = nd * sizeof(double);
    double *scratch = coons__malloc(bytes_d + nt * sizeof(size_t));
    if (!scratch) return coons__error_nomem(err);
    double *Nt = scratch, *R = scratch + nt * q1;
    size_t *ft = (size_t *)(void *)(scratch + nd);

    for (size_t j = 0; j < nt; j++) ft[j] = basis(p, 1, clamp01(t[j]), 0, Nt + j * q1);
    if (dim == 3)
        grid_lines(3, p, P, s, ns, nt, Nt, ft, R, out);
    else
        grid_lines(4, p, P, s, ns, nt, Nt, ft, R, out);
    coons__free(scratch);
    return COONS_OK;
}

static coons_status copy_data(const coons_patch *p, coons_patch *d, coons_error *err)
{
    size_t n = p->ns * p->nt;
    d->pts = d->w = d->pw = d->ks = d->kt = NULL;
    d->pts = coons__memdup(p->pts, 3 * n, sizeof(double));
    if (!d->pts) return coons__error_nomem(err);
    if (p->w && !(d->w = coons__memdup(p->w, n, sizeof(double)))) return coons__error_nomem(err);
    if (p->pw && !(d->pw = coons__memdup(p->pw, 4 * n, sizeof(double))))
        return coons__error_nomem(err);
    if (p->ks &&
        !(d->ks = coons__memdup(p->ks, p->ns + (size_t)p->ps + 1, sizeof(double))))
        return coons__error_nomem(err);
    if (p->kt &&
        !(d->kt = coons__memdup(p->kt, p->nt + (size_t)p->pt + 1, sizeof(double))))
        return coons__error_nomem(err);
    return COONS_OK;
}

static void free_data(coons_patch *p)
{
    coons__free(p->pts);
    coons__free(p->w);
    coons__free(p->pw);
    coons__free(p->ks);
    coons__free(p->kt);
}

static void control_bbox(const coons_patch *p, double lo[3], double hi[3])
{
    for (size_t i = 0; i < p->ns * p->nt; i++) bbox_add(lo, hi, p->pts + 3 * i);
}

static void bspline_breaks(const coons_patch *p, int dir, coons__breaks *B)
{
    if (dir == 0)
        coons__breaks_knots(B, p->ks, p->ns, p->ps);
    else
        coons__breaks_knots(B, p->kt, p->nt, p->pt);
}

/* Degrees ps, pt; rational with weights that differ. */
static void space(const coons_patch *p, int dir, coons__space *S)
{
    S->degree = dir == 0 ? p->ps : p->pt;
    S->kind = coons__weights_space(p->w, p->ns * p->nt);
    S->cont = dir == 0 ? coons__knots_continuity(p->ks, p->ns, p->ps)
                       : coons__knots_continuity(p->kt, p->nt, p->pt);
}

const coons__patch_kind coons__bezier_surface_kind = {
    .type = COONS_PATCH_BEZIER, .eval = eval, .grid = grid, .control_bbox = control_bbox,
    .copy = copy_data, .free = free_data, .space = space};
const coons__patch_kind coons__bspline_surface_kind = {
    .type = COONS_PATCH_BSPLINE, .eval = eval, .grid = grid, .control_bbox = control_bbox,
    .breaks = bspline_breaks, .copy = copy_data, .free = free_data, .space = space};

static coons_status check_net(const double *points, size_t ns, size_t nt, const char *what,
                              coons_error *err)
{
    if (!points) return coons__error_set(err, COONS_E_INVALID, "%s: points are NULL", what);
    for (size_t i = 0; i < ns; i++)
        for (size_t j = 0; j < nt; j++)
            if (!v3_finite(points + 3 * (i * nt + j)))
                return coons__error_set(err, COONS_E_INVALID,
                                        "%s: point [%zu][%zu] is not finite", what, i, j);
    return COONS_OK;
}

coons_status coons_patch_new_bezier(const double *points, size_t ns, size_t nt, coons_patch **out,
                                    coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "bezier surface: out is NULL");
    *out = NULL;
    if (ns < 2 || nt < 2)
        return coons__error_set(err, COONS_E_INVALID,
                                "bezier surface needs at least 2 x 2 points, got %zu x %zu", ns,
                                nt);
    if (ns > COONS_SPLINE_MAX_DEGREE + 1 || nt > COONS_SPLINE_MAX_DEGREE + 1)
        return coons__error_set(err, COONS_E_LIMIT,
                                "bezier surface of %zu x %zu points: degree above the limit %d",
                                ns, nt, COONS_SPLINE_MAX_DEGREE);
    coons_status rc = check_net(points, ns, nt, "bezier surface", err);
    if (rc) return rc;
    coons_patch *p = NULL;
    if ((rc = coons__patch_alloc(&coons__bezier_surface_kind, &p, err))) return rc;
    p->ps = (int)ns - 1;
    p->pt = (int)nt - 1;
    p->ns = ns;
    p->nt = nt;
    if (!(p->pts = coons__memdup(points, 3 * ns * nt, sizeof(double)))) {
        coons_patch_free(p);
        return coons__error_nomem(err);
    }
    *out = p;
    return COONS_OK;
}

coons_status coons_patch_new_bspline(int ps, int pt, const double *points, size_t ns, size_t nt,
                                     const double *knots_s, const double *knots_t,
                                     const double *weights, coons_patch **out, coons_error *err)
{
    static const char what[] = "bspline surface";
    if (!out) return coons__error_set(err, COONS_E_INVALID, "%s: out is NULL", what);
    *out = NULL;
    if (ps < 1 || ps > COONS_SPLINE_MAX_DEGREE || pt < 1 || pt > COONS_SPLINE_MAX_DEGREE)
        return coons__error_set(err, COONS_E_INVALID, "%s: degrees (%d, %d) outside 1..%d", what,
                                ps, pt, COONS_SPLINE_MAX_DEGREE);
    if (ns < (size_t)ps + 1 || nt < (size_t)pt + 1)
        return coons__error_set(err, COONS_E_INVALID,
                                "%s: degrees (%d, %d) need at least %d x %d points, got %zu x %zu",
                                what, ps, pt, ps + 1, pt + 1, ns, nt);
    if (ns > COONS_PATCH_MAX_POINTS || nt > COONS_PATCH_MAX_POINTS / ns)
        return coons__error_set(err, COONS_E_LIMIT,
                                "%s of %zu x %zu points: more than the limit of %d points", what,
                                ns, nt, COONS_PATCH_MAX_POINTS);
    coons_status rc = check_net(points, ns, nt, what, err);
    if (rc) return rc;
    size_t n = ns * nt;
    if (weights)
        for (size_t i = 0; i < n; i++)
            if (!(weights[i] > 0.0) || !isfinite(weights[i]))
                return coons__error_set(err, COONS_E_INVALID,
                                        "%s: weight [%zu][%zu] is %g, weights must be finite "
                                        "and > 0",
                                        what, i / nt, i % nt, weights[i]);
    coons_patch *p = NULL;
    if ((rc = coons__patch_alloc(&coons__bspline_surface_kind, &p, err))) return rc;
    p->ps = ps;
    p->pt = pt;
    p->ns = ns;
    p->nt = nt;
    if ((rc = coons__knots_make(ps, ns, knots_s, "bspline surface (s knots)", &p->ks, err)) ||
        (rc = coons__knots_make(pt, nt, knots_t, "bspline surface (t knots)", &p->kt, err))) {
        coons_patch_free(p);
        return rc;
    }
    if (weights && (rc = coons__weights_make(weights, n, what, &p->w, err))) {
        coons_patch_free(p);
        return rc;
    }
    p->pts = coons__memdup(points, 3 * n, sizeof(double));
    if (weights) p->pw = coons__malloc_array(4 * n, sizeof(double));
    if (!p->pts || (weights && !p->pw)) {
        coons_patch_free(p);
        return coons__error_nomem(err);
    }
    if (weights)
        for (size_t i = 0; i < n; i++) {
            for (int c = 0; c < 3; c++) p->pw[4 * i + (size_t)c] = p->w[i] * points[3 * i + (size_t)c];
            p->pw[4 * i + 3] = p->w[i];
        }
    *out = p;
    return COONS_OK;
}
