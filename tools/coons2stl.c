/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * coons2stl: reads a libcoons model (coons-model(5)) and writes the boundary
 * mesh of its bodies, evaluates a body at given parameters (--eval), or
 * describes the model (--info). A thin client of <coons.h>; see coons2stl(1).
 *
 * Exit status: 0 success, 1 bad input (model or --eval lines), 2 bad usage,
 * 3 a geometric operation or writing the output failed.
 */
#define _POSIX_C_SOURCE 200809L /* getline */

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <coons.h>

#include "coons_test_hooks.h" /* coons__csg_inject_failure (coons_static) */

enum { EXIT_INPUT = 1, EXIT_USAGE = 2, EXIT_GEOMETRY = 3 };

static const char *const PROG = "coons2stl";

typedef struct options {
    const char *input;  /* "-" = standard input */
    const char *output; /* NULL = standard output */
    const char *format; /* resolved: stl, stl-ascii, off, scad */
    const char *body;   /* --body argument or NULL */
    double tolerance;   /* > 0 when given */
    unsigned resolution;  /* --resolution: 0 = adaptive */
    size_t max_triangles; /* --max-triangles: 0 = the library's default */
    coons_model_load_options load; /* --max-bytes, --max-values, --max-depth, --max-points */
    int eval, jacobian, info, quiet;
    int no_repair;      /* --no-repair */
    int no_solid;       /* --no-solid (with --info) */
    int force_progress; /* --progress */
} options;

/* The loader caps max_depth here (coons-model(5)). */
#define MAX_DEPTH_CEILING 256u

static void usage(FILE *f)
{
    fprintf(f,
            "Usage: %s [OPTIONS] MODEL.json\n"
            "Reads a libcoons model (MODEL.json, or - for standard input) and writes the\n"
            "boundary mesh of its bodies.\n"
            "\n"
            "  -o, --output FILE      write the mesh to FILE (default: standard output)\n"
            "  -f, --format FMT       stl (binary), stl-ascii, off or scad; by default taken\n"
            "                         from the extension of FILE (.stl, .off, .scad), else stl\n"
            "  -t, --tolerance D      largest distance between mesh and surface (> 0),\n"
            "                         instead of the model's \"tolerance\"\n"
            "      --resolution N     sample each body on a fixed lattice of N intervals along\n"
            "                         u, v and w instead of adapting it to the tolerance\n"
            "      --max-triangles N  refuse to make more than N triangles (default %zu)\n"
            "      --max-bytes N      refuse a model file of more than N bytes (default %zu)\n"
            "      --max-values N     ... of more than N JSON values, keys included (default %zu)\n"
            "      --max-depth N      ... with arrays and objects nested deeper than N\n"
            "                         (default %u, at most %u)\n"
            "      --max-points N     ... with more than N points in one curve, surface or\n"
            "                         volume net (default %zu)\n"
            "      --body NAME|INDEX  use that body (a 0-based index if all digits, else a\n"
            "                         name); default: all bodies, or body 0 for --eval\n"
            "      --eval             read lines \"u v w\" from standard input and print\n"
            "                         \"x y z\" of the body (17 significant digits)\n"
            "      --jacobian         with --eval, also print the Jacobian (row-major,\n"
            "                         columns d/du d/dv d/dw) and its determinant\n"
            "      --info             print a JSON description of the model and its bodies,\n"
            "                         with what repair and union make of them (\"solid\")\n"
            "      --no-solid         with --info, skip the solid and the self-intersection\n"
            "                         checks (fast on big models)\n"
            "      --no-repair        write bodies that meet no other body as sampled, even\n"
            "                         if their boundary crosses itself\n"
            "      --progress         report progress on standard error even when it is not\n"
            "                         a terminal\n"
            "  -q, --quiet            no warnings and no progress report\n"
            "  -h, --help             show this help and exit\n"
            "      --version          show the version and exit\n"
            "\n"
            "Exit status: 0 success, 1 bad input, 2 bad usage, 3 a geometric operation\n"
            "or writing the output failed.\n",
            PROG, COONS_MESH_MAX_TRIANGLES, COONS_MODEL_MAX_BYTES, COONS_MODEL_MAX_VALUES,
            COONS_MODEL_MAX_DEPTH, MAX_DEPTH_CEILING, COONS_MODEL_MAX_POINTS);
}

static int usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "%s: ", PROG);
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\nTry '%s --help' for more information.\n", PROG);
    return EXIT_USAGE;
}

static const char *format_from_name(const char *f)
{
    static const char *const known[] = {"stl", "stl-ascii", "off", "scad"};
    for (size_t i = 0; i < sizeof known / sizeof *known; i++)
        if (strcmp(f, known[i]) == 0) return known[i];
    return NULL;
}

static const char *format_from_extension(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash + 1 : path, '.');
    if (!dot) return NULL;
    char ext[8];
    size_t n = strlen(dot + 1);
    if (n == 0 || n >= sizeof ext) return NULL;
    for (size_t i = 0; i <= n; i++) {
        char c = dot[1 + i];
        ext[i] = (c >= 'A' && c <= 'Z') ? (char)(c - 'A' + 'a') : c;
    }
    if (strcmp(ext, "stl") == 0) return "stl";
    if (strcmp(ext, "off") == 0) return "off";
    if (strcmp(ext, "scad") == 0) return "scad";
    return NULL;
}

