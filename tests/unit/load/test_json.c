/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The model loader (coons_model_load_memory): defaults worked out by hand,
 * error positions (line, column in code points, JSON pointer) counted by
 * hand in the literal texts below, limits, locale independence, and a
 * failing allocator at every allocation point (COONS_E_NOMEM, no leak).
 */
#define _POSIX_C_SOURCE 200809L /* setenv, mkdtemp */

#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"

#define BOX_CORNERS "[[0,0,0],[0,0,3],[0,2,0],[0,2,3],[1,0,0],[1,0,3],[1,2,0],[1,2,3]]"
#define BOX "{\"type\": \"body0\", \"corners\": " BOX_CORNERS "}"

static coons_status load(const char *text, coons_model **m, coons_error *err)
{
    return coons_model_load_memory(text, strlen(text), "t.json", NULL, m, err);
}

static void test_defaults(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    const char *t = "{\"coons\": 1, \"bodies\": [" BOX ", {\"type\": \"body0\", \"name\": "
                    "\"lid\", \"corners\": " BOX_CORNERS "}]}";
    assert_coons_ok(load(t, &m, &err), &err);
    assert_int_equal(coons_model_body_count(m), 2);
    assert_string_equal(coons_model_body_name(m, 0), "body0");
    assert_string_equal(coons_model_body_name(m, 1), "lid");
    assert_int_equal(coons_model_find_body(m, "lid"), 1);
    assert_int_equal(coons_model_find_body(m, "body0"), 0);
    assert_int_equal(coons_model_find_body(m, "nope"), -1);
    assert_null(coons_model_body(m, 2));
    assert_string_equal(coons_model_units(m), "mm");
    assert_int_equal(coons_model_operation(m), COONS_OP_UNION);
    /* box [0,1]x[0,2]x[0,3]: diagonal sqrt(14), tolerance 1/1000 of it */
    assert_near(coons_model_tolerance(m), sqrt(14.0) / 1000.0, 1e-18);
    double lo[3], hi[3], elo[3] = {0, 0, 0}, ehi[3] = {1, 2, 3};
    coons_model_control_bbox(m, lo, hi);
    assert_vec3_near(lo, elo, 0);
    assert_vec3_near(hi, ehi, 0);
    double x[3], ex[3] = {0.25, 1.0, 2.25};
    coons_body_eval(coons_model_body(m, 0), 0.25, 0.5, 0.75, x);
    assert_vec3_near(x, ex, 1e-15);
    coons_model_free(m);
}

static void test_settings(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    /* 1.0 equals 1; an escaped key is the same key; [x, y] means z = 0 */
    const char *t = "{\"coons\": 1.0, \"units\": \"in\", \"tolerance\": 2.5e-1, \"operation\": "
                    "\"none\", \"b\\u006fdies\": [{\"type\": \"body0\", \"corners\": "
                    "[[0,0],[0,0,3],[0,2],[0,2,3],[1,0],[1,0,3],[1,2],[1,2,3]]}]}";
    assert_coons_ok(load(t, &m, &err), &err);
    assert_string_equal(coons_model_units(m), "in");
    assert_near(coons_model_tolerance(m), 0.25, 0);
    assert_int_equal(coons_model_operation(m), COONS_OP_NONE);
    double x[3], ex[3] = {1, 2, 0};
    coons_body_eval(coons_model_body(m, 0), 1, 1, 0, x);
    assert_vec3_near(x, ex, 0);
    coons_model_free(m);
}

typedef struct bad_case {
    const char *text;
    coons_status code;
    int line, column;
    const char *path;
} bad_case;

