/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Strict JSON (RFC 8259) with the byte offset of every value, in two runs
 * over the text. The validating scan needs no memory: it checks the whole
 * grammar, UTF-8, escapes, the nesting depth and the number of values,
 * reports the exact offset and JSON pointer of what is wrong, and counts
 * the values, so that the limit is checked and the tokens are sized before
 * anything is allocated. Then fill_tokens() walks the now known-good text
 * once more and fills exactly that many tokens, subtree ends included.
 *
 * The second run replaces jsmn (which needed the scan anyway, kept offsets
 * in int, did not know the byte order mark and left the subtree ends to a
 * third pass). Measured, best of 30 runs, CPU time, -O3: a 38 MB
 * bspline-volume of 10^6 points (4.0 million values) parsed in 157 ms
 * instead of 182 ms (whole load 871 instead of 906 ms); an 8 MB model of
 * 3000 body1 (0.67 million values) in 24 instead of 26 ms (load 160
 * instead of 179 ms); the examples (at most 14 KB) in 0.1 ms either way.
 */
#include <locale.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "json.h"

/* A value: where its text is and how far its subtree reaches. */
typedef struct jtok {
    size_t start;       /* first byte; strings: the one after the opening quote */
    size_t end;         /* scalars: one past the text (strings: the closing quote);
                         * objects and arrays: the number of members or elements */
    uint32_t next;      /* the first token after the subtree */
    unsigned char type; /* coons__json_type */
} jtok;

struct coons__json {
    const char *buf;
    size_t len;
    jtok *tok;
    size_t n;
    locale_t cloc;
};

/* ---- the validating scan ------------------------------------------------ */

typedef struct frame {
    unsigned char is_object;
    unsigned char has_key;
    size_t index;              /* current element of an array */
    size_t key_start, key_end; /* raw key of the current member */
} frame;

typedef struct scanner {
    const char *b;
    size_t n;
    frame st[COONS__JSON_DEPTH_CEILING];
    unsigned depth;
    size_t ntok, max_tokens;
    unsigned max_depth;
    coons__json_where *where;
    coons_error *err;
} scanner;

static size_t decode_raw(const char *s, size_t len, char *dst, size_t cap);

static void where_path(scanner *sc)
{
    char *p = sc->where->path;
    size_t cap = sizeof sc->where->path, len = 0;
    p[0] = '\0';
    for (unsigned d = 0; d < sc->depth; d++) {
        const frame *f = &sc->st[d];
        if (f->is_object) {
            if (!f->has_key) break;
            char key[COONS_ERROR_PATH_MAX];
            size_t k = decode_raw(sc->b + f->key_start, f->key_end - f->key_start, key, sizeof key);
            if (k >= sizeof key) k = sizeof key - 1;
            len = coons__json_pointer_push(p, cap, len, key, k);
        } else {
            char idx[32];
            int k = snprintf(idx, sizeof idx, "%zu", f->index);
            len = coons__json_pointer_push(p, cap, len, idx, (size_t)k);
        }
    }
}

static coons_status COONS__PRINTF(4, 5)
    scan_fail(scanner *sc, coons_status code, size_t offset, const char *fmt, ...)
{
    sc->where->offset = offset;
    where_path(sc);
    if (sc->err) {
        va_list ap;
        va_start(ap, fmt);
        coons__error_set(sc->err, code, "%s", "");
        vsnprintf(sc->err->message, sizeof sc->err->message, fmt, ap);
        va_end(ap);
    }
    return code;
}

