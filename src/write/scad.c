/* SPDX-License-Identifier: GPL-3.0-or-later */
/* OpenSCAD writer: one module per mesh part holding a polyhedron(), one
 * module for the whole model, and a top-level call of it, so that
 * `use <f.scad>` imports the modules and `include <f.scad>` renders.
 *
 * OpenSCAD's polyhedron() wants each face clockwise seen from outside
 * (OpenSCAD manual, "polyhedron"), the opposite of STL/OFF, so every
 * triangle (a, b, c) is written as (a, c, b). Points are per part, so the
 * indices are shifted to the part's first vertex. Module names must be
 * OpenSCAD identifiers ([A-Za-z_][A-Za-z0-9_]*) and must not shadow a
 * keyword or a built-in module: a user module called `hull` or `cube`
 * would replace the built-in in every file that uses ours. Every module
 * name carries the model's name (outputs.md, "Boundary meshes"): the
 * model's module is the name itself, a part's is MODEL_PART, so that two
 * generated files `include`d into one design do not replace each other's
 * modules (OpenSCAD keeps the last definition of a name, silently). Parts
 * listed in coons_write_options.background are called with the background
 * modifier `%` (OpenSCAD manual, "Modifier Characters"). */
#include "writer.h"

#include "coons/version.h"

static const char *const reserved[] = {
    /* keywords */
    "module", "function", "if", "else", "let", "for", "each", "true", "false", "undef",
    "include", "use", "assert", "echo", "intersection_for", "assign",
    /* built-in modules of OpenSCAD 2021 (and a few from later releases) */
    "children", "child", "cube", "sphere", "cylinder", "polyhedron", "square", "circle",
    "polygon", "text", "import", "import_stl", "import_off", "import_dxf", "surface",
    "linear_extrude", "rotate_extrude", "dxf_linear_extrude", "dxf_rotate_extrude",
    "projection", "render", "union", "difference", "intersection", "translate", "rotate",
    "scale", "mirror", "multmatrix", "color", "offset", "hull", "minkowski", "resize",
    "group", "parent_module", "roof", "fill", NULL};

void coons__scad_identifier(char *out, size_t cap, const char *name)
{
    size_t n = 0;
    if (cap < 3) {
        if (cap) out[0] = '\0';
        return;
    }
    if (!name) name = "";
    if (!((*name >= 'A' && *name <= 'Z') || (*name >= 'a' && *name <= 'z') || *name == '_'))
        out[n++] = '_';
    for (const char *c = name; *c && n + 1 < cap; c++) {
        int ok = (*c >= 'A' && *c <= 'Z') || (*c >= 'a' && *c <= 'z') ||
                 (*c >= '0' && *c <= '9') || *c == '_';
        out[n++] = ok ? *c : '_';
    }
    out[n] = '\0';
    for (const char *const *r = reserved; *r; r++)
        if (strcmp(out, *r) == 0 && n + 1 < cap) {
            out[n++] = '_';
            out[n] = '\0';
            break;
        }
}

void coons__scad_part_identifier(char *out, size_t cap, const char *model, const char *part)
{
    char joined[2 * COONS__SCAD_IDENT_MAX];
    snprintf(joined, sizeof joined, "%s_%s", model ? model : "", part ? part : "");
    coons__scad_identifier(out, cap, joined);
}

#define IDENT_MAX COONS__SCAD_IDENT_MAX

/* Identifiers of the model (names[np]) and of the parts (names[0..np)),
 * each part's carrying the model's name; the model's first, then the parts'
 * in order, each made unique among those before it with _2, _3, ... */
static coons_status module_names(const coons_mesh *m, const coons__wopts *o, size_t np,
                                 int whole, char (**out)[IDENT_MAX], coons_error *err)
{
    char (*names)[IDENT_MAX] = coons__malloc_array(np + 1, IDENT_MAX);
    if (!names) return coons__error_nomem(err);
    for (size_t k = 0; k <= np; k++) {
        size_t i = k == 0 ? np : k - 1; /* the model first */
        char base[IDENT_MAX - 24];
        if (i == np)
            coons__scad_identifier(base, sizeof base, o->name);
        else
            coons__scad_part_identifier(base, sizeof base, o->name,
                                        whole ? "" : coons_mesh_part_name(m, i));
        snprintf(names[i], IDENT_MAX, "%s", base);
        /* Quadratic, but meshes have a handful of parts. */
        for (unsigned long n = 2;; n++) {
            size_t j = 0, before = i < np ? i : 0;
            int taken = i < np && strcmp(names[np], names[i]) == 0;
            while (!taken && j < before) taken = strcmp(names[j++], names[i]) == 0;
            if (!taken) break;
            snprintf(names[i], IDENT_MAX, "%s_%lu", base, n);
        }
    }
    *out = names;
    return COONS_OK;
}

