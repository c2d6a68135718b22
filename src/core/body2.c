/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Coons body 2 (seed 000 section 2.4) from the six faces X_i(v,w),
 * Y_j(u,w), Z_k(u,v):
 *   C2 = D - C1 - T,   D = sum_i a_i(u) X_i + sum_j a_j(v) Y_j + sum_k a_k(w) Z_k,
 * with C1, T of the faces' common boundary curves (seed 000's compatibility
 * equations). Each edge point is the average of the two faces carrying it,
 * each corner the average of the three (model format, "Consistency").
 * Since C1 = E - 2T (E the three bilinear edge blends), C2 = D - E + T: the
 * form used here, which also saves the work of the -2T/+T pair.
 * Edge e, parameter x, and the (s,t) where its two faces carry it:
 *   uJK (e = 2J+K):    Y_J(s=x, t=K)   and Z_K(s=x, t=J)
 *   vIK (e = 4+2I+K):  X_I(s=x, t=K)   and Z_K(s=I, t=x)
 *   wIJ (e = 8+2I+J):  X_I(s=J, t=x)   and Y_J(s=I, t=x)
 */
#include <stdio.h>
#include <string.h>

#include "agree.h"
#include "bspline.h"
#include "body_impl.h"
#include "patch_impl.h"

/* Source m (0, 1) of edge e: face index, which patch parameter runs with
 * the edge (0 = s, 1 = t), and the fixed value of the other. */
static void edge_source(int e, int m, int *face, int *run, int *fixed)
{
    coons__agree_edge_source(e, m, face, run, fixed);
}

static void source_at(const coons_patch *p, int run, int fixed, double x, double out[3],
                      double *dx)
{
    double s = run == 0 ? x : fixed, t = run == 0 ? fixed : x, r[3][3];
    coons_patch_eval_derivs(p, s, t, dx ? 1 : 0, r);
    v3_copy(out, r[0]);
    if (dx) v3_copy(dx, r[1 + run]);
}

static coons_status fast_build(coons_body *b, coons_error *err);

coons_status coons_body_new_body2(coons_patch *const *faces_in, coons_blend blend, double tol,
                                  coons_body **out, coons_error *err)
{
    /* The public idiom (coons/types.h, "Arrays") passes handles as X *const *;
     * the code here only reads them. */
    const coons_patch *const *faces = (const coons_patch *const *)faces_in;
    *out = NULL;
    if (!faces) return coons__error_set(err, COONS_E_INVALID, "body2: faces are NULL");
    if (blend != COONS_BLEND_LINEAR && blend != COONS_BLEND_CUBIC)
        return coons__error_set(err, COONS_E_INVALID, "body2: unknown blend %d", (int)blend);
    if (!(tol >= 0.0) || !isfinite(tol))
        return coons__error_set(err, COONS_E_INVALID, "body2: tolerance %g is not >= 0", tol);
    double lo[3], hi[3];
    bbox_empty(lo, hi);
    for (int f = 0; f < 6; f++) {
        if (!faces[f])
            return coons__error_set(err, COONS_E_INVALID, "body2: face %s is NULL",
                                    coons__body_face_name(f));
        double a[3], c[3];
        coons_patch_control_bbox(faces[f], a, c);
        bbox_add(lo, hi, a);
        bbox_add(lo, hi, c);
    }
    double eps = coons__tolerance(tol, bbox_diag(lo, hi));
    /* Parametric agreement along each shared edge (agree.h). */
    static const char *const fixed_names[3][2] = {{"v", "w"}, {"u", "w"}, {"u", "v"}};
    coons__agree ag;
    if (coons__agree_body2_edges(faces, eps, &ag)) {
        int e = ag.at, dir = e / 4;
        return coons__error_set(
            err, COONS_E_INCOMPATIBLE,
            "body2: edge %s (%s=%d,%s=%d): faces %s and %s differ by %.6g at %c=%.6g "
            "(tolerance %.3g)",
            coons__body_edge_name(e), fixed_names[dir][0], (e >> 1) & 1, fixed_names[dir][1],
            e & 1, coons__body_face_name(ag.a), coons__body_face_name(ag.b), ag.dist, "uvw"[dir],
            ag.ta, eps);
    }
    coons_body *b;
    coons_status rc = coons__body_alloc(&coons__body2_kind, blend, &b, err);
    if (rc) return rc;
    for (int f = 0; f < 6; f++) {
        if ((rc = coons_patch_copy(faces[f], &b->face[f], err))) {
            coons_body_free(b);
            return rc;
        }
    }
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) {
                double x[3], y[3], z[3];
                coons_patch_eval(faces[i], j, k, x);
                coons_patch_eval(faces[2 + j], i, k, y);
                coons_patch_eval(faces[4 + k], i, j, z);
                double *c = b->corner[4 * i + 2 * j + k];
                for (int r = 0; r < 3; r++) c[r] = (x[r] + y[r] + z[r]) / 3.0;
            }
    if ((rc = fast_build(b, err))) {
        coons_body_free(b);
        return rc;
    }
    v3_copy(b->lo, lo);
    v3_copy(b->hi, hi);
    *out = b;
    return COONS_OK;
}

/* Edge point: the average of its two faces. */
static void edge_at(const coons_body *b, int e, double x, double p[3], double *dp)
{
    double pa[3], pb[3], da[3], db[3];
    for (int m = 0; m < 2; m++) {
        int f, run, fixed;
        edge_source(e, m, &f, &run, &fixed);
        source_at(b->face[f], run, fixed, x, m ? pb : pa, dp ? (m ? db : da) : NULL);
    }
    for (int r = 0; r < 3; r++) p[r] = 0.5 * (pa[r] + pb[r]);
    if (dp)
        for (int r = 0; r < 3; r++) dp[r] = 0.5 * (da[r] + db[r]);
}

/*
 * The point, grouped as the grid groups it (grid2_regroup and w_line below,
 * the same IEEE operations in the same order), so that a grid point differs
 * from the point evaluated alone only as far as the faces' own grid values
 * differ from their point values (a few ulp; C2 = D - E + T summed term by
 * term, as the derivatives below are, differed by up to 17 ulp of the
 * body's size).
 */
static void point_from(const coons_body *b, const double bu[5], const double bv[5],
                       const double bw[5], double X[2][3], double Y[2][3], double Z[2][3],
                       double E[12][3], double out[3])
{
    const double a0 = bu[0], a1 = bu[1], b0 = bv[0], b1 = bv[1], w1 = bw[1];
    const double(*c)[3] = b->corner;
    double(*Cu)[3] = E, (*Cv)[3] = E + 4, (*Cw)[3] = E + 8;
    for (int r = 0; r < 3; r++) {
        double G[2], P[2];
        for (int j = 0; j < 2; j++) G[j] = Y[j][r] - (a0 * Cw[j][r] + a1 * Cw[2 + j][r]);
        for (int k = 0; k < 2; k++) {
            double tk = a0 * c[k][r] + a1 * c[4 + k][r];
            double t2k = a0 * c[2 + k][r] + a1 * c[6 + k][r];
            P[k] = Z[k][r] - (a0 * Cv[k][r] + a1 * Cv[2 + k][r] + b0 * (Cu[k][r] - tk) +
                              b1 * (Cu[2 + k][r] - t2k));
        }
        out[r] = (X[0][r] + a1 * (X[1][r] - X[0][r])) + (G[0] + b1 * (G[1] - G[0])) +
                 (P[0] + w1 * (P[1] - P[0]));
    }
}

/* The partials term by term: dC2 = dD - dE + dT, from the faces' values
 * and partials (Xd[x][q]: q = 0 value, 1 d/ds, 2 d/dt) and the edges with
 * their derivatives. */
static void partials(const coons_body *b, const double bu[5], const double bv[5],
                     const double bw[5], double Xd[2][3][3], double Yd[2][3][3],
                     double Zd[2][3][3], double E[12][3], double dE[12][3],
                     double d[3][3])
{
    double tmp[3];
    coons__trilinear(b->corner, bu, bv, bw, tmp, d);
    for (int x = 0; x < 2; x++) {
        v3_axpy(d[0], bu[2 + x], Xd[x][0]);
        v3_axpy(d[0], bv[x], Yd[x][1]);
        v3_axpy(d[0], bw[x], Zd[x][1]);
        v3_axpy(d[1], bu[x], Xd[x][1]);
        v3_axpy(d[1], bv[2 + x], Yd[x][0]);
        v3_axpy(d[1], bw[x], Zd[x][2]);
        v3_axpy(d[2], bu[x], Xd[x][2]);
        v3_axpy(d[2], bv[x], Yd[x][2]);
        v3_axpy(d[2], bw[2 + x], Zd[x][0]);
    }
    coons__edge_sum_tab(E, dE, -1.0, bu, bv, bw, tmp, d);
}

