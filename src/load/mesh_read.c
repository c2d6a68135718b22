/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The mesh reader (coons_mesh_read_file(), coons_mesh_read_memory()):
 * binary STL, ASCII STL and OFF, into one indexed part.
 *
 * Which format: a file of exactly 84 + 50 * count bytes (count: the
 * little-endian uint32 at byte 80) is binary STL, whatever its header says
 * (some writers start binary headers with "solid"); else text starting with
 * "solid" and free of control bytes is ASCII STL; else text starting with
 * "OFF" (after blank and '#' lines) is OFF; anything else of 84 bytes or
 * more, or named *.stl, is a binary STL whose count disagrees with its size.
 *
 * Nothing is allocated from a count before the count was checked against
 * the file's size and the triangle limit: binary STL must match its size
 * exactly, OFF's counts must fit the bytes that follow (a vertex line takes
 * at least 6 bytes, a face line at least 8), and ASCII STL grows its arrays
 * as facets are read (each facet takes at least 60 bytes).
 *
 * STL corners are welded by exact equality of their coordinates (-0 and 0
 * are equal), so a closed STL becomes a closed indexed mesh; triangles
 * whose corners coincide (in STL after welding, in OFF by index) are
 * dropped. Numbers are read in the "C" locale whatever the process uses.
 */
#define _POSIX_C_SOURCE 200809L /* newlocale, uselocale */

#include <locale.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "coons_internal.h"
#include "mesh_impl.h"
#include "read_file.h"

typedef struct reader {
    const unsigned char *p;
    size_t n;
    const char *name; /* for messages */
    size_t max_tri;
    coons_error *err;
    locale_t cloc;
    /* the result: vertices (3 doubles each), triangles */
    double *xyz;
    size_t nv, cap_v;
    uint32_t *tri;
    size_t nt, cap_t;
    /* welding (STL): open addressing, vertex index + 1, 0 empty */
    uint32_t *slot;
    size_t cap_s;
    /* text position */
    size_t pos, line, line_start;
} reader;

/* ---- messages ----------------------------------------------------------- */

