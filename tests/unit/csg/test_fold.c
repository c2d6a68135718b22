/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The pinch of a repaired fold (tests/data/csg/fold.json: the two sheets
 * of the covered region touch along the curve t = 0) and its split:
 * coons_mesh_solidify() alone returns it closed but pinched (edges of four
 * triangles, as the CGAL layer counts them and as coons_mesh_check()
 * counts them independently); coons__mesh_split_pinches() makes it a
 * closed, oriented 2-manifold of the same triangles (corner by corner
 * where they were or moved apart by at most 1e-3 of the shortest edge
 * there, far below the tolerance; the volume within what that allows),
 * crossing nowhere in double or float32 (CGAL's exact counts), with the
 * copies apart (welding by position merges nothing);
 * coons_model_solidify() returns exactly that mesh, and reports the
 * split. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pinch.h"
#include "test_util.h"

static void test_fold_pinch_split(void **state)
{
    (void)state;
    char path[1024];
    snprintf(path, sizeof path, "%s/tests/data/csg/fold.json", COONS_SOURCE_DIR);
    coons_model *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_model_load_file(path, NULL, &m, &err), &err);
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.tolerance = 0.004;
    coons_mesh *shell = NULL, *pinched = NULL, *solid = NULL;
    assert_coons_ok(coons_model_sample(m, &so, &shell, &err), &err);
    coons_csg_options co = COONS_CSG_OPTIONS_INIT;
    co.unite = 0;
    coons_csg_report r0 = COONS_CSG_REPORT_INIT;
    assert_coons_ok(coons_mesh_solidify(shell, &co, &pinched, &r0, &err), &err);
    coons_mesh_report before = COONS_MESH_REPORT_INIT;
    assert_coons_ok(coons_mesh_check(pinched, &before, &err), &err);
    printf("fold: %zu vertices, %zu triangles, CGAL's nonmanifold edges %zu, check's %zu, "
           "nonmanifold vertices %zu\n",
           coons_mesh_vertex_count(pinched), coons_mesh_triangle_count(pinched),
           r0.nonmanifold_edges, before.nonmanifold_edges, before.nonmanifold_vertices);
    assert_true(r0.closed);
    assert_true(r0.nonmanifold_edges > 0);
    assert_int_equal(before.nonmanifold_edges, r0.nonmanifold_edges);
    assert_true(before.boundary_edges == 0 && !before.manifold);
    assert_int_equal(r0.pinch_edges_split + r0.pinch_vertices_split, 0);

    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    assert_coons_ok(coons_model_solidify(m, &so, NULL, &solid, &rep, &err), &err);
    printf("split: %zu edges, %zu vertices, %zu left; %zu vertices now\n", rep.pinch_edges_split,
           rep.pinch_vertices_split, rep.nonmanifold_edges, coons_mesh_vertex_count(solid));
    assert_int_equal(rep.pinch_edges_split, r0.nonmanifold_edges);
    assert_true(rep.pinch_vertices_split > 0);
    assert_int_equal(rep.nonmanifold_edges, 0);
    assert_int_equal(coons_mesh_vertex_count(solid),
                     coons_mesh_vertex_count(pinched) + rep.pinch_vertices_split);
    coons_mesh_report after = COONS_MESH_REPORT_INIT;
    assert_coons_ok(coons_mesh_check(solid, &after, &err), &err);
    assert_true(after.closed && after.manifold && after.oriented);
    assert_int_equal(after.nonmanifold_edges + after.nonmanifold_vertices + after.boundary_edges, 0);
    /* the same triangles, corner by corner */
    assert_int_equal(coons_mesh_triangle_count(solid), coons_mesh_triangle_count(pinched));
    const double *va = coons_mesh_vertices(pinched), *vb = coons_mesh_vertices(solid);
    const uint32_t *ta = coons_mesh_triangles(pinched), *tb = coons_mesh_triangles(solid);
    double dmax = 0;
    for (size_t k = 0; k < 3 * coons_mesh_triangle_count(solid); k++) {
        const double *p = va + 3 * (size_t)ta[k], *q = vb + 3 * (size_t)tb[k];
        double d = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                        (p[2] - q[2]) * (p[2] - q[2]));
        dmax = fmax(dmax, d);
    }
    double v0 = coons_mesh_volume(pinched), v1 = coons_mesh_volume(solid);
    printf("largest move %.3g, volume %.12g -> %.12g\n", dmax, v0, v1);
    assert_true(dmax > 0 && dmax < 0.01 * so.tolerance);
    assert_true(fabs(v1 - v0) <= dmax * coons_mesh_area(solid));
    size_t pairs = 99, pairs32 = 99;
    assert_coons_ok(coons_mesh_count_self_intersections(solid, &pairs, &err), &err);
    assert_coons_ok(coons_mesh_count_self_intersections_float(solid, &pairs32, &err), &err);
    assert_int_equal(pairs, 0);
    assert_int_equal(pairs32, 0);

    /* done by hand on the pinched mesh: the same result */
    size_t e = 0, v = 0, left = 9;
    assert_coons_ok(coons__mesh_split_pinches(pinched, &e, &v, &left, &err), &err);
    assert_int_equal(e, rep.pinch_edges_split);
    assert_int_equal(v, rep.pinch_vertices_split);
    assert_int_equal(left, 0);
    assert_int_equal(coons_mesh_vertex_count(pinched), coons_mesh_vertex_count(solid));
    assert_memory_equal(coons_mesh_vertices(pinched), vb,
                        3 * coons_mesh_vertex_count(solid) * sizeof(double));
    assert_memory_equal(coons_mesh_triangles(pinched), tb,
                        3 * coons_mesh_triangle_count(solid) * sizeof(uint32_t));

    /* the copies are apart: welding by position merges nothing */
    coons_mesh *w = NULL;
    assert_coons_ok(coons__mesh_welded(solid, &w, &err), &err);
    assert_int_equal(coons_mesh_vertex_count(w), coons_mesh_vertex_count(solid));
    coons_mesh_free(w);
    coons_mesh_free(shell);
    coons_mesh_free(pinched);
    coons_mesh_free(solid);
    coons_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fold_pinch_split),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