static void eval(const coons_body *b, double u, double v, double w, double out[3],
                 double d[3][3]);

/* The general path: every face through its row. */
static void eval_rows(const coons_body *b, double u, double v, double w, double out[3],
                      double d[3][3])
{
    double bu[5], bv[5], bw[5], X[2][3], Y[2][3], Z[2][3], E[12][3], dE[12][3];
    coons__blends_at(b->blend, u, v, w, bu, bv, bw);
    for (int e = 0; e < 12; e++) {
        const double *q = e < 4 ? bu : e < 8 ? bv : bw;
        edge_at(b, e, q[4], E[e], d ? dE[e] : NULL);
    }
    if (!d) {
        for (int x = 0; x < 2; x++) {
            coons_patch_eval(b->face[x], v, w, X[x]);
            coons_patch_eval(b->face[2 + x], u, w, Y[x]);
            coons_patch_eval(b->face[4 + x], u, v, Z[x]);
        }
        point_from(b, bu, bv, bw, X, Y, Z, E, out);
        return;
    }
    double Xd[2][3][3], Yd[2][3][3], Zd[2][3][3];
    for (int x = 0; x < 2; x++) {
        coons_patch_eval_derivs(b->face[x], v, w, 1, Xd[x]);
        coons_patch_eval_derivs(b->face[2 + x], u, w, 1, Yd[x]);
        coons_patch_eval_derivs(b->face[4 + x], u, v, 1, Zd[x]);
        v3_copy(X[x], Xd[x][0]);
        v3_copy(Y[x], Yd[x][0]);
        v3_copy(Z[x], Zd[x][0]);
    }
    partials(b, bu, bv, bw, Xd, Yd, Zd, E, dE, d);
    point_from(b, bu, bv, bw, X, Y, Z, E, out);
}

/*
 * The fast path of a body whose six faces are tensor-product surfaces of
 * degree <= FAST_DEG (bezier-surface, bspline-surface): per point each
 * face's two bases are computed once and serve the face and the edges it
 * carries (an edge runs along one of its faces' parameters at the same
 * value as the face: the body's u, v or w); the bases at the faces' ends
 * and each face's net combined at s = 0 and s = 1 (the edges along t) are
 * kept with the body. The same sums as coons_patch_eval_derivs() (kinds.h),
 * so the points are bitwise those of the general path.
 */
#define FAST_DEG 15
#define FAST_NB (2 * (FAST_DEG + 1))

typedef struct fast_face {
    const coons_patch *p;
    int same[2][2];              /* [dir]: face and dir whose basis at the point is this one's */
    size_t first[2][2];          /* [dir][end]: first control index at s or t = end */
    double *N[2][2];             /* [dir][end]: the basis there, value and derivative rows */
    double *srow[2];             /* the net combined at s = 0, 1 (coons__tensor_srow) */
    double *tcol[2];             /* t = 0, 1: the net's column there where the basis picks
                                  * one (coons__tensor_tcol), else NULL */
    double pmax;                 /* the largest homogeneous coordinate's size */
} fast_face;

/* The batch of points (spec_points below), where every face has the same
 * dim (3: polynomial, 4: homogeneous) and every edge source a kept row or
 * column (spec_build): per edge source, the kept array and its basis. */
typedef struct spec_src {
    const double *arr; /* the kept column (run along s) or row (along t), 4 per index */
    int slot;          /* the basis it is summed with (roots below) */
    int addzero;       /* a column: eval_tcol's +0 */
} spec_src;

struct coons__body2_fast {
    fast_face f[6];
    int src[12][2][3]; /* edge_source of edge e, source m: face, run, fixed */
    double *mem;
    int spec_dim;           /* 0: no batch path */
    int spec_deg;           /* every face's degrees (2 or 3), else 0 */
    int nroot;              /* the distinct bases of a point (same[][] roots) */
    const coons_patch *root_p[12];
    int root_dir[12], root_par[12], root_deg[12];
    int fslot[6][2];        /* face f's basis along dir: its root's slot */
    spec_src esrc[12][2];
    double corner4[8][4];   /* the corners, lane 3 zero */
};

/* The (s,t) of face f: X_i (v,w), Y_j (u,w), Z_k (u,v); 0 = u, 1 = v, 2 = w. */
static const int face_par[6][2] = {{1, 2}, {1, 2}, {0, 2}, {0, 2}, {0, 1}, {0, 1}};

static void fast_free(coons_body *b)
{
    if (!b->fast) return;
    coons__free(b->fast->mem);
    coons__free(b->fast);
    b->fast = NULL;
}

/* Whether p along dp and q along dq have the same basis: both Bezier or
 * both B-spline, the same degree and control count, the same knots bit
 * for bit (then the same parameter gives the same basis). */
static int same_basis(const coons_patch *p, int dp, const coons_patch *q, int dq)
{
    int pd = dp ? p->pt : p->ps, qd = dq ? q->pt : q->ps;
    size_t pn = dp ? p->nt : p->ns, qn = dq ? q->nt : q->ns;
    const double *pk = dp ? p->kt : p->ks, *qk = dq ? q->kt : q->ks;
    if (p->kind != q->kind || pd != qd || pn != qn || !pk != !qk) return 0;
    return !pk || !memcmp(pk, qk, (pn + (size_t)pd + 1) * sizeof(double));
}

/* The largest size of the net's homogeneous coordinates. */
static double net_max(const coons_patch *p)
{
    const int dim = p->pw ? 4 : 3;
    const double *P = p->pw ? p->pw : p->pts;
    double m = 0.0;
    for (size_t i = 0; i < p->ns * p->nt * (size_t)dim; i++) m = fmax(m, fabs(P[i]));
    return m;
}

/* The index j of a t-basis N (values, pt + 1 of them) that is 1.0 at j
 * and 0 elsewhere (a clamped end), provided the net's homogeneous
 * coordinates are at most 1e300 in size (so that every sum of at most 16
 * of them times basis values in [0,1] is finite, and eval's terms of the
 * zeros add +-0); else pt + 1. */
static size_t pick_column(const coons_patch *p, const double *N)
{
    size_t j = (size_t)p->pt + 1, ones = 0;
    for (int k = 0; k <= p->pt; k++) {
        if (N[k] == 1.0)
            j = (size_t)k, ones++;
        else if (N[k] != 0.0)
            return (size_t)p->pt + 1;
    }
    if (ones != 1 || !(net_max(p) <= 1e300)) return (size_t)p->pt + 1;
    return j;
}

/* The batch path's tables, where it applies (spec_dim 0 otherwise). */
static void spec_build(const coons_body *b, struct coons__body2_fast *F)
{
    F->spec_dim = F->spec_deg = 0;
    const int dim = F->f[0].p->pw ? 4 : 3;
    /* one degree 2 or 3 throughout (unrolled), else the degrees at run time */
    int deg = F->f[0].p->ps;
    for (int f = 0; f < 6; f++) {
        const coons_patch *p = F->f[f].p;
        if ((p->pw ? 4 : 3) != dim) return;
        /* Bezier faces have no knots along either parameter (basis()) */
        if (!p->ks != !p->kt) return;
        if (p->ps != deg || p->pt != deg) deg = 0;
    }
    if (deg != 2 && deg != 3) deg = 0;
    int slot[6][2] = {{0}};
    F->nroot = 0;
    for (int f = 0; f < 6; f++)
        for (int dir = 0; dir < 2; dir++) {
            const int *same = F->f[f].same[dir];
            if (same[0] == f && same[1] == dir) {
                int r = F->nroot++;
                F->root_p[r] = F->f[f].p;
                F->root_dir[r] = dir;
                F->root_deg[r] = dir ? F->f[f].p->pt : F->f[f].p->ps;
                F->root_par[r] = face_par[f][dir];
                slot[f][dir] = r;
            } else {
                slot[f][dir] = slot[same[0]][same[1]];
            }
            F->fslot[f][dir] = slot[f][dir];
        }
    for (int e = 0; e < 12; e++)
        for (int m = 0; m < 2; m++) {
            const int f = F->src[e][m][0], run = F->src[e][m][1], fixed = F->src[e][m][2];
            const fast_face *ff = &F->f[f];
            spec_src *S = &F->esrc[e][m];
            if (run == 0 && !ff->tcol[fixed]) return;
            S->arr = run == 0 ? ff->tcol[fixed] : ff->srow[fixed];
            S->slot = slot[f][run];
            S->addzero = run == 0;
        }
    for (int c = 0; c < 8; c++) {
        for (int r = 0; r < 3; r++) F->corner4[c][r] = b->corner[c][r];
        F->corner4[c][3] = 0.0;
    }
    F->spec_dim = dim;
    F->spec_deg = deg;
}

