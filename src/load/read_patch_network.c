/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Reader of the network patch (seed 001 section 1.2.2; coons-model(5),
 * "Networks of curves"): rows and columns of curves, the node parameters,
 * the node twist rule and the cells' blend. The nodes must agree (row j at
 * s_i = column i at t_j): an error there names the node and both curves.
 */
#include <stdio.h>
#include <string.h>

#include "agree.h"
#include "loader.h"

static const char *const KEYS[] = {"type",    "rows",  "columns", "s_nodes",
                                   "t_nodes", "twist", "blend",   NULL};

/* An array of at least 2 curves under key; c[] (pass 2) gets n curves. */
static coons_status curves(coons__ld *L, size_t tok, const char *key, coons_curve ***c,
                           size_t *n)
{
    size_t old = coons__ld_push_key(L, key);
    char desc[64];
    snprintf(desc, sizeof desc, "an array of 2 or more curves (the %s)", key);
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_ARRAY, desc);
    if (!rc && coons__json_size(L->j, tok) < 2)
        rc = coons__ld_fail(L, tok, COONS_E_INVALID, "a network needs 2 or more %s, found %zu",
                            key, coons__json_size(L->j, tok));
    if (!rc) {
        *n = coons__json_size(L->j, tok);
        if (L->build && !(*c = coons__calloc(*n, sizeof **c)))
            rc = coons__ld_fail(L, tok, COONS_E_NOMEM, "out of memory");
    }
    size_t t = tok + 1;
    for (size_t k = 0; !rc && k < *n; k++, t = coons__json_next(L->j, t)) {
        size_t o2 = coons__ld_push_index(L, k);
        rc = coons__ld_curve(L, t, L->build ? &(*c)[k] : NULL);
        coons__ld_pop(L, o2);
    }
    coons__ld_pop(L, old);
    return rc;
}

/* "s_nodes" / "t_nodes": n numbers, strictly increasing from exactly 0 to
 * exactly 1; *out allocated. */
static coons_status node_list(coons__ld *L, size_t tok, const char *key, size_t n,
                              const char *along, double **out)
{
    size_t old = coons__ld_push_key(L, key);
    char desc[96];
    snprintf(desc, sizeof desc, "an array of %zu node parameters (one per %s)", n, along);
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_ARRAY, desc);
    if (!rc && coons__json_size(L->j, tok) != n)
        rc = coons__ld_fail(L, tok, COONS_E_INVALID, "expected %s, found %zu values", desc,
                            coons__json_size(L->j, tok));
    if (!rc && !(*out = coons__malloc_array(n, sizeof **out)))
        rc = coons__ld_fail(L, tok, COONS_E_NOMEM, "out of memory");
    size_t t = tok + 1;
    for (size_t k = 0; !rc && k < n; k++, t = coons__json_next(L->j, t)) {
        size_t o2 = coons__ld_push_index(L, k);
        rc = coons__ld_number(L, t, &(*out)[k]);
        if (!rc && k == 0 && (*out)[0] != 0.0)
            rc = coons__ld_fail(L, t, COONS_E_INVALID, "the first node must be exactly 0, not %g",
                                (*out)[0]);
        if (!rc && k > 0 && !((*out)[k] > (*out)[k - 1]))
            rc = coons__ld_fail(L, t, COONS_E_INVALID,
                                "nodes must be strictly increasing: %g follows %g", (*out)[k],
                                (*out)[k - 1]);
        if (!rc && k == n - 1 && (*out)[k] != 1.0)
            rc = coons__ld_fail(L, t, COONS_E_INVALID, "the last node must be exactly 1, not %g",
                                (*out)[k]);
        coons__ld_pop(L, o2);
    }
    coons__ld_pop(L, old);
    return rc;
}

static coons_status twist(coons__ld *L, size_t tok, coons_twist *out)
{
    static const char *const NAMES[] = {"zero", "adini", "bessel", NULL};
    static const coons_twist VALS[] = {COONS_TWIST_ZERO, COONS_TWIST_ADINI, COONS_TWIST_BESSEL};
    *out = COONS_TWIST_BESSEL;
    if (!tok) return COONS_OK;
    size_t old = coons__ld_push_key(L, "twist");
    const char *desc = "\"zero\", \"adini\" or \"bessel\"";
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_STRING, desc);
    int found = 0;
    for (int i = 0; !rc && NAMES[i] && !found; i++)
        if (coons__json_string_eq(L->j, tok, NAMES[i])) {
            *out = VALS[i];
            found = 1;
        }
    if (!rc && !found) {
        char s[64];
        coons__ld_text_of(L, tok, s, sizeof s);
        rc = coons__ld_fail(L, tok, COONS_E_INVALID, "unknown twist \"%s\"; expected %s", s,
                            desc);
    }
    coons__ld_pop(L, old);
    return rc;
}

