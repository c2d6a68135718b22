/* SPDX-License-Identifier: GPL-3.0-or-later */
/* coons_mesh_write and coons_volume_mesh_write: the format table (every
 * row's name and extension map back to it), formats from names and
 * extensions, each mesh kind refused by the other kind's formats, atomic
 * replacement
 * (a failed or cancelled write leaves the previous file byte for byte and
 * no temporary file), refusal to overwrite the input or a non-regular
 * file, permissions, symbolic links, stream errors, signals, and output
 * that does not depend on the process locale. Write errors are real: a
 * file size limit (RLIMIT_FSIZE) in a child process and /dev/full. */
#define _XOPEN_SOURCE 700
#include <errno.h>
#include <fcntl.h>
#include <locale.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>

#include "io_test_util.h"

static const char previous[] = "previous output, must survive\n";

static coons_mesh *torus_mesh(size_t n)
{
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    const double sh[3] = {0, 0, 0};
    io_torus(m, "ring", 10, 3, n, n, sh);
    return m;
}

/* A lattice of n^3 unit hex8 cells with a node and a cell field. */
static coons_volume_mesh *lattice_volume(uint32_t n)
{
    uint32_t m = n + 1;
    double *xyz = malloc(3 * sizeof(double) * m * m * m);
    double *w = malloc(sizeof(double) * m * m * m);
    uint32_t *cells = malloc(8 * sizeof(uint32_t) * n * n * n);
    int32_t *body = malloc(sizeof(int32_t) * n * n * n);
    assert_true(xyz && w && cells && body);
    for (uint32_t k = 0; k < m; k++)
        for (uint32_t j = 0; j < m; j++)
            for (uint32_t i = 0; i < m; i++) {
                size_t v = i + m * (j + (size_t)m * k);
                xyz[3 * v] = i / 3.0;
                xyz[3 * v + 1] = j * 1.1;
                xyz[3 * v + 2] = k / 7.0;
                w[v] = (double)k / n;
            }
    size_t c = 0;
    for (uint32_t k = 0; k < n; k++)
        for (uint32_t j = 0; j < n; j++)
            for (uint32_t i = 0; i < n; i++, c++) {
                static const uint32_t off[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
                for (int q = 0; q < 8; q++)
                    cells[8 * c + (size_t)q] =
                        (i + off[q][0]) + m * ((j + off[q][1]) + m * (k + off[q][2]));
                body[c] = (int32_t)(c % 3);
            }
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_new(COONS_ELEMENT_HEX8, &vm, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, xyz, (size_t)m * m * m, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "block", NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, cells, (size_t)n * n * n, 0, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "w", COONS_FIELD_FLOAT64, w,
                                                &e), &e);
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "body", COONS_FIELD_INT32,
                                                body, &e), &e);
    free(xyz);
    free(w);
    free(cells);
    free(body);
    return vm;
}

static void path_in(char *out, size_t cap, const char *dir, const char *name)
{
    snprintf(out, cap, "%s/%s", dir, name);
}

static void assert_file_is(const char *path, const char *content)
{
    size_t len;
    char *d = io_read_file(path, &len);
    assert_non_null(d);
    assert_int_equal(len, strlen(content));
    assert_memory_equal(d, content, len);
    free(d);
}

static void test_formats(void **state)
{
    (void)state;
    coons_format f = COONS_FORMAT_AUTO;
    coons_error e = COONS_ERROR_INIT;
    assert_int_equal(coons_format_from_path("a.stl", &f, &e), COONS_OK);
    assert_int_equal(f, COONS_FORMAT_STL_BINARY);
    assert_int_equal(coons_format_from_path("dir.off/A.STL", &f, &e), COONS_OK);
    assert_int_equal(f, COONS_FORMAT_STL_BINARY);
    assert_int_equal(coons_format_from_path("x/y.Off", &f, &e), COONS_OK);
    assert_int_equal(f, COONS_FORMAT_OFF);
    assert_int_equal(coons_format_from_path("part.scad", &f, &e), COONS_OK);
    assert_int_equal(f, COONS_FORMAT_SCAD);
    const char *bad[] = {"a.stl.bak", "noext", "dir.stl/file", ".stl", "a.obj", "a.", ""};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(coons_format_from_path(bad[i], &f, &e), COONS_E_INVALID);
        assert_int_equal(e.code, COONS_E_INVALID);
    }
    assert_int_equal(coons_format_from_name("STL", &f, &e), COONS_OK);
    assert_int_equal(f, COONS_FORMAT_STL_BINARY);
    assert_int_equal(coons_format_from_name("stl-binary", &f, &e), COONS_OK);
    assert_int_equal(f, COONS_FORMAT_STL_BINARY);
    assert_int_equal(coons_format_from_name("stl-ascii", &f, &e), COONS_OK);
    assert_int_equal(f, COONS_FORMAT_STL_ASCII);
    assert_int_equal(coons_format_from_name("off", &f, &e), COONS_OK);
    assert_int_equal(f, COONS_FORMAT_OFF);
    assert_int_equal(coons_format_from_name("Scad", &f, &e), COONS_OK);
    assert_int_equal(f, COONS_FORMAT_SCAD);
    assert_int_equal(coons_format_from_name("obj", &f, &e), COONS_E_INVALID);
    assert_string_equal(coons_format_name(COONS_FORMAT_STL_ASCII), "stl-ascii");
    assert_string_equal(coons_format_name((coons_format)42), "unknown");
    /* AUTO with an unknown extension is refused before anything is made. */
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    path_in(p, sizeof p, dir, "out.xyz");
    coons_mesh *m = torus_mesh(8);
    assert_int_equal(coons_mesh_write(m, p, COONS_FORMAT_AUTO, NULL, &e), COONS_E_INVALID);
    /* An explicit format does not care about the extension. */
    assert_coons_ok(coons_mesh_write(m, p, COONS_FORMAT_OFF, NULL, &e), &e);
    char *d = io_read_file(p, NULL);
    assert_int_equal(strncmp(d, "OFF\n", 4), 0);
    free(d);
    /* Bad options version. */
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.version = 99;
    assert_int_equal(coons_mesh_write(m, p, COONS_FORMAT_OFF, &o, &e), COONS_E_INVALID);
    coons_mesh_free(m);
    io_rmdir(dir);
}

