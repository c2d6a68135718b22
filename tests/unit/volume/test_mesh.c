/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The volume mesh container (include/coons/volume.h): construction, parts,
 * fields, node/cell/face sets, borrowed views that are copies of the
 * inputs, every validation error (each leaving the mesh as it was), and
 * allocation failure at every allocation point. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"

/* A 2 x 1 x 1 lattice of unit cubes: 3 x 2 x 2 nodes, node (i,j,k) at
 * index i + 3 (j + 2 k), two hex8 cells in Gmsh corner order. */
static double grid[12][3];
static uint32_t cells2[2][8];

static void make_grid(void)
{
    for (int k = 0; k < 2; k++)
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 3; i++) {
                double *p = grid[i + 3 * (j + 2 * k)];
                p[0] = i;
                p[1] = j;
                p[2] = k;
            }
    for (uint32_t c = 0; c < 2; c++) {
        /* corners (0,0,0) (1,0,0) (1,1,0) (0,1,0) then the same at z = 1 */
        static const int off[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                      {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
        for (int n = 0; n < 8; n++)
            cells2[c][n] = (uint32_t)(c + (uint32_t)off[n][0] +
                                      3 * ((uint32_t)off[n][1] + 2 * (uint32_t)off[n][2]));
    }
}

static coons_volume_mesh *grid_mesh(void)
{
    coons_volume_mesh *vm = NULL;
    coons_error e = COONS_ERROR_INIT;
    make_grid();
    assert_coons_ok(coons_volume_mesh_new(COONS_ELEMENT_HEX8, &vm, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, &grid[0][0], 12, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_part(vm, "seat", NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, &cells2[0][0], 2, 0, NULL, &e), &e);
    return vm;
}

static void test_construction(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    static const coons_element kinds[3] = {COONS_ELEMENT_HEX8, COONS_ELEMENT_HEX20,
                                           COONS_ELEMENT_HEX27};
    for (int i = 0; i < 3; i++) {
        coons_volume_mesh *vm = NULL;
        assert_coons_ok(coons_volume_mesh_new(kinds[i], &vm, &e), &e);
        assert_int_equal(coons_volume_mesh_element(vm), kinds[i]);
        assert_int_equal(coons_volume_mesh_nodes_per_cell(vm), (size_t)kinds[i]);
        assert_int_equal(coons_volume_mesh_node_count(vm), 0);
        assert_int_equal(coons_volume_mesh_cell_count(vm), 0);
        assert_int_equal(coons_volume_mesh_part_count(vm), 0);
        assert_null(coons_volume_mesh_part_name(vm, 0));
        coons_volume_mesh_free(vm);
    }
    coons_volume_mesh_free(NULL);

    make_grid();
    coons_volume_mesh *vm = NULL;
    assert_coons_ok(coons_volume_mesh_new(COONS_ELEMENT_HEX8, &vm, &e), &e);
    size_t first = 99;
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, &grid[0][0], 6, &first, &e), &e);
    assert_int_equal(first, 0);
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, &grid[6][0], 6, &first, &e), &e);
    assert_int_equal(first, 6);
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, NULL, 0, &first, &e), &e);
    assert_int_equal(first, 12);
    assert_int_equal(coons_volume_mesh_node_count(vm), 12);
    size_t part = 99;
    assert_coons_ok(coons_volume_mesh_add_part(vm, "seat", &part, &e), &e);
    assert_int_equal(part, 0);
    assert_coons_ok(coons_volume_mesh_add_part(vm, NULL, &part, &e), &e);
    assert_int_equal(part, 1);
    assert_string_equal(coons_volume_mesh_part_name(vm, 1), "part1");
    assert_coons_ok(coons_volume_mesh_add_cells(vm, cells2[0], 1, 1, &first, &e), &e);
    assert_int_equal(first, 0);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, cells2[1], 1, 0, &first, &e), &e);
    assert_int_equal(first, 1);
    assert_int_equal(coons_volume_mesh_cell_count(vm), 2);
    /* The views are copies: changing the inputs afterwards changes nothing. */
    double keep = grid[7][1];
    grid[7][1] = 42.0;
    uint32_t keepc = cells2[1][3];
    cells2[1][3] = 0;
    assert_near(coons_volume_mesh_nodes(vm)[3 * 7 + 1], keep, 0.0);
    assert_int_equal(coons_volume_mesh_cells(vm)[8 + 3], keepc);
    make_grid();
    assert_memory_equal(coons_volume_mesh_nodes(vm), grid, sizeof grid);
    assert_memory_equal(coons_volume_mesh_cells(vm), cells2, sizeof cells2);
    assert_int_equal(coons_volume_mesh_cell_parts(vm)[0], 1);
    assert_int_equal(coons_volume_mesh_cell_parts(vm)[1], 0);
    assert_string_equal(coons_volume_mesh_part_name(vm, 0), "seat");
    assert_null(coons_volume_mesh_part_name(vm, 2));
    /* A collapsed cell (repeated nodes) is allowed. */
    const uint32_t apex[8] = {0, 1, 4, 3, 6, 6, 6, 6};
    assert_coons_ok(coons_volume_mesh_add_cells(vm, apex, 1, 0, NULL, &e), &e);
    assert_int_equal(coons_volume_mesh_cell_count(vm), 3);
    coons_volume_mesh_free(vm);
}

