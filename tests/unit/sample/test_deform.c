/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Free-form deformation of a mesh by a body (src/mesh/deform.c). Expected
 * values independent of it: the affine map written out (no splitting, exact
 * vertices); for a curved body 2, the exact images of 150 random points of the
 * input's triangles against the output by brute-force point-triangle
 * distance; the enclosed volume against the body's own volume (the
 * integral of det J over the unit cube, coons_body_volume()); closedness
 * by counting directed edges; a mirrored body still outward.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "body_fixtures.h"
#include "coons_test_hooks.h"

/* The unit cube as 12 triangles, counter-clockwise seen from outside. */
static coons_mesh *unit_cube(void)
{
    double v[8][3];
    for (int n = 0; n < 8; n++) v[n][0] = n >> 2, v[n][1] = (n >> 1) & 1, v[n][2] = n & 1;
    static const uint32_t t[12][3] = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5},
                                      {0, 4, 5}, {0, 5, 1}, {2, 3, 7}, {2, 7, 6},
                                      {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    assert_coons_ok(coons_mesh_add_part(m, "cube", v[0], 8, t[0], 12, &err), &err);
    assert_true(coons_mesh_volume(m) > 0.999);
    return m;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

/* Every directed edge once, and its reverse once: closed, 2-manifold,
 * consistently wound. */
static int closed_oriented(const coons_mesh *m)
{
    size_t nt = coons_mesh_triangle_count(m);
    const uint32_t *t = coons_mesh_triangles(m);
    size_t ne = 3 * nt;
    uint64_t *e = malloc(ne * sizeof *e);
    for (size_t i = 0; i < nt; i++)
        for (int k = 0; k < 3; k++)
            e[3 * i + k] = (uint64_t)t[3 * i + k] << 32 | t[3 * i + (k + 1) % 3];
    qsort(e, ne, sizeof *e, cmp_u64);
    int ok = 1;
    for (size_t i = 0; i < ne && ok; i++) {
        uint64_t rev = (e[i] << 32) | (e[i] >> 32);
        ok = (i + 1 == ne || e[i + 1] != e[i]) && bsearch(&rev, e, ne, sizeof *e, cmp_u64);
    }
    free(e);
    return ok;
}

static void assert_same_mesh(const coons_mesh *a, const coons_mesh *b);

static double seg2(const double p[3], const double a[3], const double b[3])
{
    double ab[3], ap[3], l2 = 0, s = 0, d2 = 0;
    for (int i = 0; i < 3; i++) ab[i] = b[i] - a[i], ap[i] = p[i] - a[i], l2 += ab[i] * ab[i],
                                s += ap[i] * ab[i];
    s = l2 > 0 ? s / l2 : 0;
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    for (int i = 0; i < 3; i++) d2 += (a[i] + s * ab[i] - p[i]) * (a[i] + s * ab[i] - p[i]);
    return d2;
}

/* Distance from p to triangle abc: the plane where the foot is inside,
 * else the nearest side. */
static double tri_dist(const double p[3], const double a[3], const double b[3], const double c[3])
{
    double u[3], v[3], n[3], w[3];
    for (int i = 0; i < 3; i++) u[i] = b[i] - a[i], v[i] = c[i] - a[i], w[i] = p[i] - a[i];
    n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2],
    n[2] = u[0] * v[1] - u[1] * v[0];
    double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    double best = fmin(seg2(p, a, b), fmin(seg2(p, b, c), seg2(p, c, a)));
    if (nn > 0) {
        double d = (w[0] * n[0] + w[1] * n[1] + w[2] * n[2]) / nn, f[3];
        for (int i = 0; i < 3; i++) f[i] = p[i] - d * n[i];
        /* barycentric coordinates of the foot */
        double uu = 0, uv = 0, vv = 0, fu = 0, fv = 0;
        for (int i = 0; i < 3; i++) {
            double fi = f[i] - a[i];
            uu += u[i] * u[i], uv += u[i] * v[i], vv += v[i] * v[i], fu += fi * u[i],
                fv += fi * v[i];
        }
        double den = uu * vv - uv * uv, s = (vv * fu - uv * fv) / den, t = (uu * fv - uv * fu) / den;
        if (s >= 0 && t >= 0 && s + t <= 1) best = fmin(best, d * d * nn);
    }
    return sqrt(best);
}

