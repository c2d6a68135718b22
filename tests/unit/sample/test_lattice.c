/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The boundary of a control lattice (seed 000 §3; coons-model(5) "Bodies
 * that share faces"): bodies of a union joined by shared faces come out as
 * one closed, 2-manifold, outward part, joined by index, with the shared
 * faces left out, in a build without any C++ or CGAL. Checked against
 * closed forms: volumes of boxes, of a lattice whose inner points moved
 * (its outer boundary is the box's), of an octagonal ring of 8 cells (a
 * torus: Euler characteristic 0); the second box in each of the 48
 * parametrisations of a cube (the shared face in all 8 orientations of the
 * square, right- and left-handed); bodies that meet along an edge only
 * through a third; a neighbour that needs a finer lattice (the shared
 * lattice refines the other body, the shell stays closed and every body
 * within the tolerance, measured at exact points independently of the
 * sampler); the triangle budget; operation "none" keeps the bodies apart. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"

static coons_model *load(const char *json)
{
    coons_model *m = NULL;
    coons_error e = COONS_ERROR_INIT;
    assert_coons_ok(coons_model_load_memory(json, strlen(json), "t.json", NULL, &m, &e), &e);
    return m;
}

/* A growing JSON text. */
typedef struct text {
    char *s;
    size_t n, cap;
    int bodies;
} text;

static void put(text *t, const char *fmt, ...)
{
    va_list ap;
    for (;;) {
        va_start(ap, fmt);
        int k = vsnprintf(t->s + t->n, t->cap - t->n, fmt, ap);
        va_end(ap);
        assert_true(k >= 0);
        if ((size_t)k < t->cap - t->n) {
            t->n += (size_t)k;
            return;
        }
        t->cap = 2 * t->cap + (size_t)k + 64;
        t->s = realloc(t->s, t->cap);
        assert_non_null(t->s);
    }
}

/* A body0 of corners x[4i + 2j + k] (coons-model(5): P_ijk). */
static void body0(text *t, const char *name, double x[8][3])
{
    put(t, "%s{\"type\": \"body0\", \"name\": \"%s\", \"corners\": [", t->bodies++ ? "," : "", name);
    for (int c = 0; c < 8; c++)
        put(t, "%s[%.17g,%.17g,%.17g]", c ? "," : "", x[c][0], x[c][1], x[c][2]);
    put(t, "]}");
}

static void begin(text *t, const char *op, double tol)
{
    memset(t, 0, sizeof *t);
    put(t, "{\"coons\": 1, \"tolerance\": %.17g, \"operation\": \"%s\", \"bodies\": [", tol, op);
}

static coons_model *end(text *t)
{
    put(t, "]}");
    coons_model *m = load(t->s);
    free(t->s);
    return m;
}

/* Samples the model and checks the shell: closed, 2-manifold, outward,
 * the given number of parts and Euler characteristic. */
static coons_mesh *sample(const coons_model *model, size_t parts, long euler)
{
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_model_sample(model, NULL, &m, &err), &err);
    assert_int_equal(coons_mesh_part_count(m), parts);
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    assert_coons_ok(coons_mesh_check(m, &r, &err), &err);
    assert_true(r.closed);
    assert_true(r.manifold);
    assert_true(r.oriented);
    assert_int_equal(r.unused_vertices, 0);
    assert_int_equal(r.euler, euler);
    assert_true(coons_mesh_volume(m) > 0);
    return m;
}

/* The box [x0, x0 + 1] x [y0, y0 + 1] x [0, 1] with corner c at parameters
 * p = (c >> 2 & 1, c >> 1 & 1, c & 1) mapped by the signed permutation
 * (perm, flips) of the unit cube's parameters. */
