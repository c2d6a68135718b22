/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The shell body S(u,v,w) = x(u,v) + (w - c) h n(u,v) (coons-model(5),
 * "Shells: surfaces made solid"):
 * - of a plane rectangle: the box W x H x h, at its 8 corners, by the
 *   library's volume and by the sampled mesh's enclosed volume;
 * - of a NURBS quarter cylinder: the closed-form volumes
 *   (pi/2) L (R h + (1/2 - c) h^2) for the three sides;
 * - det J and all of J against central differences of the map (cylinder,
 *   a curved Hermite patch, a network);
 * - thicker than the radius of curvature: det J < 0 inside (a fold); a
 *   thinner one does not fold;
 * - an undefined normal is refused, saying where; the loader's errors.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "patch_fixture.h"
#include "test_util.h"

static const double PI = 3.14159265358979323846;

static coons_body *shell_of(const coons_patch *p, double h, coons_shell_side side)
{
    coons_body *b = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_body_new_shell(p, h, side, &b, &err), &err);
    assert_int_equal(coons_body_kind(b), COONS_BODY_SHELL);
    return b;
}

/* Quarter cylinder of radius R and length L about the z axis: a degree
 * (2, 1) NURBS surface, s along the arc, t along z; its normal x_s x x_t
 * points outward. */
static coons_patch *quarter_cylinder(double R, double L)
{
    const double w = sqrt(0.5);
    const double pts[3][2][3] = {{{R, 0, 0}, {R, 0, L}}, {{R, R, 0}, {R, R, L}},
                                 {{0, R, 0}, {0, R, L}}};
    const double wt[6] = {1, 1, w, w, 1, 1};
    coons_patch *p = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_patch_new_bspline(2, 1, pts[0][0], 3, 2, NULL, NULL, wt, &p, &err),
                    &err);
    return p;
}

/* Given a plane rectangle, then its shell is the box: corners, volume by
 * quadrature and by the sampled mesh. */
static void test_plane_box(void **state)
{
    (void)state;
    const double W = 4, H = 3, h = 0.5;
    const double X[12] = {0, 0, 0, W, 0, 0, 0, H, 0, W, H, 0};
    coons_patch *p = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_patch_new_bilinear(X, &p, &err), &err);
    const coons_shell_side sides[3] = {COONS_SHELL_BOTH, COONS_SHELL_FRONT, COONS_SHELL_BACK};
    const double c[3] = {0.5, 0.0, 1.0};
    for (int k = 0; k < 3; k++) {
        coons_body *b = shell_of(p, h, sides[k]);
        for (int q = 0; q < 8; q++) {
            double u = q >> 2, v = (q >> 1) & 1, w = q & 1, x[3];
            double want[3] = {u * W, v * H, (w - c[k]) * h};
            coons_body_eval(b, u, v, w, x);
            assert_vec3_near(x, want, 1e-14);
        }
        double vol = 0;
        assert_coons_ok(coons_body_volume(b, 1e-12, &vol, &err), &err);
        assert_near(vol, W * H * h, 1e-12 * W * H * h);
        coons_mesh *m = NULL;
        assert_coons_ok(coons_body_sample(b, NULL, "shell", &m, &err), &err);
        assert_near(coons_mesh_volume(m), W * H * h, 1e-9 * W * H * h);
        coons_mesh_free(m);
        coons_body_free(b);
    }
    coons_patch_free(p);
}

/* Given a quarter cylinder, then the shell's volume is the closed form
 * (pi/2) L (R h + (1/2 - c) h^2) for both, front and back. */
static void test_cylinder_volume(void **state)
{
    (void)state;
    const double R = 10, L = 5, h = 2;
    coons_patch *p = quarter_cylinder(R, L);
    const coons_shell_side sides[3] = {COONS_SHELL_BOTH, COONS_SHELL_FRONT, COONS_SHELL_BACK};
    const double c[3] = {0.5, 0.0, 1.0};
    coons_error err = COONS_ERROR_INIT;
    for (int k = 0; k < 3; k++) {
        coons_body *b = shell_of(p, h, sides[k]);
        double vol = 0, want = PI / 2 * L * (R * h + (0.5 - c[k]) * h * h);
        assert_coons_ok(coons_body_volume(b, 1e-11, &vol, &err), &err);
        assert_near(vol, want, 1e-8 * want);
        /* points lie on the offset cylinders */
        double x[3];
        coons_body_eval(b, 0.3, 0.6, 1.0, x);
        assert_near(sqrt(x[0] * x[0] + x[1] * x[1]), R + (1 - c[k]) * h, 1e-12 * R);
        assert_near(x[2], 0.6 * L, 1e-12 * L);
        coons_body_free(b);
    }
    coons_patch_free(p);
}

