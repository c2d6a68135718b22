/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Writing a mesh to a file atomically, or to a stream.
 *
 * The file protocol is the classic one (STYLE 17; the model-format spec:
 * "a failure must never write or truncate an output file"): create a new
 * temporary file in the target's directory (so rename() stays within one
 * file system and is atomic), write it completely, fsync() it, close() it
 * (NFS reports some write errors only there), and rename() it over the
 * target; on any failure unlink the temporary file. Every write(2) result is
 * checked, so a full disk (ENOSPC) or a file size limit (EFBIG) is an error,
 * never a truncated file reported as success.
 *
 * The temporary file is opened with O_EXCL and mode 0666 rather than by
 * mkstemp(), whose 0600 would have to be widened by the umask, and the
 * umask can only be read by setting it (not thread-safe). */
#define _XOPEN_SOURCE 700
#include <errno.h>
#include <float.h>
#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "coons/version.h"
#include "writer.h"

#define DEFAULT_NAME "coons_model"
#define DEFAULT_HEADER "libcoons " COONS_VERSION_STRING

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
static const char *errstr(int e, char *buf, size_t cap)
{
    if (strerror_r(e, buf, cap) != 0) snprintf(buf, cap, "error %d", e);
    return buf;
}

static void sys_error(coons__sink *s, const char *doing)
{
    char msg[128];
    errstr(errno, msg, sizeof msg);
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
    while (n > 0) {
        if (s->fd >= 0) {
            ssize_t w = write(s->fd, p, n);
            if (w < 0) {
                if (errno == EINTR && coons__sink_ok(s)) continue;
                sys_error(s, "write");
                return 0;
            }
            if (w == 0) { /* not expected for regular files; never loop forever */
                errno = EIO;
                sys_error(s, "write");
                return 0;
            }
            p += w;
            n -= (size_t)w;
        } else {
            size_t w = fwrite(p, 1, n, s->fp);
            if (w < n) {
                if (errno == 0) errno = EIO;
                sys_error(s, "write");
                return 0;
            }
            n = 0;
        }
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

/* ---- formats -------------------------------------------------------- */

static int ieq(const char *a, const char *b)
{
    for (; *a && *b; a++, b++) {
        char x = (*a >= 'A' && *a <= 'Z') ? (char)(*a + 32) : *a;
        if (x != *b) return 0;
    }
    return *a == *b;
}

coons_status coons_format_from_path(const char *path, coons_format *out, coons_error *err)
{
    if (!path || !out) return coons__error_set(err, COONS_E_INVALID, "no path given");
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    const char *dot = strrchr(base, '.');
    if (dot && dot != base) {
        if (ieq(dot, ".stl")) return *out = COONS_FORMAT_STL_BINARY, COONS_OK;
        if (ieq(dot, ".off")) return *out = COONS_FORMAT_OFF, COONS_OK;
        if (ieq(dot, ".scad")) return *out = COONS_FORMAT_SCAD, COONS_OK;
    }
    return coons__error_set(err, COONS_E_INVALID,
                            "cannot tell the output format of '%s' (use .stl, .off or .scad, "
                            "or name the format)",
                            path);
}

coons_status coons_format_from_name(const char *name, coons_format *out, coons_error *err)
{
    if (!name || !out) return coons__error_set(err, COONS_E_INVALID, "no format name given");
    if (ieq(name, "stl") || ieq(name, "stl-binary")) return *out = COONS_FORMAT_STL_BINARY, COONS_OK;
    if (ieq(name, "stl-ascii")) return *out = COONS_FORMAT_STL_ASCII, COONS_OK;
    if (ieq(name, "off")) return *out = COONS_FORMAT_OFF, COONS_OK;
    if (ieq(name, "scad")) return *out = COONS_FORMAT_SCAD, COONS_OK;
    return coons__error_set(err, COONS_E_INVALID,
                            "unknown format '%s' (stl, stl-binary, stl-ascii, off, scad)", name);
}

const char *coons_format_name(coons_format format)
{
    switch (format) {
    case COONS_FORMAT_AUTO: return "auto";
    case COONS_FORMAT_STL_BINARY: return "stl-binary";
    case COONS_FORMAT_STL_ASCII: return "stl-ascii";
    case COONS_FORMAT_OFF: return "off";
    case COONS_FORMAT_SCAD: return "scad";
    }
    return "unknown";
}

/* ---- validation shared by both entry points -------------------------- */

static coons_status prepare(const coons_mesh *m, coons_format format,
                            const coons_write_options *opts, coons__wopts *o, coons_error *err)
{
    if (!m) return coons__error_set(err, COONS_E_INVALID, "no mesh given");
    if (opts && opts->version != COONS_WRITE_OPTIONS_VERSION)
        return coons__error_set(err, COONS_E_INVALID,
                                "write options version %u, this library knows %d", opts->version,
                                COONS_WRITE_OPTIONS_VERSION);
    if (format < COONS_FORMAT_STL_BINARY || format > COONS_FORMAT_SCAD)
        return coons__error_set(err, COONS_E_INVALID, "invalid output format %d", (int)format);
    o->name = opts && opts->name && opts->name[0] ? opts->name : DEFAULT_NAME;
    o->units = opts && opts->units ? opts->units : "";
    o->header = opts && opts->header ? opts->header : DEFAULT_HEADER;

    size_t nv = coons_mesh_vertex_count(m), nt = coons_mesh_triangle_count(m);
    if (format == COONS_FORMAT_STL_BINARY && nt > UINT32_MAX)
        return coons__error_set(err, COONS_E_LIMIT,
                                "binary STL holds at most %lu triangles, the mesh has %zu",
                                (unsigned long)UINT32_MAX, nt);
    /* The container enforces these; checking again costs one pass and
     * keeps a writer from ever emitting a file that reads back wrong. */
    const double *xyz = coons_mesh_vertices(m);
    for (size_t i = 0; i < 3 * nv; i++)
        if (!isfinite(xyz[i]))
            return coons__error_set(err, COONS_E_INVALID, "vertex %zu is not finite", i / 3);
    /* STL stores float32: a larger coordinate would become infinite. */
    if (format == COONS_FORMAT_STL_BINARY || format == COONS_FORMAT_STL_ASCII)
        for (size_t i = 0; i < 3 * nv; i++)
            if (fabs(xyz[i]) > FLT_MAX)
                return coons__error_set(err, COONS_E_LIMIT,
                                        "vertex %zu has the coordinate %.17g, outside the range "
                                        "of STL's 32-bit floats (+-%.9g): write OFF or SCAD, "
                                        "which keep doubles",
                                        i / 3, xyz[i], (double)FLT_MAX);
    const uint32_t *tri = coons_mesh_triangles(m);
    for (size_t i = 0; i < 3 * nt; i++)
        if (tri[i] >= nv)
            return coons__error_set(err, COONS_E_INVALID, "triangle %zu refers to vertex %lu of %zu",
                                    i / 3, (unsigned long)tri[i], nv);
    if (format == COONS_FORMAT_SCAD)
        for (size_t p = 0; p < coons_mesh_part_count(m); p++) {
            size_t tf, tc, vf, vc;
            coons_mesh_part_range(m, p, &tf, &tc, &vf, &vc);
            for (size_t i = 3 * tf; i < 3 * (tf + tc); i++)
                if (tri[i] < vf || tri[i] - vf >= vc)
                    return coons__error_set(err, COONS_E_INVALID,
                                            "triangle %zu of part %zu uses a vertex of another part",
                                            i / 3, p);
        }
    return COONS_OK;
}

static coons_status run_writer(const coons_mesh *m, coons_format format, const coons__wopts *o,
                               coons__sink *s)
{
    switch (format) {
    case COONS_FORMAT_STL_BINARY: return coons__write_stl_binary(m, o, s);
    case COONS_FORMAT_STL_ASCII: return coons__write_stl_ascii(m, o, s);
    case COONS_FORMAT_OFF: return coons__write_off(m, o, s);
    case COONS_FORMAT_SCAD: return coons__write_scad(m, o, s);
    case COONS_FORMAT_AUTO: break;
    }
    return s->status = coons__error_set(s->err, COONS_E_INTERNAL, "no writer for format %d",
                                        (int)format);
}

/* Sets up buffer and C locale, runs the writer, flushes the buffer. */
static coons_status write_all(const coons_mesh *m, coons_format format, const coons__wopts *o,
                              coons__sink *s)
{
    coons__fmt_scope fmt;
    s->buf = coons__malloc(COONS__SINK_BUFSIZE);
    if (!s->buf) return s->status = coons__error_nomem(s->err);
    if (!coons__fmt_begin(&fmt)) {
        coons__free(s->buf);
        s->buf = NULL;
        return s->status = coons__error_nomem(s->err);
    }
    s->fmt = &fmt;
    if (coons__sink_ok(s) && run_writer(m, format, o, s) == COONS_OK) coons__sink_flush(s);
    s->fmt = NULL;
    coons__fmt_end(&fmt);
    coons__free(s->buf);
    s->buf = NULL;
    return s->status;
}

static int same_file(const struct stat *a, const struct stat *b)
{
    return a->st_dev == b->st_dev && a->st_ino == b->st_ino;
}

coons_status coons_mesh_write_stream(const coons_mesh *m, FILE *fp, coons_format format,
                                     const coons_write_options *opts, coons_error *err)
{
    coons__wopts o;
    if (!fp) return coons__error_set(err, COONS_E_INVALID, "no stream given");
    coons_status st = prepare(m, format, opts, &o, err);
    if (st != COONS_OK) return st;
    int fd = fileno(fp);
    struct stat out_st, in_st;
    if (opts && opts->protect_path && fd >= 0 && fstat(fd, &out_st) == 0 &&
        stat(opts->protect_path, &in_st) == 0 && same_file(&out_st, &in_st))
        return coons__error_set(err, COONS_E_INVALID, "the output stream is the input '%s'",
                                opts->protect_path);
    coons__sink s = {NULL, 0, -1, fp, "<stream>", opts, NULL, COONS_OK, err};
    errno = 0;
    if (write_all(m, format, &o, &s) != COONS_OK) return s.status;
    if (fflush(fp) != 0 || ferror(fp)) {
        if (errno == 0) errno = EIO;
        sys_error(&s, "write");
    }
    return s.status;
}

/* ---- atomic file output ------------------------------------------------ */

static uint64_t mix64(uint64_t x)
{
    /* splitmix64 finaliser */
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/* Creates "<dir>/.<base>.coons-XXXXXX" with O_EXCL; returns the fd or -1
 * (errno set). `tmp` receives the name. */
static int create_temp(const char *target, char *tmp, size_t cap, mode_t mode)
{
    const char *slash = strrchr(target, '/');
    size_t dirlen = slash ? (size_t)(slash - target) + 1 : 0;
    const char *base = target + dirlen;
    size_t baselen = strlen(base);
    if (baselen > 200) baselen = 200; /* stay under NAME_MAX */
    static const char alnum[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    uint64_t seed = mix64((uint64_t)ts.tv_nsec ^ ((uint64_t)ts.tv_sec << 30) ^
                          ((uint64_t)getpid() << 16) ^ (uint64_t)(uintptr_t)&ts);
    for (int attempt = 0; attempt < 100; attempt++) {
        uint64_t r = seed = mix64(seed + (uint64_t)attempt);
        char suffix[7];
        for (int i = 0; i < 6; i++, r >>= 6) suffix[i] = alnum[r % 62];
        suffix[6] = '\0';
        int n = snprintf(tmp, cap, "%.*s.%.*s.coons-%s", (int)dirlen, target, (int)baselen, base,
                         suffix);
        if (n < 0 || (size_t)n >= cap) {
            errno = ENAMETOOLONG;
            return -1;
        }
        int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode);
        if (fd >= 0 || errno != EEXIST) return fd;
    }
    errno = EEXIST;
    return -1;
}

/* Best effort: make the rename itself durable. */
static void sync_dir(const char *target)
{
    const char *slash = strrchr(target, '/');
    char dir[PATH_MAX];
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else if (slash == target)
        snprintf(dir, sizeof dir, "/");
    else
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - target), target);
    int fd = open(dir, O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
        (void)fsync(fd);
        close(fd);
    }
}

coons_status coons_mesh_write(const coons_mesh *m, const char *path, coons_format format,
                              const coons_write_options *opts, coons_error *err)
{
    coons__wopts o;
    if (!path || !path[0]) return coons__error_set(err, COONS_E_INVALID, "no output path given");
    if (format == COONS_FORMAT_AUTO) {
        coons_status st = coons_format_from_path(path, &format, err);
        if (st != COONS_OK) return st;
    }
    coons_status st = prepare(m, format, opts, &o, err);
    if (st != COONS_OK) return st;

    /* Write through a symbolic link: replace the file it names. */
    char resolved[PATH_MAX];
    const char *target = path;
    struct stat lst, out_st, in_st;
    char msg[128];
    if (lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode)) {
        if (!realpath(path, resolved))
            return coons__error_set(err, COONS_E_IO, "cannot resolve the link '%s': %s", path,
                                    errstr(errno, msg, sizeof msg));
        target = resolved;
    }
    int exists = stat(target, &out_st) == 0;
    if (exists && !S_ISREG(out_st.st_mode))
        return coons__error_set(err, COONS_E_INVALID, "'%s' exists and is not a regular file",
                                path);
    if (exists && opts && opts->protect_path && stat(opts->protect_path, &in_st) == 0 &&
        same_file(&out_st, &in_st))
        return coons__error_set(err, COONS_E_INVALID,
                                "the output '%s' is the input file '%s'; refusing to overwrite it",
                                path, opts->protect_path);

    coons__sink s = {NULL, 0, -1, NULL, path, opts, NULL, COONS_OK, err};
    if (!coons__sink_ok(&s)) return s.status;
    char tmp[PATH_MAX];
    s.fd = create_temp(target, tmp, sizeof tmp, 0666);
    if (s.fd < 0)
        return coons__error_set(err, COONS_E_IO, "cannot create a temporary file next to '%s': %s",
                                path, errstr(errno, msg, sizeof msg));
    /* Replacing a file keeps its permissions. */
    if (exists && fchmod(s.fd, out_st.st_mode & 07777) != 0) sys_error(&s, "set the mode of");

    if (s.status == COONS_OK) write_all(m, format, &o, &s);
    if (s.status == COONS_OK && fsync(s.fd) != 0) sys_error(&s, "sync");
    if (close(s.fd) != 0) sys_error(&s, "close");
    s.fd = -1;
    if (s.status == COONS_OK && coons__sink_ok(&s) && rename(tmp, target) != 0)
        sys_error(&s, "rename the temporary file onto");
    if (s.status != COONS_OK) {
        unlink(tmp);
        return s.status;
    }
    sync_dir(target);
    return COONS_OK;
}

void coons_write_options_init(coons_write_options *o)
{
    const coons_write_options d = COONS_WRITE_OPTIONS_INIT;
    if (o) *o = d;
}