/* Parses the command line; returns -1 to go on, else an exit status. */
static int parse_args(int argc, char **argv, options *o)
{
    int only_files = 0;
    const char *format = NULL, *tol = NULL, *res = NULL, *maxt = NULL;
    const char *lim[4] = {NULL, NULL, NULL, NULL};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (only_files || a[0] != '-' || strcmp(a, "-") == 0) {
            if (o->input) return usage_error("more than one model file given ('%s')", a);
            o->input = a;
            continue;
        }
        if (strcmp(a, "--") == 0) {
            only_files = 1;
            continue;
        }
        const char *name, *value = NULL;
        char shortname[3] = "-?";
        int is_long = a[1] == '-';
        if (is_long) {
            name = a + 2;
        } else {
            shortname[1] = a[1];
            static const char *const map[][2] = {
                {"o", "output"}, {"f", "format"}, {"t", "tolerance"}, {"q", "quiet"}, {"h", "help"}};
            name = NULL;
            for (size_t k = 0; k < sizeof map / sizeof *map; k++)
                if (a[1] == map[k][0][0]) name = map[k][1];
            if (!name) return usage_error("unknown option '%s'", a);
            if (a[2]) {
                if (strcmp(name, "quiet") == 0 || strcmp(name, "help") == 0)
                    return usage_error("unknown option '%s' (give short options separately)", a);
                value = a + 2; /* -ofile */
            }
        }
        char lname[32];
        const char *eq = is_long ? strchr(name, '=') : NULL;
        size_t nl = eq ? (size_t)(eq - name) : strlen(name);
        if (nl >= sizeof lname) return usage_error("unknown option '%s'", a);
        memcpy(lname, name, nl);
        lname[nl] = '\0';
        if (eq) value = eq + 1;
        static const char *const with_value[] = {
            "output",        "format",    "tolerance",  "body",      "resolution",
            "max-triangles", "max-bytes", "max-values", "max-depth", "max-points"};
        static const char *const flags[] = {"eval",      "jacobian", "info",     "quiet",
                                            "help",      "version",  "no-repair", "no-solid",
                                            "progress"};
        int takes = -1;
        for (size_t k = 0; k < sizeof with_value / sizeof *with_value; k++)
            if (strcmp(lname, with_value[k]) == 0) takes = 1;
        for (size_t k = 0; k < sizeof flags / sizeof *flags; k++)
            if (strcmp(lname, flags[k]) == 0) takes = 0;
        if (takes < 0) return usage_error("unknown option '%s'", a);
        if (takes == 0 && value) return usage_error("option '%s' takes no value", a);
        if (takes == 1 && !value) {
            if (i + 1 >= argc)
                return usage_error("option '%s' needs a value", is_long ? a : shortname);
            value = argv[++i];
        }
        if (strcmp(lname, "output") == 0) o->output = value;
        else if (strcmp(lname, "format") == 0) format = value;
        else if (strcmp(lname, "tolerance") == 0) tol = value;
        else if (strcmp(lname, "body") == 0) o->body = value;
        else if (strcmp(lname, "resolution") == 0) res = value;
        else if (strcmp(lname, "max-triangles") == 0) maxt = value;
        else if (strcmp(lname, "max-bytes") == 0) lim[0] = value;
        else if (strcmp(lname, "max-values") == 0) lim[1] = value;
        else if (strcmp(lname, "max-depth") == 0) lim[2] = value;
        else if (strcmp(lname, "max-points") == 0) lim[3] = value;
        else if (strcmp(lname, "eval") == 0) o->eval = 1;
        else if (strcmp(lname, "jacobian") == 0) o->jacobian = o->eval = 1;
        else if (strcmp(lname, "info") == 0) o->info = 1;
        else if (strcmp(lname, "quiet") == 0) o->quiet = 1;
        else if (strcmp(lname, "no-repair") == 0) o->no_repair = 1;
        else if (strcmp(lname, "no-solid") == 0) o->no_solid = 1;
        else if (strcmp(lname, "progress") == 0) o->force_progress = 1;
        else if (strcmp(lname, "help") == 0) {
            usage(stdout);
            return fflush(stdout) == 0 ? 0 : EXIT_GEOMETRY;
        } else if (strcmp(lname, "version") == 0) {
            printf("%s (libcoons) %s\nmodel format version %d\n", PROG, coons_version_string(),
                   COONS_MODEL_FORMAT_VERSION);
            return fflush(stdout) == 0 ? 0 : EXIT_GEOMETRY;
        }
    }
    if (!o->input) return usage_error("%s", "no model file given");
    if (tol) {
        char *end = NULL;
        errno = 0;
        o->tolerance = strtod(tol, &end);
        if (end == tol || *end || !isfinite(o->tolerance) || !(o->tolerance > 0))
            return usage_error("--tolerance needs a number > 0, not '%s'", tol);
    }
    if (res) {
        char *end = NULL;
        errno = 0;
        unsigned long long v = strtoull(res, &end, 10);
        if (res[0] < '0' || res[0] > '9' || *end || errno || v < 1 || v > 1u << 20)
            return usage_error("--resolution needs a whole number from 1 to 1048576, not '%s'",
                               res);
        o->resolution = (unsigned)v;
    }
    if (maxt) {
        char *end = NULL;
        errno = 0;
        unsigned long long v = strtoull(maxt, &end, 10);
        if (maxt[0] < '0' || maxt[0] > '9' || *end || errno || v < 1 || v > SIZE_MAX)
            return usage_error("--max-triangles needs a whole number > 0, not '%s'", maxt);
        o->max_triangles = (size_t)v;
    }
    /* Loader limits: whole numbers > 0 (the depth at most the ceiling). */
    static const char *const lim_names[4] = {"--max-bytes", "--max-values", "--max-depth",
                                             "--max-points"};
    for (int k = 0; k < 4; k++) {
        if (!lim[k]) continue;
        char *end = NULL;
        errno = 0;
        unsigned long long v = strtoull(lim[k], &end, 10);
        unsigned long long top = k == 2 ? MAX_DEPTH_CEILING : SIZE_MAX;
        if (lim[k][0] < '0' || lim[k][0] > '9' || *end || errno || v < 1 || v > top) {
            fprintf(stderr, "%s: %s needs a whole number from 1 to %llu, not '%s'\n", PROG,
                    lim_names[k], top, lim[k]);
            fprintf(stderr, "Try '%s --help' for more information.\n", PROG);
            return EXIT_USAGE;
        }
        if (k == 0) o->load.max_bytes = (size_t)v;
        if (k == 1) o->load.max_values = (size_t)v;
        if (k == 2) o->load.max_depth = (unsigned)v;
        if (k == 3) o->load.max_points = (size_t)v;
    }
    if (o->eval && (res || maxt))
        return usage_error("%s", "--resolution and --max-triangles are for meshes and --info");
    if (o->eval && o->info) return usage_error("%s", "--eval and --info cannot be combined");
    if (o->eval && (o->no_repair || o->force_progress))
        return usage_error("%s", "--no-repair and --progress are for meshes and --info");
    if (o->no_solid && !o->info) return usage_error("%s", "--no-solid is for --info");
    if ((o->eval || o->info) && (o->output || format))
        return usage_error("%s", "-o and -f are for meshes: --eval and --info print to "
                                 "standard output");
    if (o->eval && strcmp(o->input, "-") == 0)
        return usage_error("%s", "--eval reads parameters from standard input, so the model "
                                 "must come from a file");
    if (format) {
        if (!(o->format = format_from_name(format)))
            return usage_error("unknown format '%s': expected stl, stl-ascii, off or scad",
                               format);
    } else if (o->output && strcmp(o->output, "-") != 0) {
        if (!(o->format = format_from_extension(o->output)))
            return usage_error("cannot tell the output format from the name '%s': use -f stl, "
                               "stl-ascii, off or scad",
                               o->output);
    } else
        o->format = "stl";
    return -1;
}

