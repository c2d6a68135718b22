/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Definitions and references (coons-model(5), "Definitions and
 * references"): "define" maps names to curves, patches and bodies, and
 * {"ref": NAME, modifiers} stands wherever one of them does.
 *
 * Pass 1 reads a definition again at every reference, under the composed
 * transform of the references that lead there, so that the control box is
 * that of the control points as instanced; the values read that way are
 * counted against max_values, which bounds a chain of definitions that
 * each reference the previous one twice. Pass 2 builds each definition
 * once, at its first reference, and gives every reference its own copy
 * (wrapped by the library's transformed, reversed and reparametrised
 * objects). An error inside a definition has the definition's path and
 * names the references that lead there.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "affine.h"
#include "loader.h"

/* References nest at most this deep (each level may nest JSON again). */
#define MAX_REF_DEPTH 32

static const char *const KIND_NAME[] = {"object", "curve", "patch", "body"};
static const char *const CURVE_MODS[] = {"ref", "transform", "reverse", NULL};
static const char *const PATCH_MODS[] = {"ref", "transform", "swap", "flip_s", "flip_t", NULL};
static const char *const BODY_MODS[] = {"ref", "transform", "name", NULL};
static const char *const *const MODS[] = {NULL, CURVE_MODS, PATCH_MODS, BODY_MODS};

/* ---- the definitions ----------------------------------------------------- */

static int cmp_defs(const void *a, const void *b)
{
    const coons__ld_def *x = a, *y = b;
    int c = strcmp(x->name, y->name);
    if (c) return c;
    return x->tok < y->tok ? -1 : x->tok > y->tok;
}

/* The kind whose type names include the string tok, or NONE. */
static int kind_of_type(const coons__ld *L, size_t tok)
{
    const char *n;
    for (int i = 0; (n = coons_curve_type_name((coons_curve_type)i)); i++)
        if (coons__json_string_eq(L->j, tok, n)) return COONS__LD_KIND_CURVE;
    for (int i = 0; (n = coons_patch_type_name((coons_patch_type)i)); i++)
        if (coons__json_string_eq(L->j, tok, n)) return COONS__LD_KIND_PATCH;
    for (int i = 0; (n = coons_body_type_name((coons_body_type)i)); i++)
        if (coons__json_string_eq(L->j, tok, n)) return COONS__LD_KIND_BODY;
    return COONS__LD_KIND_NONE;
}

/* A definition that is not a reference: an object with a known type. */
static coons_status typed_def(coons__ld *L, coons__ld_def *d)
{
    size_t old = coons__ld_push_key(L, d->name), t = d->tok;
    coons_status rc = COONS_OK;
    if (coons__json_type_of(L->j, t) != COONS__JSON_OBJECT)
        rc = coons__ld_fail(L, t, COONS_E_INVALID,
                            "expected a curve, a patch or a body (an object with a \"type\" "
                            "or a \"ref\"), found %s",
                            coons__ld_kind(L, t));
    else if (coons__ld_is_ref(L, t))
        d->kind = -1; /* found when first needed */
    else {
        size_t ty = coons__ld_member(L, t, "type");
        if (!ty)
            rc = coons__ld_fail(L, t, COONS_E_INVALID,
                                "missing key \"type\": a definition is a curve, a patch or a "
                                "body, or a \"ref\" to another definition");
        else if (coons__json_type_of(L->j, ty) != COONS__JSON_STRING ||
                 !(d->kind = kind_of_type(L, ty))) {
            char name[64];
            if (coons__json_type_of(L->j, ty) == COONS__JSON_STRING)
                coons__ld_text_of(L, ty, name, sizeof name);
            else
                snprintf(name, sizeof name, "%s", coons__ld_kind(L, ty));
            coons__ld_push_key(L, "type");
            rc = coons__ld_fail(L, ty, COONS_E_INVALID,
                                "unknown type \"%s\" for a definition: expected the type of a "
                                "curve, a patch or a body",
                                name);
        }
    }
    coons__ld_pop(L, old);
    return rc;
}

coons_status coons__ld_defines(coons__ld *L, size_t tok)
{
    size_t old = coons__ld_push_key(L, "define");
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_OBJECT,
                                       "an object of named curves, patches and bodies");
    size_t n = rc ? 0 : coons__json_size(L->j, tok), k = tok + 1;
    L->define_tok = tok;
    if (n && !(L->defs = coons__calloc(n, sizeof *L->defs)))
        rc = coons__ld_fail(L, tok, COONS_E_NOMEM, "out of memory");
    for (size_t i = 0; i < n && !rc; i++, k = coons__json_next(L->j, k)) {
        char probe[2];
        size_t len = coons__json_string(L->j, k, probe, sizeof probe);
        coons__ld_def *d = &L->defs[L->ndefs];
        if (!(d->name = coons__malloc(len + 1))) {
            rc = coons__ld_fail(L, k, COONS_E_NOMEM, "out of memory");
            break;
        }
        L->ndefs++;
        coons__json_string(L->j, k, d->name, len + 1);
        d->tok = k + 1;
        if (len == 0 || strlen(d->name) != len) {
            size_t o2 = coons__ld_push_key(L, d->name);
            rc = coons__ld_fail(L, k, COONS_E_INVALID,
                                "a definition name must be a non-empty string without U+0000");
            coons__ld_pop(L, o2);
        }
        if (!rc) rc = typed_def(L, d);
    }
    if (!rc && L->ndefs) qsort(L->defs, L->ndefs, sizeof *L->defs, cmp_defs);
    for (size_t i = 1; i < L->ndefs && !rc; i++)
        if (strcmp(L->defs[i].name, L->defs[i - 1].name) == 0) {
            int line, col;
            coons__json_line_col(L->buf, L->len, coons__json_start(L->j, L->defs[i - 1].tok - 1),
                                 &line, &col);
            char nm[128];
            coons__ld_copy_trunc(nm, sizeof nm, L->defs[i].name);
            coons__ld_sanitize(nm);
            size_t o2 = coons__ld_push_key(L, L->defs[i].name);
            rc = coons__ld_fail(L, L->defs[i].tok - 1, COONS_E_INVALID,
                                "definition \"%s\" is already defined at line %d, column %d: "
                                "each name may be defined once",
                                nm, line, col);
            coons__ld_pop(L, o2);
        }
    if (!rc && L->ndefs && !(L->via = coons__calloc(MAX_REF_DEPTH, sizeof *L->via)))
        rc = coons__ld_fail(L, tok, COONS_E_NOMEM, "out of memory");
    coons__ld_pop(L, old);
    return rc;
}

