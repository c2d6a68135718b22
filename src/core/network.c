/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The network patch: a grid of curves filled cell by cell, seed 001
 * section 1.2.2 ("Utilizzo pratico"). Row j is x(s, t_j), column i is
 * x(s_i, t); cell (i,j) covers [s_i, s_i+1] x [t_j, t_j+1] and is, in its
 * local parameters a = (s - s_i)/ds, b = (t - t_j)/dt, the Hermite Coons
 * patch of eq. 1.13-1.15 (hermite_coons.c) of the four curve pieces that
 * bound it, its ribbons (eq. 1.16) built from node data, or with the
 * linear blend the Coons patch of eq. 1.8 (Fig. 1.3).
 *
 * Node data in the network's (s,t): x_s from the row, x_t from the
 * column (one-sided: each cell takes the derivative from its own side, so
 * a kink in a curve stays a kink), and one twist per node: the average of
 * its cells' proposals weighted as Bessel weights the two sides of a node
 * (coons-model(5), "Networks of curves"). In a cell's local parameters
 * tangents scale by ds or dt and twists by ds dt. Because neighbouring
 * cells share the row piece and, across it, a ribbon built from the same
 * node tangents and twists, the cross derivative agrees on both sides:
 * C1 across every inner curve where the curves are C1.
 */
#include <string.h>

#include "agree.h"
#include "body_impl.h"
#include "curve_impl.h"
#include "patch_impl.h"

/* ---- a piece of a curve: y(x) = c(a + x (b - a)) ------------------------ */

static void tangent(const coons_curve *c, double x, int left, double out[3]);

/* At its right end x = 1 a piece is the limit from the left, also at an
 * inner kink of c, where c itself gives the right-hand derivative: each cell
 * keeps its own one-sided tangents (only the first derivative: nothing
 * needs a one-sided second derivative at a cell's far side). */
static void piece_eval(const coons_curve *c, double x, int order, double out[][3])
{
    double a = c->xf[0], b = c->xf[1], len = b - a;
    /* exact at both ends, so pieces meet their neighbours bit for bit */
    c->inner->kind->eval(c->inner, clamp01((1.0 - x) * a + x * b), order, out);
    if (order >= 1 && x >= 1.0 && b < 1.0) tangent(c->inner, b, 1, out[1]);
    if (order >= 1) v3_scale(out[1], out[1], len);
    if (order >= 2) v3_scale(out[2], out[2], len * len);
}

static coons_status piece_bezier(const coons_curve *c, double *points, size_t capacity,
                                 size_t *segments, int *degree, coons_error *err)
{
    (void)c, (void)points, (void)capacity, (void)segments, (void)degree;
    return coons__error_set(err, COONS_E_UNSUPPORTED,
                            "a network's curve piece has no Bezier segments");
}

static void piece_breaks(const coons_curve *c, coons__breaks *B)
{
    double a = c->xf[0], b = c->xf[1];
    if (B->probe) {
        coons__breaks in = {.probe = 1, .at = a + B->at * (b - a), .tol = B->tol * (b - a)};
        coons__curve_breaks(c->inner, &in);
        B->hit |= in.hit;
        return;
    }
    coons__breaks in = {.all = B->all};
    coons__curve_breaks(c->inner, &in);
    for (size_t i = 0; i < in.n; i++) coons__breaks_add(B, (in.v[i] - a) / (b - a));
    if (in.nomem) B->nomem = 1;
    coons__free(in.v);
}

/* A piece [a,b] of a curve is the same polynomial (or quotient) per span. */
static void piece_space(const coons_curve *c, coons__space *S)
{
    *S = coons__curve_space(c->inner);
}

static const coons__curve_kind piece_kind = {
    COONS_CURVE_LINE, /* internal only: never seen by coons_curve_kind() */
    piece_eval, piece_bezier, piece_breaks, coons__curve_wrap_copy, coons__curve_wrap_free,
    piece_space,
};

