/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The C++ boundary (src/cxx_guard.hpp): std::bad_alloc injected at each
 * extern "C" entry of the C++ layers (test hook coons__cxx_inject_bad_alloc)
 * comes back as COONS_E_NOMEM with a message, leaves no output (out
 * pointers NULL, counts 0, reports untouched, nothing printed) and leaks
 * nothing (the library's allocator is counted here; ASan runs the tests). A
 * source scan makes sure the table below names every entry of those files. */
#define _XOPEN_SOURCE 700
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "coons_test_hooks.h"
#include "test_util.h"

/* A closed tetrahedron, outward, as one part "tet". */
static coons_mesh *tetra(void)
{
    static const double xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    static const uint32_t tri[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *m = NULL;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    assert_coons_ok(coons_mesh_add_part(m, "tet", xyz, 4, tri, 4, &err), &err);
    return m;
}

typedef struct fixture {
    coons_mesh *mesh;
    char stl[64]; /* the tetrahedron as a binary STL file */
} fixture;

/* One call of an entry; *empty receives 1 when its outputs are empty. */
typedef coons_status (*entry_call)(fixture *f, int *empty, coons_error *err);

static coons_status call_check(fixture *f, int *empty, coons_error *err)
{
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    coons_status st = coons_mesh_check(f->mesh, &r, err);
    *empty = r.triangles == 0 && r.vertices == 0 && r.openmesh == 0;
    return st;
}

static coons_status call_read(fixture *f, int *empty, coons_error *err)
{
    coons_mesh *m = (coons_mesh *)f;
    coons_status st = coons__mesh_read(f->stl, &m, err);
    *empty = m == NULL;
    coons_mesh_free(m);
    return st;
}

static coons_status call_solidify(fixture *f, int *empty, coons_error *err)
{
    coons_mesh *m = (coons_mesh *)f;
    coons_csg_report r = COONS_CSG_REPORT_INIT;
    coons_status st = coons_mesh_solidify(f->mesh, NULL, &m, &r, err);
    *empty = m == NULL && r.triangles_in == 0 && r.parts_in == 0 && r.triangles_out == 0;
    coons_mesh_free(m);
    return st;
}

static coons_status call_self(fixture *f, int *empty, coons_error *err)
{
    size_t pairs = 99;
    coons_status st = coons_mesh_count_self_intersections(f->mesh, &pairs, err);
    *empty = pairs == 0;
    return st;
}

static coons_status call_self_float(fixture *f, int *empty, coons_error *err)
{
    size_t pairs = 99;
    coons_status st = coons_mesh_count_self_intersections_float(f->mesh, &pairs, err);
    *empty = pairs == 0;
    return st;
}

static coons_status call_self_threads(fixture *f, int *empty, coons_error *err)
{
    size_t pairs = 99;
    coons_status st = coons_mesh_count_self_intersections_threads(f->mesh, 1, 2, &pairs, err);
    *empty = pairs == 0;
    return st;
}

static coons_status call_pairs(fixture *f, int *empty, coons_error *err)
{
    size_t pairs = 99, degenerate = 99;
    coons_status st = coons__csg_count_pairs(f->mesh, NULL, 0, 1, &pairs, &degenerate, err);
    *empty = pairs == 0 && degenerate == 0;
    return st;
}

typedef struct entry {
    const char *name;
    const char *file; /* the C++ source that defines it */
    entry_call call;
} entry;

static const entry ENTRIES[] = {
    {"coons_mesh_check", "src/mesh/openmesh.cpp", call_check},
    {"coons__mesh_read", "src/mesh/openmesh.cpp", call_read},
    {"coons_mesh_solidify", "src/csg/cgal_solid.cpp", call_solidify},
    {"coons_mesh_count_self_intersections", "src/csg/cgal_solid.cpp", call_self},
    {"coons_mesh_count_self_intersections_float", "src/csg/cgal_solid.cpp", call_self_float},
    {"coons_mesh_count_self_intersections_threads", "src/csg/cgal_solid.cpp", call_self_threads},
    {"coons__csg_count_pairs", "src/csg/cgal_solid.cpp", call_pairs},
};
#define N_ENTRIES (sizeof ENTRIES / sizeof ENTRIES[0])

/* 1 when the library has its OpenMesh layer (coons_mesh_check says so). */
static int have_openmesh(const coons_mesh *m)
{
    coons_error err = COONS_ERROR_INIT;
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    assert_coons_ok(coons_mesh_check(m, &r, &err), &err);
    return r.openmesh;
}

static int entry_built(const entry *e, int openmesh)
{
    return strstr(e->file, "openmesh") ? openmesh : 1;
}

static int setup(void **state)
{
    static fixture f;
    coons_test_fail_after(LONG_MAX); /* counts the library's blocks */
    f.mesh = tetra();
    snprintf(f.stl, sizeof f.stl, "guard-%ld.stl", (long)getpid());
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_write(f.mesh, f.stl, COONS_FORMAT_STL_BINARY, NULL, &err), &err);
    *state = &f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    coons__cxx_inject_bad_alloc(NULL);
    coons_mesh_free(f->mesh);
    unlink(f->stl);
    coons_test_fail_after(-1);
    return 0;
}

/* Runs an entry with stdout and stderr sent to a file; *printed receives
 * the bytes it printed. */
static coons_status quiet_call(const entry *e, fixture *f, int *empty, coons_error *err,
                               long *printed)
{
    FILE *cap = tmpfile();
    assert_non_null(cap);
    fflush(stdout);
    fflush(stderr);
    int o = dup(1), r = dup(2);
    assert_true(o >= 0 && r >= 0);
    dup2(fileno(cap), 1);
    dup2(fileno(cap), 2);
    coons_status st = e->call(f, empty, err);
    fflush(stdout);
    fflush(stderr);
    dup2(o, 1);
    dup2(r, 2);
    close(o);
    close(r);
    fseek(cap, 0, SEEK_END);
    *printed = ftell(cap);
    fclose(cap);
    return st;
}

static void test_bad_alloc_at_each_entry(void **state)
{
    fixture *f = *state;
    int openmesh = have_openmesh(f->mesh);
    size_t tried = 0;
    for (size_t i = 0; i < N_ENTRIES; i++) {
        const entry *e = &ENTRIES[i];
        if (!entry_built(e, openmesh)) continue;
        coons_error err = COONS_ERROR_INIT;
        int empty = 0;
        long printed = -1;

        /* Without the hook the entry works: the failure below is the hook's. */
        coons_status st = e->call(f, &empty, &err);
        if (st != COONS_OK) fail_msg("%s -> %d: %s", e->name, st, err.message);

        long live = coons_test_live_allocs();
        unsigned long before = coons__cxx_injected_count();
        coons__cxx_inject_bad_alloc(e->name);
        st = quiet_call(e, f, &empty, &err, &printed);
        coons__cxx_inject_bad_alloc(NULL);
        if (st != COONS_E_NOMEM) fail_msg("%s: status %d, not COONS_E_NOMEM", e->name, st);
        assert_int_equal(err.code, COONS_E_NOMEM);
        assert_string_equal(err.message, "out of memory");
        assert_int_equal(coons__cxx_injected_count(), before + 1); /* its guard threw, once */
        if (!empty) fail_msg("%s: outputs written after std::bad_alloc", e->name);
        assert_int_equal(printed, 0);
        assert_int_equal(coons_test_live_allocs(), live); /* nothing leaked */
        tried++;
    }
    assert_true(tried >= 3);
}

/* coons_model_solidify (C) reaches the CGAL entry: its std::bad_alloc comes
 * back through it as COONS_E_NOMEM, with the model's meshes freed. */
static void test_bad_alloc_through_model_solid(void **state)
{
    (void)state;
    static const char model[] =
        "{\"coons\": 1, \"bodies\": [{\"type\": \"body0\", \"name\": \"cube\", \"corners\": "
        "[[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]}";
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    assert_coons_ok(coons_model_load_memory(model, sizeof model - 1, "cube", NULL, &m, &err), &err);
    long live = coons_test_live_allocs();
    coons_mesh *out = (coons_mesh *)m;
    coons__cxx_inject_bad_alloc("coons_mesh_solidify");
    coons_status st = coons_model_solidify(m, NULL, NULL, &out, NULL, &err);
    coons__cxx_inject_bad_alloc(NULL);
    assert_int_equal(st, COONS_E_NOMEM);
    assert_string_equal(err.message, "out of memory");
    assert_null(out);
    assert_int_equal(coons_test_live_allocs(), live);
    coons_model_free(m);
}

/* Every `extern "C" coons_status NAME(` of the C++ sources is in ENTRIES. */
static void test_table_names_every_entry(void **state)
{
    fixture *f = *state;
    int openmesh = have_openmesh(f->mesh);
    static const char *const files[] = {"src/mesh/openmesh.cpp", "src/csg/cgal_solid.cpp"};
    static const char tag[] = "extern \"C\" coons_status ";
    size_t found = 0;
    for (size_t k = 0; k < 2; k++) {
        if (!openmesh && strstr(files[k], "openmesh")) continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", COONS_SOURCE_DIR, files[k]);
        FILE *fp = fopen(path, "rb");
        if (!fp) fail_msg("cannot open %s", path);
        static char text[1 << 18];
        size_t n = fread(text, 1, sizeof text - 1, fp);
        fclose(fp);
        text[n] = '\0';
        for (const char *p = strstr(text, tag); p; p = strstr(p + 1, tag)) {
            const char *name = p + sizeof tag - 1;
            size_t len = strcspn(name, "( \n");
            int listed = 0;
            for (size_t i = 0; i < N_ENTRIES; i++)
                listed |= strlen(ENTRIES[i].name) == len && !strncmp(ENTRIES[i].name, name, len) &&
                          !strcmp(ENTRIES[i].file, files[k]);
            if (!listed) fail_msg("%s: entry %.*s is not in ENTRIES", files[k], (int)len, name);
            found++;
        }
    }
    assert_int_equal(found, openmesh ? N_ENTRIES : N_ENTRIES - 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_alloc_at_each_entry),
        cmocka_unit_test(test_bad_alloc_through_model_solid),
        cmocka_unit_test(test_table_names_every_entry),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
