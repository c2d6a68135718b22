/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Sampling bodies into closed boundary meshes (src/mesh/sample.c).
 * Everything is checked against independent computations: exact volumes of
 * polyhedral bodies, an edge-use count written here, point-to-triangle
 * distances from random exact boundary points, and coons_body_volume(). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"

/* ---------- independent helpers ---------- */

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : (x > y);
}

/* Every directed edge occurs once and its reverse once: each undirected edge
 * has exactly two triangles, run in opposite directions. No triangle repeats
 * a vertex. */
static void assert_closed_oriented(const coons_mesh *m)
{
    size_t nt = coons_mesh_triangle_count(m);
    const uint32_t *t = coons_mesh_triangles(m);
    uint64_t *e = malloc(3 * nt * sizeof *e);
    assert_non_null(e);
    for (size_t i = 0; i < nt; i++) {
        assert_true(t[3 * i] != t[3 * i + 1] && t[3 * i + 1] != t[3 * i + 2] &&
                    t[3 * i + 2] != t[3 * i]);
        for (int k = 0; k < 3; k++)
            e[3 * i + k] = (uint64_t)t[3 * i + k] << 32 | t[3 * i + (k + 1) % 3];
    }
    qsort(e, 3 * nt, sizeof *e, cmp_u64);
    for (size_t i = 0; i + 1 < 3 * nt; i++)
        if (e[i] == e[i + 1]) fail_msg("directed edge %llx used twice", (unsigned long long)e[i]);
    for (size_t i = 0; i < 3 * nt; i++) {
        uint64_t r = (e[i] & 0xffffffffu) << 32 | e[i] >> 32;
        if (!bsearch(&r, e, 3 * nt, sizeof *e, cmp_u64))
            fail_msg("edge %u-%u has no opposite triangle", (unsigned)(e[i] >> 32),
                     (unsigned)(e[i] & 0xffffffffu));
    }
    free(e);
}

static void sub(double o[3], const double a[3], const double b[3])
{
    for (int i = 0; i < 3; i++) o[i] = a[i] - b[i];
}
static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Closest point on triangle abc to p (Ericson, Real-Time Collision
 * Detection, 5.1.5); returns the distance. */
static double point_tri_dist(const double p[3], const double a[3], const double b[3],
                             const double c[3])
{
    double ab[3], ac[3], ap[3], bp[3], cp[3], q[3];
    sub(ab, b, a);
    sub(ac, c, a);
    sub(ap, p, a);
    double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) {
        memcpy(q, a, sizeof q);
        goto out;
    }
    sub(bp, p, b);
    double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) {
        memcpy(q, b, sizeof q);
        goto out;
    }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        double v = d1 / (d1 - d3);
        for (int i = 0; i < 3; i++) q[i] = a[i] + v * ab[i];
        goto out;
    }
    sub(cp, p, c);
    double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) {
        memcpy(q, c, sizeof q);
        goto out;
    }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        double w = d2 / (d2 - d6);
        for (int i = 0; i < 3; i++) q[i] = a[i] + w * ac[i];
        goto out;
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        for (int i = 0; i < 3; i++) q[i] = b[i] + w * (c[i] - b[i]);
        goto out;
    }
    {
        double denom = 1.0 / (va + vb + vc), v = vb * denom, w = vc * denom;
        for (int i = 0; i < 3; i++) q[i] = a[i] + ab[i] * v + ac[i] * w;
    }
out:
    sub(q, p, q);
    return sqrt(dot(q, q));
}

static double dist_to_mesh(const coons_mesh *m, const double p[3])
{
    const double *x = coons_mesh_vertices(m);
    const uint32_t *t = coons_mesh_triangles(m);
    double best = INFINITY;
    for (size_t i = 0; i < coons_mesh_triangle_count(m); i++) {
        double d = point_tri_dist(p, x + 3 * t[3 * i], x + 3 * t[3 * i + 1], x + 3 * t[3 * i + 2]);
        if (d < best) best = d;
    }
    return best;
}

