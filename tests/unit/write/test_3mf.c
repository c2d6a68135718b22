/* SPDX-License-Identifier: GPL-3.0-or-later */
/* 3MF writer (COONS_FORMAT_3MF), read back with lib3mf's own reader
 * (tests/tools/read3mf.cpp, strict mode): the unit attribute from the
 * units, one object of type "model" per part named after it with one build
 * item each, vertices and triangles as given (hand-built meshes with
 * exactly representable coordinates), the sampled bodies of an
 * `operation: none` model facet for facet against the binary STL of the
 * same mesh read by the test's own parser; refusals (open parts, unknown
 * units) that leave an existing output as it was; determinism.
 *
 * In a build without lib3mf (COONS_WITH_LIB3MF=OFF) the same file checks
 * that every 3MF write is refused with COONS_E_UNSUPPORTED and writes
 * nothing. */
#define _XOPEN_SOURCE 700
#include <float.h>
#include <sys/stat.h>

#include "io_test_util.h"
#ifdef COONS_TEST_LIB3MF
#include "tools/read3mf.h"
#include "coons_test_hooks.h"
#endif

static const char previous[] = "previous contents\n";

static coons_mesh *box_and_tetra(void)
{
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    const double lo[3] = {-1.5, 0.25, 2}, hi[3] = {3.75, 4.5, 10.125};
    io_box(m, "box", lo, hi);
    io_tetra(m, "tetra", 2.5, 1.25, 0.5);
    return m;
}

static void assert_untouched(const char *dir, const char *p, int entries)
{
    size_t len;
    char *d = io_read_file(p, &len);
    assert_non_null(d);
    assert_int_equal(len, strlen(previous));
    assert_memory_equal(d, previous, len);
    free(d);
    assert_int_equal(io_dir_count(dir), entries); /* no temporary file left */
}

#ifdef COONS_TEST_LIB3MF

static void read_ok(const char *path, r3mf *r)
{
    char msg[512];
    if (r3mf_read(path, r, msg, sizeof msg) != 0) fail_msg("lib3mf cannot read %s: %s", path, msg);
}

/* Given a box and a tetrahedron with exactly representable coordinates,
 * when written as 3MF with units "in" and read back with lib3mf, then the
 * unit is inch, there are two "model" objects named box and tetra, each
 * with one build item and no transform, and their vertices and triangles
 * are the parts' own, bit for bit. */
static void test_round_trip(void **state)
{
    (void)state;
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/m.3mf", dir);
    coons_mesh *m = box_and_tetra();
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.units = "in";
    o.name = "two parts";
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_write(m, p, COONS_FORMAT_AUTO, &o, &e), &e);
    r3mf r;
    read_ok(p, &r);
    assert_int_equal(r.unit, R3MF_INCH);
    assert_string_equal(r.title, "two parts");
    assert_int_equal(r.nobj, 2);
    assert_int_equal(r.nitems, 2);
    assert_false(r.item_transform);
    const char *names[2] = {"box", "tetra"};
    const double *xyz = coons_mesh_vertices(m);
    const uint32_t *tri = coons_mesh_triangles(m);
    for (size_t i = 0; i < 2; i++) {
        const r3mf_object *ob = &r.obj[i];
        size_t tf, tc, vf, vc;
        coons_mesh_part_range(m, i, &tf, &tc, &vf, &vc);
        assert_string_equal(ob->name, names[i]);
        assert_int_equal(ob->type, 1); /* "model" */
        assert_true(ob->manifold);
        assert_int_equal(r.item[i], ob->id);
        assert_int_equal(ob->nv, vc);
        assert_int_equal(ob->nt, tc);
        for (size_t k = 0; k < 3 * vc; k++)
            if (ob->v[k] != (float)xyz[3 * vf + k])
                fail_msg("%s coordinate %zu: %.9g, wrote %.9g", names[i], k, ob->v[k],
                         xyz[3 * vf + k]);
        for (size_t k = 0; k < 3 * tc; k++) assert_int_equal(ob->t[k], tri[3 * tf + k] - vf);
    }
    r3mf_free(&r);
    coons_mesh_free(m);
    io_rmdir(dir);
}

/* Given the model's units in each spelling, then the 3MF unit is the
 * matching one of the specification's six; no units is millimeter. */