static coons_status fast_build(coons_body *b, coons_error *err)
{
    b->fast = NULL;
    size_t total = 0;
    for (int f = 0; f < 6; f++) {
        const coons_patch *p = b->face[f];
        if (!coons__patch_is_tensor(p) || p->ps > FAST_DEG || p->pt > FAST_DEG) return COONS_OK;
        /* rows at the ends and end bases; net sizes are bounded
         * (COONS_PATCH_MAX_POINTS), degrees here by FAST_DEG */
        total += 8 * (p->nt + p->ns) + 4 * (size_t)(p->ps + 1) + 4 * (size_t)(p->pt + 1);
    }
    /* every edge runs with its faces' parameter (agree.h) */
    for (int e = 0; e < 12; e++)
        for (int m = 0; m < 2; m++) {
            int f, run, fixed;
            edge_source(e, m, &f, &run, &fixed);
            if (face_par[f][run] != e / 4) return COONS_OK;
        }
    struct coons__body2_fast *F = coons__calloc(1, sizeof *F);
    if (!F) return coons__error_nomem(err);
    F->mem = coons__malloc_array(total, sizeof(double));
    if (!F->mem) {
        coons__free(F);
        return coons__error_nomem(err);
    }
    memset(F->mem, 0, total * sizeof(double)); /* lane 3 of the dim-3 rows */
    double *m = F->mem;
    for (int e = 0; e < 12; e++)
        for (int k = 0; k < 2; k++)
            edge_source(e, k, &F->src[e][k][0], &F->src[e][k][1], &F->src[e][k][2]);
    for (int f = 0; f < 6; f++) {
        fast_face *ff = &F->f[f];
        ff->p = b->face[f];
        ff->pmax = net_max(ff->p);
        for (int dir = 0; dir < 2; dir++) {
            ff->same[dir][0] = f, ff->same[dir][1] = dir;
            for (int g = 0; g < f; g++)
                for (int dg = 0; dg < 2; dg++)
                    if (F->f[g].same[dg][0] == g && F->f[g].same[dg][1] == dg &&
                        face_par[g][dg] == face_par[f][dir] &&
                        same_basis(b->face[g], dg, b->face[f], dir))
                        ff->same[dir][0] = g, ff->same[dir][1] = dg;
        }
        for (int dir = 0; dir < 2; dir++)
            for (int end = 0; end < 2; end++) {
                ff->N[dir][end] = m;
                m += 2 * (size_t)((dir ? ff->p->pt : ff->p->ps) + 1);
                ff->first[dir][end] =
                    coons__tensor_basis(ff->p, dir, (double)end, 1, ff->N[dir][end]);
            }
        for (int end = 0; end < 2; end++) {
            ff->srow[end] = m;
            m += 4 * ff->p->nt;
            coons__tensor_srow(ff->p, ff->first[0][end], ff->N[0][end], ff->srow[end]);
            size_t j = pick_column(ff->p, ff->N[1][end]);
            if (j <= (size_t)ff->p->pt) {
                ff->tcol[end] = m;
                m += 4 * ff->p->ns;
                coons__tensor_tcol(ff->p, ff->first[1][end] + j, ff->tcol[end]);
            }
        }
    }
    spec_build(b, F);
    b->fast = F;
    return COONS_OK;
}

static void eval_fast(const coons_body *b, double u, double v, double w, double out[3],
                      double d[3][3])
{
    const struct coons__body2_fast *F = b->fast;
    const int order = d ? 1 : 0;
    const double x[3] = {u, v, w};
    double bu[5], bv[5], bw[5], E[12][3], dE[12][3];
    size_t first[6][2] = {{0}};
    double Nb[6][2][FAST_NB];
    const double *N[6][2] = {{NULL}};
    coons__blends_at(b->blend, u, v, w, bu, bv, bw);
    for (int f = 0; f < 6; f++)
        for (int dir = 0; dir < 2; dir++) {
            const int *same = F->f[f].same[dir];
            if (same[0] == f && same[1] == dir) {
                first[f][dir] = coons__tensor_basis(F->f[f].p, dir, x[face_par[f][dir]], order,
                                                    Nb[f][dir]);
                N[f][dir] = Nb[f][dir];
            } else {
                first[f][dir] = first[same[0]][same[1]];
                N[f][dir] = N[same[0]][same[1]];
            }
        }
    /* On the Jacobian path the column shortcut also needs eval's s-derivative
     * terms finite: |sum_k N'_k P_k| <= sum_k |N'_k| max |P| <= 1e300. */
    int tcol_ok[6];
    for (int f = 0; f < 6; f++) {
        tcol_ok[f] = 1;
        if (d) {
            const int ps = F->f[f].p->ps;
            double S = 0.0;
            for (int k = 0; k <= ps; k++) S += fabs(N[f][0][ps + 1 + k]);
            tcol_ok[f] = S * F->f[f].pmax <= 1e300;
        }
    }
    for (int e = 0; e < 12; e++) {
        double pv[2][3], pd[2][3];
        for (int m = 0; m < 2; m++) {
            const int f = F->src[e][m][0], run = F->src[e][m][1], fixed = F->src[e][m][2];
            const fast_face *ff = &F->f[f];
            if (run == 0 && ff->tcol[fixed] && tcol_ok[f]) {
                coons__tensor_eval_tcol(ff->p, ff->tcol[fixed], first[f][0], N[f][0], order,
                                        pv[m], pd[m]);
            } else if (run == 0) {
                double r[3][3];
                coons__tensor_eval_basis(ff->p, first[f][0], N[f][0], ff->first[1][fixed],
                                         ff->N[1][fixed], order, r);
                v3_copy(pv[m], r[0]);
                if (d) v3_copy(pd[m], r[1]);
            } else {
                coons__tensor_eval_srow(ff->p, ff->srow[fixed], first[f][1], N[f][1], order,
                                        pv[m], pd[m]);
            }
        }
        for (int r = 0; r < 3; r++) E[e][r] = 0.5 * (pv[0][r] + pv[1][r]);
        if (d)
            for (int r = 0; r < 3; r++) dE[e][r] = 0.5 * (pd[0][r] + pd[1][r]);
    }
    double Fd[6][3][3], X[2][3], Y[2][3], Z[2][3];
    for (int f = 0; f < 6; f++)
        coons__tensor_eval_basis(F->f[f].p, first[f][0], N[f][0], first[f][1], N[f][1], order,
                                 Fd[f]);
    for (int k = 0; k < 2; k++) {
        v3_copy(X[k], Fd[k][0]);
        v3_copy(Y[k], Fd[2 + k][0]);
        v3_copy(Z[k], Fd[4 + k][0]);
    }
    if (d) partials(b, bu, bv, bw, Fd, Fd + 2, Fd + 4, E, dE, d);
    point_from(b, bu, bv, bw, X, Y, Z, E, out);
}

static void points(const coons_body *b, size_t n, const double *uvw, double *xyz, double *jac,
                   double *det);

static void eval(const coons_body *b, double u, double v, double w, double out[3],
                 double d[3][3])
{
    if (b->fast && !d && b->fast->spec_dim) {
        /* the batch path for one point (clamping again changes nothing) */
        const double q[3] = {u, v, w};
        points(b, 1, q, out, NULL, NULL);
    } else if (b->fast) {
        eval_fast(b, u, v, w, out, d);
    } else {
        eval_rows(b, u, v, w, out, d);
    }
}

#if defined(__GNUC__)
/*
 * The batch of points on the value path (coons_body_eval_points without
 * Jacobians) of a body whose tables spec_build made: eval_fast's sums
 * written out for a constant dim (and a constant degree where every face
 * is of degrees 2, 2 or 3, 3), with no call per point, and
 * the coordinates of each sum (x, y, z and the weight) as lanes of one
 * vector: per lane the same IEEE operations in the same order as
 * eval_fast (sum_rows, the quotient, point_from), so the same bits; lane 3
 * of a Cartesian sum is a spare (the weight's quotient, or 0) never stored.
 */
#define SPEC_INLINE inline __attribute__((always_inline))
typedef double v4d __attribute__((vector_size(32)));
/* The same lanes read from memory aligned only as doubles are (the body's
 * cached corners live in a malloc'ed block: 16-byte alignment at most). */
