/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The VTK XML UnstructuredGrid writers (COONS_FORMAT_VTU, appended base64
 * data; COONS_FORMAT_VTU_ASCII), read back with a reader written here from
 * VTK's "XML File Formats" description and a base64 coder checked against
 * RFC 4648's test vectors: the document's structure and array order,
 * every value to the bit, each appended array's UInt64 byte count and
 * encoded length, offsets that tile the appended section; VTK's node order
 * for 8, 20 and 27 nodes (tables transcribed from VTK's cell
 * documentation, as in write/test_vtk), hex8 cells at collapsed edges and
 * faces as wedges and pyramids oriented as VTK defines them; base64
 * padding for every length modulo 3 and across the writer's buffers; and
 * the atomic file protocol (size limit, cancellation, allocation failures,
 * a full stream). The real VTK and meshio read the files in
 * tests/cli/test_volume_vtu.py. */
#define _XOPEN_SOURCE 700
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include "io_test_util.h"

static const char previous[] = "previous output, must survive\n";

/* ---- base64 (RFC 4648, section 4), written for the test ------------------ */

static const char ALPHABET[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/* out must hold 4 * ceil(n / 3) + 1 characters. */
static void enc64(const unsigned char *d, size_t n, char *out)
{
    size_t o = 0;
    for (size_t i = 0; i < n; i += 3) {
        unsigned long g = (unsigned long)d[i] << 16;
        if (i + 1 < n) g |= (unsigned long)d[i + 1] << 8;
        if (i + 2 < n) g |= d[i + 2];
        out[o++] = ALPHABET[(g >> 18) & 63];
        out[o++] = ALPHABET[(g >> 12) & 63];
        out[o++] = i + 1 < n ? ALPHABET[(g >> 6) & 63] : '=';
        out[o++] = i + 2 < n ? ALPHABET[g & 63] : '=';
    }
    out[o] = '\0';
}

/* Decodes the m characters at s (m a multiple of 4); returns the byte
 * count or -1 on a character outside the alphabet or misplaced padding. */
static long dec64(const char *s, size_t m, unsigned char *out)
{
    if (m % 4) return -1;
    long n = 0;
    for (size_t i = 0; i < m; i += 4) {
        unsigned long g = 0;
        int pad = 0;
        for (int k = 0; k < 4; k++) {
            const char *p = s[i + k] ? strchr(ALPHABET, s[i + k]) : NULL;
            if (s[i + k] == '=' && k >= 2 && i + 4 == m) {
                pad++;
                g <<= 6;
                continue;
            }
            if (!p || pad) return -1;
            g = g << 6 | (unsigned long)(p - ALPHABET);
        }
        out[n++] = (unsigned char)(g >> 16);
        if (pad < 2) out[n++] = (unsigned char)(g >> 8);
        if (pad < 1) out[n++] = (unsigned char)g;
    }
    return n;
}

/* ---- a VTU reader, from VTK's "XML File Formats" --------------------------- */

#define MAXA 16
typedef struct vtu_array {
    char name[64], type[16];
    int section; /* 0 PointData, 1 CellData, 2 Points, 3 Cells */
    long comps;
    size_t n;           /* values */
    double *v;          /* the values (exact for these types) */
    unsigned char *raw; /* binary: the decoded bytes after the byte count */
    size_t offset, chars;
    size_t expect; /* values the counts of the Piece ask for */
} vtu_array;

typedef struct vtu_file {
    int ascii;
    char comment[512];
    size_t np, nc;
    size_t na;
    vtu_array a[MAXA];
} vtu_file;

/* Value of attribute `name` in the tag [tag, end) into out; 0 if absent. */
static int attr(const char *tag, const char *end, const char *name, char *out, size_t cap)
{
    char key[64];
    snprintf(key, sizeof key, " %s=\"", name);
    const char *p = strstr(tag, key);
    if (!p || p > end) return 0;
    p += strlen(key);
    const char *q = strchr(p, '"');
    assert_non_null(q);
    assert_true((size_t)(q - p) < cap);
    memcpy(out, p, (size_t)(q - p));
    out[q - p] = '\0';
    return 1;
}

static size_t attr_count(const char *tag, const char *end, const char *name)
{
    char t[32], *e;
    if (!attr(tag, end, name, t, sizeof t)) fail_msg("no attribute %s", name);
    unsigned long long v = strtoull(t, &e, 10);
    assert_true(*e == '\0' && t[0] >= '0' && t[0] <= '9');
    return (size_t)v;
}

static int width(const char *type)
{
    if (!strcmp(type, "Float64") || !strcmp(type, "Int64")) return 8;
    if (!strcmp(type, "Int32")) return 4;
    if (!strcmp(type, "UInt8")) return 1;
    fail_msg("unexpected type %s", type);
    return 0;
}

static double value_at(const unsigned char *b, const char *type)
{
    uint64_t u = 0;
    int w = width(type);
    for (int i = 0; i < w; i++) u |= (uint64_t)b[i] << (8 * i);
    if (!strcmp(type, "Float64")) {
        double d;
        memcpy(&d, &u, 8);
        return d;
    }
    if (!strcmp(type, "Int64")) return (double)(int64_t)u;
    if (!strcmp(type, "Int32")) return (double)(int32_t)(uint32_t)u;
    return (double)u;
}

/* Every array but the connectivity has one value (tuple) per point or cell. */
static void check_counts(const vtu_file *f)
{
    for (size_t i = 0; i < f->na; i++)
        if (strcmp(f->a[i].name, "connectivity") != 0) assert_int_equal(f->a[i].n, f->a[i].expect);
}

static void vtu_read(const char *text, vtu_file *f)
{
    memset(f, 0, sizeof *f);
    const char *decl = "<?xml version=\"1.0\"?>\n";
    assert_memory_equal(text, decl, strlen(decl));
    const char *c = strstr(text, "<!-- ");
    const char *vf = strstr(text, "<VTKFile ");
    assert_non_null(vf);
    if (c && c < vf) {
        const char *ce = strstr(c + 4, "-->");
        assert_non_null(ce);
        assert_true(ce < vf);
        /* XML comments hold no "--" and do not end in '-'. */
        for (const char *p = c + 4; p < ce; p++) assert_false(p[0] == '-' && p[1] == '-');
        assert_true(ce[-1] != '-');
        memcpy(f->comment, c + 5, (size_t)(ce - c - 6));
    }
    const char *vfe = strchr(vf, '>');
    char t[64];
    assert_true(attr(vf, vfe, "type", t, sizeof t));
    assert_string_equal(t, "UnstructuredGrid");
    assert_true(attr(vf, vfe, "version", t, sizeof t));
    assert_string_equal(t, "1.0");
    assert_true(attr(vf, vfe, "byte_order", t, sizeof t));
    assert_string_equal(t, "LittleEndian");
    assert_true(attr(vf, vfe, "header_type", t, sizeof t));
    assert_string_equal(t, "UInt64");
    const char *ug = strstr(vfe, "<UnstructuredGrid>");
    assert_non_null(ug);
    const char *piece = strstr(ug, "<Piece ");
    assert_non_null(piece);
    const char *pe = strchr(piece, '>');
    f->np = attr_count(piece, pe, "NumberOfPoints");
    f->nc = attr_count(piece, pe, "NumberOfCells");
    static const char *open[4] = {"<PointData>", "<CellData>", "<Points>", "<Cells>"};
    static const char *close[4] = {"</PointData>", "</CellData>", "</Points>", "</Cells>"};
    const char *p = pe;
    f->ascii = -1;
    for (int sec = 0; sec < 4; sec++) {
        const char *s0 = strstr(p, open[sec]), *s1 = s0 ? strstr(s0, close[sec]) : NULL;
        if (!s0 || !s1) fail_msg("no %s...%s in order", open[sec], close[sec]);
        for (const char *d = strstr(s0, "<DataArray "); d && d < s1;
             d = strstr(d + 1, "<DataArray ")) {
            vtu_array *a = &f->a[f->na++];
            assert_true(f->na <= MAXA);
            const char *de = strchr(d, '>');
            a->section = sec;
            assert_true(attr(d, de, "Name", a->name, sizeof a->name));
            assert_true(attr(d, de, "type", a->type, sizeof a->type));
            a->comps = attr(d, de, "NumberOfComponents", t, sizeof t) ? atol(t) : 1;
            assert_true(attr(d, de, "format", t, sizeof t));
            size_t count = (sec == 0 || sec == 2) ? f->np : f->nc;
            if (!strcmp(t, "ascii")) {
                assert_true(f->ascii != 0);
                f->ascii = 1;
                assert_int_equal(de[-1], '"'); /* not an empty element */
                const char *end = strstr(de, "</DataArray>");
                assert_non_null(end);
                size_t cap = (size_t)(end - de) / 2 + 1;
                a->v = malloc(cap * sizeof(double));
                const char *q = de + 1;
                while (1) {
                    while (*q == ' ' || *q == '\n') q++;
                    if (q >= end) break;
                    char *e;
                    a->v[a->n++] = strtod(q, &e);
                    assert_true(e > q && e <= end && (*e == ' ' || *e == '\n'));
                    q = e;
                }
            } else {
                assert_string_equal(t, "appended");
                assert_true(f->ascii != 1);
                f->ascii = 0;
                assert_memory_equal(de - 1, "/>", 2);
                a->offset = attr_count(d, de, "offset");
            }
            a->expect = count * (size_t)a->comps;
        }
        p = s1;
    }
    assert_non_null(strstr(p, "</Piece>"));
    if (f->ascii == 1) {
        assert_null(strstr(p, "<AppendedData"));
        check_counts(f);
        return;
    }
    const char *ad = strstr(p, "<AppendedData encoding=\"base64\">");
    assert_non_null(ad);
    const char *base = strchr(ad, '>') + 1;
    while (*base == ' ' || *base == '\n') base++;
    assert_int_equal(*base, '_');
    base++;
    const char *aend = base;
    while (*aend && (strchr(ALPHABET, *aend) || *aend == '=')) aend++;
    /* Each array: its UInt64 byte count, then the bytes, encoded as one
     * stream; the arrays tile the section in order. */
    size_t at = 0;
    for (size_t i = 0; i < f->na; i++) {
        vtu_array *a = &f->a[i];
        assert_int_equal(a->offset, at);
        assert_true(base + at + 12 <= aend);
        unsigned char head[9];
        assert_int_equal(dec64(base + at, 12, head) >= 8 ? 1 : 0, 1);
        uint64_t bytes = 0;
        for (int k = 0; k < 8; k++) bytes |= (uint64_t)head[k] << (8 * k);
        a->chars = 4 * ((8 + (size_t)bytes + 2) / 3);
        assert_true(base + at + a->chars <= aend);
        unsigned char *all = malloc(a->chars);
        assert_int_equal(dec64(base + at, a->chars, all), (long)(8 + bytes));
        int w = width(a->type);
        assert_int_equal(bytes % (uint64_t)w, 0);
        a->n = (size_t)bytes / (size_t)w;
        a->raw = malloc((size_t)bytes + 1);
        memcpy(a->raw, all + 8, (size_t)bytes);
        a->v = malloc((a->n + 1) * sizeof(double));
        for (size_t k = 0; k < a->n; k++) a->v[k] = value_at(a->raw + (size_t)w * k, a->type);
        free(all);
        at += a->chars;
    }
    assert_true(base + at == aend);
    assert_non_null(strstr(aend, "</AppendedData>"));
    assert_non_null(strstr(aend, "</VTKFile>"));
    check_counts(f);
}

static void vtu_free(vtu_file *f)
{
    for (size_t i = 0; i < f->na; i++) {
        free(f->a[i].v);
        free(f->a[i].raw);
    }
}

static const vtu_array *array_named(const vtu_file *f, const char *name)
{
    for (size_t i = 0; i < f->na; i++)
        if (!strcmp(f->a[i].name, name)) return &f->a[i];
    fail_msg("no array %s", name);
    return NULL;
}

static char *write_to(const coons_volume_mesh *vm, coons_format fmt, const coons_write_options *o,
                      size_t *len)
{
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/m.%s", dir, fmt == COONS_FORMAT_VTU ? "vtu" : "xml");
    coons_error e = COONS_ERROR_INIT;
    coons_format f = fmt == COONS_FORMAT_VTU ? COONS_FORMAT_AUTO : fmt; /* .vtu: by extension */
    assert_coons_ok(coons_volume_mesh_write(vm, p, f, o, &e), &e);
    char *text = io_read_file(p, len);
    assert_non_null(text);
    io_rmdir(dir);
    return text;
}

static const coons_format BOTH[2] = {COONS_FORMAT_VTU, COONS_FORMAT_VTU_ASCII};

/* ---- meshes ------------------------------------------------------------ */

static coons_volume_mesh *mesh_of(coons_element el, const double *xyz, size_t nn,
                                  const uint32_t *cells, size_t nc)
{
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_new(el, &vm, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, xyz, nn, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "part", NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, cells, nc, 0, NULL, &e), &e);
    return vm;
}

