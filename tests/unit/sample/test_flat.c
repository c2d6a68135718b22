/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Flat faces meshed from their boundary polygon (src/mesh/flat.c).
 * The polygon mesher is checked on its own (white box, through the static
 * library) against properties computed here: counter-clockwise triangles,
 * every polygon edge used once, every other edge twice in opposite
 * directions, areas summing to the shoelace area, m - 2 + 2s triangles for
 * m boundary and s Steiner points (Euler's formula for a disc), Steiner
 * points strictly inside, smallest angle above the bound. Bodies are
 * checked through the public API: exact volume and area of boxes and
 * parallelepipeds, every triangle in a face plane, per-face areas, a closed
 * oriented shell, and a twisted face keeping its lattice. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "body_fixtures.h"
#include "delaunay.h"
#include "flat.h"
#include "test_util.h"

#define PI 3.14159265358979323846

/* The bound the tests hold the mesher to: the refinement aims at
 * COONS__FLAT_MIN_ANGLE (20 degrees) and reaches it where the boundary
 * allows; near polygon corners and spacing jumps a little less. */
#define ANGLE_BOUND 18.0

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : (x > y);
}

static double tri_min_angle(const double *a, const double *b, const double *c, int dim)
{
    const double *p[3] = {a, b, c};
    double best = 180;
    for (int k = 0; k < 3; k++) {
        double u[3] = {0, 0, 0}, v[3] = {0, 0, 0};
        for (int d = 0; d < dim; d++) {
            u[d] = p[(k + 1) % 3][d] - p[k][d];
            v[d] = p[(k + 2) % 3][d] - p[k][d];
        }
        double uv = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
        double uu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        double vv = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        best = fmin(best, acos(fmax(-1, fmin(1, uv / (uu * vv)))) * 180 / PI);
    }
    return best;
}

/* Winding number of polygon xy (m points) around p: 1 inside (ccw). */
static int winding(const double *xy, size_t m, const double p[2])
{
    int w = 0;
    for (size_t i = 0; i < m; i++) {
        const double *a = xy + 2 * i, *b = xy + 2 * ((i + 1) % m);
        double o = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
        if (a[1] <= p[1] && b[1] > p[1] && o > 0) w++;
        if (a[1] > p[1] && b[1] <= p[1] && o < 0) w--;
    }
    return w;
}

/* Meshes the polygon and checks it; returns the triangle count, and the
 * smallest angle in *min_angle. */
static size_t check_polygon(const double *xy, size_t m, double *min_angle)
{
    double *pts = NULL;
    uint32_t *tri = NULL;
    size_t ns = 0, nt = 0;
    int ok = 0;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons__polygon_mesh(xy, m, COONS__FLAT_MIN_ANGLE, &pts, &ns, &tri, &nt,
                                        &ok, &err),
                    &err);
    assert_true(ok);
    size_t np = m + ns;
    double *all = malloc(2 * np * sizeof *all);
    memcpy(all, xy, 2 * m * sizeof *all);
    if (ns) memcpy(all + 2 * m, pts, 2 * ns * sizeof *all);
    for (size_t i = 0; i < ns; i++) assert_int_equal(winding(xy, m, pts + 2 * i), 1);
    /* Euler: a triangulated disc with m boundary and s inner vertices */
    assert_int_equal(nt, m - 2 + 2 * ns);
    double area = 0, shoelace = 0, amin = 180;
    uint64_t *e = malloc(3 * nt * sizeof *e);
    for (size_t t = 0; t < nt; t++) {
        const double *a = all + 2 * tri[3 * t], *b = all + 2 * tri[3 * t + 1],
                     *c = all + 2 * tri[3 * t + 2];
        for (int k = 0; k < 3; k++) assert_true(tri[3 * t + k] < np);
        double o = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        assert_true(o > 0);
        area += o / 2;
        amin = fmin(amin, tri_min_angle(a, b, c, 2));
        for (int k = 0; k < 3; k++)
            e[3 * t + k] = (uint64_t)tri[3 * t + k] << 32 | tri[3 * t + (k + 1) % 3];
    }
    for (size_t i = 0; i < m; i++) {
        const double *a = xy + 2 * i, *b = xy + 2 * ((i + 1) % m);
        shoelace += (a[0] * b[1] - a[1] * b[0]) / 2;
    }
    assert_near(area, shoelace, 1e-12 * shoelace);
    qsort(e, 3 * nt, sizeof *e, cmp_u64);
    size_t boundary = 0;
    for (size_t i = 0; i < 3 * nt; i++) {
        if (i + 1 < 3 * nt) assert_true(e[i] != e[i + 1]);
        uint32_t a = (uint32_t)(e[i] >> 32), b = (uint32_t)e[i];
        uint64_t r = (uint64_t)b << 32 | a;
        int seg = a < m && b == (a + 1) % m;
        if (seg) {
            boundary++;
            assert_null(bsearch(&r, e, 3 * nt, sizeof *e, cmp_u64));
        } else {
            assert_non_null(bsearch(&r, e, 3 * nt, sizeof *e, cmp_u64));
        }
    }
    assert_int_equal(boundary, m);
    *min_angle = amin;
    free(e);
    free(all);
    coons__free(pts);
    coons__free(tri);
    return nt;
}