/* ---- messages and progress ----------------------------------------------- */

/* The progress report is one line on standard error, rewritten in place
 * with '\r' and finished with a newline before anything else is printed,
 * so that warnings and errors never share its line. By default it is shown
 * only when standard error is a terminal (a log file would fill up with
 * rewrites); --progress forces it, -q turns it off. The library never
 * prints: it reports through coons_csg_options.progress (stage names and
 * the fraction done), and the CLI prints. */
static struct {
    int on;                   /* report progress */
    int quiet;                /* -q: no warnings */
    int open;                 /* a progress line is on the screen */
    size_t width;             /* its length, to blank out what a shorter one leaves */
    char last[160];           /* its text, to print only changes */
    const coons_model *model; /* names the bodies of the stage "sample" */
} ui;

static void progress_end(void)
{
    if (!ui.open) return;
    fputc('\n', stderr);
    fflush(stderr);
    ui.open = 0;
    ui.width = 0;
    ui.last[0] = '\0';
}

static void progress_line(const char *text)
{
    if (!ui.on || strcmp(text, ui.last) == 0) return;
    size_t n = strlen(text);
    fprintf(stderr, "\r%s: %s", PROG, text);
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

static void progress_sampling(size_t i, size_t n, const char *name)
{
    if (!ui.on) return;
    char nm[48], text[128];
    printable(nm, sizeof nm, name);
    snprintf(text, sizeof text, "sampling body %zu of %zu (%s)", i + 1, n, nm);
    progress_line(text);
}

/* coons_csg_options.progress. coons_model_solidify() reports the stage
 * "sample" before each body with the share of bodies done, then the
 * stages of repair and union with their own fraction. */
static void on_progress(void *userdata, const char *stage, double fraction)
{
    (void)userdata;
    if (strcmp(stage, "sample") == 0) {
        size_t n = ui.model ? coons_model_body_count(ui.model) : 0;
        size_t i = (size_t)(fraction * (double)n + 0.5);
        if (i < n) progress_sampling(i, n, coons_model_body_name(ui.model, i));
        return;
    }
    char text[128];
    snprintf(text, sizeof text, "repair and union: %s %3d%%", stage, (int)(100 * fraction));
    progress_line(text);
}

/* "coons2stl: [warning: ]message" on standard error, after the standard
 * output so far and on a line of its own; warnings obey -q. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void message(int warning, const char *fmt, ...)
{
    if (warning && ui.quiet) return;
    progress_end();
    fflush(stdout);
    fprintf(stderr, "%s: %s", PROG, warning ? "warning: " : "");
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

/* ---- input --------------------------------------------------------------- */

static int load_model(const options *o, coons_model **m)
{
    coons_error err = COONS_ERROR_INIT;
    coons_status rc;
    if (strcmp(o->input, "-") == 0) {
        /* Read at most one byte more than the loader accepts, so that it
         * reports the limit itself. */
        size_t max_bytes = o->load.max_bytes ? o->load.max_bytes : COONS_MODEL_MAX_BYTES;
        size_t cap = 1 << 16, len = 0, max = max_bytes < SIZE_MAX ? max_bytes + 1 : max_bytes;
        char *buf = malloc(cap);
        while (buf) {
            if (len == cap) {
                if (cap >= max) break;
                size_t nc = cap * 2 > max ? max : cap * 2;
                char *nb = realloc(buf, nc);
                if (!nb) {
                    free(buf);
                    buf = NULL;
                    break;
                }
                buf = nb;
                cap = nc;
            }
            size_t got = fread(buf + len, 1, cap - len, stdin);
            len += got;
            if (got == 0) break;
        }
        if (!buf) {
            fprintf(stderr, "%s: <stdin>: out of memory reading the model\n", PROG);
            return EXIT_INPUT;
        }
        if (ferror(stdin)) {
            fprintf(stderr, "%s: <stdin>: cannot read the model: %s\n", PROG, strerror(errno));
            free(buf);
            return EXIT_INPUT;
        }
        if (len > max_bytes) {
            fprintf(stderr,
                    "%s: <stdin>: the model is more than %zu bytes, the limit (raise it with "
                    "--max-bytes N)\n",
                    PROG, max_bytes);
            free(buf);
            return EXIT_INPUT;
        }
        rc = coons_model_load_memory(buf, len, "<stdin>", &o->load, m, &err);
        free(buf);
    } else {
        rc = coons_model_load_file(o->input, &o->load, m, &err);
    }
    if (rc != COONS_OK) {
        /* The message carries FILE:LINE:COL: /json/path: ... already. */
        fprintf(stderr, "%s: %s\n", PROG, err.message);
        return EXIT_INPUT;
    }
    return -1;
}

/* --body: all digits = index, else a name. Returns the index or -1. */
static long select_body(const coons_model *m, const char *arg)
{
    size_t n = coons_model_body_count(m);
    int digits = arg[0] != '\0';
    for (const char *p = arg; *p; p++)
        if (*p < '0' || *p > '9') digits = 0;
    if (digits) {
        errno = 0;
        unsigned long long i = strtoull(arg, NULL, 10);
        if (errno || i >= n) {
            fprintf(stderr, "%s: --body %s: the model has %zu bod%s (indices 0..%zu)\n", PROG, arg,
                    n, n == 1 ? "y" : "ies", n - 1);
            return -1;
        }
        return (long)i;
    }
    long i = coons_model_find_body(m, arg);
    if (i < 0) fprintf(stderr, "%s: --body %s: the model has no body of that name\n", PROG, arg);
    return i;
}

/* ---- --eval -------------------------------------------------------------- */

static int eval_lines(const coons_body *b, int jacobian)
{
    char *line = NULL;
    size_t cap = 0;
    long lineno = 0;
    int status = 0;
    /* One write per line, so that a program driving coons2stl through a
     * pipe gets each answer at once. */
    setvbuf(stdout, NULL, _IOLBF, 0);
    while (getline(&line, &cap, stdin) != -1) {
        lineno++;
        char *hash = strchr(line, '#');
        if (hash) *hash = '\0';
        double q[3];
        int n = 0;
        const char *p = line;
        for (;;) {
            while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n' || *p == '\v' ||
                   *p == '\f')
                p++;
            if (!*p) break;
            if (n == 3) {
                n = 4;
                break;
            }
            char *end;
            double x = strtod(p, &end);
            if (end == p || !(*end == '\0' || strchr(" \t\r\n\v\f", *end)) || !isfinite(x)) {
                n = -1;
                break;
            }
            q[n++] = x;
            p = end;
        }
        if (n == 0) continue; /* blank line or comment */
        if (n != 3) {
            fprintf(stderr, "%s: <stdin>:%ld: expected three numbers \"u v w\"\n", PROG, lineno);
            status = EXIT_INPUT;
            break;
        }
        static const char names[] = "uvw";
        for (int k = 0; k < 3 && !status; k++) {
            if (q[k] < -1e-12 || q[k] > 1 + 1e-12) {
                fprintf(stderr, "%s: <stdin>:%ld: %c = %.17g is outside [0, 1]\n", PROG, lineno,
                        names[k], q[k]);
                status = EXIT_INPUT;
            }
            q[k] = q[k] < 0 ? 0 : q[k] > 1 ? 1 : q[k];
        }
        if (status) break;
        double x[3], J[3][3];
        if (jacobian) {
            double det = coons_body_eval_jacobian(b, q[0], q[1], q[2], x, J);
            printf("%.17g %.17g %.17g", x[0], x[1], x[2]);
            for (int r = 0; r < 3; r++)
                for (int c = 0; c < 3; c++) printf(" %.17g", J[r][c]);
            printf(" %.17g\n", det);
        } else {
            coons_body_eval(b, q[0], q[1], q[2], x);
            printf("%.17g %.17g %.17g\n", x[0], x[1], x[2]);
        }
    }
    free(line);
    if (!status && ferror(stdin)) {
        fprintf(stderr, "%s: <stdin>: cannot read: %s\n", PROG, strerror(errno));
        status = EXIT_INPUT;
    }
    return status;
}

