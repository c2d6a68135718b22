/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The model format, version 1 (/work/shared/spec/model-format.md, man page
 * coons-model(5)): keys, types, defaults and agreement checks, on top of the
 * strict JSON reader in json.c; objects are built with the public
 * constructors only.
 *
 * Two passes over the tokens. The consistency tolerance (1e-9 of the
 * diagonal of the box of ALL control points of the model, "Consistency")
 * is known only after the whole document has been read, so pass 1 checks
 * every value and accumulates that box, and pass 2 reads the same values
 * again and builds curves, patches and bodies with that tolerance. The
 * agreement checks are made here, before the constructors repeat them, so
 * that an error can point at the first of the two disagreeing values.
 */
#include <errno.h>
#include <float.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/json.h"
#include "io/load_options.h"
#include "model_impl.h"

/* Samples per shared body 2 edge for the agreement check (ends included). */
#define EDGE_SAMPLES 33

typedef struct name_rec {
    char *name;
    size_t tok;
} name_rec;

typedef struct ld {
    const coons__json *j;
    const char *buf;
    size_t len;
    const char *file;
    coons_error *err;
    char path[4096];
    size_t plen;
    int build;   /* pass 2 */
    int bbox_on; /* points count towards the control box */
    double lo[3], hi[3];
    double ctol;
    size_t max_points;
    /* top level, read in pass 1 */
    size_t bodies_tok;
    double tolerance; /* 0: default */
    int op;
    size_t units_tok;
    name_rec *names; /* one per body; name NULL when unnamed */
} ld;

/* ---- errors and paths ---------------------------------------------------- */

static void sanitize(char *s)
{
    for (; *s; s++)
        if ((unsigned char)*s < 0x20 || *s == 0x7f) *s = '?';
}

