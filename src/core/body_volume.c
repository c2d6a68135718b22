/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Volume and fold detection of a body F: [0,1]^3 -> R^3 (seed 000 section
 * 2): the signed volume is the integral of det J = det dF/d(u,v,w) over the
 * unit cube (change of variables), computed by tensor 4-point
 * Gauss-Legendre quadrature on c^3 equal cells, c doubling until two
 * successive estimates agree. The rule is exact for polynomials of degree
 * 7 per variable, so bodies 0/1 with low-degree data converge at once, and
 * rational or piecewise data converge like h^8 per cell.
 * A negative det J somewhere means the body folds over itself.
 */
#include "body_impl.h"

/* Cells per direction never exceed this (32^3 cells * 64 nodes). */
#define MAX_CELLS 32

static double volume_level(const coons_body *b, unsigned c)
{
    static const double x[4] = {-0.86113631159405257522, -0.33998104358485626480,
                                0.33998104358485626480, 0.86113631159405257522};
    static const double wt[4] = {0.34785484513745385737, 0.65214515486254614263,
                                 0.65214515486254614263, 0.34785484513745385737};
    double h = 1.0 / c, sum = 0.0;
    for (unsigned a = 0; a < c; a++)
        for (unsigned e = 0; e < c; e++)
            for (unsigned g = 0; g < c; g++) {
                double cell = 0.0;
                for (int i = 0; i < 4; i++)
                    for (int j = 0; j < 4; j++)
                        for (int k = 0; k < 4; k++) {
                            double p[3], jac[3][3];
                            double u = (a + 0.5 * (1.0 + x[i])) * h;
                            double v = (e + 0.5 * (1.0 + x[j])) * h;
                            double w = (g + 0.5 * (1.0 + x[k])) * h;
                            cell += wt[i] * wt[j] * wt[k] *
                                    coons_body_eval_jacobian(b, u, v, w, p, jac);
                        }
                sum += cell;
            }
    return sum * (0.125 * h * h * h);
}

coons_status coons_body_volume(const coons_body *b, double rel_tol, double *volume,
                               coons_error *err)
{
    if (!b || !volume) return coons__error_set(err, COONS_E_INVALID, "body volume: NULL argument");
    if (!(rel_tol > 0.0)) rel_tol = 1e-9;
    /* An absolute floor for bodies of (near) zero volume, where a relative
     * test cannot be met: rounding of det J is about 1e-16 diag^3. */
    double diag = bbox_diag(b->lo, b->hi);
    double floor_ = 1e-14 * diag * diag * diag;
    double prev = volume_level(b, 1), cur = prev;
    for (unsigned c = 2; c <= MAX_CELLS; c *= 2) {
        cur = volume_level(b, c);
        double diff = fabs(cur - prev);
        if (diff <= rel_tol * fabs(cur) || diff <= floor_) break;
        prev = cur;
    }
    *volume = cur;
    return COONS_OK;
}

coons_status coons_body_min_jacobian(const coons_body *b, unsigned n, double *min_det,
                                     double where[3], coons_error *err)
{
    if (!b || !min_det)
        return coons__error_set(err, COONS_E_INVALID, "body min Jacobian: NULL argument");
    if (n < 1)
        return coons__error_set(err, COONS_E_INVALID, "body min Jacobian: n = %u, need n >= 1",
                                n);
    if (n > 1u << 20)
        return coons__error_set(err, COONS_E_LIMIT, "body min Jacobian: n = %u is too large", n);
    double best = INFINITY, at[3] = {0, 0, 0};
    for (unsigned i = 0; i <= n; i++)
        for (unsigned j = 0; j <= n; j++)
            for (unsigned k = 0; k <= n; k++) {
                double u = (double)i / n, v = (double)j / n, w = (double)k / n;
                double p[3], jac[3][3];
                double det = coons_body_eval_jacobian(b, u, v, w, p, jac);
                if (det < best) {
                    best = det;
                    v3_set(at, u, v, w);
                }
            }
    *min_det = best;
    if (where) v3_copy(where, at);
    return COONS_OK;
}