/* An n x n x n lattice of unit-ish hex8 cells with a node and a cell field. */
static coons_volume_mesh *lattice(uint32_t n)
{
    uint32_t m = n + 1;
    size_t nn = (size_t)m * m * m, nc = (size_t)n * n * n;
    double *xyz = malloc(3 * sizeof(double) * nn), *w = malloc(sizeof(double) * nn);
    uint32_t *cells = malloc(8 * sizeof(uint32_t) * nc);
    int32_t *body = malloc(sizeof(int32_t) * nc);
    for (uint32_t k = 0; k < m; k++)
        for (uint32_t j = 0; j < m; j++)
            for (uint32_t i = 0; i < m; i++) {
                size_t v = i + m * (j + (size_t)m * k);
                xyz[3 * v] = i / 3.0;
                xyz[3 * v + 1] = j * 1.1 + 1e-9 * i;
                xyz[3 * v + 2] = k / 7.0;
                w[v] = (double)k / n;
            }
    static const uint32_t off[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                       {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    size_t c = 0;
    for (uint32_t k = 0; k < n; k++)
        for (uint32_t j = 0; j < n; j++)
            for (uint32_t i = 0; i < n; i++, c++) {
                for (int q = 0; q < 8; q++)
                    cells[8 * c + (size_t)q] =
                        (i + off[q][0]) + m * ((j + off[q][1]) + m * (k + off[q][2]));
                body[c] = (int32_t)(c % 3) - 1;
            }
    coons_volume_mesh *vm = mesh_of(COONS_ELEMENT_HEX8, xyz, nn, cells, nc);
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "w", COONS_FIELD_FLOAT64, w,
                                                &e), &e);
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "body", COONS_FIELD_INT32,
                                                body, &e), &e);
    free(xyz);
    free(w);
    free(cells);
    free(body);
    return vm;
}