/* Truncating copy (paths longer than the error record's field are cut). */
static void copy_trunc(char *dst, size_t cap, const char *src)
{
    size_t n = strlen(src);
    if (n >= cap) n = cap - 1;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

static coons_status fail_at(ld *L, size_t offset, coons_status code, const char *msg)
{
    coons_error *e = L->err;
    if (!e) return code;
    int line, col;
    coons__json_line_col(L->buf, L->len, offset, &line, &col);
    e->code = code;
    copy_trunc(e->file, sizeof e->file, L->file);
    e->line = line;
    e->column = col;
    copy_trunc(e->path, sizeof e->path, L->path);
    /* The message repeats the position so that it can be printed alone. */
    if (snprintf(e->message, sizeof e->message, "%s:%d:%d: %s: %s", L->file, line, col,
                 L->path[0] ? L->path : "(root)", msg) < 0)
        e->message[0] = '\0';
    return code;
}

static coons_status COONS__PRINTF(4, 5)
    fail(ld *L, size_t tok, coons_status code, const char *fmt, ...)
{
    char msg[COONS_ERROR_MESSAGE_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return fail_at(L, coons__json_start(L->j, tok), code, msg);
}

static size_t push_key(ld *L, const char *k)
{
    size_t old = L->plen;
    L->plen = coons__json_pointer_push(L->path, sizeof L->path, L->plen, k, strlen(k));
    return old;
}

/* Called for every array element: digits by hand, not snprintf (which
 * took a fifth of the time of loading a large net). */
static size_t push_index(ld *L, size_t i)
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

static void pop(ld *L, size_t old)
{
    L->plen = old;
    L->path[old] = '\0';
}

static const char *kind(const ld *L, size_t tok)
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

static void join(const char *const *names, char *out, size_t cap)
{
    size_t o = 0;
    out[0] = '\0';
    for (size_t i = 0; names[i] && o < cap; i++) {
        int n = snprintf(out + o, cap - o, "%s%s", i ? ", " : "", names[i]);
        if (n < 0) break;
        o += (size_t)n;
    }
}

/* Text of a string value for messages (sanitised, truncated). */
static void text_of(const ld *L, size_t tok, char *out, size_t cap)
{
    coons__json_string(L->j, tok, out, cap);
    sanitize(out);
}

/* ---- objects ------------------------------------------------------------- */

/* Value token of the first member `key` of object obj, or 0 (token 0 is the
 * root, never a member value). */
static size_t member(const ld *L, size_t obj, const char *key)
{
    size_t n = coons__json_size(L->j, obj), k = obj + 1;
    for (size_t m = 0; m < n; m++, k = coons__json_next(L->j, k))
        if (coons__json_string_eq(L->j, k, key)) return k + 1;
    return 0;
}

/*
 * Checks that object obj has only the keys in names (NULL-terminated), each
 * at most once, and sets val[i] to the value token of names[i] or 0.
 * blend_hint: the message for a "blend" key where it is not allowed.
 */
static coons_status members(ld *L, size_t obj, const char *what, const char *const *names,
                            size_t *val, const char *blend_hint)
{
    size_t nn = 0;
    while (names[nn]) val[nn++] = 0;
    size_t n = coons__json_size(L->j, obj), k = obj + 1;
    for (size_t m = 0; m < n; m++, k = coons__json_next(L->j, k)) {
        size_t idx = 0;
        while (idx < nn && !coons__json_string_eq(L->j, k, names[idx])) idx++;
        char key[128];
        if (idx == nn || val[idx]) {
            text_of(L, k, key, sizeof key);
            size_t old = push_key(L, key);
            coons_status rc;
            if (idx < nn) {
                int line, col;
                coons__json_line_col(L->buf, L->len, coons__json_start(L->j, val[idx] - 1),
                                     &line, &col);
                rc = fail(L, k, COONS_E_INVALID,
                          "key \"%s\" appears twice in one object (first at line %d, column "
                          "%d): each key may be given once",
                          key, line, col);
            } else if (blend_hint && strcmp(key, "blend") == 0) {
                rc = fail(L, k, COONS_E_INVALID, "\"blend\" is not allowed here: %s", blend_hint);
            } else {
                char list[256];
                join(names, list, sizeof list);
                rc = fail(L, k, COONS_E_INVALID, "unknown key \"%s\" in %s; expected one of: %s",
                          key, what, list);
            }
            pop(L, old);
            return rc;
        }
        val[idx] = k + 1;
    }
    return COONS_OK;
}

static coons_status need(ld *L, size_t obj, size_t val, const char *key, const char *what)
{
    if (val) return COONS_OK;
    return fail(L, obj, COONS_E_INVALID, "missing key \"%s\": %s", key, what);
}

static coons_status expect(ld *L, size_t tok, coons__json_type type, const char *desc)
{
    if (coons__json_type_of(L->j, tok) == type) return COONS_OK;
    return fail(L, tok, COONS_E_INVALID, "expected %s, found %s", desc, kind(L, tok));
}

/* Reads the "type" of object obj, one of types[] (NULL-terminated). */
static coons_status type_of_obj(ld *L, size_t obj, const char *what, const char *const *types,
                                int *out)
{
    char list[256];
    join(types, list, sizeof list);
    if (coons__json_type_of(L->j, obj) != COONS__JSON_OBJECT)
        return fail(L, obj, COONS_E_INVALID, "expected %s (an object with a \"type\"), found %s",
                    what, kind(L, obj));
    size_t t = member(L, obj, "type");
    if (!t)
        return fail(L, obj, COONS_E_INVALID, "missing key \"type\": %s needs a type, one of: %s",
                    what, list);
    size_t old = push_key(L, "type");
    coons_status rc = COONS_OK;
    if (coons__json_type_of(L->j, t) != COONS__JSON_STRING) {
        rc = fail(L, t, COONS_E_INVALID, "expected a string naming the type of %s (%s), found %s",
                  what, list, kind(L, t));
    } else {
        int i = 0;
        while (types[i] && !coons__json_string_eq(L->j, t, types[i])) i++;
        if (types[i])
            *out = i;
        else {
            char name[64];
            text_of(L, t, name, sizeof name);
            rc = fail(L, t, COONS_E_INVALID, "unknown type \"%s\" for %s; expected one of: %s",
                      name, what, list);
        }
    }
    pop(L, old);
    return rc;
}

/* ---- numbers, points, nets, knots ---------------------------------------- */

static coons_status number(ld *L, size_t tok, double *v)
{
    if (coons__json_type_of(L->j, tok) != COONS__JSON_NUMBER)
        return fail(L, tok, COONS_E_INVALID, "expected a number, found %s", kind(L, tok));
    coons_status rc = coons__json_number(L->j, tok, v);
    if (rc == COONS_OK) return COONS_OK;
    size_t len;
    const char *s = coons__json_text(L->j, tok, &len);
    if (rc == COONS_E_INVALID)
        return fail(L, tok, COONS_E_INVALID,
                    "the number %.*s is outside the range of a double (about +-1.8e308): "
                    "numbers must be finite",
                    len > 40 ? 40 : (int)len, s);
    return fail(L, tok, COONS_E_INTERNAL, "cannot convert the number %.*s",
                len > 40 ? 40 : (int)len, s);
}

/* An integer in [1, COONS_SPLINE_MAX_DEGREE]; 3.0 counts as 3 (JSON has one number type). */
static coons_status degree(ld *L, size_t tok, int *p)
{
    double v;
    coons_status rc = number(L, tok, &v);
    if (rc) return rc;
    if (v != floor(v))
        return fail(L, tok, COONS_E_INVALID, "a degree must be an integer, found %.17g", v);
    if (v < 1)
        return fail(L, tok, COONS_E_INVALID, "a degree must be >= 1, found %.17g", v);
    if (v > COONS_SPLINE_MAX_DEGREE)
        return fail(L, tok, COONS_E_LIMIT, "degree %.17g is above the limit of %d", v,
                    COONS_SPLINE_MAX_DEGREE);
    *p = (int)v;
    return COONS_OK;
}

enum { LEAF_POINT, LEAF_VECTOR, LEAF_WEIGHT };

static coons_status vec(ld *L, size_t tok, int leaf, double out[3])
{
    const char *noun = leaf == LEAF_POINT ? "a point" : "a vector";
    if (coons__json_type_of(L->j, tok) != COONS__JSON_ARRAY)
        return fail(L, tok, COONS_E_INVALID, "expected %s [x, y, z] or [x, y], found %s", noun,
                    kind(L, tok));
    size_t n = coons__json_size(L->j, tok);
    if (n != 2 && n != 3)
        return fail(L, tok, COONS_E_INVALID,
                    "expected %s of 2 or 3 numbers ([x, y] means z = 0), found %zu values", noun,
                    n);
    size_t e = tok + 1;
    out[2] = 0.0;
    for (size_t i = 0; i < n; i++, e = coons__json_next(L->j, e)) {
        size_t old = push_index(L, i);
        coons_status rc = number(L, e, &out[i]);
        pop(L, old);
        if (rc) return rc;
    }
    if (leaf == LEAF_POINT && L->bbox_on && !L->build) bbox_add(L->lo, L->hi, out);
    return COONS_OK;
}

typedef struct netspec {
    int dims;             /* 1 (curve), 2 (surface), 3 (volume) */
    int leaf;             /* LEAF_* */
    const size_t *fixed;  /* required shape (weights), or NULL */
    size_t min;           /* at least this many along each direction */
    int exact;            /* exactly min (dims 1) */
    size_t maxdir;        /* at most this many along each direction (Bezier degree), or 0 */
    const char *what;     /* "a line", "a bezier-surface", ... */
    const char *noun;     /* "points", "tangents", "weights" */
} netspec;

static const char *axis_name(int dims, int d)
{
    static const char *const s[] = {"s", "t"}, *const u[] = {"u", "v", "w"};
    return dims == 2 ? s[d] : u[d];
}

static coons_status net_walk(ld *L, const netspec *ns, size_t tok, int d, const size_t *shape,
                             double *out, size_t *pos)
{
    if (coons__json_type_of(L->j, tok) != COONS__JSON_ARRAY)
        return fail(L, tok, COONS_E_INVALID, "expected an array of %s, found %s",
                    d + 1 < ns->dims ? "arrays" : ns->noun, kind(L, tok));
    size_t n = coons__json_size(L->j, tok);
    if (n != shape[d])
        return fail(L, tok, COONS_E_INVALID,
                    "found %zu entries here and %zu in the first row: the %s of %s must form "
                    "a rectangular net",
                    n, shape[d], ns->noun, ns->what);
    size_t e = tok + 1;
    coons_status rc = COONS_OK;
    for (size_t i = 0; i < n && !rc; i++, e = coons__json_next(L->j, e)) {
        size_t old = push_index(L, i);
        if (d + 1 < ns->dims)
            rc = net_walk(L, ns, e, d + 1, shape, out, pos);
        else if (ns->leaf == LEAF_WEIGHT) {
            double *w = out + (*pos)++;
            rc = number(L, e, w);
            if (!rc && !(*w > 0.0))
                rc = fail(L, e, COONS_E_INVALID, "weight %.17g is not > 0: weights must be positive",
                          *w);
        } else {
            rc = vec(L, e, ns->leaf, out + 3 * (*pos)++);
        }
        pop(L, old);
    }
    return rc;
}

/* Reads a rectangular net of ns->dims nested arrays; *out is allocated
 * (3 doubles per point or 1 per weight) after the shape has been checked. */
static coons_status net(ld *L, size_t tok, const netspec *ns, size_t shape[3], double **out)
{
    *out = NULL;
    size_t t = tok, old = L->plen, total = 1;
    coons_status rc = COONS_OK;
    shape[0] = shape[1] = shape[2] = 1;
    for (int d = 0; d < ns->dims && !rc; d++) {
        if (coons__json_type_of(L->j, t) != COONS__JSON_ARRAY) {
            rc = fail(L, t, COONS_E_INVALID, "expected an array of %s, found %s",
                      d + 1 < ns->dims ? "arrays" : ns->noun, kind(L, t));
            break;
        }
        size_t n = coons__json_size(L->j, t);
        shape[d] = n;
        char along[16] = "";
        if (ns->dims > 1) snprintf(along, sizeof along, " along %s", axis_name(ns->dims, d));
        if (ns->fixed && n != ns->fixed[d])
            rc = fail(L, t, COONS_E_INVALID,
                      "expected %zu %s%s (one per control point), found %zu", ns->fixed[d],
                      ns->noun, along, n);
        else if (ns->exact && n != ns->min)
            rc = fail(L, t, COONS_E_INVALID, "%s needs exactly %zu %s, found %zu", ns->what,
                      ns->min, ns->noun, n);
        else if (n < ns->min)
            rc = fail(L, t, COONS_E_INVALID, "%s needs at least %zu %s%s, found %zu", ns->what,
                      ns->min, ns->noun, along, n);
        else if (n > L->max_points || (n && total > L->max_points / n))
            rc = fail(L, t, COONS_E_LIMIT,
                      "%s has more than %zu %s: above the limit of %zu points per curve, "
                      "surface or volume (raise max_points; coons2stl --max-points N)",
                      ns->what, L->max_points, ns->noun, L->max_points);
        else if (ns->maxdir && n > ns->maxdir)
            rc = fail(L, t, COONS_E_LIMIT,
                      "%s has %zu %s%s: its degree %zu is above the limit of %d", ns->what, n,
                      ns->noun, along, n - 1, COONS_SPLINE_MAX_DEGREE);
        if (rc) break;
        total *= n;
        if (d + 1 < ns->dims) {
            push_index(L, 0);
            t = t + 1;
        }
    }
    pop(L, old);
    if (rc) return rc;
    double *buf = coons__malloc_array(total, (ns->leaf == LEAF_WEIGHT ? 1 : 3) * sizeof(double));
    if (!buf) return fail(L, tok, COONS_E_NOMEM, "out of memory reading %s", ns->noun);
    size_t pos = 0;
    rc = net_walk(L, ns, tok, 0, shape, buf, &pos);
    if (rc) {
        coons__free(buf);
        return rc;
    }
    *out = buf;
    return COONS_OK;
}

/* Knots of degree p for ncp control points: ncp + p + 1 non-decreasing
 * values, no value more than p+1 times, non-empty domain [k_p, k_ncp]. */
static coons_status knots(ld *L, size_t tok, int p, size_t ncp, double **out)
{
    *out = NULL;
    coons_status rc = expect(L, tok, COONS__JSON_ARRAY, "an array of knots");
    if (rc) return rc;
    size_t need_n = ncp + (size_t)p + 1, n = coons__json_size(L->j, tok);
    if (n != need_n)
        return fail(L, tok, COONS_E_INVALID,
                    "expected %zu knots (number of points %zu + degree %d + 1), found %zu",
                    need_n, ncp, p, n);
    double *k = coons__malloc_array(n, sizeof(double));
    if (!k) return fail(L, tok, COONS_E_NOMEM, "out of memory reading knots");
    size_t e = tok + 1, run = 1;
    for (size_t i = 0; i < n && !rc; i++, e = coons__json_next(L->j, e)) {
        size_t old = push_index(L, i);
        rc = number(L, e, &k[i]);
        if (!rc && i > 0) {
            if (k[i] < k[i - 1])
                rc = fail(L, e, COONS_E_INVALID,
                          "knot %zu (%.17g) is smaller than knot %zu (%.17g): knots must be "
                          "non-decreasing",
                          i, k[i], i - 1, k[i - 1]);
            else if (k[i] == k[i - 1] && ++run > (size_t)p + 1)
                rc = fail(L, e, COONS_E_INVALID,
                          "the knot value %.17g appears more than degree + 1 = %d times", k[i],
                          p + 1);
            else if (k[i] != k[i - 1])
                run = 1;
        }
        pop(L, old);
    }
    if (!rc && !(k[p] < k[ncp]))
        rc = fail(L, tok, COONS_E_INVALID,
                  "the domain [knots[%d], knots[%zu]] = [%.17g, %.17g] is empty: it must have a "
                  "positive length",
                  p, ncp, k[p], k[ncp]);
    if (rc) {
        coons__free(k);
        return rc;
    }
    *out = k;
    return COONS_OK;
}

/* Reads a blend ("linear" / "cubic"); tok 0 means the default. */
static coons_status blend(ld *L, size_t tok, coons_blend *out)
{
    *out = COONS_BLEND_LINEAR;
    if (!tok) return COONS_OK;
    size_t old = push_key(L, "blend");
    coons_status rc = expect(L, tok, COONS__JSON_STRING, "\"linear\" or \"cubic\"");
    if (!rc) {
        if (coons__json_string_eq(L->j, tok, "cubic"))
            *out = COONS_BLEND_CUBIC;
        else if (!coons__json_string_eq(L->j, tok, "linear")) {
            char s[64];
            text_of(L, tok, s, sizeof s);
            rc = fail(L, tok, COONS_E_INVALID, "unknown blend \"%s\"; expected \"linear\" or \"cubic\"",
                      s);
        }
    }
    pop(L, old);
    return rc;
}

/* Reads a per-direction array of `dims` items (degrees or knot vectors). */
static coons_status tuple(ld *L, size_t tok, size_t dims, const char *desc)
{
    coons_status rc = expect(L, tok, COONS__JSON_ARRAY, desc);
    if (rc) return rc;
    if (coons__json_size(L->j, tok) != dims)
        return fail(L, tok, COONS_E_INVALID, "expected %s, found an array of %zu values", desc,
                    coons__json_size(L->j, tok));
    return COONS_OK;
}

/* ---- curves -------------------------------------------------------------- */

enum { C_LINE, C_POLYLINE, C_BEZIER, C_HERMITE, C_COONS_CUBIC, C_CLAMPED, C_BSPLINE };
static const char *const CURVE_TYPES[] = {"line",        "polyline",      "bezier", "hermite",
                                          "coons-cubic", "clamped-cubic", "bspline", NULL};

static coons_status built(ld *L, size_t tok, coons_status rc, const char *what,
                          const coons_error *e)
{
    if (!rc) return COONS_OK;
    return fail(L, tok, rc, "cannot build %s: %s", what, e->message);
}

static coons_status curve(ld *L, size_t obj, coons_curve **out)
{
    int type = 0;
    coons_status rc = type_of_obj(L, obj, "a curve", CURVE_TYPES, &type);
    if (rc) return rc;
    static const char *const K_PTS[] = {"type", "points", NULL};
    static const char *const K_HERMITE[] = {"type", "points", "tangents", NULL};
    static const char *const K_CC[] = {"type", "points", "closed", NULL};
    static const char *const K_BS[] = {"type", "points", "degree", "knots", "weights", NULL};
    const char *const *keys = type == C_HERMITE ? K_HERMITE
                              : type == C_COONS_CUBIC ? K_CC
                              : type == C_BSPLINE ? K_BS
                                                  : K_PTS;
    char what[48];
    snprintf(what, sizeof what, "a %s curve", CURVE_TYPES[type]);
    size_t v[5];
    if ((rc = members(L, obj, what, keys, v,
                      "a blend belongs to coons patches and to body0, body1 and body2, not to "
                      "curves")))
        return rc;
    char keylist[128];
    join(keys, keylist, sizeof keylist);
    char need_msg[192];
    snprintf(need_msg, sizeof need_msg, "%s takes %s", what, keylist);

    int p = 3, closed = 0;
    if (type == C_BSPLINE) {
        if ((rc = need(L, obj, v[2], "degree", need_msg))) return rc;
        size_t old = push_key(L, "degree");
        rc = degree(L, v[2], &p);
        pop(L, old);
        if (rc) return rc;
    }
    if (type == C_COONS_CUBIC && v[2]) {
        size_t old = push_key(L, "closed");
        coons__json_type t = coons__json_type_of(L->j, v[2]);
        if (t == COONS__JSON_TRUE)
            closed = 1;
        else if (t != COONS__JSON_FALSE)
            rc = fail(L, v[2], COONS_E_INVALID, "expected true or false, found %s", kind(L, v[2]));
        pop(L, old);
        if (rc) return rc;
    }
    if ((rc = need(L, obj, v[1], "points", need_msg))) return rc;
    netspec ns = {1, LEAF_POINT, NULL, 2, 0, 0, what, "points"};
    switch (type) {
    case C_LINE: ns.exact = 1; break;
    case C_HERMITE: ns.exact = 1; break;
    case C_BEZIER: ns.maxdir = COONS_SPLINE_MAX_DEGREE + 1; break;
    case C_COONS_CUBIC:
        ns.min = closed ? 3 : 4;
        snprintf(what, sizeof what, "%s coons-cubic curve", closed ? "a closed" : "an open");
        break;
    case C_CLAMPED: ns.min = 4; break;
    case C_BSPLINE: ns.min = (size_t)p + 1; break;
    default: break;
    }
    double *pts = NULL, *tan = NULL, *kn = NULL, *w = NULL;
    size_t shape[3], n = 0;
    size_t old = push_key(L, "points");
    rc = net(L, v[1], &ns, shape, &pts);
    n = shape[0];
    if (!rc && type == C_COONS_CUBIC && closed && n >= 6 &&
        memcmp(pts, pts + 3 * (n - 3), 9 * sizeof(double)) == 0) {
        size_t o2 = push_index(L, n - 3);
        rc = fail(L, coons__json_nth(L->j, v[1], n - 3), COONS_E_INVALID,
                  "a closed coons-cubic curve must not repeat its first three points at the "
                  "end: give the %zu distinct points only (or set \"closed\": false)",
                  n - 3);
        pop(L, o2);
    }
    pop(L, old);
    if (!rc && type == C_HERMITE) {
        if (!(rc = need(L, obj, v[2], "tangents", need_msg))) {
            netspec ts = {1, LEAF_VECTOR, NULL, 2, 1, 0, what, "tangents"};
            old = push_key(L, "tangents");
            rc = net(L, v[2], &ts, shape, &tan);
            pop(L, old);
        }
    }
    if (!rc && type == C_BSPLINE && v[3]) {
        old = push_key(L, "knots");
        rc = knots(L, v[3], p, n, &kn);
        pop(L, old);
    }
    if (!rc && type == C_BSPLINE && v[4]) {
        size_t fixed[3] = {n, 1, 1};
        netspec ws = {1, LEAF_WEIGHT, fixed, 0, 0, 0, what, "weights"};
        old = push_key(L, "weights");
        rc = net(L, v[4], &ws, shape, &w);
        pop(L, old);
    }
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        coons_status r = COONS_OK;
        switch (type) {
        case C_LINE: r = coons_curve_new_line(pts, pts + 3, out, &e); break;
        case C_POLYLINE: r = coons_curve_new_polyline(pts, n, out, &e); break;
        case C_BEZIER: r = coons_curve_new_bezier(pts, n, out, &e); break;
        case C_HERMITE: r = coons_curve_new_hermite(pts, tan, pts + 3, tan + 3, out, &e); break;
        case C_COONS_CUBIC: r = coons_curve_new_coons_cubic(pts, n, closed, out, &e); break;
        case C_CLAMPED: r = coons_curve_new_clamped_cubic(pts, n, out, &e); break;
        default: r = coons_curve_new_bspline(p, pts, n, kn, w, out, &e); break;
        }
        rc = built(L, obj, r, what, &e);
    }
    coons__free(pts);
    coons__free(tan);
    coons__free(kn);
    coons__free(w);
    return rc;
}

/* ---- patches ------------------------------------------------------------- */

enum { P_BILINEAR, P_RULED, P_COONS, P_HERMITE, P_BEZIER, P_BSPLINE };
static const char *const PATCH_TYPES[] = {"bilinear",       "ruled",          "coons",
                                          "hermite-coons",  "bezier-surface", "bspline-surface",
                                          NULL};
static const char *const SIDES[] = {"t0", "t1", "s0", "s1", NULL};

static void free_curves(coons_curve **c, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        coons_curve_free(c[i]);
        c[i] = NULL;
    }
}