/* Positions counted by hand: line 1-based, column 1-based in code points. */
static const bad_case BAD[] = {
    /* syntax */
    {"", COONS_E_PARSE, 1, 1, ""},
    {"[1]", COONS_E_PARSE, 1, 1, ""},
    {"{\"coons\": 1,}", COONS_E_PARSE, 1, 13, ""},
    {"{\"coons\": 01}", COONS_E_PARSE, 1, 11, "/coons"},
    {"{\"coons\": 1.}", COONS_E_PARSE, 1, 11, "/coons"},
    {"{\"coons\": -}", COONS_E_PARSE, 1, 11, "/coons"},
    {"{\"coons\": tru}", COONS_E_PARSE, 1, 11, "/coons"},
    {"{\"coons\": 1}\n  x", COONS_E_PARSE, 2, 3, ""},
    {"{\"coons\": 1} {}", COONS_E_PARSE, 1, 14, ""},
    {"{\"a\": [1 2]}", COONS_E_PARSE, 1, 10, "/a/0"},
    {"{\"a\": [1, ]}", COONS_E_PARSE, 1, 11, "/a/1"},
    {"{\"a\" 1}", COONS_E_PARSE, 1, 6, "/a"}, /* the key has been read */
    {"{\"a\": \"x\ty\"}", COONS_E_PARSE, 1, 9, "/a"},
    {"{\"a\": \"\\q\"}", COONS_E_PARSE, 1, 8, "/a"},
    {"{\"a\": \"\\ud800\"}", COONS_E_PARSE, 1, 8, "/a"},
    {"{\"a\": \"\\udc00\"}", COONS_E_PARSE, 1, 8, "/a"},
    {"{\"a\": \"abc", COONS_E_PARSE, 1, 7, "/a"},
    {"{\"a\": \"\xc3\xa9\xff\"}", COONS_E_PARSE, 1, 9, "/a"},       /* é then 0xFF */
    {"{\"a\": \"\xed\xa0\x80\"}", COONS_E_PARSE, 1, 8, "/a"},       /* UTF-8 surrogate */
    {"{\"a\": \"\xc0\xaf\"}", COONS_E_PARSE, 1, 8, "/a"},           /* overlong '/' */
    {"{\"a\":\r\n [\r\n\r\n  \"\xe2\x82\xac\", 1 1]}", COONS_E_PARSE, 4, 10, "/a/1"},
    {"{\"a\":\r [\r  1 1]}", COONS_E_PARSE, 3, 5, "/a/0"}, /* lone CR ends a line too */
    /* a UTF-8 byte order mark is skipped and not counted as a column */
    {"\xef\xbb\xbf{\"coons\": 1, \"bodies\": []}", COONS_E_INVALID, 1, 24, "/bodies"},
    {"\xef\xbb\xbf{\"coons\": 1} x", COONS_E_PARSE, 1, 14, ""},
    /* version and top level */
    {"{\"bodies\": []}", COONS_E_INVALID, 1, 1, ""},
    {"{\"coons\": 2, \"bodies\": [" BOX "]}", COONS_E_UNSUPPORTED, 1, 11, "/coons"},
    {"{\"coons\": \"1\", \"bodies\": [" BOX "]}", COONS_E_INVALID, 1, 11, "/coons"},
    {"{\"coons\": 1, \"bodies\": []}", COONS_E_INVALID, 1, 24, "/bodies"},
    {"{\"coons\": 1}", COONS_E_INVALID, 1, 1, ""},
    {"{\"coons\": 1, \"tolerance\": 0, \"bodies\": [" BOX "]}", COONS_E_INVALID, 1, 27,
     "/tolerance"},
    {"{\"coons\": 1, \"tolerance\": -1e-3, \"bodies\": [" BOX "]}", COONS_E_INVALID, 1, 27,
     "/tolerance"},
    {"{\"coons\": 1, \"operation\": \"merge\", \"bodies\": [" BOX "]}", COONS_E_INVALID, 1, 27,
     "/operation"},
    {"{\"coons\": 1, \"colour\": 1, \"bodies\": [" BOX "]}", COONS_E_INVALID, 1, 14, "/colour"},
    {"{\"coons\": 1, \"bodies\": [" BOX "], \"coons\": 1}", COONS_E_INVALID, 1, 123, "/coons"},
    /* numbers */
    {"{\"coons\": 1, \"tolerance\": 1e400, \"bodies\": [" BOX "]}", COONS_E_INVALID, 1, 27,
     "/tolerance"},
    {"{\"coons\": 1, \"tolerance\": -1e400, \"bodies\": [" BOX "]}", COONS_E_INVALID, 1, 27,
     "/tolerance"},
    /* bodies: "{\"coons\": 1, \"bodies\": [" is 24 characters, so a body starts at 25 */
    {"{\"coons\": 1, \"bodies\": [{\"type\": \"body9\"}]}", COONS_E_INVALID, 1, 34,
     "/bodies/0/type"},
    {"{\"coons\": 1, \"bodies\": [{\"corners\": []}]}", COONS_E_INVALID, 1, 25, "/bodies/0"},
    {"{\"coons\": 1, \"bodies\": [{\"type\": \"body0\", \"corners\": [[0,0,0]]}]}",
     COONS_E_INVALID, 1, 54, "/bodies/0/corners"},
    {"{\"coons\": 1, \"bodies\": [{\"type\": \"body0\", \"corners\": [[0,0,0,0]]}]}",
     COONS_E_INVALID, 1, 54, "/bodies/0/corners"},
    {"{\"coons\": 1, \"bodies\": [{\"type\": \"body0\", \"corners\": "
     "[[0,0,0],[0,0,3],[0,2,0],[0,2,3],[1,0,0],[1,0,3],[1,2,0],[1,2,3,4]]}]}",
     COONS_E_INVALID, 1, 111, "/bodies/0/corners/7"},
    {"{\"coons\": 1, \"bodies\": [{\"type\": \"bezier-volume\", \"blend\": \"cubic\"}]}",
     COONS_E_INVALID, 1, 51, "/bodies/0/blend"},
    {"{\"coons\": 1, \"bodies\": [{\"type\": \"body0\", \"blend\": \"smooth\", \"corners\": "
     BOX_CORNERS "}]}",
     COONS_E_INVALID, 1, 52, "/bodies/0/blend"},
    {"{\"coons\": 1, \"bodies\": [{\"type\": \"body0\", \"name\": 7, \"corners\": " BOX_CORNERS
     "}]}",
     COONS_E_INVALID, 1, 51, "/bodies/0/name"},
    {"{\"coons\": 1, \"bodies\": [" BOX ", {\"type\": \"body0\", \"name\": \"body0\", \"corners\": "
     BOX_CORNERS "}, {\"type\": \"body0\", \"name\": \"body0\", \"corners\": " BOX_CORNERS "}]}",
     COONS_E_INVALID, 1, 262, "/bodies/2/name"},
};