static void square(double *xy, size_t k, double w, double h)
{
    /* k points per side, counter-clockwise from (0,0) */
    for (size_t i = 0; i < k; i++) {
        double s = (double)i / (double)k;
        xy[2 * i] = s * w, xy[2 * i + 1] = 0;
        xy[2 * (k + i)] = w, xy[2 * (k + i) + 1] = s * h;
        xy[2 * (2 * k + i)] = (1 - s) * w, xy[2 * (2 * k + i) + 1] = h;
        xy[2 * (3 * k + i)] = 0, xy[2 * (3 * k + i) + 1] = (1 - s) * h;
    }
}

static void test_polygon_squares(void **state)
{
    (void)state;
    double xy[2 * 4 * 64];
    for (size_t k = 1; k <= 64; k = k < 8 ? k + 1 : 2 * k) {
        double amin;
        square(xy, k, 1, 1);
        size_t nt = check_polygon(xy, 4 * k, &amin);
        print_message("square, %2zu points a side: %4zu triangles (lattice %5zu), min angle %.1f\n",
                      k, nt, 2 * k * k, amin);
        assert_true(amin >= ANGLE_BOUND);
        /* far fewer than the lattice's 2 k^2 */
        if (k >= 8) assert_true(nt <= 2 * k * k / 2);
        /* rectangles with square cells: 4 x 1 */
        square(xy, k, 4, 1);
        /* (k a side on both: cells 4 times longer than high, the lattice's
         * own shape) */
        nt = check_polygon(xy, 4 * k, &amin);
        print_message("  4:1 rectangle: %4zu triangles, min angle %.1f\n", nt, amin);
        assert_true(amin >= fmin(ANGLE_BOUND, atan(1.0 / 4.0) * 180 / PI));
    }
}

/* Rounding does not decide: the boundary of a square grid is collinear
 * along its sides and cocircular in fours, and a model scaled by 10^k
 * rounds its coordinates differently. The same square with every
 * coordinate a few ulps off (fixed pseudo-random patterns; squares of 4
 * to 32 points a side and 4:1 rectangles) gets the same triangulation:
 * the same Steiner points to 1e-12, the same triangles. */
static void test_polygon_rounding(void **state)
{
    (void)state;
    double xy[2 * 4 * 32], yx[2 * 4 * 32];
    for (size_t run = 0; run < 12; run++) {
        size_t k = (size_t)4 << run % 4;
        square(xy, k, run < 8 ? 1 : 4, 1);
        unsigned x = 12345u + 977u * (unsigned)run;
        for (size_t i = 0; i < 8 * k; i++) {
            yx[i] = xy[i];
            for (int u = 0, n = (int)((x = x * 1103515245u + 12345u) >> 16) % 7 - 3; u < abs(n);
                 u++)
                yx[i] = nextafter(yx[i], n > 0 ? INFINITY : -INFINITY);
        }
        double *p[2] = {NULL, NULL};
        uint32_t *t[2] = {NULL, NULL};
        size_t ns[2], nt[2];
        int ok[2];
        coons_error err = COONS_ERROR_INIT;
        for (int r = 0; r < 2; r++)
            assert_coons_ok(coons__polygon_mesh(r ? yx : xy, 4 * k, COONS__FLAT_MIN_ANGLE, &p[r],
                                                &ns[r], &t[r], &nt[r], &ok[r], &err),
                            &err);
        assert_true(ok[0] && ok[1]);
        assert_int_equal(nt[0], nt[1]);
        assert_int_equal(ns[0], ns[1]);
        /* the same Steiner points (numbered in the order of their
         * coordinates) and the same triangles (rotated to their smallest
         * corner, sorted) */
        uint64_t *key[2];
        for (int r = 0; r < 2; r++) {
            size_t m = 4 * k, n = ns[r];
            uint64_t *ord = malloc((n ? n : 1) * sizeof *ord);
            uint32_t *to = malloc((n ? n : 1) * sizeof *to);
            for (size_t i = 0; i < n; i++)
                ord[i] = (uint64_t)llround(p[r][2 * i] * 1e6 + 0.1234567) << 40 |
                         (uint64_t)llround(p[r][2 * i + 1] * 1e6 + 0.1234567) << 16 | i;
            qsort(ord, n, sizeof *ord, cmp_u64);
            for (size_t i = 0; i < n; i++) to[ord[i] & 0xffff] = (uint32_t)(m + i);
            if (r) /* the points match in that order */
                for (size_t i = 0; i < n; i++) {
                    size_t a = ord[i] & 0xffff, b = key[0][nt[0] + i];
                    assert_near(p[1][2 * a], p[0][2 * b], 1e-12);
                    assert_near(p[1][2 * a + 1], p[0][2 * b + 1], 1e-12);
                }
            key[r] = malloc((nt[r] + n) * sizeof *key[r]);
            for (size_t i = 0; i < nt[r]; i++) {
                uint32_t v[3];
                for (int c = 0; c < 3; c++) {
                    v[c] = t[r][3 * i + c];
                    if (v[c] >= m) v[c] = to[v[c] - m];
                }
                int j = v[0] < v[1] ? (v[0] < v[2] ? 0 : 2) : (v[1] < v[2] ? 1 : 2);
                key[r][i] = (uint64_t)v[j] << 42 | (uint64_t)v[(j + 1) % 3] << 21 | v[(j + 2) % 3];
            }
            qsort(key[r], nt[r], sizeof *key[r], cmp_u64);
            for (size_t i = 0; i < n; i++) key[r][nt[r] + i] = ord[i] & 0xffff;
            free(ord);
            free(to);
        }
        assert_memory_equal(key[0], key[1], nt[0] * sizeof *key[0]);
        free(key[0]);
        free(key[1]);
        for (int r = 0; r < 2; r++) {
            coons__free(p[r]);
            coons__free(t[r]);
        }
    }
}