/* An object of four curves t0 t1 s0 s1 (boundary or cross); tokv gets
 * their tokens. c may be NULL in pass 1. */
static coons_status four_curves(ld *L, size_t tok, const char *key, const char *what,
                                coons_curve *c[4], size_t tokv[4])
{
    size_t old = push_key(L, key);
    coons_status rc = expect(L, tok, COONS__JSON_OBJECT, what);
    if (!rc) rc = members(L, tok, what, SIDES, tokv, NULL);
    for (int k = 0; k < 4 && !rc; k++)
        if (!tokv[k]) {
            char m[96];
            snprintf(m, sizeof m, "%s needs all four curves t0, t1, s0 and s1", what);
            rc = need(L, tok, 0, SIDES[k], m);
        }
    for (int k = 0; k < 4 && !rc; k++) {
        size_t o2 = push_key(L, SIDES[k]);
        rc = curve(L, tokv[k], L->build ? &c[k] : NULL);
        pop(L, o2);
    }
    pop(L, old);
    return rc;
}

static void fmt3(char *b, size_t cap, const double p[3])
{
    snprintf(b, cap, "(%.9g, %.9g, %.9g)", p[0], p[1], p[2]);
}

/* Corners of a Coons patch: X00 = t0(0) = s0(0), X10 = t0(1) = s1(0),
 * X01 = t1(0) = s0(1), X11 = t1(1) = s1(1). */
