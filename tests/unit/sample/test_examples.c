/* SPDX-License-Identifier: GPL-3.0-or-later */
#define _POSIX_C_SOURCE 200809L
/* Every body of every model in examples/ samples, at the model's tolerance,
 * into a closed, 2-manifold, consistently and outward oriented mesh with
 * the expected Euler characteristic (edge use recounted here, independently
 * of coons_mesh_check()), whose distance to random exact boundary points is
 * within the tolerance and whose volume agrees with the det-J volume within
 * area x tolerance. Includes the degenerate tip of nail.json (a face
 * collapsed to a point) and the ring of curve-coons-cubic-closed.json
 * (coincident faces glued). */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : (x > y);
}

/* V - E + F from the arrays, failing unless every directed edge occurs
 * once and its reverse once. */
static long closed_euler(const coons_mesh *m)
{
    size_t nt = coons_mesh_triangle_count(m);
    const uint32_t *t = coons_mesh_triangles(m);
    uint64_t *e = malloc(3 * nt * sizeof *e);
    assert_non_null(e);
    for (size_t i = 0; i < nt; i++)
        for (int k = 0; k < 3; k++)
            e[3 * i + k] = (uint64_t)t[3 * i + k] << 32 | t[3 * i + (k + 1) % 3];
    qsort(e, 3 * nt, sizeof *e, cmp_u64);
    for (size_t i = 0; i < 3 * nt; i++) {
        assert_true((e[i] >> 32) != (e[i] & 0xffffffffu));
        if (i + 1 < 3 * nt) assert_true(e[i] != e[i + 1]);
        uint64_t r = (e[i] & 0xffffffffu) << 32 | e[i] >> 32;
        assert_non_null(bsearch(&r, e, 3 * nt, sizeof *e, cmp_u64));
    }
    free(e);
    /* all vertices are used: the sampler compacts them */
    return (long)coons_mesh_vertex_count(m) - (long)(3 * nt / 2) + (long)nt;
}

static double seg_dist(const double p[3], const double a[3], const double b[3])
{
    double ab[3], ap[3], l2 = 0, t = 0, d = 0;
    for (int i = 0; i < 3; i++) {
        ab[i] = b[i] - a[i];
        ap[i] = p[i] - a[i];
        l2 += ab[i] * ab[i];
        t += ap[i] * ab[i];
    }
    t = l2 > 0 ? fmin(1, fmax(0, t / l2)) : 0;
    for (int i = 0; i < 3; i++) d += (ap[i] - t * ab[i]) * (ap[i] - t * ab[i]);
    return sqrt(d);
}