static coons_status piece_new(const coons_curve *c, double a, double b, coons_curve **out,
                              coons_error *err)
{
    coons_status rc = coons__curve_wrap(&piece_kind, c, NULL, out, err);
    if (!rc) {
        (*out)->xf[0] = a;
        (*out)->xf[1] = b;
    }
    return rc;
}

/* ---- node data ----------------------------------------------------------- */

/* Is x a breakpoint of c (where a one-sided derivative may differ)? Asked
 * during evaluation, so it allocates nothing (the probe mode of breaks.h). */
static int at_break(const coons_curve *c, double x)
{
    coons__breaks B = {.probe = 1, .at = x, .tol = 1e-12};
    coons__curve_breaks(c, &B);
    return B.hit;
}

/* c'(x) from the left (left != 0) or the right. Evaluation returns the
 * right-hand derivative at an inner breakpoint; the left one is the
 * limit of the piece before it, taken to second order from x - h
 * (error h^2/2 |c'''|, ~1e-14 of the curve's size). */
static void tangent(const coons_curve *c, double x, int left, double out[3])
{
    double r[3][3];
    coons_curve_eval_derivs(c, x, 1, r);
    v3_copy(out, r[1]);
    if (!left || x >= 1.0 || !at_break(c, x)) return;
    const double h = 1e-7;
    coons_curve_eval_derivs(c, x - h, 2, r);
    double l[3];
    for (int k = 0; k < 3; k++) l[k] = r[1][k] + h * r[2][k];
    double d = v3_dist(l, out), m = v3_norm(l) + v3_norm(out);
    if (d > 1e-9 * m) v3_copy(out, l); /* a kink: keep the left limit */
}

coons_status coons__network_nodes_agree(const coons_curve *const *rows, size_t nr,
                                        const coons_curve *const *cols, size_t nc,
                                        const double *sn, const double *tn, double tol,
                                        size_t *bi, size_t *bj, double *dist)
{
    for (size_t j = 0; j < nr; j++)
        for (size_t i = 0; i < nc; i++) {
            double p[3], q[3];
            coons_curve_eval(rows[j], sn[i], p);
            coons_curve_eval(cols[i], tn[j], q);
            double d = v3_dist(p, q);
            if (!(d <= tol)) {
                *bi = i;
                *bj = j;
                *dist = d;
                return COONS_E_INCOMPATIBLE;
            }
        }
    return COONS_OK;
}

/* The node parameters: given (checked) or uniform k/(n-1). */
static coons_status nodes(const double *given, size_t n, const char *name, double **out,
                          coons_error *err)
{
    double *v = coons__malloc_array(n, sizeof *v);
    if (!v) return coons__error_nomem(err);
    for (size_t k = 0; k < n; k++) v[k] = given ? given[k] : (double)k / (double)(n - 1);
    if (!given) v[n - 1] = 1.0;
    const char *bad = NULL;
    if (v[0] != 0.0 || v[n - 1] != 1.0) bad = "start at exactly 0 and end at exactly 1";
    for (size_t k = 1; k < n && !bad; k++)
        if (!(v[k] > v[k - 1]) || !isfinite(v[k])) bad = "be strictly increasing";
    if (bad) {
        coons__free(v);
        return coons__error_set(err, COONS_E_INVALID, "network: %s must %s", name, bad);
    }
    *out = v;
    return COONS_OK;
}

/* Everything a construction computes before the cells. */
typedef struct build {
    size_t m, n;             /* cells along s, t */
    const double *sn, *tn;
    const coons_curve *const *row, *const *col;
    double (*X)[3];          /* node points, (i,j) at i*(n+1) + j */
    double (*tw)[3];         /* node twists */
    coons_twist twist;
} build;

/* Corner k = a + 2b of cell (i,j): tangents x_s, x_t in the network's
 * (s,t), one-sided from the cell's side. */
