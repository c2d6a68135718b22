/* SPDX-License-Identifier: GPL-3.0-or-later */
/* OpenSCAD writer, read back by a small tokenizer and parser of the
 * OpenSCAD subset it must produce (module definitions, calls with named
 * vector arguments, line comments), independent of the writer's layout.
 * Checks: exact doubles, each triangle reversed (clockwise from outside),
 * one module per part with a valid, unique, non-built-in name, a module for
 * the whole model and a top-level call. Rendering by the real openscad is
 * in write/test_openscad.c. */
#define _XOPEN_SOURCE 700
#include <ctype.h>
#include <float.h>

#include "io_test_util.h"

/* ---- tokenizer --------------------------------------------------------- */

enum { T_END, T_ID, T_NUM, T_PUNCT };
typedef struct tok {
    int kind;
    char text[64];
} tok;

typedef struct lexer {
    const char *p;
    tok cur;
    char comments[2048];
} lexer;

static void lex_next(lexer *lx)
{
    const char *p = lx->p;
    for (;;) {
        while (isspace((unsigned char)*p)) p++;
        if (p[0] == '/' && p[1] == '/') {
            const char *eol = strchr(p, '\n');
            size_t l = eol ? (size_t)(eol - p) + 1 : strlen(p), have = strlen(lx->comments);
            if (have + l < sizeof lx->comments) {
                memcpy(lx->comments + have, p, l);
                lx->comments[have + l] = '\0';
            }
            p += l;
            continue;
        }
        if (p[0] == '/' && p[1] == '*') fail_msg("block comments are not expected");
        break;
    }
    tok *t = &lx->cur;
    size_t n = 0;
    if (!*p) {
        t->kind = T_END;
    } else if (isalpha((unsigned char)*p) || *p == '_') {
        t->kind = T_ID;
        while (isalnum((unsigned char)*p) || *p == '_') t->text[n++] = *p++;
    } else if (isdigit((unsigned char)*p) || *p == '.') {
        /* OpenSCAD's number: D+ ('.' D*)? | '.' D+, then ([eE][+-]?D+)? */
        t->kind = T_NUM;
        while (isdigit((unsigned char)*p) || *p == '.') t->text[n++] = *p++;
        if (*p == 'e' || *p == 'E') {
            t->text[n++] = *p++;
            if (*p == '+' || *p == '-') t->text[n++] = *p++;
            assert_true(isdigit((unsigned char)*p));
            while (isdigit((unsigned char)*p)) t->text[n++] = *p++;
        }
    } else {
        t->kind = T_PUNCT;
        t->text[n++] = *p++;
    }
    t->text[n] = '\0';
    lx->p = p;
}

static void lex_expect(lexer *lx, const char *text)
{
    if (strcmp(lx->cur.text, text) != 0) fail_msg("expected '%s', got '%s'", text, lx->cur.text);
    lex_next(lx);
}

static int lex_is(const lexer *lx, const char *text) { return strcmp(lx->cur.text, text) == 0; }

/* number := '-'? NUM */
static double parse_number(lexer *lx)
{
    int neg = 0;
    if (lex_is(lx, "-")) {
        neg = 1;
        lex_next(lx);
    }
    assert_int_equal(lx->cur.kind, T_NUM);
    double v = strtod(lx->cur.text, NULL);
    lex_next(lx);
    return neg ? -v : v;
}

/* '[' '[' n n n ']' (',' ...)* ']' into a growing array of doubles. */
static size_t parse_triples(lexer *lx, double **out)
{
    size_t n = 0, cap = 64;
    *out = malloc(cap * 3 * sizeof **out);
    lex_expect(lx, "[");
    while (!lex_is(lx, "]")) {
        if (n) lex_expect(lx, ",");
        lex_expect(lx, "[");
        if (n == cap) *out = realloc(*out, (cap *= 2) * 3 * sizeof **out);
        for (int k = 0; k < 3; k++) {
            if (k) lex_expect(lx, ",");
            (*out)[3 * n + (size_t)k] = parse_number(lx);
        }
        lex_expect(lx, "]");
        n++;
    }
    lex_expect(lx, "]");
    return n;
}

typedef struct module {
    char name[64];
    size_t np, nf;
    double *points, *faces; /* faces as doubles: exact for indices */
    char calls[16][64];
    size_t ncalls;
} module;

typedef struct scad {
    module mod[16];
    size_t nmod;
    char top[4][64];
    size_t ntop;
    char comments[2048];
} scad;

