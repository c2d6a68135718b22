/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The real OpenSCAD (Debian's `openscad` binary) renders the SCAD writer's
 * output of hand-built closed meshes: no warning on stderr (in particular
 * no "not manifold" / "may not be a valid 2-manifold" / "mesh is not
 * closed"), and the volume of the STL it exports, computed here, matches
 * the mesh's (or the analytic volume of a union of overlapping parts).
 * `use <f.scad>` must give the part modules without rendering anything,
 * `include <f.scad>` must render the model.
 *
 * Note: OpenSCAD 2021.01 re-orients a closed polyhedron given inside out,
 * so a globally reversed winding does not show here; write/test_scad.c checks
 * the winding itself. An inconsistently wound one fails ("not closed"). */
#define _XOPEN_SOURCE 700
#include <sys/wait.h>

#include "io_test_util.h"

/* OpenSCAD is a real client of the .scad output: a missing openscad fails
 * the test, never skips it (tools/setup.sh installs it). */
static void need_openscad(void)
{
    if (system("openscad --version >/dev/null 2>&1") != 0)
        fail_msg("openscad is not installed (tools/setup.sh installs it)");
}

/* Runs openscad -o out in, stderr into errf; returns the exit status. */
static int run_openscad(const char *in, const char *out, const char *errf)
{
    fflush(NULL);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        if (!freopen(errf, "w", stderr)) _exit(126);
        if (!freopen("/dev/null", "w", stdout)) _exit(126);
        execlp("openscad", "openscad", "-o", out, in, (char *)NULL);
        _exit(127);
    }
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* Renders `scad` (a file) and returns the volume of OpenSCAD's STL. */
static double render_volume(const char *dir, const char *scad, long *ntri)
{
    char out[160], errf[160];
    snprintf(out, sizeof out, "%s/render.stl", dir);
    snprintf(errf, sizeof errf, "%s/stderr.txt", dir);
    int rc = run_openscad(scad, out, errf);
    char *log = io_read_file(errf, NULL);
    assert_non_null(log);
    if (rc != 0) fail_msg("openscad exited with %d:\n%s", rc, log);
    const char *bad[] = {"WARNING", "ERROR", "not manifold", "2-manifold", "not closed"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        if (strstr(log, bad[i])) fail_msg("openscad said '%s':\n%s", bad[i], log);
    free(log);
    size_t len;
    char *d = io_read_file(out, &len);
    assert_non_null(d);
    float *t = NULL;
    long n;
    if (len >= 5 && strncmp(d, "solid", 5) == 0) {
        char *name = NULL;
        n = io_parse_stl_ascii(d, &t, &name);
        free(name);
    } else {
        n = io_parse_stl_binary((const unsigned char *)d, len, &t);
    }
    assert_true(n > 0);
    double v = io_soup_volume(t, n);
    free(t);
    free(d);
    unlink(out);
    unlink(errf);
    if (ntri) *ntri = n;
    return v;
}

static void write_scad(const coons_mesh *m, const char *path)
{
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.units = "mm";
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_write(m, path, COONS_FORMAT_SCAD, &o, &e), &e);
}

/* OpenSCAD exports single-precision-ish text: compare relatively. */
static void assert_volume(double got, double want)
{
    if (!(fabs(got - want) <= 1e-5 * fabs(want)))
        fail_msg("OpenSCAD's volume %.9g, expected %.9g", got, want);
}

/* Given a cube, a tetrahedron and a torus, each alone in a file, when
 * rendered, then OpenSCAD is silent and its volume is the mesh's. */
static void test_single_parts(void **state)
{
    (void)state;
    need_openscad();
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/part.scad", dir);
    for (int which = 0; which < 3; which++) {
        coons_mesh *m;
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(coons_mesh_new(&m, &e), &e);
        const double lo[3] = {-1, 0.5, 2}, hi[3] = {1.5, 2.25, 2.75}, sh[3] = {1, 2, 3};
        if (which == 0) io_box(m, "cube", lo, hi);
        if (which == 1) io_tetra(m, "tet", 3, 0.5, 2);
        if (which == 2) io_torus(m, "ring", 4, 1.5, 24, 12, sh);
        write_scad(m, p);
        long n;
        assert_volume(render_volume(dir, p, &n), coons_mesh_volume(m));
        assert_int_equal(n, (long)coons_mesh_triangle_count(m));
        coons_mesh_free(m);
    }
    io_rmdir(dir);
}

/* Given two overlapping boxes and a torus as three parts, when the file
 * is rendered (`include` semantics: the top-level call), then the volume is
 * that of the union (analytic); and a file doing `use <it>` and calling
 * one part module renders just that part. */
static void test_union_and_use(void **state)
{
    (void)state;
    need_openscad();
    char dir[64], p[128], q[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/model.scad", dir);
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    const double a0[3] = {0, 0, 0}, a1[3] = {2, 1, 1}, b0[3] = {1, 0.5, 0.25},
                 b1[3] = {3, 2, 0.75}, sh[3] = {10, 0, 0};
    io_box(m, "cube", a0, a1); /* named like the built-in on purpose */
    io_box(m, "second box", b0, b1);
    io_torus(m, "ring", 2, 0.5, 16, 8, sh);
    write_scad(m, p);
    double overlap = 1.0 * 0.5 * 0.5; /* [1,2]x[0.5,1]x[0.25,0.75] */
    coons_mesh *ring;
    assert_coons_ok(coons_mesh_new(&ring, &e), &e);
    io_torus(ring, "ring", 2, 0.5, 16, 8, sh);
    double vring = coons_mesh_volume(ring);
    assert_volume(render_volume(dir, p, NULL), 2.0 + 2.0 * 1.5 * 0.5 - overlap + vring);
    /* use <>: only the modules; call the second box. */
    snprintf(q, sizeof q, "%s/user.scad", dir);
    FILE *f = fopen(q, "w");
    assert_non_null(f);
    fprintf(f, "use <model.scad>\ncoons_model_second_box();\n");
    fclose(f);
    assert_volume(render_volume(dir, q, NULL), 2.0 * 1.5 * 0.5);
    /* include <>: the whole model, plus OpenSCAD's own cube() still works. */
    f = fopen(q, "w");
    assert_non_null(f);
    fprintf(f, "include <model.scad>\ntranslate([-10, 0, 0]) cube(1);\n");
    fclose(f);
    assert_volume(render_volume(dir, q, NULL), 2.0 + 2.0 * 1.5 * 0.5 - overlap + vring + 1.0);
    coons_mesh_free(ring);
    coons_mesh_free(m);
    io_rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_single_parts),
        cmocka_unit_test(test_union_and_use),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
