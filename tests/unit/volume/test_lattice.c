/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Meshing bodies into hexahedra (coons_body_volume_mesh(),
 * coons_model_volume_mesh()) and the cell quality (Knupp's scaled
 * Jacobian), checked against independent facts: node counts of the
 * lattices counted by hand, node positions against coons_body_eval() at the
 * stored parameters (isoparametric), exact volumes (a trilinear body's
 * lattice cells are its exact pieces: 2x2x2 Gauss integrates their det J
 * exactly), conformity (every interior quadrangle in exactly two cells),
 * orientation of left-handed bodies, collapsed cells at an apex, a closed
 * tube, two bodies sharing a face, overlap refused, limits refused before
 * work, and allocation failure at every point. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "body_fixtures.h"
#include "test_util.h"

static coons_volume_options vopts(coons_element el, unsigned nu, unsigned nv, unsigned nw)
{
    coons_volume_options o = COONS_VOLUME_OPTIONS_INIT;
    o.element = el;
    o.resolution[0] = nu;
    o.resolution[1] = nv;
    o.resolution[2] = nw;
    return o;
}

static coons_body *body0(const double c[8][3])
{
    coons_body *b = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_body0(&c[0][0], COONS_BLEND_LINEAR, &b, &e), &e);
    return b;
}

static const double *field(const coons_volume_mesh *vm, coons_field_location loc,
                           const char *name)
{
    for (size_t i = 0; i < coons_volume_mesh_field_count(vm, loc); i++) {
        coons_field_type t;
        const void *v;
        const char *n = coons_volume_mesh_field(vm, loc, i, &t, &v);
        if (!strcmp(n, name)) return v;
    }
    fail_msg("no field %s", name);
    return NULL;
}

/* Node counts of a uniform lattice of n intervals per direction, counted
 * independently: hex8 the (n+1) lattice points, hex27 the (2n+1) points of
 * the half lattice, hex20 the corners plus one midpoint per lattice edge. */
static void test_counts(void **state)
{
    (void)state;
    coons_body *b = body0(tb_hex());
    const unsigned n[3] = {2, 3, 4};
    size_t corners = 3 * 4 * 5;
    size_t edges = 2 * 4 * 5 + 3 * 3 * 5 + 3 * 4 * 4;
    struct {
        coons_element el;
        size_t nodes;
    } want[3] = {{COONS_ELEMENT_HEX8, corners},
                 {COONS_ELEMENT_HEX20, corners + edges},
                 {COONS_ELEMENT_HEX27, 5 * 7 * 9}};
    for (int k = 0; k < 3; k++) {
        coons_volume_options o = vopts(want[k].el, n[0], n[1], n[2]);
        coons_volume_mesh *vm = NULL;
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(coons_body_volume_mesh(b, &o, "skew", &vm, &e), &e);
        assert_int_equal(coons_volume_mesh_cell_count(vm), 24);
        assert_int_equal(coons_volume_mesh_node_count(vm), want[k].nodes);
        assert_int_equal(coons_volume_mesh_element(vm), want[k].el);
        assert_int_equal(coons_volume_mesh_part_count(vm), 1);
        assert_string_equal(coons_volume_mesh_part_name(vm, 0), "skew");
        /* One cell set, six node and face sets named skew.F. */
        assert_int_equal(coons_volume_mesh_cell_set_count(vm), 1);
        assert_int_equal(coons_volume_mesh_node_set_count(vm), 6);
        assert_int_equal(coons_volume_mesh_face_set_count(vm), 6);
        static const size_t faces[6] = {12, 12, 8, 8, 6, 6}; /* nv nw, nu nw, nu nv */
        for (int f = 0; f < 6; f++) {
            const uint32_t *pairs;
            size_t cnt;
            char name[32];
            snprintf(name, sizeof name, "skew.%s", coons_body_face_name(f));
            assert_string_equal(coons_volume_mesh_face_set(vm, (size_t)f, &pairs, &cnt), name);
            assert_int_equal(cnt, faces[f]);
            for (size_t i = 0; i < cnt; i++) assert_int_equal(pairs[2 * i + 1], (uint32_t)f);
        }
        coons_volume_mesh_free(vm);
    }
    coons_body_free(b);
}

