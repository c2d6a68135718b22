/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The options and report records of the public headers: each _init()
 * function gives exactly its _INIT macro (for language bindings), and every
 * function that takes a record refuses another version with
 * COONS_E_INVALID and the one message of every record ("<record> version N,
 * expected M (use <INIT macro>)"), before doing anything. */
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
        SAME(flags), SAME(progress), SAME(userdata), SAME(threads);
    assert_null(a.progress);
    assert_int_equal(a.version, COONS_SAMPLE_OPTIONS_VERSION);
}

static void test_write_options_init(void **state)
{
    (void)state;
    FROM_INIT(coons_write_options, coons_write_options_init, COONS_WRITE_OPTIONS_INIT);
    SAME(version), SAME(name), SAME(units), SAME(header), SAME(protect_path), SAME(cancel),
        SAME(cancel_ctx), SAME(written), SAME(written_ctx);
    assert_null(a.written);
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

/* st is COONS_E_INVALID and the message is the one wording of every record:
 * "<what> version <given>, expected <current> (use <INIT macro>)". */
static void assert_refused_as(coons_status st, const coons_error *err, const char *what,
                              unsigned given, unsigned current, const char *init)
{
    if (st != COONS_E_INVALID) fail_msg("%s: status %d (%s), not COONS_E_INVALID", what, st, err->message);
    assert_int_equal(err->code, COONS_E_INVALID);
    char want[256];
    snprintf(want, sizeof want, "%s version %u, expected %u (use %s)", what, given, current, init);
    if (strcmp(err->message, want) != 0)
        fail_msg("message \"%s\", expected \"%s\"", err->message, want);
}
/* assert_refused_as() for the record COONS_<PREFIX>, given version v. */
#define assert_refused(st, err, what, v, PREFIX)                                                   \
    assert_refused_as(st, err, what, v, PREFIX##_VERSION, #PREFIX "_INIT")

static coons_model *cube(void)
{
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    assert_coons_ok(coons_model_load_memory(MODEL, sizeof MODEL - 1, "cube", NULL, &m, &err), &err);
    return m;
}

/* The model's boundary mesh. */
static coons_mesh *sampled(const coons_model *m)
{
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *mesh = NULL;
    assert_coons_ok(coons_model_sample(m, NULL, &mesh, &err), &err);
    return mesh;
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
                       "sample options", o.version, COONS_SAMPLE_OPTIONS);
        assert_null(out);
        out = (coons_mesh *)m;
        assert_refused(coons_model_sample(m, &o, &out, &err), &err, "sample options", o.version,
                       COONS_SAMPLE_OPTIONS);
        assert_null(out);
        out = (coons_mesh *)m;
        assert_refused(coons_model_solidify(m, &o, NULL, &out, NULL, &err), &err, "sample options",
                       o.version, COONS_SAMPLE_OPTIONS);
        assert_null(out);
    }
    coons_model_free(m);
}

static void test_write_options_version(void **state)
{
    (void)state;
    coons_model *m = cube();
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *mesh = sampled(m);
    char path[64];
    snprintf(path, sizeof path, "records-%ld.stl", (long)getpid());
    for (int k = 0; k < 2; k++) {
        coons_write_options o = COONS_WRITE_OPTIONS_INIT;
        o.version = wrong_version(COONS_WRITE_OPTIONS_VERSION, k);
        assert_refused(coons_mesh_write(mesh, path, COONS_FORMAT_STL_BINARY, &o, &err), &err,
                       "write options", o.version, COONS_WRITE_OPTIONS);
        assert_int_equal(access(path, F_OK), -1); /* nothing created */
        FILE *fp = tmpfile();
        assert_non_null(fp);
        assert_refused(coons_mesh_write_stream(mesh, fp, COONS_FORMAT_OFF, &o, &err), &err,
                       "write options", o.version, COONS_WRITE_OPTIONS);
        assert_int_equal(ftell(fp), 0);
        fclose(fp);
    }
    coons_mesh_free(mesh);
    coons_model_free(m);
}

