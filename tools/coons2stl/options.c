/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * coons2stl's command line: THE option table (one row per option: its
 * names, its value, its help text, where it is stored), the parser that
 * reads argv through it, the checks of the values and of options that
 * exclude each other, and the --help text, generated from the table.
 * An option is one row here and one entry in coons2stl(1); a test checks
 * that the two agree.
 */
#include <errno.h>
#include <stdarg.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

/* The loader caps max_depth here (coons-model(5)). */
#define MAX_DEPTH_CEILING 256u

/* What an option takes and how its value is stored. */
typedef enum value_kind {
    V_FLAG,     /* no value: sets an int to 1 */
    V_ACTION,   /* no value: runs at once and ends the program (--help, --version) */
    V_TEXT,     /* a string, kept as given */
    V_REAL,     /* a finite number > 0, into a double */
    V_UNSIGNED, /* a whole number from 1 to `max`, into an unsigned */
    V_SIZE,     /* a whole number from 1 to `max`, into a size_t */
    V_LATTICE,  /* N or NU,NV,NW, each from 1 to `max`: into `resolution3` (and N into
                   the unsigned at `offset` when one number is given) */
    V_LIST      /* a string, repeatable: appended to `iso` */
} value_kind;

typedef struct option_row {
    const char *name;    /* long name, without "--" */
    char short_name;     /* 0: none */
    const char *metavar; /* what --help calls the value; NULL for V_FLAG and V_ACTION */
    value_kind kind;
    size_t offset;       /* of the field in `options` (not for V_ACTION) */
    const char *help;    /* --help text; '\n' continues on the next line, {default} and
                            {max} stand for the fields below */
    const char *needs;   /* V_REAL, V_UNSIGNED, V_SIZE: what a bad value is told it needs */
    unsigned long long dflt, max;
    int (*action)(void); /* V_ACTION: returns the exit status */
} option_row;

static int show_help(void);
static int show_version(void);

#define AT(field) offsetof(options, field)