static uint64_t rng = 88172645463325252ull;
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

/* Largest distance from `count` random points of the exact boundary (random
 * face, random (s,t)) to the mesh. */
static double sampled_distance(const coons_body *b, const coons_mesh *m, int count)
{
    double worst = 0;
    for (int i = 0; i < count; i++) {
        int face = (int)(urand() * 6) % 6;
        double q[3] = {urand(), urand(), urand()}, p[3];
        q[face / 2] = (double)(face % 2);
        coons_body_eval(b, q[0], q[1], q[2], p);
        double d = dist_to_mesh(m, p);
        if (d > worst) worst = d;
    }
    return worst;
}

static void check_report(const coons_mesh *m)
{
    coons_error err = COONS_ERROR_INIT;
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    assert_coons_ok(coons_mesh_check(m, &r, &err), &err);
    assert_true(r.closed);
    assert_true(r.manifold);
    assert_true(r.oriented);
    assert_int_equal(r.shells, 1);
    assert_int_equal(r.euler, 2);
    assert_int_equal(r.openmesh_rejected, 0);
    assert_int_equal(r.openmesh_boundary, 0);
    assert_true(r.volume > 0);
}

/* ---------- bodies ---------- */

static coons_body *box_body(double lx, double ly, double lz, int mirror)
{
    double c[8][3];
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) {
                double *p = c[4 * i + 2 * j + k];
                p[0] = (mirror ? 1 - i : i) * lx;
                p[1] = j * ly;
                p[2] = k * lz;
            }
    coons_body *b = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err), &err);
    return b;
}

/* Degree-2 Bezier volume: a unit cube whose face-centre control points bulge
 * out by `bulge` (curved faces, det J > 0); mirrored in x when asked. */
static coons_body *pillow(double bulge, int mirror)
{
    double pts[27 * 3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) {
                double *p = pts + 3 * ((i * 3 + j) * 3 + k);
                int idx[3] = {i, j, k};
                int mids = (i == 1) + (j == 1) + (k == 1);
                for (int d = 0; d < 3; d++) {
                    p[d] = idx[d] / 2.0;
                    if (mids == 2 && idx[d] != 1) p[d] += (idx[d] ? 1 : -1) * bulge;
                }
                if (mirror) p[0] = -p[0];
            }
    size_t n[3] = {3, 3, 3};
    coons_body *b = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_bezier(pts, n, &b, &err), &err);
    return b;
}

/* Rounded-square section at height z, half-width r (3 x 3 control points:
 * edge midpoints pushed out so the section is curved). */
static void section(double *pts, size_t nw, size_t k, double r, double z)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double *p = pts + 3 * ((i * 3 + j) * nw + k);
            double x = (i - 1) * r, y = (j - 1) * r;
            if ((i == 1) != (j == 1)) {
                x *= 1.4;
                y *= 1.4;
            }
            p[0] = x;
            p[1] = y;
            p[2] = z;
        }
}

/* Curved cone: rounded base, all top control points at one apex. */
static coons_body *cone(void)
{
    double pts[3 * 3 * 2 * 3];
    section(pts, 2, 0, 1.0, 0.0);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double *p = pts + 3 * ((i * 3 + j) * 2 + 1);
            p[0] = 0, p[1] = 0, p[2] = 2;
        }
    size_t n[3] = {3, 3, 2};
    coons_body *b = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_bezier(pts, n, &b, &err), &err);
    return b;
}

/* Nail tip: rounded sections shrinking to a straight edge: face w1
 * collapses to a curve (all of its v-lines to points). */
static coons_body *chisel(void)
{
    double pts[3 * 3 * 3 * 3];
    section(pts, 3, 0, 1.0, 0.0);
    section(pts, 3, 1, 0.7, 1.0);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double *p = pts + 3 * ((i * 3 + j) * 3 + 2);
            p[0] = (i - 1) * 0.5, p[1] = 0, p[2] = 2.5;
        }
    size_t n[3] = {3, 3, 3};
    coons_body *b = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_bezier(pts, n, &b, &err), &err);
    return b;
}

