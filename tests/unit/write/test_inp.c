/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The Abaqus / CalculiX input deck writer (COONS_FORMAT_INP), read back with
 * a reader written here from the keyword descriptions (Abaqus Keywords
 * Reference; CalculiX User's Manual, "Input deck format", *NODE, *ELEMENT,
 * *NSET, *ELSET, *SURFACE): the line rules (at most 16 entries and 256
 * characters a line, a continued element line ends with a comma, numbers in
 * 20 characters), the keywords and set names of coons-model(5)'s outputs,
 * the C3D20 node order and the face labels S1..S6 against the two
 * projects' own statements of them (transcribed below, not taken from the
 * writer), wedges as C3D6, and the refusals (hex27, colliding names) that
 * write nothing. tests/cli/test_volume_ccx.py runs the decks through ccx. */
#define _XOPEN_SOURCE 700
#include "io_test_util.h"

/* Gmsh's hexahedron nodes (Gmsh reference manual, "Node ordering"): the
 * mesh's order. */
static const double GMSH_PARAM[20][3] = {
    {0, 0, 0},   {1, 0, 0},   {1, 1, 0},   {0, 1, 0},   {0, 0, 1},   {1, 0, 1},   {1, 1, 1},
    {0, 1, 1},   {.5, 0, 0},  {0, .5, 0},  {0, 0, .5},  {1, .5, 0},  {1, 0, .5},  {.5, 1, 0},
    {1, 1, .5},  {0, 1, .5},  {.5, 0, 1},  {0, .5, 1},  {1, .5, 1},  {.5, 1, 1}};

/* Abaqus C3D20 (and CalculiX): corners 1-8 as Gmsh's, then the edge nodes
 * 9-12 on 1-2 2-3 3-4 4-1, 13-16 on 5-6 6-7 7-8 8-5, 17-20 on 1-5 2-6 3-7
 * 4-8, as parameters. */
static const double ABQ_PARAM[20][3] = {
    {0, 0, 0},   {1, 0, 0},   {1, 1, 0},   {0, 1, 0},   {0, 0, 1},   {1, 0, 1},   {1, 1, 1},
    {0, 1, 1},   {.5, 0, 0},  {1, .5, 0},  {.5, 1, 0},  {0, .5, 0},  {.5, 0, 1},  {1, .5, 1},
    {.5, 1, 1},  {0, .5, 1},  {0, 0, .5},  {1, 0, .5},  {1, 1, .5},  {0, 1, .5}};

/* The faces of the hexahedron by (1-based) node, CalculiX *SURFACE: S1 =
 * 1-2-3-4, S2 = 5-8-7-6, S3 = 1-5-6-2, S4 = 2-6-7-3, S5 = 3-7-8-4,
 * S6 = 4-8-5-1; and of the wedge: 1-2-3, 4-5-6, 1-2-5-4, 2-3-6-5, 3-1-4-6. */
static const int HEX_FACE[6][4] = {{1, 2, 3, 4}, {5, 8, 7, 6}, {1, 5, 6, 2},
                                   {2, 6, 7, 3}, {3, 7, 8, 4}, {4, 8, 5, 1}};
static const int WEDGE_FACE[5][4] = {{1, 2, 3, 0}, {4, 5, 6, 0}, {1, 2, 5, 4}, {2, 3, 6, 5},
                                     {3, 1, 4, 6}};

/* The mesh's local faces 0..5 (r0 r1 s0 s1 t0 t1) by corner (coons/volume.h). */
static const int LOCAL_FACE[6][4] = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4},
                                     {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};

static void map(const double p[3], double out[3])
{
    out[0] = 2.0 * p[0] + 0.3 * p[1] * p[2] + 1.0;
    out[1] = 1.5 * p[1] + 0.2 * p[0] * p[0] - 0.5;
    out[2] = 0.7 * p[2] + 0.1 * p[0] * p[1] + 0.25 * p[1];
}

/* ---- a deck reader ----------------------------------------------------- */