static coons_status patch_corners(ld *L, coons_curve *const c[4], const size_t tokv[4])
{
    static const struct {
        int a, ta, b, tb;
        const char *name;
    } K[4] = {{0, 0, 2, 0, "X00 (s=0, t=0)"},
              {0, 1, 3, 0, "X10 (s=1, t=0)"},
              {1, 0, 2, 1, "X01 (s=0, t=1)"},
              {1, 1, 3, 1, "X11 (s=1, t=1)"}};
    for (int i = 0; i < 4; i++) {
        double pa[3], pb[3];
        coons_curve_eval(c[K[i].a], K[i].ta, pa);
        coons_curve_eval(c[K[i].b], K[i].tb, pb);
        double d = v3_dist(pa, pb);
        if (!(d <= L->ctol)) {
            char sa[96], sb[96];
            fmt3(sa, sizeof sa, pa);
            fmt3(sb, sizeof sb, pb);
            size_t old = push_key(L, "boundary");
            push_key(L, SIDES[K[i].a]);
            coons_status rc = fail(
                L, tokv[K[i].a], COONS_E_INCOMPATIBLE,
                "boundary curves %s and %s do not meet at corner %s: %s(%d) = %s, %s(%d) = %s, "
                "%.3g apart, more than the tolerance %.3g",
                SIDES[K[i].a], SIDES[K[i].b], K[i].name, SIDES[K[i].a], K[i].ta, sa,
                SIDES[K[i].b], K[i].tb, sb, d, L->ctol);
            pop(L, old);
            return rc;
        }
    }
    return COONS_OK;
}

/* Cross curves against corner tangents: cross.t0(a) = s_a'(0),
 * cross.t1(a) = s_a'(1), cross.s0(b) = t_b'(0), cross.s1(b) = t_b'(1)
 * (s_0 = s0, s_1 = s1, t_0 = t0, t_1 = t1). */
static coons_status cross_check(ld *L, coons_curve *const bd[4], coons_curve *const cr[4],
                                const size_t btok[4])
{
    for (int k = 0; k < 4; k++)
        for (int a = 0; a < 2; a++) {
            /* cross t0/t1 pair with boundary s0/s1 (indices 2,3) at t = k;
             * cross s0/s1 with boundary t0/t1 (0,1) at t = k-2. */
            int other = k < 2 ? 2 + a : a, at = k < 2 ? k : k - 2;
            double c[3], d2[2][3];
            coons_curve_eval(cr[k], a, c);
            coons_curve_eval_derivs(bd[other], at, 1, d2);
            double d = v3_dist(c, d2[1]);
            if (!(d <= L->ctol)) {
                char sa[96], sb[96];
                fmt3(sa, sizeof sa, c);
                fmt3(sb, sizeof sb, d2[1]);
                size_t old = push_key(L, "boundary");
                push_key(L, SIDES[other]);
                coons_status rc = fail(
                    L, btok[other], COONS_E_INCOMPATIBLE,
                    "cross curve %s disagrees with boundary curve %s: cross.%s(%d) = %s but "
                    "%s'(%d) = %s, %.3g apart, more than the tolerance %.3g",
                    SIDES[k], SIDES[other], SIDES[k], a, sa, SIDES[other], at, sb, d, L->ctol);
                pop(L, old);
                return rc;
            }
        }
    return COONS_OK;
}

static coons_status twist(ld *L, size_t tok, coons_hermite_options *o)
{
    static const char *const NAMES[] = {"zero", "adini", "bessel", NULL};
    static const coons_twist VALS[] = {COONS_TWIST_ZERO, COONS_TWIST_ADINI, COONS_TWIST_BESSEL};
    coons__json_type t = coons__json_type_of(L->j, tok);
    const char *desc = "\"zero\", \"adini\", \"bessel\" or an array of 4 twist vectors";
    if (t == COONS__JSON_STRING) {
        for (int i = 0; NAMES[i]; i++)
            if (coons__json_string_eq(L->j, tok, NAMES[i])) {
                o->twist = VALS[i];
                return COONS_OK;
            }
        char s[64];
        text_of(L, tok, s, sizeof s);
        return fail(L, tok, COONS_E_INVALID, "unknown twist \"%s\"; expected %s", s, desc);
    }
    if (t != COONS__JSON_ARRAY)
        return fail(L, tok, COONS_E_INVALID, "expected %s, found %s", desc, kind(L, tok));
    if (coons__json_size(L->j, tok) != 4)
        return fail(L, tok, COONS_E_INVALID,
                    "expected 4 twist vectors [x_st(0,0), x_st(1,0), x_st(0,1), x_st(1,1)], "
                    "found %zu",
                    coons__json_size(L->j, tok));
    size_t e = tok + 1;
    for (int i = 0; i < 4; i++, e = coons__json_next(L->j, e)) {
        size_t old = push_index(L, (size_t)i);
        coons_status rc = vec(L, e, LEAF_VECTOR, o->twists[i]);
        pop(L, old);
        if (rc) return rc;
    }
    o->twist = COONS_TWIST_EXPLICIT;
    return COONS_OK;
}

