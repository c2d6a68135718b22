/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The breakpoint list of breaks.h: the kinds' breaks operations fill it. */
#include "breaks.h"

void coons__breaks_add(coons__breaks *B, double x)
{
    if (B->nomem || !(x > 0.0 && x < 1.0)) return;
    if (B->probe) {
        if (fabs(x - B->at) <= B->tol) B->hit = 1;
        return;
    }
    if (B->n == B->cap) {
        size_t cap = B->cap ? 2 * B->cap : 16;
        double *v = coons__realloc(B->v, cap * sizeof *v);
        if (!v) {
            B->nomem = 1;
            return;
        }
        B->v = v;
        B->cap = cap;
    }
    B->v[B->n++] = x;
}

void coons__breaks_knots(coons__breaks *B, const double *k, size_t ncp, int p)
{
    if (!k) return;
    double lo = k[p], len = k[ncp] - k[p];
    for (size_t i = (size_t)p + 1; i < ncp && (B->all || B->n <= COONS__MAX_BREAKS); i++)
        coons__breaks_add(B, (k[i] - lo) / len);
}

int coons__knots_continuity(const double *k, size_t ncp, int p)
{
    int mmax = 0;
    for (size_t i = (size_t)p + 1; k && i < ncp;) {
        size_t j = i;
        while (j + 1 < ncp && k[j + 1] == k[i]) j++;
        if ((int)(j - i + 1) > mmax) mmax = (int)(j - i + 1);
        i = j + 1;
    }
    return mmax ? p - mmax : COONS__SMOOTH;
}

void coons__breaks_uniform(coons__breaks *B, size_t nseg)
{
    for (size_t s = 1; s < nseg && (B->all || B->n <= COONS__MAX_BREAKS); s++)
        coons__breaks_add(B, (double)s / nseg);
}