/* Every node is the exact body point at its (u, v, w) fields, and each
 * cell node sits at its reference position's parameters in the cell. */
static void test_isoparametric(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    for (int m = 0; m < TB_MAX_BODIES; m++) {
        coons_body *b = NULL;
        if (tb_make_body(m, &b, &e) == TB_NO_BODY) continue;
        coons_volume_options o = vopts(COONS_ELEMENT_HEX27, 3, 2, 2);
        coons_volume_mesh *vm = NULL;
        assert_coons_ok(coons_body_volume_mesh(b, &o, NULL, &vm, &e), &e);
        const double *x = coons_volume_mesh_nodes(vm);
        const double *u = field(vm, COONS_FIELD_NODE, "u");
        const double *v = field(vm, COONS_FIELD_NODE, "v");
        const double *w = field(vm, COONS_FIELD_NODE, "w");
        const double *dj = field(vm, COONS_FIELD_NODE, "det_j");
        double lo[3], hi[3];
        coons_body_control_bbox(b, lo, hi);
        double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                           (hi[2] - lo[2]) * (hi[2] - lo[2]));
        for (size_t n = 0; n < coons_volume_mesh_node_count(vm); n++) {
            double p[3], jac[3][3];
            double d = coons_body_eval_jacobian(b, u[n], v[n], w[n], p, jac);
            /* Shared points (an apex) keep the first owner's parameters:
             * the point is the same within the merge tolerance. */
            assert_vec3_near(x + 3 * n, p, 1e-8 * diag);
            if (fabs(d) > 1e-6) assert_true(d * dj[n] > 0);
        }
        /* Cell 0 spans parameters [0,1/3] x [0,1/2] x [0,1/2] (or mirrored in
         * u): its centre node 26 at (1/6, 1/4, 1/4). */
        const uint32_t *c = coons_volume_mesh_cells(vm);
        double pu = u[c[26]], pv = v[c[26]], pw = w[c[26]];
        assert_true(fabs(pv - 0.25) < 1e-15 && fabs(pw - 0.25) < 1e-15);
        assert_true(fabs(pu - 1.0 / 6) < 1e-15 || fabs(pu - 5.0 / 6) < 1e-15);
        coons_volume_mesh_free(vm);
        coons_body_free(b);
    }
}

/* det of the trilinear cell's Jacobian integrated by 2x2x2 Gauss: exact
 * for a trilinear map (degree <= 2 in each variable). */
static double hex8_volume(const double *x, const uint32_t *c)
{
    static const int R[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const double g[2] = {0.5 - 0.5 / sqrt(3.0), 0.5 + 0.5 / sqrt(3.0)};
    double vol = 0;
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++)
            for (int d = 0; d < 2; d++) {
                double q[3] = {g[a], g[b], g[d]}, J[3][3] = {{0}};
                for (int k = 0; k < 8; k++) {
                    double N[3];
                    for (int t = 0; t < 3; t++) {
                        double f = 1;
                        for (int s = 0; s < 3; s++)
                            if (s != t) f *= R[k][s] ? q[s] : 1 - q[s];
                        N[t] = (R[k][t] ? 1 : -1) * f;
                    }
                    for (int r = 0; r < 3; r++)
                        for (int t = 0; t < 3; t++) J[r][t] += x[3 * c[k] + (size_t)r] * N[t];
                }
                vol += (J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                        J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                        J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0])) /
                       8;
            }
    return vol;
}

/* Interior quadrangles in exactly two cells, boundary ones in one; the
 * number of boundary ones as the lattice says. */