static void test_affine_exact(void **state)
{
    (void)state;
    const double o[3] = {1, -2, 0.5}, A[3][3] = {{2, 0.5, 0.3}, {0.1, 3, -0.4}, {0.2, 0, 1.5}};
    double c[8][3];
    for (int n = 0; n < 8; n++) {
        double q[3] = {n >> 2, (n >> 1) & 1, n & 1};
        for (int r = 0; r < 3; r++) c[n][r] = o[r] + A[r][0] * q[0] + A[r][1] * q[1] + A[r][2] * q[2];
    }
    coons_error err = COONS_ERROR_INIT;
    coons_body *b;
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err), &err);
    coons_mesh *in = unit_cube(), *out = NULL;
    assert_coons_ok(coons_body_deform_mesh(b, in, NULL, NULL, 1e-6, 0, &out, &err), &err);
    assert_int_equal(coons_mesh_triangle_count(out), 12);
    assert_int_equal(coons_mesh_vertex_count(out), 8);
    const double *x = coons_mesh_vertices(out), *q = coons_mesh_vertices(in);
    for (int n = 0; n < 8; n++) {
        double want[3];
        for (int r = 0; r < 3; r++)
            want[r] = o[r] + A[r][0] * q[3 * n] + A[r][1] * q[3 * n + 1] + A[r][2] * q[3 * n + 2];
        assert_vec3_near(x + 3 * n, want, 1e-12);
    }
    double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                 A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                 A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    assert_near(coons_mesh_volume(out), det, 1e-12);
    coons_mesh_free(out);
    coons_mesh_free(in);
    coons_body_free(b);
}

static void check_curved(const coons_body *b, double tol, double sign)
{
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *in = unit_cube(), *out = NULL;
    assert_coons_ok(coons_body_deform_mesh(b, in, NULL, NULL, tol, 0, &out, &err), &err);
    assert_true(coons_mesh_triangle_count(out) > 12);
    assert_true(closed_oriented(out));
    /* exact images of random points of the input's faces */
    tb_rng r = {5};
    const double *qv = coons_mesh_vertices(in), *x = coons_mesh_vertices(out);
    const uint32_t *ti = coons_mesh_triangles(in), *to = coons_mesh_triangles(out);
    size_t nto = coons_mesh_triangle_count(out);
    double worst = 0;
    for (int s = 0; s < 150; s++) {
        size_t t = (size_t)(tb_rand(&r) * 12);
        double a = tb_rand(&r), bb = tb_rand(&r);
        if (a + bb > 1) a = 1 - a, bb = 1 - bb;
        double q[3], p[3], best = INFINITY;
        for (int d = 0; d < 3; d++)
            q[d] = (1 - a - bb) * qv[3 * ti[3 * t] + d] + a * qv[3 * ti[3 * t + 1] + d] +
                   bb * qv[3 * ti[3 * t + 2] + d];
        coons_body_eval(b, q[0], q[1], q[2], p);
        for (size_t k = 0; k < nto; k++)
            best = fmin(best, tri_dist(p, x + 3 * to[3 * k], x + 3 * to[3 * k + 1],
                                       x + 3 * to[3 * k + 2]));
        worst = fmax(worst, best);
    }
    print_message("deformed cube: %zu triangles, worst distance %.3g (tolerance %g)\n", nto,
                  worst, tol);
    assert_true(worst <= tol);
    /* volume: the mesh within tol of the exact boundary encloses the
     * integral of |det J| up to tol x area */
    double vol = 0;
    assert_coons_ok(coons_body_volume(b, 1e-4, &vol, &err), &err);
    double vm = coons_mesh_volume(out);
    assert_true(vm > 0);
    assert_near(vm, sign * vol, tol * coons_mesh_area(out));
    coons_mesh_free(out);
    coons_mesh_free(in);
}