/* Out of memory in lookup(). */
#define NOMEM_DEF ((size_t)-1)

/* The definition named by string token tok, or ndefs, or NOMEM_DEF. */
static size_t lookup(const coons__ld *L, size_t tok)
{
    size_t lo = 0, hi = L->ndefs;
    char small[256];
    size_t len = coons__json_string(L->j, tok, small, sizeof small);
    char *s = len < sizeof small ? small : coons__malloc(len + 1);
    if (!s) return NOMEM_DEF;
    if (s != small) coons__json_string(L->j, tok, s, len + 1);
    size_t found = L->ndefs;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        int c = strcmp(s, L->defs[mid].name);
        if (c == 0) {
            found = mid;
            break;
        }
        if (c < 0)
            hi = mid;
        else
            lo = mid + 1;
    }
    int nul = strlen(s) != len; /* names hold no U+0000 */
    if (s != small) coons__free(s);
    return nul ? L->ndefs : found;
}

/* The kind of definition d, through the references it is made of (NONE:
 * an unknown name or a cycle on the way, reported when followed). */
static int kind_of_def(coons__ld *L, size_t d)
{
    size_t e = d;
    int kind = COONS__LD_KIND_NONE;
    for (size_t steps = 0; steps <= L->ndefs; steps++) {
        if (L->defs[e].kind >= 0) {
            kind = L->defs[e].kind;
            break;
        }
        size_t r = coons__ld_member(L, L->defs[e].tok, "ref");
        if (coons__json_type_of(L->j, r) != COONS__JSON_STRING) break;
        if ((e = lookup(L, r)) >= L->ndefs) break;
    }
    /* Cache the answer along the chain, so that every chain is walked once. */
    for (size_t steps = 0; steps <= L->ndefs && L->defs[d].kind < 0; steps++) {
        L->defs[d].kind = kind;
        size_t r = coons__ld_member(L, L->defs[d].tok, "ref");
        if (coons__json_type_of(L->j, r) != COONS__JSON_STRING) break;
        if ((d = lookup(L, r)) >= L->ndefs) break;
    }
    return kind;
}