typedef double v4d_unaligned __attribute__((vector_size(32), aligned(8)));

static SPEC_INLINE void spec_load(int dim, const double *q, v4d *r)
{
    if (dim == 4)
        memcpy(r, q, sizeof *r);
    else
        *r = (v4d){q[0], q[1], q[2], 0.0};
}

/* The values of a root basis at x (basis() with nd = 0). */
static SPEC_INLINE size_t spec_basis(const coons_patch *p, int dir, int deg, double x, double *N)
{
    if (!p->ks) {
        coons__bernstein_vals(deg, x, N);
        return 0;
    }
    /* coons__bspline_basis01 */
    const double *k = dir ? p->kt : p->ks;
    const size_t ncp = dir ? p->nt : p->ns;
    double lo = k[deg], hi = k[ncp], len = hi - lo;
    double t = clamp01(x);
    double y = lo + t * len;
    if (t >= 1.0) y = hi;
    size_t span = coons__bspline_span_inl(k, ncp, deg, y);
    coons__bspline_vals(k, span, deg, y, N);
    return span - (size_t)deg;
}

/* The values and first derivatives of a root basis at x (basis() with
 * nd = 1). */
static SPEC_INLINE size_t spec_basis1(const coons_patch *p, int dir, int deg, double x,
                                      double *N)
{
    if (!p->ks) {
        coons__bernstein(deg, x, 1, N);
        return 0;
    }
    /* coons__bspline_basis01 */
    const double *k = dir ? p->kt : p->ks;
    const size_t ncp = dir ? p->nt : p->ns;
    double lo = k[deg], hi = k[ncp], len = hi - lo;
    double t = clamp01(x);
    double y = lo + t * len;
    if (t >= 1.0) y = hi;
    size_t span = coons__bspline_span_inl(k, ncp, deg, y);
    coons__bspline_vals1(k, span, deg, y, N);
    for (int j = 0; j <= deg; j++) N[deg + 1 + j] *= len;
    return span - (size_t)deg;
}

/* The quotient of a homogeneous sum (dim 4), or the sum (dim 3). */
static SPEC_INLINE void spec_point(int dim, const v4d *A, v4d *out)
{
    if (dim == 3) {
        *out = *A;
        return;
    }
    const double W = (*A)[3];
    *out = *A / (v4d){W, W, W, W};
}

/* deg > 0: every degree is deg (a constant here); 0: each basis's own */
#define SPEC_DEG(x) (deg > 0 ? deg : (x))
static SPEC_INLINE void spec_points(const coons_body *b, int dim, int deg, size_t n,
                                    const double *uvw, double *xyz)
{
    const struct coons__body2_fast *F = b->fast;
    const int nroot = F->nroot;
    const v4d zero = {0.0, 0.0, 0.0, 0.0};
    for (size_t i = 0; i < n; i++) {
        const double x[3] = {clamp01(uvw[3 * i]), clamp01(uvw[3 * i + 1]),
                             clamp01(uvw[3 * i + 2])};
        double bl[3][2];
        for (int d = 0; d < 3; d++) {
            if (b->blend == COONS_BLEND_CUBIC) { /* coons__blend */
                const double t = x[d];
                double f = 1.0 - 3.0 * t * t + 2.0 * t * t * t;
                bl[d][0] = f;
                bl[d][1] = 1.0 - f;
            } else {
                bl[d][0] = 1.0 - x[d];
                bl[d][1] = x[d];
            }
        }
        double N[12][FAST_DEG + 1];
        size_t first[12];
        for (int r = 0; r < nroot; r++)
            first[r] = spec_basis(F->root_p[r], F->root_dir[r], SPEC_DEG(F->root_deg[r]),
                                  x[F->root_par[r]], N[r]);
        /* the edges: each the average of its two sources */
        v4d E[12];
        for (int e = 0; e < 12; e++) {
            v4d pv[2];
            for (int m = 0; m < 2; m++) {
                const spec_src *S = &F->esrc[e][m];
                const double *Ns = N[S->slot], *T = S->arr + 4 * first[S->slot];
                const int dk = SPEC_DEG(F->root_deg[S->slot]);
                v4d acc = zero;
                for (int k = 0; k <= dk; k++) {
                    v4d q;
                    memcpy(&q, T + 4 * k, sizeof q);
                    acc = acc + Ns[k] * q;
                }
                if (S->addzero) acc = 0.0 + acc;
                spec_point(dim, &acc, &pv[m]);
            }
            E[e] = 0.5 * (pv[0] + pv[1]);
        }
        /* the faces */
        v4d Fv[6];
        for (int f = 0; f < 6; f++) {
            const coons_patch *p = F->f[f].p;
            const double *P = dim == 4 ? p->pw : p->pts;
            const int s0 = F->fslot[f][0], s1 = F->fslot[f][1];
            const double *Ns = N[s0], *Nt = N[s1];
            const size_t fs = first[s0], ft = first[s1], nt = p->nt;
            const int ps = SPEC_DEG(p->ps), pt = SPEC_DEG(p->pt);
            v4d A = zero;
            v4d R[FAST_DEG + 1];
            for (int l = 0; l <= pt; l++) {
                v4d acc = zero;
                for (int k = 0; k <= ps; k++) {
                    v4d q;
                    spec_load(dim, P + ((fs + (size_t)k) * nt + ft + (size_t)l) * (size_t)dim, &q);
                    acc = acc + Ns[k] * q;
                }
                R[l] = acc;
            }
            for (int l = 0; l <= pt; l++) A = A + Nt[l] * R[l];
            spec_point(dim, &A, &Fv[f]);
        }
        /* point_from */
        const double a0 = bl[0][0], a1 = bl[0][1], b0 = bl[1][0], b1 = bl[1][1],
                     w1 = bl[2][1];
        const v4d_unaligned *c = (const v4d_unaligned *)(const void *)F->corner4;
        const v4d *Cu = E, *Cv = E + 4, *Cw = E + 8;
        v4d G[2], Pk[2];
        for (int j = 0; j < 2; j++) G[j] = Fv[2 + j] - (a0 * Cw[j] + a1 * Cw[2 + j]);
        for (int k = 0; k < 2; k++) {
            v4d tk = a0 * c[k] + a1 * c[4 + k];
            v4d t2k = a0 * c[2 + k] + a1 * c[6 + k];
            Pk[k] = Fv[4 + k] - (a0 * Cv[k] + a1 * Cv[2 + k] + b0 * (Cu[k] - tk) +
                                 b1 * (Cu[2 + k] - t2k));
        }
        v4d o = (Fv[0] + a1 * (Fv[1] - Fv[0])) + (G[0] + b1 * (G[1] - G[0])) +
                (Pk[0] + w1 * (Pk[1] - Pk[0]));
        xyz[3 * i] = o[0];
        xyz[3 * i + 1] = o[1];
        xyz[3 * i + 2] = o[2];
    }
}

/* v3 of the three lanes of a vector. */
static SPEC_INLINE void spec_v3(double o[3], const v4d *a)
{
    o[0] = (*a)[0];
    o[1] = (*a)[1];
    o[2] = (*a)[2];
}

/* A value and its derivative from the homogeneous sums A (value) and D
 * (derivative): eval_tcol_dim / eval_srow_dim / eval_basis_dim's quotient. */
static SPEC_INLINE void spec_quot1(int dim, const v4d *A, const v4d *D, v4d *val, v4d *der)
{
    if (dim == 3) {
        *val = *A;
        *der = *D;
        return;
    }
    const double W = (*A)[3];
    const v4d Wv = {W, W, W, W};
    const v4d S00 = *A / Wv;
    *val = S00;
    *der = (*D - (*D)[3] * S00) / Wv;
}

/* The same points with their Jacobians and determinants (eval_fast's
 * sums, partials() and point_from, then coons_body_eval_jacobian's
 * transpose and determinant). */
