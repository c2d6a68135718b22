/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Isoparametric surfaces (src/mesh/iso.c), vertex parameters and part
 * display in the mesh container, the `%` of background parts in the SCAD
 * writer. Points are checked against coons_body_eval() at the stored
 * parameters, orientation against the body's Jacobian, shape against
 * coons_mesh_check() and an edge count written here, the boundary faces
 * against coons_model_sample()'s own mesh. */
#define _XOPEN_SOURCE 700
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "body_fixtures.h"
#include "iso_parse.h"
#include "io_test_util.h"
#include "test_util.h"

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Checks part `part` of m as the surface direction = value of b: every
 * vertex is F at its parameters (1e-12 relative), lies at the value, no
 * triangle repeats a vertex, and each normal points along +F_direction for
 * a right-handed body (the Jacobian at the triangle's parameter centroid).
 * Returns the triangle count. */
static size_t check_surface(const coons_body *b, const coons_mesh *m, size_t part, int d,
                            double value)
{
    size_t tf, tc, vf, vc;
    coons_mesh_part_range(m, part, &tf, &tc, &vf, &vc);
    const double *xyz = coons_mesh_vertices(m), *uvw = coons_mesh_vertex_parameters(m);
    const uint32_t *tri = coons_mesh_triangles(m);
    assert_non_null(uvw);
    assert_true(coons_mesh_part_has_parameters(m, part));
    for (size_t v = vf; v < vf + vc; v++) {
        const double *q = uvw + 3 * v;
        assert_true(q[d] == value);
        for (int k = 0; k < 3; k++) assert_true(q[k] >= 0.0 && q[k] <= 1.0);
        double x[3];
        coons_body_eval(b, q[0], q[1], q[2], x);
        for (int k = 0; k < 3; k++)
            if (fabs(x[k] - xyz[3 * v + k]) > 1e-12 * (1.0 + fabs(x[k])))
                fail_msg("vertex %zu at (%g,%g,%g): %.17g != %.17g", v, q[0], q[1], q[2],
                         xyz[3 * v + k], x[k]);
    }
    for (size_t t = tf; t < tf + tc; t++) {
        const uint32_t *c = tri + 3 * t;
        assert_true(c[0] != c[1] && c[1] != c[2] && c[2] != c[0]);
        for (int k = 0; k < 3; k++) assert_true(c[k] >= vf && c[k] < vf + vc);
        double e1[3], e2[3], n[3], pc[3] = {0, 0, 0}, x[3], jac[3][3];
        for (int k = 0; k < 3; k++) {
            e1[k] = xyz[3 * c[1] + k] - xyz[3 * c[0] + k];
            e2[k] = xyz[3 * c[2] + k] - xyz[3 * c[0] + k];
            for (int r = 0; r < 3; r++) pc[k] += uvw[3 * c[r] + k] / 3.0;
        }
        /* a triangle across a glued seam (the cylinder's u = 0 ~ 1) has
         * corners at both ends: its parameter centroid is elsewhere */
        int seam = 0;
        for (int k = 0; k < 3; k++)
            for (int r = 0; r < 3; r++)
                if (fabs(uvw[3 * c[r] + k] - uvw[3 * c[(r + 1) % 3] + k]) > 0.5) seam = 1;
        if (seam) continue;
        cross(e1, e2, n);
        double det = coons_body_eval_jacobian(b, pc[0], pc[1], pc[2], x, jac);
        double along = n[0] * jac[0][d] + n[1] * jac[1][d] + n[2] * jac[2][d];
        if (!(along * (det > 0 ? 1 : -1) > 0))
            fail_msg("triangle %zu of %c=%g: normal . F_%c = %g, det J %g", t, "uvw"[d], value,
                     "uvw"[d], along, det);
    }
    return tc;
}

/* Given every fixture body, when its u, v, w = 0, 0.3, 1 surfaces are made,
 * then each vertex is the body's point at its stored parameters, at the
 * requested value, the normals point along the parameter, and the free
 * directions use exactly the boundary sampler's lattice. */
static void test_points_parameters_orientation(void **state)
{
    (void)state;
    static const int bodies[] = {0, 3, 9, 4, 5, 6, 7};
    static const double values[] = {0.0, 0.3, 1.0};
    for (size_t i = 0; i < sizeof bodies / sizeof bodies[0]; i++) {
        coons_body *b;
        coons_error err = COONS_ERROR_INIT;
        assert_coons_ok(tb_make_body(bodies[i], &b, &err), &err);
        coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
        o.tolerance = 5e-3;
        coons_mesh *boundary;
        assert_coons_ok(coons_body_sample(b, &o, NULL, &boundary, &err), &err);
        size_t lat[3];
        assert_true(coons_mesh_part_sampling(boundary, 0, NULL, NULL, lat));
        coons_mesh_free(boundary);
        coons_mesh *m;
        assert_coons_ok(coons_mesh_new(&m, &err), &err);
        size_t part = 0;
        for (int d = 0; d < 3; d++)
            for (size_t k = 0; k < 3; k++, part++) {
                assert_coons_ok(coons_body_iso_surface(b, d, values[k], &o, NULL, m, &err), &err);
                assert_int_equal(coons_mesh_part_count(m), part + 1);
                char want[32];
                snprintf(want, sizeof want, "%c=%s", "uvw"[d],
                         k == 0 ? "0" : k == 1 ? "0.3" : "1");
                assert_string_equal(coons_mesh_part_name(m, part), want);
                size_t tc = check_surface(b, m, part, d, values[k]);
                /* the cylinder's v = 0 is its axis: a segment, no triangles */
                assert_true(tc > 0 || (bodies[i] == 6 && d == 1 && k == 0));
                /* the lattice: distinct values of a free direction */
                size_t vf, vc;
                coons_mesh_part_range(m, part, NULL, NULL, &vf, &vc);
                const double *uvw = coons_mesh_vertex_parameters(m);
                int a = (d + 1) % 3;
                double *vals = malloc(vc * sizeof *vals);
                for (size_t v = 0; v < vc; v++) vals[v] = uvw[3 * (vf + v) + a];
                size_t distinct = 0;
                for (size_t v = 0; v < vc; v++) {
                    size_t w = 0;
                    while (w < v && vals[w] != vals[v]) w++;
                    distinct += w == v;
                }
                free(vals);
                /* collapsed lines may hide lattice values, never add any */
                assert_true(distinct <= lat[a] + 1);
                if (bodies[i] != 6) assert_int_equal(distinct, lat[a] + 1);
            }
        /* the parameters of earlier parts survive later appends */
        check_surface(b, m, 0, 0, 0.0);
        coons_mesh_free(m);
        coons_body_free(b);
    }
}

/* Sorted bit patterns of the 9 coordinates of a triangle's corners (in
 * rotation-free order): equal keys are the same triangle, either winding. */
typedef struct tri_key {
    double p[3][3];
    size_t t; /* the triangle's index (not part of the key) */
} tri_key;

static int cmp_pt(const void *x, const void *y) { return memcmp(x, y, 3 * sizeof(double)); }
static int cmp_key(const void *x, const void *y)
{
    return memcmp(((const tri_key *)x)->p, ((const tri_key *)y)->p, sizeof(double[3][3]));
}

static tri_key key_of(const double *xyz, const uint32_t *t)
{
    tri_key k;
    for (int r = 0; r < 3; r++) memcpy(k.p[r], xyz + 3 * t[r], sizeof k.p[r]);
    qsort(k.p, 3, sizeof k.p[0], cmp_pt);
    k.t = 0;
    return k;
}

/* Given a model of a curved body1 and a body2, when the u=0 and w=1
 * surfaces are made with the boundary, then the boundary part is
 * coons_model_sample()'s mesh bit for bit, its parameters place its
 * vertices on the body, and the surface at 0 or 1 is exactly the set of
 * boundary triangles on that face, wound the other way where the outward
 * normal is -F_u. */
static void test_faces_are_the_boundary(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    for (int which = 3; which <= 9; which += 6) {
        coons_body *b;
        assert_coons_ok(tb_make_body(which, &b, &err), &err);
        coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
        o.tolerance = 4e-3;
        coons_mesh *ref, *m;
        assert_coons_ok(coons_body_sample(b, &o, "b", &ref, &err), &err);
        assert_coons_ok(coons_mesh_new(&m, &err), &err);
        assert_coons_ok(coons_body_iso_surface(b, 0, 0.0, &o, "b.u=0", m, &err), &err);
        assert_coons_ok(coons_body_iso_surface(b, 2, 1.0, &o, "b.w=1", m, &err), &err);
        const double *rx = coons_mesh_vertices(ref);
        const uint32_t *rt = coons_mesh_triangles(ref);
        size_t rn = coons_mesh_triangle_count(ref);
        tri_key *rk = malloc(rn * sizeof *rk);
        for (size_t t = 0; t < rn; t++) {
            rk[t] = key_of(rx, rt + 3 * t);
            rk[t].t = t;
        }
        qsort(rk, rn, sizeof *rk, cmp_key);
        const double *x = coons_mesh_vertices(m);
        const uint32_t *tr = coons_mesh_triangles(m);
        for (size_t part = 0; part < 2; part++) {
            size_t tf, tc;
            coons_mesh_part_range(m, part, &tf, &tc, NULL, NULL);
            assert_true(tc > 0);
            for (size_t t = tf; t < tf + tc; t++) {
                tri_key k = key_of(x, tr + 3 * t);
                tri_key *hit = bsearch(&k, rk, rn, sizeof *rk, cmp_key);
                if (!hit) fail_msg("triangle %zu of part %zu is not a boundary triangle", t, part);
                /* outward at u = 0 is against F_u, at w = 1 along F_w; the
                 * surface's normal is along F_u, F_w times sign(det J) */
                double n1[3], n2[3], e1[3], e2[3], x0[3], jac[3][3];
                const uint32_t *a = tr + 3 * t, *c = rt + 3 * hit->t;
                for (int r = 0; r < 3; r++) {
                    e1[r] = x[3 * a[1] + r] - x[3 * a[0] + r];
                    e2[r] = x[3 * a[2] + r] - x[3 * a[0] + r];
                }
                cross(e1, e2, n1);
                for (int r = 0; r < 3; r++) {
                    e1[r] = rx[3 * c[1] + r] - rx[3 * c[0] + r];
                    e2[r] = rx[3 * c[2] + r] - rx[3 * c[0] + r];
                }
                cross(e1, e2, n2);
                double det = coons_body_eval_jacobian(b, 0.5, 0.5, 0.5, x0, jac);
                double dot = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2];
                assert_true(dot * (det > 0 ? 1 : -1) * (part == 0 ? -1 : 1) > 0);
            }
        }
        /* counts: the boundary triangles whose corners all lie on the face */
        size_t on[2] = {0, 0};
        for (size_t t = 0; t < rn; t++) {
            int all[2] = {1, 1};
            for (int r = 0; r < 3; r++) {
                const double *p = rx + 3 * rt[3 * t + r];
                for (int f = 0; f < 2; f++) {
                    size_t tf, tc, vf, vc, v;
                    coons_mesh_part_range(m, (size_t)f, &tf, &tc, &vf, &vc);
                    for (v = vf; v < vf + vc; v++)
                        if (!memcmp(p, x + 3 * v, 3 * sizeof(double))) break;
                    if (v == vf + vc) all[f] = 0;
                }
            }
            on[0] += all[0];
            on[1] += all[1];
        }
        for (size_t part = 0; part < 2; part++) {
            size_t tc;
            coons_mesh_part_range(m, part, NULL, &tc, NULL, NULL);
            assert_int_equal(on[part], tc);
        }
        check_surface(b, m, 0, 0, 0.0);
        check_surface(b, m, 1, 2, 1.0);
        free(rk);
        coons_mesh_free(ref);
        coons_mesh_free(m);
        coons_body_free(b);
    }
    /* the model path: boundary parts equal coons_model_sample()'s bit for bit */
    static const char *json =
        "{\"coons\": 1, \"tolerance\": 0.01, \"operation\": \"none\", \"bodies\": ["
        "{\"type\": \"bezier-volume\", \"name\": \"blob\", \"points\": "
        "[[[[0,0,0],[0,0.2,1]],[[0,1,0],[0.3,1,1]]],"
        "[[[1,0,0.2],[1.2,0,1.5]],[[1,1,0],[1,1.4,1]]]]},"
        "{\"type\": \"body0\", \"corners\": [[3,0,0],[3,0,1],[3,1,0],[3,1,1],"
        "[4,0,0],[4,0,1],[4,1,0],[4,1.5,1]]}]}";
    coons_model *model;
    assert_coons_ok(coons_model_load_memory(json, strlen(json), NULL, NULL, &model, &err), &err);
    coons_mesh *ref, *m;
    assert_coons_ok(coons_model_sample(model, NULL, &ref, &err), &err);
    coons_iso_request req[2] = {{1, 0.5}, {2, 0.0}};
    assert_coons_ok(coons_model_iso_surfaces(model, req, 2, NULL, COONS_ISO_WITH_BOUNDARY, &m,
                                             &err),
                    &err);
    static const char *const names[6] = {"blob", "blob.v=0.5", "blob.w=0",
                                         "body1", "body1.v=0.5", "body1.w=0"};
    assert_int_equal(coons_mesh_part_count(m), 6);
    const double *uvw = coons_mesh_vertex_parameters(m);
    assert_non_null(uvw);
    for (size_t p = 0; p < 6; p++) {
        assert_string_equal(coons_mesh_part_name(m, p), names[p]);
        const coons_body *b = coons_model_body(model, p / 3);
        if (p % 3) {
            check_surface(b, m, p, req[p % 3 - 1].direction, req[p % 3 - 1].value);
            continue;
        }
        size_t tf, tc, vf, vc, rtf, rtc, rvf, rvc;
        coons_mesh_part_range(m, p, &tf, &tc, &vf, &vc);
        coons_mesh_part_range(ref, p / 3, &rtf, &rtc, &rvf, &rvc);
        assert_int_equal(tc, rtc);
        assert_int_equal(vc, rvc);
        assert_memory_equal(coons_mesh_vertices(m) + 3 * vf, coons_mesh_vertices(ref) + 3 * rvf,
                            3 * vc * sizeof(double));
        for (size_t t = 0; t < 3 * tc; t++)
            assert_int_equal(coons_mesh_triangles(m)[3 * tf + t] - vf,
                             coons_mesh_triangles(ref)[3 * rtf + t] - rvf);
        for (size_t v = vf; v < vf + vc; v++) {
            const double *q = uvw + 3 * v;
            double x[3];
            coons_body_eval(b, q[0], q[1], q[2], x);
            assert_vec3_near(x, coons_mesh_vertices(m) + 3 * v, 1e-12);
            int on_face = 0;
            for (int k = 0; k < 3; k++) on_face |= q[k] == 0.0 || q[k] == 1.0;
            assert_true(on_face);
        }
    }
    coons_mesh_free(m);
    coons_mesh_free(ref);
    coons_model_free(model);
}