static void test_polygon_shapes(void **state)
{
    (void)state;
    enum { N = 96 };
    double xy[2 * N], amin;
    /* a disc (a cylinder's end face) */
    for (int i = 0; i < N; i++) {
        xy[2 * i] = cos(2 * PI * i / N);
        xy[2 * i + 1] = sin(2 * PI * i / N);
    }
    size_t nt = check_polygon(xy, N, &amin);
    print_message("disc of %d: %zu triangles, min angle %.1f\n", N, nt, amin);
    assert_true(amin >= ANGLE_BOUND);
    /* a graded side: intervals halving toward one corner (adaptive
     * refinement), the other sides uniform */
    size_t m = 0;
    double x = 1;
    while (x > 1.0 / 64) {
        xy[2 * m] = x, xy[2 * m + 1] = 0, m++;
        x /= 2;
    }
    xy[2 * m] = 0, xy[2 * m + 1] = 0, m++;
    for (int i = 1; i < 4; i++) xy[2 * m] = 0, xy[2 * m + 1] = -i / 4.0, m++;
    for (int i = 0; i < 4; i++) xy[2 * m] = i / 4.0, xy[2 * m + 1] = -1, m++;
    for (int i = 0; i < 4; i++) xy[2 * m] = 1, xy[2 * m + 1] = -1 + i / 4.0, m++;
    nt = check_polygon(xy, m, &amin);
    print_message("graded square (%zu points): %zu triangles, min angle %.1f\n", m, nt, amin);
    /* The corner where the 1/64 intervals meet an unsplittable 1/4 edge
     * at 90 degrees bounds the angles there (measured 8.1 degrees). */
    assert_true(amin >= 8.0);
    /* an L (concave), unit spacing */
    static const int L[][2] = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 1}, {2, 1}, {1, 1},
                               {1, 2}, {1, 3}, {0, 3}, {0, 2}, {0, 1}};
    m = sizeof L / sizeof L[0];
    for (size_t i = 0; i < m; i++) xy[2 * i] = L[i][0], xy[2 * i + 1] = L[i][1];
    nt = check_polygon(xy, m, &amin);
    assert_true(amin >= ANGLE_BOUND);
}

static void test_polygon_rejects(void **state)
{
    (void)state;
    double *pts = NULL;
    uint32_t *tri = NULL;
    size_t ns = 0, nt = 0;
    int ok = 1;
    coons_error err = COONS_ERROR_INIT;
    /* a bow tie: not simple (its signed area is 0 too) */
    double bow[] = {0, 0, 1, 1, 1, 0, 0, 1};
    assert_coons_ok(coons__polygon_mesh(bow, 4, 20, &pts, &ns, &tri, &nt, &ok, &err), &err);
    assert_false(ok);
    /* a folded ring: crossing edges with positive area */
    double fold[] = {0, 0, 4, 0, 4, 4, 1, -1, 0, 4};
    assert_coons_ok(coons__polygon_mesh(fold, 5, 20, &pts, &ns, &tri, &nt, &ok, &err), &err);
    assert_false(ok);
    /* a repeated point */
    double rep[] = {0, 0, 1, 0, 1, 1, 1, 0, 0, 1};
    assert_coons_ok(coons__polygon_mesh(rep, 5, 20, &pts, &ns, &tri, &nt, &ok, &err), &err);
    assert_false(ok);
    /* clockwise */
    double cw[] = {0, 0, 0, 1, 1, 1, 1, 0};
    assert_coons_ok(coons__polygon_mesh(cw, 4, 20, &pts, &ns, &tri, &nt, &ok, &err), &err);
    assert_false(ok);
    assert_null(pts);
    assert_null(tri);
}

