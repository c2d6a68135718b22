/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Shared machinery of the mesh writers (src/io/write): the buffered byte
 * sink with a sticky error (sink.c), the format table (formats.c), the
 * atomic file and stream output that serve every format of either mesh
 * kind (atomic.c), and the per-format writers the table names (stl.c,
 * off.c, scad.c: surface; vtk.c, inp.c: volume). A new format is one writer file,
 * its declaration below, one row of the table and one value of
 * coons_format (coons/io.h). */
#ifndef COONS_IO_WRITER_H
#define COONS_IO_WRITER_H

#include <stdio.h>
#include <string.h>

#include "coons_internal.h"
#include "coons/io.h"
#include "cell_shape.h"
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
    unsigned long long bytes;    /* written out so far */
    void (*written)(void *ctx, unsigned long long bytes); /* opts' (version 2), or NULL */
    void *written_ctx;
    int threaded;                /* coons__sink_start() was called */
    struct coons__sink_bg *bg;   /* the writing thread of a file, or NULL (sink.c) */
} coons__sink;

/* For a file (fd >= 0): from the first full buffer on (outputs of at most
 * one buffer are written as before), hands the write(2) calls to a second
 * thread, so the next buffer is formatted while the last one is written;
 * where no thread can be started the sink stays synchronous, and without
 * memory for its buffers the write fails (COONS_E_NOMEM). Nothing of the
 * caller's runs on that thread (no callback, no allocation): flushes,
 * `cancel` and `written` stay on the calling thread, and errors of the
 * thread are reported by the next flush or by coons__sink_finish(). */
void coons__sink_start(coons__sink *s);
/* Waits for every buffer handed over to be written (or dropped after an
 * error) and stops the thread; s->buf is again the buffer it started
 * with. Returns 0 after an error (recorded in s). Harmless on a
 * synchronous sink. */
int coons__sink_finish(coons__sink *s);

/* Takes `written` from opts of version 2 or later (none from version 1). */
static inline void coons__sink_watch(coons__sink *s, const coons_write_options *opts)
{
    if (opts && opts->version >= 2) {
        s->written = opts->written;
        s->written_ctx = opts->written_ctx;
    }
}

/* Polls opts->cancel; on cancellation records COONS_E_IO. Returns 0 when
 * the write must stop (cancelled or an earlier error). */
int coons__sink_ok(coons__sink *s);
/* Writes out the buffer; returns 0 on error (recorded in s). */
int coons__sink_flush(coons__sink *s);
/* Records COONS_E_IO "cannot DOING 'what': <system error of errno>" unless
 * an error is already recorded. */
void coons__sink_sys_error(coons__sink *s, const char *doing);
/* Thread-safe text of an errno value, in buf. */
const char *coons__errno_text(int e, char *buf, size_t cap);

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
    const size_t *background; /* OpenSCAD: parts called with `%` (checked in range) */
    size_t nbackground;
} coons__wopts;

/* ---- the format table (formats.c) ------------------------------------ */

/* A writer emits the whole file into the sink and returns s->status. Its
 * mesh has passed the generic checks of its kind (surface.c, volume.c) and
 * the row's own `check`. */
typedef coons_status (*coons__surface_writer)(const coons_mesh *m, const coons__wopts *o,
                                              coons__sink *s);
typedef coons_status (*coons__volume_writer)(const coons_volume_mesh *m, const coons__wopts *o,
                                             coons__sink *s);
/* Format-specific limits, checked before any output exists; NULL: none. */
typedef coons_status (*coons__surface_check)(const coons_mesh *m, coons_error *err);
typedef coons_status (*coons__volume_check)(const coons_volume_mesh *m, coons_error *err);
/* Exact solids of a model (kind SOLID): the row's format tells the writer
 * which file to make (occt.cpp, or noocct/occt.c refusing). */
typedef coons_status (*coons__solid_writer)(const coons_model *m, coons_format format,
                                            const coons__wopts *o, coons__sink *s);

typedef struct coons__format_row {
    coons_format format;
    const char *name;            /* canonical, as coons_format_name() and -f */
    const char *title;           /* for messages: "binary STL" */
    const char *aliases[2];      /* other names for -f; NULL-terminated */
    const char *extensions[3];   /* ".stl", ...: what the format means; NULL-terminated */
    coons_mesh_kind kind;
    uint64_t max_triangles;      /* surface: a count field's limit; 0: none */
    coons__surface_writer write_surface; /* kind SURFACE; a VOLUME row may have one too */
    coons__surface_check check_surface;
    coons__volume_writer write_volume;   /* kind VOLUME */
    coons__volume_check check_volume;
    coons__solid_writer write_solid;     /* kind SOLID */
} coons__format_row;

/* The row of a format, or NULL (COONS_FORMAT_AUTO and unknown values). */
const coons__format_row *coons__format_row_of(coons_format format);

/* ---- the writers the table names -------------------------------------- */

