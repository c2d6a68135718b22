/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The output formats, described once: for each its enum value, its name
 * for -f (and aliases), the extensions that imply it, the kind of mesh it
 * holds and its writer. coons_format_from_path(), coons_format_from_name(),
 * coons_format_name(), coons_format_kind(), coons_format_extension() and
 * the dispatch of coons_mesh_write() / coons_volume_mesh_write() all read
 * this table, and the error messages list what it holds. */
#include "writer.h"

#define SURFACE COONS_MESH_KIND_SURFACE
#define VOLUME COONS_MESH_KIND_VOLUME
#define SOLID COONS_MESH_KIND_SOLID

/* In enum order; write/test_write checks that every row maps back to itself. */
static const coons__format_row ROWS[] = {
    {.format = COONS_FORMAT_STL_BINARY, .name = "stl-binary", .title = "binary STL",
     .aliases = {"stl"}, .extensions = {".stl"}, .kind = SURFACE, .max_triangles = UINT32_MAX,
     .write_surface = coons__write_stl_binary, .check_surface = coons__check_stl},
    {.format = COONS_FORMAT_STL_ASCII, .name = "stl-ascii", .title = "ASCII STL", .kind = SURFACE,
     .write_surface = coons__write_stl_ascii, .check_surface = coons__check_stl},
    {.format = COONS_FORMAT_OFF, .name = "off", .title = "OFF", .extensions = {".off"},
     .kind = SURFACE, .write_surface = coons__write_off},
    {.format = COONS_FORMAT_SCAD, .name = "scad", .title = "OpenSCAD", .extensions = {".scad"},
     .kind = SURFACE, .write_surface = coons__write_scad, .check_surface = coons__check_scad},
    {.format = COONS_FORMAT_VTK, .name = "vtk", .title = "legacy VTK", .extensions = {".vtk"},
     .kind = VOLUME, .write_volume = coons__write_vtk},
    {.format = COONS_FORMAT_MSH2, .name = "msh2", .title = "Gmsh MSH 2.2", .aliases = {"msh"},
     .extensions = {".msh"}, .kind = VOLUME, .write_volume = coons__write_msh2},
    {.format = COONS_FORMAT_MSH4, .name = "msh4", .title = "Gmsh MSH 4.1", .kind = VOLUME,
     .write_volume = coons__write_msh4},
    {.format = COONS_FORMAT_VTU, .name = "vtu", .title = "VTK XML", .extensions = {".vtu"},
     .kind = VOLUME, .write_volume = coons__write_vtu, .write_surface = coons__write_vtu_surface},
    {.format = COONS_FORMAT_INP, .name = "inp", .title = "Abaqus/CalculiX input deck",
     .extensions = {".inp"}, .kind = VOLUME, .write_volume = coons__write_inp,
     .check_volume = coons__check_inp},
    {.format = COONS_FORMAT_VTU_ASCII, .name = "vtu-ascii", .title = "ASCII VTK XML",
     .kind = VOLUME, .write_volume = coons__write_vtu_ascii,
     .write_surface = coons__write_vtu_surface},
    {.format = COONS_FORMAT_3MF, .name = "3mf", .title = "3MF", .extensions = {".3mf"},
     .kind = SURFACE, .max_triangles = UINT32_MAX, .write_surface = coons__write_3mf,
     .check_surface = coons__check_3mf},
    {.format = COONS_FORMAT_STEP, .name = "step", .title = "STEP AP214", .aliases = {"stp"},
     .extensions = {".step", ".stp"}, .kind = SOLID, .write_solid = coons__write_solid},
    {.format = COONS_FORMAT_STEP_AP242, .name = "step-ap242", .title = "STEP AP242",
     .kind = SOLID, .write_solid = coons__write_solid},
    {.format = COONS_FORMAT_IGES, .name = "iges", .title = "IGES", .aliases = {"igs"},
     .extensions = {".igs", ".iges"}, .kind = SOLID, .write_solid = coons__write_solid},
    {.format = COONS_FORMAT_BREP, .name = "brep", .title = "Open CASCADE BREP",
     .extensions = {".brep"}, .kind = SOLID, .write_solid = coons__write_solid},
};
#define NROWS (sizeof ROWS / sizeof ROWS[0])

const coons__format_row *coons__format_row_of(coons_format format)
{
    for (size_t i = 0; i < NROWS; i++)
        if (ROWS[i].format == format) return &ROWS[i];
    return NULL;
}

/* a equals b, ignoring the case of a's ASCII letters (b is lower case). */
static int ieq(const char *a, const char *b)
{
    for (; *a && *b; a++, b++) {
        char x = (*a >= 'A' && *a <= 'Z') ? (char)(*a + 32) : *a;
        if (x != *b) return 0;
    }
    return *a == *b;
}

/* Appends `word` to the list in buf ("a, b or c" when `last` ends it). */
static void list_add(char *buf, size_t cap, size_t *n, const char *word, int first, int last)
{
    int w = snprintf(buf + *n, cap - *n, "%s%s", first ? "" : last ? " or " : ", ", word);
    if (w > 0) *n = (size_t)w >= cap - *n ? cap - 1 : *n + (size_t)w;
}

coons_status coons_format_from_path(const char *path, coons_format *out, coons_error *err)
{
    if (!path || !out) return coons__error_set(err, COONS_E_INVALID, "no path given");
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    const char *dot = strrchr(base, '.');
    size_t total = 0;
    for (size_t i = 0; i < NROWS; i++)
        for (int k = 0; ROWS[i].extensions[k]; k++) {
            if (dot && dot != base && ieq(dot, ROWS[i].extensions[k]))
                return *out = ROWS[i].format, COONS_OK;
            total++;
        }
    char list[256];
    size_t n = 0, seen = 0;
    list[0] = '\0';
    for (size_t i = 0; i < NROWS; i++)
        for (int k = 0; ROWS[i].extensions[k]; k++, seen++)
            list_add(list, sizeof list, &n, ROWS[i].extensions[k], seen == 0, seen + 1 == total);
    return coons__error_set(err, COONS_E_INVALID,
                            "cannot tell the output format of '%s' (use %s, or name the format)",
                            path, list);
}

coons_status coons_format_from_name(const char *name, coons_format *out, coons_error *err)
{
    if (!name || !out) return coons__error_set(err, COONS_E_INVALID, "no format name given");
    char list[256];
    size_t n = 0;
    list[0] = '\0';
    for (size_t i = 0; i < NROWS; i++) {
        for (int k = 0; k < 2 && ROWS[i].aliases[k]; k++) {
            if (ieq(name, ROWS[i].aliases[k])) return *out = ROWS[i].format, COONS_OK;
            list_add(list, sizeof list, &n, ROWS[i].aliases[k], n == 0, 0);
        }
        if (ieq(name, ROWS[i].name)) return *out = ROWS[i].format, COONS_OK;
        list_add(list, sizeof list, &n, ROWS[i].name, n == 0, 0);
    }
    return coons__error_set(err, COONS_E_INVALID, "unknown format '%s' (%s)", name, list);
}

const char *coons_format_name(coons_format format)
{
    if (format == COONS_FORMAT_AUTO) return "auto";
    const coons__format_row *r = coons__format_row_of(format);
    return r ? r->name : "unknown";
}

coons_mesh_kind coons_format_kind(coons_format format)
{
    const coons__format_row *r = coons__format_row_of(format);
    return r ? r->kind : COONS_MESH_KIND_NONE;
}

const char *coons_format_extension(coons_format format)
{
    const coons__format_row *r = coons__format_row_of(format);
    return r ? r->extensions[0] : NULL;
}