/* ---- --info -------------------------------------------------------------- */

static void json_string(const char *s)
{
    putchar('"');
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            printf("\\%c", c);
        else if (c < 0x20)
            printf("\\u%04x", c);
        else
            putchar(c);
    }
    putchar('"');
}

static void json_number(double x)
{
    if (isfinite(x))
        printf("%.17g", x);
    else
        printf("null");
}

static void json_box(const double lo[3], const double hi[3])
{
    printf("{\"min\": [");
    for (int k = 0; k < 3; k++) {
        if (k) printf(", ");
        json_number(lo[k]);
    }
    printf("], \"max\": [");
    for (int k = 0; k < 3; k++) {
        if (k) printf(", ");
        json_number(hi[k]);
    }
    printf("]}");
}

static const char *body_type_name(coons_body_type t)
{
    switch (t) {
    case COONS_BODY_BODY0: return "body0";
    case COONS_BODY_BODY1: return "body1";
    case COONS_BODY_BODY2: return "body2";
    case COONS_BODY_BEZIER: return "bezier-volume";
    case COONS_BODY_BSPLINE: return "bspline-volume";
    default: return "unknown";
    }
}

#define INFO_GRID 65
#define INFO_JAC 16

/* Box of the boundary sampled on the six faces, INFO_GRID^2 points each. */
static int sampled_box(const coons_body *b, double lo[3], double hi[3], coons_error *err)
{
    static double out[INFO_GRID * INFO_GRID * 3];
    double g[INFO_GRID], ends[2] = {0.0, 1.0};
    for (int i = 0; i < INFO_GRID; i++) g[i] = (double)i / (INFO_GRID - 1);
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (int face = 0; face < 6; face++) {
        const double *e = &ends[face % 2];
        int dir = face / 2;
        coons_status rc = coons_body_eval_grid(
            b, dir == 0 ? e : g, dir == 0 ? 1 : INFO_GRID, dir == 1 ? e : g,
            dir == 1 ? 1 : INFO_GRID, dir == 2 ? e : g, dir == 2 ? 1 : INFO_GRID, out, err);
        if (rc) return rc;
        for (size_t p = 0; p < (size_t)INFO_GRID * INFO_GRID; p++)
            for (int k = 0; k < 3; k++) {
                if (out[3 * p + k] < lo[k]) lo[k] = out[3 * p + k];
                if (out[3 * p + k] > hi[k]) hi[k] = out[3 * p + k];
            }
    }
    return 0;
}

