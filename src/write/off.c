/* SPDX-License-Identifier: GPL-3.0-or-later */
/* OFF writer (Geomview's Object File Format): "OFF", the counts
 * "nv nf 0", one vertex per line, then "3 a b c" per triangle, 0-based,
 * counter-clockwise seen from outside. Vertices keep full double precision
 * (shortest round-trip text). Comment lines ('#') carrying the writer, the
 * units and the part ranges (so a multi-body mesh can be split again) come
 * after the last face: OpenMesh 9's reader, like other readers that stop
 * after the counted records, accepts them there but not after the "OFF"
 * line, where it reads nothing. */
#include "writer.h"

static int comment(coons__sink *s, const char *label, const char *text)
{
    char buf[COONS__SINK_MAXREC];
    coons__clean_text(buf, sizeof buf - 32, text);
    return coons__sink_puts(s, "# ") && coons__sink_puts(s, label) && coons__sink_puts(s, buf) &&
           coons__sink_puts(s, "\n");
}

coons_status coons__write_off(const coons_mesh *m, const coons__wopts *o, coons__sink *s)
{
    size_t nv = coons_mesh_vertex_count(m), nt = coons_mesh_triangle_count(m);
    if (!coons__sink_puts(s, "OFF\n")) return s->status;
    char *p = coons__sink_room(s, 64), *p0 = p;
    if (!p) return s->status;
    p += coons__fmt_u64(p, nv);
    *p++ = ' ';
    p += coons__fmt_u64(p, nt);
    memcpy(p, " 0\n", 3);
    s->len += (size_t)(p + 3 - p0);

    const double *xyz = coons_mesh_vertices(m);
    for (size_t v = 0; v < nv; v++) {
        p = p0 = coons__sink_room(s, 3 * COONS__FMT_MAX + 1);
        if (!p) return s->status;
        for (int k = 0; k < 3; k++) {
            p += coons__fmt_double(p, xyz[3 * v + (size_t)k]);
            *p++ = k < 2 ? ' ' : '\n';
        }
        s->len += (size_t)(p - p0);
    }
    const uint32_t *tri = coons_mesh_triangles(m);
    for (size_t t = 0; t < nt; t++) {
        p = p0 = coons__sink_room(s, 40);
        if (!p) return s->status;
        *p++ = '3';
        for (int k = 0; k < 3; k++) {
            *p++ = ' ';
            p += coons__fmt_u64(p, tri[3 * t + (size_t)k]);
        }
        *p++ = '\n';
        s->len += (size_t)(p - p0);
    }
    if (!comment(s, "", o->header)) return s->status;
    if (o->units[0] && !comment(s, "units: ", o->units)) return s->status;
    if (!comment(s, "name: ", o->name)) return s->status;
    for (size_t i = 0; i < coons_mesh_part_count(m); i++) {
        size_t tf, tc, vf, vc;
        coons_mesh_part_range(m, i, &tf, &tc, &vf, &vc);
        char buf[160];
        snprintf(buf, sizeof buf, "part %zu: vertices %zu+%zu, faces %zu+%zu, name: ", i, vf, vc,
                 tf, tc);
        if (!comment(s, buf, coons_mesh_part_name(m, i))) return s->status;
    }
    return s->status;
}