/* A washer as body 1 (like examples/curve-coons-cubic-closed.json): the four
 * u edges are closed Coons cubics, so faces u0 and u1 coincide. */
static coons_body *ring(void)
{
    static const double oct[8][2] = {{0.75, -0.75}, {1, 0},   {0.75, 0.75}, {0, 1},
                                     {-0.75, 0.75}, {-1, 0}, {-0.75, -0.75}, {0, -1}};
    const double rad[2] = {6, 3}, hgt[2] = {0, 3};
    coons_curve *e[12];
    coons_error err = COONS_ERROR_INIT;
    for (int j = 0; j < 2; j++)
        for (int k = 0; k < 2; k++) {
            double pts[8][3];
            for (int i = 0; i < 8; i++) {
                pts[i][0] = rad[j] * oct[i][0];
                pts[i][1] = rad[j] * oct[i][1];
                pts[i][2] = hgt[k];
            }
            assert_coons_ok(coons_curve_new_coons_cubic(&pts[0][0], 8, 1, &e[2 * j + k], &err), &err);
        }
    /* the closed curves start (and end) at (C0 P7 + C1 P0 + C2 P1 + C3 P2) */
    double a[2][2][3];
    for (int j = 0; j < 2; j++)
        for (int k = 0; k < 2; k++) coons_curve_eval(e[2 * j + k], 0.0, a[j][k]);
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 2; k++) /* v edges: C(i, v, k) from outer (j=0) to inner */
            assert_coons_ok(coons_curve_new_line(a[0][k], a[1][k], &e[4 + 2 * i + k], &err), &err);
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) /* w edges: C(i, j, w) */
            assert_coons_ok(coons_curve_new_line(a[j][0], a[j][1], &e[8 + 2 * i + j], &err), &err);
    coons_body *b = NULL;
    assert_coons_ok(coons_body_new_body1(e, COONS_BLEND_LINEAR, 0, &b,
                                         &err),
                    &err);
    for (int i = 0; i < 12; i++) coons_curve_free(e[i]);
    return b;
}

/* ---------- tests ---------- */

static void test_box_volume_exact(void **state)
{
    (void)state;
    coons_body *b = box_body(2, 3, 5, 0);
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_sample(b, NULL, "box", &m, &err), &err);
    assert_near(coons_mesh_volume(m), 30.0, 1e-12);
    assert_near(coons_mesh_area(m), 2 * (6 + 10 + 15), 1e-12);
    assert_string_equal(coons_mesh_part_name(m, 0), "box");
    assert_closed_oriented(m);
    check_report(m);
    double tol, dev;
    size_t lat[3];
    assert_int_equal(coons_mesh_part_sampling(m, 0, &tol, &dev, lat), 1);
    assert_near(tol, 1e-3 * sqrt(4 + 9 + 25), 1e-15);
    assert_true(dev <= 1e-12); /* planar faces: the mesh is exact */
    coons_mesh_free(m);
    coons_body_free(b);
}

