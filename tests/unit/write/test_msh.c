/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The Gmsh writers (COONS_FORMAT_MSH2, COONS_FORMAT_MSH4), read back with a
 * reader written here from the Gmsh reference manual's "MSH file format"
 * sections (versions 2.2 and 4.1): the exact sequence of sections, counts,
 * tags, physical names and dimensions, coordinates and fields to the bit.
 * Node orders are checked against the manual's tables, not the writer's:
 * each node of a cell is placed on a non-affine map at the parameters
 * Gmsh's "Node ordering" gives its index, and hexahedron node k of a
 * written element must lie at the map of Gmsh's parameters of node k (so
 * the nodes are a permutation of the cell's, node for node); quadrangle
 * and triangle nodes must be the corners of one face, counter-clockwise
 * seen from outside, then the midpoints of consecutive corners, then the
 * face centre (quad9). gmsh itself reads the same files in
 * tests/cli/test_volume_gmsh.py. */
#define _XOPEN_SOURCE 700
#include <sys/stat.h>

#include "io_test_util.h"

static const char previous[] = "previous output, must survive\n";

/* Gmsh's hexahedron nodes (Gmsh reference manual, "Node ordering"). */
static const double GMSH_PARAM[27][3] = {
    {0, 0, 0},   {1, 0, 0},   {1, 1, 0},   {0, 1, 0},   {0, 0, 1},   {1, 0, 1},   {1, 1, 1},
    {0, 1, 1},   {.5, 0, 0},  {0, .5, 0},  {0, 0, .5},  {1, .5, 0},  {1, 0, .5},  {.5, 1, 0},
    {1, 1, .5},  {0, 1, .5},  {.5, 0, 1},  {0, .5, 1},  {1, .5, 1},  {.5, 1, 1},  {.5, .5, 0},
    {.5, 0, .5}, {0, .5, .5}, {1, .5, .5}, {.5, 1, .5}, {.5, .5, 1}, {.5, .5, .5}};

/* A non-affine map, so that no two parameter points share an image. */
static void map(const double p[3], double out[3])
{
    out[0] = 2.0 * p[0] + 0.3 * p[1] * p[2] + 1.0;
    out[1] = 1.5 * p[1] + 0.2 * p[0] * p[0] - 0.5;
    out[2] = 0.7 * p[2] + 0.1 * p[0] * p[1] + 0.25 * p[1];
}

/* ---- a reader of MSH 2.2 and 4.1 ASCII, from the manual ------------------ */

#define MAXN 64
typedef struct msh_el {
    long tag, phys, ent;
    int type, dim, n;
    long node[27];
} msh_el;

typedef struct msh_field {
    char section[64], name[128];
    size_t n;
    long *tag;
    double *v;
} msh_field;

typedef struct msh_file {
    int v4;
    char sections[32][64];
    int nsec;
    size_t nnames;
    struct {
        int dim;
        long tag;
        char name[700];
    } names[MAXN];
    size_t nent[4];
    struct {
        int dim;
        long tag, phys;
        int nphys;
        double box[6];
    } ent[MAXN];
    size_t nn;
    long *ntag, *nent_of; /* per node read: its tag, its block's volume tag (4.1) */
    double *xyz;
    size_t ne;
    msh_el *el;
    size_t nf;
    msh_field f[8];
} msh_file;

static int type_nodes(int type)
{
    switch (type) {
    case 2: return 3;
    case 3: return 4;
    case 5: return 8;
    case 6: return 6;
    case 7: return 5;
    case 9: return 6;
    case 10: return 9;
    case 12: return 27;
    case 16: return 8;
    case 17: return 20;
    default: fail_msg("unexpected element type %d", type);
    }
    return 0;
}

static int type_dim(int type)
{
    return type == 2 || type == 3 || type == 9 || type == 10 || type == 16 ? 2 : 3;
}

static long rd_long(const char **s)
{
    double v = io_num(s);
    assert_true(v == floor(v));
    return (long)v;
}

/* The rest of the current line (after blanks), without the newline. */
static void rd_line(const char **s, char *out, size_t cap)
{
    const char *p = *s;
    while (*p == ' ') p++;
    if (*p == '\n') p++;
    size_t n = 0;
    while (*p && *p != '\n') {
        if (n + 1 < cap) out[n++] = *p;
        p++;
    }
    out[n] = '\0';
    *s = *p ? p + 1 : p;
}

static void rd_names(const char **s, msh_file *m)
{
    m->nnames = (size_t)rd_long(s);
    assert_true(m->nnames <= MAXN);
    for (size_t i = 0; i < m->nnames; i++) {
        m->names[i].dim = (int)rd_long(s);
        m->names[i].tag = rd_long(s);
        char line[700];
        rd_line(s, line, sizeof line);
        size_t len = strlen(line);
        assert_true(len >= 2 && line[0] == '"' && line[len - 1] == '"');
        line[len - 1] = '\0';
        assert_null(strchr(line + 1, '"'));
        snprintf(m->names[i].name, sizeof m->names[i].name, "%s", line + 1);
    }
}

static void rd_elements_v2(const char **s, msh_file *m)
{
    m->ne = (size_t)rd_long(s);
    m->el = calloc(m->ne + 1, sizeof *m->el);
    for (size_t i = 0; i < m->ne; i++) {
        msh_el *e = &m->el[i];
        e->tag = rd_long(s);
        e->type = (int)rd_long(s);
        e->n = type_nodes(e->type);
        e->dim = type_dim(e->type);
        assert_int_equal(rd_long(s), 2); /* physical and elementary tags */
        e->phys = rd_long(s);
        e->ent = rd_long(s);
        for (int k = 0; k < e->n; k++) e->node[k] = rd_long(s);
    }
}