static void box_corners(double x0, double y0, int perm, int flips, double x[8][3])
{
    static const int P[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int c = 0; c < 8; c++) {
        double p[3] = {c >> 2 & 1, c >> 1 & 1, c & 1}, q[3];
        for (int d = 0; d < 3; d++) {
            q[d] = p[P[perm][d]];
            if (flips >> d & 1) q[d] = 1 - q[d];
        }
        x[c][0] = x0 + q[0];
        x[c][1] = y0 + q[1];
        x[c][2] = q[2];
    }
}

/* A cube and its neighbour in each of the 48 parametrisations: one part,
 * volume 2, the shared face (all 8 orientations of the square occur, and
 * left-handed neighbours) left out: its triangles would make a closed
 * shell's edges non-manifold. */
static void test_two_boxes_every_parametrisation(void **state)
{
    (void)state;
    for (int perm = 0; perm < 6; perm++)
        for (int flips = 0; flips < 8; flips++) {
            text t;
            double a[8][3], b[8][3];
            begin(&t, "union", 0.01);
            box_corners(0, 0, 0, 0, a);
            box_corners(1, 0, perm, flips, b);
            body0(&t, "a", a);
            body0(&t, "b", b);
            coons_model *model = end(&t);
            coons_mesh *m = sample(model, 1, 2);
            assert_string_equal(coons_mesh_part_name(m, 0), "a+b");
            assert_near(coons_mesh_volume(m), 2, 2e-12);
            assert_near(coons_mesh_area(m), 10, 1e-11);
            /* No vertex inside the shared square x = 1, 0 < y, z < 1. */
            const double *x = coons_mesh_vertices(m);
            for (size_t v = 0; v < coons_mesh_vertex_count(m); v++) {
                const double *p = x + 3 * v;
                int inner = fabs(p[0] - 1) < 1e-12 && p[1] > 1e-9 && p[1] < 1 - 1e-9 &&
                            p[2] > 1e-9 && p[2] < 1 - 1e-9;
                assert_false(inner);
            }
            coons_mesh_free(m);
            coons_model_free(model);
        }
}

/* An n x n x n lattice of unit cells whose inner points moved: the outer
 * boundary is the box's, so the volume is exactly n^3, and every vertex
 * lies on the box's boundary. */
static void test_lattice_with_moved_inner_points(void **state)
{
    (void)state;
    enum { N = 3 };
    double P[N + 1][N + 1][N + 1][3];
    unsigned seed = 7;
    for (int i = 0; i <= N; i++)
        for (int j = 0; j <= N; j++)
            for (int k = 0; k <= N; k++) {
                double *p = P[i][j][k];
                p[0] = i, p[1] = j, p[2] = k;
                if (i > 0 && i < N && j > 0 && j < N && k > 0 && k < N)
                    for (int d = 0; d < 3; d++) {
                        seed = seed * 1103515245u + 12345u;
                        p[d] += 0.3 * ((double)(seed >> 8 & 0xffff) / 65535.0 - 0.5);
                    }
            }
    text t;
    begin(&t, "union", 0.01);
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++)
            for (int k = 0; k < N; k++) {
                double x[8][3];
                for (int c = 0; c < 8; c++)
                    memcpy(x[c], P[i + (c >> 2 & 1)][j + (c >> 1 & 1)][k + (c & 1)], sizeof x[c]);
                char name[32];
                snprintf(name, sizeof name, "c%d%d%d", i, j, k);
                body0(&t, name, x);
            }
    coons_model *model = end(&t);
    coons_mesh *m = sample(model, 1, 2);
    assert_near(coons_mesh_volume(m), N * N * N, 1e-12 * N * N * N);
    const double *x = coons_mesh_vertices(m);
    for (size_t v = 0; v < coons_mesh_vertex_count(m); v++) {
        int on = 0;
        for (int d = 0; d < 3; d++) on |= fabs(x[3 * v + d]) < 1e-12 || fabs(x[3 * v + d] - N) < 1e-12;
        assert_true(on);
    }
    /* The lattice has the box's own triangles only: a flat face of a unit
     * cell is one cell of its lattice or more, never fewer than 2 triangles
     * per cell face on the boundary, 6 N^2 of them. */
    assert_true(coons_mesh_triangle_count(m) >= 2 * 6 * N * N);
    coons_mesh_free(m);
    coons_model_free(model);
}

