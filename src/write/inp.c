/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Abaqus / CalculiX input deck writer (COONS_FORMAT_INP): the model data
 * of a deck, without material, boundary conditions or steps (Abaqus
 * Keywords Reference Guide: *HEADING, *NODE, *ELEMENT, *ELSET, *NSET,
 * *SURFACE; CalculiX CrunchiX User's Manual, "Input deck format" and the
 * same keyword sections). Keyword lines start with '*', comments with "**";
 * data lines hold at most 16 comma-separated entries, and an element whose
 * entries do not fit continues on the next line, the previous one ending
 * with a comma (Abaqus rule; CalculiX's splitline.f refuses more than 16).
 *
 * Node order: corners as in the mesh (the corner order Gmsh and Abaqus
 * share); C3D20's edge nodes are 9-12 on the edges 1-2 2-3 3-4 4-1, 13-16 on
 * 5-6 6-7 7-8 8-5, 17-20 on 1-5 2-6 3-7 4-8 (Abaqus "Three-dimensional solid
 * element library", CalculiX "C3D20"), permuted from Gmsh's order by
 * GMSH_OF_ABQ. Face labels S1 = 1-2-3-4, S2 = 5-8-7-6, S3 = 1-5-6-2,
 * S4 = 2-6-7-3, S5 = 3-7-8-4, S6 = 4-8-5-1 (CalculiX *SURFACE); C3D6 wedges
 * (hex8 cells with two collapsed parallel edges, src/volume/cell_shape.c) use Gmsh's
 * prism order, which is CalculiX's positive orientation (ccx rejects the
 * mirrored one with "nonpositive jacobian"), with faces S1 = 1-2-3,
 * S2 = 4-5-6, S3 = 1-2-5-4, S4 = 2-3-6-5, S5 = 3-1-4-6.
 *
 * CalculiX reads a coordinate from the first 20 characters of its field
 * (nodes.f: read(textpart(2)(1:20),'(f20.0)')) and a name of at most 80:
 * numbers are the shortest round-trip text when it fits in 20 characters,
 * else the most significant digits that fit; longer names are refused. */
#include <stdlib.h>

#include "writer.h"

#define NAME_MAX_INP 80 /* CalculiX and Abaqus limit of set and surface names */
#define FIELD 20        /* CalculiX reads at most 20 characters of a number */
#define PER_LINE 16     /* entries per data line */
#define ID_MAX 2147483647u /* labels are Fortran default (32-bit) integers */

/* Abaqus node k of a cell is the mesh's (Gmsh) node GMSH_OF_ABQ[k]. */
static const unsigned char GMSH_OF_ABQ[20] = {0, 1,  2,  3, 4,  5,  6,  7,  8,  11,
                                              13, 9, 16, 18, 19, 17, 10, 12, 14, 15};
/* The mesh's local faces (coons/volume.h: r0 r1 s0 s1 t0 t1) by corners,
 * and the Abaqus label of each: r=0 is 4-8-5-1 (S6), r=1 2-6-7-3 (S4),
 * s=0 1-5-6-2 (S3), s=1 3-7-8-4 (S5), t=0 1-2-3-4 (S1), t=1 5-8-7-6 (S2). */
static const unsigned char LOCAL_FACE[6][4] = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4},
                                               {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};
static const unsigned char LABEL_OF_LOCAL[6] = {6, 4, 3, 5, 1, 2};
/* C3D6 faces S1..S5 by wedge node (0-based); -1 ends a triangle. */
static const signed char WEDGE_FACE[5][4] = {
    {0, 1, 2, -1}, {3, 4, 5, -1}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};

static void sort_small(uint32_t *v, int n)
{
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && v[j - 1] > v[j]; j--) {
            uint32_t t = v[j];
            v[j] = v[j - 1];
            v[j - 1] = t;
        }
}

/* Distinct values of v[0..n) sorted into out; returns their number. */
static int distinct_sorted(const uint32_t *v, int n, uint32_t *out)
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        int dup = 0;
        for (int j = 0; j < m; j++) dup |= out[j] == v[i];
        if (!dup) out[m++] = v[i];
    }
    sort_small(out, m);
    return m;
}

/* Element type of cell c (its nodes in `out`, Abaqus order): 8 C3D8,
 * 20 C3D20, 6 C3D6. */