/* In the order --help lists them (and in which their values are checked). */
static const option_row OPTIONS[] = {
    {"output", 'o', "FILE", V_TEXT, AT(output),
     "write the mesh to FILE (default: standard output)", NULL, 0, 0, NULL},
    {"format", 'f', "FMT", V_TEXT, AT(format_arg),
     "surface: stl (binary), stl-ascii, off, scad or 3mf; volume:\n"
     "msh (Gmsh 2.2), msh4, vtu, vtu-ascii, inp or vtk; exact\n"
     "solids: step (AP214), step-ap242, iges or brep; by default\n"
     "taken from the extension of FILE (.stl, .off, .scad, .3mf,\n"
     ".msh, .vtu, .inp, .vtk, .step, .stp, .igs, .iges, .brep),\n"
     "else stl",
     NULL, 0, 0, NULL},
    {"tolerance", 't', "D", V_REAL, AT(tolerance),
     "largest distance between mesh and surface (> 0),\n"
     "instead of the model's \"tolerance\"",
     "a number > 0", 0, 0, NULL},
    {"resolution", 0, "N[,N,N]", V_LATTICE, AT(resolution),
     "sample each body on a fixed lattice of N intervals along\n"
     "u, v and w instead of adapting it to the tolerance\n"
     "(volume meshes: also NU,NV,NW)",
     "a whole number from 1 to {max}", 0, 1u << 20, NULL},
    {"element", 0, "KIND", V_TEXT, AT(element_arg),
     "volume meshes: hex8 (default), hex20 or hex27 cells", NULL, 0, 0, NULL},
    {"allow-inverted", 0, NULL, V_FLAG, AT(allow_inverted),
     "volume meshes: write them even with inverted cells", NULL, 0, 0, NULL},
    {"volume-mesh", 0, NULL, V_FLAG, AT(volume_mesh),
     "with --info, report the volume mesh (\"volume_mesh\")\n"
     "without writing one",
     NULL, 0, 0, NULL},
    {"iso", 0, "D=V[,V...]", V_LIST, 0,
     "write the surfaces D = V (D: u, v or w; V in [0,1]) of\n"
     "every body instead of the boundary (repeatable)",
     NULL, 0, 0, NULL},
    {"with-boundary", 0, NULL, V_FLAG, AT(with_boundary),
     "with --iso, write the boundary too", NULL, 0, 0, NULL},
    {"max-triangles", 0, "N", V_SIZE, AT(max_triangles),
     "refuse to make more than N triangles (default {default})", "a whole number > 0",
     COONS_MESH_MAX_TRIANGLES, SIZE_MAX, NULL},
    {"max-bytes", 0, "N", V_SIZE, AT(load.max_bytes),
     "refuse a model file of more than N bytes (default {default})",
     "a whole number from 1 to {max}", COONS_MODEL_MAX_BYTES, SIZE_MAX, NULL},
    {"max-values", 0, "N", V_SIZE, AT(load.max_values),
     "... of more than N JSON values, keys included (default {default})",
     "a whole number from 1 to {max}", COONS_MODEL_MAX_VALUES, SIZE_MAX, NULL},
    {"max-depth", 0, "N", V_UNSIGNED, AT(load.max_depth),
     "... with arrays and objects nested deeper than N\n"
     "(default {default}, at most {max})",
     "a whole number from 1 to {max}", COONS_MODEL_MAX_DEPTH, MAX_DEPTH_CEILING, NULL},
    {"max-points", 0, "N", V_SIZE, AT(load.max_points),
     "... with more than N points in one curve, surface or\n"
     "volume net (default {default})",
     "a whole number from 1 to {max}", COONS_MODEL_MAX_POINTS, SIZE_MAX, NULL},
    {"scale-to", 0, "UNIT", V_TEXT, AT(scale_to),
     "write the coordinates converted from the model's units\n"
     "to UNIT (um, mm, cm, in, ft or m), labelled UNIT",
     NULL, 0, 0, NULL},
    {"body", 0, "NAME|INDEX", V_TEXT, AT(body),
     "use that body (a 0-based index if all digits, else a\n"
     "name); default: all bodies, or body 0 for --eval",
     NULL, 0, 0, NULL},
    {"eval", 0, NULL, V_FLAG, AT(eval),
     "read lines \"u v w\" from standard input and print\n"
     "\"x y z\" of the body (17 significant digits)",
     NULL, 0, 0, NULL},
    {"jacobian", 0, NULL, V_FLAG, AT(jacobian),
     "with --eval, also print the Jacobian (row-major,\n"
     "columns d/du d/dv d/dw) and its determinant",
     NULL, 0, 0, NULL},
    {"info", 0, NULL, V_FLAG, AT(info),
     "print a JSON description of the model and its bodies,\n"
     "with what repair and union make of them (\"solid\")",
     NULL, 0, 0, NULL},
    {"no-solid", 0, NULL, V_FLAG, AT(no_solid),
     "with --info, skip the solid and the self-intersection\n"
     "checks (fast on big models)",
     NULL, 0, 0, NULL},
    {"no-repair", 0, NULL, V_FLAG, AT(no_repair),
     "write bodies that meet no other body as sampled, even\n"
     "if their boundary crosses itself",
     NULL, 0, 0, NULL},
    {"jobs", 'j', "N", V_UNSIGNED, AT(jobs),
     "sample, check, unite, mesh volumes and deform on N\n"
     "threads (default: the number of cores); the output\n"
     "does not depend on N",
     "a whole number from 1 to {max}", 0, 1024, NULL},
    {"progress", 0, NULL, V_FLAG, AT(force_progress),
     "report progress on standard error even when it is not\n"
     "a terminal (never with -q)",
     NULL, 0, 0, NULL},
    {"quiet", 'q', NULL, V_FLAG, AT(quiet), "no warnings and no progress report", NULL, 0, 0,
     NULL},
    {"time", 0, "T", V_TEXT, AT(time_arg),
     "take every morph body at time T in [0,1] instead of\n"
     "its \"t\" (also morphs inside others)",
     NULL, 0, 0, NULL},
    {"frames", 0, "N", V_UNSIGNED, AT(frames),
     "write N >= 2 frames of the morphs, at t = k/(N-1), to\n"
     "-o PATTERN holding one integer field (frame-%03d.stl);\n"
     "with .vtu also a ParaView .pvd index",
     "a whole number from 2 to {max}", 0, 100000, NULL},
    {"deform", 0, "IN", V_TEXT, AT(deform),
     "map the mesh IN (STL or OFF) through the body (--body,\n"
     "default 0) instead of meshing the model: free-form\n"
     "deformation, split to the tolerance",
     NULL, 0, 0, NULL},
    {"frame", 0, "X0,Y0,Z0,X1,Y1,Z1", V_TEXT, AT(frame_arg),
     "with --deform, the box of IN mapped to the unit cube of\n"
     "the body's parameters (default: IN's bounding box)",
     NULL, 0, 0, NULL},
    {"help", 'h', NULL, V_ACTION, 0, "show this help and exit", NULL, 0, 0, show_help},
    {"version", 0, NULL, V_ACTION, 0, "show the version and exit", NULL, 0, 0, show_version},
};

