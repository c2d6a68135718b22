/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * coons2stl's internal interface: the parsed command line, the exit
 * statuses, and the entry of each file: options.c (the option table and
 * --help), input.c (the model and --body), progress.c (diagnostics and the
 * progress line), solid.c (the mesh that -o writes and --info describes),
 * eval.c (--eval), info.c (--info), output.c (-o), volume.c (volume
 * meshes), iso.c (--iso), units.c (units, --scale-to), frames.c (--time,
 * --frames, the OpenSCAD animation) and deform.c (--deform). main.c
 * dispatches: the parsed command line (`options`) stays with the parser
 * and main.c, which hands each mode its own small record (cli_output,
 * cli_volume, cli_iso, cli_info_options). No variable is shared between
 * files (the progress line's state and the caught signal are each one
 * file's own).
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

/* The command line as parsed (options.c). */
typedef struct options {
    const char *input;    /* "-" = standard input */
    const char *output;   /* NULL = standard output */
    const char *format_arg; /* -f as given, or NULL */
    coons_format format;  /* resolved from -f, else from the output's extension, else STL */
    const char *body;     /* --body argument or NULL */
    double tolerance;     /* > 0 when given */
    unsigned resolution;  /* --resolution N: 0 = adaptive (the first of NU,NV,NW) */
    unsigned resolution3[3]; /* --resolution N or NU,NV,NW for volume meshes; 0s = adaptive */
    int resolution_split; /* --resolution gave three numbers */
    const char *element_arg; /* --element as given, or NULL */
    coons_element element; /* hex8 unless --element */
    int allow_inverted;   /* --allow-inverted */
    int volume_mesh;      /* --volume-mesh (with --info) */
    int with_boundary;    /* --with-boundary (with --iso) */
    const char *iso[64];  /* --iso SPEC, in order */
    size_t niso;
    int iso_dir[256];     /* the surfaces --iso asks for: direction 0 u, 1 v, 2 w */
    double iso_value[256];
    size_t niso_surfaces;
    size_t max_triangles; /* --max-triangles: 0 = the library's default */
    coons_model_load_options load; /* --max-bytes, --max-values, --max-depth, --max-points */
    int eval, jacobian, info, quiet;
    int no_repair;      /* --no-repair */
    int no_solid;       /* --no-solid (with --info) */
    int force_progress; /* --progress */
    const char *time_arg; /* --time as given, or NULL */
    double time;          /* --time T (when time_arg) */
    unsigned frames;      /* --frames N: 0 = none */
    unsigned jobs;        /* -j N: 0 = the number of cores */
    const char *deform;   /* --deform IN (STL or OFF), or NULL */
    const char *frame_arg; /* --frame x0,y0,z0,x1,y1,z1 as given, or NULL */
    double frame[6];      /* --frame's corners (when frame_arg) */
    const char *scale_to; /* --scale-to UNIT, or NULL */
    double scale;         /* its factor from the model's units (cli_resolve_units; 1: none) */
    const char *units_out; /* the units written: --scale-to's, else the model's */
} options;

/* Where and how a mesh is written: -o (NULL or "-": standard output), the
 * format, the model file (never overwritten; names the output on standard
 * output), and the units: coordinates multiplied by `scale` and labelled
 * `units` (--scale-to). */
typedef struct cli_output {
    const char *path;
    coons_format format;
    const char *input;
    double scale;
    const char *units;
    /* OpenSCAD background parts (`%`): the boundaries around iso surfaces */
    const size_t *background;
    size_t nbackground;
    unsigned threads; /* cli_threads(-j): the STL rounding check */
} cli_output;
/* output.c: the cli_output of the options (path -o). */
cli_output cli_output_of(const options *o);

/* The volume-mesh mode's record: the lattice and the policy on inverted
 * cells (--element, --resolution, -t, --allow-inverted). */
typedef struct cli_volume {
    coons_element element;
    unsigned resolution[3]; /* intervals along u, v, w; 0s: the sampled lattice */
    double tolerance;       /* > 0, or 0: the model's */
    int allow_inverted;
    unsigned threads;       /* cli_threads(-j) */
} cli_volume;
/* solid.c: the thread count of -j N (0: the online cores). */
unsigned cli_threads(unsigned jobs);
/* volume.c: the cli_volume of the options. */
cli_volume cli_volume_of(const options *o);

/* The --iso mode's record: the surfaces D = V and --with-boundary. */
typedef struct cli_iso {
    const int *dir;      /* 0 u, 1 v, 2 w, per surface */
    const double *value; /* per surface */
    size_t n;
    int with_boundary;
} cli_iso;

/* The --info mode's record. */
typedef struct cli_info_options {
    int solid;               /* report "solid" (not --no-solid) */
    int repair;              /* not --no-repair */
    unsigned jobs;           /* -j (0: the number of cores) */
    int volume_mesh;         /* report "volume_mesh" (--volume-mesh, or out) */
    const cli_volume *volume;/* its lattice */
    const cli_output *out;   /* a volume mesh to write after the report, or NULL */
} cli_info_options;

/* units.c: the length of one `unit` in millimetres (um, mm, cm, in, ft, m
 * and their spelled-out names, any case); 0 when unknown. */
double cli_unit_mm(const char *unit);
/* units.c: after the model is loaded: --scale-to's factor into o->scale
 * and o->units_out, and the warning when a mesh not in millimetres goes
 * to a format without units (once per run); -1 to go on, else the
 * status (reported). */
int cli_resolve_units(options *o, const coons_model *m);
/* units.c: whether `f` is a surface format whose readers take millimetres
 * (STL, OFF, SCAD: no units a reader honours). */
int cli_format_unitless(coons_format f);

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
void cli_on_deform(void *userdata, const char *stage, double fraction);
/* coons_sample_options.progress: the body being sampled, with the share
 * of the current measuring pass ("sampling body 1 of 3 (a)  40%"). */
void cli_on_measure(void *userdata, const char *stage, double fraction);
/* coons_write_options.written: "writing NAME: SIZE"; ctx is NAME. */
void cli_on_written(void *ctx, unsigned long long bytes);
/* Text put before every progress line ("frame 2 of 5: "); NULL: none. */
void cli_progress_prefix(const char *prefix);
/* "coons2stl: [warning: ]message" on standard error, after the standard
 * output so far and on a line of its own; warnings obey -q. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void cli_message(int warning, const char *fmt, ...);

/* solid.c: all bodies' solid (body < 0), else that body's alone. */
coons_status cli_make_solid(const coons_model *m, long body, const coons_sample_options *so,
                            int repair, unsigned jobs, coons_mesh **out, coons_csg_report *rep,
                            coons_error *err);

/* The modes; each prints its own diagnostics and returns the exit status. */
int cli_eval(const coons_body *b, int jacobian);
int cli_info(const coons_model *m, long only, const coons_sample_options *so,
             const cli_info_options *io);
/* volume.c: the volume mesh of all bodies (body < 0) or of one, with the
 * lattice options of `o`; reports nothing. */
coons_status cli_volume_mesh(const coons_model *m, long body, const cli_volume *v,
                             coons_volume_mesh **out, coons_error *err);
/* --info's "volume_mesh" object of part `part` (printed after a key). */
void cli_print_volume_quality(const coons_volume_mesh *vm, size_t part);
/* -o with a volume format: meshes, refuses inverted cells (unless
 * --allow-inverted), writes atomically; returns the exit status. */
int cli_write_volume(const coons_model *m, long body, const cli_volume *v,
                     const cli_output *out);
/* The same for a mesh already made (--info -o). */
int cli_write_volume_mesh(coons_volume_mesh *vm, const cli_volume *v, const cli_output *out);
/* Whether the output format `f` is a volume-mesh format. */
int cli_is_volume_format(coons_format f);

/* output.c: a volume mesh written to a file atomically, with SIGINT,
 * SIGTERM and SIGHUP cancelling the write; after it, whether one was
 * caught, and dying of it as expected. */
coons_status cli_write_volume_file(const coons_volume_mesh *vm, const char *path,
                                   coons_format format, const coons_write_options *wopts,
                                   coons_error *err);
int cli_caught_signal(void);
void cli_die_of_caught_signal(coons_status rc, const char *shown);
/* Whether `output` is the model file `input` (same device and inode). */
int cli_is_model_file(const char *output, const char *input);

/* iso.c: --iso, the isoparametric surfaces written to -o; the status. */
int cli_write_iso(const coons_model *m, long body, const cli_iso *iso,
                  const coons_sample_options *so, const cli_output *out);
/* output.c: writes a surface mesh made elsewhere (and frees it) as -o
 * writes the solid; `shown` names the output in messages. */
int cli_write_surface(coons_mesh *mesh, const cli_output *out, const char *shown);
/* output.c: the model's bodies as exact solids (STEP, IGES, BREP) to
 * out->path; the exit status. */
int cli_write_solid(const coons_model *m, long body, const cli_output *out);

/* output.c: -o of a boundary mesh: the solid of `body` (< 0: all) sampled
 * with `so`, repaired (`repair`) and united on `jobs` threads (0: the
 * number of cores), written to `out`; the exit status. */
int cli_write_output(const coons_model *m, long body, const cli_output *out,
                     const coons_sample_options *so, int repair, unsigned jobs);

/* options.c: a usage error with its message (status EXIT_USAGE). */
int cli_usage_error(const char *msg);
/* frames.c: --time (a number in [0,1]) and --frames (N >= 2 and an output
 * PATTERN with one integer field) checked; -1 to go on, else the status. */
int cli_check_time_options(options *o);
/* frames.c: -o with --frames: frame k written to PATTERN(k), at time
 * k/(N-1), each as a single output would be; stops at the first failure. */
int cli_write_frames(coons_model *m, long body, const options *o,
                     const coons_sample_options *so);

/* frames.c: --info's "morph" object of a morph body (printed after a
 * key): keys, times, path, and the sampled times where the smallest det J
 * changes sign (below -fold_threshold counts as negative); warns of a
 * fold. 0, or the exit status (reported). */
int cli_print_morph_info(const coons_body *b, double fold_threshold, const char *name,
                         size_t index);

/* frames.c: -o FILE.scad of a model with morphs (without --time): the
 * OpenSCAD animation; the exit status. */
int cli_write_scad_animation(const coons_model *m, long body, const options *o,
                             const coons_sample_options *so);

/* deform.c: --deform and --frame checked (and --frame parsed); -1 to go
 * on, else the status. */
int cli_check_deform_options(options *o);
/* deform.c: --deform IN: IN mapped through the body (--body, default 0),
 * written to -o like any surface, or described by --info; the status. */
int cli_deform(const coons_model *m, long body, const options *o);

/* Prints s as a JSON string, quoted and escaped (info.c). */
void cli_json_string(const char *s);

#endif
