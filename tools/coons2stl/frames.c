/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * --time T and --frames N (coons2stl(1), outputs.md "Metamorphosis"): the
 * morphs of the model taken at one time, or N frames at t = k/(N-1), each
 * written exactly as a single output would be (atomically, by the usual
 * writers) to -o PATTERN with one printf-style integer field. Frames are
 * written in order and the first failure stops: frames before it stay,
 * the failed frame and later ones are not written. With a volume format
 * of the VTK family (.vtu), a ParaView collection (.pvd) indexes the
 * frames by time; it is written last, so it exists only when every frame
 * does.
 */
#define _POSIX_C_SOURCE 200809L /* getpid */

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

/* The integer field of a pattern: its offset and length ("%03d"), or
 * -1 when the pattern does not hold exactly one. */
static int find_field(const char *p, size_t *at, size_t *len, const char **why)
{
    int count = 0;
    for (size_t i = 0; p[i]; i++) {
        if (p[i] != '%') continue;
        if (p[i + 1] == '%') {
            i++;
            continue;
        }
        size_t j = i + 1;
        while (p[j] && strchr("-+ #0", p[j])) j++;
        while (p[j] >= '0' && p[j] <= '9') j++;
        if (p[j] == '.') {
            j++;
            while (p[j] >= '0' && p[j] <= '9') j++;
        }
        if (!p[j] || !strchr("diu", p[j])) {
            *why = "a field other than an integer one (%d, %i, %u with flags and width)";
            return -1;
        }
        if (j - i > 12) {
            *why = "an integer field longer than 12 characters";
            return -1;
        }
        *at = i;
        *len = j - i + 1;
        count++;
        i = j;
    }
    if (count != 1) {
        *why = count ? "more than one integer field" : "no integer field such as %d or %03d";
        return -1;
    }
    return 0;
}

/* Appends s[0..n) to out with "%%" read as "%". */
static size_t put_literal(char *out, size_t cap, size_t o, const char *s, size_t n)
{
    for (size_t i = 0; i < n && o + 1 < cap; i++) {
        out[o++] = s[i];
        if (s[i] == '%' && i + 1 < n && s[i + 1] == '%') i++;
    }
    out[o < cap ? o : cap - 1] = '\0';
    return o;
}

/* PATTERN with its field replaced by k (the field was validated). */
static void frame_name(const char *pattern, unsigned k, char *out, size_t cap)
{
    size_t at = 0, len = 0;
    const char *why = NULL;
    (void)find_field(pattern, &at, &len, &why);
    char spec[16], num[64];
    memcpy(spec, pattern + at, len);
    spec[len] = '\0';
    if (spec[len - 1] == 'u') spec[len - 1] = 'd';
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
#endif
    snprintf(num, sizeof num, spec, (int)k);
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
    size_t o = put_literal(out, cap, 0, pattern, at);
    for (size_t i = 0; num[i] && o + 1 < cap; i++) out[o++] = num[i];
    out[o] = '\0';
    put_literal(out, cap, o, pattern + at + len, strlen(pattern + at + len));
}

int cli_check_time_options(options *o)
{
    if (o->time_arg) {
        char *end = NULL;
        errno = 0;
        double t = strtod(o->time_arg, &end);
        if (end == o->time_arg || *end || !isfinite(t))
            return cli_usage_error("--time needs a number from 0 to 1");
        if (t < 0 || t > 1) {
            char msg[160];
            snprintf(msg, sizeof msg, "--time %s lies outside [0, 1]", o->time_arg);
            return cli_usage_error(msg);
        }
        o->time = t;
    }
    if (!o->frames) return -1;
    if (o->frames < 2) return cli_usage_error("--frames needs a whole number from 2 to 100000");
    if (o->time_arg) return cli_usage_error("--time and --frames cannot be combined");
    if (o->eval || o->info || o->niso)
        return cli_usage_error("--frames is for -o: not with --eval, --info or --iso");
    if (!o->output || strcmp(o->output, "-") == 0)
        return cli_usage_error("--frames needs -o PATTERN with one integer field "
                               "(frame-%03d.stl)");
    size_t at, len;
    const char *why = NULL;
    if (find_field(o->output, &at, &len, &why) < 0) {
        char msg[512];
        snprintf(msg, sizeof msg, "--frames: the output pattern '%.300s' has %s", o->output, why);
        return cli_usage_error(msg);
    }
    const char *slash = strrchr(o->output, '/');
    if (slash && (size_t)(slash - o->output) > at)
        return cli_usage_error("--frames: the integer field must be in the file name, not in "
                               "a directory of the pattern");
    return -1;
}

/* The .pvd next to the frames: the pattern without its field (and the
 * '-', '_' or '.' before it) and with the extension .pvd. */
