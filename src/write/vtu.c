/* SPDX-License-Identifier: GPL-3.0-or-later */
/* VTK XML UnstructuredGrid writer, version 1.0 (Kitware, "VTK File
 * Formats", section "XML File Formats": the UnstructuredGrid dataset, its
 * Piece with PointData, CellData, Points and Cells, DataArray, and
 * AppendedData), in two encodings:
 *
 * - COONS_FORMAT_VTU (.vtu): every DataArray format="appended", their
 *   bytes in one <AppendedData encoding="base64"> section after the
 *   underscore. With header_type="UInt64" and no compressor, each array is
 *   [UInt64 byte count][raw little-endian values], base64-encoded (RFC 4648
 *   section 4, with padding) as one stream per array, and a DataArray's
 *   `offset` counts encoded characters from the one after the underscore:
 *   what VTK's own vtkXMLWriter writes and vtkXMLDataParser reads (checked
 *   against VTK 9.1's output for the same arrays).
 * - COONS_FORMAT_VTU_ASCII: the same document with format="ascii"
 *   DataArrays holding the values as text (shortest round-trip doubles).
 *
 * Points are Float64, connectivity and offsets Int64, types UInt8; the
 * mesh's node and cell fields are point and cell data in their order and
 * type (Float64, Int32). Hexahedra are VTK types 12, 25 and 29 in VTK's
 * node order (vtk_order.h). A hex8 cell with repeated corners is what
 * coons__hex8_shape() says: a wedge (13) or a pyramid (14) in VTK's order,
 * or else a degenerate hexahedron (12) as it is.
 *
 * Everything is streamed through the sink: the only copy made is one byte
 * per hex8 cell (its VTK type, classified once for the offsets, the
 * connectivity length and the types array); raw values are packed and
 * encoded 3 KiB at a time. The header text and the units go into an XML
 * comment before the VTKFile element. */
#include "vtk_order.h"
#include "writer.h"

/* Raw bytes packed before encoding; a multiple of 3 is encoded at a time,
 * so chunking does not change the text. */
#define RAW_CAP 3072

typedef struct vout {
    coons__sink *s;
    int ascii;
    unsigned char raw[RAW_CAP];
    size_t nraw;
    unsigned per_line, col; /* ascii: values per line, values on this one */
    char pair[4096][2];     /* the two characters of each 12-bit group */
} vout;

static const char B64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

static void b64_init(vout *o)
{
    for (unsigned v = 0; v < 4096; v++) {
        o->pair[v][0] = B64[v >> 6];
        o->pair[v][1] = B64[v & 63];
    }
}

/* Encodes n bytes (a multiple of 3 except at the end of an array) into
 * the sink; base64 is most of the writer's own time, hence two characters
 * per table look-up. */
static int b64_encode(vout *o, const unsigned char *d, size_t n)
{
    coons__sink *s = o->s;
    while (n > 0) {
        size_t k = n > 384 ? 384 : n; /* 384 bytes -> 512 characters */
        char *p = coons__sink_room(s, 512);
        if (!p) return 0;
        size_t i = 0;
        /* 6 bytes -> 8 characters at a time, read as one big-endian word
         * (compilers make the shifts one load and a byte swap). */
        for (; i + 8 <= k; i += 6) {
            const unsigned char *b = d + i;
            uint64_t v = (uint64_t)b[0] << 56 | (uint64_t)b[1] << 48 | (uint64_t)b[2] << 40 |
                         (uint64_t)b[3] << 32 | (uint64_t)b[4] << 24 | (uint64_t)b[5] << 16 |
                         (uint64_t)b[6] << 8 | (uint64_t)b[7];
            memcpy(p, o->pair[v >> 52], 2);
            memcpy(p + 2, o->pair[(v >> 40) & 4095], 2);
            memcpy(p + 4, o->pair[(v >> 28) & 4095], 2);
            memcpy(p + 6, o->pair[(v >> 16) & 4095], 2);
            p += 8;
        }
        for (; i + 3 <= k; i += 3) {
            unsigned v = (unsigned)d[i] << 16 | (unsigned)d[i + 1] << 8 | d[i + 2];
            memcpy(p, o->pair[v >> 12], 2);
            memcpy(p + 2, o->pair[v & 4095], 2);
            p += 4;
        }
        if (i < k) { /* 1 or 2 bytes left: the end of the stream */
            unsigned v = (unsigned)d[i] << 16 | (i + 1 < k ? (unsigned)d[i + 1] << 8 : 0u);
            *p++ = B64[v >> 18];
            *p++ = B64[(v >> 12) & 63];
            *p++ = i + 1 < k ? B64[(v >> 6) & 63] : '=';
            *p++ = '=';
        }
        s->len += 4 * ((k + 2) / 3);
        d += k;
        n -= k;
    }
    return 1;
}