static void test_curved_body2(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_patch *f[6];
    coons_body *b, *mirror;
    assert_coons_ok(tb_bspline_faces(5, f, &err), &err);
    assert_coons_ok(coons_body_new_body2(f, COONS_BLEND_LINEAR, 1e-9, &b, &err), &err);
    for (int k = 0; k < 6; k++) coons_patch_free(f[k]);
    check_curved(b, 8e-3, 1.0);
    /* through a left-handed body: still closed and outward */
    const double m[12] = {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    assert_coons_ok(coons_body_new_transformed(b, m, &mirror, &err), &err);
    check_curved(mirror, 8e-3, -1.0);
    coons_body_free(mirror);
    coons_body_free(b);
}

/* The report: the frame used, the counts of the mesh returned, the
 * deviation within 0.9 x the tolerance, the winding reversed for a
 * mirrored body; an affine body splits nothing and deviates by rounding
 * only. */
static void test_report(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_patch *f[6];
    coons_body *b, *mirror;
    assert_coons_ok(tb_bspline_faces(5, f, &err), &err);
    assert_coons_ok(coons_body_new_body2(f, COONS_BLEND_LINEAR, 1e-9, &b, &err), &err);
    for (int k = 0; k < 6; k++) coons_patch_free(f[k]);
    const double m[12] = {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    assert_coons_ok(coons_body_new_transformed(b, m, &mirror, &err), &err);
    coons_mesh *in = unit_cube(), *out = NULL;
    const double lo[3] = {-0.5, 0, 0}, hi[3] = {1, 1, 1.5};
    for (int k = 0; k < 2; k++) {
        coons_deform_report rep = COONS_DEFORM_REPORT_INIT;
        assert_coons_ok(coons_body_deform_mesh_report(k ? mirror : b, in, lo, hi, 8e-3, 0, &out,
                                                      &rep, &err),
                        &err);
        assert_memory_equal(rep.lo, lo, sizeof lo);
        assert_memory_equal(rep.hi, hi, sizeof hi);
        assert_int_equal(rep.triangles_in, 12);
        assert_int_equal(rep.vertices_in, 8);
        assert_int_equal(rep.triangles_out, coons_mesh_triangle_count(out));
        assert_int_equal(rep.vertices_out, coons_mesh_vertex_count(out));
        assert_true(rep.rounds >= 1);
        assert_true(rep.deviation > 0 && rep.deviation <= 0.9 * 8e-3 * (1 + 1e-6));
        assert_int_equal(rep.reversed, k);
        assert_true(coons_mesh_volume(out) > 0);
        assert_true(closed_oriented(out));
        coons_mesh_free(out);
    }
    /* an affine body measures (next to) nothing */
    coons_body *hex;
    const double c[8][3] = {{0, 0, 0}, {0, 0, 2}, {0, 3, 0}, {0, 3, 2},
                            {1, 0, 0}, {1, 0, 2}, {1, 3, 0}, {1, 3, 2}};
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &hex, &err), &err);
    coons_deform_report rep = COONS_DEFORM_REPORT_INIT;
    assert_coons_ok(coons_body_deform_mesh_report(hex, in, NULL, NULL, 1e-9, 0, &out, &rep, &err),
                    &err);
    assert_int_equal(rep.rounds, 0);
    assert_true(rep.deviation <= 1e-14);
    coons_mesh_free(out);
    rep.version = 7;
    assert_int_equal(coons_body_deform_mesh_report(hex, in, NULL, NULL, 1e-3, 0, &out, &rep, &err),
                     COONS_E_INVALID);
    assert_null(out);
    coons_body_free(hex);
    coons_mesh_free(in);
    coons_body_free(mirror);
    coons_body_free(b);
}

/* What the progress callback saw. */
typedef struct seen {
    size_t calls, wrong_stage, backwards;
    double first, last;
} seen;

static void on_progress(void *userdata, const char *stage, double fraction)
{
    seen *s = userdata;
    if (strcmp(stage, "deform") != 0) s->wrong_stage++;
    if (!s->calls) s->first = fraction;
    if (s->calls && fraction < s->last) s->backwards++;
    s->last = fraction;
    s->calls++;
}

/* coons_body_deform(): the progress callback sees the stage "deform" with
 * fractions from 0 that never decrease, more than one per refinement round
 * (a round reports as it measures and as it splits), ending at 1; the mesh
 * is the one of coons_body_deform_mesh_report() for the same arguments,
 * vertex for vertex and triangle for triangle; a record of another version
 * is refused with the common wording. */