/* Given an existing output and a file size limit of 1000 bytes (a full
 * disk as far as write(2) is concerned), when each format is written over
 * it in a child process, then each write fails with COONS_E_IO, the old
 * file is unchanged and no temporary file remains. */
static void test_size_limit_keeps_previous(void **state)
{
    (void)state;
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    path_in(p, sizeof p, dir, "out.stl");
    io_write_file(p, previous, strlen(previous));
    coons_mesh *m = torus_mesh(60); /* 7200 triangles, ~360 kB binary */
    fflush(NULL);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        signal(SIGXFSZ, SIG_IGN); /* write() then fails with EFBIG */
        struct rlimit rl = {1000, 1000};
        if (setrlimit(RLIMIT_FSIZE, &rl) != 0) _exit(10);
        for (int f = COONS_FORMAT_STL_BINARY; f <= COONS_FORMAT_SCAD; f++) {
            coons_error e = COONS_ERROR_INIT;
            int rc = coons_mesh_write(m, p, (coons_format)f, NULL, &e);
            if (rc != COONS_E_IO) _exit(20 + f);
            if (!strstr(e.message, "out.stl") || !strstr(e.message, "large")) _exit(30 + f);
        }
        _exit(0);
    }
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 0);
    assert_file_is(p, previous);
    assert_int_equal(io_dir_count(dir), 1);
    /* Without the limit the same write succeeds and replaces it. */
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_write(m, p, COONS_FORMAT_AUTO, NULL, &e), &e);
    size_t len;
    char *d = io_read_file(p, &len);
    assert_int_equal(len, 84 + 50 * coons_mesh_triangle_count(m));
    free(d);
    assert_int_equal(io_dir_count(dir), 1);
    coons_mesh_free(m);
    io_rmdir(dir);
}

/* Missing directory, a directory or a device as output: errors, nothing
 * created, nothing replaced (as root, rename() would replace /dev/null). */
static void test_bad_targets(void **state)
{
    (void)state;
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    coons_mesh *m = torus_mesh(8);
    coons_error e = COONS_ERROR_INIT;
    path_in(p, sizeof p, dir, "missing/out.stl");
    assert_int_equal(coons_mesh_write(m, p, COONS_FORMAT_AUTO, NULL, &e), COONS_E_IO);
    assert_non_null(strstr(e.message, "No such file"));
    assert_int_equal(coons_mesh_write(m, dir, COONS_FORMAT_OFF, NULL, &e), COONS_E_INVALID);
    struct stat before, after;
    assert_int_equal(stat("/dev/null", &before), 0);
    assert_int_equal(coons_mesh_write(m, "/dev/null", COONS_FORMAT_OFF, NULL, &e),
                     COONS_E_INVALID);
    assert_int_equal(stat("/dev/null", &after), 0);
    assert_true(S_ISCHR(after.st_mode) && after.st_ino == before.st_ino);
    assert_int_equal(io_dir_count(dir), 0);
    assert_int_equal(io_dir_count("/dev") > 0, 1);
    if (geteuid() != 0) { /* root ignores directory permissions */
        assert_int_equal(chmod(dir, 0555), 0);
        path_in(p, sizeof p, dir, "out.stl");
        assert_int_equal(coons_mesh_write(m, p, COONS_FORMAT_AUTO, NULL, &e), COONS_E_IO);
        assert_int_equal(chmod(dir, 0755), 0);
        assert_int_equal(io_dir_count(dir), 0);
    }
    coons_mesh_free(m);
    io_rmdir(dir);
}

/* Given an input file, when the output names it (directly, through a hard
 * link or a symbolic link, or as an open stream), then the write is refused
 * and the input is unchanged; another file is fine. */