/* Makes room for `need` (at most RAW_CAP - 2) more raw bytes, encoding
 * what can be encoded. */
static int raw_need(vout *o, size_t need)
{
    if (o->nraw + need <= RAW_CAP) return 1;
    size_t k = o->nraw - o->nraw % 3;
    if (!b64_encode(o, o->raw, k)) return 0;
    memmove(o->raw, o->raw + k, o->nraw - k);
    o->nraw -= k;
    return 1;
}

static int raw_room(vout *o) { return raw_need(o, 8); }

/* Little-endian bytes of v at p. */
static inline void le64(unsigned char *p, uint64_t v)
{
    for (int i = 0; i < 8; i++) p[i] = (unsigned char)(v >> (8 * i));
}

static inline void le32(unsigned char *p, uint32_t v)
{
    for (int i = 0; i < 4; i++) p[i] = (unsigned char)(v >> (8 * i));
}

/* Whole arrays in binary: the same bytes as value by value (put_f64(),
 * put_int()), packed a buffer at a time. */
static int put_f64s(vout *o, const double *v, size_t n)
{
    while (n > 0) {
        if (!raw_need(o, 8 * 8)) return 0;
        size_t m = (RAW_CAP - o->nraw) / 8;
        if (m > n) m = n;
        unsigned char *p = o->raw + o->nraw;
        for (size_t i = 0; i < m; i++) {
            uint64_t bits;
            memcpy(&bits, v + i, sizeof bits);
            le64(p + 8 * i, bits);
        }
        o->nraw += 8 * m;
        v += m;
        n -= m;
    }
    return 1;
}

static int put_i32s(vout *o, const int32_t *v, size_t n)
{
    while (n > 0) {
        if (!raw_need(o, 8 * 4)) return 0;
        size_t m = (RAW_CAP - o->nraw) / 4;
        if (m > n) m = n;
        unsigned char *p = o->raw + o->nraw;
        for (size_t i = 0; i < m; i++) le32(p + 4 * i, (uint32_t)v[i]);
        o->nraw += 4 * m;
        v += m;
        n -= m;
    }
    return 1;
}

static void put_le(vout *o, uint64_t v, int bytes)
{
    for (int i = 0; i < bytes; i++) o->raw[o->nraw++] = (unsigned char)(v >> (8 * i));
}

/* Starts an array of `bytes` raw bytes (binary: its UInt64 header) with
 * `per_line` values on each line of text (ascii). */
static void array_begin(vout *o, uint64_t bytes, unsigned per_line)
{
    o->nraw = 0;
    o->col = 0;
    o->per_line = per_line;
    if (!o->ascii) put_le(o, bytes, 8);
}

/* Ends an ascii line early (one cell's connectivity per line): the space
 * after the last value, still in the buffer, becomes the newline. */
static void end_row(vout *o)
{
    if (!o->ascii || o->col == 0) return;
    o->col = 0;
    o->s->buf[o->s->len - 1] = '\n';
}

static int array_end(vout *o)
{
    if (o->ascii) {
        end_row(o);
        return o->s->status == COONS_OK;
    }
    int ok = b64_encode(o, o->raw, o->nraw);
    o->nraw = 0;
    return ok;
}

/* One value as text, then a space or the end of the line. */
static int text_value(vout *o, const char *txt, size_t n)
{
    char *p = coons__sink_room(o->s, n + 1);
    if (!p) return 0;
    memcpy(p, txt, n);
    p[n] = ++o->col == o->per_line ? '\n' : ' ';
    if (o->col == o->per_line) o->col = 0;
    o->s->len += n + 1;
    return 1;
}

static int put_f64(vout *o, double v)
{
    if (o->ascii) {
        char t[COONS__FMT_MAX];
        return text_value(o, t, coons__fmt_double(t, v));
    }
    if (!raw_room(o)) return 0;
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    put_le(o, bits, 8);
    return 1;
}