/* ---------- bodies ---------- */

static coons_body *hexahedron(double c[8][3])
{
    coons_body *b = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err), &err);
    return b;
}

/* Corner (i, j, k) of the box [0,L0] x [0,L1] x [0,L2] sheared by s
 * (x += s z): a parallelepiped of volume L0 L1 L2. */
static coons_body *parallelepiped(const double L[3], double s)
{
    double c[8][3];
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) {
                double *p = c[4 * i + 2 * j + k];
                p[0] = i * L[0] + s * k * L[2];
                p[1] = j * L[1];
                p[2] = k * L[2];
            }
    return hexahedron(c);
}

static void assert_closed(const coons_mesh *m)
{
    size_t nt = coons_mesh_triangle_count(m);
    const uint32_t *t = coons_mesh_triangles(m);
    uint64_t *e = malloc(3 * nt * sizeof *e);
    for (size_t i = 0; i < nt; i++)
        for (int k = 0; k < 3; k++)
            e[3 * i + k] = (uint64_t)t[3 * i + k] << 32 | t[3 * i + (k + 1) % 3];
    qsort(e, 3 * nt, sizeof *e, cmp_u64);
    for (size_t i = 0; i < 3 * nt; i++) {
        if (i + 1 < 3 * nt) assert_true(e[i] != e[i + 1]);
        uint64_t r = (e[i] & 0xffffffffu) << 32 | e[i] >> 32;
        assert_non_null(bsearch(&r, e, 3 * nt, sizeof *e, cmp_u64));
    }
    free(e);
}

/* Signed volume and area of the mesh, computed here. */
static void volume_area(const coons_mesh *m, double *vol, double *area)
{
    const double *v = coons_mesh_vertices(m);
    const uint32_t *t = coons_mesh_triangles(m);
    *vol = *area = 0;
    for (size_t i = 0; i < coons_mesh_triangle_count(m); i++) {
        const double *a = v + 3 * t[3 * i], *b = v + 3 * t[3 * i + 1], *c = v + 3 * t[3 * i + 2];
        double u[3], w[3], n[3];
        for (int d = 0; d < 3; d++) u[d] = b[d] - a[d], w[d] = c[d] - a[d];
        n[0] = u[1] * w[2] - u[2] * w[1];
        n[1] = u[2] * w[0] - u[0] * w[2];
        n[2] = u[0] * w[1] - u[1] * w[0];
        *vol += (a[0] * n[0] + a[1] * n[1] + a[2] * n[2]) / 6;
        *area += sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / 2;
    }
}

static void test_box_faces(void **state)
{
    (void)state;
    const double L[3] = {2, 3, 5};
    for (unsigned N = 1; N <= 32; N *= 2) {
        coons_body *b = parallelepiped(L, 0);
        coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
        o.resolution = N;
        coons_mesh *m = NULL;
        coons_error err = COONS_ERROR_INIT;
        assert_coons_ok(coons_body_sample(b, &o, "box", &m, &err), &err);
        assert_closed(m);
        double vol, area;
        volume_area(m, &vol, &area);
        assert_near(vol, 30, 1e-12 * 30);
        assert_near(area, 62, 1e-12 * 62);
        /* every triangle in one face plane (the three vertices share a
         * coordinate at 0 or L), and the per-face areas are exact */
        const double *v = coons_mesh_vertices(m);
        const uint32_t *t = coons_mesh_triangles(m);
        size_t nt = coons_mesh_triangle_count(m), nv = coons_mesh_vertex_count(m);
        double fa[6] = {0};
        double amin = 180;
        for (size_t i = 0; i < nt; i++) {
            const double *p[3] = {v + 3 * t[3 * i], v + 3 * t[3 * i + 1], v + 3 * t[3 * i + 2]};
            int face = -1;
            for (int d = 0; d < 3 && face < 0; d++)
                for (int e = 0; e < 2 && face < 0; e++)
                    if (p[0][d] == e * L[d] && p[1][d] == e * L[d] && p[2][d] == e * L[d])
                        face = 2 * d + e;
            assert_true(face >= 0);
            int a = (face / 2 + 1) % 3, c = (face / 2 + 2) % 3;
            fa[face] += fabs((p[1][a] - p[0][a]) * (p[2][c] - p[0][c]) -
                             (p[1][c] - p[0][c]) * (p[2][a] - p[0][a])) / 2;
            amin = fmin(amin, tri_min_angle(p[0], p[1], p[2], 3));
        }
        for (int f = 0; f < 6; f++)
            assert_near(fa[f], L[(f / 2 + 1) % 3] * L[(f / 2 + 2) % 3], 1e-12 * 30);
        /* Euler for a closed genus-0 surface; the vertices are the lattice
         * points on the 12 edges plus Steiner points inside the faces */
        assert_int_equal(nt, 2 * nv - 4);
        size_t on_edges = 0;
        for (size_t i = 0; i < nv; i++) {
            int at = 0;
            for (int d = 0; d < 3; d++) at += v[3 * i + d] == 0 || v[3 * i + d] == L[d];
            on_edges += at >= 2;
        }
        assert_int_equal(on_edges, 8 + 12 * (N - 1));
        /* the cells are 2:3:5 (their aspect bounds the lattice's angles) */
        assert_true(amin >= fmin(ANGLE_BOUND, atan(2.0 / 5.0) * 180 / PI));
        print_message("box N=%2u: %5zu triangles (lattice %6u), %zu Steiner, min angle %.1f\n",
                      N, nt, 12 * N * N, nv - on_edges, amin);
        if (N >= 8) assert_true(nt < 12 * N * N / 2);
        coons_mesh_free(m);
        coons_body_free(b);
    }
}

