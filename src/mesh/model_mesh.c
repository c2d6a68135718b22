/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A model's bodies as one mesh, one part per body (sample.c does the work).
 * Without the Boolean layer, "union" is honoured only where it is a plain
 * collection: bodies whose sampled boxes, grown by twice the tolerance (the
 * sampled boundary lies within it of the exact one), are disjoint. */
#include "coons_internal.h"
#include "mesh_glue.h"
#include "mesh_impl.h"

coons_status coons__model_sample(const coons_model *model, const coons_sample_options *opts,
                                 void (*progress)(void *, const char *, double),
                                 void *userdata, coons_mesh **out, double *tolerance,
                                 coons_error *err)
{
    *out = NULL;
    coons__sample_opts o;
    coons_status st = coons__sample_opts_resolve(opts, &o, err);
    if (st) return st;
    if (!(o.tolerance > 0)) o.tolerance = coons_model_tolerance(model);
    if (tolerance) *tolerance = o.tolerance;
    coons_mesh *m;
    if ((st = coons_mesh_new(&m, err))) return st;
    size_t nb = coons_model_body_count(model), budget = o.max_triangles;
    for (size_t i = 0; i < nb && !st; i++) {
        /* By bodies: a body's share of the time is not known before. */
        if (progress) progress(userdata, "sample", (double)i / (double)nb);
        coons__sample_opts oi = o;
        oi.max_triangles = budget;
        size_t used = 0;
        st = coons__body_sample_into(coons_model_body(model, i), &oi,
                                     coons_model_body_name(model, i), m, &used, err);
        budget -= used;
    }
    if (st) {
        coons_mesh_free(m);
        return st;
    }
    if (progress) progress(userdata, "sample", 1.0);
    *out = m;
    return COONS_OK;
}

int coons__parts_meet(const coons_mesh *m, double tol, size_t *pi, size_t *pj)
{
    for (size_t i = 0; i < m->nparts; i++)
        for (size_t j = i + 1; j < m->nparts; j++) {
            double lo[2][3], hi[2][3];
            const size_t pk[2] = {i, j};
            for (int k = 0; k < 2; k++) {
                const coons__mesh_part *P = &m->parts[pk[k]];
                bbox_empty(lo[k], hi[k]);
                for (size_t v = P->vert_first; v < P->vert_first + P->vert_count; v++)
                    bbox_add(lo[k], hi[k], m->xyz + 3 * v);
            }
            int apart = 0;
            for (int d = 0; d < 3; d++)
                if (lo[0][d] > hi[1][d] + 2 * tol || lo[1][d] > hi[0][d] + 2 * tol) apart = 1;
            if (!apart) {
                *pi = i;
                *pj = j;
                return 1;
            }
        }
    return 0;
}

coons_status coons__union_unavailable(const coons_mesh *m, size_t i, size_t j, coons_error *err)
{
    return coons__error_set(err, COONS_E_UNSUPPORTED,
                            "bodies '%s' and '%s' overlap or touch, and their union needs the "
                            "Boolean (CGAL) layer, which is not available here; set "
                            "\"operation\": \"none\" to output each body's own closed shell",
                            m->parts[i].name, m->parts[j].name);
}

coons_status coons_model_sample(const coons_model *model, const coons_sample_options *opts,
                                coons_mesh **out, coons_error *err)
{
    double tol = 0;
    coons_status st = coons__model_sample(model, opts, NULL, NULL, out, &tol, err);
    size_t i, j;
    if (!st && coons_model_operation(model) == COONS_OP_UNION && coons__parts_meet(*out, tol, &i, &j)) {
        st = coons__union_unavailable(*out, i, j, err);
        coons_mesh_free(*out);
        *out = NULL;
    }
    return st;
}