static void test_units(void **state)
{
    (void)state;
    static const struct {
        const char *units;
        int unit;
    } CASES[] = {{NULL, R3MF_MILLIMETER},      {"", R3MF_MILLIMETER},
                 {"mm", R3MF_MILLIMETER},      {"Millimetre", R3MF_MILLIMETER},
                 {"um", R3MF_MICRON},          {"micron", R3MF_MICRON},
                 {"cm", R3MF_CENTIMETER},      {"CENTIMETERS", R3MF_CENTIMETER},
                 {"in", R3MF_INCH},            {"inches", R3MF_INCH},
                 {"ft", R3MF_FOOT},            {"feet", R3MF_FOOT},
                 {"m", R3MF_METER},            {"metre", R3MF_METER}};
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/u.3mf", dir);
    coons_mesh *m = box_and_tetra();
    for (size_t i = 0; i < sizeof CASES / sizeof CASES[0]; i++) {
        coons_write_options o = COONS_WRITE_OPTIONS_INIT;
        o.units = CASES[i].units;
        coons_error e = COONS_ERROR_INIT;
        assert_coons_ok(coons_mesh_write(m, p, COONS_FORMAT_3MF, &o, &e), &e);
        r3mf r;
        read_ok(p, &r);
        if (r.unit != CASES[i].unit)
            fail_msg("units '%s': unit %d, want %d", CASES[i].units ? CASES[i].units : "(null)",
                     r.unit, CASES[i].unit);
        r3mf_free(&r);
    }
    coons_mesh_free(m);
    io_rmdir(dir);
}

/* Reads a binary STL with the test's own parser: n facets, 9 floats each. */
static float *read_stl(const char *path, size_t *n)
{
    size_t len;
    unsigned char *d = (unsigned char *)io_read_file(path, &len);
    assert_non_null(d);
    assert_true(len >= 84);
    uint32_t c = (uint32_t)d[80] | (uint32_t)d[81] << 8 | (uint32_t)d[82] << 16 |
                 (uint32_t)d[83] << 24;
    assert_int_equal(len, 84 + 50 * (size_t)c);
    float *v = malloc(9 * sizeof *v * (c ? c : 1));
    for (size_t t = 0; t < c; t++)
        for (int k = 0; k < 9; k++) {
            const unsigned char *q = d + 84 + 50 * t + 12 + 4 * (size_t)k;
            uint32_t u = (uint32_t)q[0] | (uint32_t)q[1] << 8 | (uint32_t)q[2] << 16 |
                         (uint32_t)q[3] << 24;
            memcpy(&v[9 * t + (size_t)k], &u, 4);
        }
    free(d);
    *n = c;
    return v;
}

/* Given a model with operation "none" (three bodies), when its sampled
 * mesh is written as 3MF and as binary STL, then lib3mf reads one closed
 * "model" object per body, named after it, each with a build item, in
 * millimeter (the model's "mm"), and the objects' triangles, in order, are
 * the STL's facets: the same float32 corners within the 6 decimals lib3mf
 * keeps (it truncates: 1e-6) and one float32 step. */