static SPEC_INLINE void spec_points_jac(const coons_body *b, int dim, int deg, size_t n,
                                        const double *uvw, double *xyz, double *jac,
                                        double *det)
{
    const struct coons__body2_fast *F = b->fast;
    const int nroot = F->nroot;
    const v4d zero = {0.0, 0.0, 0.0, 0.0};
    for (size_t i = 0; i < n; i++) {
        const double x[3] = {clamp01(uvw[3 * i]), clamp01(uvw[3 * i + 1]),
                             clamp01(uvw[3 * i + 2])};
        double bu[5], bv[5], bw[5];
        coons__blends_at(b->blend, x[0], x[1], x[2], bu, bv, bw);
        double N[12][2 * (FAST_DEG + 1)];
        size_t first[12];
        for (int r = 0; r < nroot; r++)
            first[r] = spec_basis1(F->root_p[r], F->root_dir[r], SPEC_DEG(F->root_deg[r]),
                                   x[F->root_par[r]], N[r]);
        /* the column shortcut where eval's s-derivative terms are bounded */
        int tcol_ok[6];
        for (int f = 0; f < 6; f++) {
            const int ps = SPEC_DEG(F->f[f].p->ps);
            const double *Nd = N[F->fslot[f][0]] + ps + 1;
            double S = 0.0;
            for (int k = 0; k <= ps; k++) S += fabs(Nd[k]);
            tcol_ok[f] = S * F->f[f].pmax <= 1e300;
        }
        v4d E[12];
        double Ed[12][3], dEd[12][3];
        for (int e = 0; e < 12; e++) {
            v4d pv[2] = {zero, zero}, pd[2] = {zero, zero};
            for (int m = 0; m < 2; m++) {
                const spec_src *S = &F->esrc[e][m];
                const int f = F->src[e][m][0];
                if (S->addzero && !tcol_ok[f]) {
                    const fast_face *ff = &F->f[f];
                    const int fixed = F->src[e][m][2], s0 = F->fslot[f][0];
                    double r[3][3];
                    coons__tensor_eval_basis(ff->p, first[s0], N[s0], ff->first[1][fixed],
                                             ff->N[1][fixed], 1, r);
                    pv[m] = (v4d){r[0][0], r[0][1], r[0][2], 0.0};
                    pd[m] = (v4d){r[1][0], r[1][1], r[1][2], 0.0};
                    continue;
                }
                const int dk = SPEC_DEG(F->root_deg[S->slot]);
                const double *Nv = N[S->slot], *T = S->arr + 4 * first[S->slot];
                v4d A0 = zero, A1 = zero;
                for (int k = 0; k <= dk; k++) {
                    v4d q;
                    memcpy(&q, T + 4 * k, sizeof q);
                    A0 = A0 + Nv[k] * q;
                }
                for (int k = 0; k <= dk; k++) {
                    v4d q;
                    memcpy(&q, T + 4 * k, sizeof q);
                    A1 = A1 + Nv[dk + 1 + k] * q;
                }
                if (S->addzero) {
                    A0 = 0.0 + A0;
                    A1 = 0.0 + A1;
                }
                spec_quot1(dim, &A0, &A1, &pv[m], &pd[m]);
            }
            E[e] = 0.5 * (pv[0] + pv[1]);
            const v4d dE = 0.5 * (pd[0] + pd[1]);
            spec_v3(Ed[e], &E[e]);
            spec_v3(dEd[e], &dE);
        }
        v4d Fv[6];
        double Fd[6][3][3];
        for (int f = 0; f < 6; f++) {
            const coons_patch *p = F->f[f].p;
            const double *P = dim == 4 ? p->pw : p->pts;
            const int s0 = F->fslot[f][0], s1 = F->fslot[f][1];
            const double *Ns = N[s0], *Nt = N[s1];
            const size_t fs = first[s0], ft = first[s1], nt = p->nt;
            const int ps = SPEC_DEG(p->ps), pt = SPEC_DEG(p->pt);
            v4d R[2][FAST_DEG + 1];
            for (int a = 0; a <= 1; a++)
                for (int l = 0; l <= pt; l++) {
                    v4d acc = zero;
                    for (int k = 0; k <= ps; k++) {
                        v4d q;
                        spec_load(dim,
                                  P + ((fs + (size_t)k) * nt + ft + (size_t)l) * (size_t)dim,
                                  &q);
                        acc = acc + Ns[a * (ps + 1) + k] * q;
                    }
                    R[a][l] = acc;
                }
            v4d A00 = zero, A01 = zero, A10 = zero;
            for (int l = 0; l <= pt; l++) A00 = A00 + Nt[l] * R[0][l];
            for (int l = 0; l <= pt; l++) A01 = A01 + Nt[pt + 1 + l] * R[0][l];
            for (int l = 0; l <= pt; l++) A10 = A10 + Nt[l] * R[1][l];
            v4d d10, d01;
            spec_quot1(dim, &A00, &A10, &Fv[f], &d10);
            if (dim == 4) {
                const double W = A00[3];
                d01 = (A01 - A01[3] * Fv[f]) / (v4d){W, W, W, W};
            } else {
                d01 = A01;
            }
            spec_v3(Fd[f][0], &Fv[f]);
            spec_v3(Fd[f][1], &d10);
            spec_v3(Fd[f][2], &d01);
        }
        double d[3][3];
        partials(b, bu, bv, bw, Fd, Fd + 2, Fd + 4, Ed, dEd, d);
        /* point_from */
        const double a0 = bu[0], a1 = bu[1], b0 = bv[0], b1 = bv[1], w1 = bw[1];
        const v4d_unaligned *c = (const v4d_unaligned *)(const void *)F->corner4;
        const v4d *Cu = E, *Cv = E + 4, *Cw = E + 8;
        v4d G[2], Pk[2];
        for (int j = 0; j < 2; j++) G[j] = Fv[2 + j] - (a0 * Cw[j] + a1 * Cw[2 + j]);
        for (int k = 0; k < 2; k++) {
            v4d tk = a0 * c[k] + a1 * c[4 + k];
            v4d t2k = a0 * c[2 + k] + a1 * c[6 + k];
            Pk[k] = Fv[4 + k] - (a0 * Cv[k] + a1 * Cv[2 + k] + b0 * (Cu[k] - tk) +
                                 b1 * (Cu[2 + k] - t2k));
        }
        v4d o = (Fv[0] + a1 * (Fv[1] - Fv[0])) + (G[0] + b1 * (G[1] - G[0])) +
                (Pk[0] + w1 * (Pk[1] - Pk[0]));
        spec_v3(xyz + 3 * i, &o);
        /* coons_body_eval_jacobian */
        if (jac)
            for (int r = 0; r < 3; r++)
                for (int q = 0; q < 3; q++) jac[9 * i + 3 * (size_t)r + (size_t)q] = d[q][r];
        if (det) {
            double cr[3];
            v3_cross(cr, d[1], d[2]);
            det[i] = v3_dot(d[0], cr);
        }
    }
}

COONS__SIMD_CLONES
static void spec_points_4_2(const coons_body *b, size_t n, const double *uvw, double *xyz,
                             double *jac, double *det)
{
    if (jac || det)
        spec_points_jac(b, 4, 2, n, uvw, xyz, jac, det);
    else
        spec_points(b, 4, 2, n, uvw, xyz);
}

COONS__SIMD_CLONES
static void spec_points_3_2(const coons_body *b, size_t n, const double *uvw, double *xyz,
                             double *jac, double *det)
{
    if (jac || det)
        spec_points_jac(b, 3, 2, n, uvw, xyz, jac, det);
    else
        spec_points(b, 3, 2, n, uvw, xyz);
}

COONS__SIMD_CLONES
static void spec_points_4_3(const coons_body *b, size_t n, const double *uvw, double *xyz,
                             double *jac, double *det)
{
    if (jac || det)
        spec_points_jac(b, 4, 3, n, uvw, xyz, jac, det);
    else
        spec_points(b, 4, 3, n, uvw, xyz);
}

COONS__SIMD_CLONES
static void spec_points_3_3(const coons_body *b, size_t n, const double *uvw, double *xyz,
                             double *jac, double *det)
{
    if (jac || det)
        spec_points_jac(b, 3, 3, n, uvw, xyz, jac, det);
    else
        spec_points(b, 3, 3, n, uvw, xyz);
}

COONS__SIMD_CLONES
static void spec_points_4_any(const coons_body *b, size_t n, const double *uvw, double *xyz,
                             double *jac, double *det)
{
    if (jac || det)
        spec_points_jac(b, 4, 0, n, uvw, xyz, jac, det);
    else
        spec_points(b, 4, 0, n, uvw, xyz);
}

COONS__SIMD_CLONES
static void spec_points_3_any(const coons_body *b, size_t n, const double *uvw, double *xyz,
                             double *jac, double *det)
{
    if (jac || det)
        spec_points_jac(b, 3, 0, n, uvw, xyz, jac, det);
    else
        spec_points(b, 3, 0, n, uvw, xyz);
}

#undef SPEC_DEG
#endif

/* The row's points: the batch path where the body has its tables, else
 * point by point. */
