/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Legacy VTK writer, ASCII unstructured grid of hexahedra (Kitware, "VTK
 * File Formats", Simple Legacy Formats: header line, title line, ASCII,
 * DATASET UNSTRUCTURED_GRID with POINTS, CELLS, CELL_TYPES, then
 * POINT_DATA / CELL_DATA attributes). Read by VTK and ParaView, VisIt,
 * meshio and Gmsh.
 *
 * Cells are stored in Gmsh's node order (coons/volume.h) and written in
 * VTK's (vtk_order.h); in a hex8 mesh, cells with repeated corners become
 * VTK wedges and pyramids where they collapse so (coons__vtk_cell()). Numbers are the shortest text that reads back
 * exactly. */
#include "vtk_order.h"
#include "writer.h"

/* Writes a, the number n, then b (no newline added). */
static int put_num(coons__sink *s, const char *a, uint64_t n, const char *b)
{
    char num[COONS__FMT_MAX];
    num[coons__fmt_u64(num, n)] = '\0';
    return coons__sink_puts(s, a) && coons__sink_puts(s, num) && coons__sink_puts(s, b);
}

static int put_header(const coons_volume_mesh *vm, const coons__wopts *o, coons__sink *s)
{
    /* The title line holds at most 256 characters. */
    char title[256], units[80];
    units[0] = '\0';
    if (o->units[0]) {
        char u[64];
        coons__clean_text(u, sizeof u, o->units);
        snprintf(units, sizeof units, " units=%s", u);
    }
    coons__clean_text(title, sizeof title - strlen(units), o->header);
    return coons__sink_puts(s, "# vtk DataFile Version 3.0\n") && coons__sink_puts(s, title) &&
           coons__sink_puts(s, units) &&
           coons__sink_puts(s, "\nASCII\nDATASET UNSTRUCTURED_GRID\n") &&
           put_num(s, "POINTS ", coons_volume_mesh_node_count(vm), " double\n");
}

static int put_points(const coons_volume_mesh *vm, coons__sink *s)
{
    const double *xyz = coons_volume_mesh_nodes(vm);
    for (size_t v = 0; v < coons_volume_mesh_node_count(vm); v++) {
        char *p = coons__sink_room(s, 3 * COONS__FMT_MAX + 1), *p0 = p;
        if (!p) return 0;
        for (int k = 0; k < 3; k++) {
            p += coons__fmt_double(p, xyz[3 * v + (size_t)k]);
            *p++ = k < 2 ? ' ' : '\n';
        }
        s->len += (size_t)(p - p0);
    }
    return 1;
}

static int put_cells(const coons_volume_mesh *vm, coons__sink *s)
{
    size_t nc = coons_volume_mesh_cell_count(vm), npc = coons_volume_mesh_nodes_per_cell(vm);
    const uint32_t *cell = coons_volume_mesh_cells(vm);
    uint32_t nodes[27];
    unsigned type;
    /* "CELLS n size": size counts each cell's leading node count too. */
    uint64_t size = 0;
    for (size_t c = 0; c < nc; c++) size += 1 + coons__vtk_cell(cell + npc * c, npc, nodes, &type);
    if (!put_num(s, "CELLS ", nc, "") || !put_num(s, " ", size, "\n")) return 0;
    for (size_t c = 0; c < nc; c++) {
        /* 27 indices of at most 10 digits: within MAXREC. */
        char *p = coons__sink_room(s, COONS__SINK_MAXREC), *p0 = p;
        if (!p) return 0;
        unsigned n = coons__vtk_cell(cell + npc * c, npc, nodes, &type);
        p += coons__fmt_u64(p, n);
        for (unsigned k = 0; k < n; k++) {
            *p++ = ' ';
            p += coons__fmt_u64(p, nodes[k]);
        }
        *p++ = '\n';
        s->len += (size_t)(p - p0);
    }
    if (!put_num(s, "CELL_TYPES ", nc, "\n")) return 0;
    for (size_t c = 0; c < nc; c++) {
        char *p = coons__sink_room(s, 8), *p0 = p;
        if (!p) return 0;
        coons__vtk_cell(cell + npc * c, npc, nodes, &type);
        p += coons__fmt_u64(p, type);
        *p++ = '\n';
        s->len += (size_t)(p - p0);
    }
    return 1;
}

static int put_fields(const coons_volume_mesh *vm, coons_field_location loc, coons__sink *s)
{
    size_t nf = coons_volume_mesh_field_count(vm, loc);
    size_t n = loc == COONS_FIELD_NODE ? coons_volume_mesh_node_count(vm)
                                       : coons_volume_mesh_cell_count(vm);
    if (!nf) return 1;
    if (!put_num(s, loc == COONS_FIELD_NODE ? "POINT_DATA " : "CELL_DATA ", n, "\n")) return 0;
    for (size_t f = 0; f < nf; f++) {
        coons_field_type type;
        const void *values;
        const char *name = coons_volume_mesh_field(vm, loc, f, &type, &values);
        int f64 = type == COONS_FIELD_FLOAT64;
        if (!coons__sink_puts(s, "SCALARS ") || !coons__sink_puts(s, name) ||
            !coons__sink_puts(s, f64 ? " double 1\nLOOKUP_TABLE default\n"
                                     : " int 1\nLOOKUP_TABLE default\n"))
            return 0;
        for (size_t i = 0; i < n; i++) {
            char *p = coons__sink_room(s, COONS__FMT_MAX + 2), *p0 = p;
            if (!p) return 0;
            if (f64) {
                p += coons__fmt_double(p, ((const double *)values)[i]);
            } else {
                int32_t v = ((const int32_t *)values)[i];
                if (v < 0) *p++ = '-';
                p += coons__fmt_u64(p, v < 0 ? (uint64_t)(-(int64_t)v) : (uint64_t)v);
            }
            *p++ = '\n';
            s->len += (size_t)(p - p0);
        }
    }
    return 1;
}

coons_status coons__write_vtk(const coons_volume_mesh *vm, const coons__wopts *o, coons__sink *s)
{
    if (put_header(vm, o, s) && put_points(vm, s) && put_cells(vm, s) &&
        put_fields(vm, COONS_FIELD_NODE, s))
        put_fields(vm, COONS_FIELD_CELL, s);
    return s->status;
}