/* Signed integers of `bytes` bytes (8: Int64, 4: Int32, 1: UInt8). */
static int put_int(vout *o, int64_t v, int bytes)
{
    if (o->ascii) {
        char t[COONS__FMT_MAX];
        size_t n = 0;
        if (v < 0) t[n++] = '-';
        n += coons__fmt_u64(t + n, v < 0 ? 0u - (uint64_t)v : (uint64_t)v);
        return text_value(o, t, n);
    }
    if (!raw_room(o)) return 0;
    put_le(o, (uint64_t)v, bytes);
    return 1;
}

/* ---- cells ------------------------------------------------------------- */

typedef struct cells {
    size_t nc, npc;
    const uint32_t *cell;
    unsigned char *type; /* hex8: VTK type per cell; otherwise NULL */
    uint64_t nconn;      /* connectivity length */
} cells;

static unsigned nodes_of_type(unsigned t)
{
    switch (t) {
    case COONS__VTK_WEDGE: return 6;
    case COONS__VTK_PYRAMID: return 5;
    case COONS__VTK_HEXAHEDRON: return 8;
    case COONS__VTK_QUADRATIC_HEXAHEDRON: return 20;
    default: return 27;
    }
}

static unsigned cell_type(const cells *c, size_t i)
{
    if (c->type) return c->type[i];
    return c->npc == 20 ? COONS__VTK_QUADRATIC_HEXAHEDRON : COONS__VTK_TRIQUADRATIC_HEXAHEDRON;
}

/* VTK's nodes of cell i into out; returns how many. */
static unsigned cell_nodes(const cells *c, size_t i, uint32_t out[27])
{
    unsigned t;
    return coons__vtk_cell(c->cell + c->npc * i, c->npc, out, &t);
}

static coons_status cells_init(const coons_volume_mesh *vm, cells *c, coons__sink *s)
{
    c->nc = coons_volume_mesh_cell_count(vm);
    c->npc = coons_volume_mesh_nodes_per_cell(vm);
    c->cell = coons_volume_mesh_cells(vm);
    c->type = NULL;
    c->nconn = (uint64_t)c->nc * c->npc;
    if (c->npc != 8) return COONS_OK;
    c->type = coons__malloc(c->nc ? c->nc : 1);
    if (!c->type) return s->status = coons__error_nomem(s->err);
    c->nconn = 0;
    for (size_t i = 0; i < c->nc; i++) {
        uint32_t g[27];
        unsigned t;
        c->nconn += coons__vtk_cell(c->cell + 8 * i, 8, g, &t);
        c->type[i] = (unsigned char)t;
    }
    return COONS_OK;
}

/* ---- the document ------------------------------------------------------ */

/* The arrays in file order: node fields, cell fields, points,
 * connectivity, offsets, types. */
typedef struct array_info {
    const char *name, *type;
    unsigned comps;
    uint64_t bytes;
} array_info;

static uint64_t encoded(uint64_t bytes) { return 4 * ((8 + bytes + 2) / 3); }

static int put_u64(coons__sink *s, uint64_t v)
{
    char t[COONS__FMT_MAX];
    return coons__sink_put(s, t, coons__fmt_u64(t, v));
}

static int put_data_array(coons__sink *s, const array_info *a, int ascii, uint64_t offset)
{
    if (!coons__sink_puts(s, "        <DataArray type=\"") || !coons__sink_puts(s, a->type) ||
        !coons__sink_puts(s, "\" Name=\"") || !coons__sink_puts(s, a->name) ||
        !coons__sink_puts(s, "\""))
        return 0;
    if (a->comps > 1 && (!coons__sink_puts(s, " NumberOfComponents=\"") ||
                         !put_u64(s, a->comps) || !coons__sink_puts(s, "\"")))
        return 0;
    if (ascii) return coons__sink_puts(s, " format=\"ascii\">\n");
    return coons__sink_puts(s, " format=\"appended\" offset=\"") && put_u64(s, offset) &&
           coons__sink_puts(s, "\"/>\n");
}

/* The header text and units as an XML comment: control characters become
 * spaces (as in every writer's header), bytes beyond ASCII '?' (the text
 * need not be UTF-8, which XML requires), and the comment gets no "--"
 * and no '-' at its end, which XML forbids inside comments. */