static void test_left_handed_outward(void **state)
{
    (void)state;
    coons_body *b = box_body(2, 3, 5, 1);
    double J[3][3], x[3];
    assert_true(coons_body_eval_jacobian(b, 0.5, 0.5, 0.5, x, J) < 0);
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_sample(b, NULL, NULL, &m, &err), &err);
    assert_near(coons_mesh_volume(m), 30.0, 1e-12);
    /* Each triangle's normal points away from the box centre. */
    const double *v = coons_mesh_vertices(m);
    const uint32_t *t = coons_mesh_triangles(m);
    double centre[3] = {1, 1.5, 2.5};
    for (size_t i = 0; i < coons_mesh_triangle_count(m); i++) {
        const double *a = v + 3 * t[3 * i], *p = v + 3 * t[3 * i + 1], *c = v + 3 * t[3 * i + 2];
        double e1[3], e2[3], n[3], g[3];
        sub(e1, p, a);
        sub(e2, c, a);
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        for (int k = 0; k < 3; k++) g[k] = (a[k] + p[k] + c[k]) / 3 - centre[k];
        assert_true(dot(n, g) > 0);
    }
    assert_closed_oriented(m);
    coons_mesh_free(m);
    coons_body_free(b);

    /* A curved left-handed body too. */
    b = pillow(0.3, 1);
    assert_true(coons_body_eval_jacobian(b, 0.5, 0.5, 0.5, x, J) < 0);
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.tolerance = 1e-3;
    assert_coons_ok(coons_body_sample(b, &o, NULL, &m, &err), &err);
    double vol;
    assert_coons_ok(coons_body_volume(b, 1e-10, &vol, &err), &err);
    assert_true(vol < 0); /* the integral of det J is negative */
    assert_near(coons_mesh_volume(m), -vol, coons_mesh_area(m) * o.tolerance);
    assert_closed_oriented(m);
    check_report(m);
    coons_mesh_free(m);
    coons_body_free(b);
}

static void test_pyramid_apex(void **state)
{
    (void)state;
    /* body0 with the four top corners at one apex: planar faces, exact volume. */
    double c[8][3];
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            double *p = c[4 * i + 2 * j];
            p[0] = 2.0 * i - 1, p[1] = 2.0 * j - 1, p[2] = 0;
            p = c[4 * i + 2 * j + 1];
            p[0] = 0, p[1] = 0, p[2] = 2;
        }
    coons_body *b = NULL;
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err), &err);
    assert_coons_ok(coons_body_sample(b, NULL, NULL, &m, &err), &err);
    assert_near(coons_mesh_volume(m), 8.0 / 3.0, 1e-12);
    assert_closed_oriented(m);
    check_report(m);
    /* exactly one vertex at the apex */
    int at_apex = 0;
    const double *v = coons_mesh_vertices(m);
    for (size_t i = 0; i < coons_mesh_vertex_count(m); i++)
        at_apex += fabs(v[3 * i]) + fabs(v[3 * i + 1]) + fabs(v[3 * i + 2] - 2) < 1e-9;
    assert_int_equal(at_apex, 1);
    coons_mesh_free(m);
    coons_body_free(b);
}

static void test_wedge_face_to_curve(void **state)
{
    (void)state;
    /* body0 whose top face collapses to the segment (0,.5,1)-(2,.5,1):
     * a triangular prism of volume 1. */
    double c[8][3];
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            double *p = c[4 * i + 2 * j];
            p[0] = 2.0 * i, p[1] = j, p[2] = 0;
            p = c[4 * i + 2 * j + 1];
            p[0] = 2.0 * i, p[1] = 0.5, p[2] = 1;
        }
    coons_body *b = NULL;
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err), &err);
    assert_coons_ok(coons_body_sample(b, NULL, NULL, &m, &err), &err);
    assert_near(coons_mesh_volume(m), 1.0, 1e-12);
    assert_closed_oriented(m);
    check_report(m);
    coons_mesh_free(m);
    coons_body_free(b);
}

/* Curved bodies: closed, deviation within tolerance at random exact points,
 * volume within area * tolerance of the det-J volume. */
static void check_curved(coons_body *b, double tol, const char *what)
{
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.tolerance = tol;
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_sample(b, &o, what, &m, &err), &err);
    assert_closed_oriented(m);
    check_report(m);
    double dev, got_tol;
    size_t lat[3];
    assert_true(coons_mesh_part_sampling(m, 0, &got_tol, &dev, lat));
    assert_near(got_tol, tol, 0);
    assert_true(dev <= tol);
    assert_true(dev > 0);
    double d = sampled_distance(b, m, 300);
    assert_true(d <= tol);
    double vol;
    assert_coons_ok(coons_body_volume(b, 1e-10, &vol, &err), &err);
    double area = coons_mesh_area(m);
    assert_near(coons_mesh_volume(m), fabs(vol), area * tol);
    print_message("%-8s tol %g: %zu triangles, lattice %zux%zux%zu, measured %.3g, "
                  "random-point distance %.3g, volume %.9g vs %.9g\n",
                  what, tol, coons_mesh_triangle_count(m), lat[0], lat[1], lat[2], dev, d,
                  coons_mesh_volume(m), vol);
    coons_mesh_free(m);
}

