/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * An ordinary client of an installed libcoons: includes only <coons.h>,
 * builds objects through the public API and checks values computed here by
 * hand. tests/cli/test_install.py builds it against the installed library
 * with pkg-config (shared and static) and with CMake's find_package(coons),
 * then runs it. Exit status 0 means every check passed.
 */
#include <coons.h>

#include <stdio.h>
#include <string.h>

static int failures;

static double dist3(const double a[3], const double b[3])
{
    double s = 0.0;
    for (int i = 0; i < 3; i++)
        s += (a[i] - b[i]) * (a[i] - b[i]);
    return s; /* squared: no libm needed */
}

static void check_point(const char *what, const double got[3], const double want[3])
{
    if (!(dist3(got, want) <= 1e-24)) {
        printf("FAIL %s: got (%.17g %.17g %.17g), want (%.17g %.17g %.17g)\n", what, got[0],
               got[1], got[2], want[0], want[1], want[2]);
        failures++;
    }
}

static void check(const char *what, int ok)
{
    if (!ok) {
        printf("FAIL %s\n", what);
        failures++;
    }
}

/* The run-time library is the one the header describes. */
static void test_version(void)
{
    char expect[32];
    snprintf(expect, sizeof expect, "%d.%d.%d", COONS_VERSION_MAJOR, COONS_VERSION_MINOR,
             COONS_VERSION_PATCH);
    check("coons_version() == COONS_VERSION_NUMBER", coons_version() == COONS_VERSION_NUMBER);
    check("coons_version_string() == COONS_VERSION_STRING",
          strcmp(coons_version_string(), COONS_VERSION_STRING) == 0);
    check("COONS_VERSION_STRING is major.minor.patch", strcmp(COONS_VERSION_STRING, expect) == 0);
}

/* Quadratic Bezier: x(1/2) = P0/4 + P1/2 + P2/4, derivative 2(P2 - P0)/2 = P2 - P0. */
static void test_curve(void)
{
    const double pts[9] = {0, 0, 0, 1, 2, 0, 3, 3, 1};
    coons_curve *c = NULL;
    coons_error err = COONS_ERROR_INIT;
    coons_status st = coons_curve_new_bezier(pts, 3, &c, &err);
    check("coons_curve_new_bezier succeeds", st == COONS_OK && c != NULL);
    if (c) {
        double p[3], d[2][3];
        const double want[3] = {1.25, 1.75, 0.25}, want_d[3] = {3, 3, 1};
        coons_curve_eval(c, 0.5, p);
        check_point("bezier(1/2)", p, want);
        coons_curve_eval_derivs(c, 0.5, 1, d);
        check_point("bezier'(1/2)", d[1], want_d);
        check("coons_curve_kind", coons_curve_kind(c) == COONS_CURVE_BEZIER);
    }
    coons_curve_free(c);
    coons_curve_free(NULL); /* a harmless no-op */
}

/* A failing call returns a negative status, fills err and leaves *out NULL. */
static void test_error(void)
{
    const double one[3] = {1, 2, 3};
    coons_curve *c = NULL;
    coons_error err = COONS_ERROR_INIT;
    coons_status st = coons_curve_new_polyline(one, 1, &c, &err);
    check("polyline of 1 point is COONS_E_INVALID", st == COONS_E_INVALID);
    check("err.code is the status", err.code == (int)st);
    check("err.message is set", err.message[0] != '\0');
    check("no object on failure", c == NULL);
    check("coons_strerror", coons_strerror(st) != NULL && coons_strerror(st)[0] != '\0');
    /* err may be NULL. */
    check("NULL err accepted", coons_curve_new_polyline(one, 1, &c, NULL) == COONS_E_INVALID);
}

/* A hexahedron with no parallel faces: P_ijk, index 4i + 2j + k. */
static void corner(int i, int j, int k, double p[3])
{
    p[0] = i + 0.2 * j * k - 0.1 * j;
    p[1] = j + 0.1 * i + 0.05 * k;
    p[2] = k + 0.3 * i * j;
}

/* Trilinear interpolation T(P; u,v,w) and dT/du, written out here. */
static void trilinear(double u, double v, double w, double x[3], double xu[3])
{
    const double bu[2] = {1 - u, u}, bv[2] = {1 - v, v}, bw[2] = {1 - w, w};
    for (int d = 0; d < 3; d++)
        x[d] = xu[d] = 0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) {
                double p[3];
                corner(i, j, k, p);
                for (int d = 0; d < 3; d++) {
                    x[d] += bu[i] * bv[j] * bw[k] * p[d];
                    xu[d] += (i ? 1 : -1) * bv[j] * bw[k] * p[d];
                }
            }
}

