/* SPDX-License-Identifier: GPL-3.0-or-later */
/* coons_volume_mesh_cell_shape() on bodies that collapse, checked against
 * independent facts: a body whose face u0 is a point has one pyramid per
 * cell at u0 and hexahedra elsewhere, a body whose face u0 is a line has
 * one wedge per cell there (counts from the lattice by hand); every shape's
 * nodes are its cell's distinct corners, and its orientation is positive
 * by signed volume (a wedge's triangle 0 1 2 counter-clockwise seen from
 * 3 4 5, a pyramid's base counter-clockwise seen from the apex); the
 * nail example's shapes agree with the number of distinct corners of each
 * cell; hex20 cells stay hexahedra; bad calls are refused. */
#include <stdio.h>
#include <string.h>

#include "test_util.h"

static double orient(const double *xyz, uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
    const double *p = xyz + 3 * a, *q = xyz + 3 * b, *r = xyz + 3 * c, *s = xyz + 3 * d;
    double e1[3], e2[3], e3[3];
    for (int k = 0; k < 3; k++) e1[k] = q[k] - p[k], e2[k] = r[k] - p[k], e3[k] = s[k] - p[k];
    return (e1[1] * e2[2] - e1[2] * e2[1]) * e3[0] + (e1[2] * e2[0] - e1[0] * e2[2]) * e3[1] +
           (e1[0] * e2[1] - e1[1] * e2[0]) * e3[2];
}

static size_t distinct(const uint32_t *v, size_t n)
{
    size_t d = 0;
    for (size_t i = 0; i < n; i++) {
        size_t j = 0;
        while (j < i && v[j] != v[i]) j++;
        d += j == i;
    }
    return d;
}

/* Counts the shapes of vm into n[3] (hexahedra, wedges, pyramids) and
 * checks each shape against its cell: nodes = the cell's distinct
 * corners, wedges and pyramids distinct and positively oriented. */
static void shapes(const coons_volume_mesh *vm, size_t n[3])
{
    size_t npc = coons_volume_mesh_nodes_per_cell(vm);
    const double *xyz = coons_volume_mesh_nodes(vm);
    n[0] = n[1] = n[2] = 0;
    for (size_t i = 0; i < coons_volume_mesh_cell_count(vm); i++) {
        const uint32_t *h = coons_volume_mesh_cells(vm) + npc * i;
        coons_cell_shape s;
        uint32_t nodes[COONS_VOLUME_CELL_NODES_MAX];
        size_t count = 0;
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(coons_volume_mesh_cell_shape(vm, i, &s, nodes, &count, &e), &e);
        n[s]++;
        if (s == COONS_CELL_HEXAHEDRON) {
            assert_int_equal(count, npc);
            assert_memory_equal(nodes, h, npc * sizeof *h);
            continue;
        }
        assert_int_equal(count, s == COONS_CELL_WEDGE ? 6 : 5);
        assert_int_equal(distinct(nodes, count), count);
        assert_int_equal(distinct(h, 8), count);
        for (size_t k = 0; k < count; k++) {
            size_t j = 0;
            while (j < 8 && h[j] != nodes[k]) j++;
            assert_true(j < 8);
        }
        if (s == COONS_CELL_WEDGE) {
            for (int k = 0; k < 3; k++)
                assert_true(orient(xyz, nodes[0], nodes[1], nodes[2], nodes[3 + k]) > 0);
        } else {
            assert_true(orient(xyz, nodes[0], nodes[1], nodes[2], nodes[4]) > 0);
            assert_true(orient(xyz, nodes[0], nodes[2], nodes[3], nodes[4]) > 0);
        }
    }
}

/* A trilinear body whose face u0 is the point (0,0,0) (`line` 0) or the
 * segment on the z axis (`line` 1), meshed nu x nv x nw. */
static coons_volume_mesh *collapsed(int line, coons_element el, unsigned nu, unsigned nv,
                                    unsigned nw)
{
    double c[8][3];
    for (int i = 0; i < 8; i++) {
        int u = i >> 2 & 1, v = i >> 1 & 1, w = i & 1;
        c[i][0] = u;
        c[i][1] = u * (v - 0.5);
        c[i][2] = line ? w - 0.5 : u * (w - 0.5);
    }
    coons_body *b = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_body0(&c[0][0], COONS_BLEND_LINEAR, &b, &e), &e);
    coons_volume_options o = COONS_VOLUME_OPTIONS_INIT;
    o.element = el;
    o.resolution[0] = nu;
    o.resolution[1] = nv;
    o.resolution[2] = nw;
    coons_volume_mesh *vm = NULL;
    assert_coons_ok(coons_body_volume_mesh(b, &o, NULL, &vm, &e), &e);
    coons_body_free(b);
    return vm;
}

