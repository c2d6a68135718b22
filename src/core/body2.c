/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Coons body 2 (seed 000 section 2.4): placeholder until patches land. */
#include "body_impl.h"

void coons__body2_free_faces(coons_body *b) { (void)b; }
coons_status coons__body2_copy_faces(const coons_body *b, coons_body *d, coons_error *err)
{
    (void)b;
    (void)d;
    (void)err;
    return COONS_OK;
}

coons_status coons_body_body2(const coons_patch *const faces[6], coons_blend blend, double tol,
                              coons_body **out, coons_error *err)
{
    (void)faces;
    (void)blend;
    (void)tol;
    *out = NULL;
    return coons__error_set(err, COONS_E_UNSUPPORTED, "body2 is not implemented yet");
}

void coons__body2_eval(const coons_body *b, double u, double v, double w, double out[3],
                       double d[3][3])
{
    (void)b; (void)u; (void)v; (void)w; (void)d;
    v3_zero(out);
}

coons_status coons__body2_grid(const coons_body *b, const double *u, size_t nu,
                               const double *v, size_t nv, const double *w, size_t nw,
                               double *out, coons_error *err)
{
    (void)b; (void)u; (void)nu; (void)v; (void)nv; (void)w; (void)nw; (void)out;
    return coons__error_set(err, COONS_E_UNSUPPORTED, "body2 is not implemented yet");
}
