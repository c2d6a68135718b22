/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * -o: the mesh written to a file or standard output. A file is written to
 * a temporary file in the same directory and renamed into place only after
 * everything succeeded (coons_mesh_write()); the model file itself is
 * never overwritten; signals during the write cancel it cleanly. STL
 * stores float32: with CGAL, a mesh that does not cross itself in double
 * precision but would once rounded to float32 is refused (exit 3, nothing
 * written); OFF and SCAD keep double precision.
 */
#define _POSIX_C_SOURCE 200809L /* sigaction */

#include <signal.h>
#include <stdint.h>
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

static void mesh_warnings(const coons_csg_report *rep, const coons_sample_options *so)
{
    if (rep->triangles_out > 0 && !rep->closed)
        cli_message(1, "the mesh is not closed");
    else if (rep->nonmanifold_edges)
        cli_message(1,
                    "the mesh is closed but not a 2-manifold: %zu edges bound more than two "
                    "triangles (solids touching along a curve)",
                    rep->nonmanifold_edges);
    if (so->resolution && rep->deviation > rep->tolerance)
        cli_message(1,
                    "the fixed resolution %u leaves a deviation of %.3g, more than the "
                    "tolerance %.3g (raise --resolution, or leave it out to sample to the "
                    "tolerance)",
                    so->resolution, rep->deviation, rep->tolerance);
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

static int write_named(coons_mesh *mesh, const cli_output *out, const char *shown);

cli_output cli_output_of(const options *o)
{
    cli_output out = {o->output, o->format, o->input, o->scale, o->units_out, NULL, 0,
                      cli_threads(o->jobs)};
    return out;
}

/*
 * Whether the STL of `mesh` must be refused (reported): its triangles do
 * not cross in double precision, but rounded to float32 as STL stores them
 * some pairs would. One exact count (CGAL's box intersection, exact
 * predicates) on the float32 coordinates; a second, on the double ones,
 * only when that finds a crossing: a mesh that already crosses (written
 * with --no-repair, isoparametric surfaces) is written as it is. Without
 * CGAL there is no exact test and no check. Coordinates outside float32's
 * range are left to the writer, which refuses them with its own message.
 */
static int stl_rounding_refused(const coons_mesh *mesh, coons_format format, unsigned threads,
                                const char *shown)
{
    if ((format != COONS_FORMAT_STL_BINARY && format != COONS_FORMAT_STL_ASCII) ||
        !coons_csg_is_available())
        return 0;
    coons_error err = COONS_ERROR_INIT;
    size_t pairs32 = 0, pairs = 0;
    coons_status rc = coons_mesh_count_self_intersections_threads(mesh, 1, threads, &pairs32, &err);
    if (rc == COONS_OK && pairs32)
        rc = coons_mesh_count_self_intersections_threads(mesh, 0, threads, &pairs, &err);
    if (rc == COONS_E_LIMIT) return 0;
    if (rc != COONS_OK) {
        cli_message(0, "%s: checking the STL's float32 coordinates for crossings failed: %s; "
                       "nothing was written",
                    shown, err.message);
        return 1;
    }
    if (pairs32 && !pairs) {
        cli_message(0,
                    "%s: rounding the coordinates to float32, as STL stores them, would make %zu "
                    "pair%s of triangles cross (in double precision none do); nothing was "
                    "written. Write OFF or SCAD (-o FILE.off, -o FILE.scad: double precision), "
                    "or try a coarser tolerance (-t)",
                    shown, pairs32, pairs32 == 1 ? "" : "s");
        return 1;
    }
    return 0;
}

/*
 * A failed repair or union in words: what failed (the repair of a body that
 * crosses itself, or the union), on which bodies, and what to try. CGAL's
 * own reason (an assertion's expression or explanation: "CGAL could not
 * complete the operation on bodies 'a', 'b': REASON") is left to --info
 * (its solid.error keeps the library's whole message); a reason the
 * library wrote itself ("bodies 'a': a surface patch could not be
 * classified ...") is shown, it is meant for the user.
 */
static void csg_failure(const coons_model *m, long body, int repair, const char *shown,
                        const char *msg)
{
    static const char cgal[] = "CGAL could not complete the operation on bodies ";
    static const char ours[] = "bodies ";
    int unite = body < 0 && coons_model_operation(m) == COONS_OP_UNION;
    const char *names = NULL;
    int from_cgal = 0;
    if (strncmp(msg, cgal, sizeof cgal - 1) == 0) {
        names = msg + sizeof cgal - 1;
        from_cgal = 1;
    } else if (strncmp(msg, ours, sizeof ours - 1) == 0) {
        names = msg + sizeof ours - 1;
    }
    /* the names, 'a', 'b' (, ...), end at the first "': " or ", ...: " */
    const char *end = names ? strstr(names, "': ") : NULL;
    const char *dots = names ? strstr(names, ", ...: ") : NULL;
    if (dots && (!end || dots < end))
        end = dots + 5;
    else if (end)
        end += 1;
    int len = end ? (int)(end - names) : 0;
    int several = end && memchr(names, ',', (size_t)len) != NULL;
    /* several bodies at once: their union (or repair) failed; one: its repair */
    const char *what = several || (!end && unite) ? "repair or union" : "repair";
    const char *hint = several ? "Try another tolerance (-t), or write the bodies one at a time "
                                 "(--body NAME)"
                       : repair ? "Try another tolerance (-t), or --no-repair to write the "
                                  "shell as sampled (crossing itself)"
                                : "Try another tolerance (-t)";
    if (!end)
        cli_message(0, "%s: %s failed: %s; nothing was written. %s", shown, what, msg, hint);
    else if (from_cgal)
        cli_message(0, "%s: the %s of bod%s %.*s failed: CGAL could not complete it; nothing "
                       "was written. %s; --info shows CGAL's reason",
                    shown, what, several ? "ies" : "y", len, names, hint);
    else
        cli_message(0, "%s: the %s of bod%s %.*s failed: %s; nothing was written. %s", shown,
                    what, several ? "ies" : "y", len, names, end + 2, hint);
}

/*
 * Writes the boundary mesh of the model (all bodies, or only body `body`
 * when >= 0) to `output` (NULL or "-": standard output) in `format`,
 * sampled with `so` (its tolerance is set: -t or the model's;
 * --resolution, --max-triangles).
 */
int cli_write_output(const coons_model *m, long body, const cli_output *out,
                     const coons_sample_options *so, int repair, unsigned jobs)
{
    coons_error err = COONS_ERROR_INIT;
    int to_stdout = !out->path || strcmp(out->path, "-") == 0;
    const char *shown = to_stdout ? "<stdout>" : out->path;
    int from_file = out->input && strcmp(out->input, "-") != 0;
    if (!to_stdout && from_file && cli_is_model_file(out->path, out->input)) {
        fprintf(stderr, "%s: the output '%s' is the model file '%s'; refusing to overwrite it\n",
                PROG, out->path, out->input);
        return EXIT_USAGE;
    }

    coons_mesh *mesh = NULL;
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    coons_status rc = cli_make_solid(m, body, so, repair, jobs, &mesh, &rep, &err);
    /* The progress line stays: the writing stage replaces it (a message
     * ends it first). */
    if (rc == COONS_E_CSG) {
        csg_failure(m, body, repair, shown, err.message);
        coons_mesh_free(mesh);
        return EXIT_GEOMETRY;
    }
    if (rc != COONS_OK) {
        cli_message(0, "%s: %s; nothing was written", shown, err.message);
        coons_mesh_free(mesh);
        return EXIT_GEOMETRY;
    }
    mesh_warnings(&rep, so);
    return write_named(mesh, out, shown);
}

int cli_write_surface(coons_mesh *mesh, const cli_output *out, const char *shown)
{
    return write_named(mesh, out, shown);
}

/* Writes `mesh` (and frees it) to out->path (NULL or "-": standard
 * output), scaled to out's units, named after the output file or else the
 * model file. */
static int write_named(coons_mesh *mesh, const cli_output *out, const char *shown)
{
    coons_error err = COONS_ERROR_INIT;
    int to_stdout = !out->path || strcmp(out->path, "-") == 0;
    int from_file = out->input && strcmp(out->input, "-") != 0;
    coons_status rc;
    char name[256];
    model_name(to_stdout ? out->input : out->path, name, sizeof name);
    coons_write_options wopts = COONS_WRITE_OPTIONS_INIT;
    wopts.units = out->units;
    wopts.name = name[0] ? name : NULL;
    wopts.protect_path = from_file ? out->input : NULL;
    wopts.cancel = write_cancelled;
    wopts.background = out->background;
    wopts.nbackground = out->nbackground;
    wopts.written = cli_progress_on() ? cli_on_written : NULL;
    wopts.written_ctx = (void *)(uintptr_t)shown;
    if (out->scale != 1.0 && coons_mesh_scale(mesh, out->scale, &err) != COONS_OK) {
        cli_message(0, "%s: %s; nothing was written", shown, err.message);
        coons_mesh_free(mesh);
        return EXIT_GEOMETRY;
    }
    if (stl_rounding_refused(mesh, out->format, out->threads, shown)) {
        coons_mesh_free(mesh);
        return EXIT_GEOMETRY;
    }
    rc = write_mesh(mesh, to_stdout ? NULL : out->path, out->format, &wopts, &err);
    cli_progress_end();
    if (caught_signal) cli_die_of_caught_signal(rc, shown);
    if (rc != COONS_OK) {
        fprintf(stderr, "%s: %s\n", PROG, err.message);
        return EXIT_GEOMETRY;
    }
    return 0;
}

/*
 * Writes the model's bodies as exact solids (STEP, IGES, BREP:
 * coons_model_write_solid()) to out->path, in the model's units. Solids go
 * to a file only, all bodies at once, unscaled.
 */
int cli_write_solid(const coons_model *m, long body, const cli_output *out)
{
    coons_error err = COONS_ERROR_INIT;
    if (!out->path || strcmp(out->path, "-") == 0)
        return cli_usage_error("STEP, IGES and BREP solids are written to a file: give -o FILE");
    if (body >= 0)
        return cli_usage_error("--body cannot select one body of a STEP, IGES or BREP file: "
                               "every body is written (the model's \"operation\" decides their "
                               "union)");
    if (out->scale != 1.0)
        return cli_usage_error("--scale-to cannot rescale exact solids: STEP, IGES and BREP "
                               "files carry the model's units");
    int from_file = out->input && strcmp(out->input, "-") != 0;
    if (from_file && cli_is_model_file(out->path, out->input)) {
        fprintf(stderr, "%s: the output '%s' is the model file '%s'; refusing to overwrite it\n",
                PROG, out->path, out->input);
        return EXIT_USAGE;
    }
    char name[256];
    model_name(out->path, name, sizeof name);
    coons_write_options wopts = COONS_WRITE_OPTIONS_INIT;
    wopts.units = out->units;
    wopts.name = name[0] ? name : NULL;
    wopts.protect_path = from_file ? out->input : NULL;
    wopts.cancel = write_cancelled;
    struct sigaction old[NSIG_HANDLED];
    catch_signals(old);
    coons_status rc = coons_model_write_solid(m, out->path, out->format, &wopts, &err);
    restore_signals(old);
    cli_progress_end();
    if (caught_signal) cli_die_of_caught_signal(rc, out->path);
    if (rc != COONS_OK) {
        cli_message(0, "%s: %s; nothing was written", out->path, err.message);
        return EXIT_GEOMETRY;
    }
    return 0;
}