#define NOPTIONS (sizeof OPTIONS / sizeof OPTIONS[0])

/* --help's columns: "  -o, --output FILE      write ..." */
#define HELP_NAMES 19 /* width of "--name METAVAR" */
#define HELP_INDENT 25 /* where the help text starts */

/* ---- the help text ---------------------------------------------------- */

/* `text` with {default} and {max} replaced by the row's numbers. */
static void expand(char *out, size_t cap, const char *text, const option_row *r)
{
    size_t n = 0;
    out[0] = '\0';
    while (*text && n + 1 < cap) {
        if (strncmp(text, "{default}", 9) == 0 || strncmp(text, "{max}", 5) == 0) {
            int is_max = text[1] == 'm';
            int k = snprintf(out + n, cap - n, "%llu", is_max ? r->max : r->dflt);
            n += k > 0 ? (size_t)k : 0;
            if (n >= cap) n = cap - 1;
            text += is_max ? 5 : 9;
        } else {
            out[n++] = *text++;
        }
    }
    out[n] = '\0';
}

static void usage_row(FILE *f, const option_row *r)
{
    char names[64], help[512];
    snprintf(names, sizeof names, "--%s%s%s", r->name, r->metavar ? " " : "",
             r->metavar ? r->metavar : "");
    if (r->short_name)
        fprintf(f, "  -%c, %-*s", r->short_name, HELP_NAMES, names);
    else
        fprintf(f, "      %-*s", HELP_NAMES, names);
    if (strlen(names) + 2 > HELP_NAMES) /* too long to share its line with the text */
        fprintf(f, "\n%*s", HELP_INDENT, "");
    expand(help, sizeof help, r->help, r);
    for (const char *line = help; line;) {
        const char *nl = strchr(line, '\n');
        int len = nl ? (int)(nl - line) : (int)strlen(line);
        fprintf(f, "%.*s\n", len, line);
        line = nl ? nl + 1 : NULL;
        if (line) fprintf(f, "%*s", HELP_INDENT, "");
    }
}

static void usage(FILE *f)
{
    fprintf(f,
            "Usage: %s [OPTIONS] MODEL.json\n"
            "Reads a libcoons model (MODEL.json, or - for standard input) and writes the\n"
            "boundary mesh of its bodies.\n"
            "\n",
            PROG);
    for (size_t i = 0; i < NOPTIONS; i++) usage_row(f, &OPTIONS[i]);
    fprintf(f, "\n"
               "Exit status: 0 success, 1 bad input, 2 bad usage, 3 a geometric operation\n"
               "or writing the output failed.\n");
}

static int show_help(void)
{
    usage(stdout);
    return fflush(stdout) == 0 ? 0 : EXIT_GEOMETRY;
}

static int show_version(void)
{
    printf("%s (libcoons) %s\nmodel format version %d\n", PROG, coons_version_string(),
           COONS_MODEL_FORMAT_VERSION);
    return fflush(stdout) == 0 ? 0 : EXIT_GEOMETRY;
}

#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
static int usage_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "%s: ", PROG);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\nTry '%s --help' for more information.\n", PROG);
    return EXIT_USAGE;
}

int cli_usage_error(const char *msg) { return usage_error("%s", msg); }

/* ---- reading argv through the table ----------------------------------- */

/* What the loop has seen: each row's last value (flags: ""), stored and
 * checked after the loop, in the table's order. */
typedef struct parse_state {
    const char *given[NOPTIONS];
    const char *list[64]; /* V_LIST values, in order */
    size_t nlist;
    int only_files; /* after "--" */
} parse_state;

static const option_row *find_long(const char *name, size_t len)
{
    for (size_t i = 0; i < NOPTIONS; i++)
        if (strlen(OPTIONS[i].name) == len && strncmp(OPTIONS[i].name, name, len) == 0)
            return &OPTIONS[i];
    return NULL;
}

