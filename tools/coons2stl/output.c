/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * -o: the mesh written to a file or standard output. A file is written to
 * a temporary file in the same directory and renamed into place only after
 * everything succeeded (coons_mesh_write()); the model file itself is
 * never overwritten; signals during the write cancel it cleanly.
 */
#define _POSIX_C_SOURCE 200809L /* sigaction */

#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"

/* SIGINT, SIGTERM and SIGHUP while the output file is being written only set
 * this flag: the library polls it (coons_write_options.cancel), removes its
 * temporary file and returns, leaving any previous output untouched; then
 * the signal is raised again with its default action. Outside the write the
 * default actions stay: before it nothing exists to clean up. */
static volatile sig_atomic_t caught_signal;

static void on_signal(int sig) { caught_signal = sig; }

static int write_cancelled(void *ctx)
{
    (void)ctx;
    return caught_signal != 0;
}

static const int handled_signals[] = {SIGINT, SIGTERM, SIGHUP};
#define NSIG_HANDLED (sizeof handled_signals / sizeof handled_signals[0])

static void catch_signals(struct sigaction old[NSIG_HANDLED])
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0; /* no SA_RESTART: a blocked write returns EINTR and the cancel is polled */
    for (size_t i = 0; i < NSIG_HANDLED; i++) sigaction(handled_signals[i], &sa, &old[i]);
}

static void restore_signals(const struct sigaction old[NSIG_HANDLED])
{
    for (size_t i = 0; i < NSIG_HANDLED; i++) sigaction(handled_signals[i], &old[i], NULL);
}

/* "dir/part.scad" -> "part": the name of the module that renders the whole
 * model in SCAD (what `use <part.scad>` users call) and of the ASCII STL
 * solid; taken from the output file, else from the model file. */
static void model_name(const char *path, char *out, size_t cap)
{
    out[0] = '\0';
    if (!path || strcmp(path, "-") == 0) return;
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    snprintf(out, cap, "%s", base);
    char *dot = strrchr(out, '.');
    if (dot && dot != out) *dot = '\0';
}

/* Refuses before the (possibly long) meshing; the library checks again at
 * write time. */
int cli_is_model_file(const char *output, const char *input)
{
    struct stat in_st, out_st;
    return stat(input, &in_st) == 0 && stat(output, &out_st) == 0 &&
           in_st.st_dev == out_st.st_dev && in_st.st_ino == out_st.st_ino;
}

static void mesh_warnings(const coons_csg_report *rep)
{
    if (rep->triangles_out > 0 && !rep->closed)
        cli_message(1, "the mesh is not closed");
    else if (rep->nonmanifold_edges)
        cli_message(1,
                    "the mesh is closed but not a 2-manifold: %zu edges bound more than two "
                    "triangles (solids touching along a curve)",
                    rep->nonmanifold_edges);
}

/* Writes `mesh` (a file: with the signals caught) and frees it. */
static coons_status write_mesh(coons_mesh *mesh, const char *output, coons_format format,
                               const coons_write_options *wopts, coons_error *err)
{
    coons_status rc;
    if (!output) {
        rc = coons_mesh_write_stream(mesh, stdout, format, wopts, err);
    } else {
        struct sigaction old[NSIG_HANDLED];
        catch_signals(old);
        rc = coons_mesh_write(mesh, output, format, wopts, err);
        restore_signals(old);
    }
    coons_mesh_free(mesh);
    return rc;
}

coons_status cli_write_volume_file(const coons_volume_mesh *vm, const char *path,
                                   coons_format format, const coons_write_options *wopts,
                                   coons_error *err)
{
    coons_write_options w = *wopts;
    w.cancel = write_cancelled;
    struct sigaction old[NSIG_HANDLED];
    catch_signals(old);
    coons_status rc = coons_volume_mesh_write(vm, path, format, &w, err);
    restore_signals(old);
    return rc;
}

int cli_caught_signal(void) { return caught_signal != 0; }

/* Whatever happened, nothing partial is left: either the write was
 * cancelled (temporary file removed, old output untouched) or it had
 * already completed. Die of the signal as expected. */
void cli_die_of_caught_signal(coons_status rc, const char *shown)
{
    if (rc != COONS_OK) fprintf(stderr, "%s: %s: interrupted; nothing was written\n", PROG, shown);
    int sig = caught_signal;
    signal(sig, SIG_DFL);
    raise(sig);
}

static int write_named(const coons_model *m, coons_mesh *mesh, coons_format format,
                       const char *output, const char *input, const char *shown);

/*
 * Writes the boundary mesh of the model (all bodies, or only body `body`
 * when >= 0) to `output` (NULL or "-": standard output) in `format`,
 * sampled with `so` (its tolerance is set: -t or the model's;
 * --resolution, --max-triangles).
 */
int cli_write_output(const coons_model *m, long body, coons_format format, const char *output,
                     const coons_sample_options *so, int repair, const char *input)
{
    coons_error err = COONS_ERROR_INIT;
    int to_stdout = !output || strcmp(output, "-") == 0;
    const char *shown = to_stdout ? "<stdout>" : output;
    int from_file = input && strcmp(input, "-") != 0;
    if (!to_stdout && from_file && cli_is_model_file(output, input)) {
        fprintf(stderr, "%s: the output '%s' is the model file '%s'; refusing to overwrite it\n",
                PROG, output, input);
        return EXIT_USAGE;
    }

    coons_mesh *mesh = NULL;
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    coons_status rc = cli_make_solid(m, body, so, repair, &mesh, &rep, &err);
    cli_progress_end();
    if (rc != COONS_OK) {
        cli_message(0, "%s: %s%s; nothing was written", shown,
                    rc == COONS_E_CSG ? "repair or union failed: " : "", err.message);
        coons_mesh_free(mesh);
        return EXIT_GEOMETRY;
    }
    mesh_warnings(&rep);
    return write_named(m, mesh, format, to_stdout ? NULL : output, input, shown);
}

int cli_write_surface(const coons_model *m, coons_mesh *mesh, const options *o,
                      const char *shown)
{
    int to_stdout = !o->output || strcmp(o->output, "-") == 0;
    return write_named(m, mesh, o->format, to_stdout ? NULL : o->output, o->input, shown);
}

/* Writes `mesh` (and frees it) to `output` (NULL: standard output), named
 * after the output file or else the model file. */
static int write_named(const coons_model *m, coons_mesh *mesh, coons_format format,
                       const char *output, const char *input, const char *shown)
{
    coons_error err = COONS_ERROR_INIT;
    int to_stdout = output == NULL;
    int from_file = input && strcmp(input, "-") != 0;
    coons_status rc;
    char name[256];
    model_name(to_stdout ? input : output, name, sizeof name);
    coons_write_options wopts = COONS_WRITE_OPTIONS_INIT;
    wopts.units = coons_model_units(m);
    wopts.name = name[0] ? name : NULL;
    wopts.protect_path = from_file ? input : NULL;
    wopts.cancel = write_cancelled;
    rc = write_mesh(mesh, to_stdout ? NULL : output, format, &wopts, &err);
    if (caught_signal) cli_die_of_caught_signal(rc, shown);
    if (rc != COONS_OK) {
        fprintf(stderr, "%s: %s\n", PROG, err.message);
        return EXIT_GEOMETRY;
    }
    return 0;
}
