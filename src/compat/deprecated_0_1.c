/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The 0.1 names (include/coons/deprecated.h) as wrappers over the 0.2
 * functions, for one release. The casts are the conversions a 0.1 caller's
 * arrays need to reach the 0.2 parameters; they change no value.
 */
#include <coons.h>

coons_status coons_curve_line(const double p0[3], const double p1[3], coons_curve **out,
                              coons_error *err)
{
    return coons_curve_new_line(p0, p1, out, err);
}

coons_status coons_curve_polyline(const double *points, size_t count, coons_curve **out,
                                  coons_error *err)
{
    return coons_curve_new_polyline(points, count, out, err);
}

coons_status coons_curve_bezier(const double *points, size_t count, coons_curve **out,
                                coons_error *err)
{
    return coons_curve_new_bezier(points, count, out, err);
}

coons_status coons_curve_hermite(const double p0[3], const double t0[3], const double p1[3],
                                 const double t1[3], coons_curve **out, coons_error *err)
{
    return coons_curve_new_hermite(p0, t0, p1, t1, out, err);
}

coons_status coons_curve_coons_cubic(const double *points, size_t count, int closed,
                                     coons_curve **out, coons_error *err)
{
    return coons_curve_new_coons_cubic(points, count, closed, out, err);
}

coons_status coons_curve_clamped_cubic(const double *points, size_t count, coons_curve **out,
                                       coons_error *err)
{
    return coons_curve_new_clamped_cubic(points, count, out, err);
}

coons_status coons_curve_bspline(int degree, const double *points, size_t count,
                                 const double *knots, const double *weights, coons_curve **out,
                                 coons_error *err)
{
    return coons_curve_new_bspline(degree, points, count, knots, weights, out, err);
}

coons_status coons_cubic_open_to_clamped(const double *open, size_t count, double *clamped,
                                         coons_error *err)
{
    return coons_curve_convert_open_to_clamped(open, count, clamped, err);
}

coons_status coons_patch_bilinear(const double corners[4][3], coons_patch **out, coons_error *err)
{
    return coons_patch_new_bilinear(corners ? corners[0] : NULL, out, err);
}

coons_status coons_patch_ruled(const coons_curve *c0, const coons_curve *c1, coons_patch **out,
                               coons_error *err)
{
    return coons_patch_new_ruled(c0, c1, out, err);
}

coons_status coons_patch_coons(const coons_curve *const boundary[4], coons_blend blend,
                               double tol, coons_patch **out, coons_error *err)
{
    return coons_patch_new_coons((coons_curve *const *)boundary, blend, tol, out, err);
}

coons_status coons_patch_hermite_coons(const coons_curve *const boundary[4],
                                       const coons_hermite_options *opts, coons_patch **out,
                                       coons_error *err)
{
    return coons_patch_new_hermite_coons((coons_curve *const *)boundary, opts, out, err);
}

coons_status coons_patch_bezier(const double *points, size_t ns, size_t nt, coons_patch **out,
                                coons_error *err)
{
    return coons_patch_new_bezier(points, ns, nt, out, err);
}

coons_status coons_patch_bspline(int ps, int pt, const double *points, size_t ns, size_t nt,
                                 const double *knots_s, const double *knots_t,
                                 const double *weights, coons_patch **out, coons_error *err)
{
    return coons_patch_new_bspline(ps, pt, points, ns, nt, knots_s, knots_t, weights, out, err);
}

coons_status coons_body_body0(const double corners[8][3], coons_blend blend, coons_body **out,
                              coons_error *err)
{
    return coons_body_new_body0(corners ? corners[0] : NULL, blend, out, err);
}

coons_status coons_body_body1(const coons_curve *const edges[12], coons_blend blend, double tol,
                              coons_body **out, coons_error *err)
{
    return coons_body_new_body1((coons_curve *const *)edges, blend, tol, out, err);
}

coons_status coons_body_body2(const coons_patch *const faces[6], coons_blend blend, double tol,
                              coons_body **out, coons_error *err)
{
    return coons_body_new_body2((coons_patch *const *)faces, blend, tol, out, err);
}

coons_status coons_body_bezier(const double *points, const size_t n[3], coons_body **out,
                               coons_error *err)
{
    return coons_body_new_bezier(points, n, out, err);
}

coons_status coons_body_bspline(const int degree[3], const double *points, const size_t n[3],
                                const double *const knots[3], const double *weights,
                                coons_body **out, coons_error *err)
{
    return coons_body_new_bspline(degree, points, n, knots ? knots[0] : NULL,
                                  knots ? knots[1] : NULL, knots ? knots[2] : NULL, weights, out,
                                  err);
}

coons_status coons_model_load(const char *path, coons_model **out, coons_error *err)
{
    return coons_model_load_file(path, NULL, out, err);
}

coons_status coons_model_load_opts(const char *path, const coons_model_load_options *opts,
                                   coons_model **out, coons_error *err)
{
    return coons_model_load_file(path, opts, out, err);
}

coons_status coons_model_load_buffer(const char *data, size_t size, const char *name,
                                     coons_model **out, coons_error *err)
{
    return coons_model_load_memory(data, size, name, NULL, out, err);
}

coons_status coons_model_load_buffer_opts(const char *data, size_t size, const char *name,
                                          const coons_model_load_options *opts,
                                          coons_model **out, coons_error *err)
{
    return coons_model_load_memory(data, size, name, opts, out, err);
}

coons_status coons_model_mesh(const coons_model *m, const coons_sample_options *opts,
                              coons_mesh **out, coons_error *err)
{
    return coons_model_sample(m, opts, out, err);
}

coons_status coons_model_solid(const coons_model *model, const coons_sample_options *sopts,
                               const coons_csg_options *copts, coons_mesh **out,
                               coons_csg_report *report, coons_error *err)
{
    /* 0.1's report had no version field: a 0.1 caller never sets it. */
    if (report) report->version = COONS_CSG_REPORT_VERSION;
    return coons_model_solidify(model, sopts, copts, out, report, err);
}

coons_status coons_mesh_self_intersections(const coons_mesh *m, size_t *pairs, coons_error *err)
{
    return coons_mesh_count_self_intersections(m, pairs, err);
}

coons_status coons_mesh_self_intersections_float(const coons_mesh *m, size_t *pairs,
                                                 coons_error *err)
{
    return coons_mesh_count_self_intersections_float(m, pairs, err);
}

int coons_csg_available(void) { return coons_csg_is_available(); }
