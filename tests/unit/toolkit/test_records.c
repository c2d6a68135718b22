/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The options and report records of the public headers: each _init()
 * function gives exactly its _INIT macro (for language bindings), and every
 * function that takes a record refuses another version with
 * COONS_E_INVALID and a message naming the record, before doing anything. */
#define _XOPEN_SOURCE 700
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "test_util.h"

/* Field f of a (from _init) and b (from _INIT) are the same bytes. */
#define SAME(f) assert_memory_equal(&a.f, &b.f, sizeof a.f)
/* a filled with garbage, then set by init(); b from the macro. */
#define FROM_INIT(type, init, macro) \
    type a, b = macro;               \
    memset(&a, 0xA5, sizeof a);      \
    init(&a);                        \
    init(NULL) /* a harmless no-op */

static void test_sample_options_init(void **state)
{
    (void)state;
    FROM_INIT(coons_sample_options, coons_sample_options_init, COONS_SAMPLE_OPTIONS_INIT);
    SAME(version), SAME(tolerance), SAME(resolution), SAME(max_triangles), SAME(max_aspect),
        SAME(flags);
    assert_int_equal(a.version, COONS_SAMPLE_OPTIONS_VERSION);
}

static void test_write_options_init(void **state)
{
    (void)state;
    FROM_INIT(coons_write_options, coons_write_options_init, COONS_WRITE_OPTIONS_INIT);
    SAME(version), SAME(name), SAME(units), SAME(header), SAME(protect_path), SAME(cancel),
        SAME(cancel_ctx);
    assert_int_equal(a.version, COONS_WRITE_OPTIONS_VERSION);
}

static void test_csg_options_init(void **state)
{
    (void)state;
    FROM_INIT(coons_csg_options, coons_csg_options_init, COONS_CSG_OPTIONS_INIT);
    SAME(version), SAME(unite), SAME(repair), SAME(name), SAME(progress), SAME(userdata);
    assert_int_equal(a.version, COONS_CSG_OPTIONS_VERSION);
    assert_int_equal(a.unite, 1);
    assert_int_equal(a.repair, 1);
}

static void test_model_load_options_init(void **state)
{
    (void)state;
    FROM_INIT(coons_model_load_options, coons_model_load_options_init,
              COONS_MODEL_LOAD_OPTIONS_INIT);
    SAME(version), SAME(max_bytes), SAME(max_values), SAME(max_depth), SAME(max_points);
    assert_int_equal(a.version, COONS_MODEL_LOAD_OPTIONS_VERSION);
}

static void test_hermite_options_init(void **state)
{
    (void)state;
    FROM_INIT(coons_hermite_options, coons_hermite_options_init, COONS_HERMITE_OPTIONS_INIT);
    SAME(version), SAME(cross), SAME(twist), SAME(twists), SAME(tol);
    assert_int_equal(a.version, COONS_HERMITE_OPTIONS_VERSION);
}

static void test_mesh_report_init(void **state)
{
    (void)state;
    FROM_INIT(coons_mesh_report, coons_mesh_report_init, COONS_MESH_REPORT_INIT);
    SAME(version), SAME(vertices), SAME(unused_vertices), SAME(triangles),
        SAME(degenerate_triangles), SAME(edges), SAME(boundary_edges), SAME(nonmanifold_edges),
        SAME(misoriented_edges), SAME(nonmanifold_vertices), SAME(shells), SAME(euler),
        SAME(expected_euler), SAME(closed), SAME(manifold), SAME(oriented), SAME(openmesh),
        SAME(openmesh_rejected), SAME(openmesh_boundary), SAME(volume), SAME(area);
    assert_int_equal(a.version, COONS_MESH_REPORT_VERSION);
}

static void test_csg_report_init(void **state)
{
    (void)state;
    FROM_INIT(coons_csg_report, coons_csg_report_init, COONS_CSG_REPORT_INIT);
    SAME(version), SAME(triangles_in), SAME(degenerate_dropped), SAME(intersecting_pairs),
        SAME(parts_in), SAME(groups), SAME(passed_through), SAME(patches), SAME(patches_kept),
        SAME(fast_unions), SAME(fallbacks), SAME(triangles_out), SAME(rounding_merged),
        SAME(close_merged), SAME(slivers_fixed), SAME(closed), SAME(nonmanifold_edges),
        SAME(pinch_edges_split), SAME(pinch_vertices_split);
    assert_int_equal(a.version, COONS_CSG_REPORT_VERSION);
    /* the version comes first, as in every record */
    assert_int_equal(offsetof(coons_csg_report, version), 0);
}

