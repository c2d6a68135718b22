/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Strict JSON (RFC 8259) over jsmn. jsmn alone accepts `[1 2]`, `[,1]`,
 * control characters in strings and invalid UTF-8, and reports no useful
 * position, so a validating scan runs first: it needs no memory, gives the
 * exact offset and JSON pointer of any syntax error, and counts the tokens
 * so that the token array is sized (and the limit checked) before anything
 * is allocated. jsmn then only has to record offsets of a known-good text.
 */
#include <locale.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define JSMN_STATIC
#define JSMN_STRICT
#define JSMN_PARENT_LINKS
#include <jsmn.h>

#include "io/json/json.h"

struct coons__json {
    const char *buf;
    size_t len;
    jsmntok_t *tok;
    unsigned *next;
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

static coons_status scan(scanner *sc, size_t max_tokens, unsigned max_depth, size_t *count)
{
    enum { VALUE, KEY, AFTER } state = VALUE;
    const char *b = sc->b;
    size_t i = 0, ntok = 0;
    char d[16];
    coons_status rc;
    if (sc->n >= 3 && memcmp(b, "\xEF\xBB\xBF", 3) == 0) i = 3; /* RFC 8259 8.1: may ignore */
    i = skip_ws(sc, i);
    if (i >= sc->n) return scan_fail(sc, COONS_E_PARSE, i, "empty document: expected a JSON object");
    if (b[i] != '{')
        return scan_fail(sc, COONS_E_PARSE, i,
                         "expected a JSON object '{' at the top level, found %s",
                         describe(sc, i, d));
    for (;;) {
        if (state == VALUE) {
            if (i >= sc->n)
                return scan_fail(sc, COONS_E_PARSE, i, "unexpected end of input: expected a value");
            if (++ntok > max_tokens)
                return scan_fail(sc, COONS_E_LIMIT, i,
                                 "more than %zu JSON values, the limit (raise max_values; "
                                 "coons2stl --max-values N)",
                                 max_tokens);
            char c = b[i];
            if (c == '{' || c == '[') {
                if (sc->depth >= max_depth)
                    return scan_fail(sc, COONS_E_LIMIT, i,
                                     "arrays and objects nested deeper than the limit of %u "
                                     "levels (raise max_depth, at most %u; coons2stl "
                                     "--max-depth N)",
                                     max_depth, (unsigned)COONS__JSON_DEPTH_CEILING);
                frame *f = &sc->st[sc->depth++];
                memset(f, 0, sizeof *f);
                f->is_object = (c == '{');
                i = skip_ws(sc, i + 1);
                if (i < sc->n && b[i] == (c == '{' ? '}' : ']')) {
                    sc->depth--;
                    i++;
                    state = AFTER;
                } else
                    state = c == '{' ? KEY : VALUE;
                continue;
            }
            if (c == '"')
                rc = scan_string(sc, i, &i);
            else if (c == '-' || is_digit(c))
                rc = scan_number(sc, i, &i);
            else if (c == 't' || c == 'f' || c == 'n') {
                const char *lit = c == 't' ? "true" : c == 'f' ? "false" : "null";
                size_t l = strlen(lit);
                if (sc->n - i < l || memcmp(b + i, lit, l) != 0 ||
                    (i + l < sc->n && !is_ws(b[i + l]) && !strchr(",]}", b[i + l])))
                    return scan_fail(sc, COONS_E_PARSE, i,
                                     "invalid literal \"%.*s\": expected true, false or null",
                                     excerpt_len(sc, i), b + i);
                i += l;
                rc = COONS_OK;
            } else
                return scan_fail(sc, COONS_E_PARSE, i, "expected a value, found %s",
                                 describe(sc, i, d));
            if (rc) return rc;
            state = AFTER;
        } else if (state == KEY) {
            frame *f = &sc->st[sc->depth - 1];
            if (i >= sc->n || b[i] != '"')
                return scan_fail(sc, COONS_E_PARSE, i, "expected a key string '\"', found %s",
                                 describe(sc, i, d));
            if (++ntok > max_tokens)
                return scan_fail(sc, COONS_E_LIMIT, i,
                                 "more than %zu JSON values, the limit (raise max_values; "
                                 "coons2stl --max-values N)",
                                 max_tokens);
            size_t ks = i;
            if ((rc = scan_string(sc, i, &i))) return rc;
            f->key_start = ks + 1;
            f->key_end = i - 1;
            f->has_key = 1;
            i = skip_ws(sc, i);
            if (i >= sc->n || b[i] != ':')
                return scan_fail(sc, COONS_E_PARSE, i, "expected ':' after the key, found %s",
                                 describe(sc, i, d));
            i = skip_ws(sc, i + 1);
            state = VALUE;
        } else {
            i = skip_ws(sc, i);
            if (sc->depth == 0) break;
            frame *f = &sc->st[sc->depth - 1];
            char close = f->is_object ? '}' : ']';
            if (i < sc->n && b[i] == ',') {
                i = skip_ws(sc, i + 1);
                if (f->is_object) {
                    f->has_key = 0;
                    state = KEY;
                } else {
                    f->index++;
                    state = VALUE;
                }
            } else if (i < sc->n && b[i] == close) {
                sc->depth--;
                i++;
            } else
                return scan_fail(sc, COONS_E_PARSE, i, "expected ',' or '%c', found %s", close,
                                 describe(sc, i, d));
        }
    }
    if (i < sc->n)
        return scan_fail(sc, COONS_E_PARSE, i,
                         "unexpected %s after the end of the top-level object",
                         describe(sc, i, d));
    *count = ntok;
    return COONS_OK;
}

/* ---- the document ------------------------------------------------------- */

void coons__json_free(coons__json *j)
{
    if (!j) return;
    if (j->cloc != (locale_t)0) freelocale(j->cloc);
    coons__free(j->tok);
    coons__free(j->next);
    coons__free(j);
}

coons_status coons__json_parse(const char *buf, size_t len, size_t max_tokens, unsigned max_depth,
                               coons__json **out, coons__json_where *where, coons_error *err)
{
    *out = NULL;
    where->offset = 0;
    where->path[0] = '\0';
    if (max_depth > COONS__JSON_DEPTH_CEILING) max_depth = COONS__JSON_DEPTH_CEILING;
    /* jsmn keeps offsets in int and counts in unsigned int. */
    if (len >= (size_t)INT32_MAX)
        return coons__error_set(err, COONS_E_LIMIT, "the text is %zu bytes, above jsmn's limit of "
                                "%ld bytes", len, (long)INT32_MAX - 1);
    if (max_tokens > UINT32_MAX / 2) max_tokens = UINT32_MAX / 2;

    scanner sc;
    sc.b = buf;
    sc.n = len;
    sc.depth = 0;
    sc.where = where;
    sc.err = err;
    size_t count = 0;
    coons_status rc = scan(&sc, max_tokens, max_depth, &count);
    if (rc) return rc;

    coons__json *j = coons__calloc(1, sizeof *j);
    if (!j) return coons__error_nomem(err);
    j->buf = buf;
    j->len = len;
    j->n = count;
    j->tok = coons__malloc_array(count, sizeof *j->tok);
    j->next = coons__malloc_array(count, sizeof *j->next);
    if (!j->tok || !j->next) {
        coons__json_free(j);
        return coons__error_nomem(err);
    }
    /* jsmn does not know the byte order mark the scan skipped: it parses
     * the text after it, and the offsets are shifted back onto buf. */
    size_t bom = (len >= 3 && memcmp(buf, "\xEF\xBB\xBF", 3) == 0) ? 3 : 0;
    jsmn_parser p;
    jsmn_init(&p);
    int r = jsmn_parse(&p, buf + bom, len - bom, j->tok, (unsigned)count);
    if (r < 0 || (size_t)r != count) {
        coons__json_free(j);
        return coons__error_set(err, COONS_E_INTERNAL,
                                "jsmn disagrees with the validating scan (%d tokens, expected %zu)",
                                r, count);
    }
    if (bom)
        for (size_t i = 0; i < count; i++) {
            j->tok[i].start += (int)bom;
            j->tok[i].end += (int)bom;
        }
    /* Subtree ends: children follow their parent, so walking backwards each
     * token's end is final before it is propagated to its parent. */
    for (size_t i = 0; i < count; i++) j->next[i] = (unsigned)i + 1;
    for (size_t i = count; i-- > 1;) {
        int par = j->tok[i].parent;
        if (par >= 0 && j->next[i] > j->next[par]) j->next[par] = j->next[i];
    }
    /* Numbers are read in the "C" locale whatever the process uses. */
    j->cloc = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    if (j->cloc == (locale_t)0) {
        coons__json_free(j);
        return coons__error_nomem(err);
    }
    *out = j;
    return COONS_OK;
}

size_t coons__json_count(const coons__json *j) { return j->n; }

coons__json_type coons__json_type_of(const coons__json *j, size_t tok)
{
    const jsmntok_t *t = &j->tok[tok];
    switch (t->type) {
    case JSMN_OBJECT: return COONS__JSON_OBJECT;
    case JSMN_ARRAY: return COONS__JSON_ARRAY;
    case JSMN_STRING: return COONS__JSON_STRING;
    default: break;
    }
    switch (j->buf[t->start]) {
    case 't': return COONS__JSON_TRUE;
    case 'f': return COONS__JSON_FALSE;
    case 'n': return COONS__JSON_NULL;
    default: return COONS__JSON_NUMBER;
    }
}

size_t coons__json_start(const coons__json *j, size_t tok)
{
    const jsmntok_t *t = &j->tok[tok];
    return (size_t)t->start - (t->type == JSMN_STRING ? 1 : 0);
}

size_t coons__json_size(const coons__json *j, size_t tok)
{
    const jsmntok_t *t = &j->tok[tok];
    return (t->type == JSMN_OBJECT || t->type == JSMN_ARRAY) ? (size_t)t->size : 0;
}

size_t coons__json_next(const coons__json *j, size_t tok) { return j->next[tok]; }

size_t coons__json_nth(const coons__json *j, size_t tok, size_t i)
{
    size_t k = tok + 1;
    while (i--) k = j->next[k];
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
    const jsmntok_t *t = &j->tok[tok];
    return decode_raw(j->buf + t->start, (size_t)(t->end - t->start), dst, cap);
}

int coons__json_string_eq(const coons__json *j, size_t tok, const char *s)
{
    const jsmntok_t *t = &j->tok[tok];
    if (t->type != JSMN_STRING) return 0;
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
    const jsmntok_t *t = &j->tok[tok];
    *len = (size_t)(t->end - t->start);
    return j->buf + t->start;
}

coons_status coons__json_number(const coons__json *j, size_t tok, double *out)
{
    const jsmntok_t *t = &j->tok[tok];
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
