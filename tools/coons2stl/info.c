/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * --info: a JSON description of the model (coons2stl(1)): its units,
 * tolerance, operation and control box; per body its type, sampled and
 * control boxes, volume (the det J integral), smallest det J and its
 * sampled boundary mesh with the mesh checks; then the "solid", the very
 * mesh that -o writes, with what repair and union found and did.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

/* ---- JSON values ------------------------------------------------------ */

/* s as a JSON string (also for the other modes' reports, cli.h). */
void cli_json_string(const char *s)
{
    putchar('"');
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            printf("\\%c", c);
        else if (c < 0x20)
            printf("\\u%04x", c);
        else
            putchar(c);
    }
    putchar('"');
}

static void json_number(double x)
{
    if (isfinite(x))
        printf("%.17g", x);
    else
        printf("null");
}

static void json_box(const double lo[3], const double hi[3])
{
    printf("{\"min\": [");
    for (int k = 0; k < 3; k++) {
        if (k) printf(", ");
        json_number(lo[k]);
    }
    printf("], \"max\": [");
    for (int k = 0; k < 3; k++) {
        if (k) printf(", ");
        json_number(hi[k]);
    }
    printf("]}");
}

static void json_bool(const char *key, int v) { printf("\"%s\": %s", key, v ? "true" : "false"); }

