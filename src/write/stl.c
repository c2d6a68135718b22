/* SPDX-License-Identifier: GPL-3.0-or-later */
/* STL writers, binary and ASCII (the de-facto format of 3D Systems' 1989
 * StereoLithography Interface Specification: per facet a normal and three
 * vertices, counter-clockwise seen from outside).
 *
 * Binary STL stores IEEE float32; it is written byte by byte in
 * little-endian order so the output does not depend on the host. The ASCII
 * writer prints the same float32 values (coons__fmt_float), so both STL
 * flavours of one mesh describe bit-identical geometry, and shared vertices
 * stay shared after rounding (rounding is per vertex). Normals are
 * computed in double from the double vertices and then rounded. */
#include <float.h>
#include <math.h>

#include "coons/version.h"
#include "writer.h"

static inline unsigned char *put_u32(unsigned char *p, uint32_t u)
{
    p[0] = (unsigned char)(u & 0xffu);
    p[1] = (unsigned char)((u >> 8) & 0xffu);
    p[2] = (unsigned char)((u >> 16) & 0xffu);
    p[3] = (unsigned char)((u >> 24) & 0xffu);
    return p + 4;
}

static inline unsigned char *put_f32(unsigned char *p, double v)
{
    float f = (float)v;
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return put_u32(p, u);
}

/* x rounded to float32, as the file stores it. Through a volatile: GCC 12
 * at -O3 vectorises (double)(float)x over a vertex's coordinates and drops
 * the rounding of all but the last (seen in this file's object code). */
static double as_f32(double x)
{
    volatile float f = (float)x;
    return (double)f;
}

/* Unit normal of (a, b, c) as the file stores them, float32 (outputs.md:
 * "STL facet normals are computed from the stored float32 vertices"; a
 * normal from the double vertices disagrees with the stored facet where
 * rounding turns a thin triangle, which admesh then "fixes"), in double,
 * or 0 for a triangle degenerate in float32. */
static void facet_normal(double n[3], const double *a, const double *b, const double *c)
{
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        double fa = as_f32(a[k]);
        e1[k] = as_f32(b[k]) - fa;
        e2[k] = as_f32(c[k]) - fa;
    }
    v3_cross(n, e1, e2);
    double len = v3_norm(n);
    if (len > 0.0 && isfinite(len))
        v3_scale(n, n, 1.0 / len);
    else
        v3_zero(n);
}

/* STL stores float32: a larger coordinate would become infinite, and a
 * part whose largest coordinate is below 2^23 times the smallest normal
 * float32 would lose its 24 bits of precision (subnormals) or become 0. A
 * single tiny coordinate in a part of ordinary size is harmless. */
coons_status coons__check_stl(const coons_mesh *m, coons_error *err)
{
    const double *xyz = coons_mesh_vertices(m);
    double big = 0;
    size_t n = 3 * coons_mesh_vertex_count(m);
    for (size_t i = 0; i < n; i++) {
        if (fabs(xyz[i]) > FLT_MAX)
            return coons__error_set(err, COONS_E_LIMIT,
                                    "vertex %zu has the coordinate %.17g, outside the range "
                                    "of STL's 32-bit floats (+-%.9g): write OFF or SCAD, "
                                    "which keep doubles",
                                    i / 3, xyz[i], (double)FLT_MAX);
        big = fmax(big, fabs(xyz[i]));
    }
    const double small = ldexp((double)FLT_MIN, 23);
    if (n && big > 0 && big < small)
        return coons__error_set(err, COONS_E_LIMIT,
                                "the largest coordinate, %.17g, is below %.9g: STL's 32-bit "
                                "floats would lose the mesh's precision there (subnormal "
                                "numbers); write OFF or SCAD, which keep doubles, or use "
                                "larger units",
                                big, small);
    return COONS_OK;
}

static int starts_with_solid(const char *h)
{
    while (*h == ' ') h++;
    const char *w = "solid";
    for (int i = 0; i < 5; i++)
        if (h[i] == '\0' || (h[i] | 0x20) != w[i]) return 0;
    return 1;
}

