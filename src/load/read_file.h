/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Reading a whole input file under a size limit, and errors about a file as
 * a whole (read_file.c), shared by the model loader (json/load.c) and the
 * mesh reader (read/mesh_read.c). */
#ifndef COONS_IO_READ_FILE_H
#define COONS_IO_READ_FILE_H

#include "coons_internal.h"

/* Reads all of the file at `path` into *out (coons__malloc'd, not NUL
 * terminated; the caller frees it) and its length into *len, refusing a file
 * of more than max_bytes bytes: a regular file by its size before reading,
 * anything else (a pipe, a file that grew) once reading passes the limit.
 * `what` names the contents in the messages ("model": "the model is N bytes,
 * above the limit of M bytes (<hint>)"), `hint` says how to raise the limit.
 * Errors about the file as a whole: the message starts with the path, which
 * also goes to err->file. COONS_E_IO (cannot open, cannot read),
 * COONS_E_LIMIT, COONS_E_NOMEM. */
/* An error about a file as a whole: "path: message" in err, err->file the
 * path (cut to fit), no line, column or JSON path; returns code. */
coons_status coons__file_error(coons_error *err, coons_status code, const char *path,
                               const char *fmt, ...) COONS__PRINTF(4, 5);
coons_status coons__read_file(const char *path, const char *what, const char *hint, size_t max_bytes,
                              unsigned char **out, size_t *len, coons_error *err);

#endif