static int is_ws(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
static int is_digit(char c) { return c >= '0' && c <= '9'; }

static size_t skip_ws(const scanner *sc, size_t i)
{
    while (i < sc->n && is_ws(sc->b[i])) i++;
    return i;
}

/* Describes the byte at i for messages. */
static const char *describe(const scanner *sc, size_t i, char buf[16])
{
    if (i >= sc->n) return "the end of the input";
    unsigned char c = (unsigned char)sc->b[i];
    if (c >= 0x21 && c < 0x7f)
        snprintf(buf, 16, "'%c'", c);
    else
        snprintf(buf, 16, "byte 0x%02X", c);
    return buf;
}

/* Length of the valid UTF-8 sequence at s (>= 0x80), or 0 (Unicode 15,
 * table 3-7: no overlongs, no surrogates, nothing above U+10FFFF). */
static size_t utf8_len(const unsigned char *s, size_t avail)
{
    unsigned char c = s[0];
    size_t len;
    unsigned char lo = 0x80, hi = 0xBF;
    if (c >= 0xC2 && c <= 0xDF) len = 2;
    else if (c >= 0xE0 && c <= 0xEF) {
        len = 3;
        if (c == 0xE0) lo = 0xA0;
        if (c == 0xED) hi = 0x9F;
    } else if (c >= 0xF0 && c <= 0xF4) {
        len = 4;
        if (c == 0xF0) lo = 0x90;
        if (c == 0xF4) hi = 0x8F;
    } else
        return 0;
    if (avail < len) return 0;
    if (s[1] < lo || s[1] > hi) return 0;
    for (size_t k = 2; k < len; k++)
        if (s[k] < 0x80 || s[k] > 0xBF) return 0;
    return len;
}

static int hex4(const char *s, unsigned *out)
{
    unsigned v = 0;
    for (int k = 0; k < 4; k++) {
        char c = s[k];
        v <<= 4;
        if (c >= '0' && c <= '9') v |= (unsigned)(c - '0');
        else if (c >= 'a' && c <= 'f') v |= (unsigned)(c - 'a' + 10);
        else if (c >= 'A' && c <= 'F') v |= (unsigned)(c - 'A' + 10);
        else return 0;
    }
    *out = v;
    return 1;
}

static coons_status unterminated(scanner *sc, size_t start)
{
    return scan_fail(sc, COONS_E_PARSE, start, "unterminated string: expected a closing '\"'");
}

/* i is at the opening quote; *end receives the offset after the closing one. */
static coons_status scan_string(scanner *sc, size_t i, size_t *end)
{
    size_t start = i++;
    for (;;) {
        if (i >= sc->n) return unterminated(sc, start);
        unsigned char c = (unsigned char)sc->b[i];
        if (c == '"') {
            *end = i + 1;
            return COONS_OK;
        }
        if (c == '\\') {
            if (i + 1 >= sc->n) return unterminated(sc, start);
            char e = sc->b[i + 1];
            if (strchr("\"\\/bfnrt", e) && e) {
                i += 2;
                continue;
            }
            if (e != 'u')
                return scan_fail(sc, COONS_E_PARSE, i,
                                 "invalid escape '\\%c' in a string: expected one of \\\" \\\\ "
                                 "\\/ \\b \\f \\n \\r \\t \\uXXXX",
                                 (e >= 0x21 && e < 0x7f) ? e : '?');
            unsigned cp, lo;
            if (i + 6 > sc->n) return unterminated(sc, start);
            if (!hex4(sc->b + i + 2, &cp))
                return scan_fail(sc, COONS_E_PARSE, i,
                                 "invalid escape: \\u must be followed by 4 hexadecimal digits");
            if (cp >= 0xDC00 && cp <= 0xDFFF)
                return scan_fail(sc, COONS_E_PARSE, i,
                                 "invalid escape \\u%04X: a low surrogate without a high one", cp);
            if (cp >= 0xD800 && cp <= 0xDBFF) {
                if (i + 12 > sc->n || sc->b[i + 6] != '\\' || sc->b[i + 7] != 'u' ||
                    !hex4(sc->b + i + 8, &lo) || lo < 0xDC00 || lo > 0xDFFF)
                    return scan_fail(sc, COONS_E_PARSE, i,
                                     "invalid escape \\u%04X: a high surrogate must be followed "
                                     "by a low surrogate \\uDC00..\\uDFFF",
                                     cp);
                i += 12;
            } else
                i += 6;
            continue;
        }
        if (c < 0x20)
            return scan_fail(sc, COONS_E_PARSE, i,
                             "control character U+%04X in a string: write it as an escape", c);
        if (c < 0x80) {
            i++;
            continue;
        }
        size_t k = utf8_len((const unsigned char *)sc->b + i, sc->n - i);
        if (!k)
            return scan_fail(sc, COONS_E_PARSE, i,
                             "invalid UTF-8 (byte 0x%02X): the model must be UTF-8 text", c);
        i += k;
    }
}

/* Quoted excerpt of the text at i for messages: up to a delimiter. */
static int excerpt_len(const scanner *sc, size_t i)
{
    size_t k = i;
    while (k < sc->n && k - i < 40 && !is_ws(sc->b[k]) && !strchr(",]}", sc->b[k]) && sc->b[k])
        k++;
    return (int)(k - i);
}

static coons_status scan_number(scanner *sc, size_t i, size_t *end)
{
    size_t s = i;
    const char *b = sc->b;
    size_t n = sc->n;
    if (b[i] == '-') i++;
    if (i < n && b[i] == '0')
        i++;
    else if (i < n && is_digit(b[i]))
        while (i < n && is_digit(b[i])) i++;
    else
        goto bad;
    if (i < n && b[i] == '.') {
        i++;
        if (!(i < n && is_digit(b[i]))) goto bad;
        while (i < n && is_digit(b[i])) i++;
    }
    if (i < n && (b[i] == 'e' || b[i] == 'E')) {
        i++;
        if (i < n && (b[i] == '+' || b[i] == '-')) i++;
        if (!(i < n && is_digit(b[i]))) goto bad;
        while (i < n && is_digit(b[i])) i++;
    }
    if (i < n && !is_ws(b[i]) && !strchr(",]}", b[i])) goto bad;
    *end = i;
    return COONS_OK;
bad:
    return scan_fail(sc, COONS_E_PARSE, s,
                     "invalid number \"%.*s\": expected JSON number syntax such as -12, 0.5 or "
                     "1e-3",
                     excerpt_len(sc, s), b + s);
}

/* ---- the scan: one step per state ----------------------------------------- */

/* One more value (or key) at i, against the limit. */
static coons_status count_value(scanner *sc, size_t i)
{
    if (++sc->ntok <= sc->max_tokens) return COONS_OK;
    return scan_fail(sc, COONS_E_LIMIT, i,
                     "more than %zu JSON values, the limit (raise max_values; coons2stl "
                     "--max-values N)",
                     sc->max_tokens);
}

/* An object or array opens at i; *state: what comes next (0 VALUE, 1 KEY,
 * 2 AFTER). */
static coons_status open_frame(scanner *sc, size_t i, size_t *at, int *state)
{
    char c = sc->b[i];
    if (sc->depth >= sc->max_depth)
        return scan_fail(sc, COONS_E_LIMIT, i,
                         "arrays and objects nested deeper than the limit of %u levels (raise "
                         "max_depth, at most %u; coons2stl --max-depth N)",
                         sc->max_depth, (unsigned)COONS__JSON_DEPTH_CEILING);
    frame *f = &sc->st[sc->depth++];
    memset(f, 0, sizeof *f);
    f->is_object = (c == '{');
    i = skip_ws(sc, i + 1);
    if (i < sc->n && sc->b[i] == (c == '{' ? '}' : ']')) {
        sc->depth--;
        i++;
        *state = 2;
    } else
        *state = c == '{' ? 1 : 0;
    *at = i;
    return COONS_OK;
}

/* A value at i, counted; *state as for open_frame(). */
static coons_status scan_value(scanner *sc, size_t i, size_t *at, int *state)
{
    const char *b = sc->b;
    char c = b[i], d[16];
    coons_status rc = COONS_OK;
    if (c == '{' || c == '[') return open_frame(sc, i, at, state);
    if (c == '"')
        rc = scan_string(sc, i, at);
    else if (c == '-' || is_digit(c))
        rc = scan_number(sc, i, at);
    else if (c == 't' || c == 'f' || c == 'n') {
        const char *lit = c == 't' ? "true" : c == 'f' ? "false" : "null";
        size_t l = strlen(lit);
        if (sc->n - i < l || memcmp(b + i, lit, l) != 0 ||
            (i + l < sc->n && !is_ws(b[i + l]) && !strchr(",]}", b[i + l])))
            return scan_fail(sc, COONS_E_PARSE, i,
                             "invalid literal \"%.*s\": expected true, false or null",
                             excerpt_len(sc, i), b + i);
        *at = i + l;
    } else
        return scan_fail(sc, COONS_E_PARSE, i, "expected a value, found %s", describe(sc, i, d));
    *state = 2;
    return rc;
}

/* A key at i and the ':' after it; *at: the value. */
static coons_status scan_key(scanner *sc, size_t i, size_t *at)
{
    frame *f = &sc->st[sc->depth - 1];
    char d[16];
    coons_status rc;
    if (i >= sc->n || sc->b[i] != '"')
        return scan_fail(sc, COONS_E_PARSE, i, "expected a key string '\"', found %s",
                         describe(sc, i, d));
    if ((rc = count_value(sc, i))) return rc;
    size_t ks = i;
    if ((rc = scan_string(sc, i, &i))) return rc;
    f->key_start = ks + 1;
    f->key_end = i - 1;
    f->has_key = 1;
    i = skip_ws(sc, i);
    if (i >= sc->n || sc->b[i] != ':')
        return scan_fail(sc, COONS_E_PARSE, i, "expected ':' after the key, found %s",
                         describe(sc, i, d));
    *at = skip_ws(sc, i + 1);
    return COONS_OK;
}

/* After a value: ',' or the closing bracket; *state: what comes next. */
static coons_status scan_after(scanner *sc, size_t i, size_t *at, int *state)
{
    frame *f = &sc->st[sc->depth - 1];
    char close = f->is_object ? '}' : ']', d[16];
    if (i < sc->n && sc->b[i] == ',') {
        i = skip_ws(sc, i + 1);
        if (f->is_object) {
            f->has_key = 0;
            *state = 1;
        } else {
            f->index++;
            *state = 0;
        }
    } else if (i < sc->n && sc->b[i] == close) {
        sc->depth--;
        i++;
    } else
        return scan_fail(sc, COONS_E_PARSE, i, "expected ',' or '%c', found %s", close,
                         describe(sc, i, d));
    *at = i;
    return COONS_OK;
}

/* The top-level object '{' at *at, after a byte order mark (RFC 8259 8.1:
 * may be ignored) and white space. */
static coons_status scan_start(scanner *sc, size_t *at)
{
    size_t i = 0;
    char d[16];
    if (sc->n >= 3 && memcmp(sc->b, "\xEF\xBB\xBF", 3) == 0) i = 3;
    i = skip_ws(sc, i);
    if (i >= sc->n) return scan_fail(sc, COONS_E_PARSE, i, "empty document: expected a JSON object");
    if (sc->b[i] != '{')
        return scan_fail(sc, COONS_E_PARSE, i,
                         "expected a JSON object '{' at the top level, found %s",
                         describe(sc, i, d));
    *at = i;
    return COONS_OK;
}

static coons_status scan(scanner *sc)
{
    enum { VALUE, KEY, AFTER };
    int state = VALUE;
    size_t i = 0;
    char d[16];
    coons_status rc = scan_start(sc, &i);
    while (!rc) {
        if (state == VALUE) {
            if (i >= sc->n)
                return scan_fail(sc, COONS_E_PARSE, i, "unexpected end of input: expected a value");
            if (!(rc = count_value(sc, i))) rc = scan_value(sc, i, &i, &state);
        } else if (state == KEY) {
            if (!(rc = scan_key(sc, i, &i))) state = VALUE;
        } else {
            i = skip_ws(sc, i);
            if (sc->depth == 0) break;
            rc = scan_after(sc, i, &i, &state);
        }
    }
    if (rc) return rc;
    if (i < sc->n)
        return scan_fail(sc, COONS_E_PARSE, i,
                         "unexpected %s after the end of the top-level object",
                         describe(sc, i, d));
    return COONS_OK;
}

/* ---- the tokens ------------------------------------------------------- */

/*
 * The second run, over a text the scan has validated: only the tokens, in
 * document order. An array counts its elements and an object its keys; a
 * key's subtree holds its value. Returns the number of tokens (cap + 1
 * if there would be more than cap: the scan and this run disagree).
 */
static size_t fill_tokens(const char *b, size_t n, jtok *out, size_t cap)
{
    uint32_t open[COONS__JSON_DEPTH_CEILING], key[COONS__JSON_DEPTH_CEILING];
    unsigned depth = 0;
    int want_key = 0;
    uint32_t t = 0;
    size_t i = (n >= 3 && memcmp(b, "\xEF\xBB\xBF", 3) == 0) ? 3 : 0;
    while (i < n) {
        char c = b[i];
        jtok *p = depth ? &out[open[depth - 1]] : NULL;
        if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ':') {
            i++;
            continue;
        }
        if (c == ',' || c == '}' || c == ']') {
            if (p->type == COONS__JSON_OBJECT && p->end) out[key[depth - 1]].next = t;
            if (c == ',')
                want_key = p->type == COONS__JSON_OBJECT;
            else
                out[open[--depth]].next = t;
            i++;
            continue;
        }
        if (t == cap) return cap + 1;
        jtok *q = &out[t];
        q->next = t + 1;
        if (c == '"') {
            size_t e = i + 1;
            while (b[e] != '"') e += b[e] == '\\' ? 2 : 1;
            q->type = COONS__JSON_STRING;
            q->start = i + 1;
            q->end = e;
            i = e + 1;
        } else if (c == '{' || c == '[') {
            q->type = c == '{' ? COONS__JSON_OBJECT : COONS__JSON_ARRAY;
            q->start = i++;
            q->end = 0;
        } else {
            size_t e = i;
            while (e < n && b[e] != ',' && b[e] != ']' && b[e] != '}' && b[e] != ' ' &&
                   b[e] != '\n' && b[e] != '\r' && b[e] != '\t')
                e++;
            q->type = c == 't' ? COONS__JSON_TRUE
                    : c == 'f' ? COONS__JSON_FALSE
                    : c == 'n' ? COONS__JSON_NULL
                               : COONS__JSON_NUMBER;
            q->start = i;
            q->end = e;
            i = e;
        }
        if (want_key) {
            key[depth - 1] = t;
            p->end++;
            want_key = 0;
        } else if (p && p->type == COONS__JSON_ARRAY)
            p->end++;
        if (q->type == COONS__JSON_OBJECT || q->type == COONS__JSON_ARRAY) {
            open[depth++] = t;
            want_key = q->type == COONS__JSON_OBJECT;
        }
        t++;
    }
    return t;
}

