/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Shared machinery of the mesh writers: a buffered byte sink over a file
 * descriptor or a stdio stream with a sticky error, and the per-format
 * writers it feeds (stl.c, off.c, scad.c; driven by write.c). */
#ifndef COONS_IO_WRITER_H
#define COONS_IO_WRITER_H

#include <stdio.h>
#include <string.h>

#include "coons_internal.h"
#include "fmt.h"

/* Bytes buffered before each write(2)/fwrite: large enough that system
 * calls cost nothing next to formatting, small enough to poll `cancel`
 * often. */
#define COONS__SINK_BUFSIZE ((size_t)1 << 20)
/* Largest single reservation a writer makes (one text line or record). */
#define COONS__SINK_MAXREC ((size_t)512)

typedef struct coons__sink {
    char *buf;
    size_t len;
    int fd;                      /* >= 0: write(2) to it */
    FILE *fp;                    /* otherwise: fwrite to it */
    const char *what;            /* file name for messages */
    const coons_write_options *opts; /* for `cancel` */
    coons__fmt_scope *fmt;       /* restored around `cancel` */
    coons_status status;         /* sticky: first error wins */
    coons_error *err;
} coons__sink;

/* Polls opts->cancel; on cancellation records COONS_E_IO. Returns 0 when
 * the write must stop (cancelled or an earlier error). */
int coons__sink_ok(coons__sink *s);
/* Writes out the buffer; returns 0 on error (recorded in s). */
int coons__sink_flush(coons__sink *s);

/* Room for n <= COONS__SINK_MAXREC bytes at the end of the buffer, or NULL
 * after an error. Advance s->len by what was used. */
static inline char *coons__sink_room(coons__sink *s, size_t n)
{
    if (s->len + n > COONS__SINK_BUFSIZE && !coons__sink_flush(s)) return NULL;
    return s->status == COONS_OK ? s->buf + s->len : NULL;
}

/* Appends arbitrary bytes. Returns 0 after an error. */
int coons__sink_put(coons__sink *s, const void *data, size_t n);
static inline int coons__sink_puts(coons__sink *s, const char *str)
{
    return coons__sink_put(s, str, strlen(str));
}

/* Resolved options handed to the format writers: never NULL strings. */
typedef struct coons__wopts {
    const char *name;   /* model name ("coons_model" by default) */
    const char *units;  /* "" when none */
    const char *header; /* header / first comment text */
} coons__wopts;

/* Each writer emits the whole file into the sink and returns s->status. The
 * mesh has been validated (finite vertices, indices in range, triangle
 * count limit for binary STL) by write.c. */
coons_status coons__write_stl_binary(const coons_mesh *m, const coons__wopts *o, coons__sink *s);
coons_status coons__write_stl_ascii(const coons_mesh *m, const coons__wopts *o, coons__sink *s);
coons_status coons__write_off(const coons_mesh *m, const coons__wopts *o, coons__sink *s);
coons_status coons__write_scad(const coons_mesh *m, const coons__wopts *o, coons__sink *s);

/* Copies text into out[cap] (NUL-terminated) with every control character
 * (bytes < 0x20 and 0x7f) replaced by a space: safe inside one comment
 * line or header. Returns the length written. */
size_t coons__clean_text(char *out, size_t cap, const char *text);

#endif