/* ---- the solid ------------------------------------------------------------ */

/*
 * The mesh that -o writes (--info reports on the very same one): with
 * `body` < 0, every body sampled with `so` and made into the model's solid
 * by coons_model_solidify() (repaired and united as the model's "operation"
 * says); else that body's shell alone, repaired if it crosses itself. Without
 * CGAL the shells are as sampled (coons_model_solidify() refuses a union that
 * needs it). The environment variable COONS2STL_INJECT_CSG_FAILURE (testing
 * aid, read here and nowhere in the library) makes the CGAL step fail.
 */
static coons_status make_solid(const coons_model *m, long body, const coons_sample_options *so,
                               int repair, coons_mesh **out, coons_csg_report *rep,
                               coons_error *err)
{
    coons_csg_options copts = COONS_CSG_OPTIONS_INIT;
    copts.repair = repair;
    copts.progress = ui.on ? on_progress : NULL;
    const char *inject = getenv("COONS2STL_INJECT_CSG_FAILURE");
    coons__csg_inject_failure(inject && *inject && strcmp(inject, "0") != 0);
    coons_csg_report_init(rep);
    *out = NULL;
    coons_sample_options sopts = *so;
    if (body < 0) return coons_model_solidify(m, &sopts, &copts, out, rep, err);

    size_t i = (size_t)body;
    progress_sampling(i, coons_model_body_count(m), coons_model_body_name(m, i));
    coons_mesh *mesh = NULL;
    coons_status rc = coons_body_sample(coons_model_body(m, i), &sopts,
                                        coons_model_body_name(m, i), &mesh, err);
    if (rc != COONS_OK || !coons_csg_is_available()) {
        *out = rc == COONS_OK ? mesh : NULL;
        if (rc != COONS_OK) coons_mesh_free(mesh);
        return rc;
    }
    copts.unite = 0;
    rc = coons_mesh_solidify(mesh, &copts, out, rep, err);
    coons_mesh_free(mesh);
    return rc;
}

/* ---- --info (continued) ------------------------------------------------------ */

/* The body's sampled boundary mesh and its checks, as "mesh": {...};
 * `check_crossing`: also count its self-intersecting triangle pairs. */
