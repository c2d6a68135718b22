/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The loader's values: numbers, degrees, points and vectors, rectangular
 * nets of them (curves, surfaces, volumes), knot vectors, blends, and the
 * data of tensor-product surfaces and volumes, each checked against the
 * model format (coons-model(5)) with a message that says what was expected.
 */
#include <stdio.h>
#include <string.h>

#include "affine.h"
#include "loader.h"

coons_status coons__ld_number(coons__ld *L, size_t tok, double *v)
{
    if (coons__json_type_of(L->j, tok) != COONS__JSON_NUMBER)
        return coons__ld_fail(L, tok, COONS_E_INVALID, "expected a number, found %s",
                              coons__ld_kind(L, tok));
    coons_status rc = coons__json_number(L->j, tok, v);
    if (rc == COONS_OK) return COONS_OK;
    size_t len;
    const char *s = coons__json_text(L->j, tok, &len);
    if (rc == COONS_E_INVALID)
        return coons__ld_fail(L, tok, COONS_E_INVALID,
                              "the number %.*s is outside the range of a double (about "
                              "+-1.8e308): numbers must be finite",
                              len > 40 ? 40 : (int)len, s);
    return coons__ld_fail(L, tok, COONS_E_INTERNAL, "cannot convert the number %.*s",
                          len > 40 ? 40 : (int)len, s);
}

/* 3.0 counts as 3 (JSON has one number type). */
coons_status coons__ld_degree(coons__ld *L, size_t tok, int *p)
{
    double v;
    coons_status rc = coons__ld_number(L, tok, &v);
    if (rc) return rc;
    if (v != floor(v))
        return coons__ld_fail(L, tok, COONS_E_INVALID,
                              "a degree must be an integer, found %.17g", v);
    if (v < 1)
        return coons__ld_fail(L, tok, COONS_E_INVALID, "a degree must be >= 1, found %.17g", v);
    if (v > COONS_SPLINE_MAX_DEGREE)
        return coons__ld_fail(L, tok, COONS_E_LIMIT, "degree %.17g is above the limit of %d", v,
                              COONS_SPLINE_MAX_DEGREE);
    *p = (int)v;
    return COONS_OK;
}

coons_status coons__ld_vec(coons__ld *L, size_t tok, int leaf, double out[3])
{
    const char *noun = leaf == COONS__LD_POINT ? "a point" : "a vector";
    if (coons__json_type_of(L->j, tok) != COONS__JSON_ARRAY)
        return coons__ld_fail(L, tok, COONS_E_INVALID,
                              "expected %s [x, y, z] or [x, y], found %s", noun,
                              coons__ld_kind(L, tok));
    size_t n = coons__json_size(L->j, tok);
    if (n != 2 && n != 3)
        return coons__ld_fail(L, tok, COONS_E_INVALID,
                              "expected %s of 2 or 3 numbers ([x, y] means z = 0), found %zu "
                              "values",
                              noun, n);
    size_t e = tok + 1;
    out[2] = 0.0;
    for (size_t i = 0; i < n; i++, e = coons__json_next(L->j, e)) {
        size_t old = coons__ld_push_index(L, i);
        coons_status rc = coons__ld_number(L, e, &out[i]);
        coons__ld_pop(L, old);
        if (rc) return rc;
    }
    if (leaf == COONS__LD_POINT && L->bbox_on && !L->build) {
        /* the point as instanced: under the transforms of the references (read_ref.c) */
        double p[3];
        v3_copy(p, out);
        if (L->xf_on) coons__affine_point(L->xf, p, p);
        bbox_add(L->lo, L->hi, p);
    }
    return COONS_OK;
}

/* ---- nets ---------------------------------------------------------------- */

const char *coons__ld_axis_name(int dims, int d)
{
    static const char *const s[] = {"s", "t"}, *const u[] = {"u", "v", "w"};
    return dims == 2 ? s[d] : u[d];
}

