/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The metamorphosis of seed 000 section 4 (Fig. 10, cube to spool): "the
 * grid deformation, by moving a grid point along the path, defines the
 * metamorphosis, similar to the motion path in animation". Read pointwise:
 * M(u,v,w; t) = sum_k W_k(t) K_k(u,v,w), so that for keys of one control
 * structure it is the body whose control points move along the path (the
 * maps are linear in their control points), and for keys of any types the
 * same blend of their maps. The Jacobian is the same blend of the keys'
 * Jacobians, exact.
 *
 * The path (coons-model(5), "Resolved details"): linear, or on each
 * interval [at_i, at_i+1] of length h the cubic Hermite
 *   h00(s) K_i + h h10(s) m_i + h01(s) K_i+1 + h h11(s) m_i+1,  s = (t - at_i)/h,
 * with the non-uniform Catmull-Rom tangents m_k = (K_k+1 - K_k-1) /
 * (at_k+1 - at_k-1), one-sided at the ends; C1 in t. Each W_k is the sum
 * A0 h00 + A1 h10 + A2 h01 + A3 h11 over the four Hermite terms, evaluated
 * in that order, so the OpenSCAD animation (scad_morph.c), which writes the
 * same sums, reproduces the weights bitwise. At a key time the Hermite
 * basis is exactly (1,0,0,0) or (0,0,1,0), so the key is reproduced exactly.
 */
#include <string.h>

#include "body_impl.h"
#include "model_impl.h"
#include "morph.h"

static coons_status check_times(size_t n, const double *at, coons_error *err)
{
    if (n < 2 || n > COONS_MORPH_MAX_KEYS)
        return coons__error_set(err, COONS_E_INVALID,
                                "morph: %zu keys; a morph takes 2 to %d keys", n,
                                COONS_MORPH_MAX_KEYS);
    if (!at) return COONS_OK;
    for (size_t k = 0; k < n; k++)
        if (!isfinite(at[k]))
            return coons__error_set(err, COONS_E_INVALID, "morph: key time %zu is not finite", k);
    if (at[0] != 0.0 || at[n - 1] != 1.0)
        return coons__error_set(err, COONS_E_INVALID,
                                "morph: key times must start at exactly 0 and end at exactly 1 "
                                "(they run from %.17g to %.17g)",
                                at[0], at[n - 1]);
    for (size_t k = 1; k < n; k++)
        if (!(at[k] > at[k - 1]))
            return coons__error_set(err, COONS_E_INVALID,
                                    "morph: key times must increase strictly (time %zu is %.17g, "
                                    "time %zu is %.17g)",
                                    k - 1, at[k - 1], k, at[k]);
    return COONS_OK;
}

static double time_of(size_t n, const double *at, size_t k)
{
    return at ? at[k] : (k == n - 1 ? 1.0 : (double)k / (double)(n - 1));
}

size_t coons__morph_interval(size_t n, const double *at, double t)
{
    size_t i = 0;
    while (i + 2 < n && t >= time_of(n, at, i + 1)) i++;
    return i;
}

size_t coons__morph_terms(size_t n, const double *at, int path, size_t i, double A[4][4],
                         size_t *first)
{
    /* A[j][q]: the share of key first + j in Hermite term q (K_i, h m_i,
     * K_i+1, h m_i+1) of interval i; only keys i-1 .. i+2 take part. */
    size_t f = i ? i - 1 : 0, end = i + 3 < n ? i + 3 : n;
    memset(A, 0, 16 * sizeof A[0][0]);
    A[i - f][0] = 1.0;
    A[i + 1 - f][2] = 1.0;
    *first = f;
    if (path == COONS_MORPH_SMOOTH && n > 2) {
        double h = time_of(n, at, i + 1) - time_of(n, at, i);
        for (int e = 0; e < 2; e++) {
            size_t k = i + (size_t)e, lo = k ? k - 1 : 0, hi = k + 1 < n ? k + 1 : n - 1;
            double q = h / (time_of(n, at, hi) - time_of(n, at, lo));
            A[hi - f][1 + 2 * e] += q;
            A[lo - f][1 + 2 * e] -= q;
        }
    }
    return end - f;
}

