/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A model's bodies as one mesh, one part per body (sample.c does the work).
 * The union of overlapping bodies needs the CGAL layer; until it exists,
 * "union" is honoured only where it is a plain collection: bodies whose
 * sampled boxes, grown by the tolerance (the sampled boundary lies within it
 * of the exact one), are disjoint. */
#include "coons_internal.h"
#include "mesh_glue.h"
#include "mesh_impl.h"

coons_status coons_model_mesh(const coons_model *model, const coons_sample_options *opts,
                              coons_mesh **out, coons_error *err)
{
    *out = NULL;
    coons__sample_opts o;
    coons_status st = coons__sample_opts_resolve(opts, &o, err);
    if (st) return st;
    if (!(o.tolerance > 0)) o.tolerance = coons_model_tolerance(model);
    coons_mesh *m;
    if ((st = coons_mesh_new(&m, err))) return st;
    size_t nb = coons_model_body_count(model), budget = o.max_triangles;
    for (size_t i = 0; i < nb && !st; i++) {
        coons__sample_opts oi = o;
        oi.max_triangles = budget;
        size_t used = 0;
        st = coons__body_sample_into(coons_model_body(model, i), &oi,
                                     coons_model_body_name(model, i), m, &used, err);
        budget -= used;
    }
    if (!st && nb > 1 && coons_model_operation(model) == COONS_OP_UNION) {
        for (size_t i = 0; i < nb && !st; i++)
            for (size_t j = i + 1; j < nb && !st; j++) {
                double lo[2][3], hi[2][3];
                const size_t pj[2] = {i, j};
                for (int k = 0; k < 2; k++) {
                    const coons__mesh_part *P = &m->parts[pj[k]];
                    bbox_empty(lo[k], hi[k]);
                    for (size_t v = P->vert_first; v < P->vert_first + P->vert_count; v++)
                        bbox_add(lo[k], hi[k], m->xyz + 3 * v);
                }
                int apart = 0;
                for (int d = 0; d < 3; d++)
                    if (lo[0][d] > hi[1][d] + 2 * o.tolerance ||
                        lo[1][d] > hi[0][d] + 2 * o.tolerance)
                        apart = 1;
                if (!apart)
                    st = coons__error_set(
                        err, COONS_E_UNSUPPORTED,
                        "bodies '%s' and '%s' overlap or touch, and their union needs the "
                        "Boolean (CGAL) layer, which is not available here; set \"operation\": "
                        "\"none\" to output each body's own closed shell",
                        m->parts[i].name, m->parts[j].name);
            }
    }
    if (st) {
        coons_mesh_free(m);
        return st;
    }
    *out = m;
    return COONS_OK;
}