static void rd_nodes_v2(const char **s, msh_file *m)
{
    m->nn = (size_t)rd_long(s);
    m->ntag = calloc(m->nn + 1, sizeof *m->ntag);
    m->xyz = calloc(3 * m->nn + 1, sizeof *m->xyz);
    for (size_t i = 0; i < m->nn; i++) {
        m->ntag[i] = rd_long(s);
        for (int k = 0; k < 3; k++) m->xyz[3 * i + (size_t)k] = io_num(s);
    }
}

static void rd_entities(const char **s, msh_file *m)
{
    size_t total = 0;
    for (int d = 0; d < 4; d++) total += m->nent[d] = (size_t)rd_long(s);
    assert_int_equal(m->nent[0] + m->nent[1], 0);
    assert_true(total <= MAXN);
    for (size_t i = 0; i < total; i++) {
        m->ent[i].dim = i < m->nent[2] ? 2 : 3;
        m->ent[i].tag = rd_long(s);
        for (int k = 0; k < 6; k++) m->ent[i].box[k] = io_num(s);
        m->ent[i].nphys = (int)rd_long(s);
        assert_true(m->ent[i].nphys <= 1);
        m->ent[i].phys = m->ent[i].nphys ? rd_long(s) : 0;
        assert_int_equal(rd_long(s), 0); /* no bounding entities */
    }
}

static long ent_phys(const msh_file *m, int dim, long tag)
{
    for (size_t i = 0; i < m->nent[2] + m->nent[3]; i++)
        if (m->ent[i].dim == dim && m->ent[i].tag == tag) return m->ent[i].phys;
    fail_msg("no entity (%d, %ld)", dim, tag);
    return -1;
}

static void rd_nodes_v4(const char **s, msh_file *m)
{
    size_t blocks = (size_t)rd_long(s);
    m->nn = (size_t)rd_long(s);
    long lo = rd_long(s), hi = rd_long(s);
    assert_int_equal(lo, m->nn ? 1 : 0);
    assert_int_equal(hi, (long)m->nn);
    m->ntag = calloc(m->nn + 1, sizeof *m->ntag);
    m->nent_of = calloc(m->nn + 1, sizeof *m->nent_of);
    m->xyz = calloc(3 * m->nn + 1, sizeof *m->xyz);
    size_t i = 0;
    for (size_t b = 0; b < blocks; b++) {
        assert_int_equal(rd_long(s), 3); /* nodes in volume blocks */
        long tag = rd_long(s);
        ent_phys(m, 3, tag);
        assert_int_equal(rd_long(s), 0); /* not parametric */
        size_t n = (size_t)rd_long(s);
        assert_true(n > 0 && i + n <= m->nn);
        for (size_t j = 0; j < n; j++) m->ntag[i + j] = rd_long(s), m->nent_of[i + j] = tag;
        for (size_t j = 0; j < n; j++)
            for (int k = 0; k < 3; k++) m->xyz[3 * (i + j) + (size_t)k] = io_num(s);
        i += n;
    }
    assert_int_equal(i, m->nn);
}

static void rd_elements_v4(const char **s, msh_file *m)
{
    size_t blocks = (size_t)rd_long(s);
    m->ne = (size_t)rd_long(s);
    long lo = rd_long(s), hi = rd_long(s);
    assert_int_equal(lo, m->ne ? 1 : 0);
    assert_int_equal(hi, (long)m->ne);
    m->el = calloc(m->ne + 1, sizeof *m->el);
    size_t i = 0;
    for (size_t b = 0; b < blocks; b++) {
        int dim = (int)rd_long(s);
        long ent = rd_long(s);
        int type = (int)rd_long(s);
        size_t n = (size_t)rd_long(s);
        assert_int_equal(type_dim(type), dim);
        assert_true(n > 0 && i + n <= m->ne);
        for (size_t j = 0; j < n; j++, i++) {
            msh_el *e = &m->el[i];
            e->tag = rd_long(s);
            e->type = type;
            e->dim = dim;
            e->n = type_nodes(type);
            e->ent = ent;
            e->phys = ent_phys(m, dim, ent);
            for (int k = 0; k < e->n; k++) e->node[k] = rd_long(s);
        }
    }
    assert_int_equal(i, m->ne);
}

static void rd_field(const char **s, msh_file *m, const char *section)
{
    assert_true(m->nf < 8);
    msh_field *f = &m->f[m->nf++];
    snprintf(f->section, sizeof f->section, "%s", section);
    assert_int_equal(rd_long(s), 1);
    char line[128];
    rd_line(s, line, sizeof line);
    size_t len = strlen(line);
    assert_true(len >= 2 && line[0] == '"' && line[len - 1] == '"');
    line[len - 1] = '\0';
    snprintf(f->name, sizeof f->name, "%s", line + 1);
    assert_int_equal(rd_long(s), 1);
    assert_near(io_num(s), 0.0, 0.0); /* time */
    assert_int_equal(rd_long(s), 3);
    assert_int_equal(rd_long(s), 0); /* time step */
    assert_int_equal(rd_long(s), 1); /* components */
    f->n = (size_t)rd_long(s);
    f->tag = calloc(f->n + 1, sizeof *f->tag);
    f->v = calloc(f->n + 1, sizeof *f->v);
    for (size_t i = 0; i < f->n; i++) f->tag[i] = rd_long(s), f->v[i] = io_num(s);
}