static int put_comment(const coons__wopts *o, coons__sink *s)
{
    char t[512];
    size_t n = 0;
    const char *parts[3] = {o->header, o->units[0] ? " units=" : "", o->units};
    for (int k = 0; k < 3; k++)
        for (const char *p = parts[k]; *p && n + 1 < sizeof t; p++) {
            unsigned char b = (unsigned char)*p;
            char ch = b >= 0x80 ? '?' : (b < 0x20 || b == 0x7f) ? ' ' : *p;
            if (ch == '-' && n > 0 && t[n - 1] == '-') ch = ' ';
            t[n++] = ch;
        }
    if (n > 0 && t[n - 1] == '-') t[n++] = ' ';
    t[n] = '\0';
    return coons__sink_puts(s, "<!-- ") && coons__sink_puts(s, t) && coons__sink_puts(s, " -->\n");
}

/* The binary connectivity: a hexahedron's VTK nodes are its own (hex8)
 * or a fixed permutation (hex20, hex27); wedges and pyramids as
 * coons__vtk_cell() orders them. */
static int put_connectivity(vout *o, const cells *c)
{
    for (size_t i = 0; i < c->nc; i++) {
        if (!raw_need(o, 27 * 8)) return 0;
        unsigned char *p = o->raw + o->nraw;
        const uint32_t *h = c->cell + c->npc * i;
        unsigned n;
        if (c->type && c->type[i] == COONS__VTK_HEXAHEDRON) {
            for (unsigned j = 0; j < 8; j++) le64(p + 8 * j, h[j]);
            n = 8;
        } else {
            uint32_t v[27];
            n = cell_nodes(c, i, v);
            for (unsigned j = 0; j < n; j++) le64(p + 8 * j, v[j]);
        }
        o->nraw += 8 * (size_t)n;
    }
    return 1;
}

/* Writes the values of array k (in the order of array_info). */
static int put_values(const coons_volume_mesh *vm, const cells *c, size_t k, const array_info *a,
                      vout *o)
{
    size_t nfn = coons_volume_mesh_field_count(vm, COONS_FIELD_NODE);
    size_t nfc = coons_volume_mesh_field_count(vm, COONS_FIELD_CELL);
    size_t nn = coons_volume_mesh_node_count(vm);
    /* ascii lines: a point, a cell's connectivity, or a few values */
    array_begin(o, a->bytes, k == nfn + nfc ? 3 : k == nfn + nfc + 1 ? 27 : 8);
    if (k < nfn + nfc) {
        coons_field_location loc = k < nfn ? COONS_FIELD_NODE : COONS_FIELD_CELL;
        coons_field_type type;
        const void *values;
        coons_volume_mesh_field(vm, loc, k < nfn ? k : k - nfn, &type, &values);
        size_t n = loc == COONS_FIELD_NODE ? nn : c->nc;
        if (!o->ascii) {
            if (!(type == COONS_FIELD_FLOAT64 ? put_f64s(o, values, n) : put_i32s(o, values, n)))
                return 0;
            n = 0;
        }
        for (size_t i = 0; i < n; i++)
            if (!(type == COONS_FIELD_FLOAT64 ? put_f64(o, ((const double *)values)[i])
                                              : put_int(o, ((const int32_t *)values)[i], 4)))
                return 0;
    } else if (k == nfn + nfc) {
        const double *xyz = coons_volume_mesh_nodes(vm);
        if (!o->ascii) return put_f64s(o, xyz, 3 * nn) && array_end(o) && coons__sink_ok(o->s);
        for (size_t i = 0; i < 3 * nn; i++)
            if (!put_f64(o, xyz[i])) return 0;
    } else if (k == nfn + nfc + 1) {
        if (!o->ascii) return put_connectivity(o, c) && array_end(o) && coons__sink_ok(o->s);
        for (size_t i = 0; i < c->nc; i++) {
            uint32_t v[27];
            unsigned n = cell_nodes(c, i, v);
            for (unsigned j = 0; j < n; j++)
                if (!put_int(o, v[j], 8)) return 0;
            end_row(o);
        }
    } else if (k == nfn + nfc + 2) {
        uint64_t end = 0;
        for (size_t i = 0; i < c->nc; i++) {
            end += nodes_of_type(cell_type(c, i));
            if (!put_int(o, (int64_t)end, 8)) return 0;
        }
    } else {
        for (size_t i = 0; i < c->nc; i++)
            if (!put_int(o, cell_type(c, i), 1)) return 0;
    }
    return array_end(o) && coons__sink_ok(o->s);
}

