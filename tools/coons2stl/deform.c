/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * --deform IN: free-form deformation (coons2stl(1), "Free-form
 * deformation"). IN (binary or ASCII STL, or OFF: coons_mesh_read_file())
 * is mapped through one body, a point p going to B((p - lo) / (hi - lo))
 * with lo, hi the corners of --frame (default: IN's bounding box), its
 * triangles split until the result lies within the tolerance of the exact
 * image (coons_body_deform(), its progress shown as "deforming: N%"); the
 * result is written to -o like any surface (atomically, any surface
 * format), or --info describes it.
 * The tolerance: -t, else 1/1000 of the diagonal of the box of IN's
 * vertices' images (the output's box, up to what splitting adds).
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

int cli_check_deform_options(options *o)
{
    if (o->frame_arg && !o->deform) return cli_usage_error("--frame is for --deform");
    if (!o->deform) return -1;
    if (o->eval || o->niso || o->frames || o->volume_mesh)
        return cli_usage_error("--deform writes the deformed mesh: not with --eval, --iso, "
                               "--frames or --volume-mesh");
    if (o->resolution)
        return cli_usage_error("--resolution is for sampling bodies: --deform splits IN's "
                               "triangles to the tolerance (-t)");
    if (cli_is_volume_format(o->format) && o->format != COONS_FORMAT_VTU &&
        o->format != COONS_FORMAT_VTU_ASCII && (o->output || o->format_arg))
        return cli_usage_error("--deform writes a surface: use .stl, .off, .scad, .3mf or .vtu "
                               "(surface formats), not a volume-mesh format");
    if (o->frame_arg) {
        const char *p = o->frame_arg;
        for (int k = 0; k < 6; k++) {
            char *end;
            errno = 0;
            o->frame[k] = strtod(p, &end);
            if (end == p || !isfinite(o->frame[k]) || (k < 5 ? *end != ',' : *end != '\0')) {
                char msg[512];
                snprintf(msg, sizeof msg,
                         "--frame needs six numbers X0,Y0,Z0,X1,Y1,Z1 (the box's two corners), "
                         "not '%.300s'",
                         o->frame_arg);
                return cli_usage_error(msg);
            }
            p = end + 1;
        }
        for (int k = 0; k < 3; k++)
            if (!(o->frame[k + 3] > o->frame[k])) {
                char msg[512];
                snprintf(msg, sizeof msg,
                         "--frame %.300s: the box is empty along %c (%g to %g): the second "
                         "corner must be greater in x, y and z",
                         o->frame_arg, "xyz"[k], o->frame[k], o->frame[k + 3]);
                return cli_usage_error(msg);
            }
    }
    return -1;
}

static void json_vec(const double v[3])
{
    printf("[%.17g, %.17g, %.17g]", v[0], v[1], v[2]);
}

static void json_check(const char *key, const coons_mesh_report *r)
{
    printf("    \"%s\": {\"triangles\": %zu, \"vertices\": %zu, \"closed\": %s, "
           "\"manifold\": %s, \"oriented\": %s, \"boundary_edges\": %zu, \"shells\": %zu, "
           "\"euler\": %ld, \"volume\": %.17g, \"area\": %.17g}",
           key, r->triangles, r->vertices, r->closed ? "true" : "false",
           r->manifold ? "true" : "false", r->oriented ? "true" : "false", r->boundary_edges,
           r->shells, r->euler, r->volume, r->area);
}

/* The default tolerance (-t not given): 1/1000 of the box diagonal of the
 * images of IN's vertices, which the library computes from its own mapping
 * of them (coons_deform_options.relative_tolerance); for --info, the same
 * from the result, whose first vertices are those images. */
#define RELATIVE_TOLERANCE 1e-3
static double default_tolerance(const coons_mesh *out, size_t nv)
{
    const double *y = coons_mesh_vertices(out);
    double blo[3] = {INFINITY, INFINITY, INFINITY}, bhi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < nv; i++)
        for (int d = 0; d < 3; d++) {
            blo[d] = fmin(blo[d], y[3 * i + d]);
            bhi[d] = fmax(bhi[d], y[3 * i + d]);
        }
    double diag = 0;
    for (int d = 0; d < 3 && nv; d++) diag += (bhi[d] - blo[d]) * (bhi[d] - blo[d]);
    diag = sqrt(diag);
    return diag > 0 && isfinite(diag) ? RELATIVE_TOLERANCE * diag : RELATIVE_TOLERANCE;
}

static void input_box(const coons_mesh *in, double lo[3], double hi[3])
{
    size_t nv = coons_mesh_vertex_count(in);
    const double *x = coons_mesh_vertices(in);
    for (int d = 0; d < 3; d++) lo[d] = INFINITY, hi[d] = -INFINITY;
    for (size_t i = 0; i < nv; i++)
        for (int d = 0; d < 3; d++) {
            lo[d] = fmin(lo[d], x[3 * i + d]);
            hi[d] = fmax(hi[d], x[3 * i + d]);
        }
}