static void points(const coons_body *b, size_t n, const double *uvw, double *xyz, double *jac,
                   double *det)
{
#if defined(__GNUC__)
    const struct coons__body2_fast *F = b->fast;
    const int spec = F ? 10 * F->spec_dim + F->spec_deg : 0;
    switch (spec) {
    case 42: spec_points_4_2(b, n, uvw, xyz, jac, det); return;
    case 32: spec_points_3_2(b, n, uvw, xyz, jac, det); return;
    case 43: spec_points_4_3(b, n, uvw, xyz, jac, det); return;
    case 33: spec_points_3_3(b, n, uvw, xyz, jac, det); return;
    case 40: spec_points_4_any(b, n, uvw, xyz, jac, det); return;
    case 30: spec_points_3_any(b, n, uvw, xyz, jac, det); return;
    default: break;
    }
#endif
    for (size_t i = 0; i < n; i++) {
        const double *q = uvw + 3 * i;
        if (!jac && !det) {
            eval(b, clamp01(q[0]), clamp01(q[1]), clamp01(q[2]), xyz + 3 * i, NULL);
            continue;
        }
        double J[3][3];
        double d = coons_body_eval_jacobian(b, q[0], q[1], q[2], xyz + 3 * i, J);
        if (jac) memcpy(jac + 9 * i, J, sizeof J);
        if (det) det[i] = d;
    }
}

/*
 * The inner loop of the grid: one w-line of n3 = 3 nw doubles,
 *   o = (x0 + a1 xd) + (g0 + b1 gd) + (q0 + w1 qd),
 * q0, qd the (u,v) terms repeated twice so that blocks of 6 doubles (two
 * points) are whole SSE2/AVX vectors. The AVX2 clone performs the same
 * IEEE operations in the same order (no contraction into FMA in ISO C
 * mode), so every clone gives bitwise the same points.
 */
COONS__SIMD_CLONES
static void w_line(size_t n3, double a1, double b1, const double *restrict x0,
                   const double *restrict xd, const double *restrict g0,
                   const double *restrict gd, const double *restrict w1,
                   const double *restrict q0, const double *restrict qd, double *restrict o)
{
    size_t m = 0, n6 = n3 - n3 % 6;
    for (; m < n6; m += 6)
        for (size_t r = 0; r < 6; r++)
            o[m + r] = (x0[m + r] + a1 * xd[m + r]) + (g0[m + r] + b1 * gd[m + r]) +
                       (q0[r] + w1[m + r] * qd[r]);
    for (size_t r = 0; m < n3; m++, r++)
        o[m] = (x0[m] + a1 * xd[m]) + (g0[m] + b1 * gd[m]) + (q0[r] + w1[m] * qd[r]);
}

/*
 * Grid. Per point C2 = D - E + T regroups as
 *   C2 = a_0(u) X_0(v,w) + a_1(u) X_1(v,w)             (face grids over (v,w))
 *      + a_0(v) G_0(u,w) + a_1(v) G_1(u,w)             (over (u,w))
 *      + a_0(w) P_0(u,v) + a_1(w) P_1(u,v)             (over (u,v))
 * with G_j = Y_j - sum_i a_i(u) C(i,j,w) and
 * P_k = Z_k - sum_i a_i(u) C(i,v,k) - sum_j a_j(v) C(u,j,k) + sum_ij a_i(u) a_j(v) C_ijk,
 * so the inner loop along w reads two rows of X, two of G and six constants.
 */
/* The scratch of grid: clamped parameters and blend pairs per direction,
 * the face grids X (v,w), Y/G (u,w), Z/P (u,v), two of each, the edges
 * along each direction, and one face's boundary row. */
typedef struct grid2 {
    const coons_body *b;
    size_t nu, nv, nw, nX, nG, nZ;
    double *uc, *vc, *wc, *au, *av, *aw;
    double *X, *G, *Z;
    double *Cw, *Cv, *Cu, *row;
} grid2;

static coons_status grid2_alloc(grid2 *g, double **s, coons_error *err)
{
    size_t nu = g->nu, nv = g->nv, nw = g->nw, total = 0;
    size_t nmax = nu > nv ? (nu > nw ? nu : nw) : (nv > nw ? nv : nw);
    /* clamped parameters and blends (3 per sample), faces X (2 nv nw 3),
     * Y/G (2 nu nw 3), Z/P (2 nu nv 3), edges (12 per sample), one face's
     * two boundary rows (6 nmax) */
    if (!coons__size_addmul(&total, nu + nv + nw, 15) ||
        !coons__size_addmul(&total, nv, 6 * nw) || !coons__size_addmul(&total, nu, 6 * nw) ||
        !coons__size_addmul(&total, nu, 6 * nv) || !coons__size_addmul(&total, nmax, 6))
        return coons__error_set(err, COONS_E_LIMIT, "body2 grid: scratch size overflows");
    *s = coons__malloc_array(total, sizeof(double));
    if (!*s) return coons__error_nomem(err);
    g->uc = *s, g->vc = g->uc + nu, g->wc = g->vc + nv, g->au = g->wc + nw,
    g->av = g->au + 2 * nu, g->aw = g->av + 2 * nv;
    g->X = g->aw + 2 * nw, g->G = g->X + 6 * nv * nw, g->Z = g->G + 6 * nu * nw;
    g->Cw = g->Z + 6 * nu * nv, g->Cv = g->Cw + 12 * nw, g->Cu = g->Cv + 12 * nv,
    g->row = g->Cu + 12 * nu;
    g->nX = 3 * nv * nw, g->nG = 3 * nu * nw, g->nZ = 3 * nu * nv;
    return COONS_OK;
}

/* Clamped parameters and their blend pairs. */
static void grid2_params(grid2 *g, const double *u, const double *v, const double *w)
{
    double *par[3] = {g->uc, g->vc, g->wc}, *bl[3] = {g->au, g->av, g->aw};
    const double *src[3] = {u, v, w};
    const size_t np[3] = {g->nu, g->nv, g->nw};
    for (int d = 0; d < 3; d++)
        for (size_t m = 0; m < np[d]; m++) {
            double t[4];
            par[d][m] = clamp01(src[d][m]);
            coons__blend(g->b->blend, par[d][m], 0, t);
            bl[d][2 * m] = t[0];
            bl[d][2 * m + 1] = t[1];
        }
}

/* Face grids. Face f's parameters (s,t): X (v,w), Y (u,w), Z (u,v). */
static coons_status grid2_faces(grid2 *g, coons_error *err)
{
    const coons_body *b = g->b;
    coons_status rc = COONS_OK;
    for (int x = 0; x < 2 && !rc; x++) {
        rc = coons_patch_eval_grid(b->face[x], g->vc, g->nv, g->wc, g->nw, g->X + x * g->nX, err);
        if (!rc)
            rc = coons_patch_eval_grid(b->face[2 + x], g->uc, g->nu, g->wc, g->nw,
                                       g->G + x * g->nG, err);
        if (!rc)
            rc = coons_patch_eval_grid(b->face[4 + x], g->uc, g->nu, g->vc, g->nv,
                                       g->Z + x * g->nZ, err);
    }
    return rc;
}

/* Edges: Cw[(2i+j) 3nw + 3k] = C(i,j,w_k), Cv[(2i+k) 3nv + 3j] = C(i,v_j,k),
 * Cu[(2j+k) 3nu + 3i] = C(u_i,j,k); each the average of its two faces,
 * whose boundary rows are sampled first into Cx (first face) and `row`. */
static coons_status grid2_edges(grid2 *g, coons_error *err)
{
    static const double ends[2] = {0.0, 1.0};
    const double *par[3] = {g->uc, g->vc, g->wc};
    const size_t np[3] = {g->nu, g->nv, g->nw};
    coons_status rc = COONS_OK;
    for (int e = 0; e < 12 && !rc; e++) {
        int dir = e / 4;
        size_t n = np[dir];
        double *C = (dir == 0 ? g->Cu : dir == 1 ? g->Cv : g->Cw) + (size_t)(e % 4) * 3 * n;
        for (int m = 0; m < 2 && !rc; m++) {
            int f, run, fixed;
            edge_source(e, m, &f, &run, &fixed);
            double *dst = m == 0 ? C : g->row;
            const coons_patch *face = g->b->face[f];
            if (run == 0)
                rc = coons_patch_eval_grid(face, par[dir], n, ends + fixed, 1, dst, err);
            else
                rc = coons_patch_eval_grid(face, ends + fixed, 1, par[dir], n, dst, err);
        }
        if (!rc)
            for (size_t m = 0; m < 3 * n; m++) C[m] = 0.5 * (C[m] + g->row[m]);
    }
    return rc;
}

