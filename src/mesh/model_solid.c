/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A model's solid: every body sampled as its own closed shell (sample.c,
 * model_mesh.c), then repaired and united by the CGAL layer
 * (cgal_solid.cpp) as the model's "operation" says. Without CGAL, only
 * models that need no Boolean work (operation "none", or bodies that do not
 * meet) can be made. */
#include "coons_internal.h"
#include "csg/csg_records.h"
#include "mesh_glue.h"

coons_status coons_model_solidify(const coons_model *model, const coons_sample_options *sopts,
                                  const coons_csg_options *copts, coons_mesh **out,
                                  coons_csg_report *report, coons_error *err)
{
    *out = NULL;
    coons_status st = coons__csg_records_check(copts, report, err);
    if (st) return st;
    coons__csg_report_clear(report);
    coons_mesh *m = NULL;
    double tol = 0;
    st = coons__model_sample(model, sopts, copts ? copts->progress : NULL,
                                          copts ? copts->userdata : NULL, &m, &tol, err);
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
        return COONS_OK;
    }
    coons_csg_options co = COONS_CSG_OPTIONS_INIT;
    if (copts) co = *copts;
    co.unite = unite;
    st = coons_mesh_solidify(m, &co, out, report, err);
    coons_mesh_free(m);
    return st;
}