/* The Hermite basis at s (and its s-derivatives); linear paths use
 * (1 - s, 0, s, 0), so that they are piecewise linear to rounding. */
static void basis(int cubic, double s, double H[4], double dH[4])
{
    if (!cubic) {
        H[0] = 1.0 - s, H[1] = 0.0, H[2] = s, H[3] = 0.0;
        dH[0] = -1.0, dH[1] = 0.0, dH[2] = 1.0, dH[3] = 0.0;
        return;
    }
    double s2 = s * s, s3 = s2 * s;
    H[0] = 2 * s3 - 3 * s2 + 1;
    H[1] = s3 - 2 * s2 + s;
    H[2] = -2 * s3 + 3 * s2;
    H[3] = s3 - s2;
    dH[0] = 6 * s2 - 6 * s;
    dH[1] = 3 * s2 - 4 * s + 1;
    dH[2] = -6 * s2 + 6 * s;
    dH[3] = 3 * s2 - 2 * s;
}

/* The weights of the keys first .. first + count - 1 of a valid path at
 * t (the others are 0), and their t-derivatives. */
static size_t local_weights(size_t n, const double *at, int path, double t, size_t *first,
                            double w[4], double dw[4])
{
    t = clamp01(t);
    size_t i = coons__morph_interval(n, at, t);
    double t0 = time_of(n, at, i), h = time_of(n, at, i + 1) - t0;
    double s = (t - t0) / h, H[4], dH[4], A[4][4];
    if (s > 1.0) s = 1.0;
    basis(path == COONS_MORPH_SMOOTH && n > 2, s, H, dH);
    size_t cnt = coons__morph_terms(n, at, path, i, A, first);
    for (size_t j = 0; j < cnt; j++) {
        const double *a = A[j];
        w[j] = a[0] * H[0] + a[1] * H[1] + a[2] * H[2] + a[3] * H[3];
        dw[j] = (a[0] * dH[0] + a[1] * dH[1] + a[2] * dH[2] + a[3] * dH[3]) / h;
    }
    return cnt;
}

coons_status coons_morph_weights(size_t nkeys, const double *at, coons_morph_path path,
                                 double t, double *w, double *dw, coons_error *err)
{
    if (!w) return coons__error_set(err, COONS_E_INVALID, "morph weights: w is NULL");
    if (path != COONS_MORPH_LINEAR && path != COONS_MORPH_SMOOTH)
        return coons__error_set(err, COONS_E_INVALID, "morph: unknown path %d", (int)path);
    coons_status rc = check_times(nkeys, at, err);
    if (rc) return rc;
    double lw[4], ldw[4];
    size_t first = 0, cnt = local_weights(nkeys, at, (int)path, t, &first, lw, ldw);
    for (size_t k = 0; k < nkeys; k++) {
        int in = k >= first && k < first + cnt;
        w[k] = in ? lw[k - first] : 0.0;
        if (dw) dw[k] = in ? ldw[k - first] : 0.0;
    }
    return COONS_OK;
}

static void eval(const coons_body *b, double u, double v, double w, double out[3],
                 double d[3][3])
{
    double W[4], dW[4], p[3], dk[3][3];
    size_t first = 0, cnt = local_weights(b->nkeys, b->at, b->path, b->t, &first, W, dW);
    memset(out, 0, 3 * sizeof *out);
    if (d) memset(d, 0, 9 * sizeof **d);
    for (size_t j = 0; j < cnt; j++) {
        const coons_body *K = b->keys[first + j];
        K->kind->eval(K, u, v, w, p, d ? dk : NULL);
        for (int c = 0; c < 3; c++) out[c] += W[j] * p[c];
        if (d)
            for (int q = 0; q < 3; q++)
                for (int c = 0; c < 3; c++) d[q][c] += W[j] * dk[q][c];
    }
}

static coons_status grid(const coons_body *b, const double *u, size_t nu, const double *v,
                         size_t nv, const double *w, size_t nw, double *out, coons_error *err)
{
    size_t np = nu * nv * nw;
    double W[4], dW[4];
    size_t first = 0, cnt = local_weights(b->nkeys, b->at, b->path, b->t, &first, W, dW);
    double *g = coons__malloc_array(np, 3 * sizeof *g);
    if (!g) return coons__error_nomem(err);
    memset(out, 0, np * 3 * sizeof *out);
    coons_status rc = COONS_OK;
    for (size_t j = 0; j < cnt && !rc; j++) {
        const coons_body *K = b->keys[first + j];
        rc = K->kind->grid(K, u, nu, v, nv, w, nw, g, err);
        for (size_t i = 0; !rc && i < 3 * np; i++) out[i] += W[j] * g[i];
    }
    coons__free(g);
    return rc;
}