static void test_bad(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof BAD / sizeof *BAD; i++) {
        const bad_case *c = &BAD[i];
        coons_error err = COONS_ERROR_INIT;
        coons_model *m = (coons_model *)&err; /* must be reset to NULL */
        coons_status rc = load(c->text, &m, &err);
        if (rc != c->code || err.line != c->line || err.column != c->column ||
            strcmp(err.path, c->path) != 0 || err.code != (int)rc || m != NULL)
            fail_msg("case %zu: %s\n  got %d %d:%d '%s' (%s), expected %d %d:%d '%s'", i,
                     c->text, rc, err.line, err.column, err.path, err.message, c->code, c->line,
                     c->column, c->path);
        assert_string_equal(err.file, "t.json");
        /* The message is self-contained: FILE:LINE:COL: PATH: ... */
        char head[600];
        snprintf(head, sizeof head, "t.json:%d:%d: %s: ", c->line, c->column,
                 c->path[0] ? c->path : "(root)");
        if (strncmp(err.message, head, strlen(head)) != 0)
            fail_msg("case %zu: message '%s' does not start with '%s'", i, err.message, head);
    }
}

static void test_bom(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    assert_coons_ok(load("\xef\xbb\xbf{\"coons\": 1, \"bodies\": [" BOX "]}", &m, &err), &err);
    assert_int_equal(coons_model_body_count(m), 1);
    coons_model_free(m);
}

static void test_pointer_escape(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    /* RFC 6901: '~' -> ~0, '/' -> ~1; the key is decoded first (\u00e9 = é) */
    const char *t = "{\"coons\": 1, \"a/b~c\\u00e9\": 1, \"bodies\": [" BOX "]}";
    assert_int_equal(load(t, &m, &err), COONS_E_INVALID);
    assert_string_equal(err.path, "/a~1b~0c\xc3\xa9");
    assert_int_equal(err.column, 14);
    assert_null(m);
}

/* A model that touches every loader path that body 0/1 and volumes have:
 * curves of every type, knots, weights, names. */