/* Version 2's `written`: the bytes so far, ending with the file's size,
 * never decreasing; a version-1 record is still accepted and not asked. */
typedef struct written_log {
    unsigned long long last;
    int calls, decreased;
} written_log;

static void on_written(void *ctx, unsigned long long bytes)
{
    written_log *w = ctx;
    if (bytes < w->last) w->decreased = 1;
    w->last = bytes;
    w->calls++;
}

static void test_write_options_written(void **state)
{
    (void)state;
    coons_model *m = cube();
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *mesh = NULL;
    assert_coons_ok(coons_model_sample(m, NULL, &mesh, &err), &err);
    char path[64];
    snprintf(path, sizeof path, "records-w-%ld.off", (long)getpid());
    for (unsigned version = 1; version <= COONS_WRITE_OPTIONS_VERSION; version++) {
        written_log w = {0, 0, 0};
        coons_write_options o = COONS_WRITE_OPTIONS_INIT;
        o.version = version;
        o.written = on_written;
        o.written_ctx = &w;
        assert_coons_ok(coons_mesh_write(mesh, path, COONS_FORMAT_OFF, &o, &err), &err);
        FILE *fp = fopen(path, "rb");
        assert_non_null(fp);
        fseek(fp, 0, SEEK_END);
        long size = ftell(fp);
        fclose(fp);
        remove(path);
        if (version == 1) {
            assert_int_equal(w.calls, 0);
        } else {
            assert_true(w.calls >= 1);
            assert_false(w.decreased);
            assert_int_equal(w.last, (unsigned long long)size);
        }
    }
    coons_mesh_free(mesh);
    coons_model_free(m);
}

/* Version 2 of coons_volume_options: the stages lattice, evaluate, cells
 * in that order, each from 0 (or its first body) to 1 without going back;
 * a version-1 record still meshes, unasked. */
typedef struct stage_log {
    char order[4]; /* first letter of each stage, as they begin */
    size_t n;
    double last;
    int back, ends, bad;
} stage_log;

static void on_stage(void *ctx, const char *stage, double fraction)
{
    stage_log *l = ctx;
    if (!(fraction >= 0 && fraction <= 1)) l->bad = 1;
    if (l->n == 0 || l->order[l->n - 1] != stage[0]) {
        if (l->n < sizeof l->order - 1) l->order[l->n++] = stage[0];
        l->last = 0;
    }
    if (fraction < l->last) l->back = 1;
    l->last = fraction;
    l->ends += fraction == 1.0;
}

/* Version 2 of coons_sample_options: "measure" reports within [0, 1],
 * each pass reaching 1; the mesh is the same as without reports, and a
 * version-1 record still samples, unasked. */
static void test_sample_options_progress(void **state)
{
    (void)state;
    coons_model *m = cube();
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *mesh[3] = {NULL, NULL, NULL};
    for (unsigned k = 0; k < 3; k++) {
        stage_log l;
        memset(&l, 0, sizeof l);
        coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
        o.version = k == 0 ? 1u : COONS_SAMPLE_OPTIONS_VERSION;
        o.tolerance = 1e-4;
        o.progress = k == 2 ? NULL : on_stage;
        o.userdata = &l;
        assert_coons_ok(coons_body_sample(coons_model_body(m, 0), &o, "b", &mesh[k], &err), &err);
        if (k == 0) assert_int_equal(l.n, 0);
        if (k == 1) {
            assert_string_equal(l.order, "m");
            assert_false(l.bad);
            assert_true(l.ends >= 1);
        }
    }
    for (unsigned k = 1; k < 3; k++) {
        assert_int_equal(coons_mesh_vertex_count(mesh[k]), coons_mesh_vertex_count(mesh[0]));
        assert_memory_equal(coons_mesh_vertices(mesh[k]), coons_mesh_vertices(mesh[0]),
                            3 * sizeof(double) * coons_mesh_vertex_count(mesh[0]));
    }
    for (unsigned k = 0; k < 3; k++) coons_mesh_free(mesh[k]);
    coons_model_free(m);
}