static void test_curved_pillow(void **state)
{
    (void)state;
    coons_body *b = pillow(0.3, 0);
    check_curved(b, 1e-2, "pillow");
    check_curved(b, 1e-3, "pillow");
    check_curved(b, 1e-4, "pillow");
    coons_body_free(b);
}

static void test_curved_cone_apex(void **state)
{
    (void)state;
    coons_body *b = cone();
    check_curved(b, 1e-3, "cone");
    coons_body_free(b);
}

static void test_curved_chisel_face_to_curve(void **state)
{
    (void)state;
    coons_body *b = chisel();
    check_curved(b, 1e-3, "chisel");
    coons_body_free(b);
}

static void test_ring_glued(void **state)
{
    (void)state;
    coons_body *b = ring();
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.tolerance = 1e-2;
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_sample(b, &o, "ring", &m, &err), &err);
    assert_closed_oriented(m);
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    assert_coons_ok(coons_mesh_check(m, &r, &err), &err);
    assert_true(r.closed && r.manifold && r.oriented);
    assert_int_equal(r.euler, 0); /* a torus: the coincident faces u0, u1 are gone */
    assert_int_equal(r.expected_euler, 0);
    assert_int_equal(r.shells, 1);
    /* no vertex lies strictly inside the washer's cross-section cut at u = 0 */
    double cut[3];
    coons_body_eval(b, 0, 0.5, 0.5, cut);
    const double *v = coons_mesh_vertices(m);
    for (size_t i = 0; i < coons_mesh_vertex_count(m); i++) {
        double d[3];
        sub(d, v + 3 * i, cut);
        assert_true(sqrt(dot(d, d)) > 0.5);
    }
    double vol;
    assert_coons_ok(coons_body_volume(b, 1e-10, &vol, &err), &err);
    assert_near(coons_mesh_volume(m), vol, coons_mesh_area(m) * o.tolerance);
    /* random points of the four remaining faces */
    double worst = 0;
    for (int i = 0; i < 300; i++) {
        int face = 2 + (int)(urand() * 4) % 4;
        double q[3] = {urand(), urand(), urand()}, p[3];
        q[face / 2] = (double)(face % 2);
        coons_body_eval(b, q[0], q[1], q[2], p);
        worst = fmax(worst, dist_to_mesh(m, p));
    }
    assert_true(worst <= o.tolerance);
    print_message("ring     tol %g: %zu triangles, Euler %ld, random-point distance %.3g, "
                  "volume %.9g vs %.9g\n",
                  o.tolerance, coons_mesh_triangle_count(m), r.euler, worst,
                  coons_mesh_volume(m), vol);
    coons_mesh_free(m);
    coons_body_free(b);
}

