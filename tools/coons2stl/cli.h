/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * coons2stl's internal interface: the parsed command line, the exit
 * statuses, and the entry of each file: options.c (the option table and
 * --help), input.c (the model and --body), progress.c (diagnostics and the
 * progress line), solid.c (the mesh that -o writes and --info describes),
 * eval.c (--eval), info.c (--info) and output.c (-o). main.c dispatches.
 *
 * Exit status: 0 success, 1 bad input (model or --eval lines), 2 bad usage,
 * 3 a geometric operation or writing the output failed.
 */
#ifndef COONS2STL_CLI_H
#define COONS2STL_CLI_H

#include <stddef.h>
#include <stdio.h>

#include <coons.h>

enum { EXIT_INPUT = 1, EXIT_USAGE = 2, EXIT_GEOMETRY = 3 };

#define PROG "coons2stl"

typedef struct options {
    const char *input;    /* "-" = standard input */
    const char *output;   /* NULL = standard output */
    const char *format_arg; /* -f as given, or NULL */
    coons_format format;  /* resolved from -f, else from the output's extension, else STL */
    const char *body;     /* --body argument or NULL */
    double tolerance;     /* > 0 when given */
    unsigned resolution;  /* --resolution: 0 = adaptive */
    size_t max_triangles; /* --max-triangles: 0 = the library's default */
    coons_model_load_options load; /* --max-bytes, --max-values, --max-depth, --max-points */
    int eval, jacobian, info, quiet;
    int no_repair;      /* --no-repair */
    int no_solid;       /* --no-solid (with --info) */
    int force_progress; /* --progress */
} options;

/* options.c: parses the command line into `o` (zeroed, load.version set);
 * returns -1 to go on, else an exit status (--help, --version, a usage
 * error, reported). */
int cli_parse_args(int argc, char **argv, options *o);

/* input.c: loads the model (-1 to go on, else the exit status, reported);
 * --body: all digits = index, else a name; the index or -1 (reported). */
int cli_load_model(const options *o, coons_model **m);
long cli_select_body(const coons_model *m, const char *arg);

/* progress.c: the progress line and the messages on standard error. */
void cli_progress_start(int on, int quiet, const coons_model *m);
int cli_progress_on(void);
void cli_progress_end(void);
void cli_progress_sampling(size_t i, size_t n, const char *name);
void cli_on_progress(void *userdata, const char *stage, double fraction);
/* "coons2stl: [warning: ]message" on standard error, after the standard
 * output so far and on a line of its own; warnings obey -q. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void cli_message(int warning, const char *fmt, ...);

/* solid.c: all bodies' solid (body < 0), else that body's alone. */
coons_status cli_make_solid(const coons_model *m, long body, const coons_sample_options *so,
                            int repair, coons_mesh **out, coons_csg_report *rep,
                            coons_error *err);

/* The modes; each prints its own diagnostics and returns the exit status. */
int cli_eval(const coons_body *b, int jacobian);
int cli_info(const coons_model *m, long only, const coons_sample_options *so,
             const options *o);
int cli_write_output(const coons_model *m, long body, coons_format format, const char *output,
                     const coons_sample_options *so, int repair, const char *input);

#endif