/* ---- following a reference ----------------------------------------------- */

/* Appends " -> name of definition k" (no arrow first) to out at *o. */
static void cycle_add(const coons__ld *L, size_t k, char *out, size_t cap, size_t *o)
{
    char nm[64];
    coons__ld_copy_trunc(nm, sizeof nm, L->defs[k].name);
    coons__ld_sanitize(nm);
    int n = *o < cap ? snprintf(out + *o, cap - *o, "%s%s", *o ? " -> " : "", nm) : -1;
    if (n > 0) *o += (size_t)n;
}

/* "a -> b -> a": the definitions being read from d on, and d again (d is
 * not on the stack when it is an unused definition read for itself). */
static void cycle_text(const coons__ld *L, size_t d, char *out, size_t cap)
{
    size_t i = 0, o = 0;
    while (i < L->depth && L->via[i].def != d) i++;
    out[0] = '\0';
    if (i == L->depth) {
        cycle_add(L, d, out, cap, &o);
        i = 0;
    }
    for (; i < L->depth; i++) cycle_add(L, L->via[i].def, out, cap, &o);
    cycle_add(L, d, out, cap, &o);
}

/* Reads definition d as an object of kind at its own path (pass 2: into
 * *built). */
static coons_status read_def(coons__ld *L, size_t d, int kind, void **built)
{
    coons__ld_pop(L, 0);
    coons__ld_push_key(L, "define");
    coons__ld_push_key(L, L->defs[d].name);
    L->defs[d].state = 1;
    coons_status rc;
    size_t t = L->defs[d].tok;
    if (kind == COONS__LD_KIND_CURVE) {
        coons_curve *c = NULL;
        rc = coons__ld_curve(L, t, built ? &c : NULL);
        if (built) *built = c;
    } else if (kind == COONS__LD_KIND_PATCH) {
        coons_patch *p = NULL;
        rc = coons__ld_patch(L, t, built ? &p : NULL);
        if (built) *built = p;
    } else {
        coons_body *b = NULL;
        rc = coons__ld_body(L, t, (size_t)-1, built ? &b : NULL);
        if (built) *built = b;
    }
    L->defs[d].state = 2;
    return rc;
}

/* Follows the reference at the current path to definition d (m: its
 * transform or NULL). */
static coons_status follow(coons__ld *L, size_t tok, size_t d, int kind, const double *m,
                           void **built)
{
    /* The errors of the reference itself are at its "ref". */
    size_t old = coons__ld_push_key(L, "ref");
    coons_status rc = COONS_OK;
    if (L->defs[d].state == 1) {
        char cyc[256];
        cycle_text(L, d, cyc, sizeof cyc);
        rc = coons__ld_fail(L, tok, COONS_E_INVALID, "a cycle of references: %s", cyc);
    } else if (L->depth >= MAX_REF_DEPTH) {
        rc = coons__ld_fail(L, tok, COONS_E_LIMIT,
                            "references nest more than %d deep (a reference inside a "
                            "definition reached by a reference ...)",
                            MAX_REF_DEPTH);
    } else if (!L->build) {
        size_t n = coons__json_next(L->j, L->defs[d].tok) - L->defs[d].tok;
        if (n > L->max_values - L->expanded)
            rc = coons__ld_fail(L, tok, COONS_E_LIMIT,
                                "the references expand the model to more than %zu JSON "
                                "values, the limit (raise max_values; coons2stl "
                                "--max-values N)",
                                L->max_values);
        else
            L->expanded += n;
    }
    coons__ld_pop(L, old);
    if (rc) return rc;
    char *path = coons__memdup(L->path, L->plen + 1, 1);
    if (!path) return coons__ld_fail(L, tok, COONS_E_NOMEM, "out of memory");
    L->via[L->depth].def = d;
    L->via[L->depth].path = path;
    L->depth++;
    double xf[12];
    int on = L->xf_on;
    memcpy(xf, L->xf, sizeof xf);
    if (m && !L->build) {
        if (on)
            coons__affine_compose(xf, m, L->xf);
        else
            memcpy(L->xf, m, sizeof L->xf);
        L->xf_on = 1;
    }
    rc = read_def(L, d, kind, built);
    memcpy(L->xf, xf, sizeof xf);
    L->xf_on = on;
    L->depth--;
    memcpy(L->path, path, strlen(path) + 1);
    L->plen = strlen(path);
    coons__free(path);
    return rc;
}