/* Edge use counts of one part: boundary edges (one triangle), and whether
 * every interior edge has two triangles running it opposite ways. */
static void edge_counts(const coons_mesh *m, size_t part, size_t *boundary, int *manifold)
{
    size_t tf, tc;
    coons_mesh_part_range(m, part, &tf, &tc, NULL, NULL);
    const uint32_t *t = coons_mesh_triangles(m) + 3 * tf;
    *boundary = 0;
    *manifold = 1;
    for (size_t i = 0; i < 3 * tc; i++) {
        uint32_t a = t[i], b = t[i / 3 * 3 + (i % 3 + 1) % 3];
        size_t same = 0, rev = 0;
        for (size_t j = 0; j < 3 * tc; j++) {
            uint32_t c = t[j], d = t[j / 3 * 3 + (j % 3 + 1) % 3];
            same += c == a && d == b;
            rev += c == b && d == a;
        }
        if (same != 1 || rev > 1) *manifold = 0;
        if (!rev) ++*boundary;
    }
}

/* Given a pyramid (face u0 collapsed to an apex) and the NURBS cylinder
 * (v = 0 is the axis, u closes on itself), when surfaces through the
 * collapse are made, then degenerate triangles are gone, the surface is one
 * manifold disk (Euler characteristic 1, one boundary loop), and a surface
 * that is all apex is an empty part. */
