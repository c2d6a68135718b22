/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Every public function that takes an array, called the way a C user would:
 * ordinary arrays (`double c[8][3]` passed as `c[0]`, flat `double p[12]`,
 * `coons_curve *edges[12]` as returned by the constructors) and no cast
 * anywhere in this file (tests/cli/test_api_calls.py checks that, and
 * compiles it with gcc and clang as -std=c11, -std=c17 and -std=c2x with
 * -Wall -Wextra -Wpedantic -Werror, then runs it). A signature that needs a
 * cast fails the compile. The values checked are worked out by hand.
 */
#include <coons.h>

#include <stdint.h>
#include <stdio.h>
#include <string.h>

static int failures;

static void check(const char *what, int ok)
{
    if (!ok) {
        printf("FAIL %s\n", what);
        failures++;
    }
}

static int near3(const double a[3], double x, double y, double z)
{
    double d[3] = {a[0] - x, a[1] - y, a[2] - z};
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= 1e-24;
}

/* The unit cube's corner P_ijk = (i, j, k) at index 4i + 2j + k. */
static void cube(double c[8][3])
{
    for (int n = 0; n < 8; n++) {
        c[n][0] = n >> 2;
        c[n][1] = (n >> 1) & 1;
        c[n][2] = n & 1;
    }
}

/* Edge e of the unit cube as a line (coons_body_edge order). */
static coons_status cube_edge(double c[8][3], int e, coons_curve **out, coons_error *err)
{
    /* u edges: (J,K) fixed; v: (I,K); w: (I,J). */
    int dir = e / 4, a = (e >> 1) & 1, b = e & 1;
    int i0 = dir == 0 ? 0 : a, j0 = dir == 1 ? 0 : (dir == 0 ? a : b), k0 = dir == 2 ? 0 : b;
    int i1 = dir == 0 ? 1 : i0, j1 = dir == 1 ? 1 : j0, k1 = dir == 2 ? 1 : k0;
    return coons_curve_new_line(c[4 * i0 + 2 * j0 + k0], c[4 * i1 + 2 * j1 + k1], out, err);
}

static void curves(void)
{
    coons_error err = COONS_ERROR_INIT;
    double p0[3] = {0, 0, 0}, p1[3] = {2, 0, 0}, t0[3] = {1, 1, 0}, t1[3] = {1, -1, 0};
    double pts[5][3] = {{0, 0, 0}, {1, 1, 0}, {2, 0, 0}, {3, 1, 0}, {4, 0, 0}};
    double knots[9] = {0, 0, 0, 0, 0.5, 1, 1, 1, 1};
    double weights[5] = {1, 2, 1, 2, 1};
    double clamped[15], d[3][3], lo[3], hi[3], seg[64];
    size_t nseg = 0;
    int deg = 0;
    coons_curve *c[8] = {0};
    check("line", coons_curve_new_line(p0, p1, &c[0], &err) == COONS_OK);
    check("polyline", coons_curve_new_polyline(pts[0], 5, &c[1], &err) == COONS_OK);
    check("bezier", coons_curve_new_bezier(pts[0], 3, &c[2], &err) == COONS_OK);
    check("hermite", coons_curve_new_hermite(p0, t0, p1, t1, &c[3], &err) == COONS_OK);
    check("coons cubic", coons_curve_new_coons_cubic(pts[0], 5, 0, &c[4], &err) == COONS_OK);
    check("clamped cubic", coons_curve_new_clamped_cubic(pts[0], 5, &c[5], &err) == COONS_OK);
    check("bspline", coons_curve_new_bspline(3, pts[0], 5, knots, weights, &c[6], &err) == COONS_OK);
    check("copy", coons_curve_copy(c[0], &c[7], &err) == COONS_OK);
    check("open to clamped",
          coons_curve_convert_open_to_clamped(pts[0], 5, clamped, &err) == COONS_OK);
    /* P0 = P~0/6 + 2P~1/3 + P~2/6 = (1, 2/3, 0) */
    check("open to clamped P0", near3(clamped, 1.0, 2.0 / 3.0, 0.0));
    coons_curve_eval_derivs(c[0], 0.5, 2, d);
    check("line midpoint and slope", near3(d[0], 1, 0, 0) && near3(d[1], 2, 0, 0));
    coons_curve_control_bbox(c[1], lo, hi);
    check("polyline box", near3(lo, 0, 0, 0) && near3(hi, 4, 1, 0));
    check("bezier segments",
          coons_curve_bezier_segments(c[5], seg, 64, &nseg, &deg, &err) == COONS_OK &&
              nseg == 2 && deg == 3);
    /* transforms: a flat double[12], or m[0] of a double[3][4] */
    double mflat[12] = {1, 0, 0, 5, 0, 1, 0, 0, 0, 0, 1, 0};
    double mrows[3][4] = {{0, -1, 0, 0}, {1, 0, 0, 0}, {0, 0, 1, 0}};
    coons_curve *xc[3] = {0};
    check("curve transformed flat",
          coons_curve_new_transformed(c[0], mflat, &xc[0], &err) == COONS_OK);
    check("curve transformed rows",
          coons_curve_new_transformed(c[0], mrows[0], &xc[1], &err) == COONS_OK);
    check("curve reversed", coons_curve_new_reversed(c[0], &xc[2], &err) == COONS_OK);
    coons_curve_eval(xc[0], 0.5, d[0]);
    coons_curve_eval(xc[1], 0.5, d[1]);
    coons_curve_eval(xc[2], 0.25, d[2]);
    check("transformed and reversed points",
          near3(d[0], 6, 0, 0) && near3(d[1], 0, 1, 0) && near3(d[2], 1.5, 0, 0));
    for (int k = 0; k < 3; k++) coons_curve_free(xc[k]);
    for (int k = 0; k < 8; k++) coons_curve_free(c[k]);
}

