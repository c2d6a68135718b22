/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The legacy VTK writer (COONS_FORMAT_VTK): the file parses as VTK's
 * "Simple Legacy Formats" describe it, with a reader written here from
 * that description; coordinates and Float64 fields read back to the same
 * bits, Int32 fields exactly; and the node order of hex8, hex20 and hex27
 * cells is VTK's own. The node-order check places each node of a cell on a
 * non-affine map at the parameters Gmsh's manual gives its index (the
 * mesh's order), and asks that VTK's k-th node of the written cell sit at
 * the parameters VTK's vtkQuadraticHexahedron / vtkTriQuadraticHexahedron
 * give index k: the two tables are transcribed from the two projects'
 * documentation, not from the writer. */
#define _XOPEN_SOURCE 700
#include "io_test_util.h"

/* Gmsh's hexahedron nodes (Gmsh reference manual, "Node ordering"). */
static const double GMSH_PARAM[27][3] = {
    {0, 0, 0},     {1, 0, 0},     {1, 1, 0},     {0, 1, 0},     {0, 0, 1},     {1, 0, 1},
    {1, 1, 1},     {0, 1, 1},     {.5, 0, 0},    {0, .5, 0},    {0, 0, .5},    {1, .5, 0},
    {1, 0, .5},    {.5, 1, 0},    {1, 1, .5},    {0, 1, .5},    {.5, 0, 1},    {0, .5, 1},
    {1, .5, 1},    {.5, 1, 1},    {.5, .5, 0},   {.5, 0, .5},   {0, .5, .5},   {1, .5, .5},
    {.5, 1, .5},   {.5, .5, 1},   {.5, .5, .5}};

/* VTK's parametric coordinates of the same cells (vtkHexahedron,
 * vtkQuadraticHexahedron, vtkTriQuadraticHexahedron). */
static const double VTK_PARAM[27][3] = {
    {0, 0, 0},     {1, 0, 0},     {1, 1, 0},     {0, 1, 0},     {0, 0, 1},     {1, 0, 1},
    {1, 1, 1},     {0, 1, 1},     {.5, 0, 0},    {1, .5, 0},    {.5, 1, 0},    {0, .5, 0},
    {.5, 0, 1},    {1, .5, 1},    {.5, 1, 1},    {0, .5, 1},    {0, 0, .5},    {1, 0, .5},
    {1, 1, .5},    {0, 1, .5},    {0, .5, .5},   {1, .5, .5},   {.5, 0, .5},   {.5, 1, .5},
    {.5, .5, 0},   {.5, .5, 1},   {.5, .5, .5}};

/* A non-affine map, so that no two parameter points share an image. */
static void map(const double p[3], double out[3])
{
    out[0] = 2.0 * p[0] + 0.3 * p[1] * p[2] + 1.0;
    out[1] = 1.5 * p[1] + 0.2 * p[0] * p[0] - 0.5;
    out[2] = 0.7 * p[2] + 0.1 * p[0] * p[1] + 0.25 * p[1];
}

/* ---- a legacy VTK reader, from the file-format description ------------- */

#define MAXF 4
typedef struct vtk_field {
    char name[64], type[16];
    double *v;
} vtk_field;

typedef struct vtk_grid {
    char title[512];
    size_t np, nc, size;
    double *xyz;
    long *conn; /* size values: per cell its count then its nodes */
    long *types;
    size_t nf[2];
    vtk_field f[2][MAXF];
} vtk_grid;

static void expect(const char **s, const char *want)
{
    char tok[128];
    assert_true(io_token(s, tok, sizeof tok));
    if (strcmp(tok, want) != 0) fail_msg("expected '%s', read '%s'", want, tok);
}

static size_t read_count(const char **s)
{
    double v = io_num(s);
    assert_true(v >= 0 && v == floor(v));
    return (size_t)v;
}

static void read_attributes(const char **s, vtk_grid *g, int loc, size_t n)
{
    char tok[128];
    const char *save = *s;
    while (io_token(s, tok, sizeof tok)) {
        if (strcmp(tok, "SCALARS") != 0) {
            *s = save;
            return;
        }
        vtk_field *f = &g->f[loc][g->nf[loc]++];
        assert_true(g->nf[loc] <= MAXF);
        assert_true(io_token(s, f->name, sizeof f->name));
        assert_true(io_token(s, f->type, sizeof f->type));
        expect(s, "1");
        expect(s, "LOOKUP_TABLE");
        expect(s, "default");
        f->v = malloc((n ? n : 1) * sizeof(double));
        for (size_t i = 0; i < n; i++) f->v[i] = io_num(s);
        save = *s;
    }
}