static void test_fields(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    coons_volume_mesh *vm = grid_mesh();
    double u[12], sj[2] = {1.0, 0.5};
    for (int i = 0; i < 12; i++) u[i] = grid[i][0] / 2.0;
    const int32_t body[2] = {0, -7};
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "u", COONS_FIELD_FLOAT64, u,
                                                &e), &e);
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "body", COONS_FIELD_INT32,
                                                body, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "scaled_jacobian",
                                                COONS_FIELD_FLOAT64, sj, &e), &e);
    /* The same name at the other location is another field. */
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "body", COONS_FIELD_INT32,
                                                (int32_t[12]){0}, &e), &e);
    u[3] = -1.0;
    assert_int_equal(coons_volume_mesh_field_count(vm, COONS_FIELD_NODE), 2);
    assert_int_equal(coons_volume_mesh_field_count(vm, COONS_FIELD_CELL), 2);
    assert_int_equal(coons_volume_mesh_field_count(vm, (coons_field_location)5), 0);
    coons_field_type t = COONS_FIELD_INT32;
    const void *v = NULL;
    assert_string_equal(coons_volume_mesh_field(vm, COONS_FIELD_NODE, 0, &t, &v), "u");
    assert_int_equal(t, COONS_FIELD_FLOAT64);
    assert_near(((const double *)v)[3], 0.0, 0.0);
    assert_near(((const double *)v)[11], 1.0, 0.0);
    assert_string_equal(coons_volume_mesh_field(vm, COONS_FIELD_CELL, 0, &t, &v), "body");
    assert_int_equal(t, COONS_FIELD_INT32);
    assert_int_equal(((const int32_t *)v)[1], -7);
    assert_string_equal(coons_volume_mesh_field(vm, COONS_FIELD_CELL, 1, &t, NULL),
                        "scaled_jacobian");
    assert_int_equal(t, COONS_FIELD_FLOAT64);
    assert_null(coons_volume_mesh_field(vm, COONS_FIELD_CELL, 2, &t, &v));
    assert_null(v);
    assert_int_equal(t, COONS_FIELD_FLOAT64);
    assert_null(coons_volume_mesh_field(vm, (coons_field_location)2, 0, NULL, NULL));
    coons_volume_mesh_free(vm);
}

