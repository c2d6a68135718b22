/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The top level of a model ("coons", "units", "tolerance", "operation",
 * "bodies"), unique body names, and the two passes (loader.h): pass 1
 * checks everything and finds the box of the control points, pass 2
 * builds the bodies with the consistency tolerance that box gives.
 */
#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "loader.h"

static const char *const TOP_KEYS[] = {"coons", "units", "tolerance", "operation", "bodies",
                                       "define", NULL};

/* ---- the top level (pass 1) ---------------------------------------------- */

static coons_status version(coons__ld *L)
{
    size_t root = 0, ver = coons__ld_member(L, root, "coons");
    if (!ver)
        return coons__ld_fail(L, root, COONS_E_INVALID,
                              "missing key \"coons\": a model starts with \"coons\": 1, the "
                              "format version");
    size_t old = coons__ld_push_key(L, "coons");
    double x = 0;
    coons_status rc = COONS_OK;
    if (coons__json_type_of(L->j, ver) != COONS__JSON_NUMBER)
        rc = coons__ld_fail(L, ver, COONS_E_INVALID, "expected the format version 1, found %s",
                            coons__ld_kind(L, ver));
    else if (!(rc = coons__ld_number(L, ver, &x)) && x != 1.0) {
        size_t len;
        const char *t = coons__json_text(L->j, ver, &len);
        rc = coons__ld_fail(L, ver, COONS_E_UNSUPPORTED,
                            "format version %.*s is not supported: this libcoons reads version 1",
                            len > 40 ? 40 : (int)len, t);
    }
    coons__ld_pop(L, old);
    return rc;
}

/* Units are printed into outputs: a short, plain string. */
static coons_status units(coons__ld *L, size_t tok)
{
    size_t old = coons__ld_push_key(L, "units");
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_STRING, "a string such as \"mm\"");
    if (!rc) {
        char probe[2];
        size_t len = coons__json_string(L->j, tok, probe, sizeof probe);
        char u[80];
        coons__json_string(L->j, tok, u, sizeof u);
        if (len >= sizeof u)
            rc = coons__ld_fail(L, tok, COONS_E_INVALID, "units must be at most %zu bytes long",
                                sizeof u - 1);
        else if (strlen(u) != len)
            rc = coons__ld_fail(L, tok, COONS_E_INVALID, "units must not contain U+0000");
    }
    coons__ld_pop(L, old);
    if (!rc) L->units_tok = tok;
    return rc;
}

static coons_status tolerance(coons__ld *L, size_t tok)
{
    size_t old = coons__ld_push_key(L, "tolerance");
    coons_status rc = coons__ld_number(L, tok, &L->tolerance);
    if (!rc && !(L->tolerance > 0))
        rc = coons__ld_fail(L, tok, COONS_E_INVALID,
                            "tolerance must be > 0 (a distance in model units), found %.17g",
                            L->tolerance);
    coons__ld_pop(L, old);
    return rc;
}

static coons_status operation(coons__ld *L, size_t tok)
{
    int k = 0;
    coons_status rc = coons__ld_keyword(L, tok, "operation", "union", "none", &k);
    if (!rc) L->op = k ? COONS_OP_NONE : COONS_OP_UNION;
    return rc;
}

/* Version, keys, settings; the bodies follow. */
static coons_status top(coons__ld *L)
{
    size_t root = 0, v[6];
    coons_status rc;
    if ((rc = version(L))) return rc;
    if ((rc = coons__ld_members(L, root, "the model", TOP_KEYS, v, NULL))) return rc;
    if (v[1] && (rc = units(L, v[1]))) return rc;
    if (v[2] && (rc = tolerance(L, v[2]))) return rc;
    if (v[3] && (rc = operation(L, v[3]))) return rc;
    if (v[5] && (rc = coons__ld_defines(L, v[5]))) return rc;
    if ((rc = coons__ld_need(L, root, v[4], "bodies",
                             "a model needs \"bodies\": an array of one or more bodies")))
        return rc;
    size_t old = coons__ld_push_key(L, "bodies");
    rc = coons__ld_expect(L, v[4], COONS__JSON_ARRAY, "an array of bodies");
    if (!rc && coons__json_size(L->j, v[4]) == 0)
        rc = coons__ld_fail(L, v[4], COONS_E_INVALID,
                            "\"bodies\" is empty: a model needs at least one body");
    coons__ld_pop(L, old);
    L->bodies_tok = v[4];
    return rc;
}