static int print_info(const options *o, const coons_model *m, size_t body, const coons_mesh *in,
                      const coons_mesh *out, const coons_deform_report *rep, double tol)
{
    coons_error err = COONS_ERROR_INIT;
    coons_mesh_report ri = COONS_MESH_REPORT_INIT, ro = COONS_MESH_REPORT_INIT;
    if (coons_mesh_check(in, &ri, &err) != COONS_OK || coons_mesh_check(out, &ro, &err) != COONS_OK) {
        cli_message(0, "%s", err.message);
        return EXIT_GEOMETRY;
    }
    int closed_in = ri.closed && ri.manifold && ri.oriented;
    printf("{\n  \"deform\": {\n    \"input\": ");
    cli_json_string(o->deform);
    printf(",\n    \"body\": ");
    cli_json_string(coons_model_body_name(m, body));
    printf(",\n    \"body_index\": %zu,\n", body);
    printf("    \"frame\": {\"min\": ");
    json_vec(rep->lo);
    printf(", \"max\": ");
    json_vec(rep->hi);
    printf(", \"given\": %s},\n", o->frame_arg ? "true" : "false");
    printf("    \"tolerance\": %.17g,\n    \"deviation\": %.17g,\n", tol, rep->deviation);
    printf("    \"input_triangles\": %zu,\n    \"output_triangles\": %zu,\n", rep->triangles_in,
           rep->triangles_out);
    printf("    \"input_closed\": %s,\n", closed_in ? "true" : "false");
    printf("    \"rounds\": %u,\n    \"reversed\": %s,\n", rep->rounds,
           rep->reversed ? "true" : "false");
    json_check("input_mesh", &ri);
    printf(",\n");
    json_check("output_mesh", &ro);
    printf("\n  }\n}\n");
    if (!closed_in)
        cli_message(1, "%s is not a closed, oriented 2-manifold (%zu boundary edges): deformed "
                       "as it is, and the output is not closed either",
                    o->deform, ri.boundary_edges);
    return 0;
}

int cli_deform(const coons_model *m, long body, const options *o)
{
    coons_error err = COONS_ERROR_INIT;
    int to_stdout = !o->output || strcmp(o->output, "-") == 0;
    const char *shown = to_stdout ? "<stdout>" : o->output;
    if (!to_stdout && cli_is_model_file(o->output, o->deform)) {
        fprintf(stderr, "%s: the output '%s' is the mesh to deform '%s'; refusing to overwrite "
                        "it\n",
                PROG, o->output, o->deform);
        return EXIT_USAGE;
    }
    size_t bi = body < 0 ? 0 : (size_t)body;
    const coons_body *b = coons_model_body(m, bi);
    if (body < 0 && coons_model_body_count(m) > 1)
        cli_message(1, "the model has %zu bodies: deforming through body 0 ('%s'); --body picks "
                       "another",
                    coons_model_body_count(m), coons_model_body_name(m, 0));
    coons_mesh_read_options ro = COONS_MESH_READ_OPTIONS_INIT;
    ro.max_triangles = o->max_triangles;
    coons_mesh *in = NULL, *out = NULL;
    if (coons_mesh_read_file(o->deform, &ro, &in, &err) != COONS_OK) {
        cli_message(0, "%s; nothing was written", err.message);
        return EXIT_INPUT;
    }
    double lo[3], hi[3];
    if (o->frame_arg) {
        memcpy(lo, o->frame, sizeof lo);
        memcpy(hi, o->frame + 3, sizeof hi);
    } else {
        input_box(in, lo, hi);
    }
    if (!coons_mesh_triangle_count(in)) {
        cli_message(0, "%s: no triangles to deform; nothing was written", o->deform);
        coons_mesh_free(in);
        return EXIT_INPUT;
    }
    for (int d = 0; d < 3; d++)
        if (!(hi[d] > lo[d])) {
            cli_message(0,
                        "%s is flat along %c (%g to %g): give a --frame that is not; nothing "
                        "was written",
                        o->deform, "xyz"[d], lo[d], hi[d]);
            coons_mesh_free(in);
            return EXIT_INPUT;
        }
    double tol = o->tolerance > 0 ? o->tolerance : 0;
    coons_deform_report rep = COONS_DEFORM_REPORT_INIT;
    coons_deform_options dopts = COONS_DEFORM_OPTIONS_INIT;
    dopts.tolerance = tol;
    dopts.relative_tolerance = RELATIVE_TOLERANCE;
    dopts.max_triangles = o->max_triangles;
    dopts.lo = lo;
    dopts.hi = hi;
    dopts.progress = cli_progress_on() ? cli_on_deform : NULL;
    dopts.threads = cli_threads(o->jobs);
    coons_status rc = coons_body_deform(b, in, &dopts, &out, &rep, &err);
    if (rc != COONS_OK) {
        cli_message(0, "%s: %s%s; nothing was written", rc == COONS_E_DOMAIN ? o->deform : shown,
                    err.message,
                    rc == COONS_E_DOMAIN ? " (give a --frame that holds them)" : "");
        coons_mesh_free(in);
        return rc == COONS_E_DOMAIN ? EXIT_INPUT : EXIT_GEOMETRY;
    }
    if (o->info) {
        cli_progress_end();
        if (!(tol > 0)) tol = default_tolerance(out, coons_mesh_vertex_count(in));
        int st = print_info(o, m, bi, in, out, &rep, tol);
        coons_mesh_free(in);
        coons_mesh_free(out);
        return st;
    }
    coons_mesh_free(in);
    cli_output where = cli_output_of(o);
    return cli_write_surface(out, &where, shown);
}
