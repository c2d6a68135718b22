/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The path of a morph (morph.c), for the writers that reproduce its
 * weights (the OpenSCAD animation, src/io/write/scad_morph.c). Internal. */
#ifndef COONS_MORPH_H
#define COONS_MORPH_H

#include "coons_internal.h"

/* The interval i (0 .. n-2) of the key times that holds t: the last whose
 * start is <= t. at NULL: uniform. */
size_t coons__morph_interval(size_t n, const double *at, double t);

/* On interval i, with h its length and s = (t - at_i) / h, the weight of
 * key first + j (j < the returned count, at most 4) is
 *   A[j][0] h00(s) + A[j][1] h10(s) + A[j][2] h01(s) + A[j][3] h11(s)
 * summed in that order (the cubic Hermite basis; a linear path, or two
 * keys, uses h00 = 1 - s, h01 = s, h10 = h11 = 0); other keys weigh 0. */
size_t coons__morph_terms(size_t n, const double *at, int path, size_t i, double A[4][4],
                          size_t *first);

#endif
