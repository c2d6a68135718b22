/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The loader's errors and positions: errors with the file, line, column and JSON
 * pointer of the value they are about, the pointer kept as a stack while
 * the readers descend, and the checks of objects (known keys, each once,
 * required keys, the "type").
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "loader.h"

/* ---- errors and positions ------------------------------------------------ */

void coons__ld_sanitize(char *s)
{
    for (; *s; s++)
        if ((unsigned char)*s < 0x20 || *s == 0x7f) *s = '?';
}

/* Paths longer than the error record's field are cut. */
void coons__ld_copy_trunc(char *dst, size_t cap, const char *src)
{
    size_t n = strlen(src);
    if (n >= cap) n = cap - 1;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

/* The chain of references being followed (L->via), innermost first, as
 * " (in definition "a" referenced at /p, in "b" referenced at /q)"; empty
 * outside any reference. */
void coons__ld_via_text(const coons__ld *L, char *out, size_t cap)
{
    size_t o = 0;
    out[0] = '\0';
    for (size_t i = L->depth; i-- > 0 && o < cap;) {
        char nm[64];
        coons__ld_copy_trunc(nm, sizeof nm, L->defs[L->via[i].def].name);
        coons__ld_sanitize(nm);
        int n = snprintf(out + o, cap - o, "%s\"%s\" referenced at %s",
                         i + 1 == L->depth ? " (in definition " : ", in ", nm,
                         L->via[i].path[0] ? L->via[i].path : "(root)");
        if (n < 0) break;
        o += (size_t)n;
    }
    if (L->depth && o + 1 < cap) {
        out[o] = ')';
        out[o + 1] = '\0';
    }
}

coons_status coons__ld_fail_at(coons__ld *L, size_t offset, coons_status code, const char *msg)
{
    coons_error *e = L->err;
    if (!e) return code;
    int line, col;
    coons__json_line_col(L->buf, L->len, offset, &line, &col);
    e->code = code;
    coons__ld_copy_trunc(e->file, sizeof e->file, L->file);
    e->line = line;
    e->column = col;
    coons__ld_copy_trunc(e->path, sizeof e->path, L->path);
    /* Inside a definition: also the references that lead there. */
    char via[COONS_ERROR_MESSAGE_MAX];
    coons__ld_via_text(L, via, sizeof via);
    /* The message repeats the position so that it can be printed alone. */
    if (snprintf(e->message, sizeof e->message, "%s:%d:%d: %s: %s%s", L->file, line, col,
                 L->path[0] ? L->path : "(root)", msg, via) < 0)
        e->message[0] = '\0';
    return code;
}

coons_status coons__ld_fail(coons__ld *L, size_t tok, coons_status code, const char *fmt, ...)
{
    char msg[COONS_ERROR_MESSAGE_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return coons__ld_fail_at(L, coons__json_start(L->j, tok), code, msg);
}

coons_status coons__ld_fail_in(coons__ld *L, const char *key, const char *part, size_t tok,
                              coons_status code, const char *fmt, ...)
{
    char msg[COONS_ERROR_MESSAGE_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    size_t old = coons__ld_push_key(L, key);
    coons__ld_push_key(L, part);
    coons_status rc = coons__ld_fail_at(L, coons__json_start(L->j, tok), code, msg);
    coons__ld_pop(L, old);
    return rc;
}

coons_status coons__ld_built(coons__ld *L, size_t tok, coons_status rc, const char *what,
                             const coons_error *e)
{
    if (!rc) return COONS_OK;
    return coons__ld_fail(L, tok, rc, "cannot build %s: %s", what, e->message);
}

/* ---- the path ------------------------------------------------------------ */

size_t coons__ld_push_key(coons__ld *L, const char *k)
{
    size_t old = L->plen;
    L->plen = coons__json_pointer_push(L->path, sizeof L->path, L->plen, k, strlen(k));
    return old;
}

/* Called for every array element: digits by hand, not snprintf (which
 * took a fifth of the time of loading a large net). */
size_t coons__ld_push_index(coons__ld *L, size_t i)
{
    char b[24];
    size_t n = sizeof b;
    do {
        b[--n] = (char)('0' + i % 10);
        i /= 10;
    } while (i);
    size_t old = L->plen;
    L->plen = coons__json_pointer_push(L->path, sizeof L->path, L->plen, b + n, sizeof b - n);
    return old;
}

void coons__ld_pop(coons__ld *L, size_t old)
{
    L->plen = old;
    L->path[old] = '\0';
}

/* ---- words for messages -------------------------------------------------- */

const char *coons__ld_kind(const coons__ld *L, size_t tok)
{
    switch (coons__json_type_of(L->j, tok)) {
    case COONS__JSON_OBJECT: return "an object";
    case COONS__JSON_ARRAY: return "an array";
    case COONS__JSON_STRING: return "a string";
    case COONS__JSON_NUMBER: return "a number";
    case COONS__JSON_TRUE: return "true";
    case COONS__JSON_FALSE: return "false";
    default: return "null";
    }
}

void coons__ld_join(const char *const *names, char *out, size_t cap)
{
    size_t o = 0;
    out[0] = '\0';
    for (size_t i = 0; names[i] && o < cap; i++) {
        int n = snprintf(out + o, cap - o, "%s%s", i ? ", " : "", names[i]);
        if (n < 0) break;
        o += (size_t)n;
    }
}

void coons__ld_text_of(const coons__ld *L, size_t tok, char *out, size_t cap)
{
    coons__json_string(L->j, tok, out, cap);
    coons__ld_sanitize(out);
}

void coons__ld_fmt3(char *b, size_t cap, const double p[3])
{
    snprintf(b, cap, "(%.9g, %.9g, %.9g)", p[0], p[1], p[2]);
}

size_t coons__ld_names(const char *(*name)(int), const char **out, size_t cap)
{
    size_t n = 0;
    while (n + 1 < cap && (out[n] = name((int)n))) n++;
    out[n] = NULL;
    return n;
}

/* ---- objects ------------------------------------------------------------- */

/* Token 0 is the root, never a member value: 0 means absent. */
size_t coons__ld_member(const coons__ld *L, size_t obj, const char *key)
{
    size_t n = coons__json_size(L->j, obj), k = obj + 1;
    for (size_t m = 0; m < n; m++, k = coons__json_next(L->j, k))
        if (coons__json_string_eq(L->j, k, key)) return k + 1;
    return 0;
}

/* The error for key token k: repeated (val: the first value) or unknown. */
static coons_status bad_key(coons__ld *L, size_t k, size_t first_val, const char *what,
                            const char *const *names, const char *blend_hint)
{
    char key[128];
    coons__ld_text_of(L, k, key, sizeof key);
    size_t old = coons__ld_push_key(L, key);
    coons_status rc;
    if (first_val) {
        int line, col;
        coons__json_line_col(L->buf, L->len, coons__json_start(L->j, first_val - 1), &line,
                             &col);
        rc = coons__ld_fail(L, k, COONS_E_INVALID,
                            "key \"%s\" appears twice in one object (first at line %d, column "
                            "%d): each key may be given once",
                            key, line, col);
    } else if (blend_hint && strcmp(key, "blend") == 0) {
        rc = coons__ld_fail(L, k, COONS_E_INVALID, "\"blend\" is not allowed here: %s",
                            blend_hint);
    } else {
        char list[256];
        coons__ld_join(names, list, sizeof list);
        rc = coons__ld_fail(L, k, COONS_E_INVALID,
                            "unknown key \"%s\" in %s; expected one of: %s", key, what, list);
    }
    coons__ld_pop(L, old);
    return rc;
}

coons_status coons__ld_members(coons__ld *L, size_t obj, const char *what,
                               const char *const *names, size_t *val, const char *blend_hint)
{
    size_t nn = 0;
    while (names[nn]) val[nn++] = 0;
    size_t n = coons__json_size(L->j, obj), k = obj + 1;
    for (size_t m = 0; m < n; m++, k = coons__json_next(L->j, k)) {
        size_t idx = 0;
        while (idx < nn && !coons__json_string_eq(L->j, k, names[idx])) idx++;
        if (idx == nn || val[idx])
            return bad_key(L, k, idx < nn ? val[idx] : 0, what, names, blend_hint);
        val[idx] = k + 1;
    }
    return COONS_OK;
}

coons_status coons__ld_need(coons__ld *L, size_t obj, size_t val, const char *key,
                            const char *what)
{
    if (val) return COONS_OK;
    return coons__ld_fail(L, obj, COONS_E_INVALID, "missing key \"%s\": %s", key, what);
}

coons_status coons__ld_expect(coons__ld *L, size_t tok, coons__json_type type, const char *desc)
{
    if (coons__json_type_of(L->j, tok) == type) return COONS_OK;
    return coons__ld_fail(L, tok, COONS_E_INVALID, "expected %s, found %s", desc,
                          coons__ld_kind(L, tok));
}

coons_status coons__ld_type_of_obj(coons__ld *L, size_t obj, const char *what,
                                   const char *const *types, int *out)
{
    char list[256];
    coons__ld_join(types, list, sizeof list);
    if (coons__json_type_of(L->j, obj) != COONS__JSON_OBJECT)
        return coons__ld_fail(L, obj, COONS_E_INVALID,
                              "expected %s (an object with a \"type\"), found %s", what,
                              coons__ld_kind(L, obj));
    size_t t = coons__ld_member(L, obj, "type");
    if (!t)
        return coons__ld_fail(L, obj, COONS_E_INVALID,
                              "missing key \"type\": %s needs a type, one of: %s", what, list);
    size_t old = coons__ld_push_key(L, "type");
    coons_status rc = COONS_OK;
    if (coons__json_type_of(L->j, t) != COONS__JSON_STRING) {
        rc = coons__ld_fail(L, t, COONS_E_INVALID,
                            "expected a string naming the type of %s (%s), found %s", what, list,
                            coons__ld_kind(L, t));
    } else {
        int i = 0;
        while (types[i] && !coons__json_string_eq(L->j, t, types[i])) i++;
        if (types[i])
            *out = i;
        else {
            char name[64];
            coons__ld_text_of(L, t, name, sizeof name);
            rc = coons__ld_fail(L, t, COONS_E_INVALID,
                                "unknown type \"%s\" for %s; expected one of: %s", name, what,
                                list);
        }
    }
    coons__ld_pop(L, old);
    return rc;
}

coons_status coons__ld_typed(coons__ld *L, size_t obj, const char *kind,
                             const char *const *types, const char *suffix, int *type,
                             coons__ld_obj *o)
{
    coons_status rc = coons__ld_type_of_obj(L, obj, kind, types, type);
    if (rc) return rc;
    memset(o, 0, sizeof *o);
    o->tok = obj;
    snprintf(o->what, sizeof o->what, "a %s%s", types[*type], suffix);
    return COONS_OK;
}

coons_status coons__ld_keys(coons__ld *L, coons__ld_obj *o, const char *const *keys,
                            size_t *val)
{
    coons_status rc = coons__ld_members(L, o->tok, o->what, keys, val, o->hint);
    if (rc) return rc;
    char keylist[128];
    coons__ld_join(keys, keylist, sizeof keylist);
    snprintf(o->need, sizeof o->need, "%s takes %s", o->what, keylist);
    return COONS_OK;
}