static const option_row *find_short(char c)
{
    for (size_t i = 0; i < NOPTIONS; i++)
        if (OPTIONS[i].short_name && OPTIONS[i].short_name == c) return &OPTIONS[i];
    return NULL;
}

static int takes_value(const option_row *r) { return r->kind != V_FLAG && r->kind != V_ACTION; }

/* Finds the row of argument `a` ("-x[VALUE]", "--name[=VALUE]"); *value
 * receives an attached value or NULL. Returns -1, else an exit status. */
static int match_option(const char *a, const option_row **row, const char **value)
{
    *value = NULL;
    if (a[1] != '-') {
        if (!(*row = find_short(a[1]))) return usage_error("unknown option '%s'", a);
        if (a[2]) {
            if (!takes_value(*row))
                return usage_error("unknown option '%s' (give short options separately)", a);
            *value = a + 2; /* -ofile */
        }
        return -1;
    }
    const char *name = a + 2, *eq = strchr(name, '=');
    if (!(*row = find_long(name, eq ? (size_t)(eq - name) : strlen(name))))
        return usage_error("unknown option '%s'", a);
    if (eq) *value = eq + 1;
    return -1;
}

/* One argument that starts with '-' (and is not "-" or "--"), with the next
 * one when it is the option's value. Returns -1 to go on, else an exit
 * status. */
static int read_option(int argc, char **argv, int *i, parse_state *ps)
{
    const char *a = argv[*i], *value;
    const option_row *r;
    int rc = match_option(a, &r, &value);
    if (rc >= 0) return rc;
    if (!takes_value(r) && value) return usage_error("option '%s' takes no value", a);
    if (takes_value(r) && !value) {
        /* (A short option without a value is just "-x".) */
        if (*i + 1 >= argc) return usage_error("option '%s' needs a value", a);
        value = argv[++*i];
    }
    if (r->kind == V_ACTION) return r->action();
    if (r->kind == V_LIST) {
        if (ps->nlist == sizeof ps->list / sizeof ps->list[0])
            return usage_error("at most %zu --%s options", ps->nlist, r->name);
        ps->list[ps->nlist++] = value;
    }
    ps->given[r - OPTIONS] = value ? value : "";
    return -1;
}

static int read_args(int argc, char **argv, parse_state *ps, options *o)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (ps->only_files || a[0] != '-' || strcmp(a, "-") == 0) {
            if (o->input) return usage_error("more than one model file given ('%s')", a);
            o->input = a;
        } else if (strcmp(a, "--") == 0) {
            ps->only_files = 1;
        } else {
            int rc = read_option(argc, argv, &i, ps);
            if (rc >= 0) return rc;
        }
    }
    return -1;
}

/* ---- storing and checking the values ----------------------------------- */

static int bad_value(const option_row *r, const char *value)
{
    char needs[128], fmt[192];
    expand(needs, sizeof needs, r->needs, r);
    snprintf(fmt, sizeof fmt, "--%s needs %s, not '%%s'", r->name, needs);
    return usage_error(fmt, value);
}

/* Stores row r's value into o; returns -1, else the exit status. */
static int store_value(const option_row *r, const char *value, options *o)
{
    char *field = (char *)o + r->offset, *end = NULL;
    errno = 0;
    switch (r->kind) {
    case V_FLAG: *(int *)(void *)field = 1; return -1;
    case V_TEXT: *(const char **)(void *)field = value; return -1;
    case V_REAL: {
        double x = strtod(value, &end);
        if (end == value || *end || !isfinite(x) || !(x > 0)) return bad_value(r, value);
        *(double *)(void *)field = x;
        return -1;
    }
    case V_UNSIGNED:
    case V_SIZE: {
        unsigned long long v = strtoull(value, &end, 10);
        if (value[0] < '0' || value[0] > '9' || *end || errno || v < 1 || v > r->max)
            return bad_value(r, value);
        if (r->kind == V_UNSIGNED)
            *(unsigned *)(void *)field = (unsigned)v;
        else
            *(size_t *)(void *)field = (size_t)v;
        return -1;
    }
    case V_LATTICE: {
        unsigned n[3] = {0, 0, 0};
        int k = 0;
        const char *p = value;
        for (;;) {
            unsigned long long v = strtoull(p, &end, 10);
            if (*p < '0' || *p > '9' || errno || v < 1 || v > r->max || k == 3)
                return bad_value(r, value);
            n[k++] = (unsigned)v;
            if (*end == '\0') break;
            if (*end != ',') return bad_value(r, value);
            p = end + 1;
        }
        if (k == 2) return bad_value(r, value);
        o->resolution_split = k == 3;
        for (int d = 0; d < 3; d++) o->resolution3[d] = k == 3 ? n[d] : n[0];
        *(unsigned *)(void *)field = n[0];
        return -1;
    }
    case V_LIST:
    case V_ACTION: break;
    }
    return -1;
}