static void test_output_is_input(void **state)
{
    (void)state;
    char dir[64], in[128], hard[128], soft[128], other[128];
    io_tmpdir(dir, sizeof dir);
    path_in(in, sizeof in, dir, "model.stl");
    path_in(hard, sizeof hard, dir, "hard.stl");
    path_in(soft, sizeof soft, dir, "soft.stl");
    path_in(other, sizeof other, dir, "other.stl");
    io_write_file(in, previous, strlen(previous));
    assert_int_equal(link(in, hard), 0);
    assert_int_equal(symlink("model.stl", soft), 0);
    coons_mesh *m = torus_mesh(8);
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.protect_path = in;
    coons_error e = COONS_ERROR_INIT;
    const char *outs[] = {in, hard, soft};
    for (int i = 0; i < 3; i++) {
        assert_int_equal(coons_mesh_write(m, outs[i], COONS_FORMAT_AUTO, &o, &e), COONS_E_INVALID);
        assert_non_null(strstr(e.message, "input"));
    }
    FILE *fp = fopen(in, "ab");
    assert_non_null(fp);
    assert_int_equal(coons_mesh_write_stream(m, fp, COONS_FORMAT_OFF, &o, &e), COONS_E_INVALID);
    fclose(fp);
    assert_file_is(in, previous);
    assert_int_equal(io_dir_count(dir), 3);
    assert_coons_ok(coons_mesh_write(m, other, COONS_FORMAT_AUTO, &o, &e), &e);
    /* protect_path naming a file that does not exist protects nothing. */
    o.protect_path = "/nonexistent/input.json";
    assert_coons_ok(coons_mesh_write(m, other, COONS_FORMAT_AUTO, &o, &e), &e);
    coons_mesh_free(m);
    io_rmdir(dir);
}

/* Writing through a symbolic link replaces the file it names and keeps
 * the link. */
static void test_symlink_followed(void **state)
{
    (void)state;
    char dir[64], real[128], lnk[128];
    io_tmpdir(dir, sizeof dir);
    path_in(real, sizeof real, dir, "real.off");
    path_in(lnk, sizeof lnk, dir, "link.off");
    io_write_file(real, previous, strlen(previous));
    assert_int_equal(symlink("real.off", lnk), 0);
    coons_mesh *m = torus_mesh(8);
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_write(m, lnk, COONS_FORMAT_AUTO, NULL, &e), &e);
    struct stat st;
    assert_int_equal(lstat(lnk, &st), 0);
    assert_true(S_ISLNK(st.st_mode));
    char *d = io_read_file(real, NULL);
    assert_int_equal(strncmp(d, "OFF\n", 4), 0);
    free(d);
    assert_int_equal(io_dir_count(dir), 2);
    coons_mesh_free(m);
    io_rmdir(dir);
}

/* New files get 0666 minus the umask; a replaced file keeps its mode. */
static void test_modes(void **state)
{
    (void)state;
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    path_in(p, sizeof p, dir, "out.stl");
    coons_mesh *m = torus_mesh(8);
    coons_error e = COONS_ERROR_INIT;
    mode_t old = umask(027);
    assert_coons_ok(coons_mesh_write(m, p, COONS_FORMAT_AUTO, NULL, &e), &e);
    umask(old);
    struct stat st;
    assert_int_equal(stat(p, &st), 0);
    assert_int_equal(st.st_mode & 0777, 0640);
    assert_int_equal(chmod(p, 0604), 0);
    assert_coons_ok(coons_mesh_write(m, p, COONS_FORMAT_AUTO, NULL, &e), &e);
    assert_int_equal(stat(p, &st), 0);
    assert_int_equal(st.st_mode & 0777, 0604);
    coons_mesh_free(m);
    io_rmdir(dir);
}

/* A stream that fails (/dev/full: ENOSPC) gives COONS_E_IO. */
static void test_stream_errors(void **state)
{
    (void)state;
    coons_mesh *m = torus_mesh(40);
    for (int f = COONS_FORMAT_STL_BINARY; f <= COONS_FORMAT_SCAD; f++) {
        FILE *fp = fopen("/dev/full", "wb");
        assert_non_null(fp); /* Linux has it: its absence fails, never skips */
        coons_error e = COONS_ERROR_INIT;
        assert_int_equal(coons_mesh_write_stream(m, fp, (coons_format)f, NULL, &e), COONS_E_IO);
        assert_non_null(strstr(e.message, "space"));
        fclose(fp);
    }
    coons_error e = COONS_ERROR_INIT;
    assert_int_equal(coons_mesh_write_stream(m, stdout, COONS_FORMAT_AUTO, NULL, &e),
                     COONS_E_INVALID);
    /* A good stream gets exactly what the file writer writes. */
    char dir[64], p[128], q[128];
    io_tmpdir(dir, sizeof dir);
    path_in(p, sizeof p, dir, "a.scad");
    path_in(q, sizeof q, dir, "b.scad");
    assert_coons_ok(coons_mesh_write(m, p, COONS_FORMAT_AUTO, NULL, &e), &e);
    FILE *fp = fopen(q, "wb");
    assert_coons_ok(coons_mesh_write_stream(m, fp, COONS_FORMAT_SCAD, NULL, &e), &e);
    assert_int_equal(fclose(fp), 0);
    size_t la, lb;
    char *a = io_read_file(p, &la), *b = io_read_file(q, &lb);
    assert_int_equal(la, lb);
    assert_memory_equal(a, b, la);
    free(a);
    free(b);
    coons_mesh_free(m);
    io_rmdir(dir);
}