static void test_options_progress(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_patch *f[6];
    coons_body *b;
    assert_coons_ok(tb_bspline_faces(5, f, &err), &err);
    assert_coons_ok(coons_body_new_body2(f, COONS_BLEND_LINEAR, 1e-9, &b, &err), &err);
    for (int k = 0; k < 6; k++) coons_patch_free(f[k]);
    coons_mesh *in = unit_cube(), *old = NULL, *out = NULL;
    const double lo[3] = {-0.5, 0, 0}, hi[3] = {1, 1, 1.5};
    coons_deform_report r_old = COONS_DEFORM_REPORT_INIT, r_new = COONS_DEFORM_REPORT_INIT;
    assert_coons_ok(coons_body_deform_mesh_report(b, in, lo, hi, 5e-4, 0, &old, &r_old, &err),
                    &err);
    coons_deform_options o;
    coons_deform_options_init(&o);
    assert_int_equal(o.version, COONS_DEFORM_OPTIONS_VERSION);
    seen s = {0};
    o.tolerance = 5e-4;
    o.lo = lo;
    o.hi = hi;
    o.progress = on_progress;
    o.userdata = &s;
    assert_coons_ok(coons_body_deform(b, in, &o, &out, &r_new, &err), &err);
    assert_true(r_new.rounds >= 3);
    assert_int_equal(s.wrong_stage, 0);
    assert_int_equal(s.backwards, 0);
    assert_true(s.first == 0.0);
    assert_true(s.last == 1.0);
    assert_true(s.calls >= 2 * (size_t)r_new.rounds + 2);
    size_t nv = coons_mesh_vertex_count(old), nt = coons_mesh_triangle_count(old);
    assert_int_equal(coons_mesh_vertex_count(out), nv);
    assert_int_equal(coons_mesh_triangle_count(out), nt);
    assert_memory_equal(coons_mesh_vertices(out), coons_mesh_vertices(old),
                        nv * 3 * sizeof(double));
    assert_memory_equal(coons_mesh_triangles(out), coons_mesh_triangles(old),
                        nt * 3 * sizeof(uint32_t));
    assert_memory_equal(&r_new, &r_old, sizeof r_new);
    coons_mesh_free(out);
    out = NULL;
    o.version = 7;
    assert_int_equal(coons_body_deform(b, in, &o, &out, NULL, &err), COONS_E_INVALID);
    assert_null(out);
    assert_string_equal(err.message,
                        "deform options version 7, expected 3 (use COONS_DEFORM_OPTIONS_INIT)");
    assert_int_equal(coons_body_deform(b, in, NULL, &out, NULL, &err), COONS_E_INVALID);
    /* relative_tolerance: the tolerance from the box of the vertices'
     * images, computed here; the same mesh as that tolerance given */
    double blo[3] = {INFINITY, INFINITY, INFINITY}, bhi[3] = {-INFINITY, -INFINITY, -INFINITY};
    const double *p = coons_mesh_vertices(in);
    for (size_t i = 0; i < coons_mesh_vertex_count(in); i++) {
        double q[3], y[3];
        for (int d = 0; d < 3; d++) q[d] = (p[3 * i + d] - lo[d]) / (hi[d] - lo[d]);
        coons_body_eval(b, q[0], q[1], q[2], y);
        for (int d = 0; d < 3; d++) blo[d] = fmin(blo[d], y[d]), bhi[d] = fmax(bhi[d], y[d]);
    }
    double diag = sqrt((bhi[0] - blo[0]) * (bhi[0] - blo[0]) + (bhi[1] - blo[1]) * (bhi[1] - blo[1]) +
                       (bhi[2] - blo[2]) * (bhi[2] - blo[2]));
    coons_mesh *rel = NULL;
    coons_deform_options_init(&o);
    o.lo = lo;
    o.hi = hi;
    o.relative_tolerance = 4e-3;
    assert_coons_ok(coons_body_deform(b, in, &o, &rel, NULL, &err), &err);
    o.relative_tolerance = 0;
    o.tolerance = 4e-3 * diag;
    assert_coons_ok(coons_body_deform(b, in, &o, &out, NULL, &err), &err);
    assert_true(coons_mesh_triangle_count(out) > 12);
    assert_same_mesh(rel, out);
    coons_mesh_free(out);
    coons_mesh_free(rel);
    out = NULL;
    /* ignored in a record of version 2, where the tolerance must be given */
    o.version = 2;
    o.tolerance = 0;
    o.relative_tolerance = 4e-3;
    assert_int_equal(coons_body_deform(b, in, &o, &out, NULL, &err), COONS_E_INVALID);
    o.version = 3;
    o.relative_tolerance = -1;
    assert_int_equal(coons_body_deform(b, in, &o, &out, NULL, &err), COONS_E_INVALID);
    assert_null(out);
    coons_mesh_free(old);
    coons_mesh_free(in);
    coons_body_free(b);
}