static void check_conformal(const coons_volume_mesh *vm, size_t boundary_faces)
{
    static const int F[6][4] = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4},
                                {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};
    size_t nc = coons_volume_mesh_cell_count(vm), npc = coons_volume_mesh_nodes_per_cell(vm);
    const uint32_t *c = coons_volume_mesh_cells(vm);
    size_t nf = 6 * nc;
    uint32_t(*key)[4] = malloc(nf * sizeof *key);
    assert_non_null(key);
    for (size_t i = 0; i < nc; i++)
        for (int f = 0; f < 6; f++) {
            uint32_t *k = key[6 * i + (size_t)f];
            for (int z = 0; z < 4; z++) k[z] = c[npc * i + (size_t)F[f][z]];
            for (int a = 0; a < 4; a++) /* sort */
                for (int b = a + 1; b < 4; b++)
                    if (k[b] < k[a]) {
                        uint32_t t = k[a];
                        k[a] = k[b];
                        k[b] = t;
                    }
        }
    size_t single = 0;
    for (size_t i = 0; i < nf; i++) {
        size_t same = 0;
        for (size_t j = 0; j < nf; j++) same += !memcmp(key[i], key[j], sizeof key[i]);
        assert_true(same == 1 || same == 2);
        single += same == 1;
    }
    assert_int_equal(single, boundary_faces);
    free(key);
}

static void test_volume_and_conformity(void **state)
{
    (void)state;
    coons_body *b = body0(tb_hex());
    coons_error e = COONS_ERROR_INIT;
    double exact;
    assert_coons_ok(coons_body_volume(b, 1e-12, &exact, &e), &e);
    coons_volume_options o = vopts(COONS_ELEMENT_HEX8, 3, 2, 4);
    coons_volume_mesh *vm = NULL;
    assert_coons_ok(coons_body_volume_mesh(b, &o, NULL, &vm, &e), &e);
    double sum = 0;
    for (size_t i = 0; i < coons_volume_mesh_cell_count(vm); i++)
        sum += hex8_volume(coons_volume_mesh_nodes(vm), coons_volume_mesh_cells(vm) + 8 * i);
    assert_near(sum, exact, 1e-12 * fabs(exact));
    check_conformal(vm, 2 * (3 * 2 + 2 * 4 + 3 * 4));
    coons_volume_quality q = COONS_VOLUME_QUALITY_INIT;
    assert_coons_ok(coons_volume_mesh_quality(vm, 0, &q, &e), &e);
    assert_int_equal(q.cells, 24);
    assert_int_equal(q.nodes, 4 * 3 * 5);
    assert_int_equal(q.inverted, 0);
    assert_int_equal(q.collapsed, 0);
    assert_true(q.min_scaled_jacobian > 0 && q.min_scaled_jacobian <= q.mean_scaled_jacobian &&
                q.mean_scaled_jacobian <= 1);
    coons_volume_mesh_free(vm);
    coons_body_free(b);
}

/* Knupp's scaled Jacobian of known cells: a cube 1; a parallelepiped with
 * edges a, b, c: det of the unit edge vectors (the same at every corner). */
static void test_scaled_jacobian(void **state)
{
    (void)state;
    const double a[3] = {2, 0, 0}, bb[3] = {1, 1, 0}, cc[3] = {0, 0.5, 3};
    double c[8][3];
    for (int i = 0; i < 8; i++) {
        int u = i >> 2 & 1, v = i >> 1 & 1, w = i & 1; /* P_ijk at 4i+2j+k */
        for (int d = 0; d < 3; d++) c[i][d] = u * a[d] + v * bb[d] + w * cc[d];
    }
    coons_body *b = body0((const double(*)[3])c);
    coons_volume_options o = vopts(COONS_ELEMENT_HEX8, 1, 1, 1);
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_volume_mesh(b, &o, NULL, &vm, &e), &e);
    double la = 2, lb = sqrt(2.0), lc = sqrt(0.25 + 9);
    double want = (a[0] * (bb[1] * cc[2] - bb[2] * cc[1]) - a[1] * (bb[0] * cc[2] - bb[2] * cc[0]) +
                   a[2] * (bb[0] * cc[1] - bb[1] * cc[0])) /
                  (la * lb * lc);
    int col = 1;
    assert_near(coons_volume_mesh_cell_scaled_jacobian(vm, 0, &col), want, 1e-15);
    assert_int_equal(col, 0);
    assert_true(isnan(coons_volume_mesh_cell_scaled_jacobian(vm, 1, NULL)));
    assert_near(field(vm, COONS_FIELD_CELL, "scaled_jacobian")[0], want, 1e-15);
    coons_volume_mesh_free(vm);
    coons_body_free(b);
}

