/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * A strict JSON reader (RFC 8259) that keeps the byte offset of every value,
 * so that the model loader can say where each error is. Internal.
 *
 * Parsing runs in two steps. A validating scan (no allocation) checks the
 * whole grammar, UTF-8, escapes, the nesting depth and the number of values,
 * and on failure reports the exact byte offset and JSON pointer. Only then
 * are exactly that many tokens allocated, and the same scan fills them.
 *
 * Tokens are numbered in document order; the subtree of token i is
 * [i, next(i)). An object's children alternate key, value.
 */
#ifndef COONS_JSON_H
#define COONS_JSON_H

#include "coons_internal.h"

typedef enum coons__json_type {
    COONS__JSON_OBJECT = 1,
    COONS__JSON_ARRAY,
    COONS__JSON_STRING,
    COONS__JSON_NUMBER,
    COONS__JSON_TRUE,
    COONS__JSON_FALSE,
    COONS__JSON_NULL
} coons__json_type;

/* Hard ceiling of the nesting depth (the scan keeps a fixed stack). */
#define COONS__JSON_DEPTH_CEILING 256

typedef struct coons__json coons__json;

/* What the scan found wrong: byte offset of the offending character or value
 * and the JSON pointer of the value being read (RFC 6901). */
typedef struct coons__json_where {
    size_t offset;
    char path[COONS_ERROR_PATH_MAX];
} coons__json_where;

/*
 * Parses buf[0..len). The top-level value must be an object (all the model
 * format needs). max_tokens bounds the number of values (keys count as
 * values), max_depth the nesting of arrays and objects (at most
 * COONS__JSON_DEPTH_CEILING).
 * @return COONS_OK, COONS_E_PARSE (syntax, UTF-8, trailing text),
 *         COONS_E_LIMIT, COONS_E_NOMEM; on error err->message holds the bare
 *         message and *where the position.
 */
coons_status coons__json_parse(const char *buf, size_t len, size_t max_tokens, unsigned max_depth,
                               coons__json **out, coons__json_where *where, coons_error *err);

void coons__json_free(coons__json *j);

size_t coons__json_count(const coons__json *j);
coons__json_type coons__json_type_of(const coons__json *j, size_t tok);
/* Byte offset where the value starts (the opening quote of a string). */
size_t coons__json_start(const coons__json *j, size_t tok);
/* Number of members of an object or elements of an array; 0 otherwise. */
size_t coons__json_size(const coons__json *j, size_t tok);
/* Index of the first token after tok's subtree. */
size_t coons__json_next(const coons__json *j, size_t tok);
/* Token of element i of an array (i < size), walking siblings. */
size_t coons__json_nth(const coons__json *j, size_t tok, size_t i);

/*
 * Decoded contents of a string token, NUL-terminated and truncated to fit
 * dst[cap] (cap >= 1); returns the full decoded length in bytes. A decoded
 * string may contain U+0000: compare the returned length with strlen(dst).
 */
size_t coons__json_string(const coons__json *j, size_t tok, char *dst, size_t cap);
/* Does the decoded string equal s? */
int coons__json_string_eq(const coons__json *j, size_t tok, const char *s);

/*
 * Value of a number token, converted independently of the process locale.
 * @return COONS_OK, or COONS_E_INVALID when the value is not a finite double
 *         (e.g. 1e400); *out is set to the converted value either way.
 */
coons_status coons__json_number(const coons__json *j, size_t tok, double *out);
/* The number's text as written (not NUL-terminated), for messages. */
const char *coons__json_text(const coons__json *j, size_t tok, size_t *len);

/* 1-based line and column of a byte offset; columns count UTF-8 code points,
 * lines end at LF, CR LF or a lone CR. */
void coons__json_line_col(const char *buf, size_t len, size_t offset, int *line, int *column);

/* Appends "/" + key to a JSON pointer (escaping '~' as ~0 and '/' as ~1),
 * truncating at cap; returns the new length. */
size_t coons__json_pointer_push(char *path, size_t cap, size_t len, const char *key, size_t klen);

#endif