static int cancel_after(void *ctx)
{
    int *n = ctx;
    return --*n < 0;
}

/* Cancelling at each poll in turn leaves the previous file and no
 * temporary file, and reports COONS_E_IO "cancelled". */
static void test_cancel(void **state)
{
    (void)state;
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    path_in(p, sizeof p, dir, "out.stl");
    io_write_file(p, previous, strlen(previous));
    coons_mesh *m = torus_mesh(150); /* 45000 triangles, 2.25 MB: 3 buffers */
    for (int k = 0; k < 6; k++) {
        int left = k;
        coons_write_options o = COONS_WRITE_OPTIONS_INIT;
        o.cancel = cancel_after;
        o.cancel_ctx = &left;
        coons_error e = COONS_ERROR_INIT;
        assert_int_equal(coons_mesh_write(m, p, COONS_FORMAT_AUTO, &o, &e), COONS_E_IO);
        assert_non_null(strstr(e.message, "cancelled"));
        assert_file_is(p, previous);
        assert_int_equal(io_dir_count(dir), 1);
    }
    int left = 1000;
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.cancel = cancel_after;
    o.cancel_ctx = &left;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_write(m, p, COONS_FORMAT_AUTO, &o, &e), &e);
    assert_true(left < 1000 - 4); /* it was polled */
    coons_mesh_free(m);
    io_rmdir(dir);
}

static volatile sig_atomic_t got_signal;
static void on_signal(int sig)
{
    (void)sig;
    got_signal = 1;
}
static int signal_cancel(void *ctx)
{
    (void)ctx;
    return got_signal != 0;
}

/* Given a child writing ASCII STL over a file again and again with a
 * SIGTERM handler that sets the cancel flag (what coons2stl does), when it
 * receives SIGTERM at various moments, then afterwards the directory holds
 * exactly one file: the previous content or a complete new output. */
static void test_signal_leaves_nothing(void **state)
{
    (void)state;
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    path_in(p, sizeof p, dir, "out.stl");
    coons_mesh *m = torus_mesh(120);
    char ref_path[128];
    path_in(ref_path, sizeof ref_path, dir, "ref");
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_write(m, ref_path, COONS_FORMAT_STL_ASCII, NULL, &e), &e);
    size_t ref_len = 0;
    char *ref = io_read_file(ref_path, &ref_len);
    unlink(ref_path);
    int cancelled = 0;
    for (int round = 0; round < 12; round++) {
        io_write_file(p, previous, strlen(previous));
        int ready[2];
        assert_int_equal(pipe(ready), 0);
        fflush(NULL);
        pid_t pid = fork();
        assert_true(pid >= 0);
        if (pid == 0) {
            struct sigaction sa;
            memset(&sa, 0, sizeof sa);
            sa.sa_handler = on_signal;
            sigemptyset(&sa.sa_mask);
            sigaction(SIGTERM, &sa, NULL);
            if (write(ready[1], "r", 1) != 1) _exit(6);
            coons_write_options o = COONS_WRITE_OPTIONS_INIT;
            o.cancel = signal_cancel;
            for (int i = 0; i < 1000 && !got_signal; i++) {
                int rc = coons_mesh_write(m, p, COONS_FORMAT_STL_ASCII, &o, NULL);
                if (rc != COONS_OK) _exit(got_signal ? 3 : 4);
            }
            _exit(got_signal ? 2 : 5);
        }
        char c;
        assert_int_equal(read(ready[0], &c, 1), 1);
        close(ready[0]);
        close(ready[1]);
        struct timespec ts = {0, 3000000L * round + 200000L};
        nanosleep(&ts, NULL);
        kill(pid, SIGTERM);
        int status;
        assert_int_equal(waitpid(pid, &status, 0), pid);
        assert_true(WIFEXITED(status));
        int code = WEXITSTATUS(status);
        assert_true(code == 2 || code == 3);
        cancelled += code == 3;
        assert_int_equal(io_dir_count(dir), 1);
        size_t len = 0;
        char *d = io_read_file(p, &len);
        assert_non_null(d);
        if (!(len == strlen(previous) && memcmp(d, previous, len) == 0))
            assert_true(len == ref_len && memcmp(d, ref, len) == 0);
        free(d);
    }
    print_message("%d of 12 signals arrived mid-write\n", cancelled);
    free(ref);
    coons_mesh_free(m);
    io_rmdir(dir);
}

/* Given a German locale (decimal comma) compiled for the test, when a
 * child process selects it with setlocale and writes OFF, SCAD and ASCII
 * STL, then the bytes equal those written under the "C" locale. */