/* G_j and P_k in place of Y_j and Z_k; then, since both blends sum to one
 * (a_0 = 1 - a_1), each pair becomes a base and a difference:
 * X_0 + a_1(u) (X_1 - X_0), and so on. */
static void grid2_regroup(grid2 *g)
{
    const size_t nu = g->nu, nv = g->nv, nw = g->nw, nX = g->nX, nG = g->nG, nZ = g->nZ;
    const double *au = g->au, *av = g->av, *Cw = g->Cw, *Cv = g->Cv, *Cu = g->Cu;
    double *X = g->X, *G = g->G, *Z = g->Z;
    /* G_j(u_i, w_k) = Y_j - sum_i' a_i'(u_i) C(i',j,w_k). */
    for (int j = 0; j < 2; j++)
        for (size_t i = 0; i < nu; i++) {
            double a0 = au[2 * i], a1 = au[2 * i + 1];
            double *gj = G + j * nG + i * 3 * nw;
            const double *c0 = Cw + (size_t)j * 3 * nw, *c1 = Cw + (size_t)(2 + j) * 3 * nw;
            for (size_t m = 0; m < 3 * nw; m++) gj[m] -= a0 * c0[m] + a1 * c1[m];
        }
    /* P_k(u_i, v_j) in place of Z_k. */
    const double(*c)[3] = g->b->corner;
    for (size_t i = 0; i < nu; i++) {
        double a0 = au[2 * i], a1 = au[2 * i + 1], tu[4][3], cu[4][3];
        for (int jk = 0; jk < 4; jk++)
            for (int r = 0; r < 3; r++) {
                tu[jk][r] = a0 * c[jk][r] + a1 * c[4 + jk][r];
                cu[jk][r] = Cu[(size_t)jk * 3 * nu + 3 * i + (size_t)r];
            }
        for (size_t j = 0; j < nv; j++) {
            double b0 = av[2 * j], b1 = av[2 * j + 1];
            for (int k = 0; k < 2; k++) {
                double *z = Z + k * nZ + (i * nv + j) * 3;
                for (int r = 0; r < 3; r++)
                    z[r] -= a0 * Cv[(size_t)k * 3 * nv + 3 * j + (size_t)r] +
                            a1 * Cv[(size_t)(2 + k) * 3 * nv + 3 * j + (size_t)r] +
                            b0 * (cu[k][r] - tu[k][r]) + b1 * (cu[2 + k][r] - tu[2 + k][r]);
            }
        }
    }
    for (size_t m = 0; m < nX; m++) X[nX + m] -= X[m];
    for (size_t m = 0; m < nG; m++) G[nG + m] -= G[m];
    for (size_t m = 0; m < nZ; m++) Z[nZ + m] -= Z[m];
}

/* Every w-line of the output from the regrouped terms. */
static void grid2_lines(grid2 *g, double *out)
{
    const size_t nu = g->nu, nv = g->nv, nw = g->nw, nX = g->nX, nG = g->nG, nZ = g->nZ;
    /* a_1(w) repeated for the three coordinates (reuses the Cw rows). */
    double *w1 = g->Cw;
    for (size_t k = 0; k < nw; k++)
        w1[3 * k] = w1[3 * k + 1] = w1[3 * k + 2] = g->aw[2 * k + 1];
    for (size_t i = 0; i < nu; i++) {
        double a1 = g->au[2 * i + 1];
        const double *g0 = g->G + i * 3 * nw, *gd = g0 + nG;
        for (size_t j = 0; j < nv; j++) {
            double b1 = g->av[2 * j + 1];
            const double *x0 = g->X + j * 3 * nw, *xd = x0 + nX;
            const double *p0 = g->Z + (i * nv + j) * 3, *pd = p0 + nZ;
            /* the (u,v) terms repeated over two points: the loop below then
             * runs over whole vectors of doubles */
            double q0[6], qd[6];
            for (int r = 0; r < 6; r++) {
                q0[r] = p0[r % 3];
                qd[r] = pd[r % 3];
            }
            w_line(3 * nw, a1, b1, x0, xd, g0, gd, w1, q0, qd, out + (i * nv + j) * nw * 3);
        }
    }
}

static coons_status grid(const coons_body *b, const double *u, size_t nu, const double *v,
                         size_t nv, const double *w, size_t nw, double *out, coons_error *err)
{
    grid2 g = {.b = b, .nu = nu, .nv = nv, .nw = nw};
    double *s = NULL;
    coons_status rc = grid2_alloc(&g, &s, err);
    if (rc) return rc;
    grid2_params(&g, u, v, w);
    rc = grid2_faces(&g, err);
    if (!rc) rc = grid2_edges(&g, err);
    if (!rc) {
        grid2_regroup(&g);
        grid2_lines(&g, out);
    }
    coons__free(s);
    return rc;
}

/*
 * det J on a grid, for volume quadrature and fold detection. With the
 * regrouping of the grid above, C2 = sum_i a_i X_i + sum_j b_j G_j +
 * sum_k c_k P_k, X on (v,w), G on (u,w), P on (u,v), so
 *   F_u = sum a_i' X_i + sum b_j G_j,u + sum c_k P_k,u
 *   F_v = sum a_i X_i,v + sum b_j' G_j + sum c_k P_k,v
 *   F_w = sum a_i X_i,w + sum b_j G_j,w + sum c_k' P_k,
 * each of X, G, P with its two partials tabulated once per grid.
 */
/* The scratch of det_grid: per direction the blend pairs with
 * derivatives A[d] and the four edges with derivatives E[d]; X_i, G_j,
 * P_k (below) with their two partials. */
typedef struct jgrid {
    const coons_body *b;
    const double *par[3];
    size_t np[3];
    double *A[3], *E[3], *X, *G, *P;
} jgrid;

/* Edge e' (0..3) of direction d, value (q = 0) or derivative (q = 1), at
 * sample m. */
#define EDGE(d, e, q, m) (J->E[d] + (size_t)(2 * (e) + (q)) * 3 * J->np[d] + 3 * (m))

static coons_status jgrid_alloc(jgrid *J, double **s, coons_error *err)
{
    const size_t nu = J->np[0], nv = J->np[1], nw = J->np[2];
    size_t total = 0;
    /* blends 4 per sample, edges 24 per sample, X 18 nv nw, G 18 nu nw, P 18 nu nv */
    if (!coons__size_addmul(&total, nu + nv + nw, 28) ||
        !coons__size_addmul(&total, nv, 18 * nw) || !coons__size_addmul(&total, nu, 18 * nw) ||
        !coons__size_addmul(&total, nu, 18 * nv))
        return coons__error_set(err, COONS_E_LIMIT, "body2 Jacobian grid: scratch overflows");
    *s = coons__malloc_array(total, sizeof(double));
    if (!*s) return coons__error_nomem(err);
    J->X = *s, J->G = J->X + 18 * nv * nw, J->P = J->G + 18 * nu * nw;
    J->A[0] = J->P + 18 * nu * nv;
    for (int d = 0; d < 3; d++) {
        if (d) J->A[d] = J->E[d - 1] + 24 * J->np[d - 1];
        J->E[d] = J->A[d] + 4 * J->np[d];
    }
    return COONS_OK;
}

/* A[d][4m..]: a_0, a_1, a_0', a_1'; E[d][(2e'+q) 3n + 3m]: edge e' of
 * direction d (value q = 0, derivative q = 1) at sample m. */
static void jgrid_edges(jgrid *J)
{
    for (int d = 0; d < 3; d++)
        for (size_t m = 0; m < J->np[d]; m++) {
            double x = clamp01(J->par[d][m]);
            coons__blend(J->b->blend, x, 1, J->A[d] + 4 * m);
            for (int e = 0; e < 4; e++) edge_at(J->b, 4 * d + e, x, EDGE(d, e, 0, m), EDGE(d, e, 1, m));
        }
}

static void jgrid_x(jgrid *J)
{
    const coons_body *b = J->b;
    const double *v = J->par[1], *w = J->par[2];
    const size_t nv = J->np[1], nw = J->np[2];
    double *X = J->X;
    /* X_i and partials: X[((3i+q) nv nw + j nw + k) 3], q = value, d/dv, d/dw */
    for (int i = 0; i < 2; i++)
        for (size_t j = 0; j < nv; j++)
            for (size_t k = 0; k < nw; k++) {
                double r[3][3];
                coons_patch_eval_derivs(b->face[i], v[j], w[k], 1, r);
                for (int q = 0; q < 3; q++)
                    v3_copy(X + (((size_t)(3 * i + q) * nv + j) * nw + k) * 3, r[q]);
            }
}

