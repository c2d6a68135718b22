/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Volume meshes on threads (coons_volume_options.threads): the mesh of 2
 * and 5 threads is the mesh of one, array for array and byte for byte
 * (nodes, cells, parts, every field, every set), for every fixture body in
 * the three element kinds (uniform lattices whose u direction has fewer,
 * as many and more layers than threads), the sampled lattice, and models
 * whose bodies collapse to an apex, share faces or close into a tube
 * (examples/nail.json, lattice-l-bracket.json, thick-cylinder.json); and
 * the scaled_jacobian field is coons_volume_mesh_cell_scaled_jacobian(),
 * bit for bit (lanes of 32 cells: meshes of 6, 30 and 84 cells). */
#include <string.h>

#include "body_fixtures.h"
#include "test_util.h"

static void same_array(const void *a, const void *b, size_t bytes, const char *what)
{
    if (bytes && memcmp(a, b, bytes) != 0) fail_msg("%s differs between thread counts", what);
}

static void same_mesh(const coons_volume_mesh *a, const coons_volume_mesh *b)
{
    size_t nn = coons_volume_mesh_node_count(a), nc = coons_volume_mesh_cell_count(a);
    size_t npc = coons_volume_mesh_nodes_per_cell(a);
    assert_int_equal(coons_volume_mesh_node_count(b), nn);
    assert_int_equal(coons_volume_mesh_cell_count(b), nc);
    assert_int_equal(coons_volume_mesh_part_count(b), coons_volume_mesh_part_count(a));
    same_array(coons_volume_mesh_nodes(a), coons_volume_mesh_nodes(b), 3 * nn * sizeof(double),
               "nodes");
    same_array(coons_volume_mesh_cells(a), coons_volume_mesh_cells(b), npc * nc * 4, "cells");
    same_array(coons_volume_mesh_cell_parts(a), coons_volume_mesh_cell_parts(b), nc * 4, "parts");
    for (int l = 0; l < 2; l++) {
        coons_field_location loc = (coons_field_location)l;
        size_t nf = coons_volume_mesh_field_count(a, loc);
        assert_int_equal(coons_volume_mesh_field_count(b, loc), nf);
        for (size_t i = 0; i < nf; i++) {
            coons_field_type ta, tb;
            const void *va, *vb;
            const char *name = coons_volume_mesh_field(a, loc, i, &ta, &va);
            assert_string_equal(coons_volume_mesh_field(b, loc, i, &tb, &vb), name);
            assert_int_equal(ta, tb);
            same_array(va, vb, (l ? nc : nn) * (ta == COONS_FIELD_FLOAT64 ? 8 : 4), name);
        }
    }
    typedef const char *(*set_fn)(const coons_volume_mesh *, size_t, const uint32_t **,
                                  size_t *);
    static const set_fn sets[3] = {coons_volume_mesh_node_set, coons_volume_mesh_cell_set,
                                   coons_volume_mesh_face_set};
    size_t nsets[3] = {coons_volume_mesh_node_set_count(a), coons_volume_mesh_cell_set_count(a),
                       coons_volume_mesh_face_set_count(a)};
    assert_int_equal(coons_volume_mesh_node_set_count(b), nsets[0]);
    assert_int_equal(coons_volume_mesh_cell_set_count(b), nsets[1]);
    assert_int_equal(coons_volume_mesh_face_set_count(b), nsets[2]);
    for (int k = 0; k < 3; k++)
        for (size_t i = 0; i < nsets[k]; i++) {
            const uint32_t *ia, *ib;
            size_t ca, cb;
            const char *name = sets[k](a, i, &ia, &ca);
            assert_string_equal(sets[k](b, i, &ib, &cb), name);
            assert_int_equal(ca, cb);
            same_array(ia, ib, (k == 2 ? 2 : 1) * ca * 4, name);
        }
}

