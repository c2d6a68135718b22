/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * What the coons and hermite-coons readers share: the objects of four
 * curves t0 t1 s0 s1 ("boundary", "cross"), and the corners where the
 * boundary curves must meet (src/core/agree.h), worded as an error at the
 * first curve of the two.
 */
#include <stdio.h>

#include "agree.h"
#include "loader.h"

void coons__ld_free_curves(coons_curve **c, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        coons_curve_free(c[i]);
        c[i] = NULL;
    }
}

coons_status coons__ld_four_curves(coons__ld *L, size_t tok, const char *key, const char *what,
                                   coons_curve *c[4], size_t tokv[4])
{
    const char *sides[5];
    coons__ld_names(coons_patch_side_name, sides, 5);
    size_t old = coons__ld_push_key(L, key);
    coons_status rc = coons__ld_expect(L, tok, COONS__JSON_OBJECT, what);
    if (!rc) rc = coons__ld_members(L, tok, what, sides, tokv, NULL);
    for (int k = 0; k < 4 && !rc; k++)
        if (!tokv[k]) {
            char m[96];
            snprintf(m, sizeof m, "%s needs all four curves %s, %s, %s and %s", what, sides[0],
                     sides[1], sides[2], sides[3]);
            rc = coons__ld_need(L, tok, 0, sides[k], m);
        }
    for (int k = 0; k < 4 && !rc; k++) {
        size_t o2 = coons__ld_push_key(L, sides[k]);
        rc = coons__ld_curve(L, tokv[k], L->build ? &c[k] : NULL);
        coons__ld_pop(L, o2);
    }
    coons__ld_pop(L, old);
    return rc;
}

coons_status coons__ld_patch_corners(coons__ld *L, coons_curve *const c[4], const size_t tokv[4])
{
    const coons_curve *const b[4] = {c[0], c[1], c[2], c[3]};
    coons__agree r;
    if (!coons__agree_patch_corners(b, L->ctol, &r)) return COONS_OK;
    const char *a = coons_patch_side_name(r.a), *bn = coons_patch_side_name(r.b);
    char corner[64], sa[96], sb[96];
    snprintf(corner, sizeof corner, "X%d%d (s=%d, t=%d)", r.at & 1, r.at >> 1, r.at & 1,
             r.at >> 1);
    coons__ld_fmt3(sa, sizeof sa, r.pa);
    coons__ld_fmt3(sb, sizeof sb, r.pb);
    return coons__ld_fail_in(L, "boundary", a, tokv[r.a], COONS_E_INCOMPATIBLE,
                             "boundary curves %s and %s do not meet at corner %s: %s(%d) = %s, "
                             "%s(%d) = %s, %.3g apart, more than the tolerance %.3g",
                             a, bn, corner, a, (int)r.ta, sa, bn, (int)r.tb, sb, r.dist,
                             L->ctol);
}