static void test_collapsed(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    double c[8][3];
    for (int n = 0; n < 8; n++) {
        int i = n >> 2, j = (n >> 1) & 1, k = n & 1;
        c[n][0] = i ? j : 0.5;
        c[n][1] = i ? k : 0.5;
        c[n][2] = i ? 0 : 1;
    }
    coons_body *pyr;
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &pyr, &err), &err);
    coons_body *cyl;
    tb_nurbs_cylinder(1.5, 2.0, &cyl);
    struct {
        coons_body *b;
        int d;
        double value;
        int closed; /* 1: the u seam is glued, the boundary is the rim */
    } cases[] = {{pyr, 2, 0.5, 0}, {pyr, 1, 0.25, 0}, {cyl, 2, 0.5, 1}, {cyl, 2, 0.0, 1}};
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.tolerance = 1e-2;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        coons_mesh *m;
        assert_coons_ok(coons_mesh_new(&m, &err), &err);
        assert_coons_ok(coons_body_iso_surface(cases[i].b, cases[i].d, cases[i].value, &o, NULL,
                                               m, &err),
                        &err);
        check_surface(cases[i].b, m, 0, cases[i].d, cases[i].value);
        coons_mesh_report r = COONS_MESH_REPORT_INIT;
        assert_coons_ok(coons_mesh_check(m, &r, &err), &err);
        assert_int_equal(r.degenerate_triangles, 0);
        assert_int_equal(r.nonmanifold_edges, 0);
        assert_int_equal(r.nonmanifold_vertices, 0);
        assert_int_equal(r.misoriented_edges, 0);
        assert_int_equal(r.unused_vertices, 0);
        assert_int_equal(r.shells, 1);
        assert_int_equal(r.euler, 1);
        size_t boundary;
        int manifold;
        edge_counts(m, 0, &boundary, &manifold);
        assert_true(manifold);
        assert_int_equal(boundary, r.boundary_edges);
        /* the collapse dropped triangles: fewer than two per lattice cell */
        size_t lat[3];
        coons_mesh *s;
        assert_coons_ok(coons_body_sample(cases[i].b, &o, NULL, &s, &err), &err);
        coons_mesh_part_sampling(s, 0, NULL, NULL, lat);
        coons_mesh_free(s);
        int a = (cases[i].d + 1) % 3, bb = (cases[i].d + 2) % 3;
        assert_true(coons_mesh_triangle_count(m) < 2 * lat[a] * lat[bb]);
        /* the boundary loop: the cylinder's rim (u intervals); the
         * pyramid's square section minus its collapsed u = 0 side */
        size_t want = cases[i].closed ? lat[0] : lat[(cases[i].d + (cases[i].d == 2 ? 2 : 1)) % 3]
                                                 + 2 * lat[0];
        assert_int_equal(r.boundary_edges, want);
        coons_mesh_free(m);
    }
    /* u = 0 of the pyramid is the apex: an empty part, no error */
    coons_mesh *m;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    assert_coons_ok(coons_body_iso_surface(pyr, 0, 0.0, &o, "apex", m, &err), &err);
    assert_int_equal(coons_mesh_part_count(m), 1);
    assert_int_equal(coons_mesh_triangle_count(m), 0);
    assert_int_equal(coons_mesh_vertex_count(m), 0);
    coons_mesh_free(m);
    coons_body_free(pyr);
    coons_body_free(cyl);
}