static void cell_tangents(const build *B, size_t i, size_t j, double xs[4][3], double xt[4][3])
{
    for (int k = 0; k < 4; k++) {
        int a = k & 1, b = k >> 1;
        tangent(B->row[j + b], B->sn[i + a], a, xs[k]);
        tangent(B->col[i + a], B->tn[j + b], b, xt[k]);
    }
}

static const double *node(const build *B, size_t i, size_t j)
{
    return B->X[i * (B->n + 1) + j];
}

/* The twist cell (i,j) proposes at its corner k, in (s,t). */
static void proposal(const build *B, size_t i, size_t j, int k, double out[3])
{
    v3_zero(out);
    if (B->twist == COONS_TWIST_ZERO) return;
    double ds = B->sn[i + 1] - B->sn[i], dt = B->tn[j + 1] - B->tn[j], cell[3];
    v3_sub(cell, node(B, i, j), node(B, i + 1, j));
    v3_sub(cell, cell, node(B, i, j + 1));
    v3_add(cell, cell, node(B, i + 1, j + 1));
    if (B->twist == COONS_TWIST_BESSEL) {
        v3_scale(out, cell, 1.0 / (ds * dt));
        return;
    }
    /* Adini in the cell's local parameters (hermite_coons.c), then / ds dt:
     * local x_a = ds x_s, x_b = dt x_t. */
    double xs[4][3], xt[4][3];
    cell_tangents(B, i, j, xs, xt);
    int a = k & 1, b = k >> 1;
    for (int c = 0; c < 3; c++)
        out[c] = (dt * (xt[1 + 2 * b][c] - xt[2 * b][c]) + ds * (xs[2 + a][c] - xs[a][c]) -
                  cell[c]) /
                 (ds * dt);
}

/* Bessel weights of the cells on either side of node k of n+1 nodes x:
 * w[0] the cell before (k-1), w[1] the cell after (k). */
static void side_weights(const double *x, size_t n, size_t k, double w[2])
{
    if (k == 0) {
        w[0] = 0.0, w[1] = 1.0;
    } else if (k == n) {
        w[0] = 1.0, w[1] = 0.0;
    } else {
        double span = x[k + 1] - x[k - 1];
        w[0] = (x[k + 1] - x[k]) / span;
        w[1] = (x[k] - x[k - 1]) / span;
    }
}

static void node_twists(build *B)
{
    for (size_t i = 0; i <= B->m; i++)
        for (size_t j = 0; j <= B->n; j++) {
            double ws[2], wt[2], *tw = B->tw[i * (B->n + 1) + j];
            side_weights(B->sn, B->m, i, ws);
            side_weights(B->tn, B->n, j, wt);
            v3_zero(tw);
            for (int a = 0; a < 2; a++)
                for (int b = 0; b < 2; b++) {
                    double w = ws[a] * wt[b];
                    if (w == 0.0) continue;
                    /* the cell before the node in s is i-1, whose corner is a = 1 */
                    double p[3];
                    proposal(B, i - 1 + (size_t)a, j - 1 + (size_t)b, (1 - a) + 2 * (1 - b), p);
                    v3_axpy(tw, w, p);
                }
        }
}