/* Eight cells around the z axis between regular octagons of circumradius
 * r and R, height h: a closed loop of cells, whose first and last share a
 * face; the shell is a torus (Euler characteristic 0) of volume
 * h (2 sqrt 2) (R^2 - r^2). */
static void test_ring_of_eight(void **state)
{
    (void)state;
    const double r = 2, R = 5, h = 1.5, pi = 3.14159265358979323846;
    text t;
    begin(&t, "union", 0.01);
    for (int k = 0; k < 8; k++) {
        double x[8][3];
        for (int c = 0; c < 8; c++) {
            double rad = c >> 2 & 1 ? R : r, ang = 2 * pi * (k + (c >> 1 & 1)) / 8;
            if (k + (c >> 1 & 1) == 8) ang = 0; /* the same corners as cell 0's */
            x[c][0] = rad * cos(ang);
            x[c][1] = rad * sin(ang);
            x[c][2] = (c & 1) * h;
        }
        char name[16];
        snprintf(name, sizeof name, "s%d", k);
        body0(&t, name, x);
    }
    coons_model *model = end(&t);
    coons_mesh *m = sample(model, 1, 0);
    assert_near(coons_mesh_volume(m), h * 2 * sqrt(2.0) * (R * R - r * r), 1e-11);
    coons_mesh_free(m);
    coons_model_free(model);
}

/* An L of three cubes (b and c meet a only) and a 2 x 2 square of four:
 * the edge where b's and c's boundary faces meet is reached through a's
 * lattice, whose faces there are both shared. */
static void test_bodies_meeting_through_a_third(void **state)
{
    (void)state;
    for (int four = 0; four < 2; four++) {
        text t;
        double x[8][3];
        begin(&t, "union", 0.01);
        box_corners(0, 0, 0, 0, x);
        body0(&t, "a", x);
        box_corners(1, 0, 3, 5, x);
        body0(&t, "b", x);
        box_corners(0, 1, 1, 2, x);
        body0(&t, "c", x);
        if (four) {
            box_corners(1, 1, 4, 6, x);
            body0(&t, "d", x);
        }
        coons_model *model = end(&t);
        coons_mesh *m = sample(model, 1, 2);
        assert_near(coons_mesh_volume(m), 3 + four, 1e-12);
        assert_near(coons_mesh_area(m), four ? 16 : 14, 1e-11);
        coons_mesh_free(m);
        coons_model_free(model);
    }
}

/* Squared distance from p to triangle abc (by projection, clamped to the
 * sides): an independent measure of the mesh. */
static double seg2(const double p[3], const double a[3], const double b[3])
{
    double ab[3], ap[3], l = 0, s = 0;
    for (int d = 0; d < 3; d++) ab[d] = b[d] - a[d], ap[d] = p[d] - a[d], l += ab[d] * ab[d], s += ab[d] * ap[d];
    double u = l > 0 ? s / l : 0;
    u = u < 0 ? 0 : u > 1 ? 1 : u;
    double q = 0;
    for (int d = 0; d < 3; d++) q += (ap[d] - u * ab[d]) * (ap[d] - u * ab[d]);
    return q;
}