static void test_outside_and_invalid(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_body *b;
    assert_coons_ok(coons_body_new_body0(tb_hex()[0], COONS_BLEND_LINEAR, &b, &err), &err);
    coons_mesh *in = unit_cube(), *out = NULL;
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0.5};
    assert_int_equal(coons_body_deform_mesh(b, in, lo, hi, 1e-3, 0, &out, &err), COONS_E_DOMAIN);
    assert_non_null(strstr(err.message, "4 of the 8 points"));
    assert_null(out);
    const double flat[3] = {1, 1, 0};
    assert_int_equal(coons_body_deform_mesh(b, in, lo, flat, 1e-3, 0, &out, &err),
                     COONS_E_INVALID);
    assert_int_equal(coons_body_deform_mesh(b, in, NULL, NULL, 0, 0, &out, &err), COONS_E_INVALID);
    coons_mesh_free(in);
    coons_body_free(b);
}

static void test_budget_and_alloc(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_body *b, *hex;
    tb_nurbs_cylinder(1.0, 2.0, &b);
    coons_mesh *in = unit_cube(), *out = NULL;
    assert_int_equal(coons_body_deform_mesh(b, in, NULL, NULL, 1e-4, 200, &out, &err),
                     COONS_E_LIMIT);
    /* the skew hexahedron is trilinear: a few rounds of splitting */
    assert_coons_ok(coons_body_new_body0(tb_hex()[0], COONS_BLEND_LINEAR, &hex, &err), &err);
    int done = 0;
    for (long n = 0; !done && n < 100000; n++) {
        coons_test_fail_after(n);
        coons_status rc = coons_body_deform_mesh(hex, in, NULL, NULL, 5e-2, 0, &out, &err);
        size_t nt = out ? coons_mesh_triangle_count(out) : 0;
        coons_mesh_free(out);
        out = NULL;
        assert_int_equal(coons_test_live_allocs(), 0);
        coons_test_fail_after(-1);
        if (rc == COONS_OK) {
            assert_true(nt > 12);
            done = 1;
        } else {
            assert_int_equal(rc, COONS_E_NOMEM);
        }
    }
    assert_true(done);
    coons_mesh_free(in);
    coons_body_free(hex);
    coons_body_free(b);
}


/* The unit cube with n x n squares per face, two triangles each,
 * counter-clockwise seen from outside (vertices shared: closed). */
static coons_mesh *fine_cube(int n)
{
    size_t nv = (size_t)(n + 1) * (n + 1) * (n + 1), nt = 12 * (size_t)n * n, k = 0;
    double *v = malloc(nv * 3 * sizeof *v);
    uint32_t *t = malloc(nt * 3 * sizeof *t);
    for (int i = 0; i <= n; i++)
        for (int j = 0; j <= n; j++)
            for (int l = 0; l <= n; l++) {
                size_t id = ((size_t)i * (n + 1) + j) * (n + 1) + l;
                v[3 * id] = (double)i / n, v[3 * id + 1] = (double)j / n,
                v[3 * id + 2] = (double)l / n;
            }
#define ID(a, b, c) ((uint32_t)(((a) * (n + 1) + (b)) * (n + 1) + (c)))
    for (int d = 0; d < 3; d++)
        for (int side = 0; side <= n; side += n)
            for (int a = 0; a < n; a++)
                for (int b = 0; b < n; b++) {
                    uint32_t c[4];
                    int s[4][2] = {{a, b}, {a + 1, b}, {a + 1, b + 1}, {a, b + 1}};
                    for (int m = 0; m < 4; m++) {
                        int p[3];
                        p[d] = side, p[(d + 1) % 3] = s[m][0], p[(d + 2) % 3] = s[m][1];
                        c[m] = ID(p[0], p[1], p[2]);
                    }
                    if (!side) { /* outward: -e_d */
                        uint32_t x = c[1];
                        c[1] = c[3], c[3] = x;
                    }
                    uint32_t tri[6] = {c[0], c[1], c[2], c[0], c[2], c[3]};
                    memcpy(t + 3 * k, tri, sizeof tri);
                    k += 2;
                }
#undef ID
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    assert_coons_ok(coons_mesh_add_part(m, "cube", v, nv, t, nt, &err), &err);
    free(v);
    free(t);
    assert_true(coons_mesh_volume(m) > 0.999 && coons_mesh_volume(m) < 1.001);
    return m;
}