/* The partials (jac) as the same blend of the keys' partials on the grid,
 * each key by its own grid path; det J (det) of the blended partials, as
 * coons_body_eval_jacobian() takes it from eval(). */
static coons_status det_grid(const coons_body *b, const double *u, size_t nu, const double *v,
                             size_t nv, const double *w, size_t nw, double *det, double *jac,
                             coons_error *err)
{
    size_t np = nu * nv * nw;
    double W[4], dW[4];
    size_t first = 0, cnt = local_weights(b->nkeys, b->at, b->path, b->t, &first, W, dW);
    double *g = coons__malloc_array(np, 9 * sizeof *g);
    double *d = jac ? jac : coons__malloc_array(np, 9 * sizeof *d);
    if (!g || !d) {
        coons__free(g);
        if (d != jac) coons__free(d);
        return coons__error_nomem(err);
    }
    memset(d, 0, np * 9 * sizeof *d);
    coons_status rc = COONS_OK;
    for (size_t j = 0; j < cnt && !rc; j++) {
        const coons_body *K = b->keys[first + j];
        rc = coons__body_jac_grid(K, u, nu, v, nv, w, nw, g, err);
        for (size_t i = 0; !rc && i < 9 * np; i++) d[i] += W[j] * g[i];
    }
    if (!rc && det)
        for (size_t i = 0; i < np; i++) {
            double x[3];
            v3_cross(x, d + 9 * i + 3, d + 9 * i + 6);
            det[i] = v3_dot(d + 9 * i, x);
        }
    coons__free(g);
    if (d != jac) coons__free(d);
    return rc;
}

/* The union of the keys' breakpoints: the blend may lose smoothness
 * wherever one of its keys does. */
static void breaks(const coons_body *b, int d, coons__breaks *B)
{
    for (size_t k = 0; k < b->nkeys; k++)
        if (b->keys[k]->kind->breaks) b->keys[k]->kind->breaks(b->keys[k], d, B);
}

static coons_status copy(const coons_body *b, coons_body *d, coons_error *err)
{
    d->keys = NULL;
    d->at = NULL;
    size_t n = b->nkeys;
    d->nkeys = 0;
    d->keys = coons__calloc(n, sizeof *d->keys);
    if (!d->keys) return coons__error_nomem(err);
    if (b->at) {
        d->at = coons__malloc_array(n, sizeof *d->at);
        if (!d->at) return coons__error_nomem(err);
        memcpy(d->at, b->at, n * sizeof *d->at);
    }
    d->nkeys = n;
    for (size_t k = 0; k < n; k++) {
        coons_status rc = coons_body_copy(b->keys[k], &d->keys[k], err);
        if (rc) return rc;
    }
    return COONS_OK;
}

static void release(coons_body *b)
{
    for (size_t k = 0; b->keys && k < b->nkeys; k++) coons_body_free(b->keys[k]);
    coons__free(b->keys);
    coons__free(b->at);
}

/* At a fixed time a morph is a fixed combination of its keys. */
static void space(const coons_body *b, int d, coons__space *S)
{
    *S = coons__space_poly(1);
    for (size_t k = 0; k < b->nkeys; k++) coons__space_join(S, coons__body_space(b->keys[k], d));
}

const coons__body_kind coons__morph_kind = {
    COONS_BODY_MORPH, eval, grid, det_grid, breaks, copy, release, space, NULL,
};