/* Checks the line rules of the whole deck. */
static void check_lines(const char *text)
{
    const char *s = text;
    int in_heading = 0;
    while (*s) {
        const char *e = strchr(s, '\n');
        assert_non_null(e); /* every line ends with a newline */
        size_t n = (size_t)(e - s);
        if (n > 256) fail_msg("line longer than 256 characters: %.60s...", s);
        if (s[0] == '*') {
            in_heading = !strncmp(s, "*HEADING", 8) && n == 8;
        } else if (!in_heading) {
            /* numbers must fit 20 characters (names may be longer) */
            int entries = 1, number = 0;
            size_t field = 0;
            for (const char *p = s; p < e; p++) {
                if (*p == ',') {
                    entries++;
                    field = 0;
                } else if (*p != ' ') {
                    if (field++ == 0) number = strchr("0123456789+-.", *p) != NULL;
                    if (number && field > 20)
                        fail_msg("a number longer than 20 characters: %.*s", (int)n, s);
                }
            }
            if (e[-1] == ',') entries--; /* a continued element line */
            if (entries > 16) fail_msg("more than 16 entries: %.*s", (int)n, s);
        }
        s = e + 1;
    }
}

/* The data after the keyword line `key` (the whole line), or NULL. */
static const char *block(const char *text, const char *key)
{
    size_t n = strlen(key);
    for (const char *s = text; s; s = strchr(s, '\n'), s = s ? s + 1 : NULL)
        if (!strncmp(s, key, n) && s[n] == '\n') return s + n + 1;
    return NULL;
}

/* Integers of a block (up to its next keyword line) into v[cap]. */
static size_t block_ints(const char *s, long *v, size_t cap)
{
    size_t n = 0;
    while (s && *s && *s != '*') {
        char *end;
        long x = strtol(s, &end, 10);
        if (end == s) fail_msg("not an integer: %.20s", s);
        assert_true(n < cap);
        v[n++] = x;
        s = end;
        while (*s == ',' || *s == ' ' || *s == '\n') s++;
    }
    return n;
}

static size_t set_of(const char *text, const char *key, long *v, size_t cap)
{
    const char *b = block(text, key);
    if (!b) fail_msg("no '%s'", key);
    return block_ints(b, v, cap);
}

/* Element `id` of an *ELEMENT block: its nodes (a continued line ends with
 * a comma). Returns the node count, 0 when absent. */
static int element(const char *text, const char *key, long id, long *nodes)
{
    const char *s = block(text, key);
    while (s && *s && *s != '*') {
        long row[32];
        int n = 0;
        for (;;) {
            const char *e = strchr(s, '\n');
            int continued = e[-1] == ',';
            while (s < e) {
                char *end;
                row[n++] = strtol(s, &end, 10);
                s = end;
                while (s < e && (*s == ',' || *s == ' ')) s++;
            }
            s = e + 1;
            if (!continued) break;
        }
        if (row[0] == id) {
            memcpy(nodes, row + 1, (size_t)(n - 1) * sizeof *nodes);
            return n - 1;
        }
    }
    return 0;
}

/* The node coordinates of the *NODE block: xyz[3 (id - 1) + k]. */
static size_t nodes_of(const char *text, double *xyz, size_t cap)
{
    const char *s = block(text, "*NODE, NSET=NALL");
    assert_non_null(s);
    size_t n = 0;
    while (*s && *s != '*') {
        char *end;
        long id = strtol(s, &end, 10);
        assert_int_equal(id, (long)n + 1);
        s = end;
        assert_true(n < cap);
        for (int k = 0; k < 3; k++) {
            assert_int_equal(*s, ',');
            xyz[3 * n + (size_t)k] = strtod(s + 1, &end);
            s = end;
        }
        assert_int_equal(*s, '\n');
        s++;
        n++;
    }
    return n;
}

static char *write_inp(const coons_volume_mesh *vm, const coons_write_options *o)
{
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/m.inp", dir);
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_write(vm, p, COONS_FORMAT_AUTO, o, &e), &e);
    char *text = io_read_file(p, NULL);
    assert_non_null(text);
    io_rmdir(dir);
    check_lines(text);
    return text;
}

static coons_volume_mesh *one_cell(coons_element kind, const char *part)
{
    size_t n = (size_t)kind;
    double xyz[20][3];
    uint32_t cell[20];
    /* Nodes stored in reverse, so that node index and position differ. */
    for (size_t k = 0; k < n; k++) {
        map(GMSH_PARAM[k], xyz[n - 1 - k]);
        cell[k] = (uint32_t)(n - 1 - k);
    }
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_new(kind, &vm, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, &xyz[0][0], n, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_part(vm, part, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, cell, 1, 0, NULL, &e), &e);
    return vm;
}

