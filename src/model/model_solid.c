/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A model's solid: every body sampled as its own closed shell (sample.c,
 * model_mesh.c), then repaired and united by the CGAL layer
 * (cgal_solid.cpp) as the model's "operation" says. Without CGAL, only
 * models that need no Boolean work (operation "none", or bodies that do not
 * meet) can be made. Also one body's solid alone (coons2stl --body). */
#include "coons_internal.h"
#include "csg_records.h"
#include "model_glue.h"
#include "morph_lattice.h"
#include "pinch.h"

/* Repairs (and with `unite` unites) the parts of m, then frees m. The
 * result's pinches (solids touching along a curve or at a point: edges of
 * four triangles, vertices of two fans) are split (pinch.c), so that every
 * part is a 2-manifold; the report counts them, and its nonmanifold_edges
 * is what is left. The split moves the copies of a vertex apart by a
 * fraction of the edges there: should that make two triangles cross (the
 * exact count of the result), the pinched result is returned instead,
 * never a crossing one. */
static coons_status solidify_into(coons_mesh *m, const coons_csg_options *copts, int unite,
                                  coons_mesh **out, coons_csg_report *report, coons_error *err)
{
    coons_csg_options co;
    coons__csg_options_read(copts, &co);
    co.unite = unite;
    coons_status st = coons_mesh_solidify(m, &co, out, report, err);
    coons_mesh_free(m);
    if (st) return st;
    size_t edges = 0, vertices = 0, left = 0, pairs = 0;
    coons_mesh *split = NULL;
    st = coons__mesh_clone(*out, &split, err);
    if (!st) st = coons__mesh_split_pinches(split, &edges, &vertices, &left, err);
    if (!st && vertices) st = coons_mesh_count_self_intersections(split, &pairs, err);
    if (st) {
        coons_mesh_free(split);
        coons_mesh_free(*out);
        *out = NULL;
        coons__csg_report_clear(report);
        return st;
    }
    if (vertices && pairs == 0) {
        coons_mesh_free(*out);
        *out = split;
        if (report) {
            report->pinch_edges_split += edges;
            report->pinch_vertices_split += vertices;
            report->nonmanifold_edges = left;
        }
    } else {
        coons_mesh_free(split); /* nothing to split, or the split would cross */
    }
    return COONS_OK;
}

/* The same into a report of any version this library knows (a version-1
 * record has no pinch fields: a full one is filled and its part copied). */
static coons_status solidify(coons_mesh *m, const coons_csg_options *copts, int unite,
                             coons_mesh **out, coons_csg_report *report, coons_error *err)
{
    coons_csg_report full;
    coons_csg_report *rep = coons__csg_report_open(report, &full);
    coons_status st = solidify_into(m, copts, unite, out, rep, err);
    coons__csg_report_close(report, rep);
    return st;
}

/* What sampling measured, into the report (version 3 on): the tolerance
 * and the largest deviation of the sampled shells (coons_mesh_deviation()
 * before they are repaired or united). */
static void note_sampling(coons_csg_report *report, double tol, double dev)
{
    if (report && report->version >= 3) {
        report->tolerance = tol;
        report->deviation = dev;
    }
}

/* The checks every entry makes first: the records' versions, then a
 * cleared report and no output. */
static coons_status begin(const coons_csg_options *copts, coons_mesh **out,
                          coons_csg_report *report, coons_error *err)
{
    *out = NULL;
    coons_status st = coons__csg_records_check(copts, report, err);
    if (!st) coons__csg_report_clear(report);
    return st;
}

coons_status coons_model_solidify(const coons_model *model, const coons_sample_options *sopts,
                                  const coons_csg_options *copts, coons_mesh **out,
                                  coons_csg_report *report, coons_error *err)
{
    coons_status st = begin(copts, out, report, err);
    if (st) return st;
    coons_mesh *m = NULL;
    double tol = 0;
    coons_csg_options co;
    coons__csg_options_read(copts, &co);
    st = coons__model_sample_threads(model, sopts, co.progress, co.userdata, co.threads, &m, &tol,
                                     err);
    if (st) return st;
    int unite = coons_model_operation(model) == COONS_OP_UNION;
    if (!coons_csg_is_available()) {
        size_t i, j;
        if (unite && coons__parts_meet(m, tol, &i, &j)) {
            st = coons__union_unavailable(m, i, j, err);
            coons_mesh_free(m);
            return st;
        }
        *out = m;
        note_sampling(report, tol, coons_mesh_deviation(m));
        return COONS_OK;
    }
    double dev = coons_mesh_deviation(m);
    st = solidify(m, copts, unite, out, report, err);
    if (!st) note_sampling(report, tol, dev);
    return st;
}

/* One body alone: sampled as coons__model_sample() would sample it (the
 * model's tolerance by default, the whole triangle budget), then repaired
 * on its own; a single body needs no union, so without CGAL its shell is
 * returned as sampled. */
coons_status coons_model_solidify_body(const coons_model *model, size_t index,
                                       const coons_sample_options *sopts,
                                       const coons_csg_options *copts, coons_mesh **out,
                                       coons_csg_report *report, coons_error *err)
{
    coons_status st = begin(copts, out, report, err);
    if (st) return st;
    size_t n = coons_model_body_count(model);
    if (index >= n)
        return coons__error_set(err, COONS_E_INVALID,
                                "body index %zu is out of range: the model has %zu bod%s", index,
                                n, n == 1 ? "y" : "ies");
    coons__sample_opts o;
    if ((st = coons__sample_opts_resolve(sopts, &o, err))) return st;
    if (!(o.tolerance > 0)) o.tolerance = coons_model_tolerance(model);
    coons_progress_fn progress = copts ? copts->progress : NULL;
    void *userdata = copts ? copts->userdata : NULL;
    if (progress) progress(userdata, "sample", (double)index / (double)n);
    coons_mesh *m = NULL;
    if ((st = coons_mesh_new(&m, err))) return st;
    st = coons__body_sample_path(coons_model_body(model, index), &o,
                                 coons_model_body_name(model, index), m, NULL, err);
    if (st) {
        coons_mesh_free(m);
        return st;
    }
    if (progress) progress(userdata, "sample", 1.0);
    if (!coons_csg_is_available()) {
        *out = m;
        note_sampling(report, o.tolerance, coons_mesh_deviation(m));
        return COONS_OK;
    }
    double dev = coons_mesh_deviation(m);
    st = solidify(m, copts, 0, out, report, err);
    if (!st) note_sampling(report, o.tolerance, dev);
    return st;
}