/* ---- body names ---------------------------------------------------------- */

static int cmp_names(const void *a, const void *b)
{
    const coons__ld_name *x = a, *y = b;
    int c = strcmp(x->name, y->name);
    if (c) return c;
    return x->tok < y->tok ? -1 : x->tok > y->tok;
}

/* The first repeated name in document order: the token of the repeat
 * (*bad, 0 if none) and of its first use (*first). */
static coons_status first_repeat(coons__ld *L, size_t nb, size_t *bad, size_t *first)
{
    size_t k = 0;
    *bad = *first = 0;
    for (size_t i = 0; i < nb; i++)
        if (L->names[i].name) k++;
    if (k < 2) return COONS_OK;
    coons__ld_name *s = coons__malloc_array(k, sizeof *s);
    if (!s) return coons__ld_fail(L, 0, COONS_E_NOMEM, "out of memory");
    k = 0;
    for (size_t i = 0; i < nb; i++)
        if (L->names[i].name) s[k++] = L->names[i];
    qsort(s, k, sizeof *s, cmp_names);
    for (size_t i = 1; i < k; i++)
        if (strcmp(s[i].name, s[i - 1].name) == 0 &&
            (i < 2 || strcmp(s[i - 1].name, s[i - 2].name))) {
            if (!*bad || s[i].tok < *bad) {
                *bad = s[i].tok;
                *first = s[i - 1].tok;
            }
        }
    coons__free(s);
    return COONS_OK;
}

/* Names must be unique: report the first repeated one in document order. */
static coons_status unique_names(coons__ld *L, size_t nb)
{
    size_t bad, first;
    coons_status rc = first_repeat(L, nb, &bad, &first);
    if (rc || !bad) return rc;
    /* The body indices for the message and the path. */
    size_t bi = 0, fi = 0;
    for (size_t i = 0; i < nb; i++) {
        if (L->names[i].tok == bad) bi = i;
        if (L->names[i].tok == first) fi = i;
    }
    char nm[128];
    snprintf(nm, sizeof nm, "%s", L->names[bi].name);
    coons__ld_sanitize(nm);
    int line, col;
    coons__json_line_col(L->buf, L->len, coons__json_start(L->j, first), &line, &col);
    size_t old = coons__ld_push_key(L, "bodies");
    coons__ld_push_index(L, bi);
    size_t bt = L->bodies_tok + 1;
    for (size_t i = 0; i < bi; i++) bt = coons__json_next(L->j, bt);
    /* A reference without "name" is named after its definition (read_ref.c). */
    int named = coons__ld_member(L, bt, "name") == bad;
    coons__ld_push_key(L, named ? "name" : "ref");
    rc = coons__ld_fail(L, bad, COONS_E_INVALID,
                        "body name \"%s\" is already used by body %zu (line %d, column %d): "
                        "names must be unique%s",
                        nm, fi, line, col,
                        named ? "" : " (a reference is named after its definition: give it "
                                     "a \"name\")");
    coons__ld_pop(L, old);
    return rc;
}

/* ---- the passes ---------------------------------------------------------- */

static coons_status bodies(coons__ld *L, coons_model *m)
{
    size_t nb = coons__json_size(L->j, L->bodies_tok), t = L->bodies_tok + 1;
    size_t old = coons__ld_push_key(L, "bodies");
    coons_status rc = COONS_OK;
    for (size_t i = 0; i < nb && !rc; i++, t = coons__json_next(L->j, t)) {
        size_t o2 = coons__ld_push_index(L, i);
        rc = coons__ld_body(L, t, i, m ? &m->bodies[i] : NULL);
        coons__ld_pop(L, o2);
    }
    coons__ld_pop(L, old);
    return rc;
}

/* After pass 1: the model's tolerance (*tol) and the consistency
 * tolerance L->ctol from the box of the control points. */