static int store_values(const parse_state *ps, options *o)
{
    for (size_t i = 0; i < NOPTIONS; i++) {
        if (!ps->given[i]) continue;
        int rc = store_value(&OPTIONS[i], ps->given[i], o);
        if (rc >= 0) return rc;
    }
    if (o->jacobian) o->eval = 1; /* --jacobian implies --eval */
    for (size_t i = 0; i < ps->nlist; i++) o->iso[i] = ps->list[i];
    o->niso = ps->nlist;
    return -1;
}

static int given(const parse_state *ps, const char *name)
{
    return ps->given[find_long(name, strlen(name)) - OPTIONS] != NULL;
}

/* Options that belong to other modes. */
static int check_modes(const parse_state *ps, const options *o)
{
    if (o->eval && (given(ps, "resolution") || given(ps, "max-triangles")))
        return usage_error("%s", "--resolution and --max-triangles are for meshes and --info");
    if (o->eval && o->info) return usage_error("%s", "--eval and --info cannot be combined");
    if (o->eval && (o->no_repair || o->force_progress))
        return usage_error("%s", "--no-repair and --progress are for meshes and --info");
    if (o->no_solid && !o->info) return usage_error("%s", "--no-solid is for --info");
    if ((o->eval || (o->info && !cli_is_volume_format(o->format))) &&
        (o->output || o->format_arg))
        return usage_error("%s", "-o and -f are for meshes: --eval and --info print to "
                                 "standard output (--info -o takes a volume-mesh format)");
    int volume = cli_is_volume_format(o->format) && (o->output || o->format_arg);
    if (o->volume_mesh && !o->info) return usage_error("%s", "--volume-mesh is for --info");
    if (o->volume_mesh && volume)
        return usage_error("%s", "--volume-mesh reports without writing: leave out -o");
    volume |= o->volume_mesh;
    if (!volume && (o->element_arg || o->allow_inverted || o->resolution_split))
        return usage_error("%s", "--element, --allow-inverted and --resolution NU,NV,NW are "
                                 "for volume meshes (-o FILE.msh, .vtu, .inp, .vtk, or "
                                 "--info --volume-mesh)");
    if (o->scale_to && cli_unit_mm(o->scale_to) == 0)
        return usage_error("--scale-to needs um, mm, cm, in, ft or m, not '%s'", o->scale_to);
    if (o->scale_to && (o->eval || (o->info && !(cli_is_volume_format(o->format) && o->output))))
        return usage_error("%s", "--scale-to is for -o: --eval and --info report in the "
                                 "model's units");
    if (o->with_boundary && !o->niso) return usage_error("%s", "--with-boundary is for --iso");
    if (o->niso && (o->eval || o->info))
        return usage_error("%s", "--iso is for -o: --eval and --info write no surfaces");
    if (o->niso && o->format != COONS_FORMAT_OFF && o->format != COONS_FORMAT_SCAD &&
        o->format != COONS_FORMAT_VTU && o->format != COONS_FORMAT_VTU_ASCII)
        return usage_error("--iso writes surfaces, which '%s' cannot hold: use .off, .scad "
                           "or .vtu",
                           coons_format_name(o->format));
    if (o->eval && strcmp(o->input, "-") == 0)
        return usage_error("%s", "--eval reads parameters from standard input, so the model "
                                 "must come from a file");
    return -1;
}

/* The -f names of the formats, from the library's format table, as
 * "stl, stl-ascii, off, scad, ... or inp": a format's name is its
 * extension's stem when -f accepts that (".stl" -> "stl"), else its table
 * name. */
static void format_names(char *out, size_t cap)
{
    const char *names[32];
    size_t n = 0;
    for (int f = 1; coons_format_kind((coons_format)f) != COONS_MESH_KIND_NONE && n < 32; f++) {
        const char *ext = coons_format_extension((coons_format)f);
        coons_format g = COONS_FORMAT_AUTO;
        if (ext && coons_format_from_name(ext + 1, &g, NULL) == COONS_OK && g == (coons_format)f)
            names[n++] = ext + 1;
        else
            names[n++] = coons_format_name((coons_format)f);
    }
    size_t len = 0;
    out[0] = '\0';
    for (size_t i = 0; i < n && len < cap; i++)
        len += (size_t)snprintf(out + len, cap - len, "%s%s",
                                i == 0 ? "" : (i + 1 == n ? " or " : ", "), names[i]);
}