static void vtk_read(const char *text, vtk_grid *g)
{
    memset(g, 0, sizeof *g);
    const char *nl = strchr(text, '\n');
    assert_non_null(nl);
    assert_int_equal(nl - text, strlen("# vtk DataFile Version 3.0"));
    assert_memory_equal(text, "# vtk DataFile Version 3.0", nl - text);
    const char *t = nl + 1, *tend = strchr(t, '\n');
    assert_non_null(tend);
    assert_true(tend - t < 256); /* the title holds at most 256 characters */
    memcpy(g->title, t, (size_t)(tend - t));
    const char *s = tend + 1;
    expect(&s, "ASCII");
    expect(&s, "DATASET");
    expect(&s, "UNSTRUCTURED_GRID");
    expect(&s, "POINTS");
    g->np = read_count(&s);
    expect(&s, "double");
    g->xyz = malloc((3 * g->np + 1) * sizeof(double));
    for (size_t i = 0; i < 3 * g->np; i++) g->xyz[i] = io_num(&s);
    expect(&s, "CELLS");
    g->nc = read_count(&s);
    g->size = read_count(&s);
    g->conn = malloc((g->size + 1) * sizeof(long));
    size_t k = 0;
    for (size_t c = 0; c < g->nc; c++) {
        assert_true(k < g->size);
        size_t m = read_count(&s);
        g->conn[k++] = (long)m;
        for (size_t j = 0; j < m; j++) {
            assert_true(k < g->size);
            size_t v = read_count(&s);
            assert_true(v < g->np);
            g->conn[k++] = (long)v;
        }
    }
    assert_int_equal(k, g->size);
    expect(&s, "CELL_TYPES");
    assert_int_equal(read_count(&s), g->nc);
    g->types = malloc((g->nc + 1) * sizeof(long));
    for (size_t c = 0; c < g->nc; c++) g->types[c] = (long)read_count(&s);
    char tok[64];
    while (io_token(&s, tok, sizeof tok)) {
        int loc = strcmp(tok, "POINT_DATA") == 0 ? 0 : strcmp(tok, "CELL_DATA") == 0 ? 1 : -1;
        if (loc < 0) fail_msg("unexpected '%s'", tok);
        size_t n = read_count(&s);
        assert_int_equal(n, loc == 0 ? g->np : g->nc);
        read_attributes(&s, g, loc, n);
    }
}

static void vtk_free(vtk_grid *g)
{
    free(g->xyz);
    free(g->conn);
    free(g->types);
    for (int l = 0; l < 2; l++)
        for (size_t i = 0; i < g->nf[l]; i++) free(g->f[l][i].v);
}

static char *write_vtk(const coons_volume_mesh *vm, const coons_write_options *o)
{
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/m.vtk", dir);
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_write(vm, p, COONS_FORMAT_AUTO, o, &e), &e);
    char *text = io_read_file(p, NULL);
    assert_non_null(text);
    io_rmdir(dir);
    return text;
}

/* ---- tests ------------------------------------------------------------- */

/* Given one cell of each kind with its nodes on the map at Gmsh's
 * parameters, when written as VTK, then VTK node k of the cell lies at the
 * map of VTK's parameters of node k, and the cell type is VTK's. */
static void test_node_order(void **state)
{
    (void)state;
    static const coons_element kinds[3] = {COONS_ELEMENT_HEX8, COONS_ELEMENT_HEX20,
                                           COONS_ELEMENT_HEX27};
    static const long types[3] = {12, 25, 29};
    for (int i = 0; i < 3; i++) {
        size_t n = (size_t)kinds[i];
        /* Nodes stored in reverse, so that node index and position differ. */
        double xyz[27][3];
        uint32_t cell[27];
        for (size_t k = 0; k < n; k++) {
            map(GMSH_PARAM[k], xyz[n - 1 - k]);
            cell[k] = (uint32_t)(n - 1 - k);
        }
        coons_volume_mesh *vm = NULL;
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(coons_volume_mesh_new(kinds[i], &vm, &e), &e);
        assert_coons_ok(coons_volume_mesh_add_nodes(vm, &xyz[0][0], n, NULL, &e), &e);
        assert_coons_ok(coons_volume_mesh_add_part(vm, "cell", NULL, &e), &e);
        assert_coons_ok(coons_volume_mesh_add_cells(vm, cell, 1, 0, NULL, &e), &e);
        char *text = write_vtk(vm, NULL);
        vtk_grid g;
        vtk_read(text, &g);
        assert_int_equal(g.np, n);
        assert_int_equal(g.nc, 1);
        assert_int_equal(g.size, n + 1);
        assert_int_equal(g.conn[0], (long)n);
        assert_int_equal(g.types[0], types[i]);
        for (size_t k = 0; k < n; k++) {
            double want[3];
            map(VTK_PARAM[k], want);
            const double *got = g.xyz + 3 * (size_t)g.conn[1 + k];
            assert_vec3_near(got, want, 0.0);
        }
        vtk_free(&g);
        free(text);
        coons_volume_mesh_free(vm);
    }
}

