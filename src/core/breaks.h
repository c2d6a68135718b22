/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Breakpoints of a curve's, patch's or body's data in (0,1): where the map
 * may lose smoothness (knots, segment ends). The volume quadrature and the
 * boundary sampler start their cells there. Internal. */
#ifndef COONS_BREAKS_H
#define COONS_BREAKS_H

#include "coons_internal.h"

/* The continuity of a map without breakpoints (kinds.h, coons__space). */
#define COONS__SMOOTH 1000

/* More breakpoints than this in a direction: uniform cells instead. */
#define COONS__MAX_BREAKS 64

/* A growing list of values; nomem is set (and sticks) when growing fails.
 * In probe mode (probe != 0) nothing is stored or allocated: hit is set
 * when a value within tol of `at` would have been appended, so a question
 * asked during evaluation ("is x a breakpoint?") cannot fail. Kinds that
 * map their inner object's breakpoints map `at` and `tol` the other way. */
typedef struct coons__breaks {
    double *v;
    size_t n, cap;
    int nomem;
    int probe, hit;
    double at, tol;
    /* Set by the caller: keep every breakpoint (no COONS__MAX_BREAKS stop;
     * the spline form of nurbs.c needs them all). */
    int all;
} coons__breaks;

/* Appends x if it lies in (0,1) (probe mode: compares it with `at`). */
void coons__breaks_add(coons__breaks *B, double x);

/* The inner knots k[p+1..ncp-1] of a knot vector of degree p for ncp
 * control points, mapped from [k_p, k_ncp] onto [0,1] (nothing if k is
 * NULL); stops once the list holds more than COONS__MAX_BREAKS values
 * (unless B->all). */
void coons__breaks_knots(coons__breaks *B, const double *k, size_t ncp, int p);

/* The continuity p - m of a B-spline of degree p at its inner knots
 * k[p+1..ncp-1], m the largest multiplicity there; COONS__SMOOTH when
 * there is none. */
int coons__knots_continuity(const double *k, size_t ncp, int p);

/* The ends s/nseg, s = 1..nseg-1, of nseg equal segments (same stop). */
void coons__breaks_uniform(coons__breaks *B, size_t nseg);

#endif