static int same_set(const long *a, int na, const long *b, int nb)
{
    for (int i = 0; i < na; i++) {
        int found = 0;
        for (int j = 0; j < nb; j++) found |= a[i] == b[j];
        if (!found) return 0;
    }
    for (int j = 0; j < nb; j++) {
        int found = 0;
        for (int i = 0; i < na; i++) found |= a[i] == b[j];
        if (!found) return 0;
    }
    return 1;
}

/* ---- tests ------------------------------------------------------------- */

/* Given one hex8 and one hex20 cell with their nodes on a map at Gmsh's
 * parameters, when written, then element 1's k-th node lies at the map of
 * Abaqus's parameters of node k, and the hex20 element continues its line
 * after 16 entries. */
static void test_node_order(void **state)
{
    (void)state;
    for (int kind = 8; kind <= 20; kind += 12) {
        coons_volume_mesh *vm = one_cell((coons_element)kind, "cell");
        char *text = write_inp(vm, NULL);
        double xyz[3 * 20];
        assert_int_equal(nodes_of(text, xyz, 20), (size_t)kind);
        long nodes[32];
        const char *key = kind == 8 ? "*ELEMENT, TYPE=C3D8, ELSET=EALL"
                                    : "*ELEMENT, TYPE=C3D20, ELSET=EALL";
        assert_int_equal(element(text, key, 1, nodes), kind);
        for (int k = 0; k < kind; k++) {
            double want[3];
            map(ABQ_PARAM[k], want);
            assert_true(nodes[k] >= 1 && nodes[k] <= kind);
            assert_vec3_near(xyz + 3 * (nodes[k] - 1), want, 0.0);
        }
        if (kind == 20) {
            /* first line: the number and 15 nodes, ending with a comma */
            const char *b = block(text, key);
            const char *e = strchr(b, '\n');
            int commas = 0;
            for (const char *p = b; p < e; p++) commas += *p == ',';
            assert_int_equal(commas, 16);
            assert_int_equal(e[-1], ',');
        }
        free(text);
        coons_volume_mesh_free(vm);
    }
}

/* Given a cell with a face set per local face, when written, then each
 * face set is a *SURFACE naming one element set (BODY_FACE_Sk) that holds
 * the element, with label Sk, and the nodes of face Sk in CalculiX's table
 * are the corners of that local face (coons/volume.h's table). */
static void test_face_labels(void **state)
{
    (void)state;
    static const char *side[6] = {"c.u0", "c.u1", "c.v0", "c.v1", "c.w0", "c.w1"};
    static const char *upper[6] = {"C_U0", "C_U1", "C_V0", "C_V1", "C_W0", "C_W1"};
    for (int kind = 8; kind <= 20; kind += 12) {
        coons_volume_mesh *vm = one_cell((coons_element)kind, "c");
        coons_error e = COONS_ERROR_INIT;
        const uint32_t *cell = coons_volume_mesh_cells(vm);
        for (uint32_t f = 0; f < 6; f++) {
            uint32_t pair[2] = {0, f};
            assert_coons_ok(coons_volume_mesh_add_face_set(vm, side[f], pair, 1, &e), &e);
        }
        char *text = write_inp(vm, NULL);
        long nodes[32];
        assert_int_equal(element(text, kind == 8 ? "*ELEMENT, TYPE=C3D8, ELSET=EALL"
                                                 : "*ELEMENT, TYPE=C3D20, ELSET=EALL",
                                 1, nodes),
                         kind);
        int seen[7] = {0};
        for (int f = 0; f < 6; f++) {
            char key[96];
            snprintf(key, sizeof key, "*SURFACE, NAME=%s_S, TYPE=ELEMENT", upper[f]);
            const char *b = block(text, key);
            assert_non_null(b);
            char set[64];
            int label = 0;
            assert_int_equal(sscanf(b, "%63[^,], S%d\n", set, &label), 2);
            assert_true(label >= 1 && label <= 6);
            seen[label]++;
            char want_set[64];
            snprintf(want_set, sizeof want_set, "%s_S%d", upper[f], label);
            assert_string_equal(set, want_set);
            /* one surface line only */
            const char *next = strchr(b, '\n') + 1;
            assert_true(*next == '*' || *next == '\0');
            snprintf(key, sizeof key, "*ELSET, ELSET=%s", set);
            long members[4];
            assert_int_equal(set_of(text, key, members, 4), 1);
            assert_int_equal(members[0], 1);
            long face[4], corners[4];
            for (int k = 0; k < 4; k++) {
                face[k] = nodes[HEX_FACE[label - 1][k] - 1];
                corners[k] = (long)cell[LOCAL_FACE[f][k]] + 1;
            }
            if (!same_set(face, 4, corners, 4))
                fail_msg("local face %d written as S%d: other nodes", f, label);
        }
        for (int k = 1; k <= 6; k++) assert_int_equal(seen[k], 1);
        free(text);
        coons_volume_mesh_free(vm);
    }
}