static void assert_same_mesh(const coons_mesh *a, const coons_mesh *b)
{
    size_t nv = coons_mesh_vertex_count(a), nt = coons_mesh_triangle_count(a);
    assert_int_equal(coons_mesh_vertex_count(b), nv);
    assert_int_equal(coons_mesh_triangle_count(b), nt);
    assert_memory_equal(coons_mesh_vertices(a), coons_mesh_vertices(b), nv * 3 * sizeof(double));
    assert_memory_equal(coons_mesh_triangles(a), coons_mesh_triangles(b),
                        nt * 3 * sizeof(uint32_t));
}

/* The error estimate (src/sample/deform.c) decides triangles without
 * evaluating them; the mesh must still be the one of measuring every
 * triangle (a triangle it accepts would have been accepted, an edge it
 * leaves would not have been split), byte for byte, and the same on 1, 2
 * and 5 threads (the cylinder). Bodies: body 2 of Bezier faces, the
 * rational cylinder (C0 knots in u: no estimate across
 * them), the B-spline volume with inner knots, body 1 of curved edges, each
 * at a tolerance the input meets (some or all triangles estimated), and the
 * cylinder and the B-spline volume also at 0.8 times the measured
 * deviation there (some triangles split). Exact images of random points of
 * the input's faces lie within the tolerance of the result (brute-force
 * distance). The input has just enough triangles for the estimate's
 * lattice (kept cheap for valgrind). */