static void msh_read(const char *text, msh_file *m)
{
    memset(m, 0, sizeof *m);
    const char *s = text;
    char tok[64];
    while (io_token(&s, tok, sizeof tok)) {
        assert_true(tok[0] == '$' && m->nsec < 32);
        snprintf(m->sections[m->nsec++], sizeof m->sections[0], "%s", tok + 1);
        const char *name = tok + 1;
        if (!strcmp(name, "MeshFormat")) {
            io_token(&s, tok, sizeof tok);
            m->v4 = !strcmp(tok, "4.1");
            if (!m->v4) assert_string_equal(tok, "2.2");
            io_expect(&s, "0");
            io_expect(&s, "8");
        } else if (!strcmp(name, "PhysicalNames")) {
            rd_names(&s, m);
        } else if (!strcmp(name, "Entities")) {
            rd_entities(&s, m);
        } else if (!strcmp(name, "Nodes")) {
            m->v4 ? rd_nodes_v4(&s, m) : rd_nodes_v2(&s, m);
        } else if (!strcmp(name, "Elements")) {
            m->v4 ? rd_elements_v4(&s, m) : rd_elements_v2(&s, m);
        } else if (!strcmp(name, "NodeData") || !strcmp(name, "ElementData")) {
            rd_field(&s, m, name);
        } else {
            fail_msg("unexpected section $%s", name);
        }
        char end[64];
        snprintf(end, sizeof end, "$End%s", m->sections[m->nsec - 1]);
        io_expect(&s, end);
    }
}

static void msh_free(msh_file *m)
{
    free(m->ntag);
    free(m->nent_of);
    free(m->xyz);
    free(m->el);
    for (size_t i = 0; i < m->nf; i++) free(m->f[i].tag), free(m->f[i].v);
}

/* Coordinates of the node tagged t. */
static const double *node_at(const msh_file *m, long t)
{
    for (size_t i = 0; i < m->nn; i++)
        if (m->ntag[i] == t) return m->xyz + 3 * i;
    fail_msg("no node %ld", t);
    return NULL;
}

static const char *phys_name(const msh_file *m, int dim, long tag)
{
    for (size_t i = 0; i < m->nnames; i++)
        if (m->names[i].dim == dim && m->names[i].tag == tag) return m->names[i].name;
    return NULL;
}

static char *write_msh(const coons_volume_mesh *vm, coons_format f)
{
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/m.msh", dir);
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_write(vm, p, f, NULL, &e), &e);
    char *text = io_read_file(p, NULL);
    assert_non_null(text);
    io_rmdir(dir);
    return text;
}

static const coons_format FORMATS[2] = {COONS_FORMAT_MSH2, COONS_FORMAT_MSH4};

/* The section sequence of a file as one string: "MeshFormat PhysicalNames ...". */
static void sections(const msh_file *m, char *out, size_t cap)
{
    out[0] = '\0';
    for (int i = 0; i < m->nsec; i++) {
        strncat(out, m->sections[i], cap - strlen(out) - 2);
        if (i + 1 < m->nsec) strcat(out, " ");
    }
}

/* ---- the parameters of nodes ---------------------------------------------- */

/* Parameters of the node at x among the n points map(par[i]) (exact). */
static const double *param_of(const double *x, const double (*par)[3], size_t n)
{
    for (size_t i = 0; i < n; i++) {
        double y[3];
        map(par[i], y);
        if (y[0] == x[0] && y[1] == x[1] && y[2] == x[2]) return par[i];
    }
    fail_msg("a node at (%g, %g, %g) is no mesh node", x[0], x[1], x[2]);
    return NULL;
}

/* The nodes q of a surface element (Gmsh: quadrangle edges 0-1 1-2 2-3 3-0,
 * triangle 0-1 1-2 2-0, then a quad9's centre): the corners are distinct,
 * turn counter-clockwise seen from outside (their normal points away from
 * `inside`), the edge nodes are the midpoints of consecutive corners and a
 * ninth node their mean. In parameter space (`grid`), consecutive corners
 * of a quadrangle also differ in exactly one parameter. */
static void check_face(const double (*q)[3], int type, const double inside[3], int grid)
{
    int nc = type == 2 || type == 9 ? 3 : 4, n = type_nodes(type);
    double mean[3] = {0, 0, 0};
    for (int i = 0; i < nc; i++) {
        for (int k = 0; k < 3; k++) mean[k] += q[i][k] / nc;
        for (int j = 0; j < i; j++)
            assert_false(q[i][0] == q[j][0] && q[i][1] == q[j][1] && q[i][2] == q[j][2]);
        if (grid && nc == 4) {
            int diff = 0;
            for (int k = 0; k < 3; k++) diff += q[i][k] != q[(i + 1) % 4][k];
            assert_int_equal(diff, 1);
        }
    }
    double a[3], b[3];
    for (int k = 0; k < 3; k++) a[k] = q[1][k] - q[0][k], b[k] = q[nc - 1][k] - q[0][k];
    double nrm[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]};
    double out = 0;
    for (int k = 0; k < 3; k++) out += nrm[k] * (mean[k] - inside[k]);
    assert_true(out > 0);
    for (int i = nc; i < n && i < 2 * nc; i++)
        for (int k = 0; k < 3; k++)
            assert_near(q[i][k], 0.5 * (q[i - nc][k] + q[(i - nc + 1) % nc][k]), 1e-15);
    if (n == 9)
        for (int k = 0; k < 3; k++) assert_near(q[8][k], mean[k], 1e-15);
}