static void test_locale_independent(void **state)
{
    (void)state;
    char dir[64], cmd[256];
    io_tmpdir(dir, sizeof dir);
    snprintf(cmd, sizeof cmd, "localedef -i de_DE -f UTF-8 %s/de_DE.UTF-8 >/dev/null 2>&1", dir);
    if (system(cmd) != 0) {
        snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
        (void)system(cmd);
        fail_msg("localedef cannot compile de_DE.UTF-8 (tools/setup.sh installs `locales`)");
    }
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    const double sh[3] = {0.5, -1.25, 1e-7};
    io_torus(m, "ring", 3.3, 1.1, 10, 7, sh);
    static const char *names[3] = {"c.off", "c.scad", "c.txt"};
    static const coons_format fmts[3] = {COONS_FORMAT_OFF, COONS_FORMAT_SCAD,
                                         COONS_FORMAT_STL_ASCII};
    char p[160];
    for (int i = 0; i < 3; i++) {
        path_in(p, sizeof p, dir, names[i]);
        assert_coons_ok(coons_mesh_write(m, p, fmts[i], NULL, &e), &e);
    }
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        setenv("LOCPATH", dir, 1);
        if (!setlocale(LC_ALL, "de_DE.UTF-8")) _exit(10);
        if (strcmp(localeconv()->decimal_point, ",") != 0) _exit(11);
        char buf[32];
        snprintf(buf, sizeof buf, "%g", 0.5);
        if (strcmp(buf, "0,5") != 0) _exit(12);
        for (int i = 0; i < 3; i++) {
            char q[160], r[200];
            path_in(q, sizeof q, dir, names[i]);
            snprintf(r, sizeof r, "%s.de", q);
            if (coons_mesh_write(m, r, fmts[i], NULL, NULL) != COONS_OK) _exit(20 + i);
            size_t la = 0, lb = 1;
            char *a = io_read_file(q, &la), *b = io_read_file(r, &lb);
            if (!a || !b || la != lb || memcmp(a, b, la) != 0) _exit(30 + i);
            free(a);
            free(b);
        }
        /* The caller's locale is back after the call. */
        if (strcmp(localeconv()->decimal_point, ",") != 0) _exit(40);
        coons_mesh_free(m); /* no leak for valgrind (tools/memcheck.sh) */
        _exit(0);
    }
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 0);
    coons_mesh_free(m);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    assert_int_equal(system(cmd), 0);
}

/* Given allocations failing at each point in turn, every format either
 * fails with COONS_E_NOMEM leaving the previous file and no temporary file,
 * or succeeds with exactly the normal output (the ASCII STL writer falls
 * back to formatting without its vertex text cache). */
static void test_allocation_failures(void **state)
{
    (void)state;
    char dir[64], p[128], ref[128];
    io_tmpdir(dir, sizeof dir);
    path_in(p, sizeof p, dir, "out");
    path_in(ref, sizeof ref, dir, "ref");
    coons_mesh *m = torus_mesh(12);
    coons_error e = COONS_ERROR_INIT;
    for (int f = COONS_FORMAT_STL_BINARY; f <= COONS_FORMAT_SCAD; f++) {
        assert_coons_ok(coons_mesh_write(m, ref, (coons_format)f, NULL, &e), &e);
        size_t ref_len = 0;
        char *want = io_read_file(ref, &ref_len);
        int fallback_seen = 0;
        for (long n = 0;; n++) {
            io_write_file(p, previous, strlen(previous));
            coons_test_fail_after(n);
            int rc = coons_mesh_write(m, p, (coons_format)f, NULL, &e);
            long used = coons_test_alloc_count();
            coons_test_fail_after(-1);
            if (rc == COONS_E_NOMEM) {
                assert_file_is(p, previous);
                assert_int_equal(io_dir_count(dir), 2);
                continue;
            }
            assert_int_equal(rc, COONS_OK);
            size_t len = 0;
            char *got = io_read_file(p, &len);
            assert_int_equal(len, ref_len);
            assert_memory_equal(got, want, len);
            free(got);
            if (used <= n) break; /* nothing failed: done */
            fallback_seen = 1;
        }
        assert_int_equal(fallback_seen, f == COONS_FORMAT_STL_ASCII);
        free(want);
    }
    coons_mesh_free(m);
    io_rmdir(dir);
}

/* Given the format table, then formats are numbered 1.. without gaps, and
 * every row's name, aliases' target and extension (in any case) map back
 * to it; the refusals list every name and extension of the table. */
