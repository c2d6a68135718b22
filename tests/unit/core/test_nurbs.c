/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The B-spline / NURBS form of coons/nurbs.h:
 * - every body of every example: its 6 faces and (where polynomial) the
 *   whole body against coons_body_eval() at 200 random parameters, within
 *   1e-11 of the body's size when exact, the fit tolerance when fitted;
 *   which bodies are exact is decided here from the body types, not taken
 *   from the library;
 * - closed forms: a Bezier curve is one span of its degree with the same
 *   points; the Coons cubic of seed 002 is the uniform cubic B-spline, in
 *   clamped form the points of the seed's open-to-clamped formulas; a
 *   bilinear patch is degree (1,1) with its corners as the net;
 * - rational data is copied: a NURBS quarter circle (also reversed and
 *   moved) and a reparametrised NURBS patch keep their weights;
 * - a space too small (degree 1 for a cubic, a polyline without its
 *   breakpoints) shows a large deviation: the measurement can fail;
 * - a shell face and a Coons patch with a rational side are fitted
 *   (exact 0) within the tolerance, confirmed at other points;
 * - a collapsed face (the nail's tip) is exact, its net one point;
 * - bad arguments, allocation failures.
 */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "nurbs_impl.h"
#include "patch_fixture.h"
#include "test_util.h"

/* A fixed pseudo-random sequence in [0,1). */
static double rnd(unsigned long *s)
{
    *s = *s * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(*s >> 11) / 9007199254740992.0;
}

static double body_size(const coons_body *b)
{
    double lo[3], hi[3];
    coons_body_control_bbox(b, lo, hi);
    double d[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

static double dist(const double a[3], const double b[3])
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* The largest distance between face f of b (f < 0: the body) and its form
 * at n random parameters. */
static double face_error(const coons_body *b, int f, const coons_nurbs *N, int n,
                         unsigned long seed)
{
    double worst = 0.0;
    for (int i = 0; i < n; i++) {
        double q[3] = {rnd(&seed), rnd(&seed), rnd(&seed)}, u[3], x[3], y[3];
        if (f < 0) {
            memcpy(u, q, sizeof u);
        } else {
            int d = f / 2, m = 0;
            for (int e = 0; e < 3; e++) u[e] = e == d ? (double)(f % 2) : q[m++];
        }
        coons_body_eval(b, u[0], u[1], u[2], x);
        coons_nurbs_eval(N, q, y);
        double e = dist(x, y);
        if (!(e <= worst)) worst = isnan(e) ? INFINITY : e;
    }
    return worst;
}

/* Independent of the library: which bodies have exact forms. Rational
 * data in a Boolean sum or blend is never exact, shells never; a body
 * "rational" holds weights (the model text says so per body). */
static int body_exact(const coons_body *b, int rational)
{
    coons_body_type t = coons_body_kind(b);
    if (t == COONS_BODY_SHELL) return 0;
    if (t == COONS_BODY_MORPH) {
        for (size_t k = 0; k < coons_body_morph_keys(b); k++)
            if (!body_exact(coons_body_morph_key(b, k, NULL), rational)) return 0;
        return !rational;
    }
    if (t == COONS_BODY_BSPLINE || t == COONS_BODY_BEZIER) return 1;
    return !rational;
}

static int g_verbose;

static void check_model(const char *name, double *worst_exact, int *bodies, int *faces)
{
    char rel[512];
    snprintf(rel, sizeof rel, "examples/%s", name);
    coons_model *m = test_source_model(rel);
    /* Whether the file has weights at all: where it has none, every
     * non-shell body must be exact. */
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", COONS_SOURCE_DIR, rel);
    FILE *fp = fopen(path, "rb");
    assert_non_null(fp);
    char *text = calloc(1, 1 << 22);
    assert_non_null(text);
    size_t len = fread(text, 1, (1 << 22) - 1, fp);
    fclose(fp);
    text[len] = 0;
    int file_rational = strstr(text, "\"weights\"") != NULL;
    free(text);
    for (size_t i = 0; i < coons_model_body_count(m); i++) {
        const coons_body *b = coons_model_body(m, i);
        double size = body_size(b), tol = 1e-6 * size;
        int all_exact = 1;
        for (int f = 0; f < 6; f++) {
            coons_nurbs N = {0};
            coons_error err = COONS_ERROR_INIT;
            assert_coons_ok(coons_body_face_to_nurbs(b, f, tol, &N, &err), &err);
            assert_int_equal(N.dim, 2);
            double e = face_error(b, f, &N, 200, 7 + (unsigned long)f);
            if (g_verbose)
                printf("%s body %zu face %d: exact %d deg %d,%d count %zu,%zu dev %.3g rand %.3g "
                       "(size %.3g)\n",
                       name, i, f, N.exact, N.degree[0], N.degree[1], N.count[0], N.count[1],
                       N.deviation, e, size);
            if (!file_rational && coons_body_kind(b) != COONS_BODY_SHELL)
                assert_int_equal(N.exact, 1);
            if (coons_body_kind(b) == COONS_BODY_SHELL) assert_int_equal(N.exact, 0);
            if (N.exact) {
                if (!(e <= 1e-11 * size) || !(N.deviation <= 1e-11 * size))
                    fail_msg("%s body %zu face %d: exact form off by %g (measured %g), size %g",
                             name, i, f, e, N.deviation, size);
                if (e / size > *worst_exact) *worst_exact = e / size;
                if (N.deviation / size > *worst_exact) *worst_exact = N.deviation / size;
            } else {
                all_exact = 0;
                assert_true(N.deviation <= tol);
                if (!(e <= 4.0 * tol))
                    fail_msg("%s body %zu face %d: fit off by %g at random points, tol %g", name,
                             i, f, e, tol);
            }
            coons_nurbs_free(&N);
            (*faces)++;
        }
        if (body_exact(b, file_rational)) assert_true(all_exact);
        coons_nurbs N = {0};
        coons_error err = COONS_ERROR_INIT;
        coons_status rc = coons_body_to_nurbs(b, tol, &N, &err);
        if (rc == COONS_E_LIMIT && !body_exact(b, file_rational)) {
            /* a fit too large for the cap: said so, nothing returned */
            assert_true(strlen(err.message) > 0);
            assert_null(N.points);
            continue;
        }
        assert_coons_ok(rc, &err);
        assert_int_equal(N.dim, 3);
        double e = face_error(b, -1, &N, 200, 99);
        if (g_verbose)
            printf("%s body %zu: exact %d deg %d,%d,%d count %zu,%zu,%zu dev %.3g rand %.3g\n",
                   name, i, N.exact, N.degree[0], N.degree[1], N.degree[2], N.count[0],
                   N.count[1], N.count[2], N.deviation, e);
        if (body_exact(b, file_rational)) assert_int_equal(N.exact, 1);
        if (N.exact) {
            if (!(e <= 1e-11 * size))
                fail_msg("%s body %zu: exact body form off by %g, size %g", name, i, e, size);
            if (e / size > *worst_exact) *worst_exact = e / size;
        } else {
            assert_true(N.deviation <= tol);
            if (!(e <= 4.0 * tol))
                fail_msg("%s body %zu: body fit off by %g at random points, tol %g", name, i, e,
                         tol);
        }
        coons_nurbs_free(&N);
        (*bodies)++;
    }
    coons_model_free(m);
}

/* Under valgrind or a sanitizer (COONS_TEST_REPRESENTATIVE set, as
 * tools/memcheck.sh does) the examples are the representative subset of
 * tests/data/representative-examples.txt, and the size cap (two million
 * points) is not run into. */
static int subset(void)
{
    const char *e = getenv("COONS_TEST_REPRESENTATIVE");
    return e && *e;
}

static int representative(const char *name)
{
    FILE *f = fopen(COONS_SOURCE_DIR "/tests/data/representative-examples.txt", "r");
    if (!f) fail_msg("cannot read tests/data/representative-examples.txt");
    char line[256];
    int found = 0;
    while (!found && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = '\0';
        found = line[0] != '#' && line[0] != '\0' && strcmp(line, name) == 0;
    }
    fclose(f);
    return found;
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static void test_examples(void **state)
{
    (void)state;
    g_verbose = getenv("COONS_NURBS_VERBOSE") != NULL;
    if (g_verbose) setvbuf(stdout, NULL, _IONBF, 0);
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/examples", COONS_SOURCE_DIR);
    DIR *d = opendir(dir);
    assert_non_null(d);
    char *names[256];
    size_t n = 0;
    struct dirent *e;
    while ((e = readdir(d)) && n < 256) {
        size_t l = strlen(e->d_name);
        if (l > 5 && strcmp(e->d_name + l - 5, ".json") == 0 &&
            (!subset() || representative(e->d_name))) {
            names[n] = malloc(l + 1);
            assert_non_null(names[n]);
            memcpy(names[n++], e->d_name, l + 1);
        }
    }
    closedir(d);
    qsort(names, n, sizeof *names, cmp_str);
    assert_true(n >= (subset() ? 10 : 40));
    double worst = 0.0;
    int bodies = 0, faces = 0;
    for (size_t i = 0; i < n; i++) {
        check_model(names[i], &worst, &bodies, &faces);
        free(names[i]);
    }
    printf("examples: %zu files, %d faces, %d bodies; largest exact deviation %.3g of the size\n",
           n, faces, bodies, worst);
}

static void test_bezier_curve(void **state)
{
    (void)state;
    const double P[5][3] = {{0, 0, 0}, {1, 2, 0}, {2, -1, 1}, {3, 3, 2}, {4, 0, 0}};
    coons_curve *c = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_bezier(P[0], 5, &c, &err), &err);
    coons_nurbs N = {0};
    assert_coons_ok(coons_curve_to_nurbs(c, 0.0, &N, &err), &err);
    assert_int_equal(N.dim, 1);
    assert_int_equal(N.exact, 1);
    assert_int_equal(N.degree[0], 4);
    assert_int_equal(N.count[0], 5);
    assert_null(N.weights);
    for (int i = 0; i < 10; i++) assert_near(N.knots[0][i], i < 5 ? 0.0 : 1.0, 0.0);
    for (int i = 0; i < 5; i++) assert_vec3_near(N.points + 3 * i, P[i], 1e-14);
    assert_true(N.deviation < 1e-14);
    coons_nurbs_free(&N);
    assert_null(N.points);
    /* the form copies the net; the collocation itself (the test hook, in
     * the curve's own space) gives the same points */
    assert_coons_ok(coons__nurbs_in_space(c, NULL, NULL, 4, 0, &N, &err), &err);
    assert_int_equal(N.count[0], 5);
    for (int i = 0; i < 5; i++) assert_vec3_near(N.points + 3 * i, P[i], 1e-14);
    coons_nurbs_free(&N);
    coons_curve_free(c);
}

/* Seed 002: the open Coons cubic of P0..P6 is the uniform cubic B-spline
 * of those points; over [0,1] with clamped ends its control points are the
 * seed's clamped points: P0..P6 with the two first and two last replaced by
 * (P0 + 4P1 + P2)/6, (2P1 + P2)/3 and (P4 + 2P5)/3, (P4 + 4P5 + P6)/6
 * (computed here, not by the library), knots 0^4 1/4 1/2 3/4 1^4. */
static void test_coons_cubic(void **state)
{
    (void)state;
    const double P[7][3] = {{0, 0, 0}, {1, 2, 0}, {2, 2, 1}, {3, 0, 2},
                            {4, -1, 1}, {5, 1, 0}, {6, 3, -1}};
    coons_curve *c = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_coons_cubic(P[0], 7, 0, &c, &err), &err);
    coons_nurbs N = {0};
    assert_coons_ok(coons_curve_to_nurbs(c, 1e-9, &N, &err), &err);
    assert_int_equal(N.exact, 1);
    assert_int_equal(N.degree[0], 3);
    assert_int_equal(N.count[0], 7);
    const double K[11] = {0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1};
    for (int i = 0; i < 11; i++) assert_near(N.knots[0][i], K[i], 1e-15);
    double Q[7][3];
    memcpy(Q, P, sizeof Q);
    for (int k = 0; k < 3; k++) {
        Q[0][k] = (P[0][k] + 4 * P[1][k] + P[2][k]) / 6;
        Q[1][k] = (2 * P[1][k] + P[2][k]) / 3;
        Q[5][k] = (P[4][k] + 2 * P[5][k]) / 3;
        Q[6][k] = (P[4][k] + 4 * P[5][k] + P[6][k]) / 6;
    }
    for (int i = 0; i < 7; i++) assert_vec3_near(N.points + 3 * i, Q[i], 1e-13);
    assert_true(N.deviation < 1e-14);
    coons_nurbs_free(&N);
    coons_curve_free(c);
}

static void test_bilinear(void **state)
{
    (void)state;
    const double X[4][3] = {{0, 0, 0}, {2, 0, 1}, {0, 3, -1}, {2, 3, 4}}; /* X00 X10 X01 X11 */
    coons_patch *p = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_patch_new_bilinear(X[0], &p, &err), &err);
    coons_nurbs N = {0};
    assert_coons_ok(coons_patch_to_nurbs(p, 0.0, &N, &err), &err);
    assert_int_equal(N.exact, 1);
    assert_int_equal(N.degree[0], 1);
    assert_int_equal(N.degree[1], 1);
    assert_int_equal(N.count[0], 2);
    assert_int_equal(N.count[1], 2);
    /* net (i,j) at i*2 + j, i along s: X_ij is corner i + 2j */
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) assert_vec3_near(N.points + 3 * (i * 2 + j), X[i + 2 * j], 1e-15);
    coons_nurbs_free(&N);
    coons_patch_free(p);
}

