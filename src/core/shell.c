/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The shell: a surface made solid (coons-model(5), "Shells"; the surface
 * of seed 001 offset along its normal, a body over (u,v,w) in the sense
 * of seed 000):
 *   S(u,v,w) = x(u,v) + (w - c) h n(u,v),  n = N / |N|,  N = x_u x x_v,
 * c = 1/2, 0 or 1 (side both, front, back). The Jacobian is exact, from
 * the patch's second derivatives:
 *   N_u = x_uu x x_v + x_u x x_uv,  N_v = x_uv x x_v + x_u x x_vv,
 *   n_u = (N_u - n (n . N_u)) / |N|  (likewise v),
 *   S_u = x_u + (w - c) h n_u,  S_v = x_v + (w - c) h n_v,  S_w = h n.
 * At the surface det J = h |N| > 0; it reaches 0 where (w - c) h equals a
 * principal radius of curvature on the concave side: a thicker shell folds.
 */
#include "body_impl.h"
#include "patch_impl.h"

/* Grid of the normal check: every 1/64 of (s,t), ends included. */
#define NORMAL_SAMPLES 65

static void eval(const coons_body *b, double u, double v, double w, double out[3],
                 double d[3][3])
{
    const coons_patch *p = b->face[0];
    double x[6][3];
    p->kind->eval(p, u, v, d ? 2 : 1, x);
    double N[3], n[3];
    v3_cross(N, x[1], x[2]);
    double len = v3_norm(N);
    v3_scale(n, N, len > 0.0 ? 1.0 / len : 0.0);
    double off = (w - b->shell_c) * b->shell_h;
    v3_copy(out, x[0]);
    v3_axpy(out, off, n);
    if (!d) return;
    double a[3], c[3], Nq[2][3];
    v3_cross(a, x[3], x[2]);
    v3_cross(c, x[1], x[4]);
    v3_add(Nq[0], a, c);
    v3_cross(a, x[4], x[2]);
    v3_cross(c, x[1], x[5]);
    v3_add(Nq[1], a, c);
    for (int q = 0; q < 2; q++) {
        double nq[3];
        v3_copy(nq, Nq[q]);
        v3_axpy(nq, -v3_dot(n, Nq[q]), n);
        v3_scale(nq, nq, len > 0.0 ? 1.0 / len : 0.0);
        v3_copy(d[q], x[1 + q]);
        v3_axpy(d[q], off, nq);
    }
    v3_scale(d[2], n, b->shell_h);
}

/* The surface point and normal once per (u,v), then every w: a face grid
 * with nu = 1 or nv = 1 runs along w at one surface point. The same
 * operations as eval, so grid points equal eval's bitwise. */
static coons_status grid(const coons_body *b, const double *u, size_t nu, const double *v,
                         size_t nv, const double *w, size_t nw, double *out, coons_error *err)
{
    (void)err;
    const coons_patch *p = b->face[0];
    for (size_t i = 0; i < nu; i++)
        for (size_t j = 0; j < nv; j++) {
            double x[3][3], N[3], n[3];
            p->kind->eval(p, clamp01(u[i]), clamp01(v[j]), 1, x);
            v3_cross(N, x[1], x[2]);
            double len = v3_norm(N);
            v3_scale(n, N, len > 0.0 ? 1.0 / len : 0.0);
            for (size_t k = 0; k < nw; k++) {
                double *o = out + ((i * nv + j) * nw + k) * 3;
                v3_copy(o, x[0]);
                v3_axpy(o, (clamp01(w[k]) - b->shell_c) * b->shell_h, n);
            }
        }
    return COONS_OK;
}

/* u and v are the patch's s and t; nothing breaks along w. */
static void breaks(const coons_body *b, int d, coons__breaks *B)
{
    if (d < 2) coons__patch_breaks(b->face[0], d, B);
}

static coons_status copy(const coons_body *b, coons_body *d, coons_error *err)
{
    d->face[0] = NULL;
    return coons_patch_copy(b->face[0], &d->face[0], err);
}

static void release(coons_body *b) { coons_patch_free(b->face[0]); }

/* Linear in w; the offset along the unit normal has no spline form. */
static void space(const coons_body *b, int d, coons__space *S)
{
    (void)b;
    *S = coons__space_poly(d < 2 ? 3 : 1);
    if (d < 2) S->kind = COONS__SPACE_NONE;
}

const coons__body_kind coons__shell_kind = {
    .type = COONS_BODY_SHELL, .eval = eval, .grid = grid, .breaks = breaks, .copy = copy,
    .free = release, .space = space};

coons_status coons_body_new_shell(const coons_patch *surface, double h, coons_shell_side side,
                                  coons_body **out, coons_error *err)
{
    if (!out) return coons__error_set(err, COONS_E_INVALID, "shell: out is NULL");
    *out = NULL;
    if (!surface) return coons__error_set(err, COONS_E_INVALID, "shell: surface is NULL");
    if (!(h > 0.0) || !isfinite(h))
        return coons__error_set(err, COONS_E_INVALID,
                                "shell: thickness %g is not a finite number > 0", h);
    if (side != COONS_SHELL_BOTH && side != COONS_SHELL_FRONT && side != COONS_SHELL_BACK)
        return coons__error_set(err, COONS_E_INVALID, "shell: unknown side %d", (int)side);
    for (int i = 0; i < NORMAL_SAMPLES; i++)
        for (int j = 0; j < NORMAL_SAMPLES; j++) {
            double s = (double)i / (NORMAL_SAMPLES - 1), t = (double)j / (NORMAL_SAMPLES - 1);
            double x[3][3], N[3];
            coons_patch_eval_derivs(surface, s, t, 1, x);
            v3_cross(N, x[1], x[2]);
            double len = v3_norm(N), scale = v3_norm(x[1]) * v3_norm(x[2]);
            if (!(len > 1e-12 * scale) || !(len > 0.0))
                return coons__error_set(err, COONS_E_INVALID,
                                        "shell: the surface's normal is undefined at (s, t) = "
                                        "(%g, %g): |x_s x x_t| = %g (|x_s| = %g, |x_t| = %g)",
                                        s, t, len, v3_norm(x[1]), v3_norm(x[2]));
        }
    coons_body *b = NULL;
    coons_status rc = coons__body_alloc(&coons__shell_kind, COONS_BLEND_LINEAR, &b, err);
    if (rc) return rc;
    if ((rc = coons_patch_copy(surface, &b->face[0], err))) {
        coons_body_free(b);
        return rc;
    }
    b->shell_h = h;
    b->shell_c = side == COONS_SHELL_BOTH ? 0.5 : side == COONS_SHELL_FRONT ? 0.0 : 1.0;
    coons_patch_control_bbox(surface, b->lo, b->hi);
    for (int k = 0; k < 3; k++) {
        b->lo[k] -= h;
        b->hi[k] += h;
    }
    *out = b;
    return COONS_OK;
}