/* Given a mesh with a part, when a request is out of range (1.5, -0.1,
 * NaN, direction 3, -1), then the error names it and the mesh is
 * unchanged; the model call leaves *out NULL. */
static void test_errors(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_body *b;
    assert_coons_ok(tb_make_body(0, &b, &err), &err);
    coons_mesh *m;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    assert_coons_ok(coons_body_iso_surface(b, 1, 0.5, NULL, "ok", m, &err), &err);
    size_t nv = coons_mesh_vertex_count(m), nt = coons_mesh_triangle_count(m);
    const double *uvw0 = coons_mesh_vertex_parameters(m);
    double first[3];
    memcpy(first, uvw0, sizeof first);
    struct {
        int d;
        double v;
        int code;
        const char *msg;
    } bad[] = {{0, 1.5, COONS_E_DOMAIN, "u=1.5"}, {1, -0.1, COONS_E_DOMAIN, "v=-0.1"},
               {2, NAN, COONS_E_DOMAIN, "w=nan"}, {3, 0.5, COONS_E_INVALID, "direction 3"},
               {-1, 0.5, COONS_E_INVALID, "direction -1"}, {0, INFINITY, COONS_E_DOMAIN, "u=inf"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        coons_error e = COONS_ERROR_INIT;
        assert_int_equal(coons_body_iso_surface(b, bad[i].d, bad[i].v, NULL, NULL, m, &e),
                         bad[i].code);
        assert_int_equal(e.code, bad[i].code);
        if (!strstr(e.message, bad[i].msg)) fail_msg("'%s' lacks '%s'", e.message, bad[i].msg);
        assert_int_equal(coons_mesh_part_count(m), 1);
        assert_int_equal(coons_mesh_vertex_count(m), nv);
        assert_int_equal(coons_mesh_triangle_count(m), nt);
        assert_memory_equal(coons_mesh_vertex_parameters(m), first, sizeof first);
        coons_iso_request req = {bad[i].d, bad[i].v};
        coons_mesh *out = (coons_mesh *)1;
        coons_model *model;
        static const char *json = "{\"coons\": 1, \"bodies\": [{\"type\": \"body0\", "
                                  "\"corners\": [[0,0,0],[0,0,1],[0,1,0],[0,1,1],"
                                  "[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]}";
        assert_coons_ok(coons_model_load_memory(json, strlen(json), NULL, NULL, &model, &err),
                        &err);
        assert_int_equal(coons_model_iso_surfaces(model, &req, 1, NULL, 0, &out, &e),
                         bad[i].code);
        assert_null(out);
        coons_model_free(model);
    }
    /* bad options */
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.version = 99;
    assert_int_equal(coons_body_iso_surface(b, 0, 0.5, &o, NULL, m, &err), COONS_E_INVALID);
    /* a triangle budget too small for the boundary lattice (6 x 100 cells
     * x 2 = 1200 triangles): refused, the mesh unchanged */
    coons_sample_options small = COONS_SAMPLE_OPTIONS_INIT;
    small.resolution = 10;
    small.max_triangles = 1200;
    assert_coons_ok(coons_body_iso_surface(b, 0, 0.5, &small, NULL, m, &err), &err);
    assert_int_equal(coons_mesh_triangle_count(m), nt + 200);
    small.max_triangles = 1199;
    assert_int_equal(coons_body_iso_surface(b, 0, 0.5, &small, NULL, m, &err), COONS_E_LIMIT);
    assert_int_equal(coons_mesh_part_count(m), 2);
    assert_int_equal(coons_mesh_triangle_count(m), nt + 200);
    coons_mesh_free(m);
    coons_body_free(b);
}

/* coons2stl's option parser (tools/coons2stl/iso_parse.c): lists of values, the directions, and what it refuses. */
static void test_parse(void **state)
{
    (void)state;
    coons_iso_request r[4];
    size_t n = 0;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(cli_iso_parse("u=0.25,0.5", r, 4, &n, &err), &err);
    assert_coons_ok(cli_iso_parse("w=1e-1", r, 4, &n, &err), &err);
    assert_int_equal(n, 3);
    assert_int_equal(r[0].direction, 0);
    assert_true(r[0].value == 0.25 && r[1].value == 0.5);
    assert_int_equal(r[2].direction, 2);
    assert_true(r[2].value == 0.1);
    static const char *const bad[] = {"x=0.5", "u", "u=", "u0.5", "u=0.5,", "u=,0.5",
                                      "u=0.5;0.6", "u=abc", "u=0.5,2", "v=nan", "w=-1"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        coons_error e = COONS_ERROR_INIT;
        int rc = cli_iso_parse(bad[i], r, 4, &n, &e);
        if (rc != COONS_E_INVALID && rc != COONS_E_DOMAIN) fail_msg("'%s' -> %d", bad[i], rc);
        assert_int_equal(n, 3);
        if (!strstr(e.message, bad[i])) fail_msg("'%s' not quoted in '%s'", bad[i], e.message);
    }
    assert_int_equal(cli_iso_parse("u=0.5,2", r, 4, &n, &err), COONS_E_DOMAIN);
    assert_int_equal(cli_iso_parse("v=0.1,0.2", r, 4, &n, &err), COONS_E_LIMIT);
    assert_int_equal(n, 3);
    char name[COONS_ISO_NAME_MAX];
    coons_iso_surface_name("seat", 1, 0.1, name, sizeof name);
    assert_string_equal(name, "seat.v=0.1");
    coons_iso_surface_name(NULL, 2, 1.0 / 3.0, name, sizeof name);
    assert_string_equal(name, "w=0.3333333333333333");
    coons_iso_surface_name("b", 0, 0.0, name, 4);
    assert_string_equal(name, "b.u");
}

/* Parts with and without parameters: the accessor is all or nothing. */
static void test_parameters_all_or_nothing(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    coons_body *b;
    assert_coons_ok(tb_make_body(4, &b, &err), &err);
    static const double tri_xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const uint32_t tri[3] = {0, 1, 2};
    for (int order = 0; order < 2; order++) {
        coons_mesh *m;
        assert_coons_ok(coons_mesh_new(&m, &err), &err);
        assert_null(coons_mesh_vertex_parameters(m));
        if (order) assert_coons_ok(coons_mesh_add_part(m, "t", tri_xyz, 3, tri, 1, &err), &err);
        assert_coons_ok(coons_body_iso_surface(b, 2, 0.5, NULL, NULL, m, &err), &err);
        if (order) {
            assert_null(coons_mesh_vertex_parameters(m));
        } else {
            assert_non_null(coons_mesh_vertex_parameters(m));
            assert_coons_ok(coons_mesh_add_part(m, "t", tri_xyz, 3, tri, 1, &err), &err);
            assert_null(coons_mesh_vertex_parameters(m));
        }
        assert_int_equal(coons_mesh_part_has_parameters(m, 0), !order);
        assert_int_equal(coons_mesh_part_has_parameters(m, 1), order);
        assert_int_equal(coons_mesh_part_has_parameters(m, 2), 0);
        coons_mesh_free(m);
    }
    /* sampled boundaries carry none */
    coons_mesh *s;
    assert_coons_ok(coons_body_sample(b, NULL, NULL, &s, &err), &err);
    assert_null(coons_mesh_vertex_parameters(s));
    coons_mesh_free(s);
    coons_body_free(b);
}

/* Given a model's surfaces with the boundary, when written as OpenSCAD with
 * the boundary (part 0) in coons_write_options.background, then the
 * boundary module is called with `%` and the surface modules are plain
 * calls with valid identifiers; the same mesh with no background list
 * writes no `%`; a part that does not exist, or a count without a list, is
 * refused and nothing is written. */
static void test_scad_background(void **state)
{
    (void)state;
    coons_error err = COONS_ERROR_INIT;
    static const char *json = "{\"coons\": 1, \"bodies\": [{\"type\": \"body0\", \"name\": "
                              "\"box\", \"corners\": [[0,0,0],[0,0,1],[0,1,0],[0,1,1],"
                              "[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]}";
    coons_model *model;
    assert_coons_ok(coons_model_load_memory(json, strlen(json), NULL, NULL, &model, &err), &err);
    coons_iso_request req[2] = {{0, 0.25}, {2, 0.5}};
    coons_mesh *m;
    assert_coons_ok(coons_model_iso_surfaces(model, req, 2, NULL, COONS_ISO_WITH_BOUNDARY, &m,
                                             &err),
                    &err);
    char dir[64], path[128];
    io_tmpdir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/iso.scad", dir);
    coons_write_options wo = COONS_WRITE_OPTIONS_INIT;
    wo.name = "iso";
    const size_t bad_bg[2] = {0, 3};
    wo.background = bad_bg;
    wo.nbackground = 2;
    assert_int_equal(coons_mesh_write(m, path, COONS_FORMAT_AUTO, &wo, &err), COONS_E_INVALID);
    assert_non_null(strstr(err.message, "background part 3"));
    wo.background = NULL;
    assert_int_equal(coons_mesh_write(m, path, COONS_FORMAT_AUTO, &wo, &err), COONS_E_INVALID);
    assert_null(io_read_file(path, NULL));
    const size_t bg[1] = {0};
    wo.background = bg;
    wo.nbackground = 1;
    assert_coons_ok(coons_mesh_write(m, path, COONS_FORMAT_AUTO, &wo, &err), &err);
    size_t len;
    char *text = io_read_file(path, &len);
    assert_non_null(text);
    /* Module names carry the model's name: MODEL_PART. */
    assert_non_null(strstr(text, "module iso_box() {\n"));
    assert_non_null(strstr(text, "module iso_box_u_0_25() {\n"));
    assert_non_null(strstr(text, "module iso_box_w_0_5() {\n"));
    assert_non_null(strstr(text, "\nmodule iso() {\n  %iso_box();\n  iso_box_u_0_25();\n"
                                 "  iso_box_w_0_5();\n}\n"));
    free(text);
    wo.background = NULL;
    wo.nbackground = 0;
    assert_coons_ok(coons_mesh_write(m, path, COONS_FORMAT_AUTO, &wo, &err), &err);
    text = io_read_file(path, &len);
    assert_null(strchr(text, '%'));
    free(text);
    /* VTU takes triangle meshes; legacy VTK still refuses them */
    snprintf(path, sizeof path, "%s/iso.vtu", dir);
    assert_coons_ok(coons_mesh_write(m, path, COONS_FORMAT_AUTO, &wo, &err), &err);
    text = io_read_file(path, &len);
    assert_non_null(strstr(text, "<DataArray type=\"Float64\" Name=\"u\" format=\"ascii\">"));
    free(text);
    snprintf(path, sizeof path, "%s/iso.vtk", dir);
    assert_int_equal(coons_mesh_write(m, path, COONS_FORMAT_AUTO, &wo, &err), COONS_E_INVALID);
    assert_non_null(strstr(err.message, "volume meshes"));
    coons_mesh_free(m);
    coons_model_free(model);
    io_rmdir(dir);
}

/* Allocation failures anywhere give COONS_E_NOMEM, leave the mesh as it
 * was and leak nothing. */
static void test_alloc_failures(void **state)
{
    (void)state;
    coons_body *b;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(tb_make_body(3, &b, &err), &err);
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.tolerance = 2e-2;
    coons_mesh *m;
    assert_coons_ok(coons_mesh_new(&m, &err), &err);
    assert_coons_ok(coons_body_iso_surface(b, 0, 0.5, &o, NULL, m, &err), &err);
    size_t nv = coons_mesh_vertex_count(m);
    for (long n = 0;; n++) {
        coons_test_fail_after(n);
        int rc = coons_body_iso_surface(b, 1, 0.5, &o, NULL, m, &err);
        long live = coons_test_live_allocs();
        coons_test_fail_after(-1);
        if (rc == COONS_OK) {
            assert_int_equal(coons_mesh_part_count(m), 2);
            break;
        }
        assert_int_equal(rc, COONS_E_NOMEM);
        assert_int_equal(live, 0);
        assert_int_equal(coons_mesh_part_count(m), 1);
        assert_int_equal(coons_mesh_vertex_count(m), nv);
        assert_true(n < 10000);
    }
    coons_mesh_free(m);
    static const char *json = "{\"coons\": 1, \"tolerance\": 0.05, \"bodies\": ["
                              "{\"type\": \"body0\", \"corners\": [[0,0,0],[0,0,1],[0,1,0],"
                              "[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]}";
    coons_model *model;
    assert_coons_ok(coons_model_load_memory(json, strlen(json), NULL, NULL, &model, &err), &err);
    coons_iso_request req[2] = {{0, 0.5}, {1, 0.5}};
    for (long n = 0;; n++) {
        coons_mesh *out = NULL;
        coons_test_fail_after(n);
        int rc = coons_model_iso_surfaces(model, req, 2, NULL, COONS_ISO_WITH_BOUNDARY, &out, &err);
        long live = coons_test_live_allocs();
        coons_test_fail_after(-1);
        if (rc == COONS_OK) {
            assert_int_equal(coons_mesh_part_count(out), 3);
            coons_mesh_free(out);
            break;
        }
        assert_int_equal(rc, COONS_E_NOMEM);
        assert_int_equal(live, 0);
        assert_null(out);
        assert_true(n < 10000);
    }
    coons_model_free(model);
    coons_body_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_points_parameters_orientation),
        cmocka_unit_test(test_faces_are_the_boundary),
        cmocka_unit_test(test_collapsed),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_parse),
        cmocka_unit_test(test_parameters_all_or_nothing),
        cmocka_unit_test(test_scad_background),
        cmocka_unit_test(test_alloc_failures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