static void test_volume_options_progress(void **state)
{
    (void)state;
    FROM_INIT(coons_volume_options, coons_volume_options_init, COONS_VOLUME_OPTIONS_INIT);
    SAME(version), SAME(element), SAME(resolution), SAME(tolerance), SAME(max_cells),
        SAME(progress), SAME(userdata), SAME(threads);
    assert_null(a.progress);
    coons_model *m = cube();
    coons_error err = COONS_ERROR_INIT;
    for (unsigned version = 1; version <= COONS_VOLUME_OPTIONS_VERSION; version++) {
        stage_log l;
        memset(&l, 0, sizeof l);
        coons_volume_options o = COONS_VOLUME_OPTIONS_INIT;
        o.version = version;
        o.resolution[0] = o.resolution[1] = o.resolution[2] = 3;
        o.progress = on_stage;
        o.userdata = &l;
        coons_volume_mesh *vm = NULL;
        assert_coons_ok(coons_model_volume_mesh(m, &o, &vm, &err), &err);
        assert_int_equal(coons_volume_mesh_cell_count(vm), 27);
        coons_volume_mesh_free(vm);
        if (version == 1) {
            assert_int_equal(l.n, 0);
        } else {
            assert_string_equal(l.order, "lec");
            assert_false(l.back);
            assert_false(l.bad);
            assert_int_equal(l.ends, 3);
        }
    }
    coons_model_free(m);
}

static void test_csg_records_version(void **state)
{
    (void)state;
    coons_model *m = cube();
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *mesh = sampled(m);
    for (int k = 0; k < 2; k++) {
        coons_csg_options o = COONS_CSG_OPTIONS_INIT;
        o.version = wrong_version(COONS_CSG_OPTIONS_VERSION, k);
        coons_csg_report r = COONS_CSG_REPORT_INIT;
        coons_mesh *out = mesh;
        assert_refused(coons_mesh_solidify(mesh, &o, &out, &r, &err), &err, "csg options", o.version,
                       COONS_CSG_OPTIONS);
        assert_null(out);
        out = mesh;
        assert_refused(coons_model_solidify(m, NULL, &o, &out, &r, &err), &err, "csg options",
                       o.version, COONS_CSG_OPTIONS);
        assert_null(out);
        assert_int_equal(r.version, COONS_CSG_REPORT_VERSION);

        coons_csg_report bad = COONS_CSG_REPORT_INIT;
        bad.version = wrong_version(COONS_CSG_REPORT_VERSION, k);
        bad.triangles_in = 7;
        out = mesh;
        assert_refused(coons_mesh_solidify(mesh, NULL, &out, &bad, &err), &err, "csg report",
                       bad.version, COONS_CSG_REPORT);
        assert_null(out);
        out = mesh;
        assert_refused(coons_model_solidify(m, NULL, NULL, &out, &bad, &err), &err, "csg report",
                       bad.version, COONS_CSG_REPORT);
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
                       &err, "model load options", o.version, COONS_MODEL_LOAD_OPTIONS);
        assert_null(m);
        m = (coons_model *)&o;
        assert_refused(coons_model_load_file(path, &o, &m, &err), &err, "model load options",
                       o.version, COONS_MODEL_LOAD_OPTIONS);
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
        assert_refused(coons_patch_new_hermite_coons(NULL, &o, &p, &err), &err,
                       "hermite-coons options", o.version, COONS_HERMITE_OPTIONS);
        assert_null(p);
    }
}

static void test_mesh_report_version(void **state)
{
    (void)state;
    coons_model *m = cube();
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *mesh = sampled(m);
    for (int k = 0; k < 2; k++) {
        coons_mesh_report r = COONS_MESH_REPORT_INIT;
        r.version = wrong_version(COONS_MESH_REPORT_VERSION, k);
        assert_refused(coons_mesh_check(mesh, &r, &err), &err, "mesh report", r.version,
                       COONS_MESH_REPORT);
        assert_int_equal(r.triangles, 0);
    }
    coons_mesh_free(mesh);
    coons_model_free(m);
}