/* Cell (i,j) as its own patch over [0,1]^2. */
static coons_status make_cell(const build *B, size_t i, size_t j, coons_blend blend, double tol,
                              coons_patch **out, coons_error *err)
{
    double s0 = B->sn[i], s1 = B->sn[i + 1], t0 = B->tn[j], t1 = B->tn[j + 1];
    coons_curve *pc[4] = {0};
    coons_status rc = piece_new(B->row[j], s0, s1, &pc[COONS_SIDE_T0], err);
    if (!rc) rc = piece_new(B->row[j + 1], s0, s1, &pc[COONS_SIDE_T1], err);
    if (!rc) rc = piece_new(B->col[i], t0, t1, &pc[COONS_SIDE_S0], err);
    if (!rc) rc = piece_new(B->col[i + 1], t0, t1, &pc[COONS_SIDE_S1], err);
    double ds = s1 - s0, dt = t1 - t0;
    if (!rc && blend == COONS_BLEND_LINEAR) {
        rc = coons_patch_new_coons(pc, COONS_BLEND_LINEAR, tol, out, err);
    } else if (!rc) {
        coons_hermite_options ho = COONS_HERMITE_OPTIONS_INIT;
        ho.twist = COONS_TWIST_EXPLICIT;
        ho.tol = tol;
        for (int k = 0; k < 4; k++)
            v3_scale(ho.twists[k], B->tw[(i + (k & 1)) * (B->n + 1) + j + (k >> 1)], ds * dt);
        /* corner tangents come from the pieces, one-sided (piece_eval) */
        rc = coons_patch_new_hermite_coons(pc, &ho, out, err);
    }
    for (int k = 0; k < 4; k++) coons_curve_free(pc[k]);
    return rc;
}

static coons_status check_args(coons_curve *const *rows, size_t nr, coons_curve *const *cols,
                               size_t nc, const coons_network_options *o, coons_error *err)
{
    if (COONS__RECORD_CHECK(err, "network options", o->version, COONS_NETWORK_OPTIONS))
        return COONS_E_INVALID;
    if (!rows || !cols || nr < 2 || nc < 2)
        return coons__error_set(err, COONS_E_INVALID,
                                "network: needs at least 2 rows and 2 columns (%zu, %zu given)",
                                rows ? nr : 0, cols ? nc : 0);
    for (size_t k = 0; k < nr + nc; k++)
        if (!(k < nr ? rows[k] : cols[k - nr]))
            return coons__error_set(err, COONS_E_INVALID, "network: %s %zu is NULL",
                                    k < nr ? "row" : "column", k < nr ? k : k - nr);
    if (o->twist != COONS_TWIST_ZERO && o->twist != COONS_TWIST_ADINI &&
        o->twist != COONS_TWIST_BESSEL)
        return coons__error_set(err, COONS_E_INVALID,
                                "network: twist %d is not zero, adini or bessel", (int)o->twist);
    if (o->blend != COONS_BLEND_LINEAR && o->blend != COONS_BLEND_CUBIC)
        return coons__error_set(err, COONS_E_INVALID, "network: unknown blend %d", (int)o->blend);
    if (!(o->tol >= 0.0) || !isfinite(o->tol))
        return coons__error_set(err, COONS_E_INVALID,
                                "network: tolerance %g is not a finite number >= 0", o->tol);
    return COONS_OK;
}

static void net_bbox(const coons_patch *p, double lo[3], double hi[3])
{
    for (size_t k = 0; k < p->ncs + p->nct + 2; k++) {
        double a[3], b[3];
        coons_curve_control_bbox(p->net[k], a, b);
        bbox_add(lo, hi, a);
        bbox_add(lo, hi, b);
    }
}