/* The apex map (r, r s, t), multilinear: the face r = 0 collapses to the
 * line x = y = 0, and each straight cell edge and face stays straight, so
 * edge nodes are the midpoints and face nodes the mean of their corners.
 * side(f, x, 0) is 0 on side f of the unit cell, side(f, x, 1) on that of
 * cone() below. */
static void apex(const double p[3], double x[3]) { x[0] = p[0], x[1] = p[0] * p[1], x[2] = p[2]; }

static double side(int f, const double x[3], int cone)
{
    if (cone && f == 5) return x[2] - x[0];
    switch (f) {
    case 0: return fabs(x[0]) + fabs(x[1]);
    case 1: return x[0] - 1;
    case 2: return x[1];
    case 3: return x[1] - x[0];
    case 4: return x[2];
    default: return x[2] - 1;
    }
}

/* ---- tests ----------------------------------------------------------------- */

/* Given one cell of each kind, its nodes on the map at Gmsh's parameters
 * (stored in reverse, so that index and position differ) and its six
 * faces as six face sets, when written as MSH 2.2 and 4.1, then the cell
 * is one hexahedron of Gmsh's type whose node k lies at the map of Gmsh's
 * parameters of node k, and each face is one quadrangle of Gmsh's type on
 * that side, counter-clockwise seen from outside, edge and centre nodes at
 * the midpoints. */
static void test_node_order(void **state)
{
    (void)state;
    static const coons_element kinds[3] = {COONS_ELEMENT_HEX8, COONS_ELEMENT_HEX20,
                                           COONS_ELEMENT_HEX27};
    static const int hex[3] = {5, 17, 12}, quad[3] = {3, 16, 10};
    static const char *side[6] = {"c.u0", "c.u1", "c.v0", "c.v1", "c.w0", "c.w1"};
    for (int i = 0; i < 3; i++) {
        size_t n = (size_t)kinds[i];
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
        assert_coons_ok(coons_volume_mesh_add_part(vm, "c", NULL, &e), &e);
        assert_coons_ok(coons_volume_mesh_add_cells(vm, cell, 1, 0, NULL, &e), &e);
        for (uint32_t f = 0; f < 6; f++) {
            uint32_t pair[2] = {0, f};
            assert_coons_ok(coons_volume_mesh_add_face_set(vm, side[f], pair, 1, &e), &e);
        }
        for (int v = 0; v < 2; v++) {
            char *text = write_msh(vm, FORMATS[v]);
            msh_file m;
            msh_read(text, &m);
            assert_int_equal(m.v4, v);
            assert_int_equal(m.nn, n);
            assert_int_equal(m.ne, 7);
            assert_int_equal(m.el[0].type, hex[i]);
            assert_int_equal(m.el[0].tag, 1);
            for (size_t k = 0; k < n; k++) {
                double want[3];
                map(GMSH_PARAM[k], want);
                assert_vec3_near(node_at(&m, m.el[0].node[k]), want, 0.0);
            }
            for (int f = 0; f < 6; f++) {
                const msh_el *el = &m.el[1 + f];
                assert_int_equal(el->tag, 2 + f);
                assert_int_equal(el->type, quad[i]);
                assert_string_equal(phys_name(&m, 2, el->phys), side[f]);
                double q[9][3];
                for (int j = 0; j < el->n; j++) {
                    memcpy(q[j], param_of(node_at(&m, el->node[j]), GMSH_PARAM, n), sizeof q[j]);
                    assert_near(q[j][f / 2], f % 2, 0.0); /* on side f */
                }
                const double centre[3] = {.5, .5, .5};
                check_face((const double(*)[3])q, el->type, centre, 1);
            }
            msh_free(&m);
            free(text);
        }
        coons_volume_mesh_free(vm);
    }
}

/* Two hex8 cells on top of each other, the upper part "seat" and the lower
 * "column", with node and cell fields, the six faces of each as face sets
 * (in the order the mesher adds them), one empty set. */
static coons_volume_mesh *two_bodies(void)
{
    double xyz[12][3];
    for (int n = 0; n < 12; n++) {
        double p[3] = {n % 2, (n / 2) % 2, n / 4};
        map(p, xyz[n]);
    }
    xyz[0][1] = -0.0 * xyz[0][1];
    /* seat: z in [1,2], column: z in [0,1] */
    const uint32_t seat[8] = {4, 5, 7, 6, 8, 9, 11, 10}, column[8] = {0, 1, 3, 2, 4, 5, 7, 6};
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_new(COONS_ELEMENT_HEX8, &vm, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, &xyz[0][0], 12, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "seat", NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "column", NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, seat, 1, 0, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, column, 1, 1, NULL, &e), &e);
    static const char *body[2] = {"seat", "column"};
    static const char *side[6] = {"u0", "u1", "v0", "v1", "w0", "w1"};
    for (uint32_t c = 0; c < 2; c++)
        for (uint32_t f = 0; f < 6; f++) {
            char name[32];
            snprintf(name, sizeof name, "%s.%s", body[c], side[f]);
            uint32_t pair[2] = {c, f};
            assert_coons_ok(coons_volume_mesh_add_face_set(vm, name, pair, 1, &e), &e);
        }
    assert_coons_ok(coons_volume_mesh_add_face_set(vm, "nothing", NULL, 0, &e), &e);
    double u[12];
    for (int n = 0; n < 12; n++) u[n] = n / 3.0 - 1e-300 * (n == 5);
    const int32_t id[2] = {INT32_MIN, INT32_MAX};
    const double sj[2] = {1.0, 0.1};
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "u", COONS_FIELD_FLOAT64, u,
                                                &e), &e);
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "body", COONS_FIELD_INT32,
                                                id, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "scaled_jacobian",
                                                COONS_FIELD_FLOAT64, sj, &e), &e);
    return vm;
}