static void test_estimate(void **state)
{
    (void)state;
    static const int bodies[] = {9, 6, 5, 3};
    coons_mesh *in = fine_cube(17);
    size_t nin = coons_mesh_triangle_count(in);
    const double *qv = coons_mesh_vertices(in);
    const uint32_t *ti = coons_mesh_triangles(in);
    double measured = 0; /* the loose run's deviation, every triangle measured */
    for (size_t k = 0; k < 2 * sizeof bodies / sizeof bodies[0]; k++) {
        /* first a tolerance the input meets, then 0.8 times its measured
         * deviation: some triangles split */
        int loose = !(k & 1), body = bodies[k / 2];
        if (!loose && body != 6 && body != 5) continue; /* (kept cheap for valgrind) */
        coons_error err = COONS_ERROR_INIT;
        coons_body *b;
        if (body == 9) { /* body 2 of Bezier faces (cheaper than tb_make_body's) */
            coons_patch *f[6];
            assert_coons_ok(tb_bspline_faces(4, f, &err), &err);
            assert_coons_ok(coons_body_new_body2(f, COONS_BLEND_CUBIC, 1e-9, &b, &err), &err);
            for (int n = 0; n < 6; n++) coons_patch_free(f[n]);
        } else {
            assert_coons_ok(tb_make_body(body, &b, &err), &err);
        }
        double lo[3], hi[3];
        coons_body_control_bbox(b, lo, hi);
        double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                           (hi[2] - lo[2]) * (hi[2] - lo[2]));
        double tol = loose ? (body == 9 ? 1.5e-3 : 2e-2) * diag : 0.8 * measured;
        coons_deform_options o = COONS_DEFORM_OPTIONS_INIT;
        o.tolerance = tol;
        coons_mesh *ref = NULL, *out = NULL;
        coons_deform_report rep = COONS_DEFORM_REPORT_INIT;
        coons__deform_estimates(2); /* every triangle measured */
        assert_coons_ok(coons_body_deform(b, in, &o, &ref, &rep, &err), &err);
        assert_int_equal(coons__deform_estimated(), 0);
        measured = rep.deviation;
        coons__deform_estimates(1);
        size_t decided = 0;
        unsigned last = body == 6 ? 5 : 1;
        for (unsigned threads = 1; threads <= last; threads += 1 + (threads == 2)) { /* 1, 2, 5 */
            o.threads = threads;
            assert_coons_ok(coons_body_deform(b, in, &o, &out, &rep, &err), &err);
            if (threads == 1) decided = coons__deform_estimated();
            assert_int_equal(coons__deform_estimated(), decided);
            assert_same_mesh(out, ref);
            if (threads < last) coons_mesh_free(out);
        }
        coons__deform_estimates(0);
        size_t nto = coons_mesh_triangle_count(out);
        print_message("%s: %zu -> %zu triangles, %u rounds, %zu decided by the estimate, "
                      "deviation %.3g of %.3g\n",
                      tb_body_label(body), nin, nto, rep.rounds, decided, rep.deviation, tol);
        if (loose) assert_true(decided > 0);
        assert_true(rep.deviation <= 0.9 * tol * (1 + 1e-6));
        assert_true(closed_oriented(out));
        if (!loose) { /* split, measured where the estimate cannot decide */
            assert_true(rep.rounds >= 1);
            assert_true(decided < nto);
        }
        /* exact images of random points of the input's faces */
        tb_rng r = {11};
        const double *x = coons_mesh_vertices(out);
        const uint32_t *to = coons_mesh_triangles(out);
        double worst = 0;
        for (int s = 0; s < 24; s++) {
            size_t t = (size_t)(tb_rand(&r) * (double)nin);
            double a = tb_rand(&r), bb = tb_rand(&r);
            if (a + bb > 1) a = 1 - a, bb = 1 - bb;
            double q[3], p[3], best = INFINITY;
            for (int d = 0; d < 3; d++)
                q[d] = (1 - a - bb) * qv[3 * ti[3 * t] + d] + a * qv[3 * ti[3 * t + 1] + d] +
                       bb * qv[3 * ti[3 * t + 2] + d];
            coons_body_eval(b, q[0], q[1], q[2], p);
            for (size_t j = 0; j < nto; j++) {
                const double *A = x + 3 * to[3 * j], *B = x + 3 * to[3 * j + 1],
                             *C = x + 3 * to[3 * j + 2];
                int far = 0; /* outside the triangle's box grown by the best so far */
                for (int d = 0; d < 3 && !far; d++)
                    far = p[d] < fmin(A[d], fmin(B[d], C[d])) - best ||
                          p[d] > fmax(A[d], fmax(B[d], C[d])) + best;
                if (!far) best = fmin(best, tri_dist(p, A, B, C));
            }
            worst = fmax(worst, best);
        }
        print_message("  worst distance of 24 exact image points %.3g\n", worst);
        assert_true(worst <= tol);
        coons_mesh_free(out);
        coons_mesh_free(ref);
        coons_body_free(b);
    }
    coons_mesh_free(in);
}

/* Every allocation failing in turn with the estimate's lattice built (a
 * fine input through body 0 with cubic blends): COONS_E_NOMEM, nothing
 * leaked, until the call succeeds with triangles estimated. */
static void test_estimate_alloc(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_body *b;
    assert_coons_ok(coons_body_new_body0(tb_hex()[0], COONS_BLEND_CUBIC, &b, &err), &err);
    coons_mesh *in = fine_cube(17), *out = NULL;
    coons__deform_estimates(1);
    int done = 0;
    for (long n = 0; !done && n < 1000; n++) {
        coons_test_fail_after(n);
        coons_status rc = coons_body_deform_mesh(b, in, NULL, NULL, 1e-1, 0, &out, &err);
        coons_mesh_free(out);
        out = NULL;
        assert_int_equal(coons_test_live_allocs(), 0);
        coons_test_fail_after(-1);
        if (rc == COONS_OK) {
            assert_true(coons__deform_estimated() > 0);
            done = 1;
        } else {
            assert_int_equal(rc, COONS_E_NOMEM);
        }
    }
    coons__deform_estimates(0);
    assert_true(done);
    coons_mesh_free(in);
    coons_body_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_affine_exact),
        cmocka_unit_test(test_curved_body2),
        cmocka_unit_test(test_report),
        cmocka_unit_test(test_options_progress),
        cmocka_unit_test(test_outside_and_invalid),
        cmocka_unit_test(test_budget_and_alloc),
        cmocka_unit_test(test_estimate),
        cmocka_unit_test(test_estimate_alloc),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