/* The values of a net whose shape has been checked. */
static coons_status net_walk(coons__ld *L, const coons__ld_netspec *ns, size_t tok, int d,
                             const size_t *shape, double *out, size_t *pos)
{
    if (coons__json_type_of(L->j, tok) != COONS__JSON_ARRAY)
        return coons__ld_fail(L, tok, COONS_E_INVALID, "expected an array of %s, found %s",
                              d + 1 < ns->dims ? "arrays" : ns->noun, coons__ld_kind(L, tok));
    size_t n = coons__json_size(L->j, tok);
    if (n != shape[d])
        return coons__ld_fail(L, tok, COONS_E_INVALID,
                              "found %zu entries here and %zu in the first row: the %s of %s "
                              "must form a rectangular net",
                              n, shape[d], ns->noun, ns->what);
    size_t e = tok + 1;
    coons_status rc = COONS_OK;
    for (size_t i = 0; i < n && !rc; i++, e = coons__json_next(L->j, e)) {
        size_t old = coons__ld_push_index(L, i);
        if (d + 1 < ns->dims)
            rc = net_walk(L, ns, e, d + 1, shape, out, pos);
        else if (ns->leaf == COONS__LD_WEIGHT) {
            double *w = out + (*pos)++;
            rc = coons__ld_number(L, e, w);
            if (!rc && !(*w > 0.0))
                rc = coons__ld_fail(L, e, COONS_E_INVALID,
                                    "weight %.17g is not > 0: weights must be positive", *w);
        } else {
            rc = coons__ld_vec(L, e, ns->leaf, out + 3 * (*pos)++);
        }
        coons__ld_pop(L, old);
    }
    return rc;
}

/* The count n along direction d of the net at t (its first row), against
 * the spec and the limits; *total is the product so far. */
static coons_status net_count(coons__ld *L, const coons__ld_netspec *ns, size_t t, int d,
                              size_t n, size_t total)
{
    char along[16] = "";
    if (ns->dims > 1) snprintf(along, sizeof along, " along %s", coons__ld_axis_name(ns->dims, d));
    if (ns->fixed && n != ns->fixed[d])
        return coons__ld_fail(L, t, COONS_E_INVALID,
                              "expected %zu %s%s (one per control point), found %zu",
                              ns->fixed[d], ns->noun, along, n);
    if (ns->exact && n != ns->min)
        return coons__ld_fail(L, t, COONS_E_INVALID, "%s needs exactly %zu %s, found %zu",
                              ns->what, ns->min, ns->noun, n);
    if (n < ns->min)
        return coons__ld_fail(L, t, COONS_E_INVALID, "%s needs at least %zu %s%s, found %zu",
                              ns->what, ns->min, ns->noun, along, n);
    if (n > L->max_points || (n && total > L->max_points / n))
        return coons__ld_fail(L, t, COONS_E_LIMIT,
                              "%s has more than %zu %s: above the limit of %zu points per "
                              "curve, surface or volume (raise max_points; coons2stl "
                              "--max-points N)",
                              ns->what, L->max_points, ns->noun, L->max_points);
    if (ns->maxdir && n > ns->maxdir)
        return coons__ld_fail(L, t, COONS_E_LIMIT,
                              "%s has %zu %s%s: its degree %zu is above the limit of %d",
                              ns->what, n, ns->noun, along, n - 1, COONS_SPLINE_MAX_DEGREE);
    return COONS_OK;
}

/* The shape, from the first row along each direction. */
static coons_status net_shape(coons__ld *L, size_t tok, const coons__ld_netspec *ns,
                              size_t shape[3], size_t *total)
{
    size_t t = tok, old = L->plen;
    coons_status rc = COONS_OK;
    shape[0] = shape[1] = shape[2] = 1;
    *total = 1;
    for (int d = 0; d < ns->dims && !rc; d++) {
        if (coons__json_type_of(L->j, t) != COONS__JSON_ARRAY) {
            rc = coons__ld_fail(L, t, COONS_E_INVALID, "expected an array of %s, found %s",
                                d + 1 < ns->dims ? "arrays" : ns->noun, coons__ld_kind(L, t));
            break;
        }
        size_t n = coons__json_size(L->j, t);
        shape[d] = n;
        if ((rc = net_count(L, ns, t, d, n, *total))) break;
        *total *= n;
        if (d + 1 < ns->dims) {
            coons__ld_push_index(L, 0);
            t = t + 1;
        }
    }
    coons__ld_pop(L, old);
    return rc;
}