/* Given a hex8 cell whose r = 0 face collapses to a line (two parallel
 * edges merged: a wedge), with a face set per local face, when written,
 * then the element is a C3D6 of positive orientation, the collapsed face's
 * surface is empty, and every other face's label names, in CalculiX's
 * wedge table, exactly the distinct corners of that local face. */
static void test_wedge(void **state)
{
    (void)state;
    /* x = r, y = r s, z = t: r = 0 is the line x = y = 0. */
    double xyz[6][3] = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {1, 1, 0}, {1, 0, 1}, {1, 1, 1}};
    /* Gmsh corners: 0 (0,0,0) 1 (1,0,0) 2 (1,1,0) 3 (0,1,0) 4..7 at t = 1 */
    const uint32_t cell[8] = {0, 2, 3, 0, 1, 4, 5, 1};
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_new(COONS_ELEMENT_HEX8, &vm, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, &xyz[0][0], 6, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "w", NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, cell, 1, 0, NULL, &e), &e);
    static const char *side[6] = {"w.u0", "w.u1", "w.v0", "w.v1", "w.w0", "w.w1"};
    static const char *upper[6] = {"W_U0", "W_U1", "W_V0", "W_V1", "W_W0", "W_W1"};
    for (uint32_t f = 0; f < 6; f++) {
        uint32_t pair[2] = {0, f};
        assert_coons_ok(coons_volume_mesh_add_face_set(vm, side[f], pair, 1, &e), &e);
    }
    char *text = write_inp(vm, NULL);
    assert_null(strstr(text, "TYPE=C3D8"));
    long w[8];
    assert_int_equal(element(text, "*ELEMENT, TYPE=C3D6, ELSET=EALL", 1, w), 6);
    /* Positive orientation: triangle 1-2-3 counter-clockwise seen from 4-5-6
     * (ccx refuses the other with "nonpositive jacobian"). */
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; k++) {
        a[k] = xyz[w[1] - 1][k] - xyz[w[0] - 1][k];
        b[k] = xyz[w[2] - 1][k] - xyz[w[0] - 1][k];
        c[k] = xyz[w[3] - 1][k] - xyz[w[0] - 1][k];
    }
    double vol = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                 a[2] * (b[0] * c[1] - b[1] * c[0]);
    assert_true(vol > 0);
    for (int f = 0; f < 6; f++) {
        char key[96];
        snprintf(key, sizeof key, "*SURFACE, NAME=%s_S, TYPE=ELEMENT", upper[f]);
        const char *s = block(text, key);
        assert_non_null(s);
        if (f == 0) { /* collapsed to a line: no face */
            assert_true(*s == '*' || *s == '\0');
            continue;
        }
        char set[64];
        int label = 0;
        assert_int_equal(sscanf(s, "%63[^,], S%d\n", set, &label), 2);
        assert_true(label >= 1 && label <= 5);
        long face[4], corners[4], distinct[4];
        int nf = WEDGE_FACE[label - 1][3] ? 4 : 3, nd = 0;
        for (int k = 0; k < nf; k++) face[k] = w[WEDGE_FACE[label - 1][k] - 1];
        for (int k = 0; k < 4; k++) {
            corners[k] = (long)cell[LOCAL_FACE[f][k]] + 1;
            int dup = 0;
            for (int j = 0; j < nd; j++) dup |= distinct[j] == corners[k];
            if (!dup) distinct[nd++] = corners[k];
        }
        assert_int_equal(nd, nf);
        if (!same_set(face, nf, distinct, nd))
            fail_msg("local face %d written as wedge S%d: other nodes", f, label);
    }
    free(text);
    coons_volume_mesh_free(vm);
}

