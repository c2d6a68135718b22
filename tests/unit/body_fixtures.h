/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Sample bodies shared by the body tests (header-only: every tests/test_*.c
 * is its own executable). Everything here is static inline so that a file
 * that uses only part of it stays warning-free. */
#ifndef COONS_BODY_FIXTURES_H
#define COONS_BODY_FIXTURES_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Deterministic uniform numbers in [0,1). */
typedef struct tb_rng {
    unsigned long long s;
} tb_rng;

static inline double tb_rand(tb_rng *r)
{
    r->s = r->s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(r->s >> 11) / 9007199254740992.0;
}

/* A skew hexahedron (no two faces parallel), P_ijk at 4i+2j+k. */
static inline const double (*tb_hex(void))[3]
{
    static const double hex[8][3] = {{0, 0, 0},        {0.1, -0.2, 1.1}, {0.2, 1.0, -0.1},
                                     {-0.1, 1.2, 0.9}, {1.0, 0.1, 0.2},  {1.3, 0.0, 1.2},
                                     {0.9, 0.8, 0.1},  {1.2, 1.1, 1.4}};
    return hex;
}

/* Corner indices at t = 0 and t = 1 of body edge n (body.h order). */
static inline void tb_edge_corners(int n, int *a, int *b)
{
    int dir = n / 4, x = (n >> 1) & 1, y = n & 1;
    if (dir == 0) {
        *a = 2 * x + y;
        *b = 4 + *a;
    } else if (dir == 1) {
        *a = 4 * x + y;
        *b = *a + 2;
    } else {
        *a = 4 * x + 2 * y;
        *b = *a + 1;
    }
}

/* Curved edges over tb_hex(): cubic Beziers whose inner control points are
 * pushed off the straight line. On failure every curve made is freed. */
static inline int tb_curved_edges(coons_curve *e[12], coons_error *err)
{
    const double(*hex)[3] = tb_hex();
    memset(e, 0, 12 * sizeof e[0]);
    for (int n = 0; n < 12; n++) {
        int a, b;
        tb_edge_corners(n, &a, &b);
        double p[12];
        for (int r = 0; r < 3; r++) {
            p[r] = hex[a][r];
            p[9 + r] = hex[b][r];
            p[3 + r] = (2 * hex[a][r] + hex[b][r]) / 3 + 0.15 * sin(1.0 + n + 2 * r);
            p[6 + r] = (hex[a][r] + 2 * hex[b][r]) / 3 + 0.2 * cos(2.0 + 3 * n + r);
        }
        int rc = coons_curve_new_bezier(p, 4, &e[n], err);
        if (rc) {
            for (int m = 0; m < n; m++) coons_curve_free(e[m]);
            return rc;
        }
    }
    return COONS_OK;
}

/* NURBS solid cylinder of radius r and height h about the z axis:
 * u around (the quadratic 9-point circle), v from the axis out, w up;
 * every weight multiplied by wscale (the same map whatever wscale). */