/* Distance to triangle abc: the plane if p projects inside, else a side. */
static double tri_dist(const double p[3], const double a[3], const double b[3], const double c[3])
{
    double u[3], v[3], w[3], n[3];
    for (int i = 0; i < 3; i++) {
        u[i] = b[i] - a[i];
        v[i] = c[i] - a[i];
        w[i] = p[i] - a[i];
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    double n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (n2 > 0) {
        double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
        double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        double uv = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
        double wu = w[0] * u[0] + w[1] * u[1] + w[2] * u[2];
        double wv = w[0] * v[0] + w[1] * v[1] + w[2] * v[2];
        double den = uu * vv - uv * uv;
        double s = (wu * vv - wv * uv) / den, t = (wv * uu - wu * uv) / den;
        if (s >= 0 && t >= 0 && s + t <= 1)
            return fabs(w[0] * n[0] + w[1] * n[1] + w[2] * n[2]) / sqrt(n2);
    }
    return fmin(seg_dist(p, a, b), fmin(seg_dist(p, b, c), seg_dist(p, c, a)));
}

static uint64_t rng = 0x9e3779b97f4a7c15ull;
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

static double random_distance(const coons_body *b, const coons_mesh *m, int count)
{
    const double *x = coons_mesh_vertices(m);
    const uint32_t *t = coons_mesh_triangles(m);
    size_t nt = coons_mesh_triangle_count(m);
    double worst = 0;
    for (int i = 0; i < count; i++) {
        int face = (int)(urand() * 6) % 6;
        double q[3] = {urand(), urand(), urand()}, p[3], o[3];
        q[face / 2] = (double)(face % 2);
        coons_body_eval(b, q[0], q[1], q[2], p);
        /* a face that coincides with its opposite one lies inside the solid */
        q[face / 2] = 1.0 - q[face / 2];
        coons_body_eval(b, q[0], q[1], q[2], o);
        if (fabs(p[0] - o[0]) + fabs(p[1] - o[1]) + fabs(p[2] - o[2]) < 1e-9) continue;
        double best = INFINITY;
        for (size_t k = 0; k < nt; k++)
            best = fmin(best, tri_dist(p, x + 3 * t[3 * k], x + 3 * t[3 * k + 1],
                                       x + 3 * t[3 * k + 2]));
        worst = fmax(worst, best);
    }
    return worst;
}

static int is_json(const char *name)
{
    size_t n = strlen(name);
    return n > 5 && !strcmp(name + n - 5, ".json");
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static void test_examples(void **state)
{
    (void)state;
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/examples", COONS_SOURCE_DIR);
    DIR *d = opendir(dir);
    if (!d) fail_msg("cannot open %s", dir);
    char *names[256];
    size_t nn = 0;
    struct dirent *de;
    while ((de = readdir(d)) && nn < 256)
        if (is_json(de->d_name)) names[nn++] = strdup(de->d_name);
    closedir(d);
    qsort(names, nn, sizeof *names, cmp_str);
    assert_true(nn > 0);
    size_t bodies = 0, glued = 0;
    for (size_t f = 0; f < nn; f++) {
        char path[2048];
        snprintf(path, sizeof path, "%s/%s", dir, names[f]);
        coons_model *model = NULL;
        coons_error err = COONS_ERROR_INIT;
        assert_coons_ok(coons_model_load_file(path, NULL, &model, &err), &err);
        double tol = coons_model_tolerance(model);
        for (size_t i = 0; i < coons_model_body_count(model); i++) {
            const coons_body *b = coons_model_body(model, i);
            coons_mesh *m = NULL;
            assert_coons_ok(coons_body_sample(b, NULL, NULL, &m, &err), &err);
            coons_mesh_free(m);
            coons_sample_options o = COONS_SAMPLE_OPTIONS_INIT;
            o.tolerance = tol;
            assert_coons_ok(coons_body_sample(b, &o, coons_model_body_name(model, i), &m, &err),
                            &err);
            coons_mesh_report r = COONS_MESH_REPORT_INIT;
            assert_coons_ok(coons_mesh_check(m, &r, &err), &err);
            long euler = closed_euler(m);
            double dev, vol;
            coons_mesh_part_sampling(m, 0, NULL, &dev, NULL);
            double dist = random_distance(b, m, 100);
            assert_coons_ok(coons_body_volume(b, 1e-9, &vol, &err), &err);
            double area = coons_mesh_area(m), mv = coons_mesh_volume(m);
            print_message("%-30s %-18s tol %-7.3g %6zu tri  dev %-8.3g rnd %-8.3g euler %ld  "
                          "vol %.7g / det J %.7g\n",
                          names[f], coons_model_body_name(model, i), tol,
                          coons_mesh_triangle_count(m), dev, dist, euler, mv, vol);
            assert_true(r.closed && r.manifold && r.oriented);
            assert_int_equal(r.openmesh_rejected, 0);
            assert_int_equal(r.euler, euler);
            assert_int_equal(euler, r.expected_euler);
            assert_true(euler == 2 || euler == 0);
            glued += euler == 0;
            assert_true(dev <= tol);
            assert_true(dist <= tol);
            assert_true(mv > 0);
            assert_near(mv, fabs(vol), area * tol); /* a mirrored instance: det J < 0 */
            coons_mesh_free(m);
            bodies++;
        }
        coons_model_free(model);
        free(names[f]);
    }
    print_message("%zu bodies, %zu closing on themselves\n", bodies, glued);
    assert_true(glued >= 1); /* the ring example */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_examples),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