static const double params[4][3] = {{0, 0, 0}, {1, 1, 1}, {0.25, 0.5, 0.75}, {0.9, 0.1, 0.6}};

static void check_body(const char *what, const coons_body *b)
{
    for (int n = 0; n < 4; n++) {
        const double *q = params[n];
        double want[3], want_u[3], x[3], jx[3], jac[3][3], col[3];
        char label[96];
        trilinear(q[0], q[1], q[2], want, want_u);
        coons_body_eval(b, q[0], q[1], q[2], x);
        snprintf(label, sizeof label, "%s(%g,%g,%g)", what, q[0], q[1], q[2]);
        check_point(label, x, want);
        coons_body_eval_jacobian(b, q[0], q[1], q[2], jx, jac);
        for (int d = 0; d < 3; d++)
            col[d] = jac[d][0];
        snprintf(label, sizeof label, "%s_u(%g,%g,%g)", what, q[0], q[1], q[2]);
        check_point(label, col, want_u);
    }
}

/* Coons body 0 of the hexahedron is its trilinear map (seed 000). */
static void test_body0(void)
{
    double c[8][3];
    coons_body *b = NULL;
    coons_error err = COONS_ERROR_INIT;
    for (int n = 0; n < 8; n++)
        corner(n >> 2, (n >> 1) & 1, n & 1, c[n]);
    /* ISO C before C23 needs the cast from double (*)[3]; see libcoons(3). */
    coons_status st = coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b, &err);
    check("coons_body_new_body0 succeeds", st == COONS_OK && b != NULL);
    if (b) {
        check("coons_body_kind", coons_body_kind(b) == COONS_BODY_BODY0);
        check_body("body0", b);
    }
    coons_body_free(b);
}

/*
 * Coons body 2 whose faces are linear Coons patches of straight edges is
 * the trilinear map again (seed 000: body 2 with Coons faces is body 1,
 * body 1 with straight edges is body 0).
 */
static void test_body2(void)
{
    /* Corners X00, X10, X01, X11 of each face in its own (s,t). */
    static const int face[6][4] = {{0, 2, 1, 3}, {4, 6, 5, 7},  /* u0 u1: (v,w) */
                                   {0, 4, 1, 5}, {2, 6, 3, 7},  /* v0 v1: (u,w) */
                                   {0, 4, 2, 6}, {1, 5, 3, 7}}; /* w0 w1: (u,v) */
    coons_patch *faces[6] = {0};
    coons_body *b = NULL;
    coons_error err = COONS_ERROR_INIT;
    coons_status st = COONS_OK;
    for (int f = 0; f < 6 && st == COONS_OK; f++) {
        double x[4][3];
        coons_curve *edge[4] = {0};
        for (int n = 0; n < 4; n++)
            corner(face[f][n] >> 2, (face[f][n] >> 1) & 1, face[f][n] & 1, x[n]);
        st = coons_curve_new_line(x[0], x[1], &edge[COONS_SIDE_T0], &err); /* x(s,0) */
        if (st == COONS_OK) st = coons_curve_new_line(x[2], x[3], &edge[COONS_SIDE_T1], &err);
        if (st == COONS_OK) st = coons_curve_new_line(x[0], x[2], &edge[COONS_SIDE_S0], &err);
        if (st == COONS_OK) st = coons_curve_new_line(x[1], x[3], &edge[COONS_SIDE_S1], &err);
        if (st == COONS_OK)
            st = coons_patch_new_coons(edge, COONS_BLEND_LINEAR,
                                       COONS_TOL_DEFAULT, &faces[f], &err);
        for (int n = 0; n < 4; n++)
            coons_curve_free(edge[n]); /* the patch holds copies */
    }
    check("six Coons faces", st == COONS_OK);
    if (st == COONS_OK)
        st = coons_body_new_body2(faces, COONS_BLEND_LINEAR,
                                  COONS_TOL_DEFAULT, &b, &err);
    for (int f = 0; f < 6; f++)
        coons_patch_free(faces[f]); /* the body holds copies */
    check("coons_body_new_body2 succeeds", st == COONS_OK && b != NULL);
    if (st != COONS_OK)
        printf("  %s: %s\n", coons_strerror(st), err.message);
    if (b)
        check_body("body2", b);
    coons_body_free(b);
}

