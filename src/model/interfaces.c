/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The continuity across faces shared by two bodies (outputs.md, --info
 * "interfaces"; seed 000 section 3: the continuity between the cells of a
 * control lattice "is simply controlled in a similar way as is done for
 * B-splines"): for each shared face (shared_faces.c), the cross-boundary
 * derivatives of both bodies, each pointing from the first body into the
 * second, compared at a grid of points of the face. C1 means they are
 * equal; G1 that the bodies' tangent planes along the face's parameter
 * lines agree. */
#include <string.h>

#include "coons_internal.h"
#include "sampling.h"

#define S 9 /* samples per face direction */

static double angle_deg(const double a[3], const double b[3])
{
    double c[3];
    v3_cross(c, a, b);
    return atan2(sqrt(v3_dot(c, c)), v3_dot(a, b)) * (180.0 / 3.14159265358979323846);
}

/* Measures one shared face. */
static void measure(const coons_body *A, const coons_body *B, const coons__shared_face *sf,
                    double *c1, double *g1)
{
    int fa, aa, ba, fb, ab, bb;
    coons__face_axes(sf->face[0], &fa, &aa, &ba);
    coons__face_axes(sf->face[1], &fb, &ab, &bb);
    double sa = (double)(sf->face[0] % 2), sb = (double)(sf->face[1] % 2);
    *c1 = 0;
    *g1 = 0;
    for (int i = 0; i < S; i++)
        for (int j = 0; j < S; j++) {
            double a = (double)i / (S - 1), b = (double)j / (S - 1);
            double pa[3], pb[3];
            pa[fa] = sa;
            pa[aa] = a;
            pa[ba] = b;
            double a2 = (sf->sym & COONS__SYM_SWAP) ? b : a, b2 = (sf->sym & COONS__SYM_SWAP) ? a : b;
            if (sf->sym & COONS__SYM_FLIP_A) a2 = 1 - a2;
            if (sf->sym & COONS__SYM_FLIP_B) b2 = 1 - b2;
            pb[fb] = sb;
            pb[ab] = a2;
            pb[bb] = b2;
            double x[3], JA[3][3], JB[3][3];
            coons_body_eval_jacobian(A, pa[0], pa[1], pa[2], x, JA);
            coons_body_eval_jacobian(B, pb[0], pb[1], pb[2], x, JB);
            /* Cross derivatives from A into B: out of A's face, into B's. */
            double dA[3], dB[3], ta[3], tb[3];
            for (int r = 0; r < 3; r++) {
                dA[r] = JA[r][fa] * (sa > 0 ? 1.0 : -1.0);
                dB[r] = JB[r][fb] * (sb > 0 ? -1.0 : 1.0);
                ta[r] = JA[r][aa];
                tb[r] = JA[r][ba];
            }
            double diff[3] = {dB[0] - dA[0], dB[1] - dA[1], dB[2] - dA[2]};
            double scale = fmax(sqrt(v3_dot(dA, dA)), sqrt(v3_dot(dB, dB)));
            if (scale > 0) *c1 = fmax(*c1, sqrt(v3_dot(diff, diff)) / scale);
            /* The tangent planes along each face parameter line: spanned by
             * the line's tangent and each side's cross derivative. */
            const double *t[2] = {ta, tb};
            for (int k = 0; k < 2; k++) {
                double nA[3], nB[3];
                v3_cross(nA, t[k], dA);
                v3_cross(nB, t[k], dB);
                if (v3_dot(nA, nA) > 0 && v3_dot(nB, nB) > 0) *g1 = fmax(*g1, angle_deg(nA, nB));
            }
        }
}

coons_status coons_model_interfaces(const coons_model *m, coons_interface **out, size_t *count,
                                    coons_error *err)
{
    if (!out || !count) return coons__error_set(err, COONS_E_INVALID, "no output pointer given");
    *out = NULL;
    *count = 0;
    if (!m) return coons__error_set(err, COONS_E_INVALID, "no model given");
    size_t nb = coons_model_body_count(m);
    if (nb < 2) return COONS_OK;
    const coons_body **bodies = coons__malloc_array(nb, sizeof *bodies);
    if (!bodies) return coons__error_nomem(err);
    double lo[3], hi[3];
    bbox_empty(lo, hi);
    for (size_t i = 0; i < nb; i++) {
        bodies[i] = coons_model_body(m, i);
        double a[3], b[3];
        coons_body_control_bbox(bodies[i], a, b);
        bbox_add(lo, hi, a);
        bbox_add(lo, hi, b);
    }
    coons__shared_face *sf = NULL;
    size_t n = 0;
    coons_status st = coons__find_shared_faces(bodies, nb, COONS__REL_TOL * bbox_diag(lo, hi), &sf, &n, err);
    coons_interface *list = NULL;
    if (!st && n) {
        list = coons__malloc_array(n, sizeof *list);
        if (!list) st = coons__error_nomem(err);
    }
    for (size_t k = 0; k < n && !st; k++) {
        /* In body order. */
        coons__shared_face f = sf[k];
        if (f.body[0] > f.body[1]) {
            size_t tb = f.body[0];
            int tf = f.face[0];
            f.body[0] = f.body[1];
            f.face[0] = f.face[1];
            f.body[1] = tb;
            f.face[1] = tf;
            /* The inverse symmetry: a swap with one flip swaps the flips. */
            int flips = f.sym & (COONS__SYM_FLIP_A | COONS__SYM_FLIP_B);
            if ((f.sym & COONS__SYM_SWAP) && (flips == COONS__SYM_FLIP_A || flips == COONS__SYM_FLIP_B))
                f.sym ^= COONS__SYM_FLIP_A | COONS__SYM_FLIP_B;
        }
        coons_interface *I = &list[k];
        I->body[0] = f.body[0];
        I->body[1] = f.body[1];
        I->face[0] = f.face[0];
        I->face[1] = f.face[1];
        I->orientation = f.sym;
        measure(bodies[f.body[0]], bodies[f.body[1]], &f, &I->c1_defect, &I->g1_angle);
    }
    coons__free(sf);
    coons__free(bodies);
    if (st) {
        coons__free(list);
        return st;
    }
    *out = list;
    *count = n;
    return COONS_OK;
}

void coons_interfaces_free(coons_interface *list) { coons__free(list); }