coons_status coons_patch_new_network(coons_curve *const *rows, size_t nr,
                                     coons_curve *const *cols, size_t nc,
                                     const coons_network_options *opts, coons_patch **out,
                                     coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "network: out is NULL");
    *out = NULL;
    const coons_network_options defaults = COONS_NETWORK_OPTIONS_INIT;
    if (!opts) opts = &defaults;
    coons_status rc = check_args(rows, nr, cols, nc, opts, err);
    if (rc) return rc;
    coons_patch *p = NULL;
    if ((rc = coons__patch_alloc(&coons__network_kind, &p, err))) return rc;
    p->ncs = nc - 1;
    p->nct = nr - 1;
    p->blend = opts->blend;
    p->twist = opts->twist;
    build B = {nc - 1, nr - 1, NULL, NULL, (const coons_curve *const *)rows,
               (const coons_curve *const *)cols, NULL, NULL, opts->twist};
    if ((rc = nodes(opts->s_nodes, nc, "s_nodes", &p->sn, err)) ||
        (rc = nodes(opts->t_nodes, nr, "t_nodes", &p->tn, err)))
        goto done;
    B.sn = p->sn;
    B.tn = p->tn;
    p->net = coons__calloc(nr + nc, sizeof *p->net);
    p->cells = coons__calloc(B.m * B.n, sizeof *p->cells);
    B.X = coons__malloc_array((B.m + 1) * (B.n + 1), sizeof *B.X);
    B.tw = coons__malloc_array((B.m + 1) * (B.n + 1), sizeof *B.tw);
    if (!p->net || !p->cells || !B.X || !B.tw) {
        rc = coons__error_nomem(err);
        goto done;
    }
    for (size_t k = 0; k < nr + nc && !rc; k++)
        rc = coons_curve_copy(k < nr ? rows[k] : cols[k - nr], &p->net[k], err);
    if (rc) goto done;

    double lo[3], hi[3];
    bbox_empty(lo, hi);
    net_bbox(p, lo, hi);
    double tol = coons__tolerance(opts->tol, bbox_diag(lo, hi));
    size_t bi = 0, bj = 0;
    double dist = 0.0;
    if (coons__network_nodes_agree(B.row, nr, B.col, nc, p->sn, p->tn, tol, &bi, &bj, &dist)) {
        rc = coons__error_set(err, COONS_E_INCOMPATIBLE,
                              "node (%zu, %zu): row %zu at s = %g and column %zu at t = %g are "
                              "%g apart (tolerance %g)",
                              bi, bj, bj, p->sn[bi], bi, p->tn[bj], dist, tol);
        goto done;
    }
    for (size_t i = 0; i < nc; i++)
        for (size_t j = 0; j < nr; j++) {
            double a[3], b[3];
            coons_curve_eval(rows[j], p->sn[i], a);
            coons_curve_eval(cols[i], p->tn[j], b);
            for (int k = 0; k < 3; k++) B.X[i * nr + j][k] = 0.5 * (a[k] + b[k]);
        }
    node_twists(&B);
    /* The pieces meet where the nodes do: the cells' corner checks pass
     * with any tolerance the node check passed. */
    for (size_t i = 0; i < B.m && !rc; i++)
        for (size_t j = 0; j < B.n && !rc; j++)
            rc = make_cell(&B, i, j, opts->blend, 2.0 * tol, &p->cells[i * B.n + j], err);
done:
    coons__free(B.X);
    coons__free(B.tw);
    if (rc) {
        coons_patch_free(p);
        return rc;
    }
    *out = p;
    return COONS_OK;
}

/* ---- evaluation ------------------------------------------------------------ */

/* The cell index along nodes x[0..n] holding u (half-open spans, the last
 * closed) and the local parameter. */
static size_t locate(const double *x, size_t n, double u, double *loc)
{
    size_t lo = 0, hi = n; /* x[lo] <= u < x[hi] */
    while (hi - lo > 1) {
        size_t mid = (lo + hi) / 2;
        if (u >= x[mid])
            lo = mid;
        else
            hi = mid;
    }
    *loc = clamp01((u - x[lo]) / (x[lo + 1] - x[lo]));
    return lo;
}

/* Cell (i,j) at local (a,b), partials scaled to the network's (s,t). */
static void cell_eval(const coons_patch *p, size_t i, size_t j, double a, double b, int order,
                      double out[][3])
{
    const coons_patch *c = p->cells[i * p->nct + j];
    c->kind->eval(c, a, b, order, out);
    double ds = p->sn[i + 1] - p->sn[i], dt = p->tn[j + 1] - p->tn[j];
    if (order >= 1) {
        v3_scale(out[1], out[1], 1.0 / ds);
        v3_scale(out[2], out[2], 1.0 / dt);
    }
    if (order >= 2) {
        v3_scale(out[3], out[3], 1.0 / (ds * ds));
        v3_scale(out[4], out[4], 1.0 / (ds * dt));
        v3_scale(out[5], out[5], 1.0 / (dt * dt));
    }
}

