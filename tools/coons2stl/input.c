/* SPDX-License-Identifier: GPL-3.0-or-later */
/* coons2stl's input: the model, from a file or standard input (within
 * --max-bytes), and the body that --body names. */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

/* Reads standard input whole, at most one byte more than the loader
 * accepts, so that the loader reports the limit itself. NULL: out of
 * memory. */
static char *read_stdin(size_t max, size_t *len)
{
    size_t cap = 1 << 16;
    char *buf = malloc(cap);
    *len = 0;
    while (buf) {
        if (*len == cap) {
            if (cap >= max) break;
            size_t nc = cap * 2 > max ? max : cap * 2;
            char *nb = realloc(buf, nc);
            if (!nb) {
                free(buf);
                return NULL;
            }
            buf = nb;
            cap = nc;
        }
        size_t got = fread(buf + *len, 1, cap - *len, stdin);
        *len += got;
        if (got == 0) break;
    }
    return buf;
}

static int load_failed(const coons_error *err)
{
    /* The message carries FILE:LINE:COL: /json/path: ... already. */
    fprintf(stderr, "%s: %s\n", PROG, err->message);
    return EXIT_INPUT;
}

static int load_stdin(const options *o, coons_model **m)
{
    coons_error err = COONS_ERROR_INIT;
    size_t max_bytes = o->load.max_bytes ? o->load.max_bytes : COONS_MODEL_MAX_BYTES, len = 0;
    char *buf = read_stdin(max_bytes < SIZE_MAX ? max_bytes + 1 : max_bytes, &len);
    if (!buf) {
        fprintf(stderr, "%s: <stdin>: out of memory reading the model\n", PROG);
        return EXIT_INPUT;
    }
    if (ferror(stdin)) {
        fprintf(stderr, "%s: <stdin>: cannot read the model: %s\n", PROG, strerror(errno));
        free(buf);
        return EXIT_INPUT;
    }
    if (len > max_bytes) {
        fprintf(stderr,
                "%s: <stdin>: the model is more than %zu bytes, the limit (raise it with "
                "--max-bytes N)\n",
                PROG, max_bytes);
        free(buf);
        return EXIT_INPUT;
    }
    coons_status rc = coons_model_load_memory(buf, len, "<stdin>", &o->load, m, &err);
    free(buf);
    return rc == COONS_OK ? -1 : load_failed(&err);
}

int cli_load_model(const options *o, coons_model **m)
{
    if (strcmp(o->input, "-") == 0) return load_stdin(o, m);
    coons_error err = COONS_ERROR_INIT;
    if (coons_model_load_file(o->input, &o->load, m, &err) != COONS_OK) return load_failed(&err);
    return -1;
}

long cli_select_body(const coons_model *m, const char *arg)
{
    size_t n = coons_model_body_count(m);
    int digits = arg[0] != '\0';
    for (const char *p = arg; *p; p++)
        if (*p < '0' || *p > '9') digits = 0;
    if (digits) {
        errno = 0;
        unsigned long long i = strtoull(arg, NULL, 10);
        if (errno || i >= n) {
            fprintf(stderr, "%s: --body %s: the model has %zu bod%s (indices 0..%zu)\n", PROG, arg,
                    n, n == 1 ? "y" : "ies", n - 1);
            return -1;
        }
        return (long)i;
    }
    long i = coons_model_find_body(m, arg);
    if (i < 0) fprintf(stderr, "%s: --body %s: the model has no body of that name\n", PROG, arg);
    return i;
}