/* ---- the document ------------------------------------------------------- */

void coons__json_free(coons__json *j)
{
    if (!j) return;
    if (j->cloc != (locale_t)0) freelocale(j->cloc);
    coons__free(j->tok);
    coons__free(j);
}

static void scanner_init(scanner *sc, const char *buf, size_t len, size_t max_tokens,
                         unsigned max_depth, coons__json_where *where, coons_error *err)
{
    sc->b = buf;
    sc->n = len;
    sc->depth = 0;
    sc->ntok = 0;
    sc->max_tokens = max_tokens;
    sc->max_depth = max_depth;
    sc->where = where;
    sc->err = err;
}

coons_status coons__json_parse(const char *buf, size_t len, size_t max_tokens, unsigned max_depth,
                               coons__json **out, coons__json_where *where, coons_error *err)
{
    *out = NULL;
    where->offset = 0;
    where->path[0] = '\0';
    if (max_depth > COONS__JSON_DEPTH_CEILING) max_depth = COONS__JSON_DEPTH_CEILING;
    /* token indices are 32-bit: 4 billion values would take 100 GB */
    if (max_tokens > UINT32_MAX - 1) max_tokens = UINT32_MAX - 1;

    scanner sc;
    scanner_init(&sc, buf, len, max_tokens, max_depth, where, err);
    coons_status rc = scan(&sc);
    if (rc) return rc;

    coons__json *j = coons__calloc(1, sizeof *j);
    if (!j) return coons__error_nomem(err);
    j->buf = buf;
    j->len = len;
    j->n = sc.ntok;
    j->tok = coons__malloc_array(sc.ntok, sizeof *j->tok);
    /* Numbers are read in the "C" locale whatever the process uses. */
    if (j->tok) j->cloc = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    if (!j->tok || j->cloc == (locale_t)0) {
        coons__json_free(j);
        return coons__error_nomem(err);
    }
    size_t count = fill_tokens(buf, len, j->tok, sc.ntok);
    if (count != sc.ntok) {
        coons__json_free(j);
        return coons__error_set(err, COONS_E_INTERNAL,
                                "the tokens disagree with the scan (%zu values, expected %zu)",
                                count, sc.ntok);
    }
    *out = j;
    return COONS_OK;
}