static void eval(const coons_patch *p, double s, double t, int order, double out[][3])
{
    double a, b;
    size_t i = locate(p->sn, p->ncs, s, &a), j = locate(p->tn, p->nct, t, &b);
    cell_eval(p, i, j, a, b, order, out);
}

/* Point by point through eval: bitwise equal to it by construction. */
static coons_status grid(const coons_patch *p, const double *s, size_t ns, const double *t,
                         size_t nt, double *out, coons_error *err)
{
    (void)err;
    for (size_t i = 0; i < ns; i++)
        for (size_t j = 0; j < nt; j++) {
            double r[1][3];
            eval(p, clamp01(s[i]), clamp01(t[j]), 0, r);
            v3_copy(out + (i * nt + j) * 3, r[0]);
        }
    return COONS_OK;
}

/* Along s: the inner nodes and the rows' breakpoints; along t the same
 * with the columns. */
static void breaks(const coons_patch *p, int dir, coons__breaks *B)
{
    size_t n = dir == 0 ? p->ncs : p->nct;
    const double *x = dir == 0 ? p->sn : p->tn;
    for (size_t k = 1; k < n; k++) coons__breaks_add(B, x[k]);
    size_t first = dir == 0 ? 0 : p->nct + 1, count = dir == 0 ? p->nct + 1 : p->ncs + 1;
    for (size_t k = 0; k < count; k++) coons__curve_breaks(p->net[first + k], B);
}

/* Each cell maps its node interval linearly onto [0,1]: the cells'
 * spaces joined. */
static void space(const coons_patch *p, int dir, coons__space *S)
{
    *S = coons__space_poly(1);
    S->cont = 0; /* the cells meet with C0 at least */
    for (size_t i = 0; i < p->ncs * p->nct; i++)
        coons__space_join(S, coons__patch_space(p->cells[i], dir));
}

static coons_status copy(const coons_patch *p, coons_patch *d, coons_error *err)
{
    size_t nnet = p->ncs + p->nct + 2, ncell = p->ncs * p->nct;
    d->sn = d->tn = NULL;
    d->cells = NULL;
    d->net = NULL;
    d->sn = coons__memdup(p->sn, p->ncs + 1, sizeof(double));
    d->tn = coons__memdup(p->tn, p->nct + 1, sizeof(double));
    d->net = coons__calloc(nnet, sizeof *d->net);
    d->cells = coons__calloc(ncell, sizeof *d->cells);
    if (!d->sn || !d->tn || !d->net || !d->cells) return coons__error_nomem(err);
    coons_status rc = COONS_OK;
    for (size_t k = 0; k < nnet && !rc; k++) rc = coons_curve_copy(p->net[k], &d->net[k], err);
    for (size_t k = 0; k < ncell && !rc; k++)
        rc = coons_patch_copy(p->cells[k], &d->cells[k], err);
    return rc;
}

static void free_network(coons_patch *p)
{
    if (p->net)
        for (size_t k = 0; k < p->ncs + p->nct + 2; k++) coons_curve_free(p->net[k]);
    if (p->cells)
        for (size_t k = 0; k < p->ncs * p->nct; k++) coons_patch_free(p->cells[k]);
    coons__free(p->net);
    coons__free(p->cells);
    coons__free(p->sn);
    coons__free(p->tn);
}

const coons__patch_kind coons__network_kind = {
    .type = COONS_PATCH_NETWORK, .eval = eval, .grid = grid, .control_bbox = net_bbox,
    .breaks = breaks, .copy = copy, .free = free_network, .space = space};

void coons_network_options_init(coons_network_options *o)
{
    const coons_network_options d = COONS_NETWORK_OPTIONS_INIT;
    if (o) *o = d;
}

/* ---- seams ------------------------------------------------------------------ */