/* Given a two-cell hex8 mesh with node and cell fields of both types,
 * then the file holds exactly its nodes (same bits), cells, and fields. */
static void test_content(void **state)
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
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_new(COONS_ELEMENT_HEX8, &vm, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, &xyz[0][0], 12, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "seat", NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, cells, 2, 0, NULL, &e), &e);
    double u[12], dj[12];
    for (int n = 0; n < 12; n++) {
        u[n] = (n % 3) / 2.0;
        dj[n] = -1.0 / (n + 1);
    }
    const int32_t body[2] = {INT32_MIN, INT32_MAX};
    const double sj[2] = {1.0, 0.1};
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "u", COONS_FIELD_FLOAT64, u,
                                                &e), &e);
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "det_j",
                                                COONS_FIELD_FLOAT64, dj, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "body", COONS_FIELD_INT32,
                                                body, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "scaled_jacobian",
                                                COONS_FIELD_FLOAT64, sj, &e), &e);
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.header = "my\nheader";
    o.units = "mm";
    char *text = write_vtk(vm, &o);
    vtk_grid g;
    vtk_read(text, &g);
    assert_string_equal(g.title, "my header units=mm");
    assert_int_equal(g.np, 12);
    assert_memory_equal(g.xyz, xyz, sizeof xyz); /* bit for bit, -0 included */
    assert_int_equal(g.nc, 2);
    assert_int_equal(g.size, 18);
    for (int c = 0; c < 2; c++) {
        assert_int_equal(g.conn[9 * c], 8);
        for (int k = 0; k < 8; k++) assert_int_equal(g.conn[9 * c + 1 + k], cells[8 * c + k]);
        assert_int_equal(g.types[c], 12);
    }
    assert_int_equal(g.nf[0], 2);
    assert_string_equal(g.f[0][0].name, "u");
    assert_string_equal(g.f[0][0].type, "double");
    assert_memory_equal(g.f[0][0].v, u, sizeof u);
    assert_string_equal(g.f[0][1].name, "det_j");
    assert_memory_equal(g.f[0][1].v, dj, sizeof dj);
    assert_int_equal(g.nf[1], 2);
    assert_string_equal(g.f[1][0].name, "body");
    assert_string_equal(g.f[1][0].type, "int");
    assert_near(g.f[1][0].v[0], (double)INT32_MIN, 0.0);
    assert_near(g.f[1][0].v[1], (double)INT32_MAX, 0.0);
    assert_string_equal(g.f[1][1].type, "double");
    assert_memory_equal(g.f[1][1].v, sj, sizeof sj);
    vtk_free(&g);
    free(text);

    /* Default title; a long header is cut to fit the title line. */
    text = write_vtk(vm, NULL);
    vtk_read(text, &g);
    assert_string_equal(g.title, "libcoons " COONS_VERSION_STRING);
    vtk_free(&g);
    free(text);
    char longh[600];
    memset(longh, 'h', sizeof longh - 1);
    longh[sizeof longh - 1] = '\0';
    o.header = longh;
    text = write_vtk(vm, &o);
    vtk_read(text, &g);
    assert_int_equal(strlen(g.title), 255);
    assert_string_equal(g.title + 255 - strlen(" units=mm"), " units=mm");
    vtk_free(&g);
    free(text);
    coons_volume_mesh_free(vm);
}

/* An empty mesh is a valid empty grid with no attribute sections. */
static void test_empty(void **state)
{
    (void)state;
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_new(COONS_ELEMENT_HEX20, &vm, &e), &e);
    char *text = write_vtk(vm, NULL);
    vtk_grid g;
    vtk_read(text, &g);
    assert_int_equal(g.np, 0);
    assert_int_equal(g.nc, 0);
    assert_int_equal(g.size, 0);
    assert_int_equal(g.nf[0] + g.nf[1], 0);
    assert_null(strstr(text, "POINT_DATA"));
    vtk_free(&g);
    free(text);
    coons_volume_mesh_free(vm);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_node_order),
        cmocka_unit_test(test_content),
        cmocka_unit_test(test_empty),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