/* Quarter circle of radius 2: degree 2, weights 1, 1/sqrt2, 1. */
static coons_curve *quarter_circle(void)
{
    const double P[3][3] = {{2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, w[3] = {1, sqrt(0.5), 1};
    coons_curve *c = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_curve_new_bspline(2, P[0], 3, NULL, w, &c, &err), &err);
    return c;
}

static void check_curve_form(const coons_curve *c, const coons_nurbs *N, double eps)
{
    unsigned long s = 5;
    for (int i = 0; i < 300; i++) {
        double t = rnd(&s), x[3], y[3];
        coons_curve_eval(c, t, x);
        coons_nurbs_eval(N, &t, y);
        assert_vec3_near(x, y, eps);
    }
}

static void test_rational_copy(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_curve *c = quarter_circle(), *r = NULL, *m = NULL;
    const double M[12] = {0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 2, 3}; /* rows of [A | t] */
    assert_coons_ok(coons_curve_new_reversed(c, &r, &err), &err);
    assert_coons_ok(coons_curve_new_transformed(r, M, &m, &err), &err);
    const coons_curve *all[3] = {c, r, m};
    for (int k = 0; k < 3; k++) {
        coons_nurbs N = {0};
        assert_coons_ok(coons_curve_to_nurbs(all[k], 1e-9, &N, &err), &err);
        assert_int_equal(N.exact, 1);
        assert_int_equal(N.degree[0], 2);
        assert_int_equal(N.count[0], 3);
        assert_non_null(N.weights);
        assert_near(N.weights[1] / N.weights[0], sqrt(0.5), 1e-15);
        check_curve_form(all[k], &N, 1e-14);
        /* on the circle: |x| = 2 for the plain one */
        if (k == 0) {
            double t = 0.3, y[3];
            coons_nurbs_eval(&N, &t, y);
            assert_near(sqrt(y[0] * y[0] + y[1] * y[1]), 2.0, 1e-14);
        }
        coons_nurbs_free(&N);
    }
    /* a NURBS patch (quarter cylinder), swapped and flipped */
    const double w = sqrt(0.5);
    const double pts[3][2][3] = {{{2, 0, 0}, {2, 0, 3}}, {{2, 2, 0}, {2, 2, 3}},
                                 {{0, 2, 0}, {0, 2, 3}}};
    const double wt[6] = {1, 1, w, w, 1, 1};
    coons_patch *p = NULL, *q = NULL;
    assert_coons_ok(coons_patch_new_bspline(2, 1, pts[0][0], 3, 2, NULL, NULL, wt, &p, &err), &err);
    assert_coons_ok(coons_patch_new_reparametrized(p, 1, 1, 0, &q, &err), &err);
    const coons_patch *ps[2] = {p, q};
    for (int k = 0; k < 2; k++) {
        coons_nurbs N = {0};
        assert_coons_ok(coons_patch_to_nurbs(ps[k], 1e-9, &N, &err), &err);
        assert_int_equal(N.exact, 1);
        assert_non_null(N.weights);
        assert_int_equal(N.degree[k], 2); /* swapped: the arc runs along t */
        unsigned long s = 11;
        for (int i = 0; i < 300; i++) {
            double st[2] = {rnd(&s), rnd(&s)}, x[3], y[3];
            coons_patch_eval(ps[k], st[0], st[1], x);
            coons_nurbs_eval(&N, st, y);
            assert_vec3_near(x, y, 1e-14);
        }
        coons_nurbs_free(&N);
    }
    coons_patch_free(p);
    coons_patch_free(q);
    coons_curve_free(c);
    coons_curve_free(r);
    coons_curve_free(m);
}

/* The check can fail: a cubic in a degree-1 space, a polyline without
 * its breakpoints; the right spaces (degree 3, with breakpoints) agree. */
static void test_too_small_space(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    const double P[4][3] = {{0, 0, 0}, {1, 2, 0}, {2, -1, 1}, {3, 0, 0}};
    coons_curve *c = NULL, *pl = NULL;
    assert_coons_ok(coons_curve_new_bezier(P[0], 4, &c, &err), &err);
    coons_nurbs N = {0};
    assert_coons_ok(coons__nurbs_in_space(c, NULL, NULL, 1, 0, &N, &err), &err);
    printf("cubic in degree 1: deviation %.3g\n", N.deviation);
    assert_true(N.deviation > 1e-6);
    coons_nurbs_free(&N);
    assert_coons_ok(coons__nurbs_in_space(c, NULL, NULL, 3, 0, &N, &err), &err);
    assert_true(N.deviation < 1e-14);
    coons_nurbs_free(&N);
    const double Q[4][3] = {{0, 0, 0}, {1, 1, 0}, {2, 0, 0}, {3, 1, 1}};
    assert_coons_ok(coons_curve_new_polyline(Q[0], 4, &pl, &err), &err);
    assert_coons_ok(coons__nurbs_in_space(pl, NULL, NULL, 1, 1, &N, &err), &err);
    printf("polyline without breakpoints: deviation %.3g\n", N.deviation);
    assert_true(N.deviation > 1e-6);
    coons_nurbs_free(&N);
    assert_coons_ok(coons__nurbs_in_space(pl, NULL, NULL, 1, 0, &N, &err), &err);
    assert_true(N.deviation < 1e-15);
    coons_nurbs_free(&N);
    /* a body 1 of cubic B-spline edges in degree 1; in degree 3 it fits */
    coons_model *m = test_source_model("examples/body1-bspline-edges.json");
    const coons_body *b = coons_model_body(m, 0);
    assert_coons_ok(coons__nurbs_in_space(NULL, NULL, b, 1, 0, &N, &err), &err);
    printf("body 1 in degree 1: deviation %.3g\n", N.deviation);
    assert_true(N.deviation > 1e-6);
    coons_nurbs_free(&N);
    assert_coons_ok(coons__nurbs_in_space(NULL, NULL, b, 3, 0, &N, &err), &err);
    assert_true(N.deviation < 1e-12);
    coons_nurbs_free(&N);
    coons_model_free(m);
    coons_curve_free(c);
    coons_curve_free(pl);
}

/* Independent check of a fit at points other than the library's. */
static void check_patch_fit(const coons_patch *p, const coons_nurbs *N, double tol)
{
    unsigned long s = 3;
    double worst = 0.0;
    for (int i = 0; i < 2000; i++) {
        double st[2] = {rnd(&s), rnd(&s)}, x[3], y[3];
        coons_patch_eval(p, st[0], st[1], x);
        coons_nurbs_eval(N, st, y);
        double e = dist(x, y);
        if (e > worst) worst = e;
    }
    printf("fit: deviation %.3g measured, %.3g at 2000 other points, tol %.3g, %zu x %zu\n",
           N->deviation, worst, tol, N->count[0], N->count[1]);
    assert_true(worst <= 2.0 * tol);
}

static void test_fits(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    fx_boundary B;
    fx_boundary_make(&B);
    coons_patch *p = NULL;
    assert_coons_ok(coons_patch_new_coons(B.c, COONS_BLEND_LINEAR, 0.0, &p, &err), &err);
    /* the fixture's side t1 is rational: the Coons patch is fitted */
    coons_nurbs N = {0};
    double tol = 1e-6;
    assert_coons_ok(coons_patch_to_nurbs(p, tol, &N, &err), &err);
    assert_int_equal(N.exact, 0);
    assert_true(N.deviation <= tol);
    assert_null(N.weights);
    check_patch_fit(p, &N, tol);
    coons_nurbs_free(&N);
    /* tol <= 0 or NaN where a fit is needed */
    assert_int_equal(coons_patch_to_nurbs(p, 0.0, &N, &err), COONS_E_INVALID);
    assert_true(strstr(err.message, "tolerance") != NULL);
    assert_int_equal(coons_patch_to_nurbs(p, NAN, &N, &err), COONS_E_INVALID);
    assert_null(N.points);

    coons_body *sh = NULL;
    assert_coons_ok(coons_body_new_shell(p, 0.2, COONS_SHELL_BOTH, &sh, &err), &err);
    for (int f = 0; f < 6; f++) {
        assert_coons_ok(coons_body_face_to_nurbs(sh, f, tol, &N, &err), &err);
        assert_int_equal(N.exact, 0);
        assert_true(N.deviation <= tol);
        double e = face_error(sh, f, &N, 2000, 17);
        printf("shell face %d: deviation %.3g, %.3g at 2000 other points, %zu x %zu\n", f,
               N.deviation, e, N.count[0], N.count[1]);
        assert_true(e <= 2.0 * tol);
        if (f >= 4) assert_int_equal(N.degree[0], 3);
        else assert_int_equal(N.degree[1], 1); /* linear through the thickness */
        coons_nurbs_free(&N);
    }
    assert_coons_ok(coons_body_to_nurbs(sh, 1e-4, &N, &err), &err);
    assert_int_equal(N.exact, 0);
    assert_int_equal(N.degree[2], 1);
    assert_true(face_error(sh, -1, &N, 500, 3) <= 2e-4);
    coons_nurbs_free(&N);
    coons_body_free(sh);
    coons_patch_free(p);
    fx_boundary_free(&B);
    /* a tolerance out of reach: the size cap, said so, nothing returned */
    if (subset()) return;
    coons_model *m = test_source_model("examples/hood-shell.json");
    assert_int_equal(coons_body_face_to_nurbs(coons_model_body(m, 0), COONS_FACE_W0, 1e-13, &N,
                                              &err),
                     COONS_E_LIMIT);
    printf("out of reach: %s\n", err.message);
    assert_true(strstr(err.message, "deviation") != NULL);
    assert_null(N.points);
    assert_int_equal(N.dim, 0);
    coons_model_free(m);
}

static void test_bad_args(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_nurbs N = {0};
    const double c8[24] = {0, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 1, 0, 0, 1, 0, 1, 1, 1, 0, 1, 1, 1};
    coons_body *b = NULL;
    assert_coons_ok(coons_body_new_body0(c8, COONS_BLEND_LINEAR, &b, &err), &err);
    assert_int_equal(coons_curve_to_nurbs(NULL, 1e-6, &N, &err), COONS_E_INVALID);
    assert_true(strlen(err.message) > 0);
    assert_int_equal(coons_patch_to_nurbs(NULL, 1e-6, &N, &err), COONS_E_INVALID);
    assert_int_equal(coons_body_to_nurbs(NULL, 1e-6, &N, &err), COONS_E_INVALID);
    assert_int_equal(coons_body_to_nurbs(b, 1e-6, NULL, &err), COONS_E_INVALID);
    assert_int_equal(coons_body_face_to_nurbs(b, 6, 1e-6, &N, &err), COONS_E_INVALID);
    assert_true(strstr(err.message, "face 6") != NULL);
    assert_int_equal(coons_body_face_to_nurbs(b, -1, 1e-6, &N, NULL), COONS_E_INVALID);
    assert_int_equal(N.dim, 0);
    /* an exact form needs no tolerance */
    assert_coons_ok(coons_body_to_nurbs(b, 0.0, &N, &err), &err);
    assert_int_equal(N.exact, 1);
    double q[3] = {0.3, 0.6, 0.9}, x[3], y[3];
    coons_nurbs_eval(&N, q, x);
    coons_body_eval(b, q[0], q[1], q[2], y);
    assert_vec3_near(x, y, 1e-15);
    coons_nurbs_free(&N);
    coons_nurbs_free(&N);
    coons_nurbs_free(NULL);
    coons_nurbs_eval(NULL, q, x);
    assert_true(isnan(x[0]));
    coons_nurbs_eval(&N, q, x);
    assert_true(isnan(x[0]));
    coons_body_free(b);
}

/* The nail: a body 2 of NURBS faces whose w0 face collapses to its tip.
 * Every face is exact (the face patches' nets), the collapsed one a net
 * of coincident points at the tip. */
static void test_collapsed_face(void **state)
{
    (void)state;
    coons_model *m = test_source_model("examples/nail.json");
    const coons_body *b = coons_model_body(m, 0);
    const double tip[3] = {0, 0, 12};
    for (int f = 0; f < 6; f++) {
        coons_nurbs N = {0};
        coons_error err = COONS_ERROR_INIT;
        assert_coons_ok(coons_body_face_to_nurbs(b, f, 1e-9, &N, &err), &err);
        assert_int_equal(N.exact, 1);
        assert_non_null(N.weights);
        assert_true(face_error(b, f, &N, 500, 1) < 1e-12);
        if (f == COONS_FACE_W0)
            for (size_t i = 0; i < N.count[0] * N.count[1]; i++)
                assert_vec3_near(N.points + 3 * i, tip, 0.0);
        coons_nurbs_free(&N);
    }
    coons_model_free(m);
}

/* Every allocation failing in turn: the interpolation (body 0), the copy
 * and section of a NURBS volume, the fit of a shell face. */
static void test_alloc_failures(void **state)
{
    (void)state;
    const char *files[3] = {"examples/deformed-cube.json", "examples/volume-nurbs.json",
                            "examples/hood-shell.json"};
    for (int fi = 0; fi < 3; fi++) {
        char rel[256];
        snprintf(rel, sizeof rel, "%s", files[fi]);
        coons_model *m = test_source_model(rel);
        const coons_body *b = coons_model_body(m, 0);
        for (int which = 0; which < 2; which++) {
            long n = 0;
            for (; n < 100000; n++) {
                coons_error err = COONS_ERROR_INIT;
                coons_nurbs N = {0};
                coons_test_fail_after(n);
                coons_status rc = which ? coons_body_to_nurbs(b, 1e-3, &N, &err)
                                        : coons_body_face_to_nurbs(b, COONS_FACE_V1, 1e-3, &N,
                                                                   &err);
                if (rc == COONS_OK) coons_nurbs_free(&N);
                long live = coons_test_live_allocs();
                coons_test_fail_after(-1);
                assert_int_equal(live, 0);
                if (rc == COONS_OK) break;
                if (rc != COONS_E_NOMEM)
                    fail_msg("%s: allocation %ld failing gave %d: %s", rel, n, rc, err.message);
                assert_null(N.points);
            }
            assert_true(n > 3 && n < 100000);
        }
        coons_model_free(m);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bezier_curve),   cmocka_unit_test(test_coons_cubic),
        cmocka_unit_test(test_bilinear),       cmocka_unit_test(test_rational_copy),
        cmocka_unit_test(test_too_small_space), cmocka_unit_test(test_fits),
        cmocka_unit_test(test_bad_args),       cmocka_unit_test(test_alloc_failures),
        cmocka_unit_test(test_collapsed_face),
        cmocka_unit_test(test_examples),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
