/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The agreement checker (model format, "Consistency"; seed 001 eq. 1.5-1.8
 * for the patch corners, section 1.2.1 for the cross tangents, seed 000
 * sections 2.3 and 2.4 for the corners and edges of bodies 1 and 2). The
 * loader and the constructors both call it, so a model and a program that
 * builds the same objects are accepted or refused alike.
 */
#include "agree.h"

static coons_status found(coons__agree *r, int at, int a, double ta, const double pa[3], int b,
                          double tb, const double pb[3], double dist)
{
    r->at = at;
    r->a = a;
    r->b = b;
    r->ta = ta;
    r->tb = tb;
    v3_copy(r->pa, pa);
    v3_copy(r->pb, pb);
    r->dist = dist;
    return COONS_E_INCOMPATIBLE;
}

coons_status coons__agree_patch_corners(const coons_curve *const b[4], double tol,
                                        coons__agree *r)
{
    for (int k = 0; k < 4; k++) {
        int s = k & 1, t = k >> 1, tc = t ? COONS_SIDE_T1 : COONS_SIDE_T0, sc = s ? COONS_SIDE_S1 : COONS_SIDE_S0;
        double pa[3], pb[3];
        coons_curve_eval(b[tc], s, pa);
        coons_curve_eval(b[sc], t, pb);
        double d = v3_dist(pa, pb);
        if (!(d <= tol)) return found(r, k, tc, s, pa, sc, t, pb, d);
    }
    return COONS_OK;
}

coons_status coons__agree_cross(const coons_curve *const b[4], const coons_curve *const cross[4],
                                double tol, coons__agree *r)
{
    for (int c = 0; c < 4; c++)
        for (int e = 0; e < 2; e++) {
            /* cross t0/t1 against boundary s0/s1 (2 + e) at t = c; cross
             * s0/s1 against boundary t0/t1 (e) at s = c - 2. */
            int other = c < 2 ? 2 + e : e, at = c < 2 ? c : c - 2;
            double got[3], d2[2][3];
            coons_curve_eval(cross[c], e, got);
            coons_curve_eval_derivs(b[other], at, 1, d2);
            double d = v3_dist(got, d2[1]);
            if (!(d <= tol)) return found(r, c, c, e, got, other, at, d2[1], d);
        }
    return COONS_OK;
}

coons_status coons__agree_body1_corners(const coons_curve *const e[12], double tol,
                                        coons__agree *r)
{
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) {
                int idx[3] = {2 * j + k, 4 + 2 * i + k, 8 + 2 * i + j}, par[3] = {i, j, k};
                double p[3][3];
                for (int q = 0; q < 3; q++) coons_curve_eval(e[idx[q]], par[q], p[q]);
                for (int a = 0; a < 3; a++)
                    for (int c = a + 1; c < 3; c++) {
                        double d = v3_dist(p[a], p[c]);
                        if (!(d <= tol))
                            return found(r, 4 * i + 2 * j + k, idx[a], par[a], p[a], idx[c],
                                         par[c], p[c], d);
                    }
            }
    return COONS_OK;
}

void coons__agree_edge_source(int e, int m, int *face, int *run, int *fixed)
{
    int dir = e / 4, x = (e >> 1) & 1, y = e & 1;
    if (dir == 0) { /* u-edge, J = x, K = y */
        *face = m == 0 ? 2 + x : 4 + y;
        *run = 0;
        *fixed = m == 0 ? y : x;
    } else if (dir == 1) { /* v-edge, I = x, K = y */
        *face = m == 0 ? x : 4 + y;
        *run = m == 0 ? 0 : 1;
        *fixed = m == 0 ? y : x;
    } else { /* w-edge, I = x, J = y */
        *face = m == 0 ? x : 2 + y;
        *run = 1;
        *fixed = m == 0 ? y : x;
    }
}

static void edge_point(const coons_patch *p, int run, int fixed, double x, double out[3])
{
    if (run == 0)
        coons_patch_eval(p, x, fixed, out);
    else
        coons_patch_eval(p, fixed, x, out);
}

coons_status coons__agree_body2_edges(const coons_patch *const f[6], double tol,
                                      coons__agree *r)
{
    enum { N = COONS__AGREE_EDGE_SAMPLES };
    for (int e = 0; e < 12; e++) {
        int fa, ra, xa, fb, rb, xb;
        coons__agree_edge_source(e, 0, &fa, &ra, &xa);
        coons__agree_edge_source(e, 1, &fb, &rb, &xb);
        double worst = -1, wx = 0, wa[3] = {0}, wb[3] = {0};
        for (int s = 0; s < N; s++) {
            double x = (double)s / (N - 1), pa[3], pb[3];
            edge_point(f[fa], ra, xa, x, pa);
            edge_point(f[fb], rb, xb, x, pb);
            double d = v3_dist(pa, pb);
            if (!(d <= worst) && !(d <= tol)) {
                worst = isnan(d) ? INFINITY : d;
                wx = x;
                v3_copy(wa, pa);
                v3_copy(wb, pb);
            }
        }
        if (worst >= 0) return found(r, e, fa, wx, wa, fb, wx, wb, worst);
    }
    return COONS_OK;
}