static int info_mesh(const coons_model *m, size_t i, const coons_sample_options *so,
                     int check_crossing)
{
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *mesh = NULL;
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    size_t pairs = 0;
    progress_sampling(i, coons_model_body_count(m), coons_model_body_name(m, i));
    if (coons_body_sample(coons_model_body(m, i), so, coons_model_body_name(m, i), &mesh, &err) ||
        coons_mesh_check(mesh, &r, &err) ||
        (check_crossing && coons_mesh_count_self_intersections(mesh, &pairs, &err))) {
        message(0, "body %zu (%s): %s", i, coons_model_body_name(m, i), err.message);
        coons_mesh_free(mesh);
        return EXIT_GEOMETRY;
    }
    double tol, dev;
    size_t lat[3];
    coons_mesh_part_sampling(mesh, 0, &tol, &dev, lat);
    if (dev > tol)
        message(1,
                "body %zu (%s): the fixed resolution leaves a deviation of %.6g, more than the "
                "tolerance %.6g",
                i, coons_model_body_name(m, i), dev, tol);
    if (pairs)
        message(1, "body %zu (%s): its sampled boundary crosses itself (%zu pairs of triangles)",
                i, coons_model_body_name(m, i), pairs);
    printf(",\n     \"mesh\": {\"tolerance\": ");
    json_number(tol);
    printf(", \"deviation\": ");
    json_number(dev);
    printf(", \"lattice\": [%zu, %zu, %zu], \"vertices\": %zu, \"triangles\": %zu,\n", lat[0],
           lat[1], lat[2], r.vertices, r.triangles);
    printf("      \"closed\": %s, \"manifold\": %s, \"oriented\": %s, \"euler\": %ld, "
           "\"expected_euler\": %ld, \"shells\": %zu,\n",
           r.closed ? "true" : "false", r.manifold ? "true" : "false",
           r.oriented ? "true" : "false", r.euler, r.expected_euler, r.shells);
    printf("      \"boundary_edges\": %zu, \"nonmanifold_edges\": %zu, "
           "\"nonmanifold_vertices\": %zu, \"misoriented_edges\": %zu, \"openmesh\": %s",
           r.boundary_edges, r.nonmanifold_edges, r.nonmanifold_vertices, r.misoriented_edges,
           r.openmesh ? "true" : "false");
    if (r.openmesh) printf(", \"openmesh_rejected\": %zu", r.openmesh_rejected);
    printf(",\n      \"volume\": ");
    json_number(r.volume);
    printf(", \"area\": ");
    json_number(r.area);
    if (check_crossing)
        printf(", \"self_intersections\": %zu}", pairs);
    else
        printf(", \"self_intersections\": null}");
    coons_mesh_free(mesh);
    return 0;
}

static void json_bool(const char *key, int v) { printf("\"%s\": %s", key, v ? "true" : "false"); }

/* "solid": what -o would write (make_solid()) and what repair and union
 * found and did. A failure is reported in the JSON ("error") and warned
 * about, not turned into an exit status: --info describes the model. */
static int info_solid(const coons_model *m, long only, const coons_sample_options *so, int repair)
{
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *solid = NULL;
    coons_csg_report rep;
    int csg = coons_csg_is_available();
    coons_status rc = make_solid(m, only, so, repair, &solid, &rep, &err);
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    size_t pairs = 0, pairs32 = 0;
    if (rc == COONS_OK) rc = coons_mesh_check(solid, &r, &err);
    if (rc == COONS_OK && csg) rc = coons_mesh_count_self_intersections(solid, &pairs, &err);
    if (rc == COONS_OK && csg) rc = coons_mesh_count_self_intersections_float(solid, &pairs32, &err);
    progress_end();
    size_t parts = rc == COONS_OK ? coons_mesh_part_count(solid) : 0;
    coons_mesh_free(solid);
    if (rc == COONS_E_NOMEM) {
        message(0, "%s", err.message);
        return EXIT_GEOMETRY;
    }
    printf(",\n  \"solid\": ");
    if (rc != COONS_OK) {
        message(1, "no mesh can be made of %s: %s", only < 0 ? "this model" : "this body",
                err.message);
        printf("{\"error\": ");
        json_string(err.message);
        printf("}");
        return 0;
    }
    if (r.boundary_edges)
        message(1, "the solid's boundary is not closed (%zu border edges)", r.boundary_edges);
    else if (r.nonmanifold_edges)
        message(1,
                "the solid's boundary is closed but not a 2-manifold: %zu edges bound more than "
                "two triangles (solids touching along a curve)",
                r.nonmanifold_edges);
    if (pairs)
        message(1, "the solid's boundary crosses itself (%zu pairs of triangles)%s", pairs,
                repair ? "" : "; without --no-repair it would be repaired");
    else if (pairs32)
        message(1,
                "rounding the solid's coordinates to float32, as STL stores them, makes %zu "
                "pairs of its triangles intersect; OFF and SCAD keep double precision",
                pairs32);
    printf("{");
    json_bool("repair", repair && csg);
    printf(", ");
    json_bool("united", only < 0 && coons_model_operation(m) == COONS_OP_UNION);
    printf(", \"parts\": %zu, \"vertices\": %zu, \"triangles\": %zu,\n   ", parts, r.vertices,
           r.triangles);
    json_bool("closed", r.closed);
    printf(", ");
    json_bool("manifold", r.manifold);
    printf(", ");
    json_bool("oriented", r.oriented);
    printf(", \"euler\": %ld, \"shells\": %zu, \"boundary_edges\": %zu, \"nonmanifold_edges\": %zu,"
           " \"nonmanifold_vertices\": %zu,\n   \"volume\": ",
           r.euler, r.shells, r.boundary_edges, r.nonmanifold_edges, r.nonmanifold_vertices);
    json_number(r.volume);
    printf(", \"area\": ");
    json_number(r.area);
    if (!csg) {
        printf(", \"self_intersections\": null, \"self_intersections_float32\": null, "
               "\"csg\": null}");
        return 0;
    }
    printf(", \"self_intersections\": %zu, \"self_intersections_float32\": %zu,\n", pairs,
           pairs32);
    printf("   \"csg\": {\"triangles_in\": %zu, \"degenerate_dropped\": %zu, "
           "\"intersecting_pairs\": %zu, \"parts_in\": %zu, \"groups\": %zu,\n"
           "    \"passed_through\": %zu, \"patches\": %zu, \"patches_kept\": %zu, "
           "\"fast_unions\": %zu, \"fallbacks\": %zu, \"triangles_out\": %zu,\n"
           "    \"rounding_merged\": %zu, \"close_merged\": %zu, \"slivers_fixed\": %zu, ",
           rep.triangles_in, rep.degenerate_dropped, rep.intersecting_pairs, rep.parts_in,
           rep.groups, rep.passed_through, rep.patches, rep.patches_kept, rep.fast_unions, rep.fallbacks,
           rep.triangles_out, rep.rounding_merged, rep.close_merged, rep.slivers_fixed);
    json_bool("closed", rep.closed);
    printf(", \"nonmanifold_edges\": %zu}}", rep.nonmanifold_edges);
    return 0;
}

