/* SPDX-License-Identifier: GPL-3.0-or-later */
/**
 * @file coons/iso.h
 * @brief Isoparametric surfaces of bodies (u, v or w = const).
 *
 * Each surface is a mesh part whose vertices carry their body parameters
 * (coons_mesh_vertex_parameters(), declared here with the surfaces that
 * make them); parts are named by coons_iso_surface_name().
 */
#ifndef COONS_ISO_H
#define COONS_ISO_H

#include "coons/types.h"
#include "coons/mesh.h"
#include "coons/sample.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * The body parameters of every vertex, 3 doubles (u, v, w) per vertex in
 * vertex order (borrowed view, valid until the mesh is modified or freed),
 * or NULL when the mesh has no part or a part without them. Parts made by
 * coons_body_iso_surface() and coons_model_iso_surfaces() carry them
 * (boundary parts included); parts added with coons_mesh_add_part() or
 * sampled by coons_body_sample() / coons_model_sample() do not.
 */
COONS_EXPORT const double *coons_mesh_vertex_parameters(const coons_mesh *m);

/** 1 if part i carries vertex parameters (see coons_mesh_vertex_parameters()). */
COONS_EXPORT int coons_mesh_part_has_parameters(const coons_mesh *m, size_t i);

/** One isoparametric surface: direction 0 (u), 1 (v) or 2 (w) = value. */
typedef struct coons_iso_request {
    int direction;
    double value;
} coons_iso_request;

/** Flag of coons_model_iso_surfaces(): also each body's boundary. */
#define COONS_ISO_WITH_BOUNDARY 1u

/** Longest part name coons_iso_surface_name() writes, NUL included. */
#define COONS_ISO_NAME_MAX 320

/**
 * The name of an isoparametric surface part: `BODY.u=VALUE` (or `.v=`,
 * `.w=`), VALUE the shortest decimal text that reads back to the value
 * ("0.25", "0.1", "1", "0.3333333333333333"), whatever the locale; just
 * `u=VALUE` when `body` is NULL. The OpenSCAD writer makes module names of
 * such names by turning `.` and `=` into `_` (`BODY_u_0_25`). Written into
 * out[cap] (truncated to fit; cap >= 1).
 */
COONS_EXPORT void coons_iso_surface_name(const char *body, int direction, double value,
                                         char *out, size_t cap);

/**
 * Appends to `into` one part: the isoparametric surface of body b where
 * parameter `direction` (0 u, 1 v, 2 w) equals `value` (seed 000 section
 * 2.1, Fig. 2-6), e.g. F(0.25, v, w) over (v, w) in [0,1]^2.
 *
 * The surface is sampled on the lattice of the other two directions that
 * coons_body_sample() settles on for b with `opts` (so the surface at 0 or
 * 1 is that boundary face, point for point); each lattice cell gives two
 * triangles split along its shorter diagonal, and every vertex is the
 * body's point at its own parameters, stored with it
 * (coons_mesh_vertex_parameters()). As in coons_body_sample(), lattice
 * neighbours at the same place (collapsed edges, an apex) are merged, the
 * triangles that become degenerate are dropped, and a surface that closes
 * on itself (a seam along which its two opposite sides coincide) is glued
 * there. A surface that collapses entirely (to a curve or a point) gives a
 * part with no triangles. Triangles are wound so that their normal is
 * F_a x F_b with (a, b) = (v, w), (w, u), (u, v) for u, v, w = const: it
 * points towards increasing `direction` when the body is right-handed
 * (det J > 0), away from it when left-handed.
 *
 * @param[in]     b          the body (not modified)
 * @param[in]     direction  0, 1 or 2
 * @param[in]     value      in [0,1]
 * @param[in]     opts       NULL or sampling options (the tolerance
 *                           defaults to 1/1000 of the body's control box
 *                           diagonal, as in coons_body_sample())
 * @param[in]     name       the part's name (copied); NULL: as
 *                           coons_iso_surface_name() with no body
 * @param[in,out] into       the mesh to append to
 * @return ::COONS_OK; ::COONS_E_DOMAIN (value outside [0,1] or NaN; the
 *         message names it); ::COONS_E_INVALID (direction not 0, 1 or 2,
 *         bad options, a body that evaluates to a non-finite point);
 *         ::COONS_E_LIMIT (the boundary sampling or the surface needs more
 *         than `max_triangles`); ::COONS_E_NOMEM. On error `into` is
 *         unchanged. Thread-safe for distinct meshes.
 */
COONS_EXPORT coons_status coons_body_iso_surface(const coons_body *b, int direction, double value,
                                                 const coons_sample_options *opts,
                                                 const char *name, coons_mesh *into,
                                                 coons_error *err);

/**
 * The isoparametric surfaces `req[0..n)` of every body of a model, as a new
 * mesh: per body (in model order), with ::COONS_ISO_WITH_BOUNDARY in
 * `flags` first its boundary (a part named after the body, sampled as
 * coons_model_sample() does, with vertex parameters: body k's boundary is
 * part k * (n + 1), which is what coons_write_options.background lists to
 * show it as context in OpenSCAD), then one part per request in request order,
 * named by coons_iso_surface_name() (`BODY.u=0.25`). The lattice is
 * computed once per body. The model's operation is ignored: each body's
 * surfaces and own boundary are written as they are. The tolerance
 * defaults to the model's; `max_triangles` bounds the whole mesh.
 * @param[out] out  the new mesh (coons_mesh_free()); NULL on error
 * @return as coons_body_iso_surface(); ::COONS_E_INVALID also for
 *         unknown flags or `req` NULL with n > 0.
 */
COONS_EXPORT coons_status coons_model_iso_surfaces(const coons_model *m,
                                                   const coons_iso_request *req, size_t n,
                                                   const coons_sample_options *opts,
                                                   unsigned int flags, coons_mesh **out,
                                                   coons_error *err);

#ifdef __cplusplus
}
#endif
#endif