static void test_fixed_resolution(void **state)
{
    (void)state;
    coons_body *b = pillow(0.3, 0);
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.resolution = 3;
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_sample(b, &o, NULL, &m, &err), &err);
    /* 6 faces x 3 x 3 cells x 2 triangles; (4^3 - 2^3) lattice boundary points */
    assert_int_equal(coons_mesh_triangle_count(m), 108);
    assert_int_equal(coons_mesh_vertex_count(m), 56);
    size_t lat[3];
    double dev;
    coons_mesh_part_sampling(m, 0, NULL, &dev, lat);
    assert_int_equal(lat[0], 3);
    assert_int_equal(lat[2], 3);
    /* the measured deviation is a lower bound of the true maximum, and
     * random points cannot be farther than the true maximum */
    assert_true(dev > 1e-3);
    assert_closed_oriented(m);
    /* the same lattice without the measurement */
    o.flags = COONS_SAMPLE_UNMEASURED;
    coons_mesh *u = NULL;
    assert_coons_ok(coons_body_sample(b, &o, NULL, &u, &err), &err);
    assert_int_equal(coons_mesh_triangle_count(u), 108);
    assert_memory_equal(coons_mesh_vertices(u), coons_mesh_vertices(m), 56 * 3 * sizeof(double));
    assert_memory_equal(coons_mesh_triangles(u), coons_mesh_triangles(m), 108 * 3 * sizeof(uint32_t));
    assert_int_equal(coons_mesh_part_sampling(u, 0, NULL, &dev, lat), 1);
    assert_true(isnan(dev));
    assert_true(isnan(coons_mesh_deviation(u)));
    coons_mesh_free(u);
    coons_mesh_free(m);
    coons_body_free(b);
}

static void test_limits_and_options(void **state)
{
    (void)state;
    coons_body *b = pillow(0.3, 0);
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    coons_mesh *m = (coons_mesh *)&o; /* must be reset to NULL on failure */
    coons_error err = COONS_ERROR_INIT;
    o.tolerance = 1e-6;
    o.max_triangles = 1000;
    assert_int_equal(coons_body_sample(b, &o, "p", &m, &err), COONS_E_LIMIT);
    assert_null(m);
    assert_non_null(strstr(err.message, "1000"));
    assert_non_null(strstr(err.message, "max-triangles"));
    /* The refusal names the tolerance and a predicted count above the
     * limit, and the tolerance it suggests samples within the limit. */
    assert_non_null(strstr(err.message, "tolerance 1e-06"));
    const char *pr = strstr(err.message, "about ");
    assert_non_null(pr);
    assert_true(strtod(pr + 6, NULL) > 1000);
    const char *try_at = strstr(err.message, "(try ");
    assert_non_null(try_at);
    double suggested = strtod(try_at + 5, NULL);
    assert_true(suggested > 1e-6);
    o.tolerance = suggested;
    assert_coons_ok(coons_body_sample(b, &o, "p", &m, &err), &err);
    assert_true(coons_mesh_triangle_count(m) <= 1000);
    coons_mesh_free(m);
    m = (coons_mesh *)&o;
    o = (coons_sample_options)COONS_SAMPLE_OPTIONS_INIT;
    o.resolution = 100;
    o.max_triangles = 1000;
    assert_int_equal(coons_body_sample(b, &o, "p", &m, &err), COONS_E_LIMIT);
    o = (coons_sample_options)COONS_SAMPLE_OPTIONS_INIT;
    o.version = 99;
    assert_int_equal(coons_body_sample(b, &o, "p", &m, &err), COONS_E_INVALID);
    o = (coons_sample_options)COONS_SAMPLE_OPTIONS_INIT;
    o.max_aspect = 0.5;
    assert_int_equal(coons_body_sample(b, &o, "p", &m, &err), COONS_E_INVALID);
    o = (coons_sample_options)COONS_SAMPLE_OPTIONS_INIT;
    o.flags = 6;
    assert_int_equal(coons_body_sample(b, &o, "p", &m, &err), COONS_E_INVALID);
    coons_body_free(b);
}

/* A thin plate: triangles stay within the aspect bound (cells are split by
 * their long side), and a larger bound gives fewer triangles. */