static const char *RICH =
    "{\"coons\": 1, \"units\": \"mm\", \"bodies\": [\n"
    " {\"type\": \"body0\", \"name\": \"a\", \"blend\": \"cubic\", \"corners\": " BOX_CORNERS "},\n"
    " {\"type\": \"body1\", \"name\": \"b\", \"edges\": {\n"
    "  \"u00\": {\"type\": \"bspline\", \"degree\": 2, \"points\": [[0,0,0],[0.5,-0.1,0],[1,0,0]],"
    " \"knots\": [0,0,0,1,1,1], \"weights\": [1,2,1]},\n"
    "  \"u01\": {\"type\": \"polyline\", \"points\": [[0,0,1],[0.5,0,1],[1,0,1]]},\n"
    "  \"u10\": {\"type\": \"bezier\", \"points\": [[0,1,0],[0.5,1.2,0],[1,1,0]]},\n"
    "  \"u11\": {\"type\": \"hermite\", \"points\": [[0,1,1],[1,1,1]], \"tangents\": [[1,0],[1,0]]},\n"
    "  \"v00\": {\"type\": \"clamped-cubic\", \"points\": [[0,0,0],[0,0.3,0],[0,0.6,0],[0,1,0]]},\n"
    "  \"v01\": {\"type\": \"line\", \"points\": [[0,0,1],[0,1,1]]},\n"
    "  \"v10\": {\"type\": \"line\", \"points\": [[1,0,0],[1,1,0]]},\n"
    "  \"v11\": {\"type\": \"line\", \"points\": [[1,0,1],[1,1,1]]},\n"
    "  \"w00\": {\"type\": \"line\", \"points\": [[0,0,0],[0,0,1]]},\n"
    "  \"w01\": {\"type\": \"line\", \"points\": [[0,1,0],[0,1,1]]},\n"
    "  \"w10\": {\"type\": \"line\", \"points\": [[1,0,0],[1,0,1]]},\n"
    "  \"w11\": {\"type\": \"line\", \"points\": [[1,1,0],[1,1,1]]}}},\n"
    " {\"type\": \"bezier-volume\", \"points\": [[[[0,0,0],[0,0,1]],[[0,1,0],[0,1,1]]],"
    "[[[1,0,0],[1,0,1]],[[1,1,0],[1,1,1]]]]},\n"
    " {\"type\": \"bspline-volume\", \"degree\": [1,1,1], \"knots\": [[0,0,1,1],[0,0,2,2],[0,0,1,1]],"
    " \"weights\": [[[1,1],[1,1]],[[1,1],[1,1]]],"
    " \"points\": [[[[0,0,0],[0,0,1]],[[0,1,0],[0,1,1]]],[[[1,0,0],[1,0,1]],[[1,1,0],[1,1,1]]]]}\n"
    "]}";

/* A unit cube as a body2 whose faces use every patch type: x = (u, v, w). */
static const char *FACES =
    "{\"coons\": 1, \"bodies\": [{\"type\": \"body2\", \"blend\": \"linear\", \"faces\": {\n"
    " \"u0\": {\"type\": \"hermite-coons\", \"boundary\": {"
    "\"t0\": {\"type\": \"line\", \"points\": [[0,0,0],[0,1,0]]},"
    "\"t1\": {\"type\": \"line\", \"points\": [[0,0,1],[0,1,1]]},"
    "\"s0\": {\"type\": \"line\", \"points\": [[0,0,0],[0,0,1]]},"
    "\"s1\": {\"type\": \"line\", \"points\": [[0,1,0],[0,1,1]]}},"
    " \"cross\": {\"t0\": {\"type\": \"line\", \"points\": [[0,0,1],[0,0,1]]},"
    "\"t1\": {\"type\": \"line\", \"points\": [[0,0,1],[0,0,1]]},"
    "\"s0\": {\"type\": \"line\", \"points\": [[0,1,0],[0,1,0]]},"
    "\"s1\": {\"type\": \"line\", \"points\": [[0,1,0],[0,1,0]]}},"
    " \"twist\": [[0,0],[0,0],[0,0,0],[0,0]]},\n"
    " \"u1\": {\"type\": \"coons\", \"blend\": \"cubic\", \"boundary\": {"
    "\"t0\": {\"type\": \"line\", \"points\": [[1,0,0],[1,1,0]]},"
    "\"t1\": {\"type\": \"line\", \"points\": [[1,0,1],[1,1,1]]},"
    "\"s0\": {\"type\": \"line\", \"points\": [[1,0,0],[1,0,1]]},"
    "\"s1\": {\"type\": \"line\", \"points\": [[1,1,0],[1,1,1]]}}},\n"
    " \"v0\": {\"type\": \"bezier-surface\", \"points\": [[[0,0,0],[0,0,1]],[[1,0,0],[1,0,1]]]},\n"
    " \"v1\": {\"type\": \"bspline-surface\", \"degree\": [1,1], \"knots\": [[0,0,1,1],[0,0,1,1]],"
    " \"weights\": [[1,1],[1,1]], \"points\": [[[0,1,0],[0,1,1]],[[1,1,0],[1,1,1]]]},\n"
    " \"w0\": {\"type\": \"bilinear\", \"corners\": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]]},\n"
    " \"w1\": {\"type\": \"ruled\", \"curves\": [{\"type\": \"line\", \"points\": [[0,0,1],[1,0,1]]},"
    "{\"type\": \"line\", \"points\": [[0,1,1],[1,1,1]]}]}}}]}";