/*
 * Sampling and evaluation noise leaves det J a few units of rounding below
 * zero where it is exactly 0 (the collapsed axis of a spool, the tip of a
 * nail, the seam of a NURBS cylinder: -7e-14 on bodies ~20 mm across).
 * det J is a triple product of first derivatives, each of the order of the
 * body's control box diagonal d, so its rounding noise is ~1e-16 d^3 times
 * a few basis factors; a fold whose det J stays above -1e-9 d^3 is thinner
 * than ~1e-9 d, a million times below the default tolerance (d / 1000).
 * Only det J below that threshold is warned about; the raw minimum is
 * reported either way.
 */
#define FOLD_REL 1e-9

static int info(const coons_model *m, long only, const coons_sample_options *so,
                const options *o)
{
    size_t n = coons_model_body_count(m);
    double clo[3], chi[3];
    coons_model_control_bbox(m, clo, chi);
    double diag = sqrt((chi[0] - clo[0]) * (chi[0] - clo[0]) + (chi[1] - clo[1]) * (chi[1] - clo[1]) +
                       (chi[2] - clo[2]) * (chi[2] - clo[2]));
    double tol = coons_model_tolerance(m);
    /* Volumes to a relative accuracy tied to the model tolerance: a boundary
     * off by tol changes the volume by about tol * area ~ tol / size. */
    double rel = diag > 0 ? tol / diag : 1e-6;
    if (rel > 1e-6) rel = 1e-6;
    if (rel < 1e-12) rel = 1e-12;
    int checks = !o->no_solid && coons_csg_is_available();
    double total = 0.0;
    size_t listed = 0;
    printf("{\n  \"units\": ");
    json_string(coons_model_units(m));
    printf(",\n  \"tolerance\": ");
    json_number(tol);
    printf(",\n  \"operation\": \"%s\",\n  \"control_bbox\": ",
           coons_model_operation(m) == COONS_OP_NONE ? "none" : "union");
    json_box(clo, chi);
    printf(",\n  \"bodies\": [");
    for (size_t i = 0; i < n; i++) {
        if (only >= 0 && (size_t)only != i) continue;
        const coons_body *b = coons_model_body(m, i);
        coons_error err = COONS_ERROR_INIT;
        double lo[3], hi[3], blo[3], bhi[3], vol = NAN, mindet = NAN, where[3] = {0, 0, 0};
        if (sampled_box(b, lo, hi, &err) || coons_body_volume(b, rel, &vol, &err) ||
            coons_body_min_jacobian(b, INFO_JAC, &mindet, where, &err)) {
            message(0, "body %zu (%s): %s", i, coons_model_body_name(m, i), err.message);
            return EXIT_GEOMETRY;
        }
        coons_body_control_bbox(b, blo, bhi);
        double d3 = pow(sqrt((bhi[0] - blo[0]) * (bhi[0] - blo[0]) +
                             (bhi[1] - blo[1]) * (bhi[1] - blo[1]) +
                             (bhi[2] - blo[2]) * (bhi[2] - blo[2])),
                        3);
        total += vol;
        if (mindet < -FOLD_REL * d3)
            message(1, "body %zu (%s): det J = %.6g < 0 at (u, v, w) = (%g, %g, %g): the body %s",
                    i, coons_model_body_name(m, i), mindet, where[0], where[1], where[2],
                    vol < 0 ? "is left-handed or folds over itself" : "folds over itself there");
        printf("%s\n    {\"index\": %zu, \"name\": ", listed ? "," : "", i);
        json_string(coons_model_body_name(m, i));
        printf(", \"type\": \"%s\",\n     \"bbox\": ", body_type_name(coons_body_get_type(b)));
        json_box(lo, hi);
        printf(",\n     \"control_bbox\": ");
        json_box(blo, bhi);
        printf(",\n     \"volume\": ");
        json_number(vol);
        printf(", \"min_det_jacobian\": ");
        json_number(mindet);
        printf(", \"min_det_jacobian_at\": [%.17g, %.17g, %.17g]", where[0], where[1], where[2]);
        int rc = info_mesh(m, i, so, checks);
        if (rc) return rc;
        printf("}");
        listed++;
    }
    progress_end();
    printf("\n  ],\n  \"body_count\": %zu,\n  \"total_volume\": ", listed);
    json_number(total);
    if (o->no_solid) {
        printf(",\n  \"solid\": null");
    } else {
        int rc = info_solid(m, only, so, !o->no_repair);
        if (rc) return rc;
    }
    printf("\n}\n");
    return 0;
}