static void test_parallelepiped_adaptive(void **state)
{
    (void)state;
    const double L[3] = {1, 2, 3};
    coons_body *b = parallelepiped(L, 0.5);
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.tolerance = 1e-3;
    o.resolution = 12;
    assert_coons_ok(coons_body_sample(b, &o, NULL, &m, &err), &err);
    assert_closed(m);
    double vol, area;
    volume_area(m, &vol, &area);
    assert_near(vol, 6, 1e-12 * 6);
    /* faces: 2 of 1 x 2, 2 of 2 x 3 sqrt(1.25), 2 of 1 x 3 */
    assert_near(area, 2 * (2 + 2 * 3 * sqrt(1.25) + 3), 1e-12 * 30);
    assert_int_equal(coons_mesh_triangle_count(m), 2 * coons_mesh_vertex_count(m) - 4);
    assert_true(coons_mesh_triangle_count(m) < 12 * 12 * 12 / 3);
    coons_mesh_free(m);
    coons_body_free(b);
}

/* A twisted top (one corner raised): that face is not flat and keeps its
 * lattice, N^2 cells, with (N-1)^2 vertices inside it; the five flat faces
 * have none of the lattice's inner points. */
static void test_twisted_face_keeps_lattice(void **state)
{
    (void)state;
    double c[8][3];
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) {
                double *p = c[4 * i + 2 * j + k];
                p[0] = i, p[1] = j, p[2] = k ? 1 + 0.5 * (i && j) : 0;
            }
    coons_body *b = hexahedron(c);
    const unsigned N = 8;
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.resolution = N;
    coons_mesh *m = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_sample(b, &o, NULL, &m, &err), &err);
    assert_closed(m);
    const double *v = coons_mesh_vertices(m);
    size_t nv = coons_mesh_vertex_count(m), top_inner = 0, lattice_inner = 0;
    for (size_t i = 0; i < nv; i++) {
        const double *p = v + 3 * i;
        int edge = (p[0] == 0 || p[0] == 1) + (p[1] == 0 || p[1] == 1);
        if (p[2] > 0 && edge == 0) top_inner++;
        /* a flat face's inner point on the lattice (multiples of 1/N) */
        double g[3];
        for (int d = 0; d < 3; d++) g[d] = p[d] * N;
        if (p[2] == 0 && edge == 0 && g[0] == floor(g[0]) && g[1] == floor(g[1]))
            lattice_inner++;
    }
    assert_int_equal(top_inner, (N - 1) * (N - 1));
    assert_int_equal(lattice_inner, 0);
    /* the volume of a bilinear-topped prism: mean height 1 + 0.5/4 */
    double vol, area;
    volume_area(m, &vol, &area);
    double exact;
    assert_coons_ok(coons_body_volume(b, 1e-12, &exact, &err), &err);
    assert_near(exact, 1.125, 1e-9);
    assert_near(vol, exact, 1e-2);
    coons_mesh_free(m);
    coons_body_free(b);
}