#define SEAM_SAMPLES 65

/* The angle in degrees between the planes spanned by (a1, a2) and (b1, b2)
 * (0 where a plane is undefined). */
static double plane_angle(const double a1[3], const double a2[3], const double b1[3],
                          const double b2[3])
{
    double na[3], nb[3], c[3];
    v3_cross(na, a1, a2);
    v3_cross(nb, b1, b2);
    if (!(v3_norm(na) > 0.0) || !(v3_norm(nb) > 0.0)) return 0.0;
    v3_cross(c, na, nb);
    return atan2(v3_norm(c), fabs(v3_dot(na, nb))) * (180.0 / 3.14159265358979323846);
}

/* The network under p's wrappers, the affine part to apply to vectors
 * (xf, or NULL) and the reparametrisation (swap, flips), composed. Only
 * one reparametrisation and any number of affine maps are composed; a
 * deeper nesting is measured in the innermost network's parameters. */
typedef struct view {
    const coons_patch *net;
    double M[9]; /* vectors map by M */
    int swap, flip_s, flip_t;
} view;

static void mat_mul_vec(const double M[9], const double v[3], double out[3])
{
    double r[3];
    for (int k = 0; k < 3; k++) r[k] = M[3 * k] * v[0] + M[3 * k + 1] * v[1] + M[3 * k + 2] * v[2];
    v3_copy(out, r);
}

static int unwrap(const coons_patch *p, view *V)
{
    static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    memcpy(V->M, I, sizeof I);
    V->swap = V->flip_s = V->flip_t = 0;
    int reparam = 0;
    while (p->inner) {
        if (p->kind == &coons__patch_transformed_kind) {
            double A[9] = {p->xf[0], p->xf[1], p->xf[2], p->xf[4], p->xf[5],
                           p->xf[6], p->xf[8], p->xf[9], p->xf[10]};
            double R[9];
            for (int r = 0; r < 3; r++)
                for (int c = 0; c < 3; c++)
                    R[3 * r + c] = V->M[3 * r] * A[c] + V->M[3 * r + 1] * A[3 + c] +
                                   V->M[3 * r + 2] * A[6 + c];
            memcpy(V->M, R, sizeof R);
        } else if (!reparam++) {
            V->swap = p->swap;
            V->flip_s = p->flip_s;
            V->flip_t = p->flip_t;
        }
        p = p->inner;
    }
    V->net = p;
    return p->kind == &coons__network_kind;
}

/* The seam of direction dir (0: column s = x[k]) at position y along it:
 * both sides' derivatives in the network's parameters, mapped by M. */
static void seam_sides(const view *V, int dir, size_t k, double y, double A[3][3],
                       double Bv[3][3])
{
    const coons_patch *p = V->net;
    double loc, o[3][3];
    size_t other = locate(dir == 0 ? p->tn : p->sn, dir == 0 ? p->nct : p->ncs, y, &loc);
    for (int side = 0; side < 2; side++) {
        size_t c = k - 1 + (size_t)side;
        double a = side ? 0.0 : 1.0;
        if (dir == 0)
            cell_eval(p, c, other, a, loc, 1, o);
        else
            cell_eval(p, other, c, loc, a, 1, o);
        double (*dst)[3] = side ? Bv : A;
        for (int q = 0; q < 3; q++) mat_mul_vec(V->M, o[q], dst[q]);
    }
}