static double tri2(const double p[3], const double a[3], const double b[3], const double c[3])
{
    double e1[3], e2[3], n[3], w[3];
    for (int d = 0; d < 3; d++) e1[d] = b[d] - a[d], e2[d] = c[d] - a[d], w[d] = p[d] - a[d];
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (nn > 0) {
        double h = (w[0] * n[0] + w[1] * n[1] + w[2] * n[2]) / nn, q[3];
        for (int d = 0; d < 3; d++) q[d] = p[d] - h * n[d];
        /* barycentric inside test */
        double c1[3], c2[3], c3[3], s1 = 0, s2 = 0, s3 = 0;
        const double *V[3] = {a, b, c};
        double *C[3] = {c1, c2, c3};
        for (int k = 0; k < 3; k++) {
            const double *u = V[k], *v = V[(k + 1) % 3];
            double e[3] = {v[0] - u[0], v[1] - u[1], v[2] - u[2]};
            double f[3] = {q[0] - u[0], q[1] - u[1], q[2] - u[2]};
            C[k][0] = e[1] * f[2] - e[2] * f[1];
            C[k][1] = e[2] * f[0] - e[0] * f[2];
            C[k][2] = e[0] * f[1] - e[1] * f[0];
        }
        for (int d = 0; d < 3; d++) s1 += c1[d] * n[d], s2 += c2[d] * n[d], s3 += c3[d] * n[d];
        if (s1 >= 0 && s2 >= 0 && s3 >= 0) return h * h * nn;
    }
    double q = seg2(p, a, b), q2 = seg2(p, b, c), q3 = seg2(p, c, a);
    return q < q2 ? (q < q3 ? q : q3) : (q2 < q3 ? q2 : q3);
}

/* A box next to a Bezier volume whose top bulges (degree 2 in u and v):
 * the bulge needs lattice lines along v, which the shared face gives the
 * box too (else the border points of the shared face would not match and
 * the shell would not close); exact points of every outer face of both
 * bodies lie within the tolerance of the mesh. */
static void test_neighbour_needs_a_finer_lattice(void **state)
{
    (void)state;
    const double tol = 0.002;
    char json[4096];
    size_t n = (size_t)snprintf(json, sizeof json,
                                "{\"coons\": 1, \"tolerance\": %g, \"operation\": \"union\", "
                                "\"bodies\": [{\"type\": \"body0\", \"name\": \"box\", "
                                "\"corners\": [[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],"
                                "[1,1,0],[1,1,1]]}, {\"type\": \"bezier-volume\", \"name\": "
                                "\"bulge\", \"points\": [",
                                tol);
    for (int i = 0; i < 3; i++) {
        n += (size_t)snprintf(json + n, sizeof json - n, "%s[", i ? "," : "");
        for (int j = 0; j < 3; j++) {
            n += (size_t)snprintf(json + n, sizeof json - n, "%s[", j ? "," : "");
            for (int k = 0; k < 2; k++) {
                double z = k ? 1 + (i == 1 && j == 1 ? 0.8 : 0) : 0;
                if (i == 0) z = k; /* the shared face x = 1 is the box's */
                n += (size_t)snprintf(json + n, sizeof json - n, "%s[%g,%g,%g]", k ? "," : "",
                                      1 + 0.5 * i, 0.5 * j, z);
            }
            n += (size_t)snprintf(json + n, sizeof json - n, "]");
        }
        n += (size_t)snprintf(json + n, sizeof json - n, "]");
    }
    snprintf(json + n, sizeof json - n, "]}]}");
    coons_model *model = load(json);
    coons_mesh *m = sample(model, 1, 2);
    const double *x = coons_mesh_vertices(m);
    const uint32_t *tri = coons_mesh_triangles(m);
    size_t nt = coons_mesh_triangle_count(m);
    /* The box's top face z = 1 has vertices at the bulge's v lattice: more
     * than the two corners' lines a lone box needs along y. */
    size_t top_box = 0;
    for (size_t v = 0; v < coons_mesh_vertex_count(m); v++)
        if (x[3 * v] < 1 - 1e-9 && x[3 * v] > 1e-9 && fabs(x[3 * v + 2] - 1) < 1e-12) top_box++;
    assert_true(top_box > 0);
    /* Exact points of the outer faces vs the mesh (brute force). */
    double worst = 0;
    for (size_t b = 0; b < 2; b++) {
        const coons_body *body = coons_model_body(model, b);
        for (int f = 0; f < 6; f++) {
            if (b == 0 && f == 1) continue; /* shared: inside the solid */
            if (b == 1 && f == 0) continue;
            for (int i = 0; i <= 12; i++)
                for (int j = 0; j <= 12; j++) {
                    double p[3], X[3], s = i / 12.0, q = j / 12.0;
                    int fixed = f / 2, a = fixed == 0 ? 1 : 0, c = fixed == 2 ? 1 : 2;
                    p[fixed] = f & 1;
                    p[a] = s;
                    p[c] = q;
                    coons_body_eval(body, p[0], p[1], p[2], X);
                    double best = INFINITY;
                    for (size_t k = 0; k < nt; k++) {
                        double d2 = tri2(X, x + 3 * tri[3 * k], x + 3 * tri[3 * k + 1],
                                         x + 3 * tri[3 * k + 2]);
                        if (d2 < best) best = d2;
                    }
                    if (sqrt(best) > worst) worst = sqrt(best);
                }
        }
    }
    assert_true(worst <= tol);
    assert_true(worst > 0); /* the bulge is curved: the check measures something */
    double dev;
    coons_mesh_part_sampling(m, 0, NULL, &dev, NULL);
    assert_true(dev <= tol && dev >= 0.5 * worst);
    coons_mesh_free(m);
    coons_model_free(model);
}

