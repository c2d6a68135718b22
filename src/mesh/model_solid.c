/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A model's solid: every body sampled as its own closed shell (sample.c),
 * then repaired and united by the CGAL layer (cgal_solid.cpp) as the
 * model's "operation" says. Without CGAL, only models that need no Boolean
 * work (operation "none", or bodies that do not meet) can be made. */
#include <string.h>

#include "coons_internal.h"
#include "mesh_impl.h"

/* Do the sampled boxes of parts i and j meet (grown by tol)? */
static int parts_meet(const coons_mesh *m, size_t i, size_t j, double tol)
{
    double lo[2][3], hi[2][3];
    const size_t pj[2] = {i, j};
    for (int k = 0; k < 2; k++) {
        const coons__mesh_part *P = &m->parts[pj[k]];
        bbox_empty(lo[k], hi[k]);
        for (size_t v = P->vert_first; v < P->vert_first + P->vert_count; v++)
            bbox_add(lo[k], hi[k], m->xyz + 3 * v);
    }
    for (int d = 0; d < 3; d++)
        if (lo[0][d] > hi[1][d] + tol || lo[1][d] > hi[0][d] + tol) return 0;
    return 1;
}

coons_status coons_model_solid(const coons_model *model, const coons_sample_options *sopts,
                               const coons_csg_options *copts, coons_mesh **out,
                               coons_csg_report *report, coons_error *err)
{
    *out = NULL;
    if (report) memset(report, 0, sizeof *report);
    coons_sample_options so = COONS_SAMPLE_OPTIONS_INIT;
    if (sopts) so = *sopts;
    if (!(so.tolerance > 0)) so.tolerance = coons_model_tolerance(model);
    size_t budget = so.max_triangles ? so.max_triangles : COONS_DEFAULT_MAX_TRIANGLES;

    coons_mesh *m = NULL;
    coons_status st = coons_mesh_new(&m, err);
    size_t nb = coons_model_body_count(model);
    for (size_t i = 0; i < nb && !st; i++) {
        coons_mesh *b = NULL;
        coons_sample_options oi = so;
        oi.max_triangles = budget;
        st = coons_body_sample(coons_model_body(model, i), &oi, coons_model_body_name(model, i),
                               &b, err);
        if (!st) {
            budget -= coons_mesh_triangle_count(b) < budget ? coons_mesh_triangle_count(b) : budget;
            st = coons_mesh_add_part(m, coons_model_body_name(model, i), coons_mesh_vertices(b),
                                     coons_mesh_vertex_count(b), coons_mesh_triangles(b),
                                     coons_mesh_triangle_count(b), err);
        }
        coons_mesh_free(b);
    }
    if (st) {
        coons_mesh_free(m);
        return st;
    }
    int unite = coons_model_operation(model) == COONS_OP_UNION;
    if (!coons_csg_available()) {
        if (unite)
            for (size_t i = 0; i < nb; i++)
                for (size_t j = i + 1; j < nb; j++)
                    if (parts_meet(m, i, j, 2 * so.tolerance)) {
                        coons__error_set(err, COONS_E_UNSUPPORTED,
                                         "bodies '%s' and '%s' overlap or touch, and their union "
                                         "needs CGAL, which this libcoons was built without; "
                                         "set \"operation\": \"none\" to output each body's own "
                                         "closed shell",
                                         m->parts[i].name, m->parts[j].name);
                        coons_mesh_free(m);
                        return COONS_E_UNSUPPORTED;
                    }
        *out = m;
        return COONS_OK;
    }
    coons_csg_options co = COONS_CSG_OPTIONS_INIT;
    if (copts) co = *copts;
    co.unite = unite;
    coons_mesh *r = NULL;
    st = coons_mesh_solidify(m, &co, &r, report, err);
    coons_mesh_free(m);
    if (st) return st;
    *out = r;
    return COONS_OK;
}