static void test_model_against_stl(void **state)
{
    (void)state;
    coons_model *model;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_model_load_file(COONS_SOURCE_DIR "/examples/body-blend-cubic.json",
                                          NULL, &model, &e),
                    &e);
    assert_int_equal(coons_model_operation(model), COONS_OP_NONE);
    coons_mesh *m;
    assert_coons_ok(coons_model_sample(model, NULL, &m, &e), &e);
    char dir[64], p3[128], ps[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p3, sizeof p3, "%s/m.3mf", dir);
    snprintf(ps, sizeof ps, "%s/m.stl", dir);
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.units = coons_model_units(model);
    assert_coons_ok(coons_mesh_write(m, p3, COONS_FORMAT_AUTO, &o, &e), &e);
    assert_coons_ok(coons_mesh_write(m, ps, COONS_FORMAT_AUTO, &o, &e), &e);
    r3mf r;
    read_ok(p3, &r);
    size_t nb = coons_model_body_count(model);
    assert_int_equal(nb, 3);
    assert_int_equal(r.unit, R3MF_MILLIMETER);
    assert_int_equal(r.nobj, nb);
    assert_int_equal(r.nitems, nb);
    size_t nstl;
    float *stl = read_stl(ps, &nstl);
    size_t t = 0;
    for (size_t i = 0; i < nb; i++) {
        const r3mf_object *ob = &r.obj[i];
        assert_string_equal(ob->name, coons_model_body_name(model, i));
        assert_int_equal(ob->type, 1);
        assert_true(ob->manifold);
        assert_int_equal(r.item[i], ob->id);
        for (size_t k = 0; k < ob->nt; k++, t++) {
            assert_true(t < nstl);
            for (int c = 0; c < 3; c++)
                for (int x = 0; x < 3; x++) {
                    float a = ob->v[3 * ob->t[3 * k + (size_t)c] + (size_t)x];
                    float b = stl[9 * t + 3 * (size_t)c + (size_t)x];
                    double tol = 1e-6 + fabs((double)b) * FLT_EPSILON;
                    if (fabs((double)a - (double)b) > tol)
                        fail_msg("body %zu triangle %zu corner %d: 3MF %.9g, STL %.9g", i, k, c,
                                 a, b);
                }
        }
    }
    assert_int_equal(t, nstl);
    free(stl);
    r3mf_free(&r);
    coons_mesh_free(m);
    coons_model_free(model);
    io_rmdir(dir);
}

/* The same mesh gives the same bytes, to a file or to a stream. */
static void test_deterministic(void **state)
{
    (void)state;
    char dir[64], a[128], b[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(a, sizeof a, "%s/a.3mf", dir);
    snprintf(b, sizeof b, "%s/b.3mf", dir);
    coons_mesh *m = box_and_tetra();
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_write(m, a, COONS_FORMAT_AUTO, NULL, &e), &e);
    FILE *fp = fopen(b, "wb");
    assert_non_null(fp);
    assert_coons_ok(coons_mesh_write_stream(m, fp, COONS_FORMAT_3MF, NULL, &e), &e);
    assert_int_equal(fclose(fp), 0);
    size_t la, lb;
    char *da = io_read_file(a, &la), *db = io_read_file(b, &lb);
    assert_int_equal(la, lb);
    assert_memory_equal(da, db, la);
    assert_memory_equal(da, "PK\3\4", 4); /* a zip package */
    free(da);
    free(db);
    coons_mesh_free(m);
    io_rmdir(dir);
}

/* Given an existing output, when the C++ layer runs out of memory
 * (std::bad_alloc injected into the writer's guard), then COONS_E_NOMEM,
 * and the output and the directory are as they were. */
static void test_bad_alloc(void **state)
{
    (void)state;
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/m.3mf", dir);
    io_write_file(p, previous, strlen(previous));
    coons_mesh *m = box_and_tetra();
    const char *entries[] = {"coons__check_3mf", "coons__write_3mf"};
    for (int i = 0; i < 2; i++) {
        coons__cxx_inject_bad_alloc(entries[i]);
        coons_error e = COONS_ERROR_INIT;
        unsigned long before = coons__cxx_injected_count();
        assert_int_equal(coons_mesh_write(m, p, COONS_FORMAT_AUTO, NULL, &e), COONS_E_NOMEM);
        assert_int_equal(coons__cxx_injected_count(), before + 1);
        coons__cxx_inject_bad_alloc(NULL);
        assert_untouched(dir, p, 1);
    }
    coons_mesh_free(m);
    io_rmdir(dir);
}

#endif /* COONS_TEST_LIB3MF */

/* Given an existing output, when a mesh 3MF cannot hold is written over it
 * (a part with one triangle missing, one with a triangle turned over, a
 * closed box with a degenerate triangle across it, an empty mesh, units
 * 3MF has no name for), then COONS_E_UNSUPPORTED (or
 * COONS_E_INVALID for no part) with a message naming the part or the
 * units, and the old file is unchanged with no temporary file left. In a
 * build without lib3mf every write is refused so. */