static void jgrid_g(jgrid *J)
{
    const coons_body *b = J->b;
    const double *u = J->par[0], *w = J->par[2];
    const size_t nu = J->np[0], nw = J->np[2];
    double *const *A = J->A, *G = J->G;
    /* G_j = Y_j - sum_i a_i C(i,j,w): value, d/du, d/dw */
    for (int jj = 0; jj < 2; jj++)
        for (size_t i = 0; i < nu; i++) {
            const double *a = A[0] + 4 * i;
            for (size_t k = 0; k < nw; k++) {
                double r[3][3];
                coons_patch_eval_derivs(b->face[2 + jj], u[i], w[k], 1, r);
                const double *c0 = EDGE(2, jj, 0, k), *c1 = EDGE(2, 2 + jj, 0, k);
                const double *d0 = EDGE(2, jj, 1, k), *d1 = EDGE(2, 2 + jj, 1, k);
                double *g = G + (((size_t)(3 * jj) * nu + i) * nw + k) * 3;
                double *gu = g + nu * nw * 3, *gw = gu + nu * nw * 3;
                for (int t = 0; t < 3; t++) {
                    g[t] = r[0][t] - a[0] * c0[t] - a[1] * c1[t];
                    gu[t] = r[1][t] - a[2] * c0[t] - a[3] * c1[t];
                    gw[t] = r[2][t] - a[0] * d0[t] - a[1] * d1[t];
                }
            }
        }
}

static void jgrid_p(jgrid *J)
{
    const coons_body *b = J->b;
    const double *u = J->par[0], *v = J->par[1];
    const size_t nu = J->np[0], nv = J->np[1];
    double *const *A = J->A, *P = J->P;
    /* P_k = Z_k - sum_i a_i C(i,v,k) - sum_j b_j (C(u,j,k) - sum_i a_i C_ijk):
     * value, d/du, d/dv */
    const double(*cn)[3] = b->corner;
    for (int kk = 0; kk < 2; kk++)
        for (size_t i = 0; i < nu; i++) {
            const double *a = A[0] + 4 * i;
            for (size_t j = 0; j < nv; j++) {
                const double *bb = A[1] + 4 * j;
                double r[3][3];
                coons_patch_eval_derivs(b->face[4 + kk], u[i], v[j], 1, r);
                double *p = P + (((size_t)(3 * kk) * nu + i) * nv + j) * 3;
                double *pu = p + nu * nv * 3, *pv = pu + nu * nv * 3;
                for (int t = 0; t < 3; t++) {
                    p[t] = r[0][t];
                    pu[t] = r[1][t];
                    pv[t] = r[2][t];
                    for (int x = 0; x < 2; x++) {
                        /* C(x,v,k): v-edge 2x+k; C(u,x,k): u-edge 2x+k */
                        const double *cv = EDGE(1, 2 * x + kk, 0, j), *dv = EDGE(1, 2 * x + kk, 1, j);
                        const double *cu = EDGE(0, 2 * x + kk, 0, i), *du = EDGE(0, 2 * x + kk, 1, i);
                        p[t] -= a[x] * cv[t] + bb[x] * cu[t];
                        pu[t] -= a[2 + x] * cv[t] + bb[x] * du[t];
                        pv[t] -= a[x] * dv[t] + bb[2 + x] * cu[t];
                        for (int y = 0; y < 2; y++) {
                            double c = cn[4 * y + 2 * x + kk][t]; /* C_{y x k} */
                            p[t] += a[y] * bb[x] * c;
                            pu[t] += a[2 + y] * bb[x] * c;
                            pv[t] += a[y] * bb[2 + x] * c;
                        }
                    }
                }
            }
        }
}

/* det [F_u F_v F_w] (det not NULL) and the partials (jac not NULL) at
 * every point from the tabulated terms. */
static void jgrid_det(const jgrid *J, double *det, double *jac)
{
    const size_t nu = J->np[0], nv = J->np[1], nw = J->np[2];
    double *const *A = J->A, *X = J->X, *G = J->G, *P = J->P;
    size_t sX = nv * nw * 3, sG = nu * nw * 3, sP = nu * nv * 3;
    for (size_t i = 0; i < nu; i++) {
        const double *a = A[0] + 4 * i;
        for (size_t j = 0; j < nv; j++) {
            const double *bb = A[1] + 4 * j;
            const double *p0 = P + (i * nv + j) * 3, *p1 = p0 + 3 * sP;
            for (size_t k = 0; k < nw; k++) {
                const double *c = A[2] + 4 * k;
                const double *x0 = X + (j * nw + k) * 3, *x1 = x0 + 3 * sX;
                const double *g0 = G + (i * nw + k) * 3, *g1 = g0 + 3 * sG;
                double fu[3], fv[3], fw[3];
                for (int t = 0; t < 3; t++) {
                    fu[t] = a[2] * x0[t] + a[3] * x1[t] + bb[0] * g0[sG + t] +
                            bb[1] * g1[sG + t] + c[0] * p0[sP + t] + c[1] * p1[sP + t];
                    fv[t] = a[0] * x0[sX + t] + a[1] * x1[sX + t] + bb[2] * g0[t] +
                            bb[3] * g1[t] + c[0] * p0[2 * sP + t] + c[1] * p1[2 * sP + t];
                    fw[t] = a[0] * x0[2 * sX + t] + a[1] * x1[2 * sX + t] +
                            bb[0] * g0[2 * sG + t] + bb[1] * g1[2 * sG + t] + c[2] * p0[t] +
                            c[3] * p1[t];
                }
                size_t n = (i * nv + j) * nw + k;
                if (jac) {
                    v3_copy(jac + 9 * n, fu);
                    v3_copy(jac + 9 * n + 3, fv);
                    v3_copy(jac + 9 * n + 6, fw);
                }
                if (det) {
                    double cr[3];
                    v3_cross(cr, fv, fw);
                    det[n] = v3_dot(fu, cr);
                }
            }
        }
    }
}

#undef EDGE

static coons_status det_grid(const coons_body *b, const double *u, size_t nu,
                             const double *v, size_t nv, const double *w, size_t nw,
                             double *det, double *jac, coons_error *err)
{
    jgrid J = {.b = b, .par = {u, v, w}, .np = {nu, nv, nw}};
    double *s = NULL;
    coons_status rc = jgrid_alloc(&J, &s, err);
    if (rc) return rc;
    jgrid_edges(&J);
    jgrid_x(&J);
    jgrid_g(&J);
    jgrid_p(&J);
    jgrid_det(&J, det, jac);
    coons__free(s);
    return COONS_OK;
}

/* The faces whose s or t runs along direction d (body.h). */
static void breaks(const coons_body *b, int d, coons__breaks *B)
{
    static const int face[3][4] = {{2, 3, 4, 5}, {0, 1, 4, 5}, {0, 1, 2, 3}};
    static const int sdir[3][4] = {{0, 0, 0, 0}, {0, 0, 1, 1}, {1, 1, 1, 1}};
    for (int m = 0; m < 4; m++) coons__patch_breaks(b->face[face[d][m]], sdir[d][m], B);
}

/* The blends and the faces along d (their edges are the faces' boundary
 * curves; seed 000 section 2.4: a Coons body 2 of B-spline faces is a
 * B-spline body). */
static void space(const coons_body *b, int d, coons__space *S)
{
    static const int face[3][4] = {{2, 3, 4, 5}, {0, 1, 4, 5}, {0, 1, 2, 3}};
    static const int sdir[3][4] = {{0, 0, 0, 0}, {0, 0, 1, 1}, {1, 1, 1, 1}};
    *S = coons__space_poly(coons__blend_degree(b->blend));
    for (int m = 0; m < 4; m++)
        coons__space_join(S, coons__patch_space(b->face[face[d][m]], sdir[d][m]));
}

static coons_status copy_data(const coons_body *b, coons_body *d, coons_error *err)
{
    d->fast = NULL;
    for (int f = 0; f < 6; f++) d->face[f] = NULL;
    for (int f = 0; f < 6; f++) {
        if (!b->face[f]) continue;
        coons_status rc = coons_patch_copy(b->face[f], &d->face[f], err);
        if (rc) return rc;
    }
    return b->fast ? fast_build(d, err) : COONS_OK;
}

static void free_data(coons_body *b)
{
    fast_free(b);
    for (int f = 0; f < 6; f++) coons_patch_free(b->face[f]);
}

const coons__body_kind coons__body2_kind = {
    .type = COONS_BODY_BODY2, .eval = eval, .grid = grid, .det_grid = det_grid,
    .breaks = breaks, .copy = copy_data, .free = free_data, .space = space,
    .points = points};
