/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The test hook of nurbs.c. Internal. */
#ifndef COONS_NURBS_IMPL_H
#define COONS_NURBS_IMPL_H

#include "coons_internal.h"

/* The interpolant of one object (exactly one of c, p, b not NULL) in the
 * space of the given degree in every direction, C0 at the object's
 * breakpoints, or without them if drop_breaks, with its deviation
 * measured as coons/nurbs.h does; exact is left 0. The tests use it to
 * show that the measurement catches a space too small. */
coons_status coons__nurbs_in_space(const coons_curve *c, const coons_patch *p,
                                   const coons_body *b, int degree, int drop_breaks,
                                   coons_nurbs *out, coons_error *err);

#endif
