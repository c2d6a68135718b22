/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Faces ruled between two straight lines, meshed as strips spanning their
 * rulings (ruled.c), a step of the flat-face pass (flat.c). Internal. */
#ifndef COONS_RULED_H
#define COONS_RULED_H

#include "sampler.h"

/* For every face f of s's final mesh that is not flat[f] (and not glued,
 * not shared) and is straight along one of its directions: its strip
 * triangles in ftri[f] (coons__malloc'd, fnt[f] of them) and flat[f] = 1
 * where the strips' measured deviation stays within the tolerance; bit f
 * of *bits set for each, *dev_out the largest such deviation (scaled units).
 * Returns COONS_OK, COONS_E_NOMEM, or an evaluation error of the body. */
coons_status coons__ruled_faces(sampler *s, int flat[6], uint32_t *ftri[6], size_t fnt[6],
                                unsigned *bits, double *dev_out);

#endif