/* Given parts, cell sets, node sets and face sets with names that need
 * sanitising, when written, then the deck holds *HEADING (name, units),
 * *NODE with NSET=NALL, the *ELEMENT block with ELSET=EALL, an *ELSET per
 * part, per cell set that is not a part's copy, an *NSET per node set, named
 * upper-cased with every other character replaced by '_'; numbers fit
 * CalculiX's 20 characters and read back exactly when their shortest text
 * does. */
static void test_content(void **state)
{
    (void)state;
    double xyz[12][3];
    for (int n = 0; n < 12; n++) {
        xyz[n][0] = (n % 3) * 0.1;
        xyz[n][1] = ((n / 3) % 2) * 1.0 - 0.0;
        xyz[n][2] = (n / 6) * 12345.678901234567 + 1.0 / 3.0;
    }
    xyz[0][1] = -0.0;
    xyz[5][0] = -1.2345678901234567e-05; /* 22 characters at shortest */
    xyz[6][1] = -1.2345678901234567e-300;
    xyz[7][2] = 0.30000000000000004;
    const uint32_t cells[16] = {0, 1, 4, 3, 6, 7, 10, 9, 1, 2, 5, 4, 7, 8, 11, 10};
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_new(COONS_ELEMENT_HEX8, &vm, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, &xyz[0][0], 12, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "seat", NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "my body-2", NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, cells, 1, 0, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, cells + 8, 1, 1, NULL, &e), &e);
    const uint32_t c0 = 0, both[2] = {1, 0}, n4[4] = {3, 4, 9, 10};
    assert_coons_ok(coons_volume_mesh_add_cell_set(vm, "seat", &c0, 1, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cell_set(vm, "all cells", both, 2, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_node_set(vm, "seat.u1", n4, 4, &e), &e);
    uint32_t many[12];
    for (uint32_t i = 0; i < 12; i++) many[i] = 11 - i;
    assert_coons_ok(coons_volume_mesh_add_node_set(vm, "Ab.c~9", many, 12, &e), &e);
    const uint32_t fs[4] = {0, 1, 1, 0};
    assert_coons_ok(coons_volume_mesh_add_face_set(vm, "seat.u1+my body-2.u0", fs, 2, &e), &e);
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.name = "bracket";
    o.units = "mm";
    o.header = "my\nheader";
    char *text = write_inp(vm, &o);

    assert_non_null(strstr(text, "*HEADING\nmodel=bracket units=mm\n"));
    assert_non_null(strstr(text, "** my header\n"));
    double got[3 * 12];
    assert_int_equal(nodes_of(text, got, 12), 12);
    for (int n = 0; n < 12; n++)
        for (int k = 0; k < 3; k++) {
            double v = xyz[n][k];
            if (n == 5 && k == 0) /* 15 digits fit 20 characters */
                assert_near(got[3 * n + k], v, 5e-15 * fabs(v));
            else if (n == 6 && k == 1) /* 13 with a 3-digit exponent */
                assert_near(got[3 * n + k], v, 5e-13 * fabs(v));
            else
                assert_memory_equal(&got[3 * n + k], &v, sizeof v); /* -0 included */
        }
    long nodes[8];
    assert_int_equal(element(text, "*ELEMENT, TYPE=C3D8, ELSET=EALL", 2, nodes), 8);
    for (int k = 0; k < 8; k++) assert_int_equal(nodes[k], cells[8 + k] + 1);
    long v[16];
    assert_int_equal(set_of(text, "*ELSET, ELSET=SEAT", v, 16), 1);
    assert_int_equal(v[0], 1);
    assert_int_equal(set_of(text, "*ELSET, ELSET=MY_BODY_2", v, 16), 1);
    assert_int_equal(v[0], 2);
    /* the cell set "seat" repeats the part: written once */
    const char *first = strstr(text, "*ELSET, ELSET=SEAT\n");
    assert_null(strstr(first + 1, "*ELSET, ELSET=SEAT\n"));
    assert_int_equal(set_of(text, "*ELSET, ELSET=ALL_CELLS", v, 16), 2);
    assert_int_equal(v[0], 2);
    assert_int_equal(set_of(text, "*NSET, NSET=SEAT_U1", v, 16), 4);
    for (int i = 0; i < 4; i++) assert_int_equal(v[i], n4[i] + 1);
    assert_int_equal(set_of(text, "*NSET, NSET=AB_C_9", v, 16), 12);
    for (int i = 0; i < 12; i++) assert_int_equal(v[i], 12 - i);
    /* faces: cell 0 r=1 -> S4, cell 1 r=0 -> S6 */
    const char *s = block(text, "*SURFACE, NAME=SEAT_U1_MY_BODY_2_U0_S, TYPE=ELEMENT");
    assert_non_null(s);
    assert_int_equal(strncmp(s, "SEAT_U1_MY_BODY_2_U0_S4, S4\nSEAT_U1_MY_BODY_2_U0_S6, S6\n", 56),
                     0);
    assert_int_equal(set_of(text, "*ELSET, ELSET=SEAT_U1_MY_BODY_2_U0_S4", v, 16), 1);
    assert_int_equal(v[0], 1);
    assert_int_equal(set_of(text, "*ELSET, ELSET=SEAT_U1_MY_BODY_2_U0_S6", v, 16), 1);
    assert_int_equal(v[0], 2);
    /* no analysis: a deck of model data only */
    assert_null(strstr(text, "*STEP"));
    assert_null(strstr(text, "*MATERIAL"));
    free(text);

    /* Defaults: no units, the library's header. */
    text = write_inp(vm, NULL);
    assert_non_null(strstr(text, "*HEADING\nmodel=coons_model\n"));
    assert_non_null(strstr(text, "** libcoons " COONS_VERSION_STRING "\n"));
    free(text);
    coons_volume_mesh_free(vm);
}

/* Given a hex8 mesh of 17 cells (C3D8: 9 entries) and a node set of 40
 * nodes, then sets run 16 ids a line. */
static void test_line_length(void **state)
{
    (void)state;
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_new(COONS_ELEMENT_HEX8, &vm, &e), &e);
    double xyz[2 * 18 * 2][3];
    for (int i = 0; i < 72; i++) {
        xyz[i][0] = i % 18, xyz[i][1] = (i / 18) % 2, xyz[i][2] = i / 36;
    }
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, &xyz[0][0], 72, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "bar", NULL, &e), &e);
    for (uint32_t c = 0; c < 17; c++) {
        uint32_t h[8] = {c, c + 1, c + 19, c + 18, c + 36, c + 37, c + 55, c + 54};
        assert_coons_ok(coons_volume_mesh_add_cells(vm, h, 1, 0, NULL, &e), &e);
    }
    uint32_t ns[40];
    for (uint32_t i = 0; i < 40; i++) ns[i] = i;
    assert_coons_ok(coons_volume_mesh_add_node_set(vm, "bar.x", ns, 40, &e), &e);
    char *text = write_inp(vm, NULL); /* check_lines: <= 16 entries a line */
    long v[64];
    assert_int_equal(set_of(text, "*ELSET, ELSET=BAR", v, 64), 17);
    assert_int_equal(set_of(text, "*NSET, NSET=BAR_X", v, 64), 40);
    const char *b = block(text, "*NSET, NSET=BAR_X");
    int lines = 0;
    for (const char *p = b; *p && *p != '*'; p++) lines += *p == '\n';
    assert_int_equal(lines, 3); /* 16 + 16 + 8 */
    free(text);
    coons_volume_mesh_free(vm);
}