static int cell_nodes(const coons_volume_mesh *vm, size_t c, uint32_t out[20])
{
    size_t npc = coons_volume_mesh_nodes_per_cell(vm);
    const uint32_t *h = coons_volume_mesh_cells(vm) + npc * c;
    if (npc == 8) {
        uint32_t shaped[8];
        /* Pyramids and other degenerate cells stay C3D8 with repeated
         * nodes: CalculiX has no pyramid element. */
        if (coons__hex8_shape(h, shaped) == COONS__SHAPE_WEDGE) {
            memcpy(out, shaped, 6 * sizeof *out);
            return 6;
        }
    }
    for (size_t k = 0; k < npc; k++) out[k] = h[GMSH_OF_ABQ[k]];
    return (int)npc;
}

/* The Abaqus label (1..6) of local face f of cell c, or 0 when the face
 * has collapsed to a line or a point (no face to name). */
static int face_label(const coons_volume_mesh *vm, size_t c, unsigned f)
{
    size_t npc = coons_volume_mesh_nodes_per_cell(vm);
    const uint32_t *h = coons_volume_mesh_cells(vm) + npc * c;
    uint32_t corner[4], want[4];
    for (int k = 0; k < 4; k++) corner[k] = h[LOCAL_FACE[f][k]];
    int m = distinct_sorted(corner, 4, want);
    if (m < 3) return 0;
    uint32_t w[20];
    if (cell_nodes(vm, c, w) != 6) return LABEL_OF_LOCAL[f];
    for (int k = 0; k < 5; k++) {
        uint32_t v[4], got[4];
        int n = WEDGE_FACE[k][3] < 0 ? 3 : 4;
        for (int i = 0; i < n; i++) v[i] = w[WEDGE_FACE[k][i]];
        if (distinct_sorted(v, n, got) == m && !memcmp(got, want, (size_t)m * sizeof *got))
            return k + 1;
    }
    return 0; /* unreachable: every face of a wedge is a face of its hexahedron */
}

/* The set name of `name` (upper-cased, every byte but A-Z 0-9 _ -> _) with
 * `suffix` appended, into out[cap]; returns its length (may exceed cap-1,
 * then out is cut). */