coons_status coons_patch_network_seams(const coons_patch *p, coons_network_seam *seams,
                                       size_t cap, size_t *n, coons_error *err)
{
    view V;
    if (!p || !n) return coons__error_set(err, COONS_E_INVALID, "network seams: NULL argument");
    if (!unwrap(p, &V))
        return coons__error_set(err, COONS_E_INVALID, "network seams: the patch is a %s",
                                coons_patch_type_name(coons_patch_kind(p)));
    const coons_patch *q = V.net;
    size_t count = (q->ncs - 1) + (q->nct - 1), w = 0;
    for (int dir = 0; dir < 2; dir++) {
        size_t nk = dir == 0 ? q->ncs : q->nct;
        for (size_t k = 1; k < nk; k++, w++) {
            if (!seams || w >= cap) continue;
            double defect = 0.0, angle = 0.0;
            for (int m = 0; m < SEAM_SAMPLES; m++) {
                double y = (double)m / (SEAM_SAMPLES - 1), A[3][3], B[3][3];
                seam_sides(&V, dir, k, y, A, B);
                /* across a column the cross derivative is x_s, along it x_t */
                const double *ca = A[1 + dir], *cb = B[1 + dir];
                double big = fmax(v3_norm(ca), v3_norm(cb));
                if (big > 0.0) defect = fmax(defect, v3_dist(ca, cb) / big);
                angle = fmax(angle, plane_angle(A[1], A[2], B[1], B[2]));
            }
            coons_network_seam *S = &seams[w];
            /* in the patch's own parameters: a swap exchanges rows and columns */
            S->dir = V.swap ? 1 - dir : dir;
            int flip = dir == 0 ? V.flip_s : V.flip_t; /* flips act on the network's s, t */
            double x = dir == 0 ? q->sn[k] : q->tn[k];
            S->index = k;
            S->param = flip ? 1.0 - x : x;
            S->c1_defect = defect;
            S->g1_angle = angle;
            S->face = -1;
        }
    }
    *n = count;
    return COONS_OK;
}

/* ---- the networks of a body ------------------------------------------------ */

/* Seams of patch f (a network or not) seen through the linear map A (NULL:
 * none), appended at seams[*w] as face `face`. */
static coons_status face_seams(const coons_patch *f, const double *A, int face,
                               coons_network_seam *seams, size_t cap, size_t *w,
                               coons_error *err)
{
    view V;
    if (!unwrap(f, &V)) return COONS_OK;
    coons_patch *g = NULL;
    coons_status rc = A ? coons_patch_new_transformed(f, A, &g, err) : COONS_OK;
    if (rc) return rc;
    const coons_patch *q = g ? g : f;
    size_t n = 0;
    rc = coons_patch_network_seams(q, NULL, 0, &n, err);
    coons_network_seam *tmp = rc ? NULL : coons__malloc_array(n ? n : 1, sizeof *tmp);
    if (!rc && !tmp) rc = coons__error_nomem(err);
    if (!rc) rc = coons_patch_network_seams(q, tmp, n, &n, err);
    for (size_t k = 0; !rc && k < n; k++, (*w)++)
        if (seams && *w < cap) {
            seams[*w] = tmp[k];
            seams[*w].face = face;
        }
    coons__free(tmp);
    coons_patch_free(g);
    return rc;
}

coons_status coons_body_network_seams(const coons_body *b, coons_network_seam *seams,
                                      size_t cap, size_t *n, coons_error *err)
{
    if (!b || !n) return coons__error_set(err, COONS_E_INVALID, "network seams: NULL argument");
    /* the linear part of the composed transforms, as a 3 x 4 map */
    double A[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    int mapped = 0;
    while (b->inner) {
        double R[12] = {0};
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                for (int k = 0; k < 3; k++) R[4 * r + c] += A[4 * r + k] * b->xf[4 * k + c];
        memcpy(A, R, sizeof A);
        mapped = 1;
        b = b->inner;
    }
    size_t w = 0;
    coons_status rc = COONS_OK;
    if (b->kind == &coons__body2_kind)
        for (int f = 0; f < 6 && !rc; f++)
            rc = face_seams(b->face[f], mapped ? A : NULL, f, seams, cap, &w, err);
    else if (b->kind == &coons__shell_kind)
        rc = face_seams(b->face[0], mapped ? A : NULL, -1, seams, cap, &w, err);
    if (!rc) *n = w;
    return rc;
}