size_t coons__json_count(const coons__json *j) { return j->n; }

coons__json_type coons__json_type_of(const coons__json *j, size_t tok)
{
    return (coons__json_type)j->tok[tok].type;
}

size_t coons__json_start(const coons__json *j, size_t tok)
{
    const jtok *t = &j->tok[tok];
    return t->start - (t->type == COONS__JSON_STRING ? 1 : 0);
}

size_t coons__json_size(const coons__json *j, size_t tok)
{
    const jtok *t = &j->tok[tok];
    return (t->type == COONS__JSON_OBJECT || t->type == COONS__JSON_ARRAY) ? t->end : 0;
}

size_t coons__json_next(const coons__json *j, size_t tok) { return j->tok[tok].next; }

size_t coons__json_nth(const coons__json *j, size_t tok, size_t i)
{
    size_t k = tok + 1;
    while (i--) k = j->tok[k].next;
    return k;
}

static void put_utf8(char *dst, size_t cap, size_t *o, unsigned cp)
{
    char u[4];
    size_t l;
    if (cp < 0x80) {
        u[0] = (char)cp;
        l = 1;
    } else if (cp < 0x800) {
        u[0] = (char)(0xC0 | (cp >> 6));
        u[1] = (char)(0x80 | (cp & 0x3F));
        l = 2;
    } else if (cp < 0x10000) {
        u[0] = (char)(0xE0 | (cp >> 12));
        u[1] = (char)(0x80 | ((cp >> 6) & 0x3F));
        u[2] = (char)(0x80 | (cp & 0x3F));
        l = 3;
    } else {
        u[0] = (char)(0xF0 | (cp >> 18));
        u[1] = (char)(0x80 | ((cp >> 12) & 0x3F));
        u[2] = (char)(0x80 | ((cp >> 6) & 0x3F));
        u[3] = (char)(0x80 | (cp & 0x3F));
        l = 4;
    }
    for (size_t k = 0; k < l; k++, (*o)++)
        if (*o + 1 < cap) dst[*o] = u[k];
}