static void test_pyramids_and_wedges(void **state)
{
    (void)state;
    const unsigned nu = 3, nv = 2, nw = 4;
    size_t n[3];
    coons_volume_mesh *vm = collapsed(0, COONS_ELEMENT_HEX8, nu, nv, nw);
    shapes(vm, n);
    assert_int_equal(n[2], nv * nw);
    assert_int_equal(n[1], 0);
    assert_int_equal(n[0], (nu - 1) * nv * nw);
    coons_volume_mesh_free(vm);
    vm = collapsed(1, COONS_ELEMENT_HEX8, nu, nv, nw);
    shapes(vm, n);
    assert_int_equal(n[1], nv * nw);
    assert_int_equal(n[2], 0);
    assert_int_equal(n[0], (nu - 1) * nv * nw);
    coons_volume_mesh_free(vm);
    /* Quadratic cells are never made wedges or pyramids. */
    vm = collapsed(0, COONS_ELEMENT_HEX20, nu, nv, nw);
    shapes(vm, n);
    assert_int_equal(n[0], nu * nv * nw);
    coons_volume_mesh_free(vm);
}

/* The nail's tip collapses: every hex8 cell with 6 distinct corners is a
 * wedge, 5 a pyramid, 8 a hexahedron (this lattice repeats nodes only at
 * collapsed edges and faces), and the tip (a point) gives pyramids. */
static void test_nail(void **state)
{
    (void)state;
    char path[1024];
    snprintf(path, sizeof path, "%s/examples/nail.json", COONS_SOURCE_DIR);
    coons_model *m = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_model_load_file(path, NULL, &m, &e), &e);
    coons_volume_mesh *vm = NULL;
    assert_coons_ok(coons_model_volume_mesh(m, NULL, &vm, &e), &e);
    size_t n[3], by_corners[3] = {0, 0, 0};
    shapes(vm, n);
    for (size_t i = 0; i < coons_volume_mesh_cell_count(vm); i++) {
        size_t d = distinct(coons_volume_mesh_cells(vm) + 8 * i, 8);
        assert_true(d == 8 || d == 6 || d == 5);
        by_corners[d == 8 ? 0 : d == 6 ? 1 : 2]++;
    }
    assert_memory_equal(n, by_corners, sizeof n);
    assert_true(n[0] > 0 && n[2] > 0); /* its tip is a point: pyramids */
    coons_volume_mesh_free(vm);
    coons_model_free(m);
}

static void test_errors(void **state)
{
    (void)state;
    coons_volume_mesh *vm = collapsed(0, COONS_ELEMENT_HEX8, 1, 1, 1);
    coons_cell_shape s = COONS_CELL_WEDGE;
    uint32_t nodes[COONS_VOLUME_CELL_NODES_MAX];
    size_t count = 99;
    coons_error e = COONS_ERROR_INIT;
    assert_int_equal(coons_volume_mesh_cell_shape(vm, 1, &s, nodes, &count, &e), COONS_E_INVALID);
    assert_non_null(strstr(e.message, "no cell 1"));
    assert_int_equal(coons_volume_mesh_cell_shape(NULL, 0, &s, nodes, &count, NULL),
                     COONS_E_INVALID);
    assert_int_equal(coons_volume_mesh_cell_shape(vm, 0, NULL, nodes, &count, NULL),
                     COONS_E_INVALID);
    assert_int_equal(coons_volume_mesh_cell_shape(vm, 0, &s, NULL, &count, NULL),
                     COONS_E_INVALID);
    assert_int_equal(coons_volume_mesh_cell_shape(vm, 0, &s, nodes, NULL, NULL),
                     COONS_E_INVALID);
    assert_int_equal(s, COONS_CELL_WEDGE);
    assert_int_equal(count, 99);
    assert_coons_ok(coons_volume_mesh_cell_shape(vm, 0, &s, nodes, &count, &e), &e);
    assert_int_equal(s, COONS_CELL_PYRAMID);
    assert_int_equal(count, 5);
    coons_volume_mesh_free(vm);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pyramids_and_wedges),
        cmocka_unit_test(test_nail),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