static void test_faces(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    assert_coons_ok(load(FACES, &m, &err), &err);
    assert_int_equal(coons_body_kind(coons_model_body(m, 0)), COONS_BODY_BODY2);
    double x[3], ex[3] = {0.25, 0.5, 0.75};
    coons_body_eval(coons_model_body(m, 0), 0.25, 0.5, 0.75, x);
    assert_vec3_near(x, ex, 1e-14);
    coons_model_free(m);
}

static void test_rich(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    assert_coons_ok(load(RICH, &m, &err), &err);
    assert_int_equal(coons_model_body_count(m), 4);
    assert_int_equal(coons_body_kind(coons_model_body(m, 1)), COONS_BODY_BODY1);
    assert_string_equal(coons_model_body_name(m, 3), "body3");
    /* u10 is a quadratic Bezier: at u = 1/2 the edge point is
     * (P0 + 2 P1 + P2)/4 = (0.5, 1.1, 0). */
    double x[3], ex[3] = {0.5, 1.1, 0.0};
    coons_body_eval(coons_model_body(m, 1), 0.5, 1.0, 0.0, x);
    assert_vec3_near(x, ex, 1e-14);
    coons_model_free(m);
}

static void test_nomem(void **state)
{
    (void)state;
    const char *texts[] = {RICH, FACES, "{\"coons\": 1, \"bodies\": [" BOX ", {\"type\": \"body0\", "
                                 "\"name\": \"x\", \"corners\": " BOX_CORNERS "}]}"};
    for (size_t k = 0; k < 3; k++) {
        long n = 0;
        for (;; n++) {
            coons_error err = COONS_ERROR_INIT;
            coons_model *m = NULL;
            coons_test_fail_after(n);
            coons_status rc = load(texts[k], &m, &err);
            if (rc == COONS_OK) {
                coons_model_free(m);
                assert_int_equal(coons_test_live_allocs(), 0);
                break;
            }
            if (rc != COONS_E_NOMEM) fail_msg("allocation %ld: %d %s", n, rc, err.message);
            assert_null(m);
            assert_int_equal(err.code, COONS_E_NOMEM);
            if (coons_test_live_allocs() != 0)
                fail_msg("allocation %ld failed: %ld blocks leaked", n, coons_test_live_allocs());
            assert_true(n < 100000);
        }
        coons_test_fail_after(-1);
        assert_true(n > 10); /* it did exercise many allocation points */
    }
}

static void test_limits(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    const char *t = "{\"coons\": 1, \"bodies\": [" BOX "]}";
    coons_model_load_options o = COONS_MODEL_LOAD_OPTIONS_INIT;
    o.max_bytes = strlen(t) - 1;
    assert_int_equal(coons_model_load_memory(t, strlen(t), "t.json", &o, &m, &err),
                     COONS_E_LIMIT);
    assert_non_null(strstr(err.message, "limit"));
    assert_int_equal(err.line, 0);
    o.max_bytes = strlen(t);
    assert_coons_ok(coons_model_load_memory(t, strlen(t), "t.json", &o, &m, &err), &err);
    coons_model_free(m);

    /* root, "coons", 1, "bodies", [ , body, "type", "body0", "corners", [ : 10 values,
     * and 8 points of 1 array + 3 numbers: 42 in all */
    coons_model_load_options v = COONS_MODEL_LOAD_OPTIONS_INIT;
    v.max_values = 41;
    assert_int_equal(coons_model_load_memory(t, strlen(t), "t.json", &v, &m, &err),
                     COONS_E_LIMIT);
    assert_non_null(strstr(err.message, "41"));
    v.max_values = 42;
    assert_coons_ok(coons_model_load_memory(t, strlen(t), "t.json", &v, &m, &err), &err);
    coons_model_free(m);

    /* depth: root 1, bodies 2, body 3, corners 4, point 5 */
    coons_model_load_options d = COONS_MODEL_LOAD_OPTIONS_INIT;
    d.max_depth = 4;
    assert_int_equal(coons_model_load_memory(t, strlen(t), "t.json", &d, &m, &err),
                     COONS_E_LIMIT);
    assert_string_equal(err.path, "/bodies/0/corners/0");
    assert_int_equal(err.column, 55);
    d.max_depth = 5;
    assert_coons_ok(coons_model_load_memory(t, strlen(t), "t.json", &d, &m, &err), &err);
    coons_model_free(m);

    coons_model_load_options p = COONS_MODEL_LOAD_OPTIONS_INIT;
    p.max_points = 7;
    assert_int_equal(coons_model_load_memory(t, strlen(t), "t.json", &p, &m, &err),
                     COONS_E_LIMIT);
    assert_string_equal(err.path, "/bodies/0/corners");
    p.max_points = 8;
    assert_coons_ok(coons_model_load_memory(t, strlen(t), "t.json", &p, &m, &err), &err);
    coons_model_free(m);

    /* default depth limit 64 */
    char deep[400];
    size_t k = (size_t)snprintf(deep, sizeof deep, "{\"coons\": 1, \"x\": ");
    for (int i = 0; i < 64; i++) deep[k++] = '[';
    for (int i = 0; i < 64; i++) deep[k++] = ']';
    deep[k++] = '}';
    deep[k] = '\0';
    assert_int_equal(load(deep, &m, &err), COONS_E_LIMIT);
    assert_int_equal(err.column, 19 + 63);
    assert_non_null(strstr(err.message, "64"));
}