/* Tensor-product B-spline data shared by surfaces (dims 2) and volumes (3). */
static coons_status tensor(ld *L, size_t obj, int dims, int is_bspline, const char *what,
                           size_t vpoints, size_t vdeg, size_t vknots, size_t vweights,
                           int deg[3], size_t n[3], double **pts, double *kn[3], double **w,
                           const char *need_msg)
{
    coons_status rc;
    size_t old;
    deg[0] = deg[1] = deg[2] = 1;
    if (is_bspline) {
        if ((rc = need(L, obj, vdeg, "degree", need_msg))) return rc;
        old = push_key(L, "degree");
        char desc[64];
        snprintf(desc, sizeof desc, "an array of %d degrees %s", dims,
                 dims == 2 ? "[p, q]" : "[l, m, n]");
        rc = tuple(L, vdeg, (size_t)dims, desc);
        size_t e = vdeg + 1;
        for (int d = 0; d < dims && !rc; d++, e = coons__json_next(L->j, e)) {
            size_t o2 = push_index(L, (size_t)d);
            rc = degree(L, e, &deg[d]);
            pop(L, o2);
        }
        pop(L, old);
        if (rc) return rc;
    }
    if ((rc = need(L, obj, vpoints, "points", need_msg))) return rc;
    netspec ns = {dims, LEAF_POINT, NULL, 2, 0, is_bspline ? 0 : COONS_SPLINE_MAX_DEGREE + 1, what,
                  "points"};
    old = push_key(L, "points");
    rc = net(L, vpoints, &ns, n, pts);
    pop(L, old);
    if (rc) return rc;
    if (is_bspline)
        for (int d = 0; d < dims; d++)
            if (n[d] < (size_t)deg[d] + 1) {
                old = push_key(L, "points");
                rc = fail(L, vpoints, COONS_E_INVALID,
                          "%s of degree %d along %s needs at least %d points along %s, found %zu",
                          what, deg[d], axis_name(dims, d), deg[d] + 1, axis_name(dims, d), n[d]);
                pop(L, old);
                return rc;
            }
    if (vknots) {
        old = push_key(L, "knots");
        char desc[64];
        snprintf(desc, sizeof desc, "an array of %d knot vectors", dims);
        rc = tuple(L, vknots, (size_t)dims, desc);
        size_t e = vknots + 1;
        for (int d = 0; d < dims && !rc; d++, e = coons__json_next(L->j, e)) {
            size_t o2 = push_index(L, (size_t)d);
            rc = knots(L, e, deg[d], n[d], &kn[d]);
            pop(L, o2);
        }
        pop(L, old);
        if (rc) return rc;
    }
    if (vweights) {
        netspec ws = {dims, LEAF_WEIGHT, n, 0, 0, 0, what, "weights"};
        size_t wshape[3];
        old = push_key(L, "weights");
        rc = net(L, vweights, &ws, wshape, w);
        pop(L, old);
    }
    return rc;
}

static coons_status patch(ld *L, size_t obj, coons_patch **out)
{
    int type = 0;
    coons_status rc = type_of_obj(L, obj, "a patch", PATCH_TYPES, &type);
    if (rc) return rc;
    static const char *const K_BIL[] = {"type", "corners", NULL};
    static const char *const K_RULED[] = {"type", "curves", NULL};
    static const char *const K_COONS[] = {"type", "boundary", "blend", NULL};
    static const char *const K_HERM[] = {"type", "boundary", "cross", "twist", NULL};
    static const char *const K_BEZ[] = {"type", "points", NULL};
    static const char *const K_BSP[] = {"type", "points", "degree", "knots", "weights", NULL};
    static const char *const *const KEYS[] = {K_BIL, K_RULED, K_COONS, K_HERM, K_BEZ, K_BSP};
    const char *const *keys = KEYS[type];
    char what[48];
    snprintf(what, sizeof what, "a %s patch", PATCH_TYPES[type]);
    size_t v[5];
    if ((rc = members(L, obj, what, keys, v,
                      "only a coons patch (and body0, body1, body2) has a blend")))
        return rc;
    char keylist[128], need_msg[192];
    join(keys, keylist, sizeof keylist);
    snprintf(need_msg, sizeof need_msg, "%s takes %s", what, keylist);

    coons_curve *bd[4] = {0}, *cr[4] = {0};
    size_t btok[4] = {0}, ctok[4] = {0};
    double *pts = NULL, *kn[3] = {0}, *w = NULL;
    coons_error e = COONS_ERROR_INIT;
    coons_status r = COONS_OK;
    switch (type) {
    case P_BILINEAR: {
        if ((rc = need(L, obj, v[1], "corners", need_msg))) break;
        netspec ns = {1, LEAF_POINT, NULL, 4, 1, 0, what, "corners"};
        size_t shape[3], old = push_key(L, "corners");
        rc = net(L, v[1], &ns, shape, &pts);
        pop(L, old);
        if (!rc && L->build) {
            r = coons_patch_new_bilinear(pts, out, &e);
            rc = built(L, obj, r, what, &e);
        }
        break;
    }
    case P_RULED: {
        if ((rc = need(L, obj, v[1], "curves", need_msg))) break;
        size_t old = push_key(L, "curves");
        rc = expect(L, v[1], COONS__JSON_ARRAY, "an array of 2 curves [c0, c1]");
        if (!rc && coons__json_size(L->j, v[1]) != 2)
            rc = fail(L, v[1], COONS_E_INVALID, "a ruled patch needs exactly 2 curves, found %zu",
                      coons__json_size(L->j, v[1]));
        size_t t = v[1] + 1;
        for (int k = 0; k < 2 && !rc; k++, t = coons__json_next(L->j, t)) {
            size_t o2 = push_index(L, (size_t)k);
            rc = curve(L, t, L->build ? &bd[k] : NULL);
            pop(L, o2);
        }
        pop(L, old);
        if (!rc && L->build) {
            r = coons_patch_new_ruled(bd[0], bd[1], out, &e);
            rc = built(L, obj, r, what, &e);
        }
        break;
    }
    case P_COONS:
    case P_HERMITE: {
        coons_blend bl = COONS_BLEND_LINEAR;
        coons_hermite_options ho = COONS_HERMITE_OPTIONS_INIT;
        if ((rc = need(L, obj, v[1], "boundary", need_msg))) break;
        if ((rc = four_curves(L, v[1], "boundary", "a boundary", bd, btok))) break;
        if (type == P_COONS) {
            if ((rc = blend(L, v[2], &bl))) break;
        } else {
            if (v[2]) {
                int was = L->bbox_on;
                L->bbox_on = 0; /* cross curves are tangents, not points */
                rc = four_curves(L, v[2], "cross", "cross", cr, ctok);
                L->bbox_on = was;
                if (rc) break;
            }
            if (v[3]) {
                size_t old = push_key(L, "twist");
                rc = twist(L, v[3], &ho);
                pop(L, old);
                if (rc) break;
            }
        }
        if (!L->build) break;
        if ((rc = patch_corners(L, bd, btok))) break;
        if (type == P_HERMITE && v[2] && (rc = cross_check(L, bd, cr, btok))) break;
        if (type == P_COONS)
            r = coons_patch_new_coons(bd, bl, L->ctol, out, &e);
        else {
            if (v[2])
                for (int k = 0; k < 4; k++) ho.cross[k] = cr[k];
            ho.tol = L->ctol;
            r = coons_patch_new_hermite_coons(bd, &ho, out, &e);
        }
        rc = built(L, obj, r, what, &e);
        break;
    }
    default: {
        int deg[3];
        size_t n[3];
        int bs = type == P_BSPLINE;
        rc = tensor(L, obj, 2, bs, what, v[1], bs ? v[2] : 0, bs ? v[3] : 0, bs ? v[4] : 0, deg,
                    n, &pts, kn, &w, need_msg);
        if (!rc && L->build) {
            if (bs)
                r = coons_patch_new_bspline(deg[0], deg[1], pts, n[0], n[1], kn[0], kn[1], w, out, &e);
            else
                r = coons_patch_new_bezier(pts, n[0], n[1], out, &e);
            rc = built(L, obj, r, what, &e);
        }
        break;
    }
    }
    free_curves(bd, 4);
    free_curves(cr, 4);
    coons__free(pts);
    for (int d = 0; d < 3; d++) coons__free(kn[d]);
    coons__free(w);
    return rc;
}

/* ---- bodies -------------------------------------------------------------- */

enum { B_BODY0, B_BODY1, B_BODY2, B_BEZIER, B_BSPLINE };
static const char *const BODY_TYPES[] = {"body0", "body1", "body2", "bezier-volume",
                                         "bspline-volume", NULL};
