/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Reader of the ruled patch: the two curves c0 (t = 0) and c1 (t = 1). */
#include "loader.h"

static const char *const KEYS[] = {"type", "curves", NULL};

static coons_status two_curves(coons__ld *L, size_t tok, coons_curve *c[2])
{
    size_t old = coons__ld_push_key(L, "curves");
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_ARRAY, "an array of 2 curves [c0, c1]");
    if (!rc && coons__json_size(L->j, tok) != 2)
        rc = coons__ld_fail(L, tok, COONS_E_INVALID,
                            "a ruled patch needs exactly 2 curves, found %zu",
                            coons__json_size(L->j, tok));
    size_t t = tok + 1;
    for (int k = 0; k < 2 && !rc; k++, t = coons__json_next(L->j, t)) {
        size_t o2 = coons__ld_push_index(L, (size_t)k);
        rc = coons__ld_curve(L, t, L->build ? &c[k] : NULL);
        coons__ld_pop(L, o2);
    }
    coons__ld_pop(L, old);
    return rc;
}

coons_status coons__ld_read_ruled(coons__ld *L, coons__ld_obj *o, coons_patch **out)
{
    size_t v[2];
    coons_status rc = coons__ld_keys(L, o, KEYS, v);
    if (!rc) rc = coons__ld_need(L, o->tok, v[1], "curves", o->need);
    if (rc) return rc;
    coons_curve *c[2] = {0};
    rc = two_curves(L, v[1], c);
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        rc = coons__ld_built(L, o->tok, coons_patch_new_ruled(c[0], c[1], out, &e), o->what, &e);
    }
    coons__ld_free_curves(c, 2);
    return rc;
}