static void test_aspect(void **state)
{
    (void)state;
    coons_body *b = box_body(10, 10, 0.5, 0);
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_sample(b, NULL, NULL, &m, &err), &err);
    const double *v = coons_mesh_vertices(m);
    const uint32_t *t = coons_mesh_triangles(m);
    double worst = 0;
    for (size_t i = 0; i < coons_mesh_triangle_count(m); i++) {
        double l[3];
        for (int k = 0; k < 3; k++) {
            double d[3];
            sub(d, v + 3 * t[3 * i + k], v + 3 * t[3 * i + (k + 1) % 3]);
            l[k] = sqrt(dot(d, d));
        }
        double mx = fmax(l[0], fmax(l[1], l[2])), mn = fmin(l[0], fmin(l[1], l[2]));
        worst = fmax(worst, mx / mn);
    }
    /* a cell of side ratio k splits into triangles of edge ratio <= sqrt(1 + k^2) */
    assert_true(worst <= sqrt(1 + COONS_SAMPLE_DEFAULT_MAX_ASPECT * COONS_SAMPLE_DEFAULT_MAX_ASPECT) + 1e-9);
    size_t n1 = coons_mesh_triangle_count(m);
    coons_mesh_free(m);
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.max_aspect = INFINITY;
    assert_coons_ok(coons_body_sample(b, &o, NULL, &m, &err), &err);
    assert_true(coons_mesh_triangle_count(m) < n1);
    assert_near(coons_mesh_volume(m), 50.0, 1e-12);
    coons_mesh_free(m);
    coons_body_free(b);
}

static void test_alloc_failures(void **state)
{
    (void)state;
    coons_body *b = cone();
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.tolerance = 2e-2;
    for (long n = 0;; n++) {
        coons_mesh *m = NULL;
        coons_error err = COONS_ERROR_INIT;
        coons_test_fail_after(n);
        int rc = coons_body_sample(b, &o, NULL, &m, &err);
        coons_test_fail_after(-1);
        if (rc == COONS_OK) {
            assert_true(n > 3);
            assert_closed_oriented(m);
            coons_mesh_free(m);
            break;
        }
        assert_int_equal(rc, COONS_E_NOMEM);
        assert_null(m);
        assert_true(n < 10000);
    }
    /* the checks */
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_sample(b, &o, NULL, &m, &err), &err);
    for (long n = 0;; n++) {
        coons_mesh_report r = COONS_MESH_REPORT_INIT;
        coons_test_fail_after(n);
        int rc = coons_mesh_check(m, &r, &err);
        coons_test_fail_after(-1);
        if (rc == COONS_OK) {
            assert_true(r.closed && r.manifold && r.oriented);
            break;
        }
        assert_int_equal(rc, COONS_E_NOMEM);
        assert_true(n < 100);
    }
    coons_mesh_free(m);
    coons_body_free(b);
    /* a model of two bodies */
    static const char *json =
        "{\"coons\": 1, \"tolerance\": 0.05, \"operation\": \"none\", \"bodies\": ["
        "{\"type\": \"body0\", \"corners\": [[0,0,0],[0,0,1],[0,1,0],[0,1,1],"
        "[1,0,0],[1,0,1],[1,1,0],[1,1,1]]},"
        "{\"type\": \"bezier-volume\", \"points\": [[[[0,0,2],[0,0,3]],[[0,1,2],[0,1,3]]],"
        "[[[1,0,2],[1,0,3.5]],[[1,1,2],[1,1,3]]]]}]}";
    coons_model *model = NULL;
    assert_coons_ok(coons_model_load_memory(json, strlen(json), NULL, NULL, &model, &err), &err);
    for (long n = 0;; n++) {
        coons_test_fail_after(n);
        int rc = coons_model_sample(model, NULL, &m, &err);
        coons_test_fail_after(-1);
        if (rc == COONS_OK) {
            assert_int_equal(coons_mesh_part_count(m), 2);
            coons_mesh_free(m);
            break;
        }
        assert_int_equal(rc, COONS_E_NOMEM);
        assert_null(m);
        assert_true(n < 10000);
    }
    coons_model_free(model);
}

static const char *TWO_BOXES =
    "{\"coons\": 1, \"tolerance\": 0.01, \"operation\": \"%s\", \"bodies\": ["
    "{\"type\": \"body0\", \"name\": \"a\", \"corners\": [[0,0,0],[0,0,1],[0,1,0],[0,1,1],"
    "[1,0,0],[1,0,1],[1,1,0],[1,1,1]]},"
    "{\"type\": \"body0\", \"corners\": [[%g,0,0],[%g,0,1],[%g,1,0],[%g,1,1],"
    "[%g,0,0],[%g,0,1],[%g,1,0],[%g,1,1]]}]}";

