/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The byte sink every writer feeds: a 1 MiB buffer written out with
 * write(2) (files) or fwrite (streams), with a sticky status (the first
 * error wins and stops everything after it, as SQLite's and libarchive's
 * writers do) and the cancellation poll. Every write(2) result is checked,
 * so a full disk (ENOSPC) or a file size limit (EFBIG) is an error, never
 * a truncated file reported as success.
 *
 * A file's buffers may be written by a second thread (coons__sink_start()):
 * a ring of BG_BUFS buffers, the calling thread filling one while the
 * thread writes those handed over before, in order, so the bytes are the
 * same. */
#define _XOPEN_SOURCE 700
#include <errno.h>
#include <pthread.h>
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

/* ---- the writing thread ------------------------------------------------ */

#define BG_BUFS 4

struct coons__sink_bg {
    pthread_t tid;
    pthread_mutex_t mu;
    pthread_cond_t cv;    /* a buffer was handed over, written, or the end */
    char *buf[BG_BUFS];
    size_t len[BG_BUFS];
    unsigned head, filled; /* handed over: head .. head + filled - 1, mod BG_BUFS */
    int fd;
    int done; /* no more buffers come */
    int drop; /* write nothing more (an error, or cancelled) */
    int err;  /* errno of the first failed write(2), or 0 */
};

static void *bg_run(void *arg)
{
    struct coons__sink_bg *b = arg;
    pthread_mutex_lock(&b->mu);
    for (;;) {
        while (!b->filled && !b->done) pthread_cond_wait(&b->cv, &b->mu);
        if (!b->filled) break;
        const char *p = b->buf[b->head];
        size_t n = b->len[b->head];
        int skip = b->drop || b->err;
        pthread_mutex_unlock(&b->mu);
        int e = 0;
        while (!skip && n > 0) {
            ssize_t w = write(b->fd, p, n);
            if (w < 0 && errno == EINTR) continue;
            if (w <= 0) { /* w == 0: not expected for regular files; never loop forever */
                e = w < 0 ? errno : EIO;
                break;
            }
            p += w;
            n -= (size_t)w;
        }
        pthread_mutex_lock(&b->mu);
        if (e && !b->err) b->err = e;
        b->head = (b->head + 1) % BG_BUFS;
        b->filled--;
        pthread_cond_broadcast(&b->cv);
    }
    pthread_mutex_unlock(&b->mu);
    return NULL;
}

static void bg_free(struct coons__sink_bg *b, const char *keep)
{
    for (int i = 0; i < BG_BUFS; i++)
        if (b->buf[i] != keep) coons__free(b->buf[i]);
    coons__free(b);
}

void coons__sink_start(coons__sink *s) { s->threaded = s->fd >= 0; }

/* Starts the thread at the first full buffer: 0 (COONS_E_NOMEM recorded)
 * without memory for the ring; a thread that cannot be started leaves the
 * sink synchronous. */
static int bg_start(coons__sink *s)
{
    s->threaded = 0;
    struct coons__sink_bg *b = coons__calloc(1, sizeof *b);
    if (!b) {
        s->status = coons__error_nomem(s->err);
        return 0;
    }
    b->buf[0] = s->buf;
    for (int i = 1; i < BG_BUFS; i++)
        if (!(b->buf[i] = coons__malloc(COONS__SINK_BUFSIZE))) {
            bg_free(b, s->buf);
            s->status = coons__error_nomem(s->err);
            return 0;
        }
    b->fd = s->fd;
    if (pthread_mutex_init(&b->mu, NULL) != 0) {
        bg_free(b, s->buf);
        return 1;
    }
    if (pthread_cond_init(&b->cv, NULL) != 0) {
        pthread_mutex_destroy(&b->mu);
        bg_free(b, s->buf);
        return 1;
    }
    if (pthread_create(&b->tid, NULL, bg_run, b) != 0) {
        pthread_cond_destroy(&b->cv);
        pthread_mutex_destroy(&b->mu);
        bg_free(b, s->buf);
        return 1;
    }
    s->bg = b;
    return 1;
}

int coons__sink_finish(coons__sink *s)
{
    struct coons__sink_bg *b = s->bg;
    s->threaded = 0;
    if (!b) return s->status == COONS_OK;
    pthread_mutex_lock(&b->mu);
    if (s->status != COONS_OK) b->drop = 1;
    b->done = 1;
    pthread_cond_broadcast(&b->cv);
    while (b->filled) pthread_cond_wait(&b->cv, &b->mu);
    int e = b->err;
    pthread_mutex_unlock(&b->mu);
    pthread_join(b->tid, NULL);
    pthread_cond_destroy(&b->cv);
    pthread_mutex_destroy(&b->mu);
    bg_free(b, s->buf);
    s->bg = NULL;
    if (e && s->status == COONS_OK) {
        errno = e;
        coons__sink_sys_error(s, "write");
    }
    return s->status == COONS_OK;
}

/* Hands the n bytes of s->buf to the thread and takes a free buffer. */
static int bg_hand_over(coons__sink *s, size_t n)
{
    struct coons__sink_bg *b = s->bg;
    pthread_mutex_lock(&b->mu);
    b->len[(b->head + b->filled) % BG_BUFS] = n;
    b->filled++;
    pthread_cond_broadcast(&b->cv);
    while (b->filled == BG_BUFS) pthread_cond_wait(&b->cv, &b->mu);
    s->buf = b->buf[(b->head + b->filled) % BG_BUFS];
    int e = b->err;
    if (e) b->drop = 1;
    pthread_mutex_unlock(&b->mu);
    if (e) {
        errno = e;
        coons__sink_sys_error(s, "write");
        return 0;
    }
    return 1;
}

/* ---- flushing ------------------------------------------------------------ */

int coons__sink_flush(coons__sink *s)
{
    if (s->status != COONS_OK) return 0;
    const char *p = s->buf;
    size_t n = s->len;
    s->len = 0;
    s->bytes += n;
    if (s->threaded && n > COONS__SINK_BUFSIZE - COONS__SINK_MAXREC && !bg_start(s)) return 0;
    if (s->bg) {
        if (n && !bg_hand_over(s, n)) return 0;
        n = 0;
    }
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