/* Decodes validated raw string contents. */
static size_t decode_raw(const char *s, size_t len, char *dst, size_t cap)
{
    size_t o = 0;
    for (size_t i = 0; i < len;) {
        char c = s[i];
        if (c != '\\') {
            if (o + 1 < cap) dst[o] = c;
            o++;
            i++;
            continue;
        }
        char e = s[i + 1];
        unsigned cp = 0;
        switch (e) {
        case 'b': cp = '\b'; break;
        case 'f': cp = '\f'; break;
        case 'n': cp = '\n'; break;
        case 'r': cp = '\r'; break;
        case 't': cp = '\t'; break;
        case 'u': break;
        default: cp = (unsigned char)e; break;
        }
        if (e != 'u') {
            put_utf8(dst, cap, &o, cp);
            i += 2;
            continue;
        }
        unsigned lo;
        hex4(s + i + 2, &cp);
        i += 6;
        if (cp >= 0xD800 && cp <= 0xDBFF && i + 6 <= len && hex4(s + i + 2, &lo)) {
            cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
            i += 6;
        }
        put_utf8(dst, cap, &o, cp);
    }
    if (cap) dst[o < cap ? o : cap - 1] = '\0';
    return o;
}

size_t coons__json_string(const coons__json *j, size_t tok, char *dst, size_t cap)
{
    const jtok *t = &j->tok[tok];
    return decode_raw(j->buf + t->start, (size_t)(t->end - t->start), dst, cap);
}

