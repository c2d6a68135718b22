/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Internal checks of the records of coons/csg.h (csg_options.c), shared by
 * the CGAL layer, its stand-in (csg/nocgal) and coons_model_solidify(). */
#ifndef COONS_CSG_RECORDS_H
#define COONS_CSG_RECORDS_H

#include "coons.h"

#ifdef __cplusplus
extern "C" {
#endif

/* COONS_E_INVALID unless opts (may be NULL) and report (may be NULL) carry
 * the versions this library knows. */
coons_status coons__csg_records_check(const coons_csg_options *opts, const coons_csg_report *report,
                                      coons_error *err);
/* *out = *in (NULL: the defaults), read as the version `in` says (a
 * version-2 record has no `threads`): call after coons__csg_records_check(). */
void coons__csg_options_read(const coons_csg_options *in, coons_csg_options *out);
/* Every output field of a report (may be NULL) zeroed, its version kept. */
void coons__csg_report_clear(coons_csg_report *report);
/* A caller built against version 1 of the report passes a shorter record
 * (no pinch fields): the public functions fill *full instead and copy back
 * what version 1 holds. open returns the record to fill (report itself
 * when it has the current version, or NULL); close copies back. Call open
 * after coons__csg_records_check(). */
coons_csg_report *coons__csg_report_open(coons_csg_report *report, coons_csg_report *full);
void coons__csg_report_close(coons_csg_report *report, const coons_csg_report *filled);

#ifdef __cplusplus
}
#endif
#endif