/* ---- the modifiers ------------------------------------------------------- */

static coons_status transform(coons__ld *L, size_t tok, double m[12])
{
    size_t old = coons__ld_push_key(L, "transform");
    const char *desc = "a 3 x 4 matrix [[a,b,c,tx],[d,e,f,ty],[g,h,i,tz]]";
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_ARRAY, desc);
    if (!rc && coons__json_size(L->j, tok) != 3)
        rc = coons__ld_fail(L, tok, COONS_E_INVALID, "expected %s: 3 rows, found %zu", desc,
                            coons__json_size(L->j, tok));
    size_t r = tok + 1;
    for (int i = 0; i < 3 && !rc; i++, r = coons__json_next(L->j, r)) {
        size_t o2 = coons__ld_push_index(L, (size_t)i);
        rc = coons__ld_expect(L, r, COONS__JSON_ARRAY, "a row of 4 numbers");
        if (!rc && coons__json_size(L->j, r) != 4)
            rc = coons__ld_fail(L, r, COONS_E_INVALID,
                                "a row of a transform has 4 numbers (3 of M, 1 of t), found %zu",
                                coons__json_size(L->j, r));
        size_t e = r + 1;
        for (int j = 0; j < 4 && !rc; j++, e = coons__json_next(L->j, e)) {
            size_t o3 = coons__ld_push_index(L, (size_t)j);
            rc = coons__ld_number(L, e, &m[4 * i + j]);
            coons__ld_pop(L, o3);
        }
        coons__ld_pop(L, o2);
    }
    if (!rc) {
        coons_error e = COONS_ERROR_INIT;
        if (coons__affine_check(m, "the", &e))
            rc = coons__ld_fail(L, tok, COONS_E_INVALID, "%s", e.message);
    }
    coons__ld_pop(L, old);
    return rc;
}

static coons_status boolean(coons__ld *L, size_t tok, const char *key, int *out)
{
    size_t old = coons__ld_push_key(L, key);
    coons__json_type t = coons__json_type_of(L->j, tok);
    coons_status rc = COONS_OK;
    if (t == COONS__JSON_TRUE || t == COONS__JSON_FALSE)
        *out = t == COONS__JSON_TRUE;
    else
        rc = coons__ld_fail(L, tok, COONS_E_INVALID, "expected true or false, found %s",
                            coons__ld_kind(L, tok));
    coons__ld_pop(L, old);
    return rc;
}

/* The instance's name (pass 1, a body at the top level): "name", else the
 * definition's. */
static coons_status instance_name(coons__ld *L, size_t tok, size_t ref_tok, size_t d,
                                  size_t index)
{
    coons_status rc = COONS_OK;
    const char *src = L->defs[d].name;
    char *s = NULL;
    if (tok) {
        size_t old = coons__ld_push_key(L, "name");
        rc = coons__ld_expect(L, tok, COONS__JSON_STRING, "a string (the body's name)");
        if (!rc) {
            char probe[2];
            size_t len = coons__json_string(L->j, tok, probe, sizeof probe);
            if (!(s = coons__malloc(len + 1))) {
                rc = coons__ld_fail(L, tok, COONS_E_NOMEM, "out of memory");
            } else {
                coons__json_string(L->j, tok, s, len + 1);
                if (len == 0 || strlen(s) != len)
                    rc = coons__ld_fail(L, tok, COONS_E_INVALID,
                                        "a body name must be a non-empty string without U+0000");
            }
        }
        coons__ld_pop(L, old);
    } else if (!(s = coons__memdup(src, strlen(src) + 1, 1)))
        rc = coons__ld_fail(L, ref_tok, COONS_E_NOMEM, "out of memory");
    if (rc || index == (size_t)-1 || L->depth) {
        coons__free(s);
        return rc;
    }
    coons__free(L->names[index].name);
    L->names[index].name = s;
    L->names[index].tok = tok ? tok : ref_tok;
    return COONS_OK;
}

