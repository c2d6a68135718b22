/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/deprecated.h
 * @brief The libcoons 0.1 names, kept for the 0.2 release only.
 *
 * 0.2 names every function `coons_<object>_<verb>` and takes point arrays
 * flat and arrays of handles as `coons_X *const *` (coons/types.h, "Arrays").
 * The 0.1 functions below still work, with their 0.1 parameters, as thin
 * wrappers over the 0.2 ones, so that 0.1 code builds as it did (warning-
 * free under -Werror too). They go away in 0.3. To find every use, define
 * COONS_DEPRECATION_WARNINGS before including <coons.h> (gcc and clang then
 * warn at each call), or COONS_NO_DEPRECATED (they are not declared at
 * all); tools/migrate-0.2.py rewrites the names in a source tree.
 * libcoons(3), HISTORY, lists them.
 */
#ifndef COONS_DEPRECATED_H
#define COONS_DEPRECATED_H

#include "coons/types.h"
#include "coons/curve.h"
#include "coons/patch.h"
#include "coons/body.h"
#include "coons/model.h"
#include "coons/mesh.h"
#include "coons/csg.h"

#if defined(COONS_DEPRECATION_WARNINGS) && (defined(__GNUC__) || defined(__clang__))
#define COONS_DEPRECATED_FOR(f) __attribute__((deprecated("use " #f)))
#else
#define COONS_DEPRECATED_FOR(f)
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---- 0.1 macro names ----------------------------------------------------- */
#define COONS_T0 COONS_SIDE_T0
#define COONS_T1 COONS_SIDE_T1
#define COONS_S0 COONS_SIDE_S0
#define COONS_S1 COONS_SIDE_S1
#define COONS_MAX_CURVE_POINTS COONS_CURVE_MAX_POINTS
#define COONS_MAX_PATCH_POINTS COONS_PATCH_MAX_POINTS
#define COONS_MAX_BODY_POINTS COONS_BODY_MAX_POINTS
#define COONS_MAX_DEGREE COONS_SPLINE_MAX_DEGREE
#define COONS_DEFAULT_MAX_TRIANGLES COONS_MESH_MAX_TRIANGLES
#define COONS_DEFAULT_MAX_ASPECT COONS_SAMPLE_DEFAULT_MAX_ASPECT

/* ---- 0.1 functions: same names, same parameters as in 0.1 ---------------- */
COONS_EXPORT COONS_DEPRECATED_FOR(coons_curve_new_line) coons_status
coons_curve_line(const double p0[3], const double p1[3], coons_curve **out, coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_curve_new_polyline) coons_status
coons_curve_polyline(const double *points, size_t count, coons_curve **out, coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_curve_new_bezier) coons_status
coons_curve_bezier(const double *points, size_t count, coons_curve **out, coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_curve_new_hermite) coons_status
coons_curve_hermite(const double p0[3], const double t0[3], const double p1[3],
                    const double t1[3], coons_curve **out, coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_curve_new_coons_cubic) coons_status
coons_curve_coons_cubic(const double *points, size_t count, int closed, coons_curve **out,
                        coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_curve_new_clamped_cubic) coons_status
coons_curve_clamped_cubic(const double *points, size_t count, coons_curve **out,
                          coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_curve_new_bspline) coons_status
coons_curve_bspline(int degree, const double *points, size_t count, const double *knots,
                    const double *weights, coons_curve **out, coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_curve_convert_open_to_clamped) coons_status
coons_cubic_open_to_clamped(const double *open, size_t count, double *clamped,
                            coons_error *err);

COONS_EXPORT COONS_DEPRECATED_FOR(coons_patch_new_bilinear) coons_status
coons_patch_bilinear(const double corners[4][3], coons_patch **out, coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_patch_new_ruled) coons_status
coons_patch_ruled(const coons_curve *c0, const coons_curve *c1, coons_patch **out,
                  coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_patch_new_coons) coons_status
coons_patch_coons(const coons_curve *const boundary[4], coons_blend blend, double tol,
                  coons_patch **out, coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_patch_new_hermite_coons) coons_status
coons_patch_hermite_coons(const coons_curve *const boundary[4],
                          const coons_hermite_options *opts, coons_patch **out,
                          coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_patch_new_bezier) coons_status
coons_patch_bezier(const double *points, size_t ns, size_t nt, coons_patch **out,
                   coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_patch_new_bspline) coons_status
coons_patch_bspline(int ps, int pt, const double *points, size_t ns, size_t nt,
                    const double *knots_s, const double *knots_t, const double *weights,
                    coons_patch **out, coons_error *err);

COONS_EXPORT COONS_DEPRECATED_FOR(coons_body_new_body0) coons_status
coons_body_body0(const double corners[8][3], coons_blend blend, coons_body **out,
                 coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_body_new_body1) coons_status
coons_body_body1(const coons_curve *const edges[12], coons_blend blend, double tol,
                 coons_body **out, coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_body_new_body2) coons_status
coons_body_body2(const coons_patch *const faces[6], coons_blend blend, double tol,
                 coons_body **out, coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_body_new_bezier) coons_status
coons_body_bezier(const double *points, const size_t n[3], coons_body **out, coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_body_new_bspline) coons_status
coons_body_bspline(const int degree[3], const double *points, const size_t n[3],
                   const double *const knots[3], const double *weights, coons_body **out,
                   coons_error *err);

COONS_EXPORT COONS_DEPRECATED_FOR(coons_model_load_file) coons_status
coons_model_load(const char *path, coons_model **out, coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_model_load_file) coons_status
coons_model_load_opts(const char *path, const coons_model_load_options *opts,
                      coons_model **out, coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_model_load_memory) coons_status
coons_model_load_buffer(const char *data, size_t size, const char *name, coons_model **out,
                        coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_model_load_memory) coons_status
coons_model_load_buffer_opts(const char *data, size_t size, const char *name,
                             const coons_model_load_options *opts, coons_model **out,
                             coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_model_sample) coons_status
coons_model_mesh(const coons_model *m, const coons_sample_options *opts, coons_mesh **out,
                 coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_model_solidify) coons_status
coons_model_solid(const coons_model *model, const coons_sample_options *sopts,
                  const coons_csg_options *copts, coons_mesh **out, coons_csg_report *report,
                  coons_error *err);

COONS_EXPORT COONS_DEPRECATED_FOR(coons_mesh_count_self_intersections) coons_status
coons_mesh_self_intersections(const coons_mesh *m, size_t *pairs, coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_mesh_count_self_intersections_float) coons_status
coons_mesh_self_intersections_float(const coons_mesh *m, size_t *pairs, coons_error *err);
COONS_EXPORT COONS_DEPRECATED_FOR(coons_csg_is_available) int coons_csg_available(void);

#ifdef __cplusplus
}
#endif
#endif