/* ---- tests ------------------------------------------------------------- */

/* The coder of this test reproduces RFC 4648's test vectors both ways. */
static void test_base64_vectors(void **state)
{
    (void)state;
    static const char *plain[7] = {"", "f", "fo", "foo", "foob", "fooba", "foobar"};
    static const char *code[7] = {"", "Zg==", "Zm8=", "Zm9v", "Zm9vYg==", "Zm9vYmE=", "Zm9vYmFy"};
    for (int i = 0; i < 7; i++) {
        char out[16];
        unsigned char back[16];
        enc64((const unsigned char *)plain[i], strlen(plain[i]), out);
        assert_string_equal(out, code[i]);
        assert_int_equal(dec64(code[i], strlen(code[i]), back), (long)strlen(plain[i]));
        assert_memory_equal(back, plain[i], strlen(plain[i]));
    }
    assert_int_equal(dec64("Zg=a", 4, (unsigned char[4]){0}), -1);
    assert_int_equal(dec64("Z!==", 4, (unsigned char[4]){0}), -1);
}

/* Given a two-cell hex8 mesh with node and cell fields of both types,
 * when written in either encoding, then the document has VTK's structure,
 * the arrays in the container's order with their names and types, and
 * every value to the bit; the header text and units are in a well-formed
 * comment. */