static void test_format_table(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    char names[256] = "", exts[256] = "";
    int f = 1, surface = 0, volume = 0, solid = 0;
    for (; coons_format_kind((coons_format)f) != COONS_MESH_KIND_NONE; f++) {
        coons_format fmt = (coons_format)f, got = COONS_FORMAT_AUTO;
        const char *name = coons_format_name(fmt);
        assert_string_not_equal(name, "unknown");
        assert_coons_ok(coons_format_from_name(name, &got, &e), &e);
        assert_int_equal(got, f);
        char upper[64];
        size_t n = 0;
        for (; name[n] && n + 1 < sizeof upper; n++)
            upper[n] = (char)(name[n] >= 'a' && name[n] <= 'z' ? name[n] - 32 : name[n]);
        upper[n] = '\0';
        assert_coons_ok(coons_format_from_name(upper, &got, &e), &e);
        assert_int_equal(got, f);
        strcat(names, name);
        strcat(names, " ");
        const char *ext = coons_format_extension(fmt);
        if (ext) {
            char path[96];
            assert_int_equal(ext[0], '.');
            snprintf(path, sizeof path, "dir.x/model%s", ext);
            assert_coons_ok(coons_format_from_path(path, &got, &e), &e);
            assert_int_equal(got, f);
            for (char *c = path; *c; c++)
                if (*c >= 'a' && *c <= 'z') *c = (char)(*c - 32);
            assert_coons_ok(coons_format_from_path(path, &got, &e), &e);
            assert_int_equal(got, f);
            strcat(exts, ext);
            strcat(exts, " ");
        }
        surface += coons_format_kind(fmt) == COONS_MESH_KIND_SURFACE;
        volume += coons_format_kind(fmt) == COONS_MESH_KIND_VOLUME;
        solid += coons_format_kind(fmt) == COONS_MESH_KIND_SOLID;
    }
    assert_int_equal(f - 1, surface + volume + solid);
    assert_int_equal(solid, 4); /* STEP AP214 and AP242, IGES, BREP */
    assert_int_equal(surface, 5); /* STL binary and ASCII, OFF, SCAD, 3MF */
    assert_true(volume >= 1);
    assert_int_equal(coons_format_kind(COONS_FORMAT_AUTO), COONS_MESH_KIND_NONE);
    assert_null(coons_format_extension(COONS_FORMAT_AUTO));
    assert_null(coons_format_extension((coons_format)f));
    assert_null(coons_format_extension(COONS_FORMAT_STL_ASCII)); /* .stl means binary */
    assert_string_equal(coons_format_name((coons_format)f), "unknown");
    assert_string_equal(coons_format_name(COONS_FORMAT_AUTO), "auto");
    assert_int_equal(coons_format_kind(COONS_FORMAT_VTK), COONS_MESH_KIND_VOLUME);
    assert_string_equal(coons_format_name(COONS_FORMAT_VTK), "vtk");
    /* The refusals name everything the table holds. */
    coons_format got;
    assert_int_equal(coons_format_from_name("ply", &got, &e), COONS_E_INVALID);
    for (char *w = strtok(names, " "); w; w = strtok(NULL, " "))
        assert_non_null(strstr(e.message, w));
    assert_non_null(strstr(e.message, "stl, stl-binary"));
    assert_int_equal(coons_format_from_path("a.ply", &got, &e), COONS_E_INVALID);
    for (char *w = strtok(exts, " "); w; w = strtok(NULL, " "))
        assert_non_null(strstr(e.message, w));
    assert_non_null(strstr(e.message, "'a.ply' (use .stl, .off, "));

    /* coons_io(3) lists what the table holds: every extension under
     * coons_format_from_path, every name under coons_format_from_name. */
    char *man = io_read_file(COONS_SOURCE_DIR "/man/man3/coons_io.3", NULL);
    assert_non_null(man);
    char *by_path = strstr(man, ".It Fn coons_format_from_path");
    char *by_name = by_path ? strstr(by_path, ".It Fn coons_format_from_name") : NULL;
    char *end = by_name ? strstr(by_name, ".It Fn coons_format_name") : NULL;
    assert_non_null(end);
    *end = '\0';
    for (int k = 1; k < f; k++) {
        const char *ext = coons_format_extension((coons_format)k);
        char want[80];
        if (ext) {
            *by_name = '\0';
            assert_non_null(strstr(by_path, ext));
            *by_name = '.';
        }
        snprintf(want, sizeof want, "\n.Qq %s", coons_format_name((coons_format)k));
        int found = 0;
        for (char *q = strstr(by_name, want); q && !found; q = strstr(q + 1, want))
            found = q[strlen(want)] == ' ' || q[strlen(want)] == '\n';
        if (!found) fail_msg("coons_io(3) does not list the format name '%s'", want + 5);
    }
    free(man);
}

/* Given a triangle mesh and a volume mesh and an existing file, when each
 * is written in a format of the other kind (by name or by extension, to a
 * file or a stream), then COONS_E_INVALID says which function to call and
 * nothing is created or changed. */