int cli_is_volume_format(coons_format f) { return coons_format_kind(f) == COONS_MESH_KIND_VOLUME; }

/* -f, else the output's extension (the library's names), else binary STL. */
static int resolve_format(options *o)
{
    char list[256];
    format_names(list, sizeof list);
    if (o->format_arg) {
        if (coons_format_from_name(o->format_arg, &o->format, NULL) != COONS_OK)
            return usage_error("unknown format '%s': expected %s", o->format_arg, list);
    } else if (o->output && strcmp(o->output, "-") != 0) {
        if (coons_format_from_path(o->output, &o->format, NULL) != COONS_OK)
            return usage_error("cannot tell the output format from the name '%s': use -f %s",
                               o->output, list);
    } else {
        o->format = COONS_FORMAT_STL_BINARY;
    }
    return -1;
}

/* --element hex8|hex20|hex27; -f inp holds hex8 and hex20 only. */
static int resolve_element(options *o)
{
    o->element = COONS_ELEMENT_HEX8;
    if (o->element_arg) {
        if (strcmp(o->element_arg, "hex8") == 0)
            o->element = COONS_ELEMENT_HEX8;
        else if (strcmp(o->element_arg, "hex20") == 0)
            o->element = COONS_ELEMENT_HEX20;
        else if (strcmp(o->element_arg, "hex27") == 0)
            o->element = COONS_ELEMENT_HEX27;
        else
            return usage_error("--element needs hex8, hex20 or hex27, not '%s'", o->element_arg);
    }
    if (o->element == COONS_ELEMENT_HEX27 && o->format == COONS_FORMAT_INP &&
        (o->output || o->format_arg))
        return usage_error("%s", "--element hex27 cannot be written to an Abaqus/CalculiX deck "
                                 "(.inp holds C3D8 and C3D20: use hex8 or hex20)");
    return -1;
}

/* --iso D=V[,V...]: D one of u, v, w; every V a number in [0, 1]. */
static int resolve_iso(options *o)
{
    size_t cap = sizeof o->iso_value / sizeof o->iso_value[0];
    for (size_t i = 0; i < o->niso; i++) {
        const char *spec = o->iso[i];
        const char *dirs = "uvw", *d = spec[0] ? strchr(dirs, spec[0]) : NULL;
        if (!d || spec[1] != '=' || !spec[2])
            return usage_error("--iso needs D=V[,V...] with D one of u, v, w, not '%s'", spec);
        const char *p = spec + 2;
        for (;;) {
            char *end;
            errno = 0;
            double x = strtod(p, &end);
            if (end == p || (*end && *end != ',') || !isfinite(x))
                return usage_error("--iso '%s': '%.*s' is not a number", spec,
                                   (int)strcspn(p, ","), p);
            if (x < 0 || x > 1)
                return usage_error("--iso '%s': %c = %g lies outside the parameter range [0, 1]",
                                   spec, *d, x);
            if (o->niso_surfaces == cap)
                return usage_error("--iso: at most %zu surfaces", cap);
            o->iso_dir[o->niso_surfaces] = (int)(d - dirs);
            o->iso_value[o->niso_surfaces++] = x;
            if (!*end) break;
            p = end + 1;
        }
    }
    return -1;
}

int cli_parse_args(int argc, char **argv, options *o)
{
    parse_state ps;
    memset(&ps, 0, sizeof ps);
    int rc = read_args(argc, argv, &ps, o);
    if (rc >= 0) return rc;
    if (!o->input) return usage_error("%s", "no model file given");
    if ((rc = store_values(&ps, o)) >= 0) return rc;
    if ((rc = resolve_format(o)) >= 0) return rc;
    if ((rc = check_modes(&ps, o)) >= 0) return rc;
    if ((rc = resolve_element(o)) >= 0) return rc;
    if ((rc = resolve_iso(o)) >= 0) return rc;
    if ((rc = cli_check_deform_options(o)) >= 0) return rc;
    return cli_check_time_options(o);
}
