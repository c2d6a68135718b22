/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The B-spline / NURBS form of coons/nurbs.h. The rows' space operation
 * (kinds.h) gives, per direction, the degree p, the continuity c at the
 * breakpoints and whether the object is polynomial, a NURBS over its own
 * data, or neither. Polynomial objects are interpolated at the Greville
 * points of the space of degree p with a knot of multiplicity p - c at each
 * breakpoint (it contains them: seed 000 section 2.4 for the Coons body 2),
 * direction by direction (the collocation matrix is banded and totally
 * positive, so elimination without pivoting is stable: de Boor, A Practical
 * Guide to Splines, ch. XIII). NURBS objects are copied through their
 * wrappers. Others are fitted in refined cubic spaces. Every form is
 * measured against the object at two Gauss points per knot span.
 */
#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "affine.h"
#include "body_impl.h"
#include "bspline.h"
#include "curve_impl.h"
#include "nurbs_impl.h"
#include "patch_impl.h"

/* The object a form is made for: a curve, a patch, a body or a body face. */
typedef struct target {
    int dim;
    const coons_curve *c;
    const coons_patch *p;
    const coons_body *b;
    int face;    /* -1, or the face of b */
    int dir[3];  /* body direction of each form direction */
} target;

static target curve_target(const coons_curve *c) { return (target){1, c, NULL, NULL, -1, {0, 1, 2}}; }
static target patch_target(const coons_patch *p) { return (target){2, NULL, p, NULL, -1, {0, 1, 2}}; }
static target body_target(const coons_body *b) { return (target){3, NULL, NULL, b, -1, {0, 1, 2}}; }

static target face_target(const coons_body *b, int f)
{
    target T = {2, NULL, NULL, b, f, {0, 0, 0}};
    for (int d = 0, m = 0; d < 3; d++)
        if (d != f / 2) T.dir[m++] = d;
    return T;
}