static void test_not_terminated(void **state)
{
    (void)state;
    /* An exact-size heap copy: a read past the end shows under valgrind/ASan. */
    const char *t = "{\"coons\": 1, \"tolerance\": 0.125, \"bodies\": [" BOX "]}";
    size_t n = strlen(t);
    char *b = malloc(n);
    assert_non_null(b);
    memcpy(b, t, n);
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    assert_coons_ok(coons_model_load_memory(b, n, NULL, NULL, &m, &err), &err);
    assert_near(coons_model_tolerance(m), 0.125, 0);
    coons_model_free(m);
    assert_int_equal(coons_model_load_memory(b, n - 1, NULL, NULL, &m, &err), COONS_E_PARSE);
    assert_string_equal(err.file, "<buffer>");
    free(b);
}

static void test_file_errors(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    assert_int_equal(coons_model_load_file("/nonexistent/dir/m.json", NULL, &m, &err), COONS_E_IO);
    assert_non_null(strstr(err.message, "No such file or directory"));
    assert_string_equal(err.file, "/nonexistent/dir/m.json");
    assert_int_equal(coons_model_load_file("/", NULL, &m, &err), COONS_E_IO);
    assert_null(m);
}

/* Numbers must not follow LC_NUMERIC: in de_DE "0.5" would read as 0. The
 * locale is compiled into the build directory when localedef can do it. */
static void test_locale(void **state)
{
    (void)state;
    char dir[512];
    snprintf(dir, sizeof dir, "%s/tests/locale", COONS_BINARY_DIR);
    char cmd[2048];
    if (snprintf(cmd, sizeof cmd,
             "mkdir -p '%s' && (test -d '%s/de_DE.UTF-8' || localedef -i de_DE -f UTF-8 "
             "'%s/de_DE.UTF-8' >/dev/null 2>&1)",
             dir, dir, dir) >= (int)sizeof cmd ||
        system(cmd) != 0) {
        fail_msg("localedef cannot compile de_DE.UTF-8 (tools/setup.sh installs `locales`)");
    }
    setenv("LOCPATH", dir, 1);
    if (!setlocale(LC_ALL, "de_DE.UTF-8")) {
        fail_msg("de_DE.UTF-8 compiled but not selectable");
    }
    char probe[16];
    snprintf(probe, sizeof probe, "%.1f", 0.5);
    assert_string_equal(probe, "0,5"); /* the locale is really in effect */
    coons_error err = COONS_ERROR_INIT;
    coons_model *m = NULL;
    const char *t = "{\"coons\": 1, \"tolerance\": 0.5, \"bodies\": [" BOX "]}";
    coons_status rc = load(t, &m, &err);
    setlocale(LC_ALL, "C");
    assert_coons_ok(rc, &err);
    assert_near(coons_model_tolerance(m), 0.5, 0);
    coons_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults),       cmocka_unit_test(test_settings),
        cmocka_unit_test(test_bom),
        cmocka_unit_test(test_bad),            cmocka_unit_test(test_pointer_escape),
        cmocka_unit_test(test_rich),           cmocka_unit_test(test_faces),
        cmocka_unit_test(test_nomem),
        cmocka_unit_test(test_limits),         cmocka_unit_test(test_not_terminated),
        cmocka_unit_test(test_file_errors),    cmocka_unit_test(test_locale),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