/* A left-handed body: cells mirrored, valid; det_j negative. */
static void test_left_handed(void **state)
{
    (void)state;
    double c[8][3];
    const double (*h)[3] = tb_hex();
    for (int i = 0; i < 8; i++) memcpy(c[i], h[i ^ 4], sizeof c[i]); /* u -> 1 - u */
    coons_body *b = body0((const double(*)[3])c);
    coons_volume_options o = vopts(COONS_ELEMENT_HEX20, 2, 2, 2);
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_volume_mesh(b, &o, NULL, &vm, &e), &e);
    coons_volume_quality q = COONS_VOLUME_QUALITY_INIT;
    assert_coons_ok(coons_volume_mesh_quality(vm, 0, &q, &e), &e);
    assert_int_equal(q.inverted, 0);
    assert_true(q.min_scaled_jacobian > 0.3);
    const double *dj = field(vm, COONS_FIELD_NODE, "det_j");
    for (size_t n = 0; n < coons_volume_mesh_node_count(vm); n++) assert_true(dj[n] < 0);
    /* The face set u0 uses the cells' local face r1 (mirrored). */
    const uint32_t *pairs;
    size_t cnt;
    coons_volume_mesh_face_set(vm, 0, &pairs, &cnt);
    assert_int_equal(cnt, 4);
    for (size_t i = 0; i < cnt; i++) assert_int_equal(pairs[2 * i + 1], 1);
    /* and its corners lie on the body's u = 0 face */
    const double *u = field(vm, COONS_FIELD_NODE, "u");
    const uint32_t *cells = coons_volume_mesh_cells(vm);
    static const int R1[4] = {1, 2, 6, 5};
    for (size_t i = 0; i < cnt; i++)
        for (int z = 0; z < 4; z++) assert_true(u[cells[20 * pairs[2 * i] + (size_t)R1[z]]] == 0.0);
    coons_volume_mesh_free(vm);
    coons_body_free(b);
}

/* Face u0 collapsed to a point: the cells there are pyramids (a repeated
 * corner node), counted as collapsed, never as inverted. */
static void test_apex(void **state)
{
    (void)state;
    double c[8][3];
    for (int i = 0; i < 8; i++) {
        int u = i >> 2 & 1, v = i >> 1 & 1, w = i & 1;
        c[i][0] = u;
        c[i][1] = u * (v - 0.5);
        c[i][2] = u * (w - 0.5);
    }
    coons_body *b = body0((const double(*)[3])c);
    coons_volume_options o = vopts(COONS_ELEMENT_HEX8, 3, 2, 2);
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_volume_mesh(b, &o, NULL, &vm, &e), &e);
    assert_int_equal(coons_volume_mesh_node_count(vm), 1 + 3 * 9);
    assert_int_equal(coons_volume_mesh_cell_count(vm), 12);
    coons_volume_quality q = COONS_VOLUME_QUALITY_INIT;
    assert_coons_ok(coons_volume_mesh_quality(vm, 0, &q, &e), &e);
    assert_int_equal(q.collapsed, 4);
    assert_int_equal(q.inverted, 0);
    assert_true(q.min_scaled_jacobian > 0);
    /* The collapsed face has no faces in its set; the others all theirs. */
    size_t cnt;
    coons_volume_mesh_face_set(vm, 0, NULL, &cnt);
    assert_int_equal(cnt, 0);
    coons_volume_mesh_face_set(vm, 1, NULL, &cnt);
    assert_int_equal(cnt, 4);
    coons_volume_mesh_free(vm);
    coons_body_free(b);
}