/* Writes that must fail before anything exists: given an existing file,
 * then it is unchanged and no other file appears. */
static void refused(const coons_volume_mesh *vm, coons_status want, const char *m1,
                    const char *m2)
{
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/old.inp", dir);
    io_write_file(p, "previous\n", 9);
    coons_error e = COONS_ERROR_INIT;
    assert_int_equal(coons_volume_mesh_write(vm, p, COONS_FORMAT_AUTO, NULL, &e), want);
    if (!strstr(e.message, m1) || (m2 && !strstr(e.message, m2)))
        fail_msg("message '%s' lacks '%s' / '%s'", e.message, m1, m2 ? m2 : "");
    size_t n;
    char *text = io_read_file(p, &n);
    assert_int_equal(n, 9);
    assert_memory_equal(text, "previous\n", 9);
    free(text);
    assert_int_equal(io_dir_count(dir), 1);
    snprintf(p, sizeof p, "%s/new.inp", dir);
    assert_int_equal(coons_volume_mesh_write(vm, p, COONS_FORMAT_INP, NULL, &e), want);
    assert_int_equal(io_dir_count(dir), 1);
    assert_int_equal(coons_volume_mesh_write_stream(vm, stdout, COONS_FORMAT_INP, NULL, &e),
                     want);
    io_rmdir(dir);
}

