/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Reading a whole input file under a size limit (read_file.h): the model
 * loader's and the mesh reader's way in from a path. A regular file is
 * measured first (fstat) and read in one buffer of its size plus one byte,
 * which notices a file that grew; anything else is read in doubling
 * buffers, at most max_bytes + 1 bytes (one more shows it is too big). */
#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "read_file.h"

coons_status coons__file_error(coons_error *err, coons_status code, const char *path,
                               const char *fmt, ...)
{
    if (!err) return code;
    char msg[COONS_ERROR_MESSAGE_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    coons__error_set(err, code, "%s: %s", path, msg);
    snprintf(err->file, sizeof err->file, "%s", path);
    return code;
}

static coons_status io_error(coons_error *err, const char *path, const char *verb, const char *what,
                             int errnum)
{
    char buf[256] = "unknown error";
    if (errnum) (void)strerror_r(errnum, buf, sizeof buf);
    return coons__file_error(err, COONS_E_IO, path, "cannot %s the %s: %s", verb, what, buf);
}

/* Reads all of f, at most max_bytes + 1 bytes; cap: the first guess of the
 * size. */
static coons_status read_all(FILE *f, const char *path, const char *what, const char *hint,
                             size_t cap, size_t max_bytes, unsigned char **out, size_t *len_out,
                             coons_error *err)
{
    size_t len = 0, most = max_bytes < SIZE_MAX ? max_bytes + 1 : SIZE_MAX;
    unsigned char *buf = coons__malloc(cap);
    if (!buf) return coons__error_nomem(err);
    for (;;) {
        if (len == cap) {
            if (cap > max_bytes || cap == SIZE_MAX) break;
            size_t nc = cap > SIZE_MAX / 2 ? SIZE_MAX : cap * 2;
            if (nc > most) nc = most;
            unsigned char *nb = coons__realloc(buf, nc);
            if (!nb) {
                coons__free(buf);
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
    coons_status rc = COONS_OK;
    if (bad)
        rc = io_error(err, path, "read", what, errnum);
    else if (len > max_bytes) /* not a regular file, or one that grew */
        rc = coons__file_error(err, COONS_E_LIMIT, path, "the %s is more than %zu bytes, the limit (%s)",
                        what, max_bytes, hint);
    if (rc) {
        coons__free(buf);
        return rc;
    }
    *out = buf;
    *len_out = len;
    return COONS_OK;
}

coons_status coons__read_file(const char *path, const char *what, const char *hint, size_t max_bytes,
                              unsigned char **out, size_t *len, coons_error *err)
{
    *out = NULL;
    *len = 0;
    errno = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return io_error(err, path, "open", what, errno);
    struct stat st;
    size_t cap = 1 << 16;
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode)) {
        if ((uintmax_t)st.st_size > max_bytes) {
            fclose(f);
            return coons__file_error(err, COONS_E_LIMIT, path,
                              "the %s is %jd bytes, above the limit of %zu bytes (%s)", what,
                              (intmax_t)st.st_size, max_bytes, hint);
        }
        cap = (size_t)st.st_size + 1; /* +1: notices a file that grew */
    }
    coons_status rc = read_all(f, path, what, hint, cap, max_bytes, out, len, err);
    fclose(f);
    return rc;
}