static void test_structure(void **state)
{
    (void)state;
    double xyz[12][3];
    for (int n = 0; n < 12; n++) {
        xyz[n][0] = (n % 3) * 0.1;
        xyz[n][1] = ((n / 3) % 2) * 1e-300 - 0.0;
        xyz[n][2] = (n / 6) * 12345.678901234567 + 1.0 / 3.0;
    }
    xyz[0][1] = -0.0;
    const uint32_t cells[16] = {0, 1, 4, 3, 6, 7, 10, 9, 1, 2, 5, 4, 7, 8, 11, 10};
    coons_volume_mesh *vm = mesh_of(COONS_ELEMENT_HEX8, &xyz[0][0], 12, cells, 2);
    double u[12], dj[12];
    for (int n = 0; n < 12; n++) {
        u[n] = (n % 3) / 2.0;
        dj[n] = -1.0 / (n + 1);
    }
    const int32_t body[2] = {INT32_MIN, INT32_MAX};
    const double sj[2] = {1.0, 0.1};
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "u", COONS_FIELD_FLOAT64, u,
                                                &e), &e);
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "det_j",
                                                COONS_FIELD_FLOAT64, dj, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "body", COONS_FIELD_INT32,
                                                body, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "scaled_jacobian",
                                                COONS_FIELD_FLOAT64, sj, &e), &e);
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.header = "my\nheader -- x\xc3\xa9-";
    o.units = "mm-";
    static const char *names[7] = {"u", "det_j", "body", "scaled_jacobian",
                                   "Points", "connectivity", "offsets"};
    static const char *types[8] = {"Float64", "Float64", "Int32", "Float64",
                                   "Float64", "Int64", "Int64", "UInt8"};
    static const int sections[8] = {0, 0, 1, 1, 2, 3, 3, 3};
    for (int b = 0; b < 2; b++) {
        char *text = write_to(vm, BOTH[b], &o, NULL);
        vtu_file f;
        vtu_read(text, &f);
        assert_int_equal(f.ascii, b);
        assert_string_equal(f.comment, "my header -  x?\?- units=mm- ");
        assert_int_equal(f.np, 12);
        assert_int_equal(f.nc, 2);
        assert_int_equal(f.na, 8);
        for (int i = 0; i < 8; i++) {
            assert_string_equal(f.a[i].name, i < 7 ? names[i] : "types");
            assert_string_equal(f.a[i].type, types[i]);
            assert_int_equal(f.a[i].section, sections[i]);
            assert_int_equal(f.a[i].comps, i == 4 ? 3 : 1);
        }
        assert_int_equal(f.a[4].n, 36);
        assert_memory_equal(f.a[4].v, xyz, sizeof xyz); /* bit for bit, -0 included */
        if (!b) assert_memory_equal(f.a[4].raw, xyz, sizeof xyz); /* little-endian host */
        assert_memory_equal(f.a[0].v, u, sizeof u);
        assert_memory_equal(f.a[1].v, dj, sizeof dj);
        assert_near(f.a[2].v[0], (double)INT32_MIN, 0.0);
        assert_near(f.a[2].v[1], (double)INT32_MAX, 0.0);
        assert_memory_equal(f.a[3].v, sj, sizeof sj);
        assert_int_equal(f.a[5].n, 16);
        for (int k = 0; k < 16; k++) assert_near(f.a[5].v[k], cells[k], 0.0);
        assert_int_equal(f.a[6].n, 2);
        assert_near(f.a[6].v[0], 8, 0.0);
        assert_near(f.a[6].v[1], 16, 0.0);
        assert_near(f.a[7].v[0], 12, 0.0);
        assert_near(f.a[7].v[1], 12, 0.0);
        vtu_free(&f);
        free(text);
        /* The default comment names the library. */
        text = write_to(vm, BOTH[b], NULL, NULL);
        vtu_read(text, &f);
        assert_string_equal(f.comment, "libcoons " COONS_VERSION_STRING);
        vtu_free(&f);
        free(text);
    }
    coons_volume_mesh_free(vm);
}

/* Gmsh's hexahedron nodes (Gmsh reference manual, "Node ordering"). */
static const double GMSH_PARAM[27][3] = {
    {0, 0, 0},   {1, 0, 0},   {1, 1, 0},   {0, 1, 0},   {0, 0, 1},   {1, 0, 1},   {1, 1, 1},
    {0, 1, 1},   {.5, 0, 0},  {0, .5, 0},  {0, 0, .5},  {1, .5, 0},  {1, 0, .5},  {.5, 1, 0},
    {1, 1, .5},  {0, 1, .5},  {.5, 0, 1},  {0, .5, 1},  {1, .5, 1},  {.5, 1, 1},  {.5, .5, 0},
    {.5, 0, .5}, {0, .5, .5}, {1, .5, .5}, {.5, 1, .5}, {.5, .5, 1}, {.5, .5, .5}};

/* VTK's parametric coordinates of the same cells (vtkHexahedron,
 * vtkQuadraticHexahedron, vtkTriQuadraticHexahedron documentation). */
static const double VTK_PARAM[27][3] = {
    {0, 0, 0},   {1, 0, 0},   {1, 1, 0},   {0, 1, 0},   {0, 0, 1},   {1, 0, 1},   {1, 1, 1},
    {0, 1, 1},   {.5, 0, 0},  {1, .5, 0},  {.5, 1, 0},  {0, .5, 0},  {.5, 0, 1},  {1, .5, 1},
    {.5, 1, 1},  {0, .5, 1},  {0, 0, .5},  {1, 0, .5},  {1, 1, .5},  {0, 1, .5},  {0, .5, .5},
    {1, .5, .5}, {.5, 0, .5}, {.5, 1, .5}, {.5, .5, 0}, {.5, .5, 1}, {.5, .5, .5}};