static coons_status tolerances(coons__ld *L, double *tol)
{
    double diag = bbox_diag(L->lo, L->hi);
    *tol = L->tolerance > 0 ? L->tolerance : diag / 1000.0;
    if (!(*tol > 0) || !isfinite(*tol)) {
        if (!isfinite(diag))
            return coons__ld_fail(L, 0, COONS_E_INVALID,
                                  "the control points span more than the largest double: the "
                                  "model's size is not finite");
        return coons__ld_fail(L, 0, COONS_E_INVALID,
                              "all control points coincide, so the default tolerance (1/1000 of "
                              "the bounding-box diagonal) would be 0: give \"tolerance\"");
    }
    if (!isfinite(diag))
        return coons__ld_fail(L, 0, COONS_E_INVALID,
                              "the control points span more than the largest double: the "
                              "model's size is not finite");
    /* Scale invariance holds where a body's coordinates, and the products
     * of three of their differences (volumes, Jacobians), are ordinary
     * doubles: sizes 1e-150 to 1e150 (coons-model(5) LIMITS). */
    if (diag > 0 && (diag < COONS_MODEL_MIN_SIZE || diag > COONS_MODEL_MAX_SIZE))
        return coons__ld_fail(L, 0, COONS_E_LIMIT,
                              "the model's size (the diagonal of its control points' box) is "
                              "%.3g, outside the supported range %g to %g: express it in "
                              "other units",
                              diag, COONS_MODEL_MIN_SIZE, COONS_MODEL_MAX_SIZE);
    L->ctol = diag > 0 ? COONS__REL_TOL * diag : DBL_MIN;
    return COONS_OK;
}

/* The model record without its bodies: settings, units, names. */
static coons_status model_record(coons__ld *L, size_t nb, double tol, coons_model **out)
{
    coons_model *m = NULL;
    coons_error e = COONS_ERROR_INIT;
    if (coons__model_alloc(nb, &m, &e)) return coons__ld_fail(L, 0, COONS_E_NOMEM, "out of memory");
    m->tolerance = tol;
    m->operation = (coons_operation)L->op;
    v3_copy(m->lo, L->lo);
    v3_copy(m->hi, L->hi);
    char ubuf[80] = "mm";
    if (L->units_tok) coons__json_string(L->j, L->units_tok, ubuf, sizeof ubuf);
    m->units = coons__memdup(ubuf, strlen(ubuf) + 1, 1);
    for (size_t i = 0; i < nb && m->units; i++) {
        if (L->names[i].name) {
            m->names[i] = L->names[i].name;
            L->names[i].name = NULL;
            m->named[i] = 1;
        } else {
            char b[32];
            snprintf(b, sizeof b, "body%zu", i);
            if (!(m->names[i] = coons__memdup(b, strlen(b) + 1, 1))) break;
        }
    }
    *out = m;
    for (size_t i = 0; i < nb; i++)
        if (!m->units || !m->names[i]) return coons__ld_fail(L, 0, COONS_E_NOMEM, "out of memory");
    return COONS_OK;
}

coons_status coons__ld_model(coons__ld *L, coons_model **out)
{
    coons_status rc = top(L);
    if (rc) return rc;
    size_t nb = coons__json_size(L->j, L->bodies_tok);
    L->names = coons__calloc(nb, sizeof *L->names);
    if (!L->names) return coons__ld_fail(L, 0, COONS_E_NOMEM, "out of memory");
    bbox_empty(L->lo, L->hi);
    L->bbox_on = 1;
    if ((rc = bodies(L, NULL))) return rc;
    if ((rc = coons__ld_unused_defs(L))) return rc;
    if ((rc = unique_names(L, nb))) return rc;
    double tol;
    if ((rc = tolerances(L, &tol))) return rc;
    coons_model *m = NULL;
    rc = model_record(L, nb, tol, &m);
    if (!rc) {
        L->build = 1;
        rc = bodies(L, m);
        if (!rc) rc = coons__ld_unused_defs(L);
    }
    if (rc) {
        coons_model_free(m);
        return rc;
    }
    *out = m;
    return COONS_OK;
}