static void test_sets(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    coons_volume_mesh *vm = grid_mesh();
    uint32_t nodes[4] = {0, 3, 6, 9}, cells[2] = {1, 1}, faces[4] = {0, 0, 1, 1};
    assert_coons_ok(coons_volume_mesh_add_node_set(vm, "seat.u0", nodes, 4, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cell_set(vm, "seat", cells, 2, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_face_set(vm, "seat.u0+column.u1", faces, 2, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_node_set(vm, "empty", NULL, 0, &e), &e);
    /* Names are unique per kind only. */
    assert_coons_ok(coons_volume_mesh_add_face_set(vm, "seat", faces, 1, &e), &e);
    nodes[1] = 5;
    faces[3] = 4;
    assert_int_equal(coons_volume_mesh_node_set_count(vm), 2);
    assert_int_equal(coons_volume_mesh_cell_set_count(vm), 1);
    assert_int_equal(coons_volume_mesh_face_set_count(vm), 2);
    const uint32_t *items = NULL;
    size_t n = 0;
    assert_string_equal(coons_volume_mesh_node_set(vm, 0, &items, &n), "seat.u0");
    assert_int_equal(n, 4);
    assert_int_equal(items[1], 3);
    assert_int_equal(items[3], 9);
    assert_string_equal(coons_volume_mesh_node_set(vm, 1, &items, &n), "empty");
    assert_int_equal(n, 0);
    assert_string_equal(coons_volume_mesh_cell_set(vm, 0, &items, &n), "seat");
    assert_int_equal(n, 2);
    assert_int_equal(items[0], 1);
    assert_string_equal(coons_volume_mesh_face_set(vm, 0, &items, &n), "seat.u0+column.u1");
    assert_int_equal(n, 2);
    assert_int_equal(items[2], 1);
    assert_int_equal(items[3], 1);
    assert_null(coons_volume_mesh_face_set(vm, 2, &items, &n));
    assert_null(items);
    assert_int_equal(n, 0);
    assert_null(coons_volume_mesh_cell_set(vm, 1, NULL, NULL));
    assert_null(coons_volume_mesh_node_set(vm, 9, &items, NULL));
    coons_volume_mesh_free(vm);
}

/* Asserts the call failed with `code` and a message containing `word`. */
#define assert_fails(call, want, word)                                                   \
    do {                                                                                 \
        coons_error e_ = COONS_ERROR_INIT;                                               \
        coons_error *err = &e_;                                                          \
        int rc_ = (call);                                                                \
        if (rc_ != (want)) fail_msg("%s -> %d, expected %d: %s", #call, rc_, want,      \
                                    e_.message);                                         \
        assert_int_equal(e_.code, (want));                                               \
        if (!strstr(e_.message, (word)))                                                 \
            fail_msg("%s: message '%s' lacks '%s'", #call, e_.message, (word));          \
    } while (0)

/* Node, cell, part, field and set counts, to show a failed call changed
 * nothing. */
static void counts(const coons_volume_mesh *vm, size_t out[8])
{
    out[0] = coons_volume_mesh_node_count(vm);
    out[1] = coons_volume_mesh_cell_count(vm);
    out[2] = coons_volume_mesh_part_count(vm);
    out[3] = coons_volume_mesh_field_count(vm, COONS_FIELD_NODE);
    out[4] = coons_volume_mesh_field_count(vm, COONS_FIELD_CELL);
    out[5] = coons_volume_mesh_node_set_count(vm);
    out[6] = coons_volume_mesh_cell_set_count(vm);
    out[7] = coons_volume_mesh_face_set_count(vm);
}

static void test_validation(void **state)
{
    (void)state;
    coons_volume_mesh *out = (coons_volume_mesh *)&out;
    assert_fails(coons_volume_mesh_new((coons_element)9, &out, err), COONS_E_INVALID, "hex8");
    assert_null(out);
    assert_fails(coons_volume_mesh_new(COONS_ELEMENT_HEX8, NULL, err), COONS_E_INVALID, "output");

    coons_volume_mesh *vm = grid_mesh();
    size_t before[8], after[8];
    counts(vm, before);
    const double bad[6] = {0, 0, 0, 1, NAN, 0};
    const double inf[3] = {INFINITY, 0, 0};
    assert_fails(coons_volume_mesh_add_nodes(vm, bad, 2, NULL, err), COONS_E_INVALID, "node 13");
    assert_fails(coons_volume_mesh_add_nodes(vm, inf, 1, NULL, err), COONS_E_INVALID,
                 "not finite");
    assert_fails(coons_volume_mesh_add_nodes(vm, NULL, 1, NULL, err), COONS_E_INVALID,
                 "coordinates");
    assert_fails(coons_volume_mesh_add_nodes(NULL, bad, 1, NULL, err), COONS_E_INVALID, "mesh");
    /* Limits are checked before the input is read. */
    assert_fails(coons_volume_mesh_add_nodes(vm, inf, (size_t)UINT32_MAX - 11, NULL, err),
                 COONS_E_LIMIT, "4294967295");
    assert_fails(coons_volume_mesh_add_nodes(vm, inf, SIZE_MAX, NULL, err), COONS_E_LIMIT,
                 "nodes");
    const uint32_t far[8] = {0, 1, 4, 3, 6, 7, 10, 12};
    assert_fails(coons_volume_mesh_add_cells(vm, far, 1, 0, NULL, err), COONS_E_INVALID,
                 "cell 2 (new cell 0), node 7: index 12");
    assert_fails(coons_volume_mesh_add_cells(vm, cells2[0], 1, 1, NULL, err), COONS_E_INVALID,
                 "part 1");
    assert_fails(coons_volume_mesh_add_cells(vm, NULL, 1, 0, NULL, err), COONS_E_INVALID,
                 "nodes");
    assert_fails(coons_volume_mesh_add_cells(NULL, cells2[0], 1, 0, NULL, err), COONS_E_INVALID,
                 "mesh");
    assert_fails(coons_volume_mesh_add_cells(vm, far, (size_t)UINT32_MAX - 1, 0, NULL, err),
                 COONS_E_LIMIT, "cells");
    assert_fails(coons_volume_mesh_add_cells(vm, far, SIZE_MAX / 4, 0, NULL, err), COONS_E_LIMIT,
                 "cells");
    char longname[COONS_VOLUME_NAME_MAX + 2];
    memset(longname, 'a', sizeof longname - 1);
    longname[sizeof longname - 1] = '\0';
    assert_fails(coons_volume_mesh_add_part(vm, "seat", NULL, err), COONS_E_INVALID, "taken");
    assert_fails(coons_volume_mesh_add_part(vm, "", NULL, err), COONS_E_INVALID, "no name");
    assert_fails(coons_volume_mesh_add_part(vm, "a\tb", NULL, err), COONS_E_INVALID, "0x09");
    assert_fails(coons_volume_mesh_add_part(vm, longname, NULL, err), COONS_E_INVALID, "256");
    assert_fails(coons_volume_mesh_add_part(NULL, "x", NULL, err), COONS_E_INVALID, "mesh");
    longname[COONS_VOLUME_NAME_MAX] = '\0'; /* 255 bytes: fine, tested below */

    double u[12] = {0};
    assert_fails(coons_volume_mesh_add_field(vm, (coons_field_location)2, "u",
                                             COONS_FIELD_FLOAT64, u, err),
                 COONS_E_INVALID, "location");
    assert_fails(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "u", (coons_field_type)3, u,
                                             err),
                 COONS_E_INVALID, "type");
    static const char *const names[] = {"1u", "a b", "u-v", "det.j"};
    for (size_t i = 0; i < 4; i++)
        assert_fails(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, names[i],
                                                 COONS_FIELD_FLOAT64, u, err),
                     COONS_E_INVALID, "identifier");
    assert_fails(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "", COONS_FIELD_FLOAT64, u,
                                             err),
                 COONS_E_INVALID, "no name");
    assert_fails(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, NULL, COONS_FIELD_FLOAT64, u,
                                             err),
                 COONS_E_INVALID, "no name");
    assert_fails(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "u", COONS_FIELD_FLOAT64, NULL,
                                             err),
                 COONS_E_INVALID, "no values");
    assert_fails(coons_volume_mesh_add_field(NULL, COONS_FIELD_NODE, "u", COONS_FIELD_FLOAT64, u,
                                             err),
                 COONS_E_INVALID, "mesh");
    u[11] = INFINITY;
    assert_fails(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "det_j", COONS_FIELD_FLOAT64,
                                             u, err),
                 COONS_E_INVALID, "'det_j': the value of node 11");
    double sj[2] = {NAN, 1};
    assert_fails(coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "sj", COONS_FIELD_FLOAT64, sj,
                                             err),
                 COONS_E_INVALID, "cell 0");
    const uint32_t nodes[2] = {11, 12}, cells[2] = {0, 2}, pairs[4] = {1, 5, 0, 6};
    assert_fails(coons_volume_mesh_add_node_set(vm, "n", nodes, 2, err), COONS_E_INVALID,
                 "entry 1: node 12");
    assert_fails(coons_volume_mesh_add_cell_set(vm, "c", cells, 2, err), COONS_E_INVALID,
                 "entry 1: cell 2");
    assert_fails(coons_volume_mesh_add_face_set(vm, "f", pairs, 2, err), COONS_E_INVALID,
                 "local face 6");
    const uint32_t pairs2[2] = {2, 0};
    assert_fails(coons_volume_mesh_add_face_set(vm, "f", pairs2, 1, err), COONS_E_INVALID,
                 "cell 2");
    assert_fails(coons_volume_mesh_add_node_set(vm, "n", NULL, 1, err), COONS_E_INVALID,
                 "no indices");
    assert_fails(coons_volume_mesh_add_cell_set(vm, "x\x7f", cells, 1, err), COONS_E_INVALID,
                 "0x7f");
    assert_fails(coons_volume_mesh_add_face_set(vm, NULL, pairs, 1, err), COONS_E_INVALID,
                 "no name");
    assert_fails(coons_volume_mesh_add_face_set(vm, "f", pairs, SIZE_MAX / 4, err), COONS_E_LIMIT,
                 "too large");
    assert_fails(coons_volume_mesh_add_node_set(NULL, "n", nodes, 1, err), COONS_E_INVALID,
                 "mesh");
    counts(vm, after);
    assert_memory_equal(before, after, sizeof before);
    assert_memory_equal(coons_volume_mesh_nodes(vm), grid, sizeof grid);

    /* Repeated names; the longest allowed name. */
    coons_error e = COONS_ERROR_INIT;
    u[11] = 0;
    assert_coons_ok(coons_volume_mesh_add_part(vm, longname, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "u", COONS_FIELD_FLOAT64, u,
                                                &e), &e);
    assert_fails(coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "u", COONS_FIELD_INT32, u, err),
                 COONS_E_INVALID, "'u' is already taken");
    assert_coons_ok(coons_volume_mesh_add_node_set(vm, "n", nodes, 1, &e), &e);
    assert_fails(coons_volume_mesh_add_node_set(vm, "n", nodes, 1, err), COONS_E_INVALID, "taken");
    assert_coons_ok(coons_volume_mesh_add_cell_set(vm, "c", cells, 1, &e), &e);
    assert_fails(coons_volume_mesh_add_cell_set(vm, "c", cells, 1, err), COONS_E_INVALID, "taken");
    assert_coons_ok(coons_volume_mesh_add_face_set(vm, "f", pairs, 1, &e), &e);
    assert_fails(coons_volume_mesh_add_face_set(vm, "f", pairs, 1, err), COONS_E_INVALID, "taken");
    /* Fields come after what they describe. */
    assert_fails(coons_volume_mesh_add_nodes(vm, &grid[0][0], 1, NULL, err), COONS_E_INVALID,
                 "after a node field ('u')");
    assert_coons_ok(coons_volume_mesh_add_cells(vm, cells2[0], 1, 1, NULL, &e), &e);
    int32_t body[3] = {0, 0, 1};
    assert_coons_ok(coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "body", COONS_FIELD_INT32,
                                                body, &e), &e);
    assert_fails(coons_volume_mesh_add_cells(vm, cells2[0], 1, 1, NULL, err), COONS_E_INVALID,
                 "after a cell field ('body')");
    /* Adding nothing is still fine. */
    assert_coons_ok(coons_volume_mesh_add_nodes(vm, NULL, 0, NULL, &e), &e);
    assert_coons_ok(coons_volume_mesh_add_cells(vm, NULL, 0, 0, NULL, &e), &e);
    assert_int_equal(coons_volume_mesh_cell_count(vm), 3);
    coons_volume_mesh_free(vm);
}