/* The mesher's scaled_jacobian field (computed 32 cells at a time) is
 * coons_volume_mesh_cell_scaled_jacobian() of each cell, bit for bit. */
static void same_scaled_jacobian(const coons_volume_mesh *vm)
{
    for (size_t i = 0; i < coons_volume_mesh_field_count(vm, COONS_FIELD_CELL); i++) {
        coons_field_type t;
        const void *v;
        if (strcmp(coons_volume_mesh_field(vm, COONS_FIELD_CELL, i, &t, &v), "scaled_jacobian"))
            continue;
        const double *sj = v;
        for (size_t c = 0; c < coons_volume_mesh_cell_count(vm); c++) {
            double one = coons_volume_mesh_cell_scaled_jacobian(vm, c, NULL);
            if (memcmp(&one, &sj[c], sizeof one) != 0)
                fail_msg("cell %zu: scaled Jacobian %.17g in the field, %.17g alone", c, sj[c],
                         one);
        }
        return;
    }
    fail_msg("no scaled_jacobian field");
}

/* Meshes with 1, 2 and 5 threads and compares them with the first. */
static void check_threads(const coons_body *b, const coons_model *m, coons_volume_options o)
{
    coons_volume_mesh *ref = NULL;
    static const unsigned threads[3] = {1, 2, 5};
    for (int t = 0; t < 3; t++) {
        coons_error e = COONS_ERROR_INIT;
        coons_volume_mesh *vm = NULL;
        o.threads = threads[t];
        assert_coons_ok(m ? coons_model_volume_mesh(m, &o, &vm, &e)
                          : coons_body_volume_mesh(b, &o, "b", &vm, &e),
                        &e);
        assert_true(coons_volume_mesh_cell_count(vm) > 0);
        if (t == 0) {
            same_scaled_jacobian(vm);
            ref = vm;
            continue;
        }
        same_mesh(ref, vm);
        coons_volume_mesh_free(vm);
    }
    coons_volume_mesh_free(ref);
}

static void test_bodies(void **state)
{
    (void)state;
    static const coons_element el[3] = {COONS_ELEMENT_HEX8, COONS_ELEMENT_HEX20,
                                        COONS_ELEMENT_HEX27};
    static const unsigned res[3][3] = {{1, 3, 2}, {5, 2, 3}, {7, 4, 3}};
    for (int m = 0; m < TB_MAX_BODIES; m++) {
        coons_error e = COONS_ERROR_INIT;
        coons_body *b = NULL;
        if (tb_make_body(m, &b, &e) == TB_NO_BODY) continue;
        for (int k = 0; k < 3; k++) {
            coons_volume_options o = COONS_VOLUME_OPTIONS_INIT;
            o.element = el[k];
            memcpy(o.resolution, res[k], sizeof o.resolution);
            check_threads(b, NULL, o);
        }
        coons_body_free(b);
    }
}

static void test_sampled_lattice(void **state)
{
    (void)state;
    coons_error e = COONS_ERROR_INIT;
    coons_body *b = NULL;
    assert_int_equal(tb_make_body(0, &b, &e), 0);
    coons_volume_options o = COONS_VOLUME_OPTIONS_INIT;
    o.tolerance = 0.05;
    check_threads(b, NULL, o);
    coons_body_free(b);
}

static void test_models(void **state)
{
    (void)state;
    static const char *files[3] = {"nail.json", "lattice-l-bracket.json", "thick-cylinder.json"};
    for (int i = 0; i < 3; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/examples/%s", COONS_SOURCE_DIR, files[i]);
        coons_model *m = NULL;
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(coons_model_load_file(path, NULL, &m, &e), &e);
        coons_volume_options o = COONS_VOLUME_OPTIONS_INIT;
        o.resolution[0] = o.resolution[1] = o.resolution[2] = 3;
        check_threads(NULL, m, o);
        coons_model_free(m);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bodies),
        cmocka_unit_test(test_sampled_lattice),
        cmocka_unit_test(test_models),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