static int put_part(coons__sink *s, const coons_mesh *m, size_t tf, size_t tc, size_t vf,
                    size_t vc)
{
    const double *xyz = coons_mesh_vertices(m);
    const uint32_t *tri = coons_mesh_triangles(m);
    if (!coons__sink_puts(s, "  polyhedron(points = [\n")) return 0;
    for (size_t v = vf; v < vf + vc; v++) {
        char *p = coons__sink_room(s, 3 * COONS__FMT_MAX + 8), *p0 = p;
        if (!p) return 0;
        *p++ = '[';
        for (int k = 0; k < 3; k++) {
            p += coons__fmt_double(p, xyz[3 * v + (size_t)k]);
            *p++ = k < 2 ? ',' : ']';
        }
        if (v + 1 < vf + vc) *p++ = ',';
        *p++ = '\n';
        s->len += (size_t)(p - p0);
    }
    if (!coons__sink_puts(s, "  ], faces = [\n")) return 0;
    for (size_t t = tf; t < tf + tc; t++) {
        char *p = coons__sink_room(s, 48), *p0 = p;
        if (!p) return 0;
        /* Reversed: clockwise seen from outside. */
        static const int order[3] = {0, 2, 1};
        *p++ = '[';
        for (int k = 0; k < 3; k++) {
            p += coons__fmt_u64(p, tri[3 * t + (size_t)order[k]] - vf);
            *p++ = k < 2 ? ',' : ']';
        }
        if (t + 1 < tf + tc) *p++ = ',';
        *p++ = '\n';
        s->len += (size_t)(p - p0);
    }
    return coons__sink_puts(s, "  ], convexity = 10);\n");
}

/* Points are written per part, so a triangle must stay within its part. */
coons_status coons__check_scad(const coons_mesh *m, coons_error *err)
{
    const uint32_t *tri = coons_mesh_triangles(m);
    for (size_t p = 0; p < coons_mesh_part_count(m); p++) {
        size_t tf, tc, vf, vc;
        coons_mesh_part_range(m, p, &tf, &tc, &vf, &vc);
        for (size_t i = 3 * tf; i < 3 * (tf + tc); i++)
            if (tri[i] < vf || tri[i] - vf >= vc)
                return coons__error_set(err, COONS_E_INVALID,
                                        "triangle %zu of part %zu uses a vertex of another part",
                                        i / 3, p);
    }
    return COONS_OK;
}

void coons__scad_header(coons__sink *s, const coons__wopts *o)
{
    char line[COONS__SINK_MAXREC];
    coons__clean_text(line, sizeof line - 16, o->header);
    coons__sink_puts(s, "// ");
    coons__sink_puts(s, line);
    coons__sink_puts(s, "\n");
    if (o->units[0]) {
        coons__clean_text(line, sizeof line - 16, o->units);
        coons__sink_puts(s, "// units: ");
        coons__sink_puts(s, line);
        coons__sink_puts(s, "\n");
    }
}

coons_status coons__write_scad(const coons_mesh *m, const coons__wopts *o, coons__sink *s)
{
    size_t np = coons_mesh_part_count(m);
    int whole = np == 0; /* a mesh without parts is written as one part */
    if (whole) np = 1;
    char (*names)[IDENT_MAX] = NULL;
    coons_status st = module_names(m, o, np, whole, &names, s->err);
    if (st != COONS_OK) return s->status = st;
    char line[COONS__SINK_MAXREC];
    coons__scad_header(s, o);
    coons__sink_puts(s, "// use <this file> imports the modules; include <this file> also renders ");
    coons__sink_puts(s, names[np]);
    coons__sink_puts(s, "().\n// Faces are clockwise seen from outside, as polyhedron() expects.\n");
    for (size_t i = 0; i < np && s->status == COONS_OK; i++) {
        size_t tf, tc, vf, vc;
        if (whole) {
            tf = vf = 0;
            tc = coons_mesh_triangle_count(m);
            vc = coons_mesh_vertex_count(m);
        } else {
            coons_mesh_part_range(m, i, &tf, &tc, &vf, &vc);
        }
        /* Written in pieces: a long part name must not cut the module name. */
        char num[64];
        coons__clean_text(line, 256, whole ? "" : coons_mesh_part_name(m, i));
        snprintf(num, sizeof num, "\n// part %zu: ", i);
        coons__sink_puts(s, num);
        coons__sink_puts(s, line);
        snprintf(num, sizeof num, " (%zu triangles)\nmodule ", tc);
        coons__sink_puts(s, num);
        coons__sink_puts(s, names[i]);
        coons__sink_puts(s, "() {\n");
        if (tc && !put_part(s, m, tf, tc, vf, vc)) break;
        coons__sink_puts(s, "}\n");
    }
    coons__sink_puts(s, "\nmodule ");
    coons__sink_puts(s, names[np]);
    coons__sink_puts(s, "() {\n");
    for (size_t i = 0; i < np; i++) {
        /* Background parts (context such as a body's boundary around its
         * isoparametric surfaces): OpenSCAD's `%` modifier draws them
         * transparent in the preview and leaves them out of renders. */
        int bg = 0;
        for (size_t k = 0; k < o->nbackground && !whole; k++) bg |= o->background[k] == i;
        coons__sink_puts(s, bg ? "  %" : "  ");
        coons__sink_puts(s, names[i]);
        coons__sink_puts(s, "();\n");
    }
    coons__sink_puts(s, "}\n\n");
    coons__sink_puts(s, names[np]);
    coons__sink_puts(s, "();\n");
    coons__free(names);
    return s->status;
}
