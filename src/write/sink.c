/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The byte sink every writer feeds: a 1 MiB buffer written out with
 * write(2) (files) or fwrite (streams), with a sticky status (the first
 * error wins and stops everything after it, as SQLite's and libarchive's
 * writers do) and the cancellation poll. Every write(2) result is checked,
 * so a full disk (ENOSPC) or a file size limit (EFBIG) is an error, never
 * a truncated file reported as success. */
#define _XOPEN_SOURCE 700
#include <errno.h>
#include <unistd.h>

#include "writer.h"

size_t coons__clean_text(char *out, size_t cap, const char *text)
{
    size_t n = 0;
    if (!cap) return 0;
    for (; text && text[n] && n + 1 < cap; n++) {
        unsigned char c = (unsigned char)text[n];
        out[n] = (c < 0x20 || c == 0x7f) ? ' ' : (char)c;
    }
    out[n] = '\0';
    return n;
}

/* strerror() is not thread-safe; this is the XSI strerror_r. */
const char *coons__errno_text(int e, char *buf, size_t cap)
{
    if (strerror_r(e, buf, cap) != 0) snprintf(buf, cap, "error %d", e);
    return buf;
}

void coons__sink_sys_error(coons__sink *s, const char *doing)
{
    char msg[128];
    coons__errno_text(errno, msg, sizeof msg);
    if (s->status == COONS_OK)
        s->status = coons__error_set(s->err, COONS_E_IO, "cannot %s '%s': %s", doing, s->what, msg);
}

static int cancelled(coons__sink *s)
{
    if (!s->opts || !s->opts->cancel) return 0;
    /* The callback runs in the caller's locale, not the writer's "C". */
    if (s->fmt) coons__fmt_suspend(s->fmt);
    int c = s->opts->cancel(s->opts->cancel_ctx);
    if (s->fmt) coons__fmt_resume(s->fmt);
    return c != 0;
}

int coons__sink_ok(coons__sink *s)
{
    if (s->status == COONS_OK && cancelled(s))
        s->status = coons__error_set(s->err, COONS_E_IO, "writing '%s' was cancelled", s->what);
    return s->status == COONS_OK;
}

int coons__sink_flush(coons__sink *s)
{
    if (s->status != COONS_OK) return 0;
    const char *p = s->buf;
    size_t n = s->len;
    s->len = 0;
    s->bytes += n;
    while (n > 0) {
        if (s->fd >= 0) {
            ssize_t w = write(s->fd, p, n);
            if (w < 0) {
                if (errno == EINTR && coons__sink_ok(s)) continue;
                coons__sink_sys_error(s, "write");
                return 0;
            }
            if (w == 0) { /* not expected for regular files; never loop forever */
                errno = EIO;
                coons__sink_sys_error(s, "write");
                return 0;
            }
            p += w;
            n -= (size_t)w;
        } else {
            size_t w = fwrite(p, 1, n, s->fp);
            if (w < n) {
                if (errno == 0) errno = EIO;
                coons__sink_sys_error(s, "write");
                return 0;
            }
            n = 0;
        }
    }
    if (s->written) { /* in the caller's locale, as `cancel` */
        if (s->fmt) coons__fmt_suspend(s->fmt);
        s->written(s->written_ctx, s->bytes);
        if (s->fmt) coons__fmt_resume(s->fmt);
    }
    return coons__sink_ok(s);
}

int coons__sink_put(coons__sink *s, const void *data, size_t n)
{
    const char *d = data;
    while (n > 0) {
        if (s->status != COONS_OK) return 0;
        if (s->len == COONS__SINK_BUFSIZE && !coons__sink_flush(s)) return 0;
        size_t k = COONS__SINK_BUFSIZE - s->len;
        if (k > n) k = n;
        memcpy(s->buf + s->len, d, k);
        s->len += k;
        d += k;
        n -= k;
    }
    return s->status == COONS_OK;
}