/* Builds a hex27 mesh with everything in it: every step allocates. */
static coons_status build_all(coons_volume_mesh **out, coons_error *err)
{
    static double xyz[27][3];
    static uint32_t cell[27];
    for (int i = 0; i < 27; i++) {
        xyz[i][0] = i % 3;
        xyz[i][1] = (i / 3) % 3;
        xyz[i][2] = i / 9;
        cell[i] = (uint32_t)i;
    }
    double f[27] = {0};
    int32_t b[1] = {3};
    const uint32_t pairs[2] = {0, 5};
    coons_volume_mesh *vm = NULL;
    coons_status st = coons_volume_mesh_new(COONS_ELEMENT_HEX27, &vm, err);
    if (st == COONS_OK) st = coons_volume_mesh_add_nodes(vm, &xyz[0][0], 20, NULL, err);
    if (st == COONS_OK) st = coons_volume_mesh_add_nodes(vm, &xyz[20][0], 7, NULL, err);
    if (st == COONS_OK) st = coons_volume_mesh_add_part(vm, "a", NULL, err);
    if (st == COONS_OK) st = coons_volume_mesh_add_part(vm, NULL, NULL, err);
    if (st == COONS_OK) st = coons_volume_mesh_add_cells(vm, cell, 1, 1, NULL, err);
    if (st == COONS_OK)
        st = coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "u", COONS_FIELD_FLOAT64, f, err);
    if (st == COONS_OK)
        st = coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "b", COONS_FIELD_INT32, b, err);
    if (st == COONS_OK) st = coons_volume_mesh_add_node_set(vm, "n", cell, 27, err);
    if (st == COONS_OK) st = coons_volume_mesh_add_cell_set(vm, "c", cell, 1, err);
    if (st == COONS_OK) st = coons_volume_mesh_add_face_set(vm, "f", pairs, 1, err);
    if (st == COONS_OK) st = coons_volume_mesh_add_face_set(vm, "g", NULL, 0, err);
    *out = vm;
    return st;
}