static void test_kind_mismatch(void **state)
{
    (void)state;
    char dir[64], stl[128], vtk[128];
    io_tmpdir(dir, sizeof dir);
    path_in(stl, sizeof stl, dir, "a.stl");
    path_in(vtk, sizeof vtk, dir, "a.vtk");
    io_write_file(stl, previous, strlen(previous));
    io_write_file(vtk, previous, strlen(previous));
    coons_mesh *m = torus_mesh(8);
    coons_volume_mesh *vm = lattice_volume(2);
    coons_error e = COONS_ERROR_INIT;
    assert_int_equal(coons_mesh_write(m, vtk, COONS_FORMAT_AUTO, NULL, &e), COONS_E_INVALID);
    assert_non_null(strstr(e.message, "coons_volume_mesh_write"));
    assert_int_equal(coons_mesh_write(m, stl, COONS_FORMAT_VTK, NULL, &e), COONS_E_INVALID);
    assert_int_equal(coons_mesh_write_stream(m, stdout, COONS_FORMAT_VTK, NULL, &e),
                     COONS_E_INVALID);
    for (int f = COONS_FORMAT_STL_BINARY; f <= COONS_FORMAT_SCAD; f++) {
        assert_int_equal(coons_volume_mesh_write(vm, vtk, (coons_format)f, NULL, &e),
                         COONS_E_INVALID);
        assert_non_null(strstr(e.message, "coons_mesh_write"));
        assert_non_null(strstr(e.message, coons_format_name((coons_format)f)));
        assert_int_equal(coons_volume_mesh_write_stream(vm, stdout, (coons_format)f, NULL, &e),
                         COONS_E_INVALID);
    }
    assert_int_equal(coons_volume_mesh_write(vm, stl, COONS_FORMAT_AUTO, NULL, &e),
                     COONS_E_INVALID);
    /* The other refusals of the shared entry checks. */
    assert_int_equal(coons_volume_mesh_write(NULL, vtk, COONS_FORMAT_AUTO, NULL, &e),
                     COONS_E_INVALID);
    assert_non_null(strstr(e.message, "no mesh"));
    assert_int_equal(coons_volume_mesh_write(vm, NULL, COONS_FORMAT_VTK, NULL, &e),
                     COONS_E_INVALID);
    assert_int_equal(coons_volume_mesh_write(vm, "", COONS_FORMAT_VTK, NULL, &e), COONS_E_INVALID);
    assert_int_equal(coons_volume_mesh_write(vm, vtk, (coons_format)77, NULL, &e),
                     COONS_E_INVALID);
    assert_non_null(strstr(e.message, "invalid output format 77"));
    assert_int_equal(coons_volume_mesh_write_stream(vm, NULL, COONS_FORMAT_VTK, NULL, &e),
                     COONS_E_INVALID);
    assert_int_equal(coons_volume_mesh_write_stream(vm, stdout, COONS_FORMAT_AUTO, NULL, &e),
                     COONS_E_INVALID);
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.version = COONS_WRITE_OPTIONS_VERSION + 1;
    assert_int_equal(coons_volume_mesh_write(vm, vtk, COONS_FORMAT_VTK, &o, &e), COONS_E_INVALID);
    assert_non_null(strstr(e.message, "options version"));
    assert_file_is(stl, previous);
    assert_file_is(vtk, previous);
    assert_int_equal(io_dir_count(dir), 2);
    coons_volume_mesh_free(vm);
    coons_mesh_free(m);
    io_rmdir(dir);
}

/* The atomic file protocol, through the volume path: given an existing
 * .vtk, when a write fails (file size limit in a child, cancellation at
 * each poll, output naming the protected input, /dev/full as a stream),
 * then the file is byte for byte what it was and no temporary file
 * remains; a successful write replaces it (keeping its mode, through a
 * link) with exactly what the stream writer writes. */