/* Flat faces with per-vertex parameters (the isoparametric output with the
 * boundary): the boundary part is coons_model_sample()'s mesh bit for bit,
 * Steiner points included, and every vertex's (u,v,w) maps back to it:
 * the body's exact map at the parameters is the vertex to 1e-12 (relative
 * to a body of size ~3), for an affine box (barycentric interpolation in
 * the lattice is exact) and for the frustum of a pyramid, whose sides are
 * planar trapezoids with a bilinear, not affine, map (interpolation alone
 * is off by up to the lattice's in-plane error; Newton's method on the
 * map makes it exact). Returns the count of Steiner points. */
static size_t check_flat_params(const char *corners, unsigned N)
{
    char json[1024];
    snprintf(json, sizeof json,
             "{\"coons\": 1, \"tolerance\": 0.01, \"operation\": \"none\", \"bodies\": ["
             "{\"type\": \"body0\", \"name\": \"b\", \"corners\": %s}]}",
             corners);
    coons_error err = COONS_ERROR_INIT;
    coons_model *model;
    assert_coons_ok(coons_model_load_memory(json, strlen(json), NULL, NULL, &model, &err), &err);
    const coons_body *b = coons_model_body(model, 0);
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.resolution = N;
    coons_mesh *ref, *m;
    assert_coons_ok(coons_model_sample(model, &o, &ref, &err), &err);
    assert_coons_ok(coons_model_iso_surfaces(model, NULL, 0, &o, COONS_ISO_WITH_BOUNDARY, &m,
                                             &err),
                    &err);
    size_t nv = coons_mesh_vertex_count(m), nt = coons_mesh_triangle_count(m);
    assert_int_equal(nv, coons_mesh_vertex_count(ref));
    assert_int_equal(nt, coons_mesh_triangle_count(ref));
    assert_memory_equal(coons_mesh_vertices(m), coons_mesh_vertices(ref), 3 * nv * sizeof(double));
    assert_memory_equal(coons_mesh_triangles(m), coons_mesh_triangles(ref),
                        3 * nt * sizeof(uint32_t));
    assert_closed(m);
    /* far fewer triangles than the lattice's 12 N^2 */
    assert_true(nt < 12 * N * N / 2);
    const double *x = coons_mesh_vertices(m), *uvw = coons_mesh_vertex_parameters(m);
    assert_non_null(uvw);
    size_t steiner = 0;
    double worst = 0;
    for (size_t i = 0; i < nv; i++) {
        const double *q = uvw + 3 * i;
        double y[3];
        coons_body_eval(b, q[0], q[1], q[2], y);
        for (int d = 0; d < 3; d++) worst = fmax(worst, fabs(y[d] - x[3 * i + d]));
        /* on a face (one parameter at 0 or 1), off the lattice lines */
        int on = 0, lattice = 0;
        for (int d = 0; d < 3; d++) {
            on += q[d] == 0.0 || q[d] == 1.0;
            lattice += q[d] * N == floor(q[d] * N);
        }
        assert_true(on >= 1);
        if (on == 1 && lattice < 3) steiner++;
    }
    print_message("%s N=%u: %zu triangles (lattice %u), %zu Steiner points, |F(u,v,w) - x| <= "
                  "%.2g\n",
                  corners, N, nt, 12 * N * N, steiner, worst);
    assert_true(worst <= 1e-12);
    coons_mesh_free(m);
    coons_mesh_free(ref);
    coons_model_free(model);
    return steiner;
}

static void test_flat_params(void **state)
{
    (void)state;
    static const char box[] = "[[0,0,0],[0,0,3],[0,2,0],[0,2,3],"
                              "[1,0,0],[1,0,3],[1,2,0],[1,2,3]]";
    static const char frustum[] = "[[0,0,0],[0.5,0.5,1],[0,2,0],[0.5,1.5,1],"
                                  "[2,0,0],[1.5,0.5,1],[2,2,0],[1.5,1.5,1]]";
    for (unsigned N = 8; N <= 16; N += 8) {
        assert_true(check_flat_params(box, N) > 0);
        assert_true(check_flat_params(frustum, N) > 0);
    }
}

/* Distance from p to triangle abc, computed here: the foot of the
 * perpendicular when it falls inside, else the nearest side. */
