/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * coons2stl's standard error: the progress report and the messages.
 *
 * The progress report is one line on standard error, rewritten in place
 * with '\r' and finished with a newline before anything else is printed,
 * so that warnings and errors never share its line. By default it is shown
 * only when standard error is a terminal (a log file would fill up with
 * rewrites); --progress forces it, -q turns it off. The library never
 * prints: it reports through coons_csg_options.progress (stage names and
 * the fraction done; likewise the sample, volume and deform options) and
 * coons_write_options.written (bytes written), and
 * the CLI prints. A report that only moves a percentage or a byte count is
 * drawn at most every RATE seconds (the callbacks stay cheap); a new stage,
 * its start (0) and its end (1) are always drawn. --frames puts "frame k
 * of N" before each frame's stages.
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "cli.h"

static struct {
    int on;                   /* report progress */
    int quiet;                /* -q: no warnings */
    int open;                 /* a progress line is on the screen */
    size_t width;             /* its length, to blank out what a shorter one leaves */
    char last[160];           /* its text, to print only changes */
    const coons_model *model; /* names the bodies of the stage "sample" */
    char prefix[64];          /* "frame k of N: " or "" */
    char stage[64];           /* the stage last drawn, to draw every new one */
    double drawn_at;          /* when the line was last drawn (monotonic seconds) */
    char pending[160];        /* a report skipped by the rate limit, drawn at the end */
    char body[128];           /* "sampling body i of n (name)", the body being sampled */
} ui;

/* Seconds between two redraws of the same stage. */
#define RATE 0.1

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Whether a report of `stage` at `fraction` is drawn (see above). */
static int due(const char *stage, double fraction)
{
    double t = now();
    int fresh = strcmp(stage, ui.stage) != 0;
    if (!fresh && fraction > 0 && fraction < 1 && t - ui.drawn_at < RATE) return 0;
    snprintf(ui.stage, sizeof ui.stage, "%s", stage);
    ui.drawn_at = t;
    return 1;
}

void cli_progress_prefix(const char *prefix)
{
    snprintf(ui.prefix, sizeof ui.prefix, "%s", prefix ? prefix : "");
}

void cli_progress_start(int on, int quiet, const coons_model *m)
{
    ui.on = on;
    ui.quiet = quiet;
    ui.model = m;
}

int cli_progress_on(void) { return ui.on; }

static void progress_line(const char *text);

void cli_progress_end(void)
{
    if (ui.pending[0]) { /* the last state, skipped by the rate limit */
        char text[sizeof ui.pending];
        memcpy(text, ui.pending, sizeof text);
        ui.pending[0] = '\0';
        progress_line(text);
    }
    if (!ui.open) return;
    fputc('\n', stderr);
    fflush(stderr);
    ui.open = 0;
    ui.width = 0;
    ui.last[0] = '\0';
    ui.stage[0] = '\0';
}

static void progress_line(const char *text)
{
    ui.pending[0] = '\0';
    if (!ui.on || strcmp(text, ui.last) == 0) return;
    size_t n = strlen(ui.prefix) + strlen(text);
    fprintf(stderr, "\r%s: %s%s", PROG, ui.prefix, text);
    for (size_t k = n; k < ui.width; k++) fputc(' ', stderr);
    fflush(stderr);
    ui.open = 1;
    ui.width = n;
    snprintf(ui.last, sizeof ui.last, "%s", text);
}

/* A body name fit for the progress line: control characters shown as '?',
 * at most cap - 1 bytes, cut at a UTF-8 character boundary. */
static void printable(char *out, size_t cap, const char *s)
{
    size_t n = 0;
    for (; s[n] && n + 1 < cap; n++) out[n] = (unsigned char)s[n] < 0x20 ? '?' : s[n];
    if (s[n])
        while (n > 0 && ((unsigned char)out[n] & 0xC0) == 0x80) n--;
    out[n] = '\0';
}

void cli_progress_sampling(size_t i, size_t n, const char *name)
{
    if (!ui.on) return;
    char nm[48], text[128];
    printable(nm, sizeof nm, name);
    snprintf(text, sizeof text, "sampling body %zu of %zu (%s)", i + 1, n, nm);
    snprintf(ui.body, sizeof ui.body, "%s", text);
    snprintf(ui.stage, sizeof ui.stage, "%s", "sample");
    progress_line(text);
}

/* coons_csg_options.progress and coons_volume_options.progress; userdata
 * is what the line calls the operation ("repair and union", "volume
 * mesh"). coons_model_solidify() and coons_model_solidify_body() report
 * the stage "sample" before each body with the share of bodies done
 * (i / count), then the stages of repair and union with their own
 * fraction; the volume mesher its stages "lattice", "evaluate", "cells". */
void cli_on_progress(void *userdata, const char *stage, double fraction)
{
    const char *what = userdata ? (const char *)userdata : "repair and union";
    if (strcmp(stage, "sample") == 0) {
        size_t n = ui.model ? coons_model_body_count(ui.model) : 0;
        size_t i = (size_t)(fraction * (double)n + 0.5);
        if (i < n) cli_progress_sampling(i, n, coons_model_body_name(ui.model, i));
        return;
    }
    if (!due(stage, fraction)) return;
    char text[128];
    snprintf(text, sizeof text, "%s: %s %3d%%", what, stage, (int)(100 * fraction));
    progress_line(text);
}

void cli_on_measure(void *userdata, const char *stage, double fraction)
{
    (void)userdata;
    (void)stage;
    if (!ui.on || !ui.body[0] || !due("measure", 0.5)) return;
    char text[160];
    snprintf(text, sizeof text, "%s %3d%%", ui.body, (int)(100 * fraction));
    progress_line(text);
}

/* coons_deform_options.progress: the stage "deform", its fraction the
 * share of the refinement done ("deforming: 40%"). */
void cli_on_deform(void *userdata, const char *stage, double fraction)
{
    (void)userdata;
    if (!ui.on || !due(stage, fraction)) return;
    char text[64];
    snprintf(text, sizeof text, "deforming: %3d%%", (int)(100 * fraction));
    progress_line(text);
}

void cli_on_written(void *ctx, unsigned long long bytes)
{
    if (!ui.on) return;
    int draw = due("write", 0.5);
    char nm[64], text[128];
    printable(nm, sizeof nm, ctx ? (const char *)ctx : "<stdout>");
    if (bytes < 10000000ull)
        snprintf(text, sizeof text, "writing %s: %.1f kB", nm, (double)bytes / 1e3);
    else
        snprintf(text, sizeof text, "writing %s: %.1f MB", nm, (double)bytes / 1e6);
    if (draw)
        progress_line(text);
    else
        snprintf(ui.pending, sizeof ui.pending, "%s", text);
}

void cli_message(int warning, const char *fmt, ...)
{
    if (warning && ui.quiet) return;
    cli_progress_end();
    fflush(stdout);
    fprintf(stderr, "%s: %s", PROG, warning ? "warning: " : "");
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}
