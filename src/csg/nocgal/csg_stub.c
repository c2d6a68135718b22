/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Built when libcoons is configured without CGAL: repair and union are not
 * available, and say so. */
#include "coons_internal.h"
#include "coons_test_hooks.h"
#include "csg_records.h"

static coons_status unavailable(coons_error *err)
{
    return coons__error_set(err, COONS_E_UNSUPPORTED,
                            "repair and union need CGAL: this libcoons was built with "
                            "COONS_WITH_CGAL=OFF");
}

coons_status coons_mesh_solidify(const coons_mesh *in, const coons_csg_options *opts,
                                 coons_mesh **out, coons_csg_report *report, coons_error *err)
{
    (void)in;
    *out = NULL;
    coons_status st = coons__csg_records_check(opts, report, err);
    if (st) return st;
    return unavailable(err);
}

coons_status coons_mesh_count_self_intersections(const coons_mesh *m, size_t *pairs, coons_error *err)
{
    (void)m;
    *pairs = 0;
    return unavailable(err);
}

coons_status coons_mesh_count_self_intersections_float(const coons_mesh *m, size_t *pairs,
                                                       coons_error *err)
{
    (void)m;
    *pairs = 0;
    return unavailable(err);
}

coons_status coons_mesh_count_self_intersections_threads(const coons_mesh *m, int rounded,
                                                        unsigned threads, size_t *pairs,
                                                        coons_error *err)
{
    (void)m, (void)rounded, (void)threads;
    *pairs = 0;
    return unavailable(err);
}

coons_status coons__csg_count_pairs(const coons_mesh *m, const unsigned char *old_tri,
                                    int reference, unsigned threads, size_t *pairs,
                                    size_t *degenerate, coons_error *err)
{
    (void)m, (void)old_tri, (void)reference, (void)threads;
    *pairs = 0;
    if (degenerate) *degenerate = 0;
    return unavailable(err);
}

int coons_csg_is_available(void) { return 0; }