static void pvd_name(const char *pattern, char *out, size_t cap)
{
    size_t at = 0, len = 0;
    const char *why = NULL;
    (void)find_field(pattern, &at, &len, &why);
    size_t o = put_literal(out, cap, 0, pattern, at);
    while (o > 0 && strchr("-_.", out[o - 1])) out[--o] = '\0';
    o = put_literal(out, cap, o, pattern + at + len, strlen(pattern + at + len));
    char *dot = strrchr(out, '.'), *slash = strrchr(out, '/');
    if (dot && (!slash || dot > slash + 1)) *dot = '\0';
    size_t n = strlen(out);
    if (n == 0 || out[n - 1] == '/') snprintf(out + n, cap - n, "frames");
    n = strlen(out);
    snprintf(out + n, cap - n, ".pvd");
}

/* The collection, written to a temporary file renamed into place. */
static int write_pvd(const options *o)
{
    char path[4096], tmp[4200], name[4096];
    pvd_name(o->output, path, sizeof path);
    snprintf(tmp, sizeof tmp, "%s.tmp%ld", path, (long)getpid());
    FILE *f = fopen(tmp, "w");
    if (!f) {
        cli_message(0, "%s: cannot write: %s", path, strerror(errno));
        return EXIT_GEOMETRY;
    }
    fprintf(f, "<?xml version=\"1.0\"?>\n"
               "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
               "  <Collection>\n");
    for (unsigned k = 0; k < o->frames; k++) {
        frame_name(o->output, k, name, sizeof name);
        const char *base = strrchr(name, '/');
        base = base ? base + 1 : name;
        fprintf(f, "    <DataSet timestep=\"%.17g\" group=\"\" part=\"0\" file=\"",
                (double)k / (double)(o->frames - 1));
        for (const char *c = base; *c; c++) {
            if (*c == '&') fputs("&amp;", f);
            else if (*c == '"') fputs("&quot;", f);
            else if (*c == '<') fputs("&lt;", f);
            else fputc(*c, f);
        }
        fputs("\"/>\n", f);
    }
    fprintf(f, "  </Collection>\n</VTKFile>\n");
    int bad = ferror(f);
    if (fclose(f) != 0 || bad || rename(tmp, path) != 0) {
        cli_message(0, "%s: cannot write: %s", path, strerror(errno));
        remove(tmp);
        return EXIT_GEOMETRY;
    }
    return 0;
}

int cli_write_frames(coons_model *m, long body, const options *o,
                     const coons_sample_options *so)
{
    if (!coons_model_morph_count(m))
        cli_message(1, "the model has no morph bodies: every frame is the same");
    options fo = *o;
    char name[4096];
    fo.frames = 0;
    for (unsigned k = 0; k < o->frames; k++) {
        double t = (double)k / (double)(o->frames - 1);
        coons_error err = COONS_ERROR_INIT;
        if (coons_model_set_time(m, t, &err) != COONS_OK) {
            cli_message(0, "%s", err.message);
            return EXIT_GEOMETRY;
        }
        frame_name(o->output, k, name, sizeof name);
        fo.output = name;
        char prefix[64];
        snprintf(prefix, sizeof prefix, "frame %u of %u: ", k + 1, o->frames);
        cli_progress_prefix(prefix);
        cli_output out = cli_output_of(&fo);
        cli_volume vol = cli_volume_of(o);
        int rc = cli_is_volume_format(o->format)
                     ? cli_write_volume(m, body, &vol, &out)
                     : cli_write_output(m, body, &out, so, !o->no_repair, o->jobs);
        if (rc) {
            if (k)
                cli_message(0, "frame %u (t = %.17g) failed: frames 0 to %u were written, no "
                               "later ones",
                            k, t, k - 1);
            else
                cli_message(0, "frame 0 (t = 0) failed: no frame was written");
            return rc;
        }
    }
    if (o->format == COONS_FORMAT_VTU || o->format == COONS_FORMAT_VTU_ASCII) return write_pvd(o);
    return 0;
}

/* Times --info samples for the sign of det J: FOLD_SAMPLES + 1 uniform
 * ones and the key times; det J on a (FOLD_LATTICE + 1)^3 lattice each. */