COONS__PRINTF(4, 5)
static coons_status bin_error(reader *r, coons_status code, size_t offset, const char *fmt, ...)
{
    char msg[COONS_ERROR_MESSAGE_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    coons__error_set(r->err, code, "%s: byte %zu: %s", r->name, offset, msg);
    if (r->err) snprintf(r->err->file, sizeof r->err->file, "%s", r->name);
    return code;
}

COONS__PRINTF(5, 6)
static coons_status text_error(reader *r, coons_status code, size_t line, size_t col,
                               const char *fmt, ...)
{
    char msg[COONS_ERROR_MESSAGE_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    coons__error_set(r->err, code, "%s:%zu:%zu: %s", r->name, line, col, msg);
    if (r->err) {
        snprintf(r->err->file, sizeof r->err->file, "%s", r->name);
        r->err->line = line > INT32_MAX ? INT32_MAX : (int)line;
        r->err->column = col > INT32_MAX ? INT32_MAX : (int)col;
    }
    return code;
}

/* A token quoted in a message: at most 32 bytes, control bytes as '?'. */
static void shown(char out[48], const unsigned char *s, size_t len)
{
    size_t k = 0;
    for (; k < len && k < 32; k++) out[k] = s[k] < 0x20 || s[k] == 0x7f ? '?' : (char)s[k];
    if (k < len) out[k++] = '.', out[k++] = '.', out[k++] = '.';
    out[k] = '\0';
}

/* ---- the result ------------------------------------------------------- */

static coons_status add_triangle(reader *r, uint32_t a, uint32_t b, uint32_t c)
{
    if (a == b || b == c || c == a) return COONS_OK; /* degenerate: dropped */
    if (r->nt == r->cap_t) {
        size_t cap = r->cap_t ? 2 * r->cap_t : 256;
        uint32_t *t = coons__malloc_array(cap, 3 * sizeof *t);
        if (!t) return coons__error_nomem(r->err);
        if (r->nt) memcpy(t, r->tri, r->nt * 3 * sizeof *t);
        coons__free(r->tri);
        r->tri = t;
        r->cap_t = cap;
    }
    uint32_t *t = r->tri + 3 * r->nt++;
    t[0] = a, t[1] = b, t[2] = c;
    return COONS_OK;
}

static coons_status push_vertex(reader *r, const double x[3])
{
    if (r->nv >= UINT32_MAX - 1)
        return coons__error_set(r->err, COONS_E_LIMIT, "%s: more than %lu vertices", r->name,
                                (unsigned long)UINT32_MAX - 1);
    if (r->nv == r->cap_v) {
        size_t cap = r->cap_v ? 2 * r->cap_v : 256;
        double *v = coons__malloc_array(cap, 3 * sizeof *v);
        if (!v) return coons__error_nomem(r->err);
        if (r->nv) memcpy(v, r->xyz, r->nv * 3 * sizeof *v);
        coons__free(r->xyz);
        r->xyz = v;
        r->cap_v = cap;
    }
    memcpy(r->xyz + 3 * r->nv++, x, 3 * sizeof *x);
    return COONS_OK;
}

static uint64_t bits(double x)
{
    uint64_t u;
    if (x == 0) x = 0; /* -0 welds with 0 */
    memcpy(&u, &x, sizeof u);
    return u;
}

static size_t weld_hash(const reader *r, const double x[3])
{
    uint64_t h = bits(x[0]) * 0x9e3779b97f4a7c15ull;
    h = (h ^ (h >> 29) ^ bits(x[1])) * 0xbf58476d1ce4e5b9ull;
    h = (h ^ (h >> 31) ^ bits(x[2])) * 0x94d049bb133111ebull;
    return (size_t)(h ^ (h >> 32)) & (r->cap_s - 1);
}

static coons_status grow_slots(reader *r)
{
    size_t cap = r->cap_s ? 2 * r->cap_s : 1024;
    uint32_t *s = coons__calloc(cap, sizeof *s);
    if (!s) return coons__error_nomem(r->err);
    coons__free(r->slot);
    r->slot = s;
    r->cap_s = cap;
    for (size_t v = 0; v < r->nv; v++) {
        size_t i = weld_hash(r, r->xyz + 3 * v);
        while (r->slot[i]) i = (i + 1) & (cap - 1);
        r->slot[i] = (uint32_t)v + 1;
    }
    return COONS_OK;
}

/* The index of the vertex at x, added if new. */
static coons_status weld(reader *r, const double x[3], uint32_t *id)
{
    if (2 * (r->nv + 1) > r->cap_s) {
        coons_status st = grow_slots(r);
        if (st) return st;
    }
    size_t i = weld_hash(r, x);
    for (; r->slot[i]; i = (i + 1) & (r->cap_s - 1)) {
        const double *y = r->xyz + 3 * (r->slot[i] - 1);
        if (y[0] == x[0] && y[1] == x[1] && y[2] == x[2]) {
            *id = r->slot[i] - 1;
            return COONS_OK;
        }
    }
    coons_status st = push_vertex(r, x);
    if (st) return st;
    *id = (uint32_t)(r->nv - 1);
    r->slot[i] = (uint32_t)r->nv;
    return COONS_OK;
}

/* ---- binary STL ------------------------------------------------------- */

/*
 * Binary STL corners are welded by their float bits (-0 as 0), which is
 * equality of the doubles they become. The table keeps each vertex's bits
 * with its index, so a probe reads one 16-byte slot and not the vertex
 * array, and the slots of a block of corners are prefetched before the
 * block is welded in order: the vertices are numbered by first occurrence,
 * as before, whatever the table's layout.
 */
typedef struct fslot {
    uint32_t k[3];
    uint32_t id; /* vertex index + 1; 0: empty */
} fslot;

static uint64_t fhash(const uint32_t k[3])
{
    uint64_t h = (k[0] * 0x9e3779b97f4a7c15ull) ^ (k[1] * 0xbf58476d1ce4e5b9ull) ^
                 (k[2] * 0x94d049bb133111ebull);
    return h ^ (h >> 29) ^ (h >> 41);
}

static coons_status fslots_grow(reader *r, fslot **tab, size_t *cap, size_t want)
{
    size_t c = *cap ? *cap : 1024;
    while (c < want) c *= 2;
    fslot *t = coons__calloc(c, sizeof *t);
    if (!t) return coons__error_nomem(r->err);
    for (size_t i = 0; i < *cap; i++) {
        if (!(*tab)[i].id) continue;
        size_t j = (size_t)fhash((*tab)[i].k) & (c - 1);
        while (t[j].id) j = (j + 1) & (c - 1);
        t[j] = (*tab)[i];
    }
    coons__free(*tab);
    *tab = t;
    *cap = c;
    return COONS_OK;
}

static uint32_t le32(const unsigned char *p);

#define WELD_BLOCK 64 /* triangles whose slots are prefetched together */

static coons_status weld_binary(reader *r, size_t count)
{
    fslot *tab = NULL;
    size_t cap = 0;
    /* a closed mesh has about count / 2 vertices: the table half full at
     * most, the arrays sized once */
    coons_status st = fslots_grow(r, &tab, &cap, count < 512 ? 1024 : count);
    if (!st && count > 256) {
        r->tri = coons__malloc_array(count, 3 * sizeof *r->tri);
        r->xyz = coons__malloc_array(count / 2 + 8, 3 * sizeof *r->xyz);
        if (!r->tri || !r->xyz) st = coons__error_nomem(r->err);
        r->cap_t = r->tri ? count : 0;
        r->cap_v = r->xyz ? count / 2 + 8 : 0;
    }
    for (size_t t0 = 0; !st && t0 < count; t0 += WELD_BLOCK) {
        size_t nb = count - t0 < WELD_BLOCK ? count - t0 : WELD_BLOCK, bad = 3 * nb;
        uint32_t key[3 * WELD_BLOCK][3];
        uint64_t h[3 * WELD_BLOCK];
        for (size_t c = 0; c < 3 * nb && bad == 3 * nb; c++) {
            const unsigned char *f = r->p + 84 + 50 * (t0 + c / 3) + 12 + 12 * (c % 3);
            for (int k = 0; k < 3; k++) {
                uint32_t u = le32(f + 4 * k);
                if ((u & 0x7f800000u) == 0x7f800000u) { /* inf or nan */
                    bad = c;
                    break;
                }
                key[c][k] = (u & 0x7fffffffu) ? u : 0u; /* -0 welds with 0 */
            }
            h[c] = fhash(key[c]);
            __builtin_prefetch(tab + (h[c] & (cap - 1)));
        }
        uint32_t id[3];
        for (size_t c = 0; c < bad; c++) {
            if (2 * (r->nv + 1) > cap && (st = fslots_grow(r, &tab, &cap, 2 * cap))) break;
            size_t i = (size_t)h[c] & (cap - 1);
            for (; tab[i].id; i = (i + 1) & (cap - 1))
                if (tab[i].k[0] == key[c][0] && tab[i].k[1] == key[c][1] &&
                    tab[i].k[2] == key[c][2])
                    break;
            if (tab[i].id) {
                id[c % 3] = tab[i].id - 1;
            } else {
                double x[3];
                for (int k = 0; k < 3; k++) {
                    float g;
                    memcpy(&g, &key[c][k], sizeof g);
                    x[k] = g;
                }
                if ((st = push_vertex(r, x))) break;
                id[c % 3] = (uint32_t)(r->nv - 1);
                memcpy(tab[i].k, key[c], sizeof key[c]);
                tab[i].id = (uint32_t)r->nv;
            }
            if (c % 3 == 2 && (st = add_triangle(r, id[0], id[1], id[2]))) break;
        }
        if (!st && bad < 3 * nb) {
            size_t t = t0 + bad / 3;
            int v = (int)(bad % 3), k = 0;
            const unsigned char *f = r->p + 84 + 50 * t + 12 + 12 * (size_t)v;
            float g = 0;
            for (; k < 3; k++) {
                uint32_t u = le32(f + 4 * k);
                memcpy(&g, &u, sizeof g);
                if (!isfinite(g)) break;
            }
            st = bin_error(r, COONS_E_PARSE, (size_t)(f - r->p) + 4 * (size_t)k,
                           "triangle %zu, corner %d: %c = %s is not a finite number", t, v,
                           "xyz"[k], isnan(g) ? "nan" : g > 0 ? "inf" : "-inf");
        }
    }
    coons__free(tab);
    return st;
}

static uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static coons_status read_binary_stl(reader *r)
{
    if (r->n < 84)
        return bin_error(r, COONS_E_PARSE, r->n,
                         "truncated: a binary STL starts with an 84-byte header (80 bytes of "
                         "text and the triangle count), the file has %zu bytes",
                         r->n);
    uint64_t count = le32(r->p + 80), need = 84 + 50 * count;
    if (need > r->n)
        return bin_error(r, COONS_E_PARSE, r->n,
                         "truncated: the header (byte 80) counts %llu triangles, which need "
                         "%llu bytes (84 + 50 * %llu); the file ends inside triangle %llu",
                         (unsigned long long)count, (unsigned long long)need,
                         (unsigned long long)count, (unsigned long long)(r->n - 84) / 50);
    if (need < r->n)
        return bin_error(r, COONS_E_PARSE, 80,
                         "the triangle count %llu disagrees with the file size: it needs %llu "
                         "bytes (84 + 50 * %llu), the file has %zu (%zu bytes, %s50, after the "
                         "header)",
                         (unsigned long long)count, (unsigned long long)need,
                         (unsigned long long)count, r->n, r->n - 84,
                         (r->n - 84) % 50 ? "not a multiple of " : "a multiple of ");
    if (count > r->max_tri)
        return bin_error(r, COONS_E_LIMIT, 80,
                         "%llu triangles, more than the limit of %zu triangles (max_triangles; "
                         "coons2stl --max-triangles N)",
                         (unsigned long long)count, r->max_tri);
    return weld_binary(r, (size_t)count);
}

/* ---- text ---------------------------------------------------------------- */

static int is_space(unsigned char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

/* Skips blanks; with `newlines`, line ends too (counting lines). */
static void skip_blanks(reader *r, int newlines)
{
    while (r->pos < r->n) {
        unsigned char c = r->p[r->pos];
        if (c == '\n' && newlines) {
            r->pos++;
            r->line++;
            r->line_start = r->pos;
        } else if (is_space(c)) {
            r->pos++;
        } else {
            break;
        }
    }
}

/* The next token on this line (after blanks); len 0 at a line end or the
 * end of the file. OFF: a '#' starts a comment to the line's end. */
static size_t token(reader *r, int newlines, int comments, size_t *start)
{
    skip_blanks(r, newlines);
    *start = r->pos;
    if (comments && r->pos < r->n && r->p[r->pos] == '#') {
        while (r->pos < r->n && r->p[r->pos] != '\n') r->pos++;
        *start = r->pos;
        return 0;
    }
    while (r->pos < r->n && r->p[r->pos] != '\n' && !is_space(r->p[r->pos]) &&
           !(comments && r->p[r->pos] == '#'))
        r->pos++;
    return r->pos - *start;
}

static size_t col_of(const reader *r, size_t at) { return at - r->line_start + 1; }

static int token_is(const reader *r, size_t start, size_t len, const char *word)
{
    size_t w = strlen(word);
    if (len != w) return 0;
    for (size_t i = 0; i < w; i++) {
        unsigned char c = r->p[start + i];
        if (c >= 'A' && c <= 'Z') c = (unsigned char)(c - 'A' + 'a');
        if (c != (unsigned char)word[i]) return 0;
    }
    return 1;
}

/* Reads the token as a number (the whole token, C locale). */
static int number(reader *r, size_t start, size_t len, double *out)
{
    char buf[64];
    if (len == 0 || len >= sizeof buf) return 0;
    memcpy(buf, r->p + start, len);
    buf[len] = '\0';
    char *end;
    locale_t old = uselocale(r->cloc);
    *out = strtod(buf, &end);
    uselocale(old);
    return end == buf + len;
}

static coons_status expected(reader *r, size_t start, size_t len, const char *what)
{
    char s[48];
    shown(s, r->p + start, len);
    if (!len)
        return text_error(r, COONS_E_PARSE, r->line, col_of(r, start), "expected %s, found %s",
                          what, start >= r->n ? "the end of the file" : "the end of the line");
    return text_error(r, COONS_E_PARSE, r->line, col_of(r, start), "expected %s, found '%s'",
                      what, s);
}

/* A finite coordinate token. */
static coons_status coordinate(reader *r, int newlines, int comments, char axis, double *x)
{
    size_t start, len = token(r, newlines, comments, &start);
    if (!number(r, start, len, x)) {
        char what[32];
        snprintf(what, sizeof what, "a number (%c)", axis);
        return expected(r, start, len, what);
    }
    if (!isfinite(*x)) {
        char s[48];
        shown(s, r->p + start, len);
        return text_error(r, COONS_E_PARSE, r->line, col_of(r, start),
                          "%c = %s is not a finite number", axis, s);
    }
    return COONS_OK;
}

/* The keyword `word`, else an error. */
static coons_status keyword(reader *r, const char *word)
{
    size_t start, len = token(r, 1, 0, &start);
    if (token_is(r, start, len, word)) return COONS_OK;
    char what[32];
    snprintf(what, sizeof what, "'%s'", word);
    return expected(r, start, len, what);
}

static void rest_of_line(reader *r)
{
    while (r->pos < r->n && r->p[r->pos] != '\n') r->pos++;
}

/* ---- ASCII STL ---------------------------------------------------------- */

static coons_status read_ascii_stl(reader *r)
{
    coons_status st;
    size_t start, len;
    for (int solids = 0;; solids++) {
        len = token(r, 1, 0, &start);
        if (!len && r->pos >= r->n && solids) return COONS_OK;
        if (!token_is(r, start, len, "solid")) return expected(r, start, len, "'solid'");
        rest_of_line(r); /* the solid's name */
        for (;;) {
            len = token(r, 1, 0, &start);
            if (token_is(r, start, len, "endsolid")) {
                rest_of_line(r);
                break;
            }
            if (!token_is(r, start, len, "facet"))
                return expected(r, start, len, "'facet' or 'endsolid'");
            size_t facet_line = r->line, facet_col = col_of(r, start);
            if ((st = keyword(r, "normal"))) return st;
            for (int k = 0; k < 3; k++) {
                double x;
                len = token(r, 1, 0, &start);
                if (!number(r, start, len, &x)) return expected(r, start, len, "a number (normal)");
            }
            if ((st = keyword(r, "outer")) || (st = keyword(r, "loop"))) return st;
            uint32_t id[3];
            for (int v = 0; v < 3; v++) {
                double x[3];
                if ((st = keyword(r, "vertex"))) return st;
                for (int k = 0; k < 3; k++)
                    if ((st = coordinate(r, 1, 0, "xyz"[k], &x[k]))) return st;
                if ((st = weld(r, x, &id[v]))) return st;
            }
            if ((st = keyword(r, "endloop")) || (st = keyword(r, "endfacet"))) return st;
            if (r->nt >= r->max_tri)
                return text_error(r, COONS_E_LIMIT, facet_line, facet_col,
                                  "more than the limit of %zu triangles (max_triangles; "
                                  "coons2stl --max-triangles N)",
                                  r->max_tri);
            if ((st = add_triangle(r, id[0], id[1], id[2]))) return st;
        }
    }
}

/* ---- OFF ------------------------------------------------------------------ */

/* Moves to the next line that holds a token (skipping blank and comment
 * lines); 0 at the end of the file. */
static int next_line(reader *r)
{
    for (;;) {
        size_t start, len = token(r, 0, 1, &start);
        if (len) {
            r->pos = start;
            return 1;
        }
        if (r->pos >= r->n) return 0;
        r->pos++; /* the '\n' */
        r->line++;
        r->line_start = r->pos;
    }
}

/* A whole number token (digits only) within `max`. */
static int whole(reader *r, size_t start, size_t len, unsigned long long max,
                 unsigned long long *out)
{
    unsigned long long v = 0;
    if (!len || len > 20) return 0;
    for (size_t i = 0; i < len; i++) {
        unsigned char c = r->p[start + i];
        if (c < '0' || c > '9') return 0;
        unsigned d = (unsigned)(c - '0');
        if (v > (max - d) / 10) return 0;
        v = 10 * v + d;
    }
    *out = v;
    return 1;
}

static coons_status end_of_line(reader *r, const char *after)
{
    size_t start, len = token(r, 0, 1, &start);
    if (!len) return COONS_OK;
    char s[48];
    shown(s, r->p + start, len);
    return text_error(r, COONS_E_PARSE, r->line, col_of(r, start),
                      "unexpected '%s' after %s", s, after);
}

static coons_status truncated(reader *r, const char *what, size_t i, size_t n)
{
    return text_error(r, COONS_E_PARSE, r->line, col_of(r, r->pos),
                      "truncated: the file ends before %s %zu of %zu", what, i + 1, n);
}

static coons_status read_off(reader *r)
{
    coons_status st;
    size_t start, len;
    next_line(r);
    len = token(r, 0, 1, &start);
    if (len != 3 || memcmp(r->p + start, "OFF", 3) != 0) return expected(r, start, len, "'OFF'");
    /* the counts, on the OFF line or the next one with text */
    len = token(r, 0, 1, &start);
    if (!len) {
        if (!next_line(r)) return expected(r, r->pos, 0, "the counts 'vertices faces edges'");
        len = token(r, 0, 1, &start);
    }
    size_t count_line = r->line, count_col = col_of(r, start);
    unsigned long long nv, nf, ne;
    if (!whole(r, start, len, UINT64_MAX, &nv))
        return expected(r, start, len, "the vertex count (a whole number)");
    len = token(r, 0, 1, &start);
    if (!whole(r, start, len, UINT64_MAX, &nf))
        return expected(r, start, len, "the face count (a whole number)");
    len = token(r, 0, 1, &start);
    if (len && !whole(r, start, len, UINT64_MAX, &ne)) /* (not used) */
        return expected(r, start, len, "the edge count (a whole number) or the end of the line");
    if ((st = end_of_line(r, "the counts"))) return st;
    /* before anything is allocated: what the counts need fits the file */
    size_t rest = r->n - r->pos;
    if (nv > rest || nf > rest || 6 * nv + 8 * nf > rest + 1)
        return text_error(r, COONS_E_PARSE, count_line, count_col,
                          "truncated: %llu vertices and %llu faces cannot fit in the %zu bytes "
                          "after the counts (a vertex line takes at least 6, a face line 8)",
                          nv, nf, rest);
    if (nf > r->max_tri)
        return text_error(r, COONS_E_LIMIT, count_line, count_col,
                          "%llu faces, more than the limit of %zu triangles (max_triangles; "
                          "coons2stl --max-triangles N)",
                          nf, r->max_tri);
    if (nv > UINT32_MAX - 1)
        return text_error(r, COONS_E_LIMIT, count_line, count_col, "more than %lu vertices",
                          (unsigned long)UINT32_MAX - 1);
    for (size_t v = 0; v < (size_t)nv; v++) {
        if (!next_line(r)) return truncated(r, "vertex", v, (size_t)nv);
        double x[3];
        for (int k = 0; k < 3; k++)
            if ((st = coordinate(r, 0, 1, "xyz"[k], &x[k]))) return st;
        if ((st = end_of_line(r, "the 3 coordinates of a vertex"))) return st;
        if ((st = push_vertex(r, x))) return st;
    }
    size_t fanned = 0;
    for (size_t f = 0; f < (size_t)nf; f++) {
        if (!next_line(r)) return truncated(r, "face", f, (size_t)nf);
        unsigned long long k;
        len = token(r, 0, 1, &start);
        if (!whole(r, start, len, UINT64_MAX, &k) || k < 3) {
            if (len && whole(r, start, len, UINT64_MAX, &k))
                return text_error(r, COONS_E_PARSE, r->line, col_of(r, start),
                                  "a face of %llu corners: at least 3 are needed", k);
            return expected(r, start, len, "the number of corners of a face");
        }
        uint32_t first = 0, prev = 0;
        for (unsigned long long c = 0; c < k; c++) {
            unsigned long long i;
            len = token(r, 0, 1, &start);
            if (!whole(r, start, len, UINT64_MAX, &i)) {
                char what[64];
                snprintf(what, sizeof what, "vertex index %llu of %llu", c + 1, k);
                return expected(r, start, len, what);
            }
            if (i >= nv)
                return text_error(r, COONS_E_PARSE, r->line, col_of(r, start),
                                  "face %zu: vertex index %llu is out of range (%llu vertices, "
                                  "0 to %llu)",
                                  f, i, nv, nv ? nv - 1 : 0);
            if (c == 0) first = (uint32_t)i;
            if (c >= 2) {
                if (fanned++ >= r->max_tri)
                    return text_error(r, COONS_E_LIMIT, r->line, col_of(r, start),
                                      "more than the limit of %zu triangles (max_triangles; "
                                      "coons2stl --max-triangles N)",
                                      r->max_tri);
                if ((st = add_triangle(r, first, prev, (uint32_t)i))) return st;
            }
            prev = (uint32_t)i;
        }
        rest_of_line(r); /* a colour may follow */
    }
    if (next_line(r)) {
        len = token(r, 0, 1, &start);
        char s[48];
        shown(s, r->p + start, len);
        return text_error(r, COONS_E_PARSE, r->line, col_of(r, start),
                          "unexpected '%s' after the %llu faces the counts announce", s, nf);
    }
    return COONS_OK;
}

/* ---- which format ---------------------------------------------------------- */

static int starts_with_word(const unsigned char *p, size_t n, const char *w)
{
    size_t i = 0, k = strlen(w);
    while (i < n && (is_space(p[i]) || p[i] == '\n')) i++;
    if (n - i < k || memcmp(p + i, w, k) != 0) return 0;
    return n - i == k || is_space(p[i + k]) || p[i + k] == '\n';
}

static int has_control_bytes(const unsigned char *p, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if ((p[i] < 0x20 && p[i] != '\n' && !is_space(p[i])) || p[i] == 0x7f) return 1;
    return 0;
}

/* Whether the name ends in ".EXT" (ext: 3 lowercase letters), any case. */
static int named(const char *name, const char *ext)
{
    size_t n = strlen(name);
    return n >= 4 && name[n - 4] == '.' && (name[n - 3] | 0x20) == ext[0] &&
           (name[n - 2] | 0x20) == ext[1] && (name[n - 1] | 0x20) == ext[2];
}

/* "dir/part.stl" -> "part" */
static void part_name(const char *path, char *out, size_t cap)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    snprintf(out, cap, "%s", base);
    char *dot = strrchr(out, '.');
    if (dot && dot != out) *dot = '\0';
    if (!out[0]) snprintf(out, cap, "mesh");
}

static coons_status check_options(const coons_mesh_read_options *o, coons_error *err)
{
    if (!o) return COONS_OK;
    return COONS__RECORD_CHECK(err, "mesh read options", o->version, COONS_MESH_READ_OPTIONS);
}

coons_status coons_mesh_read_memory(const void *data, size_t size, const char *name,
                                    const coons_mesh_read_options *opts, coons_mesh **out,
                                    coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "mesh read: out is NULL");
    *out = NULL;
    if (!data && size) return coons__error_set(err, COONS_E_INVALID, "mesh read: no data");
    coons_status st = check_options(opts, err);
    if (st) return st;
    reader r;
    memset(&r, 0, sizeof r);
    r.p = data ? data : (const void *)"";
    r.n = size;
    r.name = name ? name : "<memory>";
    r.max_tri = opts && opts->max_triangles ? opts->max_triangles : COONS_MESH_MAX_TRIANGLES;
    r.err = err;
    r.line = 1;
    size_t max_bytes = opts && opts->max_bytes ? opts->max_bytes : COONS_MESH_READ_MAX_BYTES;
    if (size > max_bytes)
        return bin_error(&r, COONS_E_LIMIT, max_bytes,
                         "the mesh is %zu bytes, above the limit of %zu bytes (max_bytes)", size,
                         max_bytes);
    uint64_t count = size >= 84 ? le32(r.p + 80) : 0;
    size_t head = size < 1024 ? size : 1024;
    int binary = size >= 84 && 84 + 50 * count == size;
    if (!binary && starts_with_word(r.p, size, "solid") && !has_control_bytes(r.p, head)) {
        r.cloc = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
        st = r.cloc == (locale_t)0 ? coons__error_nomem(err) : read_ascii_stl(&r);
    } else if (!binary && (named(r.name, "off") ||
                           (!named(r.name, "stl") && !has_control_bytes(r.p, head)))) {
        r.cloc = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
        st = r.cloc == (locale_t)0 ? coons__error_nomem(err) : read_off(&r);
    } else {
        st = read_binary_stl(&r);
    }
    if (r.cloc != (locale_t)0) freelocale(r.cloc);
    if (!st) {
        char part[COONS_ERROR_FILE_MAX];
        part_name(name ? name : "mesh", part, sizeof part);
        st = coons_mesh_new(out, err);
        if (!st) st = coons_mesh_add_part(*out, part, r.xyz, r.nv, r.tri, r.nt, err);
        if (st) {
            coons_mesh_free(*out);
            *out = NULL;
        }
    }
    coons__free(r.xyz);
    coons__free(r.tri);
    coons__free(r.slot);
    return st;
}

coons_status coons_mesh_read_file(const char *path, const coons_mesh_read_options *opts,
                                  coons_mesh **out, coons_error *err)
{
    if (out) *out = NULL;
    if (!path || !out) return coons__error_set(err, COONS_E_INVALID, "mesh read: no file name");
    coons_status st = check_options(opts, err);
    if (st) return st;
    size_t max_bytes = opts && opts->max_bytes ? opts->max_bytes : COONS_MESH_READ_MAX_BYTES;
    unsigned char *buf = NULL;
    size_t len = 0;
    st = coons__read_file(path, "mesh", "max_bytes", max_bytes, &buf, &len, err);
    if (st) return st;
    st = coons_mesh_read_memory(buf, len, path, opts, out, err);
    coons__free(buf);
    return st;
}