static int mesh_two_boxes(const char *op, double x0, coons_mesh **m, coons_error *err)
{
    char json[1024];
    double x1 = x0 + 2;
    snprintf(json, sizeof json, TWO_BOXES, op, x0, x0, x0, x0, x1, x1, x1, x1);
    coons_model *model = NULL;
    assert_coons_ok(coons_model_load_memory(json, strlen(json), "two.json", NULL, &model, err), err);
    int rc = coons_model_sample(model, NULL, m, err);
    coons_model_free(model);
    return rc;
}

static void test_model_mesh(void **state)
{
    (void)state;
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    /* apart: a plain collection of two parts */
    assert_coons_ok(mesh_two_boxes("union", 3, &m, &err), &err);
    assert_int_equal(coons_mesh_part_count(m), 2);
    assert_string_equal(coons_mesh_part_name(m, 0), "a");
    assert_string_equal(coons_mesh_part_name(m, 1), "body1");
    assert_near(coons_mesh_volume(m), 1 + 2, 1e-12);
    double tol;
    coons_mesh_part_sampling(m, 1, &tol, NULL, NULL);
    assert_near(tol, 0.01, 0);
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    assert_coons_ok(coons_mesh_check(m, &r, &err), &err);
    assert_true(r.closed && r.manifold && r.oriented);
    assert_int_equal(r.shells, 2);
    assert_int_equal(r.euler, 4);
    coons_mesh_free(m);
    /* overlapping: the union is not available here */
    m = (coons_mesh *)&err;
    assert_int_equal(mesh_two_boxes("union", 0.5, &m, &err), COONS_E_UNSUPPORTED);
    assert_null(m);
    assert_non_null(strstr(err.message, "'a' and 'body1'"));
    assert_non_null(strstr(err.message, "\"none\""));
    /* touching along a whole face: a shared face, joined by index into one
     * closed part without any Boolean (seed 000 §3, control lattices) */
    assert_coons_ok(mesh_two_boxes("union", 1, &m, &err), &err);
    assert_int_equal(coons_mesh_part_count(m), 1);
    assert_string_equal(coons_mesh_part_name(m, 0), "a+body1");
    assert_near(coons_mesh_volume(m), 1 + 2, 1e-12);
    r = (coons_mesh_report)COONS_MESH_REPORT_INIT;
    assert_coons_ok(coons_mesh_check(m, &r, &err), &err);
    assert_true(r.closed && r.manifold && r.oriented);
    assert_int_equal(r.shells, 1);
    assert_int_equal(r.euler, 2);
    coons_mesh_free(m);
    /* overlapping by a thin slab across the face: still needs the Boolean */
    assert_int_equal(mesh_two_boxes("union", 0.999, &m, &err), COONS_E_UNSUPPORTED);
    /* "none": each body's own shell, overlaps allowed */
    assert_coons_ok(mesh_two_boxes("none", 0.5, &m, &err), &err);
    assert_int_equal(coons_mesh_part_count(m), 2);
    assert_near(coons_mesh_volume(m), 3, 1e-12);
    coons_mesh_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box_volume_exact),
        cmocka_unit_test(test_left_handed_outward),
        cmocka_unit_test(test_pyramid_apex),
        cmocka_unit_test(test_wedge_face_to_curve),
        cmocka_unit_test(test_curved_pillow),
        cmocka_unit_test(test_curved_cone_apex),
        cmocka_unit_test(test_curved_chisel_face_to_curve),
        cmocka_unit_test(test_ring_glued),
        cmocka_unit_test(test_fixed_resolution),
        cmocka_unit_test(test_limits_and_options),
        cmocka_unit_test(test_aspect),
        cmocka_unit_test(test_alloc_failures),
        cmocka_unit_test(test_model_mesh),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
