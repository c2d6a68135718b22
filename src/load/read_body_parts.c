/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * What every body reader (read_body*.c) shares: the body's "name", its
 * keys, the objects of named parts (body1 "edges", body2 "faces") and the
 * report of a constructor's failure at the part it names.
 */
#include <stdio.h>
#include <string.h>

#include "loader.h"

/* The body's name, kept (pass 1) for the uniqueness check and the model. */
static coons_status body_name(coons__ld *L, size_t tok, size_t index)
{
    size_t old = coons__ld_push_key(L, "name");
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_STRING, "a string (the body's name)");
    if (!rc) {
        char probe[2];
        size_t len = coons__json_string(L->j, tok, probe, sizeof probe);
        char *s = coons__malloc(len + 1);
        if (!s)
            rc = coons__ld_fail(L, tok, COONS_E_NOMEM, "out of memory");
        else {
            coons__json_string(L->j, tok, s, len + 1);
            L->names[index].name = s;
            L->names[index].tok = tok;
            if (len == 0)
                rc = coons__ld_fail(L, tok, COONS_E_INVALID, "a body name must not be empty");
            else if (strlen(s) != len)
                rc = coons__ld_fail(L, tok, COONS_E_INVALID,
                                    "a body name must not contain U+0000");
        }
    }
    coons__ld_pop(L, old);
    return rc;
}

coons_status coons__ld_body_keys(coons__ld *L, coons__ld_obj *o, const char *const *keys,
                                 size_t *val)
{
    coons_status rc = coons__ld_keys(L, o, keys, val);
    if (!rc && val[1] && !L->build) {
        if (o->index != (size_t)-1)
            rc = body_name(L, val[1], o->index);
        else { /* a definition: its instances are named by the references */
            size_t old = coons__ld_push_key(L, "name");
            rc = coons__ld_expect(L, val[1], COONS__JSON_STRING, "a string (the body's name)");
            coons__ld_pop(L, old);
        }
    }
    return rc;
}

/* The parts one by one, each under its name. */
static coons_status read_parts(coons__ld *L, int is1, const char *const *names,
                               const size_t *sub, coons_curve *c[12], coons_patch *f[6])
{
    coons_status rc = COONS_OK;
    for (size_t k = 0; names[k] && !rc; k++) {
        size_t o2 = coons__ld_push_key(L, names[k]);
        if (is1)
            rc = coons__ld_curve(L, sub[k], L->build ? &c[k] : NULL);
        else
            rc = coons__ld_patch(L, sub[k], L->build ? &f[k] : NULL);
        coons__ld_pop(L, o2);
    }
    return rc;
}

coons_status coons__ld_body_parts(coons__ld *L, coons__ld_obj *o, size_t val, int is1,
                                  coons_curve *c[12], coons_patch *f[6], size_t sub[12])
{
    const char *key = is1 ? "edges" : "faces";
    const char *names[13];
    size_t cnt = coons__ld_names(is1 ? coons_body_edge_name : coons_body_face_name, names, 13);
    coons_status rc = coons__ld_need(L, o->tok, val, key, o->need);
    if (rc) return rc;
    size_t old = coons__ld_push_key(L, key);
    const char *desc = is1 ? "the 12 edges of a body1" : "the 6 faces of a body2";
    rc = coons__ld_expect(L, val, COONS__JSON_OBJECT,
                          is1 ? "an object of 12 edge curves" : "an object of 6 face patches");
    if (!rc) rc = coons__ld_members(L, val, desc, names, sub, NULL);
    for (size_t k = 0; k < cnt && !rc; k++)
        if (!sub[k]) {
            char m[320], list[128];
            coons__ld_join(names, list, sizeof list);
            snprintf(m, sizeof m, "%s are all required: %s", desc, list);
            rc = coons__ld_need(L, val, 0, names[k], m);
        }
    if (!rc) rc = read_parts(L, is1, names, sub, c, f);
    coons__ld_pop(L, old);
    return rc;
}

coons_status coons__ld_body_built(coons__ld *L, coons__ld_obj *o, size_t val, const char *key,
                                  coons_status r, const coons_error *e)
{
    if (r != COONS_E_INCOMPATIBLE) return coons__ld_built(L, o->tok, r, o->what, e);
    /* The constructor saw a disagreement that the readers' checks did not:
     * point at the edges/faces object. */
    size_t old = coons__ld_push_key(L, key);
    coons_status rc = coons__ld_fail(L, val, r, "%s", e->message);
    coons__ld_pop(L, old);
    return rc;
}
