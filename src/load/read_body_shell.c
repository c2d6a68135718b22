/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Reader of the shell body (coons-model(5), "Shells: surfaces made
 * solid"): a patch of any type (references allowed), its thickness and
 * the side the solid lies on. An undefined normal is an error at the
 * surface that says where.
 */
#include "loader.h"

static const char *const KEYS[] = {"type", "name", "surface", "thickness", "side", NULL};

static coons_status side_of(coons__ld *L, size_t tok, coons_shell_side *out)
{
    static const char *const NAMES[] = {"both", "front", "back", NULL};
    *out = COONS_SHELL_BOTH;
    if (!tok) return COONS_OK;
    size_t old = coons__ld_push_key(L, "side");
    const char *desc = "\"both\", \"front\" or \"back\"";
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_STRING, desc);
    int found = 0;
    for (int i = 0; !rc && NAMES[i] && !found; i++)
        if (coons__json_string_eq(L->j, tok, NAMES[i])) {
            *out = (coons_shell_side)i;
            found = 1;
        }
    if (!rc && !found) {
        char s[64];
        coons__ld_text_of(L, tok, s, sizeof s);
        rc = coons__ld_fail(L, tok, COONS_E_INVALID, "unknown side \"%s\"; expected %s", s, desc);
    }
    coons__ld_pop(L, old);
    return rc;
}

coons_status coons__ld_read_shell(coons__ld *L, coons__ld_obj *o, coons_body **out)
{
    size_t v[5];
    double h = 0.0;
    coons_shell_side side = COONS_SHELL_BOTH;
    coons_patch *surf = NULL;
    coons_status rc = coons__ld_body_keys(L, o, KEYS, v);
    if (!rc) rc = coons__ld_need(L, o->tok, v[2], "surface", o->need);
    if (!rc) rc = coons__ld_need(L, o->tok, v[3], "thickness", o->need);
    if (!rc) {
        size_t old = coons__ld_push_key(L, "thickness");
        rc = coons__ld_number(L, v[3], &h);
        if (!rc && !(h > 0.0))
            rc = coons__ld_fail(L, v[3], COONS_E_INVALID, "the thickness must be > 0, not %g", h);
        coons__ld_pop(L, old);
    }
    if (!rc) rc = side_of(L, v[4], &side);
    if (!rc) {
        size_t old = coons__ld_push_key(L, "surface");
        rc = coons__ld_patch(L, v[2], L->build ? &surf : NULL);
        if (!rc && L->build) {
            coons_error e = COONS_ERROR_INIT;
            coons_status r = coons_body_new_shell(surf, h, side, out, &e);
            if (r) rc = coons__ld_fail(L, v[2], r, "cannot build %s: %s", o->what, e.message);
        }
        coons__ld_pop(L, old);
    }
    coons_patch_free(surf);
    return rc;
}