/* call := ID '(' (ID '=' (vector | number) (',' ...)*)? ')' ';' */
static void parse_call(lexer *lx, module *m, char (*calls)[64], size_t *ncalls)
{
    assert_int_equal(lx->cur.kind, T_ID);
    char name[64];
    snprintf(name, sizeof name, "%s", lx->cur.text);
    lex_next(lx);
    lex_expect(lx, "(");
    if (strcmp(name, "polyhedron") == 0) {
        assert_non_null(m);
        while (!lex_is(lx, ")")) {
            if (lex_is(lx, ",")) lex_next(lx);
            char arg[64];
            snprintf(arg, sizeof arg, "%s", lx->cur.text);
            lex_next(lx);
            lex_expect(lx, "=");
            if (strcmp(arg, "points") == 0)
                m->np = parse_triples(lx, &m->points);
            else if (strcmp(arg, "faces") == 0)
                m->nf = parse_triples(lx, &m->faces);
            else if (strcmp(arg, "convexity") == 0)
                assert_true(parse_number(lx) >= 1);
            else
                fail_msg("unexpected argument %s", arg);
        }
    } else {
        snprintf(calls[(*ncalls)++], 64, "%s", name);
    }
    lex_expect(lx, ")");
    lex_expect(lx, ";");
}

static void parse_scad(const char *text, scad *s)
{
    memset(s, 0, sizeof *s);
    lexer lx = {text, {0, {0}}, {0}};
    lex_next(&lx);
    while (lx.cur.kind != T_END) {
        if (lex_is(&lx, "module")) {
            lex_next(&lx);
            module *m = &s->mod[s->nmod++];
            assert_int_equal(lx.cur.kind, T_ID);
            snprintf(m->name, sizeof m->name, "%s", lx.cur.text);
            lex_next(&lx);
            lex_expect(&lx, "(");
            lex_expect(&lx, ")");
            lex_expect(&lx, "{");
            while (!lex_is(&lx, "}")) parse_call(&lx, m, m->calls, &m->ncalls);
            lex_expect(&lx, "}");
        } else {
            parse_call(&lx, NULL, s->top, &s->ntop);
        }
    }
    memcpy(s->comments, lx.comments, sizeof s->comments);
}

static void free_scad(scad *s)
{
    for (size_t i = 0; i < s->nmod; i++) {
        free(s->mod[i].points);
        free(s->mod[i].faces);
    }
}

static char *write_scad(const coons_mesh *m, const coons_write_options *o)
{
    char dir[64], path[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/m.scad", dir);
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_write(m, path, COONS_FORMAT_AUTO, o, &e), &e);
    char *d = io_read_file(path, NULL);
    assert_non_null(d);
    io_rmdir(dir);
    return d;
}

/* Given parts with awkward coordinates, when written as SCAD and parsed,
 * then each part module's points are the part's vertices bit for bit and
 * its faces are the part's triangles reversed, (a, b, c) -> (a, c, b),
 * with part-local indices. */
static void test_points_exact_faces_reversed(void **state)
{
    (void)state;
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    const double lo[3] = {0.1, -0.0, 1e-300}, hi[3] = {9007199254740993.0, 1.0 / 3.0, 2.5e-320};
    io_box(m, "box", lo, hi);
    const double sh[3] = {-DBL_MIN, 0.30000000000000004, -1e22};
    io_torus(m, "ring", 3.0, 1.0, 12, 6, sh);
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.units = "mm";
    char *text = write_scad(m, &o);
    scad s;
    parse_scad(text, &s);
    assert_int_equal(s.nmod, 3);
    const double *xyz = coons_mesh_vertices(m);
    const uint32_t *tri = coons_mesh_triangles(m);
    for (size_t p = 0; p < 2; p++) {
        size_t tf, tc, vf, vc;
        coons_mesh_part_range(m, p, &tf, &tc, &vf, &vc);
        module *md = &s.mod[p];
        assert_int_equal(md->np, vc);
        assert_int_equal(md->nf, tc);
        for (size_t i = 0; i < 3 * vc; i++)
            if (memcmp(&md->points[i], &xyz[3 * vf + i], sizeof(double)) != 0)
                fail_msg("part %zu coordinate %zu: wrote %a, read %a", p, i, xyz[3 * vf + i],
                         md->points[i]);
        for (size_t t = 0; t < tc; t++) {
            const uint32_t *w = tri + 3 * (tf + t);
            assert_true(md->faces[3 * t] == (double)(w[0] - vf));
            assert_true(md->faces[3 * t + 1] == (double)(w[2] - vf));
            assert_true(md->faces[3 * t + 2] == (double)(w[1] - vf));
        }
    }
    assert_string_equal(s.mod[0].name, "coons_model_box");
    assert_string_equal(s.mod[1].name, "coons_model_ring");
    assert_string_equal(s.mod[2].name, "coons_model");
    assert_int_equal(s.mod[2].ncalls, 2);
    assert_string_equal(s.mod[2].calls[0], "coons_model_box");
    assert_string_equal(s.mod[2].calls[1], "coons_model_ring");
    assert_int_equal(s.ntop, 1);
    assert_string_equal(s.top[0], "coons_model");
    assert_non_null(strstr(s.comments, "units: mm"));
    free_scad(&s);
    free(text);
    coons_mesh_free(m);
}

static int is_identifier(const char *s)
{
    if (!(isalpha((unsigned char)*s) || *s == '_')) return 0;
    for (; *s; s++)
        if (!(isalnum((unsigned char)*s) || *s == '_')) return 0;
    return 1;
}