static void map(const double p[3], double out[3])
{
    out[0] = 2.0 * p[0] + 0.3 * p[1] * p[2] + 1.0;
    out[1] = 1.5 * p[1] + 0.2 * p[0] * p[0] - 0.5;
    out[2] = 0.7 * p[2] + 0.1 * p[0] * p[1] + 0.25 * p[1];
}

/* Given one cell of each kind with its nodes on a map at Gmsh's
 * parameters, when written, then VTK's node k of the cell lies at the map
 * of VTK's parameters of node k, with VTK's cell type. */
static void test_node_order(void **state)
{
    (void)state;
    static const coons_element kinds[3] = {COONS_ELEMENT_HEX8, COONS_ELEMENT_HEX20,
                                           COONS_ELEMENT_HEX27};
    static const double types[3] = {12, 25, 29};
    for (int i = 0; i < 3; i++) {
        size_t n = (size_t)kinds[i];
        double xyz[27][3];
        uint32_t cell[27];
        for (size_t k = 0; k < n; k++) { /* stored in reverse: index != position */
            map(GMSH_PARAM[k], xyz[n - 1 - k]);
            cell[k] = (uint32_t)(n - 1 - k);
        }
        coons_volume_mesh *vm = mesh_of(kinds[i], &xyz[0][0], n, cell, 1);
        for (int b = 0; b < 2; b++) {
            char *text = write_to(vm, BOTH[b], NULL, NULL);
            vtu_file f;
            vtu_read(text, &f);
            const vtu_array *conn = array_named(&f, "connectivity");
            const vtu_array *pts = array_named(&f, "Points");
            assert_int_equal(conn->n, n);
            assert_near(array_named(&f, "offsets")->v[0], (double)n, 0.0);
            assert_near(array_named(&f, "types")->v[0], types[i], 0.0);
            for (size_t k = 0; k < n; k++) {
                double want[3];
                map(VTK_PARAM[k], want);
                assert_vec3_near(pts->v + 3 * (size_t)conn->v[k], want, 0.0);
            }
            vtu_free(&f);
            free(text);
        }
        coons_volume_mesh_free(vm);
    }
}

static void sub3(const double *a, const double *b, double *o)
{
    for (int i = 0; i < 3; i++) o[i] = a[i] - b[i];
}
static void cross3(const double *a, const double *b, double *o)
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Given hex8 cells of a unit cube lattice collapsed (by merging nodes) at
 * two parallel edges of a face, at a whole face, and at one edge only,
 * when written, then they are a VTK wedge (13), a VTK pyramid (14) and a
 * degenerate hexahedron (12) of the distinct nodes, oriented as VTK
 * defines them: the wedge's triangle (0,1,2) has its right-hand normal
 * pointing away from (3,4,5), each node i+3 across an edge from node i;
 * the pyramid's base (0,1,2,3) has its right-hand normal pointing to the
 * apex 4. A hex20 cell with repeated nodes stays a quadratic hexahedron. */