static void patches(void)
{
    coons_error err = COONS_ERROR_INIT;
    double corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1}};
    double flat[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1};
    double net[2][2][3] = {{{0, 0, 0}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 1}}};
    double x[3], d[6][3], lo[3], hi[3], grid[2 * 2 * 3], s[2] = {0, 1};
    coons_curve *side[4] = {0};
    check("t0", coons_curve_new_line(corners[0], corners[1], &side[COONS_SIDE_T0], &err) == 0);
    check("t1", coons_curve_new_line(corners[2], corners[3], &side[COONS_SIDE_T1], &err) == 0);
    check("s0", coons_curve_new_line(corners[0], corners[2], &side[COONS_SIDE_S0], &err) == 0);
    check("s1", coons_curve_new_line(corners[1], corners[3], &side[COONS_SIDE_S1], &err) == 0);
    coons_hermite_options ho = COONS_HERMITE_OPTIONS_INIT;
    ho.twist = COONS_TWIST_EXPLICIT;
    ho.twists[3][2] = 1.0;
    coons_patch *p[8] = {0};
    check("bilinear c[0]", coons_patch_new_bilinear(corners[0], &p[0], &err) == COONS_OK);
    check("bilinear flat", coons_patch_new_bilinear(flat, &p[1], &err) == COONS_OK);
    check("ruled", coons_patch_new_ruled(side[COONS_SIDE_T0], side[COONS_SIDE_T1], &p[2], &err) ==
                       COONS_OK);
    check("coons", coons_patch_new_coons(side, COONS_BLEND_LINEAR, COONS_TOL_DEFAULT, &p[3],
                                         &err) == COONS_OK);
    check("hermite coons", coons_patch_new_hermite_coons(side, &ho, &p[4], &err) == COONS_OK);
    check("bezier surface", coons_patch_new_bezier(net[0][0], 2, 2, &p[5], &err) == COONS_OK);
    check("bspline surface", coons_patch_new_bspline(1, 1, net[0][0], 2, 2, NULL, NULL, NULL,
                                                     &p[6], &err) == COONS_OK);
    check("copy", coons_patch_copy(p[3], &p[7], &err) == COONS_OK);
    /* Every one of them is the bilinear patch: x(1/2,1/2) = (1/2, 1/2, 1/4). */
    for (int k = 0; k < 8; k++) {
        coons_patch_eval(p[k], 0.5, 0.5, x);
        check("patch centre", k == 4 || near3(x, 0.5, 0.5, 0.25));
    }
    coons_patch_eval_derivs(p[0], 0.5, 0.5, 1, d);
    check("bilinear x_s", near3(d[1], 1, 0, 0.5));
    coons_patch_control_bbox(p[5], lo, hi);
    check("net box", near3(lo, 0, 0, 0) && near3(hi, 1, 1, 1));
    check("grid", coons_patch_eval_grid(p[1], s, 2, s, 2, grid, &err) == COONS_OK &&
                      near3(grid + 9, 1, 1, 1));
    double pm[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 2}};
    coons_patch *xp[2] = {0};
    check("patch transformed", coons_patch_new_transformed(p[0], pm[0], &xp[0], &err) == COONS_OK);
    check("patch reparametrized",
          coons_patch_new_reparametrized(p[0], 1, 0, 0, &xp[1], &err) == COONS_OK);
    coons_patch_eval(xp[0], 0.5, 0.5, d[0]);
    coons_patch_eval(xp[1], 0.5, 0.5, d[1]);
    check("transformed and swapped patch points",
          near3(d[0], 0.5, 0.5, 2.25) && near3(d[1], 0.5, 0.5, 0.25));
    /* The spline form of the Coons patch: a plain param array, out[3]. */
    coons_nurbs n = {0};
    double st[2] = {0.5, 0.5};
    check("patch to nurbs", coons_patch_to_nurbs(p[3], 1e-9, &n, &err) == COONS_OK && n.exact);
    coons_nurbs_eval(&n, st, x);
    check("nurbs centre", near3(x, 0.5, 0.5, 0.25));
    coons_nurbs_free(&n);
    for (int k = 0; k < 2; k++) coons_patch_free(xp[k]);
    for (int k = 0; k < 8; k++) coons_patch_free(p[k]);
    for (int k = 0; k < 4; k++) coons_curve_free(side[k]);
}