int coons__json_string_eq(const coons__json *j, size_t tok, const char *s)
{
    const jtok *t = &j->tok[tok];
    if (t->type != COONS__JSON_STRING) return 0;
    const char *raw = j->buf + t->start;
    size_t rl = (size_t)(t->end - t->start), sl = strlen(s);
    if (!memchr(raw, '\\', rl)) return rl == sl && memcmp(raw, s, sl) == 0;
    char tmp[128];
    if (sl >= sizeof tmp) return 0;
    size_t dl = decode_raw(raw, rl, tmp, sizeof tmp);
    return dl == sl && memcmp(tmp, s, sl) == 0;
}

const char *coons__json_text(const coons__json *j, size_t tok, size_t *len)
{
    const jtok *t = &j->tok[tok];
    *len = (size_t)(t->end - t->start);
    return j->buf + t->start;
}

coons_status coons__json_number(const coons__json *j, size_t tok, double *out)
{
    const jtok *t = &j->tok[tok];
    /* The scan guarantees a delimiter after the number inside the buffer, so
     * strtod stops at the token's end without a NUL-terminated copy. */
    char *end = NULL;
    locale_t old = uselocale(j->cloc);
    double v = strtod(j->buf + t->start, &end);
    uselocale(old);
    *out = v;
    if (end != j->buf + t->end) return COONS_E_INTERNAL;
    return isfinite(v) ? COONS_OK : COONS_E_INVALID;
}