coons_status coons__write_stl_binary(const coons_mesh *m, const coons__wopts *o, coons__sink *s)
{
    /* Header: the text, then " units=U" (kept whole: the text is cut
     * first), NUL-padded to 80 bytes, never starting with "solid" since
     * some readers then take the file for ASCII. */
    unsigned char header[80];
    char text[81], units[81];
    memset(header, 0, sizeof header);
    units[0] = '\0';
    if (o->units[0]) {
        char u[72];
        coons__clean_text(u, sizeof u, o->units);
        snprintf(units, sizeof units, " units=%s", u);
    }
    coons__clean_text(text, sizeof text, o->header);
    char full[200];
    snprintf(full, sizeof full, "%s%s", starts_with_solid(text) ? "libcoons: " : "", text);
    size_t ul = strlen(units), fl = strlen(full);
    if (ul > 80) ul = 80;
    if (fl > 80 - ul) fl = 80 - ul;
    memcpy(header, full, fl);
    memcpy(header + fl, units, ul);
    size_t nt = coons_mesh_triangle_count(m);
    unsigned char count[4];
    put_u32(count, (uint32_t)nt);
    if (!coons__sink_put(s, header, sizeof header) || !coons__sink_put(s, count, sizeof count))
        return s->status;
    const double *xyz = coons_mesh_vertices(m);
    const uint32_t *tri = coons_mesh_triangles(m);
    for (size_t t = 0; t < nt; t++) {
        unsigned char *p = (unsigned char *)coons__sink_room(s, 50);
        if (!p) return s->status;
        const double *a = xyz + 3 * (size_t)tri[3 * t], *b = xyz + 3 * (size_t)tri[3 * t + 1],
                     *c = xyz + 3 * (size_t)tri[3 * t + 2];
        double n[3];
        facet_normal(n, a, b, c);
        for (int i = 0; i < 3; i++) p = put_f32(p, n[i]);
        for (int i = 0; i < 3; i++) p = put_f32(p, a[i]);
        for (int i = 0; i < 3; i++) p = put_f32(p, b[i]);
        for (int i = 0; i < 3; i++) p = put_f32(p, c[i]);
        p[0] = p[1] = 0; /* attribute byte count */
        s->len += 50;
    }
    return s->status;
}

/* One token for `solid NAME`: blanks and control characters become '_'. */
static void solid_name(char *out, size_t cap, const char *name)
{
    size_t n = coons__clean_text(out, cap, name);
    for (size_t i = 0; i < n; i++)
        if (out[i] == ' ') out[i] = '_';
    if (n == 0) snprintf(out, cap, "coons_model");
}

static char *put_xyz(char *p, const double v[3])
{
    for (int i = 0; i < 3; i++) {
        *p++ = ' ';
        p += coons__fmt_float(p, (float)v[i]);
    }
    return p;
}

/* Each vertex's " x y z" text, formatted once: a vertex of a closed mesh
 * is shared by about six triangles, and formatting dominates the ASCII
 * writer. Slot: a length byte, then at most 3 * 16 bytes (a float's text
 * is at most 15 characters). NULL if memory is short: then every use
 * formats again. */
#define SLOT 50
static unsigned char *vertex_texts(const coons_mesh *m)
{
    size_t nv = coons_mesh_vertex_count(m);
    unsigned char *slots = coons__malloc_array(nv ? nv : 1, SLOT);
    if (!slots) return NULL;
    const double *xyz = coons_mesh_vertices(m);
    for (size_t v = 0; v < nv; v++) {
        unsigned char *sl = slots + SLOT * v;
        sl[0] = (unsigned char)(put_xyz((char *)sl + 1, xyz + 3 * v) - (char *)(sl + 1));
    }
    return slots;
}

coons_status coons__write_stl_ascii(const coons_mesh *m, const coons__wopts *o, coons__sink *s)
{
    char name[256];
    solid_name(name, sizeof name, o->name);
    if (!coons__sink_puts(s, "solid ") || !coons__sink_puts(s, name) || !coons__sink_puts(s, "\n"))
        return s->status;
    size_t nt = coons_mesh_triangle_count(m);
    const double *xyz = coons_mesh_vertices(m);
    const uint32_t *tri = coons_mesh_triangles(m);
    unsigned char *texts = vertex_texts(m);
    static const char fn[] = "  facet normal", ol[] = "\n    outer loop\n", vx[] = "      vertex",
                      el[] = "    endloop\n  endfacet\n";
    for (size_t t = 0; t < nt; t++) {
        /* A facet is 7 lines of < 64 bytes: within MAXREC. */
        char *p = coons__sink_room(s, COONS__SINK_MAXREC), *p0 = p;
        if (!p) break;
        const double *v[3] = {xyz + 3 * (size_t)tri[3 * t], xyz + 3 * (size_t)tri[3 * t + 1],
                              xyz + 3 * (size_t)tri[3 * t + 2]};
        double n[3];
        facet_normal(n, v[0], v[1], v[2]);
        memcpy(p, fn, sizeof fn - 1);
        p = put_xyz(p + sizeof fn - 1, n);
        memcpy(p, ol, sizeof ol - 1);
        p += sizeof ol - 1;
        for (int k = 0; k < 3; k++) {
            memcpy(p, vx, sizeof vx - 1);
            p += sizeof vx - 1;
            if (texts) {
                const unsigned char *sl = texts + SLOT * (size_t)tri[3 * t + (size_t)k];
                memcpy(p, sl + 1, sl[0]);
                p += sl[0];
            } else {
                p = put_xyz(p, v[k]);
            }
            *p++ = '\n';
        }
        memcpy(p, el, sizeof el - 1);
        p += sizeof el - 1;
        s->len += (size_t)(p - p0);
    }
    coons__free(texts);
    if (!coons__sink_puts(s, "endsolid ") || !coons__sink_puts(s, name)) return s->status;
    coons__sink_puts(s, "\n");
    return s->status;
}