/* Section of array i: 0 point data, 1 cell data, 2 points, 3 cells. */
static size_t section(size_t i, const size_t nf[2], size_t na)
{
    return i < nf[0] ? 0 : i < nf[0] + nf[1] ? 1 : i == na - 4 ? 2 : 3;
}

static coons_status write_vtu(const coons_volume_mesh *vm, const coons__wopts *wo, coons__sink *s,
                              int ascii)
{
    cells c;
    if (cells_init(vm, &c, s) != COONS_OK) return s->status;
    size_t nn = coons_volume_mesh_node_count(vm);
    size_t nf[2] = {coons_volume_mesh_field_count(vm, COONS_FIELD_NODE),
                    coons_volume_mesh_field_count(vm, COONS_FIELD_CELL)};
    size_t na = nf[0] + nf[1] + 4;
    array_info arr[2 * 64 + 4], *a = arr;
    /* Field counts are unbounded in principle: beyond the fixed table,
     * allocate. */
    if (na > sizeof arr / sizeof arr[0]) {
        a = coons__malloc_array(na, sizeof *a);
        if (!a) {
            coons__free(c.type);
            return s->status = coons__error_nomem(s->err);
        }
    }
    size_t k = 0;
    for (int l = 0; l < 2; l++)
        for (size_t f = 0; f < nf[l]; f++, k++) {
            coons_field_type type;
            a[k].name = coons_volume_mesh_field(vm, (coons_field_location)l, f, &type, NULL);
            a[k].type = type == COONS_FIELD_FLOAT64 ? "Float64" : "Int32";
            a[k].comps = 1;
            a[k].bytes = (uint64_t)(l == 0 ? nn : c.nc) * (type == COONS_FIELD_FLOAT64 ? 8 : 4);
        }
    a[k++] = (array_info){"Points", "Float64", 3, (uint64_t)nn * 24};
    a[k++] = (array_info){"connectivity", "Int64", 1, c.nconn * 8};
    a[k++] = (array_info){"offsets", "Int64", 1, (uint64_t)c.nc * 8};
    a[k++] = (array_info){"types", "UInt8", 1, (uint64_t)c.nc};

    vout out, *o = &out;
    o->s = s;
    o->ascii = ascii;
    if (!ascii) b64_init(o);

    static const char *open[] = {"      <PointData>\n", "      <CellData>\n", "      <Points>\n",
                                 "      <Cells>\n"};
    static const char *close[] = {"      </PointData>\n", "      </CellData>\n",
                                  "      </Points>\n", "      </Cells>\n"};
    int ok = coons__sink_puts(s, "<?xml version=\"1.0\"?>\n") && put_comment(wo, s) &&
             coons__sink_puts(s, "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
                                 "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                                 "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"") &&
             put_u64(s, nn) && coons__sink_puts(s, "\" NumberOfCells=\"") && put_u64(s, c.nc) &&
             coons__sink_puts(s, "\">\n");
    uint64_t offset = 0;
    for (size_t i = 0, sec = 0; ok && sec < 4; sec++) {
        ok = coons__sink_puts(s, open[sec]);
        for (; ok && i < na && section(i, nf, na) == sec; i++) {
            ok = put_data_array(s, &a[i], ascii, offset);
            offset += encoded(a[i].bytes);
            if (ok && ascii)
                ok = put_values(vm, &c, i, &a[i], o) &&
                     coons__sink_puts(s, "        </DataArray>\n");
        }
        ok = ok && coons__sink_puts(s, close[sec]);
    }
    ok = ok && coons__sink_puts(s, "    </Piece>\n  </UnstructuredGrid>\n");
    if (ok && !ascii) {
        ok = coons__sink_puts(s, "  <AppendedData encoding=\"base64\">\n   _");
        for (size_t i = 0; ok && i < na; i++) ok = put_values(vm, &c, i, &a[i], o);
        ok = ok && coons__sink_puts(s, "\n  </AppendedData>\n");
    }
    if (ok) coons__sink_puts(s, "</VTKFile>\n");
    if (a != arr) coons__free(a);
    coons__free(c.type);
    return s->status;
}

coons_status coons__write_vtu(const coons_volume_mesh *vm, const coons__wopts *o, coons__sink *s)
{
    return write_vtu(vm, o, s, 0);
}

coons_status coons__write_vtu_ascii(const coons_volume_mesh *vm, const coons__wopts *o,
                                    coons__sink *s)
{
    return write_vtu(vm, o, s, 1);
}