/* J against central differences of the map at interior points. */
static void check_jacobian_fd(const coons_body *b, double rel)
{
    const double h = 1e-6;
    const double par[4] = {0.13, 0.37, 0.62, 0.88};
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            for (int k = 0; k < 4; k++) {
                double q[3] = {par[i], par[j], par[k]}, x[3], J[3][3];
                double det = coons_body_eval_jacobian(b, q[0], q[1], q[2], x, J);
                double F[3][3], scale = 0;
                for (int c = 0; c < 3; c++) {
                    double a[3], bb[3], qp[3] = {q[0], q[1], q[2]}, qm[3] = {q[0], q[1], q[2]};
                    qp[c] += h;
                    qm[c] -= h;
                    coons_body_eval(b, qp[0], qp[1], qp[2], a);
                    coons_body_eval(b, qm[0], qm[1], qm[2], bb);
                    for (int r = 0; r < 3; r++) {
                        F[r][c] = (a[r] - bb[r]) / (2 * h);
                        scale = fmax(scale, fabs(F[r][c]));
                    }
                }
                for (int r = 0; r < 3; r++)
                    for (int c = 0; c < 3; c++) assert_near(J[r][c], F[r][c], rel * scale);
                double fdet = F[0][0] * (F[1][1] * F[2][2] - F[1][2] * F[2][1]) -
                              F[0][1] * (F[1][0] * F[2][2] - F[1][2] * F[2][0]) +
                              F[0][2] * (F[1][0] * F[2][1] - F[1][1] * F[2][0]);
                assert_near(det, fdet, 10 * rel * scale * scale * scale);
            }
}

/* Given shells of a cylinder, of a curved Hermite Coons patch and of a
 * network, then J and det J agree with finite differences. */
static void test_jacobian_fd(void **state)
{
    (void)state;
    coons_patch *p = quarter_cylinder(3, 2);
    coons_body *b = shell_of(p, 0.7, COONS_SHELL_FRONT);
    check_jacobian_fd(b, 1e-7);
    coons_body_free(b);
    coons_patch_free(p);

    fx_boundary fb;
    fx_boundary_make(&fb);
    coons_hermite_options ho = COONS_HERMITE_OPTIONS_INIT;
    ho.twist = COONS_TWIST_ADINI;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_patch_new_hermite_coons(fx_curves(&fb), &ho, &p, &err), &err);
    b = shell_of(p, 0.1, COONS_SHELL_BOTH);
    check_jacobian_fd(b, 1e-6);
    coons_body *c = NULL;
    assert_coons_ok(coons_body_copy(b, &c, &err), &err);
    check_jacobian_fd(c, 1e-6);
    coons_body_free(c);
    coons_body_free(b);
    coons_patch_free(p);
    coons_curve *rows[2] = {fb.c[COONS_SIDE_T0], fb.c[COONS_SIDE_T1]};
    coons_curve *cols[2] = {fb.c[COONS_SIDE_S0], fb.c[COONS_SIDE_S1]};
    assert_coons_ok(coons_patch_new_network(rows, 2, cols, 2, NULL, &p, &err), &err);
    b = shell_of(p, 0.05, COONS_SHELL_BACK);
    check_jacobian_fd(b, 1e-6);
    coons_body_free(b);
    coons_patch_free(p);
    fx_boundary_free(&fb);
}

/* Given a cylinder of radius 1, then a shell of thickness 3 (both sides:
 * 1.5 inwards, past the axis) folds (det J < 0 inside) and one of
 * thickness 1.5 does not. */
static void test_fold(void **state)
{
    (void)state;
    coons_patch *p = quarter_cylinder(1, 2);
    coons_error err = COONS_ERROR_INIT;
    coons_body *b = shell_of(p, 3, COONS_SHELL_BOTH);
    double mn = 0, where[3];
    assert_coons_ok(coons_body_min_jacobian(b, 8, &mn, where, &err), &err);
    assert_true(mn < 0);
    assert_true(where[2] < 1.0 / 6); /* on the inner side, w - 1/2 < -1/3 */
    coons_body_free(b);
    b = shell_of(p, 1.5, COONS_SHELL_BOTH);
    assert_coons_ok(coons_body_min_jacobian(b, 8, &mn, where, &err), &err);
    assert_true(mn > 0);
    coons_body_free(b);
    coons_patch_free(p);
}

/* Given a surface with a collapsed edge (a triangle as a bilinear patch),
 * then the shell is refused and the message says where. */