/* Given part names that are not identifiers, collide with OpenSCAD's
 * built-ins or keywords, repeat each other or are empty, and model names
 * that are not identifiers or are built-ins, when written, then the model
 * module is the model's name made an identifier, each part module is
 * MODEL_PART made an identifier (outputs.md: every module name carries the
 * model's name), every name is valid, unique (the model's first, then the
 * parts' in order, with _2, _3, ...), not reserved, and the model module
 * calls each part module in order. */
static void test_module_names(void **state)
{
    (void)state;
    static const char *const parts[] = {"hull", "2nd body", "cube", "", "box",
                                        "box", "for", "Fl\xc3\xbcgel", "box_2", "stl"};
    enum { N = sizeof parts / sizeof parts[0] };
    static const struct {
        const char *name, *model, *module[N];
    } cases[] = {
        {NULL, "coons_model",
         {"coons_model_hull", "coons_model_2nd_body", "coons_model_cube", "coons_model_",
          "coons_model_box", "coons_model_box_2", "coons_model_for", "coons_model_Fl__gel",
          "coons_model_box_2_2", "coons_model_stl"}},
        /* A built-in as the model: the model's module gets the '_' suffix
         * and the empty part's "union_" is then taken. */
        {"union", "union_",
         {"union_hull", "union_2nd_body", "union_cube", "union__2", "union_box", "union_box_2",
          "union_for", "union_Fl__gel", "union_box_2_2", "union_stl"}},
        /* MODEL_PART may itself be a built-in: import_stl. */
        {"import", "import_",
         {"import_hull", "import_2nd_body", "import_cube", "import__2", "import_box",
          "import_box_2", "import_for", "import_Fl__gel", "import_box_2_2", "import_stl_"}},
        {"2nd model.v2", "_2nd_model_v2",
         {"_2nd_model_v2_hull", "_2nd_model_v2_2nd_body", "_2nd_model_v2_cube", "_2nd_model_v2_",
          "_2nd_model_v2_box", "_2nd_model_v2_box_2", "_2nd_model_v2_for",
          "_2nd_model_v2_Fl__gel", "_2nd_model_v2_box_2_2", "_2nd_model_v2_stl"}},
    };
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    for (size_t i = 0; i < N; i++) io_tetra(m, parts[i], 1, 1, 1 + (double)i);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        coons_write_options o = COONS_WRITE_OPTIONS_INIT;
        o.name = cases[c].name;
        char *text = write_scad(m, &o);
        scad s;
        parse_scad(text, &s);
        assert_int_equal(s.nmod, N + 1);
        for (size_t i = 0; i < N; i++) {
            assert_string_equal(s.mod[i].name, cases[c].module[i]);
            assert_true(is_identifier(s.mod[i].name));
            assert_string_equal(s.mod[N].calls[i], cases[c].module[i]);
            for (size_t j = 0; j < i; j++) assert_string_not_equal(s.mod[i].name, s.mod[j].name);
        }
        assert_string_equal(s.mod[N].name, cases[c].model);
        assert_int_equal(s.ntop, 1);
        assert_string_equal(s.top[0], cases[c].model);
        free_scad(&s);
        free(text);
    }
    coons_mesh_free(m);
}

/* Given the same parts written under two model names, then no module name
 * of one file is a module name of the other: both can be `include`d. */
static void test_two_models_share_no_module(void **state)
{
    (void)state;
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    io_tetra(m, "union", 1, 1, 1);
    io_tetra(m, "", 1, 1, 2);
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.name = "spool";
    char *ta = write_scad(m, &o);
    o.name = "nail";
    char *tb = write_scad(m, &o);
    scad a, b;
    parse_scad(ta, &a);
    parse_scad(tb, &b);
    assert_int_equal(a.nmod, 3);
    assert_int_equal(b.nmod, 3);
    for (size_t i = 0; i < a.nmod; i++)
        for (size_t j = 0; j < b.nmod; j++) assert_string_not_equal(a.mod[i].name, b.mod[j].name);
    assert_string_equal(a.mod[0].name, "spool_union");
    assert_string_equal(b.mod[0].name, "nail_union");
    free_scad(&a);
    free_scad(&b);
    free(ta);
    free(tb);
    coons_mesh_free(m);
}

/* A part name with a newline cannot break out of its comment. */
static void test_comment_injection(void **state)
{
    (void)state;
    coons_mesh *m;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &e), &e);
    io_tetra(m, "evil\ncube(100);", 1, 1, 1);
    coons_write_options o = COONS_WRITE_OPTIONS_INIT;
    o.units = "mm\nsphere(5);";
    o.header = "hdr\rcylinder(1);";
    char *text = write_scad(m, &o);
    scad s;
    parse_scad(text, &s); /* a stray call would show up as a top-level call */
    assert_int_equal(s.ntop, 1);
    assert_int_equal(s.nmod, 2);
    assert_int_equal(s.mod[1].ncalls, 1);
    free_scad(&s);
    free(text);
    coons_mesh_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_points_exact_faces_reversed),
        cmocka_unit_test(test_module_names),
        cmocka_unit_test(test_comment_injection),
        cmocka_unit_test(test_two_models_share_no_module),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
