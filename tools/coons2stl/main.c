/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * coons2stl: reads a libcoons model (coons-model(5)) and writes the boundary
 * mesh of its bodies (output.c), evaluates a body at given parameters
 * (--eval, eval.c), or describes the model (--info, info.c). A thin client
 * of <coons.h>; see coons2stl(1). This file dispatches the modes.
 */
#define _POSIX_C_SOURCE 200809L /* isatty, SIGXFSZ */

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

/* The sampling options every mode shares: -t or the model's tolerance,
 * --resolution, --max-triangles. */
static coons_sample_options sample_options(const options *o, const coons_model *m)
{
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.tolerance = o->tolerance > 0 ? o->tolerance : coons_model_tolerance(m);
    so.resolution = o->resolution;
    so.max_triangles = o->max_triangles;
    /* A fixed lattice is measured too (cheaply: libcoons(3)), so that a
     * deviation above the tolerance is warned about. */
    so.progress = cli_progress_on() ? cli_on_measure : NULL;
    so.threads = cli_threads(o->jobs);
    return so;
}

/* --info's record: -o with a volume format writes that mesh after the
 * report; --volume-mesh reports it only. */
static int run_info(const options *o, const coons_model *m, long body,
                    const coons_sample_options *so)
{
    cli_volume vol = cli_volume_of(o);
    cli_output out = cli_output_of(o);
    int writes = cli_is_volume_format(o->format) && (o->output || o->format_arg);
    cli_info_options io = {!o->no_solid, !o->no_repair, o->jobs, o->volume_mesh || writes, &vol,
                           writes ? &out : NULL};
    return cli_info(m, body, so, &io);
}

static int run_mode(const options *o, coons_model *m, long body)
{
    coons_sample_options so = sample_options(o, m);
    cli_output out = cli_output_of(o);
    if (o->deform) return cli_deform(m, body, o);
    if (o->frames) return cli_write_frames(m, body, o, &so);
    if (o->eval) return cli_eval(coons_model_body(m, body < 0 ? 0 : (size_t)body), o->jacobian);
    if (o->info) return run_info(o, m, body, &so);
    if (o->niso) {
        cli_iso iso = {o->iso_dir, o->iso_value, o->niso_surfaces, o->with_boundary};
        return cli_write_iso(m, body, &iso, &so, &out);
    }
    if (o->format == COONS_FORMAT_SCAD && !o->time_arg && coons_model_morph_count(m)) {
        if (o->scale_to)
            return cli_usage_error("--scale-to cannot scale the OpenSCAD animation of a morph: "
                                   "give --time T, or --frames N");
        return cli_write_scad_animation(m, body, o, &so);
    }
    if (coons_format_kind(o->format) == COONS_MESH_KIND_SOLID) return cli_write_solid(m, body, &out);
    if (cli_is_volume_format(o->format)) {
        if (o->output && strcmp(o->output, "-") != 0 && strcmp(o->input, "-") != 0 &&
            cli_is_model_file(o->output, o->input)) {
            fprintf(stderr, "%s: the output '%s' is the model file '%s'; refusing to "
                            "overwrite it\n",
                    PROG, o->output, o->input);
            return EXIT_USAGE;
        }
        cli_volume vol = cli_volume_of(o);
        return cli_write_volume(m, body, &vol, &out);
    }
    return cli_write_output(m, body, &out, &so, !o->no_repair, o->jobs);
}

/* Binary output (binary STL, 3MF) is not written onto a terminal, where it
 * would garble the screen: without -o a mesh goes to standard output, and
 * `-o -` asks for that on purpose. 1 (reported) when refused. */
static int binary_onto_terminal(const options *o)
{
    if (o->output || o->eval || o->info) return 0;
    if (o->format != COONS_FORMAT_STL_BINARY && o->format != COONS_FORMAT_3MF) return 0;
    if (!isatty(STDOUT_FILENO)) return 0;
    fprintf(stderr,
            "%s: refusing to write %s onto a terminal; nothing was written. Give -o FILE, or "
            "-o - to write to standard output on purpose\n",
            PROG, o->format == COONS_FORMAT_3MF ? "a 3MF package" : "binary STL");
    return 1;
}

int main(int argc, char **argv)
{
    /* A file size limit (ulimit -f) must end in a write error (EFBIG),
     * after which the writer removes its temporary file, not in SIGXFSZ
     * killing the process with the temporary file left behind. */
    signal(SIGXFSZ, SIG_IGN);
    options o;
    memset(&o, 0, sizeof o);
    o.load.version = COONS_MODEL_LOAD_OPTIONS_VERSION;
    int rc = cli_parse_args(argc, argv, &o);
    if (rc >= 0) return rc;
    if (binary_onto_terminal(&o)) return EXIT_USAGE;
    coons_model *m = NULL;
    if ((rc = cli_load_model(&o, &m)) >= 0) return rc;
    long body = -1;
    if (o.body && (body = cli_select_body(m, o.body)) < 0) {
        coons_model_free(m);
        return EXIT_USAGE;
    }
    if (o.time_arg) {
        coons_error err = COONS_ERROR_INIT;
        if (coons_model_set_time(m, o.time, &err) != COONS_OK) {
            fprintf(stderr, "%s: %s\n", PROG, err.message);
            coons_model_free(m);
            return EXIT_USAGE;
        }
        if (!coons_model_morph_count(m))
            cli_message(1, "the model has no morph bodies: --time changes nothing");
    }
    /* -q silences progress too, even with --progress (issue 24) */
    cli_progress_start(!o.quiet && (o.force_progress || isatty(STDERR_FILENO)), o.quiet, m);
    if ((rc = cli_resolve_units(&o, m)) >= 0) {
        coons_model_free(m);
        return rc;
    }
    rc = run_mode(&o, m, body);
    coons_model_free(m);
    if ((o.eval || o.info) && (fflush(stdout) != 0 || ferror(stdout))) {
        fprintf(stderr, "%s: cannot write to standard output: %s\n", PROG, strerror(errno));
        if (!rc) rc = EXIT_GEOMETRY;
    }
    return rc;
}