/* Given allocations failing at the k-th point, for every k: the failing
 * call returns COONS_E_NOMEM with a message, the mesh keeps exactly what
 * the calls before it added, and freeing it leaves nothing allocated. */
static void test_allocation_failures(void **state)
{
    (void)state;
    coons_volume_mesh *ref = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(build_all(&ref, &e), &e);
    size_t full[8];
    counts(ref, full);
    coons_volume_mesh_free(ref);
    long points = 0;
    for (long k = 0;; k++) {
        coons_volume_mesh *vm = NULL;
        coons_error err = COONS_ERROR_INIT;
        coons_test_fail_after(k);
        coons_status st = build_all(&vm, &err);
        long used = coons_test_alloc_count();
        if (st == COONS_OK && used <= k) {
            coons_volume_mesh_free(vm);
            assert_int_equal(coons_test_live_allocs(), 0);
            coons_test_fail_after(-1);
            break;
        }
        assert_int_equal(st, COONS_E_NOMEM);
        assert_int_equal(err.code, COONS_E_NOMEM);
        assert_true(err.message[0] != '\0');
        if (vm) {
            size_t got[8];
            counts(vm, got);
            /* Whatever was added is whole: a prefix of the full build. */
            for (int i = 0; i < 8; i++) assert_true(got[i] <= full[i]);
            if (got[0] > 0) assert_true(got[0] == 20 || got[0] == 27);
        }
        coons_volume_mesh_free(vm);
        assert_int_equal(coons_test_live_allocs(), 0);
        coons_test_fail_after(-1);
        points++;
    }
    print_message("%ld allocation points\n", points);
    assert_true(points >= 14);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_construction),
        cmocka_unit_test(test_fields),
        cmocka_unit_test(test_sets),
        cmocka_unit_test(test_validation),
        cmocka_unit_test(test_allocation_failures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