/* ---- wrong versions ------------------------------------------------------ */

static const char MODEL[] =
    "{\"coons\": 1, \"bodies\": [{\"type\": \"body0\", \"name\": \"cube\", \"corners\": "
    "[[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]}";

/* The versions a caller might wrongly pass for a record of version v. */
static unsigned wrong_version(unsigned v, int k) { return k == 0 ? 0u : v + (unsigned)k; }

/* st is COONS_E_INVALID and the message names `what` and a version. */
static void assert_refused(coons_status st, const coons_error *err, const char *what)
{
    if (st != COONS_E_INVALID) fail_msg("%s: status %d (%s), not COONS_E_INVALID", what, st, err->message);
    assert_int_equal(err->code, COONS_E_INVALID);
    if (!strstr(err->message, what) || !strstr(err->message, "version"))
        fail_msg("message \"%s\" does not name \"%s\" and its version", err->message, what);
}

static coons_model *cube(void)
{
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    assert_coons_ok(coons_model_load_memory(MODEL, sizeof MODEL - 1, "cube", NULL, &m, &err), &err);
    return m;
}

static void test_sample_options_version(void **state)
{
    (void)state;
    coons_model *m = cube();
    for (int k = 0; k < 2; k++) {
        coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
        o.version = wrong_version(COONS_SAMPLE_OPTIONS_VERSION, k);
        coons_error err = COONS_ERROR_INIT;
        coons_mesh *out = (coons_mesh *)m;
        assert_refused(coons_body_sample(coons_model_body(m, 0), &o, "b", &out, &err), &err,
                       "sample options");
        assert_null(out);
        out = (coons_mesh *)m;
        assert_refused(coons_model_sample(m, &o, &out, &err), &err, "sample options");
        assert_null(out);
        out = (coons_mesh *)m;
        assert_refused(coons_model_solidify(m, &o, NULL, &out, NULL, &err), &err, "sample options");
        assert_null(out);
    }
    coons_model_free(m);
}

static void test_write_options_version(void **state)
{
    (void)state;
    coons_model *m = cube();
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *mesh = NULL;
    assert_coons_ok(coons_model_sample(m, NULL, &mesh, &err), &err);
    char path[64];
    snprintf(path, sizeof path, "records-%ld.stl", (long)getpid());
    for (int k = 0; k < 2; k++) {
        coons_write_options o = COONS_WRITE_OPTIONS_INIT;
        o.version = wrong_version(COONS_WRITE_OPTIONS_VERSION, k);
        assert_refused(coons_mesh_write(mesh, path, COONS_FORMAT_STL_BINARY, &o, &err), &err,
                       "write options");
        assert_int_equal(access(path, F_OK), -1); /* nothing created */
        FILE *fp = tmpfile();
        assert_non_null(fp);
        assert_refused(coons_mesh_write_stream(mesh, fp, COONS_FORMAT_OFF, &o, &err), &err,
                       "write options");
        assert_int_equal(ftell(fp), 0);
        fclose(fp);
    }
    coons_mesh_free(mesh);
    coons_model_free(m);
}