/* A closed NURBS tube: faces u0 and u1 (or whichever close) coincide and
 * share their nodes; the mesh is conformal across the seam. */
static void test_closed_tube(void **state)
{
    (void)state;
    coons_body *b = NULL;
    tb_nurbs_cylinder(1.0, 2.0, &b);
    coons_volume_options o = vopts(COONS_ELEMENT_HEX8, 8, 8, 2);
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_volume_mesh(b, &o, NULL, &vm, &e), &e);
    size_t raw = 9 * 9 * 3;
    assert_true(coons_volume_mesh_node_count(vm) < raw);
    /* The seam's two faces are inside the body: exactly one direction has
     * both face sets empty, and the other faces keep theirs. */
    int empty_pairs = 0;
    for (int ax = 0; ax < 3; ax++) {
        size_t c0, c1;
        coons_volume_mesh_face_set(vm, (size_t)(2 * ax), NULL, &c0);
        coons_volume_mesh_face_set(vm, (size_t)(2 * ax + 1), NULL, &c1);
        empty_pairs += c0 == 0 && c1 == 0;
    }
    assert_int_equal(empty_pairs, 1);
    coons_volume_quality q = COONS_VOLUME_QUALITY_INIT;
    assert_coons_ok(coons_volume_mesh_quality(vm, 0, &q, &e), &e);
    assert_int_equal(q.inverted, 0);
    coons_volume_mesh_free(vm);
    coons_body_free(b);
}

static coons_model *load(const char *json)
{
    coons_model *m = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_model_load_memory(json, strlen(json), "test.json", NULL, &m, &e), &e);
    return m;
}

/* Two unit boxes sharing the face x = 1: one conformal mesh; two
 * overlapping boxes: refused naming both. */
