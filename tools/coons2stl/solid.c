/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * The mesh that -o writes (--info reports on the very same one): with
 * `body` < 0, every body made into the model's solid by coons_model_solidify()
 * (repaired and united as the model's "operation" says); else that body's
 * shell alone, repaired if it crosses itself (coons_model_solidify_body()).
 * Without CGAL the shells are as sampled (coons_model_solidify() refuses a
 * union that needs it).
 */
#define _DEFAULT_SOURCE /* sysconf(_SC_NPROCESSORS_ONLN) */
#include <stdint.h>
#include <unistd.h>

#include "cli.h"

unsigned cli_threads(unsigned jobs)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    return jobs ? jobs : (cores > 0 ? (unsigned)cores : 1u);
}

coons_status cli_make_solid(const coons_model *m, long body, const coons_sample_options *so,
                            int repair, unsigned jobs, coons_mesh **out, coons_csg_report *rep,
                            coons_error *err)
{
    coons_csg_options copts = COONS_CSG_OPTIONS_INIT;
    copts.repair = repair;
    copts.threads = cli_threads(jobs);
    copts.progress = cli_progress_on() ? cli_on_progress : NULL;
    copts.userdata = (void *)(uintptr_t)"repair and union";
    coons_csg_report_init(rep);
    if (body < 0) return coons_model_solidify(m, so, &copts, out, rep, err);
    return coons_model_solidify_body(m, (size_t)body, so, &copts, out, rep, err);
}