static inline int tb_nurbs_cylinder_scaled_rc(double r, double h, double wscale,
                                              coons_body **out, coons_error *err)
{
    const double s = sqrt(0.5);
    const double c[9][3] = {{1, 0, 1}, {1, 1, s},  {0, 1, 1},  {-1, 1, s}, {-1, 0, 1},
                            {-1, -1, s}, {0, -1, 1}, {1, -1, s}, {1, 0, 1}};
    double P[9 * 2 * 2 * 3], W[9 * 2 * 2];
    for (int i = 0; i < 9; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) {
                int idx = (i * 2 + j) * 2 + k;
                P[3 * idx] = j * r * c[i][0];
                P[3 * idx + 1] = j * r * c[i][1];
                P[3 * idx + 2] = k * h;
                W[idx] = c[i][2] * wscale;
            }
    double ku[12] = {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
    const double *kn[3] = {ku, NULL, NULL};
    int deg[3] = {2, 1, 1};
    size_t n[3] = {9, 2, 2};
    return coons_body_new_bspline(deg, P, n, kn[0], kn[1], kn[2], W, out, err);
}

static inline int tb_nurbs_cylinder_rc(double r, double h, coons_body **out, coons_error *err)
{
    return tb_nurbs_cylinder_scaled_rc(r, h, 1.0, out, err);
}

static inline void tb_nurbs_cylinder(double r, double h, coons_body **out)
{
    coons_error err = COONS_ERROR_INIT;
    assert_coons_ok(tb_nurbs_cylinder_rc(r, h, out, &err), &err);
}

/* Net point (i,j,k) of a deformed unit cube sampled m x m x m. */
static inline void tb_cube_net(int m, int i, int j, int k, double p[3])
{
    double x = (double)i / (m - 1), y = (double)j / (m - 1), z = (double)k / (m - 1);
    /* terms in all three variables, so that no face is the Coons patch of
     * its edges and opposite faces differ */
    p[0] = x + 0.08 * sin(3.0 * y + 1.0) * sin(2.0 * z) + 0.05 * sin(4.0 * x * y + z);
    p[1] = y + 0.06 * cos(2.0 * x + 0.5) * sin(3.0 * z + 0.3) + 0.04 * cos(3.0 * x * z - y);
    p[2] = z + 0.1 * sin(2.5 * x) * cos(1.5 * y) + 0.05 * x * y + 0.06 * sin(2.0 * y * z + x);
}

/* The six bicubic B-spline faces (body.h order and parametrisations) of
 * that net, m x m control points each: boundary slices of one lattice, so
 * they agree exactly along shared edges. On failure all made are freed. */
static inline int tb_bspline_faces(int m, coons_patch *f[6], coons_error *err)
{
    memset(f, 0, 6 * sizeof f[0]);
    double *pts = malloc((size_t)m * m * 3 * sizeof *pts);
    int rc = COONS_OK;
    for (int n = 0; n < 6 && !rc; n++) {
        int fixed = (n & 1) ? m - 1 : 0;
        for (int a = 0; a < m; a++)
            for (int b = 0; b < m; b++) {
                double *p = pts + (a * m + b) * 3;
                if (n < 2)
                    tb_cube_net(m, fixed, a, b, p); /* X_I(v,w) */
                else if (n < 4)
                    tb_cube_net(m, a, fixed, b, p); /* Y_J(u,w) */
                else
                    tb_cube_net(m, a, b, fixed, p); /* Z_K(u,v) */
            }
        rc = coons_patch_new_bspline(3, 3, pts, (size_t)m, (size_t)m, NULL, NULL, NULL, &f[n], err);
    }
    free(pts);
    if (rc)
        for (int n = 0; n < 6; n++) coons_patch_free(f[n]);
    return rc;
}

#define TB_NO_BODY 1
#define TB_MAX_BODIES 10

static inline const char *tb_body_label(int m)
{
    static const char *const names[TB_MAX_BODIES] = {
        "body0 linear", "body0 cubic", "body1 linear", "body1 cubic",
        "bezier 3x4x3", "bspline", "nurbs cylinder", "nurbs random",
        "body2 linear", "body2 cubic"};
    return (m >= 0 && m < TB_MAX_BODIES) ? names[m] : "?";
}

/* Sample body m (0 <= m < TB_MAX_BODIES); TB_NO_BODY past the end. Returns
 * the constructor's status and cleans up after itself on failure. */
static inline int tb_make_body(int m, coons_body **b, coons_error *err)
{
    *b = NULL;
    switch (m) {
    case 0:
    case 1:
        return coons_body_new_body0(tb_hex()[0], m == 0 ? COONS_BLEND_LINEAR : COONS_BLEND_CUBIC, b,
                                    err);
    case 2:
    case 3: {
        coons_curve *e[12];
        int rc = tb_curved_edges(e, err);
        if (rc) return rc;
        rc = coons_body_new_body1(e,
                                  m == 2 ? COONS_BLEND_LINEAR : COONS_BLEND_CUBIC, COONS_TOL_DEFAULT,
                                  b, err);
        for (int n = 0; n < 12; n++) coons_curve_free(e[n]);
        return rc;
    }
    case 4: {
        size_t n[3] = {3, 4, 3};
        double P[3 * 4 * 3 * 3];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 4; j++)
                for (int k = 0; k < 3; k++) {
                    double *p = P + ((i * 4 + j) * 3 + k) * 3;
                    p[0] = i + 0.2 * sin(j + 2.0 * k);
                    p[1] = j + 0.3 * cos(i * k + 1.0);
                    p[2] = k + 0.1 * i * j;
                }
        return coons_body_new_bezier(P, n, b, err);
    }
    case 5:
    case 7: {
        int deg[3] = {2, 3, 2};
        size_t n[3] = {5, 6, 4};
        double ku[8] = {0, 0, 0, 0.3, 0.6, 1, 1, 1};
        double kv[10] = {0, 0, 0, 0, 0.2, 0.7, 1, 1, 1, 1};
        const double *kn[3] = {ku, kv, NULL};
        double P[5 * 6 * 4 * 3], W[5 * 6 * 4];
        for (int i = 0; i < 5; i++)
            for (int j = 0; j < 6; j++)
                for (int k = 0; k < 4; k++) {
                    int idx = (i * 6 + j) * 4 + k;
                    P[3 * idx] = i + 0.2 * sin(j + 2.0 * k);
                    P[3 * idx + 1] = 0.8 * j + 0.3 * cos(i * k + 1.0);
                    P[3 * idx + 2] = 1.2 * k + 0.1 * i * j;
                    W[idx] = 0.6 + 0.5 * fabs(sin(1.0 + idx));
                }
        return coons_body_new_bspline(deg, P, n, kn[0], kn[1], kn[2], m == 7 ? W : NULL, b, err);
    }
    case 6: return tb_nurbs_cylinder_rc(1.5, 2.0, b, err);
    case 8:
    case 9: {
        coons_patch *f[6];
        int rc = tb_bspline_faces(6, f, err);
        if (rc) return rc;
        rc = coons_body_new_body2(f,
                                  m == 8 ? COONS_BLEND_LINEAR : COONS_BLEND_CUBIC, COONS_TOL_DEFAULT,
                                  b, err);
        for (int n = 0; n < 6; n++) coons_patch_free(f[n]);
        return rc;
    }
    default: return TB_NO_BODY;
    }
}

/* All sample bodies; asserts that each builds. Returns the count. */
static inline int tb_all_bodies(coons_body *out[TB_MAX_BODIES])
{
    for (int m = 0; m < TB_MAX_BODIES; m++) {
        coons_error err = COONS_ERROR_INIT;
        assert_coons_ok(tb_make_body(m, &out[m], &err), &err);
    }
    return TB_MAX_BODIES;
}

#endif
