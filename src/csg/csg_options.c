/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The records of the repair/union layer (coons/csg.h): options and report,
 * their _init() functions and the version checks shared by every function
 * that takes them, with CGAL and without (csg/nocgal) alike. */
#include <stddef.h>
#include <string.h>

#include "coons_internal.h"
#include "csg_records.h"

void coons_csg_options_init(coons_csg_options *o)
{
    const coons_csg_options d = COONS_CSG_OPTIONS_INIT;
    if (o) *o = d;
}

void coons_csg_report_init(coons_csg_report *r)
{
    const coons_csg_report d = COONS_CSG_REPORT_INIT;
    if (r) *r = d;
}

coons_status coons__csg_records_check(const coons_csg_options *opts, const coons_csg_report *report,
                                      coons_error *err)
{
    /* options of version 2 (no `threads`) and reports of versions 1 (no
     * pinch fields) and 2 (no tolerance and deviation) are read too */
    if (opts && coons__record_version_check("csg options", opts->version, 2, COONS_CSG_OPTIONS_VERSION,
                                            "COONS_CSG_OPTIONS_INIT", err))
        return COONS_E_INVALID;
    if (report && coons__record_version_check("csg report", report->version, 1, COONS_CSG_REPORT_VERSION,
                                              "COONS_CSG_REPORT_INIT", err))
        return COONS_E_INVALID;
    return COONS_OK;
}

/* The bytes a report of an older version has: a version-1 report ends
 * before the pinch fields, a version-2 report before `tolerance`. */
static size_t report_size(unsigned version)
{
    return version == 1   ? offsetof(coons_csg_report, pinch_edges_split)
           : version == 2 ? offsetof(coons_csg_report, tolerance)
                          : sizeof(coons_csg_report);
}

void coons__csg_report_clear(coons_csg_report *report)
{
    if (!report) return;
    if (report->version != COONS_CSG_REPORT_VERSION) {
        coons_csg_report full;
        coons_csg_report_init(&full);
        full.version = report->version;
        memcpy(report, &full, report_size(report->version));
    } else {
        coons_csg_report_init(report);
    }
}

coons_csg_report *coons__csg_report_open(coons_csg_report *report, coons_csg_report *full)
{
    if (!report || report->version == COONS_CSG_REPORT_VERSION) return report;
    coons_csg_report_init(full);
    return full;
}

void coons__csg_report_close(coons_csg_report *report, const coons_csg_report *filled)
{
    if (!report || filled == report || !filled) return;
    unsigned version = report->version;
    memcpy(report, filled, report_size(version));
    report->version = version;
}

void coons__csg_options_read(const coons_csg_options *in, coons_csg_options *out)
{
    coons_csg_options_init(out);
    if (!in) return;
    if (in->version == 2) {
        /* A caller built against version 2 has no `threads`: read only
         * the fields before it. */
        memcpy(out, in, offsetof(coons_csg_options, threads));
        out->version = COONS_CSG_OPTIONS_VERSION;
        out->threads = 1;
    } else {
        *out = *in;
    }
}