/* hex27 has no place in the format. */
static void test_hex27_refused(void **state)
{
    (void)state;
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_new(COONS_ELEMENT_HEX27, &vm, &e), &e);
    refused(vm, COONS_E_UNSUPPORTED, "hex8 (C3D8) and hex20 (C3D20)", "hex27");
    coons_volume_mesh_free(vm);
}

/* Names that become the same set name, or too long for CalculiX. */
static void test_name_collisions(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    coons_volume_mesh *vm = one_cell(COONS_ELEMENT_HEX8, "a.b");
    assert_coons_ok(coons_volume_mesh_add_part(vm, "A_b", NULL, &e), &e);
    refused(vm, COONS_E_INVALID, "part 'a.b'", "part 'A_b'");
    coons_volume_mesh_free(vm);

    vm = one_cell(COONS_ELEMENT_HEX8, "eall");
    refused(vm, COONS_E_INVALID, "part 'eall'", "EALL");
    coons_volume_mesh_free(vm);

    /* a node set and a part of one name are different kinds of set */
    vm = one_cell(COONS_ELEMENT_HEX8, "x.y");
    const uint32_t n0 = 0, pair[2] = {0, 1};
    assert_coons_ok(coons_volume_mesh_add_node_set(vm, "x_y", &n0, 1, &e), &e);
    char *text = write_inp(vm, NULL);
    free(text);
    assert_coons_ok(coons_volume_mesh_add_node_set(vm, "X-Y", &n0, 1, &e), &e);
    refused(vm, COONS_E_INVALID, "node set 'x_y'", "node set 'X-Y'");
    coons_volume_mesh_free(vm);

    /* the element set of a face set's label against a part */
    vm = one_cell(COONS_ELEMENT_HEX8, "f.u1");
    assert_coons_ok(coons_volume_mesh_add_face_set(vm, "f_u1", pair, 1, &e), &e);
    text = write_inp(vm, NULL); /* surface F_U1_S, element set F_U1_S4 */
    free(text);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "f_u1_s4", NULL, &e), &e);
    refused(vm, COONS_E_INVALID, "part 'f_u1_s4'", "face set 'f_u1' (its elements with faces S4)");
    coons_volume_mesh_free(vm);

    char longname[90];
    memset(longname, 'n', 81);
    longname[81] = '\0';
    vm = one_cell(COONS_ELEMENT_HEX8, longname);
    refused(vm, COONS_E_UNSUPPORTED, "longer than 80", NULL);
    coons_volume_mesh_free(vm);
    longname[80] = '\0'; /* 80 is allowed */
    vm = one_cell(COONS_ELEMENT_HEX8, longname);
    text = write_inp(vm, NULL);
    free(text);
    coons_volume_mesh_free(vm);
}

/* The format's table row. */
static void test_format_row(void **state)
{
    (void)state;
    coons_format f = COONS_FORMAT_AUTO;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_format_from_path("dir/model.INP", &f, &e), &e);
    assert_int_equal(f, COONS_FORMAT_INP);
    assert_coons_ok(coons_format_from_name("inp", &f, &e), &e);
    assert_int_equal(f, COONS_FORMAT_INP);
    assert_string_equal(coons_format_name(COONS_FORMAT_INP), "inp");
    assert_string_equal(coons_format_extension(COONS_FORMAT_INP), ".inp");
    assert_int_equal(coons_format_kind(COONS_FORMAT_INP), COONS_MESH_KIND_VOLUME);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_node_order),     cmocka_unit_test(test_face_labels),
        cmocka_unit_test(test_wedge),          cmocka_unit_test(test_content),
        cmocka_unit_test(test_line_length),    cmocka_unit_test(test_hex27_refused),
        cmocka_unit_test(test_name_collisions), cmocka_unit_test(test_format_row),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