static double point_tri_dist(const double p[3], const double *a, const double *b, const double *c)
{
    double ab[3], ac[3], ap[3], n[3];
    for (int d = 0; d < 3; d++) ab[d] = b[d] - a[d], ac[d] = c[d] - a[d], ap[d] = p[d] - a[d];
    n[0] = ab[1] * ac[2] - ab[2] * ac[1];
    n[1] = ab[2] * ac[0] - ab[0] * ac[2];
    n[2] = ab[0] * ac[1] - ab[1] * ac[0];
    double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    double best = INFINITY;
    if (nn > 0) {
        double h = (ap[0] * n[0] + ap[1] * n[1] + ap[2] * n[2]) / nn, f[3];
        for (int d = 0; d < 3; d++) f[d] = p[d] - h * n[d];
        const double *q[3] = {a, b, c};
        int inside = 1;
        for (int k = 0; k < 3; k++) {
            const double *u = q[k], *v = q[(k + 1) % 3];
            double e[3] = {v[0] - u[0], v[1] - u[1], v[2] - u[2]};
            double g[3] = {f[0] - u[0], f[1] - u[1], f[2] - u[2]};
            double x[3] = {e[1] * g[2] - e[2] * g[1], e[2] * g[0] - e[0] * g[2],
                           e[0] * g[1] - e[1] * g[0]};
            if (x[0] * n[0] + x[1] * n[1] + x[2] * n[2] < 0) inside = 0;
        }
        if (inside) return fabs(h) * sqrt(nn);
    }
    const double *q[3] = {a, b, c};
    for (int k = 0; k < 3; k++) {
        const double *u = q[k], *v = q[(k + 1) % 3];
        double e[3], g[3], ee = 0, eg = 0;
        for (int d = 0; d < 3; d++) e[d] = v[d] - u[d], g[d] = p[d] - u[d], ee += e[d] * e[d];
        for (int d = 0; d < 3; d++) eg += e[d] * g[d];
        double t = ee > 0 ? fmin(1, fmax(0, eg / ee)) : 0, s2 = 0;
        for (int d = 0; d < 3; d++) s2 += (g[d] - t * e[d]) * (g[d] - t * e[d]);
        best = fmin(best, sqrt(s2));
    }
    return best;
}

/* Largest distance from the exact points F(q) of one face (parameter
 * `fixed` at `val`, the other two on a k x k grid) to the mesh. */
static double face_to_mesh(const coons_body *b, const coons_mesh *m, int fixed, double val, int k)
{
    const double *v = coons_mesh_vertices(m);
    const uint32_t *t = coons_mesh_triangles(m);
    size_t nt = coons_mesh_triangle_count(m);
    double worst = 0;
    for (int i = 0; i <= k; i++)
        for (int j = 0; j <= k; j++) {
            double q[3], x[3];
            q[fixed] = val;
            q[(fixed + 1) % 3] = (double)i / k;
            q[(fixed + 2) % 3] = (double)j / k;
            coons_body_eval(b, q[0], q[1], q[2], x);
            double d = INFINITY;
            for (size_t n = 0; n < nt; n++)
                d = fmin(d, point_tri_dist(x, v + 3 * t[3 * n], v + 3 * t[3 * n + 1],
                                           v + 3 * t[3 * n + 2]));
            worst = fmax(worst, d);
        }
    return worst;
}

/* Faces ruled between two straight lines. The side of a NURBS cylinder
 * (u around, v out, w up; straight along w): with max_aspect INFINITY it
 * is one strip, no vertex inside it but the seam's lattice points (x = r,
 * y = 0), which both end fans use; with the default max_aspect its strips
 * keep lattice lines across (cells at most 4 times longer than wide: here
 * all of them, as the lattice's own cells are that shape already). Both are closed and
 * their exact surface points lie within the tolerance of the mesh
 * (measured here, brute force). The twisted top of the prism (a
 * hyperbolic paraboloid, straight both ways but not along parallel
 * rulings) becomes strips only at a tolerance its twist fits in. */