static void bodies(void)
{
    coons_error err = COONS_ERROR_INIT;
    double c[8][3], flat[24], pts[2][2][2][3], x[3], jac[3][3], lo[3], hi[3], vol = 0;
    double knots[4] = {0, 0, 1, 1}, u[2] = {0, 1}, grid[8 * 3], mind = 0, where[3];
    int degree[3] = {1, 1, 1};
    size_t n[3] = {2, 2, 2};
    cube(c);
    memcpy(flat, c, sizeof flat);
    memcpy(pts, c, sizeof pts);
    coons_curve *edge[12] = {0};
    for (int e = 0; e < 12; e++) check("edge", cube_edge(c, e, &edge[e], &err) == COONS_OK);
    coons_patch *face[6] = {0};
    for (int f = 0; f < 6; f++) {
        /* Face f at (dir = f/2) = f%2: its corners X00, X10, X01, X11. */
        double q[4][3];
        int dir = f / 2, at = f % 2;
        for (int a = 0; a < 2; a++)
            for (int b = 0; b < 2; b++) {
                int ijk[3];
                ijk[dir] = at;
                ijk[dir == 0 ? 1 : 0] = a;
                ijk[dir == 2 ? 1 : 2] = b;
                memcpy(q[a + 2 * b], c[4 * ijk[0] + 2 * ijk[1] + ijk[2]], sizeof q[0]);
            }
        check("face", coons_patch_new_bilinear(q[0], &face[f], &err) == COONS_OK);
    }
    coons_body *b[7] = {0};
    check("body0 c[0]", coons_body_new_body0(c[0], COONS_BLEND_LINEAR, &b[0], &err) == COONS_OK);
    check("body0 flat", coons_body_new_body0(flat, COONS_BLEND_CUBIC, &b[1], &err) == COONS_OK);
    check("body1", coons_body_new_body1(edge, COONS_BLEND_LINEAR, COONS_TOL_DEFAULT, &b[2],
                                        &err) == COONS_OK);
    check("body2", coons_body_new_body2(face, COONS_BLEND_LINEAR, COONS_TOL_DEFAULT, &b[3],
                                        &err) == COONS_OK);
    check("bezier volume", coons_body_new_bezier(pts[0][0][0], n, &b[4], &err) == COONS_OK);
    check("bspline volume", coons_body_new_bspline(degree, pts[0][0][0], n, knots, knots, knots,
                                                   NULL, &b[5], &err) == COONS_OK);
    check("copy", coons_body_copy(b[2], &b[6], &err) == COONS_OK);
    for (int k = 0; k < 7; k++) {
        coons_body_eval(b[k], 0.25, 0.5, 0.75, x);
        check("body point", near3(x, 0.25, 0.5, 0.75) || k == 1);
        /* det J = 1 for the identity map; 1.5^3 for body 0's cubic blend
         * (f'(1/2) = -3/2 for f(t) = 1 - 3t^2 + 2t^3). */
        double det = coons_body_eval_jacobian(b[k], 0.5, 0.5, 0.5, x, jac);
        double want = k == 1 ? 3.375 : 1.0;
        if (!(det > want - 1e-12 && det < want + 1e-12)) printf("body %d: det J %.17g\n", k, det);
        check("body det J at the centre", det > want - 1e-12 && det < want + 1e-12);
    }
    coons_body_control_bbox(b[0], lo, hi);
    check("body box", near3(lo, 0, 0, 0) && near3(hi, 1, 1, 1));
    check("body grid", coons_body_eval_grid(b[3], u, 2, u, 2, u, 2, grid, &err) == COONS_OK &&
                           near3(grid + 21, 1, 1, 1));
    check("volume", coons_body_volume(b[2], 1e-12, &vol, &err) == COONS_OK && vol > 0.999999 &&
                        vol < 1.000001);
    check("min det J", coons_body_min_jacobian(b[0], 4, &mind, where, &err) == COONS_OK);
    coons_mesh *m = NULL;
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.resolution = 2;
    check("sample", coons_body_sample(b[0], &so, "cube", &m, &err) == COONS_OK);
    size_t tf = 0, tc = 0, vf = 0, vc = 0;
    coons_mesh_part_range(m, 0, &tf, &tc, &vf, &vc);
    /* flat faces meshed from their 8-point boundary rings: 8 - 2 triangles
     * each, on the 8 + 12 lattice points of the edges */
    check("cube mesh: 6 flat faces of 8 - 2 triangles", tc == 36 && vc == 20);
    double tol = 0, dev = 0;
    size_t lattice[3];
    check("sampling", coons_mesh_part_sampling(m, 0, &tol, &dev, lattice) && lattice[0] == 2);
    coons_mesh_free(m);
    double bm[12] = {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    coons_body *xb = NULL;
    check("body transformed", coons_body_new_transformed(b[2], bm, &xb, &err) == COONS_OK &&
                                  coons_body_volume(xb, 1e-12, &vol, &err) == COONS_OK &&
                                  vol < -0.999999 && vol > -1.000001);
    coons_body_free(xb);
    for (int k = 0; k < 7; k++) coons_body_free(b[k]);
    for (int f = 0; f < 6; f++) coons_patch_free(face[f]);
    for (int e = 0; e < 12; e++) coons_curve_free(edge[e]);
}

static void models_and_meshes(void)
{
    coons_error err = COONS_ERROR_INIT;
    static const char text[] =
        "{\"coons\": 1, \"bodies\": [{\"type\": \"body0\", \"corners\": [[0,0,0],[0,0,1],[0,1,0],"
        "[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]}";
    coons_model_load_options lo = COONS_MODEL_LOAD_OPTIONS_INIT;
    coons_model *model = NULL;
    check("load memory", coons_model_load_memory(text, sizeof text - 1, "cube.json", &lo, &model,
                                                 &err) == COONS_OK);
    double box_lo[3], box_hi[3];
    coons_model_control_bbox(model, box_lo, box_hi);
    check("model box", near3(box_hi, 1, 1, 1));
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    so.resolution = 1;
    coons_mesh *m = NULL;
    check("model sample", coons_model_sample(model, &so, &m, &err) == COONS_OK &&
                              coons_mesh_triangle_count(m) == 12);
    coons_mesh_free(m);
    m = NULL;
    coons_csg_options co = COONS_CSG_OPTIONS_INIT;
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    coons_status st = coons_model_solidify(model, &so, &co, &m, &rep, &err);
    check("model solidify", st == COONS_OK && coons_mesh_triangle_count(m) == 12);
    coons_mesh_free(m);
    /* Exact solids: a STEP file when the library has Open CASCADE, else
     * the refusal naming it; a mesh format is no solid format. */
    const char *step = "coons-calls-solid.step";
    st = coons_model_write_solid(model, step, COONS_FORMAT_AUTO, NULL, &err);
    check("write solid", coons_solid_formats_available()
                             ? st == COONS_OK
                             : st == COONS_E_UNSUPPORTED && strstr(err.message, "Open CASCADE"));
    remove(step);
    check("solid format", coons_format_kind(COONS_FORMAT_STEP) == COONS_MESH_KIND_SOLID &&
                              coons_model_write_solid(model, "x.stl", COONS_FORMAT_AUTO, NULL,
                                                      &err) == COONS_E_INVALID);
    coons_model_free(model);
    model = NULL;
    check("load file (missing)", coons_model_load_file("/nonexistent/m.json", NULL, &model,
                                                       &err) == COONS_E_IO);

    /* A tetrahedron from plain arrays. */
    double xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    uint32_t tri[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    check("mesh new", coons_mesh_new(&m, &err) == COONS_OK);
    check("add part", coons_mesh_add_part(m, "tet", xyz[0], 4, tri[0], 4, &err) == COONS_OK);
    double v = coons_mesh_volume(m);
    check("tetrahedron volume 1/6", v > 1.0 / 6 - 1e-15 && v < 1.0 / 6 + 1e-15);
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    check("check", coons_mesh_check(m, &r, &err) == COONS_OK && r.closed && r.oriented);
    size_t pairs = 1;
    st = coons_mesh_count_self_intersections(m, &pairs, &err);
    check("self intersections", (st == COONS_OK && pairs == 0) || st == COONS_E_UNSUPPORTED);
    coons_format fmt = COONS_FORMAT_AUTO;
    check("format from path", coons_format_from_path("x.off", &fmt, &err) == COONS_OK &&
                                  fmt == COONS_FORMAT_OFF);
    coons_mesh_free(m);
}

static void volume_meshes(void)
{
    coons_error err = COONS_ERROR_INIT;
    double c[8][3];
    cube(c);
    /* One hex8 cell in Gmsh's corner order: the bottom (z = 0) square
     * counter-clockwise, then the top one. */
    uint32_t cell[8] = {0, 4, 6, 2, 1, 5, 7, 3};
    uint32_t bottom[4] = {0, 4, 6, 2}, face[2] = {0, 4};
    double u[8];
    int32_t body[1] = {0};
    for (int n = 0; n < 8; n++) u[n] = c[n][0];
    coons_volume_mesh *vm = NULL;
    size_t first = 9, part = 9;
    check("volume mesh new", coons_volume_mesh_new(COONS_ELEMENT_HEX8, &vm, &err) == COONS_OK);
    check("add nodes", coons_volume_mesh_add_nodes(vm, c[0], 8, &first, &err) == COONS_OK &&
                           first == 0);
    check("add part", coons_volume_mesh_add_part(vm, "cube", &part, &err) == COONS_OK &&
                          part == 0);
    check("add cells", coons_volume_mesh_add_cells(vm, cell, 1, part, &first, &err) == COONS_OK);
    check("node field", coons_volume_mesh_add_field(vm, COONS_FIELD_NODE, "u", COONS_FIELD_FLOAT64,
                                                    u, &err) == COONS_OK);
    check("cell field", coons_volume_mesh_add_field(vm, COONS_FIELD_CELL, "body", COONS_FIELD_INT32,
                                                    body, &err) == COONS_OK);
    check("node set", coons_volume_mesh_add_node_set(vm, "bottom", bottom, 4, &err) == COONS_OK);
    uint32_t all[1] = {0};
    check("cell set", coons_volume_mesh_add_cell_set(vm, "all", all, 1, &err) == COONS_OK);
    check("face set", coons_volume_mesh_add_face_set(vm, "w0", face, 1, &err) == COONS_OK);
    const uint32_t *items = NULL;
    size_t count = 0;
    check("node set view", coons_volume_mesh_node_set(vm, 0, &items, &count) && count == 4 &&
                               items[3] == 2);
    check("cells view", coons_volume_mesh_cells(vm)[1] == 4 &&
                            coons_volume_mesh_node_count(vm) == 8);
    coons_volume_mesh_free(vm);
}

int main(void)
{
    curves();
    patches();
    bodies();
    models_and_meshes();
    volume_meshes();
    if (failures) return 1;
    printf("calls: every check passed\n");
    return 0;
}