static void test_volume_atomic(void **state)
{
    (void)state;
    char dir[64], p[128], lnk[128], q[128];
    io_tmpdir(dir, sizeof dir);
    path_in(p, sizeof p, dir, "out.vtk");
    io_write_file(p, previous, strlen(previous));
    coons_volume_mesh *vm = lattice_volume(40); /* 64000 cells, 68921 nodes: ~4 MB */
    fflush(NULL);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        signal(SIGXFSZ, SIG_IGN);
        /* In the third buffer (the buffers after the first are written by a
         * second thread: its error still arrives), and within the first (in
         * this order: a hard limit only goes down). */
        static const rlim_t limits[2] = {5 << 19, 100000};
        for (int i = 0; i < 2; i++) {
            struct rlimit rl = {limits[i], limits[i]};
            if (setrlimit(RLIMIT_FSIZE, &rl) != 0) _exit(10);
            coons_error e = COONS_ERROR_INIT;
            if (coons_volume_mesh_write(vm, p, COONS_FORMAT_AUTO, NULL, &e) != COONS_E_IO)
                _exit(11);
            if (!strstr(e.message, "out.vtk") || !strstr(e.message, "large")) _exit(12);
        }
        _exit(0);
    }
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 0);
    assert_file_is(p, previous);
    assert_int_equal(io_dir_count(dir), 1);

    for (int k = 0; k < 6; k++) {
        int left = k;
        coons_write_options o = COONS_WRITE_OPTIONS_INIT;
        o.cancel = cancel_after;
        o.cancel_ctx = &left;
        coons_error e = COONS_ERROR_INIT;
        assert_int_equal(coons_volume_mesh_write(vm, p, COONS_FORMAT_VTK, &o, &e), COONS_E_IO);
        assert_non_null(strstr(e.message, "cancelled"));
        assert_file_is(p, previous);
        assert_int_equal(io_dir_count(dir), 1);
    }
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.protect_path = p;
    coons_error e = COONS_ERROR_INIT;
    assert_int_equal(coons_volume_mesh_write(vm, p, COONS_FORMAT_AUTO, &o, &e), COONS_E_INVALID);
    assert_non_null(strstr(e.message, "input"));
    assert_file_is(p, previous);
    FILE *fp = fopen("/dev/full", "wb");
    if (fp) {
        assert_int_equal(coons_volume_mesh_write_stream(vm, fp, COONS_FORMAT_VTK, NULL, &e),
                         COONS_E_IO);
        assert_non_null(strstr(e.message, "space"));
        fclose(fp);
    }

    /* Success: through a link, keeping the mode, equal to the stream. */
    path_in(lnk, sizeof lnk, dir, "link.vtk");
    assert_int_equal(symlink("out.vtk", lnk), 0);
    assert_int_equal(chmod(p, 0604), 0);
    int left = 1000;
    o.protect_path = NULL;
    o.cancel = cancel_after;
    o.cancel_ctx = &left;
    assert_coons_ok(coons_volume_mesh_write(vm, lnk, COONS_FORMAT_AUTO, &o, &e), &e);
    assert_true(left < 1000 - 3); /* polled: before, per buffer, before the rename */
    struct stat st;
    assert_int_equal(stat(p, &st), 0);
    assert_int_equal(st.st_mode & 0777, 0604);
    assert_int_equal(lstat(lnk, &st), 0);
    assert_true(S_ISLNK(st.st_mode));
    path_in(q, sizeof q, dir, "stream.vtk");
    fp = fopen(q, "wb");
    assert_coons_ok(coons_volume_mesh_write_stream(vm, fp, COONS_FORMAT_VTK, NULL, &e), &e);
    assert_int_equal(fclose(fp), 0);
    size_t la, lb;
    char *a = io_read_file(p, &la), *b = io_read_file(q, &lb);
    assert_true(la > ((size_t)3 << 20));
    assert_int_equal(la, lb);
    assert_memory_equal(a, b, la);
    assert_int_equal(strncmp(a, "# vtk DataFile", 14), 0);
    free(a);
    free(b);
    assert_int_equal(io_dir_count(dir), 3);
    coons_volume_mesh_free(vm);
    io_rmdir(dir);
}

/* Given allocations failing at each point in turn, a volume write either
 * fails with COONS_E_NOMEM leaving the previous file and no temporary
 * file, or succeeds with exactly the normal output. */
static void test_volume_allocation_failures(void **state)
{
    (void)state;
    char dir[64], p[128], ref[128];
    io_tmpdir(dir, sizeof dir);
    path_in(p, sizeof p, dir, "out.vtk");
    path_in(ref, sizeof ref, dir, "ref.vtk");
    coons_volume_mesh *vm = lattice_volume(3);
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_write(vm, ref, COONS_FORMAT_AUTO, NULL, &e), &e);
    size_t ref_len = 0;
    char *want = io_read_file(ref, &ref_len);
    long failures = 0;
    for (long n = 0;; n++) {
        io_write_file(p, previous, strlen(previous));
        coons_test_fail_after(n);
        int rc = coons_volume_mesh_write(vm, p, COONS_FORMAT_AUTO, NULL, &e);
        long used = coons_test_alloc_count(), live = coons_test_live_allocs();
        coons_test_fail_after(-1);
        assert_int_equal(live, 0);
        if (rc == COONS_E_NOMEM) {
            assert_file_is(p, previous);
            assert_int_equal(io_dir_count(dir), 2);
            failures++;
            continue;
        }
        assert_int_equal(rc, COONS_OK);
        size_t len = 0;
        char *got = io_read_file(p, &len);
        assert_int_equal(len, ref_len);
        assert_memory_equal(got, want, len);
        free(got);
        if (used <= n) break;
    }
    assert_true(failures >= 1); /* at least the sink's buffer */
    free(want);
    coons_volume_mesh_free(vm);
    io_rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_formats),
        cmocka_unit_test(test_size_limit_keeps_previous),
        cmocka_unit_test(test_bad_targets),
        cmocka_unit_test(test_output_is_input),
        cmocka_unit_test(test_symlink_followed),
        cmocka_unit_test(test_modes),
        cmocka_unit_test(test_stream_errors),
        cmocka_unit_test(test_cancel),
        cmocka_unit_test(test_signal_leaves_nothing),
        cmocka_unit_test(test_locale_independent),
        cmocka_unit_test(test_allocation_failures),
        cmocka_unit_test(test_format_table),
        cmocka_unit_test(test_kind_mismatch),
        cmocka_unit_test(test_volume_atomic),
        cmocka_unit_test(test_volume_allocation_failures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