static const char *const EDGES[] = {"u00", "u01", "u10", "u11", "v00", "v01", "v10",
                                    "v11", "w00", "w01", "w10", "w11", NULL};
static const char *const FACES[] = {"u0", "u1", "v0", "v1", "w0", "w1", NULL};

/* Body 1 corners P_ijk: u_jk(i) = v_ik(j) = w_ij(k). */
static coons_status body1_corners(ld *L, coons_curve *const c[12], const size_t tok[12])
{
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) {
                int idx[3] = {2 * j + k, 4 + 2 * i + k, 8 + 2 * i + j}, par[3] = {i, j, k};
                double p[3][3];
                for (int q = 0; q < 3; q++) coons_curve_eval(c[idx[q]], par[q], p[q]);
                for (int a = 0; a < 3; a++)
                    for (int b = a + 1; b < 3; b++) {
                        double d = v3_dist(p[a], p[b]);
                        if (d <= L->ctol) continue;
                        char sa[96], sb[96];
                        fmt3(sa, sizeof sa, p[a]);
                        fmt3(sb, sizeof sb, p[b]);
                        size_t old = push_key(L, "edges");
                        push_key(L, EDGES[idx[a]]);
                        coons_status rc = fail(
                            L, tok[idx[a]], COONS_E_INCOMPATIBLE,
                            "edges %s and %s do not meet at corner P%d%d%d (u=%d, v=%d, w=%d): "
                            "%s(%d) = %s, %s(%d) = %s, %.3g apart, more than the tolerance %.3g",
                            EDGES[idx[a]], EDGES[idx[b]], i, j, k, i, j, k, EDGES[idx[a]], par[a],
                            sa, EDGES[idx[b]], par[b], sb, d, L->ctol);
                        pop(L, old);
                        return rc;
                    }
            }
    return COONS_OK;
}

/* Body 2 shared edges, parametrically: u-edge (v=J, w=K) is v_J(x, K) =
 * w_K(x, J); v-edge (u=I, w=K) is u_I(x, K) = w_K(I, x); w-edge (u=I, v=J)
 * is u_I(J, x) = v_J(I, x). Face order u0 u1 v0 v1 w0 w1, so the first face
 * of each pair is the one named first. */
static coons_status body2_edges(ld *L, coons_patch *const f[6], const size_t tok[6])
{
    for (int e = 0; e < 12; e++) {
        int dir = e / 4, A = (e / 2) % 2, B = e % 2;
        int fa, fb;
        if (dir == 0) {
            fa = 2 + A;
            fb = 4 + B;
        } else if (dir == 1) {
            fa = A;
            fb = 4 + B;
        } else {
            fa = A;
            fb = 2 + B;
        }
        double worst = -1, wx = 0, wa[3] = {0}, wb[3] = {0};
        for (int s = 0; s < EDGE_SAMPLES; s++) {
            double x = (double)s / (EDGE_SAMPLES - 1), pa[3], pb[3];
            if (dir == 0) {
                coons_patch_eval(f[fa], x, B, pa);
                coons_patch_eval(f[fb], x, A, pb);
            } else if (dir == 1) {
                coons_patch_eval(f[fa], x, B, pa);
                coons_patch_eval(f[fb], A, x, pb);
            } else {
                coons_patch_eval(f[fa], B, x, pa);
                coons_patch_eval(f[fb], A, x, pb);
            }
            double d = v3_dist(pa, pb);
            if (!(d <= worst) && !(d <= L->ctol)) {
                worst = isnan(d) ? INFINITY : d;
                wx = x;
                v3_copy(wa, pa);
                v3_copy(wb, pb);
            }
        }
        if (worst >= 0) {
            static const char *const EN[] = {"u00", "u01", "u10", "u11", "v00", "v01",
                                             "v10", "v11", "w00", "w01", "w10", "w11"};
            static const char AX[] = {'u', 'v', 'w'};
            char sa[96], sb[96];
            fmt3(sa, sizeof sa, wa);
            fmt3(sb, sizeof sb, wb);
            size_t old = push_key(L, "faces");
            push_key(L, FACES[fa]);
            coons_status rc = fail(
                L, tok[fa], COONS_E_INCOMPATIBLE,
                "faces %s and %s disagree along their shared edge %s: at %c = %.6g, %s gives %s "
                "and %s gives %s, %.3g apart, more than the tolerance %.3g",
                FACES[fa], FACES[fb], EN[e], AX[dir], wx, FACES[fa], sa, FACES[fb], sb, worst,
                L->ctol);
            pop(L, old);
            return rc;
        }
    }
    return COONS_OK;
}

static coons_status body(ld *L, size_t obj, size_t index, coons_body **out)
{
    int type = 0;
    coons_status rc = type_of_obj(L, obj, "a body", BODY_TYPES, &type);
    if (rc) return rc;
    static const char *const K_B0[] = {"type", "name", "blend", "corners", NULL};
    static const char *const K_B1[] = {"type", "name", "blend", "edges", NULL};
    static const char *const K_B2[] = {"type", "name", "blend", "faces", NULL};
    static const char *const K_BZ[] = {"type", "name", "points", NULL};
    static const char *const K_BS[] = {"type", "name", "points", "degree", "knots", "weights", NULL};
    static const char *const *const KEYS[] = {K_B0, K_B1, K_B2, K_BZ, K_BS};
    const char *const *keys = KEYS[type];
    char what[48];
    snprintf(what, sizeof what, "a %s", BODY_TYPES[type]);
    size_t v[6];
    char hint[128];
    snprintf(hint, sizeof hint,
             "\"blend\" is allowed on body0, body1 and body2 only, not on a %s",
             BODY_TYPES[type]);
    if ((rc = members(L, obj, what, keys, v, hint))) return rc;
    char keylist[128], need_msg[192];
    join(keys, keylist, sizeof keylist);
    snprintf(need_msg, sizeof need_msg, "%s takes %s", what, keylist);

    if (v[1] && !L->build) {
        size_t old = push_key(L, "name");
        rc = expect(L, v[1], COONS__JSON_STRING, "a string (the body's name)");
        if (!rc) {
            char probe[2];
            size_t len = coons__json_string(L->j, v[1], probe, sizeof probe);
            char *s = coons__malloc(len + 1);
            if (!s)
                rc = fail(L, v[1], COONS_E_NOMEM, "out of memory");
            else {
                coons__json_string(L->j, v[1], s, len + 1);
                L->names[index].name = s;
                L->names[index].tok = v[1];
                if (len == 0)
                    rc = fail(L, v[1], COONS_E_INVALID, "a body name must not be empty");
                else if (strlen(s) != len)
                    rc = fail(L, v[1], COONS_E_INVALID, "a body name must not contain U+0000");
            }
        }
        pop(L, old);
        if (rc) return rc;
    }
    coons_blend bl = COONS_BLEND_LINEAR;
    if (type <= B_BODY2 && (rc = blend(L, v[2], &bl))) return rc;

    coons_curve *c[12] = {0};
    coons_patch *f[6] = {0};
    size_t sub[12];
    double *pts = NULL, *kn[3] = {0}, *w = NULL;
    coons_error e = COONS_ERROR_INIT;
    coons_status r = COONS_OK;
    switch (type) {
    case B_BODY0: {
        if ((rc = need(L, obj, v[3], "corners", need_msg))) break;
        netspec ns = {1, LEAF_POINT, NULL, 8, 1, 0, what, "corners"};
        size_t shape[3], old = push_key(L, "corners");
        rc = net(L, v[3], &ns, shape, &pts);
        pop(L, old);
        if (!rc && L->build) {
            r = coons_body_new_body0(pts, bl, out, &e);
            rc = built(L, obj, r, what, &e);
        }
        break;
    }
    case B_BODY1:
    case B_BODY2: {
        int is1 = type == B_BODY1;
        const char *key = is1 ? "edges" : "faces";
        const char *const *names = is1 ? EDGES : FACES;
        size_t cnt = is1 ? 12 : 6;
        if ((rc = need(L, obj, v[3], key, need_msg))) break;
        size_t old = push_key(L, key);
        char desc[96];
        snprintf(desc, sizeof desc, "%s", is1 ? "the 12 edges of a body1" : "the 6 faces of a body2");
        rc = expect(L, v[3], COONS__JSON_OBJECT, is1 ? "an object of 12 edge curves"
                                                      : "an object of 6 face patches");
        if (!rc) rc = members(L, v[3], desc, names, sub, NULL);
        for (size_t k = 0; k < cnt && !rc; k++)
            if (!sub[k]) {
                char m[320];
                char list[128];
                join(names, list, sizeof list);
                snprintf(m, sizeof m, "%s are all required: %s", desc, list);
                rc = need(L, v[3], 0, names[k], m);
            }
        for (size_t k = 0; k < cnt && !rc; k++) {
            size_t o2 = push_key(L, names[k]);
            if (is1)
                rc = curve(L, sub[k], L->build ? &c[k] : NULL);
            else
                rc = patch(L, sub[k], L->build ? &f[k] : NULL);
            pop(L, o2);
        }
        pop(L, old);
        if (rc || !L->build) break;
        if (is1) {
            if ((rc = body1_corners(L, c, sub))) break;
            r = coons_body_new_body1(c, bl, L->ctol, out, &e);
        } else {
            if ((rc = body2_edges(L, f, sub))) break;
            r = coons_body_new_body2(f, bl, L->ctol, out, &e);
        }
        if (r == COONS_E_INCOMPATIBLE) {
            /* The constructor saw a disagreement that the checks above did not
             * (other sample points): point at the edges/faces object. */
            old = push_key(L, key);
            rc = fail(L, v[3], r, "%s", e.message);
            pop(L, old);
        } else
            rc = built(L, obj, r, what, &e);
        break;
    }
    default: {
        int deg[3];
        size_t n[3];
        int bs = type == B_BSPLINE;
        rc = tensor(L, obj, 3, bs, what, v[2], bs ? v[3] : 0, bs ? v[4] : 0, bs ? v[5] : 0, deg,
                    n, &pts, kn, &w, need_msg);
        if (!rc && L->build) {
            if (bs) {
                r = coons_body_new_bspline(deg, pts, n, kn[0], kn[1], kn[2], w, out, &e);
            } else
                r = coons_body_new_bezier(pts, n, out, &e);
            rc = built(L, obj, r, what, &e);
        }
        break;
    }
    }
    free_curves(c, 12);
    for (int k = 0; k < 6; k++) coons_patch_free(f[k]);
    coons__free(pts);
    for (int d = 0; d < 3; d++) coons__free(kn[d]);
    coons__free(w);
    return rc;
}