/* Given two bodies sharing a face, when written, then the file's sections
 * are exactly those of its version, nodes read back to the bit, every cell
 * is its element (tag c + 1) in its part's physical volume, each non-empty
 * face set is a physical surface, the two sets of the shared face are one,
 * "seat.w0+column.w1", outward from the seat, and the fields are there. */
static void test_structure(void **state)
{
    (void)state;
    coons_volume_mesh *vm = two_bodies();
    const double *xyz = coons_volume_mesh_nodes(vm);
    const uint32_t *cells = coons_volume_mesh_cells(vm);
    static const char *want_names[] = {
        "seat",      "column",    "seat.u0",   "seat.u1",   "seat.v0",
        "seat.v1",   "seat.w0+column.w1",      "seat.w1",   "column.u0",
        "column.u1", "column.v0", "column.v1", "column.w0"};
    for (int v = 0; v < 2; v++) {
        char *text = write_msh(vm, FORMATS[v]);
        msh_file m;
        msh_read(text, &m);
        char sec[512];
        sections(&m, sec, sizeof sec);
        /* 2.2: no cell fields, which meshio 5.0 cannot read there */
        assert_string_equal(sec, v ? "MeshFormat PhysicalNames Entities Nodes Elements NodeData "
                                     "ElementData ElementData"
                                   : "MeshFormat PhysicalNames Nodes Elements NodeData");
        assert_int_equal(m.nnames, 13);
        for (size_t i = 0; i < 13; i++) {
            assert_int_equal(m.names[i].dim, i < 2 ? 3 : 2);
            assert_int_equal(m.names[i].tag, (long)i + 1);
            assert_string_equal(m.names[i].name, want_names[i]);
        }
        /* nodes: every one exactly once, to the bit */
        assert_int_equal(m.nn, 12);
        int seen[12] = {0};
        for (size_t i = 0; i < 12; i++) {
            long t = m.ntag[i];
            assert_true(t >= 1 && t <= 12);
            assert_int_equal(seen[t - 1]++, 0);
            assert_memory_equal(m.xyz + 3 * i, xyz + 3 * (t - 1), 3 * sizeof(double));
        }
        if (v) { /* 4.1: a node is in the block of the first cell using it */
            for (size_t i = 0; i < 12; i++) /* the seat (cell 0) has nodes 5..12 */
                assert_int_equal(m.nent_of[i], m.ntag[i] >= 5 ? 1 : 2);
            assert_int_equal(m.nent[2], 11);
            assert_int_equal(m.nent[3], 2);
            for (size_t i = 0; i < 13; i++) {
                assert_int_equal(m.ent[i].dim, i < 11 ? 2 : 3);
                assert_int_equal(m.ent[i].tag, i < 11 ? (long)i + 1 : (long)i - 10);
                assert_int_equal(m.ent[i].phys, i < 11 ? (long)i + 3 : (long)i - 10);
            }
            /* the seat's box: the map of [0,1]^2 x [1,2] */
            double lo[3], hi[3];
            map((double[3]){0, 0, 1}, lo);
            map((double[3]){1, 1, 2}, hi);
            assert_near(m.ent[11].box[0], lo[0], 0.0);
            assert_near(m.ent[11].box[5], hi[2], 0.0);
        }
        /* elements: the two cells, then one quadrangle per surface */
        assert_int_equal(m.ne, 2 + 11);
        size_t found[13] = {0};
        for (size_t i = 0; i < m.ne; i++) {
            const msh_el *el = &m.el[i];
            assert_true(el->tag >= 1 && el->tag <= 13);
            assert_int_equal(found[el->tag - 1]++, 0);
            if (el->tag <= 2) {
                assert_int_equal(el->type, 5);
                assert_int_equal(el->phys, el->tag);
                assert_int_equal(el->ent, el->tag);
                for (int k = 0; k < 8; k++)
                    assert_int_equal(el->node[k], (long)cells[8 * (el->tag - 1) + k] + 1);
            } else {
                assert_int_equal(el->type, 3);
                assert_int_equal(el->phys, el->tag);
                assert_int_equal(el->ent, el->tag - 2);
            }
        }
        /* the shared face: written once, outward from the seat (-z) */
        for (size_t i = 0; i < m.ne; i++) {
            const msh_el *el = &m.el[i];
            if (el->tag != 7) continue;
            assert_string_equal(phys_name(&m, 2, el->phys), "seat.w0+column.w1");
            const double *a = node_at(&m, el->node[0]), *b = node_at(&m, el->node[1]),
                         *d = node_at(&m, el->node[3]);
            double e1[3], e2[3];
            for (int k = 0; k < 3; k++) e1[k] = b[k] - a[k], e2[k] = d[k] - a[k];
            assert_true(e1[0] * e2[1] - e1[1] * e2[0] < 0);
            int bottom = 0;
            for (int k = 0; k < 4; k++) bottom += el->node[k] >= 5 && el->node[k] <= 8;
            assert_int_equal(bottom, 4);
        }
        /* fields, listed in the file's node and element order (as meshio
         * reads them, ignoring the tags), each element with the values
         * of its cell: a face those of the cell of its (first) set */
        assert_int_equal(m.nf, v ? 3 : 1);
        assert_string_equal(m.f[0].section, "NodeData");
        assert_string_equal(m.f[0].name, "u");
        assert_int_equal(m.f[0].n, 12);
        const double *u = NULL;
        coons_volume_mesh_field(vm, COONS_FIELD_NODE, 0, NULL, (const void **)&u);
        for (size_t i = 0; i < 12; i++) {
            assert_int_equal(m.f[0].tag[i], m.ntag[i]);
            assert_memory_equal(&m.f[0].v[i], &u[m.ntag[i] - 1], sizeof(double));
        }
        if (!v) {
            msh_free(&m);
            free(text);
            continue;
        }
        assert_string_equal(m.f[1].section, "ElementData");
        assert_string_equal(m.f[1].name, "body");
        assert_string_equal(m.f[2].name, "scaled_jacobian");
        const double body_v[2] = {(double)INT32_MIN, (double)INT32_MAX}, sj_v[2] = {1.0, 0.1};
        for (int f = 1; f < 3; f++) {
            assert_int_equal(m.f[f].n, m.ne);
            for (size_t i = 0; i < m.ne; i++) {
                const msh_el *el = &m.el[i];
                assert_int_equal(m.f[f].tag[i], el->tag);
                int cell = el->dim == 3 ? (int)el->tag - 1
                                        : strncmp(phys_name(&m, 2, el->phys), "seat.", 5) != 0;
                assert_near(m.f[f].v[i], (f == 1 ? body_v : sj_v)[cell], 0.0);
            }
        }
        msh_free(&m);
        free(text);
    }
    coons_volume_mesh_free(vm);
}