coons_status coons__write_stl_binary(const coons_mesh *m, const coons__wopts *o, coons__sink *s);
coons_status coons__write_stl_ascii(const coons_mesh *m, const coons__wopts *o, coons__sink *s);
coons_status coons__check_stl(const coons_mesh *m, coons_error *err);
coons_status coons__write_off(const coons_mesh *m, const coons__wopts *o, coons__sink *s);
coons_status coons__write_scad(const coons_mesh *m, const coons__wopts *o, coons__sink *s);
coons_status coons__check_scad(const coons_mesh *m, coons_error *err);
coons_status coons__write_vtk(const coons_volume_mesh *m, const coons__wopts *o, coons__sink *s);
coons_status coons__write_msh2(const coons_volume_mesh *m, const coons__wopts *o, coons__sink *s);
coons_status coons__write_msh4(const coons_volume_mesh *m, const coons__wopts *o, coons__sink *s);
coons_status coons__write_vtu(const coons_volume_mesh *m, const coons__wopts *o, coons__sink *s);
coons_status coons__write_vtu_ascii(const coons_volume_mesh *m, const coons__wopts *o,
                                    coons__sink *s);
/* Triangle meshes as VTK XML UnstructuredGrid (vtu_surface.c), for a VTU
 * row's write_surface. */
coons_status coons__write_vtu_surface(const coons_mesh *m, const coons__wopts *o,
                                      coons__sink *s);
coons_status coons__write_inp(const coons_volume_mesh *m, const coons__wopts *o, coons__sink *s);
coons_status coons__check_inp(const coons_volume_mesh *m, coons_error *err);
/* 3MF (threemf.cpp with lib3mf; without it no3mf/threemf.c refuses with
 * COONS_E_UNSUPPORTED in the check, before any output exists). */
coons_status coons__write_3mf(const coons_mesh *m, const coons__wopts *o, coons__sink *s);
coons_status coons__check_3mf(const coons_mesh *m, coons_error *err);
/* STEP, IGES and BREP solids (occt.cpp with Open CASCADE; without it
 * noocct/occt.c refuses with COONS_E_UNSUPPORTED before any output). */
coons_status coons__write_solid(const coons_model *m, coons_format format, const coons__wopts *o,
                                coons__sink *s);
/* COONS_OK when solids can be written, else COONS_E_UNSUPPORTED naming
 * Open CASCADE (checked before a temporary file is made). */
coons_status coons__check_solid(coons_error *err);

/* ---- OpenSCAD identifiers (scad.c), for every writer of .scad text ----- */

/* Room for any identifier the two functions below make. */
#define COONS__SCAD_IDENT_MAX 320
/* `name` (NULL: "") made an OpenSCAD identifier in out[cap], cap >= 3:
 * bytes outside [A-Za-z0-9_] become '_', a name not starting with a letter
 * or '_' gets a '_' prefix, a keyword or built-in module name (`cube`,
 * `hull`, `for`, ...) a '_' suffix; cut to cap - 1 bytes. */
void coons__scad_identifier(char *out, size_t cap, const char *name);
/* The identifier of "MODEL_PART": a part's module name, carrying the
 * model's name so that modules of different models do not clash. */
void coons__scad_part_identifier(char *out, size_t cap, const char *model, const char *part);
/* The first lines of every .scad file: "// " and the header option's text,
 * then "// units: " and the units when the options name them. */
void coons__scad_header(coons__sink *s, const coons__wopts *o);

/* ---- output (atomic.c) ------------------------------------------------- */

/* One write: the row, the mesh of the row's kind, and the resolved options. */
typedef struct coons__write_job {
    const coons__format_row *row;
    const coons_mesh *surface;       /* row->kind == COONS_MESH_KIND_SURFACE */
    const coons_volume_mesh *volume; /* row->kind == COONS_MESH_KIND_VOLUME */
    const coons_model *model;        /* row->kind == COONS_MESH_KIND_SOLID */
    coons__wopts o;
} coons__write_job;

/* Checks what both mesh kinds share: a mesh was given, the options
 * version, a known format whose kind is `kind` (that of the caller's mesh;
 * the message of a mismatch names the entry point for the other kind).
 * Sets job->row and resolves the options into job->o. */
coons_status coons__write_prepare(coons__write_job *job, int mesh_given, coons_format format,
                                  coons_mesh_kind kind, const coons_write_options *opts,
                                  coons_error *err);
/* The format of `path` when `*format` is AUTO (else unchanged). */
coons_status coons__write_resolve(const char *path, coons_format *format, coons_error *err);
/* Writes the job atomically to `path` (temporary file, fsync, rename). */
coons_status coons__write_path(const coons__write_job *job, const char *path,
                               const coons_write_options *opts, coons_error *err);
/* Writes the job to an open stream and flushes it. */
coons_status coons__write_stream(const coons__write_job *job, FILE *fp,
                                 const coons_write_options *opts, coons_error *err);

/* Copies text into out[cap] (NUL-terminated) with every control character
 * (bytes < 0x20 and 0x7f) replaced by a space: safe inside one comment
 * line or header. Returns the length written. */
size_t coons__clean_text(char *out, size_t cap, const char *text);

#endif