static coons__space target_space(const target *T, int d)
{
    if (T->c) return coons__curve_space(T->c);
    if (T->p) return coons__patch_space(T->p, d);
    return coons__body_space(T->b, T->dir[d]);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The sorted distinct breakpoints in (0,1) along form direction d. */
static coons_status target_breaks(const target *T, int d, coons__breaks *B, coons_error *err)
{
    *B = (coons__breaks){.all = 1};
    if (T->c)
        coons__curve_breaks(T->c, B);
    else if (T->p)
        coons__patch_breaks(T->p, d, B);
    else if (T->b->kind->breaks)
        T->b->kind->breaks(T->b, T->dir[d], B);
    if (B->nomem) return coons__error_nomem(err);
    if (B->n) qsort(B->v, B->n, sizeof *B->v, cmp_double);
    size_t m = 0;
    for (size_t i = 0; i < B->n; i++)
        if (m == 0 || B->v[i] - B->v[m - 1] > 4.0 * DBL_EPSILON) B->v[m++] = B->v[i];
    B->n = m;
    return COONS_OK;
}

/* The object on the tensor grid par[0] x .. x par[dim-1] into out
 * (3 doubles a point, the last direction fastest). */
static coons_status target_grid(const target *T, double *const par[3], const size_t np[3],
                                double *out, coons_error *err)
{
    if (T->c) {
        for (size_t i = 0; i < np[0]; i++) coons_curve_eval(T->c, par[0][i], out + 3 * i);
        return COONS_OK;
    }
    if (T->p) return coons_patch_eval_grid(T->p, par[0], np[0], par[1], np[1], out, err);
    if (T->face < 0)
        return coons_body_eval_grid(T->b, par[0], np[0], par[1], np[1], par[2], np[2], out, err);
    const double *q[3];
    size_t n[3];
    double x = (double)(T->face % 2);
    q[T->face / 2] = &x;
    n[T->face / 2] = 1;
    for (int m = 0; m < 2; m++) {
        q[T->dir[m]] = par[m];
        n[T->dir[m]] = np[m];
    }
    return coons_body_eval_grid(T->b, q[0], n[0], q[1], n[1], q[2], n[2], out, err);
}

void coons_nurbs_free(coons_nurbs *n)
{
    if (!n) return;
    for (int d = 0; d < 3; d++) coons__free(n->knots[d]);
    coons__free(n->points);
    coons__free(n->weights);
    memset(n, 0, sizeof *n);
}

static void nurbs_empty(coons_nurbs *n, int dim)
{
    memset(n, 0, sizeof *n);
    n->dim = dim;
    for (int d = 0; d < 3; d++) n->count[d] = 1;
}

static size_t nurbs_size(const coons_nurbs *n) { return n->count[0] * n->count[1] * n->count[2]; }

/* Basis of direction d at x: returns the first index, N[0..p]. */
static size_t basis_at(const coons_nurbs *n, int d, double x, double *N)
{
    if (n->degree[d] == 0 || !n->knots[d]) {
        N[0] = 1.0;
        return 0;
    }
    return coons__bspline_basis01(n->knots[d], n->count[d], n->degree[d], clamp01(x), 0, N);
}

/* The point from the bases of each direction (first index f[d], values
 * N[d][0..degree]). */
static void nurbs_point(const coons_nurbs *n, const size_t f[3], double *const N[3], double out[3])
{
    double A[4] = {0, 0, 0, 0};
    int p0 = n->degree[0], p1 = n->degree[1], p2 = n->degree[2];
    for (int a = 0; a <= p0; a++)
        for (int b = 0; b <= p1; b++) {
            double nab = N[0][a] * N[1][b];
            size_t row = ((f[0] + (size_t)a) * n->count[1] + f[1] + (size_t)b) * n->count[2];
            for (int c = 0; c <= p2; c++) {
                size_t i = row + f[2] + (size_t)c;
                double wn = nab * N[2][c] * (n->weights ? n->weights[i] : 1.0);
                A[0] += wn * n->points[3 * i];
                A[1] += wn * n->points[3 * i + 1];
                A[2] += wn * n->points[3 * i + 2];
                A[3] += wn;
            }
        }
    for (int k = 0; k < 3; k++) out[k] = n->weights ? A[k] / A[3] : A[k];
}

void coons_nurbs_eval(const coons_nurbs *n, const double *param, double out[3])
{
    if (!n || !n->points || n->dim < 1 || n->dim > 3 || (!param && n->dim)) {
        out[0] = out[1] = out[2] = NAN;
        return;
    }
    double buf[3][COONS_SPLINE_MAX_DEGREE + 1];
    double *N[3] = {buf[0], buf[1], buf[2]};
    size_t f[3] = {0, 0, 0};
    for (int d = 0; d < 3; d++) f[d] = basis_at(n, d, d < n->dim ? param[d] : 0.0, N[d]);
    nurbs_point(n, f, N, out);
}

/* ---- spaces ------------------------------------------------------------ */

/* Knots of degree p, clamped, with multiplicity mult at each breakpoint
 * and sub - 1 simple knots spaced evenly inside each interval between. */
static coons_status make_knots(coons_nurbs *n, int d, int p, int mult, const double *br,
                               size_t nbr, size_t sub, coons_error *err)
{
    size_t len = 2 * (size_t)(p + 1) + (nbr + 1) * (sub - 1) + nbr * (size_t)mult;
    double *k = coons__malloc_array(len, sizeof *k);
    if (!k) return coons__error_nomem(err);
    size_t m = 0;
    for (int i = 0; i <= p; i++) k[m++] = 0.0;
    double a = 0.0;
    for (size_t i = 0; i <= nbr; i++) {
        double b = i < nbr ? br[i] : 1.0;
        for (size_t q = 1; q < sub; q++) k[m++] = a + (b - a) * (double)q / (double)sub;
        if (i < nbr)
            for (int r = 0; r < mult; r++) k[m++] = b;
        a = b;
    }
    for (int i = 0; i <= p; i++) k[m++] = 1.0;
    n->knots[d] = k;
    n->degree[d] = p;
    n->count[d] = m - (size_t)p - 1;
    return COONS_OK;
}

/* Greville abscissae of direction d into g (count[d] values). */
static void greville(const coons_nurbs *n, int d, double *g)
{
    int p = n->degree[d];
    for (size_t i = 0; i < n->count[d]; i++) {
        double s = 0.0;
        for (int r = 1; r <= p; r++) s += n->knots[d][i + (size_t)r];
        g[i] = clamp01(s / p);
    }
}

/* Solves the collocation system of direction d, in place, along every
 * line of the control net (the values at the Greville points in, the
 * control points out). Band of half-width p, no pivoting (total
 * positivity). */
static coons_status collocate(coons_nurbs *n, int d, const double *g, coons_error *err)
{
    size_t cnt = n->count[d];
    int p = n->degree[d], w = 2 * p + 1;
    double *A = coons__calloc(cnt * (size_t)w, sizeof *A);
    if (!A) return coons__error_nomem(err);
    double N[COONS_SPLINE_MAX_DEGREE + 1];
    for (size_t i = 0; i < cnt; i++) {
        size_t first = coons__bspline_basis01(n->knots[d], cnt, p, g[i], 0, N);
        for (int j = 0; j <= p; j++) {
            long off = (long)(first + (size_t)j) - (long)i + p;
            if (off < 0 || off >= w) {
                if (N[j] != 0.0) {
                    coons__free(A);
                    return coons__error_set(err, COONS_E_INTERNAL,
                                            "nurbs: collocation row %zu outside its band", i);
                }
                continue;
            }
            A[i * (size_t)w + (size_t)off] = N[j];
        }
    }
    for (size_t k = 0; k < cnt; k++) {
        double piv = A[k * (size_t)w + (size_t)p];
        if (!(fabs(piv) > 1e-300)) {
            coons__free(A);
            return coons__error_set(err, COONS_E_INTERNAL, "nurbs: singular collocation at %zu", k);
        }
        for (size_t r = k + 1; r < cnt && r <= k + (size_t)p; r++) {
            double *ar = A + r * (size_t)w;
            double l = ar[k - r + (size_t)p] / piv;
            ar[k - r + (size_t)p] = l;
            for (size_t c = k + 1; c < cnt && c <= k + (size_t)p; c++)
                ar[c - r + (size_t)p] -= l * A[k * (size_t)w + c - k + (size_t)p];
        }
    }
    size_t stride = 1, lines = 1;
    for (int e = d + 1; e < 3; e++) stride *= n->count[e];
    for (int e = 0; e < d; e++) lines *= n->count[e];
    for (size_t L = 0; L < lines; L++)
        for (size_t o = 0; o < stride; o++) {
            double *x = n->points + 3 * (L * cnt * stride + o);
            size_t st = 3 * stride;
            for (size_t r = 1; r < cnt; r++)
                for (size_t c = r > (size_t)p ? r - (size_t)p : 0; c < r; c++)
                    for (int q = 0; q < 3; q++)
                        x[r * st + (size_t)q] -= A[r * (size_t)w + c - r + (size_t)p] * x[c * st + (size_t)q];
            for (size_t r = cnt; r-- > 0;) {
                for (size_t c = r + 1; c < cnt && c <= r + (size_t)p; c++)
                    for (int q = 0; q < 3; q++)
                        x[r * st + (size_t)q] -= A[r * (size_t)w + c - r + (size_t)p] * x[c * st + (size_t)q];
                for (int q = 0; q < 3; q++) x[r * st + (size_t)q] /= A[r * (size_t)w + (size_t)p];
            }
        }
    coons__free(A);
    return COONS_OK;
}

/* Interpolates T in the space whose knots n already holds. */
static coons_status interpolate(const target *T, coons_nurbs *n, coons_error *err)
{
    double *g[3] = {NULL, NULL, NULL};
    size_t np[3] = {1, 1, 1};
    coons_status rc = COONS_OK;
    size_t total = nurbs_size(n);
    if (total > COONS_NURBS_MAX_POINTS)
        return coons__error_set(err, COONS_E_LIMIT,
                                "nurbs: %zu control points, more than the limit of %d", total,
                                COONS_NURBS_MAX_POINTS);
    n->points = coons__malloc_array(3 * total, sizeof(double));
    if (!n->points) return coons__error_nomem(err);
    for (int d = 0; d < T->dim && !rc; d++) {
        np[d] = n->count[d];
        if (!(g[d] = coons__malloc_array(np[d], sizeof(double))))
            rc = coons__error_nomem(err);
        else
            greville(n, d, g[d]);
    }
    if (!rc) rc = target_grid(T, g, np, n->points, err);
    for (int d = 0; d < T->dim && !rc; d++) rc = collocate(n, d, g[d], err);
    for (int d = 0; d < 3; d++) coons__free(g[d]);
    return rc;
}

/* Check parameters of direction d: both ends, the midpoint and the two
 * Gauss points of every knot span (the Gauss points are never Greville
 * points, where an interpolant matches by construction). */
static coons_status check_params(const coons_nurbs *n, int d, double **out, size_t *m,
                                 coons_error *err)
{
    static const double G[3] = {0.21132486540518713, 0.5, 0.78867513459481287};
    size_t cnt = n->count[d];
    int p = n->degree[d];
    double *x = coons__malloc_array(3 * cnt + 2, sizeof *x);
    if (!x) return coons__error_nomem(err);
    size_t k = 0;
    x[k++] = 0.0;
    for (size_t i = (size_t)p; i < cnt; i++) {
        double a = n->knots[d][i], b = n->knots[d][i + 1];
        if (!(b > a)) continue;
        for (int q = 0; q < 3; q++) x[k++] = a + G[q] * (b - a);
    }
    x[k++] = 1.0;
    *out = x;
    *m = k;
    return COONS_OK;
}

/* n->deviation: the largest distance to T over the check grid, slab by
 * slab along the first direction. */
static coons_status measure(const target *T, coons_nurbs *n, coons_error *err)
{
    double *x[3] = {NULL, NULL, NULL}, *bas[3] = {NULL, NULL, NULL}, *val = NULL;
    size_t *first[3] = {NULL, NULL, NULL}, m[3] = {1, 1, 1};
    coons_status rc = COONS_OK;
    int w[3] = {1, 1, 1};
    for (int d = 0; d < T->dim && !rc; d++) {
        w[d] = n->degree[d] + 1;
        rc = check_params(n, d, &x[d], &m[d], err);
        if (rc) break;
        bas[d] = coons__malloc_array(m[d] * (size_t)w[d], sizeof(double));
        first[d] = coons__malloc_array(m[d], sizeof(size_t));
        if (!bas[d] || !first[d]) {
            rc = coons__error_nomem(err);
            break;
        }
        for (size_t i = 0; i < m[d]; i++)
            first[d][i] = basis_at(n, d, x[d][i], bas[d] + i * (size_t)w[d]);
    }
    size_t slab = m[1] * m[2];
    if (!rc && !(val = coons__malloc_array(3 * slab, sizeof *val))) rc = coons__error_nomem(err);
    double one = 1.0, dev = 0.0;
    size_t zero = 0;
    for (size_t i = 0; !rc && i < m[0]; i++) {
        double *par[3] = {x[0] + i, x[1], x[2]};
        size_t np[3] = {1, m[1], m[2]};
        if ((rc = target_grid(T, par, np, val, err))) break;
        for (size_t j = 0; j < m[1]; j++)
            for (size_t k = 0; k < m[2]; k++) {
                double *N[3] = {bas[0] + i * (size_t)w[0],
                                T->dim > 1 ? bas[1] + j * (size_t)w[1] : &one,
                                T->dim > 2 ? bas[2] + k * (size_t)w[2] : &one};
                size_t f[3] = {first[0][i], T->dim > 1 ? first[1][j] : zero,
                               T->dim > 2 ? first[2][k] : zero};
                double q[3];
                nurbs_point(n, f, N, q);
                double e = v3_dist(q, val + 3 * (j * m[2] + k));
                if (!(e <= dev)) dev = isnan(e) ? INFINITY : e;
            }
    }
    n->deviation = dev;
    coons__free(val);
    for (int d = 0; d < 3; d++) {
        coons__free(x[d]);
        coons__free(bas[d]);
        coons__free(first[d]);
    }
    return rc;
}

/* ---- exact copies of NURBS data ---------------------------------------- */

static coons_status copy_knots(coons_nurbs *n, int d, const double *k, size_t cnt, int p,
                               coons_error *err)
{
    size_t len = cnt + (size_t)p + 1;
    double *q = coons__malloc_array(len, sizeof *q);
    if (!q) return coons__error_nomem(err);
    double lo = k[p], span = k[cnt] - k[p];
    for (size_t i = 0; i < len; i++) q[i] = (k[i] - lo) / span;
    n->knots[d] = q;
    n->degree[d] = p;
    n->count[d] = cnt;
    return COONS_OK;
}

static coons_status copy_net(coons_nurbs *n, const double *pts, const double *w, coons_error *err)
{
    size_t total = nurbs_size(n);
    n->points = coons__memdup(pts, 3 * total, sizeof(double));
    n->weights = w ? coons__memdup(w, total, sizeof(double)) : NULL;
    if (!n->points || (w && !n->weights)) return coons__error_nomem(err);
    return COONS_OK;
}

static void map_points(coons_nurbs *n, const double *xf)
{
    size_t total = nurbs_size(n);
    for (size_t i = 0; i < total; i++) coons__affine_point(xf, n->points + 3 * i, n->points + 3 * i);
}

/* Reverses direction d: knots k -> 1 - k in reverse order, the net along d. */
static void flip(coons_nurbs *n, int d)
{
    size_t len = n->count[d] + (size_t)n->degree[d] + 1;
    double *k = n->knots[d];
    for (size_t i = 0, j = len - 1; i < j; i++, j--) {
        double t = k[i];
        k[i] = 1.0 - k[j];
        k[j] = 1.0 - t;
    }
    if (len % 2) k[len / 2] = 1.0 - k[len / 2];
    size_t stride = 1, lines = 1, cnt = n->count[d];
    for (int e = d + 1; e < 3; e++) stride *= n->count[e];
    for (int e = 0; e < d; e++) lines *= n->count[e];
    for (size_t L = 0; L < lines; L++)
        for (size_t o = 0; o < stride; o++)
            for (size_t i = 0, j = cnt - 1; i < j; i++, j--) {
                size_t a = (L * cnt + i) * stride + o, b = (L * cnt + j) * stride + o;
                for (int q = 0; q < 3; q++) {
                    double t = n->points[3 * a + (size_t)q];
                    n->points[3 * a + (size_t)q] = n->points[3 * b + (size_t)q];
                    n->points[3 * b + (size_t)q] = t;
                }
                if (n->weights) {
                    double t = n->weights[a];
                    n->weights[a] = n->weights[b];
                    n->weights[b] = t;
                }
            }
}

/* Exchanges the two directions of a surface. */
static coons_status transpose(coons_nurbs *n, coons_error *err)
{
    size_t a = n->count[0], b = n->count[1];
    double *P = coons__malloc_array(3 * a * b, sizeof *P);
    double *W = n->weights ? coons__malloc_array(a * b, sizeof *W) : NULL;
    if (!P || (n->weights && !W)) {
        coons__free(P);
        coons__free(W);
        return coons__error_nomem(err);
    }
    for (size_t i = 0; i < a; i++)
        for (size_t j = 0; j < b; j++) {
            v3_copy(P + 3 * (j * a + i), n->points + 3 * (i * b + j));
            if (W) W[j * a + i] = n->weights[i * b + j];
        }
    coons__free(n->points);
    coons__free(n->weights);
    n->points = P;
    n->weights = W;
    double *k = n->knots[0];
    n->knots[0] = n->knots[1];
    n->knots[1] = k;
    int p = n->degree[0];
    n->degree[0] = n->degree[1];
    n->degree[1] = p;
    n->count[0] = b;
    n->count[1] = a;
    return COONS_OK;
}

/* Whether the object is its own control net (a B-spline-backed type,
 * through affine images, reversals and reparametrisations): then its form
 * is a copy, exact and as well conditioned as the data (interpolation at
 * equally spaced Greville points loses digits in the control points of
 * high degrees, though not in the values). */
static int curve_is_net(const coons_curve *c)
{
    while (c->kind == &coons__curve_transformed_kind || c->kind == &coons__curve_reversed_kind)
        c = c->inner;
    return c->knots != NULL && c->pts != NULL && !c->inner;
}

static int patch_is_net(const coons_patch *p)
{
    while (p->kind == &coons__patch_transformed_kind || p->kind == &coons__patch_reparam_kind)
        p = p->inner;
    return p->kind == &coons__bspline_surface_kind || p->kind == &coons__bezier_surface_kind;
}

static int body_is_net(const coons_body *b)
{
    while (b->kind == &coons__body_transformed_kind) b = b->inner;
    return b->kind == &coons__bspline_volume_kind || b->kind == &coons__bezier_volume_kind;
}

static coons_status copy_curve(const coons_curve *c, coons_nurbs *n, coons_error *err)
{
    coons_status rc;
    if (c->kind == &coons__curve_transformed_kind || c->kind == &coons__curve_reversed_kind) {
        if ((rc = copy_curve(c->inner, n, err))) return rc;
        if (c->kind == &coons__curve_reversed_kind)
            flip(n, 0);
        else
            map_points(n, c->xf);
        return COONS_OK;
    }
    if (!c->knots)
        return coons__error_set(err, COONS_E_INTERNAL, "nurbs: a rational curve without knots");
    nurbs_empty(n, 1);
    if ((rc = copy_knots(n, 0, c->knots, c->n, c->degree, err))) return rc;
    return copy_net(n, c->pts, c->w, err);
}

static coons_status copy_patch(const coons_patch *p, coons_nurbs *n, coons_error *err)
{
    coons_status rc;
    if (p->kind == &coons__patch_transformed_kind) {
        if ((rc = copy_patch(p->inner, n, err))) return rc;
        map_points(n, p->xf);
        return COONS_OK;
    }
    if (p->kind == &coons__patch_reparam_kind) {
        /* y(s,t) = x(a,b): flip the inner directions, then swap. */
        if ((rc = copy_patch(p->inner, n, err))) return rc;
        if (p->flip_s) flip(n, 0);
        if (p->flip_t) flip(n, 1);
        return p->swap ? transpose(n, err) : COONS_OK;
    }
    nurbs_empty(n, 2);
    if (!p->ks) { /* Bezier: knots 0^(p+1) 1^(p+1) */
        for (int d = 0; d < 2; d++) {
            int deg = d ? p->pt : p->ps;
            double *k = coons__malloc_array(2 * (size_t)deg + 2, sizeof *k);
            if (!k) return coons__error_nomem(err);
            for (int i = 0; i <= deg; i++) {
                k[i] = 0.0;
                k[deg + 1 + i] = 1.0;
            }
            n->knots[d] = k;
            n->degree[d] = deg;
            n->count[d] = (size_t)deg + 1;
        }
    } else if ((rc = copy_knots(n, 0, p->ks, p->ns, p->ps, err)) ||
               (rc = copy_knots(n, 1, p->kt, p->nt, p->pt, err)))
        return rc;
    return copy_net(n, p->pts, p->w, err);
}

static coons_status copy_body(const coons_body *b, coons_nurbs *n, coons_error *err)
{
    coons_status rc;
    if (b->kind == &coons__body_transformed_kind) {
        if ((rc = copy_body(b->inner, n, err))) return rc;
        map_points(n, b->xf);
        return COONS_OK;
    }
    if (!b->pts || !b->knots[0] || !b->knots[1] || !b->knots[2])
        return coons__error_set(err, COONS_E_INTERNAL, "nurbs: a rational body without a net");
    nurbs_empty(n, 3);
    for (int d = 0; d < 3; d++)
        if ((rc = copy_knots(n, d, b->knots[d], b->n[d], b->deg[d], err))) return rc;
    return copy_net(n, b->pts, b->w, err);
}

/* The face f of a volume form: the homogeneous section at u, v or w = 0/1,
 * sum_i N_i(x) (w P, w)_i along the fixed direction. */
static coons_status section(const coons_nurbs *V, int f, coons_nurbs *n, coons_error *err)
{
    int dd = f / 2, a = dd == 0 ? 1 : 0, b = dd == 2 ? 1 : 2;
    double N[COONS_SPLINE_MAX_DEGREE + 1];
    size_t first = basis_at(V, dd, (double)(f % 2), N);
    nurbs_empty(n, 2);
    int ax[2] = {a, b};
    for (int m = 0; m < 2; m++) {
        size_t len = V->count[ax[m]] + (size_t)V->degree[ax[m]] + 1;
        if (!(n->knots[m] = coons__memdup(V->knots[ax[m]], len, sizeof(double))))
            return coons__error_nomem(err);
        n->degree[m] = V->degree[ax[m]];
        n->count[m] = V->count[ax[m]];
    }
    size_t total = nurbs_size(n);
    n->points = coons__calloc(3 * total, sizeof(double));
    n->weights = V->weights ? coons__calloc(total, sizeof(double)) : NULL;
    if (!n->points || (V->weights && !n->weights)) return coons__error_nomem(err);
    for (size_t i = 0; i < n->count[0]; i++)
        for (size_t j = 0; j < n->count[1]; j++) {
            double A[4] = {0, 0, 0, 0};
            for (int r = 0; r <= V->degree[dd]; r++) {
                size_t idx[3];
                idx[dd] = first + (size_t)r;
                idx[a] = i;
                idx[b] = j;
                size_t q = (idx[0] * V->count[1] + idx[1]) * V->count[2] + idx[2];
                double wn = N[r] * (V->weights ? V->weights[q] : 1.0);
                for (int k = 0; k < 3; k++) A[k] += wn * V->points[3 * q + (size_t)k];
                A[3] += wn;
            }
            size_t o = i * n->count[1] + j;
            for (int k = 0; k < 3; k++) n->points[3 * o + (size_t)k] = A[k] / A[3];
            if (n->weights) n->weights[o] = A[3];
        }
    return COONS_OK;
}

/* ---- the form of a target ---------------------------------------------- */

/* The form of T in given spaces (fit: sub simple knots per interval in
 * the NONE directions), interpolated and measured. */
static coons_status in_space(const target *T, const coons__space S[3], const coons__breaks B[3],
                             size_t sub, int drop_breaks, coons_nurbs *n, coons_error *err)
{
    nurbs_empty(n, T->dim);
    for (int d = 0; d < T->dim; d++) {
        int p = S[d].degree, fit = S[d].kind != COONS__SPACE_POLY;
        int c = S[d].cont < p ? S[d].cont : p - 1;
        if (fit) c = 0;
        coons_status rc = make_knots(n, d, p, p - c, B[d].v, drop_breaks ? 0 : B[d].n,
                                     fit ? sub : 1, err);
        if (rc) return rc;
    }
    coons_status rc = interpolate(T, n, err);
    return rc ? rc : measure(T, n, err);
}

static coons_status check_tol(double tol, coons_error *err)
{
    if (!(tol > 0.0) || !isfinite(tol))
        return coons__error_set(err, COONS_E_INVALID,
                                "nurbs: no exact form: a fit needs a tolerance > 0, got %g", tol);
    return COONS_OK;
}

/* The diagonal of the control net's box. */
static double net_size(const coons_nurbs *n)
{
    double lo[3], hi[3];
    bbox_empty(lo, hi);
    for (size_t i = 0, m = nurbs_size(n); i < m; i++) bbox_add(lo, hi, n->points + 3 * i);
    return v3_dist(lo, hi);
}

/* An exact form whose measured deviation is more than rounding is not
 * claimed exact (a breakpoint the data did not report would show so).
 * The scale is the largest of the net's and the object's control box and
 * the coordinates' magnitude (a collapsed face has a box of size 0; the
 * rounding of a point scales with its coordinates). */
static int confirmed(const target *T, const coons_nurbs *n)
{
    double lo[3], hi[3];
    if (T->c)
        coons_curve_control_bbox(T->c, lo, hi);
    else if (T->p)
        coons_patch_control_bbox(T->p, lo, hi);
    else
        coons_body_control_bbox(T->b, lo, hi);
    double size = v3_dist(lo, hi), ns = net_size(n);
    if (!(size >= ns)) size = ns;
    for (int k = 0; k < 3; k++) {
        if (fabs(lo[k]) > size) size = fabs(lo[k]);
        if (fabs(hi[k]) > size) size = fabs(hi[k]);
    }
    return n->deviation <= 1e-10 * size;
}

static coons_status to_nurbs(const target *T, double tol, coons_nurbs *out, coons_error *err)
{
    coons__space S[3] = {{0}};
    coons__breaks B[3] = {{0}};
    coons_status rc = COONS_OK;
    int all_poly = 1, all_nurbs = 1;
    for (int d = 0; d < T->dim; d++) {
        S[d] = target_space(T, d);
        if (S[d].degree > COONS_SPLINE_MAX_DEGREE)
            return coons__error_set(err, COONS_E_LIMIT, "nurbs: degree %d above the limit %d",
                                    S[d].degree, COONS_SPLINE_MAX_DEGREE);
        all_poly &= S[d].kind == COONS__SPACE_POLY;
        all_nurbs &= S[d].kind == COONS__SPACE_NURBS;
    }
    int is_net = T->c ? curve_is_net(T->c) : T->p ? patch_is_net(T->p) : body_is_net(T->b);
    if (all_nurbs || (all_poly && is_net)) {
        out->exact = 1;
        if (T->c)
            rc = copy_curve(T->c, out, err);
        else if (T->p)
            rc = copy_patch(T->p, out, err);
        else if (T->face < 0)
            rc = copy_body(T->b, out, err);
        else {
            coons_nurbs V = {0};
            rc = copy_body(T->b, &V, err);
            if (!rc) rc = section(&V, T->face, out, err);
            coons_nurbs_free(&V);
        }
        if (!rc) rc = measure(T, out, err);
        if (!rc) out->exact = confirmed(T, out);
        return rc;
    }
    /* Body 2's faces are its face patches (Coons interpolation). */
    if (!all_poly && T->face >= 0 && T->b->kind == &coons__body2_kind) {
        rc = coons_patch_to_nurbs(T->b->face[T->face], tol, out, err);
        int exact = out->exact;
        if (!rc) rc = measure(T, out, err);
        out->exact = exact && !rc && confirmed(T, out);
        return rc;
    }
    if (!all_poly && (rc = check_tol(tol, err))) return rc;
    for (int d = 0; d < T->dim && !rc; d++) rc = target_breaks(T, d, &B[d], err);
    for (int d = 0; d < T->dim && !rc; d++)
        if (B[d].n >= COONS_NURBS_MAX_POINTS)
            rc = coons__error_set(err, COONS_E_LIMIT, "nurbs: %zu breakpoints in direction %d",
                                  B[d].n, d);
    int refit = 0;
    if (!rc && all_poly) {
        rc = in_space(T, S, B, 1, 0, out, err);
        out->exact = !rc && confirmed(T, out);
        if (!rc && !out->exact && !(out->deviation <= tol) && tol > 0.0 && isfinite(tol)) {
            refit = 1;
            for (int d = 0; d < T->dim; d++) {
                S[d].kind = COONS__SPACE_NONE;
                if (S[d].degree < 3) S[d].degree = 3;
            }
        }
    }
    if (!rc && (!all_poly || refit)) {
        for (int d = 0; d < T->dim; d++)
            if (S[d].kind != COONS__SPACE_POLY && !refit) S[d].degree = 3;
        double last = INFINITY;
        for (size_t sub = 4;; sub *= 2) {
            coons_nurbs_free(out);
            rc = in_space(T, S, B, sub, 0, out, err);
            if (rc == COONS_E_LIMIT && isfinite(last))
                rc = coons__error_set(err, COONS_E_LIMIT,
                                      "nurbs: the fit reached a deviation of %.3g, not %.3g, "
                                      "within %d control points",
                                      last, tol, COONS_NURBS_MAX_POINTS);
            if (rc || out->deviation <= tol) break;
            last = out->deviation;
        }
        out->exact = 0;
    }
    for (int d = 0; d < 3; d++) coons__free(B[d].v);
    return rc;
}

static coons_status start(const void *obj, const char *what, coons_nurbs *out, coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "%s to nurbs: out is NULL", what);
    memset(out, 0, sizeof *out);
    if (!obj) return coons__error_set(err, COONS_E_INVALID, "%s to nurbs: %s is NULL", what, what);
    return COONS_OK;
}