static void test_undefined_normal(void **state)
{
    (void)state;
    const double X[12] = {0, 0, 0, 0, 0, 0, 0, 1, 0, 1, 1, 0};
    coons_patch *p = NULL;
    coons_body *b = NULL;
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(coons_patch_new_bilinear(X, &p, &err), &err);
    assert_int_equal(coons_body_new_shell(p, 1, COONS_SHELL_BOTH, &b, &err), COONS_E_INVALID);
    assert_null(b);
    assert_non_null(strstr(err.message, "normal is undefined at (s, t) = (0, 0)"));
    assert_int_equal(coons_body_new_shell(p, 0, COONS_SHELL_BOTH, &b, &err), COONS_E_INVALID);
    assert_int_equal(coons_body_new_shell(p, 1, (coons_shell_side)7, &b, &err), COONS_E_INVALID);
    coons_patch_free(p);

    const char *json =
        "{\"coons\": 1, \"bodies\": [{\"type\": \"shell\", \"thickness\": 1,\n"
        " \"surface\": {\"type\": \"bilinear\", \"corners\": [[0,0],[0,0],[0,1],[1,1]]}}]}";
    coons_model *m = NULL;
    assert_int_equal(coons_model_load_memory(json, strlen(json), "s.json", NULL, &m, &err),
                     COONS_E_INVALID);
    assert_string_equal(err.path, "/bodies/0/surface");
    assert_int_equal(err.line, 2);
    assert_non_null(strstr(err.message, "(s, t) = (0, 0)"));
    const char *bad[] = {
        "{\"coons\": 1, \"bodies\": [{\"type\": \"shell\", \"surface\": {\"type\": \"bilinear\", "
        "\"corners\": [[0,0],[1,0],[0,1],[1,1]]}}]}",
        "{\"coons\": 1, \"bodies\": [{\"type\": \"shell\", \"thickness\": -1, \"surface\": "
        "{\"type\": \"bilinear\", \"corners\": [[0,0],[1,0],[0,1],[1,1]]}}]}",
        "{\"coons\": 1, \"bodies\": [{\"type\": \"shell\", \"thickness\": 1, \"side\": \"left\", "
        "\"surface\": {\"type\": \"bilinear\", \"corners\": [[0,0],[1,0],[0,1],[1,1]]}}]}",
        "{\"coons\": 1, \"bodies\": [{\"type\": \"shell\", \"thickness\": 1, \"blend\": \"cubic\", "
        "\"surface\": {\"type\": \"bilinear\", \"corners\": [[0,0],[1,0],[0,1],[1,1]]}}]}"};
    const char *want[] = {"thickness", "/bodies/0/thickness", "/bodies/0/side", "/bodies/0/blend"};
    for (int k = 0; k < 4; k++) {
        assert_int_not_equal(
            coons_model_load_memory(bad[k], strlen(bad[k]), "s.json", NULL, &m, &err), COONS_OK);
        if (!strstr(err.message, want[k])) fail_msg("%d: %s", k, err.message);
    }
}

/* Given a shell of a network with a ridge (rows kinked at the middle node),
 * transformed by diag(1, 1, 2), then coons_body_network_seams measures the
 * ridge as instanced: x_s jumps from (2, 0, 4) to (2, 0, -4), relative
 * defect 8 / |(2, 0, 4)| and planes at acos(0.6); untransformed sqrt 2 and
 * 90 degrees. */
static void test_network_seams(void **state)
{
    (void)state;
    coons_curve *rows[2], *cols[3];
    coons_error err = COONS_ERROR_INIT;
    for (int j = 0; j < 2; j++) {
        double p[9] = {0, j, 0, 1, j, 1, 2, j, 0};
        assert_coons_ok(coons_curve_new_polyline(p, 3, &rows[j], &err), &err);
    }
    for (int i = 0; i < 3; i++) {
        double a[3] = {i, 0, i == 1}, b[3] = {i, 1, i == 1};
        assert_coons_ok(coons_curve_new_line(a, b, &cols[i], &err), &err);
    }
    coons_patch *p = NULL;
    assert_coons_ok(coons_patch_new_network(rows, 2, cols, 3, NULL, &p, &err), &err);
    coons_body *b = shell_of(p, 0.1, COONS_SHELL_FRONT), *t = NULL;
    const double M[12] = {1, 0, 0, 5, 0, 1, 0, 0, 0, 0, 2, 1};
    assert_coons_ok(coons_body_new_transformed(b, M, &t, &err), &err);
    coons_network_seam s[2];
    size_t n = 0;
    assert_coons_ok(coons_body_network_seams(b, s, 2, &n, &err), &err);
    assert_int_equal(n, 1);
    assert_int_equal(s[0].face, -1);
    assert_near(s[0].c1_defect, sqrt(2.0), 1e-6);
    assert_near(s[0].g1_angle, 90.0, 1e-4);
    assert_coons_ok(coons_body_network_seams(t, s, 2, &n, &err), &err);
    assert_int_equal(n, 1);
    assert_near(s[0].c1_defect, 8.0 / sqrt(20.0), 1e-6);
    assert_near(s[0].g1_angle, acos(0.6) * 180.0 / PI, 1e-4);
    /* a body without networks has none */
    const double X[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    coons_patch *plane = NULL;
    assert_coons_ok(coons_patch_new_bilinear(X, &plane, &err), &err);
    coons_body *q = shell_of(plane, 1, COONS_SHELL_BOTH);
    assert_coons_ok(coons_body_network_seams(q, NULL, 0, &n, &err), &err);
    assert_int_equal(n, 0);
    coons_body_free(q);
    coons_patch_free(plane);
    coons_body_free(t);
    coons_body_free(b);
    coons_patch_free(p);
    for (int k = 0; k < 2; k++) coons_curve_free(rows[k]);
    for (int k = 0; k < 3; k++) coons_curve_free(cols[k]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_plane_box),   cmocka_unit_test(test_cylinder_volume),
        cmocka_unit_test(test_jacobian_fd), cmocka_unit_test(test_fold),
        cmocka_unit_test(test_undefined_normal), cmocka_unit_test(test_network_seams),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