static void test_model(void **state)
{
    (void)state;
    const char *two = "{\"coons\": 1, \"bodies\": ["
                      "{\"type\": \"body0\", \"name\": \"a\", \"corners\": [[0,0,0],[0,0,1],"
                      "[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]},"
                      "{\"type\": \"body0\", \"name\": \"b\", \"corners\": [[1,0,0],[1,0,1],"
                      "[1,1,0],[1,1,1],[2,0,0],[2,0,1],[2,1,0],[2,1,1]]}]}";
    coons_model *m = load(two);
    coons_volume_options o = vopts(COONS_ELEMENT_HEX8, 2, 2, 2);
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_model_volume_mesh(m, &o, &vm, &e), &e);
    assert_int_equal(coons_volume_mesh_part_count(vm), 2);
    assert_int_equal(coons_volume_mesh_cell_count(vm), 16);
    assert_int_equal(coons_volume_mesh_node_count(vm), 5 * 3 * 3);
    check_conformal(vm, 2 * (2 * 2 + 4 * 2 + 4 * 2));
    const int32_t *body = (const int32_t *)(const void *)field(vm, COONS_FIELD_CELL, "body");
    assert_int_equal(body[0], 0);
    assert_int_equal(body[15], 1);
    assert_string_equal(coons_volume_mesh_node_set(vm, 7, NULL, NULL), "b.u1");
    coons_volume_mesh_free(vm);
    coons_model_free(m);

    /* Body b is a box whose parameters run along y, -x, z: its face v1 is
     * a's face u1 with swapped and flipped parameters; the lattices the
     * sampler picks differ (b is twice as long), yet the shared face gets
     * one lattice and one set of nodes. */
    const char *turned = "{\"coons\": 1, \"tolerance\": 0.01, \"bodies\": ["
                         "{\"type\": \"body0\", \"name\": \"a\", \"corners\": [[0,0,0],[0,0,1],"
                         "[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]},"
                         "{\"type\": \"body0\", \"name\": \"b\", \"corners\": [[3,0,0],[3,0,1],"
                         "[1,0,0],[1,0,1],[3,1,0],[3,1,1],[1,1,0],[1,1,1]]}]}";
    m = load(turned);
    for (int el = 0; el < 2; el++) {
        coons_volume_options ot = COONS_VOLUME_OPTIONS_INIT;
        ot.element = el ? COONS_ELEMENT_HEX27 : COONS_ELEMENT_HEX8;
        assert_coons_ok(coons_model_volume_mesh(m, &ot, &vm, &e), &e);
        coons_volume_quality qa = COONS_VOLUME_QUALITY_INIT, qb = COONS_VOLUME_QUALITY_INIT;
        assert_coons_ok(coons_volume_mesh_quality(vm, 0, &qa, &e), &e);
        assert_coons_ok(coons_volume_mesh_quality(vm, 1, &qb, &e), &e);
        size_t shared;
        coons_volume_mesh_node_set(vm, 1, NULL, &shared); /* a.u1 */
        assert_true(shared > 4);
        assert_int_equal(coons_volume_mesh_node_count(vm), qa.nodes + qb.nodes - shared);
        /* every node of a.u1 is one of b.v1's */
        const uint32_t *na, *nbv;
        size_t ca, cb;
        coons_volume_mesh_node_set(vm, 1, &na, &ca);
        coons_volume_mesh_node_set(vm, 6 + 3, &nbv, &cb);
        assert_int_equal(ca, cb);
        for (size_t i = 0; i < ca; i++) {
            int found = 0;
            for (size_t j = 0; j < cb; j++) found |= na[i] == nbv[j];
            assert_true(found);
        }
        assert_int_equal(qa.inverted + qb.inverted, 0);
        if (!el) {
            /* conformal: interior quadrangles in two cells; the boundary is
             * the 12 faces' quadrangles but the shared face's, twice */
            size_t bnd = 0, inner;
            for (int f = 0; f < 12; f++) {
                size_t c;
                coons_volume_mesh_face_set(vm, (size_t)f, NULL, &c);
                bnd += c;
            }
            coons_volume_mesh_face_set(vm, 1, NULL, &inner);
            check_conformal(vm, bnd - 2 * inner);
        }
        coons_volume_mesh_free(vm);
    }
    coons_model_free(m);

    const char *overlap = "{\"coons\": 1, \"bodies\": ["
                          "{\"type\": \"body0\", \"name\": \"a\", \"corners\": [[0,0,0],[0,0,1],"
                          "[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]},"
                          "{\"type\": \"body0\", \"name\": \"b\", \"corners\": [[0.5,0,0],"
                          "[0.5,0,1],[0.5,1,0],[0.5,1,1],[2,0,0],[2,0,1],[2,1,0],[2,1,1]]}]}";
    m = load(overlap);
    assert_int_equal(coons_model_volume_mesh(m, &o, &vm, &e), COONS_E_UNSUPPORTED);
    assert_null(vm);
    assert_non_null(strstr(e.message, "'a' and 'b'"));
    coons_model_free(m);
}