static void test_refusals(void **state)
{
    (void)state;
    char dir[64], p[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(p, sizeof p, "%s/m.3mf", dir);
    io_write_file(p, previous, strlen(previous));
    coons_error e = COONS_ERROR_INIT;
    double v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const uint32_t open_t[3][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}};
    const uint32_t flip_t[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 3, 2}};
    /* A unit box (io_box's triangles) and the degenerate triangle 0 0 7
     * across it, whose edges 0-7 and 7-0 pair up with each other. */
    double bv[8][3];
    for (int i = 0; i < 8; i++)
        for (int k = 0; k < 3; k++) bv[i][k] = (i >> k) & 1;
    const uint32_t degen_t[13][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4},
                                     {1, 5, 4}, {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6},
                                     {1, 3, 5}, {3, 7, 5}, {0, 0, 7}};
    coons_mesh *open, *flip, *empty, *degen, *good = box_and_tetra();
    assert_coons_ok(coons_mesh_new(&degen, &e), &e);
    assert_coons_ok(coons_mesh_add_part(degen, "sliver", &bv[0][0], 8, &degen_t[0][0], 13, &e),
                    &e);
    assert_coons_ok(coons_mesh_new(&open, &e), &e);
    assert_coons_ok(coons_mesh_add_part(open, "lid-less", &v[0][0], 4, &open_t[0][0], 3, &e), &e);
    assert_coons_ok(coons_mesh_new(&flip, &e), &e);
    io_tetra(flip, "fine", 1, 2, 3);
    assert_coons_ok(coons_mesh_add_part(flip, "turned", &v[0][0], 4, &flip_t[0][0], 4, &e), &e);
    assert_coons_ok(coons_mesh_new(&empty, &e), &e);
#ifdef COONS_TEST_LIB3MF
    assert_int_equal(coons_mesh_write(open, p, COONS_FORMAT_AUTO, NULL, &e), COONS_E_UNSUPPORTED);
    assert_non_null(strstr(e.message, "'lid-less'"));
    assert_non_null(strstr(e.message, "closed"));
    assert_untouched(dir, p, 1);
    assert_int_equal(coons_mesh_write(flip, p, COONS_FORMAT_AUTO, NULL, &e), COONS_E_UNSUPPORTED);
    assert_non_null(strstr(e.message, "'turned'"));
    assert_untouched(dir, p, 1);
    assert_int_equal(coons_mesh_write(degen, p, COONS_FORMAT_AUTO, NULL, &e),
                     COONS_E_UNSUPPORTED);
    assert_non_null(strstr(e.message, "'sliver'"));
    assert_untouched(dir, p, 1);
    assert_int_equal(coons_mesh_write(empty, p, COONS_FORMAT_AUTO, NULL, &e), COONS_E_INVALID);
    assert_untouched(dir, p, 1);
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.units = "furlong";
    assert_int_equal(coons_mesh_write(good, p, COONS_FORMAT_AUTO, &o, &e), COONS_E_UNSUPPORTED);
    assert_non_null(strstr(e.message, "'furlong'"));
    assert_non_null(strstr(e.message, "millimeter"));
    assert_untouched(dir, p, 1);
#else
    coons_mesh *all[5] = {open, flip, empty, degen, good};
    for (int i = 0; i < 5; i++) {
        assert_int_equal(coons_mesh_write(all[i], p, COONS_FORMAT_AUTO, NULL, &e),
                         COONS_E_UNSUPPORTED);
        assert_non_null(strstr(e.message, "without lib3mf"));
        assert_untouched(dir, p, 1);
    }
    FILE *fp = tmpfile();
    assert_non_null(fp);
    assert_int_equal(coons_mesh_write_stream(good, fp, COONS_FORMAT_3MF, NULL, &e),
                     COONS_E_UNSUPPORTED);
    assert_int_equal(ftell(fp), 0);
    fclose(fp);
#endif
    /* The format is in the table either way. */
    coons_format f;
    assert_coons_ok(coons_format_from_name("3MF", &f, &e), &e);
    assert_int_equal(f, COONS_FORMAT_3MF);
    assert_string_equal(coons_format_extension(COONS_FORMAT_3MF), ".3mf");
    assert_int_equal(coons_format_kind(COONS_FORMAT_3MF), COONS_MESH_KIND_SURFACE);
    coons_mesh_free(open);
    coons_mesh_free(flip);
    coons_mesh_free(empty);
    coons_mesh_free(degen);
    coons_mesh_free(good);
    io_rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
#ifdef COONS_TEST_LIB3MF
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_units),
        cmocka_unit_test(test_model_against_stl),
        cmocka_unit_test(test_deterministic),
        cmocka_unit_test(test_bad_alloc),
#endif
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