/* The node agreement, as an error at the row that names the column too. */
static coons_status node_check(coons__ld *L, coons_curve **rows, size_t nr, coons_curve **cols,
                               size_t nc, const double *sn, const double *tn, size_t rtok)
{
    size_t i = 0, j = 0;
    double d = 0.0;
    if (!coons__network_nodes_agree((const coons_curve *const *)rows, nr,
                                    (const coons_curve *const *)cols, nc, sn, tn, L->ctol, &i,
                                    &j, &d))
        return COONS_OK;
    size_t t = rtok + 1;
    for (size_t k = 0; k < j; k++) t = coons__json_next(L->j, t);
    char col[4200], a[96], b[96], idx[32];
    double p[3], q[3];
    coons_curve_eval(rows[j], sn[i], p);
    coons_curve_eval(cols[i], tn[j], q);
    coons__ld_fmt3(a, sizeof a, p);
    coons__ld_fmt3(b, sizeof b, q);
    snprintf(col, sizeof col, "%s/columns/%zu", L->path, i);
    snprintf(idx, sizeof idx, "%zu", j);
    return coons__ld_fail_in(L, "rows", idx, t, COONS_E_INCOMPATIBLE,
                             "row %zu and column %zu (%s) do not meet at node (%zu, %zu): row "
                             "%zu at s = %g is %s, column %zu at t = %g is %s, %.3g apart, more "
                             "than the tolerance %.3g",
                             j, i, col, i, j, j, sn[i], a, i, tn[j], b, d, L->ctol);
}

coons_status coons__ld_read_network(coons__ld *L, coons__ld_obj *o, coons_patch **out)
{
    size_t v[7];
    coons_curve **rows = NULL, **cols = NULL;
    size_t nr = 0, nc = 0;
    double *sn = NULL, *tn = NULL;
    coons_network_options no = COONS_NETWORK_OPTIONS_INIT;
    coons_status rc = coons__ld_keys(L, o, KEYS, v);
    if (!rc) rc = coons__ld_need(L, o->tok, v[1], "rows", o->need);
    if (!rc) rc = coons__ld_need(L, o->tok, v[2], "columns", o->need);
    if (!rc) rc = curves(L, v[1], "rows", &rows, &nr);
    if (!rc) rc = curves(L, v[2], "columns", &cols, &nc);
    if (!rc && v[3]) rc = node_list(L, v[3], "s_nodes", nc, "column", &sn);
    if (!rc && v[4]) rc = node_list(L, v[4], "t_nodes", nr, "row", &tn);
    if (!rc) rc = twist(L, v[5], &no.twist);
    if (!rc && v[6]) rc = coons__ld_blend(L, v[6], &no.blend);
    if (!rc && L->build) {
        double *s = sn ? sn : coons__malloc_array(nc, sizeof *s);
        double *t = tn ? tn : coons__malloc_array(nr, sizeof *t);
        if (!s || !t) rc = coons__ld_fail(L, o->tok, COONS_E_NOMEM, "out of memory");
        for (size_t k = 0; !rc && !sn && k < nc; k++) s[k] = k + 1 == nc ? 1.0 : (double)k / (nc - 1);
        for (size_t k = 0; !rc && !tn && k < nr; k++) t[k] = k + 1 == nr ? 1.0 : (double)k / (nr - 1);
        if (!rc) rc = node_check(L, rows, nr, cols, nc, s, t, v[1]);
        if (s != sn) coons__free(s);
        if (t != tn) coons__free(t);
    }
    if (!rc && L->build) {
        no.s_nodes = sn;
        no.t_nodes = tn;
        no.tol = L->ctol;
        coons_error e = COONS_ERROR_INIT;
        rc = coons__ld_built(L, o->tok, coons_patch_new_network(rows, nr, cols, nc, &no, out, &e),
                             o->what, &e);
    }
    if (rows) coons__ld_free_curves(rows, nr);
    if (cols) coons__ld_free_curves(cols, nc);
    coons__free(rows);
    coons__free(cols);
    coons__free(sn);
    coons__free(tn);
    return rc;
}
