/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The names of the model format agree everywhere they appear:
 * - the core's names (coons_curve_type_name() and the others) are exactly
 *   the types and keys the loader accepts: every type the core names has a
 *   loader row, and the loader has no type the core does not name;
 * - what the loader accepts is asked of the loader itself: a model with an
 *   unknown type or key is refused with "expected one of: ..." listing
 *   what it takes, for the top level, every body, patch and curve type, and
 *   the edges, faces, boundary and cross objects;
 * - tests/fuzz/model.dict holds every type name and every key the loader
 *   accepts, quoted as in a model.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"

enum { MAXN = 128, NAMELEN = 40 };

typedef struct list {
    int n;
    char s[MAXN][NAMELEN];
} list;

static list accepted; /* every type name and key the loader accepts */

static void add_accepted(const char *s)
{
    for (int i = 0; i < accepted.n; i++)
        if (strcmp(accepted.s[i], s) == 0) return;
    assert_true(accepted.n < MAXN);
    snprintf(accepted.s[accepted.n++], NAMELEN, "%s", s);
}

static list core(const char *(*name)(int))
{
    list l = {0};
    while (l.n < MAXN && name(l.n)) {
        snprintf(l.s[l.n], NAMELEN, "%s", name(l.n));
        l.n++;
    }
    return l;
}

/* Casts to the int-indexed signature of the type names. */
static const char *curve_type(int i) { return coons_curve_type_name((coons_curve_type)i); }
static const char *patch_type(int i) { return coons_patch_type_name((coons_patch_type)i); }
static const char *body_type(int i) { return coons_body_type_name((coons_body_type)i); }

/* The list after "expected one of: " in the loader's refusal of json. */
static list expected(const char *json)
{
    coons_model *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    coons_status rc = coons_model_load_memory(json, strlen(json), "names", NULL, &m, &err);
    coons_model_free(m);
    const char *p = strstr(err.message, "expected one of: ");
    if (rc != COONS_E_INVALID || !p) fail_msg("%s\n -> %d: %s", json, rc, err.message);
    list l = {0};
    for (p += strlen("expected one of: "); *p && l.n < MAXN; l.n++) {
        size_t k = strcspn(p, ",");
        assert_true(k > 0 && k < NAMELEN);
        memcpy(l.s[l.n], p, k);
        l.s[l.n][k] = '\0';
        p += k;
        if (*p == ',') p += 2;
    }
    for (int i = 0; i < l.n; i++) add_accepted(l.s[i]);
    return l;
}

static void join(const list *l, char *out, size_t cap)
{
    size_t o = 0;
    out[0] = '\0';
    for (int i = 0; i < l->n && o < cap; i++) {
        int k = snprintf(out + o, cap - o, "%s%s", i ? " " : "", l->s[i]);
        if (k < 0) break;
        o += (size_t)k;
    }
}

static void assert_same(const char *what, const list *loader, const list *want)
{
    int same = loader->n == want->n;
    for (int i = 0; same && i < want->n; i++) same = strcmp(loader->s[i], want->s[i]) == 0;
    if (!same) {
        char a[1024], b[1024];
        join(loader, a, sizeof a);
        join(want, b, sizeof b);
        fail_msg("%s: the loader takes [%s], the core names [%s]", what, a, b);
    }
}

static int has(const list *l, const char *s)
{
    for (int i = 0; i < l->n; i++)
        if (strcmp(l->s[i], s) == 0) return 1;
    return 0;
}

#define LINE "{\"type\": \"line\", \"points\": [[0, 0], [1, 0]]}"

/* A body1 whose first edge (read first) is curve. */
static void in_curve(char *out, size_t cap, const char *curve)
{
    list e = core(coons_body_edge_name);
    int o = snprintf(out, cap, "{\"coons\": 1, \"bodies\": [{\"type\": \"body1\", \"edges\": {");
    for (int i = 0; i < e.n; i++)
        o += snprintf(out + o, cap - (size_t)o, "%s\"%s\": %s", i ? ", " : "", e.s[i],
                      i ? LINE : curve);
    snprintf(out + o, cap - (size_t)o, "}}]}");
}

/* A body2 whose first face (read first) is patch. */
static void in_patch(char *out, size_t cap, const char *patch)
{
    list f = core(coons_body_face_name);
    int o = snprintf(out, cap, "{\"coons\": 1, \"bodies\": [{\"type\": \"body2\", \"faces\": {");
    for (int i = 0; i < f.n; i++)
        o += snprintf(out + o, cap - (size_t)o, "%s\"%s\": %s", i ? ", " : "", f.s[i],
                      i ? "{}" : patch);
    snprintf(out + o, cap - (size_t)o, "}}]}");
}

/* Given an unknown type where a body, patch or curve goes, then the loader
 * lists exactly the core's type names, in the core's order. */