static void test_csg_records_version(void **state)
{
    (void)state;
    coons_model *m = cube();
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *mesh = NULL;
    assert_coons_ok(coons_model_sample(m, NULL, &mesh, &err), &err);
    for (int k = 0; k < 2; k++) {
        coons_csg_options o = COONS_CSG_OPTIONS_INIT;
        o.version = wrong_version(COONS_CSG_OPTIONS_VERSION, k);
        coons_csg_report r = COONS_CSG_REPORT_INIT;
        coons_mesh *out = mesh;
        assert_refused(coons_mesh_solidify(mesh, &o, &out, &r, &err), &err, "csg options");
        assert_null(out);
        out = mesh;
        assert_refused(coons_model_solidify(m, NULL, &o, &out, &r, &err), &err, "csg options");
        assert_null(out);
        assert_int_equal(r.version, COONS_CSG_REPORT_VERSION);

        coons_csg_report bad = COONS_CSG_REPORT_INIT;
        bad.version = wrong_version(COONS_CSG_REPORT_VERSION, k);
        bad.triangles_in = 7;
        out = mesh;
        assert_refused(coons_mesh_solidify(mesh, NULL, &out, &bad, &err), &err, "csg report");
        assert_null(out);
        out = mesh;
        assert_refused(coons_model_solidify(m, NULL, NULL, &out, &bad, &err), &err, "csg report");
        assert_null(out);
        assert_int_equal(bad.triangles_in, 7); /* untouched */
    }
    /* the right versions pass the check (without CGAL: COONS_E_UNSUPPORTED) */
    coons_csg_options o = COONS_CSG_OPTIONS_INIT;
    coons_csg_report r = COONS_CSG_REPORT_INIT;
    coons_mesh *out = NULL;
    coons_status st = coons_mesh_solidify(mesh, &o, &out, &r, &err);
    assert_int_equal(st, coons_csg_is_available() ? COONS_OK : COONS_E_UNSUPPORTED);
    if (st == COONS_OK) {
        assert_int_equal(r.version, COONS_CSG_REPORT_VERSION);
        assert_int_equal(r.triangles_in, coons_mesh_triangle_count(mesh));
    }
    coons_mesh_free(out);
    coons_mesh_free(mesh);
    coons_model_free(m);
}

static void test_model_load_options_version(void **state)
{
    (void)state;
    char path[64];
    snprintf(path, sizeof path, "records-%ld.json", (long)getpid());
    FILE *fp = fopen(path, "wb");
    assert_non_null(fp);
    fputs(MODEL, fp);
    fclose(fp);
    for (int k = 0; k < 2; k++) {
        coons_model_load_options o = COONS_MODEL_LOAD_OPTIONS_INIT;
        o.version = wrong_version(COONS_MODEL_LOAD_OPTIONS_VERSION, k);
        coons_error err = COONS_ERROR_INIT;
        coons_model *m = (coons_model *)&o;
        assert_refused(coons_model_load_memory(MODEL, sizeof MODEL - 1, "cube", &o, &m, &err),
                       &err, "model load options");
        assert_null(m);
        m = (coons_model *)&o;
        assert_refused(coons_model_load_file(path, &o, &m, &err), &err, "model load options");
        assert_null(m);
    }
    coons_model_load_options o = COONS_MODEL_LOAD_OPTIONS_INIT;
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    assert_coons_ok(coons_model_load_file(path, &o, &m, &err), &err);
    coons_model_free(m);
    unlink(path);
}

static void test_hermite_options_version(void **state)
{
    (void)state;
    for (int k = 0; k < 2; k++) {
        coons_hermite_options o = COONS_HERMITE_OPTIONS_INIT;
        o.version = wrong_version(COONS_HERMITE_OPTIONS_VERSION, k);
        coons_error err = COONS_ERROR_INIT;
        coons_patch *p = (coons_patch *)&o;
        /* the version is checked before the boundary is looked at */
        assert_refused(coons_patch_new_hermite_coons(NULL, &o, &p, &err), &err, "options version");
        assert_null(p);
    }
}

static void test_mesh_report_version(void **state)
{
    (void)state;
    coons_model *m = cube();
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *mesh = NULL;
    assert_coons_ok(coons_model_sample(m, NULL, &mesh, &err), &err);
    for (int k = 0; k < 2; k++) {
        coons_mesh_report r = COONS_MESH_REPORT_INIT;
        r.version = wrong_version(COONS_MESH_REPORT_VERSION, k);
        assert_refused(coons_mesh_check(mesh, &r, &err), &err, "mesh report");
        assert_int_equal(r.triangles, 0);
    }
    coons_mesh_free(mesh);
    coons_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sample_options_init),
        cmocka_unit_test(test_write_options_init),
        cmocka_unit_test(test_csg_options_init),
        cmocka_unit_test(test_model_load_options_init),
        cmocka_unit_test(test_hermite_options_init),
        cmocka_unit_test(test_mesh_report_init),
        cmocka_unit_test(test_csg_report_init),
        cmocka_unit_test(test_sample_options_version),
        cmocka_unit_test(test_write_options_version),
        cmocka_unit_test(test_csg_records_version),
        cmocka_unit_test(test_model_load_options_version),
        cmocka_unit_test(test_hermite_options_version),
        cmocka_unit_test(test_mesh_report_version),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