coons_status coons__ld_net(coons__ld *L, size_t tok, const coons__ld_netspec *ns,
                           size_t shape[3], double **out)
{
    *out = NULL;
    size_t total;
    coons_status rc = net_shape(L, tok, ns, shape, &total);
    if (rc) return rc;
    double *buf =
        coons__malloc_array(total, (ns->leaf == COONS__LD_WEIGHT ? 1 : 3) * sizeof(double));
    if (!buf) return coons__ld_fail(L, tok, COONS_E_NOMEM, "out of memory reading %s", ns->noun);
    size_t pos = 0;
    rc = net_walk(L, ns, tok, 0, shape, buf, &pos);
    if (rc) {
        coons__free(buf);
        return rc;
    }
    *out = buf;
    return COONS_OK;
}

coons_status coons__ld_net_key(coons__ld *L, size_t val, const char *key,
                               const coons__ld_netspec *ns, size_t shape[3], double **out)
{
    size_t old = coons__ld_push_key(L, key);
    coons_status rc = coons__ld_net(L, val, ns, shape, out);
    coons__ld_pop(L, old);
    return rc;
}

/* ---- knots and blends ---------------------------------------------------- */

/* Knots of degree p for ncp control points: ncp + p + 1 non-decreasing
 * values, no value more than p+1 times, non-empty domain [k_p, k_ncp]. */
coons_status coons__ld_knots(coons__ld *L, size_t tok, int p, size_t ncp, double **out)
{
    *out = NULL;
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_ARRAY, "an array of knots");
    if (rc) return rc;
    size_t need_n = ncp + (size_t)p + 1, n = coons__json_size(L->j, tok);
    if (n != need_n)
        return coons__ld_fail(L, tok, COONS_E_INVALID,
                              "expected %zu knots (number of points %zu + degree %d + 1), "
                              "found %zu",
                              need_n, ncp, p, n);
    double *k = coons__malloc_array(n, sizeof(double));
    if (!k) return coons__ld_fail(L, tok, COONS_E_NOMEM, "out of memory reading knots");
    size_t e = tok + 1, run = 1;
    for (size_t i = 0; i < n && !rc; i++, e = coons__json_next(L->j, e)) {
        size_t old = coons__ld_push_index(L, i);
        rc = coons__ld_number(L, e, &k[i]);
        if (!rc && i > 0) {
            if (k[i] < k[i - 1])
                rc = coons__ld_fail(L, e, COONS_E_INVALID,
                                    "knot %zu (%.17g) is smaller than knot %zu (%.17g): knots "
                                    "must be non-decreasing",
                                    i, k[i], i - 1, k[i - 1]);
            else if (k[i] == k[i - 1] && ++run > (size_t)p + 1)
                rc = coons__ld_fail(L, e, COONS_E_INVALID,
                                    "the knot value %.17g appears more than degree + 1 = %d "
                                    "times",
                                    k[i], p + 1);
            else if (k[i] != k[i - 1])
                run = 1;
        }
        coons__ld_pop(L, old);
    }
    if (!rc && !(k[p] < k[ncp]))
        rc = coons__ld_fail(L, tok, COONS_E_INVALID,
                            "the domain [knots[%d], knots[%zu]] = [%.17g, %.17g] is empty: it "
                            "must have a positive length",
                            p, ncp, k[p], k[ncp]);
    if (rc) {
        coons__free(k);
        return rc;
    }
    *out = k;
    return COONS_OK;
}

coons_status coons__ld_keyword(coons__ld *L, size_t tok, const char *key, const char *a,
                              const char *b, int *out)
{
    char expected[64];
    snprintf(expected, sizeof expected, "\"%s\" or \"%s\"", a, b);
    size_t old = coons__ld_push_key(L, key);
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_STRING, expected);
    if (!rc) {
        if (coons__json_string_eq(L->j, tok, a))
            *out = 0;
        else if (coons__json_string_eq(L->j, tok, b))
            *out = 1;
        else {
            char s[64];
            coons__ld_text_of(L, tok, s, sizeof s);
            rc = coons__ld_fail(L, tok, COONS_E_INVALID, "unknown %s \"%s\"; expected %s", key,
                                s, expected);
        }
    }
    coons__ld_pop(L, old);
    return rc;
}

coons_status coons__ld_blend(coons__ld *L, size_t tok, coons_blend *out)
{
    *out = COONS_BLEND_LINEAR;
    if (!tok) return COONS_OK;
    int k = 0;
    coons_status rc = coons__ld_keyword(L, tok, "blend", "linear", "cubic", &k);
    if (!rc) *out = k ? COONS_BLEND_CUBIC : COONS_BLEND_LINEAR;
    return rc;
}