/* A modifier of another kind's references, as an error. */
static coons_status foreign_mods(coons__ld *L, size_t obj, int kind)
{
    size_t n = coons__json_size(L->j, obj), k = obj + 1;
    for (size_t i = 0; i < n; i++, k = coons__json_next(L->j, k)) {
        int mine = 0;
        for (const char *const *m = MODS[kind]; *m; m++) mine |= coons__json_string_eq(L->j, k, *m);
        if (mine) continue;
        for (int o = 1; o <= 3; o++)
            for (const char *const *m = MODS[o]; *m; m++)
                if (o != kind && coons__json_string_eq(L->j, k, *m)) {
                    char list[128];
                    coons__ld_join(MODS[kind], list, sizeof list);
                    size_t old = coons__ld_push_key(L, *m);
                    coons_status rc = coons__ld_fail(
                        L, k, COONS_E_INVALID,
                        "\"%s\" modifies a reference to a %s, not to a %s; a %s reference takes "
                        "%s",
                        *m, KIND_NAME[o], KIND_NAME[kind], KIND_NAME[kind], list);
                    coons__ld_pop(L, old);
                    return rc;
                }
    }
    return COONS_OK;
}

/* ---- the reference ------------------------------------------------------- */

int coons__ld_is_ref(const coons__ld *L, size_t obj)
{
    return coons__json_type_of(L->j, obj) == COONS__JSON_OBJECT &&
           coons__ld_member(L, obj, "ref") != 0;
}

typedef struct mods {
    int has_m, flag[3]; /* curve: reverse; patch: swap, flip_s, flip_t */
    double m[12];
} mods;

/* The instance of built (kind) with the modifiers, a new object. */
static coons_status instance(coons__ld *L, size_t obj, int kind, const void *built,
                             const mods *md, void **out)
{
    coons_error e = COONS_ERROR_INIT;
    coons_status rc = COONS_OK;
    if (kind == COONS__LD_KIND_CURVE) {
        coons_curve *a = NULL, *b = NULL;
        const coons_curve *src = built;
        if (md->flag[0] && !(rc = coons_curve_new_reversed(src, &a, &e))) src = a;
        if (!rc) rc = md->has_m ? coons_curve_new_transformed(src, md->m, &b, &e)
                                : coons_curve_copy(src, &b, &e);
        coons_curve_free(a);
        *out = b;
    } else if (kind == COONS__LD_KIND_PATCH) {
        coons_patch *a = NULL, *b = NULL;
        const coons_patch *src = built;
        if ((md->flag[0] || md->flag[1] || md->flag[2]) &&
            !(rc = coons_patch_new_reparametrized(src, md->flag[0], md->flag[1], md->flag[2], &a,
                                                  &e)))
            src = a;
        if (!rc) rc = md->has_m ? coons_patch_new_transformed(src, md->m, &b, &e)
                                : coons_patch_copy(src, &b, &e);
        coons_patch_free(a);
        *out = b;
    } else {
        coons_body *b = NULL;
        rc = md->has_m ? coons_body_new_transformed(built, md->m, &b, &e)
                       : coons_body_copy(built, &b, &e);
        *out = b;
    }
    return coons__ld_built(L, obj, rc, "the reference", &e);
}