static void test_ruled_faces(void **state)
{
    (void)state;
    const double R = 1.5, H = 6.0;
    coons_body *b;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(tb_nurbs_cylinder_rc(R, H, &b, &err), &err);
    size_t counts[3];
    for (int pass = 0; pass < 3; pass++) {
        coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
        o.tolerance = 0.01;
        o.max_aspect = pass == 1 ? INFINITY : 0;
        coons_mesh *m = NULL;
        if (pass == 2) { /* the lattice itself, for the counts */
            coons__sample_opts io;
            assert_coons_ok(coons__sample_opts_resolve(&o, &io, &err), &err);
            io.flags |= COONS__SAMPLE_LATTICE_FACES;
            assert_coons_ok(coons_mesh_new(&m, &err), &err);
            assert_coons_ok(coons__body_sample_into(b, &io, "b", m, NULL, &err), &err);
        } else {
            assert_coons_ok(coons_body_sample(b, &o, NULL, &m, &err), &err);
        }
        assert_closed(m);
        counts[pass] = coons_mesh_triangle_count(m);
        const double *v = coons_mesh_vertices(m);
        size_t inside = 0, seam = 0;
        for (size_t i = 0; i < coons_mesh_vertex_count(m); i++) {
            const double *p = v + 3 * i;
            if (fabs(hypot(p[0], p[1]) - R) < 1e-9 && p[2] > 1e-9 && p[2] < H - 1e-9) {
                inside++;
                seam += fabs(p[0] - R) < 1e-12 && fabs(p[1]) < 1e-12;
            }
        }
        if (pass == 1) assert_int_equal(inside, seam);
        if (pass == 2) assert_true(inside > seam);
        double dev = face_to_mesh(b, m, 1, 1.0, 48);
        print_message("cylinder side, %s: %zu triangles, %zu vertices inside the side (%zu on "
                      "the seam), surface to mesh %.4f (tolerance 0.01)\n",
                      pass == 0 ? "max_aspect 4" : pass == 1 ? "max_aspect inf" : "lattice",
                      counts[pass], inside, seam, dev);
        assert_true(dev <= 0.01);
        coons_mesh_free(m);
    }
    assert_true(counts[1] < counts[0]);
    assert_true(counts[0] <= counts[2]);
    coons_body_free(b);
    /* the twisted top */
    double c[8][3];
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) {
                double *p = c[4 * i + 2 * j + k];
                p[0] = i, p[1] = j, p[2] = k ? 1 + 0.5 * (i && j) : 0;
            }
    b = hexahedron(c);
    for (int pass = 0; pass < 2; pass++) {
        const unsigned N = 8;
        coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
        o.resolution = N;
        o.tolerance = pass ? 0.05 : 0.0025;
        coons_mesh *m = NULL;
        assert_coons_ok(coons_body_sample(b, &o, NULL, &m, &err), &err);
        assert_closed(m);
        const double *v = coons_mesh_vertices(m);
        size_t top_inner = 0;
        for (size_t i = 0; i < coons_mesh_vertex_count(m); i++) {
            const double *p = v + 3 * i;
            top_inner += p[2] > 0 && p[0] > 0 && p[0] < 1 && p[1] > 0 && p[1] < 1;
        }
        double dev = face_to_mesh(b, m, 2, 1.0, 32);
        print_message("twisted top, tolerance %g: %zu triangles, %zu inner top vertices "
                      "(lattice %u), surface to mesh %.4f\n",
                      o.tolerance, coons_mesh_triangle_count(m), top_inner, (N - 1) * (N - 1),
                      dev);
        if (pass) assert_true(top_inner < (N - 1) * (N - 1));
        else assert_int_equal(top_inner, (N - 1) * (N - 1));
        assert_true(dev <= o.tolerance);
        coons_mesh_free(m);
    }
    coons_body_free(b);
}

/* Every allocation of sampling a box with flat faces (the polygon mesher's
 * included) fails in turn: COONS_E_NOMEM, nothing leaked. */
static void test_flat_allocation_failures(void **state)
{
    (void)state;
    const double L[3] = {1, 2, 3};
    coons_body *b = parallelepiped(L, 0.25);
    coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
    o.resolution = 6;
    int done = 0;
    for (long n = 0; !done; n++) {
        coons_mesh *m = NULL;
        coons_error err = COONS_ERROR_INIT;
        coons_test_fail_after(n);
        coons_status st = coons_body_sample(b, &o, NULL, &m, &err);
        if (st == COONS_OK) {
            done = 1;
            coons_test_fail_after(-1);
            assert_true(coons_mesh_triangle_count(m) < 12 * 36);
            coons_mesh_free(m);
        } else {
            assert_int_equal(st, COONS_E_NOMEM);
            assert_null(m);
            assert_int_equal(coons_test_live_allocs(), 0);
        }
    }
    coons_test_fail_after(-1);
    coons_body_free(b);
    /* and of a ruled face's strips (the cylinder's side) */
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(tb_nurbs_cylinder_rc(1.0, 3.0, &b, &err), &err);
    o.resolution = 0;
    o.tolerance = 0.05;
    o.max_aspect = INFINITY;
    done = 0;
    for (long n = 0; !done; n++) {
        coons_mesh *m = NULL;
        coons_test_fail_after(n);
        coons_status st = coons_body_sample(b, &o, NULL, &m, &err);
        if (st == COONS_OK) {
            done = 1;
            coons_test_fail_after(-1);
            assert_closed(m);
            coons_mesh_free(m);
        } else {
            assert_int_equal(st, COONS_E_NOMEM);
            assert_null(m);
            assert_int_equal(coons_test_live_allocs(), 0);
        }
    }
    coons_test_fail_after(-1);
    coons_body_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_polygon_squares),
        cmocka_unit_test(test_polygon_rounding),
        cmocka_unit_test(test_polygon_shapes),
        cmocka_unit_test(test_polygon_rejects),
        cmocka_unit_test(test_box_faces),
        cmocka_unit_test(test_parallelepiped_adaptive),
        cmocka_unit_test(test_twisted_face_keeps_lattice),
        cmocka_unit_test(test_flat_params),
        cmocka_unit_test(test_ruled_faces),
        cmocka_unit_test(test_flat_allocation_failures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
