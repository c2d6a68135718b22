/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Affine maps of references (coons-model(5), "Definitions and references";
 * affine.h): the regularity check, boxes and composition. */
#include "affine.h"

void coons__affine_bbox(const double *m, const double lo[3], const double hi[3],
                        double olo[3], double ohi[3])
{
    bbox_empty(olo, ohi);
    if (!(lo[0] <= hi[0] && lo[1] <= hi[1] && lo[2] <= hi[2])) return;
    for (int c = 0; c < 8; c++) {
        double p[3] = {c & 4 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 1 ? hi[2] : lo[2]};
        coons__affine_point(m, p, p);
        bbox_add(olo, ohi, p);
    }
}

coons_status coons__affine_check(const double *m, const char *what, coons_error *err)
{
    if (!m) return coons__error_set(err, COONS_E_INVALID, "%s transform: matrix is NULL", what);
    for (int i = 0; i < 12; i++)
        if (!isfinite(m[i]))
            return coons__error_set(err, COONS_E_INVALID,
                                    "%s transform: entry [%d][%d] is not a finite number", what,
                                    i / 4, i % 4);
    double det = coons__affine_det(m), norms = 1;
    for (int r = 0; r < 3; r++) norms *= sqrt(v3_dot(m + 4 * r, m + 4 * r));
    /* Relative to the row norms, so that a scale does not make a regular
     * map singular or the reverse. */
    if (!(fabs(det) > 1e-12 * norms))
        return coons__error_set(err, COONS_E_INVALID,
                                "%s transform is singular: its determinant is %.17g (|det| must "
                                "exceed 1e-12 x the product of the row norms, %.17g)",
                                what, det, norms);
    return COONS_OK;
}

void coons__affine_compose(const double a[12], const double b[12], double out[12])
{
    double r[12];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 4; j++) {
            double s = j == 3 ? a[4 * i + 3] : 0;
            for (int k = 0; k < 3; k++) s += a[4 * i + k] * b[4 * k + j];
            r[4 * i + j] = s;
        }
    }
    for (int i = 0; i < 12; i++) out[i] = r[i];
}