static size_t inp_name(char *out, size_t cap, const char *name, const char *suffix)
{
    size_t n = 0;
    for (const char *p = name; *p; p++, n++) {
        char ch = *p;
        if (ch >= 'a' && ch <= 'z') ch = (char)(ch - 32);
        if (!((ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_')) ch = '_';
        if (n + 1 < cap) out[n] = ch;
    }
    for (const char *p = suffix; *p; p++, n++)
        if (n + 1 < cap) out[n] = *p;
    out[n < cap ? n : cap - 1] = '\0';
    return n;
}

/* ---- names and their collisions ---------------------------------------- */

enum { NS_ELSET, NS_NSET, NS_SURFACE };
static const char *const NS_WORD[3] = {"element set", "node set", "surface"};

typedef struct inp_entry {
    int ns;
    char name[NAME_MAX_INP + 1];
    const char *what;   /* "part", "cell set", ... */
    const char *origin; /* the mesh's name */
    int label;          /* helper element sets: the face label; else 0 */
} inp_entry;

typedef struct inp_names {
    inp_entry *e;
    size_t n, cap;
} inp_names;

static coons_status add_name(inp_names *t, int ns, const char *what, const char *origin,
                             const char *suffix, int label, coons_error *err)
{
    if (t->n == t->cap) {
        size_t cap = t->cap ? 2 * t->cap : 64;
        inp_entry *e = coons__realloc(t->e, cap * sizeof *e);
        if (!e) return coons__error_set(err, COONS_E_NOMEM, "out of memory");
        t->e = e, t->cap = cap;
    }
    inp_entry *x = &t->e[t->n++];
    x->ns = ns, x->what = what, x->origin = origin, x->label = label;
    if (inp_name(x->name, sizeof x->name, origin, suffix) > NAME_MAX_INP)
        return coons__error_set(err, COONS_E_UNSUPPORTED,
                                "the .inp %s name of %s '%s' is longer than %d characters",
                                NS_WORD[ns], what, origin, NAME_MAX_INP);
    return COONS_OK;
}

static int cmp_entry(const void *a, const void *b)
{
    const inp_entry *x = a, *y = b;
    if (x->ns != y->ns) return x->ns < y->ns ? -1 : 1;
    return strcmp(x->name, y->name);
}

/* Whether cell set `items` is exactly the cells of part p, in order. */
static int is_part(const coons_volume_mesh *vm, size_t p, const uint32_t *items, size_t n)
{
    const uint32_t *part = coons_volume_mesh_cell_parts(vm);
    size_t k = 0;
    for (size_t c = 0; c < coons_volume_mesh_cell_count(vm); c++)
        if (part[c] == p && (k >= n || items[k++] != c)) return 0;
    return k == n;
}

/* Cell set i is written unless it repeats a part (the mesher's set of a
 * body's cells, named after the body). */
static int cell_set_written(const coons_volume_mesh *vm, size_t i)
{
    const uint32_t *items;
    size_t n;
    const char *name = coons_volume_mesh_cell_set(vm, i, &items, &n);
    for (size_t p = 0; p < coons_volume_mesh_part_count(vm); p++)
        if (!strcmp(name, coons_volume_mesh_part_name(vm, p))) return !is_part(vm, p, items, n);
    return 1;
}

/* Bit mask of the labels (bit k: label k) face set i uses. */
static unsigned face_set_labels(const coons_volume_mesh *vm, size_t i)
{
    const uint32_t *pairs;
    size_t n;
    coons_volume_mesh_face_set(vm, i, &pairs, &n);
    unsigned mask = 0;
    for (size_t k = 0; k < n; k++) mask |= 1u << face_label(vm, pairs[2 * k], pairs[2 * k + 1]);
    return mask & ~1u;
}

static const char *const LABEL_SUFFIX[7] = {"", "_S1", "_S2", "_S3", "_S4", "_S5", "_S6"};

/* Every name the deck defines, or the error of two that collide. */
static coons_status collect_names(const coons_volume_mesh *vm, inp_names *t, coons_error *err)
{
    coons_status st = add_name(t, NS_ELSET, "the set of all elements", "EALL", "", 0, err);
    if (!st) st = add_name(t, NS_NSET, "the set of all nodes", "NALL", "", 0, err);
    for (size_t p = 0; p < coons_volume_mesh_part_count(vm) && !st; p++)
        st = add_name(t, NS_ELSET, "part", coons_volume_mesh_part_name(vm, p), "", 0, err);
    for (size_t i = 0; i < coons_volume_mesh_cell_set_count(vm) && !st; i++)
        if (cell_set_written(vm, i))
            st = add_name(t, NS_ELSET, "cell set", coons_volume_mesh_cell_set(vm, i, NULL, NULL),
                          "", 0, err);
    for (size_t i = 0; i < coons_volume_mesh_node_set_count(vm) && !st; i++)
        st = add_name(t, NS_NSET, "node set", coons_volume_mesh_node_set(vm, i, NULL, NULL), "",
                      0, err);
    for (size_t i = 0; i < coons_volume_mesh_face_set_count(vm) && !st; i++) {
        const char *name = coons_volume_mesh_face_set(vm, i, NULL, NULL);
        st = add_name(t, NS_SURFACE, "face set", name, "_S", 0, err);
        unsigned mask = face_set_labels(vm, i);
        for (int k = 1; k <= 6 && !st; k++)
            if (mask & (1u << k))
                st = add_name(t, NS_ELSET, "face set", name, LABEL_SUFFIX[k], k, err);
    }
    if (st) return st;
    qsort(t->e, t->n, sizeof *t->e, cmp_entry);
    for (size_t i = 1; i < t->n; i++) {
        const inp_entry *a = &t->e[i - 1], *b = &t->e[i];
        if (a->ns != b->ns || strcmp(a->name, b->name)) continue;
        char la[48] = "", lb[48] = "";
        if (a->label) snprintf(la, sizeof la, " (its elements with faces S%d)", a->label);
        if (b->label) snprintf(lb, sizeof lb, " (its elements with faces S%d)", b->label);
        return coons__error_set(err, COONS_E_INVALID,
                                "%s '%s'%s and %s '%s'%s both become the .inp %s name %s",
                                a->what, a->origin, la, b->what, b->origin, lb, NS_WORD[a->ns],
                                a->name);
    }
    return COONS_OK;
}

coons_status coons__check_inp(const coons_volume_mesh *vm, coons_error *err)
{
    if (coons_volume_mesh_element(vm) == COONS_ELEMENT_HEX27)
        return coons__error_set(err, COONS_E_UNSUPPORTED,
                                "the .inp format holds hex8 (C3D8) and hex20 (C3D20) cells "
                                "only, not hex27");
    if (coons_volume_mesh_node_count(vm) > ID_MAX || coons_volume_mesh_cell_count(vm) > ID_MAX)
        return coons__error_set(err, COONS_E_LIMIT,
                                "the .inp format numbers nodes and elements up to %u",
                                ID_MAX);
    inp_names t = {NULL, 0, 0};
    coons_status st = collect_names(vm, &t, err);
    coons__free(t.e);
    return st;
}

/* ---- output ------------------------------------------------------------ */

/* Drops the '+' and leading zeros of an exponent: "1e-05" -> "1e-5". */
static size_t compact_exponent(char *s, size_t n)
{
    char *e = strchr(s, 'e');
    if (!e) return n;
    char *d = e + 1, *w = e + 1;
    if (*d == '+') d++;
    else if (*d == '-') *w++ = *d++;
    while (*d == '0' && d[1]) d++;
    while (*d) *w++ = *d++;
    *w = '\0';
    return (size_t)(w - s);
}

/* A number that fits CalculiX's 20-character field: the shortest
 * round-trip text, or failing that the most digits that fit: 15 for
 * exponents of one digit ("-1.23456789012346e-5"), 13 at worst
 * ("-1.234567890123e-300"). */
static size_t fmt_field(char *out, double v)
{
    size_t n = coons__fmt_double(out, v);
    if (n <= FIELD) return n;
    n = compact_exponent(out, n);
    for (int p = 17; n > FIELD && p > 0; p--) {
        int w = snprintf(out, COONS__FMT_MAX, "%.*g", p, v);
        n = compact_exponent(out, w > 0 ? (size_t)w : 0);
    }
    return n;
}

static int put_line(coons__sink *s, const char *a, const char *b, const char *c)
{
    return coons__sink_puts(s, a) && coons__sink_puts(s, b) && coons__sink_puts(s, c) &&
           coons__sink_puts(s, "\n");
}

/* The 1-based ids v[i] + 1, PER_LINE a line. */
static int put_ids(coons__sink *s, const uint32_t *v, size_t n)
{
    for (size_t i = 0; i < n; i += PER_LINE) {
        char *p = coons__sink_room(s, PER_LINE * 12 + 1), *p0 = p;
        if (!p) return 0;
        for (size_t k = i; k < n && k < i + PER_LINE; k++) {
            if (k > i) *p++ = ',', *p++ = ' ';
            p += coons__fmt_u64(p, (uint64_t)v[k] + 1);
        }
        *p++ = '\n';
        s->len += (size_t)(p - p0);
    }
    return 1;
}

static int put_heading(const coons__wopts *o, coons__sink *s)
{
    /* Abaqus reads at most 256 characters a line. */
    char header[200], name[120], units[64];
    coons__clean_text(header, sizeof header, o->header);
    coons__clean_text(name, sizeof name, o->name);
    coons__clean_text(units, sizeof units, o->units);
    /* "model=" first: a heading line must not start with '*'. */
    return put_line(s, "** ", header, "") && coons__sink_puts(s, "*HEADING\nmodel=") &&
           coons__sink_puts(s, name) && (!units[0] || coons__sink_puts(s, " units=")) &&
           coons__sink_puts(s, units) && coons__sink_puts(s, "\n");
}

static int put_nodes(const coons_volume_mesh *vm, coons__sink *s)
{
    size_t n = coons_volume_mesh_node_count(vm);
    const double *xyz = coons_volume_mesh_nodes(vm);
    if (n && !coons__sink_puts(s, "*NODE, NSET=NALL\n")) return 0;
    for (size_t v = 0; v < n; v++) {
        char *p = coons__sink_room(s, 12 + 3 * (COONS__FMT_MAX + 2)), *p0 = p;
        if (!p) return 0;
        p += coons__fmt_u64(p, (uint64_t)v + 1);
        for (int k = 0; k < 3; k++) {
            *p++ = ',', *p++ = ' ';
            p += fmt_field(p, xyz[3 * v + (size_t)k]);
        }
        *p++ = '\n';
        s->len += (size_t)(p - p0);
    }
    return 1;
}

/* The *ELEMENT block of the cells whose type is `type`; element c + 1 is
 * cell c whatever its block. */
static int put_elements(const coons_volume_mesh *vm, int type, coons__sink *s)
{
    int started = 0;
    for (size_t c = 0; c < coons_volume_mesh_cell_count(vm); c++) {
        uint32_t nodes[20];
        int n = cell_nodes(vm, c, nodes);
        if (n != type) continue;
        if (!started) {
            started = 1;
            const char *t = type == 6 ? "C3D6" : type == 8 ? "C3D8" : "C3D20";
            if (!put_line(s, "*ELEMENT, TYPE=", t, ", ELSET=EALL")) return 0;
        }
        char *p = coons__sink_room(s, 21 * 12 + 2), *p0 = p;
        if (!p) return 0;
        p += coons__fmt_u64(p, (uint64_t)c + 1);
        for (int k = 0; k < n; k++) {
            /* 16 entries a line, the element number included; a line that
             * is continued ends with a comma. */
            *p++ = ',';
            *p++ = (k + 1) % PER_LINE ? ' ' : '\n';
            p += coons__fmt_u64(p, (uint64_t)nodes[k] + 1);
        }
        *p++ = '\n';
        s->len += (size_t)(p - p0);
    }
    return 1;
}

static int put_set(coons__sink *s, const char *keyword, const char *name, const char *suffix,
                   const uint32_t *v, size_t n)
{
    char nm[NAME_MAX_INP + 1];
    inp_name(nm, sizeof nm, name, suffix);
    return put_line(s, keyword, nm, "") && put_ids(s, v, n);
}

static int put_parts(const coons_volume_mesh *vm, coons__sink *s)
{
    size_t nc = coons_volume_mesh_cell_count(vm);
    const uint32_t *part = coons_volume_mesh_cell_parts(vm);
    uint32_t *ids = coons__malloc_array(nc ? nc : 1, sizeof *ids);
    if (!ids) {
        s->status = coons__error_set(s->err, COONS_E_NOMEM, "out of memory");
        return 0;
    }
    int ok = 1;
    for (size_t p = 0; p < coons_volume_mesh_part_count(vm) && ok; p++) {
        size_t n = 0;
        for (size_t c = 0; c < nc; c++)
            if (part[c] == p) ids[n++] = (uint32_t)c;
        ok = put_set(s, "*ELSET, ELSET=", coons_volume_mesh_part_name(vm, p), "", ids, n);
    }
    coons__free(ids);
    for (size_t i = 0; i < coons_volume_mesh_cell_set_count(vm) && ok; i++) {
        const uint32_t *v;
        size_t n;
        const char *name = coons_volume_mesh_cell_set(vm, i, &v, &n);
        if (cell_set_written(vm, i)) ok = put_set(s, "*ELSET, ELSET=", name, "", v, n);
    }
    for (size_t i = 0; i < coons_volume_mesh_node_set_count(vm) && ok; i++) {
        const uint32_t *v;
        size_t n;
        const char *name = coons_volume_mesh_node_set(vm, i, &v, &n);
        ok = put_set(s, "*NSET, NSET=", name, "", v, n);
    }
    return ok;
}

/* Per face set: an element set per label used (BODY_FACE_S1 ...), then
 * the surface BODY_FACE_S naming each with its label. */
static int put_face_sets(const coons_volume_mesh *vm, coons__sink *s)
{
    for (size_t i = 0; i < coons_volume_mesh_face_set_count(vm); i++) {
        const uint32_t *pairs;
        size_t n;
        const char *name = coons_volume_mesh_face_set(vm, i, &pairs, &n);
        unsigned mask = face_set_labels(vm, i);
        for (int k = 1; k <= 6; k++) {
            if (!(mask & (1u << k))) continue;
            char nm[NAME_MAX_INP + 1];
            inp_name(nm, sizeof nm, name, LABEL_SUFFIX[k]);
            if (!put_line(s, "*ELSET, ELSET=", nm, "")) return 0;
            uint32_t line[PER_LINE];
            size_t m = 0;
            for (size_t f = 0; f < n; f++) {
                if (face_label(vm, pairs[2 * f], pairs[2 * f + 1]) != k) continue;
                line[m++] = pairs[2 * f];
                if (m == PER_LINE && !put_ids(s, line, m)) return 0;
                m %= PER_LINE;
            }
            if (m && !put_ids(s, line, m)) return 0;
        }
        char nm[NAME_MAX_INP + 1];
        inp_name(nm, sizeof nm, name, "_S");
        if (!put_line(s, "*SURFACE, NAME=", nm, ", TYPE=ELEMENT")) return 0;
        for (int k = 1; k <= 6; k++) {
            if (!(mask & (1u << k))) continue;
            char set[NAME_MAX_INP + 1];
            inp_name(set, sizeof set, name, LABEL_SUFFIX[k]);
            if (!put_line(s, set, ", S", LABEL_SUFFIX[k] + 2)) return 0;
        }
    }
    return 1;
}

coons_status coons__write_inp(const coons_volume_mesh *vm, const coons__wopts *o, coons__sink *s)
{
    if (put_heading(o, s) && put_nodes(vm, s) && put_elements(vm, 8, s) &&
        put_elements(vm, 20, s) && put_elements(vm, 6, s) && put_parts(vm, s))
        put_face_sets(vm, s);
    return s->status;
}