/* Signed volume of the tetrahedron a b c d. */
static double tet(const double *a, const double *b, const double *c, const double *d)
{
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; k++) u[k] = b[k] - a[k], v[k] = c[k] - a[k], w[k] = d[k] - a[k];
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
           u[2] * (v[0] * w[1] - v[1] * w[0]);
}

/* Builds one cell of `kind` nodes at apex-like maps of Gmsh's parameters,
 * nodes at the same point merged, with its six faces as sets "f0".."f5". */
static coons_volume_mesh *collapsed_cell(int kind, void (*f)(const double *, double *))
{
    double xyz[27][3];
    uint32_t cell[27];
    size_t nn = 0;
    for (int k = 0; k < kind; k++) {
        double x[3];
        f(GMSH_PARAM[k], x);
        size_t j = 0;
        while (j < nn && memcmp(xyz[j], x, sizeof x) != 0) j++;
        if (j == nn) memcpy(xyz[nn++], x, sizeof x);
        cell[k] = (uint32_t)j;
    }
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_new((coons_element)kind, &vm, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, &xyz[0][0], nn, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "tip", NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, cell, 1, 0, NULL, &e), &e);
    for (uint32_t i = 0; i < 6; i++) {
        char name[8];
        snprintf(name, sizeof name, "f%u", (unsigned)i);
        uint32_t pair[2] = {0, i};
        assert_coons_ok(coons_volume_mesh_add_face_set(vm, name, pair, 1, &e), &e);
    }
    return vm;
}

/* (r, r s, r t): the face r = 0 collapses to the point 0. */
static void cone(const double p[3], double x[3])
{
    x[0] = p[0], x[1] = p[0] * p[1], x[2] = p[0] * p[2];
}

/* Given a cell whose face r = 0 collapsed to a line (apex) or a point
 * (cone), of each kind, when written, then a hex8 cell is a prism (6) or
 * a pyramid (7), positively oriented in Gmsh's reference (prism: triangle
 * 0 1 2 counter-clockwise seen from 3 4 5, node i + 3 across from node i;
 * pyramid: base 0 1 2 3 counter-clockwise seen from the apex 4), a hex20
 * or hex27 cell a degenerate hexahedron with the cell's nodes; each face
 * lies on its side, faces with one collapsed edge are triangles (3 or 6
 * nodes), the others quadrangles, all outward with edge nodes at the
 * midpoints, and the face r = 0 is not written, nor its physical group. */
