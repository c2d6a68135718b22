/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Reader of morph (seed 000 section 4, Fig. 10; coons-model(5), "morph"):
 * "keys", 2 or more bodies of any types (references allowed, their names
 * ignored), "at" their times (strictly increasing from exactly 0 to
 * exactly 1, default uniform), "path" "linear" or "smooth", "t" in [0,1].
 */
#include "loader.h"

static const char *const KEYS[] = {"type", "name", "keys", "at", "path", "t", NULL};

static void free_keys(coons_body **k, size_t n)
{
    for (size_t i = 0; k && i < n; i++) coons_body_free(k[i]);
    coons__free(k);
}

/* The key bodies (pass 2: built into *out, n of them). */
static coons_status read_keys(coons__ld *L, coons__ld_obj *o, size_t tok, coons_body ***out,
                              size_t *n)
{
    size_t old = coons__ld_push_key(L, "keys");
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_ARRAY, "an array of 2 or more bodies");
    size_t nk = rc ? 0 : coons__json_size(L->j, tok);
    if (!rc && (nk < 2 || nk > COONS_MORPH_MAX_KEYS))
        rc = coons__ld_fail(L, tok, COONS_E_INVALID, "%s takes 2 to %d keys, not %zu", o->what,
                            COONS_MORPH_MAX_KEYS, nk);
    coons_body **k = NULL;
    if (!rc && L->build && !(k = coons__calloc(nk, sizeof *k)))
        rc = coons__ld_fail(L, tok, COONS_E_NOMEM, "out of memory");
    size_t e = tok + 1;
    for (size_t i = 0; i < nk && !rc; i++, e = coons__json_next(L->j, e)) {
        size_t o2 = coons__ld_push_index(L, i);
        rc = coons__ld_body(L, e, (size_t)-1, k ? &k[i] : NULL);
        coons__ld_pop(L, o2);
    }
    coons__ld_pop(L, old);
    if (rc) {
        free_keys(k, nk);
        return rc;
    }
    *out = k;
    *n = nk;
    return COONS_OK;
}

/* "at": n numbers from exactly 0 to exactly 1, strictly increasing. */
static coons_status read_at(coons__ld *L, size_t tok, size_t n, double *at)
{
    size_t old = coons__ld_push_key(L, "at");
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_ARRAY, "an array of key times");
    if (!rc && coons__json_size(L->j, tok) != n)
        rc = coons__ld_fail(L, tok, COONS_E_INVALID, "%zu key times for %zu keys; give one per key",
                            coons__json_size(L->j, tok), n);
    size_t e = tok + 1;
    for (size_t i = 0; i < n && !rc; i++, e = coons__json_next(L->j, e)) {
        size_t o2 = coons__ld_push_index(L, i);
        rc = coons__ld_number(L, e, &at[i]);
        if (!rc && i == 0 && at[0] != 0.0)
            rc = coons__ld_fail(L, e, COONS_E_INVALID, "the first key time must be 0, not %.17g",
                                at[0]);
        if (!rc && i > 0 && !(at[i] > at[i - 1]))
            rc = coons__ld_fail(L, e, COONS_E_INVALID,
                                "key times must increase strictly: %.17g follows %.17g", at[i],
                                at[i - 1]);
        if (!rc && i == n - 1 && at[i] != 1.0)
            rc = coons__ld_fail(L, e, COONS_E_INVALID, "the last key time must be 1, not %.17g",
                                at[i]);
        coons__ld_pop(L, o2);
    }
    coons__ld_pop(L, old);
    return rc;
}

coons_status coons__ld_read_morph(coons__ld *L, coons__ld_obj *o, coons_body **out)
{
    size_t v[6];
    coons_status rc = coons__ld_body_keys(L, o, KEYS, v);
    if (!rc) rc = coons__ld_need(L, o->tok, v[2], "keys", o->need);
    coons_body **keys = NULL;
    size_t n = 0;
    if (!rc) rc = read_keys(L, o, v[2], &keys, &n);
    double *at = NULL;
    if (!rc && v[3]) {
        if (!(at = coons__malloc_array(n ? n : 1, sizeof *at)))
            rc = coons__ld_fail(L, v[3], COONS_E_NOMEM, "out of memory");
        else
            rc = read_at(L, v[3], n, at);
    }
    int smooth = 0;
    if (!rc && v[4]) rc = coons__ld_keyword(L, v[4], "path", "linear", "smooth", &smooth);
    double t = 0.0;
    if (!rc && v[5]) {
        size_t old = coons__ld_push_key(L, "t");
        rc = coons__ld_number(L, v[5], &t);
        if (!rc && !(t >= 0.0 && t <= 1.0))
            rc = coons__ld_fail(L, v[5], COONS_E_INVALID, "the time t = %.17g is outside [0, 1]",
                                t);
        coons__ld_pop(L, old);
    }
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        coons_status r =
            coons_body_new_morph(keys, n, at,
                                 smooth ? COONS_MORPH_SMOOTH : COONS_MORPH_LINEAR, t, out, &e);
        rc = coons__ld_built(L, o->tok, r, o->what, &e);
    }
    coons__free(at);
    free_keys(keys, n);
    return rc;
}