coons_status coons__ld_ref(coons__ld *L, size_t obj, int kind, size_t index, void **out)
{
    char what[32];
    snprintf(what, sizeof what, "a %s reference", KIND_NAME[kind]);
    size_t v[5] = {0};
    coons_status rc = foreign_mods(L, obj, kind);
    if (!rc) rc = coons__ld_members(L, obj, what, MODS[kind], v, NULL);
    if (rc) return rc;
    size_t old = coons__ld_push_key(L, "ref");
    rc = coons__ld_expect(L, v[0], COONS__JSON_STRING, "a string naming a definition");
    size_t d = L->ndefs;
    if (!rc && (d = lookup(L, v[0])) == NOMEM_DEF)
        rc = coons__ld_fail(L, v[0], COONS_E_NOMEM, "out of memory");
    else if (!rc && d == L->ndefs) {
        char nm[64];
        coons__ld_text_of(L, v[0], nm, sizeof nm);
        rc = coons__ld_fail(L, v[0], COONS_E_INVALID, "unknown definition \"%s\"%s", nm,
                            L->ndefs ? ": \"define\" has no such name"
                                     : ": the model has no \"define\"");
    }
    int dk = rc ? 0 : kind_of_def(L, d);
    if (!rc && dk != COONS__LD_KIND_NONE && dk != kind) {
        char nm[64];
        coons__ld_copy_trunc(nm, sizeof nm, L->defs[d].name);
        coons__ld_sanitize(nm);
        int line, col;
        coons__json_line_col(L->buf, L->len, coons__json_start(L->j, L->defs[d].tok), &line,
                             &col);
        rc = coons__ld_fail(L, v[0], COONS_E_INVALID,
                            "\"%s\" is a %s (defined at line %d, column %d, /define/%s), but a "
                            "%s stands here",
                            nm, KIND_NAME[dk], line, col, nm, KIND_NAME[kind]);
    }
    coons__ld_pop(L, old);
    mods md;
    memset(&md, 0, sizeof md);
    if (!rc && v[1]) {
        rc = transform(L, v[1], md.m);
        md.has_m = 1;
    }
    static const char *const FLAGS[][3] = {{0}, {"reverse"}, {"swap", "flip_s", "flip_t"}, {0}};
    for (int f = 0; f < 3 && !rc && FLAGS[kind][f]; f++)
        if (v[2 + f]) rc = boolean(L, v[2 + f], FLAGS[kind][f], &md.flag[f]);
    if (!rc && kind == COONS__LD_KIND_BODY && !L->build)
        rc = instance_name(L, v[2], v[0], d, index);
    if (rc) return rc;
    if (!L->build) return follow(L, v[0], d, kind, md.has_m ? md.m : NULL, NULL);
    if (!L->defs[d].built && (rc = follow(L, v[0], d, kind, NULL, &L->defs[d].built)))
        return rc;
    return instance(L, obj, kind, L->defs[d].built, &md, out);
}

/* ---- the definitions no body reached, and the end -------------------------- */

static void free_built(coons__ld_def *d)
{
    if (d->kind == COONS__LD_KIND_CURVE) coons_curve_free(d->built);
    if (d->kind == COONS__LD_KIND_PATCH) coons_patch_free(d->built);
    if (d->kind == COONS__LD_KIND_BODY) coons_body_free(d->built);
    d->built = NULL;
}

coons_status coons__ld_unused_defs(coons__ld *L)
{
    int was = L->bbox_on;
    L->bbox_on = 0; /* unused definitions do not count towards the model's size */
    coons_status rc = COONS_OK;
    for (size_t d = 0; d < L->ndefs && !rc; d++) {
        if (L->build ? L->defs[d].built != NULL : L->defs[d].state != 0) continue;
        int kind = kind_of_def(L, d);
        void *b = NULL;
        /* A reference whose kind is not known fails on the way; any reader finds that. */
        rc = read_def(L, d, kind ? kind : COONS__LD_KIND_CURVE, L->build ? &b : NULL);
        coons__ld_pop(L, 0);
        L->defs[d].built = b;
        free_built(&L->defs[d]); /* built only to check it */
    }
    L->bbox_on = was;
    return rc;
}

void coons__ld_defs_free(coons__ld *L)
{
    for (size_t i = 0; i < L->ndefs; i++) {
        if (L->defs[i].kind < 0) L->defs[i].kind = 0;
        free_built(&L->defs[i]);
        coons__free(L->defs[i].name);
    }
    for (size_t i = 0; i < L->depth; i++) coons__free(L->via[i].path);
    coons__free(L->defs);
    coons__free(L->via);
    L->defs = NULL;
    L->via = NULL;
    L->ndefs = L->depth = 0;
}