static void test_collapsed(void **state)
{
    (void)state;
    /* Cube corners by Gmsh index, then the merged points. */
    double xyz[8][3];
    for (int k = 0; k < 8; k++) memcpy(xyz[k], GMSH_PARAM[k], sizeof xyz[k]);
    /* Wedge: edges 0-3 and 4-7 (the face r=0's two s edges) collapse. */
    const uint32_t cells[24] = {0, 1, 2, 0, 4, 5, 6, 4,  /* wedge */
                                0, 0, 0, 0, 4, 5, 6, 7,  /* pyramid: face t=0 to node 0 */
                                0, 1, 2, 3, 4, 4, 6, 7}; /* edge 4-5 only: degenerate */
    coons_volume_mesh *vm = mesh_of(COONS_ELEMENT_HEX8, &xyz[0][0], 8, cells, 3);
    for (int b = 0; b < 2; b++) {
        char *text = write_to(vm, BOTH[b], NULL, NULL);
        vtu_file f;
        vtu_read(text, &f);
        const vtu_array *conn = array_named(&f, "connectivity"), *pts = array_named(&f, "Points");
        const vtu_array *off = array_named(&f, "offsets"), *ty = array_named(&f, "types");
        assert_int_equal(conn->n, 6 + 5 + 8);
        assert_near(off->v[0], 6, 0.0);
        assert_near(off->v[1], 11, 0.0);
        assert_near(off->v[2], 19, 0.0);
        assert_near(ty->v[0], 13, 0.0);
        assert_near(ty->v[1], 14, 0.0);
        assert_near(ty->v[2], 12, 0.0);
        const double *P[8];
        /* wedge */
        int seen[8] = {0};
        for (int k = 0; k < 6; k++) {
            P[k] = pts->v + 3 * (size_t)conn->v[k];
            seen[(int)conn->v[k]]++;
        }
        static const int wedge_nodes[6] = {0, 1, 2, 4, 5, 6};
        for (int k = 0; k < 6; k++) assert_int_equal(seen[wedge_nodes[k]], 1);
        double e1[3], e2[3], nrm[3], c012[3], c345[3], d[3];
        sub3(P[1], P[0], e1);
        sub3(P[2], P[0], e2);
        cross3(e1, e2, nrm);
        for (int i = 0; i < 3; i++) {
            c012[i] = (P[0][i] + P[1][i] + P[2][i]) / 3;
            c345[i] = (P[3][i] + P[4][i] + P[5][i]) / 3;
        }
        sub3(c345, c012, d);
        assert_true(dot3(nrm, d) < 0);
        for (int k = 0; k < 3; k++) { /* i+3 is i moved along t by 1 */
            sub3(P[k + 3], P[k], d);
            assert_near(d[0], 0, 0);
            assert_near(d[1], 0, 0);
            assert_near(d[2], 1, 0);
        }
        /* pyramid */
        memset(seen, 0, sizeof seen);
        for (int k = 0; k < 5; k++) {
            P[k] = pts->v + 3 * (size_t)conn->v[6 + k];
            seen[(int)conn->v[6 + k]]++;
        }
        for (int k = 4; k < 8; k++) assert_int_equal(seen[k], 1);
        assert_int_equal(seen[0], 1);
        assert_int_equal(conn->v[10], 0); /* the apex */
        sub3(P[2], P[0], e1);
        sub3(P[3], P[1], e2);
        cross3(e1, e2, nrm);
        double cb[3];
        for (int i = 0; i < 3; i++) cb[i] = (P[0][i] + P[1][i] + P[2][i] + P[3][i]) / 4;
        sub3(P[4], cb, d);
        assert_true(dot3(nrm, d) > 0);
        for (int k = 0; k < 4; k++) { /* a quadrilateral: consecutive nodes share an edge */
            sub3(P[(k + 1) % 4], P[k], d);
            assert_near(dot3(d, d), 1, 0);
        }
        /* degenerate hexahedron: as given */
        for (int k = 0; k < 8; k++) assert_near(conn->v[11 + k], cells[16 + k], 0.0);
        vtu_free(&f);
        free(text);
    }
    coons_volume_mesh_free(vm);

    double q[20][3];
    uint32_t c20[20];
    for (int k = 0; k < 20; k++) {
        memcpy(q[k], GMSH_PARAM[k], sizeof q[k]);
        c20[k] = (uint32_t)k;
    }
    c20[3] = 0;
    c20[7] = 4;
    c20[9] = 0;
    c20[17] = 4;
    vm = mesh_of(COONS_ELEMENT_HEX20, &q[0][0], 20, c20, 1);
    char *text = write_to(vm, COONS_FORMAT_VTU, NULL, NULL);
    vtu_file f;
    vtu_read(text, &f);
    assert_near(array_named(&f, "types")->v[0], 25, 0.0);
    assert_int_equal(array_named(&f, "connectivity")->n, 20);
    vtu_free(&f);
    free(text);
    coons_volume_mesh_free(vm);
}

/* Given meshes whose arrays have 8 + n bytes for every n modulo 3, and one
 * large enough to cross the writer's buffers many times, when written as
 * .vtu, then each array's text is exactly this test's base64 of its
 * UInt64 byte count and the expected little-endian bytes. */
static void test_base64_arrays(void **state)
{
    (void)state;
    for (uint32_t nc = 1; nc <= 3; nc++) {
        /* 4 x 2 x 2 nodes, cells side by side along x. */
        uint32_t cells[3 * 8];
        for (uint32_t c = 0; c < nc; c++) {
            const uint32_t h[8] = {c, c + 1, c + 5, c + 4, c + 8, c + 9, c + 13, c + 12};
            for (int k = 0; k < 8; k++) cells[8 * c + (uint32_t)k] = h[k];
        }
        size_t nn = 16;
        double x16[16 * 3];
        for (size_t i = 0; i < nn; i++) {
            x16[3 * i] = (double)(i % 4) - 0.25 * (double)i;
            x16[3 * i + 1] = (double)((i / 4) % 2);
            x16[3 * i + 2] = (double)(i / 8) * 1e10;
        }
        coons_volume_mesh *vm = mesh_of(COONS_ELEMENT_HEX8, x16, nn, cells, nc);
        int32_t body[3] = {-1, 0x01020304, 7};
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "body",
                                                    COONS_FIELD_INT32, body, &e), &e);
        size_t len;
        char *text = write_to(vm, COONS_FORMAT_VTU, NULL, &len);
        const char *base = strchr(strstr(text, "<AppendedData"), '_') + 1;
        /* Expected bytes of each array, in file order. */
        unsigned char exp[8 + 16 * 24];
        char want[4 * (sizeof exp / 3 + 1) + 1];
        size_t at = 0;
        for (int arr = 0; arr < 5; arr++) {
            size_t n = 0;
            unsigned char *p = exp + 8;
            if (arr == 0) { /* body: Int32 */
                for (uint32_t c = 0; c < nc; c++, n += 4)
                    for (int k = 0; k < 4; k++)
                        p[n + k] = (unsigned char)((uint32_t)body[c] >> (8 * k));
            } else if (arr == 1) { /* points */
                for (size_t i = 0; i < 3 * nn; i++, n += 8) {
                    uint64_t u;
                    memcpy(&u, &x16[i], 8);
                    for (int k = 0; k < 8; k++) p[n + k] = (unsigned char)(u >> (8 * k));
                }
            } else if (arr == 2 || arr == 3) { /* connectivity, offsets: Int64 */
                size_t m = arr == 2 ? 8 * nc : nc;
                for (size_t i = 0; i < m; i++, n += 8) {
                    uint64_t v = arr == 2 ? cells[i] : 8 * (i + 1);
                    for (int k = 0; k < 8; k++) p[n + k] = (unsigned char)(v >> (8 * k));
                }
            } else { /* types: UInt8, 8 + nc bytes: each residue mod 3 */
                for (uint32_t c = 0; c < nc; c++) p[n++] = 12;
            }
            for (int k = 0; k < 8; k++) exp[k] = (unsigned char)((uint64_t)n >> (8 * k));
            enc64(exp, 8 + n, want);
            assert_memory_equal(base + at, want, strlen(want));
            at += strlen(want);
        }
        assert_memory_equal(base + at, "\n  </AppendedData>\n</VTKFile>\n", 30);
        assert_int_equal(base + at + 30 - text, len);
        free(text);
        coons_volume_mesh_free(vm);
    }

    /* 60^3 cells, 226981 nodes: 5.4 MB of points, several sink buffers. */
    coons_volume_mesh *vm = lattice(60);
    size_t len;
    char *text = write_to(vm, COONS_FORMAT_VTU, NULL, &len);
    vtu_file f;
    vtu_read(text, &f);
    assert_int_equal(f.np, 61 * 61 * 61);
    const vtu_array *pts = array_named(&f, "Points");
    size_t bytes = f.np * 24;
    unsigned char *exp = malloc(8 + bytes);
    for (int k = 0; k < 8; k++) exp[k] = (unsigned char)((uint64_t)bytes >> (8 * k));
    const double *xyz = coons_volume_mesh_nodes(vm);
    for (size_t i = 0; i < 3 * f.np; i++) {
        uint64_t u;
        memcpy(&u, &xyz[i], 8);
        for (int k = 0; k < 8; k++) exp[8 + 8 * i + (size_t)k] = (unsigned char)(u >> (8 * k));
    }
    char *want = malloc(4 * ((8 + bytes) / 3 + 1) + 1);
    enc64(exp, 8 + bytes, want);
    const char *base = strchr(strstr(text, "<AppendedData"), '_') + 1;
    assert_int_equal(pts->chars, strlen(want));
    assert_memory_equal(base + pts->offset, want, pts->chars);
    const vtu_array *conn = array_named(&f, "connectivity");
    const uint32_t *cells = coons_volume_mesh_cells(vm);
    assert_int_equal(conn->n, 8 * f.nc);
    for (size_t i = 0; i < conn->n; i++)
        if (conn->v[i] != cells[i]) fail_msg("connectivity %zu", i);
    const vtu_array *body = array_named(&f, "body");
    for (size_t c = 0; c < f.nc; c++) assert_near(body->v[c], (double)((int)(c % 3) - 1), 0.0);
    free(want);
    free(exp);
    vtu_free(&f);
    free(text);
    coons_volume_mesh_free(vm);
}