void coons__json_line_col(const char *buf, size_t len, size_t offset, int *line, int *column)
{
    size_t i = 0;
    long l = 1, c = 1;
    if (offset > len) offset = len;
    if (len >= 3 && memcmp(buf, "\xEF\xBB\xBF", 3) == 0 && offset >= 3) i = 3;
    for (; i < offset; i++) {
        unsigned char ch = (unsigned char)buf[i];
        if (ch == '\n' || (ch == '\r' && !(i + 1 < len && buf[i + 1] == '\n'))) {
            l++;
            c = 1;
        } else if (ch == '\r') {
            /* CR of CR LF: the LF ends the line */
        } else if ((ch & 0xC0) != 0x80)
            c++;
    }
    *line = l > INT32_MAX ? INT32_MAX : (int)l;
    *column = c > INT32_MAX ? INT32_MAX : (int)c;
}

size_t coons__json_pointer_push(char *path, size_t cap, size_t len, const char *key, size_t klen)
{
    if (cap == 0) return 0;
    if (len + 1 < cap) path[len++] = '/';
    for (size_t k = 0; k < klen && len + 1 < cap; k++) {
        char c = key[k];
        if (c == '~' || c == '/') {
            if (len + 2 >= cap) break;
            path[len++] = '~';
            path[len++] = c == '~' ? '0' : '1';
        } else
            path[len++] = c;
    }
    path[len < cap ? len : cap - 1] = '\0';
    return len;
}