static double absd(double x) { return x < 0 ? -x : x; }

/* A body 0 box [lo, hi] (an axis-aligned hexahedron). */
static coons_status box(const double lo[3], const double hi[3], coons_body **out, coons_error *err)
{
    double c[8][3];
    for (int n = 0; n < 8; n++) {
        int ijk[3] = {n >> 2, (n >> 1) & 1, n & 1};
        for (int d = 0; d < 3; d++)
            c[n][d] = ijk[d] ? hi[d] : lo[d];
    }
    return coons_body_new_body0(c[0], COONS_BLEND_LINEAR, out, err);
}

/* Appends the single part of `from` to `to`. */
static coons_status append(coons_mesh *to, const coons_mesh *from, const char *name,
                           coons_error *err)
{
    return coons_mesh_add_part(to, name, coons_mesh_vertices(from),
                               coons_mesh_vertex_count(from), coons_mesh_triangles(from),
                               coons_mesh_triangle_count(from), err);
}

/*
 * The mesh layers (C, OpenMesh and CGAL when built in): a sampled box is a
 * closed, oriented shell enclosing exactly its volume, and the union of two
 * crossing boxes encloses 8 + 2 - 1 = 9. Through a static link this pulls
 * in the C++ objects, so their private dependencies must be linked too.
 */
static void test_mesh(void)
{
    const double lo_a[3] = {0, 0, 0}, hi_a[3] = {2, 2, 2};
    const double lo_b[3] = {1, 0.5, 0.5}, hi_b[3] = {3, 1.5, 1.5};
    coons_body *a = NULL, *b = NULL;
    coons_mesh *ma = NULL, *mb = NULL, *both = NULL, *u = NULL;
    coons_error err = COONS_ERROR_INIT;
    coons_status st = box(lo_a, hi_a, &a, &err);
    if (st == COONS_OK) st = box(lo_b, hi_b, &b, &err);
    if (st == COONS_OK) st = coons_body_sample(a, NULL, "a", &ma, &err);
    if (st == COONS_OK) st = coons_body_sample(b, NULL, "b", &mb, &err);
    check("two boxes sampled", st == COONS_OK);
    if (st != COONS_OK) {
        printf("  %s: %s\n", coons_strerror(st), err.message);
        goto done;
    }
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    st = coons_mesh_check(ma, &r, &err);
    check("coons_mesh_check succeeds", st == COONS_OK);
    check("sampled box is closed, manifold, oriented", r.closed && r.manifold && r.oriented);
    check("sampled box is one sphere-like shell", r.shells == 1 && r.euler == 2);
    check("sampled box encloses 8", absd(coons_mesh_volume(ma) - 8) <= 1e-12);
    check("sampled box has area 24", absd(coons_mesh_area(ma) - 24) <= 1e-12);

    st = coons_mesh_new(&both, &err);
    if (st == COONS_OK) st = append(both, ma, "a", &err);
    if (st == COONS_OK) st = append(both, mb, "b", &err);
    check("two-part mesh", st == COONS_OK && coons_mesh_part_count(both) == 2);
    if (st != COONS_OK)
        goto done;
    coons_csg_report cr = COONS_CSG_REPORT_INIT;
    st = coons_mesh_solidify(both, NULL, &u, &cr, &err);
    if (!coons_csg_is_available()) {
        check("without CGAL, solidify is COONS_E_UNSUPPORTED", st == COONS_E_UNSUPPORTED);
        goto done;
    }
    check("coons_mesh_solidify succeeds", st == COONS_OK && u != NULL);
    if (st != COONS_OK) {
        printf("  %s: %s\n", coons_strerror(st), err.message);
        goto done;
    }
    check("union is one closed part", cr.closed && coons_mesh_part_count(u) == 1);
    check("union encloses 9", absd(coons_mesh_volume(u) - 9) <= 1e-9);
done:
    coons_mesh_free(u);
    coons_mesh_free(both);
    coons_mesh_free(mb);
    coons_mesh_free(ma);
    coons_body_free(b);
    coons_body_free(a);
}

int main(void)
{
    test_version();
    test_curve();
    test_error();
    test_body0();
    test_body2();
    test_mesh();
    if (failures) {
        printf("%d check(s) failed\n", failures);
        return 1;
    }
    printf("consumer: all checks passed (libcoons %s)\n", coons_version_string());
    return 0;
}