static void test_collapsed(void **state)
{
    (void)state;
    static const int kinds[3] = {8, 20, 27};
    static const int quad[3] = {3, 16, 10}, tri[3] = {2, 9, 9}, hex[3] = {5, 17, 12};
    /* per map, which of the faces f1..f5 are triangles */
    static const int is_tri[2][6] = {{0, 0, 0, 0, 1, 1}, {0, 0, 1, 1, 1, 1}};
    void (*maps[2])(const double *, double *) = {apex, cone};
    for (int mp = 0; mp < 2; mp++)
        for (int i = 0; i < 3; i++) {
            coons_volume_mesh *vm = collapsed_cell(kinds[i], maps[mp]);
            const uint32_t *cell = coons_volume_mesh_cells(vm);
            for (int v = 0; v < 2; v++) {
                char *text = write_msh(vm, FORMATS[v]);
                msh_file m;
                msh_read(text, &m);
                const msh_el *h = &m.el[0];
                const double *x[27];
                for (int k = 0; k < h->n; k++) x[k] = node_at(&m, h->node[k]);
                double inside[3] = {0, 0, 0};
                size_t nd = coons_volume_mesh_node_count(vm);
                for (size_t k = 0; k < nd; k++)
                    for (int d = 0; d < 3; d++)
                        inside[d] += coons_volume_mesh_nodes(vm)[3 * k + (size_t)d] / (double)nd;
                if (i > 0) {
                    assert_int_equal(h->type, hex[i]);
                    for (int k = 0; k < kinds[i]; k++)
                        assert_int_equal(h->node[k], (long)cell[k] + 1);
                } else if (mp == 0) {
                    assert_int_equal(h->type, 6);
                    assert_true(tet(x[0], x[1], x[2], x[3]) > 0);
                    for (int k = 0; k < 3; k++) {
                        assert_true(tet(x[k], x[(k + 1) % 3], x[(k + 2) % 3], x[k + 3]) > 0);
                        assert_true(x[k + 3][0] == x[k][0] && x[k + 3][1] == x[k][1]);
                    }
                } else {
                    assert_int_equal(h->type, 7);
                    for (int k = 0; k < 4; k++)
                        assert_true(tet(x[k], x[(k + 1) % 4], x[(k + 3) % 4], x[4]) > 0);
                }
                assert_int_equal(m.ne, 6);
                assert_int_equal(m.nnames, 6);
                for (size_t j = 1; j < m.ne; j++) {
                    const msh_el *el = &m.el[j];
                    const char *name = phys_name(&m, 2, el->phys);
                    assert_non_null(name);
                    int f = name[1] - '0';
                    assert_true(f >= 1 && f <= 5);
                    assert_int_equal(el->type, is_tri[mp][f] ? tri[i] : quad[i]);
                    double q[9][3];
                    for (int k = 0; k < el->n; k++) {
                        memcpy(q[k], node_at(&m, el->node[k]), sizeof q[k]);
                        assert_near(side(f, q[k], mp), 0.0, 1e-15);
                    }
                    check_face((const double(*)[3])q, el->type, inside, 0);
                }
                msh_free(&m);
                free(text);
            }
            coons_volume_mesh_free(vm);
        }
}

/* An empty mesh, and one with nodes but no parts: valid files. A double
 * quote in a name becomes a single quote. */
static void test_empty_and_names(void **state)
{
    (void)state;
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_new(COONS_ELEMENT_HEX27, &vm, &e), &e);
    for (int v = 0; v < 2; v++) {
        char *text = write_msh(vm, FORMATS[v]);
        msh_file m;
        msh_read(text, &m);
        char sec[256];
        sections(&m, sec, sizeof sec);
        assert_string_equal(sec, v ? "MeshFormat Entities Nodes Elements"
                                   : "MeshFormat Nodes Elements");
        assert_int_equal(m.nn + m.ne + m.nnames, 0);
        msh_free(&m);
        free(text);
    }
    const double p[3] = {1, 2, 3};
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, p, 1, NULL, &e), &e);
    char *text = write_msh(vm, COONS_FORMAT_MSH4);
    msh_file m;
    msh_read(text, &m);
    assert_int_equal(m.nn, 1);
    assert_int_equal(m.nent[3], 1);
    assert_int_equal(m.ent[0].nphys, 0);
    msh_free(&m);
    free(text);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "say \"hi\"", NULL, &e), &e);
    text = write_msh(vm, COONS_FORMAT_MSH2);
    msh_read(text, &m);
    assert_int_equal(m.nnames, 1);
    assert_string_equal(m.names[0].name, "say 'hi'");
    msh_free(&m);
    free(text);
    coons_volume_mesh_free(vm);
}

/* Two one-cell parts named a (na bytes) and b (nb bytes) sharing a face
 * (sets "A.w0" of a and "B.w1" of b), as the shared face's name. */
static coons_volume_mesh *named_pair(size_t na, size_t nb)
{
    char a[300], b[300];
    memset(a, 'a', na);
    memcpy(a + na - 3, ".w0", 4);
    memset(b, 'b', nb);
    memcpy(b + nb - 3, ".w1", 4);
    double xyz[12][3];
    for (int n = 0; n < 12; n++) xyz[n][0] = n % 2, xyz[n][1] = (n / 2) % 2, xyz[n][2] = n / 4;
    const uint32_t up[8] = {4, 5, 7, 6, 8, 9, 11, 10}, down[8] = {0, 1, 3, 2, 4, 5, 7, 6};
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_volume_mesh_new(COONS_ELEMENT_HEX8, &vm, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, &xyz[0][0], 12, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "up", NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "down", NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, up, 1, 0, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, down, 1, 1, NULL, &e), &e);
    const uint32_t fa[2] = {0, 4}, fb[2] = {1, 5};
    assert_coons_ok(coons_volume_mesh_add_face_set(vm, a, fa, 1, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_face_set(vm, b, fb, 1, &e), &e);
    return vm;
}

/* Gmsh reads physical names of at most 252 bytes (the rest of the line
 * goes through fgets() into 256 bytes): given a shared face whose name
 * "A+B" has 252 bytes, it is written; with 253 bytes (also a part name
 * of 253 bytes) the write fails with COONS_E_LIMIT naming the length and
 * leaves the previous file. */