/* The lattice's bodies share one triangle budget; "none" keeps each
 * body's own closed shell, shared faces included. */
static void test_budget_and_none(void **state)
{
    (void)state;
    text t;
    double a[8][3], b[8][3];
    box_corners(0, 0, 0, 0, a);
    box_corners(1, 0, 0, 0, b);
    begin(&t, "union", 0.01);
    body0(&t, "a", a);
    body0(&t, "b", b);
    coons_model *model = end(&t);
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.max_triangles = 8;
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_int_equal(coons_model_sample(model, &o, &m, &err), COONS_E_LIMIT);
    assert_null(m);
    assert_non_null(strstr(err.message, "triangles"));
    coons_model_free(model);

    begin(&t, "none", 0.01);
    body0(&t, "a", a);
    body0(&t, "b", b);
    model = end(&t);
    m = sample(model, 2, 4);
    assert_near(coons_mesh_volume(m), 2, 1e-12);
    assert_near(coons_mesh_area(m), 12, 1e-11);
    coons_mesh_free(m);
    coons_model_free(model);
}

/* Every allocation failure is reported and leaks nothing. */
static void test_lattice_alloc_failures(void **state)
{
    (void)state;
    text t;
    double x[8][3];
    begin(&t, "union", 0.05);
    box_corners(0, 0, 0, 0, x);
    body0(&t, "a", x);
    box_corners(1, 0, 3, 5, x);
    body0(&t, "b", x);
    box_corners(0, 1, 1, 2, x);
    body0(&t, "c", x);
    coons_model *model = end(&t);
    for (long n = 0;; n++) {
        coons_mesh *m = NULL;
        coons_error err = COONS_ERROR_INIT;
        coons_test_fail_after(n);
        int rc = coons_model_sample(model, NULL, &m, &err);
        long live = coons_test_live_allocs();
        coons_test_fail_after(-1);
        if (rc == COONS_OK) {
            coons_mesh_free(m);
            break;
        }
        assert_int_equal(rc, COONS_E_NOMEM);
        assert_null(m);
        assert_int_equal(live, 0);
        assert_true(n < 100000);
    }
    coons_model_free(model);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_two_boxes_every_parametrisation),
        cmocka_unit_test(test_lattice_with_moved_inner_points),
        cmocka_unit_test(test_ring_of_eight),
        cmocka_unit_test(test_bodies_meeting_through_a_third),
        cmocka_unit_test(test_neighbour_needs_a_finer_lattice),
        cmocka_unit_test(test_budget_and_none),
        cmocka_unit_test(test_lattice_alloc_failures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