/* ---- output -------------------------------------------------------------- */

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

/*
 * Writes the boundary mesh of the model (all bodies, or only body `body`
 * when >= 0) to `output` (NULL or "-": standard output) in `format` ("stl",
 * "stl-ascii", "off" or "scad"), sampled with `so` (its tolerance is set:
 * -t or the model's; --resolution, --max-triangles). A file is written
 * to a temporary file in the same directory and renamed into place only
 * after everything succeeded (coons_mesh_write()); the model file itself is
 * never overwritten. Prints its own diagnostics and returns the exit status.
 */
static int write_output(const coons_model *m, long body, const char *format, const char *output,
                        const coons_sample_options *so, int repair, const char *input)
{
    coons_error err = COONS_ERROR_INIT;
    coons_format fmt;
    int to_stdout = !output || strcmp(output, "-") == 0;
    const char *shown = to_stdout ? "<stdout>" : output;
    if (coons_format_from_name(format, &fmt, &err) != COONS_OK) {
        fprintf(stderr, "%s: %s\n", PROG, err.message);
        return EXIT_USAGE;
    }
    /* Refuse before the (possibly long) meshing; the library checks again
     * at write time. */
    struct stat in_st, out_st;
    int from_file = input && strcmp(input, "-") != 0;
    if (!to_stdout && from_file && stat(input, &in_st) == 0 && stat(output, &out_st) == 0 &&
        in_st.st_dev == out_st.st_dev && in_st.st_ino == out_st.st_ino) {
        fprintf(stderr, "%s: the output '%s' is the model file '%s'; refusing to overwrite it\n",
                PROG, output, input);
        return EXIT_USAGE;
    }

    coons_mesh *mesh = NULL;
    coons_csg_report rep;
    coons_status rc = make_solid(m, body, so, repair, &mesh, &rep, &err);
    progress_end();
    if (rc != COONS_OK) {
        message(0, "%s: %s%s; nothing was written", shown,
                rc == COONS_E_CSG ? "repair or union failed: " : "", err.message);
        coons_mesh_free(mesh);
        return EXIT_GEOMETRY;
    }
    if (rep.triangles_out > 0 && !rep.closed)
        message(1, "the mesh is not closed");
    else if (rep.nonmanifold_edges)
        message(1,
                "the mesh is closed but not a 2-manifold: %zu edges bound more than two "
                "triangles (solids touching along a curve)",
                rep.nonmanifold_edges);

    char name[256];
    model_name(to_stdout ? input : output, name, sizeof name);
    coons_write_options wopts = COONS_WRITE_OPTIONS_INIT;
    wopts.units = coons_model_units(m);
    wopts.name = name[0] ? name : NULL;
    wopts.protect_path = from_file ? input : NULL;
    wopts.cancel = write_cancelled;
    if (to_stdout) {
        rc = coons_mesh_write_stream(mesh, stdout, fmt, &wopts, &err);
    } else {
        struct sigaction old[NSIG_HANDLED];
        catch_signals(old);
        rc = coons_mesh_write(mesh, output, fmt, &wopts, &err);
        restore_signals(old);
    }
    coons_mesh_free(mesh);
    if (caught_signal) {
        /* Whatever happened, nothing partial is left: either the write was
         * cancelled (temporary file removed, old output untouched) or it
         * had already completed. Die of the signal as expected. */
        if (rc != COONS_OK)
            fprintf(stderr, "%s: %s: interrupted; nothing was written\n", PROG, shown);
        int sig = caught_signal;
        signal(sig, SIG_DFL);
        raise(sig);
    }
    if (rc != COONS_OK) {
        fprintf(stderr, "%s: %s\n", PROG, err.message);
        return EXIT_GEOMETRY;
    }
    return 0;
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
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0) return rc;
    coons_model *m = NULL;
    if ((rc = load_model(&o, &m)) >= 0) return rc;
    long body = -1;
    if (o.body && (body = select_body(m, o.body)) < 0) {
        coons_model_free(m);
        return EXIT_USAGE;
    }
    ui.quiet = o.quiet;
    ui.on = o.force_progress || (!o.quiet && isatty(STDERR_FILENO));
    ui.model = m;
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.tolerance = o.tolerance > 0 ? o.tolerance : coons_model_tolerance(m);
    so.resolution = o.resolution;
    so.max_triangles = o.max_triangles;
    /* A mesh on a fixed lattice needs no measured deviation (--info reports
     * it); measuring would be most of the sampling time. */
    if (o.resolution && !o.info) so.flags |= COONS_SAMPLE_UNMEASURED;
    if (o.eval)
        rc = eval_lines(coons_model_body(m, body < 0 ? 0 : (size_t)body), o.jacobian);
    else if (o.info)
        rc = info(m, body, &so, &o);
    else
        rc = write_output(m, body, o.format, o.output, &so, !o.no_repair, o.input);
    coons_model_free(m);
    if ((o.eval || o.info) && (fflush(stdout) != 0 || ferror(stdout))) {
        fprintf(stderr, "%s: cannot write to standard output: %s\n", PROG, strerror(errno));
        if (!rc) rc = EXIT_GEOMETRY;
    }
    return rc;
}