coons_status coons_body_new_morph(coons_body *const *keys, size_t nkeys, const double *at,
                                  coons_morph_path path, double t, coons_body **out,
                                  coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "morph: out is NULL");
    *out = NULL;
    if (!keys) return coons__error_set(err, COONS_E_INVALID, "morph: keys is NULL");
    coons_status rc = check_times(nkeys, at, err);
    if (rc) return rc;
    for (size_t k = 0; k < nkeys; k++)
        if (!keys[k]) return coons__error_set(err, COONS_E_INVALID, "morph: key %zu is NULL", k);
    if (path != COONS_MORPH_LINEAR && path != COONS_MORPH_SMOOTH)
        return coons__error_set(err, COONS_E_INVALID, "morph: unknown path %d", (int)path);
    if (!(t >= 0.0 && t <= 1.0))
        return coons__error_set(err, COONS_E_INVALID, "morph: time %.17g is outside [0, 1]", t);
    coons_body *m = NULL;
    if ((rc = coons__body_alloc(&coons__morph_kind, COONS_BLEND_LINEAR, &m, err))) return rc;
    m->path = (int)path;
    m->t = t;
    m->keys = coons__calloc(nkeys, sizeof *m->keys);
    if (!m->keys) {
        coons_body_free(m);
        return coons__error_nomem(err);
    }
    m->nkeys = nkeys;
    if (at) {
        if (!(m->at = coons__malloc_array(nkeys, sizeof *m->at))) {
            coons_body_free(m);
            return coons__error_nomem(err);
        }
        memcpy(m->at, at, nkeys * sizeof *at);
    }
    for (size_t k = 0; k < nkeys; k++) {
        if ((rc = coons_body_copy(keys[k], &m->keys[k], err))) {
            coons_body_free(m);
            return rc;
        }
        for (int c = 0; c < 3; c++) {
            if (keys[k]->lo[c] < m->lo[c]) m->lo[c] = keys[k]->lo[c];
            if (keys[k]->hi[c] > m->hi[c]) m->hi[c] = keys[k]->hi[c];
        }
    }
    *out = m;
    return COONS_OK;
}

/* The morph a body is, through transforms, or NULL. */
static const coons_body *as_morph(const coons_body *b)
{
    while (b && b->kind != &coons__morph_kind) b = b->inner;
    return b;
}

size_t coons_body_morph_keys(const coons_body *b)
{
    const coons_body *m = as_morph(b);
    return m ? m->nkeys : 0;
}

const coons_body *coons_body_morph_key(const coons_body *b, size_t k, double *at)
{
    const coons_body *m = as_morph(b);
    if (!m || k >= m->nkeys) return NULL;
    if (at) *at = time_of(m->nkeys, m->at, k);
    return m->keys[k];
}

coons_status coons_body_morph_info(const coons_body *b, coons_morph_path *path, double *t,
                                   coons_error *err)
{
    const coons_body *m = as_morph(b);
    if (!m) return coons__error_set(err, COONS_E_INVALID, "the body is not a morph");
    if (path) *path = (coons_morph_path)m->path;
    if (t) *t = m->t;
    return COONS_OK;
}

/* Sets the time of every morph in b, keys and wrapped bodies included. */
static void set_time(coons_body *b, double t)
{
    for (; b; b = b->inner) {
        if (b->kind != &coons__morph_kind) continue;
        b->t = t;
        for (size_t k = 0; k < b->nkeys; k++) set_time(b->keys[k], t);
    }
}

coons_status coons_body_at_time(const coons_body *b, double t, coons_body **out,
                                coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "body at time: out is NULL");
    *out = NULL;
    if (!b) return coons__error_set(err, COONS_E_INVALID, "body at time: body is NULL");
    if (!(t >= 0.0 && t <= 1.0))
        return coons__error_set(err, COONS_E_INVALID, "time %.17g is outside [0, 1]", t);
    coons_status rc = coons_body_copy(b, out, err);
    if (!rc) set_time(*out, t);
    return rc;
}

coons_status coons_model_set_time(coons_model *m, double t, coons_error *err)
{
    if (!m) return coons__error_set(err, COONS_E_INVALID, "model set time: model is NULL");
    if (!(t >= 0.0 && t <= 1.0))
        return coons__error_set(err, COONS_E_INVALID, "time %.17g is outside [0, 1]", t);
    for (size_t i = 0; i < m->nbodies; i++) set_time(m->bodies[i], t);
    return COONS_OK;
}

size_t coons_model_morph_count(const coons_model *m)
{
    size_t n = 0;
    for (size_t i = 0; m && i < m->nbodies; i++) n += as_morph(m->bodies[i]) != NULL;
    return n;
}