static void test_long_names(void **state)
{
    (void)state;
    coons_volume_mesh *vm = named_pair(125, 126); /* 125 + 1 + 126 = 252 */
    for (int v = 0; v < 2; v++) {
        char *text = write_msh(vm, FORMATS[v]);
        msh_file m;
        msh_read(text, &m);
        assert_int_equal(m.nnames, 3);
        assert_int_equal(strlen(m.names[2].name), 252);
        assert_non_null(strchr(m.names[2].name, '+'));
        msh_free(&m);
        free(text);
    }
    coons_volume_mesh_free(vm);
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/out.msh", dir);
    for (int k = 0; k < 2; k++) {
        vm = k ? named_pair(126, 126) : NULL;
        if (!k) {
            char name[254];
            memset(name, 'p', 253);
            name[253] = '\0';
            coons_error e = COONS_ERROR_INIT;
            assert_coons_ok(coons_volume_mesh_new(COONS_ELEMENT_HEX8, &vm, &e), &e);
            assert_coons_ok(coons_volume_mesh_add_part(vm, name, NULL, &e), &e);
        }
        for (int v = 0; v < 2; v++) {
            io_write_file(p, previous, strlen(previous));
            coons_error e = COONS_ERROR_INIT;
            assert_int_equal(coons_volume_mesh_write(vm, p, FORMATS[v], NULL, &e), COONS_E_LIMIT);
            assert_non_null(strstr(e.message, "253 bytes"));
            assert_non_null(strstr(e.message, k ? "face set 'aaa" : "part 'ppp"));
            size_t len;
            char *got = io_read_file(p, &len);
            assert_int_equal(len, strlen(previous));
            free(got);
            assert_int_equal(io_dir_count(dir), 1);
        }
        coons_volume_mesh_free(vm);
    }
    io_rmdir(dir);
}

static int cancel_after(void *ctx)
{
    int *n = ctx;
    return --*n < 0;
}

/* Given an existing .msh, when writing fails (allocations failing at each
 * point in turn, cancellation at the first polls), then the file is byte
 * for byte what it was and no temporary file remains; otherwise the output
 * is exactly the normal one. Both versions; the format table maps "msh",
 * "msh2", "msh4" and ".msh" as documented. */
static void test_failures_leave_previous(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    coons_format f;
    assert_coons_ok(coons_format_from_path("a/b.MSH", &f, &e), &e);
    assert_int_equal(f, COONS_FORMAT_MSH2);
    assert_coons_ok(coons_format_from_name("msh", &f, &e), &e);
    assert_int_equal(f, COONS_FORMAT_MSH2);
    assert_coons_ok(coons_format_from_name("MSH4", &f, &e), &e);
    assert_int_equal(f, COONS_FORMAT_MSH4);
    assert_string_equal(coons_format_name(COONS_FORMAT_MSH2), "msh2");
    assert_string_equal(coons_format_name(COONS_FORMAT_MSH4), "msh4");
    assert_int_equal(coons_format_kind(COONS_FORMAT_MSH4), COONS_MESH_KIND_VOLUME);
    assert_null(coons_format_extension(COONS_FORMAT_MSH4));

    char dir[64], p[128], ref[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/out.msh", dir);
    snprintf(ref, sizeof ref, "%s/ref.msh", dir);
    coons_volume_mesh *vm = two_bodies();
    for (int v = 0; v < 2; v++) {
        assert_coons_ok(coons_volume_mesh_write(vm, ref, FORMATS[v], NULL, &e), &e);
        size_t ref_len = 0;
        char *want = io_read_file(ref, &ref_len);
        unlink(ref);
        long failures = 0;
        for (long n = 0;; n++) {
            io_write_file(p, previous, strlen(previous));
            coons_test_fail_after(n);
            int rc = coons_volume_mesh_write(vm, p, FORMATS[v], NULL, &e);
            long used = coons_test_alloc_count(), live = coons_test_live_allocs();
            coons_test_fail_after(-1);
            assert_int_equal(live, 0);
            if (rc == COONS_E_NOMEM) {
                size_t len;
                char *got = io_read_file(p, &len);
                assert_int_equal(len, strlen(previous));
                assert_memory_equal(got, previous, len);
                free(got);
                assert_int_equal(io_dir_count(dir), 1);
                failures++;
                continue;
            }
            assert_int_equal(rc, COONS_OK);
            size_t len = 0;
            char *got = io_read_file(p, &len);
            assert_int_equal(len, ref_len);
            assert_memory_equal(got, want, len);
            free(got);
            if (used <= n) break;
        }
        assert_true(failures >= 3); /* the sink, the plan, and its sets */
        for (int k = 0; k < 3; k++) {
            io_write_file(p, previous, strlen(previous));
            int left = k;
            coons_write_options o = COONS_WRITE_OPTIONS_INIT;
            o.cancel = cancel_after;
            o.cancel_ctx = &left;
            assert_int_equal(coons_volume_mesh_write(vm, p, FORMATS[v], &o, &e), COONS_E_IO);
            size_t len;
            char *got = io_read_file(p, &len);
            assert_int_equal(len, strlen(previous));
            free(got);
            assert_int_equal(io_dir_count(dir), 1);
        }
        free(want);
    }
    coons_volume_mesh_free(vm);
    io_rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_node_order),
        cmocka_unit_test(test_structure),
        cmocka_unit_test(test_collapsed),
        cmocka_unit_test(test_empty_and_names),
        cmocka_unit_test(test_long_names),
        cmocka_unit_test(test_failures_leave_previous),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