static void test_types(void **state)
{
    (void)state;
    char m[4096];
    list bt = core(body_type), pt = core(patch_type), ct = core(curve_type);
    assert_int_equal(bt.n, COONS_BODY_MORPH + 1);    /* the last body type */
    assert_int_equal(pt.n, COONS_PATCH_NETWORK + 1); /* the last patch type */
    assert_int_equal(ct.n, 7);
    list l = expected("{\"coons\": 1, \"bodies\": [{\"type\": \"zzz\"}]}");
    assert_same("body types", &l, &bt);
    in_patch(m, sizeof m, "{\"type\": \"zzz\"}");
    l = expected(m);
    assert_same("patch types", &l, &pt);
    in_curve(m, sizeof m, "{\"type\": \"zzz\"}");
    l = expected(m);
    assert_same("curve types", &l, &ct);
}

/* Given an unknown key in the edges, faces, boundary and cross objects,
 * then the loader lists exactly the core's edge, face and side names. */
static void test_parts(void **state)
{
    (void)state;
    char m[4096];
    list e = core(coons_body_edge_name), f = core(coons_body_face_name),
         s = core(coons_patch_side_name);
    assert_int_equal(e.n, 12);
    assert_int_equal(f.n, 6);
    assert_int_equal(s.n, 4);
    list l = expected("{\"coons\": 1, \"bodies\": [{\"type\": \"body1\", \"edges\": {\"zzz\": 1}}]}");
    assert_same("body1 edges", &l, &e);
    l = expected("{\"coons\": 1, \"bodies\": [{\"type\": \"body2\", \"faces\": {\"zzz\": 1}}]}");
    assert_same("body2 faces", &l, &f);
    in_patch(m, sizeof m, "{\"type\": \"coons\", \"boundary\": {\"zzz\": 1}}");
    l = expected(m);
    assert_same("boundary sides", &l, &s);
    char p[1024];
    snprintf(p, sizeof p,
             "{\"type\": \"hermite-coons\", \"boundary\": {\"%s\": %s, \"%s\": %s, \"%s\": %s, "
             "\"%s\": %s}, \"cross\": {\"zzz\": 1}}",
             s.s[0], LINE, s.s[1], LINE, s.s[2], LINE, s.s[3], LINE);
    in_patch(m, sizeof m, p);
    l = expected(m);
    assert_same("cross sides", &l, &s);
}

/* Given an unknown key in the model and in every type, then each lists
 * what it takes, "type" (or "coons" and "bodies") among them. */
static void test_keys(void **state)
{
    (void)state;
    char m[4096], o[256];
    list l = expected("{\"coons\": 1, \"zzz\": 1}");
    assert_true(has(&l, "coons") && has(&l, "bodies"));
    list bt = core(body_type), pt = core(patch_type), ct = core(curve_type);
    for (int i = 0; i < bt.n; i++) {
        snprintf(m, sizeof m, "{\"coons\": 1, \"bodies\": [{\"type\": \"%s\", \"zzz\": 1}]}",
                 bt.s[i]);
        l = expected(m);
        assert_true(has(&l, "type") && has(&l, "name"));
    }
    for (int i = 0; i < pt.n; i++) {
        snprintf(o, sizeof o, "{\"type\": \"%s\", \"zzz\": 1}", pt.s[i]);
        in_patch(m, sizeof m, o);
        l = expected(m);
        assert_true(has(&l, "type"));
    }
    for (int i = 0; i < ct.n; i++) {
        snprintf(o, sizeof o, "{\"type\": \"%s\", \"zzz\": 1}", ct.s[i]);
        in_curve(m, sizeof m, o);
        l = expected(m);
        assert_true(has(&l, "type") && has(&l, "points"));
    }
}

/* Given the names gathered by the tests above (cmocka runs them in order),
 * then tests/fuzz/model.dict quotes each. */
static void test_dictionary(void **state)
{
    (void)state;
    assert_true(accepted.n >= 40);
    FILE *f = fopen(COONS_SOURCE_DIR "/tests/fuzz/model.dict", "r");
    assert_non_null(f);
    list d = {0};
    char line[256];
    while (fgets(line, sizeof line, f) && d.n < MAXN) {
        size_t n = strcspn(line, "\r\n");
        line[n] = '\0';
        /* "\"name\"": libFuzzer's escapes, the entry a quoted name */
        if (n < 6 || strncmp(line, "\"\\\"", 3) != 0 || strcmp(line + n - 3, "\\\"\"") != 0)
            continue;
        line[n - 3] = '\0';
        if (strchr(line + 3, '\\') || strlen(line + 3) >= NAMELEN) continue;
        snprintf(d.s[d.n++], NAMELEN, "%s", line + 3);
    }
    fclose(f);
    for (int i = 0; i < accepted.n; i++)
        if (!has(&d, accepted.s[i]))
            fail_msg("tests/fuzz/model.dict lacks the line \"\\\"%s\\\"\"", accepted.s[i]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_types),
        cmocka_unit_test(test_parts),
        cmocka_unit_test(test_keys),
        cmocka_unit_test(test_dictionary),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