static void test_network_options_version(void **state)
{
    (void)state;
    for (int k = 0; k < 2; k++) {
        coons_network_options o = COONS_NETWORK_OPTIONS_INIT;
        o.version = wrong_version(COONS_NETWORK_OPTIONS_VERSION, k);
        coons_error err = COONS_ERROR_INIT;
        coons_patch *p = (coons_patch *)&o;
        /* the version is checked before the curves are looked at */
        assert_refused(coons_patch_new_network(NULL, 0, NULL, 0, &o, &p, &err), &err,
                       "network options", o.version, COONS_NETWORK_OPTIONS);
        assert_null(p);
    }
}

static void test_mesh_read_options_version(void **state)
{
    (void)state;
    static const char OFF[] = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    for (int k = 0; k < 2; k++) {
        coons_mesh_read_options o = COONS_MESH_READ_OPTIONS_INIT;
        o.version = wrong_version(COONS_MESH_READ_OPTIONS_VERSION, k);
        coons_error err = COONS_ERROR_INIT;
        coons_mesh *m = (coons_mesh *)&o;
        assert_refused(coons_mesh_read_memory(OFF, sizeof OFF - 1, "t.off", &o, &m, &err), &err,
                       "mesh read options", o.version, COONS_MESH_READ_OPTIONS);
        assert_null(m);
        m = (coons_mesh *)&o;
        assert_refused(coons_mesh_read_file("no-such-file.off", &o, &m, &err), &err,
                       "mesh read options", o.version, COONS_MESH_READ_OPTIONS);
        assert_null(m);
    }
}

static void test_volume_records_version(void **state)
{
    (void)state;
    coons_model *m = cube();
    coons_error err = COONS_ERROR_INIT;
    coons_volume_mesh *vm = NULL;
    for (int k = 0; k < 2; k++) {
        coons_volume_options o = COONS_VOLUME_OPTIONS_INIT;
        o.version = wrong_version(COONS_VOLUME_OPTIONS_VERSION, k);
        vm = (coons_volume_mesh *)&o;
        assert_refused(coons_model_volume_mesh(m, &o, &vm, &err), &err, "volume options", o.version,
                       COONS_VOLUME_OPTIONS);
        assert_null(vm);
    }
    assert_coons_ok(coons_model_volume_mesh(m, NULL, &vm, &err), &err);
    for (int k = 0; k < 2; k++) {
        coons_volume_quality q = COONS_VOLUME_QUALITY_INIT;
        q.version = wrong_version(COONS_VOLUME_QUALITY_VERSION, k);
        assert_refused(coons_volume_mesh_quality(vm, 0, &q, &err), &err, "volume quality report",
                       q.version, COONS_VOLUME_QUALITY);
    }
    coons_volume_mesh_free(vm);
    coons_model_free(m);
}

static void test_deform_report_version(void **state)
{
    (void)state;
    coons_model *m = cube();
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *mesh = sampled(m);
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    for (int k = 0; k < 2; k++) {
        coons_deform_report r = COONS_DEFORM_REPORT_INIT;
        r.version = wrong_version(COONS_DEFORM_REPORT_VERSION, k);
        coons_mesh *out = mesh;
        assert_refused(coons_body_deform_mesh_report(coons_model_body(m, 0), mesh, lo, hi, 1e-3, 0,
                                                     &out, &r, &err),
                       &err, "deform report", r.version, COONS_DEFORM_REPORT);
        assert_null(out);
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
        cmocka_unit_test(test_write_options_written),
        cmocka_unit_test(test_volume_options_progress),
        cmocka_unit_test(test_sample_options_progress),
        cmocka_unit_test(test_csg_records_version),
        cmocka_unit_test(test_model_load_options_version),
        cmocka_unit_test(test_hermite_options_version),
        cmocka_unit_test(test_mesh_report_version),
        cmocka_unit_test(test_network_options_version),
        cmocka_unit_test(test_mesh_read_options_version),
        cmocka_unit_test(test_volume_records_version),
        cmocka_unit_test(test_deform_report_version),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