static coons_status finish(coons_status rc, coons_nurbs *out)
{
    if (rc) coons_nurbs_free(out);
    return rc;
}

coons_status coons_curve_to_nurbs(const coons_curve *c, double tol, coons_nurbs *out,
                                  coons_error *err)
{
    coons_status rc = start(c, "curve", out, err);
    if (rc) return rc;
    target T = curve_target(c);
    return finish(to_nurbs(&T, tol, out, err), out);
}

coons_status coons_patch_to_nurbs(const coons_patch *p, double tol, coons_nurbs *out,
                                  coons_error *err)
{
    coons_status rc = start(p, "patch", out, err);
    if (rc) return rc;
    target T = patch_target(p);
    return finish(to_nurbs(&T, tol, out, err), out);
}

coons_status coons_body_face_to_nurbs(const coons_body *b, int face, double tol,
                                      coons_nurbs *out, coons_error *err)
{
    coons_status rc = start(b, "body face", out, err);
    if (rc) return rc;
    if (face < 0 || face > 5)
        return coons__error_set(err, COONS_E_INVALID, "body face to nurbs: face %d is not 0..5",
                                face);
    target T = face_target(b, face);
    return finish(to_nurbs(&T, tol, out, err), out);
}

coons_status coons_body_to_nurbs(const coons_body *b, double tol, coons_nurbs *out,
                                 coons_error *err)
{
    coons_status rc = start(b, "body", out, err);
    if (rc) return rc;
    target T = body_target(b);
    return finish(to_nurbs(&T, tol, out, err), out);
}

coons_status coons__nurbs_in_space(const coons_curve *c, const coons_patch *p,
                                   const coons_body *b, int degree, int drop_breaks,
                                   coons_nurbs *out, coons_error *err)
{
    coons_status rc = start(c ? (const void *)c : p ? (const void *)p : (const void *)b, "object",
                            out, err);
    if (rc) return rc;
    target T = c ? curve_target(c) : p ? patch_target(p) : body_target(b);
    coons__space S[3] = {{0}};
    coons__breaks B[3] = {{0}};
    for (int d = 0; d < T.dim && !rc; d++) {
        S[d] = coons__space_poly(degree);
        S[d].cont = 0;
        rc = target_breaks(&T, d, &B[d], err);
    }
    if (!rc) rc = in_space(&T, S, B, 1, drop_breaks, out, err);
    for (int d = 0; d < 3; d++) coons__free(B[d].v);
    return finish(rc, out);
}
