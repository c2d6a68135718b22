/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Writing one file of any format and either mesh kind, atomically, or to a
 * stream (the entry points are surface.c and volume.c).
 *
 * The file protocol is the classic one (STYLE 17; the model-format spec:
 * "a failure must never write or truncate an output file"): create a new
 * temporary file in the target's directory (so rename() stays within one
 * file system and is atomic), write it completely, fsync() it, close() it
 * (NFS reports some write errors only there), and rename() it over the
 * target; on any failure unlink the temporary file. Every write(2) result
 * is checked (sink.c).
 *
 * The temporary file is opened with O_EXCL and mode 0666 rather than by
 * mkstemp(), whose 0600 would have to be widened by the umask, and the
 * umask can only be read by setting it (not thread-safe). */
#define _XOPEN_SOURCE 700
#include <errno.h>
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

coons_status coons__write_prepare(coons__write_job *job, int mesh_given, coons_format format,
                                  coons_mesh_kind kind, const coons_write_options *opts,
                                  coons_error *err)
{
    if (!mesh_given) return coons__error_set(err, COONS_E_INVALID, "no mesh given");
    /* version 1 has no `written` progress fields */
    if (opts && coons__record_version_check("write options", opts->version, 1,
                                            COONS_WRITE_OPTIONS_VERSION,
                                            "COONS_WRITE_OPTIONS_INIT", err))
        return COONS_E_INVALID;
    job->row = coons__format_row_of(format);
    if (!job->row)
        return coons__error_set(err, COONS_E_INVALID, "invalid output format %d", (int)format);
    /* A volume format may also hold triangle meshes (VTU): its row then
     * names a surface writer. */
    int surface_too = kind == COONS_MESH_KIND_SURFACE && job->row->write_surface;
    if (job->row->kind == COONS_MESH_KIND_SOLID && kind != COONS_MESH_KIND_SOLID)
        return coons__error_set(err, COONS_E_INVALID,
                                "the format '%s' holds exact solids, not a mesh (write the "
                                "model with coons_model_write_solid())",
                                job->row->name);
    if (kind == COONS_MESH_KIND_SOLID && job->row->kind != COONS_MESH_KIND_SOLID)
        return coons__error_set(err, COONS_E_INVALID,
                                "the format '%s' holds meshes, not exact solids (step, "
                                "step-ap242, iges or brep)",
                                job->row->name);
    if (job->row->kind != kind && !surface_too)
        return coons__error_set(err, COONS_E_INVALID,
                                kind == COONS_MESH_KIND_SURFACE
                                    ? "the format '%s' holds volume meshes, not a triangle mesh "
                                      "(write a coons_volume_mesh with coons_volume_mesh_write())"
                                    : "the format '%s' holds triangle meshes, not a volume mesh "
                                      "(write a coons_mesh with coons_mesh_write())",
                                job->row->name);
    job->o.name = opts && opts->name && opts->name[0] ? opts->name : DEFAULT_NAME;
    job->o.units = opts && opts->units ? opts->units : "";
    job->o.header = opts && opts->header ? opts->header : DEFAULT_HEADER;
    job->o.background = opts ? opts->background : NULL;
    job->o.nbackground = opts && opts->background ? opts->nbackground : 0;
    if (opts && opts->nbackground && !opts->background)
        return coons__error_set(err, COONS_E_INVALID,
                                "write options: %zu background parts but no list of them",
                                opts->nbackground);
    return COONS_OK;
}

coons_status coons__write_resolve(const char *path, coons_format *format, coons_error *err)
{
    if (!path || !path[0]) return coons__error_set(err, COONS_E_INVALID, "no output path given");
    if (*format == COONS_FORMAT_AUTO) return coons_format_from_path(path, format, err);
    return COONS_OK;
}

static coons_status run_writer(const coons__write_job *job, coons__sink *s)
{
    const coons__format_row *r = job->row;
    if (job->surface && r->write_surface) return r->write_surface(job->surface, &job->o, s);
    if (job->volume && r->write_volume)
        return r->write_volume(job->volume, &job->o, s);
    if (job->model && r->write_solid) return r->write_solid(job->model, r->format, &job->o, s);
    return s->status = coons__error_set(s->err, COONS_E_INTERNAL, "no writer for the format '%s'",
                                        r->name);
}