/* An empty mesh is a valid empty grid: arrays of no values (binary: only
 * the byte count 0). */
static void test_empty(void **state)
{
    (void)state;
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_new(COONS_ELEMENT_HEX27, &vm, &e), &e);
    for (int b = 0; b < 2; b++) {
        char *text = write_to(vm, BOTH[b], NULL, NULL);
        vtu_file f;
        vtu_read(text, &f);
        assert_int_equal(f.np + f.nc, 0);
        assert_int_equal(f.na, 4);
        for (size_t i = 0; i < 4; i++) assert_int_equal(f.a[i].n, 0);
        if (!b) /* four byte counts 0, 8 zero bytes each */
            assert_non_null(strstr(text, "_AAAAAAAAAAA=AAAAAAAAAAA=AAAAAAAAAAA=AAAAAAAAAAA=\n"));
        vtu_free(&f);
        free(text);
    }
    coons_volume_mesh_free(vm);
}

/* The formats in the table: .vtu means the binary one, vtu-ascii has no
 * extension of its own. */
static void test_format_rows(void **state)
{
    (void)state;
    coons_format f = COONS_FORMAT_AUTO;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_format_from_path("dir/A.VTU", &f, &e), &e);
    assert_int_equal(f, COONS_FORMAT_VTU);
    assert_coons_ok(coons_format_from_name("vtu", &f, &e), &e);
    assert_int_equal(f, COONS_FORMAT_VTU);
    assert_coons_ok(coons_format_from_name("VTU-ascii", &f, &e), &e);
    assert_int_equal(f, COONS_FORMAT_VTU_ASCII);
    assert_string_equal(coons_format_name(COONS_FORMAT_VTU), "vtu");
    assert_string_equal(coons_format_name(COONS_FORMAT_VTU_ASCII), "vtu-ascii");
    assert_string_equal(coons_format_extension(COONS_FORMAT_VTU), ".vtu");
    assert_null(coons_format_extension(COONS_FORMAT_VTU_ASCII));
    assert_int_equal(coons_format_kind(COONS_FORMAT_VTU), COONS_MESH_KIND_VOLUME);
    assert_int_equal(coons_format_kind(COONS_FORMAT_VTU_ASCII), COONS_MESH_KIND_VOLUME);
    /* A triangle mesh is written as VTU too (iso surfaces, src/io/write/
     * vtu_surface.c), but not as legacy VTK. */
    coons_mesh *m = NULL;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    FILE *fp = tmpfile();
    assert_non_null(fp);
    assert_coons_ok(coons_mesh_write_stream(m, fp, COONS_FORMAT_VTU, NULL, &e), &e);
    assert_coons_ok(coons_mesh_write_stream(m, fp, COONS_FORMAT_VTU_ASCII, NULL, &e), &e);
    assert_int_equal(coons_mesh_write_stream(m, fp, COONS_FORMAT_VTK, NULL, &e),
                     COONS_E_INVALID);
    fclose(fp);
    coons_mesh_free(m);
}