/* ---- tensor-product surfaces and volumes --------------------------------- */

/* A per-direction array of `dims` items (degrees or knot vectors). */
static coons_status tuple(coons__ld *L, size_t tok, size_t dims, const char *desc)
{
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_ARRAY, desc);
    if (rc) return rc;
    if (coons__json_size(L->j, tok) != dims)
        return coons__ld_fail(L, tok, COONS_E_INVALID, "expected %s, found an array of %zu values",
                              desc, coons__json_size(L->j, tok));
    return COONS_OK;
}

static coons_status tensor_degrees(coons__ld *L, const coons__ld_obj *o, int dims, size_t vdeg,
                                   int deg[3])
{
    coons_status rc;
    if ((rc = coons__ld_need(L, o->tok, vdeg, "degree", o->need))) return rc;
    size_t old = coons__ld_push_key(L, "degree");
    char desc[64];
    snprintf(desc, sizeof desc, "an array of %d degrees %s", dims,
             dims == 2 ? "[p, q]" : "[l, m, n]");
    rc = tuple(L, vdeg, (size_t)dims, desc);
    size_t e = vdeg + 1;
    for (int d = 0; d < dims && !rc; d++, e = coons__json_next(L->j, e)) {
        size_t o2 = coons__ld_push_index(L, (size_t)d);
        rc = coons__ld_degree(L, e, &deg[d]);
        coons__ld_pop(L, o2);
    }
    coons__ld_pop(L, old);
    return rc;
}

static coons_status tensor_knots(coons__ld *L, int dims, size_t vknots, coons__ld_tensor *t)
{
    size_t old = coons__ld_push_key(L, "knots");
    char desc[64];
    snprintf(desc, sizeof desc, "an array of %d knot vectors", dims);
    coons_status rc = tuple(L, vknots, (size_t)dims, desc);
    size_t e = vknots + 1;
    for (int d = 0; d < dims && !rc; d++, e = coons__json_next(L->j, e)) {
        size_t o2 = coons__ld_push_index(L, (size_t)d);
        rc = coons__ld_knots(L, e, t->deg[d], t->n[d], &t->kn[d]);
        coons__ld_pop(L, o2);
    }
    coons__ld_pop(L, old);
    return rc;
}

/* val: points, degree, knots, weights. */
coons_status coons__ld_tensor_read(coons__ld *L, const coons__ld_obj *o, int dims,
                                   int is_bspline, const size_t val[4], coons__ld_tensor *t)
{
    coons_status rc;
    memset(t, 0, sizeof *t);
    t->deg[0] = t->deg[1] = t->deg[2] = 1;
    if (is_bspline && (rc = tensor_degrees(L, o, dims, val[1], t->deg))) return rc;
    if ((rc = coons__ld_need(L, o->tok, val[0], "points", o->need))) return rc;
    coons__ld_netspec ns = {dims, COONS__LD_POINT, NULL, 2, 0,
                            is_bspline ? 0 : COONS_SPLINE_MAX_DEGREE + 1, o->what, "points"};
    if ((rc = coons__ld_net_key(L, val[0], "points", &ns, t->n, &t->pts))) return rc;
    if (is_bspline)
        for (int d = 0; d < dims; d++)
            if (t->n[d] < (size_t)t->deg[d] + 1) {
                size_t old = coons__ld_push_key(L, "points");
                const char *ax = coons__ld_axis_name(dims, d);
                rc = coons__ld_fail(L, val[0], COONS_E_INVALID,
                                    "%s of degree %d along %s needs at least %d points along "
                                    "%s, found %zu",
                                    o->what, t->deg[d], ax, t->deg[d] + 1, ax, t->n[d]);
                coons__ld_pop(L, old);
                return rc;
            }
    if (val[2] && (rc = tensor_knots(L, dims, val[2], t))) return rc;
    if (val[3]) {
        coons__ld_netspec ws = {dims, COONS__LD_WEIGHT, t->n, 0, 0, 0, o->what, "weights"};
        size_t wshape[3];
        rc = coons__ld_net_key(L, val[3], "weights", &ws, wshape, &t->w);
    }
    return rc;
}

void coons__ld_tensor_free(coons__ld_tensor *t)
{
    coons__free(t->pts);
    for (int d = 0; d < 3; d++) coons__free(t->kn[d]);
    coons__free(t->w);
    memset(t, 0, sizeof *t);
}