/* ---- top level ----------------------------------------------------------- */

static int cmp_names(const void *a, const void *b)
{
    const name_rec *x = a, *y = b;
    int c = strcmp(x->name, y->name);
    if (c) return c;
    return x->tok < y->tok ? -1 : x->tok > y->tok;
}

/* Names must be unique: report the first repeated one in document order. */
static coons_status unique_names(ld *L, size_t nb)
{
    size_t k = 0;
    for (size_t i = 0; i < nb; i++)
        if (L->names[i].name) k++;
    if (k < 2) return COONS_OK;
    name_rec *s = coons__malloc_array(k, sizeof *s);
    if (!s) return fail(L, 0, COONS_E_NOMEM, "out of memory");
    k = 0;
    for (size_t i = 0; i < nb; i++)
        if (L->names[i].name) s[k++] = L->names[i];
    qsort(s, k, sizeof *s, cmp_names);
    size_t bad = 0, first = 0;
    for (size_t i = 1; i < k; i++)
        if (strcmp(s[i].name, s[i - 1].name) == 0 && (i < 2 || strcmp(s[i - 1].name, s[i - 2].name))) {
            if (!bad || s[i].tok < bad) {
                bad = s[i].tok;
                first = s[i - 1].tok;
            }
        }
    coons__free(s);
    if (!bad) return COONS_OK;
    /* Find the body indices for the message and the path. */
    size_t bi = 0, fi = 0;
    for (size_t i = 0; i < nb; i++) {
        if (L->names[i].tok == bad) bi = i;
        if (L->names[i].tok == first) fi = i;
    }
    char nm[128];
    snprintf(nm, sizeof nm, "%s", L->names[bi].name);
    sanitize(nm);
    int line, col;
    coons__json_line_col(L->buf, L->len, coons__json_start(L->j, first), &line, &col);
    size_t old = push_key(L, "bodies");
    push_index(L, bi);
    push_key(L, "name");
    coons_status rc = fail(L, bad, COONS_E_INVALID,
                           "body name \"%s\" is already used by body %zu (line %d, column %d): "
                           "names must be unique",
                           nm, fi, line, col);
    pop(L, old);
    return rc;
}

static const char *const TOP_KEYS[] = {"coons", "units", "tolerance", "operation", "bodies", NULL};

/* Pass 1 on the top level: version, keys, settings; bodies follow. */
static coons_status top(ld *L)
{
    size_t root = 0, v[5];
    size_t ver = member(L, root, "coons");
    if (!ver)
        return fail(L, root, COONS_E_INVALID,
                    "missing key \"coons\": a model starts with \"coons\": 1, the format version");
    size_t old = push_key(L, "coons");
    double x = 0;
    coons_status rc = COONS_OK;
    if (coons__json_type_of(L->j, ver) != COONS__JSON_NUMBER)
        rc = fail(L, ver, COONS_E_INVALID, "expected the format version 1, found %s",
                  kind(L, ver));
    else if (!(rc = number(L, ver, &x)) && x != 1.0) {
        size_t len;
        const char *t = coons__json_text(L->j, ver, &len);
        rc = fail(L, ver, COONS_E_UNSUPPORTED,
                  "format version %.*s is not supported: this libcoons reads version 1",
                  len > 40 ? 40 : (int)len, t);
    }
    pop(L, old);
    if (rc) return rc;
    if ((rc = members(L, root, "the model", TOP_KEYS, v, NULL))) return rc;
    if (v[1]) {
        old = push_key(L, "units");
        rc = expect(L, v[1], COONS__JSON_STRING, "a string such as \"mm\"");
        if (!rc) {
            char probe[2];
            size_t len = coons__json_string(L->j, v[1], probe, sizeof probe);
            /* units are printed into outputs: keep them a short, plain string */
            char u[80];
            coons__json_string(L->j, v[1], u, sizeof u);
            if (len >= sizeof u)
                rc = fail(L, v[1], COONS_E_INVALID, "units must be at most %zu bytes long",
                          sizeof u - 1);
            else if (strlen(u) != len)
                rc = fail(L, v[1], COONS_E_INVALID, "units must not contain U+0000");
        }
        pop(L, old);
        if (rc) return rc;
        L->units_tok = v[1];
    }
    if (v[2]) {
        old = push_key(L, "tolerance");
        rc = number(L, v[2], &L->tolerance);
        if (!rc && !(L->tolerance > 0))
            rc = fail(L, v[2], COONS_E_INVALID,
                      "tolerance must be > 0 (a distance in model units), found %.17g",
                      L->tolerance);
        pop(L, old);
        if (rc) return rc;
    }
    if (v[3]) {
        old = push_key(L, "operation");
        rc = expect(L, v[3], COONS__JSON_STRING, "\"union\" or \"none\"");
        if (!rc) {
            if (coons__json_string_eq(L->j, v[3], "union"))
                L->op = COONS_OP_UNION;
            else if (coons__json_string_eq(L->j, v[3], "none"))
                L->op = COONS_OP_NONE;
            else {
                char s[64];
                text_of(L, v[3], s, sizeof s);
                rc = fail(L, v[3], COONS_E_INVALID,
                          "unknown operation \"%s\"; expected \"union\" or \"none\"", s);
            }
        }
        pop(L, old);
        if (rc) return rc;
    }
    if ((rc = need(L, root, v[4], "bodies", "a model needs \"bodies\": an array of one or more bodies")))
        return rc;
    old = push_key(L, "bodies");
    rc = expect(L, v[4], COONS__JSON_ARRAY, "an array of bodies");
    if (!rc && coons__json_size(L->j, v[4]) == 0)
        rc = fail(L, v[4], COONS_E_INVALID, "\"bodies\" is empty: a model needs at least one body");
    pop(L, old);
    L->bodies_tok = v[4];
    return rc;
}

