/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The model record (model format version 1, "Top level"): bodies, their
 * names, units, tolerance and operation. Loading is in src/io/json/ (loader.h). */
#include <string.h>

#include "model_impl.h"

coons_status coons__model_alloc(size_t n, coons_model **out, coons_error *err)
{
    *out = NULL;
    coons_model *m = coons__calloc(1, sizeof *m);
    if (!m) return coons__error_nomem(err);
    m->nbodies = n;
    m->bodies = coons__calloc(n, sizeof *m->bodies);
    m->names = coons__calloc(n, sizeof *m->names);
    m->named = coons__calloc(n, 1);
    if (!m->bodies || !m->names || !m->named) {
        coons_model_free(m);
        return coons__error_nomem(err);
    }
    bbox_empty(m->lo, m->hi);
    *out = m;
    return COONS_OK;
}

void coons_model_free(coons_model *m)
{
    if (!m) return;
    for (size_t i = 0; i < m->nbodies; i++) {
        if (m->bodies) coons_body_free(m->bodies[i]);
        if (m->names) coons__free(m->names[i]);
    }
    coons__free(m->bodies);
    coons__free(m->names);
    coons__free(m->named);
    coons__free(m->units);
    coons__free(m);
}

size_t coons_model_body_count(const coons_model *m) { return m ? m->nbodies : 0; }

const coons_body *coons_model_body(const coons_model *m, size_t i)
{
    return (m && i < m->nbodies) ? m->bodies[i] : NULL;
}

const char *coons_model_body_name(const coons_model *m, size_t i)
{
    return (m && i < m->nbodies) ? m->names[i] : NULL;
}

long coons_model_find_body(const coons_model *m, const char *name)
{
    if (!m || !name) return -1;
    /* Given names first: an unnamed body's "body<i>" must not hide a body
     * that was explicitly called so. */
    for (int pass = 1; pass >= 0; pass--)
        for (size_t i = 0; i < m->nbodies; i++)
            if (m->named[i] == pass && strcmp(m->names[i], name) == 0) return (long)i;
    return -1;
}

double coons_model_tolerance(const coons_model *m) { return m->tolerance; }

const char *coons_model_units(const coons_model *m) { return m->units; }

coons_operation coons_model_operation(const coons_model *m) { return m->operation; }

void coons_model_control_bbox(const coons_model *m, double lo[3], double hi[3])
{
    v3_copy(lo, m->lo);
    v3_copy(hi, m->hi);
}
