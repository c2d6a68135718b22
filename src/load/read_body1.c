/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * Reader of body1 (seed 000 section 2.3): the 12 edge curves, meeting in
 * threes at the corners (src/core/agree.h), and a blend.
 */
#include <stdio.h>

#include "agree.h"
#include "loader.h"

static const char *const KEYS[] = {"type", "name", "blend", "edges", NULL};

/* The corner agreement, as an error at the first edge of the two. */
static coons_status corners(coons__ld *L, coons_curve *const c[12], const size_t tok[12])
{
    const coons_curve *cc[12];
    for (int k = 0; k < 12; k++) cc[k] = c[k];
    coons__agree r;
    if (!coons__agree_body1_corners(cc, L->ctol, &r)) return COONS_OK;
    int i = r.at >> 2, j = (r.at >> 1) & 1, k = r.at & 1;
    const char *a = coons_body_edge_name(r.a), *b = coons_body_edge_name(r.b);
    char sa[96], sb[96];
    coons__ld_fmt3(sa, sizeof sa, r.pa);
    coons__ld_fmt3(sb, sizeof sb, r.pb);
    return coons__ld_fail_in(L, "edges", a, tok[r.a], COONS_E_INCOMPATIBLE,
                             "edges %s and %s do not meet at corner P%d%d%d (u=%d, v=%d, w=%d): "
                             "%s(%d) = %s, %s(%d) = %s, %.3g apart, more than the tolerance %.3g",
                             a, b, i, j, k, i, j, k, a, (int)r.ta, sa, b, (int)r.tb, sb, r.dist,
                             L->ctol);
}

coons_status coons__ld_read_body1(coons__ld *L, coons__ld_obj *o, coons_body **out)
{
    size_t v[4], sub[12];
    coons_blend bl = COONS_BLEND_LINEAR;
    coons_curve *c[12] = {0};
    coons_status rc = coons__ld_body_keys(L, o, KEYS, v);
    if (!rc) rc = coons__ld_blend(L, v[2], &bl);
    if (!rc) rc = coons__ld_body_parts(L, o, v[3], 1, c, NULL, sub);
    if (!rc && L->build) rc = corners(L, c, sub);
    if (!rc && L->build) {
        coons_error e = COONS_ERROR_INIT;
        coons_status r = coons_body_new_body1(c, bl, L->ctol, out, &e);
        rc = coons__ld_body_built(L, o, v[3], "edges", r, &e);
    }
    coons__ld_free_curves(c, 12);
    return rc;
}