enum { FOLD_SAMPLES = 64, FOLD_LATTICE = 8 };

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int cli_print_morph_info(const coons_body *b, double fold_threshold, const char *name,
                         size_t index)
{
    size_t nk = coons_body_morph_keys(b);
    coons_morph_path path = COONS_MORPH_LINEAR;
    double t0 = 0;
    coons_error err = COONS_ERROR_INIT;
    if (coons_body_morph_info(b, &path, &t0, &err)) return -1;
    printf(",\n     \"morph\": {\"path\": \"%s\", \"t\": %.17g, \"keys\": [",
           path == COONS_MORPH_SMOOTH ? "smooth" : "linear", t0);
    size_t nt = FOLD_SAMPLES + 1 + nk;
    double *times = malloc(nt * sizeof *times), *mins = malloc(nt * sizeof *mins);
    if (!times || !mins) {
        free(times);
        free(mins);
        cli_message(0, "out of memory");
        return EXIT_GEOMETRY;
    }
    for (size_t k = 0; k < nk; k++) {
        double at = 0;
        const coons_body *key = coons_body_morph_key(b, k, &at);
        const char *type = coons_body_type_name(coons_body_kind(key));
        printf("%s{\"type\": \"%s\", \"at\": %.17g}", k ? ", " : "", type ? type : "unknown", at);
        times[FOLD_SAMPLES + 1 + k] = at;
    }
    for (size_t j = 0; j <= FOLD_SAMPLES; j++) times[j] = (double)j / FOLD_SAMPLES;
    qsort(times, nt, sizeof *times, cmp_double);
    size_t n = 0;
    for (size_t j = 0; j < nt; j++)
        if (!n || times[j] > times[n - 1]) times[n++] = times[j];
    int rc = 0;
    for (size_t j = 0; j < n && !rc; j++) {
        coons_body *c = NULL;
        double where[3];
        if (coons_body_at_time(b, times[j], &c, &err) ||
            coons_body_min_jacobian(c, FOLD_LATTICE, &mins[j], where, &err)) {
            cli_message(0, "body %zu (%s): %s", index, name, err.message);
            rc = EXIT_GEOMETRY;
        }
        coons_body_free(c);
    }
    if (!rc) {
        /* the sign of the smallest det J, with the rounding noise of a
         * collapsed axis counted as 0 (info.c, FOLD_REL) */
        printf("],\n      \"sampled_times\": %zu, \"det_sign_changes\": [", n);
        int prev = 0, first = 1;
        double worst = INFINITY, worst_t = 0;
        for (size_t j = 0; j < n; j++) {
            int sgn = mins[j] < -fold_threshold ? -1 : 1;
            if (j && sgn != prev) {
                printf("%s{\"between\": [%.17g, %.17g], \"min_det\": [%.17g, %.17g]}",
                       first ? "" : ", ", times[j - 1], times[j], mins[j - 1], mins[j]);
                first = 0;
            }
            prev = sgn;
            if (mins[j] < worst) worst = mins[j], worst_t = times[j];
        }
        printf("], \"min_det_jacobian\": %.17g, \"min_det_jacobian_time\": %.17g}", worst,
               worst_t);
        if (worst < -fold_threshold)
            cli_message(1, "body %zu (%s): the morph folds: det J = %.6g < 0 at time %g%s",
                        index, name, worst, worst_t,
                        first ? "" : " (its keys may differ in handedness)");
    }
    free(times);
    free(mins);
    return rc;
}

int cli_write_scad_animation(const coons_model *m, long body, const options *o,
                             const coons_sample_options *so)
{
    int to_stdout = !o->output || strcmp(o->output, "-") == 0;
    const char *shown = to_stdout ? "<stdout>" : o->output;
    int from_file = o->input && strcmp(o->input, "-") != 0;
    if (!to_stdout && from_file && cli_is_model_file(o->output, o->input)) {
        fprintf(stderr, "%s: the output '%s' is the model file '%s'; refusing to overwrite it\n",
                PROG, o->output, o->input);
        return EXIT_USAGE;
    }
    /* the model's module is named after the output file, else the model file */
    char name[256] = "";
    const char *src = to_stdout ? (from_file ? o->input : NULL) : o->output;
    if (src) {
        const char *base = strrchr(src, '/');
        snprintf(name, sizeof name, "%s", base ? base + 1 : src);
        char *dot = strrchr(name, '.');
        if (dot && dot != name) *dot = '\0';
    }
    coons_write_options w = COONS_WRITE_OPTIONS_INIT;
    w.units = coons_model_units(m);
    w.name = name[0] ? name : NULL;
    w.protect_path = from_file ? o->input : NULL;
    coons_error err = COONS_ERROR_INIT;
    coons_status rc = to_stdout ? coons_model_write_scad_animation_stream(m, body, so, stdout, &w,
                                                                          &err)
                                : coons_model_write_scad_animation(m, body, so, o->output, &w,
                                                                   &err);
    cli_progress_end();
    if (rc != COONS_OK) {
        cli_message(0, "%s: %s; nothing was written", shown, err.message);
        return EXIT_GEOMETRY;
    }
    return 0;
}