static void test_errors(void **state)
{
    (void)state;
    coons_body *b = body0(tb_hex());
    coons_volume_mesh *vm = (coons_volume_mesh *)b; /* must be reset to NULL */
    coons_error e = COONS_ERROR_INIT;
    coons_volume_options o = vopts(COONS_ELEMENT_HEX8, 2, 0, 2);
    assert_int_equal(coons_body_volume_mesh(b, &o, NULL, &vm, &e), COONS_E_INVALID);
    assert_null(vm);
    o = vopts((coons_element)9, 0, 0, 0);
    assert_int_equal(coons_body_volume_mesh(b, &o, NULL, &vm, &e), COONS_E_INVALID);
    o = vopts(COONS_ELEMENT_HEX8, 0, 0, 0);
    o.version = 99;
    assert_int_equal(coons_body_volume_mesh(b, &o, NULL, &vm, &e), COONS_E_INVALID);
    /* 2^20 per direction: refused by the cell limit before any allocation
     * of that size (this would need 2^60 cells). */
    o = vopts(COONS_ELEMENT_HEX27, 1u << 20, 1u << 20, 1u << 20);
    long before = coons_test_alloc_count();
    assert_int_equal(coons_body_volume_mesh(b, &o, NULL, &vm, &e), COONS_E_LIMIT);
    assert_non_null(strstr(e.message, "limit"));
    assert_true(coons_test_alloc_count() - before < 16);
    o = vopts(COONS_ELEMENT_HEX8, 10, 10, 10);
    o.max_cells = 999;
    assert_int_equal(coons_body_volume_mesh(b, &o, NULL, &vm, &e), COONS_E_LIMIT);
    coons_volume_quality q = COONS_VOLUME_QUALITY_INIT;
    q.version = 0;
    o = vopts(COONS_ELEMENT_HEX8, 1, 1, 1);
    assert_coons_ok(coons_body_volume_mesh(b, &o, NULL, &vm, &e), &e);
    assert_int_equal(coons_volume_mesh_quality(vm, 0, &q, &e), COONS_E_INVALID);
    coons_volume_quality_init(&q);
    assert_int_equal(coons_volume_mesh_quality(vm, 1, &q, &e), COONS_E_INVALID);
    coons_volume_mesh_free(vm);
    coons_body_free(b);
}

/* The default lattice is the boundary sampler's: the same intervals as
 * coons_body_sample() reports at the same tolerance. */
static void test_sampled_lattice(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    coons_body *b = NULL;
    tb_nurbs_cylinder(1.0, 2.0, &b);
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.tolerance = 1e-3;
    coons_mesh *m = NULL;
    assert_coons_ok(coons_body_sample(b, &so, "t", &m, &e), &e);
    size_t lat[3];
    assert_true(coons_mesh_part_sampling(m, 0, NULL, NULL, lat));
    coons_volume_options o = COONS_VOLUME_OPTIONS_INIT;
    o.tolerance = 1e-3;
    coons_volume_mesh *vm = NULL;
    assert_coons_ok(coons_body_volume_mesh(b, &o, NULL, &vm, &e), &e);
    assert_int_equal(coons_volume_mesh_cell_count(vm), lat[0] * lat[1] * lat[2]);
    coons_volume_mesh_free(vm);
    coons_mesh_free(m);
    coons_body_free(b);
}

static void test_alloc_failures(void **state)
{
    (void)state;
    coons_body *b = body0(tb_hex());
    coons_volume_options o = vopts(COONS_ELEMENT_HEX20, 2, 1, 1);
    for (long n = 0;; n++) {
        coons_volume_mesh *vm = NULL;
        coons_error e = COONS_ERROR_INIT;
        long live = coons_test_live_allocs();
        coons_test_fail_after(n);
        coons_status st = coons_body_volume_mesh(b, &o, NULL, &vm, &e);
        coons_test_fail_after(-1);
        if (st == COONS_OK) {
            coons_volume_mesh_free(vm);
            break;
        }
        assert_int_equal(st, COONS_E_NOMEM);
        assert_null(vm);
        assert_int_equal(coons_test_live_allocs(), live);
    }
    coons_body_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_counts),          cmocka_unit_test(test_isoparametric),
        cmocka_unit_test(test_volume_and_conformity), cmocka_unit_test(test_scaled_jacobian),
        cmocka_unit_test(test_left_handed),     cmocka_unit_test(test_apex),
        cmocka_unit_test(test_closed_tube),     cmocka_unit_test(test_model),
        cmocka_unit_test(test_errors),          cmocka_unit_test(test_sampled_lattice),
        cmocka_unit_test(test_alloc_failures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
