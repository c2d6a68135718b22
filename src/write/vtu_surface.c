/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Triangle meshes as a VTK XML UnstructuredGrid (VTK File Formats,
 * "XML File Formats": the UnstructuredGrid dataset, VTKFile version 1.0),
 * all data ASCII: Points (Float64, 3 components), Cells with Int64
 * connectivity and offsets and UInt8 types (5, VTK_TRIANGLE, counter-
 * clockwise seen from outside as in the mesh), CellData `part` (Int32, the
 * part index) and, when every part carries vertex parameters
 * (coons_mesh_vertex_parameters(), e.g. isoparametric surfaces), PointData
 * `u`, `v`, `w` (Float64). Part names and the header go into XML comments
 * before the dataset. Numbers are the shortest round-trip text (fmt.c). */
#include "writer.h"

/* An XML comment of `text`: control characters become spaces (clean_text)
 * and '-' becomes '_', since "--" may not occur inside a comment. */
static int comment(coons__sink *s, const char *label, const char *text)
{
    char buf[COONS__SINK_MAXREC];
    coons__clean_text(buf, sizeof buf - 64, text);
    for (char *c = buf; *c; c++)
        if (*c == '-') *c = '_';
    return coons__sink_puts(s, "<!-- ") && coons__sink_puts(s, label) &&
           coons__sink_puts(s, buf) && coons__sink_puts(s, " -->\n");
}

static int put_u64(coons__sink *s, uint64_t v, char sep)
{
    char *p = coons__sink_room(s, COONS__FMT_MAX + 1);
    if (!p) return 0;
    size_t n = coons__fmt_u64(p, v);
    p[n] = sep;
    s->len += n + 1;
    return 1;
}

static int put_double(coons__sink *s, double v, char sep)
{
    char *p = coons__sink_room(s, COONS__FMT_MAX + 1);
    if (!p) return 0;
    size_t n = coons__fmt_double(p, v);
    p[n] = sep;
    s->len += n + 1;
    return 1;
}

static int begin_array(coons__sink *s, const char *type, const char *name, int comps)
{
    char buf[160];
    snprintf(buf, sizeof buf, "        <DataArray type=\"%s\"%s%s%s", type, name ? " Name=\"" : "",
             name ? name : "", name ? "\"" : "");
    if (!coons__sink_puts(s, buf)) return 0;
    if (comps > 1) {
        snprintf(buf, sizeof buf, " NumberOfComponents=\"%d\"", comps);
        if (!coons__sink_puts(s, buf)) return 0;
    }
    return coons__sink_puts(s, " format=\"ascii\">\n");
}

static int end_array(coons__sink *s) { return coons__sink_puts(s, "        </DataArray>\n"); }

coons_status coons__write_vtu_surface(const coons_mesh *m, const coons__wopts *o, coons__sink *s)
{
    size_t nv = coons_mesh_vertex_count(m), nt = coons_mesh_triangle_count(m);
    size_t np = coons_mesh_part_count(m);
    const double *xyz = coons_mesh_vertices(m), *uvw = coons_mesh_vertex_parameters(m);
    const uint32_t *tri = coons_mesh_triangles(m);
    char buf[160];
    coons__sink_puts(s, "<?xml version=\"1.0\"?>\n");
    comment(s, "", o->header);
    if (o->units[0]) comment(s, "units: ", o->units);
    comment(s, "name: ", o->name);
    for (size_t i = 0; i < np; i++) {
        size_t tf, tc;
        coons_mesh_part_range(m, i, &tf, &tc, NULL, NULL);
        snprintf(buf, sizeof buf, "part %zu: cells %zu+%zu, name: ", i, tf, tc);
        comment(s, buf, coons_mesh_part_name(m, i));
    }
    coons__sink_puts(s, "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
                        "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                        "  <UnstructuredGrid>\n");
    snprintf(buf, sizeof buf, "    <Piece NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\">\n", nv,
             nt);
    coons__sink_puts(s, buf);
    if (uvw) {
        coons__sink_puts(s, "      <PointData Scalars=\"u\">\n");
        static const char *const names[3] = {"u", "v", "w"};
        for (int k = 0; k < 3 && s->status == COONS_OK; k++) {
            begin_array(s, "Float64", names[k], 1);
            for (size_t v = 0; v < nv; v++)
                if (!put_double(s, uvw[3 * v + (size_t)k], v + 1 == nv || v % 8 == 7 ? '\n' : ' '))
                    return s->status;
            end_array(s);
        }
        coons__sink_puts(s, "      </PointData>\n");
    }
    coons__sink_puts(s, "      <CellData Scalars=\"part\">\n");
    begin_array(s, "Int32", "part", 1);
    size_t t = 0;
    for (size_t i = 0; i < np; i++) {
        size_t tf, tc;
        coons_mesh_part_range(m, i, &tf, &tc, NULL, NULL);
        for (; t < tf + tc; t++)
            if (!put_u64(s, i, t + 1 == nt || t % 16 == 15 ? '\n' : ' ')) return s->status;
    }
    for (; t < nt; t++) /* a mesh without parts: all part 0 */
        if (!put_u64(s, 0, t + 1 == nt || t % 16 == 15 ? '\n' : ' ')) return s->status;
    end_array(s);
    coons__sink_puts(s, "      </CellData>\n      <Points>\n");
    begin_array(s, "Float64", NULL, 3);
    for (size_t v = 0; v < nv; v++)
        for (int k = 0; k < 3; k++)
            if (!put_double(s, xyz[3 * v + (size_t)k], k == 2 ? '\n' : ' ')) return s->status;
    end_array(s);
    coons__sink_puts(s, "      </Points>\n      <Cells>\n");
    begin_array(s, "Int64", "connectivity", 1);
    for (size_t i = 0; i < 3 * nt; i++)
        if (!put_u64(s, tri[i], i % 3 == 2 ? '\n' : ' ')) return s->status;
    end_array(s);
    begin_array(s, "Int64", "offsets", 1);
    for (size_t i = 0; i < nt; i++)
        if (!put_u64(s, 3 * (i + 1), i + 1 == nt || i % 16 == 15 ? '\n' : ' ')) return s->status;
    end_array(s);
    begin_array(s, "UInt8", "types", 1);
    for (size_t i = 0; i < nt; i++)
        if (!put_u64(s, 5, i + 1 == nt || i % 32 == 31 ? '\n' : ' ')) return s->status;
    end_array(s);
    coons__sink_puts(s, "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
    return s->status;
}