/* Sets up buffer and C locale, runs the writer, flushes the buffer. */
static coons_status write_all(const coons__write_job *job, coons__sink *s)
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
    coons__sink_start(s);
    if (coons__sink_ok(s) && run_writer(job, s) == COONS_OK) coons__sink_flush(s);
    coons__sink_finish(s);
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

coons_status coons__write_stream(const coons__write_job *job, FILE *fp,
                                 const coons_write_options *opts, coons_error *err)
{
    int fd = fileno(fp);
    struct stat out_st, in_st;
    if (opts && opts->protect_path && fd >= 0 && fstat(fd, &out_st) == 0 &&
        stat(opts->protect_path, &in_st) == 0 && same_file(&out_st, &in_st))
        return coons__error_set(err, COONS_E_INVALID, "the output stream is the input '%s'",
                                opts->protect_path);
    coons__sink s = {NULL, 0, -1, fp, "<stream>", opts, NULL, COONS_OK, err, 0, NULL, NULL, 0, NULL};
    coons__sink_watch(&s, opts);
    errno = 0;
    if (write_all(job, &s) != COONS_OK) return s.status;
    if (fflush(fp) != 0 || ferror(fp)) {
        if (errno == 0) errno = EIO;
        coons__sink_sys_error(&s, "write");
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

coons_status coons__write_path(const coons__write_job *job, const char *path,
                               const coons_write_options *opts, coons_error *err)
{
    /* Write through a symbolic link: replace the file it names. */
    char resolved[PATH_MAX];
    const char *target = path;
    struct stat lst, out_st, in_st;
    char msg[128];
    if (lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode)) {
        if (!realpath(path, resolved))
            return coons__error_set(err, COONS_E_IO, "cannot resolve the link '%s': %s", path,
                                    coons__errno_text(errno, msg, sizeof msg));
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

    coons__sink s = {NULL, 0, -1, NULL, path, opts, NULL, COONS_OK, err, 0, NULL, NULL, 0, NULL};
    coons__sink_watch(&s, opts);
    if (!coons__sink_ok(&s)) return s.status;
    char tmp[PATH_MAX];
    s.fd = create_temp(target, tmp, sizeof tmp, 0666);
    if (s.fd < 0)
        return coons__error_set(err, COONS_E_IO, "cannot create a temporary file next to '%s': %s",
                                path, coons__errno_text(errno, msg, sizeof msg));
    /* Replacing a file keeps its permissions. */
    if (exists && fchmod(s.fd, out_st.st_mode & 07777) != 0)
        coons__sink_sys_error(&s, "set the mode of");

    if (s.status == COONS_OK) write_all(job, &s);
    if (s.status == COONS_OK && fsync(s.fd) != 0) coons__sink_sys_error(&s, "sync");
    if (close(s.fd) != 0) coons__sink_sys_error(&s, "close");
    s.fd = -1;
    if (s.status == COONS_OK && coons__sink_ok(&s) && rename(tmp, target) != 0)
        coons__sink_sys_error(&s, "rename the temporary file onto");
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

coons_status coons_model_write_solid(const coons_model *m, const char *path, coons_format format,
                                     const coons_write_options *opts, coons_error *err)
{
    coons__write_job job = {0};
    if (!m) return coons__error_set(err, COONS_E_INVALID, "no model given");
    coons_status st = coons__write_resolve(path, &format, err);
    if (st != COONS_OK) return st;
    st = coons__write_prepare(&job, m != NULL, format, COONS_MESH_KIND_SOLID, opts, err);
    if (st != COONS_OK) return st;
    if ((st = coons__check_solid(err)) != COONS_OK) return st;
    job.model = m;
    if (!(opts && opts->units && opts->units[0])) job.o.units = coons_model_units(m);
    if (!job.o.units) job.o.units = "";
    return coons__write_path(&job, path, opts, err);
}