static double box_diagonal(const double lo[3], const double hi[3])
{
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/* ---- one body --------------------------------------------------------- */

#define INFO_GRID 65
#define INFO_JAC 16

/* Box of the boundary sampled on the six faces, INFO_GRID^2 points each. */
static int sampled_box(const coons_body *b, double lo[3], double hi[3], coons_error *err)
{
    static double out[INFO_GRID * INFO_GRID * 3];
    double g[INFO_GRID], ends[2] = {0.0, 1.0};
    for (int i = 0; i < INFO_GRID; i++) g[i] = (double)i / (INFO_GRID - 1);
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (int face = 0; face < 6; face++) {
        const double *e = &ends[face % 2];
        int dir = face / 2;
        coons_status rc = coons_body_eval_grid(
            b, dir == 0 ? e : g, dir == 0 ? 1 : INFO_GRID, dir == 1 ? e : g,
            dir == 1 ? 1 : INFO_GRID, dir == 2 ? e : g, dir == 2 ? 1 : INFO_GRID, out, err);
        if (rc) return rc;
        for (size_t p = 0; p < (size_t)INFO_GRID * INFO_GRID; p++)
            for (int k = 0; k < 3; k++) {
                if (out[3 * p + k] < lo[k]) lo[k] = out[3 * p + k];
                if (out[3 * p + k] > hi[k]) hi[k] = out[3 * p + k];
            }
    }
    return 0;
}

static void mesh_warnings(const coons_model *m, size_t i, double tol, double dev, size_t pairs)
{
    if (dev > tol)
        cli_message(1,
                    "body %zu (%s): the fixed resolution leaves a deviation of %.6g, more than "
                    "the tolerance %.6g",
                    i, coons_model_body_name(m, i), dev, tol);
    if (pairs)
        cli_message(1,
                    "body %zu (%s): its sampled boundary crosses itself (%zu pairs of triangles)",
                    i, coons_model_body_name(m, i), pairs);
}

static void print_mesh(const coons_mesh_report *r, double tol, double dev, const size_t lat[3],
                       int check_crossing, size_t pairs)
{
    printf(",\n     \"mesh\": {\"tolerance\": ");
    json_number(tol);
    printf(", \"deviation\": ");
    json_number(dev);
    printf(", \"lattice\": [%zu, %zu, %zu], \"vertices\": %zu, \"triangles\": %zu,\n", lat[0],
           lat[1], lat[2], r->vertices, r->triangles);
    printf("      \"closed\": %s, \"manifold\": %s, \"oriented\": %s, \"euler\": %ld, "
           "\"expected_euler\": %ld, \"shells\": %zu,\n",
           r->closed ? "true" : "false", r->manifold ? "true" : "false",
           r->oriented ? "true" : "false", r->euler, r->expected_euler, r->shells);
    printf("      \"boundary_edges\": %zu, \"nonmanifold_edges\": %zu, "
           "\"nonmanifold_vertices\": %zu, \"misoriented_edges\": %zu, \"openmesh\": %s",
           r->boundary_edges, r->nonmanifold_edges, r->nonmanifold_vertices,
           r->misoriented_edges, r->openmesh ? "true" : "false");
    if (r->openmesh) printf(", \"openmesh_rejected\": %zu", r->openmesh_rejected);
    printf(",\n      \"volume\": ");
    json_number(r->volume);
    printf(", \"area\": ");
    json_number(r->area);
    if (check_crossing)
        printf(", \"self_intersections\": %zu}", pairs);
    else
        printf(", \"self_intersections\": null}");
}

/* The body's sampled boundary mesh and its checks, as "mesh": {...};
 * `check_crossing`: also count its self-intersecting triangle pairs. */
static int info_mesh(const coons_model *m, size_t i, const coons_sample_options *so,
                     int check_crossing)
{
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *mesh = NULL;
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    size_t pairs = 0;
    cli_progress_sampling(i, coons_model_body_count(m), coons_model_body_name(m, i));
    if (coons_body_sample(coons_model_body(m, i), so, coons_model_body_name(m, i), &mesh, &err) ||
        coons_mesh_check(mesh, &r, &err) ||
        (check_crossing && coons_mesh_count_self_intersections(mesh, &pairs, &err))) {
        cli_message(0, "body %zu (%s): %s", i, coons_model_body_name(m, i), err.message);
        coons_mesh_free(mesh);
        return EXIT_GEOMETRY;
    }
    double tol, dev;
    size_t lat[3];
    coons_mesh_part_sampling(mesh, 0, &tol, &dev, lat);
    mesh_warnings(m, i, tol, dev, pairs);
    print_mesh(&r, tol, dev, lat, check_crossing, pairs);
    coons_mesh_free(mesh);
    return 0;
}

/*
 * Sampling and evaluation noise leaves det J a few units of rounding below
 * zero where it is exactly 0 (the collapsed axis of a spool, the tip of a
 * nail, the seam of a NURBS cylinder: -7e-14 on bodies ~20 mm across).
 * det J is a triple product of first derivatives, each of the order of the
 * body's control box diagonal d, so its rounding noise is ~1e-16 d^3 times
 * a few basis factors; a fold whose det J stays above -1e-9 d^3 is thinner
 * than ~1e-9 d, a million times below the default tolerance (d / 1000).
 * Only det J below that threshold is warned about; the raw minimum is
 * reported either way.
 */
#define FOLD_REL 1e-9

/* "networks": the seams of the body's network patches (a body 2 face, a
 * shell's surface): per inner column and row of each, the measured C1
 * defect and G1 angle (coons_body_network_seams). Nothing when there are
 * none. Returns non-zero on failure (reported). */
static int print_networks(const coons_body *b, size_t i, const char *name)
{
    coons_error err = COONS_ERROR_INIT;
    size_t n = 0;
    coons_network_seam *s = NULL;
    if (coons_body_network_seams(b, NULL, 0, &n, &err) == COONS_OK && n &&
        (s = calloc(n, sizeof *s)) != NULL)
        coons_body_network_seams(b, s, n, &n, &err);
    if (err.code || (n && !s)) {
        cli_message(0, "body %zu (%s): networks: %s", i, name, n && !s ? "out of memory" : err.message);
        free(s);
        return 1;
    }
    if (!n) return 0;
    printf(",\n     \"networks\": [");
    for (size_t k = 0; k < n; k++) {
        printf("%s\n      {\"face\": \"%s\", \"seam\": \"%s\", \"index\": %zu, \"at\": ",
               k ? "," : "", s[k].face >= 0 ? coons_body_face_name(s[k].face) : "surface",
               s[k].dir == 0 ? "column" : "row", s[k].index);
        json_number(s[k].param);
        printf(", \"c1_defect\": ");
        json_number(s[k].c1_defect);
        printf(", \"g1_angle\": ");
        json_number(s[k].g1_angle);
        printf("}");
    }
    printf("]");
    free(s);
    return 0;
}

/* The body's "faces": whether all six boundary faces have an exact
 * B-spline or NURBS form (coons_body_face_to_nurbs()), whether any is
 * rational, and the largest deviation of the fitted ones (those without an
 * exact form, fitted as the solid writer fits them: within the model's
 * tolerance or 1e-5 of the body's size, whichever is finer), with their
 * names. These are the faces of the STEP, IGES and BREP solids. */
static int print_spline_faces(const coons_model *m, const coons_body *b, size_t i,
                              const char *name)
{
    double lo[3], hi[3];
    coons_body_control_bbox(b, lo, hi);
    double size = box_diagonal(lo, hi);
    if (!(size > 0) || !isfinite(size)) size = 1.0;
    double tol = coons_model_tolerance(m);
    tol = tol > 0 && tol < 1e-5 * size ? tol : 1e-5 * size;
    int exact = 1, rational = 0;
    double dev = 0;
    char fitted[64] = "";
    for (int f = 0; f < 6; f++) {
        coons_nurbs n;
        coons_error err = COONS_ERROR_INIT;
        if (coons_body_face_to_nurbs(b, f, tol, &n, &err) != COONS_OK) {
            cli_message(0, "body %zu (%s), face %s: %s", i, name, coons_body_face_name(f),
                        err.message);
            return 1;
        }
        rational |= n.weights != NULL;
        if (!n.exact) {
            exact = 0;
            if (n.deviation > dev) dev = n.deviation;
            size_t len = strlen(fitted);
            snprintf(fitted + len, sizeof fitted - len, "%s\"%s\"", len ? ", " : "",
                     coons_body_face_name(f));
        }
        coons_nurbs_free(&n);
    }
    printf(",\n     \"faces\": {");
    json_bool("exact", exact);
    printf(", ");
    json_bool("rational", rational);
    printf(", \"fitted\": [%s], \"deviation\": ", fitted);
    json_number(dev);
    printf("}");
    return 0;
}

/* One entry of "bodies"; *vol receives its volume (relative accuracy
 * `rel`). */
static int info_body(const coons_model *m, size_t i, int first, double rel,
                     const coons_sample_options *so, int checks, double *vol,
                     const coons_volume_mesh *vm, size_t part)
{
    const coons_body *b = coons_model_body(m, i);
    const char *name = coons_model_body_name(m, i);
    coons_error err = COONS_ERROR_INIT;
    double lo[3], hi[3], blo[3], bhi[3], mindet = NAN, where[3] = {0, 0, 0}, vol_err = NAN;
    *vol = NAN;
    if (sampled_box(b, lo, hi, &err) ||
        coons_body_volume_bounded(b, rel, 0, vol, &vol_err, NULL, &err) ||
        coons_body_min_jacobian(b, INFO_JAC, &mindet, where, &err)) {
        cli_message(0, "body %zu (%s): %s", i, name, err.message);
        return EXIT_GEOMETRY;
    }
    coons_body_control_bbox(b, blo, bhi);
    double d3 = pow(box_diagonal(blo, bhi), 3);
    if (mindet < -FOLD_REL * d3)
        cli_message(1, "body %zu (%s): det J = %.6g < 0 at (u, v, w) = (%g, %g, %g): the body %s",
                    i, name, mindet, where[0], where[1], where[2],
                    *vol < 0 ? "is left-handed or folds over itself" : "folds over itself there");
    const char *type = coons_body_type_name(coons_body_kind(b));
    printf("%s\n    {\"index\": %zu, \"name\": ", first ? "" : ",", i);
    cli_json_string(name);
    printf(", \"type\": \"%s\",\n     \"bbox\": ", type ? type : "unknown");
    json_box(lo, hi);
    printf(",\n     \"control_bbox\": ");
    json_box(blo, bhi);
    printf(",\n     \"volume\": ");
    json_number(*vol);
    printf(", \"volume_error\": "); /* the integral's error estimate (absolute) */
    json_number(vol_err);
    printf(", \"min_det_jacobian\": ");
    json_number(mindet);
    printf(", \"min_det_jacobian_at\": [%.17g, %.17g, %.17g]", where[0], where[1], where[2]);
    if (print_spline_faces(m, b, i, name)) return EXIT_GEOMETRY;
    if (print_networks(b, i, name)) return EXIT_GEOMETRY;
    int rc = coons_body_morph_keys(b) ? cli_print_morph_info(b, FOLD_REL * d3, name, i) : 0;
    if (rc) return rc;
    rc = info_mesh(m, i, so, checks);
    if (rc) return rc;
    if (vm) {
        printf(",\n     \"volume_mesh\": ");
        cli_print_volume_quality(vm, part);
    }
    printf("}");
    return 0;
}

/* ---- the solid -------------------------------------------------------- */

static void solid_warnings(const coons_mesh_report *r, size_t pairs, size_t pairs32, int repair)
{
    if (r->boundary_edges)
        cli_message(1, "the solid's boundary is not closed (%zu border edges)",
                    r->boundary_edges);
    else if (r->nonmanifold_edges)
        cli_message(1,
                    "the solid's boundary is closed but not a 2-manifold: %zu edges bound more "
                    "than two triangles (solids touching along a curve)",
                    r->nonmanifold_edges);
    if (pairs)
        cli_message(1, "the solid's boundary crosses itself (%zu pairs of triangles)%s", pairs,
                    repair ? "" : "; without --no-repair it would be repaired");
    else if (pairs32)
        cli_message(1,
                    "rounding the solid's coordinates to float32, as STL stores them, makes %zu "
                    "pairs of its triangles intersect; OFF and SCAD keep double precision",
                    pairs32);
}

static void print_csg_report(const coons_csg_report *rep)
{
    printf("   \"csg\": {\"triangles_in\": %zu, \"degenerate_dropped\": %zu, "
           "\"intersecting_pairs\": %zu, \"parts_in\": %zu, \"groups\": %zu,\n"
           "    \"passed_through\": %zu, \"patches\": %zu, \"patches_kept\": %zu, "
           "\"fast_unions\": %zu, \"fallbacks\": %zu, \"triangles_out\": %zu,\n"
           "    \"rounding_merged\": %zu, \"close_merged\": %zu, \"slivers_fixed\": %zu, ",
           rep->triangles_in, rep->degenerate_dropped, rep->intersecting_pairs, rep->parts_in,
           rep->groups, rep->passed_through, rep->patches, rep->patches_kept, rep->fast_unions,
           rep->fallbacks, rep->triangles_out, rep->rounding_merged, rep->close_merged,
           rep->slivers_fixed);
    json_bool("closed", rep->closed);
    printf(", \"nonmanifold_edges\": %zu, \"pinch_edges_split\": %zu, "
           "\"pinch_vertices_split\": %zu}}",
           rep->nonmanifold_edges, rep->pinch_edges_split, rep->pinch_vertices_split);
}

/* The object after "solid": (the mesh checks, then the CSG report). */
static void print_solid(const coons_mesh_report *r, const coons_csg_report *rep, size_t parts,
                        int repair, int united, int csg, size_t pairs, long pairs32)
{
    printf("{");
    json_bool("repair", repair && csg);
    printf(", ");
    json_bool("united", united);
    printf(", \"parts\": %zu, \"vertices\": %zu, \"triangles\": %zu,\n   ", parts, r->vertices,
           r->triangles);
    json_bool("closed", r->closed);
    printf(", ");
    json_bool("manifold", r->manifold);
    printf(", ");
    json_bool("oriented", r->oriented);
    printf(", \"euler\": %ld, \"shells\": %zu, \"boundary_edges\": %zu, \"nonmanifold_edges\": %zu,"
           " \"nonmanifold_vertices\": %zu,\n   \"volume\": ",
           r->euler, r->shells, r->boundary_edges, r->nonmanifold_edges, r->nonmanifold_vertices);
    json_number(r->volume);
    printf(", \"area\": ");
    json_number(r->area);
    if (!csg) {
        printf(", \"self_intersections\": null, \"self_intersections_float32\": null, "
               "\"csg\": null}");
        return;
    }
    printf(", \"self_intersections\": %zu, \"self_intersections_float32\": ", pairs);
    if (pairs32 < 0)
        printf("null,\n"); /* the solid does not fit STL's 32-bit floats */
    else
        printf("%ld,\n", pairs32);
    print_csg_report(rep);
}

/* "solid": what -o would write (cli_make_solid()) and what repair and union
 * found and did. A failure is reported in the JSON ("error") and warned
 * about, not turned into an exit status: --info describes the model. */
static int info_solid(const coons_model *m, long only, const coons_sample_options *so, int repair,
                      unsigned jobs)
{
    coons_error err = COONS_ERROR_INIT;
    coons_mesh *solid = NULL;
    coons_csg_report rep = COONS_CSG_REPORT_INIT;
    int csg = coons_csg_is_available();
    coons_status rc = cli_make_solid(m, only, so, repair, jobs, &solid, &rep, &err);
    coons_mesh_report r = COONS_MESH_REPORT_INIT;
    size_t pairs = 0, pairs32 = 0;
    if (rc == COONS_OK) rc = coons_mesh_check(solid, &r, &err);
    if (rc == COONS_OK && csg) rc = coons_mesh_count_self_intersections(solid, &pairs, &err);
    int have32 = csg; /* not when the solid does not fit float32 (STL refuses it) */
    if (rc == COONS_OK && csg) {
        coons_status r32 = coons_mesh_count_self_intersections_float(solid, &pairs32, &err);
        if (r32 == COONS_E_LIMIT)
            have32 = 0, pairs32 = 0;
        else
            rc = r32;
    }
    cli_progress_end();
    size_t parts = rc == COONS_OK ? coons_mesh_part_count(solid) : 0;
    coons_mesh_free(solid);
    if (rc == COONS_E_NOMEM) {
        cli_message(0, "%s", err.message);
        return EXIT_GEOMETRY;
    }
    printf(",\n  \"solid\": ");
    if (rc != COONS_OK) {
        cli_message(1, "no mesh can be made of %s: %s", only < 0 ? "this model" : "this body",
                    err.message);
        printf("{\"error\": ");
        cli_json_string(err.message);
        printf("}");
        return 0;
    }
    solid_warnings(&r, pairs, pairs32, repair);
    print_solid(&r, &rep, parts, repair, only < 0 && coons_model_operation(m) == COONS_OP_UNION,
                csg, pairs, have32 ? (long)pairs32 : -1);
    return 0;
}

/* ---- faces shared by two bodies ----------------------------------------- */

/* "interfaces": one entry per shared face (all bodies, or those of --body's
 * body), with the continuity across it. Returns non-zero on failure
 * (reported). */
static int print_interfaces(const coons_model *m, long only)
{
    coons_interface *list = NULL;
    size_t n = 0;
    coons_error err = COONS_ERROR_INIT;
    if (coons_model_interfaces(m, &list, &n, &err) != COONS_OK) {
        cli_message(0, "interfaces: %s", err.message);
        return 1;
    }
    printf(",\n  \"interfaces\": [");
    int first = 1;
    for (size_t k = 0; k < n; k++) {
        const coons_interface *I = &list[k];
        if (only >= 0 && I->body[0] != (size_t)only && I->body[1] != (size_t)only) continue;
        printf("%s\n    {\"bodies\": [", first ? "" : ",");
        cli_json_string(coons_model_body_name(m, I->body[0]));
        printf(", ");
        cli_json_string(coons_model_body_name(m, I->body[1]));
        printf("], \"body_indices\": [%zu, %zu], \"faces\": [\"%s\", \"%s\"], "
               "\"orientation\": %d,\n     \"c1_defect\": ",
               I->body[0], I->body[1], coons_body_face_name(I->face[0]),
               coons_body_face_name(I->face[1]), I->orientation);
        json_number(I->c1_defect);
        printf(", \"g1_angle\": ");
        json_number(I->g1_angle);
        printf("}");
        first = 0;
    }
    printf("%s]", first ? "" : "\n  ");
    coons_interfaces_free(list);
    return 0;
}

/* ---- the model -------------------------------------------------------- */

static void print_model(const coons_model *m, double tol, const double clo[3],
                        const double chi[3])
{
    printf("{\n  \"units\": ");
    cli_json_string(coons_model_units(m));
    printf(",\n  \"tolerance\": ");
    json_number(tol);
    printf(",\n  \"operation\": \"%s\",\n  \"control_bbox\": ",
           coons_model_operation(m) == COONS_OP_NONE ? "none" : "union");
    json_box(clo, chi);
}

int cli_info(const coons_model *m, long only, const coons_sample_options *so,
             const cli_info_options *io)
{
    size_t n = coons_model_body_count(m);
    double clo[3], chi[3];
    coons_model_control_bbox(m, clo, chi);
    double diag = box_diagonal(clo, chi);
    double tol = coons_model_tolerance(m);
    /* Volumes to a relative accuracy tied to the model tolerance: a boundary
     * off by tol changes the volume by about tol * area ~ tol / size. */
    double rel = diag > 0 ? tol / diag : 1e-6;
    if (rel > 1e-6) rel = 1e-6;
    if (rel < 1e-12) rel = 1e-12;
    int checks = io->solid && coons_csg_is_available();
    double total = 0.0;
    size_t listed = 0;
    coons_volume_mesh *vm = NULL;
    if (io->volume_mesh) {
        coons_error err = COONS_ERROR_INIT;
        if (cli_volume_mesh(m, only, io->volume, &vm, &err) != COONS_OK) {
            cli_progress_end();
            cli_message(0, "volume mesh: %s", err.message);
            return EXIT_GEOMETRY;
        }
    }
    print_model(m, tol, clo, chi);
    printf(",\n  \"bodies\": [");
    for (size_t i = 0; i < n; i++) {
        if (only >= 0 && (size_t)only != i) continue;
        double vol;
        int rc = info_body(m, i, listed == 0, rel, so, checks, &vol, vm, only >= 0 ? 0 : i);
        if (rc) {
            coons_volume_mesh_free(vm);
            return rc;
        }
        total += fabs(vol); /* a left-handed (mirrored) body encloses |volume| */
        listed++;
    }
    cli_progress_end();
    printf("\n  ],\n  \"body_count\": %zu,\n  \"total_volume\": ", listed);
    json_number(total);
    if (print_interfaces(m, only)) {
        coons_volume_mesh_free(vm);
        return EXIT_GEOMETRY;
    }
    if (!io->solid) {
        printf(",\n  \"solid\": null");
    } else {
        int rc = info_solid(m, only, so, io->repair, io->jobs);
        if (rc) {
            coons_volume_mesh_free(vm);
            return rc;
        }
    }
    printf("\n}\n");
    /* --info -o FILE.vtu: the report, then the mesh written as -o alone would. */
    int rc = 0;
    if (vm && io->out)
        rc = fflush(stdout) != 0 ? EXIT_GEOMETRY : cli_write_volume_mesh(vm, io->volume, io->out);
    coons_volume_mesh_free(vm);
    return rc;
}