static coons_status bodies(ld *L, coons_model *m)
{
    size_t nb = coons__json_size(L->j, L->bodies_tok), t = L->bodies_tok + 1;
    size_t old = push_key(L, "bodies");
    coons_status rc = COONS_OK;
    for (size_t i = 0; i < nb && !rc; i++, t = coons__json_next(L->j, t)) {
        size_t o2 = push_index(L, i);
        rc = body(L, t, i, m ? &m->bodies[i] : NULL);
        pop(L, o2);
    }
    pop(L, old);
    return rc;
}

static coons_status load(ld *L, coons_model **out)
{
    coons_status rc = top(L);
    if (rc) return rc;
    size_t nb = coons__json_size(L->j, L->bodies_tok);
    L->names = coons__calloc(nb, sizeof *L->names);
    if (!L->names) return fail(L, 0, COONS_E_NOMEM, "out of memory");
    bbox_empty(L->lo, L->hi);
    L->bbox_on = 1;
    if ((rc = bodies(L, NULL))) return rc;
    if ((rc = unique_names(L, nb))) return rc;

    double diag = bbox_diag(L->lo, L->hi);
    double tol = L->tolerance > 0 ? L->tolerance : diag / 1000.0;
    if (!(tol > 0) || !isfinite(tol)) {
        if (!isfinite(diag))
            return fail(L, 0, COONS_E_INVALID,
                        "the control points span more than the largest double: the model's "
                        "size is not finite");
        return fail(L, 0, COONS_E_INVALID,
                    "all control points coincide, so the default tolerance (1/1000 of the "
                    "bounding-box diagonal) would be 0: give \"tolerance\"");
    }
    if (!isfinite(diag))
        return fail(L, 0, COONS_E_INVALID,
                    "the control points span more than the largest double: the model's size is "
                    "not finite");
    L->ctol = diag > 0 ? 1e-9 * diag : DBL_MIN;

    coons_model *m = NULL;
    coons_error e = COONS_ERROR_INIT;
    if (coons__model_alloc(nb, &m, &e)) return fail(L, 0, COONS_E_NOMEM, "out of memory");
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
    for (size_t i = 0; i < nb && !rc; i++)
        if (!m->units || !m->names[i]) rc = fail(L, 0, COONS_E_NOMEM, "out of memory");
    if (!rc) {
        L->build = 1;
        rc = bodies(L, m);
    }
    if (rc) {
        coons_model_free(m);
        return rc;
    }
    *out = m;
    return COONS_OK;
}

static void resolve(const coons_model_load_options *o, coons_model_load_options *r)
{
    coons_model_load_options d = COONS_MODEL_LOAD_OPTIONS_INIT;
    if (o) d = *o;
    if (!d.max_bytes) d.max_bytes = COONS_MODEL_MAX_BYTES;
    if (d.max_bytes > (size_t)INT32_MAX - 2) d.max_bytes = (size_t)INT32_MAX - 2; /* jsmn: int */
    if (!d.max_values) d.max_values = COONS_MODEL_MAX_VALUES;
    if (!d.max_depth) d.max_depth = COONS_MODEL_MAX_DEPTH;
    if (d.max_depth > COONS__JSON_DEPTH_CEILING) d.max_depth = COONS__JSON_DEPTH_CEILING;
    if (!d.max_points) d.max_points = COONS_MODEL_MAX_POINTS;
    *r = d;
}

/* An error about the file as a whole: no line, column or path. */
static coons_status file_error(coons_error *err, coons_status code, const char *file,
                               const char *fmt, ...) COONS__PRINTF(4, 5);
static coons_status file_error(coons_error *err, coons_status code, const char *file,
                               const char *fmt, ...)
{
    if (!err) return code;
    char msg[COONS_ERROR_MESSAGE_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    coons__error_set(err, code, "%s: %s", file, msg);
    copy_trunc(err->file, sizeof err->file, file);
    return code;
}

coons_status coons_model_load_memory(const char *data, size_t size, const char *name,
                                     const coons_model_load_options *opts,
                                     coons_model **out, coons_error *err)
{
    if (out) *out = NULL;
    const char *file = name ? name : "<buffer>";
    if (!out || (!data && size))
        return file_error(err, COONS_E_INVALID, file, "no data or no place for the model");
    coons_status vrc = coons__model_load_options_check(opts, err);
    if (vrc) return vrc;
    coons_model_load_options o;
    resolve(opts, &o);
    if (size > o.max_bytes)
        return file_error(err, COONS_E_LIMIT, file,
                          "the model is %zu bytes, above the limit of %zu bytes (raise "
                          "max_bytes; coons2stl --max-bytes N)",
                          size, o.max_bytes);
    ld L;
    memset(&L, 0, sizeof L);
    L.buf = data ? data : "";
    L.len = size;
    L.file = file;
    L.err = err;
    L.max_points = o.max_points;
    L.op = COONS_OP_UNION;

    coons__json *j = NULL;
    coons__json_where where;
    coons_status rc = coons__json_parse(L.buf, size, o.max_values, o.max_depth, &j, &where, err);
    if (rc) {
        if (rc == COONS_E_NOMEM || !err) return rc;
        char msg[COONS_ERROR_MESSAGE_MAX];
        snprintf(msg, sizeof msg, "%s", err->message);
        snprintf(L.path, sizeof L.path, "%s", where.path);
        return fail_at(&L, where.offset, rc, msg);
    }
    L.j = j;
    rc = load(&L, out);
    if (L.names) {
        size_t nb = coons__json_size(j, L.bodies_tok);
        for (size_t i = 0; i < nb; i++) coons__free(L.names[i].name);
        coons__free(L.names);
    }
    coons__json_free(j);
    return rc;
}

static coons_status io_error(coons_error *err, const char *path, const char *what, int errnum)
{
    char buf[256] = "unknown error";
    if (errnum) (void)strerror_r(errnum, buf, sizeof buf);
    return file_error(err, COONS_E_IO, path, "cannot %s: %s", what, buf);
}

coons_status coons_model_load_file(const char *path, const coons_model_load_options *opts,
                                   coons_model **out, coons_error *err)
{
    if (out) *out = NULL;
    if (!path || !out) return file_error(err, COONS_E_INVALID, "?", "no file name");
    coons_status vrc = coons__model_load_options_check(opts, err);
    if (vrc) return vrc;
    coons_model_load_options o;
    resolve(opts, &o);
    errno = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return io_error(err, path, "open the model", errno);
    struct stat st;
    size_t cap = 1 << 16, len = 0;
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode)) {
        if ((uintmax_t)st.st_size > o.max_bytes) {
            fclose(f);
            return file_error(err, COONS_E_LIMIT, path,
                              "the model is %jd bytes, above the limit of %zu bytes (raise "
                              "max_bytes; coons2stl --max-bytes N)",
                              (intmax_t)st.st_size, o.max_bytes);
        }
        cap = (size_t)st.st_size + 1; /* +1: notices a file that grew */
    }
    char *buf = coons__malloc(cap);
    if (!buf) {
        fclose(f);
        return coons__error_nomem(err);
    }
    for (;;) {
        if (len == cap) {
            if (cap > o.max_bytes) break;
            size_t nc = cap > SIZE_MAX / 2 ? SIZE_MAX : cap * 2;
            if (nc > o.max_bytes + 1) nc = o.max_bytes + 1;
            char *nb = coons__realloc(buf, nc);
            if (!nb) {
                coons__free(buf);
                fclose(f);
                return coons__error_nomem(err);
            }
            buf = nb;
            cap = nc;
        }
        errno = 0;
        size_t got = fread(buf + len, 1, cap - len, f);
        len += got;
        if (got == 0) break;
    }
    int bad = ferror(f), errnum = errno;
    fclose(f);
    if (bad) {
        coons__free(buf);
        return io_error(err, path, "read the model", errnum);
    }
    if (len > o.max_bytes) { /* not a regular file: reading stopped past the limit */
        coons__free(buf);
        return file_error(err, COONS_E_LIMIT, path,
                          "the model is more than %zu bytes, the limit (raise max_bytes; "
                          "coons2stl --max-bytes N)",
                          o.max_bytes);
    }
    coons_status rc = coons_model_load_memory(buf, len, path, &o, out, err);
    coons__free(buf);
    return rc;
}