static void assert_file_is(const char *path, const char *content)
{
    size_t len;
    char *d = io_read_file(path, &len);
    assert_non_null(d);
    assert_int_equal(len, strlen(content));
    assert_memory_equal(d, content, len);
    free(d);
}

static int cancel_after(void *ctx)
{
    int *left = ctx;
    return (*left)-- <= 0;
}

/* Given an existing file, when a write in either encoding fails (file size
 * limit in a child process, cancellation at each poll, allocation failure
 * at each point, a full stream), then the file is byte for byte what it
 * was and no temporary file remains; a successful file write equals the
 * stream writer's output. */
static void test_atomic(void **state)
{
    (void)state;
    char dir[64], p[128], q[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/out.vtu", dir);
    coons_volume_mesh *big = lattice(40); /* 64000 cells: ~7 MB as .vtu */
    for (int b = 0; b < 2; b++) {
        coons_format fmt = BOTH[b];
        io_write_file(p, previous, strlen(previous));
        fflush(NULL);
        pid_t pid = fork();
        assert_true(pid >= 0);
        if (pid == 0) {
            signal(SIGXFSZ, SIG_IGN);
            struct rlimit rl = {100000, 100000};
            if (setrlimit(RLIMIT_FSIZE, &rl) != 0) _exit(10);
            coons_error e = COONS_ERROR_INIT;
            if (coons_volume_mesh_write(big, p, fmt, NULL, &e) != COONS_E_IO) _exit(11);
            if (!strstr(e.message, "out.vtu") || !strstr(e.message, "large")) _exit(12);
            _exit(0);
        }
        int status;
        assert_int_equal(waitpid(pid, &status, 0), pid);
        assert_true(WIFEXITED(status));
        assert_int_equal(WEXITSTATUS(status), 0);
        assert_file_is(p, previous);
        assert_int_equal(io_dir_count(dir), 1);
        for (int k = 0; k < 6; k++) {
            int left = k;
            coons_write_options o = COONS_WRITE_OPTIONS_INIT;
            o.cancel = cancel_after;
            o.cancel_ctx = &left;
            coons_error e = COONS_ERROR_INIT;
            assert_int_equal(coons_volume_mesh_write(big, p, fmt, &o, &e), COONS_E_IO);
            assert_non_null(strstr(e.message, "cancelled"));
            assert_file_is(p, previous);
            assert_int_equal(io_dir_count(dir), 1);
        }
        coons_error e = COONS_ERROR_INIT;
        FILE *fp = fopen("/dev/full", "wb");
        assert_non_null(fp);
        assert_int_equal(coons_volume_mesh_write_stream(big, fp, fmt, NULL, &e), COONS_E_IO);
        assert_non_null(strstr(e.message, "space"));
        fclose(fp);
        /* Success equals the stream's bytes. */
        assert_coons_ok(coons_volume_mesh_write(big, p, fmt, NULL, &e), &e);
        snprintf(q, sizeof q, "%s/stream", dir);
        fp = fopen(q, "wb");
        assert_coons_ok(coons_volume_mesh_write_stream(big, fp, fmt, NULL, &e), &e);
        assert_int_equal(fclose(fp), 0);
        size_t la, lb;
        char *x = io_read_file(p, &la), *y = io_read_file(q, &lb);
        assert_true(la > ((size_t)3 << 20));
        assert_int_equal(la, lb);
        assert_memory_equal(x, y, la);
        free(x);
        free(y);
        unlink(q);
    }
    coons_volume_mesh_free(big);

    /* Allocation failures at each point in turn, with a hex8 mesh (whose
     * writer allocates its per-cell types) and a hex27 one. */
    double xyz[8][3];
    for (int k = 0; k < 8; k++) memcpy(xyz[k], GMSH_PARAM[k], sizeof xyz[k]);
    const uint32_t cell[8] = {0, 1, 2, 0, 4, 5, 6, 4};
    coons_volume_mesh *small = mesh_of(COONS_ELEMENT_HEX8, &xyz[0][0], 8, cell, 1);
    for (int b = 0; b < 2; b++) {
        coons_error e = COONS_ERROR_INIT;
        size_t ref_len;
        char *want = write_to(small, BOTH[b], NULL, &ref_len);
        long failures = 0;
        for (long n = 0;; n++) {
            io_write_file(p, previous, strlen(previous));
            coons_test_fail_after(n);
            int rc = coons_volume_mesh_write(small, p, BOTH[b], NULL, &e);
            long used = coons_test_alloc_count(), live = coons_test_live_allocs();
            coons_test_fail_after(-1);
            assert_int_equal(live, 0);
            if (rc == COONS_E_NOMEM) {
                assert_file_is(p, previous);
                assert_int_equal(io_dir_count(dir), 1);
                failures++;
                continue;
            }
            assert_int_equal(rc, COONS_OK);
            size_t len;
            char *got = io_read_file(p, &len);
            assert_int_equal(len, ref_len);
            assert_memory_equal(got, want, len);
            free(got);
            if (used <= n) break;
        }
        assert_true(failures >= 2); /* the sink's buffer, the cell types */
        free(want);
    }
    coons_volume_mesh_free(small);
    io_rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_base64_vectors),
        cmocka_unit_test(test_structure),
        cmocka_unit_test(test_node_order),
        cmocka_unit_test(test_collapsed),
        cmocka_unit_test(test_base64_arrays),
        cmocka_unit_test(test_empty),
        cmocka_unit_test(test_format_rows),
        cmocka_unit_test(test_atomic),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
